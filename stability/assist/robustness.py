"""Closed-loop stability when the chair differs from the design model: corners of a parameter box."""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from stability.assist.design import closed_loop_poles
from stability.assist.plant import plant
from stability.assist.schedule import Schedule
from stability.chair import Chair

__all__ = ["ROBUST_PARAMETERS", "WorstCorner", "Robustness", "robustness"]

#: Parameters of the robustness box.
ROBUST_PARAMETERS = ("mass", "yaw_inertia", "main_stiffness", "caster_stiffness")


def _perturbed(chair: Chair, factors: dict[str, float]) -> Chair:
    return chair.replace(
        m=chair.m * factors["mass"],
        i_z=chair.i_z * factors["yaw_inertia"],
        main_lateral_scale=chair.main_lateral_scale * factors["main_stiffness"],
        caster_lateral_scale=chair.caster_lateral_scale * factors["caster_stiffness"],
    )


@dataclass(frozen=True)
class WorstCorner:
    """The least stable closed loop of a robustness box.

    Attributes
    ----------
    max_real_1_s : float
        Its largest closed-loop real part (1/s).
    speed_m_s : float
        At this design speed (m/s).
    corner : dict
        ``{parameter: factor}``.
    """

    max_real_1_s: float
    speed_m_s: float
    corner: dict[str, float]

    def describe(self) -> str:
        """``mass x1.30, yaw_inertia x0.70, ...``."""
        return ", ".join(f"{k} x{v:.2f}" for k, v in self.corner.items())


@dataclass(frozen=True, eq=False)
class Robustness:
    """Closed-loop stability over the corners of a parameter box, nominal controller.

    Attributes
    ----------
    box : float
        Relative half-width of the box (0.3: +/-30 %).
    speeds : ndarray (N,)
        Design speeds (m/s).
    corners : list of dict
        ``{parameter: factor}`` for each corner (mass, yaw inertia, main-tire
        and caster-tire cornering stiffness scaled independently: 16
        corners), the nominal chair first.
    max_real : ndarray (n_corners, N)
        Largest closed-loop real part (1/s) per corner and speed.
    worst : WorstCorner
        The largest real part, its speed and corner.
    stable : bool
        All corners stable at all speeds.
    """

    box: float
    speeds: np.ndarray
    corners: list[dict[str, float]]
    max_real: np.ndarray
    worst: WorstCorner
    stable: bool


def robustness(sched: Schedule, box: float = 0.3) -> Robustness:
    """Closed-loop stability of the scheduled controller when the chair differs from the design model.

    Mass, yaw inertia, main-tire and caster-tire cornering stiffness are each
    scaled by ``1 - box`` or ``1 + box`` (all 16 corners, plus the nominal
    chair); at every design speed the nominal controller closes the loop
    around the perturbed linear plant.  The stiffnesses are scaled through
    the lateral-force scale factors (TYMOD, CYMOD), so load-dependent tires
    also see the changed loads of the changed mass.

    Parameters
    ----------
    sched : Schedule
    box : float
        Relative half-width, 0 <= box < 1.

    Returns
    -------
    Robustness
    """
    if not (isinstance(box, (int, float)) and 0 <= box < 1):
        raise ValueError(f"box={box!r} is invalid; valid range: 0 <= box < 1")
    corners = [{k: 1.0 for k in ROBUST_PARAMETERS}]
    for signs in itertools.product((-1.0, 1.0), repeat=len(ROBUST_PARAMETERS)):
        corners.append({k: 1.0 + s * box for k, s in zip(ROBUST_PARAMETERS, signs, strict=True)})
    mr = np.empty((len(corners), len(sched.speeds)))
    for i, f in enumerate(corners):
        c = _perturbed(sched.chair, f)
        for j, (s, d) in enumerate(zip(sched.speeds, sched.designs, strict=True)):
            mr[i, j] = closed_loop_poles(d, plant(c, s, sched.model, sched.drive.motor_time_constant)).real.max()
    iw, jw = np.unravel_index(int(np.argmax(mr)), mr.shape)
    worst = WorstCorner(float(mr[iw, jw]), float(sched.speeds[jw]), dict(corners[iw]))
    return Robustness(float(box), sched.speeds.copy(), corners, mr, worst, bool(np.all(mr < 0)))
