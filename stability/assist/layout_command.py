"""A commanded run of a wheel layout: the short form's yaw-rate commands in the layout simulator, both directions.

:func:`stability.assist.commands.command_run` hands a layout's schedule
(:class:`stability.assist.layout.LayoutSchedule`, signed speeds) to :func:`layout_command_run`: the same sampled
controller (:class:`~stability.assist.controller.DigitalController`: the yaw-rate command through its reference
model, the heading-error integrator, the estimator, the feedforward of the steady turn, saturation and the motor
lag) is the ``yaw_moment`` hook of the layout simulator
(:func:`stability.simulate.layout_batch.simulate_layout_batch`, one run; the casters start trailing the direction
of travel, :func:`stability.study.layout_impulse.trailing_angles`).  The full-state design reads the layout's states
(``v, r`` and each caster's angle from its trailing angle, 0 deg forward and 180 deg in reverse, and rate).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.assist.controller import DigitalController
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec

__all__ = ["LayoutReading", "layout_command_result"]


class LayoutReading:
    """What the controller reads of one layout run at a step: ``yaw_rate`` (rad/s), ``v`` (m/s) and the layout's
    chair states ``chair_states`` (``v, r``, then per caster its angle from its trailing angle and its rate: the
    layout's linear model's order, :func:`stability.layout.linear.states`).

    Parameters
    ----------
    state : stability.simulate.layout_batch.LayoutState
        The batch's state (one run).
    trail : float
        The casters' trailing angle, rad (0 forward, pi in reverse).
    """

    __slots__ = ("_state", "_trail")

    def __init__(self, state: Any, trail: float) -> None:
        # read when the controller asks (at its samples, one step in several): the batch's arrays are its own
        self._state, self._trail = state, trail

    @property
    def yaw_rate(self) -> float:
        """rad/s."""
        return float(self._state.yaw_rate[0])

    @property
    def v(self) -> float:
        """m/s."""
        return float(self._state.v[0])

    @property
    def chair_states(self) -> list[float]:
        """``v, r``, then per caster its angle from its trailing angle (rad) and its rate (rad/s)."""
        deltas = np.asarray(self._state.delta, dtype=float)[:, 0] - self._trail
        rates = np.asarray(self._state.delta_rate, dtype=float)[:, 0]
        return [self.v, self.yaw_rate] + [x for pair in zip(deltas, rates, strict=True) for x in pair]


def layout_command_result(sched: Any, speed: float, ctl: DigitalController, *,
                          duration: float, impulse_force: float, dt: float | str,
                          slope: tuple[float, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray, Any]:
    """One commanded run of a layout schedule's controller in the layout simulator.

    Parameters
    ----------
    sched : stability.assist.layout.LayoutSchedule
    speed : float
        Signed speed, m/s (the direction of the schedule's grid).
    ctl : DigitalController
        The controller, with its yaw-rate command ``r_cmd(t)`` (rad/s, clockwise + in either direction of travel;
        None: straight).
    duration, impulse_force : float
        s; N for :data:`~stability.settings.reference.THESIS_PUSH`'s duration.
    dt : float or "auto"
        Step, s (``"auto"``: 1 ms).
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)``.

    Returns
    -------
    tuple
        Times (s), yaw rate (rad/s), heading (rad) of the recorded rows (every step) and the
        :class:`~stability.simulate.layout.LayoutRun`.
    """
    from stability.simulate.layout_batch import simulate_layout_batch
    from stability.study.layout_impulse import trailing_angles

    layout = sched.layout
    u = sched._check_speed(speed)
    step = 0.001 if dt == "auto" else float(dt)
    spec = RunSpec(horizon=duration, model="exact", dt=step, sample=step, push_force=impulse_force,
                   push_duration=THESIS_PUSH.duration, stop_on_warnings=False, cross_slope_deg=slope[0],
                   grade_deg=slope[1])
    trail = math.pi if u < 0 else 0.0

    def hook(t: float, state: Any) -> np.ndarray:
        return np.array([ctl(t, LayoutReading(state, trail))])

    (run,) = simulate_layout_batch(layout, [u], spec, yaw_moment=hook,
                                   caster_angles_deg=[trailing_angles(layout, u)])
    return np.asarray(run.t_s), np.asarray(run.yaw_rate_rad_s), np.asarray(run.heading_rad), run
