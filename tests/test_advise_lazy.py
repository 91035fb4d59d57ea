"""The pair screening measures a design only as far as its first broken limit, with the same answer.

:func:`stability.advise.limits.meets` checks the constraints of :func:`stability.advise.limits.constraints` the
cheapest first and stops at the first broken one; a :class:`stability.advise.measures.LazyLinear` computes each
measure when it is first read.  Checked here: ``meets`` is ``all(k.met for k in constraints(...))`` on random
measures around every limit (each branch: no cross slope, no bench, no driver); a lazy design reads only what it
is checked on, and its measures are those of the analysis functions called directly; and the advice with the lazy
screening is the advice with every pair measured in full (the proxy of ``tests/test_advise.py`` for the
simulator).
"""

from __future__ import annotations

import itertools
from types import SimpleNamespace

import numpy as np
import pytest
from test_advise import _proxy

from stability import chair as chair_mod
from stability.advise import advise
from stability.advise import advisor as advisor_mod
from stability.advise import combinations as combinations_mod
from stability.advise.layout_measures import layout_linear, layout_linear_measures
from stability.advise.lazy import Lazy, reused
from stability.advise.limits import MAX_PIN_FRICTION_N_M, MIN_SHIMMY_MARGIN_M, constraints, meets
from stability.advise.measures import IMPULSE_SPEED, Interval, bench_score, chair_linear, cross_slope_effort
from stability.advise.text import advice_mapping, advice_text
from stability.layout.presets import layout_preset
from stability.linear import eigenvalues_vs_speed
from stability.shimmy.band import shimmy_band
from stability.tipping import tip_angles

SPEEDS = (0.5, 0.75, 1.0)


def _measures(rng: np.random.Generator) -> SimpleNamespace:
    """Random measures of a changed design, each drawn at, just off and away from its limit (and None)."""
    def pick(*options):
        return options[int(rng.integers(len(options)))]

    return SimpleNamespace(
        static_stability_deg=Interval(pick(None, 8.0, 10.0 - 1e-10, 10.0 - 1e-8, 12.0), None, None),
        shimmy_margin_m=Interval(pick(None, -0.01, MIN_SHIMMY_MARGIN_M, MIN_SHIMMY_MARGIN_M - 1e-6, 0.02), None,
                                 None),
        shimmy_straddles=pick(False, True),
        turning_effort_N_m=pick(0.1, MAX_PIN_FRICTION_N_M, MAX_PIN_FRICTION_N_M + 1e-6, 0.5),
        cross_slope_effort=pick(None, 5.0, -10.9, 11.0 + 1e-10, 11.0 + 1e-6, 20.0),
        effort_key=pick("handrim_force_difference_N", "motor_torque_difference_N_m"),
        bench_score=pick(None, 0, 1, 2, 3),
        human_speed_m_s=pick(None, 0.5, 1.0 - 1e-10, 1.0 - 1e-6, 2.0),
        human_side=pick("=", ">"))


@pytest.mark.parametrize("seed", range(4))
def test_meets_is_every_constraint_met_on_random_measures(seed):
    """Around every limit and in every branch (cross slope on or off, a bench score or none, a driver or none,
    a chair as it is above the bench limit): the cheap-first check agrees with the constraints it checks."""
    rng = np.random.default_rng(seed)
    seen = set()
    for _ in range(400):
        m = _measures(rng)
        base = SimpleNamespace(turning_effort_N_m=float(rng.choice([0.1, 0.4])),
                               cross_slope_effort=[None, 10.0, -10.0][int(rng.integers(3))],
                               bench_score=[None, 1, 2][int(rng.integers(3))])
        slope = float(rng.choice([0.0, 2.0]))
        driver = [None, (0.6, 1.0)][int(rng.integers(2))]
        ks = constraints(m, base, 10.0, "own", slope, driver)
        want = all(k.met for k in ks)
        assert meets(m, base, 10.0, "own", slope, driver) is want
        seen.add((want, len(ks)))
    assert {w for w, _ in seen} == {True, False} and len({n for _, n in seen}) >= 3


