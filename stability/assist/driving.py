"""Commanded driving in the nonlinear simulator: yaw-rate steps, ramps, torque requirement, cross slope.

The commands and one commanded run are in :mod:`.commands` (re-exported here).
The torque requirement is the peak and RMS differential wheel torque of these
runs and of the recovery from the reference push, against the traction limit
``mu N r`` of a drive wheel; :func:`slope_hold` checks the assist holding a
straight line along a cross slope against the statics of
:mod:`stability.slope.equilibrium`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.assist.commands import (
    COMMAND_FILTER,
    LATERAL_ACCELERATION,
    MAX_YAW_RATE,
    CommandRun,
    command_run,
    ramp_command,
    reference_command,
    slalom_command,
    step_command,
)
from stability.assist.controller import DigitalController
from stability.assist.schedule import Schedule
from stability.assist.tracking import TrackingMetrics, step_metrics
from stability.models.statics import static_loads
from stability.runtime.checks import check_speed
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.slope import equilibrium
from stability.study.veer import MAX_CASTER_SWING_DEG

__all__ = ["MAX_YAW_RATE", "LATERAL_ACCELERATION", "step_command", "ramp_command", "slalom_command",
           "reference_command", "COMMAND_FILTER", "CommandRun", "command_run", "tracking_step", "traction_limit",
           "TorqueRow", "torque_requirement", "TRACKING_SPEED", "TrackingRuns", "tracking_runs",
           "CROSS_SLOPES", "HOLD_TOLERANCE", "SlopeHold", "slope_hold"]


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

    A wheel layout's schedule: the less loaded drive wheel's, in the direction of its grid
    (:func:`stability.assist.layout_checks.layout_traction_limit`).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    float
    """
    layout = getattr(sched, "layout", None)
    if layout is not None:
        from stability.assist.layout_checks import layout_traction_limit

        return layout_traction_limit(layout, sched.drive, bool(sched.speeds[0] < 0))
    n = static_loads(sched.chair)["main"]
    return sched.drive.traction_coefficient * n * sched.drive.wheel_radius


