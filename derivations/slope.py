"""The chair on an inclined plane: cross slope ``phi`` and grade ``theta``.

Extends the exact full-width model of :mod:`derivations.full_width` (Kane's
method, three rigid bodies) and the zero-width model of chapter 5 with
gravity.  The plane is the contact plane; body axes c1 forward, c2 right, c3
into the plane (SAE).  With the path direction n1 along the plane, n2 to its
right and the plane falling to the right by ``phi`` and rising ahead by
``theta`` (radians here, degrees at the user interface), gravity per unit
mass is ``g (-sin(theta) n1 + cos(theta) sin(phi) n2 + cos(theta) cos(phi) n3)``;
for a chair headed ``psi`` (clockwise) from n1 its in-plane body components
are ``g1 = gx cos(psi) + gy sin(psi)``, ``g2 = -gx sin(psi) + gy cos(psi)``
and the normal one ``gn = g cos(theta) cos(phi)``.

* Exact model: the in-plane weight of each body (chair + user at ``G_b``,
  each caster at its own c.g. ``l1`` behind its pin) is added to Kane's
  generalized active forces (``Q = sum_i dv_i/du . m_i g``); the mass matrix
  is unchanged.  The caster's weight gives the moment
  ``-m_c l1 (g2 cos(eta) - g1 sin(eta))`` about its pin: it swings the
  caster c.g. downhill.
* Normal loads: eq 6-25 with the tire-force resultant replaced by
  ``m (a - g_in)`` (free body of the chair with the d'Alembert force): the
  in-plane weight enters the load-transfer moments, ``m gn`` the normal
  weight.
* Steady straight running with frictionless or rubbing pins: the statics
  (all accelerations and rates zero) solved for the caster side forces, the
  main-wheel force sums and the yaw moment of the drive forces.
* Zero-width model: ``m (v' + U r) = F_f + F_r + m g2``,
  ``I_z r' = s1 F_f - s2 F_r + M_z`` and its closed forms.

:func:`checks` returns expressions that must simplify to zero (zero slope
recovers :mod:`derivations.full_width` and eq 6-25; the generalized forces are
those of a potential).  :func:`generate` writes ``stability/_generated/slope.py``;
the normal loads are generated once, with the level ones, from
:mod:`derivations.forces` (checked there against :func:`normal_loads_plane`).
"""

from __future__ import annotations

import functools
import sys
import time
from pathlib import Path
from types import SimpleNamespace

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # pragma: no cover
    sys.path.insert(0, str(ROOT))

import sympy as sp  # noqa: E402
import sympy.physics.mechanics as me  # noqa: E402

from derivations import full_width as fw  # noqa: E402
from derivations import generate as gen  # noqa: E402

__all__ = ["G", "derive_gravity", "normal_loads", "normal_loads_plane", "hold_statics", "zero_width_slope", "checks",
           "render", "generate"]

S = fw.S
_g_names = "g1 g2 gn g a1 a2 c_phi s_phi c_theta s_theta c_psi s_psi h roll_k Mh Sx Sy"
G = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in _g_names.split()})
"""Symbols added by the slope model (attribute = symbol name)."""


def gravity_body() -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """Body components ``(g1, g2, gn)`` of gravity (m/s^2) on the plane, chair headed ``psi`` from n1."""
    gx = -G.g * G.s_theta
    gy = G.g * G.c_theta * G.s_phi
    return (gx * G.c_psi + gy * G.s_psi, -gx * G.s_psi + gy * G.c_psi, G.g * G.c_theta * G.c_phi)


@functools.cache
def derive_gravity() -> SimpleNamespace:
    """Generalized active forces of the in-plane weight, exact model.

    Returns
    -------
    SimpleNamespace
        ``Q`` (5, one per generalized speed ``u, v, r, eta_d, beta_d``) in
        ``g1, g2`` (body components of in-plane gravity); ``F`` = the exact
        forcing of :func:`derivations.full_width.derive_exact` plus ``Q``;
        ``M`` its (unchanged) mass matrix.
    """
    ex = fw.derive_exact()
    N, C = ex.frames.N, ex.frames.C
    d = ex.dynamic
    speeds = (d.u, d.v, d.r, d.eta_d, d.beta_d)
    grav = G.g1 * C.x + G.g2 * C.y
    Q = []
    for us in speeds:
        q = sp.Integer(0)
        for body in ex.bodies:
            q += body.masscenter.vel(N).diff(us, N).dot(body.mass * grav)
        q = me.msubs(q, ex.dyn)
        assert not me.find_dynamicsymbols(q), q
        Q.append(fw._trig_simplify(sp.cancel(fw._trig_simplify(q))))
    F = [fw._trig_simplify(ex.F[i] + Q[i]) for i in range(5)]
    return SimpleNamespace(Q=tuple(Q), F=tuple(F), M=ex.M)


