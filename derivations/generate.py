"""Generate the plain-Python numeric modules from the symbolic derivations.

Usage::

    python derivations/generate.py [--out DIR]

writes ``zero_width.py``, ``full_width.py`` and ``forces.py`` into ``DIR``
(default ``stability/_generated``).  The generated functions use only ``+ - * / **`` (small integer powers written as
products) on their arguments (cosines and sines of the caster angles are passed in as
``ce, se, cb, sb``), so the same function runs on Python floats and on
broadcast numpy arrays; they import nothing.  The exceptions are in
``forces.py``: its slip angle and pin friction laws are scalar (``math.atan2``,
``math.copysign``, ``abs``, comparisons), for floats and the compiled kernels.

Common subexpressions are eliminated with :func:`sympy.cse` (canonical
order, numbered temporaries ``_a0, _a1, ...``) and printed with sympy's
``StrPrinter``; every expression is checked to be pure arithmetic before it
is printed.  The output is deterministic: the script re-executes itself with
``PYTHONHASHSEED=0`` so that no set/dict ordering can leak into the text.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Iterable, Sequence
from pathlib import Path

if __name__ == "__main__" and os.environ.get("PYTHONHASHSEED") != "0":  # pragma: no cover
    env = dict(os.environ, PYTHONHASHSEED="0")
    os.execve(sys.executable, [sys.executable, *sys.argv], env)

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import sympy as sp  # noqa: E402
from sympy.printing.precedence import precedence  # noqa: E402
from sympy.printing.pycode import PythonCodePrinter  # noqa: E402
from sympy.printing.str import StrPrinter  # noqa: E402

from derivations import forces as fo  # noqa: E402
from derivations import full_width as fw  # noqa: E402
from derivations import zero_width as zw  # noqa: E402

__all__ = ["generate", "render_zero_width", "render_full_width", "render_forces", "main"]


# ---------------------------------------------------------------------------
# printing helpers


def _check_arith(expr: sp.Expr) -> None:
    """Raise if ``expr`` is not built from + - * / and integer powers."""
    for node in sp.preorder_traversal(expr):
        if isinstance(node, (sp.Symbol, sp.Integer, sp.Rational)):
            continue
        if isinstance(node, (sp.Add, sp.Mul)):
            continue
        if isinstance(node, sp.Pow) and node.exp.is_Integer:
            continue
        raise ValueError(f"non-arithmetic node {type(node).__name__}: {node}")


class _Printer(StrPrinter):
    """sympy's StrPrinter, with small integer powers written as products: ``x**2`` -> ``(x*x)``.

    CPython evaluates ``x**2`` on floats through ``pow`` and numba (and numpy's
    ``square``) as ``x*x``; the two differ in the last bit on about 0.06 % of
    inputs.  Written as a parenthesised product, every caller (Python floats,
    numpy arrays, numba) evaluates one arithmetic, in the same order.
    """

    def _print_Pow(self, expr, rational=False):
        b, e = expr.as_base_exp()
        if e.is_Integer and 2 <= int(e) <= 4:
            base = self.parenthesize(b, precedence(expr), strict=False)
            return "(" + "*".join([base] * int(e)) + ")"
        return super()._print_Pow(expr, rational)


_PRINTER = _Printer({"order": "lex"})


def _pr(expr) -> str:
    expr = sp.sympify(expr)
    _check_arith(expr)
    return _PRINTER.doprint(expr)


def _step_lines(steps: Sequence[tuple[sp.Symbol, sp.Expr]]) -> list[str]:
    """Assignments printed in the order given, no elimination: each step is one or two operations on earlier
    names, so that every caller (floats, numpy, numba) evaluates the same arithmetic in the same order."""
    return [f"{sym} = {_pr(e)}" for sym, e in steps]


class _ScalarPrinter(PythonCodePrinter):
    """Python's printer for the scalar laws: ``copysign`` as ``math.copysign``, products as :class:`_Printer`'s."""

    def _print_copysign(self, expr):
        return f"math.copysign({self._print(expr.args[0])}, {self._print(expr.args[1])})"

    def _print_Pow(self, expr, rational=False):
        return _PRINTER._print_Pow(expr, rational)


_SCALAR = _ScalarPrinter({"standard": "python3"})


def _cse_lines(named: Sequence[tuple[str, sp.Expr]], tmp: str) -> list[str]:
    """Assignments computing ``named`` with common subexpressions eliminated."""
    exprs = [sp.sympify(e) for _, e in named]
    reps, reduced = sp.cse(exprs, symbols=sp.numbered_symbols(tmp), order="canonical")
    lines = [f"{s} = {_pr(e)}" for s, e in reps]
    lines += [f"{n} = {_pr(e)}" for (n, _), e in zip(named, reduced, strict=False)]
    return lines


# the chair's parameters: in a batch they are shared Python floats, so that
# products of them cost nothing next to operations on arrays of runs
CHAIR_SYMBOLS = frozenset(("x_m", "x_p", "d1", "d2", "t1", "t2", "trail", "l1", "m", "m_c", "i_z", "i_zp"))


def _split_by_parameters(named: Sequence[tuple[str, sp.Expr]], tmp: str
                         ) -> tuple[list[tuple[sp.Symbol, sp.Expr]], list[tuple[str, sp.Expr]]]:
    """Write each expression as ``sum(c_k * s_k)``: ``c_k`` parameters only, ``s_k`` the rest.

    Every coefficient other than +-1 becomes one temporary (``_p0, _p1, ...``,
    shared between equal coefficients) and the terms sharing a coefficient
    are summed before it multiplies them, so that an expression costs about
    one array operation per state factor, not one per factor.  Returns the
    temporaries and the rewritten expressions.
    """
    params = {sp.Symbol(n, real=True) for n in CHAIR_SYMBOLS} | {sp.Symbol(n) for n in CHAIR_SYMBOLS}
    coef_sym: dict[sp.Expr, sp.Symbol] = {}
    defs: list[tuple[sp.Symbol, sp.Expr]] = []
    out = []
    for name, e in named:
        groups: dict[sp.Expr, sp.Expr] = {}
        order: list[sp.Expr] = []
        for term in sp.Add.make_args(sp.expand(sp.sympify(e))):
            c, s = [], []
            for f in sp.Mul.make_args(term):
                (c if f.free_symbols <= params else s).append(f)
            mono = sp.Mul(*s)
            if mono not in groups:
                order.append(mono)
                groups[mono] = sp.Integer(0)
            groups[mono] += sp.Mul(*c)
        by_coef: dict[sp.Expr, list[sp.Expr]] = {}
        for mono in order:
            coef = sp.factor_terms(groups[mono])
            if coef == 0:
                continue
            if coef not in (1, -1) and not coef.is_Symbol:
                if coef not in coef_sym:
                    coef_sym[coef] = sp.Symbol(f"{tmp}{len(defs)}")
                    defs.append((coef_sym[coef], coef))
                coef = coef_sym[coef]
            by_coef.setdefault(coef, []).append(mono)
        # one multiplication per distinct coefficient: c * (s_1 + s_2 + ...)
        terms = [c * _factor_greedily(monos) for c, monos in by_coef.items()]
        out.append((name, sp.Add(*terms)))
    return defs, out


def _factor_greedily(monos: Sequence[sp.Expr]) -> sp.Expr:
    """``sum(monos)`` with the most frequent factor taken out, recursively.

    ``a*x + b*x + c`` becomes ``x*(a + b) + c`` (two array operations fewer);
    ties are broken by name, so the result is deterministic.
    """
    if len(monos) < 2:
        return sp.Add(*monos)
    counts: dict[sp.Symbol, int] = {}
    for mono in monos:
        for sym in mono.free_symbols:
            counts[sym] = counts.get(sym, 0) + 1
    best = max(sorted(counts, key=str), key=lambda sym: counts[sym], default=None)
    if best is None or counts[best] < 2:
        return sp.Add(*monos, evaluate=False)
    inner = [mono / best for mono in monos if mono.has(best)]
    rest = [mono for mono in monos if not mono.has(best)]
    factored = best * _factor_greedily(inner)
    return sp.Add(factored, _factor_greedily(rest), evaluate=False) if rest else factored


def _hoisted_cse_lines(named: Sequence[tuple[str, sp.Expr]], tmp: str, ptmp: str) -> list[str]:
    """Like :func:`_cse_lines`, parameter-only coefficients first (see :func:`_split_by_parameters`)."""
    defs, rewritten = _split_by_parameters(named, ptmp)
    lines = _cse_lines([(str(s), e) for s, e in defs], "_q" + ptmp.lstrip("_")) if defs else []
    return lines + _cse_lines(rewritten, tmp)


def _function(name: str, args: Sequence[str], doc: str, body: Iterable[str], ret: str,
              defaults: dict[str, str] | None = None) -> str:
    defaults = defaults or {}
    sig = ", ".join(f"{a}={defaults[a]}" if a in defaults else a for a in args)
    doc_lines = doc.strip("\n").splitlines()
    out = [f"def {name}({sig}):", '    """' + doc_lines[0]]
    out += [("    " + line).rstrip() for line in doc_lines[1:]]
    out.append('    """')
    out += ["    " + line for line in body]
    out.append(f"    return {ret}")
    return "\n".join(out) + "\n"


