"""The advisor's screening: every change measured once per measure first, intervals only where they can decide.

The advisor judges a change on the *low ends* of its critical-impulse and equal-instability intervals
(:func:`.advisor.advise`).  An interval's low end is the smallest value over the nominal case and its variants
(pin friction x0.5/x1.5, the thesis model, half the step; for the speed also the push), so it is never above any
one variant's value.  The screening runs one variant of every change, x0.5 pin friction
(:func:`.measures.screening_measures`: the variant that sets the low end in most cases, so the bound is usually
the low end itself).  Hence the rule, with ``s`` a change's screening value and ``l_b`` the low end of the chair
as it is (always measured with its intervals), per measure:

    robust gain = min over the two measures of (l / l_b - 1)  <=  min of (s / l_b - 1) =: upper bound,

and a pair's predicted gain (per measure the product of its parts' ``l / l_b``) is at most the same product of
the parts' ``s / l_b`` (all factors non-negative; a change whose bound is not finite or below -100 % is computed
at once).  Every choice the advisor makes from these gains is "the first ``k`` of a list sorted by gain, among
those that meet a condition that only a larger gain can meet" (the pairs it measures, the triple, the
recommendation and runner-up, the blocked changes: a :class:`Choice`).  :func:`settle` computes the intervals,
one batch a round, of the changes whose upper bound lets them reach such a prefix: walking each list in the order
of (bound or exact value, not-yet-computed first, position), it stops once every choice's first ``k`` eligible
entries are all computed.  Every change left bounded then sorts after the ``k``-th computed entry by its bound
(a tie is computed), so by its exact value too, which is lower: the choice equals the one the advisor makes with
every interval computed (``advise(..., prune=False)``; ``tests/test_advise_pruning.py`` compares the two).  When a
change's intervals arrive, its exact gains are checked against its bound (:meth:`Pool.refine`).

A change whose intervals are not computed keeps its screening values (:class:`Pool`, ``Candidate.bounded``); the
advice prints them, marked as the x0.5-pin-friction run, with the gain as an upper bound.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from stability.advise.measures import Interval

__all__ = ["Choice", "settle", "screening_of", "Pool"]


@dataclass(frozen=True)
class Choice:
    """One of the advisor's choices: the first eligible entries of ``items`` sorted by ``order``.

    Attributes
    ----------
    items : sequence of int
        Entries, in the order a stable sort keeps for equal keys.
    order : callable
        Entry -> sort key (ascending; the gain enters as ``-gain``).  For an entry not computed yet it must be at
        most the key of its computed value (an upper bound of the gain).
    exact : callable
        Whether an entry's key is its computed value.
    eligible : callable
        Whether an entry counts; for an entry not computed yet it must be true whenever its computed value could
        make it true (a condition a larger gain only helps).  It may read other entries: it must hold this way
        once they are computed.
    enough : callable
        Whether an eligible prefix is all the choice takes.
    needs : callable
        Entry -> the candidates (:class:`Pool` indices) to compute for it (default: the entry itself).
    """

    items: Sequence[int]
    order: Callable[[int], tuple]
    exact: Callable[[int], bool]
    eligible: Callable[[int], bool]
    enough: Callable[[list[int]], bool]
    needs: Callable[[int], list[int]] = lambda i: [i]

    def pending(self) -> tuple[list[int], list[int]]:
        """The eligible prefix in walk order (computed or not) and its entries not computed yet."""
        prefix: list[int] = []
        todo: list[int] = []
        walk = sorted(range(len(self.items)), key=lambda p: (self.order(self.items[p]), self.exact(self.items[p]), p))
        for p in walk:
            i = self.items[p]
            if not self.eligible(i):
                continue
            prefix.append(i)
            if not self.exact(i):
                todo.append(i)
            if self.enough(prefix):
                break
        return prefix, todo


def settle(choices: Sequence[Choice], refine: Callable[[list[int]], None]) -> list[list[int]]:
    """Compute exactly the entries that can reach the choices' prefixes, all choices' in one batch a round.

    Parameters
    ----------
    choices : sequence of Choice
    refine : callable
        Computes the given candidates (one batch, :meth:`Pool.refine`); afterwards the choices read their exact
        values.

    Returns
    -------
    list of list of int
        Each choice's eligible prefix, computed, in the order the full sort gives.
    """
    while True:
        found = [c.pending() for c in choices]
        todo = [k for c, (_, t) in zip(choices, found, strict=True) for i in t for k in c.needs(i)]
        if not todo:
            return [p for p, _ in found]
        refine(todo)


def screening_of(nonlinear: Callable) -> Callable:
    """The screening stage of a replacement of :func:`.measures.nonlinear_measures` (tests): its nominal values as
    the bounds (an interval's low end is never above its nominal value).

    Parameters
    ----------
    nonlinear : callable
        ``nonlinear(chairs)`` -> tuples as :func:`.measures.nonlinear_measures`.

    Returns
    -------
    callable
        Same signature; every interval ``Interval(None, value, None)``.
    """
    def screening(chairs: Sequence) -> list:
        return [(Interval(None, imp.value, None), Interval(None, eq.value, None), *rest)
                for imp, eq, *rest in nonlinear(chairs)]

    return screening


class Pool:
    """Candidates whose intervals are computed on demand.

    Parameters
    ----------
    make : callable
        ``make(changes, measures, bounded)`` -> Candidate (the advisor's, with gain and constraints).
    nonlinear : callable
        ``nonlinear(chairs)`` -> the interval tuples of :func:`.measures.nonlinear_measures`, one per chair (a
        stand-in may give only their first three or four entries: the critical impulse's status is then
        ``"found"``, its half-step value None).

    Attributes
    ----------
    refined : int
        How many candidates :meth:`refine` has computed so far (each once): it grows with every refinement, so a
        value read from the pool can be kept until it changes (:func:`.combinations._per_round`).
    """

    def __init__(self, make: Callable, nonlinear: Callable) -> None:
        self.make, self.nonlinear = make, nonlinear
        self.cands: list[Any] = []
        self.chairs: list[Any] = []
        self.index: dict[tuple, int] = {}
        self.refined = 0

    def add(self, cands: Sequence, chairs: Sequence) -> None:
        """Append candidates with the changed chairs they were measured on (one chair per candidate: lists of
        different lengths are refused, ValueError)."""
        for c, ch in zip(cands, chairs, strict=True):
            self.index[c.changes] = len(self.cands)
            self.cands.append(c)
            self.chairs.append(ch)

    def current(self, c: Any) -> Any:
        """The pool's current version of candidate ``c`` (same changes)."""
        return self.cands[self.index[c.changes]]

    def refine(self, idx: Sequence[int]) -> None:
        """Compute the intervals of the bounded candidates among ``idx`` in one batch.

        Raises RuntimeError when a computed robust gain exceeds its bound (an interval that does not contain its
        nominal value: the screening's premise broken), ValueError when ``nonlinear`` answers a different number
        of chairs than it was given.
        """
        todo = [i for i in dict.fromkeys(idx) if self.cands[i].bounded]
        if not todo:
            return
        for i, (imp, eq, status, *more) in zip(todo, self.nonlinear([self.chairs[i] for i in todo]), strict=True):
            old = self.cands[i]
            m = dataclasses.replace(old.measures, critical_impulse_Ns=imp, equal_instability_speed_m_s=eq,
                                    equal_instability_status=status,
                                    critical_impulse_status=more[0] if more else "found",
                                    critical_impulse_half_step_Ns=more[1] if len(more) > 1 else None)
            new = self.make(old.changes, m, False)
            if any(new.gains[k] > old.gains[k] for k in old.gains):
                raise RuntimeError(f"screening bound broken for {old.label}: robust gains {new.gains} above the "
                                   f"nominal bound {old.gains}")
            self.cands[i] = new
        self.refined += len(todo)

    def unbounded(self) -> list[int]:
        """Bounded candidates whose bound cannot order them (a gain not finite or below -100 %): computed first."""
        return [i for i, c in enumerate(self.cands)
                if c.bounded and any(not math.isfinite(g) or g < -1.0 for g in c.gains.values())]
