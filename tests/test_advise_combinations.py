"""The advisor's three-lever combination and the note on a chair that already breaks a limit, checked from values.

The simulated measures are replaced by a separable closed form of the chair's fields (``_separable``: each
measure a product of powers of pin friction, trail and caster mass, so the gain of changes to different fields
is exactly the product of their relative changes).  The limits are recomputed with the analysis functions
(``tests/test_advise_decisions.py``'s ``_limits_met``, the tip limit at :data:`MIN_TIP`), the gains from the closed form, and every single change,
pair and triple of three levers is enumerated here (:func:`stability.advise.levers.lever_changes`).

The choices of :mod:`stability.advise.combinations` themselves are checked on hand-built changes (no chair, no
simulation; the changed chair stood in by its changed fields, the limits looked up): the pairs measured against
docs/advise.md's rule enumerated here (the six best predicted pairs that meet every limit above a 25 % cost, the
two best a limit blocks that predict more than every passing pair, the three best acceptable levers), the same
choice from upper bounds of the gains with the chosen parts computed, the recommendation, runner-up and blocked
changes against the advisor's own rules with every change computed, and small cases where a change no choice can
take keeps its bound.
"""

from __future__ import annotations

import functools
import itertools
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).parent))

from test_advise_decisions import SPEEDS, _limits_met, _peaked_at  # noqa: E402
from test_advise_pruning import _Measured as _PoolMeasured  # noqa: E402

from stability import chair as chair_mod  # noqa: E402
from stability.advise import Interval, advise  # noqa: E402
from stability.advise.advisor import Candidate  # noqa: E402
from stability.advise.levers import Change, apply, lever_changes  # noqa: E402
from stability.advise.limits import Constraint  # noqa: E402
from stability.tipping import tip_angles  # noqa: E402

#: Exponents of the stand-in: more pin friction, a longer trail and a lighter caster each raise both measures;
#: the axle and wheelbase levers change neither (gain 0: no lever of the trio), a tire change costs 20 %.
_CI = {"pin_friction_left": 0.5, "pin_friction_right": 0.5, "trail": 1.0, "m_c": -0.3}
_EI = {"pin_friction_left": 0.3, "pin_friction_right": 0.3, "trail": 0.5, "m_c": -0.2}
#: Tip limit (deg) low enough for the 7 cm trail (the chair's own angle would block it).
MIN_TIP = 5.0


def _met(c, base) -> bool:
    """Every limit of the advisor recomputed from the analysis functions, the tip limit at :data:`MIN_TIP`."""
    met = _limits_met(c, base, 0.0)
    met["static_stability_deg"] = tip_angles(c).smallest_deg >= MIN_TIP
    return all(met.values())


def _factor(c, base, powers) -> float:
    f = math.prod((getattr(c, k) / getattr(base, k)) ** p for k, p in powers.items())
    return f * (0.8 if c.caster_tire != base.caster_tire else 1.0)


def _separable(base, ci_powers=None, ei_powers=None):
    """Measures that are products of powers of the fields (default :data:`_CI`, :data:`_EI`)."""
    ci_powers, ei_powers = ci_powers or _CI, ei_powers or _EI

    def measures(chairs):
        out = []
        for c in chairs:
            ci, ei = 6.0 * _factor(c, base, ci_powers), 1.1 * _factor(c, base, ei_powers)
            out.append((Interval(ci, 0.5 * ci, 1.5 * ci), Interval(ei, 0.9 * ei, 1.1 * ei), "found", "found", None))
        return out

    return measures


def _gain(c, base) -> float:
    """Robust gain recomputed: the smaller relative change of the two low ends (each a fixed share of the value)."""
    return min(_factor(c, base, _CI), _factor(c, base, _EI)) - 1.0


def _combos(chair, sizes):
    """Every combination of single changes of different levers touching different fields, as (label, chair)."""
    singles, _ = lever_changes(chair)
    for n in sizes:
        for group in itertools.combinations(singles, n):
            changes = [ch for ch, _ in group]
            fields = [k for ch in changes for k, _ in ch.fields]
            if len({ch.lever for ch in changes}) < n or len(set(fields)) < len(fields):
                continue
            try:
                yield " + ".join(ch.label for ch in changes), apply(chair, [f for ch in changes for f in ch.fields])
            except ValueError:
                continue