def _header(title: str, body: str, names: Sequence[str]) -> str:
    all_ = ",\n".join(f'    "{n}"' for n in sorted(names))
    return (
        f'"""{title}\n\n'
        "Generated by derivations/generate.py -- DO NOT EDIT.\n"
        f"sympy version: {sp.__version__}\n\n"
        f"{body.strip()}\n"
        '"""\n'
        "# ruff: noqa\n"
        "# flake8: noqa\n"
        "# fmt: off\n\n"
        f"__all__ = [\n{all_},\n]\n"
    )


# ---------------------------------------------------------------------------
# zero-width module

ZW_BODY = """
Zero-width (bicycle) model of Collins (1987), chapter 5, eqs 5-9..5-17.
Two identical tires per axle; C_f, C_r are the cornering stiffnesses of ONE
front / ONE rear tire (N/rad); W_f, W_r the static load on one front / one
rear tire (N, eq 5-13); s1, s2 the distances from the c.g. to the front and
rear axles (m); U the forward speed (m/s).  SAE axes: v lateral velocity (+
right), r yaw rate (+ clockwise seen from above).

Every function uses only arithmetic and accepts floats or broadcast numpy
arrays.  See derivations/zero_width.py for the derivation and the symbolic
proofs that each result equals the thesis's printed form.
"""


