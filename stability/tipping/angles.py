"""Static stability angles of the rigid chair with its brakes locked (ISO 7176-1 directions).

A rigid chair on a plane tilted by ``alpha`` tips when the gravity line through
its centre of gravity reaches the tipping line through its downhill contacts
(``derivations/tipping.py``).  The gravity line meets the plane at
``h tan(alpha)`` from the c.g.'s foot point, down the fall line ``e``; so the
chair tips at ``tan(alpha) = rho(e) / h``, where ``rho(e)`` is the distance
from the foot point along ``e`` to the edge of the support polygon.

The casters swivel: each caster contact lies on a circle of radius ``trail``
about its pin.  The least stable orientation (ISO 7176-1: the caster set in its
least stable position) minimises ``rho``.  Over all caster angles

    rho(e) = min over unit n with n.e > 0 of  max_k (n.P_k - r_k) / (n.e)

with ``P_k`` the two main-wheel contacts (``r_k = 0``) and the two pins
(``r_k = trail``): the support polygon's gauge, minimised over both swivel
angles (the minimum over each caster's angle of ``n.contact`` is
``n.pin - trail``).  With ``n`` proportional to ``e + t e_perp`` the ratio is a
maximum of lines and concave curves in ``t``, so its minimum lies where two
terms cross; :func:`fall_distance` solves every crossing in closed form
(linear or quadratic) and takes the smallest value.  The minimising ``n`` is
the tipping line's outward normal, and a caster on that line points its
contact along ``-n`` from its pin.

The normal loads of the slope statics (:func:`stability.models.slope.normal_loads`)
reach zero on the uphill contacts at the same angle (tests/test_tipping.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.models import slope as slope_model
from stability.models.params import Params, parameters

__all__ = ["TipAngles", "SlopeTip", "FallLine", "tip_angles", "slope_tip", "fall_distance", "support_fall_distance",
           "anti_tip_angle",
           "LOANE_KIRBY_REAR_DEG", "DIRECTIONS"]

#: Loane & Kirby (1985), Arch Phys Med Rehabil 66(3):174-176: mean static rear stability of ten
#: able-bodied subjects in a conventional (22.6 kg) manual wheelchair, brakes unlocked, tilt platform:
#: 28.6 (SD 2.7) deg; in a lightweight chair 21.7 to 9.4 deg depending on the axle position.  A measured
#: mean, not a requirement: no citable numeric minimum of EN 12183 / EN 12184 was found (docs/tipping.md).
LOANE_KIRBY_REAR_DEG = 28.6

#: Fall-line directions in body axes (x forward, y right) of the four ISO 7176-1 tests, by JSON key stem.
DIRECTIONS = ("toward_main_wheels", "toward_casters", "lateral_left", "lateral_right")


@dataclass(frozen=True)
class FallLine:
    """Where a chair tips along one fall line, casters in their least stable orientation.

    Attributes
    ----------
    distance_m : float
        ``rho``: from the c.g.'s foot point along the fall line to the tipping line (m); negative
        when the c.g. lies outside the support polygon with the casters so turned.
    angle_deg : float
        Static stability angle ``atan2(rho, h)`` (deg).
    normal : tuple of float
        Outward unit normal of the tipping line in body axes (x forward, y right).
    caster_angles_deg : tuple
        ``(eta, beta)``: swivel angles (deg, from trailing, clockwise seen from above) of the
        left and right casters on the tipping line; ``None`` for a caster not on it.
    """

    distance_m: float
    angle_deg: float
    normal: tuple[float, float]
    caster_angles_deg: tuple


@dataclass(frozen=True)
class TipAngles:
    """ISO 7176-1 static stability angles of a rigid chair with locked brakes.

    Attributes
    ----------
    chair : str
        Chair name.
    toward_main_wheels_deg, toward_casters_deg, lateral_left_deg, lateral_right_deg : float
        Plane angle (deg) at which the chair tips toward its main wheels, toward its casters, and
        over its left and right side (fall line parallel to the chair's long axis tilted about), each
        with the casters in their least stable orientation.
    anti_tip_deg : float or None
        Angle (deg) at which it tips over its anti-tip devices toward the main wheels; ``None``
        without anti-tip devices (``anti_tip_reach = 0``).
    lines : dict
        :class:`FallLine` per direction (keys :data:`DIRECTIONS`).
    """

    chair: str
    toward_main_wheels_deg: float
    toward_casters_deg: float
    lateral_left_deg: float
    lateral_right_deg: float
    anti_tip_deg: float | None
    lines: dict

    @property
    def smallest_deg(self) -> float:
        """The smallest of the four angles (deg): the chair's static stability."""
        return min(self.toward_main_wheels_deg, self.toward_casters_deg, self.lateral_left_deg,
                   self.lateral_right_deg)

    @property
    def smallest_direction(self) -> str:
        """Which of :data:`DIRECTIONS` gives :attr:`smallest_deg`."""
        return min(DIRECTIONS, key=lambda k: getattr(self, k + "_deg"))

    def to_mapping(self) -> dict:
        """JSON-ready dict (keys with unit suffixes)."""
        out: dict = {k + "_deg": getattr(self, k + "_deg") for k in DIRECTIONS}
        out["static_stability_deg"] = self.smallest_deg
        out["least_stable_direction"] = self.smallest_direction
        out["anti_tip_deg"] = self.anti_tip_deg
        out["tipping_lines"] = {
            k: {"distance_m": ln.distance_m, "normal": list(ln.normal),
                "caster_angle_left_deg": ln.caster_angles_deg[0], "caster_angle_right_deg": ln.caster_angles_deg[1]}
            for k, ln in self.lines.items()}
        return out


@dataclass(frozen=True)
class SlopeTip:
    """Tipping on a combined grade and cross slope (the slope command's inputs).

    Attributes
    ----------
    cross_slope_deg, grade_deg : float
        The slope (deg; cross slope positive falling to the right, grade positive uphill ahead),
        the chair heading along the path.
    tilt_deg : float
        The plane's tilt: angle of its fall line to the horizontal (deg).
    fall_direction_deg : float
        Fall line in body axes (deg from straight ahead, clockwise seen from above).
    tip_deg : float
        Tilt at which the chair tips on a plane with the same fall line (deg), casters least stable.
    margin_deg : float
        ``tip_deg - tilt_deg``: how much steeper the slope may get before the chair tips (deg).
    """

    cross_slope_deg: float
    grade_deg: float
    tilt_deg: float
    fall_direction_deg: float
    tip_deg: float
    margin_deg: float

    def to_mapping(self) -> dict:
        """JSON-ready dict (keys with unit suffixes)."""
        return {"cross_slope_deg": self.cross_slope_deg, "grade_deg": self.grade_deg, "tilt_deg": self.tilt_deg,
                "fall_direction_deg": self.fall_direction_deg, "tip_deg": self.tip_deg,
                "margin_deg": self.margin_deg}


def _direction(chair: Chair, key: str) -> tuple[float, float]:
    main = 1.0 if chair.caster_position == "rear" else -1.0    # sign of x_main
    return {"toward_main_wheels": (main, 0.0), "toward_casters": (-main, 0.0),
            "lateral_left": (0.0, -1.0), "lateral_right": (0.0, 1.0)}[key]


def fall_distance(p: Params, ex: float, ey: float) -> FallLine:
    """Distance to the tipping line along the fall line ``(ex, ey)``, casters least stable.

    Parameters
    ----------
    p : Params
        One chair's parameters (floats).
    ex, ey : float
        Fall line (unit vector) in body axes, x forward, y right.

    Returns
    -------
    FallLine
    """
    points = ((p.x_m, -p.d1, 0.0), (p.x_m, p.d2, 0.0), (p.x_p, -p.t1, p.trail), (p.x_p, p.t2, p.trail))
    return support_fall_distance(points, p.h, ex, ey)


def support_fall_distance(points, h: float, ex: float, ey: float) -> FallLine:
    """Distance to the tipping line along the fall line for any set of contacts, casters least stable.

    Parameters
    ----------
    points : sequence of (float, float, float)
        ``(x, y, r)`` per contact in body axes (m): a fixed wheel's contact with ``r = 0``, a caster's pin with
        ``r`` its trail (its contact anywhere on that circle).
    h : float
        c.g. height, m.
    ex, ey : float
        Fall line in body axes.

    Returns
    -------
    FallLine
        ``caster_angles_deg`` has one entry per contact with ``r > 0`` (None when not on the tipping line).
    """
    norm = math.hypot(ex, ey)
    ex, ey = ex / norm, ey / norm
    px, py = -ey, ex                                   # e_perp
    n_pts = len(points)
    a = [x * ex + y * ey for x, y, _ in points]
    b = [x * px + y * py for x, y, _ in points]
    r = [rk for _, _, rk in points]

    def f(t: float) -> float:
        s = math.sqrt(1.0 + t * t)
        return max(a[k] + t * b[k] - r[k] * s for k in range(n_pts))

    candidates: list[float] = []
    for i in range(n_pts):
        for j in range(i + 1, n_pts):
            da, db, dr = a[i] - a[j], b[i] - b[j], r[i] - r[j]
            if dr == 0.0:
                if db != 0.0:
                    candidates.append(-da / db)
                continue
            # da + t db = dr s (s = sqrt(1 + t^2) > 0): (db^2 - dr^2) t^2 + 2 da db t + da^2 - dr^2 = 0
            qa, qb, qc = db * db - dr * dr, 2.0 * da * db, da * da - dr * dr
            if abs(qa) < 1e-15 * max(db * db, dr * dr):
                if qb != 0.0:
                    candidates.append(-qc / qb)
                continue
            disc = qb * qb - 4.0 * qa * qc
            if disc < 0.0:
                continue
            sq = math.sqrt(disc)
            candidates += [(-qb + sq) / (2.0 * qa), (-qb - sq) / (2.0 * qa)]
    if not candidates:
        candidates = [0.0]
    t_best = min(candidates, key=f)
    rho = f(t_best)
    s = math.sqrt(1.0 + t_best * t_best)
    nx, ny = (ex + t_best * px) / s, (ey + t_best * py) / s
    tol = 1e-9 * (1.0 + abs(rho))
    angles: list[float | None] = []
    for k in range(n_pts):                             # a caster on the tipping line points along -n
        if r[k] > 0:
            on_line = a[k] + t_best * b[k] - r[k] * s >= rho - tol
            angles.append(math.degrees(math.atan2(ny, nx)) if on_line else None)
    return FallLine(distance_m=rho, angle_deg=math.degrees(math.atan2(rho, h)), normal=(nx, ny),
                    caster_angles_deg=tuple(angles))


@takes_chair
def anti_tip_angle(chair: Chair) -> float | None:
    """Plane angle (deg) at which the chair tips over its anti-tip devices toward the main wheels.

    The chair lifts off its casters at ``atan(s1/h)`` and rotates about the main-wheel contacts
    until the anti-tip contact (``reach`` beyond them, ``clearance`` up) touches; resting on the
    main wheels and the anti-tip devices, it tips over them when the gravity line reaches their
    contact: ``tan(alpha) = (L^2 + s1 reach - h clearance) / (s1 clearance + h reach)``,
    ``L^2 = reach^2 + clearance^2`` (``derivations/tipping.py``).  If that is below the lift-off
    angle the chair goes over as soon as it lifts.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    float or None
        Degrees; ``None`` without anti-tip devices.
    """
    reach, clear = chair.anti_tip_reach, chair.anti_tip_clearance
    if reach <= 0.0:
        return None
    s1, h = chair.s1, chair.h
    over = math.degrees(math.atan2(reach**2 + clear**2 + s1 * reach - h * clear, s1 * clear + h * reach))
    return max(over, math.degrees(math.atan2(s1, h)))


@takes_chair
def tip_angles(chair: Chair) -> TipAngles:
    """The four ISO 7176-1 static stability angles of ``chair`` (rigid, brakes locked).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    TipAngles
    """
    p = parameters(chair)
    lines = {k: fall_distance(p, *_direction(chair, k)) for k in DIRECTIONS}
    return TipAngles(chair=chair.name, anti_tip_deg=anti_tip_angle(chair), lines=lines,
                     **{k + "_deg": lines[k].angle_deg for k in DIRECTIONS})


@takes_chair
def slope_tip(chair: Chair, cross_slope_deg: float, grade_deg: float = 0.0) -> SlopeTip:
    """Tipping on a combined cross slope and grade, the chair heading along the path.

    Gravity in body axes is :func:`stability.models.slope.gravity`'s; the fall line is its in-plane
    part ``(g1, g2)``, the plane's tilt ``atan(|g_in| / g_n)``.

    Parameters
    ----------
    chair : Chair
    cross_slope_deg : float
        Cross slope (deg), positive falling to the right of the path.
    grade_deg : float
        Grade (deg), positive uphill ahead.

    Returns
    -------
    SlopeTip
        On level ground the fall line is undefined: ``tip_deg`` is the smallest of the four
        angles and ``fall_direction_deg`` NaN-free 0.
    """
    g1, g2, gn = slope_model.gravity(chair.g, math.radians(cross_slope_deg), math.radians(grade_deg))
    g_in = math.hypot(g1, g2)
    tilt = math.degrees(math.atan2(g_in, gn))
    if g_in == 0.0:
        tip = tip_angles(chair).smallest_deg
        direction = 0.0
    else:
        tip = fall_distance(parameters(chair), g1, g2).angle_deg
        direction = math.degrees(math.atan2(g2, g1))
    return SlopeTip(cross_slope_deg=cross_slope_deg, grade_deg=grade_deg, tilt_deg=tilt,
                    fall_direction_deg=direction, tip_deg=tip, margin_deg=tip - tilt)
