"""Nonlinear checks of the assist in the simulator: recovery after a lateral push, decay rate, torque need."""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, NamedTuple

import numpy as np

from stability.assist._format import json_float
from stability.assist.controller import DigitalController
from stability.assist.design import closed_loop_poles
from stability.assist.schedule import Schedule
from stability.assist.settling import SETTLE_FLOOR_DEG, SETTLE_FRACTION, settle_time, settled_value
from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.runtime.checks import check_speed
from stability.settings.reference import HORIZON, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.simulate.signals import envelope_rate
from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = ["SETTLE_FRACTION", "SETTLE_FLOOR_DEG", "RecoveryRun", "RecoveryPair", "settle_time", "recovery",
           "recovery_runs", "recovery_table", "minimum_torque_limit", "bisect_limit", "DecayAgreement",
           "decay_agreement", "decay_window", "fit_decay_rate", "CHECK_SPEEDS", "minimum_torque_json"]

#: The ten-times push of the strong-disturbance check (N): 400 N for 0.1 s.
STRONG_FORCE = 10.0 * THESIS_PUSH.force

@dataclass(frozen=True, eq=False)
class RecoveryRun:
    """One nonlinear run after a lateral impulse at the c.g.

    The *disturbance response* is the heading of this run minus the heading
    of a twin run without the impulse but with the same gyro noise and bias
    (same seed; for the noise-free full-state design and the open loop the
    twin runs straight and the response is the heading itself).

    Attributes
    ----------
    speed : float
        m/s.
    impulse_force, impulse_duration : float
        N, s (the thesis's reference: :data:`stability.settings.reference.THESIS_PUSH`).
    controlled : bool
        Closed loop (True) or the open-loop chair.
    peak_heading_error_deg : float
        Largest ``|heading|`` over the run (deg): what the user sees,
        including the drift and wander the gyro's bias and noise cause.
    peak_response_deg : float
        Largest ``|disturbance response|`` (deg).
    peak_torque_N_m : float
        Largest applied ``|tau|`` per wheel (N m); 0 open loop.
    saturated_fraction : float
        Share of the controller samples at the torque limit.
    settle_time_s : float or None
        Time after which the disturbance response stays within the larger of
        5 % of its peak departure from its final value and 0.1 deg of that
        final value (:func:`settle_time`); None if it never does before the
        end of the run or still departs in its last fifth (a diverging
        open-loop chair, a drifting heading).
    settled_response_deg : float or None
        The final value it settles about (deg; None when it does not settle).
    final_drift_deg_s : float
        Slope of the heading over the last 20 % of the run (deg/s): in
        closed loop the drift a gyro bias imposes (minus the bias).
    max_yaw_rate_deg_s : float
        Largest ``|r|`` (deg/s).
    time_to_10deg_s : float or None
        First time ``|heading|`` reaches 10 deg.
    caster_out_of_range : int
        Steps with a caster slip angle above 8 deg or a caster load above
        450 N (outside the caster tire's data; the drive tire is linear).
    stopped_by_warnings : bool
        The simulator stopped the run.
    result : SimulationResult
        The run.
    response : ndarray
        The disturbance response (deg) on ``result.t``.
    """

    speed: float
    impulse_force: float
    impulse_duration: float
    controlled: bool
    peak_heading_error_deg: float
    peak_response_deg: float
    peak_torque_N_m: float
    saturated_fraction: float
    settle_time_s: float | None
    final_drift_deg_s: float
    max_yaw_rate_deg_s: float
    time_to_10deg_s: float | None
    caster_out_of_range: int
    stopped_by_warnings: bool
    result: Any = field(repr=False)
    response: Any = field(repr=False, default=None)
    settled_response_deg: float | None = None

    def row(self) -> dict[str, Any]:
        """JSON-ready summary (the fields without ``result`` and ``response``)."""
        return {
            "speed_m_s": self.speed, "impulse_N": self.impulse_force, "impulse_s": self.impulse_duration,
            "controlled": self.controlled, "peak_heading_error_deg": self.peak_heading_error_deg,
            "peak_response_deg": self.peak_response_deg,
            "peak_torque_N_m": self.peak_torque_N_m, "saturated_fraction": self.saturated_fraction,
            "settle_time_s": self.settle_time_s, "settled_response_deg": self.settled_response_deg,
            "final_drift_deg_s": json_float(self.final_drift_deg_s),
            "max_yaw_rate_deg_s": self.max_yaw_rate_deg_s, "time_to_10deg_s": self.time_to_10deg_s,
            "caster_out_of_range_steps": self.caster_out_of_range, "stopped_by_warnings": self.stopped_by_warnings,
        }




