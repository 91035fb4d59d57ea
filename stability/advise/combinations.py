"""The combinations the advisor measures: the pairs of two levers and the triple, chosen on predicted gains.

A pair's gain is predicted from its two single changes (per measure the product of their relative changes,
:func:`_predicted`).  The pairs are checked on the limits without simulation, in the order of that prediction, as
far as the choice reaches (:func:`_screen`); with the screening of :mod:`.pruning` the singles that can reach a
choice get their intervals first, and :func:`_settle_choice` does the same for the recommendation, the runner-up
and the changes a limit blocks.  Used by :func:`.advisor.advise`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from stability.advise.pruning import Choice, Pool, settle
from stability.advise.subject import apply, linear_measures
from stability.chair import Chair
from stability.layout.model import Layout

__all__ = ["MAX_FIX_COST", "PAIR_BUDGET", "BLOCKED_BUDGET"]

Candidate = Any          # stability.advise.advisor.Candidate (defined there; this module is imported by it)

#: A change that only fixes a constraint the chair breaks is recommended if it costs at most this fraction of
#: the robust measures; a dearer fix is the runner-up behind "no change, measure first".
MAX_FIX_COST = 0.25
#: Pairs of changes measured by simulation after the screening on the constraints (the best predicted ones).
PAIR_BUDGET = 6
#: Pairs a limit blocks that predict more than every pair meeting the limits, measured to be named (BLOCKED).
BLOCKED_BUDGET = 2

def _pairs(singles: list[Candidate]) -> list[tuple]:
    """Every pair of single changes of two different levers that touch different chair fields."""
    out = []
    for i, a in enumerate(singles):
        for b in singles[i + 1:]:
            if a.changes[0].lever != b.changes[0].lever and not set(a.fields) & set(b.fields):
                out.append((a, b))
    return out


def _predicted(combo: tuple) -> float:
    """The robust gain a combination predicts from its parts: per measure the product of the relative changes."""
    worst = math.inf
    for key in ("critical_impulse", "equal_instability_speed"):
        f = 1.0
        for x in combo:
            g = x.gains[key]
            if not math.isfinite(g):
                return -math.inf
            f *= 1.0 + g
        worst = min(worst, f - 1.0)
    return worst


def _screen(chair: Chair | Layout, cands: list[Candidate], broken: set, meets: Callable, use: tuple,
            cross_slope_deg: float, cores: dict, reaction_time: float | None = None,
            pool: Pool | None = None) -> tuple[list, int]:
    """The combinations worth simulating: the pairs of two levers that meet every limit (checked without
    simulation) ranked by the gain their parts predict (the best :data:`PAIR_BUDGET` above ``-MAX_FIX_COST``), the
    best :data:`BLOCKED_BUDGET` that a limit blocks but predict more than every pair meeting the limits (to be named
    with their values), and the triple of the three best acceptable levers.

    The pairs are walked in the order of their predicted gain and checked on the limits only as far as these
    choices reach (:func:`.pruning.settle`; a pair further down cannot be chosen); with a ``pool`` of bounded
    singles (:mod:`.pruning`) the singles that can reach the choices get their intervals first.  ``meets(m)`` says
    whether a pair's measures meet every limit (:func:`.limits.meets`: a pair is measured only as far as its
    first broken limit).

    Returns
    -------
    tuple
        ``([(parts, changed chair), ...], pairs checked on the limits)``.
    """
    if pool is None:                          # every single's intervals computed: nothing to refine
        pool = Pool(lambda *a: None, lambda chairs: [])
        pool.add(cands, [None] * len(cands))
    screened = []
    for combo in _pairs(cands):
        try:
            screened.append((combo, apply(chair, [f for x in combo for f in x.changes[0].fields])))
        except ValueError:
            continue
    parts = [[pool.index[x.changes] for x in combo] for combo, _ in screened]
    met_of: dict[int, bool] = {}

    def met(j: int) -> bool:                  # the pair's limits, checked once, when the walk reaches it, and
        if j not in met_of:                   # measured only as far as the first limit it breaks
            lin = linear_measures([screened[j][1]], speeds=use, cross_slope_deg=cross_slope_deg, cores=cores,
                                  reaction_time=reaction_time, lazy=True)[0]
            met_of[j] = meets(lin)
        return met_of[j]

    def pred(j: int) -> float:
        return _predicted(tuple(pool.cands[i] for i in parts[j]))

    def by_pred(j: int) -> tuple:
        return (-pred(j),)

    def exact(j: int) -> bool:
        return not any(pool.cands[i].bounded for i in parts[j])

    def needs(j: int) -> list[int]:
        return parts[j]

    every = range(len(screened))
    first = Choice(every, by_pred, exact, met, lambda p: len(p) >= 1, needs)

    threshold = _per_round(pool, lambda: (lambda p: pred(p[0]) if p else -math.inf)(first.pending()[0]))

    def blocked(j: int) -> bool:              # predicts more than the best passing pair (exact once settled)
        return pred(j) > threshold() and not met(j)

    singles = [i for i, c in enumerate(pool.cands) if len(c.changes) == 1]
    _, top, over, levers = settle([
        first,
        Choice(every, by_pred, exact, lambda j: pred(j) > -MAX_FIX_COST and met(j), lambda p: len(p) >= PAIR_BUDGET,
               needs),
        Choice(every, by_pred, exact, blocked, lambda p: len(p) >= BLOCKED_BUDGET, needs),
        Choice(singles, lambda i: (-pool.cands[i].gain,), lambda i: not pool.cands[i].bounded,
               lambda i: pool.cands[i].gain > 0 and all(k.met or k.name in broken for k in pool.cands[i].constraints),
               lambda p: len({pool.cands[i].changes[0].lever for i in p}) >= 3)], pool.refine)

    def current(j: int) -> tuple:
        return (tuple(pool.cands[i] for i in parts[j]), screened[j][1])

    chosen = [current(j) for j in top[:PAIR_BUDGET]] + [current(j) for j in over[:BLOCKED_BUDGET]]
    best: dict[str, Candidate] = {}
    for i in levers:
        best.setdefault(pool.cands[i].changes[0].lever, pool.cands[i])
    trio = tuple(list(best.values())[:3])
    if len(trio) == 3 and len({k for x in trio for k in x.fields}) == sum(len(x.fields) for x in trio):
        try:
            chosen.append((trio, apply(chair, [f for x in trio for f in x.changes[0].fields])))
        except ValueError:
            pass
    return chosen, len(met_of)


def _per_round(pool: Pool, fn: Callable[[], Any]) -> Callable[[], Any]:
    """``fn()`` computed once per state of the pool (until its next refinement): a threshold read by every entry."""
    cache: dict[int, Any] = {}

    def get() -> Any:
        if pool.refined not in cache:
            cache.clear()
            cache[pool.refined] = fn()
        return cache[pool.refined]

    return get


def _settle_choice(pool: Pool, broken: set) -> None:
    """Compute the intervals of the changes that can be the recommendation or the runner-up (the two best that
    meet every limit), of the parts of a combination among them, and of the changes that can be among
    :func:`_blocked`'s three (a limit blocks them, and they beat the recommendation or fix what the chair breaks):
    :func:`.pruning.settle`."""
    every = range(len(pool.cands))

    def exact(i: int) -> bool:
        return not pool.cands[i].bounded

    def gain(i: int) -> tuple:
        return (-pool.cands[i].gain,)

    top = Choice(every, gain, exact, lambda i: pool.cands[i].feasible, lambda p: len(p) >= 2)
    leaders = _per_round(pool, lambda: top.pending()[0])

    def fixes(c: Candidate) -> int:
        return sum(1 for k in c.constraints if k.met and k.name in broken)

    def order(i: int) -> tuple:
        c = pool.cands[i]
        return (-fixes(c), sum(1 for k in c.constraints if not k.met), -c.gain)

    def blocked(i: int) -> bool:             # beats the recommendation's gain (exact once ``top`` is settled)
        c, p = pool.cands[i], leaders()
        g0 = pool.cands[p[0]].gain if p else None
        best = g0 if g0 is not None and (g0 >= -MAX_FIX_COST if broken else g0 > 0) else 0.0    # else "no change"
        return not c.feasible and bool(c.changes) and (fixes(c) > 0 or c.gain > best)

    def parts(p: list[int]) -> list[int]:
        return [pool.index[(ch,)] for i in p[:2] if len(pool.cands[i].changes) > 1 for ch in pool.cands[i].changes]

    def refine(todo: list[int]) -> None:
        pool.refine(todo + [j for j in parts(top.pending()[0]) if j not in todo])

    settle([top, Choice(every, order, exact, blocked, lambda p: len(p) >= 3)], refine)
    pool.refine(parts(top.pending()[0]))
