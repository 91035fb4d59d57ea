"""The lanes kernel (runs as SIMD lanes, issue 36) against the scalar kernel, timed in the same run.

Run with ``python -m pytest tests/benchmarks/test_bench_lanes.py --benchmark-enable -s -n 0``.  Both kernels
are timed alternately (best of three each, in alternating order) in one process, so a passing load slows both
alike; the figure is process CPU time (every thread) per run.  Nothing asserts a time: a benchmark reports, and
asserts the work (the runs executed, their steps, their stops) is the same for both kernels.  docs/simulator.md
("Runs as lanes") gives the measured figures.
"""

import os
import resource
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import StepStabilityWarning, engine, simulate, simulate_batch

EJ = preset("ej-premier")
#: the speed study (issue 10): ej-premier at 2,000 speeds, default settings (10 s, 1 ms, stick-slip pins, stop at
#: the 11th warning)
SPEEDS = np.linspace(0.3, 1.5, 2000)


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StepStabilityWarning)
        yield


def _cpu(fn):
    c0 = time.process_time()
    out = fn()
    return time.process_time() - c0, out


def _alternate(fn, repeat=3):
    """Best CPU seconds of ``fn`` on the lanes and on the scalar kernel, alternately; the last results of each."""
    best = {"lanes": float("inf"), "scalar": float("inf")}
    out = {}
    for _ in range(repeat):
        for name in ("lanes", "scalar"):
            with engine.use_kernel(name):
                cpu, out[name] = _cpu(fn)
            best[name] = min(best[name], cpu)
    return best, out


def _work(results):
    """The work: runs, which runs reach 1 rad/s (what the searches use), steps executed (each run's last time).

    The runs that reach the level spin out, and where such a run then stops by the warning rule is as sensitive to
    rounding as a chaotic run is (1 run of 2,000 stops differently, 330 stop at other times), so the steps are
    compared to 0.1 %, the runs and the reaching set exactly.
    """
    last = np.array([r.t[-1] for r in results])
    reach = tuple(i for i, r in enumerate(results) if r.stats.time_to_level[-1] is not None)
    return len(results), reach, int(np.rint(last / 0.001).sum())


def test_bench_lanes_batch_2000(bench):
    kw = dict(progress=False, record="final")
    for name in ("lanes", "scalar"):
        with engine.use_kernel(name):
            simulate_batch(EJ, SPEEDS[:4], run=RunSpec(horizon=0.1), **kw)    # compile / load the caches
    best, out = _alternate(lambda: simulate_batch(EJ, SPEEDS, **kw))
    bench.pedantic(lambda: None, rounds=1)
    wl, ws = _work(out["lanes"]), _work(out["scalar"])
    assert wl[:2] == ws[:2]
    # error model: rounding-level differences move where a spun-out run stops (330 of the 2,000 runs stop at other
    # times; their shifts sum to 3.2e-3 of the steps in magnitude, to a net 9.1e-5 as shifts of either sign cancel,
    # observed): 1e-2 is ~100x the net and 3x the summed shifts
    assert wl[2] == pytest.approx(ws[2], rel=1e-2)
    n = len(SPEEDS)
    lanes_ms, scalar_ms = best["lanes"] / n * 1e3, best["scalar"] / n * 1e3
    bench.extra_info.update(lanes_ms_per_run_cpu=lanes_ms, scalar_ms_per_run_cpu=scalar_ms,
                            ratio=scalar_ms / lanes_ms, steps=wl[2])
    print(f"\n2,000 x 10 s runs (ej-premier, defaults, record='final'): lanes {lanes_ms:.3f} ms CPU per run, "
          f"scalar {scalar_ms:.3f} ms -> x{scalar_ms / lanes_ms:.2f}; {wl[2]} steps (scalar {ws[2]})")


