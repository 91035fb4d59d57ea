"""The assist's figures: each draws the data it is given and returns the Figure (nothing is computed here)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib import cm
from matplotlib.colors import Normalize
from matplotlib.figure import Figure

from stability.assist._format import fmt, json_float
from stability.assist.destabilising import DestabilisingSummary
from stability.assist.digital import MarginCurves
from stability.assist.driving import TorqueRow, TrackingRuns
from stability.assist.plant import STATES
from stability.assist.recovery import RecoveryPair, RecoveryRun
from stability.assist.robustness import Robustness
from stability.assist.schedule import Schedule
from stability.assist.tables import GainRow, PoleCurves
from stability.assist.tracking import DriftCurves
from stability.chair.power import DriveTrain
from stability.plotting import page, table_page
from stability.plotting.style import colour
from stability.settings.reference import THESIS_PUSH

__all__ = ["figure_gains", "figure_poles", "figure_margins", "figure_robustness", "figure_destabilising",
           "figure_recovery", "figure_recovery_table", "figure_tracking", "figure_drift", "figure_margin_pair",
           "figure_torque", "flat_axis", "label_axes"]


def _finish(fig: Figure) -> Figure:
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.93))
    return fig


def flat_axis(a: Any, values: Any) -> None:
    """No offset on the y axis, and +/-10 % around values that are constant to 1e-3 (not round-off magnified).

    Parameters
    ----------
    a : matplotlib.axes.Axes
    values : array_like
    """
    a.ticklabel_format(axis="y", useOffset=False)
    lo, hi = float(np.min(values)), float(np.max(values))
    if hi - lo < 1e-3 * max(abs(lo), abs(hi), 1e-12):
        a.set_ylim(min(0.9 * lo, 1.1 * lo), max(0.9 * hi, 1.1 * hi))


def figure_gains(sched: Schedule, rows: Sequence[GainRow]) -> Figure:
    """Gains (differential torque per wheel per unit state) and the Kalman gain against speed.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Gain schedule: {sched.kind} LQR, {sched.chair.name}",
                   "tau = -(k . x) per wheel; linear interpolation between design speeds", nrows=2, ncols=4)
    U = sched.speeds
    K = np.array([r.wheel_torque_gains[:len(STATES)] for r in rows])
    units = ["N m/(m/s)", "N m/(rad/s)", "N m/rad", "N m/(rad/s)", "N m/rad", "N m/(rad/s)", "N m/rad"]
    for j, (s, u) in enumerate(zip(STATES, units, strict=True)):
        a = ax.flat[j]
        a.plot(U, K[:, j], "o-", ms=3)
        flat_axis(a, K[:, j])
        a.set_title(f"k_{s}")
        a.set_xlabel("speed (m/s)")
        a.set_ylabel(u)
        a.grid(alpha=0.3)
    a = ax.flat[7]
    if sched.kind == "gyro":
        Lm = np.array([r.estimator_gain for r in rows])
        for j, s in enumerate(STATES[:6]):
            a.plot(U, Lm[:, j], label=s)
        a.set_title("Kalman gain (per rad/s of innovation)")
        a.set_xlabel("speed (m/s)")
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    else:
        a.axis("off")
    return _finish(fig)