def contact_xy() -> tuple[tuple[sp.Expr, sp.Expr], ...]:
    """Body coordinates of the contacts A, B, D, E (eq 6-24), casters at ``eta, beta``."""
    return ((S.x_p - S.trail * S.ce, -S.t1 - S.trail * S.se),
            (S.x_p - S.trail * S.cb, S.t2 - S.trail * S.sb),
            (S.x_m, -S.d1), (S.x_m, S.d2))


@functools.cache
def normal_loads() -> tuple[sp.Expr, ...]:
    """Normal loads ``(N_A, N_B, N_D, N_E)`` on the plane, eq 6-25 extended.

    Free body of chair + user + casters: normal forces ``-N_i c3`` and tire
    forces ``F_i`` at the contacts ``(x_i, y_i, h)`` below the c.g., weight
    ``m (g1, g2, gn)`` and d'Alembert force ``-m (a1, a2, 0)`` at the c.g.
    Force balance along c3 gives ``sum N = m gn``; moments about the c.g.
    give ``sum x_i N_i = -h sum F_x`` and ``sum y_i N_i = -h sum F_y`` with
    ``sum F = m (a - g_in)`` (the in-plane weight in the load-transfer
    moments); the roll moment splits ``1/(k+1)`` to the casters (6-30).
    """
    n = sp.symbols("N_A N_B N_D N_E")
    pts = contact_xy()
    fx, fy = sp.symbols("F_x0:4"), sp.symbols("F_y0:4")
    m_about_cg = sp.Matrix([0, 0, 0])
    for (x, y), ni, fxi, fyi in zip(pts, n, fx, fy, strict=True):
        m_about_cg += sp.Matrix([x, y, G.h]).cross(sp.Matrix([fxi, fyi, -ni]))
    # sum of tire forces from Newton: sum F + m g_in = m a
    sub = {fx[0]: S.m * (G.a1 - G.g1) - fx[1] - fx[2] - fx[3], fy[0]: S.m * (G.a2 - G.g2) - fy[1] - fy[2] - fy[3]}
    roll = sp.expand(m_about_cg[0].subs(sub))   # = -sum y N - h sum Fy
    pitch = sp.expand(m_about_cg[1].subs(sub))  # = sum x N + h sum Fx
    assert not (roll.free_symbols | pitch.free_symbols) & (set(fx) | set(fy))
    roll_total = -sp.expand(roll - sum(-y * ni for (_, y), ni in zip(pts, n, strict=True)))  # h m (a2 - g2)
    c1 = 1 / (G.roll_k + 1)
    eqs = [
        sum(n) - S.m * G.gn,
        pitch,
        pts[0][1] * n[0] + pts[1][1] * n[1] + roll_total * c1,
        pts[2][1] * n[2] + pts[3][1] * n[3] + roll_total * G.roll_k * c1,
    ]
    sol = sp.solve(eqs, n, dict=True)[0]
    return tuple(sp.simplify(sol[k]) for k in n)


@functools.cache
def normal_loads_plane() -> tuple[sp.Expr, ...]:
    """:func:`normal_loads` in terms of the tire-force sums ``sum_fx, sum_fy`` (body axes, N) and ``gn``.

    ``m a = sum F + m g_in``: the in-plane weight drops out (the load-transfer
    moments are ``h sum F``), so the loads depend on the slope only through
    the normal weight ``m gn``.  The form the simulator calls with its
    previous step's (WCHAIR) or consistent (adaptive) force sums.
    """
    sfx, sfy = sp.symbols("sum_fx sum_fy", real=True)
    out = []
    for e in normal_loads():
        f = sp.factor(sp.cancel(e.subs({G.a1: sfx / S.m + G.g1, G.a2: sfy / S.m + G.g2})))
        assert not f.free_symbols & {G.g1, G.g2, G.a1, G.a2}, f
        out.append(f)
    return tuple(out)


