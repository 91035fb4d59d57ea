"""Where a simulated run stops being trustworthy: first slip > 8 deg, load outside the tire data,
heading past 90 deg, or the chair rolling backwards (rule and rationale: docs/report.md)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.settings.run import RunSpec
from stability.simulate import LOAD_LIMIT_N, SLIP_LIMIT_DEG
from stability.study import runs

__all__ = ["Validity", "run_validity", "responses_validity", "HEADING_LIMIT_DEG"]

#: Heading change after which a run is no longer "straight running with a disturbance" (deg).
HEADING_LIMIT_DEG = 90.0


@dataclass(frozen=True)
class Validity:
    """The time up to which a run is within the model's range, and why it ends there.

    Attributes
    ----------
    until : float or None
        s; None when the whole run is valid.
    reason : str
        ``""`` or one of ``"slip > 8 deg"``, ``"load > 450 N"``, ``"heading past 90 deg"``,
        ``"speed reversal"``.
    """

    until: float | None
    reason: str = ""

    def covers(self, t: float) -> bool:
        """Whether time ``t`` (s) lies within the valid part."""
        return self.until is None or t <= self.until

    def describe(self) -> str:
        """``"valid to 3.21 s (slip > 8 deg)"`` or ``"valid throughout"``."""
        return "valid throughout" if self.until is None else f"valid to {self.until:.2f} s ({self.reason})"


def run_validity(result: Any) -> Validity:
    """The validity of one simulated run.

    Parameters
    ----------
    result : stability.simulate.SimulationResult
        Uses its ``warnings`` (first slip above ``SLIP_LIMIT_DEG``, first load
        above ``LOAD_LIMIT_N``, where the tire data end), ``heading`` and ``u``.

    Returns
    -------
    Validity
        The earliest of the four events.
    """
    events: list[tuple[float, str]] = []
    w = result.warnings
    if w.get("slip", {}).get("first_time") is not None:
        events.append((float(w["slip"]["first_time"]), f"slip > {SLIP_LIMIT_DEG:g} deg"))
    if w.get("load", {}).get("first_time") is not None:
        events.append((float(w["load"]["first_time"]), f"load > {LOAD_LIMIT_N:g} N"))
    t = np.asarray(result.t)
    heading = np.asarray(result.heading)
    turned = np.flatnonzero(np.abs(heading - heading[0]) > math.radians(HEADING_LIMIT_DEG))
    if len(turned):
        events.append((float(t[turned[0]]), f"heading past {HEADING_LIMIT_DEG:g} deg"))
    back = np.flatnonzero(np.asarray(result.u) < 0)
    if len(back):
        events.append((float(t[back[0]]), "speed reversal"))
    if not events:
        return Validity(None)
    until, reason = min(events)
    return Validity(until, reason)


def responses_validity(chairs: Sequence[Chair], speeds: Sequence[float], run: RunSpec) -> tuple[Validity, ...]:
    """Validity of the runs behind a :class:`stability.study.ResponseSet` (the same runs, simulated again).

    Parameters
    ----------
    chairs, speeds : sequence
        One chair and one speed (m/s) per run, as given to the study.
    run : RunSpec
        The runs' settings, as given to the study.

    Returns
    -------
    tuple of Validity
    """
    return tuple(run_validity(r) for r in runs.simulate_runs(list(chairs), list(speeds), runs.study_run(run)))
