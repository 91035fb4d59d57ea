"""The value groups of docs/simulator.md's measured speeds: the two WCHAIR kernels timed in the same process.

As :mod:`value_groups_pages`: each function calls the toolkit's public API and returns formatted strings; import
:mod:`value_groups`, not this module.  Times are process CPU seconds (every thread), measured alternately on the
lanes and the scalar kernel (best of the repeats of each), so a load from other work slows both alike and the
ratio is the figure to trust; the load average before and after is stated with them.
"""

from __future__ import annotations

from value_groups import fixed, group, pct, sig

#: the speed study of issue 10: the E&J Premier at 2,000 speeds 0.3-1.5 m/s, default settings, record="final"
STUDY_RUNS, STUDY_LO, STUDY_HI = 2000, 0.3, 1.5
#: repeats of each measurement (alternately on the two kernels); a single run is repeated more (it is short)
BATCH_REPEATS, SINGLE_REPEATS = 3, 20


def _cpu_best(fn, kernels: tuple[str, ...], repeats: int) -> tuple[dict[str, float], dict[str, float], dict]:
    """Best process CPU seconds and best wall seconds of ``fn()`` per kernel, measured alternately; the last
    result of each."""
    import time

    from stability.simulate import engine

    cpu = dict.fromkeys(kernels, float("inf"))
    wall = dict.fromkeys(kernels, float("inf"))
    out: dict = {}
    for _ in range(repeats):
        for k in kernels:
            with engine.use_kernel(k):
                c0, w0 = time.process_time(), time.perf_counter()
                out[k] = fn()
                cpu[k] = min(cpu[k], time.process_time() - c0)
                wall[k] = min(wall[k], time.perf_counter() - w0)
    return cpu, wall, out


@group("kernel_speed", "engine.use_kernel('lanes'|'scalar') around simulate_batch(ej-premier, "
       "linspace(0.3, 1.5, 2000), record='final') (3 times) and simulate(ej-premier, 0.75, "
       "RunSpec(stop_on_warnings=False)) (20 times), alternately in one process; time.process_time, "
       "os.getloadavg")
def kernel_speed() -> dict:
    """CPU per run of the 2,000-run speed study and of one 10 s run on both kernels, their ratios, the work (steps
    executed), the load average around the measurement."""
    import os
    import warnings

    import numpy as np

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import StepStabilityWarning, engine, simulate, simulate_batch

    ej = preset("ej-premier")
    speeds = np.linspace(STUDY_LO, STUDY_HI, STUDY_RUNS)
    kernels = ("lanes", "scalar")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", StepStabilityWarning)       # 0.3 m/s is below the 1 ms step's limit
        for k in kernels:                                           # compile or load the caches first
            with engine.use_kernel(k):
                simulate_batch(ej, speeds[:4], run=RunSpec(horizon=0.1), progress=False, record="final")
                simulate(ej, 0.75, run=RunSpec(horizon=0.1))
        load0 = os.getloadavg()[0]
        bcpu, _, bout = _cpu_best(lambda: simulate_batch(ej, speeds, progress=False, record="final"), kernels,
                                  BATCH_REPEATS)
        one = RunSpec(stop_on_warnings=False)
        scpu, swall, _ = _cpu_best(lambda: simulate(ej, 0.75, run=one), kernels, SINGLE_REPEATS)
        load1 = os.getloadavg()[0]
    steps = {k: int(np.rint(np.array([r.t[-1] for r in bout[k]]) / 0.001).sum()) for k in kernels}
    # the same answers: which runs reach 1 rad/s (the searches' level) and when; where the spun-out runs stop
    lv = {k: np.array([np.nan if r.stats.time_to_level[-1] is None else r.stats.time_to_level[-1]
                       for r in bout[k]]) for k in kernels}
    both = ~np.isnan(lv["lanes"]) & ~np.isnan(lv["scalar"])
    one = np.isnan(lv["lanes"]) != np.isnan(lv["scalar"])
    dt_level = float(np.max(np.abs(lv["lanes"][both] - lv["scalar"][both]), initial=0.0))
    last = {k: np.array([r.t[-1] for r in bout[k]]) for k in kernels}
    stopped = {k: np.array([r.stop_time is not None for r in bout[k]]) for k in kernels}
    per = {k: 1e3 * bcpu[k] / STUDY_RUNS for k in kernels}
    return {"lanes_ms": sig(per["lanes"], 2), "scalar_ms": sig(per["scalar"], 2),
            "batch_ratio": fixed(per["scalar"] / per["lanes"], 2),
            "steps": f"{steps['scalar']:,}", "steps_lanes": f"{steps['lanes']:,}",
            "steps_m": fixed(steps["scalar"] / 1e6, 1),
            "step_ns": sig(1e6 * per["scalar"] * STUDY_RUNS / steps["scalar"], 2),
            "lanes_step_ns": sig(1e6 * per["lanes"] * STUDY_RUNS / steps["lanes"], 2),
            "single_lanes_ms": sig(1e3 * scpu["lanes"], 2), "single_scalar_ms": sig(1e3 * scpu["scalar"], 2),
            "single_ratio": fixed(scpu["scalar"] / scpu["lanes"], 2),
            "single_wall_ms": sig(1e3 * swall["scalar"], 2),
            "reach_both": f"{int(both.sum())}", "reach_one": f"{int(one.sum())}",
            "dt_level": "0" if dt_level == 0.0 else f"{dt_level:.0e}",
            "stop_elsewhere": f"{int((both & (last['lanes'] != last['scalar'])).sum())}",
            "stop_one": f"{int((stopped['lanes'] != stopped['scalar']).sum())}",
            "load_before": fixed(load0, 1), "load_after": fixed(load1, 1)}


