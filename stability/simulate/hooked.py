"""The WCHAIR kernel stepped one step at a time with a Python yaw-moment input sampled in between.

:func:`hooked_steps` is the loop of :func:`stability.simulate.engine.run_compiled` for a Python
``opts.yaw_moment(t, state)``: the hook is called before every step with the state of the runs still going, its
moment is held over the step, and the kernel advances every run one step.  Per step only what changes is done (the
per-step Python cost is most of such a run's: the kernel's step of one run takes about a microsecond).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import numpy as np

from stability.simulate.going import GoingRuns
from stability.simulate.options import Options, n_steps
from stability.simulate.results import ChairState

__all__ = ["hooked_steps"]


def hooked_steps(k: Any, opts: Options, args: tuple, state: np.ndarray, status: np.ndarray, var: tuple[int, int],
                 batch: bool, lanes: Callable[[int], None] | None = None) -> None:
    """Step the runs of ``args`` one step at a time on this thread, ``opts.yaw_moment`` sampled before each step.

    The runs still going are found again only when the kernel stopped one (the count of set stop codes, which the
    kernel sets once per run, changed); while every run goes the hook's arrays are one copy of the state's first
    columns and its moments are stored by a slice, broadcast only when their shape differs; the scalar kernel's
    specialisation is found by :func:`kernel.call_model` at the first step and called directly after it
    (:func:`_serial_entry`).  The kernel's arithmetic and the hook's inputs are those of stepping through
    ``call_model`` with the runs found again at every step.

    Parameters
    ----------
    k : module
        :mod:`stability.simulate.kernel`.
    opts : Options
        Checked options with a Python ``yaw_moment`` (``opts.dt``: the step, s).
    args : tuple
        :func:`kernel.run_serial`'s arguments after the variant and the steps (the engine's packed arrays,
        configuration with the external-moment flag set, controller arrays, ``state`` ... ``status``, counts).
    state : ndarray, shape (runs, columns)
        The kernel's per-run state in ``args``: columns 0-9 the ten states (m, rad, m/s, rad/s), ``ST_MZ`` the
        held yaw moment (N m), written here.
    status : ndarray, shape (runs, 6)
        The kernel's per-run status in ``args`` (``status[:, 0]``: why a run stopped, ``status[:, 2]``: a
        refused tire input; 0: still going).
    var : tuple of int
        :func:`kernel.variant` of the runs.
    batch : bool
        The hook sees arrays over the runs still going (``state.run``: their indices, read-only) or, for one
        run, floats (``state.run`` 0).
    lanes : callable, optional
        ``lanes(step)`` steps every run one step on the lanes kernel; None: the scalar kernel.
    """
    hook, dt = opts.yaw_moment, opts.dt
    if hook is None:
        raise ValueError("yaw_moment=None is invalid; valid: a callable yaw_moment(t, state) for a hooked run")
    runs = GoingRuns(status[:, 0:3:2])  # a run's stop codes: the warning rule or a level; a refused tire input
    step_runs: Callable[..., Any] | None = None
    for step in range(n_steps(opts)):
        if not runs.update():
            break
        going = runs.index
        if batch:
            st = (state[:, :10] if runs.everyone else state[going, :10]).T.copy()  # each state a row of a fresh copy
            runs.store(state, k.ST_MZ, hook(step * dt, ChairState._make([*st, going])))
        else:
            state[0, k.ST_MZ] = float(hook(step * dt, ChairState._make([*state[going[0], :10].tolist(), 0])))
        if lanes is not None:
            lanes(step)
        elif step_runs is None:
            k.call_model(k.run_serial, var, step, step + 1, *args)
            step_runs = _serial_entry(k, var, (step, step + 1, *args))
        else:
            step_runs(step, step + 1, *args)


def _serial_entry(k: Any, var: tuple[int, int], args: tuple) -> Callable[..., Any]:
    """:func:`kernel.run_serial`'s specialisation that ``kernel.call_model(run_serial, var, *args)`` has just
    called, from its memo of compiled entry points by its own key (the variant and the arguments' numba type
    fingerprints), to call with arguments of the same types without finding it again at every step (~4 us of a
    step); ``call_model`` itself when the memo does not hold it."""
    from numba._dispatcher import compute_fingerprint

    fn = getattr(k, "_ENTRIES", {}).get((k.run_serial, var, tuple(map(compute_fingerprint, args))))
    return fn if fn is not None else functools.partial(k.call_model, k.run_serial, var)
