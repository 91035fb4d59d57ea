"""Simulator benchmarks: the compiled kernel against the pure-numpy reference path, measured in the same run.

Skipped in the normal test run (pyproject's ``--benchmark-disable``); run with
``pytest tests/benchmarks/test_bench_simulate.py --benchmark-enable -s``.
Each benchmark prints and records (``extra_info``) its time and the ratio to
the numpy reference path timed in the same session.  Targets (issue 10): a
10 s WCHAIR run in a few ms; a 2,000-run batch at least 3x faster than the
numpy batch.  Numbers measured on the 2-core machine are in docs/simulator.md.
"""

import os
import subprocess
import sys
import time

import numpy as np
import pytest

from stability.chair import preset
from stability.simulate import DEFAULTS, simulate, simulate_batch
from stability.simulate.options import make_options
from stability.simulate.reference import wchair_batch

EJ = preset("ej-premier")
SPEEDS = np.linspace(0.5, 1.0, 2000)


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


def _timed(fn, repeat=1):
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _numpy(speeds, **kw):
    opts = dict(DEFAULTS.as_dict(), stop_on_warnings=False, **kw)
    del opts["controller"], opts["record"]
    return wchair_batch([EJ] * len(speeds), np.asarray(speeds, dtype=float), make_options(batch=True, **opts), False)


def test_bench_single_run(bench):
    simulate(EJ, 0.75, duration=0.1)  # compile / load the cache
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(stop_on_warnings=False), rounds=20, iterations=1,
                         warmup_rounds=2)
    assert len(res.t) == 10002
    mean = bench.stats.stats.mean
    ref = _timed(lambda: _numpy([0.75], sample=0.001))
    bench.extra_info.update(seconds=mean, numpy_reference_seconds=ref, speedup=ref / mean)
    print(f"\nsingle 10 s run: compiled {mean * 1e3:.2f} ms; numpy reference {ref * 1e3:.0f} ms -> x{ref / mean:.0f}")
    assert mean < 0.05


def test_bench_batch_2000(bench):
    simulate_batch(EJ, SPEEDS[:4], duration=0.1, progress=False)
    kw = dict(stop_on_warnings=False, sample=0.01, progress=False, record="states")
    res = bench.pedantic(simulate_batch, args=(EJ, SPEEDS), kwargs=kw, rounds=3, iterations=1)
    assert len(res) == 2000 and all(len(r.t) == 1001 for r in res)
    best = bench.stats.stats.min
    ref = _timed(lambda: _numpy(SPEEDS, sample=0.01))
    bench.extra_info.update(seconds=best, per_run_ms=best / 2 * 1e3, numpy_reference_seconds=ref, speedup=ref / best)
    print(f"\n2000 x 10 s batch: compiled {best:.2f} s ({best / 2:.2f} ms per run); numpy reference {ref:.1f} s "
          f"-> x{ref / best:.1f}")
    assert ref / best >= 3.0


def test_bench_adaptive_run(bench):
    simulate(EJ, 0.75, duration=0.1, scheme="adaptive")
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(scheme="adaptive"), rounds=2, iterations=1)
    assert res.t[-1] == pytest.approx(10.0)
    mean = bench.stats.stats.mean
    wchair = _timed(lambda: simulate(EJ, 0.75, stop_on_warnings=False), repeat=3)
    bench.extra_info.update(seconds=mean, rhs_evaluations=res.settings["nfev"], compiled_wchair_seconds=wchair)
    print(f"\nadaptive 10 s run: {mean:.2f} s ({res.settings['nfev']} evaluations, Python right-hand side); "
          f"compiled WCHAIR run {wchair * 1e3:.1f} ms")


def _fresh_process(cache_dir):
    code = ("import time; t=time.perf_counter(); from stability.chair import preset; "
            "from stability.simulate import simulate; simulate(preset('ej-premier'), 0.75, duration=0.01); "
            "print(time.perf_counter()-t)")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def test_bench_compile_and_cached_startup(bench, tmp_path):
    first = _fresh_process(tmp_path / "cache")       # empty cache: compiles
    cached = _fresh_process(tmp_path / "cache")      # loads the cache
    bench.pedantic(lambda: None, rounds=1)
    bench.extra_info.update(first_call_seconds=first, cached_startup_seconds=cached)
    print(f"\nfirst call (compile): {first:.1f} s; cached start-up: {cached:.2f} s")
    assert cached < first
