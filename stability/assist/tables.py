"""The gain table (one frozen row per scheduled speed) and the assist's text tables."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.assist._format import fmt, json_float
from stability.assist.controller import DigitalController
from stability.assist.design import GAIN_UNITS, LoopMargins, closed_loop_poles, loop_margins
from stability.assist.digital import MarginPair, margin_pair
from stability.assist.driving import HOLD_TOLERANCE, SlopeHold, tracking_step
from stability.assist.plant import plant, reversed_chair
from stability.assist.recovery import RecoveryPair, recovery
from stability.assist.schedule import Schedule
from stability.assist.settling import recovery_rule
from stability.assist.tracking import TrackingMetrics
from stability.settings.reference import HORIZON, THESIS_PUSH

__all__ = ["ReverseRow", "reverse_table", "GainRow", "gain_table", "format_table", "format_margins",
           "format_slope_holds",
           "format_recovery", "PoleCurves", "pole_curves"]


@dataclass(frozen=True)
class GainRow:
    """One scheduled speed: gains, poles, margins and (optionally) the nonlinear check.

    Attributes
    ----------
    speed_m_s : float
        Design speed (m/s).
    design : str
        ``"full-state"`` or ``"gyro"``.
    gain_states : tuple of str
        Names of the plant states the gains act on.
    gains : tuple of float
        LQR gain on :data:`~stability.assist.plant.STATES` (N m of yaw moment
        per SI unit of each state, ``Mz = -gains . x``).
    wheel_torque_gains : tuple of float
        The same as differential torque per wheel (N m per unit state; ``gains`` times ``r / (d1 + d2)``,
        :attr:`~stability.assist.design.Design.wheel_torque_gains`).  The JSON row also lists each gain's unit
        (``gain_units``, :data:`~stability.assist.design.GAIN_UNITS`; N m of yaw moment for ``gains``, N m per
        wheel for ``wheel_torque_gains``).
    estimator_gain : tuple of float or None
        Gyro design: Kalman gain on ``v, r, eta, eta_dot, beta, beta_dot``
        per rad/s of gyro innovation.
    closed_loop_poles : tuple of complex
        1/s, slowest first.
    open_loop_max_real_1_s : float
        Largest real part of the chair alone (1/s).
    margins : LoopMargins
        At the plant input, continuous loop.
    margin_pair : MarginPair
        Continuous and sampled loop (ZOH, one-sample delay, motor lag).
    tracking : TrackingMetrics or None
        Yaw-rate step in the nonlinear loop (None when not checked).
    peak_torque_N_m, peak_heading_error_deg, settle_time_s, peak_response_deg, saturated_fraction,
    final_drift_deg_s : float or None
        Nonlinear closed loop after the push (None when not checked).
    settled_response_deg : float or None
        The final value the response settles about (:func:`stability.assist.settling.settled_value`; None when
        not checked or not settled).
    checked : bool
        The nonlinear check was run.
    """

    speed_m_s: float
    design: str
    gain_states: tuple[str, ...]
    gains: tuple[float, ...]
    wheel_torque_gains: tuple[float, ...]
    estimator_gain: tuple[float, ...] | None
    closed_loop_poles: tuple[complex, ...]
    open_loop_max_real_1_s: float
    margins: LoopMargins
    margin_pair: MarginPair
    tracking: TrackingMetrics | None = None
    peak_torque_N_m: float | None = None
    peak_heading_error_deg: float | None = None
    settle_time_s: float | None = None
    peak_response_deg: float | None = None
    saturated_fraction: float | None = None
    final_drift_deg_s: float | None = None
    checked: bool = False
    settled_response_deg: float | None = None

    @property
    def closed_loop_max_real_1_s(self) -> float:
        """Largest closed-loop real part (1/s)."""
        return float(max(p.real for p in self.closed_loop_poles))

    @property
    def stable(self) -> bool:
        """All closed-loop poles in the open left half-plane."""
        return self.closed_loop_max_real_1_s < 0

    def to_dict(self) -> dict[str, Any]:
        """The JSON row (keys as documented in ``docs/assist.md``)."""
        row: dict[str, Any] = {
            "speed_m_s": self.speed_m_s,
            "direction": "forward",
            "design": self.design,
            "gains": list(self.gains),
            "gain_states": list(self.gain_states),
            "gain_units": [GAIN_UNITS.get(x, "") for x in self.gain_states],
            "wheel_torque_gains": list(self.wheel_torque_gains),
            "estimator_gain": None if self.estimator_gain is None else list(self.estimator_gain),
            "closed_loop_poles": [[float(p.real), float(p.imag)] for p in self.closed_loop_poles],
            "stable": self.stable,
            "closed_loop_max_real_1_s": self.closed_loop_max_real_1_s,
            "open_loop_max_real_1_s": self.open_loop_max_real_1_s,
            "loop_margins": self.margins.to_dict(),
            "margins": self.margin_pair.to_dict(),
            "tracking": None if self.tracking is None else self.tracking.to_dict(),
            "peak_torque_N_m": self.peak_torque_N_m,
            "peak_heading_error_deg": self.peak_heading_error_deg,
            "settle_time_s": self.settle_time_s,
        }
        if self.checked:
            row.update(peak_response_deg=self.peak_response_deg, saturated_fraction=self.saturated_fraction,
                       final_drift_deg_s=json_float(self.final_drift_deg_s),
                       settled_response_deg=self.settled_response_deg)
        return row


def gain_table(sched: Schedule, *, check: bool = True, impulse_force: float = THESIS_PUSH.force, seed: int = 0,
               duration: float = HORIZON) -> list[GainRow]:
    """One :class:`GainRow` per scheduled speed.

    Parameters
    ----------
    sched : Schedule
    check : bool
        Run the nonlinear closed loop after the lateral push ``impulse_force``
        for :data:`~stability.settings.reference.THESIS_PUSH`'s duration (with
        saturation, and for the gyro design noise and bias).
    impulse_force : float
        N.
    seed : int
        Gyro noise seed (plus the row index).
    duration : float
        s.

    Returns
    -------
    list of GainRow
    """
    rows = []
    for i, (s, d) in enumerate(zip(sched.speeds, sched.designs, strict=True)):
        poles = closed_loop_poles(d)
        kw: dict[str, Any] = {}
        if check:
            ctl = DigitalController(d, sched.chair, sched.drive, gyro=sched.gyro, seed=seed + i)
            run = recovery(sched.chair, s, ctl, impulse_force=impulse_force, duration=duration, model=sched.model)
            kw = dict(peak_torque_N_m=run.peak_torque_N_m, peak_heading_error_deg=run.peak_heading_error_deg,
                      peak_response_deg=run.peak_response_deg, settle_time_s=run.settle_time_s,
                      saturated_fraction=run.saturated_fraction, final_drift_deg_s=run.final_drift_deg_s,
                      settled_response_deg=run.settled_response_deg, checked=True, tracking=tracking_step(sched, s))
        rows.append(GainRow(
            speed_m_s=float(s), design=sched.kind, gain_states=d.plant.states, gains=tuple(float(k) for k in d.K[0]),
            wheel_torque_gains=tuple(float(sched.drive.wheel_torque(sched.chair, k)) for k in d.K[0]),
            estimator_gain=None if d.L is None else tuple(float(x) for x in d.L[:, 0]),
            closed_loop_poles=tuple(complex(p) for p in poles),
            open_loop_max_real_1_s=float(np.linalg.eigvals(d.plant.A6).real.max()),
            margins=loop_margins(d), margin_pair=margin_pair(d, 1.0 / sched.gyro.sample_rate_hz), **kw))
    return rows


@dataclass(frozen=True, eq=False)
class PoleCurves:
    """What the eigenvalue figure draws besides the gain table.

    Attributes
    ----------
    open_loop : tuple of ndarray
        Eigenvalues of the chair alone at each design speed (1/s).
    fine_speeds : ndarray
        Speeds between the design speeds (m/s).
    fine_max_real : ndarray
        Largest closed-loop real part with the interpolated controller there (1/s).
    """

    open_loop: tuple[np.ndarray, ...]
    fine_speeds: np.ndarray
    fine_max_real: np.ndarray


def pole_curves(sched: Schedule) -> PoleCurves:
    """Open-loop eigenvalues at the design speeds and the interpolated closed loop between them.

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    PoleCurves
    """
    ol = tuple(np.linalg.eigvals(d.plant.A6) for d in sched.designs)
    fine = np.linspace(sched.speeds[0], sched.speeds[-1], 4 * len(sched.speeds) - 3)
    return PoleCurves(ol, fine, np.array([closed_loop_poles(sched.at(s)).real.max() for s in fine]))


def _db(ratio: float) -> float:
    """A gain ratio in dB (0 -> -inf, inf -> inf)."""
    return 20.0 * math.log10(ratio) if 0 < ratio < math.inf else (math.inf if ratio > 0 else -math.inf)


def format_table(sched: Schedule, rows: Sequence[GainRow]) -> str:
    """The gain table as text.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow

    Returns
    -------
    str
    """
    c = sched.chair
    w = sched.weights
    motor = sched.designs[0].plant.n == 8
    head = [
        f"Motor assist ({sched.kind} LQR) for {c.name}: model {sched.model}, "
        f"wheel radius {sched.drive.wheel_radius:g} m, torque limit {sched.drive.torque_limit:g} N m per wheel, "
        f"motor lag {1e3 * sched.drive.motor_time_constant:g} ms",
        f"Bryson weights: heading {w.max_heading_error_deg:g} deg, yaw rate "
        f"{fmt(w.max_yaw_rate_deg_s)} deg/s, lateral velocity {fmt(w.max_lateral_velocity_m_s)} m/s, "
        f"torque budget {w.budget(sched.drive):g} N m per wheel"
        + (f"; gyro {sched.gyro.noise_density_deg_s:g} deg/s/rtHz, bias {sched.gyro.bias_deg_s:g} deg/s, "
           f"{sched.gyro.sample_rate_hz:g} Hz, bias estimate {sched.gyro.bias_time_constant_s:g} s"
           if sched.kind == "gyro" else f"; {sched.gyro.sample_rate_hz:g} Hz"),
        "Gains: differential torque per wheel, tau = -(k . x), x = [v m/s, r rad/s, eta rad, eta_dot rad/s, "
        "beta rad, beta_dot rad/s, psi rad" + (", mz N m]" if motor else "]")
        + f" (Python: Design.wheel_torque_gains; the yaw-moment gain Design.K = k (d1 + d2) / r = "
        f"{sched.designs[0].yaw_moment_per_wheel_torque:.4g} k)",
        "",
        f"{'U':>5s} {'k_v':>8s} {'k_r':>8s} {'k_eta':>8s} {'k_etad':>8s} {'k_beta':>8s} {'k_betad':>8s} "
        f"{'k_psi':>8s}" + (f" {'k_mz':>8s}" if motor else "")
        + f" | {'OL max':>7s} {'CL max':>7s} {'GM up':>6s} {'GM dn':>6s} {'PM':>5s} {'|1+L|':>5s} "
        f"| {'tau pk':>6s} {'psi pk':>6s} {'settle':>6s}",
        f"{'m/s':>5s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s}"
        + (f" {'':>8s}" if motor else "") + f" | {'1/s':>7s} {'1/s':>7s} "
        f"{'dB':>6s} {'dB':>6s} {'deg':>5s} {'min':>5s} | {'N m':>6s} {'deg':>6s} {'s':>6s}",
    ]
    lines = list(head)
    for r in rows:
        m = r.margins
        lines.append(
            f"{r.speed_m_s:5.2f} " + " ".join(f"{x:8.4g}" for x in r.wheel_torque_gains)
            + f" | {r.open_loop_max_real_1_s:7.3f} {r.closed_loop_max_real_1_s:7.3f} "
            f"{fmt(_db(m.gain_margin_upper), '.1f'):>6s} {fmt(-_db(m.gain_margin_lower), '.1f'):>6s} "
            f"{fmt(m.phase_margin_deg, '.0f'):>5s} {fmt(m.min_return_difference, '.2f'):>5s} | "
            f"{fmt(r.peak_torque_N_m, '.1f'):>6s} {fmt(r.peak_heading_error_deg, '.2f'):>6s} "
            f"{fmt(r.settle_time_s, '.2f'):>6s}"
        )
    stable = all(r.stable for r in rows)
    lines += ["", "All scheduled closed loops stable." if stable else
              "UNSTABLE closed loop at " + ", ".join(f"{r.speed_m_s:g}" for r in rows if not r.stable) + " m/s."]
    return "\n".join(lines)


def format_recovery(runs: Sequence[RecoveryPair]) -> str:
    """The recovery table as text.

    Parameters
    ----------
    runs : sequence of RecoveryPair

    Returns
    -------
    str
    """
    lines = [f"{'U m/s':>6s} {'impulse':>8s} {'psi pk CL':>10s} {'resp pk':>8s} {'psi pk OL':>10s} {'tau pk':>7s} "
             f"{'sat':>6s} {'settle s':>9s} {'about':>7s} {'drift':>7s} {'OL 10deg s':>10s}",
             f"{'':>6s} {'':>8s} {'deg':>10s} {'deg':>8s} {'deg':>10s} {'N m':>7s} {'':>6s} {'':>9s} "
             f"{'deg':>7s} {'deg/s':>7s} {'':>10s}"]
    for cl, ol in runs:
        lines.append(
            f"{cl.speed:6.2f} {cl.impulse_force:7.0f}N {cl.peak_heading_error_deg:10.2f} "
            f"{cl.peak_response_deg:8.3f} {fmt(ol.peak_heading_error_deg if ol else None, '.1f'):>10s} "
            f"{cl.peak_torque_N_m:7.1f} {cl.saturated_fraction:6.1%} "
            f"{fmt(cl.settle_time_s, '.2f', 'no'):>9s} {fmt(cl.settled_response_deg, '+.3f', '-'):>7s} "
            f"{fmt(json_float(cl.final_drift_deg_s), '.3f'):>7s} "
            f"{fmt(ol.time_to_10deg_s if ol else None, '.2f', 'never'):>10s}")
    lines.append(f"settle s: when the disturbance response {recovery_rule(None)} ('about')")
    return "\n".join(lines)


def format_margins(rows: Sequence[GainRow]) -> str:
    """Continuous vs sampled-loop margins and the yaw-rate step, one line per speed.

    Parameters
    ----------
    rows : sequence of GainRow

    Returns
    -------
    str
    """
    lines = [f"{'U':>5s} | {'GM dB c/d':>11s} {'PM deg c/d':>11s} {'DM ms c/d':>11s} | {'disk a c/d':>11s} "
             f"{'DGM dB c/d':>11s} {'DPM deg c/d':>11s} | {'r_cmd':>6s} {'sse %':>6s} {'os %':>5s} {'settle':>6s} "
             f"{'tau pk':>6s}",
             f"{'m/s':>5s} | {'classical':^35s} | {'disk (gain, phase together)':^35s} | "
             f"{'rad/s':>6s} {'':>6s} {'':>5s} {'s':>6s} {'N m':>6s}"]
    for r in rows:
        m = r.margin_pair.to_dict()
        c, d = m["continuous"], m["discrete"]
        tr = r.tracking
        track = (f"{tr.command_rad_s:6.3f} {tr.steady_state_error_pct:6.2f} {tr.overshoot_pct:5.1f} "
                 f"{fmt(tr.settling_time_s, '.2f'):>6s} {tr.peak_torque_N_m:6.1f}") if tr else "     -"
        lines.append(f"{r.speed_m_s:5.2f} | {fmt(c['gain_db'], '.1f'):>5s}/{fmt(d['gain_db'], '.1f'):<5s} "
                     f"{fmt(c['phase_deg'], '.1f'):>5s}/{fmt(d['phase_deg'], '.1f'):<5s} "
                     f"{fmt(c['delay_ms'], '.1f'):>5s}/{fmt(d['delay_ms'], '.1f'):<5s} | "
                     f"{fmt(c['disk_margin'], '.2f'):>5s}/{fmt(d['disk_margin'], '.2f'):<5s} "
                     f"{fmt(c['disk_gain_db'], '.1f'):>5s}/{fmt(d['disk_gain_db'], '.1f'):<5s} "
                     f"{fmt(c['disk_phase_deg'], '.1f'):>5s}/{fmt(d['disk_phase_deg'], '.1f'):<5s} | {track}")
    unstable = [r.speed_m_s for r in rows if r.margin_pair.discrete.delay_margin_s == 0.0]
    if unstable:
        lines.append("SAMPLED LOOP UNSTABLE at " + ", ".join(f"{u:g}" for u in unstable) + " m/s at "
                     f"{1 / rows[0].margin_pair.sample_time:g} Hz (closed-loop pole outside the unit circle): no "
                     "margin is left there (phase shown negative, delay 0); raise --sample-rate")
    return "\n".join(lines)


@dataclass(frozen=True)
class ReverseRow:
    """Driving backwards at one speed: the open-loop chair as seen in the direction of travel.

    Attributes
    ----------
    speed_m_s : float
        Backward speed (m/s).
    max_real_1_s : float
        Largest real part of the reversed chair's linear model (1/s).
    stable : bool
        ``max_real_1_s < 0``: no assist needed.
    """

    speed_m_s: float
    max_real_1_s: float
    stable: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON row (``direction: "reverse"``)."""
        return {"speed_m_s": self.speed_m_s, "direction": "reverse", "open_loop_max_real_1_s": self.max_real_1_s,
                "stable": self.stable}


