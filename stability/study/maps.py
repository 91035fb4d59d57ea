"""Stability maps: the criterion's time over speed x pin friction, and over speed x push size (one batch each)."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.settings.reference import REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion, check_impulse
from stability.study.equal_instability import interp_speed, reference_time

__all__ = ["StabilityMap", "stability_map", "disturbance_map"]


@dataclass(frozen=True, eq=False)
class StabilityMap:
    """The criterion's time over a grid of speed x a second variable.

    Attributes
    ----------
    chair : Chair
    speeds : numpy.ndarray
        m/s.
    y_name, y_label, y_unit : str
        The second variable.
    y_values : numpy.ndarray
    times : numpy.ndarray
        ``times[j, i]``: time (s) to the yaw-rate level at ``speeds[i]`` and
        ``y_values[j]`` (+inf: never within ``criterion.duration``).
    reference_time : float
        s.
    criterion : Criterion
    model, scheme : str
    impulse : (float, float)
        The first row's push: force (N), duration (s).
    """

    chair: Chair
    speeds: np.ndarray
    y_name: str
    y_label: str
    y_unit: str
    y_values: np.ndarray
    times: np.ndarray
    reference_time: float
    criterion: Criterion
    model: str
    scheme: str
    impulse: tuple

    def boundary(self) -> np.ndarray:
        """Equal-instability speed for each ``y_values`` row (m/s; nan if not crossed), interpolated."""
        out = np.full(len(self.y_values), np.nan)
        for j, row in enumerate(self.times):
            k = np.flatnonzero(row <= self.reference_time)
            if len(k) == 0 or k[0] == 0:
                continue
            i = int(k[0])
            out[j] = interp_speed(self.speeds[i - 1], row[i - 1], self.speeds[i], row[i], self.reference_time)
        return out


def _map(chair: Chair, speeds: Any, y_name: str, y_label: str, y_unit: str, y_values: Any,
         make_chair: Callable[[float], Chair], impulses: Callable[[float], tuple[float, float]], run: RunSpec, *,
         criterion: Criterion, reference: float, progress: bool) -> StabilityMap:
    speeds = np.asarray(speeds, dtype=float)
    yv = np.asarray(y_values, dtype=float)
    run_chairs, run_speeds, run_force = [], [], []
    for y in yv:
        c = make_chair(y)
        f = impulses(y)
        for s in speeds:
            run_chairs.append(c)
            run_speeds.append(float(s))
            run_force.append(f)
    forces = np.array([f[0] for f in run_force])
    length = run_force[0][1]
    # one batch for the whole map: the chair and the push force may differ from run to run
    spec = runs.study_run(run).replace(push_duration=float(length), horizon=criterion.duration)
    results = runs.simulate_runs(run_chairs, run_speeds, spec, progress=progress,
                                 push_forces=forces if np.any(forces != forces[0]) else None)
    times = np.array([criterion.time(r) for r in results]).reshape(len(yv), len(speeds))
    return StabilityMap(chair, speeds, y_name, y_label, y_unit, yv, times, float(reference), criterion,
                        spec.model, spec.scheme, (float(forces[0]), float(length)))


@takes_chair
def stability_map(chair: Chair, speeds: Sequence[float] | None = None, frictions: Sequence[float] | None = None,
                  run: RunSpec | None = None, *, criterion: Criterion = DEFAULT_CRITERION,
                  reference: float | None = None, progress: bool = True) -> StabilityMap:
    """Time to the yaw-rate level over speed x pin friction (both pins), one batch of simulations.

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float, optional
        m/s (default 0.3-2.0 in 18 steps).
    frictions : sequence of float, optional
        Pin friction M_f of both pins, N m (default 0-0.3 in 13 steps).
    run : RunSpec, optional
        The runs' settings (the push, model, scheme, step, pin-friction law; the thesis's maps use
        ``model="thesis"``); the horizon is the criterion's.
    criterion, progress
        As in :func:`stability.study.yaw_rate_responses`.
    reference : float, optional
        The reference case's time, s (computed with :func:`reference_time` when None).

    Returns
    -------
    StabilityMap
    """
    run = runs.study_run(run)
    impulse = check_impulse(run.push.as_tuple)
    speeds_: Any = np.linspace(0.3, 2.0, 18) if speeds is None else speeds
    frictions_: Any = np.linspace(0.0, 0.3, 13) if frictions is None else frictions
    if reference is None:
        reference = reference_time(None, REFERENCE_SPEED, run, criterion=criterion)
    return _map(chair, speeds_, "pin_friction", "pin friction M_f (both pins)", "N m", frictions_,
                lambda f: chair.replace(pin_friction_left=float(f), pin_friction_right=float(f)),
                lambda f: impulse, run, criterion=criterion, reference=reference, progress=progress)


@takes_chair
def disturbance_map(chair: Chair, speeds: Sequence[float] | None = None, impulses: Sequence[float] | None = None,
                    run: RunSpec | None = None, *, criterion: Criterion = DEFAULT_CRITERION,
                    reference: float | None = None, progress: bool = True) -> StabilityMap:
    """Time to the yaw-rate level over speed x push size (lateral impulse at the c.g.), one batch.

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float, optional
        m/s (default 0.3-2.0 in 18 steps).
    impulses : sequence of float, optional
        N s (default 1-10 in 10 steps): a force of ``impulse / run.push_duration``
        N for ``run.push_duration`` s.
    run : RunSpec, optional
        The runs' settings (push duration, model, scheme, step, pin-friction law); the horizon is the
        criterion's.
    criterion, progress
        As in :func:`stability.study.yaw_rate_responses`.
    reference : float, optional
        The reference case's time under the run's push, s (computed when None).

    Returns
    -------
    StabilityMap
    """
    run = runs.study_run(run)
    impulse_duration = run.push_duration
    speeds_: Any = np.linspace(0.3, 2.0, 18) if speeds is None else speeds
    impulses_: Any = np.linspace(1.0, 10.0, 10) if impulses is None else impulses
    if reference is None:
        reference = reference_time(None, REFERENCE_SPEED, run, criterion=criterion)
    return _map(chair, speeds_, "impulse", "lateral impulse at the c.g.", "N s", impulses_,
                lambda j: chair, lambda j: (float(j) / impulse_duration, impulse_duration), run,
                criterion=criterion, reference=reference, progress=progress)
