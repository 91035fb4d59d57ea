"""The chair on a slope (cross slope and grade): the door to :mod:`stability._generated.slope`.

Derived in ``derivations/slope.py`` (exact full-width model with in-plane
gravity on the chair and on each caster, normal loads with the slope's
weight components, steady straight-running statics, zero-width closed
forms); see ``docs/slopes.md``.  Every function takes floats or broadcast
arrays; angles in radians.
"""

from __future__ import annotations

import math

from stability._generated import slope as _sl
from stability.models.forces import generated as _fo
from stability.models.params import Params

__all__ = ["generated", "gravity", "accelerations", "normal_loads", "normal_loads_plane", "hold_statics",
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

    As :func:`stability.models.full_width.accelerations` plus the in-plane
    gravity acting on the chair and on each caster at its own c.g.

    Parameters
    ----------
    p : Params
        Chair parameters.
    u, v : float or ndarray
        Forward and lateral velocity of the c.g. in body axes, m/s.
    r : float or ndarray
        Yaw rate, rad/s.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left) and beta (right).
    eta_d, beta_d : float or ndarray
        Caster swivel rates, rad/s.
    F : tuple of 8 float or ndarray
        ``(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy)``: tire forces in wheel frames, N.
    M_A, M_B : float or ndarray
        Moments on the left and right casters about their pins, N m.
    g1, g2 : float or ndarray
        In-plane gravity components in body axes (forward, right), m/s^2 (:func:`gravity`).
    Fy_ext : float or ndarray, optional
        Lateral force at the c.g., N; default 0.
    Mz_ext : float or ndarray, optional
        Yaw moment on the chair, N m; default 0.

    Returns
    -------
    tuple of 5 float or ndarray
        ``u_dot``, ``v_dot`` (m/s^2), ``r_dot``, ``eta_dd``, ``beta_dd`` (rad/s^2).
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return _sl.accelerations_slope_exact(u, v, r, ce, se, cb, sb, eta_d, beta_d, FAx, FAy, FBx, FBy, FDx, FDy,
                                         FEx, FEy, M_A, M_B, Fy_ext, Mz_ext, g1, g2, p.x_m, p.x_p, p.d1, p.d2,
                                         p.t1, p.t2, p.trail, p.l1, p.m, p.m_c, p.i_z, p.i_zp)


def normal_loads(p: Params, a1, a2, g1, g2, gn, ce=1.0, se=0.0, cb=1.0, sb=0.0):
    """Normal loads ``(N_A, N_B, N_D, N_E)`` on the plane, eq 6-25 extended to a slope.

    The load-transfer moments are ``h m (a - g_in)``, split between the caster
    and main axles by the roll coefficient k = k_f/k_r (eqs 6-25a,b):
    :func:`normal_loads_plane` with the force sums ``m (a - g_in)``.

    Parameters
    ----------
    p : Params
        Chair parameters (``h``, ``m``, ``roll_k`` and the geometry used).
    a1, a2 : float or ndarray
        In-plane c.g. acceleration in body axes (forward, right), m/s^2.
    g1, g2, gn : float or ndarray
        Gravity in body axes: forward and right in the plane, normal to it, m/s^2 (:func:`gravity`).
    ce, se, cb, sb : float or ndarray, optional
        cos and sin of the caster angles (default trailing straight: 1, 0, 1, 0).

    Returns
    -------
    tuple of 4 float or ndarray
        Normal loads on the left and right casters and left and right main wheels, N.
    """
    return normal_loads_plane(p, p.m * (a1 - g1), p.m * (a2 - g2), gn, ce, se, cb, sb)


def normal_loads_plane(p: Params, sum_fx, sum_fy, gn, ce=1.0, se=0.0, cb=1.0, sb=0.0):
    """Normal loads ``(N_A, N_B, N_D, N_E)`` on the plane from the tire-force sums (the simulator's form).

    :func:`normal_loads` with ``m a = sum F + m g_in``: the in-plane weight
    drops out of the load transfer (moments ``h sum F``) and only the normal
    weight ``m gn`` remains; ``gn = g`` is eq 6-25
    (:func:`stability.models.statics.normal_loads`: the same generated function,
    :mod:`stability.models.forces`).

    Parameters
    ----------
    p : Params
        Chair parameters (``h``, ``m``, ``roll_k`` and the geometry used).
    sum_fx, sum_fy : float or ndarray
        Sums of the tire forces (and any force at the c.g.) in body axes, N.
    gn : float or ndarray
        Gravity normal to the plane, m/s^2 (``g cos(phi) cos(theta)``).
    ce, se, cb, sb : float or ndarray, optional
        cos and sin of the caster angles (default trailing straight: 1, 0, 1, 0).

    Returns
    -------
    tuple of 4 float or ndarray
        Normal loads on the left and right casters and left and right main wheels, N.
    """
    return _fo.normal_loads(sum_fx, sum_fy, gn, ce, se, cb, sb, p.x_m, p.x_p, p.d1, p.d2, p.t1, p.t2, p.trail,
                            p.h, p.m, p.roll_k)


def hold_statics(p: Params, ce, se, cb, sb, g1, g2, M_A=0.0, M_B=0.0, FAx=0.0, FBx=0.0):
    """Steady straight running on the plane: ``(FAy, FBy, Sx, Sy, Mh)``.

    Parameters
    ----------
    p : Params
        Chair parameters.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left) and beta (right).
    g1, g2 : float or ndarray
        In-plane gravity components in body axes (forward, right), m/s^2.
    M_A, M_B : float or ndarray, optional
        Pin moments on the left and right casters, N m; default 0.
    FAx, FBx : float or ndarray, optional
        Caster rolling forces in the caster wheel frames, N; default 0.

    Returns
    -------
    tuple of 5 float or ndarray
        Caster side forces ``FAy``, ``FBy`` (N), main-wheel force sums
        ``Sx = FDx + FEx`` and ``Sy = FDy + FEy`` (N), and the yaw moment
        ``Mh = d1 FDx - d2 FEx`` (N m) the main wheels must supply to hold the line.
    """
    return _sl.hold_statics(ce, se, cb, sb, g1, g2, M_A, M_B, FAx, FBx, *p.inertia[:10])


def gravity_generalized_forces(p: Params, ce, se, cb, sb, g1, g2):
    """Generalized forces of the in-plane weight on ``(u, v, r, eta_d, beta_d)``.

    Parameters
    ----------
    p : Params
        Chair parameters (masses m, m_c and the caster geometry used).
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left) and beta (right).
    g1, g2 : float or ndarray
        In-plane gravity components in body axes (forward, right), m/s^2.

    Returns
    -------
    tuple of 5 float or ndarray
        Generalized forces on u, v (N) and on r, eta_d, beta_d (N m).
    """
    return _sl.gravity_generalized_forces(ce, se, cb, sb, g1, g2, p.x_p, p.t1, p.t2, p.l1, p.m, p.m_c)
