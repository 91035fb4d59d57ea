"""Motor assist for a front-wheel-drive power chair: LQR yaw stabilisation.

Collins (1987, chapter 9, "Future work") notes that an electric chair can use
automatic control to hold a straight path, and that its motors must at least
offset the destabilising moment of the tire forces (his Figure 9-4).  This
module designs that control for the ``power-fwd`` preset
(:mod:`stability.power_chair`) or any other chair given a
:class:`~stability.power_chair.DriveTrain`, and checks it in the nonlinear
simulator.

Plant
-----
The linear model of :func:`stability.linear.state_space` at forward speed
``U`` (straight running, casters trailing, linear tires at their static
loads, frictionless pins) with states ``[v, r, eta, eta_dot, beta,
beta_dot]``, augmented with the heading ``psi`` (``psi_dot = r``; rad,
positive clockwise seen from above, like ``r``): seven states.  The input is
the yaw moment ``Mz`` of a differential drive-wheel torque ``tau`` per wheel,
``Mz = tau (d1 + d2) / r_wheel`` (derivation in :mod:`stability.power_chair`);
the common-mode torque holds the speed, so ``U`` is a parameter and every
design is a gain schedule over ``U``.  A second input, a lateral force ``Fy``
at the c.g. (the thesis's disturbance), is used for the estimator design and
for disturbance responses; its column comes from
:func:`stability.models.accelerations` (the equations of motion are linear in
the external loads at a fixed state).

Weights (Bryson's rule)
-----------------------
``Q = diag(1/x_max^2)``, ``R = 1/Mz_max^2`` with ``psi_max`` the acceptable
heading error (default 2 deg) and ``Mz_max`` the yaw moment of the torque
budget (default half the motor limit per wheel, 35 N m for the preset,
leaving the other half for larger disturbances before saturation).  For the
heading the LQR gain is then ``Mz_max/psi_max``: a 2 deg error commands the
whole budget (17.5 N m per wheel per degree).  Optional limits on the yaw
rate ``r_max`` and the lateral velocity ``v_max`` are off by default: the
heading weight alone gives a well-damped loop (slowest closed-loop pair
about ``-9 +/- 8j`` 1/s, crossover ~20 rad/s, delay margin ~50 ms), while a
yaw-rate weight of 10 deg/s pushes the crossover to ~40 rad/s and halves
the delay margin, which unmodelled lags (tire longitudinal relaxation,
gearbox backlash, the user's body not being rigid) would eat.  The caster
angles are not weighted: they are free to swivel, and the regulator only
needs them to stay stable.

Designs
-------
``"full-state"``
    LQR (:func:`control.lqr`) on all seven states, ``Mz = -K x``.  It needs
    the caster angles and rates (encoders on the caster stems, as some
    products have) and the lateral velocity (in practice from an
    accelerometer-aided estimator; here taken as measured), so it is the
    ideal benchmark: it has the LQR guarantees at the plant input (gain
    margin [1/2, inf), phase margin >= 60 deg, ``|1 + L| >= 1``).
``"gyro"``
    Gyro only: the yaw-rate gyro and its integral, the heading
    ``psi_m = integral of r_m`` (a state of the controller itself).  The same
    LQR gain acts on a Kalman estimate of the six chair states
    (:func:`control.lqe`, continuous-time, the gyro as the only
    measurement); the heading term uses ``psi_m`` directly.  This is LQG with
    loop-transfer recovery at the plant input: the estimator's process
    noise is a lateral force at the c.g. (spectral density ``W_Fy``, set
    from the thesis's 4 N s impulse arriving about once a second) and a yaw
    moment at the plant input (``W_Mz``), which is both physical (one drive
    wheel hitting a bump) and the Doyle-Stein recovery knob: as ``W_Mz``
    grows the loop broken at the plant input approaches the LQR loop and
    its margins.  The measurement noise is the gyro's white noise plus the
    frame vibration it picks up (``noise_density``).  The default recovery
    (``EstimatorWeights.recovery = 1``) puts the estimator's new pole near
    -160 1/s, about an eighth of the 200 Hz sample rate; it keeps a phase
    margin of ~57 deg and ``min |1 + L|`` ~0.9 (LQR: 64 deg, 1.0).  More
    recovery buys little margin for an estimator faster than the sampling
    supports.

    Why an estimator rather than static output feedback (yaw-rate damping
    plus heading stiffness): the chair's instability is a coupled
    yaw-caster motion, and an estimator lets the same LQR gains act on the
    caster states the gyro cannot see directly, so one weighting gives both
    designs and the full-state design is the measure of what the gyro
    design gives away.  A static output feedback has no such optimality
    and no systematic way to recover margins; the recovery term makes the
    estimator-based design keep most of the LQR margins, which is checked
    (margins, ``+/-30 %`` robustness box) rather than assumed.

Implementation
--------------
:class:`DigitalController` runs either design at a fixed sample rate
(default 200 Hz) with zero-order hold, as a motor controller does: the
estimator is discretised exactly for piecewise-constant inputs, the heading
integrates the sampled gyro, the torque saturates at the motor limit and the
estimator is fed the torque actually applied (no estimator wind-up).  Gyro
white noise and a constant bias come from a seeded generator, so every run is
deterministic.  A gyro bias is not observable from the gyro alone: the
controller holds the *measured* heading, so the chair drifts at minus the
bias rate; the nonlinear check reports that drift.

Analysis
--------
:func:`schedule` designs over a speed grid and interpolates gains (and, for
the gyro design, the estimator matrices) linearly in speed;
:func:`closed_loop_poles`, :func:`loop_margins` (loop broken at the plant
input, :func:`control.stability_margins`), :func:`robustness` (corners of a
``+/-30 %`` box in mass, yaw inertia and main and caster cornering
stiffness, nominal controller), :func:`destabilising_moment` (Figure 9-4 from
the simulator) and :func:`recovery` (nonlinear closed loop vs open loop).

Command line
------------
::

    python -m stability.assist --chair power-fwd --speeds 0.5:3.0:0.25 --design gyro \\
        --json assist.json --pdf assist.pdf
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ._validate import check_choice, check_nonnegative, check_positive, check_speed
from .chair import Chair
from .power_chair import DriveTrain
from .signals import envelope_rate
from .signals import settle_time as _settle_time

__all__ = [
    "DESIGNS",
    "STATES",
    "Weights",
    "GyroSensor",
    "EstimatorWeights",
    "Plant",
    "plant",
    "Design",
    "design",
    "Schedule",
    "schedule",
    "closed_loop_poles",
    "loop_margins",
    "Robustness",
    "robustness",
    "DigitalController",
    "RecoveryRun",
    "recovery",
    "recovery_table",
    "recovery_runs",
    "decay_agreement",
    "minimum_torque_limit",
    "destabilising_summary",
    "valid_until",
    "settle_time",
    "destabilising_moment",
    "fit_decay_rate",
    "main",
]

DESIGNS = ("full-state", "gyro")
STATES = ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "psi")
_DEG = math.pi / 180.0


# ---------------------------------------------------------------------------
# weights and sensors
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Weights:
    """LQR weights in physical terms (Bryson's rule).

    Attributes
    ----------
    max_heading_error_deg : float
        Acceptable heading error (deg): ``Q_psi = 1/psi_max^2``.
    max_yaw_rate_deg_s : float or None
        Acceptable yaw rate (deg/s): ``Q_r = 1/r_max^2`` (None: not weighted).
    max_lateral_velocity_m_s : float or None
        Acceptable lateral velocity (m/s) (None: not weighted).
    torque_budget_nm : float or None
        Differential torque per wheel (N m) the design may use for a typical
        error: ``R = 1/Mz_max^2`` with ``Mz_max`` its yaw moment.  None: half
        the drive train's torque limit.
    """

    max_heading_error_deg: float = 2.0
    max_yaw_rate_deg_s: float | None = None
    max_lateral_velocity_m_s: float | None = None
    torque_budget_nm: float | None = None

    def __post_init__(self) -> None:
        check_positive("max_heading_error_deg", self.max_heading_error_deg)
        for name in ("max_yaw_rate_deg_s", "max_lateral_velocity_m_s", "torque_budget_nm"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))

    def matrices(self, chair: Chair, drive: DriveTrain) -> tuple[np.ndarray, np.ndarray]:
        """``(Q, R)`` for the seven states of :data:`STATES` and the input ``Mz``."""
        q = np.zeros(len(STATES))
        q[STATES.index("psi")] = 1.0 / (self.max_heading_error_deg * _DEG) ** 2
        if self.max_yaw_rate_deg_s is not None:
            q[STATES.index("r")] = 1.0 / (self.max_yaw_rate_deg_s * _DEG) ** 2
        if self.max_lateral_velocity_m_s is not None:
            q[STATES.index("v")] = 1.0 / self.max_lateral_velocity_m_s ** 2
        budget = self.budget(drive)
        mz_max = drive.yaw_moment(chair, budget)
        return np.diag(q), np.array([[1.0 / mz_max ** 2]])

    def budget(self, drive: DriveTrain) -> float:
        """Torque budget per wheel (N m)."""
        return float(self.torque_budget_nm) if self.torque_budget_nm is not None else 0.5 * drive.torque_limit


@dataclass(frozen=True)
class GyroSensor:
    """Yaw-rate gyro as the controller sees it.

    Attributes
    ----------
    noise_density_deg_s : float
        White-noise density (deg/s per sqrt(Hz)) of the gyro signal
        including the frame vibration it picks up on a rolling chair.  MEMS
        gyros alone are 0.005-0.015 deg/s/sqrt(Hz); 0.05 allows for
        vibration.  The sampled noise has standard deviation
        ``density * sqrt(sample_rate/2)``.
    bias_deg_s : float
        Constant bias left after the at-rest calibration a controller does
        at power-up (deg/s).  Uncalibrated MEMS bias is up to ~1 deg/s;
        calibrated and temperature-drifted, ~0.05-0.1 deg/s.
    sample_rate_hz : float
        Controller and sensor sample rate (Hz).
    """

    noise_density_deg_s: float = 0.05
    bias_deg_s: float = 0.1
    sample_rate_hz: float = 200.0

    def __post_init__(self) -> None:
        for name in ("noise_density_deg_s", "bias_deg_s"):
            check_nonnegative(name, getattr(self, name))
        check_positive("sample_rate_hz", self.sample_rate_hz)

    @property
    def noise_psd(self) -> float:
        """Measurement-noise spectral density for the Kalman filter ((rad/s)^2 s)."""
        return max(self.noise_density_deg_s * _DEG, 1e-6 * _DEG) ** 2

    @property
    def sample_std(self) -> float:
        """Standard deviation of one noise sample (rad/s)."""
        return self.noise_density_deg_s * _DEG * math.sqrt(self.sample_rate_hz / 2.0)


@dataclass(frozen=True)
class EstimatorWeights:
    """Process-noise spectral densities of the Kalman filter of the gyro design.

    Attributes
    ----------
    lateral_force : float
        Lateral force at the c.g. (N^2 s).  The thesis's disturbance is a
        4 N s impulse; one such impulse a second is a white force of density
        ``4^2 = 16 N^2 s``.
    recovery : float
        Yaw-moment process noise at the plant input,
        ``W_Mz = (recovery * 0.5 m)^2 W_Fy``: the lateral-force noise acting
        with a lever of ``recovery`` times 0.5 m (about the wheelbase).
        Larger values recover the LQR loop at the plant input (Doyle and
        Stein) at the cost of a faster, noisier estimator.
    """

    lateral_force: float = 16.0
    recovery: float = 1.0

    def __post_init__(self) -> None:
        check_positive("lateral_force", self.lateral_force)
        check_positive("recovery", self.recovery)

    @property
    def yaw_moment(self) -> float:
        """Yaw-moment spectral density ``W_Mz`` (N^2 m^2 s)."""
        return (self.recovery * 0.5) ** 2 * self.lateral_force


# ---------------------------------------------------------------------------
# plant
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Plant:
    """Linear plant at one speed, augmented with the heading.

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    A : ndarray (7, 7)
        State matrix for :data:`STATES`.
    B : ndarray (7, 1)
        Yaw-moment input ``Mz`` (N m).
    Bf : ndarray (7, 1)
        Lateral force at the c.g. ``Fy`` (N).
    """

    speed: float
    A: np.ndarray
    B: np.ndarray
    Bf: np.ndarray

    @property
    def A6(self) -> np.ndarray:
        return self.A[:6, :6]

    @property
    def B6(self) -> np.ndarray:
        return self.B[:6]

    @property
    def Bf6(self) -> np.ndarray:
        return self.Bf[:6]

    def ss(self, outputs: str = "states"):
        """:class:`control.StateSpace` with inputs ``Mz``, ``Fy``.

        ``outputs="states"``: all seven states; ``"gyro"``: ``r`` and ``psi``.
        """
        import control

        Bu = np.hstack([self.B, self.Bf])
        if outputs == "states":
            C, names = np.eye(7), list(STATES)
        elif outputs == "gyro":
            C = np.zeros((2, 7))
            C[0, 1] = C[1, 6] = 1.0
            names = ["r", "psi"]
        else:
            raise ValueError(f"outputs={outputs!r} is invalid; valid choices: ['states', 'gyro']")
        return control.ss(self.A, Bu, C, np.zeros((C.shape[0], 2)), states=list(STATES),
                          inputs=["Mz", "Fy"], outputs=names, name=_sysname("chair", self.speed))


def _sysname(prefix: str, speed: float) -> str:
    """A python-control system name (no dots allowed): ``chair_U0p75``."""
    return f"{prefix}_U{speed:g}".replace(".", "p").replace("-", "_")


def _lateral_force_column(chair: Chair, speed: float, model: str) -> np.ndarray:
    """Response ``d(x_dot)/d(Fy)`` of the six chair states to a lateral force at the c.g."""
    from .models import accelerations
    from .params import parameters

    p = parameters(chair)
    z = 0.0

    def acc(fy):
        return np.array(accelerations(p, speed, z, z, 1.0, z, 1.0, z, z, z,
                                      z, z, z, z, z, z, z, z, z, z,
                                      Fy_ext=fy, Mz_ext=0.0, variant=model), dtype=float)

    d = acc(1.0) - acc(0.0)   # (u_dot, v_dot, r_dot, eta_dd, beta_dd)
    return np.array([d[1], d[2], 0.0, d[3], 0.0, d[4]])


def plant(chair: Chair, speed: float, model: str = "exact") -> Plant:
    """Linear plant of ``chair`` at ``speed`` (m/s), augmented with the heading."""
    from .linear import input_matrices, state_matrices

    speed = check_speed(speed)
    A6 = state_matrices(chair, speed, model)[0]
    B6 = input_matrices(chair, speed, model)[0]
    A = np.zeros((7, 7))
    A[:6, :6] = A6
    A[6, 1] = 1.0
    B = np.zeros((7, 1))
    B[:6] = B6
    Bf = np.zeros((7, 1))
    Bf[:6, 0] = _lateral_force_column(chair, speed, model)
    return Plant(speed, A, B, Bf)


# ---------------------------------------------------------------------------
# design at one speed
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Design:
    """A yaw controller at one speed.

    The controller's output is the yaw moment ``Mz = -(Cc xc + Dc y)`` with
    ``xc_dot = Ac xc + Bc y``; its measurement ``y`` is the seven states
    (full-state design) or ``[r, psi]`` (gyro design).

    Attributes
    ----------
    kind : {"full-state", "gyro"}
    speed : float
    plant : Plant
        Nominal plant the controller was designed on.
    K : ndarray (1, 7)
        LQR gain (N m per unit state) on :data:`STATES`.
    L : ndarray (6, 1) or None
        Kalman gain of the gyro design.
    Ac, Bc, Cc, Dc : ndarray
        Controller realisation.
    model_A6, model_B6 : ndarray or None
        The chair model inside the estimator (gyro design): the nominal
        plant's, or interpolated ones for a scheduled speed between grid
        points.
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
    model_A6: np.ndarray | None = None
    model_B6: np.ndarray | None = None

    @property
    def measured(self) -> tuple[str, ...]:
        """Names of the controller's inputs."""
        return STATES if self.kind == "full-state" else ("r", "psi")

    def controller_ss(self):
        """Controller as a :class:`control.StateSpace` (output ``u`` = ``-Mz``)."""
        import control

        name = _sysname(self.kind, self.speed)
        if self.Ac.shape[0] == 0:
            return control.ss([], [], [], self.Dc, inputs=list(self.measured), outputs=["u"], name=name)
        return control.ss(self.Ac, self.Bc, self.Cc, self.Dc, states=[f"xhat_{s}" for s in STATES[:6]],
                          inputs=list(self.measured), outputs=["u"], name=name)

    def loop(self, true_plant: Plant | None = None):
        """Loop transfer broken at the plant input, ``L(s) = C(s) P(s)`` (negative feedback)."""
        import control

        p = true_plant or self.plant
        P = p.ss("states" if self.kind == "full-state" else "gyro")[:, 0]
        return control.series(P, self.controller_ss())

    def closed_loop_matrix(self, true_plant: Plant | None = None) -> np.ndarray:
        """State matrix of plant (seven states) plus controller."""
        p = true_plant or self.plant
        Cy = _measurement_matrix(self.kind)
        n = self.Ac.shape[0]
        top = np.hstack([p.A - p.B @ self.Dc @ Cy, -p.B @ self.Cc]) if n else p.A - p.B @ self.Dc @ Cy
        if not n:
            return top
        bottom = np.hstack([self.Bc @ Cy, self.Ac])
        return np.vstack([top, bottom])

    def gains_dict(self) -> dict:
        """LQR gains by state name (N m per SI unit of the state)."""
        return {s: float(k) for s, k in zip(STATES, self.K[0])}


def _measurement_matrix(kind: str) -> np.ndarray:
    if kind == "full-state":
        return np.eye(7)
    C = np.zeros((2, 7))
    C[0, 1] = C[1, 6] = 1.0
    return C


def design(chair: Chair, speed: float, kind: str = "gyro", *, weights: Weights = Weights(),
           drive: DriveTrain | None = None, gyro: GyroSensor = GyroSensor(),
           estimator: EstimatorWeights = EstimatorWeights(), model: str = "exact") -> Design:
    """LQR design (and, for ``kind="gyro"``, its Kalman estimator) at one speed."""
    import control

    check_choice("design", kind, DESIGNS)
    drive = drive or DriveTrain()
    p = plant(chair, speed, model)
    Q, R = weights.matrices(chair, drive)
    K, _, _ = control.lqr(p.A, p.B, Q, R)
    K = np.asarray(K, dtype=float).reshape(1, 7)
    return _realise(kind, p, K, _kalman(p, gyro, estimator) if kind == "gyro" else None)


def _kalman(p: Plant, gyro: GyroSensor, est: EstimatorWeights) -> np.ndarray:
    import control

    C = np.zeros((1, 6))
    C[0, 1] = 1.0
    G = np.hstack([p.Bf6, p.B6])
    QN = np.diag([est.lateral_force, est.yaw_moment])
    RN = np.array([[gyro.noise_psd]])
    L, _, _ = control.lqe(p.A6, G, C, QN, RN)
    return np.asarray(L, dtype=float).reshape(6, 1)


def _realise(kind: str, p: Plant, K: np.ndarray, L: np.ndarray | None) -> Design:
    """Controller matrices from the gains (see :class:`Design`)."""
    if kind == "full-state":
        return Design(kind, p.speed, p, K, None, np.zeros((0, 0)), np.zeros((0, 7)), np.zeros((1, 0)), K.copy())
    Kx, Kpsi = K[:, :6], K[:, 6:7]
    C = np.zeros((1, 6))
    C[0, 1] = 1.0
    Ac = p.A6 - p.B6 @ Kx - L @ C
    Bc = np.hstack([L, -p.B6 @ Kpsi])
    Dc = np.hstack([np.zeros((1, 1)), Kpsi])
    return Design(kind, p.speed, p, K, L, Ac, Bc, Kx.copy(), Dc, p.A6.copy(), p.B6.copy())


# ---------------------------------------------------------------------------
# closed loop, margins
# ---------------------------------------------------------------------------
def closed_loop_poles(d: Design, true_plant: Plant | None = None) -> np.ndarray:
    """Closed-loop eigenvalues (1/s), sorted by decreasing real part."""
    lam = np.linalg.eigvals(d.closed_loop_matrix(true_plant))
    return lam[np.lexsort((-lam.imag, -lam.real))]


def loop_margins(d: Design, true_plant: Plant | None = None) -> dict:
    """Stability margins of the loop broken at the plant input (the yaw-moment command).

    Uses :func:`control.stability_margins` (``returnall=True``) on
    ``L(s) = C(s) P(s)``.  The open-loop chair is unstable, so the Nyquist
    plot must encircle -1 and a gain *reduction* can destabilise as well as
    an increase: ``gain_margin_upper`` is the smallest gain margin above 1
    (inf if none), ``gain_margin_lower`` the largest below 1 (0 if none).
    ``phase_margin_deg`` is the smallest phase margin in magnitude,
    ``delay_margin_s`` the smallest ``pm/w_gc`` (the loop delay that
    destabilises), and ``disk_margin`` ``min |1 + L(jw)|`` (the return
    difference; LQR guarantees >= 1), checked on a dense frequency grid.
    """
    import control

    L = d.loop(true_plant)
    gm, pm, sm, wpc, wgc, wms = control.stability_margins(L, returnall=True)
    gm = np.atleast_1d(np.asarray(gm, dtype=float))
    pm = np.atleast_1d(np.asarray(pm, dtype=float))
    wgc = np.atleast_1d(np.asarray(wgc, dtype=float))
    gm = gm[np.isfinite(gm) & (gm > 0)]
    gm = np.where(gm > 1e6, np.inf, gm)       # the polynomial method returns ~1e14 for "none"
    upper = gm[gm > 1.0]
    lower = gm[gm < 1.0]
    ok = np.isfinite(pm) & (wgc > 0)
    pm_abs = np.abs(pm[ok])
    delay = (np.where(pm[ok] > 0, pm[ok], np.inf) * _DEG / wgc[ok]) if ok.any() else np.array([np.inf])
    w = np.geomspace(1e-3, 1e4, 6000)
    resp = np.asarray(L(1j * w)).reshape(-1)
    disk = float(np.min(np.abs(1.0 + resp)))
    sm_c = np.atleast_1d(np.asarray(sm, dtype=float))
    return {
        "gain_margin_upper": float(upper.min()) if upper.size else math.inf,
        "gain_margin_lower": float(lower.max()) if lower.size else 0.0,
        "phase_margin_deg": float(pm_abs.min()) if pm_abs.size else math.inf,
        "crossover_rad_s": float(wgc[ok][np.argmin(pm_abs)]) if pm_abs.size else None,
        "delay_margin_s": float(np.min(delay)) if np.size(delay) else math.inf,
        "disk_margin": min(disk, float(np.min(sm_c))) if sm_c.size and np.all(np.isfinite(sm_c)) else disk,
    }


# ---------------------------------------------------------------------------
# gain schedule
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class Schedule:
    """Designs over a speed grid and their interpolation.

    Attributes
    ----------
    chair : Chair
    kind : {"full-state", "gyro"}
    speeds : ndarray (N,)
        Increasing design speeds (m/s).
    designs : tuple of Design
    drive : DriveTrain
    weights, gyro, estimator, model
        The design options.
    """

    chair: Chair
    kind: str
    speeds: np.ndarray
    designs: tuple
    drive: DriveTrain
    weights: Weights
    gyro: GyroSensor
    estimator: EstimatorWeights
    model: str

    @property
    def gains(self) -> np.ndarray:
        """LQR gains (N, 7)."""
        return np.array([d.K[0] for d in self.designs])

    def _interp(self, speed: float, attr: Callable[[Design], np.ndarray]) -> np.ndarray:
        stack = np.array([attr(d) for d in self.designs], dtype=float)
        s = float(np.clip(speed, self.speeds[0], self.speeds[-1]))
        if len(self.speeds) == 1:
            return stack[0]
        flat = stack.reshape(len(self.speeds), -1)
        out = np.array([np.interp(s, self.speeds, flat[:, j]) for j in range(flat.shape[1])])
        return out.reshape(stack.shape[1:])

    def gains_at(self, speed: float) -> np.ndarray:
        """LQR gain (1, 7) at ``speed``: linear interpolation in speed, held at the ends of the grid."""
        return self._interp(check_speed(speed), lambda d: d.K)

    def at(self, speed: float) -> Design:
        """The scheduled controller at ``speed``.

        Grid speeds give the designs themselves; between them the gains
        ``K`` and ``L`` and the estimator's model matrices (``A``, ``B`` of
        the plant) are interpolated entrywise, which is what a controller
        that stores tables does.  The ``plant`` of the returned design is
        the true linear plant at ``speed``.
        """
        speed = check_speed(speed)
        hit = np.flatnonzero(np.isclose(self.speeds, speed, rtol=0, atol=1e-12))
        if hit.size:
            return self.designs[int(hit[0])]
        K = self._interp(speed, lambda d: d.K)
        true_p = plant(self.chair, speed, self.model)
        if self.kind == "full-state":
            return _realise(self.kind, true_p, K, None)
        L = self._interp(speed, lambda d: d.L)
        A = self._interp(speed, lambda d: d.plant.A)
        B = self._interp(speed, lambda d: d.plant.B)
        p_model = Plant(speed, A, B, true_p.Bf)
        d = _realise(self.kind, p_model, K, L)
        return replace(d, plant=true_p)


def schedule(chair: Chair, speeds: Sequence[float], kind: str = "gyro", *, weights: Weights = Weights(),
             drive: DriveTrain | None = None, gyro: GyroSensor = GyroSensor(),
             estimator: EstimatorWeights = EstimatorWeights(), model: str = "exact") -> Schedule:
    """Design at every speed of an increasing grid (see :class:`Schedule`)."""
    check_choice("design", kind, DESIGNS)
    U = np.asarray(speeds, dtype=float).reshape(-1)
    if U.size == 0:
        raise ValueError("speeds: expected at least one speed")
    for s in U:
        check_speed(s)
    if np.any(np.diff(U) <= 0):
        raise ValueError("speeds must be strictly increasing")
    drive = drive or DriveTrain()
    ds = tuple(design(chair, s, kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator, model=model)
               for s in U)
    return Schedule(chair, kind, U, ds, drive, weights, gyro, estimator, model)


# ---------------------------------------------------------------------------
# robustness
# ---------------------------------------------------------------------------
#: Parameters of the robustness box and how a factor is applied to a chair.
ROBUST_PARAMETERS = ("mass", "yaw_inertia", "main_stiffness", "caster_stiffness")


def _perturbed(chair: Chair, factors: dict) -> Chair:
    return chair.replace(
        m=chair.m * factors["mass"],
        i_z=chair.i_z * factors["yaw_inertia"],
        main_lateral_scale=chair.main_lateral_scale * factors["main_stiffness"],
        caster_lateral_scale=chair.caster_lateral_scale * factors["caster_stiffness"],
    )


@dataclass(frozen=True, eq=False)
class Robustness:
    """Closed-loop stability over the corners of a parameter box, nominal controller.

    Attributes
    ----------
    box : float
        Relative half-width of the box (0.3: +/-30 %).
    speeds : ndarray (N,)
    corners : list of dict
        ``{parameter: factor}`` for each corner (mass, yaw inertia, main-tire
        and caster-tire cornering stiffness scaled independently: 16
        corners), the nominal chair first.
    max_real : ndarray (n_corners, N)
        Largest closed-loop real part (1/s) per corner and speed.
    worst : dict
        ``{"max_real_1_s", "speed_m_s", "corner"}`` of the largest real part.
    stable : bool
        All corners stable at all speeds.
    """

    box: float
    speeds: np.ndarray
    corners: list
    max_real: np.ndarray
    worst: dict
    stable: bool


def robustness(sched: Schedule, box: float = 0.3) -> Robustness:
    """Closed-loop stability of the scheduled controller when the chair differs from the design model.

    Mass, yaw inertia, main-tire and caster-tire cornering stiffness are each
    scaled by ``1 - box`` or ``1 + box`` (all 16 corners, plus the nominal
    chair); at every design speed the nominal controller closes the loop
    around the perturbed linear plant.  The stiffnesses are scaled through
    the lateral-force scale factors (TYMOD, CYMOD), so load-dependent tires
    also see the changed loads of the changed mass.
    """
    if not (isinstance(box, (int, float)) and 0 <= box < 1):
        raise ValueError(f"box={box!r} is invalid; valid range: 0 <= box < 1")
    corners = [{k: 1.0 for k in ROBUST_PARAMETERS}]
    for signs in itertools.product((-1.0, 1.0), repeat=len(ROBUST_PARAMETERS)):
        corners.append({k: 1.0 + s * box for k, s in zip(ROBUST_PARAMETERS, signs)})
    mr = np.empty((len(corners), len(sched.speeds)))
    for i, f in enumerate(corners):
        c = _perturbed(sched.chair, f)
        for j, (s, d) in enumerate(zip(sched.speeds, sched.designs)):
            mr[i, j] = closed_loop_poles(d, plant(c, s, sched.model)).real.max()
    i, j = np.unravel_index(int(np.argmax(mr)), mr.shape)
    worst = {"max_real_1_s": float(mr[i, j]), "speed_m_s": float(sched.speeds[j]), "corner": dict(corners[i])}
    return Robustness(float(box), sched.speeds.copy(), corners, mr, worst, bool(np.all(mr < 0)))


# ---------------------------------------------------------------------------
# digital implementation
# ---------------------------------------------------------------------------
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

    Attributes after a run: ``samples`` (list of ``(t_k, tau_k)``, the
    applied differential torque per wheel, N m).
    """

    def __init__(self, d: Design, chair: Chair, drive: DriveTrain, *, gyro: GyroSensor = GyroSensor(),
                 seed: int = 0, noise: bool = True, saturate: bool = True):
        from scipy.linalg import expm

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
        self._Kx = d.Cc if d.kind == "gyro" else None
        self._Kpsi = float(d.Dc[0, 1]) if d.kind == "gyro" else None
        self.reset()

    def reset(self) -> None:
        """Forget the run: estimate, heading and history back to zero."""
        self._k = -1
        self._hist: list = []        # per sample: (xhat_k, psi_k, mz_k, tau_k)
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

    def _step(self, k: int, state) -> None:
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

    def __call__(self, t: float, state) -> float:
        k = int(math.floor(t / self.Ts + 1e-9))
        if k < 0:
            k = 0
        if k < len(self._hist) - 1:
            del self._hist[k + 1:]          # an integrator went back in time
        while len(self._hist) <= k:
            self._step(len(self._hist), state)
        return self._hist[k][2]

    @property
    def samples(self) -> list:
        """``[(t_k, tau_k)]``: applied differential torque per wheel (N m) at each sample."""
        return [(i * self.Ts, h[3]) for i, h in enumerate(self._hist)]


# ---------------------------------------------------------------------------
# nonlinear check
# ---------------------------------------------------------------------------
#: Settling: the disturbance's effect on the heading stays within this fraction of its peak ...
SETTLE_FRACTION = 0.05
#: ... or within this many degrees, whichever is larger.
SETTLE_FLOOR_DEG = 0.01


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
        N, s (the thesis's reference: 40 N for 0.1 s).
    controlled : bool
        Closed loop (True) or the open-loop chair.
    peak_heading_error_deg : float
        Largest ``|heading|`` over the run (deg): what the user sees,
        including the drift and wander the gyro's bias and noise cause.
    peak_response_deg : float
        Largest ``|disturbance response|`` (deg).
    peak_torque_Nm : float
        Largest applied ``|tau|`` per wheel (N m); 0 open loop.
    saturated_fraction : float
        Share of the controller samples at the torque limit.
    settle_time_s : float or None
        Time after which the disturbance response stays within the larger of
        5 % of its peak and 0.01 deg; None if it never does before the end
        of the run (a diverging open-loop chair).
    final_drift_deg_s : float
        Slope of the heading over the last 20 % of the run (deg/s): in
        closed loop the drift a gyro bias imposes (minus the bias).
    max_yaw_rate_deg_s : float
    time_to_10deg_s : float or None
        First time ``|heading|`` reaches 10 deg.
    caster_out_of_range : int
        Steps with a caster slip angle above 8 deg or a caster load above
        450 N (outside the caster tire's data; the drive tire is linear).
    stopped_by_warnings : bool
    result : SimulationResult
    response : ndarray
        The disturbance response (deg) on ``result.t``.
    """

    speed: float
    impulse_force: float
    impulse_duration: float
    controlled: bool
    peak_heading_error_deg: float
    peak_response_deg: float
    peak_torque_Nm: float
    saturated_fraction: float
    settle_time_s: float | None
    final_drift_deg_s: float
    max_yaw_rate_deg_s: float
    time_to_10deg_s: float | None
    caster_out_of_range: int
    stopped_by_warnings: bool
    result: Any = field(repr=False)
    response: Any = field(repr=False, default=None)

    def row(self) -> dict:
        """JSON-ready summary."""
        return {
            "speed_m_s": self.speed, "impulse_N": self.impulse_force, "impulse_s": self.impulse_duration,
            "controlled": self.controlled, "peak_heading_error_deg": self.peak_heading_error_deg,
            "peak_response_deg": self.peak_response_deg,
            "peak_torque_Nm": self.peak_torque_Nm, "saturated_fraction": self.saturated_fraction,
            "settle_time_s": self.settle_time_s, "final_drift_deg_s": _json_float(self.final_drift_deg_s),
            "max_yaw_rate_deg_s": self.max_yaw_rate_deg_s, "time_to_10deg_s": self.time_to_10deg_s,
            "caster_out_of_range_steps": self.caster_out_of_range, "stopped_by_warnings": self.stopped_by_warnings,
        }


def settle_time(t: np.ndarray, response_deg: np.ndarray) -> float | None:
    """First time after which ``|response|`` stays within max(5 % of its peak, 0.01 deg); None if never."""
    return _settle_time(t, response_deg, SETTLE_FRACTION, SETTLE_FLOOR_DEG)


def _simulate(chair, speed, controller, impulse_force, impulse_duration, duration, dt, model, scheme):
    from .simulate import simulate

    if controller is not None:
        controller.reset()
    return simulate(chair, speed, duration=duration, scheme=scheme, model=model, dt=dt,
                    impulse_force=impulse_force, impulse_duration=impulse_duration,
                    yaw_moment=controller, stop_on_warnings=False)


def recovery(chair: Chair, speed: float, controller: DigitalController | None, *, impulse_force: float = 40.0,
             impulse_duration: float = 0.1, duration: float = 10.0, dt: float = 0.001,
             model: str = "exact", scheme: str = "wchair") -> RecoveryRun:
    """Simulate the nonlinear chair after a lateral impulse at the c.g., with or without the controller.

    Default: the WCHAIR fixed-step scheme (1 ms) on the exact model with the
    chair's Coulomb pin friction; the thesis's range rules are counted but do
    not stop the run (the power chair's drive wheels carry more than the
    450 N of the treadmill data by design; its drive tire is linear).  With
    a noisy gyro a twin run without the impulse gives the disturbance
    response (see :class:`RecoveryRun`).
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
    if taus is not None and taus.size:
        peak_tau = float(np.max(np.abs(taus)))
        sat = float(np.mean(np.abs(taus) >= controller.drive.torque_limit * (1 - 1e-9)))
    else:
        peak_tau, sat = 0.0, 0.0
    tail = t >= t[-1] - 0.2 * (t[-1] - t[0])
    drift = float(np.polyfit(t[tail], head[tail], 1)[0]) if tail.sum() >= 2 else float("nan")
    big = np.flatnonzero(np.abs(head) >= 10.0)
    slip = np.abs(np.asarray(res.slip_deg)[:, :2])
    load = np.asarray(res.normal_load)[:, :2]
    oor = int(np.sum(np.any((slip > 8.0) | (load > 450.0), axis=1)))
    return RecoveryRun(
        speed=speed, impulse_force=float(impulse_force), impulse_duration=float(impulse_duration),
        controlled=controller is not None, peak_heading_error_deg=float(np.max(np.abs(head))),
        peak_response_deg=float(np.max(np.abs(resp))), peak_torque_Nm=peak_tau, saturated_fraction=sat,
        settle_time_s=settle_time(t[:len(resp)], resp), final_drift_deg_s=drift,
        max_yaw_rate_deg_s=float(np.degrees(np.max(np.abs(res.yaw_rate)))),
        time_to_10deg_s=float(t[big[0]]) if big.size else None, caster_out_of_range=oor,
        stopped_by_warnings=bool(res.stopped_by_warnings), result=res, response=resp,
    )


def recovery_runs(sched: Schedule, speeds: Sequence[float] = (1.0, 2.0, 3.0),
                  impulses: Sequence[float] = (40.0, 400.0), *, seed: int = 0, duration: float = 10.0,
                  noise: bool = True, open_loop: bool = True) -> list[tuple]:
    """``[(closed, open)]`` :class:`RecoveryRun` pairs for every speed and impulse (N for 0.1 s at the c.g.).

    Closed loop: the scheduled controller at that speed, torque-limited,
    with (gyro design, ``noise``) gyro noise and bias seeded with ``seed``
    plus the run's index, so the runs are deterministic.  ``open`` is None
    when ``open_loop`` is False.
    """
    out = []
    for i, (s, f) in enumerate(itertools.product(speeds, impulses)):
        ctl = DigitalController(sched.at(s), sched.chair, sched.drive, gyro=sched.gyro, seed=seed + i, noise=noise)
        closed = recovery(sched.chair, s, ctl, impulse_force=f, duration=duration, model=sched.model)
        opened = recovery(sched.chair, s, None, impulse_force=f, duration=duration, model=sched.model) \
            if open_loop else None
        out.append((closed, opened))
    return out


def recovery_table(runs: Sequence[tuple]) -> list[dict]:
    """JSON-ready rows ``{"speed_m_s", "impulse_N", "closed", "open"}`` from :func:`recovery_runs`."""
    rows = []
    for closed, opened in runs:
        row = {"speed_m_s": closed.speed, "impulse_N": closed.impulse_force, "closed": closed.row()}
        if opened is not None:
            row["open"] = opened.row()
        rows.append(row)
    return rows


def minimum_torque_limit(sched: Schedule, speed: float, impulse_force: float = 400.0, *,
                         max_heading_deg: float = 10.0, tol: float = 0.25, duration: float = 10.0) -> float:
    """Smallest per-wheel torque limit with which the scheduled controller still recovers (N m).

    The thesis's question (chapter 9, "Future work"): what motor torque is
    needed to stabilise the chair against a disturbance.  The design (its
    gains) is kept; only the saturation of the digital controller changes.
    "Recovers": the disturbance response settles (:func:`settle_time`)
    and the heading stays within ``max_heading_deg``.  Noise-free sensors
    (the bias and noise would blur the threshold); bisection to ``tol``
    N m between 0 and the drive train's limit.  Returns ``inf`` if even the
    full limit does not recover.
    """
    speed = check_speed(speed)
    d = sched.at(speed)

    def ok(limit: float) -> bool:
        drive = replace(sched.drive, torque_limit=limit)
        ctl = DigitalController(d, sched.chair, drive, gyro=sched.gyro, noise=False)
        run = recovery(sched.chair, speed, ctl, impulse_force=impulse_force, duration=duration, model=sched.model)
        return run.settle_time_s is not None and run.peak_heading_error_deg <= max_heading_deg

    hi = float(sched.drive.torque_limit)
    if not ok(hi):
        return math.inf
    lo = 0.0
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if ok(mid):
            hi = mid
        else:
            lo = mid
    return hi


def decay_agreement(sched: Schedule, speed: float, *, impulse_force: float = 4.0, impulse_duration: float = 0.1,
                    decades: float = 3.0) -> dict:
    """Does the linear closed loop predict the nonlinear decay rate?

    Simulates the scheduled controller (noise-free, sampled every step of
    the 1 ms WCHAIR scheme, no saturation reached) on the chair with its
    Coulomb pin friction removed (the linear model's pins are frictionless;
    friction would make small disturbances stick the casters), after a small
    lateral impulse (default 4 N for 0.1 s, a tenth of the reference).  The
    envelope of the yaw rate is fitted (:func:`fit_decay_rate`) in a window
    that starts when the next-slowest closed-loop mode has decayed
    ``decades`` decades relative to the slowest and spans at least three
    half-periods of the slowest (if oscillatory) or ``decades`` decades of
    its decay.  Returns ``{"speed_m_s", "predicted_1_s", "fitted_1_s",
    "relative_error", "window_s", "frequency_rad_s"}``.
    """
    speed = check_speed(speed)
    d = sched.at(speed)
    lam = closed_loop_poles(d)
    slow = lam[0]
    others = lam[np.abs(lam - np.conj(slow)) > 1e-9 * max(1.0, abs(slow))]
    others = others[np.abs(others - slow) > 1e-9 * max(1.0, abs(slow))]
    s2 = others.real.max() if others.size else 10 * slow.real
    gap = max(slow.real - s2, 1e-6)
    t0 = impulse_duration + decades * math.log(10) / gap
    w = abs(slow.imag)
    span = max(decades * math.log(10) / abs(slow.real), 3.5 * math.pi / w if w > 1e-6 else 0.0)
    t1 = t0 + span
    c = sched.chair.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    gyro = replace(sched.gyro, sample_rate_hz=1000.0)
    ctl = DigitalController(d, c, sched.drive, gyro=gyro, noise=False, saturate=False)
    res = _simulate(c, speed, ctl, impulse_force, impulse_duration, t1 + 0.1, 0.001, sched.model, "wchair")
    fitted = fit_decay_rate(res.t, res.yaw_rate, t0, t1)
    return {"speed_m_s": speed, "predicted_1_s": float(slow.real), "fitted_1_s": fitted,
            "relative_error": abs(fitted - slow.real) / abs(slow.real), "window_s": [t0, t1],
            "frequency_rad_s": float(w)}


def destabilising_moment(chair: Chair | str = "ej-premier", speed: float = 0.75, *, duration: float = 10.0,
                         model: str = "thesis", scheme: str = "wchair", impulse_force: float = 40.0,
                         impulse_duration: float = 0.1):
    """Figure 9-4: total yaw moment of the tire forces about the c.g. over time (open loop).

    Defaults are the thesis's reference case (E&J Premier, 0.75 m/s, 40 N for
    0.1 s at the c.g., thesis model, WCHAIR scheme and its warning rule).
    Returns the :class:`~stability.simulate.SimulationResult`; the curve is
    ``(result.t, result.tire_yaw_moment)``.
    """
    from . import chair as chair_mod
    from .simulate import simulate

    c = chair_mod.resolve(chair) if isinstance(chair, str) else chair
    return simulate(c, speed, duration=duration, model=model, scheme=scheme, impulse_force=impulse_force,
                    impulse_duration=impulse_duration)


def fit_decay_rate(t: np.ndarray, y: np.ndarray, t_start: float, t_end: float) -> float:
    """Exponential rate of the envelope of ``y`` (1/s); see :func:`stability.signals.envelope_rate`."""
    return envelope_rate(t, y, t_start, t_end)


# ---------------------------------------------------------------------------
# the gain table
# ---------------------------------------------------------------------------
def _json_float(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else (None if math.isnan(x) else ("inf" if x > 0 else "-inf"))


def gain_table(sched: Schedule, *, check: bool = True, impulse_force: float = 40.0, seed: int = 0,
               duration: float = 10.0) -> list[dict]:
    """One JSON-ready row per scheduled speed.

    Keys: ``speed_m_s``; ``gains`` (the LQR gain on :data:`STATES`, N m of
    yaw moment per SI unit of each state, ``Mz = -gains . x``);
    ``wheel_torque_gains`` (the same as differential torque per wheel);
    ``estimator_gain`` (gyro design: the Kalman gain on ``v, r, eta,
    eta_dot, beta, beta_dot`` per rad/s of gyro innovation, else None);
    ``closed_loop_poles`` ([real, imag] pairs, 1/s); ``stable``;
    ``open_loop_max_real_1_s``; ``margins`` (:func:`loop_margins`);
    ``peak_torque_Nm`` and ``peak_heading_error_deg`` of the nonlinear
    closed loop after the lateral impulse ``impulse_force`` for 0.1 s (with
    saturation, and for the gyro design noise and bias; None when
    ``check`` is False) and ``settle_time_s``.
    """
    rows = []
    for i, (s, d) in enumerate(zip(sched.speeds, sched.designs)):
        poles = closed_loop_poles(d)
        ol = np.linalg.eigvals(d.plant.A6).real.max()
        row = {
            "speed_m_s": float(s),
            "design": sched.kind,
            "gains": [float(k) for k in d.K[0]],
            "gain_states": list(STATES),
            "wheel_torque_gains": [float(sched.drive.wheel_torque(sched.chair, k)) for k in d.K[0]],
            "estimator_gain": None if d.L is None else [float(x) for x in d.L[:, 0]],
            "closed_loop_poles": [[float(p.real), float(p.imag)] for p in poles],
            "stable": bool(poles.real.max() < 0),
            "closed_loop_max_real_1_s": float(poles.real.max()),
            "open_loop_max_real_1_s": float(ol),
            "margins": {k: _json_float(v) for k, v in loop_margins(d).items()},
            "peak_torque_Nm": None,
            "peak_heading_error_deg": None,
            "settle_time_s": None,
        }
        if check:
            ctl = DigitalController(d, sched.chair, sched.drive, gyro=sched.gyro, seed=seed + i)
            run = recovery(sched.chair, s, ctl, impulse_force=impulse_force, duration=duration, model=sched.model)
            row.update(peak_torque_Nm=run.peak_torque_Nm, peak_heading_error_deg=run.peak_heading_error_deg,
                       peak_response_deg=run.peak_response_deg, settle_time_s=run.settle_time_s,
                       saturated_fraction=run.saturated_fraction,
                       final_drift_deg_s=_json_float(run.final_drift_deg_s))
        rows.append(row)
    return rows


def _fmt(x, spec: str = ".3g", none: str = "-") -> str:
    if x is None:
        return none
    if isinstance(x, str):
        return x
    if not math.isfinite(x):
        return "inf" if x > 0 else ("-inf" if x < 0 else "nan")
    return format(x, spec)


def format_table(sched: Schedule, rows: list[dict]) -> str:
    """The gain table as text."""
    c = sched.chair
    w = sched.weights
    head = [
        f"Motor assist ({sched.kind} LQR) for {c.name}: model {sched.model}, "
        f"wheel radius {sched.drive.wheel_radius:g} m, torque limit {sched.drive.torque_limit:g} N m per wheel",
        f"Bryson weights: heading {w.max_heading_error_deg:g} deg, yaw rate "
        f"{_fmt(w.max_yaw_rate_deg_s)} deg/s, lateral velocity {_fmt(w.max_lateral_velocity_m_s)} m/s, "
        f"torque budget {w.budget(sched.drive):g} N m per wheel"
        + (f"; gyro {sched.gyro.noise_density_deg_s:g} deg/s/rtHz, bias {sched.gyro.bias_deg_s:g} deg/s, "
           f"{sched.gyro.sample_rate_hz:g} Hz" if sched.kind == "gyro" else f"; {sched.gyro.sample_rate_hz:g} Hz"),
        "Gains: differential torque per wheel, tau = -(k . x), x = [v m/s, r rad/s, eta rad, eta_dot rad/s, "
        "beta rad, beta_dot rad/s, psi rad]",
        "",
        f"{'U':>5s} {'k_v':>8s} {'k_r':>8s} {'k_eta':>8s} {'k_etad':>8s} {'k_beta':>8s} {'k_betad':>8s} "
        f"{'k_psi':>8s} | {'OL max':>7s} {'CL max':>7s} {'GM up':>6s} {'GM low':>6s} {'PM':>5s} {'|1+L|':>5s} "
        f"| {'tau pk':>6s} {'psi pk':>6s} {'settle':>6s}",
        f"{'m/s':>5s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} {'':>8s} | {'1/s':>7s} {'1/s':>7s} "
        f"{'':>6s} {'':>6s} {'deg':>5s} {'':>5s} | {'N m':>6s} {'deg':>6s} {'s':>6s}",
    ]
    lines = list(head)
    for r in rows:
        k = r["wheel_torque_gains"]
        m = r["margins"]
        lines.append(
            f"{r['speed_m_s']:5.2f} " + " ".join(f"{x:8.4g}" for x in k)
            + f" | {r['open_loop_max_real_1_s']:7.3f} {r['closed_loop_max_real_1_s']:7.3f} "
            f"{_fmt(m['gain_margin_upper'], '.3g'):>6s} {_fmt(m['gain_margin_lower'], '.2g'):>6s} "
            f"{_fmt(m['phase_margin_deg'], '.0f'):>5s} {_fmt(m['disk_margin'], '.2f'):>5s} | "
            f"{_fmt(r['peak_torque_Nm'], '.1f'):>6s} {_fmt(r['peak_heading_error_deg'], '.2f'):>6s} "
            f"{_fmt(r['settle_time_s'], '.2f'):>6s}"
        )
    stable = all(r["stable"] for r in rows)
    lines += ["", "All scheduled closed loops stable." if stable else
              "UNSTABLE closed loop at " + ", ".join(f"{r['speed_m_s']:g}" for r in rows if not r["stable"]) + " m/s."]
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# figures
# ---------------------------------------------------------------------------
def _page(title: str, subtitle: str = "", nrows: int = 1, ncols: int = 1):
    try:
        from .plotting import page
        return page(title, subtitle, nrows=nrows, ncols=ncols)
    except ImportError:  # pragma: no cover - plotting is optional
        from matplotlib.figure import Figure

        fig = Figure(figsize=(11.69, 8.27))
        fig.suptitle(title, fontsize=13, fontweight="bold")
        if subtitle:
            fig.text(0.5, 0.945, subtitle, ha="center", va="top", fontsize=9)
        return fig, fig.subplots(nrows, ncols, squeeze=False)


def _finish(fig):
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.93))
    return fig


def figure_gains(sched: Schedule, rows: list[dict]):
    """Gains (differential torque per wheel per unit state) against speed."""
    fig, ax = _page(f"Gain schedule: {sched.kind} LQR, {sched.chair.name}",
                    "tau = -(k . x) per wheel; linear interpolation between design speeds", 2, 4)
    U = sched.speeds
    K = np.array([r["wheel_torque_gains"] for r in rows])
    units = ["N m/(m/s)", "N m/(rad/s)", "N m/rad", "N m/(rad/s)", "N m/rad", "N m/(rad/s)", "N m/rad"]
    for j, (s, u) in enumerate(zip(STATES, units)):
        a = ax.flat[j]
        a.plot(U, K[:, j], "o-", ms=3)
        a.ticklabel_format(axis="y", useOffset=False)
        lo, hi = float(K[:, j].min()), float(K[:, j].max())
        if hi - lo < 1e-3 * max(abs(lo), abs(hi), 1e-12):
            a.set_ylim(min(0.9 * lo, 1.1 * lo), max(0.9 * hi, 1.1 * hi))
        a.set_title(f"k_{s}")
        a.set_xlabel("speed (m/s)")
        a.set_ylabel(u)
        a.grid(alpha=0.3)
    a = ax.flat[7]
    if sched.kind == "gyro":
        Lm = np.array([r["estimator_gain"] for r in rows])
        for j, s in enumerate(STATES[:6]):
            a.plot(U, Lm[:, j], label=s)
        a.set_title("Kalman gain (per rad/s of innovation)")
        a.set_xlabel("speed (m/s)")
        a.legend(fontsize=7)
        a.grid(alpha=0.3)
    else:
        a.axis("off")
    return _finish(fig)


def figure_poles(sched: Schedule, rows: list[dict], rob: Robustness | None = None):
    """Closed-loop eigenvalues against speed and the largest real part (open loop, closed loop, worst corner)."""
    from matplotlib import cm
    from matplotlib.colors import Normalize

    fig, ax = _page(f"Closed-loop eigenvalues: {sched.kind} LQR, {sched.chair.name}",
                    f"model {sched.model}; colour = speed", 1, 2)
    a = ax[0, 0]
    norm = Normalize(sched.speeds[0], sched.speeds[-1])
    for r in rows:
        p = np.array(r["closed_loop_poles"])
        a.scatter(p[:, 0], p[:, 1], s=10, color=cm.viridis(norm(r["speed_m_s"])))
        ol = np.linalg.eigvals(plant(sched.chair, r["speed_m_s"], sched.model).A6)
        a.scatter(ol.real, ol.imag, s=14, marker="x", color=cm.viridis(norm(r["speed_m_s"])))
    a.axvline(0, color="k", lw=0.8)
    a.set_xlabel("real part (1/s)")
    a.set_ylabel("imaginary part (rad/s)")
    a.set_title("o closed loop, x open loop (chair alone)")
    lim = np.array([max(abs(np.array(r["closed_loop_poles"])[:, 0]).min(), 1.0) for r in rows]).max()
    a.set_xlim(-12 * lim, 2 * lim)
    a.grid(alpha=0.3)
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap="viridis"), ax=a, label="speed (m/s)")
    b = ax[0, 1]
    b.plot(sched.speeds, [r["open_loop_max_real_1_s"] for r in rows], "r--", label="open loop (chair alone)")
    b.plot(sched.speeds, [r["closed_loop_max_real_1_s"] for r in rows], "b-o", ms=3, label="closed loop, nominal")
    if rob is not None:
        b.plot(rob.speeds, rob.max_real.max(axis=0), "k:", label=f"closed loop, worst of +/-{rob.box:.0%} box")
    fine = np.linspace(sched.speeds[0], sched.speeds[-1], 4 * len(sched.speeds) - 3)
    b.plot(fine, [closed_loop_poles(sched.at(s)).real.max() for s in fine], "c.", ms=3,
           label="closed loop, interpolated gains")
    b.axhline(0, color="k", lw=0.8)
    b.set_xlabel("speed (m/s)")
    b.set_ylabel("largest real part (1/s)")
    b.legend(fontsize=8)
    b.grid(alpha=0.3)
    return _finish(fig)


def figure_margins(sched: Schedule, rows: list[dict]):
    """Stability margins of the loop broken at the plant input against speed."""
    fig, ax = _page(f"Loop margins at the plant input: {sched.kind} LQR, {sched.chair.name}",
                    "L(s) = C(s) P(s) from the yaw-moment command; control.stability_margins", 1, 3)
    U = sched.speeds
    m = [r["margins"] for r in rows]

    def val(key):
        return np.array([np.inf if x[key] == "inf" else (np.nan if x[key] is None else float(x[key])) for x in m])

    a = ax[0, 0]
    up, lo = val("gain_margin_upper"), val("gain_margin_lower")
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
    c.plot(U, val("disk_margin"), "m-o", ms=3, label="min |1 + L(jw)|")
    c.plot(U, val("delay_margin_s") * 10, "k--", label="delay margin x 10 (s)")
    c.axhline(1, color="0.5", ls=":", lw=0.8)
    c.set_xlabel("speed (m/s)")
    c.legend(fontsize=8)
    c.grid(alpha=0.3)
    return _finish(fig)


def figure_robustness(rob: Robustness, sched: Schedule):
    """Largest closed-loop real part at every corner of the box against speed."""
    fig, ax = _page(f"Robustness: +/-{rob.box:.0%} in mass, yaw inertia, main and caster cornering stiffness",
                    f"{sched.kind} LQR designed on the nominal {sched.chair.name}; worst case "
                    f"{rob.worst['max_real_1_s']:.3f} 1/s at {rob.worst['speed_m_s']:g} m/s, corner "
                    + ", ".join(f"{k} x{v:.2f}" for k, v in rob.worst["corner"].items()))
    a = ax[0, 0]
    for i, c in enumerate(rob.corners):
        lab = "nominal" if i == 0 else None
        a.plot(rob.speeds, rob.max_real[i], "k-" if i == 0 else "-", lw=2 if i == 0 else 0.8, alpha=1 if i == 0 else 0.6,
               label=lab)
    a.axhline(0, color="r", lw=0.8)
    a.set_xlabel("speed (m/s)")
    a.set_ylabel("largest closed-loop real part (1/s)")
    a.legend()
    a.grid(alpha=0.3)
    return _finish(fig)


def _first_slip_warning(res) -> float:
    w = res.warnings.get("slip", {}) if isinstance(res.warnings, dict) else {}
    t = w.get("first_time")
    return float(t) if t is not None else float(res.t[-1]) + 1e-9


def valid_until(res, max_heading_deg: float = 90.0) -> float:
    """End of the meaningful part of an open-loop run (s).

    The first time any tire's slip angle passes 8 deg (the simulator's
    warning; beyond it tested tire data are extrapolated and a linear tire
    model is not defensible either) or the heading reaches
    ``max_heading_deg``, whichever comes first.
    """
    tw = _first_slip_warning(res)
    slip = np.flatnonzero(np.any(np.abs(np.asarray(res.slip_deg)) > 8.0, axis=1))
    if slip.size:
        tw = min(tw, float(res.t[slip[0]]))
    big = np.flatnonzero(np.abs(np.degrees(np.asarray(res.heading))) >= max_heading_deg)
    return min(tw, float(res.t[big[0]])) if big.size else tw


def destabilising_summary(res, drive: DriveTrain, chair: Chair) -> dict:
    """The thesis's criterion (chapter 9, "Future work") applied to an open-loop run.

    Once the destabilising moment of the tire forces exceeds what the
    motors can produce, the chair cannot be returned to straight motion.
    Over the meaningful part of the run (:func:`valid_until`) returns
    ``{"valid_until_s", "heading_at_end_deg", "peak_moment_Nm",
    "motor_capacity_Nm", "fraction_of_capacity", "exceeds_capacity_at_s"}``
    (the last None if the moment stays below the capacity).
    """
    t = np.asarray(res.t)
    end = valid_until(res)
    k = t < end
    m = np.abs(np.asarray(res.tire_yaw_moment))[k]
    cap = drive.max_yaw_moment(chair)
    over = np.flatnonzero(m > cap)
    return {
        "valid_until_s": float(min(end, t[-1])),
        "heading_at_end_deg": float(np.degrees(np.asarray(res.heading)[k][-1])) if k.any() else 0.0,
        "peak_moment_Nm": float(m.max()) if m.size else 0.0,
        "motor_capacity_Nm": float(cap),
        "fraction_of_capacity": float(m.max() / cap) if m.size else 0.0,
        "exceeds_capacity_at_s": float(t[k][over[0]]) if over.size else None,
    }


def figure_destabilising(ref, runs: Sequence, drive: DriveTrain, chair: Chair):
    """Figure 9-4 (reference case) and the power chair's open-loop destabilising moment vs its motors.

    Curves end at the first slip-angle warning (beyond 8 deg the caster
    tire data are extrapolated); the reference run itself stops at WCHAIR's
    eleventh warning.
    """
    fig, ax = _page("Destabilising yaw moment of the tire forces (thesis Figure 9-4)",
                    "open loop, lateral impulse at the c.g. (to the right), WCHAIR scheme; curves end at the first "
                    "slip angle above 8 deg (any tire) or, right, at 90 deg of heading", 1, 2)
    a = ax[0, 0]
    tw = valid_until(ref, max_heading_deg=math.inf)
    k = np.asarray(ref.t) < tw
    a.plot(np.asarray(ref.t)[k], np.asarray(ref.tire_yaw_moment)[k], "k")
    a.set_title(f"{ref.chair.name}, {ref.speed:g} m/s, 40 N for 0.1 s, {ref.settings.get('model')} model\n"
                f"(first slip warning {tw:.2f} s)")
    a.set_xlabel("time (s)")
    a.set_ylabel("yaw moment of the tire forces about the c.g. (N m)")
    a.grid(alpha=0.3)
    b = ax[0, 1]
    cap = drive.max_yaw_moment(chair)
    for run in runs:
        res = run.result
        k = np.asarray(res.t) < valid_until(res)
        summ = destabilising_summary(res, drive, chair)
        b.plot(np.asarray(res.t)[k], np.asarray(res.tire_yaw_moment)[k],
               label=f"{run.speed:g} m/s, {run.impulse_force:g} N: peak {summ['peak_moment_Nm']:.0f} N m "
                     f"({summ['fraction_of_capacity']:.0%} of the motors) by {summ['valid_until_s']:.2f} s")
    b.axhline(cap, color="r", ls="--", label=f"motor limit {cap:.0f} N m")
    b.axhline(-cap, color="r", ls="--")
    b.set_title(f"{chair.name} open loop ({runs[0].result.settings.get('model') if runs else ''} model)")
    b.set_ylim(-1.6 * cap, 1.6 * cap)
    b.set_xlabel("time (s)")
    b.set_ylabel("yaw moment of the tire forces about the c.g. (N m)")
    b.legend(fontsize=8)
    b.grid(alpha=0.3)
    return _finish(fig)


def figure_recovery(runs: Sequence[tuple], sched: Schedule):
    """Heading and torque after the disturbances, closed loop vs open loop."""
    fig, ax = _page(f"Nonlinear recovery: {sched.kind} LQR on {sched.chair.name}",
                    "solid: closed loop (saturation" + (", gyro noise and bias" if sched.kind == "gyro" else "")
                    + "); dashed: open loop", 2, 2)
    for (closed, opened) in runs:
        col = {1.0: "C0", 2.0: "C1", 3.0: "C2"}.get(closed.speed, None)
        j = 0 if closed.impulse_force <= 40.0 + 1e-9 else 1
        lab = f"{closed.speed:g} m/s"
        ax[0, j].plot(closed.result.t, np.degrees(closed.result.heading), color=col, label=lab)
        if opened is not None:
            ax[0, j].plot(opened.result.t, np.degrees(opened.result.heading), color=col, ls="--")
        tau = sched.drive.wheel_torque(sched.chair, np.asarray(closed.result.yaw_moment_input))
        ax[1, j].plot(closed.result.t, tau, color=col, lw=0.8, label=lab)
    for j, f in enumerate(("40 N x 0.1 s (reference)", "400 N x 0.1 s (ten times)")):
        ax[0, j].set_title(f)
        ax[0, j].set_ylim(-10, 10)
        ax[0, j].set_ylabel("heading (deg)")
        ax[1, j].set_ylabel("differential torque per wheel (N m)")
        ax[1, j].axhline(sched.drive.torque_limit, color="r", ls="--", lw=0.8)
        ax[1, j].axhline(-sched.drive.torque_limit, color="r", ls="--", lw=0.8)
        for i in range(2):
            ax[i, j].set_xlabel("time (s)")
            ax[i, j].grid(alpha=0.3)
            ax[i, j].legend(fontsize=8)
    return _finish(fig)


def figure_recovery_table(table: list[dict], sched: Schedule):
    """The recovery table as a page."""
    header = ["U (m/s)", "impulse", "peak heading CL/OL", "response pk", "torque pk",
              "saturated", "settle (s)", "drift", "OL 10 deg at"]
    rows = []
    for r in table:
        c, o = r["closed"], r.get("open", {})
        rows.append([f"{r['speed_m_s']:g}", f"{r['impulse_N']:g} N x 0.1 s",
                     f"{c['peak_heading_error_deg']:.2f} / {_fmt(o.get('peak_heading_error_deg'), '.1f')} deg",
                     f"{c['peak_response_deg']:.3f} deg", f"{c['peak_torque_Nm']:.1f} N m", f"{c['saturated_fraction']:.1%}",
                     _fmt(c["settle_time_s"], ".2f", "not settled"), _fmt(c["final_drift_deg_s"], ".3f") + " deg/s",
                     _fmt(o.get("time_to_10deg_s"), ".2f", "not reached") + " s"])
    try:
        from .plotting import table_page
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
    except ImportError:  # pragma: no cover
        fig, ax = _page("Recovery in the nonlinear simulator")
        ax[0, 0].axis("off")
        ax[0, 0].text(0, 1, "\n".join(" | ".join(x) for x in [header] + rows), va="top", family="monospace",
                      fontsize=7)
        return fig


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------
def format_recovery(table: list[dict]) -> str:
    """The recovery table as text."""
    lines = [f"{'U m/s':>6s} {'impulse':>8s} {'psi pk CL':>10s} {'resp pk':>8s} {'psi pk OL':>10s} {'tau pk':>7s} "
             f"{'sat':>6s} {'settle s':>9s} {'drift':>7s} {'OL 10deg s':>10s}",
             f"{'':>6s} {'':>8s} {'deg':>10s} {'deg':>8s} {'deg':>10s} {'N m':>7s} {'':>6s} {'':>9s} "
             f"{'deg/s':>7s} {'':>10s}"]
    for r in table:
        cl, ol = r["closed"], r.get("open") or {}
        lines.append(
            f"{r['speed_m_s']:6.2f} {r['impulse_N']:7.0f}N {cl['peak_heading_error_deg']:10.2f} "
            f"{cl['peak_response_deg']:8.3f} {_fmt(ol.get('peak_heading_error_deg'), '.1f'):>10s} "
            f"{cl['peak_torque_Nm']:7.1f} {cl['saturated_fraction']:6.1%} "
            f"{_fmt(cl['settle_time_s'], '.2f', 'no'):>9s} {_fmt(cl['final_drift_deg_s'], '.3f'):>7s} "
            f"{_fmt(ol.get('time_to_10deg_s'), '.2f', 'never'):>10s}")
    return "\n".join(lines)


def build_parser() -> argparse.ArgumentParser:
    from .cli import OneLineErrorParser, add_chair_options

    p = OneLineErrorParser(prog="python -m stability.assist",
                           description="LQR motor assist (differential drive torque) for a power chair: "
                                       "gain schedule, margins, robustness and a nonlinear check.")
    add_chair_options(p, default="power-fwd")
    p.add_argument("--speeds", default="0.5:3.0:0.25", help="design speeds START:STOP:STEP or a list (m/s)")
    p.add_argument("--design", default="gyro", choices=list(DESIGNS), help="feedback structure (default gyro)")
    p.add_argument("--model", default="exact", choices=["exact", "thesis"], help="equation variant (default exact)")
    p.add_argument("--max-heading-error", type=float, default=Weights.max_heading_error_deg, metavar="DEG",
                   help="Bryson weight: acceptable heading error (deg, default 2)")
    p.add_argument("--max-yaw-rate", type=float, default=0.0, metavar="DEG_S",
                   help="Bryson weight: acceptable yaw rate (deg/s; default 0 = unweighted)")
    p.add_argument("--torque-limit", type=float, default=DriveTrain.torque_limit, metavar="NM",
                   help="motor torque limit per drive wheel (N m, default 70)")
    p.add_argument("--torque-budget", type=float, default=None, metavar="NM",
                   help="Bryson weight: torque budget per wheel (N m, default half the limit)")
    p.add_argument("--wheel-radius", type=float, default=DriveTrain.wheel_radius, metavar="M",
                   help="drive-wheel radius (m, default 0.178)")
    p.add_argument("--gyro-noise", type=float, default=GyroSensor.noise_density_deg_s, metavar="DEG_S_RTHZ",
                   help="gyro noise density incl. vibration (deg/s/sqrt(Hz), default 0.05)")
    p.add_argument("--gyro-bias", type=float, default=GyroSensor.bias_deg_s, metavar="DEG_S",
                   help="gyro bias after calibration (deg/s, default 0.1)")
    p.add_argument("--sample-rate", type=float, default=GyroSensor.sample_rate_hz, metavar="HZ",
                   help="controller sample rate (Hz, default 200)")
    p.add_argument("--seed", type=int, default=0, help="seed of the gyro noise (default 0)")
    p.add_argument("--no-check", action="store_true", help="skip the nonlinear simulations")
    p.add_argument("--min-torque", action="store_true",
                   help="also find the smallest torque limit that recovers from the 400 N disturbance "
                        "at 1, 2, 3 m/s (bisection, ~1 min)")
    p.add_argument("--json", metavar="FILE", help="write the gain table as JSON (a list of rows, one per speed)")
    p.add_argument("--pdf", metavar="FILE", help="write the figures as a PDF")
    return p


def _options(args) -> tuple[Weights, DriveTrain, GyroSensor]:
    if not (math.isfinite(args.max_heading_error) and args.max_heading_error > 0):
        raise ValueError(f"--max-heading-error {args.max_heading_error!r} is invalid; valid range: > 0 deg")
    if not (math.isfinite(args.max_yaw_rate) and args.max_yaw_rate >= 0):
        raise ValueError(f"--max-yaw-rate {args.max_yaw_rate!r} is invalid; valid range: >= 0 deg/s (0: unweighted)")
    if not (math.isfinite(args.torque_limit) and args.torque_limit > 0):
        raise ValueError(f"--torque-limit {args.torque_limit!r} is invalid; valid range: > 0 N m")
    if args.torque_budget is not None and not (math.isfinite(args.torque_budget) and args.torque_budget > 0):
        raise ValueError(f"--torque-budget {args.torque_budget!r} is invalid; valid range: > 0 N m")
    if not (math.isfinite(args.wheel_radius) and 0 < args.wheel_radius <= 0.5):
        raise ValueError(f"--wheel-radius {args.wheel_radius!r} is invalid; valid range: 0 < r <= 0.5 m")
    if not (math.isfinite(args.sample_rate) and args.sample_rate >= 10):
        raise ValueError(f"--sample-rate {args.sample_rate!r} is invalid; valid range: >= 10 Hz")
    for name in ("gyro_noise", "gyro_bias"):
        v = getattr(args, name)
        if not (math.isfinite(v) and v >= 0):
            raise ValueError(f"--{name.replace('_', '-')} {v!r} is invalid; valid range: >= 0 deg/s")
    w = Weights(max_heading_error_deg=args.max_heading_error,
                max_yaw_rate_deg_s=args.max_yaw_rate or None, torque_budget_nm=args.torque_budget)
    drive = DriveTrain(wheel_radius=args.wheel_radius, torque_limit=args.torque_limit)
    gyro = GyroSensor(noise_density_deg_s=args.gyro_noise, bias_deg_s=args.gyro_bias,
                      sample_rate_hz=args.sample_rate)
    return w, drive, gyro


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.assist``; returns the exit status (2 on bad input)."""
    from .cli import run

    return run(build_parser(), argv, _run)


