"""The public entry points :func:`simulate` and :func:`simulate_batch`."""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from stability.chair import Chair, check_chair
from stability.chair.model import check_chairs
from stability.runtime.checks import check_choice, real_array, value_text
from stability.runtime.progress import ProgressBar
from stability.settings.run import (
    MAX_BATCH_BYTES,
    ROW_BYTES,
    RUN_BYTES,
    RUN_SETTINGS,
    STEP_SECONDS,
    WORK_BUDGET_S,
    RunSpec,
)
from stability.simulate.adaptive import adaptive_single
from stability.simulate.controller import SampledController
from stability.simulate.engine import RECORDS, run_compiled
from stability.simulate.options import make_options
from stability.simulate.results import ChairState, SimulationResult
from stability.simulate.stepcheck import StepStabilityWarning, auto_step, stable_steps

__all__ = ["simulate", "simulate_batch"]

def _spec(speed: Any, run: RunSpec | None) -> RunSpec:
    if run is None:
        run = RunSpec()
    elif not isinstance(run, RunSpec):
        raise TypeError(f"run={value_text(run)} is invalid; expected a stability.settings.run.RunSpec")
    return run if speed is None else run.replace(speed=speed)


def simulate(chair: Chair, speed: float | None = None, run: RunSpec | None = None, *,
             yaw_moment: Callable[[float, ChairState], float] | None = None,
             controller: SampledController | None = None, record: str = "all") -> SimulationResult:
    """Simulate one run of a freely rolling chair disturbed from straight motion.

    Parameters
    ----------
    chair : Chair
        The chair (rear or front casters).
    speed : float, optional
        Initial forward speed, m/s: shorthand for ``run.replace(speed=speed)``
        (default ``run.speed``, 0.75 m/s).
    run : RunSpec, optional
        Every other setting of the run (:class:`stability.settings.run.RunSpec`); default
        ``RunSpec()``: the thesis's reference push, the wchair scheme, stick-slip pin friction.
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

    Returns
    -------
    SimulationResult

    Raises
    ------
    ValueError
        A bad argument (the message names it, its value and the valid range).
    TypeError
        ``chair`` is not a Chair, ``run`` not a RunSpec, or a setting of the wrong type.
    """
    chair = check_chair(chair)
    spec = _spec(speed, run)
    check_choice("record", record, RECORDS)
    return _run([chair], np.array([spec.speed]), spec, None, yaw_moment, controller, record, progress=False,
                threads=None, batch=False)[0]