ZW_OUTPUT_NAMES = {
    "understeer_coefficient": "k_us",
    "critical_speed_squared": "u_crit_sq",
    "routh_hurwitz_margin": "margin",
    "a_coefficients": ("a1", "a2", "a3", "a4"),
    "state_matrix": None,
    "characteristic_coefficients": ("c2", "c1", "c0"),
}


def render_zero_width() -> str:
    funcs = zw.generated_functions()
    parts = []
    names = []
    for name, args, outputs, doc in funcs:
        names_o = ZW_OUTPUT_NAMES[name]
        if len(outputs) == 1:
            named, ret = [(names_o, sp.sympify(outputs[0]))], names_o
        elif name == "state_matrix":
            named = [(f"S{i}{j}", outputs[i][j]) for i in range(2) for j in range(2)]
            ret = "((S00, S01), (S10, S11))"
        else:
            named = list(zip(names_o, outputs, strict=False))
            ret = "(" + ", ".join(names_o) + ")"
        body = _cse_lines(named, "_a")
        defaults = {"g": "9.81"} if name in ("critical_speed_squared",) else None
        parts.append(_function(name, args, doc, body, ret, defaults))
        names.append(name)
    return _header("Zero-width wheelchair model (generated).", ZW_BODY, names) + "\n\n" + "\n\n".join(parts)


