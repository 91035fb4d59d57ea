"""The compiled WCHAIR kernel alone on one run: the baseline against which the Python around a run is measured.

Used by ``tests/benchmarks/test_bench_simulate.py`` and the value groups ``single_run_python`` and
``kernel_trig`` of ``docs/simulator.md``.  :func:`polynomial_trig_step` is the scalar step with the lanes
kernel's polynomial trigonometry instead of libm's: a measurement of what libm's calls cost the step (issue 36),
never what a simulation runs.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.simulate import engine
from stability.simulate.controller import SampledController
from stability.simulate.options import Options, n_steps
from stability.simulate.packing import Packed

__all__ = ["kernel_only", "polynomial_trig_step"]


#: the entries :func:`kernel_only` runs
ENTRIES = ("single", "batch", "polynomial_trig")


def kernel_only(chair: Chair, speed: float, opts: Options, entry: str = "single") -> Callable[[], np.ndarray]:
    """The compiled kernel alone on one run packed once: what the Python around a run is measured against.

    Parameters
    ----------
    chair : Chair
    speed : float
        Initial forward speed, m/s.
    opts : Options
        Checked options, ``scheme="wchair"``, no Python ``yaw_moment``.
    entry : {"single", "batch", "polynomial_trig"}
        The kernel's entry: ``"single"`` :func:`~stability.simulate.kernel.run_one` called from Python (how
        :func:`~stability.simulate.engine.run_compiled` runs one run), ``"batch"`` the parallel entry
        :func:`~stability.simulate.kernel.run_batch` on one thread (how one run was run before issue 36),
        ``"polynomial_trig"`` :func:`polynomial_trig_step` called as ``"single"`` (level runs).

    Returns
    -------
    callable
        Runs the kernel on fresh output arrays and returns the recorded columns, shape
        (31, n) (the rows of :data:`stability.simulate.results.COLUMNS` after ``t``).
    """
    if entry not in ENTRIES:
        raise ValueError(f"entry={entry!r} is invalid; valid values: {', '.join(map(repr, ENTRIES))}")
    k = engine._kernel()
    pk = Packed([chair], np.array([float(speed)]), opts, None)
    ctl = SampledController.none().arrays()
    steps = n_steps(opts)
    nrec = (steps - 1) // opts.stride + 1
    levels = np.array(engine.STATS_LEVELS, dtype=float)
    fixed = (0, steps, pk.P, pk.S, pk.TK, pk.TS, pk.TL, pk.LIM, pk.RK, pk.RC, pk.RS, pk.CAM, pk.CHK,
             engine._config(opts, 0, -1), levels, *ctl)
    state0 = engine.initial_state(pk.S, ctl)

    def call() -> np.ndarray:
        rec = np.empty((1, k.NREC_ALL, nrec))
        counts = np.zeros(1, dtype=np.int64)
        args = (*fixed, state0.copy(), rec, np.full((1, 3 + len(levels)), np.nan), np.zeros((1, 3, 3)),
                np.zeros((1, 6)), counts)
        var = k.variant(args[13], args[15])
        with engine.kernel_entry_guard():
            if entry != "batch":
                k.run_single(var, args, polynomial_trig_step() if entry == "polynomial_trig" else None)
            else:
                before = k.get_num_threads()
                k.set_num_threads(1)
                try:
                    k.call_model(k.run_batch, var, *args)
                finally:
                    k.set_num_threads(before)
        return rec[0, :, :int(counts[0])]

    return call


@functools.cache
def polynomial_trig_step() -> Any:
    """:func:`~stability.simulate.kernel.run_one` compiled again with :mod:`~stability.simulate.lanemath`'s
    sine, cosine and slip-angle arctangent (the lanes kernel's polynomials, inlined) in place of libm's calls.

    The same source and helpers, in a namespace whose ``math`` is
    :data:`~stability.simulate.lanemath.LANE_MATH` (the caster angles' and the
    heading's sine and cosine) and whose ``slip_angles`` computes the
    generated slip angle with it; the slope's gravity keeps libm's (level runs
    only).  Its answers differ from the kernel's by the polynomials' rounding
    (:mod:`~stability.simulate.lanemath`'s bounds).  Not cached on disk (a copy
    of a cached function under the same name would share its cache index), so
    each process compiles it once, on first call.

    Returns
    -------
    numba dispatcher
        Called as :func:`~stability.simulate.kernel.run_one` (:func:`~stability.simulate.kernel.call_model`).
    """
    from numba import njit

    from stability.models.forces import generated as forces
    from stability.simulate import kernel
    from stability.simulate.kernel_equations import _NOWRAP, compiled
    from stability.simulate.lanemath import LANE_MATH

    inline = njit(nogil=True, forceinline=True, **_NOWRAP)
    slip = compiled(forces, ("slip_angle",), inline, {"math": LANE_MATH}).slip_angle
    angles = compiled(kernel, ("slip_angles",), inline, {"slip_angle": slip}).slip_angles
    return compiled(kernel, ("run_one",), njit(nogil=True), {"math": LANE_MATH, "slip_angles": angles}).run_one