def figure_poles(sched: Schedule, rows: Sequence[GainRow], curves: PoleCurves,
                 rob: Robustness | None = None) -> Figure:
    """Closed-loop eigenvalues against speed and the largest real part (open loop, closed loop, worst corner).

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow
    curves : PoleCurves
        Open-loop eigenvalues and the interpolated closed loop.
    rob : Robustness, optional

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Closed-loop eigenvalues: {sched.kind} LQR, {sched.chair.name}",
                   f"model {sched.model}; colour = speed", nrows=1, ncols=2)
    a = ax[0, 0]
    norm = Normalize(sched.speeds[0], sched.speeds[-1])
    for r, ol in zip(rows, curves.open_loop, strict=True):
        p = np.array(r.closed_loop_poles)
        a.scatter(p.real, p.imag, s=10, color=cm.viridis(norm(r.speed_m_s)))
        a.scatter(ol.real, ol.imag, s=14, marker="x", color=cm.viridis(norm(r.speed_m_s)))
    a.axvline(0, color="k", lw=0.8)
    a.set_xlabel("real part (1/s)")
    a.set_ylabel("imaginary part (rad/s)")
    a.set_title("o closed loop, x open loop (chair alone)")
    lim = max(max(float(np.abs(np.array(r.closed_loop_poles).real).min()), 1.0) for r in rows)
    a.set_xlim(-12 * lim, 2 * lim)
    a.grid(alpha=0.3)
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap="viridis"), ax=a, label="speed (m/s)")
    b = ax[0, 1]
    b.plot(sched.speeds, [r.open_loop_max_real_1_s for r in rows], "r--", label="open loop (chair alone)")
    b.plot(sched.speeds, [r.closed_loop_max_real_1_s for r in rows], "b-o", ms=3, label="closed loop, nominal")
    if rob is not None:
        b.plot(rob.speeds, rob.max_real.max(axis=0), "k:", label=f"closed loop, worst of +/-{rob.box:.0%} box")
    b.plot(curves.fine_speeds, curves.fine_max_real, "c.", ms=3, label="closed loop, interpolated gains")
    b.axhline(0, color="k", lw=0.8)
    b.set_xlabel("speed (m/s)")
    b.set_ylabel("largest real part (1/s)")
    b.legend(fontsize=8)
    b.grid(alpha=0.3)
    return _finish(fig)


def figure_margins(sched: Schedule, rows: Sequence[GainRow]) -> Figure:
    """Stability margins of the loop broken at the plant input against speed.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Loop margins at the plant input: {sched.kind} LQR, {sched.chair.name}",
                   "L(s) = C(s) P(s) from the yaw-moment command; control.stability_margins", nrows=1, ncols=3)
    U = sched.speeds
    m = [r.margins for r in rows]

    def val(key: str) -> np.ndarray:
        return np.array([np.nan if getattr(x, key) is None else float(getattr(x, key)) for x in m])

    a = ax[0, 0]
    up, lo = val("gain_margin_upper"), val("gain_margin_lower")
    with np.errstate(divide="ignore"):
        a.plot(U, 20 * np.log10(np.where(np.isfinite(up), up, np.nan)), "b-o", ms=3, label="upper (gain increase)")
        a.plot(U, 20 * np.log10(np.where(lo > 0, lo, np.nan)), "r-o", ms=3, label="lower (gain reduction)")
    a.axhline(0, color="k", lw=0.8)
    a.set_ylabel("gain margin (dB)")
    a.set_xlabel("speed (m/s)")
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    b = ax[0, 1]
    b.plot(U, val("phase_margin_deg"), "g-o", ms=3)
    b.axhline(60, color="0.5", ls=":", lw=0.8)
    b.set_ylabel("phase margin (deg)")
    b.set_xlabel("speed (m/s)")
    b.grid(alpha=0.3)
    c = ax[0, 2]
    c.plot(U, val("min_return_difference"), "m-o", ms=3, label="min |1 + L(jw)|")
    c.plot(U, val("disk_margin"), "c-s", ms=3, label="balanced disk margin alpha")
    c.plot(U, val("delay_margin_s") * 10, "k--", label="delay margin x 10 (s)")
    c.axhline(1, color="0.5", ls=":", lw=0.8)
    c.set_xlabel("speed (m/s)")
    c.legend(fontsize=8)
    c.grid(alpha=0.3)
    return _finish(fig)


