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

from .._generated import full_width as _fw
from .._validate import check_casters, check_model, check_speeds
from ..params import Params
from ..statics import caster_contact_points

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
    """Velocity of each tire contact point in its own wheel frame (m/s).

    Returns ``(vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy)`` (eqs 6-17a-d for the
    thesis variant).  ``ce, se, cb, sb`` are cos/sin of the caster angles.
    """
    check_model(variant)
    fn = getattr(_fw, f"contact_velocities_{variant}")
    return fn(u, v, r, ce, se, cb, sb, eta_d, beta_d, *p.geometry)


def accelerations(p: Params, u, v, r, ce, se, cb, sb, eta_d, beta_d,
                  FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, M_A, M_B,
                  Fy_ext=0.0, Mz_ext=0.0, variant: str = "exact", r_dot_casters=None):
    """Accelerations ``(u_dot, v_dot, r_dot, eta_ddot, beta_ddot)``.

    Tire forces are in each wheel's frame (N), pin moments ``M_A``, ``M_B``
    act on the casters (N m), ``Fy_ext`` is a lateral force at the c.g. (N)
    and ``Mz_ext`` a yaw moment on the chair (N m).  For the thesis variant
    ``r_dot_casters`` optionally replaces the yaw acceleration used in the
    caster equations (program WCHAIR uses the previous step's value).
    """
    check_model(variant)
    args = (u, v, r, ce, se, cb, sb, eta_d, beta_d, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy,
            M_A, M_B, Fy_ext, Mz_ext, *p.inertia)
    if variant == "thesis":
        return _fw.accelerations_thesis(*args, r_dot_casters=r_dot_casters)  # type: ignore[misc]
    return _fw.accelerations_exact(*args)


def linear_matrices(p: Params, speeds, stiffness: dict[str, Any], variant: str = "exact",
                    casters: str = "free"):
    """Mass, stiffness and input matrices of the linearised model.

    ``M @ acc = K @ x + Bm * Mz`` with ``acc = [v_dot, r_dot, eta_dd, beta_dd]``
    and ``x = [v, r, eta, eta_dot, beta, beta_dot]`` (free casters) or
    ``acc = [v_dot, r_dot]``, ``x = [v, r]`` (locked casters).

    Returns numpy arrays broadcast over ``speeds``: ``M`` (N, k, k), ``K``
    (N, k, n) and ``Bm`` (N, k).
    """
    check_model(variant)
    check_casters(casters)
    U = check_speeds(speeds)
    name = f"linear_{variant}" if casters == "free" else f"linear_locked_{variant}"
    fn = getattr(_fw, name)
    args = [U, stiffness["A"], stiffness["B"], stiffness["D"], stiffness["E"]]
    if casters == "free":
        args.append(p.pin_damping)
    M, K, Bm = fn(*args, *p.inertia)
    entries = [e for row in (*M, *K) for e in row] + list(Bm)
    shape = np.broadcast_shapes(U.shape, *(np.shape(e) for e in entries),
                                *(np.shape(x) for x in p.inertia))

    def stack(rows):
        return np.stack([np.stack([np.broadcast_to(np.asarray(e, dtype=float), shape) for e in row], -1)
                         for row in rows], -2)

    return stack(M), stack(K), np.stack([np.broadcast_to(np.asarray(e, dtype=float), shape) for e in Bm], -1)


def trig(angle):
    """``(cos, sin)`` of an angle: ``math`` for floats, numpy for arrays."""
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
        ``(sum_fx, sum_fy)``, N (program WCHAIR's FC1, FC2 without FCIMP).
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    fc1 = FDx + FEx + FAx * ce - FAy * se + FBx * cb - FBy * sb
    fc2 = FDy + FEy + FAx * se + FAy * ce + FBx * sb + FBy * cb
    return fc1, fc2


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
        ``sum (x_i F_yi - y_i F_xi)`` over the four contacts (eq 6-24 points).
    """
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    (xa, ya), (xb, yb) = caster_contact_points(p, ce, se, cb, sb)
    fax, fay = FAx * ce - FAy * se, FAx * se + FAy * ce
    fbx, fby = FBx * cb - FBy * sb, FBx * sb + FBy * cb
    return xa * fay - ya * fax + xb * fby - yb * fbx + p.x_m * (FDy + FEy) + p.d1 * FDx - p.d2 * FEx