def _best_feasible(chair, sizes):
    """The largest recomputed gain among the combinations that meet every recomputed limit (the gains sorted
    first, so the limits are measured only until the first feasible one)."""
    rows = sorted(((_gain(c, chair), label, c) for label, c in _combos(chair, sizes)), key=lambda r: -r[0])
    for g, label, c in rows:
        if _met(c, chair):
            return g, label
    raise AssertionError("no feasible combination")


@functools.cache
def _trio_case():
    """E&J Premier with a 6 cm trail and 0.2 N m pins: raising the pins to 0.4 N m gains most but breaks the
    turning-effort limit, so the best acceptable change is three levers (0.3 N m pins, the lighter caster, the
    7 cm trail) and no single change or pair reaches it."""
    chair = chair_mod.preset("ej-premier").replace(trail=0.06, pin_friction_left=0.2, pin_friction_right=0.2)
    a = advise(chair, speeds=SPEEDS, nonlinear=_separable(chair), time_to_correct=False, cross_slope_deg=0.0,
               min_tip_deg=MIN_TIP)
    return chair, a


def test_the_only_answer_is_three_levers_and_the_advisor_finds_it():
    chair, a = _trio_case()
    rec = a.recommendations[0].candidate
    c = apply(chair, list(rec.fields.items()))
    # the premise, recomputed: the best feasible triple beats every feasible single change and pair
    best3, label3 = _best_feasible(chair, (3,))
    best12, label12 = _best_feasible(chair, (1, 2))
    assert best3 > best12 + 0.05, (label3, best3, label12, best12)
    # the advice: three levers, every limit met (recomputed), the recomputed gain the best triple's
    assert len({ch.lever for ch in rec.changes}) == 3, rec.label
    assert _met(c, chair), rec.label
    assert _gain(c, chair) >= best3 - 1e-12, (rec.label, label3)   # the same chair: equal to rounding
    # and the best single change of a lever that the limits block (0.4 N m pins) is not part of it
    assert c.pin_friction_left <= 0.3 + 1e-12


@functools.cache
def _broken_case(kind: str):
    """A 4.75 cm trail: inside a shimmy zone (the chair breaks the shimmy margin); with the separable stand-in
    the fixes also gain (less than 100 %: 0.2 N m pins leave 0.3 N m a factor 1.5), with a stand-in peaked at the
    chair every fix costs a little."""
    chair = chair_mod.preset("ej-premier").replace(trail=0.0475, pin_friction_left=0.2, pin_friction_right=0.2)
    stand_in = _separable(chair) if kind == "gains" else _peaked_at(chair, 1.0)
    a = advise(chair, speeds=SPEEDS, nonlinear=stand_in, time_to_correct=False, cross_slope_deg=0.0,
               min_tip_deg=MIN_TIP)
    return chair, a


def _recomputed_gain(kind, c, chair) -> float:
    """The robust gain of ``c`` from the stand-in's low ends (the test's own model, not the advisor's numbers)."""
    if kind == "gains":
        return _gain(c, chair)
    (ci, ei, *_), (ci0, ei0, *_) = _peaked_at(chair, 1.0)([c, chair])
    return min(ci.low / ci0.low, ei.low / ei0.low) - 1.0


def test_the_note_on_a_fix_gives_its_recomputed_gain_or_cost():
    """For a chair that breaks a limit, each recommended fix's note says 'and gains N %' or 'at a cost of N %' on
    the robust measures: N is the robust gain recomputed from the stand-in's low ends of the changed chair, in
    whole percent (the note's rounding: within 0.5), and the word follows its sign."""
    for kind in ("gains", "costs"):
        chair, a = _broken_case(kind)
        assert {k.name for k in a.own_constraints if not k.met} == {"shimmy_margin_m"}       # the premise
        seen = 0
        for r in a.recommendations:
            if not r.candidate.changes:
                continue
            c = apply(chair, list(r.candidate.fields.items()))
            assert _met(c, chair), r.candidate.label
            g = _recomputed_gain(kind, c, chair)
            assert (0 < g < 1) if kind == "gains" else (-0.25 < g < 0)      # a gain below 100 %, a small cost
            note = next(n for n in r.notes if n.startswith("The chair as it is breaks the limit on shimmy margin"))
            words, pct = re.search(r"\((and gains|at a cost of) (\d+) % on the robust measures\)", note).groups()
            assert words == ("and gains" if g > 0 else "at a cost of"), note
            # error model: rounding to whole percent (half a unit, 0.5: a strict bound), plus the gain's round-off
            assert abs(int(pct) - 100 * abs(g)) <= 0.5 + 1e-9, (note, g)
            seen += 1
        assert seen, kind


