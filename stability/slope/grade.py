"""Grades: speed change with constant propulsion, and the stability of the faster chair.

On a grade ``theta`` (uphill +) with the drive force that holds the speed on
level ground kept constant (zero with rolling resistance off), the chair
accelerates at ``a = -g sin(theta) - (rolling change)/m`` (the loads, hence
rolling resistance, scale with ``cos(theta)``; the tire forces sum to the
constant propulsion, so there is no load transfer from the grade while
coasting).  The lateral stability at the speeds reached comes from
:func:`stability.slope.linear.stability_vs_speed` on the grade.  See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.runtime.checks import check_positive, check_speed
from stability.slope.linear import stability_vs_speed
from stability.slope.model import Plane, SlopeModel

__all__ = ["GradeRun", "grade_run", "forward_gravity"]


def forward_gravity(chair: Chair, grade_deg: float) -> float:
    """Forward component of the weight on a grade, ``-m g sin(theta)`` (N; uphill grade +).

    Parameters
    ----------
    chair : Chair
        The chair (mass m, kg; gravity g, m/s^2).
    grade_deg : float
        Grade theta, deg (positive uphill).

    Returns
    -------
    float
        Forward component of the weight in the plane, N (negative uphill).
    """
    return float(SlopeModel(chair, Plane(0.0, grade_deg)).plane.gravity(chair.g)[0] * chair.m)


@dataclass(frozen=True)
class GradeRun:
    """Constant propulsion on a grade.

    Attributes
    ----------
    grade_deg : float
    acceleration : float
        Forward acceleration (m/s^2).
    times : ndarray
        (s).
    speeds : ndarray
        Speed at each time (m/s); stops at zero uphill.
    max_real : ndarray
        Largest real part of the lateral eigenvalues at each speed (1/s; NaN where stopped).
    doubling_time : ndarray
        ``ln 2 / max_real`` where positive (s; inf where stable).
    """

    grade_deg: float
    acceleration: float
    times: np.ndarray
    speeds: np.ndarray
    max_real: np.ndarray
    doubling_time: np.ndarray

    def to_dict(self) -> dict:
        """JSON-ready dict."""
        return {"grade_deg": self.grade_deg, "acceleration_m_s2": self.acceleration,
                "times_s": self.times.tolist(), "speeds_m_s": self.speeds.tolist(),
                "max_real_part_1_s": [None if not math.isfinite(x) else x for x in self.max_real],
                "doubling_time_s": [None if not math.isfinite(x) else x for x in self.doubling_time]}


def grade_run(chair: Chair, grade_deg: float, speed: float, duration: float = 5.0, n: int = 6) -> GradeRun:
    """Speed and lateral stability of a chair rolling onto a grade with unchanged propulsion.

    Parameters
    ----------
    chair : Chair
    grade_deg : float
        Grade (deg), uphill +.
    speed : float
        Speed when the grade starts (m/s).
    duration : float
        Time span (s).
    n : int
        Number of times reported.

    Returns
    -------
    GradeRun
    """
    speed = check_speed(speed)
    check_positive("duration", duration)
    level = SlopeModel(chair, Plane(0.0, 0.0))
    model = SlopeModel(chair, Plane(0.0, grade_deg))
    g_lvl = level.plane.gravity(chair.g)
    g_gr = model.plane.gravity(chair.g)
    f0 = level.forces(speed, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, (0.0, 0.0), g_lvl)
    propulsion = -sum(f0.F[k] for k in (0, 2, 4, 6))          # holds speed on level ground
    half = 0.5 * propulsion
    f1 = model.forces(speed, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, (half, half), g_gr)
    acc = (sum(f1.F[k] for k in (0, 2, 4, 6))) / chair.m + g_gr[0]
    t = np.linspace(0.0, duration, n)
    U = speed + acc * t
    mr = np.full(n, np.nan)
    ok = U > 0.05
    if ok.any():
        st = stability_vs_speed(chair, 0.0, U[ok] if acc >= 0 else U[ok][::-1], grade_deg, critical=False)
        mr[ok] = st.max_real if acc >= 0 else st.max_real[::-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        dbl = np.where(mr > 0, math.log(2.0) / mr, np.inf)
    return GradeRun(grade_deg=float(grade_deg), acceleration=float(acc), times=t, speeds=np.maximum(U, 0.0),
                    max_real=mr, doubling_time=dbl)
