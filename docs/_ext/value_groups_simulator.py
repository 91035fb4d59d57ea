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
#: issue 36's targets: CPU per run of the speed study (ms), one 10 s run (ms), a first use with an empty cache (s)
TARGET_BATCH_MS, TARGET_SINGLE_MS, TARGET_FIRST_S = 0.4, 1.0, 5.0


def verdict(value: float, target: float) -> str:
    """``"met"`` when ``value`` is at most ``target``, else ``"not met"``: the docs' words for a measured target."""
    return "met" if value <= target else "not met"


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
       "linspace(0.3, 1.5, 2000), record='final') (3 times; on the lanes kernel also in a seeded random order) and "
       "simulate(ej-premier, 0.75, "
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
        # the same runs in a seeded random order, as a sweep's rows come: a block's runs stop at more different
        # times, so its stopped lanes matter more (lanes_kernel.COMPACT_AFTER)
        shuffled = np.random.default_rng(36).permutation(speeds)
        rcpu, _, _ = _cpu_best(lambda: simulate_batch(ej, shuffled, progress=False, record="final"), ("lanes",),
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
            "lanes_shuffled_ms": sig(1e3 * rcpu["lanes"] / STUDY_RUNS, 2),
            "batch_ratio": fixed(per["scalar"] / per["lanes"], 2),
            "steps": f"{steps['scalar']:,}", "steps_lanes": f"{steps['lanes']:,}",
            "steps_m": fixed(steps["scalar"] / 1e6, 1),
            "step_ns": sig(1e6 * per["scalar"] * STUDY_RUNS / steps["scalar"], 2),
            "lanes_step_ns": sig(1e6 * per["lanes"] * STUDY_RUNS / steps["lanes"], 2),
            "single_lanes_ms": sig(1e3 * scpu["lanes"], 2), "single_scalar_ms": sig(1e3 * scpu["scalar"], 2),
            "single_ratio": fixed(scpu["scalar"] / scpu["lanes"], 2),
            "single_wall_ms": sig(1e3 * swall["scalar"], 2),
            "batch_verdict": verdict(min(per.values()), TARGET_BATCH_MS),
            "single_verdict": verdict(1e3 * min(scpu.values()), TARGET_SINGLE_MS),
            "reach_both": f"{int(both.sum())}", "reach_one": f"{int(one.sum())}",
            "dt_level": "0" if dt_level == 0.0 else f"{dt_level:.0e}",
            "stop_elsewhere": f"{int((both & (last['lanes'] != last['scalar'])).sum())}",
            "stop_one": f"{int((stopped['lanes'] != stopped['scalar']).sum())}",
            "load_before": fixed(load0, 1), "load_after": fixed(load1, 1)}


@group("kernel_trig", "baseline.kernel_only(ej-premier, 0.75, make_options(RunSpec(stop_on_warnings=False))) with "
       "entry='single' (libm's sincos and atan2) and entry='polynomial_trig' (lanemath's polynomials), alternately "
       "30 times in one process; time.process_time, best; the recorded columns compared step by step against "
       "lanemath's rounding bound")
