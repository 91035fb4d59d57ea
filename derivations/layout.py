"""Planar model of a chair with any wheel layout: J fixed wheels and K swivelling casters (Kane's method).

The thesis's full-width model (``full_width.derive_exact``) has two fixed main wheels and two casters.  A
mid-wheel-drive power base has two drive wheels and four casters (a pair ahead, a pair behind); a layout is any
number of each.  The bodies and conventions are the thesis model's (SAE body axes: c1 forward, c2 right, c3 down;
yaw positive clockwise seen from above), generalised:

- the chair body (with the user and the fixed wheels) of mass ``m - sum(m_c_k)``, placed so that the system's
  centre of mass is C when every caster trails forward (``delta_k = 0``), with a central yaw inertia such that
  the total yaw inertia about C is ``i_z`` there (parallel-axis theorem);
- fixed wheel ``j``: contact ``W_j = C + x_w_j c1 + y_w_j c2``, contact force ``(FWx_j, FWy_j)`` in the body
  frame;
- caster ``k``: pin ``P_k = C + x_p_k c1 + y_p_k c2``, swivel angle ``delta_k`` from c1 about c3, caster frame
  ``k1 = cos(delta_k) c1 + sin(delta_k) c2``, contact ``P_k - trail_k k1``, caster centre of mass
  ``P_k - l_k k1``, mass ``m_c_k``, yaw inertia about its pin ``i_zp_k``; contact force ``(FCx_k, FCy_k)`` in the
  caster frame; pin moment ``M_k`` on the caster (its reaction on the chair);
- a lateral force ``Fy_ext`` at C and a yaw moment ``Mz_ext`` on the chair body.

Generalized speeds ``u, v, r, delta_d_1..K``.  The linear model about straight running at speed ``U`` has the
tires of the thesis's linear model (``Fy = -C alpha``, ``alpha = v_y / |v_x|`` in the wheel's frame, no
longitudinal forces) and viscous pins ``M_k = -c_pin_k delta_d_k``; a fixed wheel turned by its angle ``a_w_j``
(toe) has its slip ``atan(v_y' / |v_x'|)`` in its own frame and its force along its own lateral axis, turned back
into body axes (the linear model takes the angle's cosine and sine, ``ca_w_j``, ``sa_w_j``).  Forward
(``U > 0``) the casters trail at ``delta_k = 0``; in reverse (``U < 0``) they trail the other way, at
``delta_k = pi``, and the model is linearised there.  ``tests/test_layout.py`` checks that the layout of two
fixed wheels and two casters gives the thesis model's exact linear matrices (``full_width.linearise('exact')``).
"""

from __future__ import annotations

import functools
from types import SimpleNamespace

import sympy as sp
import sympy.physics.mechanics as me

__all__ = ["symbols", "derive", "gravity", "linearise", "parameters", "nonlinear", "nonlinear_parameters"]


def symbols(n_fixed: int, n_casters: int) -> SimpleNamespace:
    """The plain symbols of a layout: per wheel and per caster, and the shared ones.

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    SimpleNamespace
        ``U, m, i_z, Fy_ext, Mz_ext``; lists ``x_w, y_w, C_w, a_w, ca_w, sa_w, FWx, FWy`` (fixed wheels;
        ``a_w`` the wheel's angle, rad, ``ca_w, sa_w`` its cosine and sine in the generated code) and ``x_p, y_p,
        trail, l, m_c, i_zp, C_c, c_pin, FCx, FCy, M, delta, delta_d`` (casters); ``v, r, u`` and their rates.
    """
    def many(name: str, n: int) -> list:
        return [sp.Symbol(f"{name}_{i}", real=True) for i in range(n)]

    s = SimpleNamespace(**{n: sp.Symbol(n, real=True) for n in "U m i_z Fy_ext Mz_ext u v r u_dot v_dot r_dot".split()})
    for name in ("x_w", "y_w", "C_w", "a_w", "ca_w", "sa_w", "FWx", "FWy"):
        setattr(s, name, many(name, n_fixed))
    for name in ("x_p", "y_p", "trail", "l", "m_c", "i_zp", "C_c", "c_pin", "FCx", "FCy", "M", "delta", "delta_d",
                 "delta_dd"):
        setattr(s, name, many(name, n_casters))
    return s


