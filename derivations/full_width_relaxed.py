"""Linear full-width chair with relaxation-length caster tires (shimmy), optionally on compliant pins.

Builds on the exact Kane derivation of :mod:`derivations.full_width` (and, for
comparison, the thesis's Table 6-1).  Each caster's lateral tire force
``F_A`` (``F_B``) becomes a state with first-order relaxation (Pacejka,
*Tyre and Vehicle Dynamics*, 2006, sec. 5.3 and ch. 7)::

    (sigma/U) dF_A/dt + F_A = -C_A alpha_A,   alpha_A = vAy/vAx (linearised),

the sign convention of ``full_width._tire_substitution`` (force opposing the
contact's lateral velocity).  The main wheels keep point contact (their lag
``sigma_main/U`` is slow next to nothing in the shimmy band and fast next to the
chair's modes; see docs/shimmy.md).  With ``pin=True`` each caster pin may also
move laterally in the chair on a spring ``k_pin`` (a massless housing, the
towed wheel's compliant pivot); the caster's own mass moves with it.  That
system is derived here with Kane's method, reusing the frames, points and chair
body of :func:`derivations.full_width.derive_exact`.

Usage::

    python derivations/full_width_relaxed.py [--out DIR]

writes ``full_width_relaxed.py`` into ``DIR`` (default ``stability/_generated``).
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from types import SimpleNamespace

if __name__ == "__main__" and os.environ.get("PYTHONHASHSEED") != "0":  # pragma: no cover
    env = dict(os.environ, PYTHONHASHSEED="0")
    os.execve(sys.executable, [sys.executable, *sys.argv], env)

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import sympy as sp  # noqa: E402
import sympy.physics.mechanics as me  # noqa: E402

from derivations import full_width as fw  # noqa: E402
from derivations.generate import _cse_lines, _function, _header  # noqa: E402

__all__ = ["R", "VARIANTS", "derive_compliant_pin", "linear_relaxed", "render", "generate", "main"]

S = fw.S
R = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in (
    "sigma k_pin y_A y_B w_A w_B w_A_dot w_B_dot F_A F_B".split())})
"""New plain symbols: relaxation length, pin stiffness, pin offsets/rates/accelerations, tire-force states."""

VARIANTS = ("exact", "thesis", "pin_exact")
"""``exact``/``thesis``: rigid pins (8 states); ``pin_exact``: exact model on compliant pins (12 states)."""

STATES = {
    "exact": ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "F_A", "F_B"),
    "thesis": ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "F_A", "F_B"),
    "pin_exact": ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "y_A", "y_A_dot", "y_B", "y_B_dot",
                  "F_A", "F_B"),
}


@functools.cache
def derive_compliant_pin() -> SimpleNamespace:
    """Kane's equations of the exact model with each caster pin on a lateral spring.

    Generalized coordinates ``X, Y, theta, eta, beta, y_A, y_B`` and speeds
    ``u, v, r, eta_d, beta_d, w_A, w_B``; ``y_A`` is the lateral (``c2``)
    offset of the left pin from its place ``Pa`` in the chair, ``w_A`` its
    rate relative to the chair.  The spring force ``-k_pin y_A c2`` acts on
    caster A at the displaced pin and its reaction on the chair at ``Pa``.  The
    pin housing is massless and does not turn relative to the chair (the pin
    moments ``M_A``, ``M_B`` react on the chair as before).

    Returns
    -------
    SimpleNamespace
        ``M`` (7x7), ``F`` (7), ``vel`` (the eight contact-velocity
        components as in ``derive_exact``), all in plain symbols.
    """
    ex = fw.derive_exact()
    N, C, A, B = ex.frames.N, ex.frames.C, ex.frames.A, ex.frames.B
    d = ex.dynamic
    t = d.t
    X, Y = me.dynamicsymbols("X Y")
    yA, yB, wA, wB = me.dynamicsymbols("y_A y_B w_A w_B")
    x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp = fw.INERTIA
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, M_A, M_B, Fy_ext, Mz_ext = fw.FORCES
    P = ex.points
    I_c = i_zp - m_c * l1 ** 2
    pts = {}
    bodies = [ex.bodies[0]]
    for name, pin, y, w, frame in (("a", P.Pa, yA, wA, A), ("b", P.Pb, yB, wB, B)):
        q = pin.locatenew(f"Q{name}", y * C.y)
        q.set_vel(C, w * C.y)
        q.v1pt_theory(pin, N, C)
        cg = q.locatenew(f"G{name}", -l1 * frame.x)
        cg.v2pt_theory(q, N, frame)
        contact = q.locatenew(f"K{name}", -trail * frame.x)
        contact.v2pt_theory(q, N, frame)
        pts[name] = (q, contact)
        bodies.append(me.RigidBody(f"caster_{name}", cg, frame, m_c, (me.inertia(frame, 0, 0, I_c), cg)))
    (Qa, Ka), (Qb, Kb) = pts["a"], pts["b"]
    loads = [
        (Ka, FAx * A.x + FAy * A.y), (Kb, FBx * B.x + FBy * B.y),
        (P.D, FDx * C.x + FDy * C.y), (P.E, FEx * C.x + FEy * C.y),
        (P.C, Fy_ext * C.y), (C, (Mz_ext - M_A - M_B) * C.z), (A, M_A * A.z), (B, M_B * B.z),
        (Qa, -R.k_pin * yA * C.y), (P.Pa, R.k_pin * yA * C.y),
        (Qb, -R.k_pin * yB * C.y), (P.Pb, R.k_pin * yB * C.y),
    ]
    th = d.theta
    kd = [X.diff(t) - (d.u * sp.cos(th) - d.v * sp.sin(th)), Y.diff(t) - (d.u * sp.sin(th) + d.v * sp.cos(th)),
          th.diff(t) - d.r, d.eta.diff(t) - d.eta_d, d.beta.diff(t) - d.beta_d,
          yA.diff(t) - wA, yB.diff(t) - wB]
    km = me.KanesMethod(N, q_ind=[X, Y, th, d.eta, d.beta, yA, yB],
                        u_ind=[d.u, d.v, d.r, d.eta_d, d.beta_d, wA, wB], kd_eqs=kd)
    km.kanes_equations(bodies, loads)
    dyn = dict(ex.dyn)
    dyn.update({yA: R.y_A, yB: R.y_B, wA: R.w_A, wB: R.w_B})

    def plain(e):
        e = me.msubs(e, dyn)
        if me.find_dynamicsymbols(e):
            raise ValueError(f"dynamic symbols left: {me.find_dynamicsymbols(e)}")
        return e

    vel = []
    for pt, frame in ((Ka, A), (Kb, B), (P.D, C), (P.E, C)):
        v = pt.vel(N)
        vel += [sp.expand(plain(v.dot(frame.x))), sp.expand(plain(v.dot(frame.y)))]
    return SimpleNamespace(M=km.mass_matrix.applyfunc(plain), F=km.forcing.applyfunc(plain), vel=tuple(vel))


def _residuals(variant: str) -> tuple[list[sp.Expr], tuple[sp.Expr, ...], tuple[sp.Symbol, ...]]:
    """``(residuals, contact velocities, accelerations)`` of a variant (residual form ``R = 0``)."""
    if variant == "exact":
        ex = fw.derive_exact()
        return list(ex.M * sp.Matrix(fw.ACC5) - ex.F), ex.vel, fw.ACC5
    if variant == "thesis":
        th = fw.thesis_model()
        scale = (S.m, S.m, S.i_z, S.i_zp, S.i_zp)
        res = [scale[k] * (fw.ACC5[k] - th.acc[k].subs(S.r_dot_casters, S.r_dot)) for k in range(5)]
        return res, th.vel, fw.ACC5
    if variant == "pin_exact":
        cp = derive_compliant_pin()
        acc = fw.ACC5 + (R.w_A_dot, R.w_B_dot)
        return list(cp.M * sp.Matrix(acc) - cp.F), cp.vel, acc
    raise ValueError(f"variant={variant!r} is invalid; valid choices: {list(VARIANTS)}")


@functools.cache
def linear_relaxed(variant: str) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix, sp.Matrix]:
    """Linearise about straight running at ``U`` with the caster lateral forces as states.

    Main tires ``Fy = -C atan(vy/vx)``, no longitudinal forces, viscous pins
    ``M_A = -c_pin eta_d``; caster forces ``F_A``, ``F_B`` relax towards
    ``-C_A vAy/vAx`` with length ``sigma``.

    Parameters
    ----------
    variant : {"exact", "thesis", "pin_exact"}

    Returns
    -------
    (M, K, Bm, T) : sympy Matrices
        ``M acc = K x + Bm Mz_ext`` (``acc`` the second derivatives of the
        mechanical coordinates other than ``u``: ``[v_dot, r_dot, eta_dd,
        beta_dd]`` and for ``pin_exact`` also ``[w_A_dot, w_B_dot]``) and
        ``[F_A_dot, F_B_dot] = T x``, ``x`` the states :data:`STATES`.
    """
    res, vel, acc = _residuals(variant)
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    sub = {S.FAx: 0, S.FBx: 0, S.FDx: 0, S.FEx: 0, S.FAy: R.F_A, S.FBy: R.F_B,
           S.FDy: -S.C_D * sp.atan(vDy / vDx), S.FEy: -S.C_E * sp.atan(vEy / vEx),
           S.M_A: -S.c_pin * S.eta_d, S.M_B: -S.c_pin * S.beta_d, S.Fy_ext: 0}
    pin = variant == "pin_exact"
    mech = [S.v, S.r, S.eta, S.eta_d, S.beta, S.beta_d] + ([R.y_A, R.w_A, R.y_B, R.w_B] if pin else [])
    x = mech + [R.F_A, R.F_B]
    eq = dict(fw.EQUILIBRIUM)
    eq.update({R.y_A: 0, R.y_B: 0, R.w_A: 0, R.w_B: 0, R.F_A: 0, R.F_B: 0})
    zero_acc = {a: 0 for a in acc}
    res = [e.xreplace(sub) for e in res]
    rows = range(1, len(res))
    for i in rows:  # the forward-speed equation decouples at first order
        assert sp.simplify(sp.diff(res[i], S.u_dot).subs(eq)) == 0
        assert sp.simplify(sp.diff(res[i], S.u).subs(eq).subs(zero_acc)) == 0
    for e in res:  # straight running is an equilibrium
        assert sp.simplify(e.subs(eq).subs(zero_acc).subs(S.Mz_ext, 0)) == 0
    acc_l = acc[1:]
    M = sp.Matrix([[sp.simplify(sp.diff(res[i], a).subs(eq)) for a in acc_l] for i in rows])
    K = sp.Matrix([[sp.simplify(-sp.diff(res[i], xj).subs(eq).subs(zero_acc)) for xj in x] for i in rows])
    Bm = sp.Matrix([sp.simplify(-sp.diff(res[i], S.Mz_ext).subs(eq)) for i in rows])
    T = []
    for F, C_, vx, vy in ((R.F_A, S.C_A, vAx, vAy), (R.F_B, S.C_B, vBx, vBy)):
        ux = sp.simplify(vx.subs(eq))
        assert ux == S.U, ux
        row = [sp.simplify(-C_ / R.sigma * sp.diff(vy, xj).subs(eq)) for xj in x]
        row[x.index(F)] = -S.U / R.sigma
        T.append(row)
    return M, K, Bm, sp.Matrix(T)


# ---------------------------------------------------------------------------
# code generation

LINEAR_ARGS = ("U", "C_A", "C_B", "C_D", "C_E", "c_pin", "sigma",
               "x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c", "i_z", "i_zp")
PIN_ARGS = LINEAR_ARGS[:7] + ("k_pin",) + LINEAR_ARGS[7:]

BODY = """
Full-width wheelchair model (Collins 1987, chapter 6) linearised about
straight running at speed U, with relaxation-length caster tires:
(sigma/U) dF_A/dt + F_A = -C_A vAy/U (F_A the left caster's lateral force
along a2, N; the same for B), main wheels with point contact.  Variants:
exact and thesis (rigid pins) and pin_exact (each caster pin on a lateral
spring k_pin, N/m).  Conventions and arguments as in full_width.py; sigma is
the caster tire relaxation length (m).