def kernel_trig() -> dict:
    """The scalar step with libm's trigonometry against a copy with the lanes kernel's polynomials: CPU of one 10 s
    run on each, the ratio, and the time at which the two runs first differ by more than the rounding bound."""
    import time

    import numpy as np

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import baseline, lanemath
    from stability.simulate.options import make_options

    opts = make_options(RunSpec(stop_on_warnings=False))
    fns = {e: baseline.kernel_only(preset("ej-premier"), 0.75, opts, entry=e) for e in ("single", "polynomial_trig")}
    out = {e: fn() for e, fn in fns.items()}
    best = dict.fromkeys(fns, float("inf"))
    for _ in range(30):
        for e, fn in fns.items():
            c0 = time.process_time()
            fn()
            best[e] = min(best[e], time.process_time() - c0)
    libm, poly = out["single"], out["polynomial_trig"]
    # the linear rounding bound of tests/test_lanes_kernel.py: n (SIN_COS_ULP + ATAN2_ULP + 2) eps max|column|
    per_step = (lanemath.SIN_COS_ULP + lanemath.ATAN2_ULP + 2.0) * np.finfo(float).eps
    n = np.arange(libm.shape[1])
    bound = n * per_step * np.maximum(np.fmax.accumulate(np.abs(libm), axis=1), 1e-300)
    over = np.any(np.abs(libm - poly) > bound, axis=0)
    first = int(np.argmax(over)) if over.any() else None
    return {"libm_ms": sig(best["single"] * 1e3, 2), "poly_ms": sig(best["polynomial_trig"] * 1e3, 2),
            "ratio": fixed(best["single"] / best["polynomial_trig"], 2),
            "saved_pct": pct(1.0 - best["polynomial_trig"] / best["single"]),
            "departs_s": "never" if first is None else sig(first * opts.dt, 2),
            "yaw_rate_diff": f"{float(np.nanmax(np.abs(libm[3] - poly[3]))):.0e}"}


#: a first scalar simulate with an empty cache, timing numba's two LLVM stages per code library (the final
#: module's optimisation, its machine code), counting the libraries whose code holds the step ``run_one``
#: (numba internals: ``numba.core.codegen``) and the package's functions compiled (numba's compile events); prints
#: process CPU, the LLVM part and those counts
_LLVM_CHILD = r"""
import time
from numba.core import codegen as cg
llvm, holders = [0.0, 0.0], set()
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
            else:
                llvm[1] += time.process_time() - t0
    setattr(cg.CPUCodeLibrary, meth, w)
timed("_optimize_final_module")
timed("_finalize_final_module")
t0 = time.process_time()
from numba.core import event
with event.install_recorder("numba:compile") as rec:
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.01))
ours = [ev for _, ev in rec.buffer if ev.is_start
        and getattr(getattr(ev.data.get("dispatcher"), "py_func", None), "__module__", "").startswith("stability.")]
print(time.process_time() - t0, llvm[0], llvm[1], len(holders), len(ours))
"""


#: the first-use children's OpenBLAS as a command line runs it (stability.runtime.blas: one thread); a script that
#: imports the library keeps OpenBLAS's own threads, whose busy-waiting adds CPU time, not wall time
_ONE_BLAS_THREAD = {"OPENBLAS_NUM_THREADS": "1"}


@group("kernel_first_use", "simulate(ej-premier, 0.75, RunSpec(horizon=0.01)) in a fresh process with an empty "
       "NUMBA_CACHE_DIR, then again with that cache, under engine.use_kernel('scalar'|'lanes'), and "
       "simulate_layout(layout_preset('mid-wheel-drive'), 1.0, RunSpec(horizon=0.01, stop_on_warnings=False)) "
       "likewise (CPU time of the child: user + sys; OpenBLAS on one thread, as the command lines run it); a "
       "scalar one timing numba's LLVM stages per code library (numba.core.codegen) and counting the package's "
       "compiles (numba.core.event)")
