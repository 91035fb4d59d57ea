"""Driver of the compiled WCHAIR kernel: run the packed arrays (:mod:`.packing`), build the results.

:func:`run_compiled` serves :func:`~stability.simulate.simulate` (one run)
and :func:`~stability.simulate.simulate_batch` (many, threads over runs)
with the same kernel, so the same run gives the same numbers either way.
"""

from __future__ import annotations

import functools
import math
import threading
from collections.abc import Sequence
from contextlib import AbstractContextManager, nullcontext
from typing import Any

import numpy as np

from stability import tires as _tires
from stability.chair import Chair
from stability.settings.reference import LEVEL
from stability.simulate import kernel_choice as _kc
from stability.simulate.controller import SampledController
from stability.simulate.first_use import first_use
from stability.simulate.hooked import hooked_steps
from stability.simulate.options import LOAD_LIMIT_N, SLIP_LIMIT_DEG, WARNING_LIMIT, Options, n_steps
from stability.simulate.packing import Packed, policy_code, slope_slots
from stability.simulate.results import RunStats, SimulationResult, warning_table

__all__ = ["RECORDS", "STATS_LEVELS", "PackedRuns", "run_compiled", "run_summaries", "raise_non_finite",
           "use_kernel"]

#: the kernel choice (tests, benchmarks): :func:`stability.simulate.kernel_choice.use_kernel`
use_kernel = _kc.use_kernel

#: What a run records: every column, the ten states only, or only the final step (plus :class:`RunStats`).
RECORDS = ("all", "states", "final")
#: |yaw rate| levels (rad/s) whose first crossing every compiled run reports in ``result.stats``.
STATS_LEVELS = (0.5, LEVEL)
#: Runs stopped at a level (the searches) and with stick-slip friction also stop once settled (kernel.SETTLE).
SETTLE_STOP = True


_LOADED: dict[str, Any] = {}


def _kernel():
    k = _LOADED.get("kernel")
    if k is None:
        with first_use("wchair_load"):
            from stability.simulate import kernel as k  # numba and the compiled code load on first use (CLI start-up)
        _LOADED["kernel"] = k
    return k


@functools.lru_cache(maxsize=16)
def _times(nrec: int, stride: int, dt: float) -> np.ndarray:
    """The recorded rows' times, s (read-only; the results hold views of it)."""
    t = np.arange(nrec) * float(stride) * dt
    t.flags.writeable = False
    return t


