"""Numeric full-width and zero-width wheelchair models.

This module is the single numeric entry point to the equations of motion.
The equations themselves are derived symbolically in ``derivations/`` and
generated, once, into :mod:`stability._generated`; nothing here (or anywhere
at run time) does symbolic algebra.  Two variants exist:

``"exact"``
    the first-principles derivation (Kane's method, three rigid bodies);
``"thesis"``
    Table 6-1 and eqs 6-17/6-18 of Collins (1987) as printed, which is what
    program WCHAIR integrates.

See ``derivations/README.md`` for every difference between them.

All functions accept Python floats (fast single runs) or broadcast numpy
arrays (batches over speeds, runs or chairs).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple, Sequence

import numpy as np

from ._validate import VARIANTS, check_casters, check_model, check_speeds
from .chair import Chair

__all__ = [
    "VARIANTS",
    "Params",
    "parameters",
    "contact_velocities",
    "accelerations",
    "static_stiffness",
    "linear_matrices",
]


class Params(NamedTuple):
    """Numeric chair parameters in signed body coordinates (SI units).

    Each field is a float (one chair) or an ndarray (a batch of chairs).
    ``x_m`` and ``x_p`` are the signed x coordinates of the main axle and
    of the caster pins relative to the centre of gravity (positive forward).
    """

    x_m: Any
    x_p: Any
    d1: Any
    d2: Any
    t1: Any
    t2: Any
    trail: Any
    l1: Any
    h: Any
    m: Any
    m_c: Any
    i_z: Any
    i_zp: Any
    g: Any
    roll_k: Any
    pin_damping: Any
    pin_friction_left: Any
    pin_friction_right: Any

    @property
    def geometry(self) -> tuple:
        """(x_m, x_p, d1, d2, t1, t2, trail): arguments of the kinematics."""
        return (self.x_m, self.x_p, self.d1, self.d2, self.t1, self.t2, self.trail)

    @property
    def inertia(self) -> tuple:
        """(x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp): arguments of the dynamics."""
        return self.geometry + (self.l1, self.m, self.m_c, self.i_z, self.i_zp)


def _one(c: Chair) -> Params:
    return Params(
        float(c.x_main), float(c.x_pin), float(c.d1), float(c.d2), float(c.t1), float(c.t2),
        float(c.trail), float(c.l1), float(c.h), float(c.m), float(c.m_c), float(c.i_z),
        float(c.i_zp), float(c.g), float(c.roll_k), float(c.pin_damping),
        float(c.pin_friction_left), float(c.pin_friction_right),
    )


def parameters(chairs: Chair | Sequence[Chair]) -> Params:
    """Pack one chair (floats) or a sequence of chairs (arrays of shape (N,))."""
    if isinstance(chairs, Chair):
        return _one(chairs)
    rows = [_one(c) for c in chairs]
    if not rows:
        raise ValueError("chairs: expected a Chair or a non-empty sequence of Chair")
    return Params(*(np.array(col, dtype=float) for col in zip(*rows)))


def _gen():
    from ._generated import full_width

    return full_width


def contact_velocities(p: Params, u, v, r, ce, se, cb, sb, eta_d, beta_d, variant: str = "exact"):
    """Velocity of each tire contact point in its own wheel frame (m/s).

    Returns ``(vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy)`` (eqs 6-17a-d for the
    thesis variant).  ``ce, se, cb, sb`` are cos/sin of the caster angles.
    """
    check_model(variant)
    fn = getattr(_gen(), f"contact_velocities_{variant}")
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
    g = _gen()
    args = (u, v, r, ce, se, cb, sb, eta_d, beta_d, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy,
            M_A, M_B, Fy_ext, Mz_ext, *p.inertia)
    if variant == "thesis":
        return g.accelerations_thesis(*args, r_dot_casters=r_dot_casters)
    return g.accelerations_exact(*args)


def static_stiffness(chair: Chair) -> dict[str, float]:
    """Cornering stiffness (N/rad) of each tire at its static normal load.

    The stiffness is the slope of the tire's fit between 0 and 1 deg at that
    load (Table 4-1 method), times the lateral scale factor (TYMOD/CYMOD).
    Returns keys ``"A"``, ``"B"`` (left, right caster), ``"D"``, ``"E"``
    (left, right main wheel).
    """
    from .loads import normal_loads

    n_a, n_b, n_d, n_e = normal_loads(parameters(chair))
    main = chair.main_tire_model()
    caster = chair.caster_tire_model()
    return {
        "A": float(caster.cornering_stiffness_per_rad(n_a)),
        "B": float(caster.cornering_stiffness_per_rad(n_b)),
        "D": float(main.cornering_stiffness_per_rad(n_d)),
        "E": float(main.cornering_stiffness_per_rad(n_e)),
    }


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
    g = _gen()
    name = f"linear_{variant}" if casters == "free" else f"linear_locked_{variant}"
    fn = getattr(g, name)
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