def kernel_first_use() -> dict:
    """CPU time of a fresh process's first simulation on each kernel (the WCHAIR kernel's scalar and lanes forms,
    the layout kernel) with an empty numba cache and with the cache."""
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
        if kernel == "layout":
            code = ("from stability.layout.presets import layout_preset; from stability.settings.run import RunSpec; "
                    "from stability.simulate.layout import simulate_layout\n"
                    "simulate_layout(layout_preset('mid-wheel-drive'), 1.0, "
                    "RunSpec(horizon=0.01, stop_on_warnings=False))")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, "-c", code], cwd=ROOT, check=True, capture_output=True,
                       env={**os.environ, **_ONE_BLAS_THREAD, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)})
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

    out = {"load_before": fixed(os.getloadavg()[0], 1)}
    with tempfile.TemporaryDirectory() as cache:
        llvm = subprocess.run([sys.executable, "-c", _LLVM_CHILD], cwd=ROOT, check=True, capture_output=True,
                              text=True, env={**os.environ, **_ONE_BLAS_THREAD, "NUMBA_CACHE_DIR": cache,
                                              "PYTHONPATH": str(ROOT)})
    total, llvm_s, helpers_s, copies, compiles = (float(x) for x in llvm.stdout.split()[-5:])
    out.update(llvm_pct=pct(llvm_s / total), llvm_helpers_pct=pct(helpers_s / total), run_one_copies=f"{int(copies)}",
               compiles=f"{int(compiles)}")
    for kernel in ("scalar", "lanes"):
        with tempfile.TemporaryDirectory() as cache:
            first = child_cpu(kernel, cache)
            cached = child_cpu(kernel, cache)
        out[f"{kernel}_first_s"], out[f"{kernel}_cached_s"] = sig(first, 2), sig(cached, 2)
        out[f"{kernel}_first_verdict"] = verdict(first, TARGET_FIRST_S)
    with tempfile.TemporaryDirectory() as cache:      # the layout kernel: a mid-wheel-drive base's first run
        first = child_cpu("layout", cache)
        cached = child_cpu("layout", cache)
    out["layout_first_s"], out["layout_cached_s"] = sig(first, 2), sig(cached, 2)
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