@functools.cache
def hold_statics() -> dict[str, sp.Expr]:
    """Steady straight running (``r = eta_d = beta_d = 0``, all accelerations zero) solved.

    Unknowns: the caster side forces ``FAy, FBy``, the main-wheel sums
    ``Sy = FDy + FEy``, ``Sx = FDx + FEx`` and ``Mh = d1 FDx - d2 FEx`` (the
    yaw moment of the drive forces that holds the line); given: caster
    angles, in-plane gravity ``g1, g2``, pin moments ``M_A, M_B`` (frictionless
    pins: 0; Coulomb: any value within +-friction) and caster rolling forces
    ``FAx, FBx``.  ``Mz_ext = 0``.
    """
    F = derive_gravity().F
    still = {S.r: 0, S.eta_d: 0, S.beta_d: 0, S.Mz_ext: 0, S.Fy_ext: 0,
             S.FDy: G.Sy, S.FEy: 0,
             S.FDx: (S.d2 * G.Sx + G.Mh) / (S.d1 + S.d2), S.FEx: (S.d1 * G.Sx - G.Mh) / (S.d1 + S.d2)}
    eqs = [fw.to_trig(e.xreplace(still)) for e in F]
    unknowns = (S.FAy, S.FBy, G.Sx, G.Sy, G.Mh)
    sol = sp.solve(eqs, unknowns, dict=True)[0]
    return {str(k): sp.simplify(sol[k]) for k in unknowns}


@functools.cache
def zero_width_slope() -> dict[str, sp.Expr]:
    """Zero-width model on a cross slope and its closed forms.

    ``m (v' + U r) = F_f + F_r + m g2``, ``I_z r' = s1 F_f - s2 F_r + M_z`` with
    ``F_f = -2 C_f (v + s1 r)/U``, ``F_r = -2 C_r (v - s2 r)/U`` (eqs 5-5..5-9 plus
    the weight at the c.g.).  Returns the straight-line solution (``r = 0``,
    accelerations zero, ``M_z`` the holding moment) and the quasi-steady
    uncorrected turn (``M_z = 0``, gravity frozen in the body frame).
    """
    U, m, i_z, s1, s2, C_f, C_r = (sp.Symbol(n, positive=True) for n in "U m i_z s1 s2 C_f C_r".split())
    v, r, Mz, v_dot, r_dot = sp.symbols("v r M_z v_dot r_dot")
    g2 = G.g2
    Ff = -2 * C_f * (v + s1 * r) / U
    Fr = -2 * C_r * (v - s2 * r) / U
    eq_v = m * (v_dot + U * r) - (Ff + Fr + m * g2)
    eq_r = i_z * r_dot - (s1 * Ff - s2 * Fr + Mz)
    st = {v_dot: 0, r_dot: 0}
    straight = sp.solve([eq_v.subs(st).subs(r, 0), eq_r.subs(st).subs(r, 0)], [v, Mz], dict=True)[0]
    turn = sp.solve([eq_v.subs(st).subs(Mz, 0), eq_r.subs(st).subs(Mz, 0)], [v, r], dict=True)[0]
    alpha = sp.simplify(straight[v] / U)
    return {
        "alpha": alpha,                                  # body slip angle, both axles (rad)
        "F_f": sp.simplify(Ff.subs({v: straight[v], r: 0})),
        "F_r": sp.simplify(Fr.subs({v: straight[v], r: 0})),
        "M_hold": sp.simplify(straight[Mz]),
        "v_turn": sp.simplify(turn[v]),
        "r_turn": sp.simplify(turn[r]),
        "eq_v": eq_v, "eq_r": eq_r,
        "symbols": SimpleNamespace(U=U, m=m, i_z=i_z, s1=s1, s2=s2, C_f=C_f, C_r=C_r, v=v, r=r, M_z=Mz),
    }