def test_no_three_lever_combination_is_measured_when_only_two_levers_help():
    """The triple is of three levers that each gain: with a stand-in in which only the pin friction and the caster
    mass change the measures (the trail, axle and wheelbase levers gain exactly nothing), no combination of three
    changes is simulated; with the trail helping too (the trio case) one is."""
    chair = chair_mod.preset("ej-premier").replace(trail=0.06, pin_friction_left=0.2, pin_friction_right=0.2)
    no_trail = ({k: v for k, v in d.items() if k != "trail"} for d in (_CI, _EI))
    a = advise(chair, speeds=SPEEDS, nonlinear=_separable(chair, *no_trail), time_to_correct=False,
               cross_slope_deg=0.0, min_tip_deg=MIN_TIP)
    gains = {c.changes[0].lever: c.gain for c in a.candidates}
    assert sorted(k for k, g in gains.items() if g > 0) == ["caster_mass", "pin_friction"]        # the premise
    assert gains["trail"] == 0.0
    assert a.combinations and all(len(c.changes) <= 2 for c in a.combinations)
    assert any(len(c.changes) == 3 for c in _trio_case()[1].combinations)


def test_no_change_gains_nothing_on_either_measure():
    """When the advice is to keep the chair (every change loses: a stand-in peaked at the chair), the 'no change'
    recommendation is the chair against itself: its relative gains on both low ends are 0 exactly (x / x - 1), in
    the advice and in its JSON, and its predicted measures are the verdict's."""
    from stability.advise.text import advice_mapping

    chair = chair_mod.preset("ej-premier").replace(trail=0.06)
    a = advise(chair, speeds=SPEEDS, nonlinear=_peaked_at(chair), time_to_correct=False, cross_slope_deg=0.0)
    keep = a.recommendations[0].candidate
    assert keep.changes == () and all(k.met for k in a.own_constraints)          # the premise: nothing to fix
    v = a.verdict
    own = {"critical_impulse": v.critical_impulse_Ns.robust / v.critical_impulse_Ns.robust - 1.0,
           "equal_instability_speed": v.equal_instability_speed_m_s.robust / v.equal_instability_speed_m_s.robust - 1.0}
    assert keep.gains == own == {"critical_impulse": 0.0, "equal_instability_speed": 0.0} and keep.gain == 0.0
    rec = advice_mapping(a)["recommendations"][0]
    assert rec["gains"] == own and rec["robust_gain"] == 0.0 and rec["change"] == {}


def test_a_chair_breaking_two_limits_is_told_both_in_the_note():
    """A 4.75 cm trail (inside a shimmy zone) and a 40 deg tip limit (the chair tips at less): both limits broken,
    recomputed here; every recommendation's note names exactly those limits, one per item of its list."""
    from stability.advise.limits import limit_words

    chair = chair_mod.preset("ej-premier").replace(trail=0.0475)
    a = advise(chair, speeds=SPEEDS, nonlinear=_peaked_at(chair, 1.0), time_to_correct=False, cross_slope_deg=0.0,
               min_tip_deg=40.0)
    met = _limits_met(chair, chair, 0.0)
    met["static_stability_deg"] = tip_angles(chair).smallest_deg >= 40.0
    broken = {k for k, ok in met.items() if not ok}
    assert broken == {"shimmy_margin_m", "static_stability_deg"}                    # the premise, recomputed
    for r in a.recommendations:
        note = next(n for n in r.notes if n.startswith("The chair as it is breaks the limit on "))
        listed = re.match(r"The chair as it is breaks the limit on (.*?)(?:;|, and no change)", note).group(1)
        assert sorted(listed.split(", ")) == sorted(limit_words(k) for k in broken), note


# --- the choice of the pairs on hand-built singles: _screen against the rule enumerated here ---------------------

_Measured = _PoolMeasured          # the Measures stand-in of tests/test_advise_pruning.py


