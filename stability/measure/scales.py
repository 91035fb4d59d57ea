"""Centre of gravity from wheel-scale readings, c.g. height by axle lift, and caster pin friction.

Four scales, one under each wheel, chair level and casters trailing.  Body
axes: x forward along the chair's centre line from the main axle, y to the
right; the main-wheel and caster contact pairs are assumed symmetric about
the same centre line.  Readings may be in any consistent unit (kg or N):
only their ratios and sum matter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["WheelLoads", "ScaleCG", "cg_from_scales", "cg_height_from_tilt", "tilt_reading",
           "pin_friction_moment"]


@dataclass(frozen=True)
class WheelLoads:
    """Four wheel-scale readings, chair level and casters trailing.

    Readings may be in any one unit (kg or N); only their ratios and sum matter.

    Attributes
    ----------
    left_main, right_main : float
        Readings under the left and right main wheels (>= 0).
    left_caster, right_caster : float
        Readings under the left and right casters (>= 0); the four must not all be zero.
    """

    left_main: float
    right_main: float
    left_caster: float
    right_caster: float

    def __post_init__(self) -> None:
        for name in ("left_main", "right_main", "left_caster", "right_caster"):
            v = getattr(self, name)
            if not math.isfinite(v) or v < 0:
                raise ValueError(f"scale reading {name}={v!r} is invalid; valid range: >= 0")
        if self.total <= 0:
            raise ValueError("scale readings are all zero; valid range: a positive total")

    @property
    def total(self) -> float:
        """Sum of the four readings."""
        return self.left_main + self.right_main + self.left_caster + self.right_caster

    @property
    def caster(self) -> float:
        """Sum of the two caster readings."""
        return self.left_caster + self.right_caster


@dataclass(frozen=True)
class ScaleCG:
    """Centre of gravity from four scales.

    Attributes
    ----------
    total : float
        Sum of the readings (the scales' unit).
    x : float
        Longitudinal distance of the c.g. from the main axle towards the casters (m).
    y : float
        Lateral offset of the c.g. from the centre line, positive to the right (m).
    """

    total: float
    x: float
    y: float


def cg_from_scales(loads: WheelLoads, wheelbase: float, main_track: float, caster_track: float,
                   *, expected_total: float | None = None, tolerance: float = 0.02) -> ScaleCG:
    """C.g. position from four wheel-scale readings (moments about the main axle and the centre line).

    ``x = L (W_lc + W_rc) / W`` and
    ``y = [b_m (W_rm - W_lm) + b_c (W_rc - W_lc)] / (2 W)``, with W the sum
    of the readings, L the wheelbase (main contacts to caster contacts) and
    b_m, b_c the main and caster tracks.

    Parameters
    ----------
    loads : WheelLoads
        The four readings.
    wheelbase : float
        Main-wheel contacts to caster contacts, longitudinal, casters trailing (m).
    main_track, caster_track : float
        Distances between the left and right main-wheel contacts and caster contacts (m).
    expected_total : float, optional
        Independently known weight, same unit as the readings; the sum must
        agree within ``tolerance`` (relative) or ValueError is raised.
    tolerance : float
        Relative tolerance of that check.

    Returns
    -------
    ScaleCG
    """
    for name, v in (("wheelbase", wheelbase), ("main_track", main_track), ("caster_track", caster_track)):
        if not v > 0:
            raise ValueError(f"{name}={v!r} is invalid; valid range: > 0 m")
    w = loads.total
    if expected_total is not None:
        lo, hi = expected_total * (1 - tolerance), expected_total * (1 + tolerance)
        if not lo <= w <= hi:
            raise ValueError(f"scale readings sum to {w:.6g} but the weight is {expected_total:.6g}; "
                             f"valid range: {lo:.6g} to {hi:.6g} (within {tolerance:.1%})")
    x = wheelbase * loads.caster / w
    y = (main_track * (loads.right_main - loads.left_main)
         + caster_track * (loads.right_caster - loads.left_caster)) / (2 * w)
    if not 0 < x < wheelbase:
        raise ValueError(f"c.g. x={x:.4g} m is outside the wheelbase; valid range: 0 < x < {wheelbase:g} m "
                         "(a wheel carries no load: is the chair on all four scales?)")
    return ScaleCG(w, x, y)


def _tilt_angle(x_c: float, dz: float, lift: float) -> float:
    # solve lift + dz = x_c sin(theta) + dz cos(theta) for theta, |theta| < pi/2
    r = math.hypot(x_c, dz)
    phi = math.atan2(dz, x_c)
    s = (lift + dz) / r
    if not -1 < s < 1:
        raise ValueError(f"lift={lift!r} m is invalid for this wheelbase; valid range: |lift| < {r - dz:.4g} m")
    return math.asin(s) - phi


def cg_height_from_tilt(total: float, level_lifted_load: float, tilted_lifted_load: float, lift: float,
                        wheelbase: float, pivot_radius: float, lifted_radius: float | None = None) -> float:
    """C.g. height from weighing with one axle raised (axle-lift method).

    The chair pivots about the axle of the wheels left on the ground; the
    wheels of the raised end rest on their scales ``lift`` higher.  Vertical
    reactions act through the wheel centres, so moments about the pivot axle
    give (equal wheel radii r, tilt ``sin(theta) = lift / L``) the standard
    formula ``h = r + L (W_1 - W_1') / (W tan(theta))`` with W_1, W_1' the
    raised end's load level and tilted (e.g. Gillespie 1992, *Fundamentals
    of Vehicle Dynamics*, SAE).  Unequal radii are handled exactly here.

    Parameters
    ----------
    total : float
        Total weight W (same unit as the loads).
    level_lifted_load, tilted_lifted_load : float
        Sum of the readings under the end that is raised, level and raised.
    lift : float
        Height the raised end's contacts are lifted (m), > 0.
    wheelbase : float
        Level wheelbase between the contacts (m).
    pivot_radius : float
        Wheel radius at the end on the ground (m).
    lifted_radius : float, optional
        Wheel radius at the raised end (m); default ``pivot_radius``.

    Returns
    -------
    float
        C.g. height above the ground when level (m).
    """
    r_p = pivot_radius
    r_l = pivot_radius if lifted_radius is None else lifted_radius
    if not lift > 0:
        raise ValueError(f"lift={lift!r} is invalid; valid range: > 0 m")
    dz = r_l - r_p
    theta = _tilt_angle(wheelbase, dz, lift)
    x_g = wheelbase * level_lifted_load / total  # level: c.g. distance from the pivot axle
    x_l = wheelbase * math.cos(theta) - dz * math.sin(theta)  # raised axle's horizontal distance, tilted
    z_g = (x_g * math.cos(theta) - tilted_lifted_load * x_l / total) / math.sin(theta)
    return r_p + z_g


def tilt_reading(total: float, x_g: float, h: float, lift: float, wheelbase: float, pivot_radius: float,
                 lifted_radius: float | None = None) -> float:
    """Load under the raised end for a c.g. at (``x_g``, ``h``): the inverse of :func:`cg_height_from_tilt`.

    For planning a measurement (how big a lift gives a readable change).

    Parameters
    ----------
    total : float
        Total weight W (any unit; the result has the same unit).
    x_g : float
        Level c.g. distance from the pivot axle towards the raised end (m).
    h : float
        C.g. height above the ground when level (m).
    lift : float
        Height the raised end's contacts are lifted (m).
    wheelbase : float
        Level wheelbase between the contacts (m).
    pivot_radius : float
        Wheel radius at the end on the ground (m).
    lifted_radius : float, optional
        Wheel radius at the raised end (m); default ``pivot_radius``.

    Returns
    -------
    float
        Sum of the readings under the raised end when tilted, in the unit of ``total``.
    """
    r_p = pivot_radius
    r_l = pivot_radius if lifted_radius is None else lifted_radius
    dz = r_l - r_p
    theta = _tilt_angle(wheelbase, dz, lift)
    x_l = wheelbase * math.cos(theta) - dz * math.sin(theta)
    xg_t = x_g * math.cos(theta) - (h - r_p) * math.sin(theta)
    return total * xg_t / x_l


def pin_friction_moment(force: float, lever_arm: float, angle_deg: float = 90.0) -> float:
    """Coulomb friction moment at a caster pin from a spring-scale pull (Collins 1987, Appendix D).

    ``M = F a sin(angle)``: the force that just keeps the caster turning slowly,
    applied at a distance from the pin, at an angle to the lever arm.

    Parameters
    ----------
    force : float
        Spring-scale force F (N, >= 0).
    lever_arm : float
        Distance a from the pin axis to where the force is applied (m, > 0).
    angle_deg : float, optional
        Angle between the force and the lever arm (deg, 0 < angle <= 180);
        default 90 (perpendicular).

    Returns
    -------
    float
        Pin friction moment M_f (N m).
    """
    if not force >= 0:
        raise ValueError(f"force={force!r} is invalid; valid range: >= 0 N")
    if not lever_arm > 0:
        raise ValueError(f"lever_arm={lever_arm!r} is invalid; valid range: > 0 m")
    if not 0 < angle_deg <= 180:
        raise ValueError(f"angle_deg={angle_deg!r} is invalid; valid range: 0 < angle <= 180 deg")
    return force * lever_arm * math.sin(math.radians(angle_deg))
