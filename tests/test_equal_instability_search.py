"""The equal-instability bisection (:mod:`stability.study.equal_instability`) against closed-form time-vs-speed laws.

Every law here is a synthetic ``summarise`` (no kernel): the time to the yaw-rate level at speed U is a closed form,
so the bracket the search returns can be checked against the law's own crossing of the reference time, and the
regula-falsi pair of :func:`equal_instability._pair` against its formula (log time linear between the bracket's ends).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from test_advisor_runs import GRID, TARGET, ClosedForm, monotone, search

from stability.chair import preset
from stability.settings.reference import REFERENCE_CHAIR
from stability.settings.run import RunSpec
from stability.study import equal_instability as ei
from stability.study.criteria import DEFAULT_CRITERION, Criterion

# error model: every speed below is a few additions and one division of O(1) m/s values in double precision
# (relative rounding 1e-16 a step): 1e-12 m/s is ~1e3 x that error yet ~1e6 x below the smallest tol used (5e-3)
ABS = 1e-12
HORIZON = min(DEFAULT_CRITERION.duration, 1.5 * TARGET + 0.5)   # the bisection's horizon for TARGET, s


def _regula_falsi(lo, t_lo, hi, t_hi, target=TARGET, w_lo=1.0, w_hi=1.0):
    """The root of the line through (lo, w_lo ln(t_lo / target)) and (hi, w_hi ln(t_hi / target)), m/s."""
    f_lo, f_hi = w_lo * math.log(t_lo / target), w_hi * math.log(t_hi / target)
    return lo + (hi - lo) * f_lo / (f_lo - f_hi)


def _pts(lo, t_lo, hi, t_hi):
    # points outside the bracket first and between its ends, so only the bracket's own ends may be read
    return [(0.1, 50.0), (0.5 * (lo + hi), 3.0), (lo, t_lo), (5.0, 0.1), (hi, t_hi)]


def test_pair_is_centred_on_the_regula_falsi_root():
    tol = 0.01
    x = _regula_falsi(1.0, 4.0, 2.0, 2.0)
    assert ei._pair(_pts(1.0, 4.0, 2.0, 2.0), 1.0, 2.0, TARGET, tol, 100.0, 0) == pytest.approx(
        [x - 0.45 * tol, x + 0.45 * tol], abs=ABS)
    # one round with the same end kept is not yet Illinois
    for kept in (1, -1):
        assert ei._pair(_pts(1.0, 4.0, 2.0, 2.0), 1.0, 2.0, TARGET, tol, 100.0, kept) == pytest.approx(
            [x - 0.45 * tol, x + 0.45 * tol], abs=ABS)


@pytest.mark.parametrize("kept", [2, 3, 4, -2, -3, -4])
def test_pair_illinois_halves_the_far_ends_margin_per_round(kept):
    """``kept >= 2`` rounds with the high end kept: the high end's log-time margin halved ``kept - 1`` times."""
    tol = 0.01
    w = 0.5 ** (abs(kept) - 1)
    x = _regula_falsi(1.0, 4.0, 2.0, 2.0, w_hi=w if kept > 0 else 1.0, w_lo=w if kept < 0 else 1.0)
    assert ei._pair(_pts(1.0, 4.0, 2.0, 2.0), 1.0, 2.0, TARGET, tol, 100.0, kept) == pytest.approx(
        [x - 0.45 * tol, x + 0.45 * tol], abs=ABS)


def test_pair_counts_a_time_beyond_the_horizon_as_the_horizon():
    tol = 0.01
    x = _regula_falsi(1.0, 6.0, 2.0, 2.0)               # inf -> end = 6 s
    assert ei._pair(_pts(1.0, math.inf, 2.0, 2.0), 1.0, 2.0, TARGET, tol, 6.0, 0) == pytest.approx(
        [x - 0.45 * tol, x + 0.45 * tol], abs=ABS)


