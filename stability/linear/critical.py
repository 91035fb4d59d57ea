"""Critical speeds: where the largest real part of a speed-parameterised system crosses zero."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["Crossing", "GUARD_FRACTIONS", "critical_speeds", "hermite", "max_real_part"]


@dataclass(frozen=True)
class Crossing:
    """A speed where the largest real part of the eigenvalues crosses zero.

    Attributes
    ----------
    speed : float
        Critical speed (m/s), refined to 1e-10 m/s.
    kind : {"real", "complex"}
        "real": a real eigenvalue crosses (divergence); "complex": a complex
        pair crosses (oscillatory, flutter/shimmy-like instability).
    direction : {"destabilising", "stabilising"}
        Whether the system becomes unstable or stable as speed increases.
    eigenvalue : complex
        The crossing eigenvalue at the critical speed (imaginary part gives
        the frequency of an oscillatory crossing, rad/s).
    """

    speed: float
    kind: str
    direction: str
    eigenvalue: complex


def max_real_part(state_matrix: Callable[[np.ndarray], np.ndarray], speeds) -> np.ndarray:
    """Largest real part of the eigenvalues of ``state_matrix(speeds)`` (1/s).

    Parameters
    ----------
    state_matrix : callable
        Maps a 1-D array of N speeds (m/s) to an (N, n, n) array of state matrices.
    speeds : float or array_like
        Forward speeds U (m/s).

    Returns
    -------
    numpy.ndarray
        Shape (N,): ``max Re(lambda)`` at each speed, 1/s (> 0: unstable).
    """
    A = np.asarray(state_matrix(np.atleast_1d(np.asarray(speeds, dtype=float))))
    return np.linalg.eigvals(A).real.max(axis=-1)


def _slopes(state_matrix, speeds: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """d(alpha)/dU at the grid points from eigenvalue perturbation theory.

    ``d lambda = (w^H dA v) / (w^H v)`` for the eigenvalue of largest real
    part, with ``dA`` by a central difference of the state matrix.
    """
    h = 1e-6 * np.maximum(1.0, np.abs(speeds))
    lo = np.maximum(speeds - h, speeds * 0.5)
    dA = (np.asarray(state_matrix(speeds + h)) - np.asarray(state_matrix(lo))) / (speeds + h - lo)[:, None, None]
    A = np.asarray(state_matrix(speeds))
    lam, V = np.linalg.eig(A)
    lamL, W = np.linalg.eig(np.swapaxes(A, -1, -2).conj())
    k = np.arange(len(speeds))
    i = np.argmax(lam.real, axis=1)
    j = np.argmin(np.abs(lamL.conj() - lam[k, i][:, None]), axis=1)
    v, w = V[k, :, i], W[k, :, j]                      # the right and left eigenvectors, one row per speed
    den = np.sum(w.conj() * v, axis=1)
    num = np.sum(w.conj() * np.einsum("kab,kb->ka", dA, v), axis=1)
    ok = np.abs(den) > 1e-14
    return np.where(ok, (num / np.where(ok, den, 1.0)).real, 0.0)


#: Where the double-crossing guard samples the Hermite interpolant: fractions of a grid interval.
GUARD_FRACTIONS = np.linspace(0.0, 1.0, 9)[1:-1]


def hermite(a0: float | np.ndarray, a1: float | np.ndarray, s0: float | np.ndarray, s1: float | np.ndarray,
            h: float | np.ndarray, t: np.ndarray = GUARD_FRACTIONS) -> np.ndarray:
    """Cubic Hermite interpolant on an interval of width ``h`` from its end values and slopes.

    Parameters
    ----------
    a0, a1 : float or ndarray
        Values at the interval's ends (unit of the value, 1/s for ``alpha``); arrays of shape (n, 1): n intervals.
    s0, s1 : float or ndarray
        Slopes at the ends (value per unit of the abscissa, 1/s per m/s for ``alpha``).
    h : float or ndarray
        Width of the interval (unit of the abscissa, m/s).
    t : ndarray, optional
        Fractions of the interval (0 at ``a0``, 1 at ``a1``); default :data:`GUARD_FRACTIONS`.

    Returns
    -------
    ndarray
        The interpolant at ``t`` (unit of the value), one row per interval; exact for a cubic.
    """
    h00, h10 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t
    h01, h11 = -2 * t**3 + 3 * t**2, t**3 - t**2
    return h00 * a0 + h10 * h * s0 + h01 * a1 + h11 * h * s1


def critical_speeds(state_matrix: Callable[[np.ndarray], np.ndarray], speeds,
                    xtol: float = 1e-10) -> list[Crossing]:
    """Every speed in the grid's range where the largest real part crosses zero.

    Works for any speed-parameterised linear system.

    Parameters
    ----------
    state_matrix : callable
        Maps a 1-D array of N speeds to an (N, n, n) array of state matrices.
    speeds : array_like
        Search grid (m/s), increasing, positive.
    xtol : float
        Absolute tolerance of the refined speeds (m/s).

    Returns
    -------
    list of Crossing
        Sorted by speed.

    Notes
    -----
    ``alpha(U) = max Re(lambda)`` is continuous in U; each sign change between
    grid points is refined with Brent's method to ``xtol``.  A pair of roots
    that crosses and re-crosses between two grid points leaves no sign change
    on the grid.  The guard: the slope of ``alpha`` at every grid point is
    computed from eigenvalue perturbation theory, and on every interval where
    the cubic Hermite interpolant of ``alpha`` (values and slopes) comes within
    a margin of zero or where the slopes change sign, ``alpha`` is maximised
    (bounded Brent) inside the interval; if the maximum is positive the two
    crossings on either side are refined separately.  Only a crossing pair
    narrower than both the grid and the curvature implied by the endpoint
    slopes can escape, which the Hermite test makes a measurable hazard
    rather than a silent one.
    """
    from scipy.optimize import brentq, minimize_scalar

    U = np.asarray(speeds, dtype=float)
    if U.ndim != 1 or len(U) < 2:
        raise ValueError(f"speeds must be a 1-D grid of at least 2 speeds, got shape {U.shape}")
    if np.any(np.diff(U) <= 0):
        raise ValueError("speeds must be strictly increasing")
    if U[0] <= 0:
        raise ValueError(f"speeds[0]={float(U[0])!r} is invalid; valid range: speed > 0 m/s")

    def alpha(x: float) -> float:
        return float(max_real_part(state_matrix, np.array([x]))[0])

    a = max_real_part(state_matrix, U)
    brackets: list[tuple[float, float]] = []
    for k in range(len(U) - 1):
        if a[k] == 0.0:
            continue
        if np.sign(a[k]) != np.sign(a[k + 1]) and a[k + 1] != 0.0:
            brackets.append((U[k], U[k + 1]))
    # exact zeros on grid points: bracket around them
    for kz in np.flatnonzero(a == 0.0):
        k = int(kz)
        lo = U[k - 1] if k > 0 else U[k]
        hi = U[k + 1] if k < len(U) - 1 else U[k]
        if lo < hi and np.sign(alpha(lo)) != np.sign(alpha(hi)):
            brackets.append((lo, hi))

    # guard against double crossings hidden between grid points
    da = _slopes(state_matrix, U, a)
    scale = max(np.max(np.abs(a)), 1e-9)
    h = np.diff(U)[:, None]
    a0, a1, d0, d1 = a[:-1, None], a[1:, None], da[:-1, None], da[1:, None]
    herm = hermite(a0, a1, d0, d1, h)                                # one row per grid interval
    same = np.sign(a[:-1]) == np.sign(a[1:])
    suspicious = same & (np.any(np.sign(herm) != np.sign(a0), axis=1) | (
        (np.sign(da[:-1]) != np.sign(da[1:])) & (np.min(np.abs(herm), axis=1) < 0.05 * scale)))
    for kk in np.flatnonzero(suspicious):
        k = int(kk)
        sgn = np.sign(a[k])
        res = minimize_scalar(lambda x, sgn=sgn: sgn * alpha(x), bounds=(U[k], U[k + 1]), method="bounded",
                              options={"xatol": 1e-9})
        if np.sign(alpha(res.x)) != sgn:
            brackets.append((U[k], res.x))
            brackets.append((res.x, U[k + 1]))

    out: list[Crossing] = []
    for lo, hi in sorted(set(brackets)):
        s = brentq(alpha, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=500)
        lam = np.linalg.eigvals(np.asarray(state_matrix(np.array([s])))[0])
        i = int(np.argmax(lam.real))
        kind = "complex" if abs(lam[i].imag) > 1e-8 * max(1.0, abs(lam[i])) else "real"
        direction = "destabilising" if alpha(hi) > alpha(lo) else "stabilising"
        out.append(Crossing(float(s), kind, direction, complex(lam[i])))
    return out