def run_compiled(chairs: Sequence[Chair], speeds: np.ndarray, opts: Options, *, forces: np.ndarray | None = None,
                 controller: SampledController | None = None, record: str = "all",
                 threads: int | None = None, batch: bool = True, step_limits: np.ndarray | None = None,
                 dt_auto: bool = False) -> list[SimulationResult]:
    """Run the WCHAIR scheme compiled for every (chair, speed) pair; one result per run.

    A Python ``opts.yaw_moment(t, state)`` input is sampled at every step and
    held over it (a sampled controller with the step as its sample time): the
    kernel runs one step at a time and the input is called in between, with
    floats for one run (``batch`` False) or arrays over the runs still going
    (``batch`` True, ``state.run`` their indices).

    Parameters
    ----------
    chairs : sequence of Chair
        One chair per run.
    speeds : ndarray
        Initial forward speeds, m/s (> 0), shape ``(len(chairs),)``.
    opts : Options
        Checked options (:func:`~stability.simulate.options.make_options`),
        ``scheme="wchair"``.
    forces : ndarray, optional
        Per-run lateral push at the c.g., N (FCIMP), shape ``(len(chairs),)``,
        instead of ``opts.impulse_force``.
    controller : SampledController, optional
        Sampled linear yaw-moment controller run inside the kernel (not with
        a Python ``opts.yaw_moment``).
    record : {"all", "states", "final"}
        Every column, the ten states (the other columns NaN), or only the
        last executed step (:data:`RECORDS`).
    threads : int, optional
        Threads of the kernel (>= 1); None: numba's default.  The numbers do
        not depend on it.
    batch : bool
        How a Python ``yaw_moment`` sees the state: arrays (True) or floats.
    step_limits : ndarray, optional
        Each run's largest stable step, s (:func:`stability.simulate.stepcheck.stable_steps`): a run whose
        ``opts.dt`` exceeds it is flagged ``step_unstable``, and ``settings`` record it as ``stable_dt`` with
        ``dt_auto``.  None: nothing flagged or recorded.
    dt_auto : bool
        Whether ``opts.dt`` was chosen by ``dt="auto"`` (recorded with ``step_limits``).

    Returns
    -------
    list of SimulationResult
        One per run, in input order, each with ``stats``
        (:class:`~stability.simulate.results.RunStats` at the
        :data:`STATS_LEVELS`) and ``settings["engine"] == "compiled"``.

    Raises
    ------
    ValueError
        With ``out_of_range="raise"``, the first tire input outside the data
        (the tire's own error).
    """
    k = _kernel()
    n_runs = len(chairs)
    steps = n_steps(opts)
    mode = RECORDS.index(record)
    nrec = 1 if mode == 2 else (steps - 1) // opts.stride + 1
    levels = np.array(STATS_LEVELS, dtype=float)
    rec, stats, warn, status, counts = _launch_runs(k, chairs, speeds, opts, forces, controller, mode, nrec, levels,
                                                    -1, threads, batch)
    _raise_refused(chairs, opts, status)
    raise_non_finite(chairs, speeds, status)
    times = _times(nrec, opts.stride, opts.dt)
    settings = opts.settings()
    settings.update(engine="compiled", record=record)
    if controller is not None:
        settings["controller"] = controller.name
    unstable = np.zeros(n_runs, dtype=bool) if step_limits is None else opts.dt > step_limits * (1.0 + 1e-12)
    out = []
    for i in range(n_runs):
        s = settings if forces is None else dict(settings, impulse_force=float(forces[i]))
        if step_limits is not None:
            s = dict(s, stable_dt=float(step_limits[i]), dt_auto=dt_auto)
        w = warning_table(warn[i])
        m = int(counts[i])
        t = times[:m] if mode != 2 else np.array([_last_time(opts, status[i], steps)])
        run_stats = RunStats(levels=STATS_LEVELS, time_to_level=tuple(None if math.isnan(x) else float(x)
                                                                        for x in stats[i, 2:2 + len(levels)]),
                             peak_abs_yaw_rate=float(stats[i, 0]), peak_time=float(stats[i, 1]))
        out.append(SimulationResult.from_columns(
            t, rec[i, :, :m], warnings=w, stopped=bool(status[i, 0]), stop_time=float(status[i, 1]) if status[i, 0]
            else None, chair=chairs[i], speed=float(speeds[i]), settings=s, stats=run_stats,
            step_unstable=bool(unstable[i])))
    return out


#: serialises entry into the parallel kernel where numba's threading layer is not thread-safe
KERNEL_LOCK = threading.Lock()
#: numba threading layers that allow parallel=True functions to be entered from several threads at once
#: (numba's documentation: "tbb" and "omp" are thread-safe; the fallback "workqueue" aborts the process)
THREAD_SAFE_LAYERS = ("tbb", "omp")


def kernel_entry_guard() -> AbstractContextManager:
    """The lock to hold while calling the parallel kernel, or a no-op where that is safe.

    The threading layer is chosen at the first parallel launch; until then (and under
    ``workqueue``) entry is serialised by :data:`KERNEL_LOCK`.
    """
    from numba import threading_layer

    try:
        layer = threading_layer()
    except ValueError:          # no parallel launch yet: the layer is not chosen
        return KERNEL_LOCK
    return nullcontext() if layer in THREAD_SAFE_LAYERS else KERNEL_LOCK


def _config(opts: Options, mode: int, stop_level: int) -> np.ndarray:
    """The kernel's configuration row (step, push, model, warning rule, slope, stop level, settle stop, and the
    flag of a Python yaw-moment input, set by :func:`_launch_runs`)."""
    return np.array([opts.dt, opts.impulse_duration, opts.tire_impulse, n_steps(opts), opts.stride,
                     0 if opts.model == "thesis" else 1, opts.pin_mode, opts.stop_on_warnings,
                     policy_code(opts), mode, SLIP_LIMIT_DEG, LOAD_LIMIT_N, WARNING_LIMIT,
                     *slope_slots(opts), stop_level, float(SETTLE_STOP), 0.0], dtype=float)