def test_pair_stays_inside_the_bracket_near_either_end():
    """A root within half a pair of an end: the pair shifts to ``0.05 tol`` inside that end, still ``0.9 tol`` wide."""
    tol = 0.1
    lo, hi = 1.0, 2.0
    t_near_lo = TARGET * math.exp(0.01)                  # root at lo + 0.01/(0.01 + ln(TARGET/1)) of the width
    assert _regula_falsi(lo, t_near_lo, hi, 1.0) - lo < 0.45 * tol
    assert ei._pair(_pts(lo, t_near_lo, hi, 1.0), lo, hi, TARGET, tol, 100.0, 0) == pytest.approx(
        [lo + 0.05 * tol, lo + 0.95 * tol], abs=ABS)
    t_near_hi = TARGET * math.exp(-0.01)
    assert hi - _regula_falsi(lo, 10.0, hi, t_near_hi) < 0.45 * tol
    assert ei._pair(_pts(lo, 10.0, hi, t_near_hi), lo, hi, TARGET, tol, 100.0, 0) == pytest.approx(
        [hi - 0.95 * tol, hi - 0.05 * tol], abs=ABS)


def test_pair_of_a_bracket_narrower_than_a_pair_is_its_midpoint():
    assert ei._pair(_pts(1.0, 4.0, 1.009, 2.0), 1.0, 1.009, TARGET, 0.01, 100.0, 0) == [1.0045]


def test_a_log_linear_law_closes_with_one_pair():
    """``t = T exp(-(U - U*))``: log time is linear in speed, so the first regula-falsi root is U* itself and the
    pair around it closes the bracket in the second round: the first round's five runs, the pair, nothing more."""
    u_star, tol = 1.1, 0.005
    res, fake = search({"c": lambda u: TARGET * math.exp(-(u - u_star))}, tol=tol)
    r = res["c"]
    assert [u for _, u in fake.runs][:5] == pytest.approx([3.0, *GRID[:4]], abs=ABS)
    assert len(fake.runs) == 7
    assert sorted(u for _, u in fake.runs[5:]) == pytest.approx([u_star - 0.45 * tol, u_star + 0.45 * tol], abs=ABS)
    assert (r.status, r.low, r.high) == ("found", fake.runs[5][1], fake.runs[6][1])
    assert r.speed == pytest.approx(u_star, abs=ABS)


def _laws():
    steep = lambda u: TARGET * math.exp(-4.0 * (u - 0.75) * abs(u - 0.75))   # noqa: E731
    bump = lambda u: TARGET * math.exp(-2.0 * (u - 1.3)) * (1 + 0.8 * math.sin(9 * u) ** 2)   # noqa: E731
    return {"exp": monotone(1.37), "steep": steep, "power": lambda u: TARGET * (2.2 / u) ** 3, "bump": bump}


def test_the_bracket_holds_a_crossing_of_the_law():
    """Monotone and non-monotone laws: the final bracket is at most ``tol`` wide, more stable than the reference at
    its low end and at least as unstable at its high end (a crossing of ``t(U) = T`` lies inside), both ends run."""
    tol = 0.005
    laws = _laws()
    res, _ = search(laws, tol=tol)
    for name, law in laws.items():
        r = res[name]
        assert r.status == "found", name
        assert r.high - r.low <= tol * (1 + 1e-9), name
        assert law(r.low) > TARGET >= law(r.high), name
        assert r.low <= r.speed <= r.high
        assert dict(r.evaluations)[r.low] == law(r.low) and dict(r.evaluations)[r.high] == law(r.high)


def test_the_answer_does_not_depend_on_the_batch():
    """Each chair's search alone gives the same result as all chairs searched together (bit-identical)."""
    laws = _laws()
    together, _ = search(laws, tol=0.005)
    for name, law in laws.items():
        alone, _ = search({name: law}, tol=0.005)
        a, b = alone[name], together[name]
        assert (a.status, a.low, a.high, a.speed, a.evaluations) == (b.status, b.low, b.high, b.speed, b.evaluations)


def test_illinois_keeps_a_one_sided_approach_from_stalling():
    """Laws curved in log time: regula falsi alone would keep one end round after round; with Illinois each bracket
    closes to ``tol`` within ``max_rounds`` around a crossing."""
    laws = {"quadratic": lambda u: TARGET * math.exp(-3.0 * (u - 1.37) - 2.0 * (u - 1.37) ** 2),
            "sinh": lambda u: TARGET * math.exp(-math.sinh(3.0 * (u - 1.0))),
            "power": lambda u: TARGET * (2.2 / u) ** 3}
    res, _ = search(laws, tol=0.002)
    for name, law in laws.items():
        r = res[name]
        assert r.status == "found" and r.high - r.low <= 0.002 * (1 + 1e-9), name
        assert law(r.low) > TARGET >= law(r.high), name


