"""Design options in physical terms: LQR weights (Bryson's rule), the gyro, the estimator's noise.

Rationale in ``docs/assist.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.assist.plant import STATES
from stability.chair import Chair
from stability.chair.power import DriveTrain
from stability.runtime.checks import check_nonnegative, check_positive
from stability.settings import defaults as D

__all__ = ["DESIGNS", "Weights", "GyroSensor", "EstimatorWeights", "DEFAULT_WEIGHTS", "DEFAULT_GYRO",
           "DEFAULT_ESTIMATOR"]

#: Feedback structures: all seven states measured, or the yaw-rate gyro only.
DESIGNS = ("full-state", "gyro")
_DEG = math.pi / 180.0


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

    max_heading_error_deg: float = D.MAX_HEADING_ERROR
    max_yaw_rate_deg_s: float | None = None
    max_lateral_velocity_m_s: float | None = None
    torque_budget_nm: float | None = None

    def __post_init__(self) -> None:
        check_positive("max_heading_error_deg", self.max_heading_error_deg)
        for name in ("max_yaw_rate_deg_s", "max_lateral_velocity_m_s", "torque_budget_nm"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))

    def matrices(self, chair: Chair, drive: DriveTrain, n: int = 7) -> tuple[np.ndarray, np.ndarray]:
        """``(Q, R)`` for the states of :data:`STATES` (and the unweighted motor state) and the input ``Mz``.

        Parameters
        ----------
        chair : Chair
        drive : DriveTrain
        n : int
            Number of plant states (7, or 8 with a motor lag).

        Returns
        -------
        Q : ndarray (n, n)
            State weight (per SI unit squared).
        R : ndarray (1, 1)
            Input weight (1/(N m)^2).
        """
        return self.weight_matrices(STATES, n, drive.yaw_moment(chair, self.budget(drive)))

    def weight_matrices(self, states: Sequence[str], n: int, mz_max: float) -> tuple[np.ndarray, np.ndarray]:
        """``(Q, R)`` for named states (any plant: the short form's, a wheel layout's) and the input ``Mz``.

        Parameters
        ----------
        states : sequence of str
            State names in the plant's order (``psi``, ``r``, ``v`` are weighted; the rest not).
        n : int
            Number of plant states.
        mz_max : float
            Yaw moment of the torque budget, N m (``R = 1 / mz_max^2``).

        Returns
        -------
        Q : ndarray (n, n)
        R : ndarray (1, 1)
        """
        names = list(states)
        q = np.zeros(n)
        q[names.index("psi")] = 1.0 / (self.max_heading_error_deg * _DEG) ** 2
        if self.max_yaw_rate_deg_s is not None:
            q[names.index("r")] = 1.0 / (self.max_yaw_rate_deg_s * _DEG) ** 2
        if self.max_lateral_velocity_m_s is not None:
            q[names.index("v")] = 1.0 / self.max_lateral_velocity_m_s ** 2
        return np.diag(q), np.array([[1.0 / mz_max ** 2]])

    def budget(self, drive: DriveTrain) -> float:
        """Torque budget per wheel (N m).

        Parameters
        ----------
        drive : DriveTrain

        Returns
        -------
        float
        """
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
    bias_time_constant_s : float
        Time constant of the bias estimate from the gyro minus the yaw rate
        of the drive-wheel speeds (s); 0: no bias handling (the controller
        then holds the biased heading and the chair turns at minus the bias).
    """

    noise_density_deg_s: float = D.GYRO_NOISE
    bias_deg_s: float = D.GYRO_BIAS
    sample_rate_hz: float = D.SAMPLE_RATE_HZ
    bias_time_constant_s: float = D.BIAS_TIME_CONSTANT

    def __post_init__(self) -> None:
        for name in ("noise_density_deg_s", "bias_deg_s", "bias_time_constant_s"):
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



#: Default design options (module-level singletons used as argument defaults).
DEFAULT_WEIGHTS = Weights()
DEFAULT_GYRO = GyroSensor()
DEFAULT_ESTIMATOR = EstimatorWeights()