class _Reads(SimpleNamespace):
    """Measures that record which are read."""

    def __getattribute__(self, name: str):
        if not name.startswith("_"):
            object.__getattribute__(self, "_read").append(name)
        return object.__getattribute__(self, name)


def test_meets_stops_at_the_first_broken_limit_and_checks_the_cheap_ones_first():
    """A design below the tip limit is not asked for anything else; one that meets the cheap limits is asked for
    the shimmy band before the bench, and the driver's speed last."""
    ok = dict(static_stability_deg=Interval(12.0, 12.0, 12.0), shimmy_margin_m=Interval(0.02, None, None),
              shimmy_straddles=False, turning_effort_N_m=0.1, cross_slope_effort=5.0,
              effort_key="handrim_force_difference_N", bench_score=1, human_speed_m_s=2.0, human_side="=")
    base = SimpleNamespace(turning_effort_N_m=0.1, cross_slope_effort=10.0, bench_score=1)
    low = _Reads(**{**ok, "static_stability_deg": Interval(8.0, 8.0, 8.0)}, _read=[])
    assert meets(low, base, 10.0, "own", 2.0, (0.6, 1.0)) is False
    assert low._read == ["static_stability_deg"]
    good = _Reads(**ok, _read=[])
    assert meets(good, base, 10.0, "own", 2.0, (0.6, 1.0)) is True
    order = list(dict.fromkeys(good._read))
    assert order == ["static_stability_deg", "turning_effort_N_m", "cross_slope_effort", "effort_key",
                     "shimmy_margin_m", "shimmy_straddles", "bench_score", "human_speed_m_s", "human_side"]


def test_a_lazy_value_is_computed_once_with_its_group_and_in_order_when_all_are_asked():
    calls = []

    def group(name, **values):
        def compute():
            calls.append(name)
            return values
        return tuple(values), compute

    lazy = Lazy({"a": group("a", x=1, y=2), "b": group("b", z=3)})
    assert lazy.computed() == [] and calls == []
    assert lazy.z == 3 and lazy.z == 3 and calls == ["b"]
    assert lazy.values() == {"x": 1, "y": 2, "z": 3} and calls == ["b", "a"]
    assert lazy.computed() == ["b", "a"]
    with pytest.raises(AttributeError):
        lazy.w  # noqa: B018
    with pytest.raises(AttributeError):
        lazy._hidden  # noqa: B018


def test_the_values_of_the_same_design_with_the_same_inputs_are_reused():
    """The same object with the same inputs gets the values made for it; an equal copy, or other inputs, new ones."""
    cache: dict = {}
    made = []

    def make():
        made.append(1)
        return Lazy({})

    a, copy = [1.0, 2.0], [1.0, 2.0]
    first = reused(cache, a, (0.5,), make)
    assert reused(cache, a, (0.5,), make) is first and len(made) == 1
    assert reused(cache, copy, (0.5,), make) is not first and len(made) == 2
    assert reused(cache, a, (0.75,), make) is not first and len(made) == 3