class RecoveryPair(NamedTuple):
    """A closed-loop run and its open-loop twin (same speed and push).

    Attributes
    ----------
    closed : RecoveryRun
    open : RecoveryRun or None
        None when the open loop was not run.
    """

    closed: RecoveryRun
    open: RecoveryRun | None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready ``{"speed_m_s", "impulse_N", "closed", "open"}`` (``open`` only if run)."""
        row: dict[str, Any] = {"speed_m_s": self.closed.speed, "impulse_N": self.closed.impulse_force,
                               "closed": self.closed.row()}
        if self.open is not None:
            row["open"] = self.open.row()
        return row


def _simulate(chair: Chair, speed: float, controller: DigitalController | None, impulse_force: float,
              impulse_duration: float, duration: float, dt: float, model: str, scheme: str) -> Any:
    if controller is not None:
        controller.reset()
    return simulate(chair, speed, RunSpec(horizon=duration, scheme=scheme, model=model, dt=dt, push_force=impulse_force,
                                          push_duration=impulse_duration, stop_on_warnings=False),
                    yaw_moment=controller)


@takes_chair
def recovery(chair: Chair, speed: float, controller: DigitalController | None, *,
             impulse_force: float = THESIS_PUSH.force, impulse_duration: float = THESIS_PUSH.duration,
             duration: float = HORIZON, dt: float = 0.001, model: str = "exact",
             scheme: str = "wchair") -> RecoveryRun:
    """Simulate the nonlinear chair after a lateral impulse at the c.g., with or without the controller.

    Default: the WCHAIR fixed-step scheme (1 ms) on the exact model with the
    chair's Coulomb pin friction; the thesis's range rules are counted but do
    not stop the run (the power chair's drive wheels carry more than the
    450 N of the treadmill data by design; its drive tire is linear).  With
    a noisy gyro a twin run without the impulse gives the disturbance
    response (see :class:`RecoveryRun`).

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    controller : DigitalController or None
        None: the open-loop chair.
    impulse_force, impulse_duration : float
        Lateral push at the c.g. (N, s).
    duration, dt : float
        Run length and step (s).
    model : {"exact", "thesis"}
    scheme : {"wchair", "adaptive"}

    Returns
    -------
    RecoveryRun
    """
    speed = check_speed(speed)
    res = _simulate(chair, speed, controller, impulse_force, impulse_duration, duration, dt, model, scheme)
    t = np.asarray(res.t)
    head = np.degrees(np.asarray(res.heading))
    taus = np.array([s[1] for s in controller.samples if s[0] <= t[-1] + 1e-9]) if controller is not None else None
    noisy = controller is not None and controller.design.kind == "gyro" and controller.noise
    if noisy:
        twin = _simulate(chair, speed, controller, 0.0, impulse_duration, duration, dt, model, scheme)
        n = min(len(twin.t), len(t))
        resp = head[:n] - np.degrees(np.asarray(twin.heading))[:n]
    else:
        resp = head
    if controller is not None and taus is not None and taus.size:
        peak_tau = float(np.max(np.abs(taus)))
        sat = float(np.mean(np.abs(taus) >= controller.drive.torque_limit * (1 - 1e-9)))
    else:
        peak_tau, sat = 0.0, 0.0
    tail = t >= t[-1] - 0.2 * (t[-1] - t[0])
    drift = float(np.polyfit(t[tail], head[tail], 1)[0]) if tail.sum() >= 2 else float("nan")
    big = np.flatnonzero(np.abs(head) >= 10.0)
    slip = np.abs(np.asarray(res.slip_deg)[:, :2])
    load = np.asarray(res.normal_load)[:, :2]
    oor = int(np.sum(np.any((slip > SLIP_MAX_DEG) | (load > FZ_MAX_N), axis=1)))
    return RecoveryRun(
        speed=speed, impulse_force=float(impulse_force), impulse_duration=float(impulse_duration),
        controlled=controller is not None, peak_heading_error_deg=float(np.max(np.abs(head))),
        peak_response_deg=float(np.max(np.abs(resp))), peak_torque_N_m=peak_tau, saturated_fraction=sat,
        settle_time_s=settle_time(t[:len(resp)], resp), final_drift_deg_s=drift,
        settled_response_deg=settled_value(t[:len(resp)], resp),
        max_yaw_rate_deg_s=float(np.degrees(np.max(np.abs(res.yaw_rate)))),
        time_to_10deg_s=float(t[big[0]]) if big.size else None, caster_out_of_range=oor,
        stopped_by_warnings=bool(res.stopped_by_warnings), result=res, response=resp,
    )


#: The speeds of the nonlinear checks, m/s: the recovery runs, the decay checks, ``assist --min-torque`` and the
#: open-loop runs of the destabilising-moment figure (the layout form takes those inside each direction's grid).
CHECK_SPEEDS = (1.0, 2.0, 3.0)


def recovery_runs(sched: Schedule, speeds: Sequence[float] = CHECK_SPEEDS,
                  impulses: Sequence[float] = (THESIS_PUSH.force, STRONG_FORCE), *, seed: int = 0,
                  duration: float = HORIZON, noise: bool = True, open_loop: bool = True) -> list[RecoveryPair]:
    """Closed- and open-loop :class:`RecoveryRun` for every speed and impulse.

    Closed loop: the scheduled controller at that speed, torque-limited,
    with (gyro design, ``noise``) gyro noise and bias seeded with ``seed``
    plus the run's index, so the runs are deterministic.

    Parameters
    ----------
    sched : Schedule
    speeds : sequence of float
        m/s.
    impulses : sequence of float
        Push forces at the c.g. (N, for :data:`~stability.settings.reference.THESIS_PUSH`'s duration).
    seed : int
    duration : float
        s.
    noise : bool
        Gyro noise and bias.
    open_loop : bool
        Also run the chair without the controller.

    Returns
    -------
    list of RecoveryPair
    """
    out = []
    for i, (s, f) in enumerate(itertools.product(speeds, impulses)):
        ctl = DigitalController(sched.at(s), sched.chair, sched.drive, gyro=sched.gyro, seed=seed + i, noise=noise)
        closed = recovery(sched.chair, s, ctl, impulse_force=f, duration=duration, model=sched.model)
        opened = recovery(sched.chair, s, None, impulse_force=f, duration=duration, model=sched.model) \
            if open_loop else None
        out.append(RecoveryPair(closed, opened))
    return out


def recovery_table(runs: Sequence[RecoveryPair]) -> list[dict[str, Any]]:
    """JSON-ready rows ``{"speed_m_s", "impulse_N", "closed", "open"}`` from :func:`recovery_runs`.

    Parameters
    ----------
    runs : sequence of RecoveryPair

    Returns
    -------
    list of dict
    """
    return [RecoveryPair(*r).to_dict() for r in runs]


def minimum_torque_limit(sched: Schedule, speed: float, impulse_force: float = STRONG_FORCE, *,
                         max_heading_deg: float = 10.0, tol: float = 0.25, duration: float = HORIZON) -> float:
    """Smallest per-wheel torque limit with which the scheduled controller still recovers (N m).

    The thesis's question (chapter 9, "Future work"): what motor torque is
    needed to stabilise the chair against a disturbance.  The design (its
    gains) is kept; only the saturation of the digital controller changes.
    "Recovers" (:func:`stability.assist.settling.recovery_rule`): the disturbance response settles
    about its final value (:func:`settle_time`) and the heading stays
    within ``max_heading_deg``; 0 when the chair recovers unassisted.  Noise-free sensors
    (the bias and noise would blur the threshold); bisection to ``tol``
    N m between 0 and the drive train's limit.

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    impulse_force : float
        N for :data:`~stability.settings.reference.THESIS_PUSH`'s duration.
    max_heading_deg, tol, duration : float
        deg, N m, s.

    Returns
    -------
    float
        N m per wheel; ``inf`` if even the full limit does not recover.
    """
    speed = check_speed(speed)
    d = sched.at(speed)

    def ok(limit: float) -> bool:
        ctl = None if limit == 0 else DigitalController(d, sched.chair, replace(sched.drive, torque_limit=limit),
                                                        gyro=sched.gyro, noise=False)
        run = recovery(sched.chair, speed, ctl, impulse_force=impulse_force, duration=duration, model=sched.model)
        return run.settle_time_s is not None and run.peak_heading_error_deg <= max_heading_deg

    return bisect_limit(ok, float(sched.drive.torque_limit), tol)


def minimum_torque_json(least: Sequence[tuple[float, float]], push: float = STRONG_FORCE) -> list[dict[str, Any]]:
    """The JSON rows of ``assist --min-torque`` (both forms): one per speed, ``inf`` as ``"inf"`` (no limit up to
    the drive's recovers).

    Parameters
    ----------
    least : sequence of (float, float)
        (speed in m/s, negative in reverse; smallest torque limit per wheel in N m) pairs.
    push : float
        Lateral push force of the disturbance, N for :data:`~stability.settings.reference.THESIS_PUSH`'s duration.

    Returns
    -------
    list of dict
        ``speed_m_s``, ``push_N``, ``minimum_torque_limit_N_m`` per speed.
    """
    return [{"speed_m_s": float(u), "push_N": float(push), "minimum_torque_limit_N_m": json_float(t)}
            for u, t in least]


def bisect_limit(ok: Callable[[float], bool], hi: float, tol: float) -> float:
    """The smallest limit in ``[0, hi]`` for which ``ok`` holds, by bisection to ``tol`` (``ok`` taken monotone).

    Parameters
    ----------
    ok : callable
        ``ok(limit)``: does the controller with this torque limit (N m per wheel; 0: the chair unassisted)
        recover?
    hi : float
        The drive train's limit, N m per wheel.
    tol : float
        N m.

    Returns
    -------
    float
        N m per wheel (the upper end of the last bracket); ``inf`` if ``ok(hi)`` fails, 0 if ``ok(0)`` holds.
    """
    if not ok(hi):
        return math.inf
    if ok(0.0):
        return 0.0
    lo = 0.0
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if ok(mid):
            hi = mid
        else:
            lo = mid
    return hi


@dataclass(frozen=True)
class DecayAgreement:
    """Linear prediction vs nonlinear fit of the slowest closed-loop decay rate.

    Attributes
    ----------
    speed_m_s : float
    predicted_1_s : float
        Real part of the slowest closed-loop eigenvalue (1/s).
    fitted_1_s : float
        Envelope rate fitted to the simulated yaw rate (1/s).
    relative_error : float
        ``|fitted - predicted| / |predicted|``.
    window_s : tuple of float
        Fit window (s).
    frequency_rad_s : float
        Imaginary part of the slowest eigenvalue (rad/s).
    """

    speed_m_s: float
    predicted_1_s: float
    fitted_1_s: float
    relative_error: float
    window_s: tuple[float, float]
    frequency_rad_s: float


def decay_agreement(sched: Schedule, speed: float, *, impulse_force: float = THESIS_PUSH.force / 10.0,
                    impulse_duration: float = THESIS_PUSH.duration, decades: float = 3.0) -> DecayAgreement:
    """Does the linear closed loop predict the nonlinear decay rate?

    Simulates the scheduled controller (noise-free, sampled every step of
    the 1 ms WCHAIR scheme, no saturation reached) on the chair with its
    Coulomb pin friction removed (the linear model's pins are frictionless;
    friction would make small disturbances stick the casters), after a small
    lateral impulse (default a tenth of the reference push).  The
    envelope of the yaw rate is fitted (:func:`fit_decay_rate`) in a window
    that starts when the next-slowest closed-loop mode has decayed
    ``decades`` decades relative to the slowest and spans at least three
    half-periods of the slowest (if oscillatory) or ``decades`` decades of
    its decay.

    Parameters
    ----------
    sched : Schedule
    speed : float
        m/s.
    impulse_force, impulse_duration : float
        N, s.
    decades : float
        Decades of separation and of fit span.

    Returns
    -------
    DecayAgreement
    """
    speed = check_speed(speed)
    d = sched.at(speed)
    slow, (t0, t1) = decay_window(closed_loop_poles(d), impulse_duration, decades)
    w = abs(slow.imag)
    c = sched.chair.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    gyro = replace(sched.gyro, sample_rate_hz=1000.0)
    ctl = DigitalController(d, c, sched.drive, gyro=gyro, noise=False, saturate=False)
    res = _simulate(c, speed, ctl, impulse_force, impulse_duration, t1 + 0.1, 0.001, sched.model, "wchair")
    fitted = fit_decay_rate(res.t, res.yaw_rate, t0, t1)
    return DecayAgreement(speed, float(slow.real), fitted, abs(fitted - slow.real) / abs(slow.real),
                          (t0, t1), float(w))


def decay_window(lam: np.ndarray, impulse_duration: float, decades: float = 3.0) -> tuple[complex, tuple[float, float]]:
    """The slowest closed-loop eigenvalue and the window in which its decay is fitted (:func:`decay_agreement`).

    Parameters
    ----------
    lam : ndarray
        Closed-loop eigenvalues, slowest first (:func:`stability.assist.design.closed_loop_poles`), 1/s.
    impulse_duration : float
        s.
    decades : float
        Decades of separation from the next-slowest mode and of fit span.

    Returns
    -------
    (complex, (float, float))
        The slowest eigenvalue (1/s) and the window (s).
    """
    slow = lam[0]
    others = lam[np.abs(lam - np.conj(slow)) > 1e-9 * max(1.0, abs(slow))]
    others = others[np.abs(others - slow) > 1e-9 * max(1.0, abs(slow))]
    s2 = others.real.max() if others.size else 10 * slow.real
    gap = max(slow.real - s2, 1e-6)
    t0 = impulse_duration + decades * math.log(10) / gap
    w = abs(slow.imag)
    span = max(decades * math.log(10) / abs(slow.real), 3.5 * math.pi / w if w > 1e-6 else 0.0)
    return complex(slow), (float(t0), float(t0 + span))


def fit_decay_rate(t: np.ndarray, y: np.ndarray, t_start: float, t_end: float) -> float:
    """Exponential rate of the envelope of ``y`` (1/s); see :func:`stability.simulate.signals.envelope_rate`.

    Parameters
    ----------
    t, y : ndarray
        Time (s) and signal.
    t_start, t_end : float
        Fit window (s).

    Returns
    -------
    float
        1/s (negative for a decaying signal).
    """
    return envelope_rate(t, y, t_start, t_end)
