"""Stability about straight running on a slope, and grades: the simulator's own linearisation on the plane.

Central differences of the simulator's right-hand side
(:func:`stability.simulate.linearise` with ``slope=`` and the operating point)
about the straight-running equilibrium of the slope statics
(:func:`stability.slope.equilibrium.operating_point`: casters no longer
trailing straight, loads transferred, tires at nonzero slip), in the lateral
states ``[v, r, eta, eta_dot, beta, beta_dot]`` of
:data:`stability.linear.STATES_FREE` with the forward speed, heading and the
statics' drive forces held.  On level ground this is
:func:`stability.linear.state_matrices` (the simulator's linearisation equals
the linear model there).  The simulator has no viscous pin damping:
``pin_damping`` is not modelled.  Grades: with the propulsion that holds the
speed on level ground kept, the chair accelerates at ``-g sin(theta)`` and the
change of rolling resistance, and the stability at the speeds reached follows.
See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.linear import critical_speeds
from stability.runtime.checks import check_positive, check_speed, check_speeds
from stability.simulate.linearise import forward_acceleration, linearise
from stability.slope.equilibrium import operating_point
from stability.slope.model import Plane
from stability.study.veer import plane_seen_from

__all__ = ["state_matrix", "SlopeStability", "stability_vs_speed", "slope_critical_speeds", "GradeRun", "grade_run",
           "forward_gravity"]


def state_matrix(chair: Chair, plane: Plane, speed: float, step: float = 1e-6) -> np.ndarray:
    """State matrix (6x6) of the lateral motion about straight running on ``plane`` at ``speed``.

    Parameters
    ----------
    chair : Chair
    plane : Plane
    speed : float
        Speed along the path (m/s).
    step : float
        Central-difference step (SI units of each state).

    Returns
    -------
    ndarray
        ``d/dt [v, r, eta, eta_dot, beta, beta_dot] = A [...]`` (1/s).
    """
    psi, eta, beta, drive = operating_point(chair, plane, speed)
    u, v = speed * math.cos(psi), -speed * math.sin(psi)
    sys = linearise(chair, u, model="exact", step=step, slope=plane_seen_from(chair, plane, psi), at=(v, eta, beta),
                    drive=drive)
    return np.asarray(sys.A)


@dataclass(frozen=True)
class SlopeStability:
    """Eigenvalues about the slope equilibrium against speed.

    Attributes
    ----------
    cross_slope_deg, grade_deg : float
    speeds : ndarray
        (m/s).
    eigenvalues : ndarray
        (N, 6) complex, sorted by decreasing real part (1/s).
    max_real : ndarray
        Largest real part at each speed (1/s).
    critical : tuple
        Speeds where the largest real part crosses zero (m/s).
    """

    cross_slope_deg: float
    grade_deg: float
    speeds: np.ndarray
    eigenvalues: np.ndarray
    max_real: np.ndarray
    critical: tuple

    def to_dict(self) -> dict:
        """JSON-ready summary."""
        return {"cross_slope_deg": self.cross_slope_deg, "grade_deg": self.grade_deg,
                "speeds_m_s": self.speeds.tolist(), "max_real_part_1_s": self.max_real.tolist(),
                "critical_speeds_m_s": list(self.critical)}


def _matrices(chair: Chair, plane: Plane):
    def fn(speeds) -> np.ndarray:
        return np.stack([state_matrix(chair, plane, float(U)) for U in np.atleast_1d(speeds)])
    return fn


def slope_critical_speeds(chair: Chair, plane: Plane, speeds) -> tuple:
    """Speeds in the range of ``speeds`` where the largest real part crosses zero, on a plane.

    Parameters
    ----------
    chair : Chair
        The chair.
    plane : Plane
        Cross slope and grade, deg.
    speeds : array_like
        Search grid, m/s (increasing, > 0); crossings are refined to 1e-4 m/s.

    Returns
    -------
    tuple of float
        Critical speeds, m/s, in increasing order; empty if none in the range.
    """
    U = check_speeds(speeds)
    return tuple(float(c.speed) for c in critical_speeds(_matrices(chair, plane), U, xtol=1e-4))


def stability_vs_speed(chair: Chair, cross_slope_deg: float, speeds, grade_deg: float = 0.0,
                       critical: bool = True) -> SlopeStability:
    """Eigenvalues of the lateral motion about the slope equilibrium at each speed.

    Parameters
    ----------
    chair : Chair
    cross_slope_deg, grade_deg : float
        The plane (deg).
    speeds : array_like
        Increasing speeds (m/s).
    critical : bool
        Also locate the critical speeds (zero crossings of the largest real part).

    Returns
    -------
    SlopeStability
    """
    U = check_speeds(speeds)
    plane = Plane(cross_slope_deg, grade_deg)
    A = _matrices(chair, plane)(U)
    eig = np.linalg.eigvals(A)
    eig = np.take_along_axis(eig, np.argsort(-eig.real, axis=1), axis=1)
    crit = slope_critical_speeds(chair, plane, U) if critical and len(U) > 1 else ()
    return SlopeStability(cross_slope_deg=plane.cross_slope_deg, grade_deg=plane.grade_deg, speeds=U,
                          eigenvalues=eig, max_real=eig[:, 0].real, critical=crit)


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
    return float(Plane(0.0, grade_deg).gravity(chair.g)[0] * chair.m)


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
    half = -0.5 * chair.m * forward_acceleration(chair, speed)     # the propulsion that holds the speed when level
    acc = forward_acceleration(chair, speed, slope=(0.0, grade_deg), drive=(half, half))
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
