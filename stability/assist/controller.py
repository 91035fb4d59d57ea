"""A design run as a sampled motor controller: the ``yaw_moment(t, state)`` hook of the simulator."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.linalg import expm

from ..chair import Chair
from ..power_chair import DriveTrain
from .design import Design
from .weights import DEFAULT_GYRO, GyroSensor

__all__ = ["DigitalController"]

_DEG = math.pi / 180.0


class DigitalController:
    """A design run as a sampled controller: the ``yaw_moment(t, state)`` hook of the simulator.

    At every sample ``t_k = k / sample_rate`` the controller reads the
    simulator's :class:`~stability.simulate.ChairState`, computes the yaw
    moment, converts it to a differential wheel torque, saturates that at
    the drive train's torque limit and holds the resulting yaw moment until
    the next sample.

    Full-state design: ``Mz = -K x(t_k)`` from the true states (ideal
    sensors: caster encoders, and the lateral velocity and heading taken
    as known).  Gyro design: the gyro reads ``r + bias + noise_k`` (white,
    seeded); the heading is its running sum ``psi_m``; the Kalman estimator
    is discretised exactly for inputs held over a sample and is driven by the
    torque actually applied.  The output at ``t_k`` uses the estimate
    predicted from samples before ``k`` (one sample of computation delay).

    Calls may come in any order (an adaptive integrator revisits times):
    the controller keeps its history per sample and rolls back.

    Parameters
    ----------
    d : Design
        The controller (e.g. ``Schedule.at(speed)``).
    chair : Chair
    drive : DriveTrain
        Wheel radius and torque limit.
    gyro : GyroSensor
        Sample rate, noise and bias.
    seed : int
        Seed of the gyro noise.
    noise : bool
        Gyro noise and bias on (gyro design).
    saturate : bool
        Limit the torque at ``drive.torque_limit``.

    Attributes after a run: ``samples`` (list of ``(t_k, tau_k)``, the
    applied differential torque per wheel, N m).
    """

    def __init__(self, d: Design, chair: Chair, drive: DriveTrain, *, gyro: GyroSensor = DEFAULT_GYRO,
                 seed: int = 0, noise: bool = True, saturate: bool = True) -> None:
        self.design = d
        self.chair = chair
        self.drive = drive
        self.gyro = gyro
        self.noise = bool(noise)
        self.saturate = bool(saturate)
        self.Ts = 1.0 / gyro.sample_rate_hz
        self._rng = np.random.default_rng(seed)
        self._noise = np.zeros(0)
        self._bias = gyro.bias_deg_s * _DEG if noise else 0.0
        self.__name__ = f"{d.kind} LQR"
        if d.kind == "gyro":
            assert d.model_A6 is not None and d.model_B6 is not None and d.L is not None
            C = np.zeros((1, 6))
            C[0, 1] = 1.0
            n = 6
            M = np.zeros((n + 2, n + 2))
            M[:n, :n] = d.model_A6 - d.L @ C       # the estimator's own model (interpolated if scheduled)
            M[:n, n:n + 1] = d.model_B6
            M[:n, n + 1:n + 2] = d.L
            E = expm(M * self.Ts)
            self._Phi = E[:n, :n]
            self._Gam = E[:n, n:n + 2]
        self._Kx: np.ndarray = d.Cc     # gyro design: the gain on the estimate
        self._Kpsi = float(d.Dc[0, 1]) if d.kind == "gyro" else 0.0
        self.reset()

    def reset(self) -> None:
        """Forget the run: estimate, heading and history back to zero."""
        self._k = -1
        self._hist: list[tuple[Any, ...]] = []        # per sample: (xhat_k, psi_k, mz_k, tau_k)
        self._xhat = np.zeros(6)
        self._psi = 0.0

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

    def _step(self, k: int, state: Any) -> None:
        d = self.design
        if d.kind == "full-state":
            x = np.array([state.v, state.yaw_rate, state.eta, state.eta_dot, state.beta, state.beta_dot,
                          state.heading], dtype=float)
            mz, tau = self._limit(-float(d.K[0] @ x))
            self._hist.append((None, None, mz, tau))
            return
        if k == 0:
            xhat, psi = np.zeros(6), 0.0
        else:
            xprev, psiprev, mzprev, _, rprev = self._hist[k - 1]
            xhat = self._Phi @ xprev + self._Gam @ np.array([mzprev, rprev])
            psi = psiprev + self.Ts * rprev
        r_m = float(state.yaw_rate) + self._bias + self._noise_at(k)
        mz, tau = self._limit(-(float(self._Kx[0] @ xhat) + self._Kpsi * psi))
        self._hist.append((xhat, psi, mz, tau, r_m))

    def __call__(self, t: float, state: Any) -> float:
        k = int(math.floor(t / self.Ts + 1e-9))
        if k < 0:
            k = 0
        if k < len(self._hist) - 1:
            del self._hist[k + 1:]          # an integrator went back in time
        while len(self._hist) <= k:
            self._step(len(self._hist), state)
        return self._hist[k][2]

    @property
    def samples(self) -> list[tuple[float, float]]:
        """``[(t_k, tau_k)]``: applied differential torque per wheel (N m) at each sample."""
        return [(i * self.Ts, h[3]) for i, h in enumerate(self._hist)]

