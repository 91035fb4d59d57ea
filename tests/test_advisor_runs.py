"""Runs the advisor's searches spend: the equal-instability bisection's first round runs only the points that decide it."""

import math
from itertools import pairwise

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.study import equal_instability as ei
from stability.study.criteria import DEFAULT_CRITERION
from stability.study.summaries import Summaries

GRID = np.linspace(0.2, 3.0, 9)      # the first round's grid: bracket (0.2, 3) m/s, 7 candidates inside
TARGET = 3.2                         # the reference time, s
# error model: a grid speed is linspace's, a few roundings of O(1) m/s values (1e-16 relative), and is compared with
# the very same float when run; 1e-12 m/s is ~1e4 x that rounding yet ~1e9 x below the grid's spacing (0.35 m/s)
ON_GRID = 1e-12


class ClosedForm:
    """Time to the level of chair ``name`` at speed U: ``times[name](U)`` (s); records every run (chair, U)."""

    def __init__(self, times):
        self.times, self.runs = times, []

    def __call__(self, chairs, speeds, forces, run, *, level):
        t = np.array([self.times[c](float(u)) for c, u in zip(chairs, speeds, strict=True)])
        self.runs += list(zip(chairs, [float(u) for u in speeds], strict=True))
        return Summaries(np.where(np.isfinite(t), level, 0.5 * level), t, t, np.minimum(t, 10.0))

    def first_round(self, chair):
        """The speeds of ``chair`` run in the first round (every run on the grid; later rounds' pairs are not)."""
        return sorted(u for c, u in self.runs if c == chair and np.isclose(GRID, u, rtol=0, atol=ON_GRID).any())


def monotone(u_star):
    """3.2 s exp(-4 (U - U*)) / 1 s: the reference's time at U* exactly, falling with speed."""
    return lambda u: TARGET * math.exp(-4.0 * (u - u_star))


def search(times, tol=0.002):
    fake = ClosedForm(times)
    names = list(times)
    res = ei.bisect_speeds(names, [TARGET] * len(names), [40.0] * len(names), RunSpec(model="thesis"),
                           criterion=DEFAULT_CRITERION, bracket=(0.2, 3.0), tol=tol, candidates=7, max_rounds=8,
                           progress=False, reference_text="-", summarise=fake)
    return dict(zip(names, res, strict=True)), fake


def test_first_round_launches():
    assert ei._first_round(7) == [[8], [0, 1, 2, 3], [4, 5, 6, 7]]
    assert ei._first_round(2) == [[3], [0, 1, 2], []]          # a grid smaller than FIRST_SCAN: two launches


def test_first_round_runs_only_what_decides():
    res, fake = search({"slow": monotone(0.75), "fast": monotone(2.0), "above": monotone(3.75),
                        "below": monotone(0.1)})
    # above: 3 m/s alone (more stable than the reference there) decides; nothing else is run at all
    assert [u for _, u in fake.runs if _ == "above"] == [3.0]
    assert res["above"].status == "above" and res["above"].describe() == "> 3 m/s"
    # below: the fastest and the slowest four (0.2 m/s is already as unstable)
    assert fake.first_round("below") == pytest.approx(list(GRID[:4]) + [3.0], abs=ON_GRID)
    assert res["below"].status == "below" and res["below"].describe() == "< 0.2 m/s"
    # U* = 0.75: first point at least as unstable, 0.9 m/s, among the slowest four; 1.6-2.65 m/s not run
    assert fake.first_round("slow") == pytest.approx(list(GRID[:4]) + [3.0], abs=ON_GRID)
    # U* = 2.0: none of the slowest four; the rest of the grid then (the whole grid, 9 runs)
    assert fake.first_round("fast") == pytest.approx(list(GRID), abs=ON_GRID)
    # the final brackets hold U* and are at most tol wide (0.002 m/s); the interpolation in log time is exact for
    # this exponential (rounding only: 1e-12 m/s)
    for name, u_star in (("slow", 0.75), ("fast", 2.0)):
        r = res[name]
        assert r.status == "found" and r.low <= u_star <= r.high and r.high - r.low <= 0.002 + 1e-12
        assert r.speed == pytest.approx(u_star, abs=1e-12)


