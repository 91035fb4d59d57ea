"""Commanded driving in the nonlinear simulator: yaw-rate steps, ramps, a slalom; torque requirement.

The scheduled controller (:class:`~stability.assist.controller.DigitalController`)
follows a yaw-rate command ``r_cmd(t)`` from the joystick at a constant
forward speed (held by the drive's common-mode torque).  The torque
requirement is the peak and RMS differential wheel torque of these runs and
of the recovery from the reference push, against the traction limit
``mu N r`` of a drive wheel.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validate import check_speed
from ..reference import THESIS_PUSH
from ..simulate import simulate
from ..statics import static_loads
from .controller import TRACKING_TIME, DigitalController
from .schedule import Schedule
from .tracking import TrackingMetrics, step_metrics

__all__ = ["MAX_YAW_RATE", "LATERAL_ACCELERATION", "step_command", "ramp_command", "slalom_command",
           "reference_command", "COMMAND_FILTER", "CommandRun", "command_run", "tracking_step", "traction_limit",
           "TorqueRow", "torque_requirement", "TRACKING_SPEED", "TrackingRuns", "tracking_runs"]

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
        m/s.
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
    result : SimulationResult
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
                anti_windup: str = "back-calculation", tracking_time_s: float = TRACKING_TIME) -> CommandRun:
    """Simulate the scheduled controller following ``command`` (WCHAIR scheme, exact model by default).

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    command : callable
        ``r_cmd(t)`` (rad/s).
    duration : float
        s.
    impulse_force : float
        Lateral push at the c.g. (N, for :data:`~stability.reference.THESIS_PUSH`'s duration).
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

    Returns
    -------
    CommandRun
    """
    speed = check_speed(speed)
    ctl = DigitalController(sched.at(speed), sched.chair, sched.drive, gyro=sched.gyro, seed=seed, noise=noise,
                            saturate=saturate, command=command, command_filter_s=command_filter_s,
                            anti_windup=anti_windup, tracking_time_s=tracking_time_s)
    res = simulate(sched.chair, speed, duration=duration, model=sched.model, dt=dt, impulse_force=impulse_force,
                   impulse_duration=THESIS_PUSH.duration, yaw_moment=ctl, stop_on_warnings=False)
    t = np.asarray(res.t)
    samples = [s for s in ctl.samples if s[0] <= t[-1] + 1e-9]
    tau = np.array([s[1] for s in samples])
    lim = sched.drive.torque_limit
    return CommandRun(speed, t, np.asarray(res.yaw_rate), np.array([command(x) for x in t]),
                      np.asarray(res.heading), tau, np.array([s[0] for s in samples]),
                      float(np.max(np.abs(tau))) if tau.size else 0.0,
                      float(np.sqrt(np.mean(tau ** 2))) if tau.size else 0.0,
                      float(np.mean(np.abs(tau) >= lim * (1 - 1e-9))) if tau.size else 0.0, res)


#: Reference-model time constant of the tracking check (s): no overshoot, ~0.7 s settling (docs/assist.md).
COMMAND_FILTER = 0.2


def tracking_step(sched: Schedule, speed: float, command: float | None = None, *,
                  duration: float = 3.0, command_filter_s: float = COMMAND_FILTER) -> TrackingMetrics:
    """Yaw-rate step in the nonlinear loop (noise-free, saturating): :class:`TrackingMetrics`.

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    command : float, optional
        rad/s (default :func:`reference_command`).
    duration : float
        s.
    command_filter_s : float
        Reference-model time constant (s).

    Returns
    -------
    TrackingMetrics
    """
    c = reference_command(speed) if command is None else float(command)
    run = command_run(sched, speed, step_command(c), duration=duration, command_filter_s=command_filter_s)
    return step_metrics(run.t, run.yaw_rate, run.torque, c)


def traction_limit(sched: Schedule) -> float:
    """Largest wheel torque the drive tire can pass to the floor: ``mu N r`` (N m per wheel, static load).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    float
    """
    n = static_loads(sched.chair)["main"]
    return sched.drive.traction_coefficient * n * sched.drive.wheel_radius


@dataclass(frozen=True)
class TorqueRow:
    """Differential torque per wheel needed at one speed (N m), against the limits.

    Attributes
    ----------
    speed_m_s : float
    push_peak_N_m, push_rms_N_m : float
        Recovery from the reference push (:data:`~stability.reference.THESIS_PUSH`), 2 s, noise-free.
    turn_peak_N_m, turn_rms_N_m : float
        Yaw-rate step :func:`reference_command` through the reference model, 3 s.
    steady_turn_N_m : float
        Torque that holds the commanded turn (last sample of the step).
    motor_limit_N_m, traction_limit_N_m : float
        The drive train's limit and ``mu N r`` at the static drive-wheel load.
    """

    speed_m_s: float
    push_peak_N_m: float
    push_rms_N_m: float
    turn_peak_N_m: float
    turn_rms_N_m: float
    steady_turn_N_m: float
    motor_limit_N_m: float
    traction_limit_N_m: float

    def to_dict(self) -> dict[str, float]:
        """JSON-ready dict."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def torque_requirement(sched: Schedule, speeds: tuple[float, ...] = (0.5, 1.0, 2.0, 3.0)) -> list[TorqueRow]:
    """Peak and RMS differential torque for the reference push and a commanded turn, against speed.

    Parameters
    ----------
    sched : Schedule
    speeds : tuple of float
        m/s.

    Returns
    -------
    list of TorqueRow
    """
    rows = []
    trac = traction_limit(sched)
    for s in speeds:
        push = command_run(sched, s, step_command(0.0), duration=2.0, impulse_force=THESIS_PUSH.force)
        turn = command_run(sched, s, step_command(reference_command(s)), duration=3.0,
                           command_filter_s=COMMAND_FILTER)
        rows.append(TorqueRow(float(s), push.peak_torque_N_m, push.rms_torque_N_m, turn.peak_torque_N_m,
                              turn.rms_torque_N_m, float(turn.torque[-1]), sched.drive.torque_limit, trac))
    return rows


#: Speed of the tracking figure (m/s).
TRACKING_SPEED = 1.0


@dataclass(frozen=True, eq=False)
class TrackingRuns:
    """A yaw-rate step (through the reference model) and a ramp in the nonlinear loop at one speed.

    Attributes
    ----------
    speed_m_s : float
    step, ramp : CommandRun
    step_label, ramp_label : str
        What each command was (for legends).
    torque_limit_N_m : float
        Motor limit per wheel.
    """

    speed_m_s: float
    step: CommandRun
    ramp: CommandRun
    step_label: str
    ramp_label: str
    torque_limit_N_m: float


def tracking_runs(sched: Schedule, speed: float = TRACKING_SPEED, *, ramp_rate: float = 0.4,
                  duration: float = 4.0) -> TrackingRuns:
    """Step :func:`reference_command` (through :data:`COMMAND_FILTER`) and a ramp to it, noise-free.

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    ramp_rate : float
        rad/s^2.
    duration : float
        s.

    Returns
    -------
    TrackingRuns
    """
    c = reference_command(speed)
    step = command_run(sched, speed, step_command(c), duration=duration, command_filter_s=COMMAND_FILTER)
    ramp = command_run(sched, speed, ramp_command(ramp_rate, c), duration=duration)
    return TrackingRuns(float(speed), step, ramp,
                        f"step {c:g} rad/s, {1e3 * COMMAND_FILTER:g} ms reference model",
                        f"ramp {ramp_rate:g} rad/s^2 to {c:g} rad/s", sched.drive.torque_limit)
