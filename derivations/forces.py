"""Contact forces of the chair: contact points, normal loads, resultant, slip angles, pin friction laws.

Everything the simulator evaluates per step besides the equations of motion
(:mod:`derivations.full_width`, :mod:`derivations.slope`) and the tire force
law (:mod:`stability.tires.law`), derived once here and generated into
``stability/_generated/forces.py`` by :mod:`derivations.generate`:

* the caster contact points, eq 6-24: ``A = Pa - trail a1``, ``B = Pb - trail b1``;
* the normal loads of eq 6-25 on a plane, from the sums of the tire forces and
  the normal gravity ``gn`` (``gn = g`` on level ground): the symbolic solution
  of :func:`derivations.slope.normal_loads_plane` written as the elimination a
  hand solution takes (the caster pair's effective contact ``x_c``, the main
  axle's share ``s_m`` from the pitch balance, then each pair's roll split), one
  operation per step so that every caller evaluates one arithmetic;
* the resultant of the tire forces in body axes (eq 6-2) and their yaw moment
  about the c.g. (eq 6-3), casters' forces turned from their wheel frames;
* the signed slip angle ``atan2(v_y, |v_x|)`` in degrees (program WCHAIR's SLIP);
* Coulomb pin friction: the kinetic moment ``-M_f sign(rate)`` (zero at rest,
  WCHAIR's DYNAM), the stick condition ``|M_hold| <= M_f``, the break-away
  moment ``M_f sign(M_hold)``, and the rest rule of the fixed-step stick-slip law
  (a rate that would change sign within a step comes to rest).

:func:`checks` returns differences that must simplify to zero: the stepwise
loads equal the symbolic solution of the slope derivation (and so eq 6-25 at
``gn = g``) and satisfy the four load equations; the resultant and moment equal
the vector sums over the contact points; the friction laws' closed forms.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path
from types import SimpleNamespace

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # pragma: no cover
    sys.path.insert(0, str(ROOT))

import sympy as sp  # noqa: E402

from derivations import full_width as fw  # noqa: E402
from derivations import slope as sl  # noqa: E402

__all__ = ["F", "copysign", "contact_steps", "load_steps", "resultant_steps", "moment_steps", "slip_angle",
           "pin_laws", "compose", "checks"]

S = fw.S
G = sl.G
_names = "sum_fx sum_fy rate limit moment new vx vy DEG_PER_RAD"
F = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in _names.split()})
"""Symbols added here (attribute = symbol name); ``DEG_PER_RAD`` stands for 180/pi."""


class copysign(sp.Function):  # noqa: N801  (printed as math.copysign)
    """``copysign(a, b) = |a| sign(b)`` (``math.copysign``); ``b`` is never zero where it is used."""

    nargs = 2

    def _eval_rewrite_as_sign(self, a, b, **kwargs):
        return sp.Abs(a) * sp.sign(b)


def _sym(name: str) -> sp.Symbol:
    return sp.Symbol(name, real=True)


def contact_steps() -> list[tuple[sp.Symbol, sp.Expr]]:
    """Caster contacts (eq 6-24): ``(x_A, y_A, x_B, y_B)`` as assignments."""
    return [(_sym("x_A"), S.x_p - S.trail * S.ce), (_sym("y_A"), -S.t1 - S.trail * S.se),
            (_sym("x_B"), S.x_p - S.trail * S.cb), (_sym("y_B"), S.t2 - S.trail * S.sb)]


def load_steps() -> list[tuple[sp.Symbol, sp.Expr]]:
    """Normal loads on the plane from the force sums, one operation per step; the last four are N_A, N_B, N_D, N_E.

    The elimination: the caster pair acts at ``x_c`` (where its two loads'
    resultant lies when they carry no roll moment); the pitch balance about
    the c.g. then gives the main pair's share ``s_m``, the rest ``s_c`` is the
    casters'; each pair splits its share by its roll moment (``1/(k+1)`` of
    ``-h sum_fy`` to the casters, eq 6-30).
    """
    s = {n: _sym(n) for n in "x_A y_A x_B y_B c1 weight hfy hfx kc r_c r_m dy x_c q n1 n2 den s_m s_c".split()}
    out = contact_steps()
    out += [
        (s["c1"], 1 / (G.roll_k + 1)),
        (s["weight"], G.gn * S.m),
        (s["hfy"], G.h * F.sum_fy),
        (s["r_c"], -s["hfy"] * s["c1"]),              # roll moment carried by the caster pair
        (s["kc"], G.roll_k * s["c1"]),
        (s["r_m"], -s["hfy"] * s["kc"]),              # ... and by the main-wheel pair
        (s["dy"], s["y_B"] - s["y_A"]),
        (s["x_c"], (s["x_A"] * s["y_B"] - s["x_B"] * s["y_A"]) / s["dy"]),   # effective x of the caster pair
        (s["hfx"], G.h * F.sum_fx),
        (s["q"], s["r_c"] * (s["x_B"] - s["x_A"])),
        (s["n1"], -s["hfx"] - s["q"] / s["dy"]),
        (s["n2"], s["n1"] - s["weight"] * s["x_c"]),
        (s["den"], S.x_m - s["x_c"]),
        (s["s_m"], s["n2"] / s["den"]),              # the main pair's share of the weight
        (s["s_c"], s["weight"] - s["s_m"]),
        (_sym("N_A"), (s["y_B"] * s["s_c"] - s["r_c"]) / s["dy"]),
        (_sym("N_B"), (s["r_c"] - s["y_A"] * s["s_c"]) / s["dy"]),
        (_sym("N_E"), (s["r_m"] + S.d1 * s["s_m"]) / (S.d1 + S.d2)),
    ]
    out.append((_sym("N_D"), s["s_m"] - out[-1][0]))
    return out


def _caster_forces() -> list[tuple[sp.Symbol, sp.Expr]]:
    """The caster forces turned from their wheel frames into body axes."""
    return [(_sym("fax"), S.FAx * S.ce - S.FAy * S.se), (_sym("fay"), S.FAx * S.se + S.FAy * S.ce),
            (_sym("fbx"), S.FBx * S.cb - S.FBy * S.sb), (_sym("fby"), S.FBx * S.sb + S.FBy * S.cb)]


def _left_sum(name: str, terms: list[sp.Expr]) -> list[tuple[sp.Symbol, sp.Expr]]:
    """``terms`` summed left to right, one addition per step; the last step is ``name``."""
    steps: list[tuple[sp.Symbol, sp.Expr]] = []
    acc = terms[0]
    for k, t in enumerate(terms[1:], start=1):
        sym = _sym(name if k == len(terms) - 1 else f"{name}_{k}")
        steps.append((sym, acc + t))
        acc = sym
    return steps


def resultant_steps() -> list[tuple[sp.Symbol, sp.Expr]]:
    """``sum_fx``, ``sum_fy``: the tire forces' resultant in body axes (eq 6-2), summed D, E, A, B."""
    return (_left_sum("sum_fx", [S.FDx, S.FEx, S.FAx * S.ce, -S.FAy * S.se, S.FBx * S.cb, -S.FBy * S.sb])
            + _left_sum("sum_fy", [S.FDy, S.FEy, S.FAx * S.se, S.FAy * S.ce, S.FBx * S.sb, S.FBy * S.cb]))