class PackedRuns:
    """Runs packed for the kernel once and launched many times, on any subset and with new push forces.

    A search (critical impulse, equal-instability speed) simulates the same
    (chair, speed) pairs round after round with other pushes: packing the
    chairs' parameters and tire tables once, instead of every round, leaves
    the kernel's own time.  Each launch gives the summaries of
    :func:`run_summaries` (the same kernel and arithmetic).

    Parameters
    ----------
    chairs, speeds
        One per pair, as in :func:`run_compiled`.
    opts : dict of float to Options
        Checked options per fixed step (s): the runs of a pair use ``opts[steps[i]]``.
    steps : ndarray
        Each pair's step, s (a key of ``opts``).
    levels, stop_level
        As in :func:`run_summaries`.
    """

    def __init__(self, chairs: Sequence[Chair], speeds: np.ndarray, opts: dict[float, Options], steps: np.ndarray,
                 levels: Sequence[float] = STATS_LEVELS, stop_level: int | None = None):
        self.k = _kernel()
        self.chairs = list(chairs)
        self.speeds = np.asarray(speeds, dtype=float)
        self.steps = np.asarray(steps, dtype=float)
        first = opts[float(self.steps[0])] if len(self.steps) else next(iter(opts.values()))
        self.pk = Packed(self.chairs, np.asarray(speeds, dtype=float), first, np.zeros(len(self.chairs)))
        stop = -1 if stop_level is None else int(stop_level)
        self.levels = np.array(levels, dtype=float)
        self.cfg = {float(h): _config(o, 2, stop) for h, o in opts.items()}
        self.opts = opts
        self.ctl = SampledController.none().arrays()

    def launch(self, pairs: np.ndarray, forces: np.ndarray, threads: int | None = None) -> tuple[np.ndarray, ...]:
        """Run pair ``pairs[j]`` under push force ``forces[j]`` (N) for every ``j``, as :func:`run_summaries`.

        Parameters
        ----------
        pairs : ndarray of int
            Indices into the packed pairs (repeats allowed).
        forces : ndarray
            N, one per run.
        threads : int, optional
            Kernel threads (None: numba's default).

        Returns
        -------
        stats, status : ndarray
        """
        pairs = np.asarray(pairs, dtype=np.int64)
        n = len(pairs)
        stats = np.full((n, 3 + len(self.levels)), np.nan)
        status = np.zeros((n, 6))
        pk = self.pk
        run_h = self.steps[pairs]
        for h in np.unique(run_h):
            sel = np.flatnonzero(run_h == h)
            idx = pairs[sel]
            S = pk.S[idx]
            S[:, 4] = forces[sel]
            m = len(idx)
            rec = np.empty((m, self.k.NREC_STATES, 1))      # the states only: no per-step forces written
            st = np.full((m, 3 + len(self.levels)), np.nan)
            warn = np.zeros((m, 3, 3))
            stat = np.zeros((m, 6))
            counts = np.zeros(m, dtype=np.int64)
            _launch(self.k, threads, m, (0, n_steps(self.opts[float(h)]), pk.P[idx], S,
                                         pk.TK[idx], pk.TS[idx], pk.TL[idx], pk.LIM[idx], pk.RK[idx], pk.RC[idx],
                                         pk.RS[idx], pk.CAM[idx], pk.CHK[idx], self.cfg[float(h)], self.levels,
                                         *self.ctl, initial_state(S, self.ctl), rec, st, warn, stat, counts))
            batch = [self.chairs[int(i)] for i in idx]
            _raise_refused(batch, self.opts[float(h)], stat)
            raise_non_finite(batch, self.speeds[idx], stat)     # a NaN run is an error, never "did not reach"
            stats[sel], status[sel] = st, stat
        return stats, status


def initial_state(S: np.ndarray, ctl: tuple[np.ndarray, ...]) -> np.ndarray:
    """The kernels' per-run state at ``t = 0``, shape (n, NSTATE + ``nz`` + the controller's scratch) (``nz``: the
    controller's states; ``ctl``: its kernel arrays, :meth:`SampledController.arrays`): the ten states (u, v and the
    caster angles from the packed scalars ``S``), the rest zero, the settle tracker unset."""
    k = _kernel()
    state = np.zeros((S.shape[0], k.NSTATE + ctl[3].shape[0] + k.scratch_columns(ctl[0], ctl[3], ctl[1])))
    state[:, 3], state[:, 4], state[:, 6], state[:, 8] = S[:, k.U0], S[:, k.V0], S[:, k.ETA0], S[:, k.BETA0]
    state[:, k.ST_TRACK] = -1.0
    return state


