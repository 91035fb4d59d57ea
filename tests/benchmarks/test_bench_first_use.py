"""What a first ``simulate`` (and a first layout run) compiles with an empty numba cache: each function's compile time (recorded, not
asserted) and how many times each is compiled (asserted: docs/simulator.md, "Compile time", says every
dispatcher is compiled for one signature except the two it names), on the scalar and layout kernels that only the
package's functions are (none of numba's own), and that a first layout run compiles its own shape's equations only.

Run with ``python -m pytest tests/benchmarks/test_bench_first_use.py --benchmark-enable -s -n 0``.  numba's
compile events (``numba.core.event``, kind ``numba:compile``) give each compile's start and end in the fresh
process; a compile's own time excludes the compiles nested in it.  The first use's CPU is printed twice: for the
whole child process (the interpreter's start, numba's import, the compiles and the run, OpenBLAS on one thread as
the command lines run it: what a user waits for, and what docs/simulator.md's first-use row measures) and from
after numba's import (the child's own clock starts after ``numba.core.event`` is imported).
"""

import json
import os
import resource
import subprocess
import sys

import pytest

#: compiled for more than one signature by design (docs/simulator.md): the thesis accelerations with and without
#: the lagged yaw acceleration
MANY_SIGNATURES = {"stability._generated.full_width.accelerations_thesis"}
#: what a first scalar ``simulate`` (the exact model, level, no controller, one run) does not run, so must not compile
#: (docs/simulator.md, "Compile time"): the batch and step-by-step entry points, the controller, the other models'
#: equations, the plane's gravity
NOT_FIRST = {"stability.simulate.kernel.run_batch", "stability.simulate.kernel.run_serial",
             "stability.simulate.kernel.controlled", "stability.simulate.kernel_controller.controller_output",
             "stability._generated.full_width.accelerations_thesis",
             "stability._generated.full_width.contact_velocities_thesis",
             "stability._generated.slope.accelerations_slope_exact", "stability._generated.slope.gravity_body",
             "stability.simulate.kernel.plane"}

_CHILD = r"""
import json, sys, time
from numba.core import event
t0 = time.process_time()
with event.install_recorder("numba:compile") as rec:
    from stability.settings.run import RunSpec
    if sys.argv[1] == "layout":
        import numpy as np
        from stability.layout.presets import layout_preset
        from stability.simulate.layout import simulate_layout
        from stability.simulate.layout_batch import simulate_layout_batch
        spec = RunSpec(horizon=0.01, stop_on_warnings=False)
        simulate_layout(layout_preset("mid-wheel-drive"), 1.0, spec)
        simulate_layout_batch(layout_preset("mid-wheel-drive"), [1.0, -1.0], spec,
                              yaw_moment=lambda t, s: np.zeros(len(s.run)))
    elif sys.argv[1] == "wchair":
        sys.path.insert(0, sys.argv[2])
        import kernel_warmup
        kernel_warmup.warm("wchair")
    else:
        from stability.chair import preset
        from stability.simulate import engine, simulate
        with engine.use_kernel(sys.argv[1]):
            simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.01))
cpu = time.process_time() - t0
stack, own, count = [], {}, {}
for ts, ev in rec.buffer:
    d = ev.data.get("dispatcher")
    f = getattr(d, "py_func", None)
    name = f"{f.__module__}.{f.__qualname__}#{id(d)}" if f else "?"
    if ev.is_start:
        stack.append([name, ts, 0.0])
        continue
    n, t, child = stack.pop()
    own[n] = own.get(n, 0.0) + (ts - t) - child
    count[n] = count.get(n, 0) + 1
    if stack:
        stack[-1][2] += ts - t
print(json.dumps({"cpu": cpu, "own": own, "count": count}))
"""


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