def _run(args: argparse.Namespace) -> int:
    from .cli import check_directory, load_chair, parse_speeds
    from .output import atomic_write_text, write_pdf

    c = load_chair(args.chair, args.set)
    speeds = parse_speeds(args.speeds, increasing=True)
    weights, drive, gyro = _options(args)
    check_directory(args.json, "--json")
    check_directory(args.pdf, "--pdf")
    sched = schedule(c, speeds, args.design, weights=weights, drive=drive, gyro=gyro, model=args.model)
    rows = gain_table(sched, check=not args.no_check, seed=args.seed)
    print(format_table(sched, rows))
    rob = robustness(sched)
    w = rob.worst
    print(f"\nRobustness, +/-{rob.box:.0%} in mass, yaw inertia, main and caster cornering stiffness (16 corners x "
          f"{len(sched.speeds)} speeds): {'all stable' if rob.stable else 'UNSTABLE corners'}; worst largest real part "
          f"{w['max_real_1_s']:.4f} 1/s at {w['speed_m_s']:g} m/s, corner "
          + ", ".join(f"{k} x{v:.2f}" for k, v in w["corner"].items()))
    runs = table = None
    if not args.no_check:
        runs = recovery_runs(sched, seed=args.seed)
        table = recovery_table(runs)
        print("\nNonlinear recovery (10 s, WCHAIR scheme, exact model, pin friction, torque limit"
              + (", gyro noise and bias" if sched.kind == "gyro" else "") + "): closed loop vs open loop")
        print(format_recovery(table))
        print("\nFigure 9-4 criterion, open loop (destabilising moment of the tire forces vs the motors' "
              f"{sched.drive.max_yaw_moment(sched.chair):.0f} N m):")
        for closed, opened in runs:
            if opened is not None:
                d_ = destabilising_summary(opened.result, sched.drive, sched.chair)
                print(f"  {closed.speed:g} m/s, {closed.impulse_force:g} N: peak {d_['peak_moment_Nm']:.0f} N m "
                      f"({d_['fraction_of_capacity']:.0%}) up to {d_['valid_until_s']:.2f} s (heading "
                      f"{d_['heading_at_end_deg']:.0f} deg; a slip angle reaches 8 deg or the heading 90 deg)"
                      + ("" if d_["exceeds_capacity_at_s"] is None else
                         f"; exceeds the motors at {d_['exceeds_capacity_at_s']:.2f} s"))
        agree = [decay_agreement(sched, s) for s in (1.0, 2.0, 3.0)]
        print("\nLinear vs nonlinear decay (4 N x 0.1 s, pin friction off, 1 kHz): "
              + "; ".join(f"{a['speed_m_s']:g} m/s: predicted {a['predicted_1_s']:.3f}, fitted "
                          f"{a['fitted_1_s']:.3f} 1/s ({a['relative_error']:.2%})" for a in agree))
    if args.min_torque:
        for s_ in (1.0, 2.0, 3.0):
            mt = minimum_torque_limit(sched, s_)
            print(f"smallest torque limit that recovers from 400 N x 0.1 s at {s_:g} m/s: "
                  f"{_fmt(mt, '.1f')} N m per wheel (noise-free, same gains)")
    if args.json:
        atomic_write_text(args.json, json.dumps(rows, indent=2) + "\n")
    if args.pdf:
        figs = [figure_gains(sched, rows), figure_poles(sched, rows, rob), figure_margins(sched, rows),
                figure_robustness(rob, sched)]
        ref = destabilising_moment()
        ol = [r[1] for r in runs if r[1] is not None and r[1].impulse_force == 40.0] if runs else \
            [recovery(sched.chair, s, None, model=sched.model) for s in (1.0, 2.0, 3.0)]
        figs.append(figure_destabilising(ref, ol, sched.drive, sched.chair))
        if runs is not None:
            figs.append(figure_recovery(runs, sched))
            figs.append(figure_recovery_table(table, sched))
        write_pdf(figs, args.pdf, title=f"stability.assist: {sched.kind} LQR for {sched.chair.name}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
