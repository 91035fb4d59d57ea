"""Static loads of a layout: the lever rule on two support lines, vertical compliance on more.

A chair on two support lines (an axle and a caster pair: the thesis's chairs) is statically determinate: the
line loads follow from the moment balance about the c.g. and each line's load splits between its two contacts
by the lever rule, which is eq 6-25 of Collins (1987) with no tire forces.  A base with more lines (a
mid-wheel-drive chair with casters ahead and behind) is not: its loads follow from the wheels' vertical
stiffnesses (suspension and tire), the body rigid: ``N_i = k_i (z + theta x_i + phi y_i)`` with heave ``z``, pitch
``theta`` and roll ``phi`` solving the three equilibrium equations.  A load that would come out negative means the
wheel lifts: the layout is refused for the linear analysis.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from stability.layout.model import Layout

if TYPE_CHECKING:
    from stability.tipping.angles import SlopeTip

__all__ = ["contacts", "static_loads", "cornering_stiffnesses", "tip_angles", "centre_of_mass", "distribute",
           "slope_tip"]


def contacts(layout: Layout, reverse: bool = False) -> list[tuple[str, float, float, float]]:
    """Every contact: ``(label, x, y, vertical stiffness)``, fixed wheels first, then casters.

    Parameters
    ----------
    layout : Layout
    reverse : bool
        The casters trail backwards (their contacts ``trail`` ahead of the pins).

    Returns
    -------
    list of (str, float, float, float)
        m, m, N/m.
    """
    out = [(f"wheel {j}", w.x, w.y, w.vertical_stiffness) for j, w in enumerate(layout.wheels)]
    sign = -1.0 if reverse else 1.0
    out += [(f"caster {k}", c.x - sign * c.trail, c.y, c.vertical_stiffness)
            for k, c in enumerate(layout.casters)]
    return out


def centre_of_mass(layout: Layout, reverse: bool = False) -> tuple[float, float]:
    """The system's centre of mass relative to C (the c.g. with every caster trailing forward), m.

    Parameters
    ----------
    layout : Layout
    reverse : bool
        Casters trailing backwards: each caster's centre of mass moves ``2 l`` forward.

    Returns
    -------
    (float, float)
        ``(0, 0)`` forward.
    """
    if not reverse:
        return 0.0, 0.0
    return sum(c.m_c * 2.0 * c.l for c in layout.casters) / layout.m, 0.0


def _lines(points: list[tuple[str, float, float, float]], tol: float = 1e-9) -> list[list[int]]:
    xs: list[float] = []
    groups: list[list[int]] = []
    for i, (_, x, _, _) in enumerate(points):
        for g, x0 in zip(groups, xs, strict=True):
            if abs(x - x0) <= tol:
                g.append(i)
                break
        else:
            xs.append(x)
            groups.append([i])
    return groups


def distribute(points: list[tuple[str, float, float, float]], weight: float, centre: tuple[float, float]
               ) -> np.ndarray:
    """Share a vertical load among contacts so that its moments about ``centre`` balance (may give loads < 0).

    Three contacts: the three equilibrium equations alone.  Two support lines of at most two contacts each: the
    lever rule (eq 6-25 of Collins 1987).  Otherwise the contacts' vertical stiffnesses with the body rigid:
    ``N_i = k_i (z + theta x_i + phi y_i)``.

    Parameters
    ----------
    points : list of (label, x, y, vertical stiffness)
        As :func:`contacts` (m, m, N/m).
    weight : float
        The vertical load to share, N.
    centre : (float, float)
        Where it acts, m.

    Returns
    -------
    ndarray
        N per contact.
    """
    xg, yg = centre
    x = np.array([p[1] for p in points])
    y = np.array([p[2] for p in points])
    lines = _lines(points)
    if len(points) == 3:
        A = np.stack([np.ones(3), x, y])
        return np.linalg.solve(A, np.array([weight, weight * xg, weight * yg]))
    if len(lines) == 2 and all(len(g) <= 2 for g in lines):
        loads = np.zeros(len(points))
        (a, b) = lines
        xa, xb = x[a[0]], x[b[0]]
        la = weight * (xb - xg) / (xb - xa)             # moments about the centre
        for g, load in ((a, la), (b, weight - la)):
            if len(g) == 1:
                loads[g[0]] = load
            else:
                (i, j) = g
                loads[i] = load * (y[j] - yg) / (y[j] - y[i])
                loads[j] = load - loads[i]
        return loads
    k = np.array([p[3] for p in points])
    basis = np.stack([np.ones_like(x), x, y])            # heave, pitch, roll
    z = np.linalg.solve((basis * k) @ basis.T, np.array([weight, weight * xg, weight * yg]))
    return k * (z @ basis)


def static_loads(layout: Layout, reverse: bool = False) -> np.ndarray:
    """Static normal load on every contact (fixed wheels, then casters), N.

    Parameters
    ----------
    layout : Layout
    reverse : bool
        Casters trailing backwards.

    Returns
    -------
    ndarray
        Positive loads, in :func:`contacts` order.

    Raises
    ------
    ValueError
        A contact would carry no load (the c.g. outside the support, or a wheel of a compliant base that lifts).
    """
    pts = contacts(layout, reverse)
    loads = distribute(pts, layout.m * layout.g, centre_of_mass(layout, reverse))
    for (label, _, _, _), n in zip(pts, loads, strict=True):
        if not n > 0:
            raise ValueError(f"layout {layout.name!r}: static load on {label} is {n:.4g} N: the centre of gravity "
                             "lies outside the support or the base rocks on it (valid: every static load > 0)")
    return loads


def cornering_stiffnesses(layout: Layout, reverse: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Cornering stiffness of every fixed wheel and caster at its static load, N/rad.

    The tire's fit between 0 and 1 deg at the load (Table 4-1 method, as
    :func:`stability.models.statics.static_stiffness`) times the wheel's lateral scale.

    Parameters
    ----------
    layout : Layout
    reverse : bool

    Returns
    -------
    (ndarray, ndarray)
        Fixed wheels, casters.
    """
    from stability import tires

    loads = static_loads(layout, reverse)
    nw = len(layout.wheels)
    cw = np.array([tires.get(w.tire).scaled(lateral=w.lateral_scale).cornering_stiffness_per_rad(loads[j])
                   for j, w in enumerate(layout.wheels)], dtype=float)
    cc = np.array([tires.get(c.tire).scaled(lateral=c.lateral_scale).cornering_stiffness_per_rad(loads[nw + k])
                   for k, c in enumerate(layout.casters)], dtype=float)
    return cw, cc


