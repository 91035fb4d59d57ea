"""Run summaries for the searches (critical impulse, equal-instability speed): the kernel alone, stopped at a level.

A search only needs, per run, whether and when ``|yaw rate|`` reaches a
level, how fast it was growing there and, if it never does, its peak.  The
compiled WCHAIR kernel reports these at every step; with a stop level every
run ends at the step at which it reaches the level (nothing after it can
change the answer), and no per-run result is built.  Runs whose speed needs
a smaller step than the requested one (the stiff caster modes at slow
speeds) get the same step :func:`stability.study.runs.simulate_runs` gives
them, one kernel call per step.  The adaptive scheme (and any Python input)
runs through :func:`~stability.study.runs.simulate_runs` with the same summaries.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.settings.run import RunSpec
from stability.simulate.options import make_options
from stability.simulate.signals import time_to_level
from stability.simulate.stepcheck import SAFETY, stable_steps
from stability.study import runs

__all__ = ["Summaries", "SummaryRunner", "run_summaries", "run_steps"]


@dataclass(frozen=True)
class Summaries:
    """Per-run summaries of a search round (arrays over runs).

    Attributes
    ----------
    peak : ndarray
        Largest ``|yaw rate|`` up to the horizon or the stop, rad/s.
    t_half : ndarray
        First time ``|yaw rate|`` reaches half the level, s (inf: never).
    t_level : ndarray
        First time it reaches the level, s (inf: never within the horizon).
    sim_time : ndarray
        Simulated time of each run, s (a run stopped at the level is shorter).
    """

    peak: np.ndarray
    t_half: np.ndarray
    t_level: np.ndarray
    sim_time: np.ndarray

    def margin(self, level: float, horizon: float) -> np.ndarray:
        """The search's margin, in natural-log units of the yaw rate (0 at the critical case).

        ``ln(peak / level)`` (< 0) for a run that does not reach the level;
        ``ln 2 (horizon - t_level) / (t_level - t_half)`` (>= 0) for one that
        does: how much more the response would grow by the horizon at the
        growth rate it had on its way from half the level to the level.  Both
        go to 0 at the critical case, and for a response that grows
        exponentially and linearly in the push both equal ``ln(push / critical push)``.

        Parameters
        ----------
        level : float
            rad/s.
        horizon : float
            s.

        Returns
        -------
        ndarray
        """
        reached = self.t_level <= horizon
        with np.errstate(divide="ignore", invalid="ignore"):
            below = np.log(np.maximum(self.peak, 1e-300) / level)
            rise = np.maximum(self.t_level - np.minimum(self.t_half, self.t_level), 1e-9)
            above = math.log(2.0) * (horizon - self.t_level) / rise
        return np.where(reached, np.maximum(above, 0.0), np.minimum(below, 0.0))


def _compiled(run: RunSpec) -> bool:
    """Whether the runs go through the packed kernel with only summaries kept: the WCHAIR scheme (a run
    specification holds no Python input or controller; the adaptive scheme runs through
    :func:`~stability.study.runs.simulate_runs`)."""
    return run.scheme == "wchair"


def _kernel_options(run: RunSpec, h: float) -> Any:
    """The engines' options of one step ``h`` (s): every sample kept out, the push force given per run."""
    return make_options(run.replace(dt=float(h), sample=None, push_force=0.0), batch=True)