def simulate_batch(chairs: Chair | Sequence[Chair], speeds: Any = None, run: RunSpec | None = None, *,
                   push_forces: Any = None, yaw_moment: Callable | None = None,
                   controller: SampledController | None = None, record: str = "all", progress: bool = True,
                   workers: int | None = None) -> list[SimulationResult]:
    """Simulate many runs at once.

    ``chairs`` (one chair or a sequence) is broadcast against ``speeds`` (a
    number or a 1-D array) and ``push_forces`` with numpy rules; ``run``
    applies to all runs (``yaw_moment`` receives arrays over the active runs,
    with ``state.run`` their indices).

    The wchair scheme runs compiled, one run per thread (with a Python
    ``yaw_moment`` the kernel steps all runs on this thread, one step at a
    time, and calls it in between with arrays over the runs still going).
    The adaptive scheme integrates the runs one after another.  Batches record
    every 0.01 s by default (``run.sample``): about ``runs * samples * 31 * 8``
    bytes, or ``* 10 * 8`` with ``record="states"``; ``record="final"``
    keeps one row per run.  ``progress`` shows a bar on a terminal.
    The results do not depend on ``workers``: one run is the same arithmetic
    alone or in any batch, and equals :func:`simulate`.

    Parameters
    ----------
    chairs : Chair or sequence of Chair
        One chair for all runs, or a non-empty sequence broadcast against
        ``speeds``.
    speeds : float or array_like, optional
        Initial forward speeds, m/s: a number or a 1-D array (default ``run.speed``).
    run : RunSpec, optional
        The settings of every run (default ``RunSpec()``).
    push_forces : array_like, optional
        One push force per run, N (a non-empty 1-D array of finite forces broadcast with ``chairs`` and
        ``speeds``; each result's ``settings`` holds its own); default ``run.push_force`` for all.
    yaw_moment, controller, record
        As in :func:`simulate`.
    progress : bool
        Show a progress bar on a terminal (default True).
    workers : int, optional
        Threads of the compiled kernel, 1 to :data:`MAX_WORKERS` (more than numba's pool, ``NUMBA_NUM_THREADS``,
        run as many as the pool has); None: numba's default.

    Returns
    -------
    list of SimulationResult
        One per run, in broadcast order.

    Raises
    ------
    ValueError
        A bad argument, or shapes that do not broadcast (the message names the parameter, its value and the
        valid range).
    """
    spec = _spec(None, run)
    one = isinstance(chairs, Chair)
    chair_list: list[Chair] = [chairs] if isinstance(chairs, Chair) else list(check_chairs(chairs))
    if not chair_list:
        raise ValueError("chairs=[] is invalid; expected a Chair or a non-empty sequence of Chair")
    sp = _array("speeds", spec.speed if speeds is None else speeds, "m/s")
    _within(spec, "speed", sp, "speeds")
    fa = None
    if push_forces is not None:
        fa = _array("push_forces", push_forces, "N")
        if fa.ndim != 1:
            raise ValueError(f"push_forces={value_text(push_forces)} is invalid; expected a non-empty 1-D array "
                             "of finite forces (N)")
        _within(spec, "push_force", fa, "push_forces")
    try:
        shape = np.broadcast_shapes(() if one else (len(chair_list),), sp.shape, () if fa is None else fa.shape)
    except ValueError:
        raise ValueError(f"cannot broadcast {len(chair_list)} chairs against {sp.size} speeds"
                         + ("" if fa is None else f" and {fa.size} push forces")
                         + "; give one of each or equally many") from None
    chair_idx = np.broadcast_to(0 if one else np.arange(len(chair_list)), shape).reshape(-1)
    speed_arr = np.broadcast_to(sp, shape).reshape(-1).astype(float)
    run_chairs = [chair_list[int(i)] for i in chair_idx]
    forces = None if fa is None else np.broadcast_to(fa, shape).reshape(-1).astype(float)
    threads = None if workers is None else _check_workers(workers)
    check_choice("record", record, RECORDS)
    _check_batch_work(len(speed_arr), spec, record, "speeds" if one else "chairs and speeds")
    return _run(run_chairs, speed_arr, spec, forces, yaw_moment, controller, record, progress=progress,
                threads=threads, batch=True)


def _array(name: str, values: Any, unit: str) -> np.ndarray:
    """``values`` as a non-empty float array of at most one dimension (an integer beyond the float range as
    +-inf, refused by the setting's range), or a ValueError naming ``name``."""
    try:
        a = real_array(values)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value_text(values)} is invalid; expected a number or a 1-D array of numbers "
                         f"({unit})") from None
    if a.ndim > 1:
        raise ValueError(f"{name} has shape {a.shape}; expected a number or a 1-D array")
    if a.size == 0:
        raise ValueError(f"{name}=[] is invalid; expected at least one value ({unit})")
    return a


def _within(spec: RunSpec, setting: str, values: np.ndarray, name: str) -> None:
    """Every one of ``values`` valid as ``spec``'s ``setting``: the RunSpec's range, the first invalid one named."""
    bound = RUN_SETTINGS[setting].bound
    assert bound is not None
    bad = np.flatnonzero(~bound.holds(values))
    for v in ([values.flat[bad[0]]] if bad.size else []) + [values.min(), values.max()]:
        try:
            spec.replace(**{setting: float(v)})             # the RunSpec's own message (and its checks together)
        except ValueError as exc:
            raise ValueError(f"{name}: {exc}") from None


#: Most threads a batch may ask for: far above any machine this runs on (numba's pool, ``NUMBA_NUM_THREADS``, caps
#: a request between its size and this), low enough that an absurd integer is named as bad input, not obeyed.
MAX_WORKERS = 1024


def _check_workers(workers: Any) -> int:
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or not 1 <= workers <= MAX_WORKERS:
        shown = value_text(workers) if isinstance(workers, (int, np.integer)) else repr(workers)
        raise ValueError(f"workers={shown} is invalid; valid range: an integer 1 to {MAX_WORKERS}, or None "
                         "(automatic)")
    return int(workers)