def _launch_runs(k: Any, chairs: Sequence[Chair], speeds: np.ndarray, opts: Options, forces: np.ndarray | None,
                 controller: SampledController | None, mode: int, nrec: int, levels: np.ndarray, stop_level: int,
                 threads: int | None, batch: bool = True) -> tuple[np.ndarray, ...]:
    """Pack, allocate and run the kernel: ``(rec, stats, warn, status, counts)``.

    With a Python ``opts.yaw_moment`` the kernel runs step by step on this
    thread and the input is sampled in between (:func:`run_compiled`).
    """
    pk = Packed(chairs, speeds, opts, forces)
    n_runs = len(chairs)
    ncol = (k.NREC_ALL, k.NREC_STATES, k.NREC_ALL)[mode]
    cfg = _config(opts, mode, stop_level)
    ctl = (controller or SampledController.none()).arrays()
    state = initial_state(pk.S, ctl)
    rec = np.empty((n_runs, ncol, nrec))
    stats = np.full((n_runs, 3 + len(levels)), np.nan)
    warn = np.zeros((n_runs, 3, 3))
    status = np.zeros((n_runs, 6))
    counts = np.zeros(n_runs, dtype=np.int64)
    args = (pk.P, pk.S, pk.TK, pk.TS, pk.TL, pk.LIM, pk.RK, pk.RC, pk.RS, pk.CAM, pk.CHK, cfg, levels, *ctl, state,
            rec, stats, warn, status, counts)
    if opts.yaw_moment is None:
        _launch(k, threads, n_runs, (0, n_steps(opts), *args))
        return rec, stats, warn, status, counts
    cfg[k.EXTERNAL_MZ] = 1.0
    lanes = None if _kc.choice() == "scalar" else functools.partial(_lanes_step, args, n_runs)
    # each kernel's specialisation is loaded under the first-use notice where it is found (kernel.call_model)
    hooked_steps(k, opts, args, state, status, k.variant(cfg, ctl[0]), batch, lanes)
    return rec, stats, warn, status, counts


def _lanes_step(args: tuple, n_runs: int, step: int) -> None:
    """Step ``step`` of every run on the lanes kernel (a Python yaw-moment input's steps), under the entry guard."""
    with kernel_entry_guard():
        _kc.run_lanes(step, step + 1, args, 1, n_runs)