@dataclass(frozen=True)
class TorqueRow:
    """Differential torque per wheel needed at one speed (N m), against the limits.

    Attributes
    ----------
    speed_m_s : float
    push_peak_N_m, push_rms_N_m : float
        Recovery from the reference push (:data:`~stability.settings.reference.THESIS_PUSH`), 2 s, noise-free.
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

    A wheel layout's schedule runs in the layout simulator (:func:`~stability.assist.commands.command_run`), at
    signed speeds (negative in reverse: the turn's command is that of the speed's magnitude).

    Parameters
    ----------
    sched : Schedule
    speeds : tuple of float
        m/s (signed for a layout's schedule).

    Returns
    -------
    list of TorqueRow
    """
    rows = []
    trac = traction_limit(sched)
    for s in speeds:
        push = command_run(sched, s, step_command(0.0), duration=2.0, impulse_force=THESIS_PUSH.force)
        turn = command_run(sched, s, step_command(reference_command(abs(s))), duration=3.0,
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


#: Cross slopes of the closed-loop check (deg, falling to the right).
CROSS_SLOPES = (2.0, 4.0)
#: Stated agreement of the closed loop's steady torque with the statics' holding torque (relative; docs/assist.md).
HOLD_TOLERANCE = 0.01


@dataclass(frozen=True, eq=False)
class SlopeHold:
    """Straight command along a cross slope, with and without the assist (nonlinear, exact model).

    Attributes
    ----------
    speed_m_s, cross_slope_deg, duration_s : float
        Initial speed (the chair coasts), cross slope (falling to the right +) and run length.
    closed, open_t, open_heading : CommandRun, ndarray, ndarray
        The closed-loop run; the open-loop time (s) and heading (rad) up to its end.
    closed_heading_deg, closed_offset_m : float
        Closed loop at the end: heading (deg, clockwise = to the right +) and lateral offset of the c.g. (m).
    open_heading_deg, open_end_s : float
        Open loop: heading at the end of its run (deg) and that time (s): ``duration_s``, or where the
        heading passes 45 deg or a caster swings 30 deg (beyond the tire data).
    open_turn : str
        ``"uphill"`` or ``"downhill"``.
    crab_deg : float
        Heading from the path of the statics' equilibrium (deg).
    hold_heading_deg : float
        The loop's predicted settled heading from its start (deg):
        :meth:`~stability.assist.controller.DigitalController.holding_heading` of the statics' frictionless
        holding moment (the full-state design measures the statics' states, its lateral velocity
        ``-u tan(crab)`` at the run's final forward speed ``u``: the simulator coasts).  The loop holds the
        integral of the gyro, not the path, so its course ends ``hold_heading_deg - crab_deg`` from the start
        line (:attr:`course_deg`); without pin friction the run settles on it.
    steady_torque_N_m, peak_torque_N_m : float
        Commanded differential torque per wheel: mean over the last second, and peak (N m).
    holding_torque_N_m : float
        The statics' frictionless holding moment as wheel torque, ``DriveTrain.wheel_torque`` (N m).
    holding_band_N_m : tuple of float
        The same over the equilibria allowed by the chair's Coulomb pin friction (N m).
    relative_error : float
        ``steady / holding - 1``.
    motor_limit_N_m, traction_limit_N_m : float
        Motor limit; ``mu N r`` at the lighter drive wheel on the slope.
    friction_use : float
        Largest ``|(F_x, F_y)| / (mu N)`` of the drive wheels at the equilibrium.
    """

    speed_m_s: float
    cross_slope_deg: float
    duration_s: float
    closed: CommandRun
    open_t: np.ndarray
    open_heading: np.ndarray
    closed_heading_deg: float
    closed_offset_m: float
    open_heading_deg: float
    open_end_s: float
    open_turn: str
    crab_deg: float
    hold_heading_deg: float
    steady_torque_N_m: float
    peak_torque_N_m: float
    holding_torque_N_m: float
    holding_band_N_m: tuple[float, float]
    relative_error: float
    motor_limit_N_m: float
    traction_limit_N_m: float
    friction_use: float

    @property
    def harder_side(self) -> str:
        """Which drive wheel the assist loads more to hold the line, ``"uphill"`` or ``"downhill"``.

        The steady torque is the differential ``(left - right)/2`` per wheel, so right minus left is
        ``-2 x steady``; :func:`stability.slope.equilibrium.harder_side` names the side (the statics give
        the same side through ``holding_torque_N_m``; the tests check that all three paths agree).
        """
        return equilibrium.harder_side(-2.0 * self.steady_torque_N_m, self.cross_slope_deg)

    @property
    def course_deg(self) -> float:
        """Predicted course of the settled loop from the start line (deg, clockwise +): its heading minus the
        statics' crab angle, ``hold_heading_deg - crab_deg``; the c.g. drifts sideways at ``u sin(course)``."""
        return self.hold_heading_deg - self.crab_deg

    @property
    def within_limits(self) -> bool:
        """Peak torque within the motor and traction limits and the drive tires below full friction."""
        return self.peak_torque_N_m <= min(self.motor_limit_N_m, self.traction_limit_N_m) and self.friction_use < 1

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no time histories)."""
        skip = {"closed", "open_t", "open_heading"}
        d: dict[str, Any] = {k: getattr(self, k) for k in self.__dataclass_fields__ if k not in skip}
        d["holding_band_N_m"] = list(self.holding_band_N_m)
        d["within_limits"] = self.within_limits
        d["harder_side"] = self.harder_side
        d["course_deg"] = self.course_deg
        return d


def slope_hold(sched: Schedule, speed: float, cross_slope_deg: float, *, duration: float = 10.0,
               window: float = 1.0) -> SlopeHold:
    """Straight joystick command along a cross slope: the assist against the open loop and the statics.

    Both runs start straight (no crab, casters trailing) on the slope, noise-free, with the chair's pin
    friction, exact model (the simulator's only model on a slope), WCHAIR scheme.  In steady state the
    closed loop is the statics of :func:`stability.slope.equilibrium.solve` (no yaw rate, casters still),
    so its torque is the holding moment's (within :data:`HOLD_TOLERANCE`).

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    cross_slope_deg : float
        Falling to the right + (deg).
    duration : float
        s.
    window : float
        Averaging window at the end for the steady torque (s).

    Returns
    -------
    SlopeHold

    Raises
    ------
    ValueError
        No equilibrium inside the tire data on this slope (the message names the slope and the valid range).
    """
    speed = check_speed(speed)
    slope = (float(cross_slope_deg), 0.0)
    eq = equilibrium.solve(sched.chair, slope[0], speed)
    run = command_run(sched, speed, step_command(0.0), duration=duration, slope=slope, model="exact")
    ol = simulate(sched.chair, speed, RunSpec(horizon=duration, model="exact", push_force=0.0, cross_slope_deg=slope[0],
                                              grade_deg=slope[1], stop_on_warnings=False))
    cut = np.flatnonzero((np.abs(ol.heading) > math.radians(45.0)) | (np.maximum(np.abs(ol.eta), np.abs(ol.beta))
                                                                      > math.radians(MAX_CASTER_SWING_DEG)))
    n = int(cut[0]) + 1 if cut.size else len(ol.t)
    side = math.copysign(1.0, slope[0])
    crab = math.radians(eq.heading_deg)
    ctl = DigitalController(sched.at(speed), sched.chair, sched.drive, gyro=sched.gyro, noise=False)
    states = (-float(run.result.u[-1]) * math.tan(crab), 0.0, math.radians(eq.eta_deg), 0.0,
              math.radians(eq.beta_deg), 0.0)
    held = math.degrees(ctl.holding_heading(eq.holding_moment, states if sched.kind == "full-state" else None))
    tail = run.torque[run.torque_t >= run.torque_t[-1] - window]
    steady = float(np.mean(tail))
    wt = sched.drive.wheel_torque
    hold = float(wt(sched.chair, eq.holding_moment))
    mu, r = sched.drive.traction_coefficient, sched.drive.wheel_radius
    use = max(math.hypot(fx, fy) / (mu * nz) for fx, fy, nz in zip(eq.drive_forces, eq.lateral_forces[2:],
                                                                    eq.loads[2:], strict=True))
    return SlopeHold(speed, slope[0], float(duration), run, np.asarray(ol.t[:n]), np.asarray(ol.heading[:n]),
                     math.degrees(run.heading[-1]), float(run.result.y[-1]), math.degrees(ol.heading[n - 1]),
                     float(ol.t[n - 1]), "downhill" if ol.heading[n - 1] * side > 0 else "uphill", eq.heading_deg,
                     held, steady, run.peak_torque_N_m, hold,
                     (float(wt(sched.chair, eq.friction_range[0])), float(wt(sched.chair, eq.friction_range[1]))),
                     steady / hold - 1.0, sched.drive.torque_limit, mu * min(eq.loads[2:]) * r, use)
