"""Stability about the slope equilibrium: eigenvalues and critical speeds against speed.

Central differences of the exact equations with gravity
(:meth:`stability.slope.model.SlopeModel.accelerations`) about the straight
running equilibrium of :func:`stability.slope.equilibrium.solve` (casters no
longer trailing straight, loads transferred, tires at nonzero slip), in the
lateral states ``[v, r, eta, eta_dot, beta, beta_dot]`` of
:data:`stability.linear.STATES_FREE` with the forward speed, heading and drive
forces held.  On level ground this is :func:`stability.linear.state_matrices`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.linear import critical_speeds
from stability.runtime.checks import check_speeds
from stability.slope.equilibrium import _root, _state
from stability.slope.model import Plane, SlopeModel

__all__ = ["state_matrix", "SlopeStability", "stability_vs_speed", "slope_critical_speeds"]


def _equilibrium(model: SlopeModel, speed: float):
    z, ok = _root(model, speed)
    if not ok:
        raise ValueError(f"speed={speed!r}: no straight-running equilibrium on cross slope "
                         f"{model.plane.cross_slope_deg:g} deg")
    _, _, drive, _ = _state(model, speed, z)
    return z, drive


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
    model = SlopeModel(chair, plane)
    (psi, eta, beta), drive = _equilibrium(model, speed)
    u, v = speed * math.cos(psi), -speed * math.sin(psi)
    x0 = np.array([v, 0.0, eta, 0.0, beta, 0.0])

    def f(x):
        acc, _ = model.accelerations(u, x[0], x[1], x[2], x[3], x[4], x[5], psi, drive)
        return np.array([acc[1], acc[2], x[3], acc[3], x[5], acc[4]])

    A = np.empty((6, 6))
    for j in range(6):
        dx = np.zeros(6)
        dx[j] = step
        A[:, j] = (f(x0 + dx) - f(x0 - dx)) / (2 * step)
    return A


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
