"""The instability criterion of chapter 8: time for |yaw rate| to reach a level (Collins 1987, Figure 8-3a)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.settings.reference import HORIZON, LEVEL, Push
from stability.simulate.signals import time_to_level

__all__ = ["Criterion", "DEFAULT_CRITERION", "PATHS_CRITERION", "time_to_yaw_rate", "check_impulse"]

_INF = float("inf")


@dataclass(frozen=True)
class Criterion:
    """Time to reach ``|yaw rate| = yaw_rate`` within ``duration`` of simulated time.

    Attributes
    ----------
    yaw_rate : float
        The level, rad/s (default :data:`stability.settings.reference.LEVEL`).
    duration : float
        Simulated time, s (default :data:`stability.settings.reference.HORIZON`).
    """

    yaw_rate: float = LEVEL
    duration: float = HORIZON

    def __post_init__(self) -> None:
        if not (self.yaw_rate > 0 and math.isfinite(self.yaw_rate)):
            raise ValueError(f"criterion yaw_rate={self.yaw_rate!r} is invalid; valid range: > 0 rad/s")
        if not (self.duration > 0 and math.isfinite(self.duration)):
            raise ValueError(f"criterion duration={self.duration!r} is invalid; valid range: > 0 s")

    def describe(self) -> str:
        """The criterion in words."""
        return (f"time for |yaw rate| to reach {self.yaw_rate:g} rad/s after the disturbance "
                f"(within {self.duration:g} s simulated)")

    def time(self, result: Any) -> float:
        """The criterion's time (s) for one simulation result (+inf if never reached).

        Parameters
        ----------
        result : SimulationResult or similar
            Anything with ``t`` (s) and ``yaw_rate`` (rad/s) arrays.

        Returns
        -------
        float
            Seconds, or +inf.
        """
        return time_to_yaw_rate(result, self.yaw_rate, self.duration)


#: The thesis's criterion: |yaw rate| reaching LEVEL within HORIZON.
DEFAULT_CRITERION = Criterion()
#: The default of the path plots (Figure 8-4 analogue): 6 s simulated.
PATHS_CRITERION = Criterion(duration=6.0)


def time_to_yaw_rate(result: Any, level: float = LEVEL, duration: float | None = None) -> float:
    """First time ``|yaw rate|`` reaches ``level``, linearly interpolated between samples.

    Parameters
    ----------
    result : SimulationResult or similar
        Anything with ``t`` (s) and ``yaw_rate`` (rad/s) arrays and optionally
        ``stopped_by_warnings``.
    level : float
        The level, rad/s.
    duration : float, optional
        The simulated time asked for, s: a run stopped early by the warning
        rule before reaching the level counts as reaching it when it stopped.

    Returns
    -------
    float
        Seconds; +inf when the level is never reached.
    """
    t = np.asarray(result.t, dtype=float)
    hit = time_to_level(t, result.yaw_rate, level)
    if math.isfinite(hit):
        return hit
    stopped = bool(getattr(result, "stopped_by_warnings", False))
    if duration is not None and len(t) and t[-1] < duration - 1e-9 and stopped:
        return float(t[-1])
    return _INF


def check_impulse(impulse: Any) -> tuple[float, float]:
    """A push as ``(force N, duration s)``; accepts a :class:`stability.settings.reference.Push` or a pair.

    Parameters
    ----------
    impulse : Push or (float, float)
        Lateral force at the c.g. (N) and how long it acts (s, >= 0).

    Returns
    -------
    (float, float)
        ``(force, duration)``.
    """
    if isinstance(impulse, Push):
        impulse = impulse.as_tuple
    try:
        force, length = (float(x) for x in impulse)
    except (TypeError, ValueError):
        raise ValueError(f"impulse={impulse!r} is invalid; expected (force N, duration s)") from None
    if not (math.isfinite(force) and math.isfinite(length) and length >= 0):
        raise ValueError(f"impulse={impulse!r} is invalid; valid range: finite force, duration >= 0 s")
    return force, length