def reverse_table(sched: Schedule) -> list[ReverseRow]:
    """Reverse-driving rows at the schedule's speeds (:func:`~stability.assist.plant.reversed_chair`).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    list of ReverseRow
    """
    rev = reversed_chair(sched.chair)
    out = []
    for s in sched.speeds:
        m = float(np.linalg.eigvals(plant(rev, s, sched.model).A6).real.max())
        out.append(ReverseRow(float(s), m, m < 0))
    return out


def format_slope_holds(holds: Sequence[SlopeHold | dict[str, Any]]) -> str:
    """The cross-slope section of the text output (one line per slope; a skipped slope says why).

    Parameters
    ----------
    holds : sequence of SlopeHold or dict
        :func:`~stability.assist.driving.slope_hold` results, or ``{"cross_slope_deg", "skipped"}``.

    Returns
    -------
    str
    """
    speed = next((h.speed_m_s for h in holds if isinstance(h, SlopeHold)), float("nan"))
    lines = [f"\nCross slope, straight command ({speed:g} m/s, exact model, pin friction, noise-free, heading to the "
             "right +): steady torque vs the statics' holding torque (frictionless, tolerance "
             f"{HOLD_TOLERANCE:.0%}; pin-friction band in brackets)"]
    for h in holds:
        if not isinstance(h, SlopeHold):
            lines.append(f"  {h['cross_slope_deg']:g} deg: skipped ({h['skipped']})")
            continue
        lines.append(
            f"  {h.cross_slope_deg:g} deg: open loop {h.open_heading_deg:+.1f} deg ({h.open_turn}) at "
            f"{h.open_end_s:.2f} s; assist {h.closed_heading_deg:+.2f} deg at {h.duration_s:g} s (crab "
            f"{h.crab_deg:+.2f} deg, offset {1e3 * h.closed_offset_m:+.1f} mm); torque {h.steady_torque_N_m:.2f} "
            f"({h.harder_side} wheel harder) vs "
            f"{h.holding_torque_N_m:.2f} N m ({100 * h.relative_error:+.3g} %) [{h.holding_band_N_m[0]:.2f}, "
            f"{h.holding_band_N_m[1]:.2f}], peak {h.peak_torque_N_m:.1f} N m, "
            f"{'within' if h.within_limits else 'BEYOND'} the motor ({h.motor_limit_N_m:g} N m) and traction "
            f"({h.traction_limit_N_m:.0f} N m, friction use {h.friction_use:.0%}) limits")
    return "\n".join(lines)
