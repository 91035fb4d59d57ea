"""Runs of one wheel layout stepped together with a Python yaw moment on the body (the firmware's fault runs).

:func:`simulate_layout_batch` is the thesis engine's :func:`stability.simulate.simulate_batch` with a ``yaw_moment``
input, for a layout: the compiled layout kernel (:mod:`stability.simulate.layout_kernel`) advances every run one
step from its saved state (:func:`~stability.simulate.layout_kernel.step_layouts`, the arithmetic of
:func:`stability.simulate.layout.simulate_layout`, bit for bit) and the hook is called in between.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from stability.layout.model import Layout
from stability.settings.run import RunSpec
from stability.simulate.first_use import load_kernel
from stability.simulate.going import GoingRuns
from stability.simulate.layout import (
    LayoutRun,
    _caster_angles,
    _check_run,
    _controller_arrays,
    _kernel_inputs,
    _layout_run,
)

__all__ = ["LayoutState", "simulate_layout_batch"]


class LayoutState(NamedTuple):
    """State handed to :func:`simulate_layout_batch`'s ``yaw_moment(t, state)``: arrays over the runs still going
    (the thesis engine's :class:`~stability.simulate.results.ChairState` for a layout)."""

    x: Any            #: x of the c.g. along the initial heading (m)
    y: Any            #: y of the c.g. to its right (m)
    heading: Any      #: yaw angle (rad, clockwise from above)
    u: Any            #: forward velocity (m/s, body axes; negative: reverse)
    v: Any            #: lateral velocity (m/s, body axes, to the right)
    yaw_rate: Any     #: yaw rate (rad/s)
    delta: Any        #: caster swivel angles (rad), shape (casters, runs)
    delta_rate: Any   #: their rates (rad/s)
    run: Any          #: index into the batch of each run still going


def _compiled(kernel: Any, args: tuple) -> Callable[..., Any]:
    """The machine code ``kernel`` (a numba dispatcher, already called with ``args``) runs for ``args``' types, to
    call directly with arguments of the same types: the dispatcher's own choice without its per-call resolution of
    the 33 argument types (~6 us a step, most of a batch step's Python overhead); the dispatcher itself when numba
    does not expose it."""
    import numba

    try:
        return kernel.get_overload(tuple(numba.typeof(a) for a in args))
    except (AttributeError, KeyError, TypeError, ValueError):
        return kernel


def simulate_layout_batch(layout: Layout, speeds: Sequence[float], run: RunSpec | None = None, *,
                          yaw_moment: Callable[[float, LayoutState], Any],
                          caster_angles_deg: Sequence[Sequence[float]] | None = None,
                          motor_lag_s: float = 0.0) -> list[LayoutRun]:
    """Runs of one layout at several signed speeds, stepped together with a Python yaw moment on the body.

    The thesis engine's :func:`stability.simulate.simulate_batch` with a ``yaw_moment`` input, for a layout: every
    step, ``yaw_moment(t, state)`` (:class:`LayoutState` of the runs still going) returns the yaw moment of each
    (N m), which acts over the step through ``motor_lag_s``; then the compiled kernel advances every run one step
    (:func:`stability.simulate.layout_kernel.step_layouts`, the arithmetic of :func:`simulate_layout`).  Rows
    are recorded as a batch's, every 0.01 s unless ``run.sample``.  A run that leaves the finite numbers ends
    there (``ended == "non-finite"``) instead of raising.

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        Initial forward speed of each run, m/s (negative: reverse; 0.01 <= |speed| <= 20).
    run : RunSpec, optional
        As :func:`simulate_layout`'s (one for all runs).
    yaw_moment : callable
        ``yaw_moment(t, state) -> array`` over ``state.run``, N m.
    caster_angles_deg : sequence of sequence of float, optional
        Each run's initial swivel angles (deg; default :func:`simulate_layout`'s).
    motor_lag_s : float
        s (>= 0).

    Returns
    -------
    list of LayoutRun
        In the order of ``speeds``.
    """
    if not callable(yaw_moment):
        raise TypeError(f"yaw_moment={yaw_moment!r} is invalid; expected a callable yaw_moment(t, state)")
    U = list(speeds)
    if not U:
        raise ValueError("speeds=[] is invalid; valid: at least one speed")
    if caster_angles_deg is not None and len(caster_angles_deg) != len(U):
        raise ValueError(f"caster_angles_deg has {len(caster_angles_deg)} rows, which is invalid; valid: one per "
                         f"speed ({len(U)})")
    checked = [_check_run(layout, u, run) for u in U]
    deltas = [_caster_angles(layout, r, None if caster_angles_deg is None else caster_angles_deg[i])
              for i, (_, _, r) in enumerate(checked)]
    cfg, nrec, consts = _kernel_inputs(layout, checked[0][2], motor_lag_s, batch=True)
    from stability.simulate import layout_kernel as k

    nc, R = len(layout.casters), len(U)
    ctl = _controller_arrays(layout, None)
    states = np.array([k.initial_state(s, r.lateral_velocity, d, 0) for (_, s, r), d in zip(checked, deltas,
                                                                                            strict=True)])
    recs = np.full((R, k.NREC + 2 * nc, nrec), np.nan)
    status, warn, mzrec = np.zeros((R, 2)), np.zeros((R, 3, 3)), np.zeros((R, nrec))
    args = k.arguments(cfg, consts, states, recs, status, warn, ctl, mzrec)
    runs = GoingRuns(status[:, 0])     # the kernel sets a run's code once, when it ends (0: still going)
    d0, d1, d2 = k.NSTATE, k.NSTATE + nc, k.NSTATE + 2 * nc
    dt = float(cfg[0])
    step_layouts: Callable[..., Any] = k.step_layouts
    for step in range(int(cfg[1])):
        if not runs.update():
            break
        going = runs.index
        # the hook's arrays: a copy of the rows still going each step (a hook may keep them)
        st = states.copy() if runs.everyone else states[going]
        runs.store(states, k.S_CMD, yaw_moment(step * dt, LayoutState(st[:, 0], st[:, 1], st[:, 2], st[:, 4], st[:, 5],
                                                                    st[:, 3], st[:, d0:d1].T, st[:, d1:d2].T, going)))
        if step == 0:
            load_kernel(k.step_layouts, (0, 1, *args), "layout")
        step_layouts(step, step + 1, *args)
        if step == 0:
            step_layouts = _compiled(k.step_layouts, (0, 1, *args))
    out = []
    for i, ((_, signed, r), d) in enumerate(zip(checked, deltas, strict=True)):
        settings = dict(r.to_dict(), caster_angles_deg=[float(x) for x in np.degrees(d)], dt_s=float(cfg[0]),
                        controller="yaw_moment", motor_lag_s=float(motor_lag_s))
        out.append(_layout_run(layout, signed, recs[i], int(states[i, k.S_NREC]), status[i], warn[i], settings,
                               mzrec[i], int(cfg[2]), float(cfg[0])))
    return out