def test_bench_lanes_batch_order(bench):
    """The speed study on the lanes kernel in speed order and in a seeded random order (a sweep's order, where a
    block's runs stop at more different times and its running lanes move together, lanes_kernel._compact),
    alternately in one process.  The work is the same runs, so it is asserted exactly: each run's results do not
    depend on its block or column (bit for bit), hence the same steps and the same runs reaching the level."""
    kw = dict(progress=False, record="final")
    order = np.random.default_rng(36).permutation(len(SPEEDS))
    best = {"ordered": float("inf"), "shuffled": float("inf")}
    out = {}
    with engine.use_kernel("lanes"):
        simulate_batch(EJ, SPEEDS[:4], run=RunSpec(horizon=0.1), **kw)      # compile / load the cache
        for _ in range(3):
            for name, speeds in (("ordered", SPEEDS), ("shuffled", SPEEDS[order])):
                cpu, out[name] = _cpu(lambda s=speeds: simulate_batch(EJ, s, **kw))
                best[name] = min(best[name], cpu)
    bench.pedantic(lambda: None, rounds=1)
    back = [None] * len(SPEEDS)
    for k, r in zip(order, out["shuffled"], strict=True):
        back[k] = r
    for a, b in zip(out["ordered"], back, strict=True):
        assert a.stats == b.stats and a.stop_time == b.stop_time
        np.testing.assert_array_equal(np.asarray(a.yaw_rate), np.asarray(b.yaw_rate))
    assert _work(out["ordered"]) == _work(back)
    n = len(SPEEDS)
    ordered_ms, shuffled_ms = best["ordered"] / n * 1e3, best["shuffled"] / n * 1e3
    bench.extra_info.update(ordered_ms_per_run_cpu=ordered_ms, shuffled_ms_per_run_cpu=shuffled_ms,
                            ratio=shuffled_ms / ordered_ms)
    print(f"\nlanes, 2,000 x 10 s runs: in speed order {ordered_ms:.3f} ms CPU per run, in random order "
          f"{shuffled_ms:.3f} ms (x{shuffled_ms / ordered_ms:.2f})")


def test_bench_lanes_single_run(bench):
    run = RunSpec(stop_on_warnings=False)
    for name in ("lanes", "scalar"):
        with engine.use_kernel(name):
            simulate(EJ, 0.75, run=RunSpec(horizon=0.1))
    best, out = _alternate(lambda: simulate(EJ, 0.75, run=run), repeat=10)
    bench.pedantic(lambda: None, rounds=1)
    assert len(out["lanes"].t) == len(out["scalar"].t) == 10002
    bench.extra_info.update(lanes_ms=best["lanes"] * 1e3, scalar_ms=best["scalar"] * 1e3)
    print(f"\none 10 s run (record='all'): lanes {best['lanes'] * 1e3:.2f} ms CPU, scalar {best['scalar'] * 1e3:.2f} "
          f"ms -> x{best['scalar'] / best['lanes']:.2f}")


def _first_use(kernel, cache_dir):
    """CPU seconds (user + system) of a fresh process's first simulation with ``cache_dir`` as numba's cache."""
    code = ("from stability.chair import preset; from stability.simulate import simulate, engine; "
            "from stability.settings.run import RunSpec\n"
            f"with engine.use_kernel({kernel!r}):\n"
            "    simulate(preset('ej-premier'), 0.75, RunSpec(horizon=0.01))")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", code], env=dict(os.environ, NUMBA_CACHE_DIR=str(cache_dir)), check=True,
                   capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


@pytest.mark.parametrize("kernel", ["lanes", "scalar"])
def test_bench_first_use(bench, tmp_path, kernel):
    """An empty numba cache (a fresh install, a new Dask worker, a CI step), then the same with the cache."""
    first = _first_use(kernel, tmp_path / "cache")
    cached = _first_use(kernel, tmp_path / "cache")
    bench.pedantic(lambda: None, rounds=1)
    bench.extra_info.update(first_use_cpu_s=first, cached_cpu_s=cached)
    print(f"\n{kernel}: first use with an empty cache {first:.1f} s CPU; with the cache {cached:.2f} s CPU")