def checks() -> dict[str, sp.Expr]:
    """Differences that must simplify to zero.

    * ``Q_u - m g1``, ``Q_v - m g2``: the whole weight acts on the translation;
    * ``F(g1 = g2 = 0) - F_exact``: zero slope recovers the level equations;
    * loads at ``g1 = g2 = 0, gn = g, m a = sum F`` minus eq 6-25 (the closed form
      of :func:`stability.models.statics.normal_loads` re-derived here);
    * ``Q_eta + dV/deta`` with ``V = -m_c g . r_Ca`` (the caster's weight is conservative);
    * zero-width: free castered rear axle (``C_r = 0``) holds with ``M = m g2 s1``,
      and with one axle castered (zero stiffness) the uncorrected quasi-steady turn is
      ``r = g2/U`` (neither axle carries force: the moment balance forbids it).
    """
    gr = derive_gravity()
    ex = fw.derive_exact()
    out = {
        "Q_u": sp.simplify(gr.Q[0] - S.m * G.g1),
        "Q_v": sp.simplify(gr.Q[1] - S.m * G.g2),
    }
    for i in range(5):
        out[f"level_F{i}"] = sp.simplify(gr.F[i].subs({G.g1: 0, G.g2: 0}) - ex.F[i])
    # caster potential about its pin: V = -m_c (g1 x + g2 y) with Ca = Pa - l1 a1
    V = -S.m_c * (G.g1 * (S.x_p - S.l1 * sp.cos(S.eta)) + G.g2 * (-S.t1 - S.l1 * sp.sin(S.eta)))
    out["Q_eta"] = sp.simplify(gr.Q[3] + sp.diff(V, S.eta))
    # eq 6-25 (as statics.normal_loads): sum_fx, sum_fy the tire forces
    sfx, sfy = sp.symbols("sum_fx sum_fy")
    loads = normal_loads()
    lvl = [e.subs({G.g1: 0, G.g2: 0, G.gn: G.g, G.a1: sfx / S.m, G.a2: sfy / S.m})
           for e in loads]
    (xa, ya), (xb, yb), _, _ = contact_xy()
    gg = G.g
    c1 = 1 / (G.roll_k + 1)
    r_c, r_m = -G.h * sfy * c1, -G.h * sfy * G.roll_k * c1
    dy = yb - ya
    x_c = (xa * yb - xb * ya) / dy
    s_m = (-G.h * sfx - r_c * (xb - xa) / dy - S.m * gg * x_c) / (S.x_m - x_c)
    s_c = S.m * gg - s_m
    n_e = (r_m + S.d1 * s_m) / (S.d1 + S.d2)
    ref = ((yb * s_c - r_c) / dy, (r_c - ya * s_c) / dy, s_m - n_e, n_e)
    for k, (a, b) in enumerate(zip(lvl, ref, strict=True)):
        out[f"loads_6_25_{'ABDE'[k]}"] = sp.simplify(a - b)
    plane = normal_loads_plane()
    sums = {sp.Symbol("sum_fx", real=True): sfx, sp.Symbol("sum_fy", real=True): sfy, G.gn: gg}
    for k, (a, b) in enumerate(zip(plane, ref, strict=True)):
        out[f"plane_loads_6_25_{'ABDE'[k]}"] = sp.simplify(a.xreplace(sums) - b)
    zw = zero_width_slope()
    z = zw["symbols"]
    out["zw_free_rear_hold"] = sp.simplify(zw["M_hold"].subs(z.C_r, 0) - z.m * G.g2 * z.s1)
    out["zw_free_front_hold"] = sp.simplify(zw["M_hold"].subs(z.C_f, 0) + z.m * G.g2 * z.s2)
    out["zw_turn_rate_free_rear"] = sp.simplify(zw["r_turn"].subs(z.C_r, 0) - G.g2 / z.U)
    out["zw_turn_rate_free_front"] = sp.simplify(zw["r_turn"].subs(z.C_f, 0) - G.g2 / z.U)
    return out


# ---------------------------------------------------------------------------
# code generation

BODY = """
The exact full-width model (derivations/full_width.py) on a plane with cross
slope phi (falling to the right) and grade theta (rising ahead), and the
zero-width model on a cross slope.  Conventions as in full_width.py: SAE body
axes c1 forward, c2 right, c3 into the plane; g1, g2 the in-plane body
components of gravity (m/s^2), gn the normal one; psi the chair's heading
from the path direction n1, clockwise.  Angles enter through their cosines
and sines.  Every function uses only arithmetic and accepts floats or
broadcast numpy arrays.  See derivations/slope.py and docs/slopes.md.
"""

