"""Joystick yaw-rate commands and one commanded run of the sampled controller in the nonlinear simulator.

The scheduled controller (:class:`~stability.assist.controller.DigitalController`)
follows a yaw-rate command ``r_cmd(t)`` at a constant forward speed (held by the
drive's common-mode torque); see ``docs/assist.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from stability.assist.controller import TRACKING_TIME, DigitalController
from stability.assist.schedule import Schedule
from stability.runtime.checks import check_speed
from stability.settings import defaults as D
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate import simulate

__all__ = ["MAX_YAW_RATE", "LATERAL_ACCELERATION", "step_command", "ramp_command", "slalom_command",
           "reference_command", "COMMAND_FILTER", "CommandRun", "command_run"]

#: Largest yaw-rate command of the joystick (rad/s; ~46 deg/s, a common power-chair setting).
MAX_YAW_RATE = 0.8
#: Lateral acceleration of the reference turn (m/s^2): the command is min(MAX_YAW_RATE, a / U).
LATERAL_ACCELERATION = 1.0


def reference_command(speed: float) -> float:
    """Yaw-rate step of the tracking check at ``speed``: ``min(MAX_YAW_RATE, LATERAL_ACCELERATION / U)`` (rad/s).

    Parameters
    ----------
    speed : float
        m/s.

    Returns
    -------
    float
    """
    return min(MAX_YAW_RATE, LATERAL_ACCELERATION / check_speed(speed))


def step_command(size: float, t0: float = 0.0) -> Callable[[float], float]:
    """``r_cmd(t) = size`` from ``t0`` (rad/s).

    Parameters
    ----------
    size : float
        rad/s.
    t0 : float
        s.

    Returns
    -------
    callable
    """
    return lambda t: size if t >= t0 else 0.0


def ramp_command(rate: float, top: float) -> Callable[[float], float]:
    """``r_cmd(t) = min(rate t, top)`` (rad/s; ``rate`` in rad/s^2).

    Parameters
    ----------
    rate, top : float

    Returns
    -------
    callable
    """
    return lambda t: math.copysign(min(abs(rate) * t, abs(top)), top)


def slalom_command(amplitude: float, period: float) -> Callable[[float], float]:
    """``r_cmd(t) = amplitude sin(2 pi t / period)`` (rad/s).

    Parameters
    ----------
    amplitude : float
        rad/s.
    period : float
        s.

    Returns
    -------
    callable
    """
    return lambda t: amplitude * math.sin(2.0 * math.pi * t / period)


@dataclass(frozen=True, eq=False)
class CommandRun:
    """One commanded run in the nonlinear simulator.

    Attributes
    ----------
    speed : float
        m/s (signed for a wheel layout's schedule: negative in reverse).
    t, yaw_rate, command, heading : ndarray
        s, rad/s, rad/s, rad.
    torque : ndarray
        Commanded differential torque per wheel at the samples (N m).
    torque_t : ndarray
        Times of those samples (s; each value is held until the next).
    peak_torque_N_m, rms_torque_N_m : float
        Of ``torque``.
    saturated_fraction : float
        Share of samples at the torque limit.
    result : SimulationResult or LayoutRun
        The simulator's run (a wheel layout's: :class:`stability.simulate.layout.LayoutRun`).
    """

    speed: float
    t: np.ndarray
    yaw_rate: np.ndarray
    command: np.ndarray
    heading: np.ndarray
    torque: np.ndarray
    torque_t: np.ndarray
    peak_torque_N_m: float
    rms_torque_N_m: float
    saturated_fraction: float
    result: Any


def command_run(sched: Schedule, speed: float, command: Callable[[float], float], *, duration: float = 4.0,
                impulse_force: float = 0.0, noise: bool = False, seed: int = 0, saturate: bool = True,
                dt: float | str = "auto", command_filter_s: float = 0.0,
                anti_windup: str = "back-calculation", tracking_time_s: float = TRACKING_TIME,
                slope: tuple[float, float] = (0.0, 0.0), model: str | None = None,
                assisted: bool = True) -> CommandRun:
    """Simulate the scheduled controller following ``command`` (WCHAIR scheme, the schedule's model by default).

    A wheel layout's schedule (:class:`stability.assist.layout.LayoutSchedule`, signed speeds: negative in reverse)
    runs in the layout simulator (:func:`stability.assist.layout_command.layout_command_result`, exact model, the
    casters starting trailing the direction of travel, every step recorded); ``model`` must then be None or
    ``"exact"``.  Unassisted (``assisted=False``) the same controller runs with its feedback gains zeroed: the
    joystick's command through the reference model times the linear model's steady-turn moment
    (:func:`~stability.assist.tracking.feedforward`), saturated and lagged as the assisted one's, no gyro feedback.

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s (a layout's schedule: signed, the direction of its grid).
    command : callable
        ``r_cmd(t)`` (rad/s).
    duration : float
        s.
    impulse_force : float
        Lateral push at the c.g. (N, for :data:`~stability.settings.reference.THESIS_PUSH`'s duration).
    noise : bool
        Gyro noise and bias.
    seed : int
        Seed of the gyro noise.
    saturate : bool
        Limit the torque at the drive train's limit.
    dt : float or "auto"
        Step of the WCHAIR scheme (s); ``"auto"``: 1 ms, or 1 ms / k below
        the speed where the tire modes (``-C/(m U)``) need a smaller step
        (about 0.3 m/s for the preset).
    command_filter_s : float
        Reference-model time constant (s).
    anti_windup : str
        Integrator protection (:data:`~stability.assist.controller.ANTI_WINDUP`).
    tracking_time_s : float
        Back-calculation time constant (s).
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)`` of the simulator (deg; a slope needs the exact model).
    model : str, optional
        Equations of motion of the simulator (default the schedule's).
    assisted : bool
        False: the feedback gains zeroed (the command fed forward only, the chair on its own).

    Returns
    -------
    CommandRun
    """
    layout = getattr(sched, "layout", None)
    if layout is not None and model not in (None, "exact"):
        raise ValueError(f"model={model!r} is invalid for a wheel layout; valid values: None, 'exact' (a layout's "
                         "equations are derived from first principles only)")
    speed = float(sched._check_speed(speed)) if layout is not None else check_speed(speed)
    d = sched.at(speed)
    if not assisted:
        d = replace(d, K=np.zeros_like(d.K))
        anti_windup = "none"                 # no heading-error gain to wind back through
    ctl = DigitalController(d, sched.chair, sched.drive, gyro=sched.gyro, seed=seed, noise=noise,
                            saturate=saturate, command=command, command_filter_s=command_filter_s,
                            anti_windup=anti_windup, tracking_time_s=tracking_time_s)
    if layout is not None:
        from stability.assist.layout_command import layout_command_result

        t, yaw, head, res = layout_command_result(sched, speed, ctl, duration=duration,
                                                  impulse_force=impulse_force, dt=dt, slope=slope)
    else:
        res = simulate(sched.chair, speed, RunSpec(horizon=duration, model=model or sched.model, dt=dt,
                                                   push_force=impulse_force, push_duration=THESIS_PUSH.duration,
                                                   stop_on_warnings=False, cross_slope_deg=slope[0],
                                                   grade_deg=slope[1]),
                       yaw_moment=ctl)
        t, yaw, head = np.asarray(res.t), np.asarray(res.yaw_rate), np.asarray(res.heading)
    samples = [s for s in ctl.samples if s[0] <= t[-1] + 1e-9]
    tau = np.array([s[1] for s in samples])
    lim = sched.drive.torque_limit
    return CommandRun(speed, t, yaw, np.array([command(x) for x in t]), head, tau, np.array([s[0] for s in samples]),
                      float(np.max(np.abs(tau))) if tau.size else 0.0,
                      float(np.sqrt(np.mean(tau ** 2))) if tau.size else 0.0,
                      float(np.mean(np.abs(tau) >= lim * (1 - 1e-9))) if tau.size else 0.0, res)


#: Reference-model time constant of the tracking check (s): no overshoot, ~0.7 s settling (docs/assist.md).
COMMAND_FILTER = D.COMMAND_FILTER