def tip_angles(layout: Layout) -> dict[str, float]:
    """ISO 7176-1 static stability angles of the rigid layout (brakes locked, casters in their least stable
    position), by direction: forward, backward, left, right.

    The tipping line is the edge of the support polygon of every contact (a caster's contact anywhere on the
    circle of its trail about its pin), :func:`stability.tipping.angles.support_fall_distance`; the suspension's
    deflection is neglected (rigid body).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    dict
        ``forward_deg``, ``backward_deg``, ``left_deg``, ``right_deg``.
    """
    from stability.tipping.angles import support_fall_distance

    points = [(w.x, w.y, 0.0) for w in layout.wheels] + [(c.x, c.y, c.trail) for c in layout.casters]
    dirs = {"forward_deg": (1.0, 0.0), "backward_deg": (-1.0, 0.0), "left_deg": (0.0, -1.0),
            "right_deg": (0.0, 1.0)}
    return {k: support_fall_distance(points, layout.h, *e).angle_deg for k, e in dirs.items()}


def slope_tip(layout: Layout, cross_slope_deg: float, grade_deg: float = 0.0) -> SlopeTip:
    """Tipping of the rigid layout on a combined cross slope and grade, heading along the path.

    As :func:`stability.tipping.angles.slope_tip` for the short form: gravity in body axes from
    :func:`stability.models.slope.gravity`, the fall line its in-plane part, the tip angle along that line over every
    contact's tipping edge (:func:`stability.tipping.angles.support_fall_distance`).

    Parameters
    ----------
    layout : Layout
    cross_slope_deg : float
        deg, positive falling to the right of the path.
    grade_deg : float
        deg, positive uphill ahead.

    Returns
    -------
    stability.tipping.angles.SlopeTip
        On level ground ``tip_deg`` is the smallest of the four angles of :func:`tip_angles`.
    """
    from stability.models import slope as slope_model
    from stability.tipping.angles import SlopeTip, support_fall_distance

    g1, g2, gn = slope_model.gravity(layout.g, math.radians(cross_slope_deg), math.radians(grade_deg))
    g_in = math.hypot(g1, g2)
    tilt = math.degrees(math.atan2(g_in, gn))
    if g_in == 0.0:
        tip, direction = min(tip_angles(layout).values()), 0.0
    else:
        points = [(w.x, w.y, 0.0) for w in layout.wheels] + [(c.x, c.y, c.trail) for c in layout.casters]
        tip, direction = support_fall_distance(points, layout.h, g1, g2).angle_deg, math.degrees(math.atan2(g2, g1))
    return SlopeTip(cross_slope_deg=cross_slope_deg, grade_deg=grade_deg, tilt_deg=tilt,
                    fall_direction_deg=direction, tip_deg=tip, margin_deg=tip - tilt)