GRAV_ARGS = ("g", "c_phi", "s_phi", "c_theta", "s_theta", "c_psi", "s_psi")
ACC_ARGS = fw.ACCEL_ARGS[:21] + ("g1", "g2") + fw.ACCEL_ARGS[21:]
HOLD_ARGS = ("ce", "se", "cb", "sb", "g1", "g2", "M_A", "M_B", "FAx", "FBx",
             "x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c")
ZW_ARGS = ("U", "m", "g2", "s1", "s2", "C_f", "C_r")

_SOLVE = [
    "# eliminate the caster accelerations (caster block diagonal: m33, m44)",
    "k3 = 1/m33", "k4 = 1/m44",
    "s00 = m00 - m03*m03*k3 - m04*m04*k4", "s01 = m01 - m03*m13*k3 - m04*m14*k4",
    "s02 = m02 - m03*m23*k3 - m04*m24*k4", "s11 = m11 - m13*m13*k3 - m14*m14*k4",
    "s12 = m12 - m13*m23*k3 - m14*m24*k4", "s22 = m22 - m23*m23*k3 - m24*m24*k4",
    "g0_ = f0 - m03*f3*k3 - m04*f4*k4", "g1_ = f1 - m13*f3*k3 - m14*f4*k4",
    "g2_ = f2 - m23*f3*k3 - m24*f4*k4",
    "# LDL^T solve of the symmetric positive definite 3x3 Schur complement",
    "l10 = s01/s00", "l20 = s02/s00", "e1 = s11 - l10*l10*s00",
    "l21 = (s12 - l20*l10*s00)/e1", "e2 = s22 - l20*l20*s00 - l21*l21*e1",
    "y1 = g1_ - l10*g0_", "y2 = g2_ - l20*g0_ - l21*y1",
    "r_dot = y2/e2", "v_dot = y1/e1 - l21*r_dot", "u_dot = g0_/s00 - l10*v_dot - l20*r_dot",
    "eta_dd = (f3 - m03*u_dot - m13*v_dot - m23*r_dot)*k3",
    "beta_dd = (f4 - m04*u_dot - m14*v_dot - m24*r_dot)*k4",
]


