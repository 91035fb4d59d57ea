"""The compiled WCHAIR kernel alone on one run: the baseline against which the Python around a run is measured.

Used by ``tests/benchmarks/test_bench_simulate.py`` and the value group ``single_run_python`` of
``docs/simulator.md``.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from stability.chair import Chair
from stability.simulate import engine
from stability.simulate.controller import SampledController
from stability.simulate.options import Options, n_steps
from stability.simulate.packing import Packed

__all__ = ["kernel_only"]


def kernel_only(chair: Chair, speed: float, opts: Options, entry: str = "single") -> Callable[[], np.ndarray]:
    """The compiled kernel alone on one run packed once: what the Python around a run is measured against.

    Parameters
    ----------
    chair : Chair
    speed : float
        Initial forward speed, m/s.
    opts : Options
        Checked options, ``scheme="wchair"``, no Python ``yaw_moment``.
    entry : {"single", "batch"}
        The kernel's entry: ``"single"`` :func:`~stability.simulate.kernel.run_one` called from Python (how
        :func:`~stability.simulate.engine.run_compiled` runs one run), ``"batch"`` the parallel entry
        :func:`~stability.simulate.kernel.run_batch` on one thread (how one run was run before issue 36).

    Returns
    -------
    callable
        Runs the kernel on fresh output arrays and returns the recorded columns, shape
        (31, n) (the rows of :data:`stability.simulate.results.COLUMNS` after ``t``).
    """
    if entry not in ("single", "batch"):
        raise ValueError(f"entry={entry!r} is invalid; valid values: 'single', 'batch'")
    k = engine._kernel()
    pk = Packed([chair], np.array([float(speed)]), opts, None)
    ctl = SampledController.none().arrays()
    steps = n_steps(opts)
    nrec = (steps - 1) // opts.stride + 1
    levels = np.array(engine.STATS_LEVELS, dtype=float)
    fixed = (0, steps, pk.P, pk.S, pk.TK, pk.TS, pk.TL, pk.LIM, pk.RK, pk.RC, pk.RS, pk.CAM, pk.CHK,
             engine._config(opts, 0, -1), levels, *ctl)
    state0 = engine.initial_state(pk.S, ctl[3].shape[0])

    def call() -> np.ndarray:
        rec = np.empty((1, k.NREC_ALL, nrec))
        counts = np.zeros(1, dtype=np.int64)
        args = (*fixed, state0.copy(), rec, np.full((1, 3 + len(levels)), np.nan), np.zeros((1, 3, 3)),
                np.zeros((1, 6)), counts)
        var = k.variant(args[13], args[15])
        with engine.kernel_entry_guard():
            if entry == "single":
                k.run_single(var, args)
            else:
                before = k.get_num_threads()
                k.set_num_threads(1)
                try:
                    k.call_model(k.run_batch, var, *args)
                finally:
                    k.set_num_threads(before)
        return rec[0, :, :int(counts[0])]

    return call
