"""Simulator access for the studies: many runs per call of :func:`stability.simulate.simulate_batch`."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from stability import simulate as sim
from stability.chair import Chair
from stability.settings.defaults import MEASURE_FRICTION_LAW
from stability.simulate.stepcheck import SAFETY, stable_steps

__all__ = ["SCALAR_RUNS", "simulate_runs", "sim_options"]

#: Up to this many runs, :func:`simulate_runs` runs them one by one with
#: :func:`stability.simulate.simulate`: the vectorised wchair stepping of
#: ``simulate_batch`` costs about 0.3-0.5 ms per step whatever the number of
#: runs, while a scalar run costs about 0.04 ms per step.  Both give the same numbers.
SCALAR_RUNS = 12


def simulate_runs(chairs: Sequence[Chair], speeds: Sequence[float], *, progress: bool = False,
                  desc: str = "simulating", **options: Any) -> list:
    """Simulate runs (chair i at speed i): one ``simulate_batch`` call, or scalar runs for a few.

    Parameters
    ----------
    chairs : sequence of Chair
        One chair per run.
    speeds : sequence of float
        One speed per run, m/s.
    progress : bool
        Show a progress bar (batches only).
    desc : str
        Progress-bar label (unused by the simulator; kept for callers).
    **options
        :func:`stability.simulate.simulate` options; ``impulse_force`` may be
        one force per run (N).  ``sample`` defaults to 0.01 s.  A fixed ``dt``
        (WCHAIR scheme) is kept for every run it integrates stably; a run for
        which it exceeds the scheme's stability limit (slow speeds, where the
        caster modes are stiff) gets the largest ``dt / k`` (whole k) within
        0.8 of its limit instead, so no study result comes from an unstable
        integration (the result's ``settings["dt"]`` records the step used).

    Returns
    -------
    list of SimulationResult
    """
    chairs = list(chairs)
    speeds = [float(s) for s in speeds]
    if not chairs:
        return []
    options = dict(options)
    options.setdefault("sample", 0.01)
    dt = options.get("dt", sim.DEFAULTS.dt)
    if options.get("scheme", sim.DEFAULTS.scheme) == "wchair" and isinstance(dt, float):
        limits = stable_steps(chairs, np.asarray(speeds), options.get("model", sim.DEFAULTS.model),
                              options.get("casters", sim.DEFAULTS.casters))
        steps = [dt if dt <= lim else dt / math.ceil(dt / (SAFETY * lim)) for lim in limits]
        if any(h != dt for h in steps):
            return _by_step(chairs, speeds, steps, progress, options)
    return _runs(chairs, speeds, progress, options)


def _by_step(chairs: list[Chair], speeds: list[float], steps: list[float], progress: bool,
             options: dict[str, Any]) -> list:
    """Runs grouped by their time step (one batch per step), returned in the callers' order."""
    forces = options.get("impulse_force", 0.0)
    out: list = [None] * len(chairs)
    for h in sorted(set(steps)):
        idx = [i for i, s in enumerate(steps) if s == h]
        opts = dict(options, dt=h)
        if np.ndim(forces) != 0:
            opts["impulse_force"] = np.asarray(forces)[idx]
        for i, r in zip(idx, _runs([chairs[i] for i in idx], [speeds[i] for i in idx], progress, opts),
                        strict=True):
            out[i] = r
    return out


def _runs(chairs: list[Chair], speeds: list[float], progress: bool, options: dict[str, Any]) -> list:
    if len(chairs) <= SCALAR_RUNS and options.get("scheme", "wchair") == "wchair":
        if np.ndim(options.get("impulse_force", 0.0)) == 0:
            return [sim.simulate(c, s, **options) for c, s in zip(chairs, speeds, strict=True)]
        forces = options.pop("impulse_force")           # one per run (a disturbance map)
        return [sim.simulate(c, s, impulse_force=float(f), **options)
                for c, s, f in zip(chairs, speeds, forces, strict=True)]
    return list(sim.simulate_batch(chairs, speeds, progress=progress, **options))


def sim_options(model: str, scheme: str, impulse: tuple[float, float], dt: float | None, duration: float,
                extra: dict) -> dict:
    """Simulator keywords for a study run.

    Parameters
    ----------
    model : {"exact", "thesis"}
    scheme : {"wchair", "adaptive"}
    impulse : (float, float)
        Push force (N) and duration (s).
    dt : float or None
        Fixed step, s (None: the simulator's default).
    duration : float
        Simulated time, s.
    extra : dict
        More simulator options (override the above).

    Returns
    -------
    dict
        Keywords for :func:`simulate_runs`; ``stop_on_warnings=False`` and
        ``friction_law=``:data:`stability.settings.defaults.MEASURE_FRICTION_LAW`
        ("stick-slip") unless ``extra`` says otherwise.
    """
    force, length = impulse
    opts: dict[str, Any] = dict(model=model, scheme=scheme, impulse_force=float(force),
                                impulse_duration=float(length), duration=float(duration))
    if dt is not None:
        opts["dt"] = float(dt)
    # WCHAIR stops a run at its 11th slip (> 8 deg) or load (> 450 N) warning.  At low speed the
    # disturbance alone pushes the slip angles past 8 deg at once (40 N for 0.1 s gives 0.04 m/s
    # sideways: 11 deg at 0.2 m/s), which says nothing about stability; the studies let runs go on
    # (tire forces clamped at the edge of the data) unless told otherwise.
    opts["stop_on_warnings"] = False
    # The measures ask when a push or a speed first spins the chair, which WCHAIR's kinetic pin friction at 1 ms
    # gets wrong where the caster mode is fast (docs/simulator.md): their runs use the step-converged stick-slip law
    # unless told otherwise (the adaptive scheme has only that law).
    opts["friction_law"] = MEASURE_FRICTION_LAW
    opts.update(extra)
    return opts
