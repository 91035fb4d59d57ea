"""The advisor's screening (stability.advise.pruning): the pruned advisor decides as the one that computes every
interval.

The rule (docs in :mod:`stability.advise.pruning`): an interval's low end is never above any of its variants, so
a change's x0.5-pin-friction run bounds its robust gain from above, and a change whose bound cannot reach one of
the advisor's choices keeps that run only.  Checked here: :func:`settle` against a full sort on random
lists; the pruned and the unpruned advisor's decisions (recommendation, runner-up, blocked changes, the pairs
measured, the decision text) on random chairs with the closed-form stand-in of the simulator (default run) and on
every preset and two random seeded chairs with the simulator (slow).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_advise import _plausible, _proxy

from stability import chair as chair_mod
from stability.advise import advise
from stability.advise.decision import decide
from stability.advise.pruning import Choice, settle
from stability.advise.text import advice_mapping, advice_text

PRESETS = ["ej-premier", "revised", "ej-premier-front-caster", "power-fwd", "manual-front-caster"]


def _decision(a) -> tuple:
    """Everything the advice decides: page 1's decision, the recommendations and the blocked changes with their
    values, the pairs measured (labels).  Not the count of pairs checked on the limits: the walk in the order of
    predicted gain reaches further while some parts are only bounded (more checks, the same choice)."""
    d = advice_mapping(a)
    return (decide(a).to_mapping(), d["recommendations"], d["blocked"], d["pairs_measured"],
            [c.label for c in a.combinations])


def _same(pruned, full) -> None:
    assert _decision(pruned) == _decision(full)
    exact = {c.changes: c for c in full.candidates + full.combinations}
    for c in pruned.candidates + pruned.combinations:
        e = exact[c.changes]
        if c.bounded:          # the bound: the screening run's gain is at least the robust gain
            assert all(c.gains[k] >= e.gains[k] for k in e.gains), c.label
            assert c.measures.critical_impulse_Ns.low >= e.measures.critical_impulse_Ns.low, c.label
            assert c.measures.equal_instability_speed_m_s.low >= e.measures.equal_instability_speed_m_s.low
        else:
            assert c == e, c.label
    assert "(x0.5)" in advice_text(pruned) or pruned.intervals_computed == len(exact)


@pytest.mark.parametrize("seed", range(6))
def test_settle_gives_the_prefix_of_the_full_sort(seed):
    """Random values, random upper bounds above them, random eligibility thresholds and ties: the computed prefix is
    the full sort's, and fewer entries than all are computed when the bounds allow."""
    rng = np.random.default_rng(seed)
    n = 40
    value = np.round(rng.normal(size=n), 1)                   # rounded: ties
    bound = value + np.where(rng.random(n) < 0.3, 0.0, rng.exponential(0.5, n))
    known = np.zeros(n, bool)
    for k, threshold in ((1, -math.inf), (3, 0.0), (6, 0.5)):
        known[:] = False

        def key(i: int) -> float:
            return float(value[i] if known[i] else bound[i])

        def refine(idx: list[int]) -> None:
            known[idx] = True

        def eligible(i: int, threshold: float = threshold) -> bool:
            return key(i) > threshold

        items = list(rng.permutation(n))
        (prefix,) = settle([Choice(items, lambda i: (-key(i),), lambda i: bool(known[i]), eligible,
                                   lambda p, k=k: len(p) >= k)], refine)
        full = [i for i in sorted(items, key=lambda i: -value[i]) if value[i] > threshold][:k]
        assert prefix == full
        assert known[prefix].all()


def test_a_bound_below_the_computed_gain_is_refused():
    """The screening's premise (the low end is at most the nominal value) is checked when an interval arrives."""
    from stability.advise.measures import Interval

    def liar(chairs):          # a "nominal" stage below its interval's low end
        return [(Interval(v.value, v.value, v.value), Interval(e.value, e.value, e.value), *rest)
                for v, e, *rest in _proxy(chairs)]

    def nominal_then_more(chairs):
        return [(Interval(2 * v.value, 2 * v.value, 2 * v.value), e, *rest) for v, e, *rest in liar(chairs)]

    import stability.advise.advisor as adv

    c = chair_mod.preset("ej-premier")
    orig = adv.screening_of
    adv.screening_of = lambda nl: liar
    try:
        with pytest.raises(RuntimeError, match="screening bound broken"):
            advise(c, nonlinear=nominal_then_more, time_to_correct=False)
    finally:
        adv.screening_of = orig


def _random_chairs(n: int, seed: int) -> list:
    rng = np.random.default_rng(seed)
    out: list = []
    while len(out) < n:
        c = _plausible(rng)
        if c is not None:
            out.append(c)
    return out


_SLOW = pytest.mark.slow
STAND_IN = [PRESETS[0]] + [pytest.param(c, marks=_SLOW) for c in PRESETS[1:] + _random_chairs(6, seed=35)]


@pytest.mark.parametrize("chair", STAND_IN, ids=PRESETS + [f"random{k}" for k in range(6)])
def test_pruned_and_full_advisor_decide_alike_with_the_stand_in(chair):
    """ej-premier in the default run (about 3 s of CPU), the other presets and six random chairs in the slow one."""
    c = chair_mod.preset(chair) if isinstance(chair, str) else chair
    pruned = advise(c, nonlinear=_proxy, time_to_correct=False)
    full = advise(c, nonlinear=_proxy, time_to_correct=False, prune=False)
    _same(pruned, full)


@pytest.mark.slow
@pytest.mark.parametrize("chair", PRESETS + _random_chairs(2, seed=3535),
                         ids=PRESETS + ["random0", "random1"])
def test_pruned_and_full_advisor_decide_alike_with_the_simulator(chair):
    """Every preset and two random seeded chairs, the simulator's measures (about 7 s of CPU a chair)."""
    c = chair_mod.preset(chair) if isinstance(chair, str) else chair
    pruned = advise(c)
    full = advise(c, prune=False)
    _same(pruned, full)
    assert pruned.intervals_computed <= len(full.candidates) + len(full.combinations)
