"""Thesis Figure 9-4: the destabilising yaw moment of the tire forces (open loop) against the motors.

Collins (1987), chapter 9 "Future work": once the destabilising moment
exceeds what the motors can produce, the chair cannot be returned to
straight motion.  This is a criterion on an open-loop run, not a torque
requirement (see ``docs/assist.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from stability import chair as chair_mod
from stability.chair import Chair
from stability.chair.power import DriveTrain
from stability.settings.reference import HORIZON, REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate import simulate

__all__ = ["destabilising_moment", "valid_until", "DestabilisingSummary", "destabilising_summary"]


def destabilising_moment(chair: Chair | str = REFERENCE_CHAIR, speed: float = REFERENCE_SPEED, *,
                         duration: float = HORIZON, model: str = "thesis", scheme: str = "wchair",
                         impulse_force: float = THESIS_PUSH.force,
                         impulse_duration: float = THESIS_PUSH.duration) -> Any:
    """Figure 9-4: total yaw moment of the tire forces about the c.g. over time (open loop).

    Defaults are the thesis's reference case (:mod:`stability.settings.reference`:
    E&J Premier, 0.75 m/s, 40 N for 0.1 s at the c.g., thesis model, WCHAIR
    scheme and its warning rule).

    Parameters
    ----------
    chair : Chair or str
        Chair or preset name.
    speed : float
        m/s.
    duration : float
        s.
    model, scheme : str
        As :func:`stability.simulate.simulate`.
    impulse_force, impulse_duration : float
        N, s.

    Returns
    -------
    SimulationResult
        The curve is ``(result.t, result.tire_yaw_moment)``.
    """
    c = chair_mod.resolve(chair) if isinstance(chair, str) else chair
    return simulate(c, speed, RunSpec(horizon=duration, model=model, scheme=scheme, push_force=impulse_force,
                                      push_duration=impulse_duration))


def _first_slip_warning(res: Any) -> float:
    w = res.warnings.get("slip", {}) if isinstance(res.warnings, dict) else {}
    t = w.get("first_time")
    return float(t) if t is not None else float(res.t[-1]) + 1e-9


def valid_until(res: Any, max_heading_deg: float = 90.0) -> float:
    """End of the meaningful part of an open-loop run (s).

    The first time any tire's slip angle passes 8 deg (the simulator's
    warning; beyond it tested tire data are extrapolated and a linear tire
    model is not defensible either) or the heading reaches
    ``max_heading_deg``, whichever comes first.

    Parameters
    ----------
    res : SimulationResult
    max_heading_deg : float
        deg.

    Returns
    -------
    float
        s (just past the end of the run if neither happens).
    """
    tw = _first_slip_warning(res)
    slip = np.flatnonzero(np.any(np.abs(np.asarray(res.slip_deg)) > 8.0, axis=1))
    if slip.size:
        tw = min(tw, float(res.t[slip[0]]))
    big = np.flatnonzero(np.abs(np.degrees(np.asarray(res.heading))) >= max_heading_deg)
    return min(tw, float(res.t[big[0]])) if big.size else tw


@dataclass(frozen=True)
class DestabilisingSummary:
    """The thesis's criterion applied to an open-loop run, over its meaningful part.

    Attributes
    ----------
    valid_until_s : float
        End of the meaningful part (:func:`valid_until`, s).
    heading_at_end_deg : float
        Heading there (deg).
    peak_moment_N_m : float
        Largest ``|tire yaw moment|`` (N m).
    motor_capacity_N_m : float
        Yaw moment of the motors at their torque limit (N m).
    fraction_of_capacity : float
        ``peak_moment_N_m / motor_capacity_N_m``.
    exceeds_capacity_at_s : float or None
        When the moment first exceeds the capacity (s); None if never.
    """

    valid_until_s: float
    heading_at_end_deg: float
    peak_moment_N_m: float
    motor_capacity_N_m: float
    fraction_of_capacity: float
    exceeds_capacity_at_s: float | None

    def to_dict(self) -> dict[str, float | None]:
        """JSON-ready dict (keys with their units: ``peak_moment_N_m``, ``motor_capacity_N_m``)."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def destabilising_summary(res: Any, drive: DriveTrain, chair: Chair) -> DestabilisingSummary:
    """The thesis's criterion (chapter 9, "Future work") applied to an open-loop run.

    Parameters
    ----------
    res : SimulationResult
        An open-loop run.
    drive : DriveTrain
    chair : Chair

    Returns
    -------
    DestabilisingSummary
    """
    t = np.asarray(res.t)
    end = valid_until(res)
    k = t < end
    m = np.abs(np.asarray(res.tire_yaw_moment))[k]
    cap = drive.max_yaw_moment(chair)
    over = np.flatnonzero(m > cap)
    return DestabilisingSummary(
        valid_until_s=float(min(end, t[-1])),
        heading_at_end_deg=float(np.degrees(np.asarray(res.heading)[k][-1])) if k.any() else 0.0,
        peak_moment_N_m=float(m.max()) if m.size else 0.0,
        motor_capacity_N_m=float(cap),
        fraction_of_capacity=float(m.max() / cap) if m.size else 0.0,
        exceeds_capacity_at_s=float(t[k][over[0]]) if over.size else None,
    )
