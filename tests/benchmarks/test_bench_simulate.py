"""Simulator benchmarks: the compiled kernels against the pure-numpy / Python reference paths, in the same run.

Skipped in the normal test run (pyproject's ``--benchmark-disable``); run with
``pytest tests/benchmarks/test_bench_simulate.py --benchmark-enable -s``.
Every benchmark times the compiled path and its reference in the same process
(minimum over repeats of the wall time; the process CPU time is reported too,
since the 2-core machine is shared) and asserts the issue-10 targets on the
ratio: a single 10 s WCHAIR run at least 20x faster than the numpy reference
and a few ms; the 2,000-run speed study at least 3x faster than the numpy
batch.  Numbers measured here are in docs/simulator.md.
"""

import os
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import StepStabilityWarning, simulate, simulate_batch
from stability.simulate.options import make_options
from stability.simulate.reference import wchair_batch

EJ = preset("ej-premier")
#: the speed study (issue 10): ej-premier at 2,000 speeds, default options (10 s, 1 ms, stop at 11 warnings)
STUDY_SPEEDS = np.linspace(0.3, 1.5, 2000)


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


def _timed(fn, repeat=1):
    """``(best wall s, best CPU s, last result)`` over ``repeat`` calls."""
    wall = cpu = float("inf")
    out = None
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        wall, cpu = min(wall, time.perf_counter() - w0), min(cpu, time.process_time() - c0)
    return wall, cpu, out


def _numpy(speeds, **kw):
    """The pure-numpy reference batch (reference.wchair_batch) with program WCHAIR's kinetic law."""
    run = RunSpec(friction_law="kinetic", **kw)
    return wchair_batch([EJ] * len(speeds), np.asarray(speeds, dtype=float), make_options(run, batch=True), False)


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StepStabilityWarning)     # 0.3 m/s is below the 1 ms step's limit
        yield


def test_bench_single_run(bench):
    simulate(EJ, 0.75, run=RunSpec(horizon=0.1, friction_law="kinetic"))  # compile / load the cache
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(run=RunSpec(stop_on_warnings=False,
                                                                          friction_law="kinetic")), rounds=20, iterations=1,
                         warmup_rounds=2)
    assert len(res.t) == 10002
    best = bench.stats.stats.min
    cw, cc, _ = _timed(lambda: simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False, friction_law="kinetic")), repeat=20)
    rw, rc, ref = _timed(lambda: _numpy([0.75], sample=0.001, stop_on_warnings=False))
    np.testing.assert_allclose(res.yaw_rate, ref[0].yaw_rate, rtol=1e-6, atol=1e-9)
    bench.extra_info.update(seconds=best, cpu_seconds=cc, numpy_reference_seconds=rw, numpy_reference_cpu=rc,
                            speedup=rw / best, cpu_speedup=rc / cc)
    print(f"\nsingle 10 s run: compiled {best * 1e3:.2f} ms wall ({cc * 1e3:.2f} ms CPU); numpy reference "
          f"{rw * 1e3:.0f} ms ({rc * 1e3:.0f} ms CPU) -> x{rw / best:.0f} wall, x{rc / cc:.0f} CPU")
    assert rw / best >= 20.0


def test_bench_batch_2000(bench):
    simulate_batch(EJ, STUDY_SPEEDS[:4], run=RunSpec(horizon=0.1, friction_law="kinetic"), progress=False)
    kw = dict(run=RunSpec(friction_law="kinetic"), progress=False, record="final")
    res = bench.pedantic(simulate_batch, args=(EJ, STUDY_SPEEDS), kwargs=kw, rounds=3, iterations=1)
    assert len(res) == 2000 and all(len(r.t) == 1 for r in res)
    best = bench.stats.stats.min
    # compiled and reference timed alternately, best of each: a passing load on the shared 2-core
    # machine then slows both sides of the ratio alike instead of only one
    cw = cc = rw = rc = float("inf")
    ref = None
    for _ in range(3):
        w, c, _ = _timed(lambda: simulate_batch(EJ, STUDY_SPEEDS, **kw))
        cw, cc = min(cw, w), min(cc, c)
        w, c, ref = _timed(lambda: _numpy(STUDY_SPEEDS))
        rw, rc = min(rw, w), min(rc, c)
    sw, sc, states = _timed(lambda: simulate_batch(EJ, STUDY_SPEEDS, run=RunSpec(friction_law="kinetic"), progress=False, record="states"))
    # the same runs (rounding-level differences, libm vs numpy's SIMD functions, can move a stop by a step)
    stop_c = np.array([r.stop_time if r.stopped_by_warnings else np.inf for r in res])
    stop_r = np.array([r.stop_time if r.stopped_by_warnings else np.inf for r in ref])
    assert np.mean(np.isclose(stop_c, stop_r, rtol=0, atol=0.0015) | (stop_c == stop_r)) >= 0.99
    wall = min(best, cw)
    bench.extra_info.update(seconds=wall, cpu_seconds=cc, per_run_ms=wall / 2, states_seconds=sw,
                            numpy_reference_seconds=rw, numpy_reference_cpu=rc, speedup=rw / wall,
                            cpu_speedup=rc / cc)
    print(f"\n2000-run speed study (record='final'): compiled {wall:.2f} s wall, {cc:.2f} s CPU "
          f"({wall / 2:.2f} ms per run); record='states' {sw:.2f} s; numpy reference {rw:.2f} s wall, {rc:.2f} s CPU "
          f"-> x{rw / wall:.1f} wall, x{rc / cc:.1f} CPU (per core)")
    assert rw / wall >= 3.0


def test_bench_adaptive_run(bench):
    def zero(t, state):
        return 0.0

    simulate(EJ, 0.75, run=RunSpec(horizon=0.1, scheme="adaptive"))
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(run=RunSpec(scheme="adaptive")), rounds=5, iterations=1)
    assert res.t[-1] == pytest.approx(10.0) and res.settings["engine"] == "compiled"
    best = bench.stats.stats.min
    pw, pc, py = _timed(lambda: simulate(EJ, 0.75, run=RunSpec(scheme="adaptive"), yaw_moment=zero), repeat=2)
    assert py.settings["engine"] == "python"
    bench.extra_info.update(seconds=best, rhs_evaluations=res.settings["nfev"], python_rhs_seconds=pw,
                            speedup=pw / best)
    print(f"\nadaptive 10 s run: compiled right-hand side {best * 1e3:.0f} ms ({res.settings['nfev']} evaluations); "
          f"Python right-hand side {pw * 1e3:.0f} ms -> x{pw / best:.1f}")
    assert pw / best >= 1.5


def _fresh_process(cache_dir, scheme):
    code = ("import time; t=time.perf_counter(); from stability.chair import preset; "
            "from stability.simulate import RunSpec, simulate; "
            f"simulate(preset('ej-premier'), 0.75, RunSpec(horizon=0.01, scheme={scheme!r})); "
            "print(time.perf_counter()-t)")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, check=True)
    return float(out.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("scheme", ["wchair", "adaptive"])
def test_bench_compile_and_cached_startup(bench, tmp_path, scheme):
    first = _fresh_process(tmp_path / "cache", scheme)       # empty cache: compiles
    cached = _fresh_process(tmp_path / "cache", scheme)      # loads the cache
    bench.pedantic(lambda: None, rounds=1)
    bench.extra_info.update(first_call_seconds=first, cached_startup_seconds=cached, ratio=first / cached)
    print(f"\n{scheme}: first call in a fresh process (compile) {first:.1f} s; cached start-up {cached:.2f} s "
          f"-> x{first / cached:.0f}")
    assert cached < 0.5 * first
