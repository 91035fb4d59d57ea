"""Zero-width ("bicycle") wheelchair model, chapter 5 of Collins (1987).

The derivation follows the thesis step by step but is done from first
principles with :mod:`sympy.physics.vector`:

* eqs 5-1..5-4: the acceleration of the centre of mass expressed in the body
  frame, ``a = (u_dot - r v) c1 + (v_dot + r u) c2``, from differentiating
  ``u c1 + v c2`` in the ground frame N (c1, c2 rotate at ``r c3``);
* eqs 5-5..5-8: linear tires, ``F_y = -2 C alpha`` per axle (two tires per
  axle, ``C`` the cornering stiffness of ONE tire in N/rad), with slip angles
  ``alpha = (lateral velocity)/(forward velocity)`` at the front axle (``s1``
  ahead of the c.g.) and the rear axle (``s2`` behind it);
* eqs 5-9a,b: the two linear equations of motion in ``v`` and ``r``;
* eq 5-11 with 5-12a-d: the characteristic equation;
* eq 5-14 with 5-13: the Routh-Hurwitz stability condition;
* eqs 5-15, 5-16, 5-17a,b: critical speed and understeer coefficient.

Every derived result is compared with the thesis's printed form in
:func:`checks`; each entry of the returned dict is a sympy expression that
simplifies to zero.

Sign conventions are SAE (c1 forward, c2 right, c3 down, yaw rate ``r``
positive clockwise seen from above), which are the thesis's.  Note on
eq 5-12b: the thesis prints ``a2 = m u + (2 C_f s1 - 2 C_r s2)/u``; the
derivation below gives exactly that sign (the ``m u`` is the centripetal term
``m r u`` of eq 5-4b moved to the left-hand side), so 5-12b is correct as
printed.

The thesis writes the forward *velocity* as ``u_dot`` (u is a displacement);
here ``U`` (or ``u``) is the forward velocity and ``v`` the lateral velocity.
"""

from __future__ import annotations

import functools

import sympy as sp
import sympy.physics.vector as spv

__all__ = [
    "SYMBOLS",
    "derive",
    "checks",
    "generated_functions",
]

# Symbols ------------------------------------------------------------------
U, m, i_z, s1, s2, C_f, C_r, g = sp.symbols("U m i_z s1 s2 C_f C_r g", positive=True)
v, r, lam = sp.symbols("v r lambda")
W_f, W_r, W, s = sp.symbols("W_f W_r W s", positive=True)

SYMBOLS: dict[str, sp.Symbol] = {
    str(x): x for x in (U, m, i_z, s1, s2, C_f, C_r, g, v, r, lam, W_f, W_r, W, s)
}


