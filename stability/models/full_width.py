"""Full-width planar model (chapter 6): contact velocities, accelerations, linear matrices.

The equations are derived in ``derivations/full_width.py`` and generated into
:mod:`stability._generated.full_width`; this module is their numeric door.
Variants: ``"exact"`` (first-principles Kane derivation) and ``"thesis"``
(Table 6-1, eqs 6-17/6-18, what program WCHAIR integrates); see
``derivations/README.md``.  Every function takes floats or broadcast arrays.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability._generated import full_width as _fw
from stability.models.forces import generated as _fo
from stability.models.params import Params
from stability.runtime.checks import check_casters, check_model, check_speeds

__all__ = [
    "generated",
    "contact_velocities",
    "accelerations",
    "tire_resultant",
    "tire_yaw_moment",
    "linear_matrices",
    "trig",
]

#: The generated module itself, for the simulator's hot loop (looked up once).
generated = _fw


def contact_velocities(p: Params, u, v, r, ce, se, cb, sb, eta_d, beta_d, variant: str = "exact"):
    """Velocity of each tire contact point in its own wheel frame (m/s), eqs 6-17a-d.

    Parameters
    ----------
    p : Params
        Chair parameters (:func:`stability.models.params.parameters`).
    u, v : float or ndarray
        Forward and lateral velocity of the c.g. in body axes, m/s.
    r : float or ndarray
        Yaw rate, rad/s (clockwise seen from above).
    ce, se, cb, sb : float or ndarray
        cos and sin of the left (eta) and right (beta) caster angles.
    eta_d, beta_d : float or ndarray
        Caster swivel rates, rad/s.
    variant : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``); ``"thesis"`` is eqs 6-17a-d as printed (OCR-corrected).

    Returns
    -------
    tuple of 8 float or ndarray
        ``(vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy)``, m/s: casters A (left), B
        (right) in their wheel frames, main wheels D (left), E (right) in body axes.
    """
    check_model(variant)
    fn = getattr(_fw, f"contact_velocities_{variant}")
    return fn(u, v, r, ce, se, cb, sb, eta_d, beta_d, *p.geometry)


def accelerations(p: Params, u, v, r, ce, se, cb, sb, eta_d, beta_d,
                  FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, M_A, M_B,
                  Fy_ext=0.0, Mz_ext=0.0, variant: str = "exact", r_dot_casters=None):
    """Accelerations ``(u_dot, v_dot, r_dot, eta_ddot, beta_ddot)`` of the full-width model (Table 6-1, eqs 6-17..6-21).

    Parameters
    ----------
    p : Params
        Chair parameters (:func:`stability.models.params.parameters`).
    u, v : float or ndarray
        Forward and lateral velocity of the c.g. in body axes, m/s.
    r : float or ndarray
        Yaw rate, rad/s.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left) and beta (right).
    eta_d, beta_d : float or ndarray
        Caster swivel rates, rad/s.
    FAx, FAy, FBx, FBy : float or ndarray
        Caster tire forces in each caster wheel's frame (x rolling, y lateral), N.
    FDx, FDy, FEx, FEy : float or ndarray
        Main tire forces (left D, right E) in body axes, N.
    M_A, M_B : float or ndarray
        Moments on the left and right casters about their pins (pin friction), N m.
    Fy_ext : float or ndarray, optional
        Lateral force at the c.g. (a push), N; default 0.
    Mz_ext : float or ndarray, optional
        Yaw moment on the chair (e.g. a motor assist), N m; default 0.
    variant : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    r_dot_casters : float or ndarray or None, optional
        Thesis variant only: yaw acceleration (rad/s^2) used in the caster
        equations 6-20/6-21 in place of the current one (program WCHAIR uses
        the previous step's value); ``None`` uses the current one.

    Returns
    -------
    tuple of 5 float or ndarray
        ``u_dot``, ``v_dot`` (m/s^2), ``r_dot``, ``eta_ddot``, ``beta_ddot`` (rad/s^2).
    """
    check_model(variant)
    args = (u, v, r, ce, se, cb, sb, eta_d, beta_d, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy,
            M_A, M_B, Fy_ext, Mz_ext, *p.inertia)
    if variant == "thesis":
        return _fw.accelerations_thesis(*args, r_dot_casters=r_dot_casters)  # type: ignore[misc]
    return _fw.accelerations_exact(*args)


def linear_matrices(p: Params, speeds, stiffness: dict[str, Any], variant: str = "exact",
                    casters: str = "free"):
    """Mass, stiffness and input matrices of the model linearised about straight running at speed U.

    ``M @ acc = K @ x + Bm * Mz`` with ``acc = [v_dot, r_dot, eta_dd, beta_dd]``
    and ``x = [v, r, eta, eta_dot, beta, beta_dot]`` (free casters) or
    ``acc = [v_dot, r_dot]``, ``x = [v, r]`` (locked casters).

    Parameters
    ----------
    p : Params
        Chair parameters (floats or arrays of shape (N,)).
    speeds : float or array_like
        Forward speeds U, m/s (finite, > 0).
    stiffness : dict of str to float or ndarray
        Cornering stiffness of each tire at its static load, N/rad: keys
        ``"A"``, ``"B"`` (left, right caster), ``"D"``, ``"E"`` (left, right main
        wheel), as :func:`stability.models.statics.static_stiffness` returns them.
    variant : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Free casters (k = 4, n = 6, with the viscous pin damping ``p.pin_damping``,
        N m s/rad) or locked casters (k = n = 2); default ``"free"``.

    Returns
    -------
    M : numpy.ndarray
        Mass matrix (kg, kg m, kg m^2 entries): shape (k, k) when it is the
        same for every speed and chair (it never depends on speed), else (N, k, k).
    K : numpy.ndarray
        Shape (N, k, n), stiffness and damping matrix.
    Bm : numpy.ndarray
        Shape (N, k), input column of a yaw moment Mz on the chair (N m).
    """
    check_model(variant)
    check_casters(casters)
    U = check_speeds(speeds, floor=0.0)         # the public functions bound user speeds (MIN_SPEED)
    name = f"linear_{variant}" if casters == "free" else f"linear_locked_{variant}"
    fn = getattr(_fw, name)
    args = [U, stiffness["A"], stiffness["B"], stiffness["D"], stiffness["E"]]
    if casters == "free":
        args.append(p.pin_damping)
    M, K, Bm = fn(*args, *p.inertia)
    entries = [e for row in (*M, *K) for e in row] + list(Bm)
    shape = np.broadcast_shapes(U.shape, *(np.shape(e) for e in entries),
                                *(np.shape(x) for x in p.inertia))
    m_shape = np.broadcast_shapes(*(np.shape(e) for row in M for e in row))

    def stack(rows, to):
        return np.stack([np.stack([np.broadcast_to(np.asarray(e, dtype=float), to) for e in row], -1)
                         for row in rows], -2)

    return (stack(M, m_shape), stack(K, shape),
            np.stack([np.broadcast_to(np.asarray(e, dtype=float), shape) for e in Bm], -1))


def trig(angle):
    """``(cos, sin)`` of an angle: ``math`` for floats, numpy for arrays.

    Parameters
    ----------
    angle : float or ndarray
        Angle, rad.

    Returns
    -------
    tuple of (float, float) or (ndarray, ndarray)
        ``(cos(angle), sin(angle))``.
    """
    if isinstance(angle, float):
        return math.cos(angle), math.sin(angle)
    return np.cos(angle), np.sin(angle)


def tire_resultant(F, ce, se, cb, sb):
    """Total tire force on the chair in body axes (N), eq 6-2's c1, c2 components.

    Parameters
    ----------
    F : tuple
        ``(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy)``: each tire's force in its
        own wheel frame (N); casters A (left), B (right) turned by eta, beta.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta and beta.

    Returns
    -------
    tuple
        ``(sum_fx, sum_fy)``, N (program WCHAIR's FC1, FC2 without FCIMP;
        generated, :mod:`stability.models.forces`).
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return _fo.tire_resultant(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, ce, se, cb, sb)


def tire_yaw_moment(p: Params, F, ce, se, cb, sb):
    """Yaw moment of the tire forces about the c.g. (N m, clockwise seen from above).

    Parameters
    ----------
    p : Params
        Chair parameters.
    F : tuple
        Tire forces in wheel frames, as for :func:`tire_resultant` (N).
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles.

    Returns
    -------
    float or ndarray
        ``sum (x_i F_yi - y_i F_xi)`` over the four contacts (eq 6-24 points;
        generated, :mod:`stability.models.forces`).
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    return _fo.tire_yaw_moment(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, ce, se, cb, sb, p.x_m, p.x_p, p.d1, p.d2,
                               p.t1, p.t2, p.trail)
