"""Full-width planar wheelchair model (chapter 6 of Collins 1987): two variants.

``exact``
    Derived here from first principles with :class:`sympy.physics.mechanics.KanesMethod`:
    three rigid bodies (chair + user, caster A, caster B), five generalized
    speeds ``u, v, r, eta_d, beta_d`` (body-frame velocity of C, yaw rate,
    caster swivel rates).  Table 6-1 is NOT used.
``thesis``
    Table 6-1 (eqs 6-17..6-21) and the contact velocities 6-17a-d as printed,
    corrected only for evident OCR damage (:data:`OCR_CORRECTIONS`), which is
    what the Fortran program WCHAIR (Appendix C, subroutines SLIP and DYNAM)
    integrates.

Conventions (SAE body axes; the thesis's): c1 forward, c2 right, c3 down; yaw
angle and rate ``r`` positive clockwise seen from above.  C is the centre of
mass of chair + user + both casters when both casters trail
(``eta = beta = 0``) and is fixed in the chair.  Signed body coordinates
relative to C: main-wheel contacts D (left) ``(x_m, -d1)``, E (right)
``(x_m, +d2)``; caster pins Pa (left) ``(x_p, -t1)``, Pb (right)
``(x_p, +t2)``; caster frames ``a1 = cos(eta) c1 + sin(eta) c2``,
``a2 = -sin(eta) c1 + cos(eta) c2`` (b likewise); caster contact
``A = Pa - trail a1``, caster centre of mass ``Ca = Pa - l1 a1``.  The thesis's
rear-caster chair has ``x_m = s1``, ``x_p = -s2``.

Mass data: ``m`` total mass, ``m_c`` one caster assembly, ``i_z`` total yaw
inertia about C with the casters trailing, ``i_zp`` one caster's yaw inertia
about its own pin.  Forces: ``(FAx, FAy)`` in frame a at A, ``(FBx, FBy)`` in
frame b at B, ``(FDx, FDy)``, ``(FEx, FEy)`` in frame c at D, E; ``M_A``,
``M_B`` act on the casters about their pins (reaction on the chair);
``Fy_ext`` a lateral force at C; ``Mz_ext`` a yaw moment on the chair body.

All expressions below are in plain symbols (:data:`S`); caster angles appear
through ``cos``/``sin`` of the symbols ``eta``, ``beta`` (use :func:`to_trig`
to replace them with ``ce, se, cb, sb``).
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from types import SimpleNamespace

import sympy as sp
import sympy.physics.mechanics as me

__all__ = [
    "S",
    "OCR_CORRECTIONS",
    "STATE",
    "ACC",
    "to_trig",
    "derive_exact",
    "thesis_model",
    "compare",
    "linearise",
    "hybrid_linear",
    "load_transfer_first_order",
    "generated_functions",
]

# ---------------------------------------------------------------------------
# Symbols
_names = (
    "u v r eta beta eta_d beta_d ce se cb sb "
    "u_dot v_dot r_dot eta_dd beta_dd r_dot_casters "
    "FAx FAy FBx FBy FDx FDy FEx FEy M_A M_B Fy_ext Mz_ext "
    "x_m x_p d1 d2 t1 t2 trail l1 m m_c i_z i_zp "
    "U C_A C_B C_D C_E c_pin"
)
S = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in _names.split()})
"""Namespace of every plain symbol used (attribute = symbol name)."""

GEOMETRY = tuple(getattr(S, n) for n in "x_m x_p d1 d2 t1 t2 trail".split())
INERTIA = GEOMETRY + tuple(getattr(S, n) for n in "l1 m m_c i_z i_zp".split())
FORCES = tuple(getattr(S, n) for n in "FAx FAy FBx FBy FDx FDy FEx FEy M_A M_B Fy_ext Mz_ext".split())
SPEEDS = (S.u, S.v, S.r, S.eta_d, S.beta_d)
ACC5 = (S.u_dot, S.v_dot, S.r_dot, S.eta_dd, S.beta_dd)
STATE = (S.v, S.r, S.eta, S.eta_d, S.beta, S.beta_d)
"""Linear-model state ``[v, r, eta, eta_dot, beta, beta_dot]``."""
ACC = (S.v_dot, S.r_dot, S.eta_dd, S.beta_dd)
"""Linear-model accelerations ``[v_dot, r_dot, eta_dd, beta_dd]``."""

TRIG = {sp.cos(S.eta): S.ce, sp.sin(S.eta): S.se, sp.cos(S.beta): S.cb, sp.sin(S.beta): S.sb}


def to_trig(expr: sp.Expr) -> sp.Expr:
    """Replace ``cos/sin(eta)``, ``cos/sin(beta)`` by the symbols ``ce, se, cb, sb``.

    Compound angles (``sin(eta - beta)`` ...) are expanded first.  Raises
    ``ValueError`` if ``eta`` or ``beta`` survive (e.g. inside another function).
    """
    e = sp.expand_trig(sp.sympify(expr)).xreplace(TRIG)
    if e.has(S.eta) or e.has(S.beta):
        raise ValueError(f"caster angle left after trig substitution: {e}")
    return e


def _trig_simplify(expr: sp.Expr) -> sp.Expr:
    """Expand and use cos^2 + sin^2 = 1 on both caster angles."""
    e = sp.expand(expr)
    for c, s_ in ((sp.cos(S.eta), sp.sin(S.eta)), (sp.cos(S.beta), sp.sin(S.beta))):
        e = sp.expand(e.subs(s_ ** 2, 1 - c ** 2))
    return e


# ---------------------------------------------------------------------------
# Exact model (Kane's method)


@functools.cache
def derive_exact() -> SimpleNamespace:
    """Derive the exact five-degree-of-freedom model with Kane's method.

    Bodies
    ------
    chair (+ user)
        mass ``m - 2 m_c``, centre of mass ``G_b`` placed so that the system
        centre of mass is C when ``eta = beta = 0``:
        ``(m - 2 m_c) r_CGb + m_c (r_CCa0 + r_CCb0) = 0``; central yaw inertia
        ``I_b`` chosen so that the total yaw inertia about C at
        ``eta = beta = 0`` equals ``i_z`` (parallel-axis theorem).
    casters A, B
        mass ``m_c`` at ``Ca = Pa - l1 a1`` (``Cb``), central yaw inertia
        ``i_zp - m_c l1^2`` (``i_zp`` is about the pin).

    Generalized coordinates ``X, Y, theta, eta, beta`` (ground position of C,
    yaw, caster swivel angles); generalized speeds ``u, v, r, eta_d, beta_d``
    with ``X' = u cos(theta) - v sin(theta)``,
    ``Y' = u sin(theta) + v cos(theta)``, ``theta' = r``, ``eta' = eta_d``,
    ``beta' = beta_d``.

    Returns
    -------
    SimpleNamespace
        ``M`` (5x5, symmetric, configuration dependent) and ``F`` (5) with
        ``M [u_dot, v_dot, r_dot, eta_dd, beta_dd] = F``; ``vel`` the eight
        contact-velocity components ``(vAx, vAy, vBx, vBy, vDx, vDy, vEx,
        vEy)`` each in its wheel frame; ``ke`` kinetic energy; ``gb``
        (chair-body c.g. coordinates), ``I_b``; ``frames``/``points`` (sympy
        objects with dynamic symbols, for further vector work) and ``dyn``
        (dynamic-symbol -> plain-symbol map).
    """
    t = me.dynamicsymbols._t
    X, Y, th, eta, beta = me.dynamicsymbols("X Y theta eta beta")
    u, v, r, etad, betad = me.dynamicsymbols("u v r eta_d beta_d")
    x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp = INERTIA
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, M_A, M_B, Fy_ext, Mz_ext = FORCES

    N = me.ReferenceFrame("N")
    C = N.orientnew("C", "Axis", (th, N.z))  # c3 = n3 = down
    A = C.orientnew("A", "Axis", (eta, C.z))
    B = C.orientnew("B", "Axis", (beta, C.z))
    C.set_ang_vel(N, r * C.z)
    A.set_ang_vel(C, etad * C.z)
    B.set_ang_vel(C, betad * C.z)

    O = me.Point("O")
    O.set_vel(N, 0)
    Cp = O.locatenew("C", X * N.x + Y * N.y)
    Cp.set_vel(N, u * C.x + v * C.y)
    Pa = Cp.locatenew("Pa", x_p * C.x - t1 * C.y)
    Pb = Cp.locatenew("Pb", x_p * C.x + t2 * C.y)
    Pa.v2pt_theory(Cp, N, C)
    Pb.v2pt_theory(Cp, N, C)
    Ca = Pa.locatenew("Ca", -l1 * A.x)
    Cb = Pb.locatenew("Cb", -l1 * B.x)
    Ac = Pa.locatenew("A", -trail * A.x)
    Bc = Pb.locatenew("B", -trail * B.x)
    for P, Q, F_ in ((Ca, Pa, A), (Ac, Pa, A), (Cb, Pb, B), (Bc, Pb, B)):
        P.v2pt_theory(Q, N, F_)
    D = Cp.locatenew("D", x_m * C.x - d1 * C.y)
    E = Cp.locatenew("E", x_m * C.x + d2 * C.y)
    D.v2pt_theory(Cp, N, C)
    E.v2pt_theory(Cp, N, C)

    m_b = m - 2 * m_c
    # c.g. of each caster at eta = beta = 0
    ca0 = (x_p - l1, -t1)
    cb0 = (x_p - l1, t2)
    gb = (-m_c * (ca0[0] + cb0[0]) / m_b, -m_c * (ca0[1] + cb0[1]) / m_b)
    Gb = Cp.locatenew("Gb", gb[0] * C.x + gb[1] * C.y)
    Gb.v2pt_theory(Cp, N, C)
    I_c = i_zp - m_c * l1 ** 2  # caster central inertia
    I_b = (i_z - m_b * (gb[0] ** 2 + gb[1] ** 2) - 2 * I_c
           - m_c * (ca0[0] ** 2 + ca0[1] ** 2 + cb0[0] ** 2 + cb0[1] ** 2))
    chair = me.RigidBody("chair", Gb, C, m_b, (me.inertia(C, 0, 0, I_b), Gb))
    casterA = me.RigidBody("casterA", Ca, A, m_c, (me.inertia(A, 0, 0, I_c), Ca))
    casterB = me.RigidBody("casterB", Cb, B, m_c, (me.inertia(B, 0, 0, I_c), Cb))
    bodies = [chair, casterA, casterB]

    loads = [
        (Ac, FAx * A.x + FAy * A.y),
        (Bc, FBx * B.x + FBy * B.y),
        (D, FDx * C.x + FDy * C.y),
        (E, FEx * C.x + FEy * C.y),
        (Cp, Fy_ext * C.y),
        (C, (Mz_ext - M_A - M_B) * C.z),  # pin reactions on the chair
        (A, M_A * A.z),
        (B, M_B * B.z),
    ]
    kd = [
        X.diff(t) - (u * sp.cos(th) - v * sp.sin(th)),
        Y.diff(t) - (u * sp.sin(th) + v * sp.cos(th)),
        th.diff(t) - r,
        eta.diff(t) - etad,
        beta.diff(t) - betad,
    ]
    km = me.KanesMethod(N, q_ind=[X, Y, th, eta, beta], u_ind=[u, v, r, etad, betad], kd_eqs=kd)
    km.kanes_equations(bodies, loads)

    dyn = {eta: S.eta, beta: S.beta, u: S.u, v: S.v, r: S.r, etad: S.eta_d, betad: S.beta_d}

    def plain(e):
        e = me.msubs(e, dyn)
        if me.find_dynamicsymbols(e):
            raise ValueError(f"dynamic symbols left: {me.find_dynamicsymbols(e)}")
        return e

    Mm = km.mass_matrix.applyfunc(lambda e: sp.simplify(_trig_simplify(plain(e))))
    # cancel() removes the chair-body terms in 1/(m - 2 m_c), which cancel exactly
    Fv = km.forcing.applyfunc(lambda e: _trig_simplify(sp.cancel(_trig_simplify(plain(e)))))
    for e in Fv:
        assert sp.denom(sp.together(e)) == 1, e
    assert Mm == Mm.T
    assert Mm[3, 4] == 0 and Mm[4, 3] == 0
    vel = []
    for P, F_ in ((Ac, A), (Bc, B), (D, C), (E, C)):
        vP = P.vel(N)
        vel += [sp.expand(plain(vP.dot(F_.x))), sp.expand(plain(vP.dot(F_.y)))]
    vel = [sp.simplify(_trig_simplify(e)) for e in vel]
    ke = _trig_simplify(sp.cancel(_trig_simplify(plain(me.kinetic_energy(N, *bodies)))))
    return SimpleNamespace(
        M=Mm, F=Fv, vel=tuple(vel), ke=ke, gb=gb, I_b=I_b, m_b=m_b,
        frames=SimpleNamespace(N=N, C=C, A=A, B=B),
        points=SimpleNamespace(C=Cp, Pa=Pa, Pb=Pb, Ca=Ca, Cb=Cb, A=Ac, B=Bc, D=D, E=E, Gb=Gb),
        dyn=dyn, dynamic=SimpleNamespace(u=u, v=v, r=r, eta=eta, beta=beta, eta_d=etad, beta_d=betad,
                                         theta=th, t=t),
        bodies=bodies,
    )


# ---------------------------------------------------------------------------
# Thesis model (Table 6-1, eqs 6-17a-d), as printed

OCR_CORRECTIONS: tuple[str, ...] = (
    "Eq 6-19 (yaw, Table 6-1) is printed with the prefactor 1/m_c; it is 1/I_z "
    "(eq 6-6 and DYNAM: THEDD = (...)/IZ).",
    "The left-hand sides of Table 6-1 lines 6-18..6-21 are garbled (v-vector, "
    "mu-vector); they are v_ddot, theta_ddot, eta_ddot, beta_ddot (text and DYNAM).",
    "The caster trail l is OCR'd as '1' (6-3, 6-16, 6-19, 6-20, 6-21, 6-17c,d); l_1 as "
    "'1_1'.",
    "Eq 6-14 prints M_Pa = (M_af - F_AY) c3; the tire-force moment about the pin is "
    "-l F_AY: M_Pa = (M_af - l F_AY) c3 (6-16/6-20 contain F_AY(1 - l m/(l1 m_c)), DYNAM "
    "Z7 = 1 - L*M/MC/L1).",
    "Eq 6-16 repeats the line -(F_DX + F_EX) sin(eta); it appears once (6-20, DYNAM: "
    "- Z9*SINE).",
    "Eq 6-21 (beta_ddot) is scrambled: the terms F_BY(1 - l m/(l1 m_c)) + F_AX sin(eta-beta) "
    "+ F_AY cos(eta-beta) are lost, a line '+ m theta_dot (t2 sin(beta) - s2 cos(beta))' "
    "and '-(F_DX + F_EX) sin(beta)' are duplicated.  Reconstructed as the mirror image "
    "of 6-20, identical to DYNAM: BDD = (Z13*Z6 + FBY*Z7 + FAX*SDIF + FAY*CDIF + Z8*COSB "
    "- Z9*SINB + Z10*Z4 - Z11*Z3)*Z5.",
    "Eq 6-17b prints (v_ddot + theta_dot s1) for the lateral velocity of E; it is v_dot "
    "(velocity), as in 6-17a, 6-18b and SLIP (VEY = VD + THED*S1).",
    "Eq 6-7 calls a_Pa 'acceleration of Pa relative to the caster centre of gravity'; "
    "it is the absolute acceleration of the pin (6-8).",
)

_T = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in (
    "s_1 s_2 l l_1 d_1 d_2 t_1 t_2 I_z I_zp theta_dot theta_ddot u_dot_ v_dot_ eta_dot beta_dot "
    "F_AX F_AY F_BX F_BY F_DX F_DY F_EX F_EY M_af M_bf F_CIMP M_zext").split()})
"""Thesis-notation symbols (``u_dot_``, ``v_dot_`` are the thesis's velocities)."""

_THESIS_TO_GENERIC = {
    _T.s_1: S.x_m, _T.s_2: -S.x_p, _T.l: S.trail, _T.l_1: S.l1, _T.d_1: S.d1, _T.d_2: S.d2,
    _T.t_1: S.t1, _T.t_2: S.t2, _T.I_z: S.i_z, _T.I_zp: S.i_zp, _T.theta_dot: S.r,
    _T.theta_ddot: S.r_dot_casters, _T.u_dot_: S.u, _T.v_dot_: S.v, _T.eta_dot: S.eta_d,
    _T.beta_dot: S.beta_d, _T.F_AX: S.FAx, _T.F_AY: S.FAy, _T.F_BX: S.FBx, _T.F_BY: S.FBy,
    _T.F_DX: S.FDx, _T.F_DY: S.FDy, _T.F_EX: S.FEx, _T.F_EY: S.FEy, _T.M_af: S.M_A,
    _T.M_bf: S.M_B, _T.F_CIMP: S.Fy_ext, _T.M_zext: S.Mz_ext,
}


@functools.cache
def thesis_model() -> SimpleNamespace:
    """Table 6-1 and eqs 6-17a-d as printed (OCR-corrected), in generic symbols.

    The thesis's symbols map to the generic ones by ``s1 -> x_m``,
    ``s2 -> -x_p``, ``l -> trail``, ``M_af -> M_A``, ``M_bf -> M_B``,
    ``FCIMP -> Fy_ext``; theta_dot -> r; the thesis's velocities
    ``u_dot, v_dot`` -> ``u, v``.  Two additions, both documented: ``Fy_ext``
    enters the v equation only (as WCHAIR adds FCIMP to FC2 and nowhere
    else), and ``Mz_ext`` is added to the yaw equation 6-19 (a motor-assist
    yaw moment on the chair body; it reaches the caster equations only
    through theta_ddot, as any other yaw moment would).

    Returns
    -------
    SimpleNamespace
        ``vel``: 6-17a-d contact velocities ``(vAx, vAy, vBx, vBy, vDx, vDy,
        vEx, vEy)`` in wheel frames; ``acc``: ``(u_dot, v_dot, r_dot, eta_dd,
        beta_dd)`` where the caster equations contain the symbol
        ``r_dot_casters`` for theta_ddot (WCHAIR: the previous step's value);
        ``printed``: the same in thesis notation; ``slip``: 6-18a-d.
    """
    T = _T
    ce, se = sp.cos(S.eta), sp.sin(S.eta)
    cb, sb = sp.cos(S.beta), sp.sin(S.beta)
    m, m_c = S.m, S.m_c
    # eq 6-17a-d
    vD = ((T.u_dot_ + T.theta_dot * T.d_1), (T.v_dot_ + T.theta_dot * T.s_1))
    vE = ((T.u_dot_ - T.theta_dot * T.d_2), (T.v_dot_ + T.theta_dot * T.s_1))
    vA = (T.u_dot_ * ce + T.v_dot_ * se + T.theta_dot * T.t_1 * ce - T.theta_dot * T.s_2 * se,
          -(T.u_dot_ * se - T.v_dot_ * ce + T.theta_dot * T.t_1 * se + T.theta_dot * T.s_2 * ce
            + T.eta_dot * T.l))
    vB = (T.u_dot_ * cb + T.v_dot_ * sb - T.theta_dot * T.t_2 * cb - T.theta_dot * T.s_2 * sb,
          -(T.u_dot_ * sb - T.v_dot_ * cb - T.theta_dot * T.t_2 * sb + T.theta_dot * T.s_2 * cb
            + T.beta_dot * T.l))
    # eq 6-18a-d (printed: note alpha_A's numerator is -vAy while alpha_B's is +vBy)
    slip = (sp.atan(-vA[1] / vA[0]), sp.atan(vB[1] / vB[0]),
            sp.atan(vD[1] / vD[0]), sp.atan(vE[1] / vE[0]))
    # Table 6-1
    sum_x = T.F_DX + T.F_EX + T.F_AX * ce - T.F_AY * se + T.F_BX * cb - T.F_BY * sb
    sum_y = T.F_DY + T.F_EY + T.F_AX * se + T.F_AY * ce + T.F_BX * sb + T.F_BY * cb
    udd = sum_x / m + T.theta_dot * T.v_dot_  # 6-17
    vdd = (sum_y + T.F_CIMP) / m - T.theta_dot * T.u_dot_  # 6-18 (+ FCIMP as WCHAIR)
    mz = ((T.F_DX * T.d_1 - T.F_EX * T.d_2) + (T.F_DY + T.F_EY) * T.s_1
          + T.F_AX * (T.t_1 * ce - T.s_2 * se)
          - T.F_AY * (T.t_1 * se + T.s_2 * ce + T.l)
          - T.F_BX * (T.t_2 * cb + T.s_2 * sb)
          + T.F_BY * (T.t_2 * sb - T.s_2 * cb - T.l))
    thdd = (mz + T.M_zext) / T.I_z  # 6-19 (1/I_z, + Mz_ext extension)
    pre = T.l_1 * m_c / (T.I_zp * m)
    etadd = pre * (T.M_af * (m / (T.l_1 * m_c)) + T.F_AY * (1 - T.l * m / (T.l_1 * m_c))  # 6-20
                   - T.F_BX * sp.sin(S.eta - S.beta) + T.F_BY * sp.cos(S.eta - S.beta)
                   + (T.F_DY + T.F_EY) * ce - (T.F_DX + T.F_EX) * se
                   - m * T.theta_ddot * (T.t_1 * se + T.s_2 * ce)
                   + m * T.theta_dot ** 2 * (T.t_1 * ce - T.s_2 * se))
    betadd = pre * (T.M_bf * (m / (T.l_1 * m_c)) + T.F_BY * (1 - T.l * m / (T.l_1 * m_c))  # 6-21
                    + T.F_AX * sp.sin(S.eta - S.beta) + T.F_AY * sp.cos(S.eta - S.beta)
                    + (T.F_DY + T.F_EY) * cb - (T.F_DX + T.F_EX) * sb
                    + m * T.theta_ddot * (T.t_2 * sb - T.s_2 * cb)
                    - m * T.theta_dot ** 2 * (T.t_2 * cb + T.s_2 * sb))
    printed = SimpleNamespace(vel=vA + vB + vD + vE, acc=(udd, vdd, thdd, etadd, betadd), slip=slip)

    def gen(e):
        # (l1 m_c) cancels algebraically, so the generic form has no 1/(l1 m_c)
        return sp.expand(sp.expand_trig(e.xreplace(_THESIS_TO_GENERIC)))

    return SimpleNamespace(
        vel=tuple(gen(e) for e in printed.vel),
        acc=tuple(gen(e) for e in printed.acc),
        slip=tuple(e.xreplace(_THESIS_TO_GENERIC) for e in slip),
        printed=printed,
        symbols=T,
    )


# ---------------------------------------------------------------------------
# Term-by-term comparison


def _a_C():
    """Body-frame acceleration components of the chair point C (eq 5-3)."""
    return (S.u_dot - S.r * S.v, S.v_dot + S.r * S.u)


@functools.cache
def _cg_shift_acceleration() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """``m (a_G - a_C)`` in (c1, c2) and in a2, G = system c.g., C = chair point.

    ``G - C = (m_c l1/m) ((c1 - a1) + (c1 - b1))``; differentiated twice in
    the ground frame with the Kane frames, then written in plain symbols.
    """
    ex = derive_exact()
    fr, dy = ex.frames, ex.dynamic
    t = dy.t
    rel = S.m_c * S.l1 * ((fr.C.x - fr.A.x) + (fr.C.x - fr.B.x))  # = m (G - C)
    acc = rel.dt(fr.N).dt(fr.N)
    rep = {dy.theta.diff(t): dy.r, dy.eta.diff(t): dy.eta_d, dy.beta.diff(t): dy.beta_d}
    acc = acc.subs(rep)
    rep2 = {dy.r.diff(t): S.r_dot, dy.eta_d.diff(t): S.eta_dd, dy.beta_d.diff(t): S.beta_dd}
    comps = []
    for uvec in (fr.C.x, fr.C.y, fr.A.y):
        e = acc.dot(uvec).subs(rep2)
        e = me.msubs(e, ex.dyn)
        comps.append(_trig_simplify(e))
    return tuple(comps)


@functools.cache
def compare() -> list[dict[str, object]]:
    """Term-by-term comparison of the exact and thesis variants.

    Every entry is verified symbolically: ``check`` must simplify to zero.

    Returns
    -------
    list of dict
        Keys ``id``, ``quantity``, ``thesis``, ``exact``, ``difference``
        (exact minus thesis, in the row's natural residual form), ``check``
        (``difference - claimed``, simplifies to 0), ``verdict``.
    """
    ex = derive_exact()
    th = thesis_model()
    out: list[dict[str, object]] = []
    names = ("vAx", "vAy", "vBx", "vBy", "vDx", "vDy", "vEx", "vEy")
    claimed_vel = {"vAy": -S.trail * S.r, "vBy": -S.trail * S.r}
    for i, n in enumerate(names):
        d = sp.simplify(_trig_simplify(ex.vel[i] - th.vel[i]))
        claim = claimed_vel.get(n, sp.Integer(0))
        out.append(dict(
            id="K-" + n, quantity=f"contact velocity {n} (eq 6-17, SLIP)",
            thesis=th.vel[i], exact=ex.vel[i], difference=d, check=sp.simplify(d - claim),
            verdict=("exact: the contact A = Pa - trail a1 turns with the caster's ABSOLUTE "
                     "rate r + eta_d, so its a2 velocity has -trail (r + eta_d); 6-17c,d and "
                     "SLIP keep only -trail eta_d" if n in claimed_vel else "identical"),
        ))

    acc = sp.Matrix(ACC5)
    resid_exact = ex.M * acc - ex.F  # = 0
    # thesis residuals in the same units, theta_ddot in the caster rows = r_dot
    scale = (S.m, S.m, S.i_z, S.i_zp, S.i_zp)
    resid_thesis = [scale[k] * (ACC5[k] - th.acc[k].subs(S.r_dot_casters, S.r_dot)) for k in range(5)]
    aC = _a_C()
    mdG = _cg_shift_acceleration()  # m (a_G - a_C) . (c1, c2, a2)
    ce, se = sp.cos(S.eta), sp.sin(S.eta)
    cb, sb = sp.cos(S.beta), sp.sin(S.beta)
    # total force on the system without / with the external force
    Fx_t = S.FDx + S.FEx + S.FAx * ce - S.FAy * se + S.FBx * cb - S.FBy * sb
    Fy_t = S.FDy + S.FEy + S.FAx * se + S.FAy * ce + S.FBx * sb + S.FBy * cb
    F_t_a2 = -se * Fx_t + ce * Fy_t
    aC_a2 = -se * aC[0] + ce * aC[1]

    rows = [
        ("D-u", "longitudinal equation (6-17)", mdG[0],
         "exact: u, v are the velocity of the chair point C, which is the system c.g. only "
         "when eta = beta = 0; m a_G = F, and a_G - a_C = (m_c l1/m) d2/dt2[(c1-a1)+(c1-b1)] "
         "(swivelling casters move the system c.g.).  The thesis treats C as the c.g. always."),
        ("D-v", "lateral equation (6-18)", mdG[1], "as D-u (c2 component)."),
    ]
    for k, (rid, q, claim, verdict) in enumerate(rows):
        d = _trig_simplify(resid_exact[k] - resid_thesis[k])
        out.append(dict(id=rid, quantity=q, thesis=resid_thesis[k], exact=resid_exact[k],
                        difference=d, check=sp.simplify(d - claim), verdict=verdict))
    # yaw: the difference is the rate of change of the casters' relative
    # angular momentum (no simple closed form claimed; first order below)
    d = _trig_simplify(resid_exact[2] - resid_thesis[2])
    lin = {S.eta: 0, S.beta: 0}
    d1 = sp.expand(d.subs(lin))
    # drop second-order products of small quantities
    eps = sp.Symbol("eps")
    small = {S.v: eps * S.v, S.r: eps * S.r, S.eta_d: eps * S.eta_d, S.beta_d: eps * S.beta_d,
             S.r_dot: eps * S.r_dot, S.eta_dd: eps * S.eta_dd, S.beta_dd: eps * S.beta_dd,
             S.u_dot: eps * S.u_dot}
    d_lin = sp.expand(d.subs({S.eta: eps * S.eta, S.beta: eps * S.beta}).subs(small))
    d_lin = sp.expand(sp.series(d_lin, eps, 0, 2).removeO().subs(eps, 1))
    claim_lin = (S.i_zp - S.m_c * S.l1 * S.x_p) * (S.eta_dd + S.beta_dd)
    out.append(dict(
        id="D-r", quantity="yaw equation (6-19)", thesis=resid_thesis[2], exact=resid_exact[2],
        difference=d, check=sp.simplify(d_lin - claim_lin), linear=claim_lin, at_trailing=d1,
        verdict=("exact: the system's angular momentum about C includes the casters' spin "
                 "i_zp (r + eta_d) and the moment of their c.g. motion; the thesis uses "
                 "i_z r_dot only (casters frozen in the chair).  First order: "
                 "+(i_zp - m_c l1 x_p)(eta_dd + beta_dd)."),
    ))
    # caster equations: split into the named parts
    for k, (rid, _ang_dd, _claim_extra) in enumerate((("D-eta", S.eta_dd, None), ("D-beta", S.beta_dd, None))):
        row = 3 + k
        d = _trig_simplify(resid_exact[row] - resid_thesis[row])
        if k == 0:
            a2_aC, a2_Ft = aC_a2, F_t_a2
        else:
            a2_aC = -sb * aC[0] + cb * aC[1]
            a2_Ft = -sb * Fx_t + cb * Fy_t
        # exact - thesis = i_zp r_dot - m_c l1 (a_C . a2 - F_tires . a2 / m)
        claim = S.i_zp * S.r_dot - S.m_c * S.l1 * (a2_aC - a2_Ft / S.m)
        out.append(dict(
            id=rid, quantity=f"caster equation ({'6-20' if k == 0 else '6-21'})",
            thesis=resid_thesis[row], exact=resid_exact[row], difference=d,
            check=sp.simplify(d - claim),
            parts={
                "absolute angular acceleration": S.i_zp * S.r_dot,
                "pin acceleration from tire forces / m instead of kinematics":
                    -S.m_c * S.l1 * (a2_aC - a2_Ft / S.m),
            },
            verdict=("exact (two parts).  (1) Euler about the pin needs the caster's ABSOLUTE "
                     "angular acceleration: i_zp (r_dot + eta_dd); 6-7/6-13 use i_zp eta_dd.  "
                     "(2) The pin acceleration must be the kinematic acceleration of the chair "
                     "point (u_dot - r v, v_dot + r u) + rotation terms; the thesis uses the "
                     "TIRE forces / m, which omits the external force FCIMP/Fy_ext "
                     "(m_c l1 Fy_ext cos(eta)/m) and the c.g. shift of D-u/D-v."),
        ))
    # verify the decomposition of part (2) with the exact chair equations:
    # a_C.a2 - F_t.a2/m = Fy_ext cos(eta)/m - (a_G - a_C).a2
    dec = sp.simplify(_trig_simplify(
        (aC_a2 - F_t_a2 / S.m) - (S.Fy_ext * ce / S.m - mdG[2] / S.m)
        - (-se * (resid_exact[0]) + ce * (resid_exact[1])) / S.m))
    out.append(dict(
        id="D-pin", quantity="pin acceleration in 6-11 (a_C = F_tires/m)",
        thesis=F_t_a2 / S.m, exact=aC_a2, difference=aC_a2 - F_t_a2 / S.m, check=dec,
        verdict=("exact.  Using the exact chair equations, a_C.a2 - F_tires.a2/m = "
                 "Fy_ext cos(eta)/m - (a_G - a_C).a2: the thesis's caster does not feel a push "
                 "at C (FCIMP is added to FC2 after the caster terms are formed) and ignores "
                 "the casters' own c.g. motion (second order in m_c l1)."),
    ))
    out.append(dict(
        id="N-lag", quantity="theta_ddot in the caster equations (DYNAM Z10 = M*THEDD)",
        thesis=sp.Symbol("THEDD_previous_step"), exact=S.r_dot, difference=sp.Integer(0),
        check=sp.Integer(0),
        verdict=("numerical, not a modelling difference: DYNAM forms Z10 = M*THEDD before "
                 "updating THEDD, so the caster equations use the previous time step's yaw "
                 "acceleration (an O(dt) lag).  accelerations_thesis(..., r_dot_casters=) "
                 "reproduces it."),
    ))
    return out


# ---------------------------------------------------------------------------
# Linearisation


def _tire_substitution(vel: Sequence[sp.Expr]) -> dict[sp.Symbol, sp.Expr]:
    """Linear tires Fy = -C atan(vy/vx), no longitudinal forces, viscous pins."""
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    return {
        S.FAx: 0, S.FBx: 0, S.FDx: 0, S.FEx: 0,
        S.FAy: -S.C_A * sp.atan(vAy / vAx), S.FBy: -S.C_B * sp.atan(vBy / vBx),
        S.FDy: -S.C_D * sp.atan(vDy / vDx), S.FEy: -S.C_E * sp.atan(vEy / vEx),
        S.M_A: -S.c_pin * S.eta_d, S.M_B: -S.c_pin * S.beta_d, S.Fy_ext: 0,
    }


EQUILIBRIUM = {S.v: 0, S.r: 0, S.eta: 0, S.beta: 0, S.eta_d: 0, S.beta_d: 0, S.u: S.U}


def _residuals(variant: str) -> list[sp.Expr]:
    """Residual form R(acc, state, forces) = 0 of the five equations."""
    acc = sp.Matrix(ACC5)
    if variant == "exact":
        ex = derive_exact()
        return list(ex.M * acc - ex.F)
    if variant == "thesis":
        th = thesis_model()
        scale = (S.m, S.m, S.i_z, S.i_zp, S.i_zp)
        return [scale[k] * (ACC5[k] - th.acc[k].subs(S.r_dot_casters, S.r_dot)) for k in range(5)]
    raise ValueError(f"variant={variant!r} is invalid; valid choices: ['exact', 'thesis']")


@functools.cache
def linearise(variant: str, locked: bool = False) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    """Linearise about straight running at speed ``U`` (all tire forces zero).

    Tires: ``Fy_i = -C_i atan(vy_i/vx_i)`` (N/rad at the static load), no
    longitudinal forces, viscous pins ``M_A = -c_pin eta_d``; input
    ``Mz_ext``.  The forward-speed equation decouples at first order (checked:
    the u_dot column of the mass matrix and the u column of the Jacobian are
    zero at equilibrium in the lateral rows).

    The thesis variant is linearised with ``r_dot_casters = r_dot`` (no lag);
    its "mass matrix" is that of its equations written as
    ``m v_dot = ...``, ``i_z r_dot = ...``, ``i_zp eta_dd - i_zp (d eta_dd/d
    theta_ddot) r_dot = ...``.

    Parameters
    ----------
    variant : {"exact", "thesis"}
    locked : bool
        Casters held at ``eta = beta = 0`` (states ``[v, r]``; for the exact
        model the pin moments are workless constraint torques and drop out of
        the v and r rows).

    Returns
    -------
    (M, K, Bm) : sympy Matrices
        ``M acc = K x + Bm Mz_ext`` with ``acc = [v_dot, r_dot, eta_dd,
        beta_dd]`` and ``x = [v, r, eta, eta_d, beta, beta_d]`` (free) or
        ``acc = [v_dot, r_dot]``, ``x = [v, r]`` (locked).
    """
    R = _residuals(variant)
    vel = derive_exact().vel if variant == "exact" else thesis_model().vel
    sub = _tire_substitution(vel)
    R = [e.xreplace(sub) for e in R]
    rows = [1, 2, 3, 4]
    # decoupling of u
    for i in rows:
        assert sp.simplify(sp.diff(R[i], S.u_dot).subs(EQUILIBRIUM)) == 0
        assert sp.simplify(sp.diff(R[i], S.u).subs(EQUILIBRIUM).subs(
            {a: 0 for a in ACC5})) == 0
    M = sp.Matrix([[sp.simplify(sp.diff(R[i], a).subs(EQUILIBRIUM)) for a in ACC] for i in rows])
    K = sp.Matrix([[sp.simplify(-sp.diff(R[i], x).subs(EQUILIBRIUM).subs({a: 0 for a in ACC5}))
                    for x in STATE] for i in rows])
    Bm = sp.Matrix([sp.simplify(-sp.diff(R[i], S.Mz_ext).subs(EQUILIBRIUM)) for i in rows])
    # equilibrium really is one
    for i in range(5):
        assert sp.simplify(R[i].subs(EQUILIBRIUM).subs({a: 0 for a in ACC5}).subs(S.Mz_ext, 0)) == 0
    if locked:
        return M[:2, :2], K[:2, :2], Bm[:2, :]
    return M, K, Bm


def hybrid_linear(k_slip: sp.Expr | int = 1, k_abs: sp.Expr | int = 1, k_pin: sp.Expr | int = 1,
                  k_lat: sp.Expr | int = 1, k_yaw: sp.Expr | int = 1,
                  k_fext: sp.Expr | int = 0) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]:
    """Linear model with each thesis-vs-exact difference switched separately.

    All switches 1: the exact linear model; all 0: the thesis's (both
    verified against :func:`linearise` in :func:`hybrid_checks`).

    Parameters
    ----------
    k_slip : caster contact lateral velocity includes ``-trail r`` (K-vAy).
    k_abs : caster inertia acts on the absolute acceleration ``r_dot + eta_dd`` (D-eta, part 1).
    k_pin : pin acceleration from kinematics (1) or tire forces / m (0) (D-eta part 2).
    k_lat : lateral equation includes the casters' c.g. motion ``-m_c l1 (eta_dd + beta_dd)`` (D-v).
    k_yaw : yaw equation includes ``(i_zp - m_c l1 x_p)(eta_dd + beta_dd)`` (D-r).
    k_fext : with ``k_pin = 0``, whether ``Fy_ext`` is added to the tire forces in the
        pin acceleration (WCHAIR: 0).

    Returns
    -------
    (M, K, Bm, Bf)
        As :func:`linearise` plus ``Bf``, the column multiplying a lateral
        force ``Fy_ext`` at C.
    """
    v_dot, r_dot, eta_dd, beta_dd = ACC
    v, r, eta, eta_d, beta, beta_d = STATE
    U = S.U
    x_p, x_m, trail, l1, m, m_c = S.x_p, S.x_m, S.trail, S.l1, S.m, S.m_c
    vAy = v + (x_p - k_slip * trail) * r - U * eta - trail * eta_d
    vBy = v + (x_p - k_slip * trail) * r - U * beta - trail * beta_d
    vDy = v + x_m * r
    FAy, FBy = -S.C_A * vAy / U, -S.C_B * vBy / U
    FDy, FEy = -S.C_D * vDy / U, -S.C_E * vDy / U
    Fsum = FAy + FBy + FDy + FEy
    Fy, Mz = sp.Symbol("Fy_ext"), sp.Symbol("Mz_ext")
    mz = FAy * (x_p - trail) + FBy * (x_p - trail) + (FDy + FEy) * x_m
    R = [
        m * (v_dot + U * r) - k_lat * m_c * l1 * (eta_dd + beta_dd) - Fsum - Fy,
        S.i_z * r_dot + k_yaw * (S.i_zp - m_c * l1 * x_p) * (eta_dd + beta_dd) - mz - Mz,
    ]
    for ang_dd, M_pin, Fpin in ((eta_dd, -S.c_pin * eta_d, FAy), (beta_dd, -S.c_pin * beta_d, FBy)):
        pin_acc = k_pin * (v_dot + U * r) + (1 - k_pin) * (Fsum + k_fext * Fy) / m
        R.append(S.i_zp * (ang_dd + k_abs * r_dot) - m_c * l1 * x_p * r_dot
                 - m_c * l1 * pin_acc - (M_pin - trail * Fpin))
    M = sp.Matrix([[sp.diff(e, a) for a in ACC] for e in R]).applyfunc(sp.simplify)
    K = sp.Matrix([[-sp.diff(e, x) for x in STATE] for e in R]).applyfunc(sp.simplify)
    Bm = sp.Matrix([-sp.diff(e, Mz) for e in R])
    Bf = sp.Matrix([-sp.diff(e, Fy) for e in R])
    return M, K, Bm, Bf