@functools.cache
def derive() -> dict[str, object]:
    """Derive the zero-width model (eqs 5-1..5-17) from body-frame Newton-Euler.

    Returns
    -------
    dict
        ``"accel"``: body-frame components of the c.g. acceleration (5-3);
        ``"alpha_f"``, ``"alpha_r"``: slip angles (5-8a,b);
        ``"eq_v"``, ``"eq_r"``: left-hand sides of 5-9a, 5-9b (``= 0``);
        ``"M"``, ``"A"``: ``M [v_dot, r_dot] + A [v, r] = 0``;
        ``"state_matrix"``: ``-M^-1 A`` (``[v_dot, r_dot] = S [v, r]``);
        ``"char_poly"``: monic characteristic polynomial in ``lambda``;
        ``"a"``: the derived ``(a1, a2, a3, a4)``;
        ``"rh_constant"``: the constant coefficient ``a1 a4 - a2 a3`` (the
        term whose sign decides stability), ``"k_us"``, ``"u_crit_sq"``.
    """
    t = spv.dynamicsymbols._t
    ut, vt, th = spv.dynamicsymbols("u v theta")
    N = spv.ReferenceFrame("N")
    Cf = N.orientnew("C", "Axis", (th, N.z))  # c3 = n3 (down), theta about c3
    vel = ut * Cf.x + vt * Cf.y  # eq 5-1
    acc = vel.diff(t, N)  # eqs 5-2, 5-3
    ax = sp.simplify(acc.dot(Cf.x))
    ay = sp.simplify(acc.dot(Cf.y))
    rep = {ut.diff(t): sp.Symbol("u_dot"), vt.diff(t): sp.Symbol("v_dot"),
           th.diff(t): r, ut: U, vt: v}
    ax = ax.subs(rep)
    ay = ay.subs(rep)

    # contact-point velocities (5-6a,b): v_C + r c3 x (x c1)
    w = r * Cf.z
    v_front = (U * Cf.x + v * Cf.y) + w.cross(s1 * Cf.x)
    v_rear = (U * Cf.x + v * Cf.y) + w.cross(-s2 * Cf.x)
    alpha_f = v_front.dot(Cf.y) / v_front.dot(Cf.x)  # 5-7, 5-8a (small angle)
    alpha_r = v_rear.dot(Cf.y) / v_rear.dot(Cf.x)  # 5-8b
    F_yf = -2 * C_f * alpha_f  # 5-5a (two tires)
    F_yr = -2 * C_r * alpha_r  # 5-5b
    v_dot, r_dot = sp.symbols("v_dot r_dot")
    ay = ay.subs(sp.Symbol("v_dot"), v_dot)
    # 5-4b, 5-4c: sum F_y = m a_y ; sum M_z = I_z r_dot
    eq_v = sp.expand(m * ay - (F_yf + F_yr))
    eq_r = sp.expand(i_z * r_dot - (s1 * F_yf - s2 * F_yr))
    Mmat = sp.Matrix([[eq_v.coeff(v_dot), eq_v.coeff(r_dot)],
                      [eq_r.coeff(v_dot), eq_r.coeff(r_dot)]])
    rest_v = sp.expand(eq_v - Mmat[0, 0] * v_dot - Mmat[0, 1] * r_dot)
    rest_r = sp.expand(eq_r - Mmat[1, 0] * v_dot - Mmat[1, 1] * r_dot)
    Amat = sp.Matrix([[rest_v.coeff(v), rest_v.coeff(r)],
                      [rest_r.coeff(v), rest_r.coeff(r)]])
    assert sp.simplify(rest_v - Amat[0, 0] * v - Amat[0, 1] * r) == 0
    assert sp.simplify(rest_r - Amat[1, 0] * v - Amat[1, 1] * r) == 0
    S = (-Mmat.inv() * Amat).applyfunc(sp.simplify)
    char_poly = sp.expand((lam * Mmat + Amat).det() / (m * i_z))
    a1, a2 = Amat[0, 0], Amat[0, 1]
    a3, a4 = Amat[1, 0], Amat[1, 1]
    rh_constant = sp.simplify(a1 * a4 - a2 * a3)
    # critical speed: the constant coefficient vanishes
    Usq = sp.Symbol("Usq", positive=True)
    sol = sp.solve(sp.numer(sp.together(rh_constant.subs(U, sp.sqrt(Usq)))), Usq)
    assert len(sol) == 1
    # understeer coefficient expressed with the per-tire static loads of 5-13
    k_us = W_f / C_f - W_r / C_r
    return {
        "accel": (ax, ay),
        "alpha_f": alpha_f,
        "alpha_r": alpha_r,
        "eq_v": eq_v,
        "eq_r": eq_r,
        "M": Mmat,
        "A": Amat,
        "state_matrix": S,
        "char_poly": char_poly,
        "a": (a1, a2, a3, a4),
        "rh_constant": rh_constant,
        "k_us": k_us,
        "u_crit_sq": sp.simplify(sol[0]),
        "v_dot": v_dot,
        "r_dot": r_dot,
    }


