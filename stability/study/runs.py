"""Simulator access for the studies: many runs per call of :func:`stability.simulate.simulate_batch`."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from stability import simulate as sim
from stability.chair import Chair
from stability.settings.run import RunSpec
from stability.simulate.stepcheck import SAFETY, stable_steps

__all__ = ["SCALAR_RUNS", "simulate_runs", "study_run"]

#: Up to this many runs, :func:`simulate_runs` runs them one by one with
#: :func:`stability.simulate.simulate`: the vectorised wchair stepping of
#: ``simulate_batch`` costs about 0.3-0.5 ms per step whatever the number of
#: runs, while a scalar run costs about 0.04 ms per step.  Both give the same numbers.
SCALAR_RUNS = 12


def study_run(run: RunSpec | None = None) -> RunSpec:
    """The run settings of a study: ``run`` (default ``RunSpec()``), runs going on past the warnings.

    WCHAIR stops a run at its 11th slip (> 8 deg) or load (> 450 N) warning.
    At low speed the push alone takes the slip angles past 8 deg at once (40 N
    for 0.1 s gives 0.04 m/s sideways: 11 deg at 0.2 m/s), which says nothing
    about stability, so a study lets its runs go on (tire forces clamped at the
    edge of the data) unless ``run.stop_on_warnings`` says otherwise.

    Parameters
    ----------
    run : RunSpec, optional

    Returns
    -------
    RunSpec
        ``run`` with ``stop_on_warnings=False`` where it was None.

    Raises
    ------
    TypeError
        ``run`` is not a RunSpec.
    """
    if run is None:
        run = RunSpec()
    elif not isinstance(run, RunSpec):
        raise TypeError(f"run={run!r} is invalid; expected a stability.settings.run.RunSpec")
    return run.replace(stop_on_warnings=False) if run.stop_on_warnings is None else run


def simulate_runs(chairs: Sequence[Chair], speeds: Sequence[float], run: RunSpec, *,
                  push_forces: Sequence[float] | np.ndarray | None = None, progress: bool = False) -> list:
    """Simulate runs (chair i at speed i): one ``simulate_batch`` call, or scalar runs for a few.

    Parameters
    ----------
    chairs : sequence of Chair
        One chair per run.
    speeds : sequence of float
        One speed per run, m/s.
    run : RunSpec
        The runs' settings (``sample`` defaults to 0.01 s).  A fixed ``dt``
        (WCHAIR scheme) is kept for every run it integrates stably; a run for
        which it exceeds the scheme's stability limit (slow speeds, where the
        caster modes are stiff) gets the largest ``dt / k`` (whole k) within
        0.8 of its limit instead, so no study result comes from an unstable
        integration (the result's ``settings["dt"]`` records the step used).
    push_forces : sequence of float, optional
        One push force per run, N (default ``run.push_force`` for all).
    progress : bool
        Show a progress bar (batches only).

    Returns
    -------
    list of SimulationResult
    """
    chairs = list(chairs)
    speeds = [float(s) for s in speeds]
    if not chairs:
        return []
    if run.sample is None:
        run = run.replace(sample=0.01)
    forces = None if push_forces is None else np.asarray(push_forces, dtype=float)
    if run.scheme == "wchair" and run.dt != "auto":
        dt = float(run.dt)
        limits = stable_steps(chairs, np.asarray(speeds), run.model, run.casters)
        steps = [dt if dt <= lim else dt / math.ceil(dt / (SAFETY * lim)) for lim in limits]
        if any(h != dt for h in steps):
            return _by_step(chairs, speeds, steps, progress, run, forces)
    return _runs(chairs, speeds, progress, run, forces)


def _by_step(chairs: list[Chair], speeds: list[float], steps: list[float], progress: bool, run: RunSpec,
             forces: np.ndarray | None) -> list:
    """Runs grouped by their time step (one batch per step), returned in the callers' order."""
    out: list = [None] * len(chairs)
    for h in sorted(set(steps)):
        idx = [i for i, s in enumerate(steps) if s == h]
        for i, r in zip(idx, _runs([chairs[i] for i in idx], [speeds[i] for i in idx], progress, run.replace(dt=h),
                                   None if forces is None else forces[idx]), strict=True):
            out[i] = r
    return out


def _runs(chairs: list[Chair], speeds: list[float], progress: bool, run: RunSpec,
          forces: np.ndarray | None) -> list:
    if len(chairs) <= SCALAR_RUNS and run.scheme == "wchair":
        if forces is None:
            return [sim.simulate(c, s, run) for c, s in zip(chairs, speeds, strict=True)]
        return [sim.simulate(c, s, run.replace(push_force=float(f)))             # one force per run
                for c, s, f in zip(chairs, speeds, forces, strict=True)]
    return list(sim.simulate_batch(chairs, speeds, run, push_forces=forces, progress=progress))
