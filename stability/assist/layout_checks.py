"""The nonlinear checks of a layout's assist: the closed loop simulated with the layout simulator.

The controller is the design's sampled one (:func:`stability.assist.digital.discrete_controller`: the exact
discretisation of the estimator for held inputs, the heading as the running sum of the gyro, one sample of
computation delay), the one whose margins :mod:`stability.assist.layout` prints.  The layout simulator runs it
compiled (:class:`stability.simulate.controller.SampledController` in
:func:`stability.simulate.layout.simulate_layout`): at each sample it reads the gyro (the gyro design) or the
layout's states (the full-state design, the caster angles from their trailing angle, 0 or 180 deg), commands a
yaw moment, saturated at the drive wheels' torque limit
(``tau_max w / r``, ``w`` the design's drive lever, :func:`stability.assist.layout.drive_lever`) and held until
the next sample, and the estimator
is driven by the saturated command (no wind-up); the motors apply it through the drive train's first-order lag.
The full-state design measures the applied moment of the motor lag, which the simulator does not give the
controller: with a motor lag it is refused (use the gyro design).

- :func:`layout_recovery`: after a push, closed loop against open loop: the peak heading error, the peak and RMS
  differential torque per wheel, the share of samples at the torque limit, whether it returns to a straight line;
- :func:`layout_decay_agreement`: the short form's check that the linear closed loop predicts the nonlinear
  decay (pin friction removed, a tenth of the reference push, sampled every 1 ms step, no saturation reached;
  :func:`stability.assist.recovery.decay_window` and :func:`~stability.assist.recovery.fit_decay_rate`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import control
import numpy as np

from stability.assist.commands import COMMAND_FILTER
from stability.assist.design import Design, closed_loop_poles
from stability.assist.digital import discrete_controller
from stability.assist.recovery import CHECK_SPEEDS, DecayAgreement, decay_window, fit_decay_rate
from stability.assist.tracking import closed_loop
from stability.chair.power import DriveTrain
from stability.layout.model import Layout
from stability.settings.defaults import STEADY_YAW_RATE
from stability.settings.reference import HORIZON, LEVEL, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate.controller import SampledController
from stability.simulate.layout import LayoutRun, layout_state_order, simulate_layout
from stability.simulate.signals import time_to_level
from stability.study.layout_impulse import trailing_angles

__all__ = ["layout_controller", "LayoutRecovery", "layout_recovery", "layout_decay_agreement", "TORQUE_WINDOW_S",
           "CHECK_SPEEDS", "check_speeds", "layout_traction_limit", "LayoutChecks", "layout_checks",
           "layout_minimum_torque_limit", "layout_vector_loop"]

#: The window of the peak and RMS torque after the push, s (the short form's push recovery window).
TORQUE_WINDOW_S = 2.0


def layout_controller(d: Design, layout: Layout, drive: DriveTrain, *, sample_time: float | None = None,
                      saturate: bool = True) -> SampledController:
    """The design's sampled controller for the layout simulator.

    Parameters
    ----------
    d : Design
        From :func:`stability.assist.layout.layout_design` (the sign of ``d.speed`` is the direction).
    layout : Layout
    drive : DriveTrain
        The torque limit (with ``saturate``).
    sample_time : float, optional
        s (default the design's).
    saturate : bool
        Limit the yaw moment at ``drive.torque_limit`` per wheel.

    Returns
    -------
    SampledController
        Measuring the yaw rate (gyro design) or the layout's states (full-state).
    """
    T = float(d.sample_time if sample_time is None else sample_time)
    p = d.plant
    if d.kind == "full-state" and p.n != len(p.internal) + 1:
        raise ValueError(f"design={d.kind!r} with a motor lag is invalid for the layout simulator (the full-state "
                         "design measures the motor's applied moment, which the simulator does not give the "
                         "controller); valid: design 'gyro', or the full-state design with no motor lag")
    cd = discrete_controller(d, T)
    A, B, C = (np.asarray(x, dtype=float) for x in (cd.A, cd.B, cd.C))
    # the command's part of the update, A = A0 - G C: fed by the saturated command instead (no wind-up)
    d0 = dataclasses.replace(d, K=np.zeros_like(d.K))
    A0 = np.asarray(discrete_controller(d0, T).A, dtype=float)
    cc = float((C @ C.T)[0, 0])
    G = ((A0 - A) @ C.T / cc).reshape(-1) if cc > 0 else np.zeros(A.shape[0])
    order = layout_state_order(layout)
    names = ["r"] if d.kind == "gyro" else [p.states[i] for i in p.internal]
    kernel = {"v": "v", "r": "yaw_rate", **{f"delta_{k}": f"delta_{k}" for k in range(len(layout.casters))},
              **{f"delta_d_{k}": f"delta_d_{k}" for k in range(len(layout.casters))}}
    Cy = np.zeros((len(names), len(order)))
    offset = np.zeros(len(names))
    for i, n in enumerate(names):
        Cy[i, order.index(kernel[n])] = 1.0
        if n.startswith("delta_") and not n.startswith("delta_d_") and d.speed < 0:
            offset[i] = -math.pi                 # the caster angle from its reversing trail
    lim = drive.torque_limit * d.track_width / drive.wheel_radius if saturate else math.inf
    return SampledController(T, Cy, np.zeros(len(names)), Az=A0, Bu=G, By=B, Cz=-C.reshape(-1), limit=lim,
                             offset=offset, name=f"{d.kind} assist designed at {d.speed:g} m/s",
                             state_names=order)


@dataclass(frozen=True)
class LayoutRecovery:
    """A push, closed loop and open loop.

    Attributes
    ----------
    speed_m_s, push_N : float
        Signed speed (m/s) and the push's force (N, for the reference push's 0.1 s).
    peak_heading_error_deg, final_heading_deg : float
        Closed loop, deg.
    final_yaw_rate_rad_s : float
        Closed loop, the mean over the last second, rad/s.
    straight : bool
        Closed loop: the mean yaw rate over the last second is below the report's steady-turn level (0.01 rad/s)
        and the run reached its horizon.
    peak_torque_N_m, rms_torque_N_m : float
        Differential torque per drive wheel over the first :data:`TORQUE_WINDOW_S` s, N m.
    saturated_fraction : float
        Share of the rows at the torque limit.
    open_time_to_level_s : float or None
        Open loop: when ``|yaw rate|`` reaches 1 rad/s (None: never within the run).
    open_final_heading_deg : float
        Open loop, deg.
    closed, opened : LayoutRun
    """

    speed_m_s: float
    push_N: float
    peak_heading_error_deg: float
    final_heading_deg: float
    final_yaw_rate_rad_s: float
    straight: bool
    peak_torque_N_m: float
    rms_torque_N_m: float
    saturated_fraction: float
    open_time_to_level_s: float | None
    open_final_heading_deg: float
    closed: Any = None
    opened: Any = None

    def to_mapping(self) -> dict:
        """JSON-ready dict (unit last)."""
        return {k: v for k, v in dataclasses.asdict(self).items() if k not in ("closed", "opened")}

    def text(self) -> str:
        """One line."""
        way = "backwards" if self.speed_m_s < 0 else "forwards"
        opened = ("spins up to 1 rad/s at " + f"{self.open_time_to_level_s:.2f} s" if self.open_time_to_level_s
                  is not None else f"ends {self.open_final_heading_deg:+.0f} deg off its heading")
        return (f"{abs(self.speed_m_s):g} m/s {way}, {self.push_N:g} N x {THESIS_PUSH.duration:g} s: assisted, peak "
                f"heading error {self.peak_heading_error_deg:.2f} deg, "
                + ("back to a straight line" if self.straight else
                   f"still turning at {self.final_yaw_rate_rad_s:+.3f} rad/s") +
                f"; torque per wheel peak {self.peak_torque_N_m:.1f} N m, RMS {self.rms_torque_N_m:.1f} N m "
                f"(first {TORQUE_WINDOW_S:g} s; {100 * self.saturated_fraction:.0f} % of the time at the limit); "
                f"unassisted it {opened}")


def _run(layout: Layout, speed: float, push: float, duration: float, controller: Any, lag: float) -> LayoutRun:
    run = RunSpec(horizon=duration, push_force=push, push_duration=THESIS_PUSH.duration, stop_on_warnings=False)
    return simulate_layout(layout, speed, run, caster_angles_deg=trailing_angles(layout, speed),
                           controller=controller, motor_lag_s=lag)


def layout_recovery(layout: Layout, d: Design, drive: DriveTrain, *, push: float = THESIS_PUSH.force,
                    duration: float = HORIZON) -> LayoutRecovery:
    """Closed- and open-loop runs after a push at the design's speed.

    Parameters
    ----------
    layout : Layout
    d : Design
        At the run's signed speed.
    drive : DriveTrain
        Radius, torque limit, motor lag.
    push : float
        N, for :data:`~stability.settings.reference.THESIS_PUSH`'s duration.
    duration : float
        s.

    Returns
    -------
    LayoutRecovery
    """
    speed = float(d.speed)
    ctl = layout_controller(d, layout, drive)
    closed = _run(layout, speed, push, duration, ctl, drive.motor_time_constant)
    opened = _run(layout, speed, push, duration, None, 0.0)
    t = np.asarray(closed.t_s)
    head = np.degrees(np.asarray(closed.heading_rad))
    last = t >= t[-1] - 1.0
    final_rate = float(np.mean(np.asarray(closed.yaw_rate_rad_s)[last]))
    per_wheel = np.abs(np.asarray(closed.yaw_moment_N_m)) * drive.wheel_radius / d.track_width
    win = t <= THESIS_PUSH.duration + TORQUE_WINDOW_S
    tl = time_to_level(np.asarray(opened.t_s), np.asarray(opened.yaw_rate_rad_s), LEVEL)
    return LayoutRecovery(
        speed, float(push), float(np.max(np.abs(head))), float(head[-1]), final_rate,
        bool(abs(final_rate) < STEADY_YAW_RATE and closed.ended == "horizon"), float(np.max(per_wheel[win])),
        float(np.sqrt(np.mean(per_wheel[win] ** 2))),
        float(np.mean(per_wheel >= drive.torque_limit * (1 - 1e-9))), float(tl) if math.isfinite(tl) else None,
        opened.final_heading_deg, closed, opened)


def layout_decay_agreement(layout: Layout, d: Design, drive: DriveTrain, *,
                           impulse_force: float = THESIS_PUSH.force / 10.0, decades: float = 3.0) -> DecayAgreement:
    """Does the linear closed loop predict the layout simulator's decay rate? (the short form's
    :func:`stability.assist.recovery.decay_agreement` for a layout)

    Parameters
    ----------
    layout : Layout
    d : Design
    drive : DriveTrain
    impulse_force : float
        N (for :data:`~stability.settings.reference.THESIS_PUSH`'s duration).
    decades : float

    Returns
    -------
    DecayAgreement
    """
    slow, (t0, t1) = decay_window(closed_loop_poles(d), THESIS_PUSH.duration, decades)
    free = dataclasses.replace(layout, casters=tuple(dataclasses.replace(c, pin_friction=0.0)
                                                     for c in layout.casters))
    ctl = layout_controller(d, free, drive, sample_time=0.001, saturate=False)
    r = _run(free, float(d.speed), impulse_force, t1 + 0.1, ctl, drive.motor_time_constant)
    fitted = fit_decay_rate(np.asarray(r.t_s), np.asarray(r.yaw_rate_rad_s), t0, t1)
    return DecayAgreement(float(d.speed), float(slow.real), fitted, abs(fitted - slow.real) / abs(slow.real),
                          (t0, t1), float(abs(slow.imag)))


def check_speeds(grid: Sequence[float]) -> tuple[float, ...]:
    """The signed check speeds of one direction's grid: :data:`CHECK_SPEEDS` within its range of ``|U|``, else its
    fastest speed.

    Parameters
    ----------
    grid : sequence of float
        Signed design speeds of one direction, m/s.

    Returns
    -------
    tuple of float
    """
    if not len(grid):
        return ()
    mags = [abs(float(u)) for u in grid]
    sign = -1.0 if float(grid[0]) < 0 else 1.0
    inside = [s for s in CHECK_SPEEDS if min(mags) - 1e-9 <= s <= max(mags) + 1e-9]
    return tuple(sign * s for s in (inside or [max(mags)]))


def layout_traction_limit(layout: Layout, drive: DriveTrain, reverse: bool = False) -> float:
    """``mu N r`` of the less loaded drive wheel at its static load, N m per wheel (the short form's
    :func:`stability.assist.driving.traction_limit` for a layout).

    Parameters
    ----------
    layout : Layout
    drive : DriveTrain
    reverse : bool

    Returns
    -------
    float
    """
    from stability.layout.statics import static_loads
    from stability.study.layout_slope import drive_wheels

    loads = static_loads(layout, reverse)
    n = min(float(loads[j]) for j in drive_wheels(layout))
    return drive.traction_coefficient * n * drive.wheel_radius


@dataclass(frozen=True)
class LayoutChecks:
    """The nonlinear checks of one direction.

    Attributes
    ----------
    recoveries : tuple of LayoutRecovery
        Per check speed, the reference push and the strong one (ten times it).
    decays : tuple of DecayAgreement
    traction_limit_N_m, motor_limit_N_m : float
        Per drive wheel.
    """

    recoveries: tuple
    decays: tuple
    traction_limit_N_m: float
    motor_limit_N_m: float

    @property
    def peak_torque_N_m(self) -> float:
        """The largest peak torque per wheel after the reference push, N m (the short form's push torque)."""
        ref = [r.peak_torque_N_m for r in self.recoveries if r.push_N == THESIS_PUSH.force]
        return max(ref) if ref else math.nan

    def to_mapping(self) -> dict:
        """JSON-ready dict (unit last)."""
        return {"recovery": [r.to_mapping() for r in self.recoveries],
                "decay": [{"speed_m_s": a.speed_m_s, "predicted_1_s": a.predicted_1_s, "fitted_1_s": a.fitted_1_s,
                           "relative_error": a.relative_error} for a in self.decays],
                "torque_requirement": {"push_peak_N_m": self.peak_torque_N_m,
                                       "motor_limit_N_m": self.motor_limit_N_m,
                                       "traction_limit_N_m": self.traction_limit_N_m,
                                       "within_limits": bool(self.peak_torque_N_m <= min(self.motor_limit_N_m,
                                                                                         self.traction_limit_N_m))}}

    def lines(self) -> list[str]:
        """The text."""
        out = [f"  {r.text()}" for r in self.recoveries]
        out.append(f"  torque per wheel after the reference push: peak {self.peak_torque_N_m:.1f} N m against the "
                   f"motor limit {self.motor_limit_N_m:g} N m and the traction limit mu N r = "
                   f"{self.traction_limit_N_m:.0f} N m")
        out.append("  linear vs nonlinear decay (4 N x 0.1 s, pin friction off, 1 kHz): " + "; ".join(
            f"{abs(a.speed_m_s):g} m/s: predicted {a.predicted_1_s:.3f}, fitted {a.fitted_1_s:.3f} 1/s "
            f"({a.relative_error:.2%})" for a in self.decays))
        return out


def layout_checks(layout: Layout, designs: Sequence[Design], drive: DriveTrain) -> LayoutChecks:
    """Recoveries after the reference and the strong push, and the decay agreement, at each design's speed.

    Parameters
    ----------
    layout : Layout
    designs : sequence of Design
        One direction's, at its check speeds (:func:`check_speeds`).
    drive : DriveTrain

    Returns
    -------
    LayoutChecks
    """
    from stability.assist.recovery import STRONG_FORCE

    rec = tuple(layout_recovery(layout, d, drive, push=f) for d in designs for f in (THESIS_PUSH.force, STRONG_FORCE))
    dec = tuple(layout_decay_agreement(layout, d, drive) for d in designs)
    reverse = bool(designs) and designs[0].speed < 0
    return LayoutChecks(rec, dec, layout_traction_limit(layout, drive, reverse), float(drive.torque_limit))


def layout_minimum_torque_limit(layout: Layout, d: Design, drive: DriveTrain, *, impulse_force: float | None = None,
                                max_heading_deg: float = 10.0, tol: float = 0.25,
                                duration: float = HORIZON) -> float:
    """Smallest per-wheel torque limit with which the design still recovers on the layout simulator (N m).

    The short form's :func:`stability.assist.recovery.minimum_torque_limit` for a layout: the design's gains are
    kept, only the controller's saturation changes; "recovers" (:func:`stability.assist.settling.recovery_rule`):
    the heading after the push settles about its final value (:func:`stability.assist.recovery.settle_time`) and
    stays within ``max_heading_deg``; noise-free; bisection (:func:`stability.assist.recovery.bisect_limit`) to
    ``tol`` between 0 (the chair unassisted) and ``drive.torque_limit``.

    Parameters
    ----------
    layout : Layout
    d : Design
        At the run's signed speed (negative: reverse).
    drive : DriveTrain
    impulse_force : float, optional
        N for :data:`~stability.settings.reference.THESIS_PUSH`'s duration (default the strong push,
        :data:`stability.assist.recovery.STRONG_FORCE`).
    max_heading_deg, tol, duration : float
        deg, N m, s.

    Returns
    -------
    float
        N m per wheel; ``inf`` if even the full limit does not recover, 0 if the chair recovers unassisted.
    """
    from stability.assist.recovery import STRONG_FORCE, bisect_limit, settle_time

    push = STRONG_FORCE if impulse_force is None else float(impulse_force)

    def ok(limit: float) -> bool:
        ctl = None if limit == 0 else layout_controller(d, layout, dataclasses.replace(drive, torque_limit=limit))
        run = _run(layout, float(d.speed), push, duration, ctl, drive.motor_time_constant)
        head = np.degrees(np.asarray(run.heading_rad))
        return settle_time(np.asarray(run.t_s), head) is not None and float(np.max(np.abs(head))) <= max_heading_deg

    return bisect_limit(ok, float(drive.torque_limit), tol)


@dataclass(frozen=True)
class _YawRate:
    """What the gyro design's sampled controller reads of the chair: its yaw rate, rad/s."""

    yaw_rate: float


def layout_vector_loop(layout: Layout, sched: Any) -> Any:
    """The closed loop the firmware's test vectors are recorded in, for a layout
    (:data:`stability.assist.export_c.ClosedLoop`).

    As recorded before the layout simulator had a command path
    (:func:`stability.assist.layout_command.layout_command_result`), kept so: the Python controller
    (:class:`~stability.assist.controller.DigitalController`, with the case's command, the gyro's bias and seeded
    noise) reads, at its samples, the yaw rate of a closed loop run beforehand: after a push, the layout
    simulator's with the design's sampled controller; for a commanded turn, the linear closed loop's
    (:func:`stability.assist.tracking.closed_loop`, the reference model of
    :data:`~stability.assist.commands.COMMAND_FILTER`), which follows the command without the torque limit (a
    replay: the torques the Python controller computes do not act back on that run).

    Parameters
    ----------
    layout : Layout
    sched : stability.assist.layout.LayoutSchedule
        A gyro schedule of the layout.

    Returns
    -------
    callable
        ``loop(speed, push_force, duration, controller)``.
    """
    def loop(speed: float, force: float, duration: float, ctl: Any) -> None:
        d = sched.at(speed)
        if force or ctl.command is None:
            run = _run(layout, float(speed), force, duration, layout_controller(d, layout, sched.drive),
                       sched.drive.motor_time_constant)
            t, r = np.asarray(run.t_s), np.asarray(run.yaw_rate_rad_s)
        else:       # a commanded turn: the linear closed loop's yaw rate (kept: in the layout simulator's closed loop
            # the mid-wheel-drive base's 2 s saturating case peaks at 64-69 N m, below its 70 N m limit)
            t = np.linspace(0.0, duration, int(round(duration / 1e-3)) + 1)
            cmd = np.array([float(ctl.command(x)) for x in t])
            r = np.asarray(control.forced_response(closed_loop(d, command_filter=COMMAND_FILTER), t,
                                                   np.vstack([cmd, np.zeros_like(t), np.zeros_like(t)])).outputs[0])
        for k in range(int(math.floor(duration / ctl.Ts + 1e-9)) + 1):
            ctl(k * ctl.Ts, _YawRate(float(np.interp(k * ctl.Ts, t, r))))

    return loop