def thesis_forms() -> dict[str, sp.Expr]:
    """The thesis's printed chapter-5 results, transcribed (eqs 5-9..5-17).

    ``U`` stands for the thesis's forward velocity ``u_dot``.
    """
    v_dot, r_dot = sp.symbols("v_dot r_dot")
    a1 = (2 * C_f + 2 * C_r) / U  # 5-12a
    a2 = m * U + (2 * C_f * s1 - 2 * C_r * s2) / U  # 5-12b (as printed)
    a3 = (2 * C_f * s1 - 2 * C_r * s2) / U  # 5-12c
    a4 = (2 * C_f * s1 ** 2 + 2 * C_r * s2 ** 2) / U  # 5-12d
    eq_5_9a = m * v_dot + (m * U + (2 * C_f * s1 - 2 * C_r * s2) / U) * r + ((2 * C_f + 2 * C_r) / U) * v
    eq_5_9b = i_z * r_dot + ((2 * C_f * s1 ** 2 + 2 * C_r * s2 ** 2) / U) * r + ((2 * C_f * s1 - 2 * C_r * s2) / U) * v
    char_5_11 = lam ** 2 + (a1 * i_z + a4 * m) / (i_z * m) * lam + (a1 * a4 - a2 * a3) / (i_z * m)
    Wt = m * g  # 5-13a
    s_tot = s1 + s2
    W_r_513 = Wt * s1 / (2 * s_tot)  # 5-13b (per rear tire)
    W_f_513 = Wt * s2 / (2 * s_tot)  # 5-13c (per front tire)
    lhs_5_14 = U ** 2 / g * (W_f_513 / C_f - W_r_513 / C_r) + s_tot
    k_us_516 = W_f / C_f - W_r / C_r
    k_us_517a = (W_f * C_r - W_r * C_f) / (C_f * C_r)
    k_us_517b = W * (s2 * C_r - s1 * C_f) / (2 * s * C_f * C_r)
    u_crit_sq_515 = -g * s / k_us_516
    return {
        "a": (a1, a2, a3, a4),
        "eq_5_9a": eq_5_9a,
        "eq_5_9b": eq_5_9b,
        "char_5_11": char_5_11,
        "lhs_5_14": lhs_5_14,
        "W_f_513": W_f_513,
        "W_r_513": W_r_513,
        "k_us_516": k_us_516,
        "k_us_517a": k_us_517a,
        "k_us_517b": k_us_517b,
        "u_crit_sq_515": u_crit_sq_515,
    }


@functools.cache
def checks() -> dict[str, sp.Expr]:
    """Derived minus printed, for every chapter-5 result (each simplifies to 0).

    Keys name the thesis equation.  ``"5-14"`` compares the derived constant
    coefficient ``a1 a4 - a2 a3`` with the printed left-hand side of 5-14 times
    the positive factor ``4 C_f C_r s / U^2`` (so both have the same sign for
    every speed: 5-14 is the Routh-Hurwitz condition).  ``"5-15"`` compares the
    derived ``U_crit^2`` (root of the constant coefficient, with the static
    per-tire loads 5-13) with ``-g s / k_us``.
    """
    d = derive()
    th = thesis_forms()
    v_dot, r_dot = d["v_dot"], d["r_dot"]
    out: dict[str, sp.Expr] = {}
    for i, name in enumerate(("5-12a", "5-12b", "5-12c", "5-12d")):
        out[name] = sp.simplify(d["a"][i] - th["a"][i])
    out["5-9a"] = sp.simplify(d["eq_v"] - th["eq_5_9a"].subs({sp.Symbol("v_dot"): v_dot}))
    out["5-9b"] = sp.simplify(d["eq_r"] - th["eq_5_9b"].subs({sp.Symbol("r_dot"): r_dot}))
    out["5-11"] = sp.simplify(d["char_poly"] - th["char_5_11"])
    s_tot = s1 + s2
    out["5-14"] = sp.simplify(d["rh_constant"] - 4 * C_f * C_r * s_tot / U ** 2 * th["lhs_5_14"])
    k_us_static = th["W_f_513"] / C_f - th["W_r_513"] / C_r
    out["5-15"] = sp.simplify(d["u_crit_sq"] - (-g * s_tot / k_us_static))
    sub = {W_f: W * s2 / (2 * s), W_r: W * s1 / (2 * s)}
    out["5-16"] = sp.simplify(d["k_us"] - th["k_us_516"])
    out["5-17a"] = sp.simplify(th["k_us_516"] - th["k_us_517a"])
    out["5-17b"] = sp.simplify(th["k_us_516"].subs(sub) - th["k_us_517b"])
    # 5-18: rear-caster limit, C_r -> 0 dominates: U^2/g (-W_r/C_r) + s
    lhs_518 = -U ** 2 * W_r / (g * C_r) + s
    lhs_514 = U ** 2 / g * th["k_us_516"] + s
    out["5-18"] = sp.limit((lhs_514 - lhs_518) * C_r, C_r, 0)
    return out