def render() -> str:
    """Text of ``stability/_generated/slope.py``."""
    parts, names = [], []
    gb = gravity_body()
    parts.append(gen._function(
        "gravity_body", GRAV_ARGS,
        "Gravity on the plane in body axes, (g1, g2, gn) in m/s^2.\n\n"
        "g: gravitational acceleration; c_phi, s_phi: cos/sin of the cross slope (plane falls to the\n"
        "right); c_theta, s_theta: of the grade (plane rises ahead); c_psi, s_psi: of the heading\n"
        "from the path direction (clockwise).\n",
        gen._cse_lines(list(zip(("g1", "g2", "gn"), gb, strict=True)), "_a"), "(g1, g2, gn)"))
    names.append("gravity_body")

    gr = derive_gravity()
    Mup = {(i, j): fw.to_trig(gr.M[i, j]) for i in range(5) for j in range(i, 5)}
    named = [(f"m{i}{j}", Mup[(i, j)]) for (i, j) in sorted(Mup) if (i, j) != (3, 4)]
    named += [(f"f{i}", fw.to_trig(gr.F[i])) for i in range(5)]
    body = gen._hoisted_cse_lines(named, "_a", "_p") + _SOLVE
    parts.append(gen._function(
        "accelerations_slope_exact", ACC_ARGS,
        "Accelerations of the exact model with in-plane gravity (g1, g2) on every body.\n\n"
        "Arguments as full_width.accelerations_exact, plus g1, g2 (m/s^2): body components of\n"
        "the in-plane gravity (gravity_body).  g1 = g2 = 0 gives accelerations_exact.\n"
        "Returns (u_dot, v_dot, r_dot, eta_dd, beta_dd).\n",
        body, "(u_dot, v_dot, r_dot, eta_dd, beta_dd)"))
    names.append("accelerations_slope_exact")

    Qn = [(f"Q{i}", fw.to_trig(q)) for i, q in enumerate(gr.Q)]
    parts.append(gen._function(
        "gravity_generalized_forces", ("ce", "se", "cb", "sb", "g1", "g2", "x_p", "t1", "t2", "l1", "m", "m_c"),
        "Generalized active forces of the in-plane weight (u, v, r, eta_d, beta_d rows).\n\n"
        "(Q_u, Q_v) = m (g1, g2) (N); Q_r the yaw moment of the displaced caster weights about C,\n"
        "Q_eta, Q_beta the moments of each caster's weight about its pin (N m).\n",
        gen._cse_lines(Qn, "_a"), "(Q0, Q1, Q2, Q3, Q4)"))
    names.append("gravity_generalized_forces")

    # the loads (normal_loads, normal_loads_plane) are generated once, in _generated/forces.py
    # (derivations/forces.py: the elimination, checked against normal_loads_plane here)
    hs = hold_statics()
    keys = ("FAy", "FBy", "Sx", "Sy", "Mh")
    parts.append(gen._function(
        "hold_statics", HOLD_ARGS,
        "Steady straight running on the plane (r = 0, casters still, no accelerations).\n\n"
        "Given caster angles, in-plane gravity g1, g2, pin moments M_A, M_B and caster rolling\n"
        "forces FAx, FBx: caster side forces FAy, FBy, main-wheel sums Sx = FDx + FEx,\n"
        "Sy = FDy + FEy (N) and the yaw moment Mh = d1 FDx - d2 FEx of the drive forces\n"
        "(N m) that holds the line.\n",
        gen._cse_lines([(k, hs[k]) for k in keys], "_a"), "(" + ", ".join(keys) + ")"))
    names.append("hold_statics")

    zw = zero_width_slope()
    zkeys = (("alpha", "alpha"), ("F_f", "F_f"), ("F_r", "F_r"), ("M_hold", "M_hold"))
    parts.append(gen._function(
        "zero_width_straight", ZW_ARGS,
        "Zero-width model held straight on a cross slope (r = 0).\n\n"
        "C_f, C_r per tire (N/rad), two tires per axle; returns the body slip angle alpha (rad),\n"
        "axle forces F_f, F_r (N) and the holding yaw moment M_hold (N m).  C_r = 0 (free\n"
        "castered rear axle): M_hold = m g2 s1.  U does not enter.\n",
        gen._cse_lines([(n, zw[k]) for n, k in zkeys], "_a"), "(alpha, F_f, F_r, M_hold)"))
    names.append("zero_width_straight")
    parts.append(gen._function(
        "zero_width_turn", ZW_ARGS,
        "Zero-width model on a cross slope, uncorrected (M_z = 0), gravity frozen in the body.\n\n"
        "Quasi-steady lateral velocity v (m/s) and yaw rate r (rad/s).  With one axle castered\n"
        "(C_f = 0 or C_r = 0) r = g2/U: neither axle carries force and the path curves downhill\n"
        "like a sliding mass (stable for a castered front axle, divergent for a castered rear).\n",
        gen._cse_lines([("v", zw["v_turn"]), ("r", zw["r_turn"])], "_a"), "(v, r)"))
    names.append("zero_width_turn")
    text = gen._header("Wheelchair on a slope (generated).", BODY, names) + "\n\n" + "\n\n".join(parts)
    return text.replace("Generated by derivations/generate.py", "Generated by derivations/slope.py", 1)


def generate(out: Path | None = None) -> float:
    """Write ``slope.py`` into ``out`` (default ``stability/_generated``); return seconds taken."""
    out = out or ROOT / "stability" / "_generated"
    t0 = time.perf_counter()
    (out / "slope.py").write_text(render(), encoding="utf-8")
    return time.perf_counter() - t0


if __name__ == "__main__":  # pragma: no cover
    import os

    if os.environ.get("PYTHONHASHSEED") != "0":
        os.execve(sys.executable, [sys.executable, *sys.argv], dict(os.environ, PYTHONHASHSEED="0"))
    bad = {k: v for k, v in checks().items() if v != 0}
    if bad:
        raise SystemExit(f"checks failed: {bad}")
    print(f"wrote slope.py in {generate():.1f} s")
