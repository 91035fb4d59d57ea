"""Eigenvalues against speed, with each mode followed across speeds."""

from __future__ import annotations

import numpy as np

from stability.chair import check_chair
from stability.chair.model import takes_chair
from stability.linear.batch import MAX_MATRICES
from stability.linear.model import state_matrices
from stability.runtime.checks import check_casters, check_model, check_speeds, value_text

__all__ = ["track_modes", "eigenvalues_vs_speed"]


def track_modes(eigs: np.ndarray) -> np.ndarray:
    """Reorder eigenvalues along the first axis so each column is one mode.

    Consecutive rows are matched by minimum total distance (an assignment
    problem, solved exactly with :func:`scipy.optimize.linear_sum_assignment`
    wherever the cheap nearest-neighbour match is not a permutation).  Rows
    are matched independently and the permutations composed, so the work is
    vectorised over rows; zero and repeated eigenvalues cause no special
    trouble because matching never divides by a gap.

    Parameters
    ----------
    eigs : ndarray, shape (N, n)
        Eigenvalues in arbitrary order per row.

    Returns
    -------
    ndarray, shape (N, n)
        The same eigenvalues, each column one mode.
    """
    from scipy.optimize import linear_sum_assignment

    eigs = np.asarray(eigs)
    N, n = eigs.shape
    if N < 2 or n < 2:
        return eigs.copy()
    cost = np.abs(eigs[:-1, :, None] - eigs[1:, None, :])  # (N-1, n, n): i at k -> j at k+1
    match = np.argmin(cost, axis=2)                         # (N-1, n)
    ok = np.all(np.sort(match, axis=1) == np.arange(n), axis=1)
    for k in np.flatnonzero(~ok):
        _, cols = linear_sum_assignment(cost[k])
        match[k] = cols
    # compose: column c of output follows index order[k, c] in row k
    order = np.empty((N, n), dtype=int)
    order[0] = np.argsort(-eigs[0].real, kind="stable")
    for j in range(N - 1):
        order[j + 1] = match[j][order[j]]
    return np.take_along_axis(eigs, order, axis=1)




@takes_chair
def eigenvalues_vs_speed(chair, speeds, model: str = "exact", casters: str = "free",
                         track: bool = True) -> np.ndarray:
    """Eigenvalues of the linear model at many speeds in one batched call.

    Parameters
    ----------
    chair : Chair
    speeds : array_like
        Forward speeds (m/s), sorted when ``track`` is true.
    model : {"exact", "thesis"}
    casters : {"free", "locked"}
    track : bool
        Follow each mode across speeds (:func:`track_modes`).

    Returns
    -------
    ndarray
        Shape (N, n), complex, 1/s.

    Raises
    ------
    TypeError
        ``chair`` is not a Chair, or ``track`` not a bool.
    ValueError
        A speed outside 0.01-100 m/s, more than :data:`~stability.linear.batch.MAX_MATRICES` speeds, or an
        unknown ``model`` or ``casters`` (the message names the argument, its value and the valid range).
    """
    chair = check_chair(chair)
    speeds = check_speeds(speeds, "speeds", max_count=MAX_MATRICES, one_dim=True)     # memory: one batched call
    model, casters = check_model(model), check_casters(casters)
    if not isinstance(track, (bool, np.bool_)):
        raise TypeError(f"track={value_text(track)} is invalid; valid values: True or False")
    eigs = np.linalg.eigvals(state_matrices(chair, speeds, model, casters))
    return track_modes(eigs) if track else eigs
