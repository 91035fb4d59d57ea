"""Linear results for many chairs at once: growth rates and first critical speeds, vectorised over chairs.

Parameters and tire stiffnesses are packed once per chair; the state matrices of
every (speed, chair) pair then come from one broadcast call of the generated
equations, and critical speeds are refined by bisection on all chairs together.
Used by Monte Carlo uncertainty propagation and parameter studies.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from stability.chair import Chair
from stability.linear.model import _assemble, _stiffness_for
from stability.models import linear_matrices
from stability.models.params import parameters
from stability.runtime.checks import check_casters, check_model

__all__ = ["ChairBatch", "MAX_MATRICES", "EIGEN_SECONDS", "MAX_EIGEN_SOLVES", "check_eigen_work"]

#: Largest number of state matrices assembled and solved in one call (memory bounded whatever the number of
#: chairs and speeds): about 1 kB each with numpy's intermediates (order 6 to 8), so some 50 MB at most;
#: more are solved in chunks of chairs.
MAX_MATRICES = 50_000
#: Cost of one eigenvalue problem of the linear model (order 6 to 8) in a batch, s: 25 us measured on one
#: core of the 2-core CI machine with nothing else running, 76 us with both cores shared by other work.
EIGEN_SECONDS = 25e-6
#: Largest number of eigenvalue problems one call may ask for: 2.4e7 x 25 us = 10 minutes.
MAX_EIGEN_SOLVES = 24_000_000


def check_eigen_work(name: str, value: int, solves_per_unit: float) -> None:
    """Refuse ``value`` units of work (samples, chairs) costing ``solves_per_unit`` eigenvalue problems each.

    Parameters
    ----------
    name : str
        The argument or option that asked for it (``"samples"``, ``"--samples"``).
    value : int
        Units asked for.
    solves_per_unit : float
        Eigenvalue problems per unit.

    Raises
    ------
    ValueError
        Naming ``name``, the estimated time and the largest allowed value.
    """
    if value * solves_per_unit > MAX_EIGEN_SOLVES:
        largest = int(MAX_EIGEN_SOLVES // solves_per_unit)
        raise ValueError(f"{name}={value} is invalid: it asks for {value * solves_per_unit:.3g} eigenvalue problems "
                         f"(about {value * solves_per_unit * EIGEN_SECONDS / 60:.0f} min); the largest allowed "
                         f"here is {name}={largest}")


class ChairBatch:
    """N chairs packed for the linear model (parameters and static stiffnesses computed once).

    Parameters
    ----------
    chairs : sequence of Chair
        The chairs (N >= 1).
    model : {"exact", "thesis"}
        Equation variant.
    """

    def __init__(self, chairs: Sequence[Chair], model: str = "exact") -> None:
        if not len(chairs):
            raise ValueError("chairs: expected at least one chair")
        self.model = check_model(model)
        self.n = len(chairs)
        self._p = parameters(list(chairs))
        self._stiffness = _stiffness_for(list(chairs))

    def state_matrices(self, speeds, casters: str = "free") -> np.ndarray:
        """State matrices at speeds of shape (..., N) or broadcastable to it.

        Parameters
        ----------
        speeds : array_like
            Forward speeds, m/s, broadcast against the N chairs (last axis).
        casters : {"free", "locked"}

        Returns
        -------
        ndarray
            Shape ``broadcast(speeds, (N,)) + (n, n)``.
        """
        check_casters(casters)
        U = np.asarray(speeds, dtype=float)
        M, K, Bm = linear_matrices(self._p, U, self._stiffness, variant=self.model, casters=casters)
        return _assemble(M, K, Bm, casters)[0]

    def max_real_part(self, speeds, casters: str = "free") -> np.ndarray:
        """Largest real part of the eigenvalues (1/s) at ``speeds`` (broadcast against the chairs).

        Parameters
        ----------
        speeds : array_like
            Speeds, m/s, shape (..., N) or broadcastable.
        casters : {"free", "locked"}

        Returns
        -------
        ndarray
            Shape ``broadcast(speeds, (N,))``.
        """
        U = np.asarray(speeds, dtype=float)
        U = np.broadcast_to(U, np.broadcast_shapes(U.shape, (self.n,)))
        per_chair = max(1, U.size // self.n)
        step = max(1, MAX_MATRICES // per_chair)
        if step >= self.n:
            return np.linalg.eigvals(self.state_matrices(U, casters)).real.max(axis=-1)
        out = np.empty(U.shape)
        for i in range(0, self.n, step):           # bounded memory: chunks of chairs
            idx = np.arange(i, min(i + step, self.n))
            out[..., idx] = _SubBatch(self, idx).max_real_part(U[..., idx], casters)
        return out

    def growth_rates(self, speeds: Sequence[float] | np.ndarray, casters: str = "free") -> np.ndarray:
        """Growth rate of the least stable mode of every chair at every speed (1/s).

        Parameters
        ----------
        speeds : sequence of float
            K speeds, m/s.
        casters : {"free", "locked"}

        Returns
        -------
        ndarray
            Shape (N, K).
        """
        U = np.asarray(speeds, dtype=float)[:, None]
        return self.max_real_part(np.broadcast_to(U, (len(U), self.n)), casters).T

    def first_critical_speed(self, grid: Sequence[float] | np.ndarray, casters: str = "free",
                             xtol: float = 1e-6) -> np.ndarray:
        """Lowest speed on ``grid`` where each chair turns unstable (largest real part crosses zero upwards).

        Parameters
        ----------
        grid : sequence of float
            Increasing search speeds, m/s.
        casters : {"free", "locked"}
        xtol : float
            Bisection tolerance, m/s.

        Returns
        -------
        ndarray
            Shape (N,), m/s; NaN where no destabilising crossing lies in the grid's range
            (stable throughout, or unstable from the first grid speed: :meth:`first_critical_speed_bounded` tells
            which).
        """
        return self._first_crossing(grid, casters, xtol)[0]

    def first_critical_speed_bounded(self, grid: Sequence[float] | np.ndarray, casters: str = "free",
                                     xtol: float = 1e-6) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`first_critical_speed` with a bound where the grid holds no destabilising crossing.

        A bound is a value: a chair stable at every grid speed is stable up to at least the grid's last speed
        (status ``"above"``, the best a ranking can say), a chair already unstable at the first grid speed and
        never turning unstable from stable on the grid is stable up to at most the first (``"below"``, the worst).

        Parameters
        ----------
        grid, casters, xtol
            As :meth:`first_critical_speed` (m/s, ``"free"`` or ``"locked"``, m/s).

        Returns
        -------
        speeds : ndarray
            Shape (N,), m/s: the crossing, or the bound (the grid's last speed for ``"above"``, its first for
            ``"below"``).
        statuses : ndarray of str
            Shape (N,): ``"found"``, ``"above"`` or ``"below"``
            (:func:`stability.study.censored.side_of` reads them).
        """
        U = np.asarray(grid, dtype=float)
        out, stable_first = self._first_crossing(U, casters, xtol)
        found = np.isfinite(out)
        status = np.where(found, "found", np.where(stable_first, "above", "below")).astype(object)
        return np.where(found, out, np.where(stable_first, U[-1], U[0])), status

    def _first_crossing(self, grid: Sequence[float] | np.ndarray, casters: str,
                        xtol: float) -> tuple[np.ndarray, np.ndarray]:
        """The first destabilising crossing (NaN where none) and whether each chair is stable at the first grid
        speed."""
        U = np.asarray(grid, dtype=float)
        a = self.max_real_part(np.broadcast_to(U[:, None], (len(U), self.n)), casters)  # (G, N)
        stable_first = a[0] < 0
        up = (a[:-1] < 0) & (a[1:] >= 0)
        has = up.any(axis=0)
        k = np.argmax(up, axis=0)
        lo = np.where(has, U[k], np.nan)
        hi = np.where(has, U[np.minimum(k + 1, len(U) - 1)], np.nan)
        idx = np.flatnonzero(has)
        if idx.size == 0:
            return np.full(self.n, np.nan), stable_first
        lo_i, hi_i = lo[idx], hi[idx]
        sub = _SubBatch(self, idx)
        while np.max(hi_i - lo_i) > xtol:
            mid = 0.5 * (lo_i + hi_i)
            am = sub.max_real_part(mid, casters)
            neg = am < 0
            lo_i = np.where(neg, mid, lo_i)
            hi_i = np.where(neg, hi_i, mid)
        out = np.full(self.n, np.nan)
        out[idx] = 0.5 * (lo_i + hi_i)
        return out, stable_first


class _SubBatch(ChairBatch):
    """The chairs of ``parent`` at positions ``idx`` (no repacking)."""

    def __init__(self, parent: ChairBatch, idx: np.ndarray) -> None:  # noqa: D107
        self.model = parent.model
        self.n = len(idx)
        self._p = type(parent._p)(*(np.asarray(f)[idx] for f in parent._p))
        self._stiffness = {k: np.asarray(v)[idx] for k, v in parent._stiffness.items()}