def generated_functions() -> list:
    """Expressions for :mod:`stability._generated.zero_width`.

    Returns
    -------
    list of (name, args, outputs, doc)
        ``outputs`` is a list of expressions (or nested tuples of them) in
        the symbols named by ``args``.
    """
    d = derive()
    th = thesis_forms()
    S = d["state_matrix"]
    cp = sp.Poly(d["char_poly"], lam)
    c2, c1, c0 = cp.all_coeffs()
    lhs_514 = U ** 2 / g * (W_f / C_f - W_r / C_r) + s
    return [
        (
            "understeer_coefficient",
            ("W_f", "W_r", "C_f", "C_r"),
            (d["k_us"],),
            "Understeer coefficient k_us = W_f/C_f - W_r/C_r (rad), eq 5-16.\n\n"
            "Parameters\n----------\n"
            "W_f, W_r : float or ndarray\n    Static normal load on ONE front / ONE rear tire (N), eq 5-13.\n"
            "C_f, C_r : float or ndarray\n    Cornering stiffness of ONE front / ONE rear tire (N/rad).\n\n"
            "Returns\n-------\nk_us : float or ndarray\n"
            "    Radians (N / (N/rad)).  Positive: understeer (stable at every speed);\n"
            "    negative: oversteer (unstable above the critical speed, eq 5-15).",
        ),
        (
            "critical_speed_squared",
            ("W_f", "W_r", "C_f", "C_r", "s", "g"),
            (sp.simplify(-g * s / d["k_us"]),),
            "Square of the critical speed, U_crit^2 = -g s / k_us (m^2/s^2), eqs 5-15, 5-16.\n\n"
            "Parameters\n----------\n"
            "W_f, W_r : float or ndarray\n    Static load on one front / one rear tire (N).\n"
            "C_f, C_r : float or ndarray\n    Cornering stiffness of one front / one rear tire (N/rad).\n"
            "s : float or ndarray\n    Wheelbase (m), front axle to rear contact.\n"
            "g : float or ndarray\n    Gravitational acceleration (m/s^2), normally 9.81.\n\n"
            "Returns\n-------\nfloat or ndarray\n"
            "    Positive: the locked-wheel vehicle is unstable above sqrt(value).\n"
            "    Negative: understeer, no critical speed (stable at every speed).\n"
            "    Neutral steer (k_us = 0) divides by zero: ZeroDivisionError for\n"
            "    Python floats, +-inf for numpy arrays (no critical speed).",
        ),
        (
            "routh_hurwitz_margin",
            ("U", "W_f", "W_r", "C_f", "C_r", "s", "g"),
            (lhs_514,),
            "Left-hand side of the stability condition eq 5-14 (m): stable iff > 0.\n\n"
            "U^2/g (W_f/C_f - W_r/C_r) + s; it has the sign of the constant\n"
            "coefficient a1 a4 - a2 a3 of eq 5-11 (W_f, W_r static per-tire loads).",
        ),
        (
            "a_coefficients",
            ("U", "m", "s1", "s2", "C_f", "C_r"),
            tuple(th["a"]),
            "Coefficients (a1, a2, a3, a4) of eqs 5-9 / 5-12a-d.\n\n"
            "m v_dot + a2 r + a1 v = 0 and I_z r_dot + a4 r + a3 v = 0, with U the\n"
            "forward speed (m/s), s1 / s2 the c.g. to front / rear axle distances (m)\n"
            "and C_f, C_r per-tire cornering stiffnesses (N/rad, two tires per axle).",
        ),
        (
            "state_matrix",
            ("U", "m", "i_z", "s1", "s2", "C_f", "C_r"),
            ((S[0, 0], S[0, 1]), (S[1, 0], S[1, 1])),
            "State matrix of eqs 5-9: d/dt [v, r] = S [v, r].\n\n"
            "Parameters\n----------\n"
            "U : float or ndarray\n    Forward speed (m/s), > 0.\n"
            "m, i_z : float or ndarray\n    Total mass (kg) and yaw inertia about the c.g. (kg m^2).\n"
            "s1, s2 : float or ndarray\n    c.g. to front axle / to rear axle (contact points), m.\n"
            "C_f, C_r : float or ndarray\n    Cornering stiffness of one front / one rear tire (N/rad).\n\n"
            "Returns\n-------\n((S00, S01), (S10, S11))\n"
            "    v lateral velocity of the c.g. (m/s, + right), r yaw rate (rad/s,\n"
            "    + clockwise seen from above).",
        ),
        (
            "characteristic_coefficients",
            ("U", "m", "i_z", "s1", "s2", "C_f", "C_r"),
            (c2, sp.simplify(c1), sp.simplify(c0)),
            "Coefficients (1, c1, c0) of the characteristic equation 5-11,\n"
            "lambda^2 + c1 lambda + c0 = 0, c1 = (a1 I_z + a4 m)/(I_z m),\n"
            "c0 = (a1 a4 - a2 a3)/(I_z m).  Stable iff c1 > 0 and c0 > 0 (eq 5-14).",
        ),
    ]