def run_summaries(chairs: Sequence[Chair], speeds: Sequence[float] | np.ndarray,
                  forces: Sequence[float] | np.ndarray, run: RunSpec, *, level: float, stop: bool = True,
                  steps: Sequence[float] | np.ndarray | None = None) -> Summaries:
    """Simulate runs (chair i at speed i under a push of force i) and summarise them.

    Parameters
    ----------
    chairs : sequence of Chair
    speeds : sequence of float
        m/s.
    forces : sequence of float
        Push force at the c.g., N (for ``run.push_duration``).
    run : RunSpec
        The runs' settings (through :func:`stability.study.runs.study_run`: no stop at the warnings unless
        asked for); a fixed ``dt``
        is kept where it is stable, else ``dt / k`` as in :func:`stability.study.runs.simulate_runs`.
    level : float
        |yaw rate| level, rad/s.
    stop : bool
        Stop each compiled run when it reaches the level.
    steps : sequence of float, optional
        Each run's step, s, from :func:`run_steps` (computed when None).

    Returns
    -------
    Summaries
    """
    n = len(chairs)
    run = runs.study_run(run)
    if n == 0:
        e = np.empty(0)
        return Summaries(e, e, e, e)
    if not _compiled(run):
        return _from_results(chairs, speeds, forces, run, level)
    from stability.simulate import engine  # numba and the compiled kernel load on first use

    step = run.fixed_step
    run_h = np.asarray(run_steps(chairs, speeds, step, run.model, run.casters) if steps is None else steps)
    peak, t_half, t_level, sim_time = (np.empty(n) for _ in range(4))
    sp = np.asarray(speeds, dtype=float)
    fo = np.asarray(forces, dtype=float)
    for h in np.unique(run_h):
        idx = np.flatnonzero(run_h == h)
        batch = [chairs[int(i)] for i in idx]
        stats, status = engine.run_summaries(batch, sp[idx], _kernel_options(run, h), forces=fo[idx],
                                             levels=(0.5 * level, level), stop_level=1 if stop else None)
        engine.raise_non_finite(batch, sp[idx], status)   # a NaN run is an error, never "did not reach"
        peak[idx] = stats[:, 0]
        t_half[idx] = np.where(np.isnan(stats[:, 2]), np.inf, stats[:, 2])
        t_level[idx] = np.where(np.isnan(stats[:, 3]), np.inf, stats[:, 3])
        sim_time[idx] = stats[:, 4]
        warned = status[:, 0] == 1.0          # stopped by the warning rule: counts as reaching it then
        if warned.any():
            j = idx[warned]
            t_level[j] = np.minimum(t_level[j], status[warned, 1])
    return Summaries(peak, t_half, t_level, sim_time)


#: Rounds of fewer runs than this run on one thread.  Waking the kernel's thread team and waiting for a free
#: core costs 0.1-10 ms per launch (10 ms measured on the shared 2-core machine under load), more than one
#: search's pair takes on one thread (a 10 s run: 2.4 ms); from four runs up (the critical-impulse search over
#: two or more speeds, a few ms a round) the threads win on an idle machine: six speeds x1.45 measured
#: (61 -> 89 ms on one thread).  A sweep's rounds (hundreds of runs) use all threads.
SERIAL_BELOW = 4


class SummaryRunner:
    """:func:`run_summaries` for a fixed set of (chair, speed) pairs, called once per search round.

    The pairs are packed for the compiled kernel once
    (:class:`stability.simulate.engine.PackedRuns`); a round then costs the
    kernel and a few array copies.  Where :func:`run_summaries` would not use
    the packed kernel (adaptive scheme, Python inputs) every call goes
    through it unchanged.  Either way the numbers are
    those of :func:`run_summaries`.

    Parameters
    ----------
    chairs : sequence of Chair
        One per pair.
    speeds : sequence of float
        m/s, one per pair.
    run : RunSpec
        As in :func:`run_summaries`.
    level, stop
        As in :func:`run_summaries`.
    steps : ndarray, optional
        Each pair's step, s (:func:`run_steps`; computed when None).
    """

    def __init__(self, chairs: Sequence[Chair], speeds: Sequence[float] | np.ndarray, run: RunSpec, *, level: float,
                 stop: bool = True, steps: Sequence[float] | np.ndarray | None = None):
        self.chairs, self.speeds = list(chairs), np.asarray(speeds, dtype=float)
        run = runs.study_run(run)
        self.run, self.level, self.stop = run, level, stop
        self.steps = steps
        self.packed = None
        if not _compiled(run) or not self.chairs:
            return
        from stability.simulate import engine

        step = run.fixed_step
        run_h = np.asarray(run_steps(self.chairs, self.speeds, step, run.model, run.casters)
                           if steps is None else steps, dtype=float)
        by_step = {float(h): _kernel_options(run, h) for h in np.unique(run_h)}
        self.packed = engine.PackedRuns(self.chairs, self.speeds, by_step, run_h, levels=(0.5 * level, level),
                                        stop_level=1 if stop else None)

    def __call__(self, pairs: Sequence[int] | np.ndarray, forces: Sequence[float] | np.ndarray) -> Summaries:
        """Summaries of the runs of pair ``pairs[j]`` under push force ``forces[j]`` (N).

        Parameters
        ----------
        pairs : sequence of int
            Indices into the pairs (repeats allowed).
        forces : sequence of float
            N, one per run.

        Returns
        -------
        Summaries
        """
        idx = np.asarray(pairs, dtype=np.int64)
        fo = np.asarray(forces, dtype=float)
        if self.packed is None:
            steps = None if self.steps is None else np.asarray(self.steps)[idx]
            return run_summaries([self.chairs[int(i)] for i in idx], self.speeds[idx], fo, self.run,
                                 level=self.level, stop=self.stop, steps=steps)
        if len(idx) == 0:
            e = np.empty(0)
            return Summaries(e, e, e, e)
        stats, status = self.packed.launch(idx, fo, threads=1 if len(idx) < SERIAL_BELOW else None)
        return _summaries(stats, status)


