"""LQR yaw controller at one speed, its Kalman estimator (gyro design), closed-loop poles and margins.

References: Kwakernaak and Sivan (1972) for LQR and the Kalman-Bucy filter;
Doyle and Stein (1981) for loop-transfer recovery.  Rationale in ``docs/assist.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import control
import numpy as np

from stability.assist._format import json_float
from stability.assist.plant import Plant, measurement_matrix, plant, standstill_plant, system_name
from stability.assist.weights import (
    DEFAULT_ESTIMATOR,
    DEFAULT_GYRO,
    DEFAULT_WEIGHTS,
    DESIGNS,
    EstimatorWeights,
    GyroSensor,
    Weights,
)
from stability.chair import Chair
from stability.chair.power import DriveTrain
from stability.runtime.checks import check_choice
from stability.runtime.notes import library_warnings
from stability.settings.defaults import SAMPLE_RATE_HZ

__all__ = ["Design", "design", "realise", "closed_loop_poles", "LoopMargins", "loop_margins"]

_DEG = math.pi / 180.0


@dataclass(frozen=True, eq=False)
class Design:
    """A yaw controller at one speed.

    The controller's output is the yaw moment ``Mz = -(Cc xc + Dc y)`` with
    ``xc_dot = Ac xc + Bc y``; its measurement ``y`` is the seven states
    (full-state design) or ``[r, psi]`` (gyro design).

    Attributes
    ----------
    kind : {"full-state", "gyro"}
        Feedback structure.
    speed : float
        Design speed (m/s).
    plant : Plant
        Nominal plant the controller was designed on.
    K : ndarray (1, n)
        LQR gain (N m per unit state) on ``plant.states``.
    L : ndarray (6, 1) or None
        Kalman gain of the gyro design.
    Ac, Bc, Cc, Dc : ndarray
        Controller realisation.
    model_A, model_B : ndarray or None
        The model inside the estimator (gyro design; the plant without the
        heading: six chair states and, with a motor lag, the applied
        moment): the nominal plant's, or interpolated ones for a scheduled
        speed between grid points.
    sample_time : float
        Sample time of the sampled controller (s): ``1 / gyro.sample_rate_hz``
        of the design's :class:`~stability.assist.weights.GyroSensor`, so the
        discrete loop and its margins take it from here (given once).
    """

    kind: str
    speed: float
    plant: Plant
    K: np.ndarray
    L: np.ndarray | None
    Ac: np.ndarray
    Bc: np.ndarray
    Cc: np.ndarray
    Dc: np.ndarray
    model_A: np.ndarray | None = None
    model_B: np.ndarray | None = None
    sample_time: float = 1.0 / SAMPLE_RATE_HZ

    @property
    def measured(self) -> tuple[str, ...]:
        """Names of the controller's inputs."""
        return self.plant.states if self.kind == "full-state" else ("r", "psi")

    def controller_ss(self) -> control.StateSpace:
        """Controller as a :class:`control.StateSpace` (output ``u`` = ``-Mz``).

        Returns
        -------
        control.StateSpace
        """
        name = system_name(self.kind, self.speed)
        if self.Ac.shape[0] == 0:
            return control.ss([], [], [], self.Dc, inputs=list(self.measured), outputs=["u"], name=name)
        states = [f"xhat_{self.plant.states[i]}" for i in self.plant.internal]
        return control.ss(self.Ac, self.Bc, self.Cc, self.Dc, states=states,
                          inputs=list(self.measured), outputs=["u"], name=name)

    def loop(self, true_plant: Plant | None = None) -> control.StateSpace:
        """Loop transfer broken at the plant input, ``L(s) = C(s) P(s)`` (negative feedback).

        Parameters
        ----------
        true_plant : Plant, optional
            The plant the controller acts on (default: its design plant).

        Returns
        -------
        control.StateSpace
        """
        p = true_plant or self.plant
        P = p.ss("states" if self.kind == "full-state" else "gyro")[:, 0]
        return control.series(P, self.controller_ss())

    def closed_loop_matrix(self, true_plant: Plant | None = None) -> np.ndarray:
        """State matrix (1/s) of plant (seven states) plus controller.

        Parameters
        ----------
        true_plant : Plant, optional
            The plant the controller acts on (default: its design plant).

        Returns
        -------
        ndarray (n + n_c, n + n_c)
        """
        p = true_plant or self.plant
        Cy = measurement_matrix(self.kind, p.n)
        n = self.Ac.shape[0]
        top = np.hstack([p.A - p.B @ self.Dc @ Cy, -p.B @ self.Cc]) if n else p.A - p.B @ self.Dc @ Cy
        if not n:
            return top
        bottom = np.hstack([self.Bc @ Cy, self.Ac])
        return np.vstack([top, bottom])

    def gains_dict(self) -> dict[str, float]:
        """LQR gains by state name (N m per SI unit of the state)."""
        return {s: float(k) for s, k in zip(self.plant.states, self.K[0], strict=True)}