def _hand_built(seed: int, low: float = -0.4, high: float = 0.6):
    """Twelve single changes, two per lever of six, each touching its own field but for two that share one:
    robust gains on the two measures drawn at random in ``[low, high)`` (distinct: no ties), a random quarter
    breaking a limit (turning effort or shimmy margin); a random fifth of the pairs break a limit that neither
    part breaks alone."""
    rng = np.random.default_rng(seed)
    singles = []
    for k in range(12):
        lever = f"lever{k // 2}"
        field = "shared" if k in (4, 6) else f"field{k}"
        ch = Change(lever, f"{lever}:{k}", ((field, float(k)),))
        ci, ei = (float(x) for x in np.round(rng.uniform(low, high, 2), 6) + 1e-7 * k)
        name = "shimmy_margin_m" if rng.random() < 0.5 else "turning_effort_N_m"
        met = bool(rng.random() > 0.25)
        m = _Measured(Interval(None, 1.0 + ci, None), Interval(None, 1.0 + ei, None))
        singles.append(Candidate((ch,), m, min(ci, ei), {"critical_impulse": ci, "equal_instability_speed": ei},
                                 (Constraint(name, None, 1.0, "<=", met),)))
    pair_breaks = {frozenset((a, b)) for a, b in itertools.combinations(range(12), 2) if rng.random() < 0.2}
    return singles, pair_breaks


def _run_screen(monkeypatch, singles, pair_breaks, broken=frozenset(), pool=None, meets=None):
    """``_screen`` with the changed chair stood in by its changed fields and the limits looked up: a pair meets
    every limit when both parts do (or break only what the chair breaks) and the pair is not in ``pair_breaks``."""
    from stability.advise import combinations as comb

    index = {s.changes[0].fields[0][0] + str(s.changes[0].fields[0][1]): k for k, s in enumerate(singles)}
    monkeypatch.setattr(comb, "apply", lambda chair, fields: tuple(fields))
    monkeypatch.setattr(comb, "linear_measures", lambda chairs, **kw: list(chairs))

    def table(fields) -> bool:
        ks = [index[f + str(v)] for f, v in fields]
        return (frozenset(ks) not in pair_breaks
                and all(k.met or k.name in broken for s in ks for k in singles[s].constraints))

    meets = meets or table
    chosen, checked = comb._screen(None, singles, set(broken), meets, (1.0,), 0.0, {}, pool=pool)
    return [tuple(x.changes[0].label for x in parts) for parts, _ in chosen], checked, meets


def _expected_choice(singles, pair_breaks, broken=frozenset()) -> list:
    """The rule of :func:`.combinations._screen`, enumerated: the pairs of different levers and fields by the
    product of their parts' relative changes (the smaller over the two measures), the best six meeting every limit
    above a 25 % cost, then the best two a limit blocks that predict more than every pair meeting the limits, then
    the three best levers' best acceptable single changes (a gain, no limit broken beyond the chair's own)."""
    pairs = []
    for a, b in itertools.combinations(range(12), 2):
        sa, sb = singles[a], singles[b]
        if sa.changes[0].lever == sb.changes[0].lever or set(sa.fields) & set(sb.fields):
            continue
        pred = min((1 + sa.gains[k]) * (1 + sb.gains[k]) for k in sa.gains) - 1
        ok = (frozenset((a, b)) not in pair_breaks
              and all(k.met or k.name in broken for s in (sa, sb) for k in s.constraints))
        pairs.append((pred, (sa.changes[0].label, sb.changes[0].label), ok))
    pairs.sort(key=lambda p: -p[0])
    best_met = max((p for p, _, ok in pairs if ok), default=-math.inf)
    out = [lab for p, lab, ok in pairs if ok and p > -0.25][:6]
    out += [lab for p, lab, ok in pairs if not ok and p > best_met][:2]
    good = sorted((s for s in singles if s.gain > 0 and all(k.met or k.name in broken for k in s.constraints)),
                  key=lambda s: -s.gain)
    best: dict = {}
    for s in good:
        best.setdefault(s.changes[0].lever, s)
    trio = list(best.values())[:3]
    if len(trio) == 3 and len({k for s in trio for k in s.fields}) == 3:
        out.append(tuple(s.changes[0].label for s in trio))
    return out


#: (seed, gain range, what the chair breaks): changes that mostly gain, and changes that mostly cost on a chair
#: that breaks the shimmy margin (the 25 % cost cut and the chair's own broken limit then decide).
HAND_BUILT = [(seed, -0.4, 0.6, frozenset()) for seed in range(4)] + \
             [(seed, -0.45, 0.15, frozenset({"shimmy_margin_m"})) for seed in (4, 5)] + \
             [(seed, -0.55, 0.0, frozenset({"shimmy_margin_m"})) for seed in (6, 7)]