@functools.cache
def derive(n_fixed: int, n_casters: int) -> SimpleNamespace:
    """Kane's equations of a layout: ``M(q) [u_dot, v_dot, r_dot, delta_dd...] = F``.

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    SimpleNamespace
        ``M`` (symmetric, 3 + K square), ``F``, ``vel`` (the contact velocities in each wheel's frame: fixed
        wheels then casters, ``(vx, vy)`` each), ``sym`` (:func:`symbols`).
    """
    s = symbols(n_fixed, n_casters)
    t = me.dynamicsymbols._t
    X, Y, th = me.dynamicsymbols("X Y theta")
    u, v, r = me.dynamicsymbols("u v r")
    dl = [me.dynamicsymbols(f"delta_{k}") for k in range(n_casters)]
    dld = [me.dynamicsymbols(f"delta_d_{k}") for k in range(n_casters)]
    N = me.ReferenceFrame("N")
    Cf = N.orientnew("C", "Axis", (th, N.z))
    Cf.set_ang_vel(N, r * Cf.z)
    O = me.Point("O")
    O.set_vel(N, 0)
    Cp = O.locatenew("C", X * N.x + Y * N.y)
    Cp.set_vel(N, u * Cf.x + v * Cf.y)

    m_b = s.m - sum(s.m_c)
    # casters' centres of mass with every caster trailing forward (delta = 0)
    c0 = [(s.x_p[k] - s.l[k], s.y_p[k]) for k in range(n_casters)]
    gb = (-sum(s.m_c[k] * c0[k][0] for k in range(n_casters)) / m_b,
          -sum(s.m_c[k] * c0[k][1] for k in range(n_casters)) / m_b)
    Gb = Cp.locatenew("Gb", gb[0] * Cf.x + gb[1] * Cf.y)
    Gb.v2pt_theory(Cp, N, Cf)
    I_c = [s.i_zp[k] - s.m_c[k] * s.l[k] ** 2 for k in range(n_casters)]
    I_b = (s.i_z - m_b * (gb[0] ** 2 + gb[1] ** 2)
           - sum(I_c[k] + s.m_c[k] * (c0[k][0] ** 2 + c0[k][1] ** 2) for k in range(n_casters)))
    bodies = [me.RigidBody("chair", Gb, Cf, m_b, (me.inertia(Cf, 0, 0, I_b), Gb))]
    loads = [(Cp, s.Fy_ext * Cf.y)]
    body_moment = s.Mz_ext
    vel = []
    contacts = []
    for j in range(n_fixed):
        W = Cp.locatenew(f"W{j}", s.x_w[j] * Cf.x + s.y_w[j] * Cf.y)
        W.v2pt_theory(Cp, N, Cf)
        loads.append((W, s.FWx[j] * Cf.x + s.FWy[j] * Cf.y))
        contacts.append((W, Cf))
    for k in range(n_casters):
        Kf = Cf.orientnew(f"K{k}", "Axis", (dl[k], Cf.z))
        Kf.set_ang_vel(Cf, dld[k] * Cf.z)
        P = Cp.locatenew(f"P{k}", s.x_p[k] * Cf.x + s.y_p[k] * Cf.y)
        P.v2pt_theory(Cp, N, Cf)
        G = P.locatenew(f"G{k}", -s.l[k] * Kf.x)
        G.v2pt_theory(P, N, Kf)
        A = P.locatenew(f"A{k}", -s.trail[k] * Kf.x)
        A.v2pt_theory(P, N, Kf)
        bodies.append(me.RigidBody(f"caster{k}", G, Kf, s.m_c[k], (me.inertia(Kf, 0, 0, I_c[k]), G)))
        loads.append((A, s.FCx[k] * Kf.x + s.FCy[k] * Kf.y))
        loads.append((Kf, s.M[k] * Kf.z))
        body_moment = body_moment - s.M[k]
        contacts.append((A, Kf))
    loads.append((Cf, body_moment * Cf.z))
    kd = [X.diff(t) - (u * sp.cos(th) - v * sp.sin(th)), Y.diff(t) - (u * sp.sin(th) + v * sp.cos(th)),
          th.diff(t) - r] + [dl[k].diff(t) - dld[k] for k in range(n_casters)]
    km = me.KanesMethod(N, q_ind=[X, Y, th, *dl], u_ind=[u, v, r, *dld], kd_eqs=kd)
    km.kanes_equations(bodies, loads)
    dyn = {u: s.u, v: s.v, r: s.r, **dict(zip(dl, s.delta, strict=True)), **dict(zip(dld, s.delta_d, strict=True))}

    def plain(e):
        e = me.msubs(e, dyn)
        if me.find_dynamicsymbols(e):
            raise ValueError(f"dynamic symbols left: {me.find_dynamicsymbols(e)}")
        return e

    Mm = km.mass_matrix.applyfunc(lambda e: sp.cancel(plain(e)))
    Fv = km.forcing.applyfunc(lambda e: sp.cancel(plain(e)))
    for P, F_ in contacts:
        vP = P.vel(N)
        vel += [sp.expand(plain(vP.dot(F_.x))), sp.expand(plain(vP.dot(F_.y)))]
    return SimpleNamespace(M=Mm, F=Fv, vel=tuple(vel), sym=s, gb=gb, I_b=I_b, m_b=m_b, bodies=tuple(bodies), N=N,
                           frame=Cf, speeds=(u, v, r, *dld), plain=plain)