# ---------------------------------------------------------------------------
# full-width module

FW_BODY = """
Full-width five-degree-of-freedom planar wheelchair model (Collins 1987,
chapter 6), in two variants:

exact
    first-principles Kane's-method derivation (three rigid bodies);
thesis
    Table 6-1 and eqs 6-17a-d as printed (OCR-corrected), i.e. what program
    WCHAIR (Appendix C, SLIP and DYNAM) integrates.

Conventions: SAE body axes, c1 forward, c2 right, c3 down; yaw rate r
positive clockwise seen from above.  u, v: velocity of C (system c.g. with
the casters trailing, fixed in the chair) along c1, c2.  Signed body
coordinates relative to C: main-wheel contacts D (left) (x_m, -d1), E (right)
(x_m, +d2); caster pins Pa (left) (x_p, -t1), Pb (right) (x_p, +t2); caster
angles eta (left, A), beta (right, B) from c1, positive about c3; caster
contact = pin - trail * a1, caster c.g. = pin - l1 * a1.  Rear-caster chair:
x_m = s1 > 0, x_p = -s2 < 0; front-caster chair: x_m = -s1, x_p = +s2.

Arguments ce, se, cb, sb are cos(eta), sin(eta), cos(beta), sin(beta).
Forces: (FAx, FAy) at A in the caster-A frame, (FBx, FBy) at B in the caster-B
frame, (FDx, FDy), (FEx, FEy) at D, E in the chair frame (N); M_A, M_B pin
moments acting on the casters (N m; reaction on the chair); Fy_ext lateral
force at C (N); Mz_ext yaw moment on the chair body (N m).  Mass data: m
total mass, m_c one caster assembly, i_z total yaw inertia about C with the
casters trailing, i_zp one caster's yaw inertia about its pin.

Every function uses only arithmetic and accepts floats or broadcast numpy
arrays.  See derivations/full_width.py and derivations/README.md.
"""

_VEL_DOC = """
Velocity of each tire contact point in its own wheel frame ({which}).

Parameters
----------
u, v : float or ndarray
    Velocity of C along c1, c2 (m/s).
r : float or ndarray
    Yaw rate (rad/s, + clockwise from above).
ce, se, cb, sb : float or ndarray
    cos(eta), sin(eta), cos(beta), sin(beta) of the caster angles.
eta_d, beta_d : float or ndarray
    Caster swivel rates relative to the chair (rad/s).
x_m, x_p, d1, d2, t1, t2, trail : float or ndarray
    Signed geometry (m): main-axle and pin x coordinates, lateral offsets of
    D, E, Pa, Pb, caster trail.

Returns
-------
(vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy)
    A in frame a, B in frame b, D and E in frame c (m/s).  The slip angle is
    atan(vy/vx); a lateral force opposing vy is negative for vy > 0.
{note}"""

_VEL_NOTE_EXACT = """
Notes
-----
Exact kinematics: v_A = v_C + r c3 x r_CPa + (r + eta_d) c3 x (-trail a1),
so vAy contains -trail*(r + eta_d).
"""

_VEL_NOTE_THESIS = """
Notes
-----
Eqs 6-17a-d / subroutine SLIP as printed: vAy and vBy contain -trail*eta_d
but NOT the -trail*r of the exact kinematics.
"""

