"""The runs still going of a batch stepped one step at a time from Python (a hook sampled between the steps).

Shared by the thesis engine's hooked runs (:mod:`stability.simulate.hooked`) and the layout's
(:mod:`stability.simulate.layout_batch`): the kernels set a run's stop codes once, when it stops, so the runs still
going are found again only when the count of set codes changes, and while every run goes the hook's moments are
stored by a slice.  Index bookkeeping only: no arithmetic of the runs is done here.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["GoingRuns"]


class GoingRuns:
    """The runs still going, found again only when the kernel stops one.

    Parameters
    ----------
    codes : ndarray, shape (runs,) or (runs, k)
        A view of the kernel's stop codes (0: still going; a run stops when any of its codes is set).

    Attributes
    ----------
    index : ndarray of int
        The runs still going (read-only: handed to a hook as ``state.run``).
    everyone : bool
        No run has stopped yet (``index`` is every run).
    stopped : int
        Stop codes set when ``index`` was last found.
    """

    def __init__(self, codes: np.ndarray) -> None:
        self.codes = codes
        self.stopped = 0
        self.everyone = True
        self.index = np.arange(codes.shape[0])
        self.index.flags.writeable = False

    def update(self) -> bool:
        """Find the runs still going again when a stop code was set since the last call.

        Returns
        -------
        bool
            Whether any run is still going.
        """
        n_stopped = int(np.count_nonzero(self.codes))
        if n_stopped != self.stopped:       # a run stopped at the last step: the runs still going change
            going = self.codes == 0.0 if self.codes.ndim == 1 else np.all(self.codes == 0.0, axis=1)
            self.stopped, self.index = n_stopped, np.flatnonzero(going)
            self.index.flags.writeable = False
            self.everyone = False
        return self.index.size > 0

    def store(self, target: np.ndarray, column: int, values: Any) -> None:
        """Write the hook's values (N m; one per run still going, or one for all) into ``target[:, column]``.

        Parameters
        ----------
        target : ndarray, shape (runs, columns)
            The kernel's per-run state.
        column : int
            The column of the held input.
        values : array_like
            The hook's answer, broadcast to the runs still going when its shape differs.
        """
        v = np.asarray(values, dtype=np.float64)
        if v.shape != self.index.shape:
            v = np.broadcast_to(v, self.index.shape)
        if self.everyone:
            target[:, column] = v
        else:
            target[self.index, column] = v