def hybrid_checks() -> dict[str, sp.Matrix]:
    """``hybrid_linear`` end points minus :func:`linearise` (all zero matrices)."""
    out = {}
    for name, k in (("exact", 1), ("thesis", 0)):
        M, K, Bm, _ = hybrid_linear(k, k, k, k, k, 0)
        M0, K0, Bm0 = linearise(name)
        out[name] = sp.Matrix.vstack((M - M0).T, (K - K0).T, (Bm - Bm0).T).applyfunc(sp.simplify)
    return out


# ---------------------------------------------------------------------------
# Lateral load transfer


def load_transfer_first_order() -> dict[str, sp.Expr]:
    """Show that lateral load transfer has no first-order effect without camber.

    Any smooth tire law with ``Fy(0, Fz) = 0`` for every load can be written
    ``Fy(alpha, Fz) = alpha G(alpha, Fz)`` (Hadamard's lemma), so
    ``dFy/dFz = alpha dG/dFz`` vanishes at ``alpha = 0``.  Around straight
    running the load change ``dFz`` is itself first order (it is driven by
    the lateral force ``sum Fy``, eqs 6-25), so its effect on ``Fy`` is
    ``alpha * dFz``: second order.  The linear models therefore need only the
    cornering stiffness at the STATIC load.

    With camber ``gamma`` a camber thrust ``H(gamma, Fz)`` (``H(0, Fz) = 0``)
    is present at ``alpha = 0`` and ``dFy/dFz = dH/dFz != 0``: WCHAIR adds
    ``+CAMCOF*POLYFT(FDZ)`` at D and ``-CAMCOF*POLYFT(FEZ)`` at E, equal and
    opposite at the static loads, whose sum under a load transfer
    ``dFz_D = -dFz_E`` becomes ``2 CAMCOF P'(Fz) dFz_D`` -- a first-order
    lateral force (and yaw moment ``x_m`` times it) proportional to the total
    lateral force, i.e. an extra lateral-acceleration feedback.  (Rolling
    resistance ``Fx = f(Fz) != 0`` would likewise give a first-order yaw
    moment ``d1 dFDx - d2 dFEx``; the linear models assume no longitudinal
    forces.)

    Returns
    -------
    dict
        ``"dFy_dFz_at_zero_slip"`` (0), ``"second_order"`` (the load-transfer
        term of the expansion, proportional to ``alpha dFz``),
        ``"camber_dFy_dFz"`` (nonzero), ``"camber_pair_sum"`` (first-order
        net camber force of a D/E pair under load transfer).
    """
    alpha, Fz, Fz0, dFz, gamma, eps = sp.symbols("alpha F_z F_z0 dF_z gamma epsilon")
    G = sp.Function("G")
    H = sp.Function("H")
    P = sp.Function("P")
    Fy = alpha * G(alpha, Fz)
    d0 = sp.diff(Fy, Fz).subs(alpha, 0)
    # expansion in eps with alpha, dFz both O(eps)
    Fy_eps = (eps * alpha) * G(eps * alpha, Fz0 + eps * dFz)
    ser = sp.series(Fy_eps, eps, 0, 3).removeO().doit()
    first = sp.simplify(ser.coeff(eps, 1))
    second = sp.simplify(ser.coeff(eps, 2))
    Fy_c = alpha * G(alpha, Fz) + H(gamma, Fz)
    dc = sp.diff(Fy_c, Fz).subs(alpha, 0)
    cam = sp.Symbol("CAMCOF")
    pair = cam * P(Fz0 + eps * dFz) - cam * P(Fz0 - eps * dFz)
    pair1 = sp.simplify(sp.series(pair, eps, 0, 2).removeO().doit())
    return {
        "dFy_dFz_at_zero_slip": sp.simplify(d0),
        "first_order": first,
        "second_order": second,
        "camber_dFy_dFz": dc,
        "camber_pair_sum": pair1,
    }