_ACC_PARAMS = """
Parameters
----------
u, v, r : float or ndarray
    Velocity of C (m/s) and yaw rate (rad/s).
ce, se, cb, sb : float or ndarray
    cos/sin of the caster angles eta (left), beta (right).
eta_d, beta_d : float or ndarray
    Caster swivel rates relative to the chair (rad/s).
FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy : float or ndarray
    Tire forces in each wheel's frame (N).
M_A, M_B : float or ndarray
    Pin moments acting on casters A and B about c3 (N m).
Fy_ext : float or ndarray
    External lateral force at C along c2 (N) (WCHAIR's FCIMP).
Mz_ext : float or ndarray
    External yaw moment on the chair body about c3 (N m).
x_m, x_p, d1, d2, t1, t2, trail, l1 : float or ndarray
    Signed geometry (m).
m, m_c, i_z, i_zp : float or ndarray
    Total mass, one caster's mass (kg), total yaw inertia about C with the
    casters trailing, one caster's yaw inertia about its pin (kg m^2)."""

_ACC_EXACT_DOC = """
Accelerations of the exact (Kane's method) model.
""" + _ACC_PARAMS + """

Returns
-------
(u_dot, v_dot, r_dot, eta_dd, beta_dd)
    Body-frame derivatives of u, v (m/s^2), yaw acceleration and caster
    angular accelerations relative to the chair (rad/s^2).

Notes
-----
M(eta, beta) [u_dot, v_dot, r_dot, eta_dd, beta_dd] = F.  The 5x5 mass
matrix is symmetric positive definite and its caster block is diag(i_zp,
i_zp); the casters are eliminated (Schur complement) and the 3x3 chair block
is solved by an LDL^T factorisation, all in arithmetic.  Requires i_zp > 0.
"""

_ACC_THESIS_DOC = """
Accelerations of Table 6-1 (eqs 6-17..6-21), as program WCHAIR (DYNAM).
""" + _ACC_PARAMS + """
r_dot_casters : float or ndarray or None
    Yaw acceleration used in the caster equations (6-20, 6-21).  None: the
    current r_dot.  WCHAIR's DYNAM uses the previous call's THEDD here.

Returns
-------
(u_dot, v_dot, r_dot, eta_dd, beta_dd)

Notes
-----
Fy_ext enters v_dot only (WCHAIR adds FCIMP to FC2 after forming the caster
terms); Mz_ext is added to the yaw equation 6-19 (an extension: it reaches the
caster equations only through the yaw acceleration).  The caster equations
are written without 1/(l1 m_c), so l1 = 0 or m_c = 0 are allowed.
"""

_LIN_DOC = """
Linearised {which} model about straight running at speed U{locked}.

Linear tires Fy_i = -C_i * alpha_i, alpha_i = vy_i/vx_i (C_i in N/rad at the
static load), no longitudinal forces{pin}; input Mz_ext (N m).

Returns
-------
(M, K, Bm)
    Nested tuples with M acc = K x + Bm Mz_ext, where
    {shape}.
    Entries are scalars or arrays (broadcast over the arguments).
"""


