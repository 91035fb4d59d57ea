"""Preset ``power-fwd`` (a front-wheel-drive power chair with rear casters) and its drive train.

The values, their sources and the derivation of the yaw moment of a
differential wheel torque (``Mz = tau (d1 + d2) / r``, from eq 6-3 of
Collins 1987) are in ``docs/power-chair.md``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from stability.chair import Chair, preset
from stability.runtime.checks import check_nonnegative, check_positive
from stability.settings import defaults as D
from stability.settings.bounds import DRIVE_WHEEL_RADIUS

__all__ = ["DriveAxle", "DriveTrain", "power_fwd", "drive_train", "drive_kind", "COMPONENTS", "LumpedEstimate",
           "lumped_estimate"]

#: Lumped masses behind the estimates of ``m``, ``s1``, ``h`` and ``i_z``:
#: (name, mass kg, x from the drive axle m (forward +), |y| of a symmetric pair m,
#: height m, own yaw inertia about its c.g. kg m^2).
COMPONENTS: tuple[tuple[str, float, float, float, float, float], ...] = (
    ("user: ISO 7176-11 100 kg dummy", 100.0, -0.25, 0.0, 0.70, 3.1 * (100.0 / 75.0) ** (5.0 / 3.0)),
    ("batteries: 2 x 12.5 kg group 22NF AGM", 25.0, -0.15, 0.0, 0.20, 0.45),
    ("motors and gearboxes: 2 x 9 kg", 18.0, 0.0, 0.20, 0.18, 0.0),
    ("drive wheels: 2 x 4 kg, 14 inch", 8.0, 0.0, 0.275, 0.178, 2 * 4.0 * 0.178**2 / 4),
    ("casters: 2 x 1.6 kg, 8 inch", 3.2, -0.535, 0.22, 0.10, 0.0),
    ("frame, seat, footrests, electronics", 60.8, -0.12, 0.0, 0.40, 0.6 * 60.8 * (1.0**2 + 0.6**2) / 12),
)


@dataclass(frozen=True)
class LumpedEstimate:
    """Mass properties of a table of lumped masses.

    Attributes
    ----------
    m : float
        Total mass (kg).
    s1 : float
        c.g. behind the drive axle (m).
    h : float
        c.g. height (m).
    i_z : float
        Yaw inertia about the c.g. (kg m^2, parallel-axis theorem).
    """

    m: float
    s1: float
    h: float
    i_z: float


def lumped_estimate(components: Sequence[Sequence[Any]] = COMPONENTS) -> LumpedEstimate:
    """Total mass, c.g. position and yaw inertia of a table of lumped masses.

    Parameters
    ----------
    components : sequence of (name, mass kg, x m, |y| m, height m, own yaw inertia kg m^2)
        x from the drive axle, forward positive; a nonzero ``|y|`` is a
        symmetric pair whose mass is the pair's total.

    Returns
    -------
    LumpedEstimate
    """
    m = sum(c[1] for c in components)
    x = sum(c[1] * c[2] for c in components) / m
    h = sum(c[1] * c[4] for c in components) / m
    i_z = sum(c[5] + c[1] * ((c[2] - x) ** 2 + c[3] ** 2) for c in components)
    return LumpedEstimate(m=m, s1=-x, h=h, i_z=i_z)


@dataclass(frozen=True)
class DriveAxle:
    """The two drive wheels as the drive train reads them, for a chair given as a wheel layout.

    Attributes
    ----------
    name : str
        The chair's (or layout's) name.
    d1, d2 : float
        Lateral distances of the left and right drive wheels' contact points from the chair's centre line, m;
        ``d1 + d2`` is the lever of their forces' couple (:meth:`DriveTrain.lever`), as the short form's.
    """

    name: str
    d1: float
    d2: float


@dataclass(frozen=True)
class DriveTrain:
    """Drive wheels and motors of a differential-drive (power) chair.

    Attributes
    ----------
    wheel_radius : float
        Rolling radius of the drive wheels (m).
    torque_limit : float
        Largest differential torque per drive wheel, at the wheel (N m),
        available for steering (the motors' short-time peak less a reserve
        for propulsion).
    motor_time_constant : float
        First-order lag from the controller's torque command to the torque
        at the wheel (s): the motor controller's current/speed loop (0: none).
    traction_coefficient : float
        Tire-floor friction coefficient of the drive wheels for the traction
        limit ``mu N r`` (dry indoor floors and concrete 0.6-0.9; 0.4 wet).
    yaw_damping : float
        Yaw damping of a pivot turn at standstill (N m s/rad): tire scrub of
        the drive wheels' contact patches and the casters' pin friction,
        linearised.  The standstill design assumes none (0, conservative: the
        chair is then a pure inertia about the drive-axle midpoint).
    """

    wheel_radius: float = D.DRIVE_WHEEL_RADIUS
    torque_limit: float = D.TORQUE_LIMIT
    motor_time_constant: float = D.MOTOR_LAG
    traction_coefficient: float = D.TRACTION_COEFFICIENT
    yaw_damping: float = 0.0

    def __post_init__(self) -> None:
        for name in ("wheel_radius", "torque_limit", "traction_coefficient"):
            check_positive(name, getattr(self, name), prefix="drive-train parameter ")
        check_nonnegative("motor_time_constant", self.motor_time_constant, prefix="drive-train parameter ")
        check_nonnegative("yaw_damping", self.yaw_damping, prefix="drive-train parameter ")
        if not DRIVE_WHEEL_RADIUS.holds(self.wheel_radius):
            raise ValueError(f"drive-train parameter wheel_radius={self.wheel_radius!r} is invalid; "
                             f"valid range: {DRIVE_WHEEL_RADIUS.text('wheel_radius')}")

    @staticmethod
    def lever(chair: Chair | DriveAxle) -> float:
        """``(d1 + d2)``: the arm of the couple formed by the two drive-wheel forces (m).

        Parameters
        ----------
        chair : Chair or DriveAxle

        Returns
        -------
        float
        """
        return chair.d1 + chair.d2

    def yaw_moment(self, chair: Chair | DriveAxle, tau: Any) -> Any:
        """Yaw moment ``Mz = tau (d1 + d2) / r`` (N m) of a differential torque ``tau`` per wheel (N m).

        Positive ``tau`` drives the left wheel forward and the right wheel
        back (clockwise yaw).

        Parameters
        ----------
        chair : Chair or DriveAxle
        tau : float or ndarray
            N m per wheel.

        Returns
        -------
        float or ndarray
            N m.
        """
        return tau * self.lever(chair) / self.wheel_radius

    def wheel_torque(self, chair: Chair | DriveAxle, mz: Any) -> Any:
        """Differential torque per wheel (N m) that produces the yaw moment ``mz`` (N m).

        Parameters
        ----------
        chair : Chair or DriveAxle
        mz : float or ndarray
            N m.

        Returns
        -------
        float or ndarray
            N m per wheel.
        """
        return mz * self.wheel_radius / self.lever(chair)

    def max_yaw_moment(self, chair: Chair | DriveAxle) -> float:
        """Yaw moment at the torque limit (N m).

        Parameters
        ----------
        chair : Chair or DriveAxle

        Returns
        -------
        float
        """
        return float(self.yaw_moment(chair, self.torque_limit))

    def wheel_forces(self, chair: Chair, tau: Any, tau_common: Any = 0.0) -> tuple[Any, Any]:
        """Longitudinal ground forces ``(F_DX, F_EX)`` (N) for differential and common-mode torques.

        Parameters
        ----------
        chair : Chair or DriveAxle
        tau, tau_common : float or ndarray
            Differential and common-mode torque per wheel (N m).

        Returns
        -------
        tuple
            ``(F_DX, F_EX)``, N.
        """
        return (tau_common + tau) / self.wheel_radius, (tau_common - tau) / self.wheel_radius


def power_fwd() -> Chair:
    """The ``power-fwd`` preset: a front-wheel-drive power chair with rear casters and a 100 kg user.

    Returns
    -------
    Chair
    """
    return preset("power-fwd")


def drive_kind(chair: Chair) -> str:
    """What drives ``chair``: ``"motor"`` for the power-chair presets and chairs made from them (a name that
    starts with ``power``), ``"handrim"`` for a manual chair pushed on its hand rims.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    {"handrim", "motor"}
    """
    return "motor" if chair.name.startswith("power") else "handrim"


def drive_train(name: str = "power-fwd") -> DriveTrain:
    """Drive train of a chair preset.

    ``"power-fwd"`` has its own (:class:`DriveTrain` defaults); any other
    chair gets the same motors and wheels, which is what "put the
    power-fwd drive on this chair" means in :mod:`stability.assist`.

    Parameters
    ----------
    name : str
        Preset name.

    Returns
    -------
    DriveTrain
    """
    return DriveTrain()