def figure_robustness(rob: Robustness, sched: Schedule) -> Figure:
    """Largest closed-loop real part at every corner of the box against speed.

    Parameters
    ----------
    rob : Robustness
    sched : Schedule

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Robustness: +/-{rob.box:.0%} in mass, yaw inertia, main and caster cornering stiffness",
                   f"{sched.kind} LQR designed on the nominal {sched.chair.name}; worst case "
                   f"{rob.worst.max_real_1_s:.3f} 1/s at {rob.worst.speed_m_s:g} m/s, corner "
                   + rob.worst.describe())
    a = ax[0, 0]
    for i in range(len(rob.corners)):
        lab = "nominal" if i == 0 else None
        a.plot(rob.speeds, rob.max_real[i], "k-" if i == 0 else "-", lw=2 if i == 0 else 0.8,
               alpha=1 if i == 0 else 0.6, label=lab)
    a.axhline(0, color="r", lw=0.8)
    a.set_xlabel("speed (m/s)")
    a.set_ylabel("largest closed-loop real part (1/s)")
    a.legend()
    a.grid(alpha=0.3)
    return _finish(fig)


def figure_destabilising(ref: Any, ref_end_s: float, runs: Sequence[RecoveryRun],
                         summaries: Sequence[DestabilisingSummary], ends_s: Sequence[float], capacity_N_m: float,
                         chair_name: str) -> Figure:
    """Figure 9-4 (reference case) and the power chair's open-loop destabilising moment vs its motors.

    Curves end at the first slip-angle warning (beyond 8 deg the caster
    tire data are extrapolated); the reference run itself stops at WCHAIR's
    eleventh warning.

    Parameters
    ----------
    ref : SimulationResult
        The thesis's reference run.
    ref_end_s : float
        Its first slip warning (s).
    runs : sequence of RecoveryRun
        Open-loop runs of the power chair.
    summaries : sequence of DestabilisingSummary
        One per run.
    ends_s : sequence of float
        End of each run's meaningful part (s).
    capacity_N_m : float
        Yaw moment of the motors at their limit (N m).
    chair_name : str

    Returns
    -------
    Figure
    """
    fig, ax = page("Destabilising yaw moment of the tire forces (thesis Figure 9-4)",
                   "open loop, lateral impulse at the c.g. (to the right), WCHAIR scheme; curves end at the first "
                   "slip angle above 8 deg (any tire) or, right, at 90 deg of heading", nrows=1, ncols=2)
    a = ax[0, 0]
    k = np.asarray(ref.t) < ref_end_s
    a.plot(np.asarray(ref.t)[k], np.asarray(ref.tire_yaw_moment)[k], "k")
    a.set_title(f"{ref.chair.name}, {ref.speed:g} m/s, {THESIS_PUSH.describe(None)}, "
                f"{ref.settings.get('model')} model\n(first slip warning {ref_end_s:.2f} s)")
    a.set_xlabel("time (s)")
    a.set_ylabel("yaw moment of the tire forces about the c.g. (N m)")
    a.grid(alpha=0.3)
    b = ax[0, 1]
    for run, summ, end in zip(runs, summaries, ends_s, strict=True):
        res = run.result
        k = np.asarray(res.t) < end
        b.plot(np.asarray(res.t)[k], np.asarray(res.tire_yaw_moment)[k],
               label=f"{run.speed:g} m/s, {run.impulse_force:g} N: peak {summ.peak_moment_N_m:.0f} N m "
                     f"({summ.fraction_of_capacity:.0%} of the motors) by {summ.valid_until_s:.2f} s")
    b.axhline(capacity_N_m, color="r", ls="--", label=f"motor limit {capacity_N_m:.0f} N m")
    b.axhline(-capacity_N_m, color="r", ls="--")
    b.set_title(f"{chair_name} open loop ({runs[0].result.settings.get('model') if runs else ''} model)")
    b.set_ylim(-1.6 * capacity_N_m, 1.6 * capacity_N_m)
    b.set_xlabel("time (s)")
    b.set_ylabel("yaw moment of the tire forces about the c.g. (N m)")
    b.legend(fontsize=8)
    b.grid(alpha=0.3)
    return _finish(fig)


def figure_recovery(runs: Sequence[RecoveryPair], sched: Schedule) -> Figure:
    """Heading and torque after the disturbances, closed loop vs open loop.

    Parameters
    ----------
    runs : sequence of RecoveryPair
    sched : Schedule

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Nonlinear recovery: {sched.kind} LQR on {sched.chair.name}",
                   "solid: closed loop (saturation" + (", gyro noise and bias" if sched.kind == "gyro" else "")
                   + "); dashed: open loop", nrows=2, ncols=2)
    drive: DriveTrain = sched.drive
    for closed, opened in runs:
        col = {1.0: "C0", 2.0: "C1", 3.0: "C2"}.get(closed.speed, None)
        j = 0 if closed.impulse_force <= THESIS_PUSH.force + 1e-9 else 1
        lab = f"{closed.speed:g} m/s"
        ax[0, j].plot(closed.result.t, np.degrees(closed.result.heading), color=col, label=lab)
        if opened is not None:
            ax[0, j].plot(opened.result.t, np.degrees(opened.result.heading), color=col, ls="--")
        tau = drive.wheel_torque(sched.chair, np.asarray(closed.result.yaw_moment_input))   # unit conversion
        ax[1, j].plot(closed.result.t, tau, color=col, lw=0.8, label=lab)
    strong = 10.0 * THESIS_PUSH.force
    for j, f in enumerate((f"{THESIS_PUSH.force:g} N x {THESIS_PUSH.duration:g} s (reference)",
                           f"{strong:g} N x {THESIS_PUSH.duration:g} s (ten times)")):
        ax[0, j].set_title(f)
        ax[0, j].set_ylim(-10, 10)
        ax[0, j].set_ylabel("heading (deg)")
        ax[1, j].set_ylabel("differential torque per wheel (N m)")
        ax[1, j].axhline(drive.torque_limit, color="r", ls="--", lw=0.8)
        ax[1, j].axhline(-drive.torque_limit, color="r", ls="--", lw=0.8)
        for i in range(2):
            ax[i, j].set_xlabel("time (s)")
            ax[i, j].grid(alpha=0.3)
            ax[i, j].legend(fontsize=8)
    return _finish(fig)