def render_full_width() -> str:
    g = fw.generated_functions()
    parts: list[str] = []
    names: list[str] = []

    # contact velocities
    vel_names = ("vAx", "vAy", "vBx", "vBy", "vDx", "vDy", "vEx", "vEy")
    for variant, note in (("exact", _VEL_NOTE_EXACT), ("thesis", _VEL_NOTE_THESIS)):
        named = list(zip(vel_names, g[f"vel_{variant}"], strict=False))
        body = _hoisted_cse_lines(named, "_a", "_p")
        doc = _VEL_DOC.format(which={"exact": "exact kinematics",
                                     "thesis": "eqs 6-17a-d, SLIP"}[variant], note=note)
        name = f"contact_velocities_{variant}"
        parts.append(_function(name, fw.CONTACT_ARGS, doc, body, "(" + ", ".join(vel_names) + ")"))
        names.append(name)

    # exact accelerations: mass-matrix entries, forcing, explicit elimination
    M = g["M_exact"]
    named = [(f"m{i}{j}", M[(i, j)]) for (i, j) in sorted(M) if (i, j) != (3, 4)]
    named += [(f"f{i}", g["F_exact"][i]) for i in range(5)]
    body = _hoisted_cse_lines(named, "_a", "_p")
    body += [
        "# eliminate the caster accelerations (caster block diagonal: m33, m44)",
        "k3 = 1/m33",
        "k4 = 1/m44",
        "s00 = m00 - m03*m03*k3 - m04*m04*k4",
        "s01 = m01 - m03*m13*k3 - m04*m14*k4",
        "s02 = m02 - m03*m23*k3 - m04*m24*k4",
        "s11 = m11 - m13*m13*k3 - m14*m14*k4",
        "s12 = m12 - m13*m23*k3 - m14*m24*k4",
        "s22 = m22 - m23*m23*k3 - m24*m24*k4",
        "g0 = f0 - m03*f3*k3 - m04*f4*k4",
        "g1 = f1 - m13*f3*k3 - m14*f4*k4",
        "g2 = f2 - m23*f3*k3 - m24*f4*k4",
        "# LDL^T solve of the symmetric positive definite 3x3 Schur complement",
        "l10 = s01/s00",
        "l20 = s02/s00",
        "e1 = s11 - l10*l10*s00",
        "l21 = (s12 - l20*l10*s00)/e1",
        "e2 = s22 - l20*l20*s00 - l21*l21*e1",
        "y1 = g1 - l10*g0",
        "y2 = g2 - l20*g0 - l21*y1",
        "r_dot = y2/e2",
        "v_dot = y1/e1 - l21*r_dot",
        "u_dot = g0/s00 - l10*v_dot - l20*r_dot",
        "eta_dd = (f3 - m03*u_dot - m13*v_dot - m23*r_dot)*k3",
        "beta_dd = (f4 - m04*u_dot - m14*v_dot - m24*r_dot)*k4",
    ]
    parts.append(_function("accelerations_exact", fw.ACCEL_ARGS, _ACC_EXACT_DOC, body,
                           "(u_dot, v_dot, r_dot, eta_dd, beta_dd)"))
    names.append("accelerations_exact")

    # thesis accelerations
    acc = g["acc_thesis"]
    rdc = fw.S.r_dot_casters
    for e in acc[:3]:
        assert not e.has(rdc)
    body = _hoisted_cse_lines(list(zip(("u_dot", "v_dot", "r_dot"), acc[:3], strict=False)), "_a", "_p")
    body += ["if r_dot_casters is None:", "    r_dot_casters = r_dot"]
    body += _hoisted_cse_lines(list(zip(("eta_dd", "beta_dd"), acc[3:], strict=False)), "_b", "_pb")
    parts.append(_function("accelerations_thesis", fw.ACCEL_ARGS + ("r_dot_casters",),
                           _ACC_THESIS_DOC, body, "(u_dot, v_dot, r_dot, eta_dd, beta_dd)",
                           {"r_dot_casters": "None"}))
    names.append("accelerations_thesis")

    # kinetic energy
    parts.append(_function(
        "kinetic_energy_exact", fw.KE_ARGS,
        "Kinetic energy of chair + user + both casters (J), exact model.\n\n"
        "Same arguments as accelerations_exact (no forces).  At eta = beta = 0 it\n"
        "reduces to m (u^2 + v^2)/2 + i_z r^2/2 + i_zp (eta_d^2 + beta_d^2)/2 + ...\n",
        _cse_lines([("ke", g["ke_exact"])], "_a"), "ke"))
    names.append("kinetic_energy_exact")

    # linear models
    for variant in ("exact", "thesis"):
        for locked in (False, True):
            M_, K_, B_ = g["linear"][(variant, locked)]
            n = M_.shape[0]
            named_o = [(f"M{i}{j}", M_[i, j]) for i in range(n) for j in range(M_.shape[1])]
            named_o += [(f"K{i}{j}", K_[i, j]) for i in range(n) for j in range(K_.shape[1])]
            named_o += [(f"B{i}", B_[i, 0]) for i in range(n)]
            ret = "(({}), ({}), ({}))".format(
                ", ".join("(" + ", ".join(f"M{i}{j}" for j in range(M_.shape[1])) + ")" for i in range(n)),
                ", ".join("(" + ", ".join(f"K{i}{j}" for j in range(K_.shape[1])) + ")" for i in range(n)),
                ", ".join(f"B{i}" for i in range(n)))
            body = _cse_lines(named_o, "_a")
            name = f"linear_{'locked_' if locked else ''}{variant}"
            args = fw.LOCKED_ARGS if locked else fw.LINEAR_ARGS
            doc = _LIN_DOC.format(
                which=variant,
                locked=", casters locked at eta = beta = 0" if locked else "",
                pin="" if locked else ", viscous pins M_A = -c_pin eta_d",
                shape=("acc = [v_dot, r_dot] and x = [v, r]" if locked else
                       "acc = [v_dot, r_dot, eta_dd, beta_dd] and\n    x = [v, r, eta, eta_d, beta, beta_d]"),
            )
            if variant == "thesis":
                doc += ("\nThe caster equations are used with the current yaw acceleration\n"
                        "(no DYNAM lag); the thesis's M is that of its equations written as\n"
                        "m v_dot, i_z r_dot, i_zp eta_dd - m_c l1 x_p r_dot, ... (not symmetric).\n")
            parts.append(_function(name, args, doc, body, ret))
            names.append(name)
    return _header("Full-width wheelchair model (generated).", FW_BODY, names) + "\n\n" + "\n\n".join(parts)