@pytest.mark.parametrize(("seed", "low", "high", "broken"), HAND_BUILT)
def test_the_pairs_measured_are_the_rules_on_hand_built_singles(monkeypatch, seed, low, high, broken):
    """Every single's intervals computed: the combinations measured are the rule's, in its order (the pairs a
    limit blocks after the six, the triple last)."""
    singles, pair_breaks = _hand_built(seed, low, high)
    got, _, _ = _run_screen(monkeypatch, singles, pair_breaks, broken)
    assert got == _expected_choice(singles, pair_breaks, broken)


@pytest.mark.parametrize(("seed", "low", "high", "broken"), HAND_BUILT)
def test_bounded_singles_give_the_same_pairs_with_their_parts_computed(monkeypatch, seed, low, high, broken):
    """The same singles known first by upper bounds of their gains (a random margin above each measure's, as the
    x0.5-pin-friction screening gives): the pairs chosen are the ones the exact gains give, and every part of a
    chosen combination has its intervals computed (:mod:`stability.advise.pruning`)."""
    from stability.advise.pruning import Pool

    singles, pair_breaks = _hand_built(seed, low, high)
    exact = {s.changes: s for s in singles}
    rng = np.random.default_rng(100 + seed)

    def make(changes, m, bounded):
        g = {"critical_impulse": m.critical_impulse_Ns.robust - 1.0,
             "equal_instability_speed": m.equal_instability_speed_m_s.robust - 1.0}
        return Candidate(changes, m, min(g.values()), g, exact[changes].constraints, bounded)

    def nonlinear(chairs):                     # a "chair" here is the single's changes: its exact low ends
        return [(exact[c].measures.critical_impulse_Ns, exact[c].measures.equal_instability_speed_m_s, "found",
                 "found", None) for c in chairs]

    def above(x: Interval) -> Interval:
        return Interval(None, x.robust + float(rng.exponential(0.2)), None)

    screened = [make(s.changes, _Measured(above(s.measures.critical_impulse_Ns),
                                          above(s.measures.equal_instability_speed_m_s)), True) for s in singles]
    pool = Pool(make, nonlinear)
    pool.add(screened, [s.changes for s in singles])
    got, _, _ = _run_screen(monkeypatch, screened, pair_breaks, broken, pool=pool)
    assert got == _expected_choice(singles, pair_breaks, broken)
    labels = {s.changes[0].label: s.changes for s in singles}
    assert all(not pool.current(exact[labels[lab]]).bounded for combo in got for lab in combo)


