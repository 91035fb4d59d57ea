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
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from stability.layout.model import Layout, takes_layout

if TYPE_CHECKING:
    from stability.tipping.angles import SlopeTip

__all__ = ["contacts", "static_loads", "cornering_stiffnesses", "tip_angles", "centre_of_mass", "distribute",
           "slope_tip", "LoadRule", "load_rule", "LEVER", "THREE", "COMPLIANT"]


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
    ``N_i = k_i (z + theta x_i + phi y_i)``.  A contact of zero vertical stiffness (a wheel that does not reach
    the ground) carries nothing; the others share the load by these rules.

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
    k_all = np.array([p[3] for p in points], dtype=float)
    if np.any(k_all == 0.0):                             # wheels off the ground carry nothing
        out = np.zeros(len(points))
        on = np.flatnonzero(k_all != 0.0)
        out[on] = distribute([points[i] for i in on], weight, centre)
        return out
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


@takes_layout
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


#: Load rules of the simulator (:func:`load_rule`): two support lines of two contacts (the lever rule with the
#: roll moment shared by the lines' roll stiffnesses: eq 6-25 and 6-28 of Collins 1987), three contacts
#: (equilibrium alone), a rigid body on compliant contacts.
LEVER, THREE, COMPLIANT = 0, 1, 2


@dataclass(frozen=True)
class LoadRule:
    """How a layout's normal loads follow the tire forces (quasi-static load transfer, :func:`load_rule`).

    Attributes
    ----------
    mode : int
        :data:`LEVER`, :data:`THREE` or :data:`COMPLIANT`.
    line : ndarray of int
        Support line of each contact (:data:`LEVER`: 0 or 1; -1 for a contact off the ground).
    roll_share : ndarray
        Share of the roll moment each line carries (:data:`LEVER`), in ``line`` order.
    stiffness : ndarray
        Vertical stiffness of each contact, N/m (0: off the ground).
    """

    mode: int
    line: np.ndarray
    roll_share: np.ndarray
    stiffness: np.ndarray


def load_rule(layout: Layout) -> LoadRule:
    """The load rule of a layout, as :func:`distribute` chooses it for the contacts with the casters trailing
    forward.

    The loads then balance the weight ``m g`` at the c.g. and the moments of the tire forces' resultant
    ``(F_x, F_y)`` acting at the ground, ``h`` below it: ``sum N = m g``, ``sum N x = -h F_x``,
    ``sum N y = -h F_y``, with the contacts where they are at the moment (casters swivelled).  Two support
    lines of two contacts (the thesis's chairs) are statically indeterminate in roll only: each line carries the
    share of the roll moment ``-h F_y`` of its roll stiffness ``k_a k_b (y_b - y_a)^2 / (k_a + k_b)``, which is
    the thesis's roll coefficient ``k = k_f / k_r`` (eq 6-28) and gives its loads (eq 6-25, program WCHAIR's
    STATICS) when the stiffnesses are :meth:`~stability.layout.model.Layout.from_chair`'s.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    LoadRule
    """
    pts = contacts(layout)
    k = np.array([p[3] for p in pts], dtype=float)
    on = [i for i in range(len(pts)) if k[i] != 0.0]
    line = np.full(len(pts), -1, dtype=np.int64)
    share = np.zeros(2)
    if len(on) < 3:
        raise ValueError(f"layout {layout.name!r} has {len(on)} contacts on the ground; valid: at least 3")
    groups = _lines([pts[i] for i in on])
    if len(on) == 3:
        mode = THREE
    elif len(groups) == 2 and all(len(g) == 2 for g in groups):
        mode = LEVER
        roll = []
        for g_i, g in enumerate(groups):
            a, b = (on[i] for i in g)
            line[a] = line[b] = g_i
            roll.append(k[a] * k[b] * (pts[b][2] - pts[a][2]) ** 2 / (k[a] + k[b]))
        share = np.array(roll) / sum(roll)
    else:
        mode = COMPLIANT
    return LoadRule(mode, line, share, k)