Every function uses only arithmetic and accepts floats or broadcast numpy
arrays.  See derivations/full_width_relaxed.py and docs/shimmy.md.
"""

_DOC = """
Linearised {variant} model with relaxation-length caster tires at speed U.

Returns
-------
(M, K, Bm, T)
    Nested tuples with M acc = K x + Bm Mz_ext and [F_A_dot, F_B_dot] = T x,
    where acc = [{acc}] and
    x = [{states}].
"""


def _render_variant(variant: str) -> str:
    M_, K_, B_, T_ = linear_relaxed(variant)
    n, nx = M_.shape[0], K_.shape[1]
    named = [(f"M{i}{j}", M_[i, j]) for i in range(n) for j in range(n)]
    named += [(f"K{i}_{j}", K_[i, j]) for i in range(n) for j in range(nx)]
    named += [(f"B{i}", B_[i, 0]) for i in range(n)]
    named += [(f"T{i}_{j}", T_[i, j]) for i in range(2) for j in range(nx)]

    def rows(prefix: str, nr: int, nc: int, sep: str = "") -> str:
        return ", ".join("(" + ", ".join(f"{prefix}{i}{sep}{j}" for j in range(nc)) + ")" for i in range(nr))

    ret = "(({}), ({}), ({}), ({}))".format(rows("M", n, n), rows("K", n, nx, "_"),
                                            ", ".join(f"B{i}" for i in range(n)), rows("T", 2, nx, "_"))
    acc = "v_dot, r_dot, eta_dd, beta_dd" + (", y_A_dd, y_B_dd" if variant == "pin_exact" else "")
    doc = _DOC.format(variant=variant, acc=acc, states=", ".join(STATES[variant]))
    args = PIN_ARGS if variant == "pin_exact" else LINEAR_ARGS
    return _function(f"linear_relaxed_{variant}", args, doc, _cse_lines(named, "_a"), ret)


def render() -> str:
    """The text of ``stability/_generated/full_width_relaxed.py``."""
    names = [f"linear_relaxed_{v}" for v in VARIANTS]
    parts = [_render_variant(v) for v in VARIANTS]
    states = "\n\nSTATES = {\n" + "".join(f"    {v!r}: {STATES[v]!r},\n" for v in VARIANTS) + "}\n"
    head = _header("Full-width wheelchair model with relaxation-length caster tires (generated).", BODY,
                   names + ["STATES"])
    return head.replace("Generated by derivations/generate.py", "Generated by derivations/full_width_relaxed.py") \
        + states + "\n\n" + "\n\n".join(parts)


def generate(out: str | os.PathLike[str] | None = None) -> Path:
    """Write ``full_width_relaxed.py`` into ``out`` (default ``stability/_generated``); return its path."""
    path = Path(out or ROOT / "stability" / "_generated") / "full_width_relaxed.py"
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(render(), encoding="utf-8")
    return path


def main(argv: Sequence[str] | None = None) -> int:  # pragma: no cover
    """Command line: ``python derivations/full_width_relaxed.py [--out DIR]``."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=None, help="output directory (default stability/_generated)")
    t0 = time.perf_counter()
    path = generate(p.parse_args(argv).out)
    print(f"wrote {path} in {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
