"""The driver's delayed loop on a linear plant: the closed-loop matrix, its abscissa, and the search for the gains
that make it most stable (:func:`best_gains`), shared by the heading limit (:mod:`.linear`), the lane operator
(:mod:`stability.study.lane`) and the tracking task (:mod:`.tracking`); and the same search on the worst abscissa
over a spread of the delay (:func:`robust_gains`, the lane operator's)."""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable

import numpy as np

try:                             # numpy's private gufunc module (numpy 1.8 to 2.4, the versions pyproject allows)
    from numpy.linalg import _umath_linalg
except ImportError:              # pragma: no cover - a numpy that moved it: the public wrapper, the same answers
    _umath_linalg = None  # type: ignore[assignment]
from scipy.optimize import minimize

from stability.driver.delay import PADE_ORDER, pade

__all__ = ["closed_loop_matrix", "abscissa", "best_gains", "worst_abscissa", "robust_gains"]

#: Operator gain search box (log10): k_p in N m/rad, k_d in N m s/rad.
_LOG_KP, _LOG_KD = (-1.0, 4.5), (-2.0, 3.5)


def closed_loop_matrix(A: np.ndarray, B: np.ndarray, C: np.ndarray, gains: np.ndarray, tau: float,
                       order: int = PADE_ORDER) -> np.ndarray:
    """State matrix of the plant ``x' = A x + B u`` closed by ``u(t) = -(gains . C x)(t - tau)`` (Pade delay).

    Parameters
    ----------
    A : ndarray (n, n)
    B : ndarray (n, 1)
    C : ndarray (p, n)
        What the operator sees.
    gains : ndarray (..., p)
        Operator gains; leading axes give a batch of closed loops.
    tau : float
        Delay, s.
    order : int
        Pade order.

    Returns
    -------
    ndarray (..., n + order, n + order)
    """
    return _Loop(A, B, C, tau, order).matrix(gains)


