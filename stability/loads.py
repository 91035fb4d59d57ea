"""Quasi-static normal loads with lateral load transfer (thesis eqs 6-19..6-30).

The chair is treated as a rigid body in quasi-static roll and pitch
equilibrium: the vertical forces balance the weight, their pitch moment
balances ``h * sum(Fx)`` and their roll moment balances ``h * sum(Fy)``, the
latter split between the caster pair and the main-wheel pair in proportion
to their roll stiffnesses (``C1 = 1/(k+1)`` to the casters, ``C2 = k/(k+1)``
to the main wheels, eq 6-30, with ``k = k_f/k_r`` the roll coefficient).
This is eq 6-25 written in signed body coordinates, so that it serves rear-
and front-caster chairs alike.  Normal loads here are positive magnitudes
(the thesis's F_Z are negative because its z axis points down).

The closed-form solution below is pure arithmetic: it evaluates on Python
floats (fast single simulations) and on broadcast numpy arrays (batches).
"""

from __future__ import annotations

from typing import Any

__all__ = ["normal_loads", "static_loads"]


def normal_loads(p: Any, sum_fx: Any = 0.0, sum_fy: Any = 0.0,
                 ce: Any = 1.0, se: Any = 0.0, cb: Any = 1.0, sb: Any = 0.0):
    """Normal load on each tire from the total horizontal tire force.

    Solves eq 6-25 (a-d) exactly:

    * ``N_A + N_B + N_D + N_E = m g``                              (6-25c)
    * ``sum_i x_i N_i = -h sum(Fx)``                               (6-25d)
    * ``y_A N_A + y_B N_B = -h sum(Fy) / (k + 1)``                 (6-25a)
    * ``y_D N_D + y_E N_E = -h sum(Fy) k / (k + 1)``               (6-25b)

    with the caster contact points at ``(x_p - l cos eta, -t1 - l sin eta)``
    and ``(x_p - l cos beta, t2 - l sin beta)`` (eq 6-24) and the main
    wheels at ``(x_m, -d1)``, ``(x_m, d2)``.

    Parameters
    ----------
    p : stability.models.Params
        Chair parameters (floats, or arrays for a batch of chairs).
    sum_fx, sum_fy : float or ndarray
        Total tire force on the chair along the body x (forward) and y
        (right) axes, N (the c1 and c2 components of eq 6-2).  Positive
        ``sum_fy`` (the ground pushing the chair to the right, i.e. a right
        turn) loads the left wheels.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left, A) and beta (right, B).

    Returns
    -------
    tuple
        ``(N_A, N_B, N_D, N_E)``: left caster, right caster, left main wheel,
        right main wheel, N (positive when pressing on the ground).
    """
    c1 = 1.0 / (p.roll_k + 1.0)
    c2 = p.roll_k * c1
    xa = p.x_p - p.trail * ce
    ya = -p.t1 - p.trail * se
    xb = p.x_p - p.trail * cb
    yb = p.t2 - p.trail * sb
    weight = p.m * p.g
    r_c = -p.h * sum_fy * c1           # roll moment carried by the caster pair
    r_m = -p.h * sum_fy * c2           # ... and by the main-wheel pair
    dy = yb - ya
    x_c = (xa * yb - xb * ya) / dy     # effective x of the caster pair
    s_m = (-p.h * sum_fx - r_c * (xb - xa) / dy - weight * x_c) / (p.x_m - x_c)
    s_c = weight - s_m
    n_a = (yb * s_c - r_c) / dy
    n_b = (r_c - ya * s_c) / dy
    n_e = (r_m + p.d1 * s_m) / (p.d1 + p.d2)
    n_d = s_m - n_e
    return n_a, n_b, n_d, n_e


def static_loads(chair) -> dict[str, float]:
    """Static normal loads (N) with no tire forces and the casters trailing.

    Returns a dict with keys ``"caster_left"``, ``"caster_right"``,
    ``"main_left"``, ``"main_right"``, ``"main"`` and ``"caster"`` (the last two:
    one wheel of a symmetric chair, the mean of the pair).
    """
    from .models import parameters

    n_a, n_b, n_d, n_e = normal_loads(parameters(chair))
    return {
        "caster_left": float(n_a), "caster_right": float(n_b),
        "main_left": float(n_d), "main_right": float(n_e),
        "main": float(0.5 * (n_d + n_e)), "caster": float(0.5 * (n_a + n_b)),
    }
