"""Towed-wheel (caster) shimmy model: Lagrange's equations with a multiplier, linearised.

Usage::

    python derivations/shimmy.py [--out DIR]

writes ``shimmy.py`` into ``DIR`` (default ``stability/_generated``).

The system (Pacejka, *Tyre and Vehicle Dynamics*, 2nd ed. 2006, sec. 5.3;
Schwab and Meijaard 2003; Takacs and Stepan 2009): a pivot P moves forward
at constant speed ``U`` along x and is held laterally by a spring of
stiffness ``k`` (y its lateral displacement; the pivot itself is massless).
The wheel and fork are one rigid body of mass ``m`` and yaw inertia ``I``
about its centre of mass G, which lies ``b`` behind P; the tire contact C
lies ``a`` behind G, so the trail is ``L = a + b``.  The yaw angle of the
fork is ``psi`` (counter-clockwise seen from above, x forward, y left).

Generalised coordinates ``q = (y, psi)``; positions::

    P = (U t, y),  e = (cos psi, sin psi),  G = P - b e,  C = P - L e

The tire force ``F`` acts at C along the wheel's lateral unit vector
``n = (-sin psi, cos psi)``; its generalised forces are ``(F cos psi, -L F)``.

* rigid tire: no side slip, ``n . v_C = 0`` -- a non-holonomic constraint
  ``y_dot cos psi - U sin psi - L psi_dot = 0`` whose multiplier is ``F``;
* compliant tire: first-order relaxation (Pacejka eq 5.12 in the
  single-contact-point form) ``sigma/U alpha_dot + alpha = -n.v_C / U``
  and ``F = C alpha`` (C the cornering stiffness, N/rad; sigma the
  relaxation length, m).

The pin carries a torque ``T`` on the fork (``T = -c psi_dot`` for viscous
pin damping; Coulomb friction is an input, see ``stability.shimmy``).  A
rigid pivot (``k = inf``) removes ``y``.  Four configurations are derived:

=========  =========  ===============================  =====
pivot      tire       states                           order
=========  =========  ===============================  =====
compliant  compliant  y, psi, y_dot, psi_dot, alpha    5
rigid      compliant  psi, psi_dot, alpha             3
compliant  rigid      y, psi, psi_dot                  3
rigid      rigid      psi                              1
=========  =========  ===============================  =====

For each: the state matrix ``A``, the pin-torque input column ``B``
(``x_dot = A x + B T``) and the characteristic polynomial with
positive leading coefficient (``det(s E - F)`` of the natural first-order
form, cleared of denominators).
"""

from __future__ import annotations

import argparse
import functools
import os
import sys
from collections.abc import Sequence
from pathlib import Path

if __name__ == "__main__" and os.environ.get("PYTHONHASHSEED") != "0":  # pragma: no cover
    os.execve(sys.executable, [sys.executable, *sys.argv], dict(os.environ, PYTHONHASHSEED="0"))

import sympy as sp  # noqa: E402

__all__ = ["SYMBOLS", "CASES", "nonlinear_equations", "linear_system", "characteristic_polynomial",
           "render", "generate", "main"]

ROOT = Path(__file__).resolve().parents[1]

t = sp.Symbol("t", real=True)
mass, inertia, a, b, k, C, sigma, c, U = sp.symbols("mass inertia a b k C sigma c U", positive=True)
s = sp.Symbol("s")
SYMBOLS: dict[str, sp.Symbol] = {str(x): x for x in (mass, inertia, a, b, k, C, sigma, c, U, s)}
ARGS = ("mass", "inertia", "a", "b", "k", "C", "sigma", "c", "U")

CASES: dict[str, tuple[str, ...]] = {
    "compliant_compliant": ("y", "psi", "y_dot", "psi_dot", "alpha"),
    "rigid_compliant": ("psi", "psi_dot", "alpha"),
    "compliant_rigid": ("y", "psi", "psi_dot"),
    "rigid_rigid": ("psi",),
}