#: ``layout``: the layout kernel's one run and its stepped batch with a Python hook (tests/kernel_warmup.py's layout
#: group) share one compile of every function: one run is a batch of one (no second entry point that optimised the
#: whole step again), and the solves' sizes and the warning kinds are passed as int64, not as literals that numba
#: compiled once per value (34 -> 27 compiles); a run's steps are written in ``step_layouts``' loop, not in a jitted
#: ``advance`` compiled to machine code on its own and again inside it, and each pin law and load rule solves at one
#: call site (65 -> 62 compiles of this test's count, 15.9 -> 11.8 s CPU measured once each).  Issue 36 again
#: (62 -> 31 compiles, every one the package's): ``step_layouts`` calls the run's shape's generated equations and
#: contact velocities at their addresses, so a first run compiles its own shape's two (``LAYOUT_FIRST_SHAPES``)
#: instead of all four shapes' eight and their run-time ``equations`` / ``contact_velocities`` branches; the step
#: allocates nothing (its scratch comes from Python), so numba compiles none of its own functions for it
#: (``min``, ``max``, ``int()`` written as selects and casts, as in the scalar kernel)
#: ``wchair``: tests/kernel_warmup.py's wchair group (every variant of the scalar kernel the default tests use, one
#: run, a batch, a Python hook; the adaptive scheme is in the layout group): the batch and step-by-step entries call the variant's
#: ``run_one`` at its address, so each is compiled once for all variants, not once per model (91 -> 81 compiles),
#: and ``run_one`` once per variant (thesis, exact, each with and without a controller, the slope)
#: the generated functions a first mid-wheel-drive run (two fixed wheels, four casters) compiles: its shape's only
LAYOUT_FIRST_SHAPES = {"stability._generated.layout_nonlinear.equations_2w4c",
                       "stability._generated.layout_nonlinear.contact_velocities_2w4c"}
WCHAIR_ONCE = {"stability.simulate.kernel.run_batch": 1, "stability.simulate.kernel.run_serial": 1,
               "stability.simulate.kernel.run_one": 5}


@pytest.mark.parametrize("kernel", ["scalar", "lanes", "layout", "wchair"])
def test_bench_what_first_use_compiles(bench, tmp_path, kernel):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([sys.executable, "-c", _CHILD, kernel, os.path.dirname(os.path.dirname(__file__))],
                         check=True, capture_output=True, text=True,
                         env=dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"), OPENBLAS_NUM_THREADS="1"))
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    # the whole process (the interpreter's start, numba's import, the compile, the run): what a user waits for, and
    # what docs/simulator.md's first-use row (value group kernel_first_use) measures
    process_cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    data = json.loads(out.stdout.strip().splitlines()[-1])
    bench.pedantic(lambda: None, rounds=1)
    # per dispatcher (a function compiled again in another namespace, as the lanes kernel's copies, is another one)
    own, count = data["own"], data["count"]
    ours = {n: c for n, c in count.items() if n.startswith("stability.")}
    assert ours, "nothing of the package was compiled: the cache was not empty"
    many = {n: c for n, c in ours.items() if c > 1 and n.split("#")[0] not in MANY_SIGNATURES}
    bench.extra_info.update(cpu_s=data["cpu"], process_cpu_s=process_cpu, compiles=sum(count.values()), own_s=own,
                            many=many)
    top = sorted(own.items(), key=lambda kv: -kv[1])[:12]
    print(f"\n{kernel}: first use {process_cpu:.1f} s CPU for the whole process ({data['cpu']:.1f} s after numba's "
          f"import), {sum(count.values())} compiles "
          f"({len(ours)} of the package's dispatchers); largest own compile times (wall, s):")
    for n, s in top:
        print(f"  {s:6.2f}  {n.split('#')[0]} (x{count[n]})")
    if kernel == "wchair":      # a variant per model and controller by design (docs/simulator.md, "Compile time")
        counts = {n.split("#")[0]: c for n, c in ours.items()}
        assert {n: counts.get(n) for n in WCHAIR_ONCE} == WCHAIR_ONCE
        return
    assert not many, f"compiled for more than one signature: {many}"
    if kernel == "layout":
        compiled = {n.split("#")[0] for n in ours}
        assert {n for n in compiled if ".layout_nonlinear." in n} == LAYOUT_FIRST_SHAPES
    if kernel in ("scalar", "layout"):
        # nothing of numba's own (its min, max and int() are functions compiled on a first use, each with a
        # C-callable wrapper: the steps write them as selects and casts, docs/simulator.md "Compile time")
        theirs = sorted(n.split("#")[0] for n in count if not n.startswith("stability."))
        assert not theirs, f"numba's own functions compiled for the step: {theirs}"
    if kernel == "scalar":
        compiled = {n.split("#")[0] for n in ours}
        assert "stability.simulate.kernel.run_one" in compiled
        assert not compiled & NOT_FIRST, f"compiled though the first run does not run it: {compiled & NOT_FIRST}"
