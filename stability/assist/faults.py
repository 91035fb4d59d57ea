"""Single sensor faults of the gyro assist in the nonlinear closed loop: monitor, detection, degraded mode.

Every run drives straight (joystick centred) at one scheduled speed, on level
ground or along a cross slope, with the firmware controller
(:class:`~stability.assist.firmware.FirmwareController`: the exported C's
arithmetic, stepping all runs of a batch together on numpy arrays) as the
simulator's ``yaw_moment`` hook, seeded gyro noise and the sensor's bias.
One fault from :data:`FAULTS` starts at :data:`FAULT_TIME`.

Monitor (part of the firmware, :class:`~stability.assist.firmware.FirmwareController`
and the exported C): the gyro minus the wheel-speed yaw rate, low-passed with
:data:`MONITOR_TIME` and less the slow bias estimate, compared with
:data:`MONITOR_THRESHOLD_DEG_S` (the residual the bias estimator already
forms; a healthy gyro keeps it at the noise level, ~0.1 deg/s).  Degraded
mode on detection (latched): fading the assist out is no option for this
chair, which is unstable without it at every scheduled speed (the unassisted
runs), so the controller keeps steering on the redundant yaw sensor: if the
wheel-speed yaw rate is implausible (:data:`WHEEL_PLAUSIBLE`) the wheel-speed
sensor is at fault and the gyro is used alone (bias estimate frozen), else
the gyro is at fault and the wheel-speed yaw rate replaces it.  The joystick
speed is limited to :data:`DEGRADED_SPEED` (reported; the simulator holds the
forward speed, so the limit is not simulated).

Outcome "safe" when, over the :data:`WINDOW` after the fault, the peak heading
error and the lateral drift stay within the stated bounds
:data:`HEADING_BOUND_DEG` and :data:`DRIFT_BOUND_M`.  The unassisted chair's
response (same speed and slope, no fault) is reported beside it but is no
criterion here: the power-fwd chair is unstable without the assist at every
scheduled speed (it veers 24 deg in 5 s at 1 m/s on level ground from its own
asymmetry), so "no worse than unassisted" would pass any fault.  See
docs/assist.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.assist.commands import COMMAND_FILTER
from stability.assist.driving import traction_limit
from stability.assist.firmware import (
    DEGRADED_SPEED,
    MONITOR_THRESHOLD_DEG_S,
    MONITOR_TIME,
    WHEEL_PLAUSIBLE,
    FirmwareController,
    FirmwareTables,
    firmware_tables,
)
from stability.assist.schedule import Schedule
from stability.settings.run import RunSpec
from stability.simulate import simulate_batch

__all__ = ["FAULTS", "FAULT_TIME", "WINDOW", "MONITOR_TIME", "MONITOR_THRESHOLD_DEG_S", "WHEEL_PLAUSIBLE",
           "DEGRADED_SPEED", "HEADING_BOUND_DEG", "DRIFT_BOUND_M", "FaultRow", "fault_runs", "format_faults"]

_DEG = math.pi / 180.0
#: The single faults: name -> (kind, value).
FAULTS: dict[str, tuple[str, float]] = {
    "gyro_stuck_last": ("stuck_last", 0.0),
    "gyro_stuck_zero": ("stuck_zero", 0.0),
    "gyro_bias_1_deg_s": ("bias", 1.0),
    "gyro_bias_5_deg_s": ("bias", 5.0),
    "gyro_bias_20_deg_s": ("bias", 20.0),
    "gyro_sign_inverted": ("sign", 0.0),
    "gyro_dropout_0.1_s": ("dropout", 0.1),
    "gyro_dropout_1_s": ("dropout", 1.0),
    "gyro_noise_x10": ("noise", 10.0),
    "wheel_speed_sensor_lost": ("wheel_lost", 0.0),
    "wheel_slip": ("slip", 0.5),
}
#: Time of the fault (s) and the window after it that is judged (s).
FAULT_TIME = 1.0
WINDOW = 5.0
#: Stated bounds of a safe response within WINDOW of the fault: heading error (deg) and lateral drift (m).
#: 10 deg is about the heading a driver corrects without a swerve; 0.3 m is the clearance each side of a
#: 0.6 m wide chair in a 1.2 m corridor (design choices of this check, not numbers from a standard).
HEADING_BOUND_DEG = 10.0
DRIFT_BOUND_M = 0.3


@dataclass(frozen=True)
class FaultRow:
    """One fault at one speed and slope.

    Attributes
    ----------
    fault : str
    speed_m_s, slope_deg : float
    detected : bool
    detection_time_s : float or None
        From the fault to the monitor's alarm (None: not detected).
    peak_heading_error_deg, peak_yaw_rate_deg_s, drift_m : float
        Over :data:`WINDOW` after the fault.
    unassisted_heading_error_deg, unassisted_drift_m : float
        The unassisted chair's, same window.
    outcome : str
        "safe" (within :data:`HEADING_BOUND_DEG` and :data:`DRIFT_BOUND_M`) or "unsafe".
    """

    fault: str
    speed_m_s: float
    slope_deg: float
    detected: bool
    detection_time_s: float | None
    peak_heading_error_deg: float
    peak_yaw_rate_deg_s: float
    drift_m: float
    unassisted_heading_error_deg: float
    unassisted_drift_m: float
    outcome: str

    def to_dict(self) -> dict[str, Any]:
        """JSON entry of ``faults``."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