def design(chair: Chair, speed: float, kind: str = "gyro", *, weights: Weights = DEFAULT_WEIGHTS,
           drive: DriveTrain | None = None, gyro: GyroSensor = DEFAULT_GYRO,
           estimator: EstimatorWeights = DEFAULT_ESTIMATOR, model: str = "exact") -> Design:
    """LQR design (and, for ``kind="gyro"``, its Kalman estimator) at one speed.

    Parameters
    ----------
    chair : Chair
    speed : float
        Design speed (m/s, > 0; or exactly 0: the standstill design on
        :func:`~stability.assist.plant.standstill_plant`, LQR and Kalman on
        its yaw loop, zero gains on the slaved lateral velocity and the
        casters).
    kind : {"full-state", "gyro"}
        Feedback structure.
    weights : Weights
        LQR weights (Bryson's rule).
    drive : DriveTrain, optional
        Default :class:`~stability.chair.power.DriveTrain`; its
        ``motor_time_constant`` puts the motor lag into the design model.
    gyro : GyroSensor
        Gyro noise (Kalman measurement noise).
    estimator : EstimatorWeights
        Kalman process noise.
    model : {"exact", "thesis"}

    Returns
    -------
    Design
    """
    check_choice("design", kind, DESIGNS)
    drive = drive or DriveTrain()
    if speed == 0:
        p = standstill_plant(chair, drive.motor_time_constant, drive.yaw_damping)
        keep = [1, 6] + ([7] if p.n == 8 else [])        # the yaw loop: r, psi (, mz)
    else:
        p = plant(chair, speed, model, drive.motor_time_constant)
        keep = list(range(p.n))
    Q, R = weights.matrices(chair, drive, p.n)
    ix = np.ix_(keep, keep)
    Kr, _, _ = control.lqr(p.A[ix], p.B[keep], Q[ix], R)
    K = np.zeros((1, p.n))
    K[0, keep] = np.asarray(Kr, dtype=float).reshape(-1)
    if kind == "full-state":
        return replace(realise(kind, p, K, None), sample_time=1.0 / gyro.sample_rate_hz)
    d = realise(kind, p, K, _kalman(p, gyro, estimator) if speed != 0 else _kalman_standstill(p, gyro, estimator))
    return replace(d, sample_time=1.0 / gyro.sample_rate_hz)


def _kalman(p: Plant, gyro: GyroSensor, est: EstimatorWeights) -> np.ndarray:
    C = np.zeros((1, 6))
    C[0, 1] = 1.0
    G = np.hstack([p.Bf6, p.B6])
    QN = np.diag([est.lateral_force, est.yaw_moment])
    RN = np.array([[gyro.noise_psd]])
    L, _, _ = control.lqe(p.A6, G, C, QN, RN)
    return np.asarray(L, dtype=float).reshape(6, 1)


def _kalman_standstill(p: Plant, gyro: GyroSensor, est: EstimatorWeights) -> np.ndarray:
    """Kalman gain of the standstill plant: the yaw rate alone is estimated (the other gains are zero)."""
    G = np.hstack([p.Bf6[1:2], p.B6[1:2]])
    L, _, _ = control.lqe(p.A6[1:2, 1:2], G, np.ones((1, 1)), np.diag([est.lateral_force, est.yaw_moment]),
                          np.array([[gyro.noise_psd]]))
    out = np.zeros((6, 1))
    out[1, 0] = float(np.asarray(L).reshape(-1)[0])
    return out


def realise(kind: str, p: Plant, K: np.ndarray, L: np.ndarray | None) -> Design:
    """Controller matrices from the gains (see :class:`Design`).

    Parameters
    ----------
    kind : {"full-state", "gyro"}
    p : Plant
        The model inside the controller.
    K : ndarray (1, n)
        LQR gain.
    L : ndarray (6, 1) or None
        Kalman gain (gyro design).

    Returns
    -------
    Design
    """
    if kind == "full-state":
        return Design(kind, p.speed, p, K, None, np.zeros((0, 0)), np.zeros((0, p.n)), np.zeros((1, 0)), K.copy())
    assert L is not None
    idx = p.internal
    Am, Bm = p.A[np.ix_(idx, idx)], p.B[idx]
    Le = np.vstack([L, np.zeros((len(idx) - 6, 1))])
    Kx, Kpsi = K[:, idx], K[:, 6:7]
    C = np.zeros((1, len(idx)))
    C[0, 1] = 1.0
    Ac = Am - Bm @ Kx - Le @ C
    Bc = np.hstack([Le, -Bm @ Kpsi])
    Dc = np.hstack([np.zeros((1, 1)), Kpsi])
    return Design(kind, p.speed, p, K, L, Ac, Bc, Kx.copy(), Dc, Am.copy(), Bm.copy())


