"""Quasi-static wheel loads under acceleration on a slope, wheel lift and tipping (ISO 7176-2-style scores).

The chair is a rigid body on its contacts (:mod:`stability.layout.statics`).  Accelerating at ``(a_x, a_y)`` in
body axes on a plane with grade ``gamma`` (rising ahead) and cross slope ``phi`` (falling to the right), the
d'Alembert force and gravity act at the c.g., height ``h``: per unit mass the effective gravity in body axes is
``e = (-g sin(gamma) - a_x, g cos(gamma) sin(phi) - a_y, g cos(gamma) cos(phi))`` (x forward, y right, z down),
so the contacts carry ``m e_z`` with its moments balanced about the *effective centre*
``(x_g + h e_x / e_z, y_g + h e_y / e_z)``.  A contact whose share would be negative lifts; the others carry the
load (the share recomputed without it, until none is negative).  The chair tips when the effective centre leaves
the polygon of its wheel contacts; anti-tip devices extend that polygon.

Scores (issue 39's statement of ISO 7176-2:2017's scoring): 0 no wheel lifts; 1 a wheel lifts and the chair
stays on the others (the effective centre inside the wheels' polygon); 2 the chair tips onto its anti-tip
devices and is held there (inside the polygon that includes them); 3 it tips over.  Quasi-static: what a full
tip-over's dynamics do (the chair's rotation, an impact) is not modelled; a run that reaches score 2 or 3 is
flagged as the end of what the model predicts.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from stability.layout.model import Layout, takes_layout
from stability.layout.statics import centre_of_mass, contacts, distribute
from stability.models import slope as slope_model

__all__ = ["LoadCase", "case_loads", "effective_centre", "polygon_margin", "SCORE_WORDS"]

#: The scores in words.
SCORE_WORDS = {0: "no wheel lifts", 1: "a wheel lifts, the chair stays on the others",
               2: "tips onto its anti-tip devices and is held", 3: "tips over"}


@dataclass(frozen=True)
class LoadCase:
    """The loads of one quasi-static state.

    Attributes
    ----------
    loads_N : ndarray
        Per contact (fixed wheels, then casters), >= 0.
    lifted : tuple of str
        Contacts that carry nothing.
    centre_m : (float, float)
        The effective centre.
    margin_m : float
        Signed distance of the effective centre inside the wheels' support polygon, m (negative: outside).
    score : int
        0-3 (:data:`SCORE_WORDS`).
    """

    loads_N: np.ndarray
    lifted: tuple
    centre_m: tuple
    margin_m: float
    score: int


def effective_centre(layout: Layout, ax: float, ay: float, grade_deg: float, cross_deg: float,
                     reverse: bool = False) -> tuple[float, float, float]:
    """The effective centre and the normal load of a quasi-static state.

    Parameters
    ----------
    layout : Layout
    ax, ay : float
        Acceleration of the c.g. in body axes, m/s^2 (x forward, y right).
    grade_deg, cross_deg : float
        Plane rising ahead, falling to the right, deg.
    reverse : bool
        Casters trailing backwards (their centres of mass ahead of the pins).

    Returns
    -------
    (x, y, normal load)
        m, m, N.
    """
    # gravity in body axes on the plane, the generated model's (stability.models.slope.gravity), less the
    # d'Alembert acceleration
    g1, g2, ez = slope_model.gravity(layout.g, math.radians(cross_deg), math.radians(grade_deg))
    ex, ey = g1 - ax, g2 - ay
    xg, yg = centre_of_mass(layout, reverse)
    return xg + layout.h * ex / ez, yg + layout.h * ey / ez, layout.m * ez


def _hull(points: np.ndarray) -> np.ndarray:
    """Convex hull, counter-clockwise in (x, y) (Andrew's monotone chain)."""
    pts = sorted(set(map(tuple, points.tolist())))
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower: list = []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    upper: list = []
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def polygon_margin(points: np.ndarray, centre: tuple[float, float]) -> float:
    """Signed distance of ``centre`` inside the convex hull of ``points`` (negative: outside), m.

    Parameters
    ----------
    points : ndarray (n, 2)
    centre : (float, float)

    Returns
    -------
    float
    """
    hull = _hull(np.asarray(points, dtype=float))
    c = np.asarray(centre, dtype=float)
    if len(hull) < 3:
        return -math.inf
    margin = math.inf
    outside = 0.0
    for i in range(len(hull)):
        a, b = hull[i], hull[(i + 1) % len(hull)]
        edge = b - a
        normal = np.array([edge[1], -edge[0]]) / np.hypot(*edge)     # outward for a counter-clockwise hull
        d = float(normal @ (c - a))                                  # > 0: outside this edge
        margin = min(margin, -d)
        outside = max(outside, d)
    return margin if outside <= 0 else -_distance_to_polygon(hull, c)


def _distance_to_polygon(hull: np.ndarray, c: np.ndarray) -> float:
    best = math.inf
    for i in range(len(hull)):
        a, b = hull[i], hull[(i + 1) % len(hull)]
        t = float(np.clip((c - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0))
        best = min(best, float(np.hypot(*(a + t * (b - a) - c))))
    return best


@takes_layout
def case_loads(layout: Layout, ax: float = 0.0, ay: float = 0.0, grade_deg: float = 0.0, cross_deg: float = 0.0,
               reverse: bool = False) -> LoadCase:
    """Wheel loads, lift and the score of one quasi-static state.

    Parameters
    ----------
    layout : Layout
    ax, ay : float
        m/s^2, body axes.
    grade_deg, cross_deg : float
        deg.
    reverse : bool
        Casters trailing backwards.

    Returns
    -------
    LoadCase
    """
    pts = contacts(layout, reverse)
    xe, ye, normal = effective_centre(layout, ax, ay, grade_deg, cross_deg, reverse)
    xy = np.array([[p[1], p[2]] for p in pts])
    margin = polygon_margin(xy, (xe, ye))
    loads = np.zeros(len(pts))
    if margin < 0:                              # the effective centre is outside the wheels: the chair tips
        with_anti = np.concatenate([xy, np.array(layout.anti_tip, dtype=float).reshape(-1, 2)])
        score = 2 if layout.anti_tip and polygon_margin(with_anti, (xe, ye)) >= 0 else 3
        return LoadCase(loads, tuple(p[0] for p in pts), (xe, ye), margin, score)
    active = list(range(len(pts)))
    while True:
        share = distribute([pts[i] for i in active], normal, (xe, ye))
        if share.min() >= 0 or len(active) <= 3:
            break
        active.pop(int(np.argmin(share)))
    if share.min() < 0:                         # the last three do not hold it: the triple that does
        best = None
        for trio in itertools.combinations(range(len(pts)), 3):
            if abs(np.linalg.det(np.stack([np.ones(3), xy[list(trio), 0], xy[list(trio), 1]]))) < 1e-12:
                continue
            sh = distribute([pts[i] for i in trio], normal, (xe, ye))
            if best is None or sh.min() > best[1].min():
                best = (list(trio), sh)
        if best is not None:
            active, share = best
    loads[active] = np.maximum(share, 0.0)
    lifted = tuple(pts[i][0] for i in range(len(pts)) if i not in active or loads[i] <= 0)
    return LoadCase(loads, lifted, (xe, ye), margin, 1 if lifted else 0)