def _documented_search(law, tol, max_rounds=8):
    """The speeds the bisection runs, from its documented rules alone (docs/studies.md, :func:`_pair`): the first
    round's decision from the whole grid; then each round a pair ``0.9 tol`` apart centred on the regula-falsi root
    of ``ln(t / T)`` between the bracket's ends, the margin of an end kept ``k >= 2`` rounds running halved
    ``k - 1`` times (Illinois), moved to ``0.05 tol`` inside an end it would cross; its faster speed run only where
    the slower one is not as unstable."""
    t = [law(u) for u in GRID]
    k = next(j for j, x in enumerate(t) if x <= TARGET)
    lo, hi, streak, ran = GRID[k - 1], GRID[k], 0, []       # streak: +n high end kept n rounds, -n low end
    for _ in range(max_rounds - 1):
        if hi - lo <= tol:
            break
        f_lo, f_hi = math.log(law(lo) / TARGET), math.log(law(hi) / TARGET)
        if streak >= 2:
            f_hi *= 0.5 ** (streak - 1)
        if streak <= -2:
            f_lo *= 0.5 ** (-streak - 1)
        x = lo + (hi - lo) * f_lo / (f_lo - f_hi)
        a = min(max(x - 0.45 * tol, lo + 0.05 * tol), hi - 0.95 * tol)
        ran.append(a)
        if law(a) <= TARGET:
            lo, hi, streak = lo, a, min(streak, 0) - 1
            continue
        ran.append(a + 0.9 * tol)
        if law(a + 0.9 * tol) <= TARGET:
            lo, hi, streak = a, a + 0.9 * tol, 0
        else:
            lo, hi, streak = a + 0.9 * tol, hi, max(streak, 0) + 1
    return ran, lo, hi


@pytest.mark.parametrize("name", ["steep", "expexp", "recip"])
def test_later_rounds_follow_the_documented_illinois_pairs(name):
    """Laws convex or flat at the crossing in log time, so regula falsi keeps one end for rounds on end: every pair
    run is the documented rule's (Illinois included), and so is the final bracket."""
    law = {"steep": _laws()["steep"], "expexp": lambda u: TARGET * math.exp(math.exp(-2.0 * (u - 1.3)) - 1.0),
           "recip": lambda u: TARGET * math.exp(1.0 / u - 1.0 / 1.7)}[name]
    tol = 0.0005
    res, fake = search({name: law}, tol=tol)
    later = [u for _, u in fake.runs if not np.isclose(GRID, u, rtol=0, atol=ABS).any()]
    ran, lo, hi = _documented_search(law, tol)
    # error model: the test's arithmetic differs from the module's in order only (a, b from x, shifts as a min/max):
    # a few roundings of O(1) m/s values, 1e-16 relative each, amplified by the rounds' chain of predictions
    # (each a ratio of log-time margins, condition < 1e3 here): 1e-9 m/s is ~1e3 x that, 1e-5 of a pair's spacing
    assert later == pytest.approx(ran, abs=1e-9)
    assert (res[name].low, res[name].high) == pytest.approx((lo, hi), abs=1e-9)


def _horizon_law(t_top):
    return lambda u: t_top if u == 3.0 else 10.0


@pytest.mark.parametrize("spec, reached", [(RunSpec(model="thesis", dt="auto"), True),
                                           (RunSpec(model="thesis", dt=0.002), True),
                                           (RunSpec(model="thesis", scheme="adaptive"), False)])
def test_a_time_within_one_step_of_the_horizon_counts(spec, reached):
    """The fixed-step scheme runs to ``horizon + dt`` (WCHAIR's loop, :class:`RunSpec`): a time up to one step past the
    horizon is a time; the adaptive scheme stops at the horizon, so the same time is "never" (inf)."""
    t = HORIZON + 0.0005                             # inside one step of 1 ms (auto) or 2 ms
    fake = ClosedForm({"c": _horizon_law(t)})
    r = ei.bisect_speeds(["c"], [TARGET], [40.0], spec, criterion=DEFAULT_CRITERION, bracket=(0.2, 3.0), tol=0.01,
                         candidates=7, max_rounds=8, progress=False, reference_text="-", summarise=fake)[0]
    assert r.status == "above" and r.evaluations == ((3.0, t if reached else math.inf),)


