"""Simulator benchmarks: the one compiled engine, and what a Python yaw-moment input costs it, in the same run.

Skipped in the normal test run (pyproject's ``--benchmark-disable``); run with
``pytest tests/benchmarks/test_bench_simulate.py --benchmark-enable -s``.
Times are the minimum over repeats of the wall time (the process CPU time is
reported too, since the 2-core machine is shared).  The numpy and Python
transcriptions the kernel used to be timed against are gone (one engine), so
no speed-up over them is asserted; a Python ``yaw_moment`` (the kernel run one
step at a time, the input called in between) is timed against the same run
without one.  Nothing asserts a time: a benchmark reports.
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


def _alternate_cpu(fns, repeat=30):
    """Best process CPU seconds of each of ``fns`` (name: callable), called alternately ``repeat`` times."""
    best = {name: float("inf") for name in fns}
    for _ in range(repeat):
        for name, fn in fns.items():
            c0 = time.process_time()
            fn()
            best[name] = min(best[name], time.process_time() - c0)
    return best


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StepStabilityWarning)     # 0.3 m/s is below the 1 ms step's limit
        yield


def _zero(t, state):
    return 0.0


def test_bench_single_run(bench):
    simulate(EJ, 0.75, run=RunSpec(horizon=0.1))  # compile / load the cache
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(run=RunSpec(stop_on_warnings=False)), rounds=20, iterations=1,
                         warmup_rounds=2)
    assert len(res.t) == 10002
    best = bench.stats.stats.min
    cw, cc, _ = _timed(lambda: simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False)), repeat=20)
    hw, hc, hooked = _timed(lambda: simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False), yaw_moment=_zero), repeat=2)
    np.testing.assert_array_equal(res.yaw_rate, hooked.yaw_rate)     # a zero input: the same run, bit for bit
    bench.extra_info.update(seconds=best, cpu_seconds=cc, python_input_seconds=hw, python_input_cpu=hc,
                            input_cost=hw / best)
    print(f"\nsingle 10 s run: compiled {best * 1e3:.2f} ms wall ({cc * 1e3:.2f} ms CPU); with a Python yaw_moment "
          f"{hw * 1e3:.0f} ms ({hc * 1e3:.0f} ms CPU, x{hw / best:.0f})")


def test_bench_single_run_step_check_cached(bench):
    """One 10 s run with the step check's eigenvalues computed (cache emptied before each call) against the same
    run with them cached, alternately; the work asserted: the same run, bit for bit, and the same limit."""
    from stability.simulate import stepcheck

    run = RunSpec(stop_on_warnings=False)
    simulate(EJ, 0.75, run=RunSpec(horizon=0.1))
    cold_best = warm_best = float("inf")
    cold = warm = None
    for _ in range(20):
        stepcheck._CACHE.clear()
        c0 = time.process_time()
        cold = simulate(EJ, 0.75, run=run)
        cold_best = min(cold_best, time.process_time() - c0)
        c0 = time.process_time()
        warm = simulate(EJ, 0.75, run=run)
        warm_best = min(warm_best, time.process_time() - c0)
    bench.pedantic(lambda: None, rounds=1)
    np.testing.assert_array_equal(cold.yaw_rate, warm.yaw_rate)
    assert cold.settings["stable_dt"] == warm.settings["stable_dt"]
    bench.extra_info.update(cold_cpu_ms=cold_best * 1e3, cached_cpu_ms=warm_best * 1e3, ratio=cold_best / warm_best)
    print(f"\none 10 s run, CPU: step check computed {cold_best * 1e3:.2f} ms, cached {warm_best * 1e3:.2f} ms "
          f"-> x{cold_best / warm_best:.2f}")


def test_bench_single_run_entries(bench):
    """One 10 s run through the kernel's entry for one run (``run_one`` called from Python, its arrays without
    reference counts) against the parallel entry on one thread (how one run was run before issue 36), alternately
    in this process (process CPU, best of the repeats).  The work asserted: the same run, bit for bit."""
    from stability.simulate import baseline
    from stability.simulate.options import make_options

    opts = make_options(RunSpec(stop_on_warnings=False))
    fns = {name: baseline.kernel_only(EJ, 0.75, opts, entry=name) for name in ("single", "batch")}
    out = {name: fn() for name, fn in fns.items()}
    np.testing.assert_array_equal(out["single"], out["batch"])
    assert out["single"].shape == (31, 10002)      # 10 s at 1 ms: the rows of simulate()'s 10,002 times
    best = _alternate_cpu(fns)
    bench.pedantic(lambda: None, rounds=1)
    bench.extra_info.update(single_cpu_ms=best["single"] * 1e3, batch_cpu_ms=best["batch"] * 1e3,
                            ratio=best["batch"] / best["single"])
    print(f"\none 10 s run, kernel CPU: run_one from Python {best['single'] * 1e3:.3f} ms, the parallel entry "
          f"{best['batch'] * 1e3:.3f} ms -> x{best['batch'] / best['single']:.3f}")


def test_bench_scalar_step_trigonometry(bench):
    """One 10 s run through the scalar step as it is (libm's ``sincos`` and ``atan2``) against a copy compiled with
    the lanes kernel's polynomial trigonometry (``baseline.polynomial_trig_step``), alternately in this process
    (process CPU, best of the repeats): what replacing libm would gain (issue 36).  The work asserted: the same
    rows, and the same run within the polynomials' rounding bound for the first second (the run later spins out
    and a step-unstable phase amplifies any rounding difference, as ``docs/simulator.md`` says)."""
    from stability.simulate import baseline, lanemath
    from stability.simulate.options import make_options

    opts = make_options(RunSpec(stop_on_warnings=False))
    fns = {name: baseline.kernel_only(EJ, 0.75, opts, entry=name) for name in ("single", "polynomial_trig")}
    out = {name: fn() for name, fn in fns.items()}
    libm, poly = out["single"], out["polynomial_trig"]
    assert libm.shape == poly.shape == (31, 10002)
    # error model: a step perturbs the state by at most (SIN_COS_ULP + ATAN2_ULP + 2) eps relative (the polynomials'
    # bounds and libm's own ulp), adding at most linearly while the run neither grows nor crosses a discontinuity:
    # after n steps a column differs by at most n times that times its largest magnitude (observed about 1/70 of
    # it over the first 1,000 steps)
    n = 1000
    per_step = (lanemath.SIN_COS_ULP + lanemath.ATAN2_ULP + 2.0) * np.finfo(float).eps
    for c in range(libm.shape[0]):
        a, b = libm[c, :n + 1], poly[c, :n + 1]
        assert np.nanmax(np.abs(a - b)) <= n * per_step * max(float(np.nanmax(np.abs(a))), 1e-300), c
    best = _alternate_cpu(fns)
    bench.pedantic(lambda: None, rounds=1)
    bench.extra_info.update(libm_cpu_ms=best["single"] * 1e3, polynomial_cpu_ms=best["polynomial_trig"] * 1e3,
                            ratio=best["single"] / best["polynomial_trig"])
    print(f"\none 10 s run, kernel CPU: libm trigonometry {best['single'] * 1e3:.3f} ms, polynomial "
          f"{best['polynomial_trig'] * 1e3:.3f} ms -> x{best['single'] / best['polynomial_trig']:.3f}")


@pytest.mark.parametrize("horizon", [10.0, 0.002], ids=["10s", "2ms"])
def test_bench_single_run_python_share(bench, horizon):
    """``simulate`` against the compiled kernel called alone on the same run, alternately in this process
    (process CPU, best and median of the repeats): the ratio is the figure (the machine is shared); the 2 ms run
    is almost all Python.  The work asserted: the same run, bit for bit."""
    from stability.simulate import baseline
    from stability.simulate.options import make_options

    run = RunSpec(stop_on_warnings=False, horizon=horizon)
    bare = baseline.kernel_only(EJ, 0.75, make_options(run))
    res = simulate(EJ, 0.75, run=run)
    np.testing.assert_array_equal(bare()[3], res.yaw_rate)     # row 3: the yaw rate
    inner = max(1, int(round(0.02 / horizon)))        # short runs timed in groups (the clock's resolution)
    cpu: dict[str, list[float]] = {"simulate": [], "kernel": []}
    for _ in range(60):
        for name, fn in (("simulate", lambda: simulate(EJ, 0.75, run=run)), ("kernel", bare)):
            c0 = time.process_time()
            for _ in range(inner):
                fn()
            cpu[name].append((time.process_time() - c0) / inner)
    bench.pedantic(lambda: None, rounds=1)
    best = {k: min(v) for k, v in cpu.items()}
    med = {k: float(np.median(v)) for k, v in cpu.items()}
    bench.extra_info.update(simulate_cpu_ms=med["simulate"] * 1e3, kernel_cpu_ms=med["kernel"] * 1e3,
                            ratio_median=med["simulate"] / med["kernel"], ratio_best=best["simulate"] / best["kernel"],
                            python_ms=(med["simulate"] - med["kernel"]) * 1e3)
    print(f"\none {horizon:g} s run, CPU (median): simulate {med['simulate'] * 1e3:.3f} ms, the kernel alone "
          f"{med['kernel'] * 1e3:.3f} ms -> x{med['simulate'] / med['kernel']:.3f} (best x"
          f"{best['simulate'] / best['kernel']:.3f}); Python {(med['simulate'] - med['kernel']) * 1e3:.3f} ms")


def test_bench_batch_2000(bench):
    simulate_batch(EJ, STUDY_SPEEDS[:4], run=RunSpec(horizon=0.1), progress=False)
    kw = dict(progress=False, record="final")
    res = bench.pedantic(simulate_batch, args=(EJ, STUDY_SPEEDS), kwargs=kw, rounds=3, iterations=1)
    assert len(res) == 2000 and all(len(r.t) == 1 for r in res)
    best = bench.stats.stats.min
    cw, cc, _ = _timed(lambda: simulate_batch(EJ, STUDY_SPEEDS, **kw), repeat=3)
    sw, sc, states = _timed(lambda: simulate_batch(EJ, STUDY_SPEEDS, run=RunSpec(friction_law="kinetic"), progress=False, record="states"))
    wall = min(best, cw)
    bench.extra_info.update(seconds=wall, cpu_seconds=cc, per_run_ms=wall / 2, states_seconds=sw)
    print(f"\n2000-run speed study (record='final'): compiled {wall:.2f} s wall, {cc:.2f} s CPU "
          f"({wall / 2:.2f} ms per run); record='states' {sw:.2f} s")


def test_bench_adaptive_run(bench):
    simulate(EJ, 0.75, run=RunSpec(horizon=0.1, scheme="adaptive"))
    res = bench.pedantic(simulate, args=(EJ, 0.75), kwargs=dict(run=RunSpec(scheme="adaptive")), rounds=5, iterations=1)
    assert res.t[-1] == pytest.approx(10.0, rel=1e-13)    # rounding of the sample grid's times, a few ulp (observed 0)
    best = bench.stats.stats.min
    pw, pc, py = _timed(lambda: simulate(EJ, 0.75, run=RunSpec(scheme="adaptive"), yaw_moment=_zero), repeat=2)
    np.testing.assert_array_equal(res.yaw_rate, py.yaw_rate)
    bench.extra_info.update(seconds=best, rhs_evaluations=res.settings["nfev"], python_input_seconds=pw,
                            input_cost=pw / best)
    print(f"\nadaptive 10 s run: {best * 1e3:.0f} ms ({res.settings['nfev']} evaluations); with a Python "
          f"yaw_moment {pw * 1e3:.0f} ms (x{pw / best:.1f})")


def _fresh_process(cache_dir, scheme):
    code = ("import time; t=time.perf_counter(); from stability.chair import preset; "
            "from stability.simulate import simulate; from stability.settings.run import RunSpec; "
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
