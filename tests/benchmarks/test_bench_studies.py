"""Study and report benchmarks (issue 10): the compiled simulator against the reference paths in the same run.

``stability.simulate.reference_engine()`` makes every WCHAIR run inside it use the
pure-Python/numpy reference paths that the kernel is tested against, so the same
study or report is timed both ways in one process (best of repeats, after a
warm-up that loads the cached kernels).  Targets: ``equal_instability_speed`` at
least 20x faster, the report build at least 3x faster.  Skipped unless
``--benchmark-enable`` (CI runs them as their own step).
"""

import time
import warnings

import pytest

from stability import simulate as sim
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


def test_bench_equal_instability_speed(bench):
    study = _quiet(lambda: equal_instability_speed(REVISED, run=RunSpec(model="thesis")))
    study()                                                     # warm-up: cached kernels, imports

    def reference():
        with sim.reference_engine():
            return study()

    t_ref, ref = _best(reference, 2)
    t_fast, fast = _best(study, 5)
    bench.pedantic(study, rounds=3, iterations=1)
    ratio = t_ref / t_fast
    bench.extra_info.update(compiled_s=t_fast, reference_s=t_ref, speedup=ratio)
    print(f"\nequal_instability_speed(revised): compiled {t_fast:.3f} s, reference {t_ref:.2f} s (x{ratio:.0f})")
    assert fast.speed == pytest.approx(ref.speed, rel=1e-6)     # same answer either way
    assert ratio >= 20


@pytest.mark.parametrize("quick", [True, False], ids=["quick", "full"])
def test_bench_report_build(bench, tmp_path, quick):
    def build(path):
        return _quiet(lambda: document.build(REVISED, path, quick=quick, progress=False))()

    build(tmp_path / "warm.pdf")

    def reference():
        with sim.reference_engine():
            return build(tmp_path / "ref.pdf")

    t_ref, _ = _best(reference, 1)
    t_fast, res = _best(lambda: build(tmp_path / "fast.pdf"), 2 if quick else 1)
    bench.pedantic(lambda: build(tmp_path / "b.pdf"), rounds=1, iterations=1)
    ratio = t_ref / t_fast
    bench.extra_info.update(compiled_s=t_fast, reference_s=t_ref, speedup=ratio, pages=len(res.pages))
    print(f"\nreport ({'quick' if quick else 'full'}, revised, {len(res.pages)} pages): compiled {t_fast:.1f} s, "
          f"reference {t_ref:.1f} s (x{ratio:.1f})")
    assert ratio >= (1.5 if quick else 3.0)