#: In-plane gravity in body axes, m/s^2: ``g1`` forward, ``g2`` to the right (the slope model's symbols,
#: :data:`derivations.slope.G`: on a plane of cross slope ``phi`` and grade ``theta`` at heading ``psi``).
G1, G2 = sp.Symbol("g1", real=True), sp.Symbol("g2", real=True)


@functools.cache
def gravity(n_fixed: int, n_casters: int) -> tuple[sp.Expr, ...]:
    """Generalized active forces of the in-plane weight of every body (chair at ``Gb``, each caster at its own
    centre of mass ``l_k`` behind its pin): ``Q_i = sum_b dv_b/du_i . m_b (g1 c1 + g2 c2)``, the slope model's
    construction (:func:`derivations.slope.derive_gravity`) for any layout.

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    tuple of sympy.Expr
        One per generalized speed ``u, v, r, delta_d_0..``, in ``g1, g2`` (m/s^2) and the layout's symbols.
    """
    d = derive(n_fixed, n_casters)
    grav = G1 * d.frame.x + G2 * d.frame.y
    out = []
    for us in d.speeds:
        q = sp.Integer(0)
        for body in d.bodies:
            q += body.masscenter.vel(d.N).diff(us, d.N).dot(body.mass * grav)
        out.append(sp.cancel(d.plain(q)))
    return tuple(out)