def _settle_case(seed: int, broken: frozenset, low: float, high: float):
    """Twelve singles and eight pairs of them, with random exact gains in ``[low, high)`` and, for the screening,
    random upper bounds above them; two limits per change (shimmy margin, turning effort) met at random."""
    from stability.advise.pruning import Pool

    rng = np.random.default_rng(200 + seed)
    changes = [(Change(f"lever{k // 2}", f"lever{k // 2}:{k}", ((f"field{k}", float(k)),)),) for k in range(12)]
    two_levers = [(a, b) for a, b in itertools.combinations(range(12), 2) if a // 2 != b // 2]
    changes += [changes[a] + changes[b] for a, b in (two_levers[k] for k in rng.choice(len(two_levers), 8, False))]
    exact = {}
    for k, ch in enumerate(changes):
        ci, ei = (float(x) for x in np.round(rng.uniform(low, high, 2), 6) + 1e-7 * k)
        cons = (Constraint("shimmy_margin_m", None, 0.005, ">=", bool(rng.random() < (0.3 if broken else 0.8))),
                Constraint("turning_effort_N_m", None, 1.0, "<=", bool(rng.random() < 0.7)))
        m = _Measured(Interval(None, 1.0 + ci, None), Interval(None, 1.0 + ei, None))
        exact[ch] = Candidate(ch, m, min(ci, ei), {"critical_impulse": ci, "equal_instability_speed": ei}, cons)

    def make(ch, m, bounded):
        g = {"critical_impulse": m.critical_impulse_Ns.robust - 1.0,
             "equal_instability_speed": m.equal_instability_speed_m_s.robust - 1.0}
        return Candidate(ch, m, min(g.values()), g, exact[ch].constraints, bounded)

    def nonlinear(chairs):
        return [(exact[c].measures.critical_impulse_Ns, exact[c].measures.equal_instability_speed_m_s, "found",
                 "found", None) for c in chairs]

    def above(x: Interval) -> Interval:
        return Interval(None, x.robust + float(rng.exponential(0.3)), None)

    pool = Pool(make, nonlinear)
    pool.add([make(ch, _Measured(above(exact[ch].measures.critical_impulse_Ns),
                                 above(exact[ch].measures.equal_instability_speed_m_s)), True) for ch in changes],
             changes)
    return pool, [exact[ch] for ch in changes]


def _advised(cands, broken):
    """The advisor's choices from a list of measured changes (:func:`stability.advise.advisor.advise`, docs/advise.md
    steps 3-5): the two best that meet every limit, and the changes a limit blocks that beat the recommendation
    (the best feasible gain; "no change", 0, when that costs more than 25 % on a chair that breaks a limit or
    gains nothing on one that does not) or fix what the chair breaks."""
    from stability.advise.advisor import _blocked

    feasible = sorted((c for c in cands if c.feasible), key=lambda c: -c.gain)
    top = feasible[0].gain if feasible else None
    best = top if top is not None and (top >= -0.25 if broken else top > 0) else 0.0
    return [c.changes for c in feasible[:2]], [b.candidate.changes for b in _blocked(cands, set(broken), best)]


@pytest.mark.parametrize("broken", [frozenset(), frozenset({"shimmy_margin_m"})], ids=["nothing", "shimmy"])
@pytest.mark.parametrize(("seed", "low", "high"), [(0, -0.5, 0.5), (1, -0.5, 0.5), (2, -0.5, 0.5), (3, -0.5, 0.5),
                                                   (4, -0.6, 0.02), (5, -0.6, 0.02)])
def test_the_recommendation_and_the_blocked_are_computed_before_they_are_chosen(seed, low, high, broken):
    """After :func:`.combinations._settle_choice` the pool's changes, some still known only by their bounds, give
    the same two best feasible changes and the same blocked changes as every change computed, and those (and the
    parts of a chosen pair) have their intervals."""
    from stability.advise.combinations import _settle_choice

    pool, exact = _settle_case(seed, broken, low, high)
    _settle_choice(pool, set(broken))
    want_top, want_blocked = _advised(exact, broken)
    got_top, got_blocked = _advised(pool.cands, broken)
    assert (got_top, got_blocked) == (want_top, want_blocked)
    parts = [(x,) for pair in want_top if len(pair) > 1 for x in pair]
    for ch in want_top + want_blocked + parts:
        assert not pool.cands[pool.index[ch]].bounded, ch
    assert pool.refined < len(exact)                   # the premise: the bounds spared some


def _hand_pool(rows):
    """A pool of single changes known by upper bounds: ``rows`` of (label, exact gain, bound, shimmy margin met,
    turning effort met[, the fields it changes[, its lever]]), the gain the same on both measures; by default each
    change its own lever and field; a label ``"a+b"`` is the pair of the earlier rows ``a`` and ``b``."""
    from stability.advise.pruning import Pool

    exact = {}
    for label, g, _, shimmy, turning, *more in rows:
        fields, lever = (more + [(label,), label][len(more):])
        ch = (tuple(next(c for c in exact if c[0].label == x)[0] for x in label.split("+")) if "+" in label
              else (Change(lever, label, tuple((f, 1.0) for f in fields)),))
        cons = (Constraint("shimmy_margin_m", None, 0.005, ">=", shimmy),
                Constraint("turning_effort_N_m", None, 1.0, "<=", turning))
        exact[ch] = Candidate(ch, _Measured(Interval(None, 1 + g, None), Interval(None, 1 + g, None)), g,
                              {"critical_impulse": g, "equal_instability_speed": g}, cons)

    def make(ch, m, bounded):
        g = m.critical_impulse_Ns.robust - 1.0
        return Candidate(ch, m, g, {"critical_impulse": g, "equal_instability_speed": g}, exact[ch].constraints,
                         bounded)

    def nonlinear(chairs):
        return [(exact[c].measures.critical_impulse_Ns, exact[c].measures.equal_instability_speed_m_s, "found",
                 "found", None) for c in chairs]

    pool = Pool(make, nonlinear)
    pool.add([make(ch, _Measured(Interval(None, 1 + b, None), Interval(None, 1 + b, None)), True)
              for ch, (_, _, b, *_) in zip(exact, rows, strict=True)], list(exact))
    return pool


def _computed(pool) -> set:
    return {c.label for c in pool.cands if not c.bounded}


def test_a_change_bounded_below_the_runner_up_is_not_computed():
    """Four changes that meet every limit: the two best bounds computed are the recommendation (50 %) and the
    runner-up (40 %); the third's bound (30 %) is below the runner-up's computed gain, so it cannot be either and
    keeps its bound, as does the fourth."""
    from stability.advise.combinations import _settle_choice

    pool = _hand_pool([("a", 0.5, 0.6, True, True), ("b", 0.4, 0.45, True, True), ("c", 0.2, 0.3, True, True),
                       ("d", 0.0, 0.1, True, True)])
    _settle_choice(pool, set())
    assert _computed(pool) == {"a", "b"}


def test_only_the_three_blocked_changes_named_are_computed():
    """A chair that breaks the shimmy margin; one change meets every limit (10 %), four fix the shimmy margin but
    break the turning effort: the three named under BLOCKED BY A LIMIT are the three largest gains (30, 20, 10 %,
    bounds 35, 25, 15 %); the fourth's bound (5 %) is below the third's gain, so it keeps its bound."""
    from stability.advise.combinations import _settle_choice

    pool = _hand_pool([("r", 0.1, 0.2, True, True), ("x1", 0.3, 0.35, True, False), ("x2", 0.2, 0.25, True, False),
                       ("x3", 0.1, 0.15, True, False), ("x4", 0.0, 0.05, True, False)])
    _settle_choice(pool, {"shimmy_margin_m"})
    assert _computed(pool) == {"r", "x1", "x2", "x3"}


def _screened(monkeypatch, rows) -> tuple[list, set]:
    """``_screen`` on :func:`_hand_pool`'s changes, every pair meeting every limit: the combinations chosen and the
    changes computed."""
    pool = _hand_pool(rows)
    got, _, _ = _run_screen(monkeypatch, pool.cands[:], set(), pool=pool, meets=lambda fields: True)
    return got, _computed(pool)


def test_a_fourth_lever_is_not_computed_for_the_triple(monkeypatch):
    """The triple takes the best acceptable change of each of the three best levers: with bounds 55, 45, 35 and
    20 % (gains 50, 40, 30 and 10 %) the fourth lever's change, whose bound is below the third's gain and which
    pairs with no other (it changes all their fields), is not computed."""
    got, computed = _screened(monkeypatch, [("a", 0.5, 0.55, True, True), ("b", 0.4, 0.45, True, True),
                                            ("c", 0.3, 0.35, True, True),
                                            ("d", 0.1, 0.2, True, True, ("a", "b", "c", "d"))])
    assert got == [("a", "b"), ("a", "c"), ("b", "c"), ("a", "b", "c")]
    assert computed == {"a", "b", "c"}


def test_a_pair_that_no_choice_can_take_is_not_computed(monkeypatch):
    """Two pairs meet every limit: a+b (gains 10 and 5 %: about 15.5 %) and c+d (-30 and -35 %: about -54 %, below
    the 25 % cost cut; c is a lever of a and changes b's field, d a lever of b changing a's field, so neither
    pairs with a or b; they cost, so are no lever of the triple): only a+b can be measured, so c and d keep their
    bounds."""
    got, computed = _screened(monkeypatch, [("a", 0.1, 0.15, True, True), ("b", 0.05, 0.1, True, True),
                                            ("c", -0.3, -0.28, True, True, ("b", "c"), "a"),
                                            ("d", -0.35, -0.3, True, True, ("a", "d"), "b")])
    assert got == [("a", "b")]
    assert computed == {"a", "b"}


def test_a_seventh_pair_is_not_computed(monkeypatch):
    """Four changes that gain 50, 45, 40 and 35 % make the six best pairs (the worst, c+d, about 89 %); e and f
    (-5 and -6 %) pair with them above the 25 % cost cut, but every such pair's bound (at most 1.55 x 0.96 - 1,
    about 49 %) is below the sixth pair's gain: e and f keep their bounds."""
    four = ("a", "b", "c", "d")
    got, computed = _screened(monkeypatch, [("a", 0.5, 0.55, True, True), ("b", 0.45, 0.5, True, True),
                                            ("c", 0.4, 0.45, True, True), ("d", 0.35, 0.4, True, True),
                                            ("e", -0.05, -0.04, True, True), ("f", -0.06, -0.05, True, True)])
    assert got == [("a", "b"), ("a", "c"), ("b", "c"), ("a", "d"), ("b", "d"), ("c", "d"), ("a", "b", "c")]
    assert computed == set(four)


def test_a_blocked_pair_must_predict_more_than_every_passing_pair(monkeypatch):
    """a+b meets every limit; c+d, which a limit blocks, predicts exactly as much (gains 20 and 10 %, 10 and 20 %:
    1.2 x 1.1 and 1.1 x 1.2, the same float): it does not predict more, so it is not measured to be named; with d
    at 21 % it is.  (a and c are one lever, b and d another, a and d share a field, b and c too: a+b and c+d are the
    only pairs, and no three levers.)"""
    for d, want in ((0.2, [("a", "b")]), (0.21, [("a", "b"), ("c", "d")])):
        pool = _hand_pool([("a", 0.2, 0.2, True, True, ("fa", "s1"), "L1"),
                           ("b", 0.1, 0.1, True, True, ("fb", "s2"), "L2"),
                           ("c", 0.1, 0.1, True, True, ("fc", "s2"), "L1"),
                           ("d", d, d, True, True, ("fd", "s1"), "L2")])
        got, _, _ = _run_screen(monkeypatch, pool.cands[:], set(), pool=pool,
                                meets=lambda fields: not {"fc", "fd"} <= {f for f, _ in fields})
        assert got == want, d


def test_a_recommended_pairs_parts_are_computed_in_its_batch():
    """The recommendation is a pair, a+b (30 %; bound 35 %), whose parts gain little (5 and 4 %) and the runner-up a
    single change, c (20 %): the parts are computed, for the pair's note, in the same batch as the pair and c (one
    batch of simulations a round, :mod:`stability.advise.pruning`), not in a batch of their own afterwards."""
    from stability.advise.combinations import _settle_choice

    pool = _hand_pool([("a", 0.05, 0.1, True, True), ("b", 0.04, 0.08, True, True), ("c", 0.2, 0.25, True, True),
                       ("a+b", 0.3, 0.35, True, True)])
    nonlinear, batches = pool.nonlinear, []

    def counted(chairs):
        batches.append({" + ".join(ch.label for ch in c) for c in chairs})
        return nonlinear(chairs)

    pool.nonlinear = counted
    _settle_choice(pool, set())
    assert batches == [{"a + b", "c", "a", "b"}]


def test_a_blocked_change_that_cannot_beat_the_recommendation_keeps_its_bound():
    """Nothing to fix; the recommendation gains 30 % (its bound too).  Two changes a limit blocks are named only if
    they beat it, which their bounds say they cannot: 20 %, and exactly 30 % (a tie does not beat it), so neither
    is computed."""
    from stability.advise.combinations import _settle_choice

    pool = _hand_pool([("r", 0.3, 0.3, True, True), ("x", 0.1, 0.2, True, False), ("y", 0.25, 0.3, True, False)])
    _settle_choice(pool, set())
    assert _computed(pool) == {"r"}


def test_only_the_two_blocked_pairs_named_are_computed(monkeypatch):
    """Every pair but p+q (1 % each: about 2 %) breaks a limit, and the two that predict most, a+b and a+d (gains
    50, 40 and 30 %), are measured to be named; the third, a+c (c: 10 %, bound 15 %: at most 1.5 x 1.15 - 1, about
    72.5 %, below a+d's 95 %), is not, and c keeps its bound (b and d share a field: no a, b, d triple)."""
    pool = _hand_pool([("a", 0.5, 0.55, True, True), ("b", 0.4, 0.45, True, True, ("b", "s")),
                       ("c", 0.1, 0.15, True, True), ("d", 0.3, 0.35, True, True, ("d", "s")),
                       ("p", 0.01, 0.02, True, True), ("q", 0.01, 0.02, True, True)])
    got, _, _ = _run_screen(monkeypatch, pool.cands[:], set(), pool=pool,
                            meets=lambda fields: {f for f, _ in fields} == {"p", "q"})
    assert got == [("p", "q"), ("a", "b"), ("a", "d")]
    assert _computed(pool) == {"a", "b", "d", "p", "q"}
