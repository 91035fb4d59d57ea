"""Study and report benchmarks (issue 10): what a study and a report cost on the compiled simulator.

The numpy/Python reference engine these were timed against is gone (one
engine).  ``equal_instability_speed`` is timed against the same study with
every run built as a full result through :func:`stability.study.runs.simulate_runs`
(the path of the adaptive scheme and Python inputs) instead of the packed
kernel's summaries, the same kernel either way (best of repeats, after a
warm-up that loads the cached kernels; the answers are asserted equal); the
report build is timed alone.  Nothing asserts a time.  Skipped unless
``--benchmark-enable`` (CI runs them as their own step).
"""

import time
import warnings

import pytest

from stability.chair import preset
from stability.report import document
from stability.settings.run import RunSpec
from stability.study import equal_instability_speed

REVISED = preset("revised")


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


def _best(fn, repeat):
    best, out = float("inf"), None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def _quiet(fn):
    def run():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return fn()
    return run


def test_bench_equal_instability_speed(bench, monkeypatch):
    from stability.study import summaries

    study = _quiet(lambda: equal_instability_speed(REVISED, run=RunSpec(model="thesis")))
    study()                                                     # warm-up: cached kernels, imports
    t_fast, fast = _best(study, 5)
    bench.pedantic(study, rounds=3, iterations=1)
    monkeypatch.setattr(summaries, "_compiled", lambda run: False)
    t_full, full = _best(study, 2)
    ratio = t_full / t_fast
    bench.extra_info.update(summaries_s=t_fast, full_results_s=t_full, ratio=ratio)
    print(f"\nequal_instability_speed(revised): packed summaries {t_fast:.3f} s, full results {t_full:.2f} s "
          f"(x{ratio:.1f})")
    # same answer either way; wiring check; error model: rounding: the criterion times of the packed summaries and of
    # the full results differ by a few ulp, so the search takes the same brackets to the same speed (observed 0)
    assert fast.speed == pytest.approx(full.speed, rel=1e-12)


@pytest.mark.parametrize("quick", [True, False], ids=["quick", "full"])
def test_bench_report_build(bench, tmp_path, quick):
    def build(path):
        return _quiet(lambda: document.build(REVISED, path, quick=quick, progress=False))()

    build(tmp_path / "warm.pdf")
    t_fast, res = _best(lambda: build(tmp_path / "fast.pdf"), 2 if quick else 1)
    bench.pedantic(lambda: build(tmp_path / "b.pdf"), rounds=1, iterations=1)
    bench.extra_info.update(compiled_s=t_fast, pages=len(res.pages))
    print(f"\nreport ({'quick' if quick else 'full'}, revised, {len(res.pages)} pages): {t_fast:.1f} s")
