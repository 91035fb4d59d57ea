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
from stability.assist._memo import memo
from stability.assist.disk import disk_margins, frequency_response
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
from stability.chair.model import takes_chair
from stability.chair.power import DriveTrain
from stability.runtime.checks import check_choice
from stability.settings.defaults import SAMPLE_RATE_HZ

__all__ = ["Design", "design", "realise", "closed_loop_poles", "LoopMargins", "loop_margins", "LOOP_INPUT",
           "LOOP_OUTPUT", "GAIN_UNITS", "on_drive"]

_DEG = math.pi / 180.0
#: Signal names of the loop broken at the plant input (:meth:`Design.loop`, ``discrete_loop``): the yaw moment
#: applied at the plant input and the controller's output ``-Mz`` (both N m).
LOOP_INPUT, LOOP_OUTPUT = "Mz_N_m", "u_N_m"
#: Unit of each gain by state (:attr:`Design.K`: N m of yaw moment; :attr:`Design.wheel_torque_gains`: N m per
#: drive wheel) per SI unit of the state.
GAIN_UNITS = {"v": "N m/(m/s)", "r": "N m/(rad/s)", "eta": "N m/rad", "eta_dot": "N m/(rad/s)", "beta": "N m/rad",
              "beta_dot": "N m/(rad/s)", "psi": "N m/rad", "mz": "N m/N m"}


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
        LQR gain on ``plant.states`` as a yaw moment: ``Mz = -K x`` (N m of yaw
        moment per SI unit of each state: N m/(m/s), N m/(rad/s), N m/rad, ...).
        The command line prints the same gain per drive wheel,
        :attr:`wheel_torque_gains` (``K`` times ``wheel_radius / track_width``).
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
    wheel_radius : float
        Rolling radius ``r`` of the drive wheels (m), from the design's
        :class:`~stability.chair.power.DriveTrain` (nan for a design made by
        :func:`realise` alone).
    track_width : float
        ``d1 + d2``, the lateral distance between the drive wheels' contact
        points (m): the arm of the couple of the two wheel forces
        (:meth:`~stability.chair.power.DriveTrain.lever`).  A differential
        torque ``tau`` per wheel (``+tau`` left, ``-tau`` right) gives ground
        forces ``+-tau / r`` and the yaw moment ``Mz = tau (d1 + d2) / r``
        (Collins 1987, eq 6-3; ``docs/power-chair.md``).
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
    wheel_radius: float = math.nan
    track_width: float = math.nan

    @property
    def yaw_moment_per_wheel_torque(self) -> float:
        """``(d1 + d2) / r``: yaw moment (N m) per N m of differential torque per wheel (-).

        3.09 for the power-fwd preset (0.55 m / 0.178 m); nan when the design has no drive train.
        """
        return float(self.track_width / self.wheel_radius)

    @property
    def wheel_torque_gains(self) -> np.ndarray:
        """The LQR gain as differential torque per drive wheel, ``tau = -k x`` (1, n): the command line's gains.

        ``k = K r / (d1 + d2)`` (:attr:`wheel_radius`, :attr:`track_width`), in N m per wheel per SI unit of
        each state (:data:`GAIN_UNITS`).

        Returns
        -------
        ndarray (1, n)
        """
        return self.K / self.yaw_moment_per_wheel_torque

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
            SISO, continuous: input ``Mz_N_m`` (the yaw moment at the plant
            input, N m), output ``u_N_m`` (the controller's output ``-Mz``,
            N m); named ``<design>_loop_U<speed>`` like
            :func:`~stability.assist.digital.discrete_loop`.
        """
        p = true_plant or self.plant
        P = p.ss("states" if self.kind == "full-state" else "gyro")[:, 0]
        C = self.controller_ss()
        L = control.series(P, C)            # states: the plant's, then the controller's
        states = [*p.states, *C.state_labels] if L.nstates == p.n + C.nstates else None
        return control.ss(L.A, L.B, L.C, L.D, inputs=[LOOP_INPUT], outputs=[LOOP_OUTPUT], states=states,
                          name=system_name(f"{self.kind.replace('-', '_')}_loop", self.speed))

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
        Cy = measurement_matrix(self.kind, p.n, p.psi)
        n = self.Ac.shape[0]
        top = np.hstack([p.A - p.B @ self.Dc @ Cy, -p.B @ self.Cc]) if n else p.A - p.B @ self.Dc @ Cy
        if not n:
            return top
        bottom = np.hstack([self.Bc @ Cy, self.Ac])
        return np.vstack([top, bottom])

    def gains_dict(self, per_wheel: bool = False) -> dict[str, float]:
        """LQR gains by state name: yaw moment (N m per SI unit of the state, :attr:`K`) or, with
        ``per_wheel``, differential torque per drive wheel (:attr:`wheel_torque_gains`, the command line's).

        Parameters
        ----------
        per_wheel : bool

        Returns
        -------
        dict
        """
        k = self.wheel_torque_gains if per_wheel else self.K
        return {s: float(x) for s, x in zip(self.plant.states, k[0], strict=True)}


@takes_chair
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
        return on_drive(realise(kind, p, K, None), gyro, drive, chair)
    d = realise(kind, p, K, _kalman(p, gyro, estimator) if speed != 0 else _kalman_standstill(p, gyro, estimator))
    return on_drive(d, gyro, drive, chair)


def on_drive(d: Design, gyro: GyroSensor, drive: DriveTrain, chair: Chair) -> Design:
    """``d`` with the sample time of ``gyro`` and the wheel radius and track width of ``drive`` on ``chair``.

    Parameters
    ----------
    d : Design
    gyro : GyroSensor
    drive : DriveTrain
    chair : Chair

    Returns
    -------
    Design
    """
    return replace(d, sample_time=1.0 / gyro.sample_rate_hz, wheel_radius=float(drive.wheel_radius),
                   track_width=float(drive.lever(chair)))


def _kalman(p: Plant, gyro: GyroSensor, est: EstimatorWeights) -> np.ndarray:
    C = np.zeros((1, p.psi))
    C[0, 1] = 1.0
    G = np.hstack([p.Bf6, p.B6])
    QN = np.diag([est.lateral_force, est.yaw_moment])
    RN = np.array([[gyro.noise_psd]])
    L, _, _ = control.lqe(p.A6, G, C, QN, RN)
    return np.asarray(L, dtype=float).reshape(p.psi, 1)


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
    Le = np.vstack([L, np.zeros((len(idx) - p.psi, 1))])
    Kx, Kpsi = K[:, idx], K[:, p.psi:p.psi + 1]
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
    min_return_difference : float
        ``min |1 + L(jw)|`` (-), the return difference: the skew-1 (sensitivity) disk margin ``1 / max |S|``
        (LQR guarantees >= 1).
    disk_margin : float
        Balanced (skew 0) disk margin ``alpha`` (-; :mod:`stability.assist.disk`, Seiler, Packard & Gahinet
        2020): stable for every simultaneous gain and phase change inside the disk.
    disk_gain_margin_db : float
        Gain change the disk guarantees, up or down (dB); at most the classical margins.
    disk_phase_margin_deg : float
        Phase change the disk guarantees (deg), ``2 atan(alpha / 2)``; at most the classical one.
    disk_frequency_rad_s : float or None
        Frequency of the disk margin's worst case (rad/s).
    """

    gain_margin_upper: float
    gain_margin_lower: float
    phase_margin_deg: float
    crossover_rad_s: float | None
    delay_margin_s: float
    min_return_difference: float
    disk_margin: float = math.nan
    disk_gain_margin_db: float = math.nan
    disk_phase_margin_deg: float = math.nan
    disk_frequency_rad_s: float | None = None

    def to_dict(self) -> dict[str, float | str | None]:
        """JSON-ready dict (infinities as ``"inf"``)."""
        return {k: json_float(getattr(self, k)) for k in self.__dataclass_fields__}


def loop_margins(d: Design, true_plant: Plant | None = None) -> LoopMargins:
    """Stability margins of the loop broken at the plant input (the yaw-moment command).

    Uses :func:`control.stability_margins` (``returnall=True``) on
    ``L(s) = C(s) P(s)``; the return difference ``min |1 + L(jw)|`` is
    checked on a dense frequency grid (1e-3 to 1e4 rad/s), and the balanced
    disk margin (:func:`~stability.assist.disk.disk_margins`) is taken on
    the same grid.

    Parameters
    ----------
    d : Design
    true_plant : Plant, optional
        The plant the controller acts on (default: its design plant).

    Returns
    -------
    LoopMargins
    """
    if true_plant is None:
        return memo(d, ("loop",), lambda: _loop_margins(d, None))
    return _loop_margins(d, true_plant)


def _loop_margins(d: Design, true_plant: Plant | None) -> LoopMargins:
    L = d.loop(true_plant)
    # python-control's search for the stability-margin frequency (_poly_iw_wstab) evaluates a polynomial's
    # derivative at each of its roots; at a root near the top of the floating-point range that overflows (a numpy
    # RuntimeWarning).  There |1 + L(jw)| -> 1 (L strictly proper), never the minimum, and the margins reported
    # here come from the crossings and the dense-grid return difference: not a fault, and printed on every run it
    # was noise (the user-journey review), so that overflow alone is silenced; any other warning still shows
    with np.errstate(over="ignore"):
        gm, pm, sm, wpc, wgc, wms = control.stability_margins(L, returnall=True)
    m = _margins(L, gm, pm, sm, wgc, continuous=True)
    if closed_loop_poles(d, true_plant).real.max() >= 0:
        # the disk margin is the distance to instability of a stable loop; an unstable one has none
        m = replace(m, disk_margin=0.0, disk_gain_margin_db=0.0, disk_phase_margin_deg=0.0, disk_frequency_rad_s=None)
    return m


def _margins(L: Any, gm: Any, pm: Any, sm: Any, wgc: Any, *, continuous: bool, dt: float = 0.0,
             return_difference: float | None = None) -> LoopMargins:
    w = np.geomspace(1e-3, 1e4, 6000) if continuous else np.geomspace(1e-3, math.pi / dt * (1 - 1e-9), 6000)
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
    rd, resp = return_difference, None
    if rd is None:
        resp = frequency_response(L, w)
        rd = float(np.min(np.abs(1.0 + resp)))
    sm_c = np.atleast_1d(np.asarray(sm, dtype=float))
    # 2000 frequencies, the worst one refined; the dense grid's response at them when computed above (each
    # frequency is its own solve: the same numbers as solving at the subset)
    dk = disk_margins(L, w[::3], None if resp is None else resp[::3])
    return LoopMargins(
        gain_margin_upper=float(upper.min()) if upper.size else math.inf,
        gain_margin_lower=float(lower.max()) if lower.size else 0.0,
        phase_margin_deg=float(pm_abs.min()) if pm_abs.size else math.inf,
        crossover_rad_s=float(wgc[ok][np.argmin(pm_abs)]) if pm_abs.size else None,
        delay_margin_s=float(np.min(delay)) if np.size(delay) else math.inf,
        min_return_difference=min(rd, float(np.min(sm_c))) if sm_c.size and np.all(np.isfinite(sm_c)) else rd,
        disk_margin=dk.alpha, disk_gain_margin_db=dk.gain_db, disk_phase_margin_deg=dk.phase_deg,
        disk_frequency_rad_s=dk.frequency_rad_s,
    )