@functools.cache
def nonlinear_equations() -> dict[str, sp.Expr]:
    """Lagrange's equations of the compliant-pivot wheel with a generalised tire force.

    Returns ``{"y": ..., "psi": ..., "slip": ..., "constraint": ...}``: the two
    equations ``d/dt dT/dq_dot - dT/dq + dV/dq - Q = 0`` (functions of ``t``),
    the lateral slip velocity ``-n . v_C`` of the contact and the
    non-holonomic constraint ``n . v_C`` (= 0 for a rigid tire).
    """
    y = sp.Function("y")(t)
    psi = sp.Function("psi")(t)
    F, T = sp.symbols("F T")
    L = a + b
    e = sp.Matrix([sp.cos(psi), sp.sin(psi)])
    n = sp.Matrix([-sp.sin(psi), sp.cos(psi)])
    P = sp.Matrix([U * t, y])
    G = P - b * e
    Cp = P - L * e
    vG = G.diff(t)
    kinetic = (mass * vG.dot(vG) + inertia * psi.diff(t) ** 2) / 2
    potential = k * y**2 / 2
    vC = Cp.diff(t)
    force = F * n
    q = (y, psi)
    eqs = {}
    for name, qi in zip(("y", "psi"), q, strict=True):
        Q = force.dot(Cp.diff(qi)) + (T if qi is psi else 0)
        lag = kinetic.diff(qi.diff(t)).diff(t) - kinetic.diff(qi) + potential.diff(qi) - Q
        eqs[name] = sp.simplify(lag)
    eqs["slip"] = sp.simplify(-n.dot(vC))
    eqs["constraint"] = sp.simplify(n.dot(vC))
    return eqs


@functools.cache
def linear_system(case: str) -> tuple[sp.Matrix, sp.Matrix, tuple[str, ...]]:
    """``(A, B, states)`` with ``x_dot = A x + B T`` for ``case`` (see :data:`CASES`).

    ``T`` is the pin torque on the fork (N m); viscous pin damping ``c`` is
    already in ``A`` (``T_total = -c psi_dot + T``).
    """
    pivot, tire = case.split("_")
    eqs = nonlinear_equations()
    y_, psi_ = sp.Function("y")(t), sp.Function("psi")(t)
    Y, P_, Yd, Pd, Ydd, Pdd, F, T, al = sp.symbols("Y P_ Yd Pd Ydd Pdd F T alpha")
    subs = {y_.diff(t, 2): Ydd, psi_.diff(t, 2): Pdd, y_.diff(t): Yd, psi_.diff(t): Pd, y_: Y, psi_: P_}
    if pivot == "rigid":
        subs.update({y_.diff(t, 2): 0, y_.diff(t): 0, y_: 0})

    def lin(expr):
        e = expr
        for key in (y_.diff(t, 2), psi_.diff(t, 2), y_.diff(t), psi_.diff(t), y_, psi_):
            e = e.subs(key, subs[key])
        eps = sp.Symbol("eps")
        small = [Y, P_, Yd, Pd, Ydd, Pdd, F, T, al]
        e = e.subs({x: eps * x for x in small})
        return sp.expand(sp.series(e, eps, 0, 2).removeO().subs(eps, 1))

    e_y, e_psi = lin(eqs["y"]), lin(eqs["psi"])
    e_psi = e_psi.subs(T, T - c * Pd)
    slip, cons = lin(eqs["slip"]), lin(eqs["constraint"])
    names = CASES[case]
    if tire == "compliant":
        e_y, e_psi = e_y.subs(F, C * al), e_psi.subs(F, C * al)
        alpha_dot = sp.expand((slip - U * al) / sigma)  # sigma alpha_dot + U alpha = -n.v_C
        if pivot == "compliant":
            sol = sp.solve([e_y, e_psi], [Ydd, Pdd], dict=True)[0]
            rhs = [Yd, Pd, sol[Ydd], sol[Pdd], alpha_dot]
            xs = [Y, P_, Yd, Pd, al]
        else:
            sol = sp.solve([e_psi], [Pdd], dict=True)[0]
            rhs = [Pd, sol[Pdd], alpha_dot]
            xs = [P_, Pd, al]
    else:
        if pivot == "compliant":
            # constraint n.v_C = 0 gives Yd; its derivative gives Ydd; F is the multiplier
            yd = sp.solve(cons, Yd)[0]
            ydd = sp.expand(yd.subs({P_: Pd, Pd: Pdd}, simultaneous=True))  # yd is linear in (psi, psi_dot)
            sol = sp.solve([e_y.subs(Ydd, ydd), e_psi.subs(Ydd, ydd)], [Pdd, F], dict=True)[0]
            rhs = [yd, Pd, sol[Pdd]]
            xs = [Y, P_, Pd]
        else:
            pd = sp.solve(cons, Pd)[0]
            rhs = [pd]
            xs = [P_]
    A = sp.Matrix([[sp.simplify(sp.diff(r, x)) for x in xs] for r in rhs])
    Bv = sp.Matrix([sp.simplify(sp.diff(r, T)) for r in rhs])
    state_names = {"Y": "y", "P_": "psi", "Yd": "y_dot", "Pd": "psi_dot", "alpha": "alpha"}
    assert tuple(state_names[str(x)] for x in xs) == names
    return A, Bv, names


