"""A design run as a sampled motor controller: the ``yaw_moment(t, state)`` hook of the simulator."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from scipy.linalg import expm

from stability.assist.design import Design
from stability.assist.tracking import feedforward
from stability.assist.weights import DEFAULT_GYRO, GyroSensor
from stability.chair import Chair
from stability.chair.power import DriveTrain
from stability.runtime.checks import check_choice, check_positive

__all__ = ["ANTI_WINDUP", "TRACKING_TIME", "DigitalController"]

_DEG = math.pi / 180.0
#: Anti-windup schemes of the heading-error integrator (the first is the default).
ANTI_WINDUP = ("back-calculation", "conditional", "none")
#: Tracking time constant ``T_t`` of the back-calculation (s); see docs/assist.md.
TRACKING_TIME = 0.005


class DigitalController:
    """A design run as a sampled controller: the ``yaw_moment(t, state)`` hook of the simulator.

    At every sample ``t_k = k T`` (``T = 1/sample_rate``) the controller
    reads the simulator's :class:`~stability.simulate.ChairState` and
    computes a yaw-moment command from the samples before ``k`` (one sample
    of computation delay: the command applied from ``t_k`` was computed
    during the previous interval); the command is converted to a
    differential wheel torque, saturated at the drive train's limit and
    held (zero-order hold).  The wheels apply it through the drive train's
    first-order motor lag (``motor_time_constant``), evaluated exactly
    between samples.

    Full-state design: ``x`` from the true states (caster encoders, lateral
    velocity known), with the gyro's yaw rate.  Gyro design: the gyro reads
    ``r + bias + noise_k`` (white, seeded); the Kalman estimator (with the
    motor model) is discretised exactly for inputs held over a sample and
    is driven by the torque actually commanded after saturation (no
    wind-up).  Both: the heading error is the running sum of the corrected
    gyro minus the yaw-rate command, the command's steady turn is fed
    forward (:func:`~stability.assist.tracking.feedforward`), and, with
    ``gyro.bias_time_constant_s > 0``, the bias estimate from the gyro minus
    the drive wheels' yaw rate is subtracted.

    Calls may come in any order (an adaptive integrator revisits times):
    the controller keeps its history per sample and rolls back.

    Parameters
    ----------
    d : Design
        The controller (e.g. ``Schedule.at(speed)``).
    chair : Chair
    drive : DriveTrain
        Wheel radius, torque limit, motor lag.
    gyro : GyroSensor
        Sample rate, noise, bias and bias handling.
    seed : int
        Seed of the gyro noise.
    noise : bool
        Gyro noise and bias on.
    saturate : bool
        Limit the torque at ``drive.torque_limit``.
    command : callable, optional
        Yaw-rate command ``r_cmd(t)`` (rad/s); None: straight (0).
    command_filter_s : float
        Time constant of the first-order reference model the command passes
        through before the controller uses it (s; 0: none), like the
        turn-acceleration setting of a power-chair controller.
    anti_windup : {"back-calculation", "conditional", "none"}
        Protection of the heading-error integrator while the torque
        saturates (:data:`ANTI_WINDUP`; docs/assist.md):
        ``"back-calculation"`` adds ``(Mz_k - sat(Mz_k)) / (K_psi T_t)`` to
        the integrator's rate (Astrom & Hagglund 1995, sec. 3.5; with
        ``Mz = ... - K_psi e`` this drives the unsaturated command back
        towards the limit); ``"conditional"`` freezes the integrator at the
        samples where the command is saturated and the error would drive it
        further into saturation; ``"none"``: the plain integrator.  Both act
        only while the joystick's (raw) command is a turn: with a straight
        command the integrator is the heading to hold, which must survive a
        saturating push.  Without saturation all three are the same
        controller.
    tracking_time_s : float
        ``T_t`` of the back-calculation (s; at least one sample).

    Attributes after a run: ``samples`` (list of ``(t_k, tau_k)``, the
    commanded differential torque per wheel, N m).
    """

    def __init__(self, d: Design, chair: Chair, drive: DriveTrain, *, gyro: GyroSensor = DEFAULT_GYRO,
                 seed: int = 0, noise: bool = True, saturate: bool = True,
                 command: Callable[[float], float] | None = None, command_filter_s: float = 0.0,
                 anti_windup: str = "back-calculation", tracking_time_s: float = TRACKING_TIME) -> None:
        self.design = d
        self.chair = chair
        self.drive = drive
        self.gyro = gyro
        self.noise = bool(noise)
        self.saturate = bool(saturate)
        self.command = command
        self._cmd_gain = 1.0 - math.exp(-1.0 / (gyro.sample_rate_hz * command_filter_s)) if command_filter_s > 0 \
            else 1.0
        self.Ts = 1.0 / gyro.sample_rate_hz
        self.anti_windup = check_choice("anti_windup", anti_windup, ANTI_WINDUP)
        self._aw_gain = self.Ts / max(float(check_positive("tracking_time_s", tracking_time_s)), self.Ts)
        self._rng = np.random.default_rng(seed)
        self._noise = np.zeros(0)
        self._bias = gyro.bias_deg_s * _DEG if noise else 0.0
        self.__name__ = f"{d.kind} LQR"
        p = d.plant
        self._idx = p.internal
        self._motor = p.has_motor
        self._tau = p.motor_time_constant
        self._decay = math.exp(-self.Ts / self._tau) if self._tau > 0 else 0.0
        tb = gyro.bias_time_constant_s
        self._bias_gain = 1.0 - math.exp(-self.Ts / tb) if tb > 0 else 0.0
        ff = feedforward(d.plant)
        Kint = d.K[0, self._idx]
        self._Kint = Kint
        self._Kpsi = float(d.K[0, p.psi])
        self._F = ff.Nu + float(Kint @ ff.Nx)
        if d.kind == "gyro":
            assert d.model_A is not None and d.model_B is not None and d.L is not None
            n = len(self._idx)
            C = np.zeros((1, n))
            C[0, 1] = 1.0
            Le = np.vstack([d.L, np.zeros((n - p.psi, 1))])
            M = np.zeros((n + 2, n + 2))
            M[:n, :n] = d.model_A - Le @ C       # the estimator's own model (interpolated if scheduled)
            M[:n, n:n + 1] = d.model_B
            M[:n, n + 1:n + 2] = Le
            E = expm(M * self.Ts)
            self._Phi = E[:n, :n]
            self._Gam = E[:n, n:n + 2]
        self.reset()

    def holding_heading(self, mz: float, states: Sequence[float] | None = None) -> float:
        """The heading (rad, clockwise +) at which the loop, commanded straight, holds the yaw moment ``mz``.

        In a steady state (noise-free, unsaturated, straight command) the yaw rate is zero, the motor has reached
        its command and the estimate is still, so the law ``Mz = -K_int x - K_psi e`` gives
        ``e = -(mz + K_int x) / K_psi``: the heading is wherever the heading-error integrator has to sit for the
        law to deliver ``mz``.  It is not the path's direction: the loop holds the integral of the gyro, so with
        a disturbance that needs a holding moment (a cross slope) the course ends ``e`` minus the crab angle.

        Gyro design: ``x`` is the estimator's fixed point ``x = Phi x + Gam [mz, 0]``, its level-ground model
        driven by ``mz`` with the gyro reading zero (biased: no model of the disturbance explains a constant
        moment without a yaw rate).  Full-state design: ``x`` is the measured steady states ``states``.

        Parameters
        ----------
        mz : float
            The steady applied yaw moment (N m, clockwise +).
        states : sequence of float, optional
            Full-state design only: the chair's steady states ``[v, r, eta, eta_dot, beta, beta_dot]``
            (m/s, rad/s, rad, rad/s, rad, rad/s; the simulator's convention).

        Returns
        -------
        float
            The heading-error integrator's steady value, rad: the loop's settled heading from its start.

        Raises
        ------
        ValueError
            A full-state design without ``states``, or ``states`` of the wrong length.
        """
        n = len(self._idx)
        if self.design.kind == "gyro":
            x = np.linalg.solve(np.eye(n) - self._Phi, self._Gam @ np.array([float(mz), 0.0]))
        else:
            chair = n - (1 if self._motor else 0)
            if states is None or len(states) != chair:
                raise ValueError(f"states={states!r} is invalid; valid: the full-state design's {chair} chair "
                                 f"states")
            x = np.array([*states, *([float(mz)] if self._motor else [])], dtype=float)
        return -(float(mz) + float(self._Kint @ x)) / self._Kpsi

    def reset(self) -> None:
        """Forget the run: estimate, heading, bias estimate, motor and history back to zero."""
        self._hist: list[tuple[Any, ...]] = []

    def _noise_at(self, k: int) -> float:
        if not self.noise:
            return 0.0
        while k >= self._noise.size:
            self._noise = np.concatenate([self._noise, self._rng.standard_normal(4096)])
        return float(self._noise[k]) * self.gyro.sample_std

    def _limit(self, mz: float) -> tuple[float, float]:
        tau = float(self.drive.wheel_torque(self.chair, mz))
        if self.saturate:
            lim = self.drive.torque_limit
            tau = min(max(tau, -lim), lim)
        return float(self.drive.yaw_moment(self.chair, tau)), tau

    def _cmd(self, k: int) -> float:
        """The reference-model output at sample ``k`` (rad/s)."""
        raw = float(self.command(k * self.Ts)) if self.command is not None else 0.0
        prev = self._hist[k - 1][8] if k > 0 else 0.0
        return prev + self._cmd_gain * (raw - prev)

    def _step(self, k: int, state: Any) -> None:
        # history entry: (xhat_k, e_k, u_k, tau_k, r_k corrected, m_k, x_k, bhat_k, rcmd_k, unsaturated Mz_k)
        r_gyro = float(state.yaw_rate) + self._bias + self._noise_at(k)
        if k == 0:
            xhat, e, m, bhat, u_prev, r_prev, x_prev, rc_prev = np.zeros(len(self._idx)), 0.0, 0.0, 0.0, 0.0, \
                0.0, None, 0.0
        else:
            xh, e0, u_prev, _, r_prev, m0, x_prev, bhat, rc_prev, mz_prev = self._hist[k - 1]
            turning = self.command is not None and float(self.command((k - 1) * self.Ts)) != 0.0
            e = e0 + self._integrate(r_prev - rc_prev, mz_prev - u_prev if turning else 0.0)
            m = u_prev + (m0 - u_prev) * self._decay if self._motor else u_prev
            xhat = self._Phi @ xh + self._Gam @ np.array([u_prev, r_prev]) if self.design.kind == "gyro" else xh
        # the bias estimate: gyro minus the drive wheels' yaw rate (the true yaw rate: no wheel slip)
        bhat = bhat + self._bias_gain * ((r_gyro - float(state.yaw_rate)) - bhat)
        r_corr = r_gyro - bhat
        # the full-state design's measurement (the short form's states; a gyro design reads the gyro alone)
        # (a layout's reading gives its own: v, r, then each caster's angle from its trailing angle and rate)
        x = np.array(self._chair_states(state, r_corr) + ([m] if self._motor else []), dtype=float) \
            if self.design.kind == "full-state" else None
        rc_prev_cmd = self._hist[k - 1][8] if k > 0 else 0.0
        if k == 0:
            mz, u, tau = 0.0, 0.0, 0.0
        else:
            est = xhat if self.design.kind == "gyro" else x_prev
            # Mz = -K_int (est - Nx r_cmd) - K_psi e + Nu r_cmd = -K_int est - K_psi e + F r_cmd
            mz = -float(self._Kint @ est) - self._Kpsi * e + self._F * rc_prev_cmd
            u, tau = self._limit(mz)
            # the excess is exactly 0 unless the torque is at its limit (no round-off from the unit conversion)
            mz = mz if self.saturate and abs(tau) >= self.drive.torque_limit else u
        self._hist.append((xhat, e, u, tau, r_corr, m, x, bhat, self._cmd(k), mz))

    @staticmethod
    def _chair_states(state: Any, r_corr: float) -> list[float]:
        """The full-state design's chair states, the yaw rate the corrected gyro's: the short form's ``v, r, eta,
        eta_dot, beta, beta_dot``, or a wheel layout's ``state.chair_states`` (``v, r``, then per caster its angle
        from its trailing angle and its rate; :class:`stability.assist.layout_command.LayoutReading`)."""
        own = getattr(state, "chair_states", None)
        if own is not None:
            return [float(own[0]), r_corr, *(float(x) for x in own[2:])]
        return [state.v, r_corr, state.eta, state.eta_dot, state.beta, state.beta_dot]

    def _integrate(self, err: float, excess: float) -> float:
        """Increment of the heading-error integrator over one sample (rad).

        ``err`` is the corrected yaw rate minus the command (rad/s), ``excess``
        the unsaturated minus the applied yaw moment (N m) of that sample
        while the joystick commands a turn (0 otherwise: with a straight
        command the integrator is the heading to hold and keeps its memory).
        """
        if excess == 0.0 or self.anti_windup == "none":
            return self.Ts * err
        if self.anti_windup == "conditional":
            # Mz = ... - K_psi e: a positive excess grows with -K_psi err, so freeze when that has its sign
            return 0.0 if -self._Kpsi * err * excess > 0 else self.Ts * err
        return self.Ts * err + self._aw_gain * excess / self._Kpsi

    def __call__(self, t: float, state: Any) -> float:
        k = int(math.floor(t / self.Ts + 1e-9))
        if k < 0:
            k = 0
        if k < len(self._hist) - 1:
            del self._hist[k + 1:]          # an integrator went back in time
        while len(self._hist) <= k:
            self._step(len(self._hist), state)
        h = self._hist[k]
        u, m = h[2], h[5]
        if not self._motor:
            return u
        return u + (m - u) * math.exp(-(t - k * self.Ts) / self._tau)

    @property
    def samples(self) -> list[tuple[float, float]]:
        """``[(t_k, tau_k)]``: commanded differential torque per wheel (N m) at each sample."""
        return [(i * self.Ts, h[3]) for i, h in enumerate(self._hist)]