def figure_recovery_table(runs: Sequence[RecoveryPair], sched: Schedule) -> Figure:
    """The recovery table as a page.

    Parameters
    ----------
    runs : sequence of RecoveryPair
    sched : Schedule

    Returns
    -------
    Figure
    """
    header = ["U (m/s)", "impulse", "peak heading CL/OL", "response pk", "torque pk",
              "saturated", "settle (s)", "drift", "OL 10 deg at"]
    rows = []
    for c, o in runs:
        rows.append([f"{c.speed:g}", f"{c.impulse_force:g} N x {c.impulse_duration:g} s",
                     f"{c.peak_heading_error_deg:.2f} / {fmt(o.peak_heading_error_deg if o else None, '.1f')} deg",
                     f"{c.peak_response_deg:.3f} deg", f"{c.peak_torque_N_m:.1f} N m", f"{c.saturated_fraction:.1%}",
                     fmt(c.settle_time_s, ".2f", "not settled"),
                     fmt(json_float(c.final_drift_deg_s), ".3f") + " deg/s",
                     fmt(o.time_to_10deg_s if o else None, ".2f", "not reached") + " s"])
    return table_page(f"Recovery in the nonlinear simulator: {sched.kind} LQR, {sched.chair.name}", header, rows,
                      "10 s, WCHAIR scheme 1 ms, exact model, Coulomb pin friction, torque limit "
                      f"{sched.drive.torque_limit:g} N m per wheel",
                      col_widths=[0.7, 1.1, 1.5, 1.1, 1.0, 0.9, 0.9, 1.1, 1.0],
                      wrap=[8, 14, 20, 12, 12, 10, 10, 14, 12],
                      notes="peak heading: largest |heading| of the closed loop (including the drift and wander "
                            "the gyro bias and noise cause) / of the open-loop chair over 10 s; settle: the "
                            "disturbance response (heading minus that of a twin run with the same gyro noise "
                            "and no impulse) stays within 5 % of its peak; drift: heading slope over the last "
                            "2 s.")


def label_axes(a: Any, xlabel: str, ylabel: str, legend: bool = True) -> None:
    """Axis labels, a light grid and (with ``legend``) a small legend.

    Parameters
    ----------
    a : matplotlib.axes.Axes
    xlabel, ylabel : str
    legend : bool
    """
    a.set_xlabel(xlabel)
    a.set_ylabel(ylabel)
    a.grid(alpha=0.3)
    if legend:
        a.legend(fontsize=8)


def figure_tracking(sched: Schedule, runs: TrackingRuns) -> Figure:
    """Yaw-rate step and ramp commands followed in the nonlinear loop: yaw rate and wheel torque.

    Parameters
    ----------
    sched : Schedule
    runs : TrackingRuns

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Yaw-rate command tracking: {sched.kind} LQR on {sched.chair.name}, {sched.model} model, "
                   f"{runs.speed_m_s:g} m/s", "nonlinear simulator (WCHAIR scheme, pin friction), sampled controller "
                   "with feedforward, integral action and anti-windup; noise-free gyro", nrows=1, ncols=2)
    a, b = ax[0, 0], ax[0, 1]
    for i, (run, lab) in enumerate(((runs.step, runs.step_label), (runs.ramp, runs.ramp_label))):
        a.plot(run.t, run.command, color=colour(i), ls="--", lw=1.0, label=f"{lab}: joystick command")
        a.plot(run.t, run.yaw_rate, color=colour(i), lw=1.6, label=f"{lab}: chair yaw rate")
        b.step(run.torque_t, run.torque, where="post", color=colour(i), lw=1.0, label=lab)
    for sign in (1, -1):
        b.axhline(sign * runs.torque_limit_N_m, color="k", ls=":", lw=0.8,
                  label=f"motor limit +/-{runs.torque_limit_N_m:g} N m" if sign > 0 else None)
    a.set_title("yaw rate")
    b.set_title("differential torque per wheel (commanded, held)")
    label_axes(a, "time (s)", "yaw rate (rad/s)")
    label_axes(b, "time (s)", "torque per wheel (N m)")
    return _finish(fig)


def figure_drift(sched: Schedule, curves: DriftCurves) -> Figure:
    """Heading drift with a constant gyro bias, straight command, with and without the bias handling.

    Parameters
    ----------
    sched : Schedule
    curves : DriftCurves

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Heading drift from gyro bias: {sched.kind} LQR on {sched.chair.name}, {sched.model} model, "
                   f"{curves.speed_m_s:g} m/s", "linear closed loop, straight command; without handling the chair "
                   "turns at minus the bias, with the wheel-speed bias estimate the heading settles at -b T_b")
    a = ax[0, 0]
    for i, b in enumerate(curves.bias_deg_s):
        a.plot(curves.t, curves.without[i], color=colour(i), ls="--", label=f"{b:g} deg/s bias, no bias handling")
        a.plot(curves.t, curves.handled[i], color=colour(i), lw=1.8,
               label=f"{b:g} deg/s bias, estimated from the wheel speeds (T_b = {curves.bias_time_constant_s:g} s)")
    a.axhline(0, color="k", lw=0.8)
    label_axes(a, "time (s)", "true heading (deg)")
    return _finish(fig)