def test_first_round_keeps_the_whole_grids_decision():
    """Not monotone in speed: the decision is still the whole grid's (the fastest point; the first point as unstable)."""
    def dip(u):                                   # as unstable only from 0.5 to 1.0 m/s: 0.55 and 0.9 on the grid
        return 2.0 if 0.5 <= u <= 1.0 else 5.0

    def late(u):                                  # as unstable at 0.55 m/s only, and from 2.5 m/s on
        return 2.0 if abs(u - GRID[1]) < ON_GRID or u >= 2.5 else 5.0

    res, fake = search({"dip": dip, "late": late}, tol=0.5)
    # the whole grid: 3 m/s not as unstable -> "above", whatever 0.55-0.9 m/s do
    assert res["dip"].status == "above" and fake.first_round("dip") == [3.0]
    # the whole grid: the first point as unstable is 0.55 m/s -> bracket (0.2, 0.55); 0.35 m/s <= tol: no pairs
    assert (res["late"].status, res["late"].low, res["late"].high) == ("found", GRID[0], GRID[1])
    assert fake.first_round("late") == pytest.approx(list(GRID[:4]) + [3.0], abs=ON_GRID)


def test_front_caster_above_in_one_run():
    """The front-caster E&J Premier is more stable than the reference at 3 m/s: one run, not the grid's nine."""
    r = ei.equal_instability_speed(preset("ej-premier-front-caster"), progress=False)
    assert r.status == "above" and r.evaluations[0][0] == 3.0 and len(r.evaluations) == 1


def test_pair_runs_its_faster_point_only_when_needed():
    """A pair's slower point as unstable as the reference ends the bracket there: its faster point is not run."""
    tol = 0.002

    def steep(u):                  # 3.2 s at 0.75 m/s; regula falsi in log time approaches from above
        return TARGET * math.exp(-4.0 * (u - 0.75) * abs(u - 0.75))

    res, fake = search({"slow": monotone(0.75), "steep": steep}, tol=tol)
    off = {name: sorted(u for c, u in fake.runs if c == name and not np.isclose(GRID, u, rtol=0, atol=ON_GRID).any())
           for name in ("slow", "steep")}
    # steep: every later round's slower point is already as unstable (above 0.75 m/s): one run a round, 0.9 tol
    # faster never run; the bracket closes from above on its first point as unstable
    assert len(off["steep"]) >= 3 and all(u > 0.75 for u in off["steep"])
    assert all(v - u > 0.9 * tol + 1e-9 for u, v in pairwise(off["steep"]))
    assert res["steep"].high == off["steep"][0] and res["steep"].low < 0.75
    # exponential: a pair whose slower point is not as unstable runs its faster one too (0.9 tol apart)
    pairs = [(u, v) for u, v in pairwise(off["slow"]) if abs(v - u - 0.9 * tol) < 1e-9]
    assert any(u < 0.75 for u, _ in pairs)
    r = res["slow"]
    assert r.low <= 0.75 <= r.high and r.high - r.low <= tol + 1e-12


def test_run_steps_split_per_job():
    """One step call for a round gives each job the steps a call for it alone gives."""
    from stability.study.summaries import run_steps

    chairs = [preset("ej-premier"), preset("revised")]
    speeds = {0: [0.2, 0.55, 3.0], 1: [0.9]}
    got = ei._run_steps(chairs, speeds, RunSpec())
    assert got is not None and list(got) == [0, 1]
    for i, sp in speeds.items():
        assert got[i] == run_steps([chairs[i]] * len(sp), sp, 0.001, "exact", "free").tolist()
    assert ei._run_steps(chairs, speeds, RunSpec(scheme="adaptive")) is None


def test_as_unstable_exactly_at_the_fastest_point_is_a_crossing_not_above():
    """"At least as unstable" is ``t <= t_ref``: a chair reaching the level in exactly the reference's time at
    3 m/s (and later below it) crosses there, bracket (2.65, 3) m/s, not "above"."""
    res, _ = search({"edge": lambda u: TARGET if u >= 3.0 else 5.0}, tol=0.5)
    assert (res["edge"].status, res["edge"].low, res["edge"].high) == ("found", GRID[-2], GRID[-1])


def test_an_empty_speed_bracket_is_refused():
    """A bracket whose ends coincide holds no speed to search: refused, naming it."""
    with pytest.raises(ValueError, match=r"bracket=\(1\.0, 1\.0\) is invalid; expected 0 < low < high \(m/s\)"):
        ei.equal_instability_speeds([preset("ej-premier")], bracket=(1.0, 1.0), progress=False)
