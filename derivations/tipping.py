"""Static tipping of a rigid chair on a tilted plane (sympy): the conditions ``stability.tipping`` uses.

1. The gravity line through the c.g. (height ``h`` above the plane) meets the plane at
   ``h (g1, g2) / gn`` from the c.g.'s foot point, ``(g1, g2)`` the in-plane and ``gn`` the
   normal gravity in body axes; on a plane tilted by ``alpha`` along the unit fall line ``e``
   that is ``h tan(alpha) e``.
2. Rigid-body statics: the moment about a tipping line of the normal loads on the contacts off
   it equals the moment of the weight about that line, ``m (gn (rho - 0) - h g_in e.n)`` per unit
   normal ``n`` with the line at distance ``rho e.n`` along ``n``; it vanishes, so the uphill
   contacts unload, exactly at ``tan(alpha) = rho / h`` (whatever the load distribution model).
3. The least stable swivel angle: ``min over eta of n.(pin - l (cos eta, sin eta)) = n.pin - l``.
4. Anti-tip devices: resting on the main wheels and an anti-tip contact ``reach`` beyond them and
   ``clearance`` above the ground, the chair tips over them at
   ``tan(alpha) = (reach^2 + clearance^2 + s1 reach - h clearance) / (s1 clearance + h reach)``.

``python derivations/tipping.py`` checks each statement symbolically and prints the closed forms.
Nothing is generated: the run-time code (``stability/tipping/angles.py``) is the geometry above.
"""

from __future__ import annotations

import sympy as sp


def gravity_line_foot() -> sp.Expr:
    """Statement 1: where the gravity line meets the plane, along the fall line (m)."""
    h, g, a = sp.symbols("h g alpha", positive=True)
    lam = sp.symbols("lambda")
    # c.g. at (0, h) in (along fall line, normal) plane coordinates; gravity (g sin a, -g cos a)
    foot = sp.solve(sp.Eq(h - lam * g * sp.cos(a), 0), lam)[0]
    along = sp.simplify(foot * g * sp.sin(a))
    assert sp.simplify(along - h * sp.tan(a)) == 0
    return along


def moment_about_tipping_line() -> sp.Expr:
    """Statement 2: moment of the weight about the tipping line; zero at tan(alpha) = rho/h."""
    h, g, m, a, rho = sp.symbols("h g m alpha rho", positive=True)
    # tipping line through (rho, 0) perpendicular to the fall line, in the plane; c.g. at (0, h)
    # weight m (g sin a, -g cos a): moment about the line (restoring positive)
    moment = m * g * sp.cos(a) * rho - m * g * sp.sin(a) * h
    assert sp.simplify(moment.subs(a, sp.atan(rho / h))) == 0
    return moment


def least_stable_swivel() -> sp.Expr:
    """Statement 3: the smallest support value of a caster contact over its swivel angle.

    With ``n = (cos theta, sin theta)`` the support value ``n.(pin - l (cos eta, sin eta))`` is
    stationary at ``eta = theta`` (the contact pointing along -n from the pin) with positive curvature
    ``l``: the minimum ``n.pin - l``.
    """
    th, px, py, eta = sp.symbols("theta p_x p_y eta", real=True)
    l = sp.symbols("l", positive=True)
    value = sp.cos(th) * (px - l * sp.cos(eta)) + sp.sin(th) * (py - l * sp.sin(eta))
    assert sp.simplify(sp.diff(value, eta).subs(eta, th)) == 0
    assert sp.simplify(sp.diff(value, eta, 2).subs(eta, th) - l) == 0
    target = sp.cos(th) * px + sp.sin(th) * py - l
    assert sp.simplify(value.subs(eta, th) - target) == 0
    return target


def anti_tip() -> sp.Expr:
    """Statement 4: tan of the plane angle at which the chair tips over its anti-tip devices."""
    s1, h, r, c = sp.symbols("s1 h reach clearance", positive=True)
    L = sp.sqrt(r**2 + c**2)
    u = sp.Matrix([r, c]) / L                 # along the plane through main contact and anti-tip contact
    n = sp.Matrix([-c, r]) / L                # its normal, toward the c.g.
    cg = sp.Matrix([-s1, h])                  # c.g. from the main-wheel contact, chair level
    along, up = (cg.T * u)[0], (cg.T * n)[0]
    tan_alpha = sp.simplify((L - along) / up)
    closed = (r**2 + c**2 + s1 * r - h * c) / (s1 * c + h * r)
    assert sp.simplify(tan_alpha - closed) == 0
    assert sp.simplify(closed.subs(c, 0) - (s1 + r) / h) == 0
    return closed


if __name__ == "__main__":
    print("gravity line foot along the fall line:", gravity_line_foot())
    print("restoring moment about the tipping line:", moment_about_tipping_line())
    print("least stable caster support value:", least_stable_swivel())
    print("anti-tip: tan(alpha) =", anti_tip())
