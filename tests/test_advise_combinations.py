"""The advisor's three-lever combination and the note on a chair that already breaks a limit, checked from values.

The simulated measures are replaced by a separable closed form of the chair's fields (``_separable``: each
measure a product of powers of pin friction, trail and caster mass, so the gain of changes to different fields
is exactly the product of their relative changes).  The limits are recomputed with the analysis functions
(``tests/test_advise_decisions.py``'s ``_limits_met``, the tip limit at :data:`MIN_TIP`), the gains from the closed form, and every single change,
pair and triple of three levers is enumerated here (:func:`stability.advise.levers.lever_changes`).
"""

from __future__ import annotations

import functools
import itertools
import math
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))

from test_advise_decisions import SPEEDS, _limits_met, _peaked_at  # noqa: E402

from stability import chair as chair_mod  # noqa: E402
from stability.advise import Interval, advise  # noqa: E402
from stability.advise.levers import apply, lever_changes  # noqa: E402
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