#: a first scalar simulate with an empty cache, timing numba's two LLVM stages per code library (the final
#: module's optimisation, its machine code) and counting the libraries whose code holds the step ``run_one``
#: (numba internals: ``numba.core.codegen``); prints process CPU, the LLVM part and that count
_LLVM_CHILD = r"""
import time
from numba.core import codegen as cg
llvm, holders = [0.0], set()
def timed(meth):
    f = getattr(cg.CPUCodeLibrary, meth)
    def w(self, *a, **k):
        t0 = time.process_time()
        try:
            return f(self, *a, **k)
        finally:
            llvm[0] += time.process_time() - t0
            if any("run_one" in fn.name and not fn.is_declaration for fn in self._final_module.functions):
                holders.add(id(self))
    setattr(cg.CPUCodeLibrary, meth, w)
timed("_optimize_final_module")
timed("_finalize_final_module")
t0 = time.process_time()
from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import simulate
simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.01))
print(time.process_time() - t0, llvm[0], len(holders))
"""


@group("kernel_first_use", "simulate(ej-premier, 0.75, RunSpec(horizon=0.01)) in a fresh process with an empty "
       "NUMBA_CACHE_DIR, then again with that cache, under engine.use_kernel('scalar'|'lanes') (CPU time of the "
       "child: user + sys); a scalar one timing numba's LLVM stages per code library (numba.core.codegen)")
def kernel_first_use() -> dict:
    """CPU time of a fresh process's first simulation on each kernel with an empty numba cache and with the cache."""
    import os
    import resource
    import subprocess
    import sys
    import tempfile

    from value_groups import ROOT

    def child_cpu(kernel: str, cache: str) -> float:
        code = ("from stability.chair import preset; from stability.simulate import simulate, engine; "
                "from stability.settings.run import RunSpec\n"
                f"with engine.use_kernel({kernel!r}):\n"
                "    simulate(preset('ej-premier'), 0.75, RunSpec(horizon=0.01))")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True, capture_output=True,
                       env={**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)})
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

    out = {"load_before": fixed(os.getloadavg()[0], 1)}
    with tempfile.TemporaryDirectory() as cache:
        llvm = subprocess.run([sys.executable, "-c", _LLVM_CHILD], cwd=ROOT, check=True, capture_output=True,
                              text=True, env={**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)})
    total, llvm_s, copies = (float(x) for x in llvm.stdout.split()[-3:])
    out.update(llvm_pct=pct(llvm_s / total), run_one_copies=f"{int(copies)}")
    for kernel in ("scalar", "lanes"):
        with tempfile.TemporaryDirectory() as cache:
            first = child_cpu(kernel, cache)
            cached = child_cpu(kernel, cache)
        out[f"{kernel}_first_s"], out[f"{kernel}_cached_s"] = sig(first, 2), sig(cached, 2)
    out["load_after"] = fixed(os.getloadavg()[0], 1)
    return out


#: the short run of :func:`single_run_python`, s: almost all of its cost is the Python around the kernel
SHORT_HORIZON = 0.002


@group("single_run_python", "simulate(ej-premier, 0.75, RunSpec(stop_on_warnings=False, horizon=h)) against "
       "baseline.kernel_only on the same run (the compiled kernel alone on arrays packed once), alternately 60 times "
       "in one process for h = 10 s and 2 ms; time.process_time, median")
def single_run_python() -> dict:
    """The Python around one run: simulate's CPU against the compiled kernel's alone on the same run, as a ratio
    (10 s run) and as the difference (10 s and 2 ms runs; a 2 ms run is almost all Python)."""
    import time

    import numpy as np

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import baseline, simulate
    from stability.simulate.options import make_options

    ej = preset("ej-premier")
    out = {"short_horizon_ms": sig(SHORT_HORIZON * 1e3, 1)}
    for label, horizon, inner in (("long", 10.0, 1), ("short", SHORT_HORIZON, 10)):
        run = RunSpec(stop_on_warnings=False, horizon=horizon)
        bare = baseline.kernel_only(ej, 0.75, make_options(run))
        simulate(ej, 0.75, run=run)
        cpu: dict[str, list[float]] = {"simulate": [], "kernel": []}
        for _ in range(60):
            for name, fn in (("simulate", lambda run=run: simulate(ej, 0.75, run=run)), ("kernel", bare)):
                c0 = time.process_time()
                for _ in range(inner):
                    fn()
                cpu[name].append((time.process_time() - c0) / inner)
        med = {k: float(np.median(v)) for k, v in cpu.items()}
        out[f"{label}_ratio"] = fixed(med["simulate"] / med["kernel"], 2)
        out[f"{label}_python_ms"] = sig(max(med["simulate"] - med["kernel"], 0.0) * 1e3, 2)
        out[f"{label}_kernel_ms"] = sig(med["kernel"] * 1e3, 2)
    return out