def test_the_pairs_measured_are_not_measured_again_for_their_limits(monkeypatch):
    """Every chair's measures that need no simulation are computed once in an advise call (the pairs the screening
    chose reuse what it computed)."""
    from stability.advise import measures as measures_mod

    seen: list = []
    tips = measures_mod.tip_angles

    def counted(c):
        seen.append(c)
        return tips(c)

    monkeypatch.setattr(measures_mod, "tip_angles", counted)
    a = advise(chair_mod.preset("revised"), nonlinear=_proxy, time_to_correct=False)
    assert a.pairs_measured > 0
    assert len(seen) == len(set(seen))


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd"])
def test_a_lazy_chair_is_measured_only_as_far_as_it_is_checked(name):
    """Above the chair's own tip angle only the tip angles are computed; against the chair itself every limit
    holds (each measure equals the chair's own) and every measure the limits read is computed, the bench only
    for a powered chair."""
    c = chair_mod.preset(name)
    base = chair_linear(c, speeds=SPEEDS, cross_slope_deg=2.0, cores={}).linear()
    own = float(base.static_stability_deg.value)
    lazy = chair_linear(c, speeds=SPEEDS, cross_slope_deg=2.0, cores={})
    assert meets(lazy, base, own + 1.0, "own", 2.0) is False
    assert lazy.computed() == ["tips"]
    lazy = chair_linear(c, speeds=SPEEDS, cross_slope_deg=2.0, cores={})
    assert meets(lazy, base, own, "own", 2.0) is (base.shimmy_margin_m.value >= MIN_SHIMMY_MARGIN_M)
    assert set(lazy.computed()) >= {"tips", "turning", "slope", "drive"}
    assert "growth" not in lazy.computed() and "human" not in lazy.computed()


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd"])
def test_a_lazy_chairs_measures_are_the_analysis_functions_answers(name):
    """Each measure is what the analysis function gives for the chair, called directly."""
    c = chair_mod.preset(name)
    lin = chair_linear(c, speeds=SPEEDS, cross_slope_deg=2.0, cores={}, reaction_time=0.6).linear()
    assert lin.static_stability_deg.value == tip_angles(c).smallest_deg
    assert lin.shimmy_margin_m.value == shimmy_band(c, SPEEDS).shimmy_margin_m
    assert lin.turning_effort_N_m == max(c.pin_friction_left, c.pin_friction_right)
    assert lin.cross_slope_effort == cross_slope_effort(c, 2.0)
    assert lin.bench_score == bench_score(c)
    assert lin.growth_rate_1_s == float(np.max(eigenvalues_vs_speed(c, [IMPULSE_SPEED], track=False).real))
    assert lin.human_speed_m_s is not None


def test_a_lazy_layout_gives_its_eager_measures():
    """A layout's lazy measures, read in any order, are its measures computed together."""
    lay = layout_preset("power-fwd-base")
    (whole,) = layout_linear_measures([lay], speeds=SPEEDS, cross_slope_deg=2.0)
    for order in itertools.islice(itertools.permutations(["bench_score", "shimmy_row", "static_stability_deg"]), 3):
        lazy = layout_linear(lay, speeds=SPEEDS, cores={}, cross_slope_deg=2.0)
        for f in order:
            assert getattr(lazy, f) == getattr(whole, f)
        assert lazy.linear() == whole


def _eager(monkeypatch) -> None:
    """Every screened pair measured in full and checked on every constraint (the screening before it was lazy)."""
    whole = combinations_mod.linear_measures

    def linear_measures(subjects, **kw):
        kw.pop("lazy", None)
        return whole(subjects, **kw)

    def meets_of(m, *args):
        return all(k.met for k in constraints(m, *args))

    monkeypatch.setattr(combinations_mod, "linear_measures", linear_measures)
    monkeypatch.setattr(advisor_mod, "meets_of", meets_of)


@pytest.mark.parametrize("name", ["revised", pytest.param("power-fwd", marks=pytest.mark.slow)])
def test_the_advice_is_the_one_with_every_screened_pair_measured_in_full(name, monkeypatch):
    """The same decision, pairs checked and printed numbers, to the character (about 1.5 s of CPU for revised; the
    powered chair, whose bench the screening skips, about 5 s in the slow run)."""
    c = chair_mod.preset(name)
    lazy = advise(c, nonlinear=_proxy, time_to_correct=False, cross_slope_deg=2.0)
    _eager(monkeypatch)
    full = advise(c, nonlinear=_proxy, time_to_correct=False, cross_slope_deg=2.0)
    assert advice_mapping(lazy) == advice_mapping(full)
    assert advice_text(lazy) == advice_text(full)
    assert lazy.pairs_screened == full.pairs_screened > 0