class FaultHook:
    """The ``yaw_moment(t, state)`` hook of a batch: firmware controller, sensors with faults, monitor, motor lag.

    Parameters
    ----------
    tables : FirmwareTables
    sched : Schedule
    speeds : ndarray (runs,)
        m/s.
    kinds : sequence of str
        Fault kind per run (:data:`FAULTS` values; "" none; "open" no assist).
    values : ndarray (runs,)
    seed : int
    traction_limit_N_m : float, optional
        The drive wheels' traction limit ``mu N r`` (N m per wheel; default the schedule's,
        :func:`~stability.assist.driving.traction_limit`, a layout's too): a slipping wheel passes half of it.
    """

    def __init__(self, tables: FirmwareTables, sched: Schedule, speeds: np.ndarray, kinds: Sequence[str],
                 values: np.ndarray, seed: int = 0, traction_limit_N_m: float | None = None) -> None:
        R = len(speeds)
        self.fc = FirmwareController(tables, runs=R)
        self.T = tables.sample_time
        self.speeds = np.asarray(speeds, dtype=float)
        self.kinds = np.array(kinds)
        self.values = np.asarray(values, dtype=float)
        self.k = -1
        self.kf = int(round(FAULT_TIME / self.T))
        # each run's noise from its own stream (seed, speed in mm/s modulo 2^32 (a reverse speed's stream is not
        # the forward one's), fault kind and value): a run's result does not depend on the other runs of its batch
        nk = int(math.ceil((FAULT_TIME + WINDOW) / self.T)) + 2
        self.noise = np.array([np.random.default_rng([seed, int(round(1e3 * u)) % 2 ** 32, sum(map(ord, kd)),
                                                      int(round(1e3 * v))]).standard_normal(nk)
                               for u, kd, v in zip(self.speeds, kinds, self.values, strict=True)])
        self.sigma = sched.gyro.sample_std
        self.bias = sched.gyro.bias_deg_s * _DEG
        self.track = tables.track
        self.d1 = sched.chair.d1
        self.mz_per_tau = float(sched.drive.yaw_moment(sched.chair, 1.0))
        self.slip_cap = (traction_limit(sched) if traction_limit_N_m is None else float(traction_limit_N_m)) * 0.5
        self.lag = sched.drive.motor_time_constant
        self.decay = math.exp(-self.T / self.lag) if self.lag > 0 else 0.0
        self.u = np.zeros(R)          # held yaw moment
        self.m = np.zeros(R)          # motor state at the sample
        self.last_gyro = np.zeros(R)
        self.held = np.zeros(R)
        self.detect_k = np.full(R, -1)
        self.r = np.zeros(R)

    def _sensors(self, k: int, r: np.ndarray, u_fwd: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        kinds, vals = self.kinds, self.values
        after = k >= self.kf
        noise = self.noise[:, min(k, self.noise.shape[1] - 1)] * self.sigma
        noise = np.where(after & (kinds == "noise"), noise * vals, noise)
        g = r + self.bias + noise
        g = np.where(after & (kinds == "bias"), g + vals * _DEG, g)
        g = np.where(after & (kinds == "sign"), -g, g)
        g = np.where(after & (kinds == "stuck_zero"), 0.0, g)
        if k == self.kf:
            self.held = self.last_gyro.copy()
        hold = after & ((kinds == "stuck_last") | ((kinds == "dropout") & (k < self.kf + np.rint(vals / self.T))))
        g = np.where(hold, self.held, g)
        # wheel speeds: left U + r d1, right U - r d2; a lost sensor reads 0 (the right one here)
        w = np.where(after & (kinds == "wheel_lost"), (u_fwd + r * self.d1) / self.track, r)
        self.last_gyro = g
        return g, w

    def __call__(self, t: float, state: Any) -> np.ndarray:
        idx = np.asarray(state.run, dtype=int)
        k = int(math.floor(t / self.T + 1e-9))
        while self.k < k:
            self.k += 1
            r = np.zeros(len(self.speeds))
            u_fwd = self.speeds.copy()
            r[idx] = np.asarray(state.yaw_rate, dtype=float)
            u_fwd[idx] = np.asarray(state.u, dtype=float)
            g, w = self._sensors(self.k, r, u_fwd)
            tau = self.fc.step(self.speeds, 0.0, g, w)
            self.detect_k = np.where((self.fc.mode != 0) & (self.detect_k < 0), self.k, self.detect_k)
            tau = np.where(self.kinds == "slip", np.clip(tau, -self.slip_cap, self.slip_cap), tau)
            tau = np.where(self.kinds == "open", 0.0, tau)
            self.m = self.u + (self.m - self.u) * self.decay if self.k > 0 else self.m
            self.u = tau * self.mz_per_tau
        out = self.u + (self.m - self.u) * (math.exp(-(t - self.k * self.T) / self.lag) if self.lag > 0 else 0.0)
        return out[idx]


def _measures(res: Any, window: float = WINDOW) -> tuple[float, float, float]:
    """Peak heading error (deg), peak yaw rate (deg/s) and lateral drift (m) over the window after the fault."""
    t = np.asarray(res.t)
    sel = (t >= FAULT_TIME - 1e-9) & (t <= FAULT_TIME + window + 1e-9)
    psi0 = float(res.heading[0])
    x0, y0 = float(res.x[0]), float(res.y[0])
    lat = -(np.asarray(res.x) - x0) * math.sin(psi0) + (np.asarray(res.y) - y0) * math.cos(psi0)
    if not np.any(sel):
        return math.inf, math.inf, math.inf
    i0 = int(np.flatnonzero(sel)[0])
    he = float(np.max(np.abs(np.asarray(res.heading)[sel] - psi0))) / _DEG
    pr = float(np.max(np.abs(np.asarray(res.yaw_rate)[sel]))) / _DEG
    drift = float(abs(lat[sel][-1] - lat[i0]))
    if res.stopped_by_warnings or t[-1] < FAULT_TIME + window - 1e-6:
        return max(he, HEADING_BOUND_DEG * 10), pr, max(drift, DRIFT_BOUND_M * 10)    # left the model: unbounded
    return he, pr, drift


def fault_runs(sched: Schedule, *, speeds: Sequence[float] | None = None, slopes: Sequence[float] = (0.0, 2.0),
               faults: Sequence[str] | None = None, seed: int = 0, dt: float = 0.001,
               progress: bool = False, window: float = WINDOW) -> list[FaultRow]:
    """Each fault at each speed and slope, with the unassisted chair as reference (one batch per slope).

    A layout's schedule (:class:`stability.assist.layout.LayoutSchedule`, signed speeds) runs in the layout
    simulator (:func:`stability.simulate.layout_batch.simulate_layout_batch`: the same hook at every step, the casters
    starting trailing for the direction, :func:`stability.study.layout_impulse.trailing_angles`), the slipping
    wheel capped at half the layout's traction limit (:func:`stability.assist.layout_checks.layout_traction_limit`).

    Parameters
    ----------
    sched : Schedule
        Gyro schedule (the short form's or a layout's).
    speeds : sequence of float, optional
        m/s; default the schedule's grid.
    slopes : sequence of float
        Cross slopes, deg.
    faults : sequence of str, optional
        Names from :data:`FAULTS` (default all).
    seed : int
    dt : float
        Simulator step, s.
    progress : bool
    window : float
        Judged time after the fault, s (default :data:`WINDOW`; shorter only for quick checks: the bounds are
        stated for :data:`WINDOW`).

    Returns
    -------
    list of FaultRow
    """
    names = list(FAULTS) if faults is None else list(faults)
    for n in names:
        if n not in FAULTS:
            raise ValueError(f"fault={n!r} is invalid; valid: {', '.join(FAULTS)}")
    U = np.asarray(sched.speeds if speeds is None else speeds, dtype=float)
    tables = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    layout = getattr(sched, "layout", None)
    rows: list[FaultRow] = []
    cases = [("open", "open", 0.0), *((n, *FAULTS[n]) for n in names)]
    for phi in slopes:
        run_speeds = np.repeat(U, len(cases))
        kinds = [c[1] for _ in U for c in cases]
        vals = np.array([c[2] for _ in U for c in cases])
        spec = RunSpec(horizon=FAULT_TIME + window, dt=dt, stop_on_warnings=False, cross_slope_deg=float(phi),
                       model="exact")
        hook = FaultHook(tables, sched, run_speeds, kinds, vals, seed=seed)     # traction_limit: a layout's too
        if layout is None:
            res = simulate_batch(sched.chair, run_speeds, spec, yaw_moment=hook, progress=progress)
        else:
            res = _layout_batch(layout, run_speeds, spec, hook)
        for i, s in enumerate(U):
            base = i * len(cases)
            he0, _, dr0 = _measures(res[base], window)
            for j, (name, _kind, _v) in enumerate(cases[1:], start=1):
                he, pr, dr = _measures(res[base + j], window)
                dk = int(hook.detect_k[base + j])
                det = dk >= 0
                ok = he <= HEADING_BOUND_DEG and dr <= DRIFT_BOUND_M
                rows.append(FaultRow(name, float(s), float(phi), det,
                                     (dk - hook.kf) * hook.T if det else None, he, pr, dr, he0, dr0,
                                     "safe" if ok else "unsafe"))
    return rows


def _layout_batch(layout: Any, speeds: np.ndarray, spec: RunSpec, hook: FaultHook) -> list[Any]:
    """The batch in the layout simulator, each run as :func:`_measures` reads it."""
    from types import SimpleNamespace

    from stability.simulate.layout_batch import simulate_layout_batch
    from stability.study.layout_impulse import trailing_angles

    runs = simulate_layout_batch(layout, [float(u) for u in speeds], spec, yaw_moment=hook,
                                 caster_angles_deg=[trailing_angles(layout, float(u)) for u in speeds])
    return [SimpleNamespace(t=r.t_s, heading=r.heading_rad, x=r.x_m, y=r.y_m, yaw_rate=r.yaw_rate_rad_s,
                            stopped_by_warnings=r.ended != "horizon") for r in runs]


def format_faults(rows: Sequence[FaultRow]) -> str:
    """A text table of :func:`fault_runs`.

    Parameters
    ----------
    rows : sequence of FaultRow

    Returns
    -------
    str
    """
    lines = [f"Single sensor faults at t = {FAULT_TIME:g} s, straight command, judged over {WINDOW:g} s (monitor: "
             f"|gyro - wheel yaw rate - bias estimate| > {MONITOR_THRESHOLD_DEG_S:g} deg/s after a "
             f"{1e3 * MONITOR_TIME:g} ms low-pass; degraded mode: steer on the healthy yaw sensor, speed "
             f"limit {DEGRADED_SPEED:g} m/s; safe: heading error within {HEADING_BOUND_DEG:g} deg and drift within "
             f"{DRIFT_BOUND_M:g} m)",
             f"{'fault':26s} {'m/s':>5s} {'slope':>5s} {'detect s':>8s} {'head deg':>8s} {'yaw deg/s':>9s} "
             f"{'drift m':>7s}  outcome"]
    for r in rows:
        det = f"{r.detection_time_s:8.3f}" if r.detection_time_s is not None else f"{'-':>8s}"
        lines.append(f"{r.fault:26s} {r.speed_m_s:5.2f} {r.slope_deg:5.1f} {det} {r.peak_heading_error_deg:8.2f} "
                     f"{r.peak_yaw_rate_deg_s:9.2f} {r.drift_m:7.3f}  {r.outcome}")
    return "\n".join(lines)