def moment_steps() -> list[tuple[sp.Symbol, sp.Expr]]:
    """``mz``: the tire forces' yaw moment about the c.g. (eq 6-3), ``sum x_i F_yi - y_i F_xi``."""
    c = {str(k): k for k, _ in contact_steps()}
    f = {str(k): k for k, _ in _caster_forces()}
    terms = [c["x_A"] * f["fay"], -c["y_A"] * f["fax"], c["x_B"] * f["fby"], -c["y_B"] * f["fbx"],
             S.x_m * _sym("fdey"), S.d1 * S.FDx, -S.d2 * S.FEx]
    return (contact_steps() + _caster_forces() + [(_sym("fdey"), S.FDy + S.FEy)]
            + _left_sum("mz", terms))


def slip_angle() -> sp.Expr:
    """Signed slip angle of a contact moving at ``(vx, vy)`` in its wheel frame, deg: ``atan2(vy, |vx|)``."""
    return sp.atan2(F.vy, sp.Abs(F.vx)) * F.DEG_PER_RAD


def pin_laws() -> dict[str, sp.Expr]:
    """Coulomb pin friction: kinetic moment, stick condition, break-away moment, rest rule.

    ``rate`` a caster's swivel rate (rad/s), ``limit`` its friction moment
    (N m), ``moment`` the moment that holds it at rest (N m), ``new`` the rate
    after a fixed step (rad/s).
    """
    return {
        "kinetic": sp.Piecewise((sp.Float(0.0), sp.Eq(F.rate, 0)), (copysign(F.limit, -F.rate), True)),
        "holds": sp.Abs(F.moment) <= F.limit,
        "break_away": copysign(F.limit, F.moment),
        "rest": sp.Piecewise((sp.Float(0.0), sp.And(F.limit > 0, sp.Ne(F.rate, 0), F.new * F.rate <= 0)),
                             (F.new, True)),
    }


