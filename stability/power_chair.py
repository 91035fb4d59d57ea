"""Preset ``power-fwd``: a front-wheel-drive electric wheelchair with rear casters.

Collins (1987, chapter 9, "Future work") asks for the stability study to be
extended to electric chairs, which use rear casters more often than manual
chairs do, and for the motor torque needed to hold such a chair on a straight
path.  No tire data for power-chair tires exist in the thesis, and no single
commercial chair is modelled here: every number below is a typical value
with its source or its reasoning, so that the motor-assist design of
:mod:`stability.assist` has a defensible plant.  The robustness analysis of
:mod:`stability.assist` checks the design over +/-30 % of the three least
certain of them (mass, yaw inertia, cornering stiffness).

Axes and symbols are those of :mod:`stability.chair` (Figure 6-1; SAE body
axes, x forward, y right, z down, yaw positive clockwise seen from above).
A front-wheel-drive chair with rear casters is the thesis's configuration
(``caster_position="rear"``): the main wheels D (left) and E (right) are the
drive wheels, ahead of the centre of gravity; the casters trail behind it.

Parameters of :func:`power_fwd` and their justification
--------------------------------------------------------
m = 215 kg
    The 100 kg test dummy of ISO 7176-11 (which specifies dummies over a
    range of masses; the thesis's manual chair used the 75 kg one, and
    100 kg is a common rated-user class of a full-size power chair) plus a
    115 kg chair: 90 kg of frame, seat, footrests, electronics, two geared
    motors (~9 kg each), wheels and casters, and two 12 V group-22NF AGM
    batteries (~12.5 kg each, 24 V pack).  Front-wheel-drive chairs with
    group-24 batteries weigh up to ~160 kg; the +30 % corner of the
    robustness box (280 kg) covers them.
i_z = 13 kg m^2 (and a check of s1 and h)
    Lumped estimate, :func:`lumped_estimate` (positions from the drive
    axle, x forward): the user, 3.1 kg m^2 for the 75 kg ISO dummy (Duffey,
    thesis Appendix D) scaled geometrically to 100 kg (``I ~ m^(5/3)``,
    5.0 kg m^2), at x = -0.25 m; batteries 25 kg at -0.15 m; motors and
    gearboxes 2 x 9 kg on the axle at y = +/-0.20 m; drive wheels 2 x 4 kg;
    casters 2 x 1.6 kg at -0.535 m, y = +/-0.22 m; frame, seat, footrests
    and electronics 60.8 kg at -0.12 m spread over 1.0 m x 0.6 m (0.6 of a
    uniform plate's inertia).  Parallel-axis sum: 13.1 kg m^2, used as
    13 kg m^2 (the thesis's manual chair: 5.6 kg m^2 for 95 kg).  The same
    table puts the c.g. 0.176 m behind the drive axle (s1 = 0.18 m) at a
    height of 0.485 m (h = 0.49 m).
s1 = 0.18 m, s2 = 0.32 m, trail = 0.05 m
    Drive axle to caster pins 0.50 m, a typical front-wheel-drive base
    (overall length ~1.0-1.1 m with footrests).  The seat sits behind the
    drive axle so that about two thirds of the weight is on the drive
    wheels (traction, kerb climbing): with the caster contacts 0.05 m
    behind the pins, the static split is ``(s2 + l)/(s1 + s2 + l)`` = 67 %
    drive / 33 % casters.  A 5 cm trail is typical of 8-inch power-chair
    casters and is the largest value the thesis recommends (chapter 9,
    conclusion 4).
d1 = d2 = 0.275 m, t1 = t2 = 0.22 m
    Drive-wheel track 0.55 m (overall width ~0.63 m with 3-inch tires, a
    common indoor-capable width that passes standard doorways);
    caster-pin track 0.44 m.
h = 0.49 m
    c.g. of the 100 kg user ~0.70 m above the ground (seat-to-floor
    0.50 m, power chairs sit higher than manual ones, plus ~0.20 m), the
    chair's masses low (batteries 0.20 m, motors and wheels on the axle at
    0.18 m, frame and seat 0.40 m): 0.485 m by :func:`lumped_estimate`.
m_c = 1.6 kg, l1 = 0.035 m, i_zp = 0.006 kg m^2
    One 8 x 2 inch caster: wheel ~0.9 kg at the trail (0.05 m behind the
    pin), fork, bearings and stem ~0.7 kg about 0.015 m behind it:
    ``l1 = (0.9 x 0.05 + 0.7 x 0.015)/1.6`` = 0.035 m.  Inertia about the
    pin: wheel about its vertical diameter ``m(r^2/4 + w^2/12)`` = 0.0024
    plus ``0.9 x 0.05^2`` = 0.0023, fork ~0.0009: 0.006 kg m^2
    (>= ``m_c l1^2`` = 0.002, as validation requires).
pin_friction_left = pin_friction_right = 0.15 N m
    The thesis's 0.10 N m (Appendix D) for ~270 N on each caster of the
    manual chair, scaled with the normal load (pin friction of a ball- or
    plain-bearing stem is roughly proportional to the load it carries):
    ~350 N here gives 0.13, rounded up to 0.15 N m.  The linear models
    ignore Coulomb friction (frictionless pins, the worst case).
main_tire = "linear:110" (N/deg per drive wheel)
    Power-chair drive tires (12-14 inch x 3 inch, pneumatic or foam-filled)
    were not tested in the thesis, and the static drive-wheel load
    (~710 N) is beyond the tested range (75-450 N), where the cubic fits of
    the 24-inch tires must not be extrapolated.  The closest tested tire is
    the Everest & Jennings pneumatic EJP; its cornering coefficient at its
    highest tested load is 70.5 N/deg / 450 N = 0.157 /deg (Table 4-1), and
    0.157 /deg x 709 N = 111 N/deg.  A linear tire of 110 N/deg is used;
    the robustness box covers 77-143 N/deg.
caster_tire = "ER"
    Essem 7 3/4-inch solid-rubber caster (Table 3-1), the tested tire
    closest to an 8-inch solid or foam-filled power-chair caster; the
    static caster load (~345 N) is inside its tested range, so its own fit
    (26-27 N/deg there, Table 4-1) is used without scaling.
roll_k = 1, camber 0, toe 0, rolling resistance off (TXMOD = CXMOD = 0)
    As the thesis's reference case.  With rolling resistance off the
    forward speed stays constant in the simulator, which is what the drive
    does with its common-mode torque (the speed is held by the drive, so
    forward speed is a parameter of the design).

Drive train (:class:`DriveTrain`, :func:`drive_train`)
------------------------------------------------------
wheel_radius = 0.178 m
    A 14-inch (0.356 m) drive wheel, the usual size on front-wheel-drive
    chairs (10-14 inch range).
torque_limit = 70 N m per wheel (at the wheel)
    Two 24 V, 300 W motors with ~32:1 worm or helical gearboxes: the rated
    (continuous) wheel torque is ~30 N m (300 W at 1.7 m/s, i.e. 9.4 rad/s
    of the wheel), and the controller's current limit (50-70 A, ~0.057 N m/A
    motor torque constant, 80 % gearbox efficiency) gives a short-time peak
    of ~75-100 N m at the wheel.  70 N m leaves the rest for propulsion
    and stays under the traction limit (0.7 x 710 N x 0.178 m = 88 N m).

Yaw moment of a differential wheel torque
-----------------------------------------
Wheel torques ``tau_D`` (left) and ``tau_E`` (right), positive driving the
chair forward, push the ground contact points D = (x_m, -d1) and
E = (x_m, +d2) forward with the longitudinal forces ``F_DX = tau_D / r`` and
``F_EX = tau_E / r``.  Their moment about the c.g. (z down) is
``r_D x F_D + r_E x F_E``, whose longitudinal-force part is
``-(-d1) F_DX - d2 F_EX = d1 F_DX - d2 F_EX``: exactly the first term of
eq 6-3.  Writing ``tau_D = tau_0 + tau`` and ``tau_E = tau_0 - tau``
(common-mode ``tau_0``, differential ``tau``)::

    Mz = tau (d1 + d2) / r + tau_0 (d1 - d2) / r

For a symmetric chair (d1 = d2 = track/2) the common mode gives no yaw
moment and ``Mz = 2 tau (track/2) / r = tau (d1 + d2) / r``; the two
longitudinal forces are equal and opposite, so they form a pure couple:
no net force, no pitch moment (``h sum(Fx) = 0``, eq 6-25d) and no term in
the caster equations (which contain ``F_DX + F_EX``, eq 6-16).  The
differential torque therefore enters the equations of motion exactly as
the linear model's yaw-moment input ``Mz``.  Positive ``tau`` (left wheel
forward, right wheel back) gives positive (clockwise, rightward) yaw.
Like the thesis (chapter 2) the tire model ignores the effect of the
tractive force on the lateral force (combined slip); at the torque limit
the longitudinal force is 390 N against ~710 N of normal load.
"""

