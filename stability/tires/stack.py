"""Several tested tires evaluated in one call (the batch simulator's tire kernel)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG
from stability.tires.model import Tire
from stability.tires.ranges import Policy, _check_policy

__all__ = ["TireStack"]


class TireStack:
    """Several tested tires evaluated in one call: row ``j`` of the input uses tire ``j``.

    The batch simulator's kernel (:mod:`stability.simulate`): the four wheels
    of every run of a batch, as ``(k, n)`` arrays of slip angles and normal
    loads, go through one sequence of array operations instead of one per
    tire.  The force law is exactly :meth:`Tire.lateral_force` (same
    interpolation, same policies, same rounding), but no
    :class:`TireRangeWarning` is emitted: the caller counts out-of-range
    points itself, as WCHAIR's range warnings do.

    Parameters
    ----------
    tires : sequence of Tire
        One tested tire per row (:class:`LinearTire` has no table to stack).
    """

    def __init__(self, tires: tuple[Tire, ...] | list[Tire]):
        tires = tuple(tires)
        if not tires or not all(isinstance(t, Tire) for t in tires):
            raise ValueError(f"tires={tires!r} is not valid; valid: a non-empty sequence of tested Tire objects")
        k = len(tires)
        # (6, 8 k): a0, b0, c0, da, db, dc of every tire's 8 one-degree segments, end to end
        self._table = tuple(np.ascontiguousarray(np.concatenate([t._segments[c] for t in tires]))
                            for c in range(6))
        self._offset = (8 * np.arange(k, dtype=np.intp))[:, None]
        scale = np.array([t.lateral_scale for t in tires], dtype=float)[:, None]
        self._scale = None if np.all(scale == 1.0) else scale
        # each row's fitted range (scalars when all tires share the thesis range)
        smax = np.array([t.slip_max_deg for t in tires], dtype=float)[:, None]
        fmax = np.array([t.fz_max_N for t in tires], dtype=float)[:, None]
        uniform = bool(np.all(smax == SLIP_MAX_DEG) and np.all(fmax == FZ_MAX_N))
        self._smax: float | NDArray[np.float64] = SLIP_MAX_DEG if uniform else smax
        self._fmax: float | NDArray[np.float64] = FZ_MAX_N if uniform else fmax
        self.tires = tires
        self.names = tuple(t.name for t in tires)

    def lateral_force(self, slip_deg: NDArray[np.float64], fz: NDArray[np.float64], *,
                      policy: Policy = "clamp") -> NDArray[np.float64]:
        """Cornering force (N) of each row's tire; ``slip_deg``, ``fz`` of shape ``(k, n)``.

        See :meth:`Tire.lateral_force` for the force law and ``policy``
        (``"raise"`` raises ValueError naming the first offending value).
        """
        _check_policy(policy)
        return np.array([t.lateral_force(slip_deg[j], fz[j], policy=policy, warn=False)
                         for j, t in enumerate(self.tires)])