# ---------------------------------------------------------------------------
# forces module

FO_BODY = """
The contact forces of the chair (derivations/forces.py): caster contact
points (eq 6-24), normal loads with quasi-static load transfer on a plane
(eq 6-25; gn = g on level ground), the resultant and yaw moment of the tire
forces (eqs 6-2, 6-3), the signed slip angle (program WCHAIR's SLIP) and
Coulomb pin friction (kinetic moment, stick condition, break-away moment,
the fixed-step rest rule).  Conventions as in full_width.py.

The arithmetic functions are written one operation per step in a fixed order
and run on floats and broadcast numpy arrays; slip_angle and the pin laws are
scalar (floats, and compiled by numba as they are, like every function here).
"""

_FORCE_ARGS = ("FAx", "FAy", "FBx", "FBy", "FDx", "FDy", "FEx", "FEy", "ce", "se", "cb", "sb")
_FO_FUNCS = (
    ("caster_contacts", ("ce", "se", "cb", "sb", "x_p", "t1", "t2", "trail"), "contact", "(x_A, y_A, x_B, y_B)",
     "Body coordinates of the caster contacts A, B (m), eq 6-24: trail behind the pins along each heading.\n\n"
     "ce, se, cb, sb: cos/sin of the caster angles; x_p, t1, t2, trail: signed pin x, pin offsets, trail (m).\n"),
    ("normal_loads", ("sum_fx", "sum_fy", "gn", "ce", "se", "cb", "sb", "x_m", "x_p", "d1", "d2", "t1", "t2",
                      "trail", "h", "m", "roll_k"), "loads", "(N_A, N_B, N_D, N_E)",
     "Normal loads (N_A, N_B, N_D, N_E) in N, eq 6-25 on a plane, from the tire-force sums.\n\n"
     "sum_fx, sum_fy: sums of the forces on the chair in body axes (N); gn: gravity normal to the\n"
     "plane (m/s^2; g on level ground); h: c.g. height (m); m: mass (kg); roll_k: roll-stiffness\n"
     "ratio (1/(k+1) of the roll moment to the casters, eq 6-30).  The in-plane weight drops out\n"
     "of the load transfer (m a = sum F + m g_in).\n"),
    ("tire_resultant", _FORCE_ARGS, "resultant", "(sum_fx, sum_fy)",
     "Resultant of the tire forces on the chair in body axes (N), eq 6-2 (WCHAIR's FC1, FC2 without FCIMP).\n\n"
     "FAx..FEy: each tire's force in its own wheel frame (casters A, B turned by eta, beta) (N).\n"),
    ("tire_yaw_moment", _FORCE_ARGS + ("x_m", "x_p", "d1", "d2", "t1", "t2", "trail"), "moment", "mz",
     "Yaw moment of the tire forces about the c.g. (N m, clockwise seen from above), eq 6-3.\n\n"
     "sum (x_i F_yi - y_i F_xi) over the four contacts (caster contacts of caster_contacts).\n"),
)
_FO_LAWS = (
    ("kinetic_pin_moment", ("rate", "limit"), "kinetic",
     "Kinetic Coulomb pin moment on a caster (N m): -limit sign(rate), exactly zero at rest (WCHAIR's DYNAM).\n\n"
     "rate: swivel rate (rad/s); limit: friction moment (N m, >= 0).\n"),
    ("pin_holds", ("moment", "limit"), "holds",
     "Stick condition: a caster at rest stays at rest while the moment that holds it (N m) is within\n"
     "its friction limit (N m).\n"),
    ("break_away_moment", ("moment", "limit"), "break_away",
     "Moment on a caster breaking away (N m): the friction limit in the holding moment's direction.\n"),
    ("rest_rate", ("rate", "new", "limit"), "rest",
     "Swivel rate after a fixed step under the stick-slip law (rad/s): zero where the rate (rad/s)\n"
     "would change sign within the step and the pin has friction (limit > 0, N m), else new.\n"),
)


