"""Steady straight running along a cross slope: crab angle, caster angles, loads and holding moment.

The equilibrium of the exact model with gravity (``r = 0``, casters still,
no accelerations): the statics of :func:`stability.models.slope.hold_statics`
give the caster side forces, the main-wheel force sums and the yaw moment of
the drive forces; the tire fits must produce those side forces, which fixes
the heading (crab angle) and the caster angles (three equations, solved by
``scipy.optimize.root``).  Frictionless pins give one equilibrium; Coulomb pin
friction a range of holding moments.  See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.chair.power import DriveTrain
from stability.models import slope as sl
from stability.runtime.checks import check_positive, check_speed
from stability.settings import defaults as D
from stability.slope.model import Plane, SlopeModel
from stability.tires.data import FZ_MAX_N

__all__ = ["HandRim", "Equilibrium", "solve", "harder_side", "holding_moment_closed_form", "max_cross_slope",
           "drive_report", "operating_point"]


@dataclass(frozen=True)
class HandRim:
    """Wheel and hand-rim radii of a manual chair (24-inch wheels by default).

    Attributes
    ----------
    wheel_radius : float
        Rolling radius of the drive wheel (m); 0.305 m for a 24-inch wheel.
    handrim_radius : float
        Hand-rim radius (m); 0.265 m is typical for 24-inch wheels.
    """

    wheel_radius: float = D.HANDRIM_WHEEL_RADIUS
    handrim_radius: float = D.HANDRIM_RADIUS

    def __post_init__(self) -> None:
        check_positive("wheel_radius", self.wheel_radius, prefix="hand-rim parameter ")
        check_positive("handrim_radius", self.handrim_radius, prefix="hand-rim parameter ")
        if self.handrim_radius > self.wheel_radius:
            raise ValueError(f"hand-rim parameter handrim_radius={self.handrim_radius!r} is invalid; "
                             f"valid range: 0 < handrim_radius <= wheel_radius = {self.wheel_radius:g} m")

    def rim_force(self, contact_force):
        """Tangential hand-rim force (N) giving the longitudinal ground force ``contact_force`` (N)."""
        return contact_force * self.wheel_radius / self.handrim_radius


@dataclass(frozen=True)
class Equilibrium:
    """Steady straight running on a plane.

    Attributes
    ----------
    chair, cross_slope_deg, grade_deg, speed
        Inputs (speed along the path, m/s).
    heading_deg : float
        Crab angle: the chair's heading from the path (deg, clockwise).
    eta_deg, beta_deg : float
        Caster angles from the chair's axis (deg).
    slips_deg, lateral_forces, loads : tuple
        Per wheel (left caster A, right caster B, left main D, right main E): signed
        slip angle (deg), lateral tire force (N), normal load (N).
    drive_forces : tuple
        Drive forces ``(F_D, F_E)`` at the left and right main-wheel contacts (N, forward +).
    holding_moment : float
        Yaw moment of the drive forces, ``d1 F_D - d2 F_E`` (N m, clockwise +), frictionless pins.
    friction_range : tuple
        ``(min, max)`` holding moment over the equilibria allowed by Coulomb pin friction (N m); ``(nan, nan)``
        when not asked for (:func:`solve` with ``friction_range=False``).
    closed_form : float
        :func:`holding_moment_closed_form`, N m: the frictionless holding moment with the casters straight.
    problems : tuple of str
        Tire-data or lift-off problems at this equilibrium (empty when the result is inside the data).
    """

    chair: str
    cross_slope_deg: float
    grade_deg: float
    speed: float
    heading_deg: float
    eta_deg: float
    beta_deg: float
    slips_deg: tuple
    lateral_forces: tuple
    loads: tuple
    drive_forces: tuple
    holding_moment: float
    friction_range: tuple
    closed_form: float
    problems: tuple

    @property
    def uncorrected_turn(self) -> str:
        """``"downhill"`` or ``"uphill"``: the way the chair yaws when the holding moment is removed.

        ``"none"`` on level ground or with no holding moment.
        """
        s = -np.sign(self.holding_moment) * np.sign(self.cross_slope_deg)
        return "downhill" if s > 0 else ("uphill" if s < 0 else "none")

    def to_dict(self) -> dict:
        """JSON-ready dict (names with units)."""
        d = asdict(self)
        d["uncorrected_turn_statics"] = self.uncorrected_turn
        return d


def _state(model: SlopeModel, speed: float, z, pins=(0.0, 0.0)):
    """Residuals and everything else at ``z = (psi, eta, beta)``."""
    p = model.p
    psi, eta, beta = z
    ce, se, cb, sb = math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta)
    g1, g2, gn = model.plane.gravity(p.g, psi)
    u, v = speed * math.cos(psi), -speed * math.sin(psi)
    loads = sl.normal_loads(p, 0.0, 0.0, g1, g2, gn, ce, se, cb, sb)
    f = model.forces(u, v, 0.0, ce, se, cb, sb, 0.0, 0.0, (0.0, 0.0), loads)
    RA, FAy, RB, FBy, RD, FDy, RE, FEy = f.F
    FAy_req, FBy_req, Sx, Sy, Mh = sl.hold_statics(p, ce, se, cb, sb, g1, g2, pins[0], pins[1], RA, RB)
    scale = p.m * p.g
    res = np.array([FAy - FAy_req, FBy - FBy_req, FDy + FEy - Sy]) / scale * 100.0
    Sxd = Sx - RD - RE
    Mhd = Mh - (p.d1 * RD - p.d2 * RE)
    drive = ((p.d2 * Sxd + Mhd) / (p.d1 + p.d2), (p.d1 * Sxd - Mhd) / (p.d1 + p.d2))
    return res, f, drive, Mhd


def _root(model: SlopeModel, speed: float, pins=(0.0, 0.0), guess=None):
    from scipy.optimize import root  # heavy optional import kept local

    p = model.p
    if guess is None:
        g2 = model.plane.gravity(p.g)[1]
        c_main = model.chair.main_tire_model().cornering_stiffness_per_rad(p.m * p.g / 4)
        a = p.m * g2 / (2 * max(float(c_main), 1.0))
        guess = (-a, a, a)
    def fun(z):
        return _state(model, speed, z, pins)[0]

    x = np.asarray(guess, dtype=float)
    for start in (x, 0.5 * x, np.zeros(3), 2.0 * x):  # hybr can stall on the kinks of the tire fits
        sol = root(fun, start, method="hybr", options={"xtol": 1e-13})
        ok = float(np.max(np.abs(sol.fun))) < 1e-8 and float(np.max(np.abs(sol.x))) < 0.5
        if ok:
            return sol.x, True
    return sol.x, False


def operating_point(chair: Chair, plane: Plane, speed: float) -> tuple[float, float, float, tuple[float, float]]:
    """Crab angle, caster angles and drive forces of straight running: :func:`solve`'s frictionless equilibrium
    without its report (no tire-range check), what a linearisation about it needs.

    Parameters
    ----------
    chair, plane
        The chair and the plane (cross slope and grade, deg).
    speed : float
        Speed along the path, m/s.

    Returns
    -------
    tuple
        ``(psi, eta, beta, (F_D, F_E))``: rad, and the drive forces on the
        left and right main wheels, N.  ValueError when there is none.
    """
    model = SlopeModel(chair, plane)
    z, ok = _root(model, speed)
    if not ok:
        raise ValueError(f"speed={speed!r}: no straight-running equilibrium on cross slope "
                         f"{plane.cross_slope_deg:g} deg")
    drive = _state(model, speed, z)[2]
    return float(z[0]), float(z[1]), float(z[2]), (float(drive[0]), float(drive[1]))


@takes_chair
def holding_moment_closed_form(chair: Chair, plane: Plane) -> float:
    """Frictionless holding moment with the casters straight and no crab angle (N m, clockwise +).

    ``g2 (m x_m - 2 m_c (l1/trail)(x_m - x_c))`` with ``g2 = g cos(theta) sin(phi)`` and
    ``x_c = x_p - trail``: the main wheels carry the slope's lateral weight except the fraction
    ``l1/trail`` of each caster's own weight that its tire carries (the rest reaches the chair at the pin).

    Parameters
    ----------
    chair, plane
        The chair (trail > 0 m) and the plane (cross slope phi, grade theta, deg).

    Returns
    -------
    float
        Yaw moment the main wheels must supply to hold a straight line, N m (clockwise seen from above +);
        a check on :func:`solve` at zero pin friction.
    """
    p = SlopeModel(chair, plane).p
    g2 = plane.gravity(p.g)[1]
    x_c = p.x_p - p.trail
    return g2 * (p.m * p.x_m - 2 * p.m_c * (p.l1 / p.trail) * (p.x_m - x_c))


def _solve_once(chair: Chair, plane: Plane, speed: float, friction_range: bool = True) -> Equilibrium | None:
    model = SlopeModel(chair, plane)
    z, ok = _root(model, speed)
    if not ok:
        return None
    _, f, drive, mh = _state(model, speed, z)
    fr = []
    for pins in ((1, 1), (-1, -1), (1, -1), (-1, 1)) if friction_range else ():
        mp = (pins[0] * chair.pin_friction_left, pins[1] * chair.pin_friction_right)
        zf, okf = _root(model, speed, mp, guess=z)
        fr.append(_state(model, speed, zf, mp)[3] if okf else math.nan)
    return Equilibrium(
        chair=chair.name, cross_slope_deg=plane.cross_slope_deg, grade_deg=plane.grade_deg, speed=speed,
        heading_deg=math.degrees(z[0]), eta_deg=math.degrees(z[1]), beta_deg=math.degrees(z[2]),
        slips_deg=tuple(float(s) for s in f.slips_deg),
        lateral_forces=tuple(float(f.F[k]) for k in (1, 3, 5, 7)),
        loads=f.loads, drive_forces=tuple(float(d) for d in drive), holding_moment=float(mh),
        friction_range=(float(np.nanmin(fr)), float(np.nanmax(fr))) if fr and not all(map(math.isnan, fr))
        else (math.nan, math.nan),
        closed_form=holding_moment_closed_form(chair, plane), problems=tuple(model.range_problems(f)))


@takes_chair
def max_cross_slope(chair: Chair, grade_deg: float, speed: float, sign: float = 1.0, hi: float = 20.0) -> float:
    """Largest cross slope with an equilibrium inside the tire data, by bisection.

    Parameters
    ----------
    chair, grade_deg, speed
        As in :func:`solve` (deg, uphill +; m/s).
    sign : float, optional
        +1 (default) for cross slopes falling to the right, -1 for falling to the left.
    hi : float, optional
        Largest cross slope tried, deg (default 20).

    Returns
    -------
    float
        Cross-slope magnitude, deg, resolved to ``hi / 2**14``; ``hi`` if every
        slope up to it has an equilibrium, -1.0 if even zero cross slope has none.
    """
    def good(phi: float) -> bool:
        e = _solve_once(chair, Plane(sign * phi, grade_deg), speed)
        return e is not None and not e.problems

    if not good(0.0):
        return -1.0
    lo = 0.0
    if good(hi):
        return hi
    for _ in range(14):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if good(mid) else (lo, mid)
    return lo


@takes_chair
def solve(chair: Chair, cross_slope_deg: float, speed: float, grade_deg: float = 0.0,
          strict: bool = True, friction_range: bool = True) -> Equilibrium:
    """Steady straight running along the path on a plane.

    Parameters
    ----------
    chair : Chair
    cross_slope_deg : float
        Cross slope (deg), positive falling to the right.
    speed : float
        Speed along the path (m/s).
    grade_deg : float
        Grade (deg), positive uphill.
    strict : bool
        Raise ValueError (naming the parameter, value and valid range) when the equilibrium does
        not exist or lies outside the tire data (slip > 8 deg, load > 450 N) or a wheel lifts off;
        with ``False`` such a result is returned with :attr:`Equilibrium.problems` filled.
    friction_range : bool
        Also solve the four equilibria at the pins' Coulomb friction limits (:attr:`Equilibrium.friction_range`;
        four root solves more). Nothing else of the result depends on them.

    Returns
    -------
    Equilibrium
    """
    speed = check_speed(speed)
    plane = Plane(cross_slope_deg, grade_deg)
    eq = _solve_once(chair, plane, speed, friction_range)
    if eq is not None and (not eq.problems or not strict):
        return eq
    if eq is None and not strict:
        raise ValueError(f"cross_slope={cross_slope_deg!r} deg: no straight-running equilibrium found "
                         "(the tires cannot hold the chair on this slope)")
    why = eq.problems[0] if eq is not None else "the tires cannot hold the chair (no equilibrium)"
    lim = max_cross_slope(chair, grade_deg, speed, 1.0 if cross_slope_deg >= 0 else -1.0,
                          hi=abs(cross_slope_deg))
    if lim < 0 and grade_deg == 0:
        raise ValueError(f"chair={chair.name!r} is invalid for the slope model: {why} on level ground; "
                         f"valid range: chairs whose static loads are inside the tire data (<= {FZ_MAX_N:g} N)")
    if lim < 0:
        raise ValueError(f"grade={grade_deg!r} deg is invalid for chair {chair.name}: {why} even without "
                         "cross slope; valid range: a smaller grade")
    raise ValueError(f"cross_slope={cross_slope_deg!r} deg is invalid for chair {chair.name}: {why}; "
                     f"valid range: |cross_slope| <= {lim:.2f} deg (grade {grade_deg:g} deg, {speed:g} m/s)")


def residual_accelerations(chair: Chair, eq: Equilibrium) -> tuple:
    """``(u_dot, v_dot, r_dot, eta_dd, beta_dd)`` (m/s^2, rad/s^2) at the equilibrium ``eq`` of ``chair``: they
    should vanish (a check).

    The generated exact model with gravity (:func:`stability.models.slope.accelerations`) at the
    equilibrium's state, with its tire and drive forces at its loads (the loads of zero acceleration, so
    consistent if the accelerations vanish) and frictionless pins.
    """
    model = SlopeModel(chair, Plane(eq.cross_slope_deg, eq.grade_deg))
    psi, eta, beta = (math.radians(x) for x in (eq.heading_deg, eq.eta_deg, eq.beta_deg))
    u, v = eq.speed * math.cos(psi), -eq.speed * math.sin(psi)
    ce, se, cb, sb = math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta)
    g1, g2, _ = model.plane.gravity(model.p.g, psi)
    f = model.forces(u, v, 0.0, ce, se, cb, sb, 0.0, 0.0, eq.drive_forces, eq.loads)
    return sl.accelerations(model.p, u, v, 0.0, ce, se, cb, sb, 0.0, 0.0, f.F, 0.0, 0.0, g1, g2)


def harder_side(right_minus_left: float, cross_slope_deg: float) -> str:
    """Which drive wheel works harder on a cross slope: ``"uphill"``, ``"downhill"`` or ``"neither"``.

    The one sign convention of the toolkit: a positive cross slope falls to
    the right of the heading, so the right wheels are the downhill ones; a
    drive difference is right minus left (hand-rim force or wheel torque).
    The side follows from the statics (:func:`solve`): the drive must supply
    the holding moment against the chair's uncorrected turn, so the wheel on
    the side the chair turns away from works harder (a rear-caster chair
    turns uphill, its uphill wheel works harder; a front-caster chair turns
    downhill, its downhill wheel works harder).

    Parameters
    ----------
    right_minus_left : float
        Right minus left drive force or torque (any unit).
    cross_slope_deg : float
        Cross slope, deg (falling to the right +).

    Returns
    -------
    str

    Examples
    --------
    >>> harder_side(-47.2, 2.0), harder_side(8.3, 2.0), harder_side(0.0, 0.0)
    ('uphill', 'downhill', 'neither')
    """
    if right_minus_left == 0 or cross_slope_deg == 0:
        return "neither"
    return "downhill" if right_minus_left * cross_slope_deg > 0 else "uphill"


def drive_report(chair: Chair, eq: Equilibrium, drive: str = "handrim", handrim: HandRim | None = None,
                 drive_train: DriveTrain | None = None) -> dict:
    """Per-wheel drive quantities for the equilibrium: hand-rim forces or motor torques.

    Parameters
    ----------
    chair : Chair
        The chair ``eq`` was solved for.
    eq : Equilibrium
        Steady straight-running equilibrium (:func:`solve`), with the forward
        contact forces of the left and right main wheels (N).
    drive : {"handrim", "motor"}
        Manual chair pushed on the hand rims, or power chair with wheel motors.
    handrim : HandRim, optional
        Radii for a manual chair (default :class:`HandRim`).
    drive_train : DriveTrain, optional
        Motors of a power chair (default :class:`stability.chair.power.DriveTrain`).

    Returns
    -------
    dict
        Contact forces (N) and, for ``"handrim"``, the tangential hand-rim forces and their
        difference (right minus left, N); for ``"motor"``, the wheel torques, the
        differential torque per wheel ``(tau_D - tau_E)/2`` (N m) and whether it is within the limit;
        both: ``harder_side`` (:func:`harder_side`).

    Raises
    ------
    ValueError
        If ``drive`` is not ``"handrim"`` or ``"motor"``.
    """
    fd, fe = eq.drive_forces
    out: dict = {"drive": drive, "contact_force_left_N": fd, "contact_force_right_N": fe}
    if drive == "handrim":
        hr = handrim or HandRim()
        left, right = hr.rim_force(fd), hr.rim_force(fe)
        out.update(wheel_radius_m=hr.wheel_radius, handrim_radius_m=hr.handrim_radius,
                   handrim_force_left_N=left, handrim_force_right_N=right,
                   handrim_force_difference_N=right - left,
                   harder_side=harder_side(right - left, eq.cross_slope_deg))
    elif drive == "motor":
        dt = drive_train or DriveTrain()
        td, te = fd * dt.wheel_radius, fe * dt.wheel_radius
        tau = 0.5 * (td - te)
        out.update(wheel_radius_m=dt.wheel_radius, motor_torque_left_N_m=td, motor_torque_right_N_m=te,
                   differential_torque_N_m=tau, torque_limit_N_m=dt.torque_limit,
                   within_torque_limit=bool(abs(tau) <= dt.torque_limit),
                   harder_side=harder_side(te - td, eq.cross_slope_deg))
    else:
        raise ValueError(f"drive={drive!r} is invalid; valid choices: ['handrim', 'motor']")
    return out