from __future__ import annotations

from dataclasses import dataclass

from ._validate import check_positive
from .chair import Chair, preset

__all__ = ["DriveTrain", "power_fwd", "drive_train", "COMPONENTS", "lumped_estimate"]

#: Lumped masses behind the estimates of ``m``, ``s1``, ``h`` and ``i_z``:
#: (name, mass kg, x from the drive axle m (forward +), |y| of a symmetric pair m,
#: height m, own yaw inertia about its c.g. kg m^2).
COMPONENTS: tuple = (
    ("user: ISO 7176-11 100 kg dummy", 100.0, -0.25, 0.0, 0.70, 3.1 * (100.0 / 75.0) ** (5.0 / 3.0)),
    ("batteries: 2 x 12.5 kg group 22NF AGM", 25.0, -0.15, 0.0, 0.20, 0.45),
    ("motors and gearboxes: 2 x 9 kg", 18.0, 0.0, 0.20, 0.18, 0.0),
    ("drive wheels: 2 x 4 kg, 14 inch", 8.0, 0.0, 0.275, 0.178, 2 * 4.0 * 0.178**2 / 4),
    ("casters: 2 x 1.6 kg, 8 inch", 3.2, -0.535, 0.22, 0.10, 0.0),
    ("frame, seat, footrests, electronics", 60.8, -0.12, 0.0, 0.40, 0.6 * 60.8 * (1.0**2 + 0.6**2) / 12),
)


