"""The public entry points :func:`simulate` and :func:`simulate_batch`."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.runtime.checks import check_choice, check_speed
from stability.runtime.progress import ProgressBar
from stability.simulate.adaptive import adaptive_single
from stability.simulate.controller import SampledController
from stability.simulate.engine import RECORDS, run_compiled
from stability.simulate.options import DEFAULTS, WCHAIR_DT, make_options
from stability.simulate.results import ChairState, SimulationResult
from stability.simulate.stepcheck import StepStabilityWarning, auto_step, stable_steps

__all__ = ["simulate", "simulate_batch"]

def _check_chair(chair: Any) -> Chair:
    if not isinstance(chair, Chair):
        raise ValueError(f"chair={chair!r} is invalid; expected a stability.chair.Chair "
                         "(see stability.chair.preset / resolve)")
    return chair


def simulate(chair: Chair, speed: float, *, duration: float = DEFAULTS.duration, scheme: str = DEFAULTS.scheme,
             model: str = DEFAULTS.model, dt: float | str = DEFAULTS.dt, impulse_force: float = DEFAULTS.impulse_force,
             impulse_duration: float = DEFAULTS.impulse_duration, tire_impulse: float = DEFAULTS.tire_impulse,
             lateral_velocity: float = DEFAULTS.lateral_velocity, eta0_deg: float = DEFAULTS.eta0_deg,
             beta0_deg: float = DEFAULTS.beta0_deg, casters: str = DEFAULTS.casters,
             friction_law: str | None = DEFAULTS.friction_law,
             yaw_moment: Callable[[float, ChairState], float] | None = DEFAULTS.yaw_moment,
             stop_on_warnings: bool | None = DEFAULTS.stop_on_warnings, out_of_range: str = DEFAULTS.out_of_range,
             sample: float | None = DEFAULTS.sample, rtol: float = DEFAULTS.rtol, atol: float = DEFAULTS.atol,
             reverse: bool = DEFAULTS.reverse, controller: SampledController | None = DEFAULTS.controller,
             record: str = DEFAULTS.record, slope: tuple[float, float] = DEFAULTS.slope) -> SimulationResult:
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
    dt : float or "auto"
        Step of the wchair scheme, s (TSTEP).  ``"auto"``: WCHAIR's 1 ms, or
        1 ms / k when the stability limit at this speed needs a smaller step.
    impulse_force, impulse_duration : float
        Lateral force at the c.g., N (FCIMP, positive to the right), and how
        long it acts, s (DUIMP; ``t <= DUIMP``).  Default: the thesis's
        reference push :data:`stability.settings.reference.THESIS_PUSH`; ``impulse_duration=math.inf``
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
    friction_law : {"kinetic", "stick-slip"} or None
        Pin friction of free casters.  "kinetic": program WCHAIR's law (the
        moment opposes the swivel rate and switches with its sign every
        step; the default of the wchair scheme).  "stick-slip": a caster
        whose rate would change sign within a step comes to rest, and stays
        at rest while the moment that holds it is within the friction limit
        (the adaptive scheme's law, resolved at the step; converged in the
        step where the kinetic law is not, see ``docs/simulator.md``).
        None: the scheme's default.
    yaw_moment : callable, optional
        ``yaw_moment(t, state) -> N m``: a yaw moment on the chair; ``state``
        is a :class:`ChairState`.  The wchair scheme samples it at every step
        and holds it over the step (the compiled kernel runs one step at a
        time with the call in between: slower than a ``controller``); the
        adaptive scheme calls it at every evaluation of its right-hand side.
    controller : SampledController, optional
        A sampled linear yaw-moment controller run inside the compiled kernel
        (:class:`stability.simulate.controller.SampledController`).
    record : {"all", "states", "final"}
        What the compiled WCHAIR scheme keeps: every column, the ten states
        (the rest read as NaN), or only the last step; ``result.stats`` always
        holds the peak |yaw rate| and the first times of 0.5 and 1 rad/s.
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
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)``: the plane falls to the right of the
        chair's initial heading by the cross slope and rises ahead by the
        grade, deg (each within +-15 deg; default level).  The in-plane weight
        acts on the chair and on each caster at its own c.g. and turns with
        the heading; the normal loads carry the normal weight (generated
        slope equations, :mod:`stability.models.slope`).  A nonzero slope
        needs ``model="exact"``.  No drive force: the chair coasts.

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
    given = dict(locals())
    options = {k: given[k] for k in DEFAULTS.as_dict()}
    return _run([chair], np.array([speed]), options, None, progress=False, threads=None, batch=False)[0]


def simulate_batch(chairs: Chair | Sequence[Chair], speeds, *, progress: bool = True,
                   workers: int | None = None, **options: Any) -> list[SimulationResult]:
    """Simulate many runs at once.

    ``chairs`` (one chair or a sequence) is broadcast against ``speeds`` (a
    number or a 1-D array) with numpy rules; every other keyword is as in
    :func:`simulate` and applies to all runs (``yaw_moment`` receives arrays
    over the active runs, with ``state.run`` their indices), except
    ``impulse_force``, which may also be a 1-D array broadcast with the
    chairs and speeds: one disturbance per run (a speed x disturbance-size
    map in one call; each result's ``settings`` holds its own force).

    The wchair scheme runs compiled, one run per thread (with a Python
    ``yaw_moment`` the kernel steps all runs on this thread, one step at a
    time, and calls it in between with arrays over the runs still going).
    The adaptive scheme integrates the runs one after another.  Batches record
    every 0.01 s by default (``sample``): about ``runs * samples * 31 * 8``
    bytes, or ``* 10 * 8`` with ``record="states"``; ``record="final"``
    keeps one row per run.  ``progress`` shows a bar on a terminal.

    ``workers``: threads of the compiled kernel (``None``: numba's default,
    the usable CPUs).  The results do not depend on it: one run is the same
    arithmetic alone or in any batch, and equals :func:`simulate`.

    Parameters
    ----------
    chairs : Chair or sequence of Chair
        One chair for all runs, or a non-empty sequence broadcast against
        ``speeds``.
    speeds : float or array_like
        Initial forward speeds, m/s (each > 0): a number or a 1-D array.
    progress : bool
        Show a progress bar on a terminal (default True).
    workers : int, optional
        Threads of the compiled kernel (>= 1); None: numba's default.
    **options
        Any keyword of :func:`simulate` (defaults in
        :data:`stability.simulate.DEFAULTS`); ``impulse_force`` (N) may be a
        non-empty 1-D array of finite forces, broadcast with ``chairs`` and
        ``speeds``.  ``sample`` defaults to the multiple of ``dt`` nearest
        0.01 s.

    Returns
    -------
    list of SimulationResult
        One per run, in broadcast order.

    Raises
    ------
    ValueError
        A bad argument, an unknown option, or shapes that do not broadcast
        (the message names the parameter, its value and the valid range).
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
    if n == 0:
        return []
    forces = None if fa is None else np.broadcast_to(fa, shape).reshape(-1).astype(float)
    threads = None if workers is None else _check_workers(workers)
    return _run(run_chairs, speed_arr, defaults, forces, progress=progress, threads=threads, batch=True)


def _check_workers(workers: Any) -> int:
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers={workers!r} is invalid; valid range: an integer >= 1, or None (automatic)")
    return int(workers)


def _run(chairs: list[Chair], speeds: np.ndarray, options: dict[str, Any], forces: np.ndarray | None, *,
         progress: bool, threads: int | None, batch: bool) -> list[SimulationResult]:
    """Check the options, pick the step and the engine, run, flag runs outside the step's stability limit."""
    options = dict(options)
    controller, record = options.pop("controller"), options.pop("record")
    check_choice("record", record, RECORDS)
    if controller is not None and not isinstance(controller, SampledController):
        raise ValueError(f"controller={controller!r} is invalid; expected a SampledController (or use yaw_moment=)")
    auto = isinstance(options["dt"], str) and options["dt"] == "auto"
    if auto:
        options["dt"] = WCHAIR_DT
    opts = make_options(batch=batch, **options)
    if opts.yaw_moment is not None and controller is not None:
        raise ValueError("yaw_moment and controller are both given; choose one")
    if opts.scheme == "adaptive" and (controller is not None or record != "all"):
        raise ValueError(f"controller= and record={record!r} need the WCHAIR scheme (scheme='wchair')")
    if opts.scheme == "adaptive":
        return _adaptive_runs(chairs, speeds, opts, forces, progress)
    limits = stable_steps(chairs, speeds, opts.model, opts.casters)
    if auto:
        options["dt"] = auto_step(float(limits.min()))
        opts = make_options(batch=batch, **options)
    out = run_compiled(chairs, speeds, opts, forces=forces, controller=controller, record=record, threads=threads,
                       batch=batch)
    return _flag_steps(out, opts.dt, limits, auto, speeds)


def _flag_steps(out: list[SimulationResult], dt: float, limits: np.ndarray, auto: bool,
                speeds: np.ndarray) -> list[SimulationResult]:
    bad = dt > limits * (1.0 + 1e-12)
    if bad.any():
        i = int(np.argmin(limits))
        warnings.warn(f"dt={dt:g} s exceeds the WCHAIR scheme's stability limit in {int(bad.sum())} of {len(out)} "
                      f"run(s) (largest safe step {limits[i]:.3g} s at {speeds[i]:g} m/s): flagged step_unstable; "
                      "use dt='auto', a smaller dt or scheme='adaptive'", StepStabilityWarning, stacklevel=4)
    return [dataclasses.replace(r, step_unstable=bool(b), settings=dict(r.settings, stable_dt=float(lim), dt_auto=auto))
            for r, b, lim in zip(out, bad, limits, strict=True)]


def _adaptive_runs(chairs, speeds, opts, forces, progress) -> list[SimulationResult]:
    out = []
    with ProgressBar(len(chairs), "simulate (adaptive)", enabled=progress and len(chairs) > 1, unit="run") as bar:
        for i, (c, s) in enumerate(zip(chairs, speeds, strict=True)):
            o = opts if forces is None else dataclasses.replace(opts, impulse_force=float(forces[i]))
            out.append(adaptive_single(c, float(s), o))
            bar.update()
    return out