# ---------------------------------------------------------------------------
# Expressions for the generated module

CONTACT_ARGS = ("u", "v", "r", "ce", "se", "cb", "sb", "eta_d", "beta_d",
                "x_m", "x_p", "d1", "d2", "t1", "t2", "trail")
ACCEL_ARGS = ("u", "v", "r", "ce", "se", "cb", "sb", "eta_d", "beta_d",
              "FAx", "FAy", "FBx", "FBy", "FDx", "FDy", "FEx", "FEy", "M_A", "M_B",
              "Fy_ext", "Mz_ext",
              "x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c", "i_z", "i_zp")
LINEAR_ARGS = ("U", "C_A", "C_B", "C_D", "C_E", "c_pin",
               "x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c", "i_z", "i_zp")
LOCKED_ARGS = tuple(a for a in LINEAR_ARGS if a != "c_pin")
KE_ARGS = ("u", "v", "r", "ce", "se", "cb", "sb", "eta_d", "beta_d",
           "x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c", "i_z", "i_zp")


def generated_functions() -> dict[str, object]:
    """Everything :mod:`derivations.generate` needs, in trig-symbol form.

    Returns
    -------
    dict
        ``vel_exact``, ``vel_thesis`` (8-tuples); ``M_exact`` (upper triangle
        dict ``(i, j) -> expr``), ``F_exact`` (5); ``acc_thesis`` (5, caster
        rows in ``r_dot_casters``); ``ke_exact``; ``linear`` dict
        ``(variant, locked) -> (M, K, Bm)``.
    """
    ex = derive_exact()
    th = thesis_model()
    Mup = {(i, j): to_trig(ex.M[i, j]) for i in range(5) for j in range(i, 5)}
    lin = {}
    for variant in ("exact", "thesis"):
        for locked in (False, True):
            lin[(variant, locked)] = linearise(variant, locked)
    return {
        "vel_exact": tuple(to_trig(e) for e in ex.vel),
        "vel_thesis": tuple(to_trig(e) for e in th.vel),
        "M_exact": Mup,
        "F_exact": tuple(to_trig(e) for e in ex.F),
        "acc_thesis": tuple(to_trig(e) for e in th.acc),
        "ke_exact": to_trig(ex.ke),
        "linear": lin,
    }