def _run(chairs: list[Chair], speeds: np.ndarray, run: RunSpec, forces: np.ndarray | None, yaw_moment: Any,
         controller: Any, record: str, *, progress: bool, threads: int | None,
         batch: bool) -> list[SimulationResult]:
    """Resolve the options, pick the step and the engine, run, flag runs outside the step's stability limit."""
    check_choice("record", record, RECORDS)
    if controller is not None and not isinstance(controller, SampledController):
        raise ValueError(f"controller={controller!r} is invalid; expected a SampledController (or use yaw_moment=)")
    auto = run.dt == "auto"
    opts = make_options(run, yaw_moment=yaw_moment, batch=batch)
    if opts.yaw_moment is not None and controller is not None:
        raise ValueError("yaw_moment and controller are both given; choose one")
    if opts.scheme == "adaptive" and (controller is not None or record != "all"):
        raise ValueError(f"controller= and record={record!r} need the WCHAIR scheme (scheme='wchair')")
    if opts.scheme == "adaptive":
        return _adaptive_runs(chairs, speeds, opts, forces, progress)
    limits = stable_steps(chairs, np.abs(speeds), opts.model, opts.casters)   # a reverse run: as with reverse=True
    if auto:
        opts = make_options(run, yaw_moment=yaw_moment, batch=batch, dt=auto_step(float(limits.min())))
    out = run_compiled(chairs, speeds, opts, forces=forces, controller=controller, record=record, threads=threads,
                       batch=batch, step_limits=limits, dt_auto=auto)
    _warn_steps(out, opts.dt, limits, speeds)
    return out


def _warn_steps(out: list[SimulationResult], dt: float, limits: np.ndarray, speeds: np.ndarray) -> None:
    """Warn when ``dt`` exceeds a run's stability limit (the runs are flagged ``step_unstable`` by the engine)."""
    bad = [r.step_unstable for r in out]
    if any(bad):
        i = int(np.argmin(limits))
        warnings.warn(f"dt={dt:g} s exceeds the WCHAIR scheme's stability limit in {sum(bad)} of {len(out)} "
                      f"run(s) (largest safe step {limits[i]:.3g} s at {speeds[i]:g} m/s): flagged step_unstable; "
                      "use dt='auto', a smaller dt or scheme='adaptive'", StepStabilityWarning, stacklevel=4)


def _adaptive_runs(chairs, speeds, opts, forces, progress) -> list[SimulationResult]:
    out = []
    with ProgressBar(len(chairs), "simulate (adaptive)", enabled=progress and len(chairs) > 1, unit="run") as bar:
        for i, (c, s) in enumerate(zip(chairs, speeds, strict=True)):
            o = opts if forces is None else dataclasses.replace(opts, impulse_force=float(forces[i]))
            out.append(adaptive_single(c, float(s), o))
            bar.update()
    return out


def _check_batch_work(runs: int, run: RunSpec, record: str, name: str = "speeds") -> None:
    """Refuse a batch of ``runs`` runs whose steps or kept results exceed the bounds, before any run.

    The steps are ``runs x horizon / dt`` (dt ``"auto"`` taken at :data:`WCHAIR_DT`; the adaptive scheme's are
    not known before it runs), at most :data:`WORK_BUDGET_S` / :data:`STEP_SECONDS`; the memory is ``runs x
    (RUN_BYTES + rows x ROW_BYTES)`` with one row per run for ``record="final"``, else one per output interval
    (the batch's default, :data:`stability.simulate.options.BATCH_SAMPLE`, when ``run.sample`` is None), at most
    :data:`MAX_BATCH_BYTES`.

    Parameters
    ----------
    runs : int
        Runs asked for (after broadcasting).
    run : RunSpec
        Their settings.
    record : str
        ``"all"``, ``"states"`` or ``"final"``.
    name : str
        The argument to name (default ``"speeds"``).

    Raises
    ------
    ValueError
        Naming ``name``, the number of runs, the estimate and the largest allowed number of runs.
    """
    interval = make_options(run, batch=True).sample       # the batch's own output interval (None: every step)
    if interval is None:
        interval = run.fixed_step
    rows = 1.0 if record == "final" else run.horizon / interval + 1.0
    per_run = RUN_BYTES + rows * ROW_BYTES
    largest = int(MAX_BATCH_BYTES // per_run)
    if runs > largest:
        raise ValueError(f"{name} asks for {runs} runs keeping about {runs * per_run / 2**30:.3g} GiB of results "
                         f"(record={record!r}, {rows:.0f} row(s) each); at most {MAX_BATCH_BYTES / 2**30:.3g} GiB: "
                         f"the largest allowed is {largest} runs"
                         + ("" if record == "final" else " (or record='final', or a longer sample)"))
    if run.scheme == "wchair":
        steps = run.horizon / run.fixed_step
        largest = int(WORK_BUDGET_S / STEP_SECONDS // steps)
        if runs > largest:
            raise ValueError(f"{name} asks for {runs} runs of {steps:.3g} steps (about "
                             f"{runs * steps * STEP_SECONDS / 60:.0f} min); the largest allowed is {largest} runs "
                             f"(or a shorter horizon)")