def _test_module(name: str):
    """A module of ``tests/`` (its cases and helpers are the inputs of a check this page quotes), imported by path
    with ``tests/`` on the path for its helpers (``numerics``)."""
    import importlib.util
    import sys

    from value_groups import ROOT

    if str(ROOT / "tests") not in sys.path:
        sys.path.insert(0, str(ROOT / "tests"))
    spec = importlib.util.spec_from_file_location(f"_docs_{name}", ROOT / "tests" / f"{name}.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


#: docs/simulator.md's lanemath check: random inputs per range, below this size of angle "small" (rad), the seed
LANEMATH_N, LANEMATH_SMALL_RAD, LANEMATH_SEED = 400_000, 100.0, 7
#: CPython's ``r**2`` against ``r*r``: inputs drawn uniformly from +-POW_SPAN, POW_N of them, seed 0
POW_N, POW_SPAN = 200_000, 10.0


@group("simulator_lanemath", "stability.simulate.lanemath.sin_cos / atan2_pos (numba loops as "
       "tests/test_lanemath.py) against numpy on 400,000 uniform random inputs per range (seeds 7 and 11); "
       "CPython x**2 against x*x on 200,000 uniform inputs in +-10")
def simulator_lanemath() -> dict:
    """Largest observed ulp differences of the lanes kernel's polynomials from numpy (glibc), and how often
    CPython's ``x**2`` differs from ``x*x``."""
    import math
    import random

    import numpy as np

    from stability.simulate import lanemath as lm

    t = _test_module("test_lanemath")
    worst_small = worst_all = 0.0
    for span in (math.pi, 4 * math.pi, 1e3, lm.REDUCTION_LIMIT):
        x = np.random.default_rng(LANEMATH_SEED).uniform(-span, span, LANEMATH_N)
        s, c = t._sin_cos(x)
        for got, ref in ((s, np.sin(x)), (c, np.cos(x))):
            u = t._ulps(got, ref)
            worst_all = max(worst_all, float(u.max()))
            small = np.abs(x) < LANEMATH_SMALL_RAD
            worst_small = max(worst_small, float(u[small].max(initial=0.0)))
    worst_atan = 0.0
    rng = np.random.default_rng(11)
    for scale in (1e-6, 1e-2, 1.0, 1e2):
        y = rng.standard_normal(LANEMATH_N) * scale * np.exp(rng.uniform(-14, 14, LANEMATH_N))
        x = np.abs(rng.standard_normal(LANEMATH_N)) * scale * np.exp(rng.uniform(-14, 14, LANEMATH_N))
        worst_atan = max(worst_atan, float(t._ulps(t._atan2(y, x), np.arctan2(y, x)).max()))
    r = random.Random(0)
    xs = [r.uniform(-POW_SPAN, POW_SPAN) for _ in range(POW_N)]
    differ = sum(1 for v in xs if v ** 2 != v * v) / POW_N
    return {"ulp_small": f"{math.ceil(worst_small - 1e-9):d}", "ulp_all": f"{math.ceil(worst_all - 1e-9):d}",
            "ulp_atan": f"{math.ceil(worst_atan - 1e-9):d}", "small_rad": f"{LANEMATH_SMALL_RAD:g}",
            "n": f"{LANEMATH_N:,}", "pow_pct": sig(100 * differ, 1)}


@group("simulator_lanes_bound", "tests/test_lanes_kernel.py's 8 cases over 3 s, lanes against scalar "
       "(simulate_batch under engine.use_kernel), largest |difference| / bound over the recorded quantities; "
       "the E&J Premier on a 4 deg cross slope, 1 N s push at 0.75 m/s, 0.1 s")
def simulator_lanes_bound() -> dict:
    """The largest observed fraction of the rounding bound per case (the range over the cases) and on a slope."""
    import dataclasses

    import numpy as np

    from stability.settings.run import RunSpec
    from stability.simulate import engine

    t = _test_module("test_lanes_kernel")

    def worst(chair, speed, run) -> float:
        with engine.use_kernel("lanes"):
            lanes, scalar = t._both(chair, speed, run)
        n, out = len(lanes.t), 0.0
        for name in t.FIELDS:
            a, b = np.asarray(getattr(lanes, name), float), np.asarray(getattr(scalar, name), float)
            if a.ndim == 1:
                a, b = a[:, None], b[:, None]
            for j in range(a.shape[1]):
                out = max(out, float(np.nanmax(np.abs(a[:, j] - b[:, j]))) / t._bound(n, b[:, j]))
        return out

    fr = [worst(c, u, dataclasses.replace(run, horizon=min(run.horizon, 3.0))) for c, u, run in t.CASES.values()]
    slope = worst(t.EJ, 0.75, RunSpec(horizon=0.1, cross_slope_deg=4.0, push_force=10.0, push_duration=0.1))
    return {"cases": f"{len(fr)}", "most": f"1/{sig(1 / max(fr), 2)}", "least": f"1/{sig(1 / min(fr), 2)}",
            "slope": sig(slope, 2)}


def _kinetic_impulse(chair, speed: float, dt: float | None):
    from stability.settings.run import RunSpec
    from stability.study import critical_impulses

    run = RunSpec(scheme="adaptive") if dt is None else RunSpec(dt=dt, friction_law="kinetic")
    return critical_impulses(chair, [speed], run)[0]


@group("simulator_kinetic", "stability.linear.eigenvalues_vs_speed (largest |lambda| x 1 ms); "
       "stability.study.critical_impulses with RunSpec(dt=DT, friction_law='kinetic') and RunSpec(scheme='adaptive')")
def simulator_kinetic() -> dict:
    """Program WCHAIR's kinetic law against the step: |lambda| dt of the fastest mode, the E&J Premier's error at
    1.0 m/s, the thesis's cases' spread, power-fwd at 1.5 m/s at four steps."""
    import numpy as np
    from value_groups_pages import _preset

    from stability.linear import eigenvalues_vs_speed
    from stability.settings.run import RunSpec
    from stability.study import equal_instability_speeds

    ej, pf, rv = _preset("ej-premier"), _preset("power-fwd"), _preset("revised")

    def lam_dt(chair, speed):
        return float(np.abs(eigenvalues_vs_speed(chair, [speed], track=False)).max()) * 1e-3

    steps = (1e-3, 5e-4, 2.5e-4)
    ej1 = {dt: _kinetic_impulse(ej, 1.0, dt).impulse_Ns for dt in (1e-3, None)}
    ej075 = [_kinetic_impulse(ej, 0.75, dt).impulse_Ns for dt in steps]
    rv_eis = [equal_instability_speeds([rv], RunSpec(dt=dt, friction_law="kinetic", model="thesis"),
                                       progress=False)[0].speed for dt in steps]
    spread = max(max(v) / min(v) - 1.0 for v in (ej075, rv_eis))
    pf15 = {}
    for dt in (1e-3, 5e-4, 2.5e-4, 1.25e-4):
        r = _kinetic_impulse(pf, 1.5, dt)
        pf15[dt] = f"below {r.bound_Ns:.0e}" if r.status == "below" else f"{r.impulse_Ns:.2g}"
    return {"pf_lam_dt": fixed(lam_dt(pf, 1.5), 2), "ej_lam_dt": fixed(lam_dt(ej, 1.0), 2),
            "ej_1_off_pct": f"{100 * abs(ej1[1e-3] / ej1[None] - 1):.0f}", "thesis_spread_pct": sig(100 * spread, 1),
            "ej_075": sig(ej075[0], 3), "pf_1": pf15[1e-3], "pf_05": pf15[5e-4], "pf_025": pf15[2.5e-4],
            "pf_0125": pf15[1.25e-4]}


@group("simulator_stick_slip", "tests/test_stick_slip.py's convergence case: simulate(ej-premier, 0.75, "
       "RunSpec(push_force=20, push_duration=0.1, horizon=3, sample=0.01, dt=DT, friction_law=LAW)) against "
       "RunSpec(scheme='adaptive'); CPU time of simulate(ej-premier, 0.75, RunSpec(stop_on_warnings=False)) with "
       "each law (best of 10, time.process_time), measured on the build machine")
def simulator_stick_slip() -> dict:
    """The stick-slip law's distance from the event-located solution at three steps, the kinetic law's at 1 ms,
    and the CPU time of a 10 s run with each law."""
    import time

    import numpy as np

    from stability.settings.run import RunSpec
    from stability.simulate import simulate

    t = _test_module("test_stick_slip")
    chair = t.preset("ej-premier")
    ref = np.asarray(simulate(chair, 0.75, RunSpec(scheme="adaptive", **t.PUSH, horizon=3.0, sample=0.01)).yaw_rate)
    err = [float(np.abs(t._yaw(chair, 0.75, dt=dt, friction_law="stick-slip") - ref).max())
           for dt in (1e-3, 5e-4, 2.5e-4)]
    kinetic = float(np.abs(t._yaw(chair, 0.75) - ref).max())
    peak = float(np.abs(ref).max())

    def cpu(law: str) -> float:
        run = RunSpec(stop_on_warnings=False, friction_law=law)
        simulate(chair, 0.75, run=run)
        best = float("inf")
        for _ in range(10):
            c0 = time.process_time()
            simulate(chair, 0.75, run=run)
            best = min(best, time.process_time() - c0)
        return best

    return {"err_1": f"{err[0]:.1e}", "err_05": f"{err[1]:.1e}", "err_025": f"{err[2]:.1e}",
            "kinetic": f"{kinetic:.1e}", "kinetic_pct": f"{100 * kinetic / peak:.0f}",
            "time_ratio": fixed(cpu("stick-slip") / cpu("kinetic"), 1)}


@group("single_run_entries", "baseline.kernel_only(ej-premier, 0.75, RunSpec(stop_on_warnings=False), entry='single'"
       "|'batch'): run_one called from Python against run_batch on one thread, alternately 30 times in one process; "
       "time.process_time, best")
def single_run_entries() -> dict:
    """One 10 s run's kernel CPU through the entry for one run and through the parallel entry, and their ratio."""
    import time

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import baseline
    from stability.simulate.options import make_options

    opts = make_options(RunSpec(stop_on_warnings=False))
    fns = {name: baseline.kernel_only(preset("ej-premier"), 0.75, opts, entry=name) for name in ("single", "batch")}
    best = dict.fromkeys(fns, float("inf"))
    for fn in fns.values():
        fn()
    for _ in range(30):
        for name, fn in fns.items():
            c0 = time.process_time()
            fn()
            best[name] = min(best[name], time.process_time() - c0)
    return {"single_ms": sig(best["single"] * 1e3, 2), "batch_ms": sig(best["batch"] * 1e3, 2),
            "ratio": fixed(best["batch"] / best["single"], 2)}