def render_forces() -> str:
    """Text of ``stability/_generated/forces.py``."""
    steps = {"contact": fo.contact_steps(), "loads": fo.load_steps(), "resultant": fo.resultant_steps(),
             "moment": fo.moment_steps()}
    parts, names = [], []
    for name, args, key, ret, doc in _FO_FUNCS:
        parts.append(_function(name, args, doc, _step_lines(steps[key]), ret))
        names.append(name)
    parts.append(_function(
        "slip_angle", ("vx", "vy"),
        "Signed slip angle of a contact (deg): ``atan2(vy, abs(vx))`` (WCHAIR's SLIP takes its magnitude).\n\n"
        "vx, vy: the contact's velocity along and across its wheel's heading (m/s).\n",
        [], _SCALAR.doprint(fo.slip_angle())))
    names.append("slip_angle")
    laws = fo.pin_laws()
    for name, args, key, doc in _FO_LAWS:
        parts.append(_function(name, args, doc, [], _SCALAR.doprint(laws[key])))
        names.append(name)
    head = _header("Contact forces of the chair (generated).", FO_BODY, names)
    head += "\nimport math\n\n#: 180/pi: radians to degrees\nDEG_PER_RAD = 180.0 / math.pi\n"
    return head + "\n\n" + "\n\n".join(parts)


def generate(out: Path) -> dict[str, float]:
    """Write the modules into ``out``; return the time spent on each (s)."""
    out.mkdir(parents=True, exist_ok=True)
    times = {}
    for fname, render in (("zero_width.py", render_zero_width), ("full_width.py", render_full_width),
                          ("forces.py", render_forces)):
        t0 = time.perf_counter()
        text = render()
        (out / fname).write_text(text, encoding="utf-8")
        times[fname] = time.perf_counter() - t0
    return times


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", type=Path, default=ROOT / "stability" / "_generated",
                   help="output directory (default: stability/_generated)")
    a = p.parse_args(argv)
    times = generate(a.out)
    for k, v in times.items():
        print(f"wrote {a.out / k} in {v:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