@functools.cache
def linearise(n_fixed: int, n_casters: int, reverse: bool = False) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix,
                                                                            sp.Matrix]:
    """The linear model about straight running: ``M acc = K x + Bm Mz_ext + Bf Fy_ext``.

    Parameters
    ----------
    n_fixed, n_casters : int
    reverse : bool
        Linearise about ``U < 0`` with every caster trailing backwards (``delta_k = pi``).

    Returns
    -------
    (M, K, Bm, Bf) : sympy Matrices
        ``acc = [v_dot, r_dot, delta_dd_0, ...]``, ``x = [v, r, delta_0, delta_d_0, ...]``.  Symbols:
        :func:`symbols`; ``U`` signed, ``|U|`` written as ``-U`` in reverse.
    """
    d = derive(n_fixed, n_casters)
    s = d.sym
    absU = -s.U if reverse else s.U
    sign = -1 if reverse else 1
    delta0 = sp.pi if reverse else sp.Integer(0)
    K_ = n_casters
    # tire forces of the linear model: Fy = -C vy / |vx|, Fx = 0; viscous pins.  A fixed wheel turned by its
    # angle a_w (toe) about c3 has its slip in its own frame, alpha = atan(vy' / |vx'|) as the simulator's SLIP,
    # and its force -C alpha along its own lateral axis, written back into body axes
    sub: dict = {}
    for j in range(n_fixed):
        a = s.a_w[j]
        vx, vy = d.vel[2 * j], d.vel[2 * j + 1]
        vxw, vyw = vx * sp.cos(a) + vy * sp.sin(a), -vx * sp.sin(a) + vy * sp.cos(a)
        fyw = -s.C_w[j] * sp.atan(vyw / (sign * vxw))
        sub[s.FWx[j]] = -fyw * sp.sin(a)
        sub[s.FWy[j]] = fyw * sp.cos(a)
    for k in range(K_):
        sub[s.FCx[k]] = 0
        sub[s.FCy[k]] = -s.C_c[k] * d.vel[2 * (n_fixed + k) + 1] / absU
        sub[s.M[k]] = -s.c_pin[k] * s.delta_d[k]
    acc = [s.u_dot, s.v_dot, s.r_dot, *s.delta_dd]
    R = [sum(d.M[i, c] * acc[c] for c in range(3 + K_)) - d.F[i].xreplace(sub) for i in range(3 + K_)]
    eq = {s.v: 0, s.r: 0, s.u: s.U, **{s.delta[k]: delta0 for k in range(K_)},
          **{s.delta_d[k]: 0 for k in range(K_)}, **{a: 0 for a in acc}, s.Mz_ext: 0, s.Fy_ext: 0}
    straight = {a: 0 for a in s.a_w}
    for i in range(3 + K_):        # straight running is an equilibrium (with toe, where the toe forces balance)
        assert sp.simplify(R[i].subs(eq).subs(straight)) == 0, (i, R[i].subs(eq))
    rows = [1, 2] + [3 + k for k in range(K_)]
    for i in rows:                                       # the forward speed decouples at first order
        assert sp.simplify(sp.diff(R[i], s.u_dot).subs(eq)) == 0
        assert sp.simplify(sp.diff(R[i], s.u).subs(eq)) == 0
    state = [s.v, s.r] + [x for k in range(K_) for x in (s.delta[k], s.delta_d[k])]
    lin_acc = [s.v_dot, s.r_dot, *s.delta_dd]
    M = sp.Matrix([[sp.simplify(sp.diff(R[i], a).subs(eq)) for a in lin_acc] for i in rows])
    K = sp.Matrix([[_simplify_angles(-sp.diff(R[i], x).subs(eq), s.a_w, reverse) for x in state] for i in rows])
    Bm = sp.Matrix([sp.simplify(-sp.diff(R[i], s.Mz_ext).subs(eq)) for i in rows])
    Bf = sp.Matrix([sp.simplify(-sp.diff(R[i], s.Fy_ext).subs(eq)) for i in rows])
    trig = {}
    for j in range(n_fixed):                             # the generated code takes the angle's cosine and sine
        trig[sp.cos(s.a_w[j])] = s.ca_w[j]
        trig[sp.sin(s.a_w[j])] = s.sa_w[j]
    M, K, Bm, Bf = (X.xreplace(trig) for X in (M, K, Bm, Bf))
    for X in (M, K, Bm, Bf):
        assert not (X.free_symbols & set(s.a_w)), "a wheel angle left outside its cosine and sine"
    return M, K, Bm, Bf


def _simplify_angles(e: sp.Expr, angles: list, reverse: bool) -> sp.Expr:
    """Simplify a linear coefficient with the fixed wheels' angles in it: ``atan`` of the slip at straight
    running, ``atan(-tan a) = -a`` forward (``+a`` in reverse), valid for ``|a| < 90 deg``."""
    e = sp.simplify(e)
    for a in angles:
        e = e.subs(sp.atan(sp.tan(a)), a).subs(sp.atan(-sp.tan(a)), -a)
    return sp.simplify(e)


def parameters(n_fixed: int, n_casters: int) -> tuple[sp.Symbol, ...]:
    """The argument order of the generated linear function of a layout.

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    tuple of sympy.Symbol
        ``U, m, i_z``, then per fixed wheel ``x_w, y_w, C_w, ca_w, sa_w`` (the cosine and sine of its angle),
        then per caster ``x_p, trail, l, m_c, i_zp,
        C_c, c_pin`` (a fixed wheel's lateral position enters through its angle's longitudinal force; the
        casters' do not enter the linear model).
    """
    s = symbols(n_fixed, n_casters)
    out = [s.U, s.m, s.i_z]
    for j in range(n_fixed):
        out += [s.x_w[j], s.y_w[j], s.C_w[j], s.ca_w[j], s.sa_w[j]]
    for k in range(n_casters):
        out += [s.x_p[k], s.trail[k], s.l[k], s.m_c[k], s.i_zp[k], s.C_c[k], s.c_pin[k]]
    return tuple(out)


def nonlinear_parameters(n_fixed: int, n_casters: int) -> tuple[sp.Symbol, ...]:
    """The order of the parameter vector ``p`` of the generated nonlinear functions of a layout.

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    tuple of sympy.Symbol
        ``m, i_z``, then per fixed wheel ``x_w, y_w``, then per caster ``x_p, y_p, trail, l, m_c, i_zp``.
    """
    s = symbols(n_fixed, n_casters)
    out = [s.m, s.i_z]
    for j in range(n_fixed):
        out += [s.x_w[j], s.y_w[j]]
    for k in range(n_casters):
        out += [s.x_p[k], s.y_p[k], s.trail[k], s.l[k], s.m_c[k], s.i_zp[k]]
    return tuple(out)


