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

import dataclasses
import math

import numpy as np
import pytest
from test_advise import _plausible, _proxy

from stability import chair as chair_mod
from stability.advise import advise
from stability.advise.decision import decide
from stability.advise.measures import Interval
from stability.advise.pruning import Choice, Pool, settle
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


def test_a_choice_is_a_value():
    """``settle`` reads the same choices every round: a Choice cannot be changed once made (frozen)."""
    c = Choice([0, 1], lambda i: (i,), lambda i: True, lambda i: True, lambda p: len(p) >= 1)
    with pytest.raises(dataclasses.FrozenInstanceError):
        c.items = [1]
    assert c.pending() == ([0], [])


@dataclasses.dataclass(frozen=True)
class _Measured:
    """The fields of :class:`stability.advise.measures.Measures` that :meth:`Pool.refine` replaces."""

    critical_impulse_Ns: Interval
    equal_instability_speed_m_s: Interval
    equal_instability_status: str = "found"
    critical_impulse_status: str = "found"
    critical_impulse_half_step_Ns: float | None = None


@dataclasses.dataclass(frozen=True)
class _Cand:
    changes: tuple
    measures: _Measured
    gains: dict
    bounded: bool
    label: str = ""


def _make(changes, m, bounded):
    """A candidate judged on the low ends against a chair whose low ends are both 1 (gain = low - 1)."""
    return _Cand(changes, m, {"critical_impulse": m.critical_impulse_Ns.robust - 1.0,
                              "equal_instability_speed": m.equal_instability_speed_m_s.robust - 1.0}, bounded,
                 " + ".join(changes))


def _intervals(chairs):
    """A chair is a number x: critical impulse x with the interval [x/2, 2x], equal-instability speed [x/4, 4x]."""
    return [(Interval(x, x / 2, 2 * x), Interval(x, x / 4, 4 * x), "found", "found", None) for x in chairs]


def test_the_pool_pairs_each_candidate_with_its_chair_and_counts_what_it_refines():
    """``add`` takes one chair per candidate (a candidate without its chair is refused, not dropped); ``refined``
    counts the candidates computed, each once: a candidate asked for twice in a batch or again later, or one
    already computed, is not computed again; a measurement that answers fewer chairs than it was given is
    refused."""
    pool = Pool(_make, _intervals)
    screened = [_make((f"c{k}",), _Measured(*(Interval(None, x, None),) * 2), True) for k, x in enumerate((1, 2, 3))]
    with pytest.raises(ValueError):
        pool.add(screened[:1], [])
    assert pool.cands == [] and pool.refined == 0
    pool.add(screened, [1.0, 2.0, 3.0])
    assert [pool.index[c.changes] for c in screened] == [0, 1, 2] and pool.refined == 0
    pool.refine([2, 0, 2])
    assert pool.refined == 2 and [c.bounded for c in pool.cands] == [False, True, False]
    # the computed gains are those of the low ends of the candidate's own chair, x/2 and x/4
    assert pool.cands[2].gains == {"critical_impulse": 3 / 2 - 1, "equal_instability_speed": 3 / 4 - 1}
    pool.refine([0, 2])
    assert pool.refined == 2
    pool.refine([1])
    assert pool.refined == 3 and not any(c.bounded for c in pool.cands)
    # a measurement that answers fewer chairs than it was given is refused, not read as far as it goes
    short = Pool(_make, lambda chairs: _intervals(chairs)[:-1])
    short.add(screened, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError):
        short.refine([0, 1])


def test_the_pool_reads_a_measurement_with_or_without_its_last_entries():
    """A measurement is ``nonlinear_measures``' five entries, or a stand-in's first three or four: the critical
    impulse's status is then "found" and its half-step value None; given, both are kept."""
    for extra, status, half in (((), "found", None), (("below",), "below", None), (("below", 0.7), "below", 0.7),
                                (("found", 0.7), "found", 0.7)):
        pool = Pool(_make, lambda chairs, extra=extra: [(Interval(x, x / 2, 2 * x), Interval(x, x / 4, 4 * x),
                                                         "above", *extra) for x in chairs])
        screened = _Measured(*(Interval(None, 1.0, None),) * 2, "x0.5", "x0.5", 9.9)     # none of it kept
        pool.add([_make(("c",), screened, True)], [1.0])
        pool.refine([0])
        m = pool.cands[0].measures
        assert (m.equal_instability_status, m.critical_impulse_status, m.critical_impulse_half_step_Ns) == \
            ("above", status, half), extra


def test_the_candidates_a_bound_cannot_order_are_the_ones_computed_first():
    """``unbounded``: the bounded candidates with a gain that is not finite or below -100 % (a low end below zero,
    which the ratio to the chair's low end cannot order); -100 % itself (a low end of 0) and a computed
    candidate are not among them."""
    def cand(k, ci, ei, bounded=True):
        m = _Measured(Interval(None, ci + 1.0, None), Interval(None, ei + 1.0, None))
        return _Cand((f"c{k}",), m, {"critical_impulse": ci, "equal_instability_speed": ei}, bounded)

    gains = [(0.2, -0.1), (-1.0, 0.3), (-1.5, 0.0), (0.1, math.inf), (-math.inf, 0.0), (0.0, math.nan), (-1.5, -2.0)]
    pool = Pool(_make, _intervals)
    pool.add([cand(k, *g) for k, g in enumerate(gains)] + [cand(7, -1.5, math.inf, bounded=False)], [0.0] * 8)
    assert pool.unbounded() == [2, 3, 4, 5, 6]


def test_a_bound_is_checked_when_the_intervals_arrive():
    """A computed gain equal to its bound is the usual case (the x0.5-pin-friction run sets the low end) and is
    accepted; one above it is refused, naming the change and both gains."""
    def screened(label, ci, ei):
        return _make((label,), _Measured(Interval(None, ci, None), Interval(None, ei, None)), True)

    pool = Pool(_make, _intervals)           # chair 2: low ends 1 and 0.5, gains 0 and -50 %
    pool.add([screened("equal", 1.0, 0.5)], [2.0])
    pool.refine([0])
    assert pool.cands[0].gains == {"critical_impulse": 0.0, "equal_instability_speed": -0.5}
    pool.add([screened("below", 1.0, 0.25)], [2.0])
    with pytest.raises(RuntimeError) as err:
        pool.refine([1])
    assert str(err.value) == ("screening bound broken for below: robust gains {'critical_impulse': 0.0, "
                              "'equal_instability_speed': -0.5} above the nominal bound {'critical_impulse': 0.0, "
                              "'equal_instability_speed': -0.75}")


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
