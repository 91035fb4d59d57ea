"""The public entry points :func:`simulate` and :func:`simulate_batch`."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .._validate import check_speed
from ..chair import Chair
from ..progress import ProgressBar
from .adaptive import adaptive_single
from .options import DEFAULTS, make_options
from .processes import auto_workers, check_workers, fork_context, wchair_batch_processes
from .results import ChairState, SimulationResult
from .wchair import wchair_batch, wchair_single

__all__ = ["simulate", "simulate_batch"]


def _check_chair(chair: Any) -> Chair:
    if not isinstance(chair, Chair):
        raise ValueError(f"chair={chair!r} is invalid; expected a stability.chair.Chair "
                         "(see stability.chair.preset / resolve)")
    return chair


def simulate(chair: Chair, speed: float, *, duration: float = DEFAULTS.duration, scheme: str = DEFAULTS.scheme,
             model: str = DEFAULTS.model, dt: float = DEFAULTS.dt, impulse_force: float = DEFAULTS.impulse_force,
             impulse_duration: float = DEFAULTS.impulse_duration, tire_impulse: float = DEFAULTS.tire_impulse,
             lateral_velocity: float = DEFAULTS.lateral_velocity, eta0_deg: float = DEFAULTS.eta0_deg,
             beta0_deg: float = DEFAULTS.beta0_deg, casters: str = DEFAULTS.casters,
             yaw_moment: Callable[[float, ChairState], float] | None = DEFAULTS.yaw_moment,
             stop_on_warnings: bool | None = DEFAULTS.stop_on_warnings, out_of_range: str = DEFAULTS.out_of_range,
             sample: float | None = DEFAULTS.sample, rtol: float = DEFAULTS.rtol, atol: float = DEFAULTS.atol,
             reverse: bool = DEFAULTS.reverse) -> SimulationResult:
    """Simulate one run of a freely rolling chair disturbed from straight motion.

    Parameters
    ----------
    chair : Chair
        The chair (rear or front casters).
    speed : float
        Initial forward speed, m/s (> 0).
    duration : float
        Simulated time, s (WCHAIR's TTOTAL; the wchair scheme runs to
        ``duration + dt`` as WCHAIR's DO loop does).
    scheme : {"wchair", "adaptive"}
        Program WCHAIR's fixed-step scheme, or error-controlled integration
        with stick-slip pin friction (see ``docs/simulator.md``).
    model : {"thesis", "exact"}
        Equations of motion (:mod:`stability.models`).
    dt : float
        Step of the wchair scheme, s (TSTEP).
    impulse_force, impulse_duration : float
        Lateral force at the c.g., N (FCIMP, positive to the right), and how
        long it acts, s (DUIMP; ``t <= DUIMP``).  Default: the thesis's
        reference push :data:`stability.reference.THESIS_PUSH`; ``impulse_duration=math.inf``
        (or >= duration) gives a constant side force.
    tire_impulse : float
        Lateral force on EACH main tire while ``t <= impulse_duration``, N
        (FTIMP; replaces the tire forces there, as MECHAN does).
    lateral_velocity : float
        Initial lateral velocity, m/s (VD).
    eta0_deg, beta0_deg : float
        Initial caster angles, deg (E, B).
    casters : {"free", "locked"}
        Free casters with Coulomb pin friction, or casters locked at their
        initial angles.
    yaw_moment : callable, optional
        ``yaw_moment(t, state) -> N m``: a yaw moment on the chair (e.g. a
        motor-assist controller); ``state`` is a :class:`ChairState`.
    stop_on_warnings : bool, optional
        Stop at the eleventh warning of a kind (WCHAIR's rule).  Default:
        True for the wchair scheme, False for the adaptive one.
    out_of_range : {"clamp", "extrapolate", "raise"}
        What the tire fits do outside their data (slip > 8 deg, load >
        450 N): passed to :meth:`stability.tires.Tire.lateral_force`.
    sample : float, optional
        Output interval, s: every step of the wchair scheme by default (must
        be a multiple of ``dt``); 0.01 s for the adaptive scheme.
    rtol, atol : float
        Tolerances of the adaptive scheme.
    reverse : bool
        Drive the chair backwards (initial forward velocity ``-speed``).  Only
        for reproducing the thesis's front-caster trick of section "Method
        One" (a rear-caster model driven backwards with its casters at
        180 deg); a front-caster chair is normally simulated directly.

    Returns
    -------
    SimulationResult

    Raises
    ------
    ValueError
        A bad argument (the message names it, its value and the valid range).
    """
    chair = _check_chair(chair)
    speed = check_speed(speed)
    opts = make_options(duration=duration, scheme=scheme, model=model, dt=dt, impulse_force=impulse_force,
                         impulse_duration=impulse_duration, tire_impulse=tire_impulse,
                         lateral_velocity=lateral_velocity, eta0_deg=eta0_deg, beta0_deg=beta0_deg,
                         casters=casters, yaw_moment=yaw_moment, stop_on_warnings=stop_on_warnings,
                         out_of_range=out_of_range, sample=sample, rtol=rtol, atol=atol, reverse=reverse)
    if opts.scheme == "wchair":
        return wchair_single(chair, speed, opts)
    return adaptive_single(chair, speed, opts)


def simulate_batch(chairs: Chair | Sequence[Chair], speeds, *, progress: bool = True,
                   workers: int | None = None, **options) -> list[SimulationResult]:
    """Simulate many runs at once.

    ``chairs`` (one chair or a sequence) is broadcast against ``speeds`` (a
    number or a 1-D array) with numpy rules; every other keyword is as in
    :func:`simulate` and applies to all runs (``yaw_moment`` receives arrays
    over the active runs, with ``state.run`` their indices), except
    ``impulse_force``, which may also be a 1-D array broadcast with the
    chairs and speeds: one disturbance per run (a speed x disturbance-size
    map in one call; each result's ``settings`` holds its own force).

    The wchair scheme steps all runs together on numpy arrays (runs grouped
    by tire type where they differ); a run stopped by the warning rule is
    frozen and drops out.  The adaptive scheme integrates the runs one after
    another.  Batches record every 0.01 s by default (``sample``) to bound
    memory (about ``runs * samples * 32 * 8`` bytes).  ``progress`` shows a
    bar on a terminal.

    ``workers`` (wchair scheme): processes sharing the runs (forked, POSIX
    only).  ``None`` picks one per 250 runs up to the usable CPUs, and one
    when a ``yaw_moment`` input is given (a stateful controller must see all
    its calls in this process); ``1`` keeps everything in this process.  The
    results do not depend on it beyond floating-point rounding.

    Returns
    -------
    list of SimulationResult, one per run in broadcast order.
    """
    if isinstance(chairs, Chair):
        chair_list = [chairs]
    else:
        chair_list = list(chairs)
        if not chair_list:
            raise ValueError("chairs=[] is invalid; expected a Chair or a non-empty sequence of Chair")
    for c in chair_list:
        _check_chair(c)
    sp = np.asarray(speeds, dtype=float)
    if sp.ndim > 1:
        raise ValueError(f"speeds has shape {sp.shape}; expected a number or a 1-D array")
    if sp.size == 0:
        raise ValueError("speeds=[] is invalid; expected at least one speed > 0 m/s")
    for s in np.atleast_1d(sp).tolist():
        check_speed(s)
    fa = None
    if np.ndim(options.get("impulse_force", 0.0)) > 0:   # one force per run
        try:
            fa = np.asarray(options["impulse_force"], dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"impulse_force={options['impulse_force']!r} is invalid; expected a number or a 1-D "
                             "array of finite forces (N)") from None
        if fa.ndim != 1 or fa.size == 0 or not np.all(np.isfinite(fa)):
            raise ValueError(f"impulse_force={options['impulse_force']!r} is invalid; expected a number or a "
                             "non-empty 1-D array of finite forces (N)")
        options = dict(options, impulse_force=float(fa[0]))
    try:
        shape = np.broadcast_shapes((len(chair_list),) if not isinstance(chairs, Chair) else (), sp.shape,
                                    () if fa is None else fa.shape)
    except ValueError:
        raise ValueError(f"cannot broadcast {len(chair_list)} chairs against {sp.size} speeds"
                         + ("" if fa is None else f" and {fa.size} impulse forces")
                         + "; give one of each or equally many") from None
    n = int(np.prod(shape)) if shape else 1
    chair_idx = np.broadcast_to(np.arange(len(chair_list)) if not isinstance(chairs, Chair) else 0, shape).reshape(-1)
    speed_arr = np.broadcast_to(sp, shape).reshape(-1).astype(float)
    run_chairs = [chair_list[int(i)] for i in chair_idx]
    defaults = DEFAULTS.as_dict()
    unknown = set(options) - set(defaults)
    if unknown:
        raise ValueError(f"unknown option(s) {sorted(unknown)}; valid options: {sorted(defaults)}")
    defaults.update(options)
    opts = make_options(batch=True, **defaults)
    if n == 0:
        return []
    forces = None if fa is None else np.broadcast_to(fa, shape).reshape(-1).astype(float)
    if opts.scheme == "wchair":
        nw = auto_workers(n, opts) if workers is None else check_workers(workers)
        if nw > 1 and fork_context() is not None:
            return wchair_batch_processes(run_chairs, speed_arr, opts, progress, min(nw, n), forces)
        return wchair_batch(run_chairs, speed_arr, opts, progress, forces=forces)
    out = []
    with ProgressBar(n, "simulate (adaptive)", enabled=progress, unit="run") as bar:
        for i, (c, s) in enumerate(zip(run_chairs, speed_arr, strict=False)):
            o = opts if forces is None else dataclasses.replace(opts, impulse_force=float(forces[i]))
            out.append(adaptive_single(c, float(s), o))
            bar.update()
    return out