@functools.cache
def nonlinear(n_fixed: int, n_casters: int) -> SimpleNamespace:
    """The nonlinear equations of a layout in the symbols the generated code takes.

    ``sin(delta_k)``, ``cos(delta_k)`` become the symbols ``sn_k``, ``cs_k`` (the simulator evaluates them once
    per step).  The pin moments enter the forcing only as ``F = F0 + sum_k M_k e_(3+k)`` (the moment's power is
    ``M_k delta_d_k``: it acts on the caster and reacts on the chair), checked here, so ``F0`` (the forcing with
    every pin moment zero) is what is generated and the simulator adds the moments it chooses (free, stuck or
    held casters).

    Parameters
    ----------
    n_fixed, n_casters : int

    Returns
    -------
    SimpleNamespace
        ``M`` (3 + K square), ``F0`` (3 + K, with the in-plane weight of :func:`gravity` in ``g1, g2``),
        ``vel`` (2 (J + K): each contact's ``(vx, vy)`` in its wheel's
        frame, fixed wheels then casters), ``cs``, ``sn`` (the symbols).
    """
    d = derive(n_fixed, n_casters)
    s = d.sym
    cs = [sp.Symbol(f"cs_{k}", real=True) for k in range(n_casters)]
    sn = [sp.Symbol(f"sn_{k}", real=True) for k in range(n_casters)]
    trig = {}
    for k in range(n_casters):
        trig[sp.sin(s.delta[k])] = sn[k]
        trig[sp.cos(s.delta[k])] = cs[k]

    def plain(e: sp.Expr) -> sp.Expr:
        e = sp.expand(sp.expand_trig(e)).xreplace(trig)
        left = e.free_symbols & set(s.delta)
        if left:
            raise ValueError(f"caster angles left outside sin/cos: {left}")
        return e

    n = 3 + n_casters
    for k in range(n_casters):                           # the pin moments enter as e_(3+k) only
        for i in range(n):
            assert sp.simplify(sp.diff(d.F[i], s.M[k]) - (1 if i == 3 + k else 0)) == 0, (k, i)
    zero = {m_: 0 for m_ in s.M}
    M = d.M.applyfunc(plain)
    Q = gravity(n_fixed, n_casters)
    F0 = (d.F + sp.Matrix(Q)).xreplace(zero).applyfunc(plain)
    vel = tuple(plain(v) for v in d.vel)
    return SimpleNamespace(M=M, F0=F0, vel=vel, cs=cs, sn=sn, sym=s)


# ---------------------------------------------------------------------------
# Code generation

#: Layout shapes generated into ``stability/_generated/layout.py``: (fixed wheels, casters).  Two fixed wheels
#: with one to four casters covers the thesis's chairs (2, 2), a three-wheeler (2, 1) and a mid-wheel-drive base
#: with casters ahead and behind (2, 4); add a shape here and rerun ``python derivations/layout.py``.
SHAPES = ((2, 1), (2, 2), (2, 3), (2, 4))


def _function_text(n_fixed: int, n_casters: int, reverse: bool) -> tuple[str, str]:
    from derivations.generate import _cse_lines

    M, K, Bm, Bf = linearise(n_fixed, n_casters, reverse)
    n = M.shape[0]
    named = [(f"M{i}{j}", M[i, j]) for i in range(n) for j in range(n)]
    named += [(f"K{i}{j}", K[i, j]) for i in range(n) for j in range(K.shape[1])]
    named += [(f"Bm{i}", Bm[i]) for i in range(n)] + [(f"Bf{i}", Bf[i]) for i in range(n)]
    body = _cse_lines(named, "_a")
    name = f"linear_{n_fixed}w{n_casters}c_{'reverse' if reverse else 'forward'}"
    args = ", ".join(str(p) for p in parameters(n_fixed, n_casters))
    rows = lambda pre, cols: "(" + ", ".join("(" + ", ".join(f"{pre}{i}{j}" for j in range(cols)) + ",)"  # noqa: E731
                                            for i in range(n)) + ",)"
    ret = (f"return ({rows('M', n)}, {rows('K', K.shape[1])}, ({', '.join(f'Bm{i}' for i in range(n))},), "
           f"({', '.join(f'Bf{i}' for i in range(n))},))")
    doc = (f'"""Linear model of a layout with {n_fixed} fixed wheels and {n_casters} casters, '
           f'{"in reverse (U < 0, casters trailing at pi)" if reverse else "forward (U > 0, casters trailing at 0)"}.'
           "\n\n    Returns (M, K, Bm, Bf) as nested tuples: M acc = K x + Bm Mz_ext + Bf Fy_ext, acc = [v_dot, r_dot, "
           'delta_dd...], x = [v, r, delta_0, delta_d_0, ...]."""')
    lines = [f"def {name}({args}):", f"    {doc}"] + [f"    {x}" for x in body] + [f"    {ret}", ""]
    return name, "\n".join(lines)