class _Loop:
    """The delayed loop's gain-free parts, built once per plant (a gain search asks for hundreds of gains on one);
    :meth:`matrix` is :func:`closed_loop_matrix`'s arithmetic, operation for operation (the same to the bit)."""

    def __init__(self, A: np.ndarray, B: np.ndarray, C: np.ndarray, tau: float, order: int) -> None:
        Ad, Bd, Cd, Dd = pade(tau, order, copy=False)
        n, m = A.shape[0], Ad.shape[0]
        self.A, self.C, self.n = A, C, n
        self.direct = (B[:, 0] * float(Dd[0, 0]))[:, None]      # (n, 1): the delay's feed-through into the plant
        self.into_delay = Bd[:, 0][:, None]                      # (m, 1)
        self.fixed = np.zeros((n + m, n + m))                    # the gain-free blocks
        self.fixed[:n, n:] = -B @ Cd
        self.fixed[n:, n:] = Ad

    def matrix(self, gains: np.ndarray) -> np.ndarray:
        g = np.asarray(gains, dtype=float)
        Kc = g @ self.C                                 # (..., n): the operator's combination of the states
        n, out = self.n, np.broadcast_to(self.fixed, g.shape[:-1] + self.fixed.shape).copy()
        out[..., :n, :n] = self.A - self.direct * Kc[..., None, :]
        out[..., n:, :n] = self.into_delay * Kc[..., None, :]
        return out

    def abscissa(self, gains: np.ndarray) -> np.ndarray:
        return np.max(np.linalg.eigvals(self.matrix(gains)).real, axis=-1)

    def smallest(self, gains: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """The indices of the ``k`` smallest abscissae of a batch ``gains (N, p)`` (ties: the lower index first,
        a stable sort) and those abscissae."""
        return _smallest(self.abscissa(gains), k)

    def abscissa_one(self, gains: np.ndarray) -> float:
        """:meth:`abscissa` of one gain vector ``(p,)``, without the batch machinery (a search's inner call: the
        same arithmetic and the same LAPACK call on the same matrix, so the same value to the bit)."""
        Kc = gains @ self.C
        n, out = self.n, self.fixed.copy()
        out[:n, :n] = self.A - self.direct * Kc
        out[n:, :n] = self.into_delay * Kc
        return _largest_real_part(out)


class _WorstLoop:
    """Several delayed loops on one plant (one per delay): :meth:`abscissa` and :meth:`abscissa_one` are the
    largest of theirs (the worst case over the delays), with :class:`_Loop`'s interface for the search."""

    def __init__(self, A: np.ndarray, B: np.ndarray, C: np.ndarray, taus: tuple[float, ...], order: int) -> None:
        self.loops = [_Loop(A, B, C, t, order) for t in taus]
        self.lead = int(np.argmax(taus))            # the longest delay: usually the worst, the tightest lower bound
        # the loops' gain-free parts stacked (one per delay), for abscissa_one's single batched eigenvalue call
        self.A, self.C, self.n = A, C, self.loops[0].n
        self.fixed = np.stack([lp.fixed for lp in self.loops])
        self.direct = np.stack([lp.direct for lp in self.loops])
        self.into_delay = np.stack([lp.into_delay for lp in self.loops])

    def abscissa(self, gains: np.ndarray) -> np.ndarray:
        return np.max([lp.abscissa(gains) for lp in self.loops], axis=0)

    def smallest(self, gains: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`_Loop.smallest` of the worst abscissa, the same indices and values to the bit, with fewer
        eigenvalue problems: one loop's abscissa bounds the worst from below, so the worst is computed in order of
        the bound until the next bound exceeds the ``k``-th smallest worst found; every point left has a worst above
        ``k`` points' and cannot be among them, ties included (a grid search's starts: about a third of the
        work of :meth:`abscissa` on the lane operator's grid)."""
        gains = np.asarray(gains, dtype=float)
        bound = self.loops[self.lead].abscissa(gains)
        k = min(int(k), bound.size)
        if not np.all(np.isfinite(bound)):
            return _smallest(self.abscissa(gains), k)
        order = np.argsort(bound, kind="stable")
        worst = np.full(bound.shape, np.inf)
        others = [lp for i, lp in enumerate(self.loops) if i != self.lead]
        done, chunk = 0, max(k, 64)
        while done < order.size:
            idx = order[done:done + chunk]
            worst[idx] = np.max([bound[idx], *(lp.abscissa(gains[idx]) for lp in others)], axis=0)
            done += idx.size
            if done < order.size and bound[order[done]] > np.partition(worst, k - 1)[k - 1]:
                break
        return _smallest(worst, k)

    def abscissa_one(self, gains: np.ndarray) -> float:
        """The largest of the loops' :meth:`_Loop.abscissa_one`: each delay's matrix is built by the same
        elementwise arithmetic, and one batched LAPACK call on the stack computes each matrix's eigenvalues as the
        single call does (the same value to the bit, at a third of the call overhead: the lane operator's search
        spends most of its time here)."""
        Kc = gains @ self.C
        n, out = self.n, self.fixed.copy()
        out[:, :n, :n] = self.A - self.direct * Kc
        out[:, n:, :n] = self.into_delay * Kc
        return _largest_real_part(out)


def _largest_real_part(m: np.ndarray) -> float:
    """``float(np.linalg.eigvals(m).real.max())`` of a float64 matrix or stack of matrices ``m``, to the bit.

    The same LAPACK eigenvalue routine through the same numpy gufunc (``np.linalg.eigvals``'s own call, signature
    ``d->D``) on the same matrix, so the same eigenvalues, without the wrapper's per-call work (its error-state
    context and dtype dispatch: about a third of a call on the search's 9-15 state loops, called tens of thousands
    of times per search).  The wrapper's refusals are kept: a non-finite matrix raises numpy's LinAlgError, and a
    LAPACK failure to converge (NaN eigenvalues) is handed to ``np.linalg.eigvals``, which raises it.

    Parameters
    ----------
    m : ndarray (..., k, k)
        float64.

    Returns
    -------
    float
        1/s.
    """
    if _umath_linalg is None:
        return float(np.linalg.eigvals(m).real.max())
    if not np.isfinite(m).all():
        raise np.linalg.LinAlgError("Array must not contain infs or NaNs")
    with np.errstate(invalid="ignore"):                  # a failed convergence: NaN, re-raised below
        w = _umath_linalg.eigvals(m, signature="d->D")
    value = float(w.real.max())
    if value != value:
        return float(np.linalg.eigvals(m).real.max())
    return value


def _smallest(values: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """The indices of the ``k`` smallest ``values`` (ties: the lower index first) and those values."""
    idx = np.argsort(values, kind="stable")[:k]
    return idx, values[idx]


def abscissa(A: np.ndarray, B: np.ndarray, C: np.ndarray, gains: np.ndarray, tau: float,
             order: int = PADE_ORDER) -> np.ndarray:
    """Largest real part of the closed loop's eigenvalues (1/s): negative means stable.

    Parameters
    ----------
    A, B, C, gains, tau, order
        As :func:`closed_loop_matrix`.

    Returns
    -------
    ndarray
        One per closed loop (shape ``gains.shape[:-1]``).
    """
    return _Loop(A, B, C, tau, order).abscissa(gains)


#: Most recent :func:`best_gains` answers kept (an entry is a few kB); see :func:`best_gains`.
_BEST_GAINS_KEPT = 512
_best_gains_kept: OrderedDict[tuple, tuple[np.ndarray, float]] = OrderedDict()
_kept_lock = threading.Lock()


def best_gains(A: np.ndarray, B: np.ndarray, C: np.ndarray, tau: float, order: int = PADE_ORDER,
               log_bounds: tuple[tuple[float, float], ...] = (_LOG_KP, _LOG_KD), grid: int = 21,
               start: np.ndarray | None = None, starts: int = 1, restarts: int = 0) -> tuple[np.ndarray, float]:
    """The positive operator gains that make the delayed loop most stable (smallest abscissa).

    A log-spaced grid over ``log_bounds`` (or a given start, e.g. the best gains at a nearby speed), then
    Nelder-Mead (in log10 of the gains) from the best ``starts`` points (the abscissa is not smooth where two
    roots tie).  The most stable loop sits where several roots meet, a cusp of the abscissa only a few hundredths of
    a decade wide that a coarse grid does not see and at which one Nelder-Mead run stalls, often far from the
    cusp's bottom (three gains: the lane operator of :mod:`stability.study.lane`).  With ``restarts`` each run is
    begun again from where it stopped, on a fresh simplex of half a grid step on every gain, while that improves
    the abscissa; the best of all runs and of the single run without restarts (the search with ``starts=1,
    restarts=0``) is returned, never worse than either, nor than the best grid point (or ``start``).

    The search is deterministic in its inputs, so the last :data:`_BEST_GAINS_KEPT` answers are kept, keyed by the
    inputs' exact bytes: the same plant asked again (a lane limit at each push of its range, a command and a
    reference computing one layout's limit) returns the identical answer without a second search.

    Parameters
    ----------
    A, B, C, tau, order
        As :func:`closed_loop_matrix` (``C`` has one row per gain).
    log_bounds : tuple of (float, float)
        log10 range of each gain.
    grid : int
        Grid points per gain (without ``start``).
    start : ndarray, optional
        Gains to start from instead of the grid.
    starts : int
        Grid points, best first, Nelder-Mead starts from (>= 1; ignored with ``start``).
    restarts : int
        Fresh-simplex restarts of each run at most (0: one run on scipy's default simplex, 5 % of each log10
        gain).

    Returns
    -------
    (ndarray, float)
        The gains and the abscissa they give (1/s).
    """
    key = (*(_exact(a) for a in (A, B, C)), float(tau), int(order),
           tuple((float(lo), float(hi)) for lo, hi in log_bounds), int(grid), None if start is None else _exact(start),
           int(starts), int(restarts))
    return _kept_search(key, lambda keep: _search_gains(_Loop(A, B, C, tau, order), log_bounds, grid, start, starts,
                                                        restarts, keep))


def delay_spread(tau: float, spread: float) -> tuple[float, float, float]:
    """The delays a robust operator is designed for: ``tau (1 - spread), tau, tau (1 + spread)``, s.

    Parameters
    ----------
    tau : float
        The driver's delay, s (> 0).
    spread : float
        Relative spread, 0 <= spread < 1.

    Returns
    -------
    tuple of float
        s.
    """
    if not (tau > 0 and 0.0 <= spread < 1.0):
        raise ValueError(f"tau={tau!r}, spread={spread!r} are invalid; valid: tau > 0 s, 0 <= spread < 1")
    return (tau * (1.0 - spread), float(tau), tau * (1.0 + spread))


def worst_abscissa(A: np.ndarray, B: np.ndarray, C: np.ndarray, gains: np.ndarray, taus: tuple[float, ...],
                   order: int = PADE_ORDER) -> np.ndarray:
    """The largest of :func:`abscissa` over the delays ``taus`` (1/s): the worst case of one operator whose delay
    varies from one correction to the next.

    Parameters
    ----------
    A, B, C, gains, order
        As :func:`closed_loop_matrix`.
    taus : tuple of float
        Delays, s.

    Returns
    -------
    ndarray
        One per closed loop (shape ``gains.shape[:-1]``).
    """
    return _WorstLoop(A, B, C, tuple(float(t) for t in taus), order).abscissa(gains)


def robust_gains(A: np.ndarray, B: np.ndarray, C: np.ndarray, taus: tuple[float, ...], order: int = PADE_ORDER,
                 log_bounds: tuple[tuple[float, float], ...] = (_LOG_KP, _LOG_KD), grid: int = 21,
                 starts: int = 1, restarts: int = 0) -> tuple[np.ndarray, float]:
    """The positive operator gains that make the delayed loop most stable in the worst case over the delays
    ``taus`` (the smallest :func:`worst_abscissa`): a max-min design.

    The most stable loop at one delay sits where several roots meet, a notch a few hundredths of a decade wide
    whose margin a small change of the delay loses (the roots split); the worst case over a spread of delays has
    no such notch, so these gains keep their margin when the delay varies.  The search is :func:`best_gains`'s
    (grid, then Nelder-Mead from the best ``starts`` points with ``restarts``) on the worst-case objective, with
    its guarantee: the answer is never worse than the best grid point; answers are kept alike.

    Parameters
    ----------
    A, B, C, order, log_bounds, grid, starts, restarts
        As :func:`best_gains`.
    taus : tuple of float
        Delays, s (e.g. :func:`delay_spread`).

    Returns
    -------
    (ndarray, float)
        The gains and their worst abscissa over ``taus`` (1/s).
    """
    taus = tuple(float(t) for t in taus)
    if not taus or min(taus) <= 0:
        raise ValueError(f"taus={taus!r} is invalid; expected one or more delays > 0 s")
    key = ("worst", *(_exact(a) for a in (A, B, C)), taus, int(order),
           tuple((float(lo), float(hi)) for lo, hi in log_bounds), int(grid), int(starts), int(restarts))
    return _kept_search(key, lambda keep: _search_gains(_WorstLoop(A, B, C, taus, order), log_bounds, grid, None,
                                                        starts, restarts, keep))


_Keep = Callable[[np.ndarray, float], None]


def _kept_search(key: tuple, search: Callable[[_Keep | None], tuple[np.ndarray, float]]) -> tuple[np.ndarray, float]:
    """``search(keep)``'s answer, kept under ``key`` (the last :data:`_BEST_GAINS_KEPT`); a fresh copy of the gains.

    ``key`` ends with ``(starts, restarts)``; a search with more starts or restarts computes the single run's answer
    (``starts=1, restarts=0``) on its way, the same arithmetic to the bit, and hands it to ``keep`` to be kept
    under that key too (``keep`` is None for the single run itself)."""
    with _kept_lock:
        kept = _best_gains_kept.get(key)
        if kept is not None:
            _best_gains_kept.move_to_end(key)
    if kept is None:
        single = (*key[:-2], 1, 0)
        # outside the lock: threads search in parallel (an app's requests)
        kept = search(None if single == key else lambda g, v: _keep(single, (g, v)))
        _keep(key, kept)
    return kept[0].copy(), kept[1]


def _keep(key: tuple, answer: tuple[np.ndarray, float]) -> None:
    """Keep ``answer`` under ``key`` among the last :data:`_BEST_GAINS_KEPT`."""
    with _kept_lock:
        _best_gains_kept[key] = answer
        _best_gains_kept.move_to_end(key)
        while len(_best_gains_kept) > _BEST_GAINS_KEPT:
            _best_gains_kept.popitem(last=False)


def _exact(a: np.ndarray) -> tuple:
    """An array's shape and exact float64 bytes: a cache key that only identical inputs share."""
    x = np.asarray(a, dtype=float)
    return x.shape, x.tobytes()


def _search_gains(loop: _Loop | _WorstLoop, log_bounds: tuple[tuple[float, float], ...], grid: int,
                  start: np.ndarray | None, starts: int = 1, restarts: int = 0,
                  keep_single: _Keep | None = None) -> tuple[np.ndarray, float]:
    """:func:`best_gains`'s search (grid or start, then Nelder-Mead) of the gains minimising ``loop``'s abscissa,
    without the kept answers; ``keep_single`` is given the single run's answer (``starts=1, restarts=0``)."""
    if int(starts) != starts or starts < 1 or int(restarts) != restarts or restarts < 0:
        raise ValueError(f"starts={starts!r}, restarts={restarts!r} are invalid; valid: starts >= 1, restarts >= 0")
    lo_b = np.array([lo for lo, _ in log_bounds])
    hi_b = np.array([hi for _, hi in log_bounds])

    def f(x: np.ndarray) -> float:
        return loop.abscissa_one(10.0 ** np.clip(x, lo_b, hi_b))

    if start is None:
        axes = [np.linspace(lo, hi, grid) for lo, hi in log_bounds]
        mesh = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(axes))
        order_, values = loop.smallest(10.0**mesh, int(starts))
        firsts = [(mesh[i], float(v)) for i, v in zip(order_, values, strict=True)]
    else:
        x0 = np.clip(np.log10(np.asarray(start, dtype=float)), lo_b, hi_b)
        firsts = [(x0, f(x0))]
    step = 0.5 * (hi_b - lo_b) / max(int(grid) - 1, 1)          # half a grid step per gain, log10
    best, value = _polish(f, *firsts[0], lo_b, hi_b, step, 0)        # the single run's search, as it always was
    if keep_single is not None:
        keep_single(10.0**best, value)
    for x0, v0 in firsts if restarts else ():                           # ... and never worse than it
        x, v = _polish(f, x0, v0, lo_b, hi_b, step, int(restarts))
        if v < value:
            best, value = x, v
    return 10.0**best, value


def _polish(f: Callable[[np.ndarray], float], x0: np.ndarray, v0: float, lo_b: np.ndarray, hi_b: np.ndarray,
            step: np.ndarray, restarts: int) -> tuple[np.ndarray, float]:
    """Nelder-Mead on ``f`` (log10 gains) from ``x0`` (where ``f`` is ``v0``), restarted up to ``restarts`` times
    on a fresh simplex of edges ``step`` while that lowers ``f`` by more than the stopping tolerance; the best point
    seen (``x0`` if nothing beats it) and its value."""
    options = ({"xatol": 1e-3, "fatol": 1e-6, "maxiter": 400} if restarts == 0 else
               {"xatol": 1e-4, "fatol": 1e-7, "maxiter": 400 * len(x0)})
    x, v = x0, v0
    for _ in range(restarts + 1):
        simplex = None if restarts == 0 else np.vstack([x, x + np.diag(step)])
        res = minimize(f, x, method="Nelder-Mead", options={**options, "initial_simplex": simplex})
        xn = np.clip(res.x, lo_b, hi_b)
        vn = f(xn)
        if (vn > v) if restarts == 0 else not vn < v - options["fatol"]:     # restarted while it improves
            break
        x, v = xn, vn
    return x, v