def run_summaries(chairs: Sequence[Chair], speeds: np.ndarray, opts: Options, *, forces: np.ndarray | None = None,
                  levels: Sequence[float] = STATS_LEVELS, stop_level: int | None = None,
                  threads: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Run the compiled WCHAIR scheme keeping only each run's summaries; optionally stop every run at a level.

    The same kernel and arithmetic as :func:`run_compiled` (one final row
    recorded, nothing built per run): what a search over pushes or speeds
    needs, at the cost of the kernel alone.

    Parameters
    ----------
    chairs, speeds, forces, threads
        As in :func:`run_compiled`.
    opts : Options
        Checked options, ``scheme="wchair"``, no Python ``yaw_moment``.
    levels : sequence of float
        |yaw rate| levels whose first crossing is reported, rad/s.
    stop_level : int, optional
        Index into ``levels``: every run stops at the step at which
        ``|yaw rate|`` first reaches that level (its summaries are final then:
        the first crossing is found, and the peak up to it is the level).
        None: every run goes to the end.

    Returns
    -------
    stats : ndarray, shape (n, 3 + len(levels))
        Peak |yaw rate| (rad/s), its time (s), the first time at each level
        (s, NaN: never), the time of the last step (s).
    status : ndarray, shape (n, 6)
        ``status[:, 0]``: 0 ran to the end, 1 stopped by the warning rule, 2
        stopped at the level, 3 stopped because the yaw rate became NaN or
        infinite (its peak is then NaN); ``status[:, 1]``: when, s.
    """
    k = _kernel()
    lv = np.array(levels, dtype=float)
    stop = -1 if stop_level is None else int(stop_level)
    if not -1 <= stop < len(lv):
        raise ValueError(f"stop_level={stop_level!r} is invalid; valid range: None or 0..{len(lv) - 1}")
    _, stats, _, status, _ = _launch_runs(k, chairs, speeds, opts, forces, None, 2, 1, lv, stop, threads)
    _raise_refused(chairs, opts, status)
    return stats, status


def _launch(k: Any, threads: int | None, n_runs: int, args: tuple) -> None:
    """Run the kernel: one thread for one run, else ``prange`` over runs in small chunks.

    One run on one thread avoids waking the thread team (about 10 ms on a
    loaded machine).  Runs differ in cost (early stops), so a batch hands its
    runs out in chunks of about 1/16 of a thread's share (dynamic scheduling)
    instead of one contiguous block per thread.  Neither changes any number.
    Calls from several Python threads are safe: under a threading layer that
    is not thread-safe they enter the kernel one at a time (:func:`kernel_entry_guard`).
    """
    with kernel_entry_guard():
        _launch_unguarded(k, threads, n_runs, args)


def _launch_unguarded(k: Any, threads: int | None, n_runs: int, args: tuple) -> None:
    """:func:`_launch` without the entry guard; a ``threads`` request holds for this call only."""
    before = k.get_num_threads()
    if threads is not None:
        k.set_num_threads(max(1, min(int(threads), k.NUMBA_NUM_THREADS)))
    try:
        nthreads = k.get_num_threads()
        # each kernel's specialisation (scalar or lanes) is loaded under the first-use notice where it is found
        # (kernel.call_model), apart from the runs: a large first batch of a cached kernel says nothing
        _launch_inner(k, threads, n_runs, args, nthreads)
    finally:
        if threads is not None:     # a search's one-thread round must not leave later batches on one thread
            k.set_num_threads(before)


def _launch_inner(k: Any, threads: int | None, n_runs: int, args: tuple, nthreads: int) -> None:
    if _kc.choice() == "lanes" and len(args[14]) <= _kc.lanes_kernel().MAX_LEVELS:
        lk = _kc.lanes_kernel()
        lanes = _kc.lane_block(n_runs, nthreads)
        with lk.parallel_chunksize(1):      # one block (or thread) runs on this thread: lanes_kernel.run_lanes
            lk.run_lanes(*args, lanes)
        return
    var = k.variant(args[13], args[15])     # the model's (and controller's) own specialisation of the kernel
    if n_runs == 1:     # on this thread, without the parallel entry (whose compile a first run need not wait for)
        k.run_single(var, args)
        return
    with k.parallel_chunksize(max(1, n_runs // (16 * nthreads))):
        k.call_model(k.run_batch, var, *args)


def _last_time(opts: Options, status: np.ndarray, steps: int) -> float:
    """Time of the last executed step (the one before a stop, else the last of the loop), s."""
    last = steps - 1 if not status[0] else int(round(status[1] / opts.dt)) - 1
    return max(last, 0) * opts.dt


def raise_non_finite(chairs: Sequence[Chair], speeds: Sequence[float] | np.ndarray, status: np.ndarray) -> None:
    """A run whose state left the finite numbers is an error, never a result.

    Parameters
    ----------
    chairs : sequence of Chair
    speeds : sequence of float
        m/s.
    status : ndarray, shape (n, >= 2)
        Each run's stop code and stop time, s (:func:`run_summaries`).

    Raises
    ------
    FloatingPointError
        Naming the first such run's chair, speed and time.
    """
    bad = np.flatnonzero(status[:, 0] == _kernel().STOPPED_NONFINITE)
    if bad.size:
        i = int(bad[0])
        raise FloatingPointError(
            f"the simulation of chair {chairs[i].name!r} at {float(speeds[i]):g} m/s left the finite numbers at "
            f"t = {float(status[i, 1]):g} s ({bad.size} of {len(chairs)} runs)")


def _raise_refused(chairs: Sequence[Chair], opts: Options, status: np.ndarray) -> None:
    """Policy "raise": the first refused tire input raises the tire's own error (what Tire.lateral_force raises)."""
    bad = np.flatnonzero(status[:, 2] != 0)
    if bad.size == 0:
        return
    i = int(bad[0])
    c = chairs[i]
    wheel = int(status[i, 3])
    if status[i, 2] == 2.0:
        _tires.get(c.main_tire).lateral_force(float(status[i, 4]), float(status[i, 5]), policy="raise")
    tire = c.caster_tire_model() if wheel < 2 else c.main_tire_model()
    tire.lateral_force(float(status[i, 4]), float(status[i, 5]), policy="raise")
    raise ValueError(f"tire input out of range (slip {status[i, 4]!r} deg, load {status[i, 5]!r} N)")  # unreachable