def _unpack_lines(n_fixed: int, n_casters: int, with_forces: bool) -> list[str]:
    s = symbols(n_fixed, n_casters)
    lines = [f"{p} = p[{i}]" for i, p in enumerate(nonlinear_parameters(n_fixed, n_casters))]
    for k in range(n_casters):
        lines += [f"cs_{k} = cs[{k}]", f"sn_{k} = sn[{k}]", f"delta_d_{k} = dd[{k}]"]
    if with_forces:
        for j in range(n_fixed):
            lines += [f"{s.FWx[j]} = fw[{2 * j}]", f"{s.FWy[j]} = fw[{2 * j + 1}]"]
        for k in range(n_casters):
            lines += [f"{s.FCx[k]} = fc[{2 * k}]", f"{s.FCy[k]} = fc[{2 * k + 1}]"]
    return lines


def _nonlinear_text(n_fixed: int, n_casters: int) -> tuple[list[str], str]:
    from derivations.generate import _cse_lines

    d = nonlinear(n_fixed, n_casters)
    n = 3 + n_casters
    tag = f"{n_fixed}w{n_casters}c"
    # the equations: M and F0 written into the caller's arrays
    named = [(f"M[{i}, {j}]", d.M[i, j]) for i in range(n) for j in range(n)] + [(f"F[{i}]", d.F0[i])
                                                                              for i in range(n)]
    body = _unpack_lines(n_fixed, n_casters, True) + _cse_lines(named, "_e")
    doc = (f'"""Nonlinear equations of a layout with {n_fixed} fixed wheels and {n_casters} casters: '
           "writes M (n x n) and F0 (n), n = 3 + casters,\n    with M [u_dot, v_dot, r_dot, delta_dd...] = F0 + "
           "sum_k M_k e_(3+k) (M_k the pin moment on caster k).\n\n    u, v, r (m/s, m/s, rad/s); cs, sn, dd: "
           "cos, sin and rate (rad/s) of each caster angle;\n    p: parameters (nonlinear_parameters order); "
           "fw: (Fx, Fy) of each fixed wheel in body axes;\n    fc: (Fx, Fy) of each caster in its frame; Fy_ext "
           "(N) at the c.g., Mz_ext (N m) on the body;\n    g1, g2: in-plane gravity in body axes (m/s^2, forward and "
           "to the right; 0 on level ground).\n    " + '"' * 3)
    eq = [f"def equations_{tag}(u, v, r, cs, sn, dd, p, fw, fc, Fy_ext, Mz_ext, g1, g2, M, F):", f"    {doc}"]
    eq += [f"    {x}" for x in body] + ["    return None", ""]
    # the contact velocities
    named = [(f"out[{i}]", e) for i, e in enumerate(d.vel)]
    body = _unpack_lines(n_fixed, n_casters, False) + _cse_lines(named, "_v")
    doc = ('"""Contact velocities (vx, vy) in each wheel\'s frame (m/s): fixed wheels, then casters, written '
           'into out."""')
    cv = [f"def contact_velocities_{tag}(u, v, r, cs, sn, dd, p, out):", f"    {doc}"]
    cv += [f"    {x}" for x in body] + ["    return None", ""]
    return [f"equations_{tag}", f"contact_velocities_{tag}"], "\n".join(eq) + "\n\n" + "\n".join(cv)


