"""The driver's limit with the motor assist on: does the assisted chair still diverge?

Without assist a driver who corrects ``tau`` late holds a chair whose heading diverges at ``lambda(U)`` only while
``lambda tau < 1`` (:mod:`stability.driver`).  With the yaw-rate assist on, the joystick commands a yaw rate and
the assist's closed loop holds it: the driver steers a heading that follows the command, and the divergence the
rule is about is that of the assisted closed loop.  Its slowest pole at each speed of the schedule decides: the
rule ``max(Re p) tau = 1`` is met first where that pole crosses ``1/tau``; a closed loop whose poles all have
negative real parts never meets it, and the driver's limit is then a bound at the schedule's top speed (the
assist's own limits, its safe top speed, decide beyond: ``python -m stability.assist``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.assist.design import closed_loop_poles
from stability.assist.schedule import schedule
from stability.chair import Chair

__all__ = ["AssistedDriver", "assisted_driver_limit", "ASSIST_SPEEDS"]

#: Speeds of the assist schedule the driver's limit is checked at, m/s (the assist command's default grid).
ASSIST_SPEEDS = tuple(float(u) for u in np.arange(0.25, 3.001, 0.25))


@dataclass(frozen=True)
class AssistedDriver:
    """The driver's limit with the default gyro assist on.

    Attributes
    ----------
    reaction_time_s : float
    speeds_m_s : tuple of float
        The schedule's speeds.
    slowest_pole_1_s : tuple of float
        The largest real part of the assisted closed loop's poles at each speed, 1/s (negative: no divergence).
    speed_m_s : float
        The first speed where ``max(Re p) tau >= 1``, or the schedule's top speed as a bound.
    side : str
        ``"="`` (found) or ``">"`` (a bound: the rule is not met at any speed of the schedule).
    """

    reaction_time_s: float
    speeds_m_s: tuple
    slowest_pole_1_s: tuple
    speed_m_s: float
    side: str

    def sentence(self) -> str:
        """The limit in one sentence, with what decides beyond it."""
        worst = max(self.slowest_pole_1_s)
        if self.side == ">":
            return (f"With the assist on (default gyro design) the closed loop does not diverge at any speed from "
                    f"{self.speeds_m_s[0]:g} to {self.speeds_m_s[-1]:g} m/s (slowest pole {worst:.3g} 1/s), so a "
                    f"driver who corrects {self.reaction_time_s:g} s late is not limited by divergence there: above "
                    f"{self.speed_m_s:g} m/s; the assist's own safe top speed decides (python -m stability.assist)")
        return (f"With the assist on (default gyro design) a driver who corrects {self.reaction_time_s:g} s late can "
                f"hold this chair up to {self.speed_m_s:.3g} m/s ({3.6 * self.speed_m_s:.1f} km/h), where the "
                "assisted loop's divergence reaches 1/tau")

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"reaction_time_s": self.reaction_time_s, "speeds_m_s": list(self.speeds_m_s),
                "slowest_pole_1_s": list(self.slowest_pole_1_s), "speed_m_s": self.speed_m_s, "side": self.side}


def assisted_driver_limit(chair: Chair, reaction_time: float, speeds: Sequence[float] = ASSIST_SPEEDS
                          ) -> AssistedDriver:
    """The divergence rule on the assisted closed loop of ``chair`` (the default gyro design at each speed).

    Parameters
    ----------
    chair : Chair
        A powered chair (:func:`stability.chair.power.drive_kind` ``"motor"``).
    reaction_time : float
        The driver's effective delay, s (> 0).
    speeds : sequence of float
        Schedule speeds, m/s, increasing.

    Returns
    -------
    AssistedDriver
    """
    if not reaction_time > 0:
        raise ValueError(f"reaction_time={reaction_time!r} is invalid; valid range: > 0 s")
    s = schedule(chair, np.asarray(speeds, dtype=float), "gyro")
    poles = tuple(float(closed_loop_poles(d).real.max()) for d in s.designs)
    found = [u for u, p in zip(s.speeds, poles, strict=True) if p * reaction_time >= 1.0]
    if found:
        return AssistedDriver(reaction_time, tuple(float(u) for u in s.speeds), poles, float(found[0]), "=")
    return AssistedDriver(reaction_time, tuple(float(u) for u in s.speeds), poles, float(s.speeds[-1]), ">")
