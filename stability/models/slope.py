"""The chair on a slope (cross slope and grade): the door to :mod:`stability._generated.slope`.

Derived in ``derivations/slope.py`` (exact full-width model with in-plane
gravity on the chair and on each caster, normal loads with the slope's
weight components, steady straight-running statics, zero-width closed
forms); see ``docs/slopes.md``.  Every function takes floats or broadcast
arrays; angles in radians.
"""

from __future__ import annotations

import math

from .._generated import slope as _sl
from ..params import Params

__all__ = ["generated", "gravity", "accelerations", "normal_loads", "hold_statics",
           "gravity_generalized_forces", "zero_width_straight", "zero_width_turn"]

#: The generated module itself.
generated = _sl

zero_width_straight = _sl.zero_width_straight
zero_width_turn = _sl.zero_width_turn


def gravity(g: float, cross_slope: float, grade: float, heading: float = 0.0):
    """Gravity in body axes on the plane, ``(g1, g2, gn)`` (m/s^2).

    Parameters
    ----------
    g : float
        Gravitational acceleration (m/s^2).
    cross_slope : float
        Cross slope phi (rad), positive when the plane falls to the right of the path.
    grade : float
        Grade theta (rad), positive uphill along the path.
    heading : float
        Chair heading psi from the path direction (rad, clockwise seen from above).

    Returns
    -------
    tuple
        ``g1`` (forward), ``g2`` (right) in the plane, ``gn`` normal to it.
    """
    return _sl.gravity_body(g, math.cos(cross_slope), math.sin(cross_slope), math.cos(grade),
                            math.sin(grade), math.cos(heading), math.sin(heading))


def accelerations(p: Params, u, v, r, ce, se, cb, sb, eta_d, beta_d, F, M_A, M_B, g1, g2,
                  Fy_ext=0.0, Mz_ext=0.0):
    """Accelerations ``(u_dot, v_dot, r_dot, eta_dd, beta_dd)`` of the exact model on the plane.

    As :func:`stability.models.full_width.accelerations` (``F`` the eight tire
    forces in wheel frames, N) plus the in-plane gravity ``g1, g2`` (m/s^2)
    acting on the chair and on each caster at its own c.g.
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return _sl.accelerations_slope_exact(u, v, r, ce, se, cb, sb, eta_d, beta_d, FAx, FAy, FBx, FBy, FDx, FDy,
                                         FEx, FEy, M_A, M_B, Fy_ext, Mz_ext, g1, g2, p.x_m, p.x_p, p.d1, p.d2,
                                         p.t1, p.t2, p.trail, p.l1, p.m, p.m_c, p.i_z, p.i_zp)


def normal_loads(p: Params, a1, a2, g1, g2, gn, ce=1.0, se=0.0, cb=1.0, sb=0.0):
    """Normal loads ``(N_A, N_B, N_D, N_E)`` (N) on the plane, eq 6-25 extended.

    ``a1, a2``: in-plane c.g. acceleration (m/s^2), ``g1, g2, gn`` gravity in
    body axes; the load-transfer moments are ``h m (a - g_in)``.
    """
    return _sl.normal_loads_slope(a1, a2, g1, g2, gn, ce, se, cb, sb, p.x_m, p.x_p, p.d1, p.d2, p.t1, p.t2,
                                  p.trail, p.h, p.m, p.roll_k)


def hold_statics(p: Params, ce, se, cb, sb, g1, g2, M_A=0.0, M_B=0.0, FAx=0.0, FBx=0.0):
    """Steady straight running: ``(FAy, FBy, Sx, Sy, Mh)``.

    Caster side forces (N), main-wheel force sums ``FDx + FEx``,
    ``FDy + FEy`` (N) and the yaw moment ``d1 FDx - d2 FEx`` (N m) that holds
    the line, for given caster angles, gravity, pin moments and caster rolling forces.
    """
    return _sl.hold_statics(ce, se, cb, sb, g1, g2, M_A, M_B, FAx, FBx, *p.inertia[:10])


def gravity_generalized_forces(p: Params, ce, se, cb, sb, g1, g2):
    """Generalized forces of the in-plane weight on ``(u, v, r, eta_d, beta_d)`` (N, N, N m, N m, N m)."""
    return _sl.gravity_generalized_forces(ce, se, cb, sb, g1, g2, p.x_p, p.t1, p.t2, p.l1, p.m, p.m_c)
