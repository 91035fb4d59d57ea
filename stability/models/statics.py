"""Statics: contact-point geometry, quasi-static normal loads, tire stiffness at load.

Eqs 6-19..6-30 of Collins (1987), written in signed body coordinates so that
rear- and front-caster chairs are served alike.  Normal loads are positive
magnitudes.  Pure arithmetic: floats (single runs) or broadcast arrays.
"""

from __future__ import annotations

from typing import Any

from stability.chair import Chair
from stability.models.forces import generated as _fo
from stability.models.params import Params, parameters

__all__ = ["caster_contact_points", "normal_loads", "static_loads", "static_stiffness", "check_static_loads"]


def caster_contact_points(p: Params, ce: Any = 1.0, se: Any = 0.0, cb: Any = 1.0, sb: Any = 0.0):
    """Body coordinates of the two caster contact points (m), eq 6-24.

    Parameters
    ----------
    p : Params
        Chair parameters (floats, or arrays for a batch).
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (left, A) and beta (right, B),
        rad; the defaults are the casters trailing straight.

    Returns
    -------
    tuple
        ``((x_A, y_A), (x_B, y_B))``: the contacts lie ``trail`` behind the
        pins at ``(x_p, -t1)`` and ``(x_p, t2)`` along each caster's heading.
    """
    x_a, y_a, x_b, y_b = _fo.caster_contacts(ce, se, cb, sb, p.x_p, p.t1, p.t2, p.trail)
    return (x_a, y_a), (x_b, y_b)


def normal_loads(p: Params, sum_fx: Any = 0.0, sum_fy: Any = 0.0,
                 ce: Any = 1.0, se: Any = 0.0, cb: Any = 1.0, sb: Any = 0.0):
    """Normal load on each tire from the total horizontal tire force, eq 6-25 solved exactly (generated).

    * ``N_A + N_B + N_D + N_E = m g``                              (6-25c)
    * ``sum_i x_i N_i = -h sum(Fx)``                               (6-25d)
    * ``y_A N_A + y_B N_B = -h sum(Fy) / (k + 1)``                 (6-25a)
    * ``y_D N_D + y_E N_E = -h sum(Fy) k / (k + 1)``               (6-25b)

    with the caster contacts of :func:`caster_contact_points` and the main
    wheels at ``(x_m, -d1)``, ``(x_m, d2)``; ``k`` is the roll-stiffness ratio
    (eq 6-30: ``1/(k+1)`` of the roll moment to the casters).  Level ground is
    the plane of :func:`stability.models.slope.normal_loads_plane` with the
    normal gravity ``g``: one generated function
    (:mod:`stability.models.forces`).

    Parameters
    ----------
    p : Params
        Chair parameters (floats, or arrays for a batch of chairs).
    sum_fx, sum_fy : float or ndarray
        Total tire force on the chair along body x (forward) and y (right), N.
        Positive ``sum_fy`` (a right turn) loads the left wheels.
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles eta (A) and beta (B).

    Returns
    -------
    tuple
        ``(N_A, N_B, N_D, N_E)``: left caster, right caster, left main wheel,
        right main wheel, N (positive when pressing on the ground).
    """
    return _fo.normal_loads(sum_fx, sum_fy, p.g, ce, se, cb, sb, p.x_m, p.x_p, p.d1, p.d2, p.t1, p.t2, p.trail,
                            p.h, p.m, p.roll_k)


def static_loads(chair: Chair) -> dict[str, float]:
    """Static normal loads (N) with no tire forces and the casters trailing.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    dict
        Keys ``"caster_left"``, ``"caster_right"``, ``"main_left"``,
        ``"main_right"``, and ``"main"``, ``"caster"`` (the mean of each pair), N.
    """
    n_a, n_b, n_d, n_e = normal_loads(parameters(chair))
    return {
        "caster_left": float(n_a), "caster_right": float(n_b),
        "main_left": float(n_d), "main_right": float(n_e),
        "main": float(0.5 * (n_d + n_e)), "caster": float(0.5 * (n_a + n_b)),
    }


def static_stiffness(chair: Chair) -> dict[str, float]:
    """Cornering stiffness (N/rad) of each tire at its static normal load.

    The slope of the tire's fit between 0 and 1 deg at that load (Table 4-1
    method) times the chair's lateral scale factor (WCHAIR's TYMOD/CYMOD).
    This is the one place the toolkit computes stiffness at load.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    dict
        Keys ``"A"``, ``"B"`` (left, right caster), ``"D"``, ``"E"`` (left,
        right main wheel), N/rad.
    """
    check_static_loads(chair)
    n_a, n_b, n_d, n_e = normal_loads(parameters(chair))
    main = chair.main_tire_model()
    caster = chair.caster_tire_model()
    return {
        "A": float(caster.cornering_stiffness_per_rad(n_a)),
        "B": float(caster.cornering_stiffness_per_rad(n_b)),
        "D": float(main.cornering_stiffness_per_rad(n_d)),
        "E": float(main.cornering_stiffness_per_rad(n_e)),
    }


def check_static_loads(chair: Chair) -> None:
    """Refuse a chair whose c.g. lies outside its wheel contacts (a static load <= 0).

    Parameters
    ----------
    chair : Chair

    Raises
    ------
    ValueError
        One sentence naming the wheel, its load and why.
    """
    names = ("left caster", "right caster", "left main wheel", "right main wheel")
    for name, load in zip(names, normal_loads(parameters(chair)), strict=True):
        if not load > 0:
            raise ValueError(
                f"chair {chair.name!r}: static load on the {name} is {float(load):.4g} N: the centre of gravity "
                "lies outside the wheel contacts (valid: every static load > 0; check s1, s2, trail, d1, d2, t1, t2)")