def figure_margin_pair(sched: Schedule, curves: MarginCurves) -> Figure:
    """Gain, phase and delay margins of the continuous and the sampled loop against speed.

    Parameters
    ----------
    sched : Schedule
    curves : MarginCurves

    Returns
    -------
    Figure
    """
    rate = 1.0 / curves.sample_time
    fig, ax = page(f"Continuous vs sampled loop margins: {sched.kind} LQR on {sched.chair.name}, {sched.model} model",
                   f"loop broken at the plant input; sampled at {rate:g} Hz with zero-order hold and one sample of "
                   f"computation delay; {1e3 * sched.drive.motor_time_constant:g} ms motor lag in both. Dotted: "
                   "the balanced disk margin's gain and phase, which the loop tolerates together (at most the "
                   "classical ones; Seiler, Packard & Gahinet 2020)",
                   nrows=1, ncols=3)
    names = ("continuous", f"sampled, {rate:g} Hz")
    for a, data, disk, what, unit in ((ax[0, 0], curves.gain_db, curves.disk_gain_db,
                                       "gain margin (smaller of up/down)", "dB"),
                                      (ax[0, 1], curves.phase_deg, curves.disk_phase_deg, "phase margin", "deg"),
                                      (ax[0, 2], curves.delay_ms, None, "delay margin", "ms")):
        for i, name in enumerate(names):
            a.plot(curves.speeds, data[i], color=colour(i), marker="os"[i], ms=4, ls="-" if i == 0 else "--",
                   label=f"{name}, classical" if disk is not None else name)
            if disk is not None:
                a.plot(curves.speeds, disk[i], color=colour(i), marker="os"[i], ms=3, mfc="none", ls=":",
                       label=f"{name}, disk")
        a.set_title(what)
        label_axes(a, "speed (m/s)", f"{what.split(' (')[0]} ({unit})", legend=False)
        a.legend(fontsize=7, loc="upper right")
    return _finish(fig)


def figure_torque(sched: Schedule, rows: Sequence[TorqueRow]) -> Figure:
    """Peak and RMS differential torque needed against speed, with the motor and traction limits.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of TorqueRow

    Returns
    -------
    Figure
    """
    fig, ax = page(f"Torque requirement: {sched.kind} LQR on {sched.chair.name}, {sched.model} model",
                   f"nonlinear loop, noise-free: recovery from the reference push ({THESIS_PUSH.describe(None)}, 2 s) "
                   "and the yaw-rate step through the reference model (3 s)")
    a = ax[0, 0]
    U = [r.speed_m_s for r in rows]
    series = (("push_peak_N_m", "push recovery, peak", "-", "o"), ("push_rms_N_m", "push recovery, RMS", "--", "o"),
              ("turn_peak_N_m", "commanded turn, peak", "-", "s"), ("turn_rms_N_m", "commanded turn, RMS", "--", "s"),
              ("steady_turn_N_m", "holding the steady turn (against the turn)", ":", "^"))
    for i, (key, lab, ls, mk) in enumerate(series):
        a.plot(U, [getattr(r, key) for r in rows], color=colour(i), ls=ls, marker=mk, ms=4, label=lab)
    if rows:
        a.axhline(rows[0].motor_limit_N_m, color="k", ls="-.", lw=1.0,
                  label=f"motor limit {rows[0].motor_limit_N_m:g} N m")
        a.axhline(rows[0].traction_limit_N_m, color=colour(5), ls="-.", lw=1.0,
                  label=f"traction limit mu N r = {rows[0].traction_limit_N_m:.0f} N m "
                        f"(mu = {sched.drive.traction_coefficient:g})")
    a.axhline(0, color="k", lw=0.6)
    label_axes(a, "speed (m/s)", "differential torque per wheel (N m)")
    return _finish(fig)
