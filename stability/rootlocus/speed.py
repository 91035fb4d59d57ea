"""Eigenvalues of the linear model as the forward speed varies (the parametric root locus)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.linear import STATES_FREE, STATES_LOCKED, critical_speeds, state_matrices, track_modes
from stability.runtime.checks import check_casters, check_model

__all__ = ["SpeedLocus", "speed_locus", "layout_speed_locus", "readonly"]


def readonly(a) -> np.ndarray:
    """A read-only copy of ``a`` (result arrays are immutable).

    Parameters
    ----------
    a : array_like
        Values to copy.

    Returns
    -------
    numpy.ndarray
        A new array with ``writeable`` False.
    """
    a = np.array(a)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class SpeedLocus:
    """Eigenvalues of a linear model as the forward speed varies.

    Attributes
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    casters : {"free", "locked"}
    speeds : ndarray, shape (N,)
        Increasing forward speeds (m/s).
    eigenvalues : ndarray, shape (N, n)
        Column ``j`` is one tracked branch (mode), 1/s.
    crossings : list of Crossing
        Critical speeds: where the largest real part crosses zero.
    states : tuple of str
        State names of the model.
    """

    chair: Chair
    model: str
    casters: str
    speeds: np.ndarray
    eigenvalues: np.ndarray
    crossings: list = field(default_factory=list)
    states: tuple = ()

    @property
    def max_real(self) -> np.ndarray:
        """Largest real part at each speed (1/s)."""
        return self.eigenvalues.real.max(axis=1)

    @property
    def unstable(self) -> np.ndarray:
        """Boolean mask of the speeds at which some eigenvalue has a positive real part."""
        return self.max_real > 0

    def unstable_intervals(self) -> list[tuple[float, float]]:
        """Speed intervals (m/s) in which the model is unstable, ends refined to the crossings."""
        out: list[tuple[float, float]] = []
        U = self.speeds
        start: float = float(U[0])
        crit = sorted(c.speed for c in self.crossings)
        inside = bool(self.unstable[0])
        for s in crit:
            if inside:
                out.append((start, s))
                inside = False
            else:
                start, inside = s, True
        if inside:
            out.append((start, float(U[-1])))
        return out

    @property
    def title(self) -> str:
        return f"{self.chair.name}, {self.model} model, {self.casters} casters"


@takes_chair
def speed_locus(chair: Chair, speeds=None, *, model: str = "exact", casters: str = "free",
                max_speed: float = 15.0, n: int = 600) -> SpeedLocus:
    """Eigenvalues against forward speed, tracked, and the critical speeds.

    Parameters
    ----------
    chair : Chair
        The chair.
    speeds : array_like, optional
        Increasing speeds (m/s, > 0, at least 2); default ``geomspace(0.05, max_speed, n)``.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Caster state (default ``"free"``).
    max_speed : float, optional
        Upper end of the default speeds, m/s (> 0.05, default 15); ignored when ``speeds`` is given.
    n : int, optional
        Number of default speeds (default 600); ignored when ``speeds`` is given.

    Returns
    -------
    SpeedLocus
        Speeds (m/s), tracked eigenvalues at each (1/s), the speeds where the
        largest real part crosses zero, and the state names.

    Raises
    ------
    ValueError
        If ``speeds`` is not increasing and positive, ``max_speed`` <= 0.05, or
        the model or caster state is invalid.
    """
    check_model(model)
    check_casters(casters)
    if speeds is None:
        if not (math.isfinite(max_speed) and max_speed > 0.05):
            raise ValueError(f"max_speed={max_speed!r} is invalid; valid range: > 0.05 m/s")
        speeds = np.geomspace(0.05, max_speed, int(n))
    U = np.asarray(speeds, dtype=float)
    if U.ndim != 1 or len(U) < 2 or np.any(np.diff(U) <= 0) or U[0] <= 0:
        raise ValueError("speeds must be an increasing 1-D array of at least 2 positive speeds (m/s)")
    A = state_matrices(chair, U, model, casters)
    eig = track_modes(np.linalg.eigvals(A))
    crossings = critical_speeds(lambda s: state_matrices(chair, s, model, casters), U)
    states = STATES_FREE if casters == "free" else STATES_LOCKED
    return SpeedLocus(chair, model, casters, readonly(U), readonly(eig), list(crossings), tuple(states))


def layout_speed_locus(layout, *, reverse: bool = False, max_speed: float = 15.0, n: int = 600) -> SpeedLocus:
    """Eigenvalues of a wheel layout's linear model against the speed's size, forward or in reverse, tracked.

    :func:`speed_locus` on :func:`stability.layout.linear.state_matrices` (free frictionless casters, trailing at
    0 deg forwards and at 180 deg in reverse), with the same tracking and crossing search.

    Parameters
    ----------
    layout : stability.layout.Layout
    reverse : bool
        Backwards: the matrices at ``-U``.
    max_speed : float
        Upper end of the speeds' sizes, m/s (0.05 < value <= 20, the layout model's range).
    n : int
        Number of speeds (geometric from 0.05 m/s).

    Returns
    -------
    SpeedLocus
        ``chair`` the layout, ``model`` ``"layout"``, ``casters`` ``"free"``; ``speeds`` the sizes (m/s).
    """
    from stability.layout.linear import state_matrices as layout_matrices
    from stability.layout.linear import states

    if not (math.isfinite(max_speed) and 0.05 < max_speed <= 20.0):
        raise ValueError(f"max_speed={max_speed!r} is invalid; valid range: 0.05 < value <= 20 m/s")
    sign = -1.0 if reverse else 1.0
    U = np.geomspace(0.05, max_speed, int(n))
    eig = track_modes(np.linalg.eigvals(layout_matrices(layout, sign * U)))
    # the crossing search's slope probe steps 1e-6 U past the grid's end: held at the model's 20 m/s there (the
    # probe only guards against hidden double crossings; the crossings themselves are refined inside the grid)
    crossings = critical_speeds(lambda s: layout_matrices(layout, sign * np.minimum(np.asarray(s, dtype=float),
                                                                                     20.0)), U)
    return SpeedLocus(layout, "layout", "free", readonly(U), readonly(eig), list(crossings), states(layout))