def _summaries(stats: np.ndarray, status: np.ndarray) -> Summaries:
    """:class:`Summaries` from the kernel's ``(stats, status)`` (a run stopped by the warning rule reaches then)."""
    t_half = np.where(np.isnan(stats[:, 2]), np.inf, stats[:, 2])
    t_level = np.where(np.isnan(stats[:, 3]), np.inf, stats[:, 3])
    warned = status[:, 0] == 1.0
    t_level = np.where(warned, np.minimum(t_level, status[:, 1]), t_level)
    return Summaries(stats[:, 0].copy(), t_half, t_level, stats[:, 4].copy())


def run_steps(chairs: Sequence[Chair], speeds: Sequence[float] | np.ndarray, dt: float, model: str,
              casters: str, limits: np.ndarray | None = None) -> np.ndarray:
    """Each run's step: ``dt`` where stable, else ``dt / k`` as :func:`~stability.study.runs.simulate_runs` picks.

    Parameters
    ----------
    chairs : sequence of Chair
    speeds : sequence of float
        m/s.
    dt : float
        Requested fixed step, s.
    model, casters : str
    limits : ndarray, optional
        The pairs' stable steps, s (:func:`~stability.simulate.stepcheck.stable_steps`; computed when None).

    Returns
    -------
    ndarray
        s.
    """
    if limits is None:
        limits = stable_steps(list(chairs), np.asarray(speeds, dtype=float), model, casters)
    return np.array([dt if dt <= lim else dt / math.ceil(dt / (SAFETY * lim)) for lim in limits])


def _from_results(chairs: Sequence[Chair], speeds: Sequence[float] | np.ndarray, forces: Sequence[float] | np.ndarray,
                  run: RunSpec, level: float) -> Summaries:
    """The same summaries from full simulation results (adaptive scheme, the reference engine)."""
    if run.scheme == "wchair":      # every step, so that the crossing is interpolated as the kernel does
        run = run.replace(sample=run.fixed_step)
    res = runs.simulate_runs(list(chairs), [float(s) for s in speeds], run, push_forces=np.asarray(forces, float))
    horizon = run.horizon
    peak, t_half, t_level, sim_time = (np.empty(len(res)) for _ in range(4))
    for i, r in enumerate(res):
        t, y = np.asarray(r.t), np.abs(np.asarray(r.yaw_rate))
        peak[i] = float(y.max()) if y.size else 0.0
        t_half[i] = time_to_level(t, y, 0.5 * level)
        t_level[i] = time_to_level(t, y, level)
        stop = getattr(r, "stop_time", None) if bool(getattr(r, "stopped_by_warnings", False)) else None
        if stop is None and bool(getattr(r, "stopped_by_warnings", False)) and len(t):
            stop = float(t[-1])
        if stop is not None and stop < horizon - 1e-9:
            # stopped early (the warning rule, or an adaptive run whose loads lost their solution): it reaches
            # the level at its crossing, else at the stop, as the kernel's stop time in _summaries
            t_level[i] = min(t_level[i], float(stop))
        sim_time[i] = float(t[-1]) if len(t) else 0.0
    return Summaries(peak, t_half, t_level, sim_time)