def closed_loop_poles(d: Design, true_plant: Plant | None = None) -> np.ndarray:
    """Closed-loop eigenvalues (1/s), sorted by decreasing real part.

    Parameters
    ----------
    d : Design
    true_plant : Plant, optional
        The plant the controller acts on (default: its design plant).

    Returns
    -------
    ndarray (complex)
    """
    lam = np.linalg.eigvals(d.closed_loop_matrix(true_plant))
    return lam[np.lexsort((-lam.imag, -lam.real))]


@dataclass(frozen=True)
class LoopMargins:
    """Stability margins of a loop broken at the plant input.

    Attributes
    ----------
    gain_margin_upper : float
        Smallest gain margin above 1 (inf if none).
    gain_margin_lower : float
        Largest gain margin below 1 (0 if none): the open-loop chair is
        unstable, so a gain *reduction* can destabilise.
    phase_margin_deg : float
        Smallest phase margin in magnitude (deg).
    crossover_rad_s : float or None
        Gain-crossover frequency of that phase margin (rad/s).
    delay_margin_s : float
        Smallest ``pm / w_gc``: the loop delay that destabilises (s).
    disk_margin : float
        ``min |1 + L(jw)|``, the return difference (LQR guarantees >= 1).
    """

    gain_margin_upper: float
    gain_margin_lower: float
    phase_margin_deg: float
    crossover_rad_s: float | None
    delay_margin_s: float
    disk_margin: float

    def to_dict(self) -> dict[str, float | str | None]:
        """JSON-ready dict (infinities as ``"inf"``)."""
        return {k: json_float(getattr(self, k)) for k in self.__dataclass_fields__}


def loop_margins(d: Design, true_plant: Plant | None = None) -> LoopMargins:
    """Stability margins of the loop broken at the plant input (the yaw-moment command).

    Uses :func:`control.stability_margins` (``returnall=True``) on
    ``L(s) = C(s) P(s)``; the return difference ``min |1 + L(jw)|`` is
    checked on a dense frequency grid (1e-3 to 1e4 rad/s).

    Parameters
    ----------
    d : Design
    true_plant : Plant, optional
        The plant the controller acts on (default: its design plant).

    Returns
    -------
    LoopMargins
    """
    L = d.loop(true_plant)
    # python-control's search for the stability-margin frequency (_poly_iw_wstab) evaluates a polynomial's
    # derivative at each of its roots; at a root near the top of the floating-point range that overflows (a numpy
    # RuntimeWarning).  There |1 + L(jw)| -> 1 (L strictly proper), never the minimum, and the margins reported
    # here come from the crossings and the dense-grid return difference: a note, not a fault
    with library_warnings("stability margins (python-control)",
                          "a candidate frequency near the floating-point limit, where |1 + L| is 1, never the "
                          "minimum: the margins are unaffected"):
        gm, pm, sm, wpc, wgc, wms = control.stability_margins(L, returnall=True)
    return _margins(L, gm, pm, sm, wgc, continuous=True)


def _margins(L: Any, gm: Any, pm: Any, sm: Any, wgc: Any, *, continuous: bool, dt: float = 0.0,
             disk: float | None = None) -> LoopMargins:
    gm = np.atleast_1d(np.asarray(gm, dtype=float))
    pm = np.atleast_1d(np.asarray(pm, dtype=float))
    wgc = np.atleast_1d(np.asarray(wgc, dtype=float))
    gm = gm[np.isfinite(gm) & (gm > 0)]
    gm = np.where(gm > 1e6, np.inf, gm)       # the polynomial method returns ~1e14 for "none"
    upper = gm[gm > 1.0]
    lower = gm[gm < 1.0]
    ok = np.isfinite(pm) & (wgc > 0)
    pm_abs = np.abs(pm[ok])
    # the smallest delay tau > 0 that rotates L(jw_gc) onto -1: w tau = pm (mod 360 deg); a negative pm at a
    # crossing of a stable loop needs 360 + pm of lag there (it read inf before)
    delay = (np.mod(pm[ok], 360.0) * _DEG / wgc[ok]) if ok.any() else np.array([np.inf])
    if disk is None:
        w = np.geomspace(1e-3, 1e4, 6000) if continuous else np.geomspace(1e-3, math.pi / dt, 6000)
        resp = np.asarray(L(1j * w if continuous else np.exp(1j * w * dt))).reshape(-1)
        disk = float(np.min(np.abs(1.0 + resp)))
    sm_c = np.atleast_1d(np.asarray(sm, dtype=float))
    return LoopMargins(
        gain_margin_upper=float(upper.min()) if upper.size else math.inf,
        gain_margin_lower=float(lower.max()) if lower.size else 0.0,
        phase_margin_deg=float(pm_abs.min()) if pm_abs.size else math.inf,
        crossover_rad_s=float(wgc[ok][np.argmin(pm_abs)]) if pm_abs.size else None,
        delay_margin_s=float(np.min(delay)) if np.size(delay) else math.inf,
        disk_margin=min(disk, float(np.min(sm_c))) if sm_c.size and np.all(np.isfinite(sm_c)) else disk,
    )