def render_nonlinear() -> str:
    """The text of ``stability/_generated/layout_nonlinear.py``: the equations and contact velocities per shape,
    and ``equations`` / ``contact_velocities`` dispatching on the shape's index in ``SHAPES``."""
    header = ('"""Nonlinear equations of chairs with any wheel layout (generated).\n\nGenerated by '
              "derivations/layout.py -- DO NOT EDIT.\nsympy version: " + sp.__version__ + "\n\nSee "
              "derivations/layout.py (derive, nonlinear) for the bodies and conventions.  Plain arithmetic on "
              "floats and\nindexable sequences: the simulator compiles these functions as they are.\n\"\"\"\n\n")
    names, parts = [], []
    for shape in SHAPES:
        ns, text = _nonlinear_text(*shape)
        names += ns
        parts.append(text)
    disp_e = ["def equations(shape, u, v, r, cs, sn, dd, p, fw, fc, fy_ext, mz_ext, g1, g2, M, F):",
              '    """equations_<shape> of the shape SHAPES[shape]."""']
    disp_v = ["def contact_velocities(shape, u, v, r, cs, sn, dd, p, out):",
              '    """contact_velocities_<shape> of the shape SHAPES[shape]."""']
    for i, (j, k) in enumerate(SHAPES):
        kw = "if" if i == 0 else "elif"
        disp_e += [f"    {kw} shape == {i}:", f"        equations_{j}w{k}c(u, v, r, cs, sn, dd, p, fw, fc, fy_ext, "
                   "mz_ext, g1, g2, M, F)"]
        disp_v += [f"    {kw} shape == {i}:", f"        contact_velocities_{j}w{k}c(u, v, r, cs, sn, dd, p, out)"]
    disp_e.append("    return None")
    disp_v.append("    return None")
    names += ["equations", "contact_velocities"]
    shapes = "SHAPES = " + repr(tuple(SHAPES)) + "\n"
    shapes += ("#: the parameter vector p of each shape, by name (a fixed wheel's x_w_j, y_w_j; a caster's x_p_k, "
               "y_p_k, trail_k, l_k, m_c_k, i_zp_k)\nPARAMETERS = {\n" + "".join(
                   f"    {shape!r}: {tuple(str(x) for x in nonlinear_parameters(*shape))!r},\n" for shape in SHAPES)
               + "}\n")
    return (header + f"__all__ = {names!r}\n\n" + shapes + "\n\n" + "\n\n".join(parts) + "\n\n"
            + "\n".join(disp_e) + "\n\n\n" + "\n".join(disp_v) + "\n")


def render() -> str:
    """The text of ``stability/_generated/layout.py``: one function per shape and direction."""
    header = ('"""Linear models of chairs with any wheel layout (generated).\n\nGenerated by derivations/layout.py '
              "-- DO NOT EDIT.\nsympy version: " + sp.__version__ + "\n\nSee derivations/layout.py for the bodies, "
              "conventions and the tire and pin laws of the\nlinear model.  Arguments: U (signed forward speed, m/s), "
              "m, i_z, then per fixed wheel\nx_w, y_w (contact, m ahead of and right of C), C_w (cornering stiffness, "
              "N/rad), ca_w, sa_w (cosine and\nsine of the wheel's angle, toe), then per caster x_p, trail, l (c.g. "
              "behind the pin), m_c, i_zp, C_c, c_pin\n(SI units).\n\"\"\"\n\n")
    names, parts = [], []
    for shape in SHAPES:
        for reverse in (False, True):
            name, text = _function_text(*shape, reverse)
            names.append(name)
            parts.append(text)
    shapes = "SHAPES = " + repr(tuple(SHAPES)) + "\n"
    return header + f"__all__ = {names!r}\n\n" + shapes + "\n\n" + "\n\n".join(parts)


def main() -> None:  # pragma: no cover - run by hand after changing the derivation
    """Write ``stability/_generated/layout.py`` (linear) and ``layout_nonlinear.py``."""
    import os
    from pathlib import Path

    os.environ.setdefault("PYTHONHASHSEED", "0")
    gen = Path(__file__).resolve().parents[1] / "stability" / "_generated"
    for name, text in (("layout.py", render()), ("layout_nonlinear.py", render_nonlinear())):
        (gen / name).write_text(text, encoding="utf-8")
        print(f"wrote {gen / name}")


if __name__ == "__main__":  # pragma: no cover
    import os
    import sys

    if os.environ.get("PYTHONHASHSEED") != "0":
        os.execve(sys.executable, [sys.executable, *sys.argv], dict(os.environ, PYTHONHASHSEED="0"))
    sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1]))
    main()
