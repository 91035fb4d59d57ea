"""What a simulated run did, in numbers and in the words derived from them: the one place where the report's
direction words ("spins up", "keeps turning", "returns to a straight line", "pin friction holds it" or "keeps
it turning", "better", "worse") come from, so a caption cannot contradict its figure.

Every quantity is read from the run's valid part only (:class:`stability.report.validity.Validity`): a run's
state past its validity end is not a result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.report.validity import Validity
from stability.settings import defaults as D

__all__ = ["Motion", "motion", "friction_role", "better_word", "STEADY_YAW_RATE", "STRAIGHT_HEADING_DEG",
           "sig3"]

#: Yaw rate (rad/s) above which a run ends in a steady turn (:data:`stability.settings.defaults.STEADY_YAW_RATE`).
STEADY_YAW_RATE = D.STEADY_YAW_RATE
#: Heading change (deg) below which a run that settles counts as keeping its line.
STRAIGHT_HEADING_DEG = 5.0
#: The final stretch (s) over which the steady yaw rate is averaged.
SETTLE_WINDOW_S = 1.0


def sig3(x: float) -> str:
    """``x`` to 3 significant figures for prose (``0.0750`` -> ``"0.075"``; no exponent below 1e6).

    Parameters
    ----------
    x : float

    Returns
    -------
    str
    """
    if x == 0 or not math.isfinite(x):
        return f"{x:g}"
    return f"{float(f'{x:.3g}'):g}"


@dataclass(frozen=True)
class Motion:
    """A run's valid part summarised.

    Attributes
    ----------
    speed : float
        m/s.
    until : float
        End of the valid part (s): the validity end or the run's end.
    reason : str
        Why the valid part ends there (``""``: the run's end).
    sideways, travel : float
        Lateral displacement and path length over the valid part, m.
    heading_deg : float
        Heading change over the valid part, deg (signed, as the run's heading).
    final_rate : float
        Mean yaw rate over the last :data:`SETTLE_WINDOW_S` of the valid part, rad/s (signed).
    spins_up : bool
        The run reached the yaw-rate level within its valid part.
    time_to_level : float
        s (inf: never).
    """

    speed: float
    until: float
    reason: str
    sideways: float
    travel: float
    heading_deg: float
    final_rate: float
    spins_up: bool
    time_to_level: float

    @property
    def kind(self) -> str:
        """``"spins up"``, ``"keeps turning"`` or ``"straight"``: the one classification every sentence uses."""
        if self.spins_up:
            return "spins up"
        if abs(self.final_rate) > STEADY_YAW_RATE:
            return "keeps turning"
        return "straight" if abs(self.heading_deg) < STRAIGHT_HEADING_DEG else "settles on a new heading"

    def words(self) -> str:
        """The run's behaviour in a clause with its numbers."""
        k = self.kind
        if k == "spins up":
            return f"spins up to the yaw-rate level after {sig3(self.time_to_level)} s"
        if k == "keeps turning":
            r = abs(self.final_rate)
            return f"keeps turning steadily at {sig3(r)} rad/s ({sig3(math.degrees(r) * 10)} deg in 10 s)"
        if k == "straight":
            return f"returns to a straight line (heading changed by {abs(self.heading_deg):.0f} deg)"
        return f"settles on a new heading {abs(self.heading_deg):.0f} deg off its line"

    def where(self) -> str:
        """``"1.5 m sideways after 3.8 m of travel, heading changed by 79 deg by 3.33 s (valid part ends: slip
        > 8 deg)"``."""
        end = f" (where the run stops being valid: {self.reason})" if self.reason else ""
        return (f"{sig3(self.sideways)} m sideways after {sig3(self.travel)} m of travel, heading changed by "
                f"{abs(self.heading_deg):.0f} deg by {sig3(self.until)} s{end}")


def motion(r: Any, validity: Validity | None = None) -> Motion:
    """Summarise one run's valid part.

    Parameters
    ----------
    r : stability.study.Response
        The run (``t``, ``x``, ``y``, ``heading``, ``yaw_rate``, ``time_to_level``, ``speed``).
    validity : Validity, optional
        Where the run stops being valid (None: valid throughout).

    Returns
    -------
    Motion
    """
    t = np.asarray(r.t, float)
    keep = t <= (validity.until if validity is not None and validity.until is not None else math.inf)
    keep[0] = True
    t = t[keep]
    x, y = np.asarray(r.x, float)[keep], np.asarray(r.y, float)[keep]
    head = np.asarray(r.heading, float)[keep]
    yaw = np.asarray(r.yaw_rate, float)[keep]
    travel = float(np.sum(np.hypot(np.diff(x), np.diff(y))))
    # sideways: the distance from the initial line of travel (the initial heading's direction)
    h0 = float(head[0])
    side = float(-(x[-1] - x[0]) * math.sin(h0) + (y[-1] - y[0]) * math.cos(h0))
    settle = t >= t[-1] - SETTLE_WINDOW_S
    final = float(np.mean(yaw[settle]))
    ttl = float(r.time_to_level)
    spins = math.isfinite(ttl) and ttl <= t[-1] + 1e-9
    reason = validity.reason if validity is not None and validity.until is not None else ""
    return Motion(float(r.speed), float(t[-1]), reason, abs(side), travel,
                  float(np.degrees(head[-1] - head[0])), final, spins, ttl)


def friction_role(with_friction: Motion, without: Motion) -> str:
    """What the pin friction does, from the same speed's runs with and without it.

    Parameters
    ----------
    with_friction, without : Motion
        The chair's run and its frictionless twin's at the same speed.

    Returns
    -------
    str
        ``"holds it"`` (without friction it spins up, with friction it does not), ``"keeps it turning"``
        (without friction it runs straight, with friction it keeps turning), ``"delays the spin"`` (both spin,
        with friction later), ``"hastens the spin"`` or ``"changes little"``.
    """
    a, b = with_friction.kind, without.kind
    if b == "spins up" and a != "spins up":
        return "holds it"
    if a == "keeps turning" and b in ("straight", "settles on a new heading"):
        return "keeps it turning"
    if a == b == "spins up":
        return ("delays the spin" if with_friction.time_to_level > without.time_to_level
                else "hastens the spin" if with_friction.time_to_level < without.time_to_level else "changes little")
    return "changes little"


def better_word(change: float, higher_is_better: bool, tolerance: float = 0.0) -> str:
    """``"better"``, ``"worse"`` or ``"no change"`` for a signed change of a measure.

    Parameters
    ----------
    change : float
        New minus old.
    higher_is_better : bool
    tolerance : float
        Changes within +/- this are "no change".

    Returns
    -------
    str
    """
    if not math.isfinite(change) or abs(change) <= tolerance:
        return "no change"
    return "better" if (change > 0) == higher_is_better else "worse"
