"""Searches asked again inside an open memo are not run again (stability.study.memo), and nothing changes.

The premise, checked independently of the memo: a job's result does not depend on the batch it runs in (the same
chair alone and beside others gives the same critical impulse, the same equal-instability bisection and the same
reference time, to the bit).  The consequence: the advisor (which opens a memo) decides exactly as without it, on
the committed report chairs and on seeded random chairs, with fewer simulated runs.
"""

from __future__ import annotations

import contextlib
import dataclasses
from pathlib import Path

import pytest
from test_advise_pruning import _random_chairs

from stability.advise import advise
from stability.advise.decision import decide
from stability.advise.text import advice_mapping
from stability.chair import io as chair_io
from stability.chair import preset
from stability.settings.run import RunSpec
from stability.study import critical_impulses, memo
from stability.study.criteria import DEFAULT_CRITERION
from stability.study.equal_instability import bisect_speeds
from stability.study.intervals import reference_times

ROOT = Path(__file__).resolve().parents[1]


class _Batches:
    """A ``compute`` for :func:`memo.memoised` that records the batches it is asked for."""

    def __init__(self):
        self.calls: list[list[int]] = []

    def __call__(self, idx):
        self.calls.append(list(idx))
        return [f"r{i}" for i in idx]


def test_without_an_open_memo_every_job_is_computed():
    b = _Batches()
    assert memo.memoised("k", ["a", "a", "b"], b) == ["r0", "r1", "r2"]
    assert b.calls == [[0, 1, 2]]


def test_inside_a_memo_a_job_asked_again_is_reused_and_a_repeated_job_runs_once():
    b = _Batches()
    with memo.search_memo():
        assert memo.memoised("k", ["a", "b", "a"], b) == ["r0", "r1", "r0"]
        # "a" known, "c" new, None and an unhashable key always computed; another kind is another search
        assert memo.memoised("k", ["c", "a", None, ["x"]], b) == ["r0", "r0", "r2", "r3"]
        assert memo.memoised("other", ["a"], b) == ["r0"]
    assert b.calls == [[0, 1], [0, 2, 3], [0]]
    assert memo.memoised("k", ["a"], b) == ["r0"] and b.calls[-1] == [0]     # closed: forgotten


def test_nested_memos_share_one_and_the_decorator_opens_one():
    b = _Batches()

    @memo.memo_searches
    def twice():
        with memo.search_memo():
            memo.memoised("k", ["a"], b)
        return memo.memoised("k", ["a"], b)

    assert twice() == ["r0"] and b.calls == [[0]]


def _ci(chairs, speed=0.75):
    return [r.to_dict() for r in critical_impulses(chairs, speed, RunSpec())]


def _bisect(chairs, targets):
    run = RunSpec().replace(dt=0.001)
    res = bisect_speeds(chairs, targets, [40.0] * len(chairs), run, criterion=DEFAULT_CRITERION, bracket=(0.2, 3.0),
                        tol=0.01, candidates=7, max_rounds=8, progress=False, reference_text="ref")
    return [(r.speed, r.status, r.low, r.high, r.evaluations) for r in res]


def test_a_jobs_result_does_not_depend_on_its_batch():
    """The memo's premise, without the memo: alone and beside other chairs, the same result to the bit."""
    ej, rv = preset("ej-premier"), preset("revised")
    other = ej.replace(trail=0.06, name="t6")
    assert _ci([ej]) == _ci([rv, ej, other])[1:2]
    t = float(reference_times(ej, 0.75, [40.0], RunSpec(), criterion=DEFAULT_CRITERION)[0])
    both = reference_times([rv, ej], 0.75, [20.0, 40.0], RunSpec(), criterion=DEFAULT_CRITERION)
    assert both[1] == t
    assert _bisect([ej], [t]) == _bisect([other, ej], [0.5 * t, t])[1:2]


def _runs_of(fn, monkeypatch) -> tuple[int, object]:
    from stability.simulate import engine

    n = [0]
    inner = engine._launch

    def counting(k, threads, n_runs, args):
        n[0] += int(n_runs)
        return inner(k, threads, n_runs, args)

    monkeypatch.setattr(engine, "_launch", counting)
    out = fn()
    monkeypatch.setattr(engine, "_launch", inner)
    return n[0], out


def test_inside_a_memo_the_results_are_the_same_and_fewer_runs_are_made(monkeypatch):
    ej = preset("ej-premier")
    t6 = ej.replace(trail=0.06, name="t6")
    first, plain = _runs_of(lambda: _ci([ej, t6]), monkeypatch)
    with memo.search_memo():
        again, found = _runs_of(lambda: _ci([ej, t6]), monkeypatch)
        assert found == plain and again == first
        assert _runs_of(lambda: _ci([t6]), monkeypatch) == (0, plain[1:])      # nothing run again


def _everything(a) -> tuple:
    """The whole advice: decision, recommendations, blocked, every candidate and combination with its measures."""
    d = advice_mapping(a)
    return (decide(a).to_mapping(), d, [(c.label, c.bounded, c.gains, c.measures.to_mapping())
                                       for c in a.candidates + a.combinations], a.intervals_computed)


def _committed_chairs() -> list:
    """The chairs of the committed reports (tests/test_committed_reports.py): three presets and the measured chair."""
    return [preset("ej-premier"), preset("revised"), preset("ej-premier-front-caster"),
            chair_io.load(ROOT / "docs" / "examples" / "measured_chair.toml")]


_CHAIRS = _committed_chairs()


@pytest.mark.parametrize("chair", [_CHAIRS[0]] + [pytest.param(c, marks=pytest.mark.slow)
                                                  for c in _CHAIRS[1:] + _random_chairs(3, seed=3535)],
                         ids=["ej-premier", "revised", "front-caster", "measured-chair", "random0", "random1",
                              "random2"])
def test_the_advisor_decides_exactly_as_without_the_memo(chair, monkeypatch):
    """ej-premier in the default run (about 5 s of CPU), the other committed chairs and three seeded random chairs
    in the slow one."""
    with_memo = _runs_of(lambda: advise(chair), monkeypatch)
    monkeypatch.setattr(memo, "search_memo", contextlib.nullcontext)     # memo_searches opens nothing
    without = _runs_of(lambda: advise(chair), monkeypatch)
    assert _everything(with_memo[1]) == _everything(without[1])
    assert with_memo[0] < without[0]


def test_a_reused_bisection_carries_the_callers_reference_words():
    ej = preset("ej-premier")
    run = RunSpec().replace(dt=0.001)
    kw = dict(criterion=DEFAULT_CRITERION, bracket=(0.2, 3.0), tol=0.01, candidates=7, max_rounds=8, progress=False)
    with memo.search_memo():
        a = bisect_speeds([ej], [3.0], [40.0], run, reference_text="a", **kw)[0]
        b = bisect_speeds([ej], [3.0], [40.0], run, reference_text="b", **kw)[0]
    assert (a.reference, b.reference) == ("a", "b")
    assert dataclasses.replace(b, reference="a").evaluations == a.evaluations and b.speed == a.speed