def test_a_time_exactly_at_the_horizon_plus_a_step_counts():
    end = float(np.minimum(DEFAULT_CRITERION.duration, 1.5 * np.asarray([TARGET]) + 0.5)[0]) + 0.001 + 1e-12
    fake = ClosedForm({"c": _horizon_law(end)})
    r = ei.bisect_speeds(["c"], [TARGET], [40.0], RunSpec(model="thesis"), criterion=DEFAULT_CRITERION,
                         bracket=(0.2, 3.0), tol=0.01, candidates=7, max_rounds=8, progress=False, reference_text="-",
                         summarise=fake)[0]
    assert r.evaluations == ((3.0, end),)


class _Kernel:
    """A stand-in for the thesis engine's ``run_summaries`` (and no step call: the adaptive scheme)."""

    def __init__(self, law):
        self.fake = ClosedForm({"c": law})

    def __call__(self, chairs, speeds, forces, run, *, level, **_):
        return self.fake(["c"] * len(chairs), speeds, forces, run, level=level)


def _speeds(monkeypatch, law, **options):
    k = _Kernel(law)
    monkeypatch.setattr(ei, "run_summaries", k)
    r = ei.equal_instability_speeds([preset("revised")], RunSpec(model="thesis", scheme="adaptive"),
                                    reference=TARGET, progress=False, **options)[0]
    return r, k.fake


def test_the_defaults_search_0_2_to_3_m_s_against_the_premier(monkeypatch):
    """The default search range is 0.2-3 m/s (docs/report.md) and the reference the E&J Premier at 0.75 m/s."""
    r, fake = _speeds(monkeypatch, monotone(1.1))
    assert r.bracket == (0.2, 3.0) and r.status == "found" and r.low <= 1.1 <= r.high
    assert r.reference == f"{preset(REFERENCE_CHAIR).name} at 0.75 m/s"


@pytest.mark.parametrize("candidates, grid", [(0, [0.2, 1.6, 3.0]), (1, [0.2, 1.6, 3.0]),
                                              (3, [0.2, 0.9, 1.6, 2.3, 3.0])])
def test_candidates_below_one_are_one(monkeypatch, candidates, grid):
    """The first round's grid: ``candidates`` speeds inside the bracket, at least one (its midpoint)."""
    _, fake = _speeds(monkeypatch, monotone(0.1), candidates=candidates)    # "below": the whole grid is run
    assert sorted(u for _, u in fake.runs) == pytest.approx(grid, abs=ABS)


def test_refusals_read_whole(monkeypatch):
    monkeypatch.setattr(ei, "run_summaries", _Kernel(monotone(1.0)))
    c = [preset("revised")]
    with pytest.raises(ValueError, match=r"^tol=0\.0 is invalid; valid range: > 0 m/s$"):
        ei.equal_instability_speeds(c, reference=TARGET, tol=0.0, progress=False)
    with pytest.raises(ValueError, match=r"^bracket=\(3\.0, 0\.2\) is invalid; expected 0 < low < high \(m/s\)$"):
        ei.equal_instability_speeds(c, reference=TARGET, bracket=(3.0, 0.2), progress=False)


def test_a_reference_that_never_reaches_the_level_is_refused():
    """1000 rad/s in 0.05 s is out of reach of any push of the study (the reference's message read whole)."""
    crit = Criterion(yaw_rate=1000.0, duration=0.05)
    with pytest.raises(ValueError, match=r"^the reference case \(ej-premier at 0\.75 m/s\) never reaches 1000 rad/s "
                                         r"within 0\.05 s; choose another reference$"):
        ei.reference_time(preset("ej-premier"), 0.75, RunSpec(model="thesis"), criterion=crit)


def test_the_result_is_frozen():
    r, _ = search({"c": monotone(1.1)}, tol=0.01)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r["c"].speed = 2.0                                         # type: ignore[misc]


def test_progress_is_shown_by_default(monkeypatch):
    """Without ``progress=False`` the bisection draws its bar (the commands' ``--quiet`` turns it off)."""
    seen = []

    class Bar:
        def __init__(self, total, desc, enabled=True, unit=""):
            seen.append(enabled)

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def update(self, n=1):
            pass

    monkeypatch.setattr(ei, "ProgressBar", Bar)
    monkeypatch.setattr(ei, "run_summaries", _Kernel(monotone(1.1)))
    ei.equal_instability_speeds([preset("revised")], RunSpec(model="thesis", scheme="adaptive"), reference=TARGET)
    assert seen == [True]