@functools.cache
def characteristic_polynomial(case: str) -> list[sp.Expr]:
    """Coefficients (highest power first, leading one positive) of ``det(s I - A)`` cleared of denominators."""
    A, _, _ = linear_system(case)
    n = A.shape[0]
    det = sp.together(sp.expand((s * sp.eye(n) - A).det(method="berkowitz")))
    num, _ = sp.fraction(sp.factor(det))
    poly = sp.Poly(sp.expand(num), s)
    coeffs = [sp.factor(x) for x in poly.all_coeffs()]
    # divide by the content common to all coefficients (a positive parameter product)
    common = functools.reduce(sp.gcd, coeffs)
    coeffs = [sp.factor(sp.cancel(x / common)) for x in coeffs]
    return coeffs


# ---------------------------------------------------------------------------
# code generation


def _pr(expr) -> str:
    expr = sp.sympify(expr)
    for node in sp.preorder_traversal(expr):
        ok = isinstance(node, (sp.Symbol, sp.Integer, sp.Rational, sp.Add, sp.Mul)) or (
            isinstance(node, sp.Pow) and node.exp.is_Integer)
        if not ok:
            raise ValueError(f"non-arithmetic node {type(node).__name__}: {node}")
    return sp.sstr(expr, order="lex")


def _function(name: str, doc: str, named: Sequence[tuple[str, sp.Expr]], ret: str) -> str:
    reps, reduced = sp.cse([sp.sympify(e) for _, e in named], symbols=sp.numbered_symbols("_t"),
                           order="canonical")
    body = [f"{x} = {_pr(e)}" for x, e in reps] + [f"{n} = {_pr(e)}" for (n, _), e in zip(named, reduced, strict=True)]
    lines = [f"def {name}({', '.join(ARGS)}):", f'    """{doc}"""']
    lines += ["    " + line for line in body] + [f"    return {ret}", ""]
    return "\n".join(lines)


HEADER = '''"""Towed-wheel shimmy model (generated).

Generated by derivations/shimmy.py -- DO NOT EDIT.
sympy version: {version}

Arguments (SI): mass (kg), inertia about the wheel-and-fork c.g. (kg m^2),
a = c.g. to contact (m), b = pivot to c.g. (m), k = lateral pivot stiffness
(N/m), C = cornering stiffness (N/rad), sigma = relaxation length (m),
c = viscous pin damping (N m s/rad), U = speed (m/s).  Arguments a case does
not use are ignored.  Pure arithmetic: floats or broadcast numpy arrays.
"""
# ruff: noqa
# flake8: noqa
# fmt: off

STATES = {states!r}

'''


def render() -> str:
    """The text of ``stability/_generated/shimmy.py``."""
    parts = [HEADER.format(version=sp.__version__, states=dict(CASES))]
    for case in CASES:
        A, Bv, names = linear_system(case)
        n = len(names)
        named = [(f"a{i}{j}", A[i, j]) for i in range(n) for j in range(n)]
        named += [(f"b{i}", Bv[i]) for i in range(n)]
        rows = ", ".join("(" + ", ".join(f"a{i}{j}" for j in range(n)) + ",)" for i in range(n))
        cols = ", ".join(f"b{i}" for i in range(n))
        parts.append(_function(f"state_space_{case}",
                               f"State matrix A and pin-torque column B: x_dot = A x + B T; states {names}.",
                               named, f"({rows},), ({cols},)"))
        coeffs = characteristic_polynomial(case)
        named = [(f"p{i}", e) for i, e in enumerate(coeffs)]
        parts.append(_function(f"characteristic_{case}",
                               "Characteristic polynomial coefficients, highest power of s first.",
                               named, "(" + ", ".join(x for x, _ in named) + ",)"))
    return "\n".join(parts).rstrip() + "\n"


def generate(out: str | os.PathLike[str] | None = None) -> Path:
    """Write the generated module into ``out`` (default ``stability/_generated``); return its path."""
    path = Path(out or ROOT / "stability" / "_generated") / "shimmy.py"
    path.write_text(render())
    return path


def main(argv: Sequence[str] | None = None) -> int:  # pragma: no cover
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output directory (default stability/_generated)")
    print(generate(parser.parse_args(argv).out))
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