def compose(steps: list[tuple[sp.Symbol, sp.Expr]]) -> dict[sp.Symbol, sp.Expr]:
    """Every step in terms of the inputs (the assignments substituted in order)."""
    env: dict[sp.Symbol, sp.Expr] = {}
    for sym, e in steps:
        env[sym] = e.xreplace(env)
    return env


@functools.cache
def checks() -> dict[str, sp.Expr]:
    """Differences that must simplify to zero (:mod:`tests.test_derivations` asserts them)."""
    out: dict[str, sp.Expr] = {}
    env = compose(load_steps())
    names = ("N_A", "N_B", "N_D", "N_E")
    loads = [env[_sym(n)] for n in names]
    sums = {sp.Symbol("sum_fx", real=True): F.sum_fx, sp.Symbol("sum_fy", real=True): F.sum_fy}
    for n, mine, ref in zip(names, loads, sl.normal_loads_plane(), strict=True):
        out[f"loads_{n}"] = sp.simplify(mine - ref.xreplace(sums))
    (xa, ya), (xb, yb), (xd, yd), (xe, ye) = sl.contact_xy()
    xs, ys = (xa, xb, xd, xe), (ya, yb, yd, ye)
    c1 = 1 / (G.roll_k + 1)
    out["loads_weight"] = sp.simplify(sum(loads) - S.m * G.gn)                               # 6-25c
    out["loads_pitch"] = sp.simplify(sum(x * n for x, n in zip(xs, loads, strict=True)) + G.h * F.sum_fx)   # 6-25d
    out["loads_roll_casters"] = sp.simplify(ya * loads[0] + yb * loads[1] + G.h * F.sum_fy * c1)          # 6-25a
    out["loads_roll_main"] = sp.simplify(yd * loads[2] + ye * loads[3] + G.h * F.sum_fy * G.roll_k * c1)  # 6-25b
    # resultant and moment: the vector sums of the forces at the contacts
    fa = sp.Matrix([S.FAx * S.ce - S.FAy * S.se, S.FAx * S.se + S.FAy * S.ce, 0])
    fb = sp.Matrix([S.FBx * S.cb - S.FBy * S.sb, S.FBx * S.sb + S.FBy * S.cb, 0])
    forces = (fa, fb, sp.Matrix([S.FDx, S.FDy, 0]), sp.Matrix([S.FEx, S.FEy, 0]))
    total = sum(forces, sp.zeros(3, 1))
    moment = sum((sp.Matrix([x, y, 0]).cross(f)[2] for x, y, f in zip(xs, ys, forces, strict=True)), sp.Integer(0))
    env = compose(resultant_steps())
    out["resultant_x"] = sp.expand(env[_sym("sum_fx")] - total[0])
    out["resultant_y"] = sp.expand(env[_sym("sum_fy")] - total[1])
    out["yaw_moment"] = sp.expand(compose(moment_steps())[_sym("mz")] - moment)
    # friction laws: the kinetic moment is -limit sign(rate); break-away has the holding moment's sign
    laws = pin_laws()
    lim = sp.Symbol("limit", positive=True)
    exact = {sp.Float(0.0): sp.Integer(0)}       # the printed 0.0 is the integer zero here
    out["kinetic"] = sp.simplify((laws["kinetic"].xreplace(exact).rewrite(sp.sign) + F.limit * sp.sign(F.rate))
                                 .subs(F.limit, lim))
    out["break_away"] = sp.simplify((laws["break_away"].rewrite(sp.sign) - F.limit * sp.sign(F.moment))
                                    .subs(F.limit, lim))
    return out