def lumped_estimate(components=COMPONENTS) -> dict:
    """Total mass, c.g. position and yaw inertia of a table of lumped masses.

    Returns a dict with ``m`` (kg), ``s1`` (c.g. behind the drive axle, m),
    ``h`` (c.g. height, m) and ``i_z`` (yaw inertia about the c.g.,
    parallel-axis theorem, kg m^2).
    """
    m = sum(c[1] for c in components)
    x = sum(c[1] * c[2] for c in components) / m
    h = sum(c[1] * c[4] for c in components) / m
    i_z = sum(c[5] + c[1] * ((c[2] - x) ** 2 + c[3] ** 2) for c in components)
    return {"m": m, "s1": -x, "h": h, "i_z": i_z}


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
    """

    wheel_radius: float = 0.178
    torque_limit: float = 70.0

    def __post_init__(self) -> None:
        for name in ("wheel_radius", "torque_limit"):
            check_positive(name, getattr(self, name), prefix="drive-train parameter ")
        if self.wheel_radius > 0.5:
            raise ValueError(f"drive-train parameter wheel_radius={self.wheel_radius!r} is invalid; "
                             "valid range: 0 < wheel_radius <= 0.5 m")

    @staticmethod
    def lever(chair: Chair) -> float:
        """``(d1 + d2)``: the arm of the couple formed by the two drive-wheel forces (m)."""
        return chair.d1 + chair.d2

    def yaw_moment(self, chair: Chair, tau):
        """Yaw moment ``Mz = tau (d1 + d2) / r`` (N m) of a differential torque ``tau`` per wheel (N m).

        Works on floats and numpy arrays.  Positive ``tau`` drives the left
        wheel forward and the right wheel back (clockwise yaw).
        """
        return tau * self.lever(chair) / self.wheel_radius

    def wheel_torque(self, chair: Chair, mz):
        """Differential torque per wheel (N m) that produces the yaw moment ``mz`` (N m)."""
        return mz * self.wheel_radius / self.lever(chair)

    def max_yaw_moment(self, chair: Chair) -> float:
        """Yaw moment at the torque limit (N m)."""
        return float(self.yaw_moment(chair, self.torque_limit))

    def wheel_forces(self, chair: Chair, tau, tau_common=0.0):
        """Longitudinal ground forces ``(F_DX, F_EX)`` (N) for differential and common-mode torques."""
        return (tau_common + tau) / self.wheel_radius, (tau_common - tau) / self.wheel_radius


def power_fwd() -> Chair:
    """The ``power-fwd`` preset: a front-wheel-drive power chair with rear casters and a 100 kg user."""
    return preset("power-fwd")


def drive_train(name: str = "power-fwd") -> DriveTrain:
    """Drive train of a chair preset.

    ``"power-fwd"`` has its own (:class:`DriveTrain` defaults); any other
    chair gets the same motors and wheels, which is what "put the
    power-fwd drive on this chair" means in :mod:`stability.assist`.
    """
    return DriveTrain()
