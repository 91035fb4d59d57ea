"""Tests of stability.shimmy: the towed wheel against an independent Newton-Euler derivation,
closed-form stability conditions, the describing function against stick-slip simulation, and
the wheelchair caster chart."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import scipy.linalg
import sympy as sp
from numerics import assert_eigenvalues_match, eig_bounds

from stability.shimmy import TowedWheel, hurwitz_determinants
from stability.shimmy import describing as df

# ---------------------------------------------------------------------------
# independent derivation: Newton-Euler, linearised by the Jacobian of the
# first-order equations (the package's derivation uses Lagrange's equations,
# a multiplier and a series expansion)

m, Iz, a, b, k, C, sig, c, U = sp.symbols("m I a b k C sigma c U", positive=True)
PARAM_SYMBOLS = (m, Iz, a, b, k, C, sig, c, U)


@functools.cache
def newton_euler_polynomial(rigid_pivot: bool, rigid_tire: bool):
    """Monic characteristic polynomial coefficients (functions of the parameters) by Newton-Euler."""
    y, yd, p, pd, al = sp.symbols("y yd p pd al")
    ydd, pdd, Rx, F = sp.symbols("ydd pdd Rx F")
    L = a + b
    if rigid_pivot:
        y_, yd_, ydd_ = 0, 0, 0
    else:
        y_, yd_, ydd_ = y, yd, ydd
    # c.g. G = (U t - b cos p, y - b sin p); its acceleration with p_dot = pd, p_ddot = pdd
    aGx = b * (sp.cos(p) * pd**2 + sp.sin(p) * pdd)
    aGy = ydd_ + b * (sp.sin(p) * pd**2 - sp.cos(p) * pdd)
    n = (-sp.sin(p), sp.cos(p))
    # contact velocity: v_C = (U + L sin p pd, yd - L cos p pd); slip velocity across the wheel
    vCn = n[0] * (U + L * sp.sin(p) * pd) + n[1] * (yd_ - L * sp.cos(p) * pd)
    Fpiv_y = -k * y_ if not rigid_pivot else sp.Symbol("Ry")  # rigid pivot: unknown reaction
    Fx = Rx + F * n[0]
    Fy = Fpiv_y + F * n[1]
    # moments about G (z up): r x F with r_P = b e, r_C = -a e
    e = (sp.cos(p), sp.sin(p))
    Mz = (b * e[0] * Fpiv_y - b * e[1] * Rx) + (-a) * (e[0] * F * n[1] - e[1] * F * n[0]) - c * pd
    eqs = [m * aGx - Fx, m * aGy - Fy, Iz * pdd - Mz]
    unknowns = [Rx, pdd] + ([sp.Symbol("Ry")] if rigid_pivot else [ydd])
    if rigid_tire:
        if rigid_pivot:  # first-order: L pd = -U sin p from vCn = 0
            return [sp.Integer(1), sp.diff(sp.solve(vCn, pd)[0], p).subs(p, 0) * -1]
        ydot = sp.solve(vCn, yd)[0]                      # constraint gives y_dot
        vdot = (sp.diff(vCn, p) * pd + sp.diff(vCn, yd) * ydd + sp.diff(vCn, pd) * pdd).subs(yd, ydot)
        sol = solve_linear(eqs + [vdot], unknowns + [F])
        x, f = [y, p, pd], [ydot, pd, sol[pdd]]
    else:
        eqs = [eq.subs(F, C * al) for eq in eqs]
        sol = solve_linear(eqs, unknowns)
        aldot = (-vCn - U * al) / sig
        if rigid_pivot:
            x, f = [p, pd, al], [pd, sol[pdd], aldot]
        else:
            x, f = [y, p, yd, pd, al], [yd, pd, sol[ydd], sol[pdd], aldot]
    zero = {v: 0 for v in x}
    J = sp.Matrix([[sp.diff(fi, xj).subs(zero) for xj in x] for fi in f])
    s = sp.Symbol("s")
    poly = sp.Poly(sp.expand((s * sp.eye(len(x)) - J).det(method="berkowitz")), s)
    return poly.all_coeffs()


def solve_linear(eqs, unknowns):
    """Solve equations linear in ``unknowns`` (Cramer's rule through sympy's LU)."""
    M, rhs = sp.linear_eq_to_matrix(eqs, unknowns)
    return dict(zip(unknowns, M.LUsolve(rhs), strict=True))


def wheel_from(vals, rigid_pivot, rigid_tire):
    mass, inertia, a_, b_, k_, C_, s_, c_ = vals
    return TowedWheel(mass=mass, inertia=inertia, contact_behind_cm=a_, pivot_ahead_of_cm=b_,
                      lateral_stiffness=math.inf if rigid_pivot else k_,
                      cornering_stiffness=None if rigid_tire else C_,
                      relaxation_length=None if rigid_tire else s_, pin_damping=c_)


PARAMETER_SETS = [
    (1.2, 0.016, 0.022, 0.058, 5e4, 1500.0, 0.02, 0.0),
    (1.2, 0.016, -0.02, 0.058, 2e4, 1500.0, 0.05, 0.03),
    (30.0, 1.5, 0.05, 0.30, 2e5, 8e4, 0.4, 20.0),     # an aircraft-nose-gear-like wheel
    (0.5, 0.002, 0.01, 0.02, 1e4, 400.0, 0.015, 0.001),
]
CASES = [(rp, rt) for rp in (False, True) for rt in (False, True)]


@pytest.mark.parametrize("rigid_pivot,rigid_tire", CASES)
def test_characteristic_polynomial_matches_newton_euler(rigid_pivot, rigid_tire):
    expected = newton_euler_polynomial(rigid_pivot, rigid_tire)
    f = sp.lambdify(PARAM_SYMBOLS, expected)
    for vals in PARAMETER_SETS:
        w = wheel_from(vals, rigid_pivot, rigid_tire)
        for speed in (0.3, 1.7):
            got = w.characteristic_polynomial(speed)
            ref = np.array(f(*vals, speed), dtype=float)
            # error model: rounding of the generated coefficients against sympy's, a few ulp (observed 4.2e-16)
            np.testing.assert_allclose(got / got[0], ref / ref[0], rtol=1e-13, atol=0)
            # and the state matrix has those roots: compare the monic polynomial of A; error model: np.poly rebuilds
            # the coefficients from LAPACK eigenvalues, each within n eps ||A|| kappa, times the products of the
            # others (observed 1.1e-14 relative, 4e-15 of the largest coefficient): margins 90 and 250
            A, _ = w.state_matrix(speed)
            np.testing.assert_allclose(np.poly(A), ref / ref[0], rtol=1e-12,
                                       atol=1e-12 * np.abs(ref / ref[0]).max())


def test_rigid_caster_first_order_eigenvalue():
    # rigid pivot, rigid tire: L psi_dot = -U psi, eigenvalue -U/L for any mass and damping
    w = TowedWheel(mass=2.0, inertia=0.1, contact_behind_cm=0.03, pivot_ahead_of_cm=0.05, pin_damping=3.0)
    speeds = np.array([0.2, 1.0, 4.0])
    np.testing.assert_allclose(w.eigenvalues(speeds)[:, 0], -speeds / 0.08, rtol=1e-14)   # rounding (observed 0)
    assert w.routh_hurwitz(1.0).stable
    # a negative trail is refused (it is not a caster)
    with pytest.raises(ValueError, match="pivot_ahead_of_cm"):
        TowedWheel(mass=2.0, inertia=0.1, contact_behind_cm=0.03, pivot_ahead_of_cm=-0.05)


def test_relaxation_wheel_rigid_pivot_hurwitz_condition():
    # characteristic J sigma s^3 + (J U + c sigma) s^2 + (c U + C L^2) s + C L U, J = I + m b^2:
    # stable iff (J U + c sigma)(c U + C L^2) > J sigma C L U; with c = 0 iff L > sigma (any speed)
    mass, inertia, a_, b_, C_ = 1.2, 0.016, 0.022, 0.058, 1500.0
    L, J = a_ + b_, inertia + mass * b_**2
    w = TowedWheel(mass=mass, inertia=inertia, contact_behind_cm=a_, pivot_ahead_of_cm=b_,
                   cornering_stiffness=C_, relaxation_length=0.05)
    for speed in (0.5, 2.0):
        hb = w.hopf_boundary("relaxation_length", np.linspace(0.01, 0.3, 30), speed)
        np.testing.assert_allclose(hb.crossings[0], [L], rtol=1e-10)     # bisection bracket: brentq's rtol 1e-12 on the boundary (observed <= 5.8e-16 relative), x100
        assert hb.destabilising[0].tolist() == [True]
    # with damping: the two roots of J c U^2 + (J C L^2 + c^2 sigma - J sigma C L) U + c sigma C L^2 = 0
    c_, s_ = 0.01, 0.12
    wd = w.replace(pin_damping=c_, relaxation_length=s_)
    roots = np.sort(np.roots([J * c_, J * C_ * L**2 + c_**2 * s_ - J * s_ * C_ * L, c_ * s_ * C_ * L**2]).real)
    hb = wd.hopf_boundary("speed", np.geomspace(0.01, 1e4, 400))
    # error model: bisection bracket: brentq's rtol 1e-12 on the boundary (observed <= 5.8e-16 relative), x100; numpy.roots of the quadratic, a few ulp
    np.testing.assert_allclose(hb.crossings[0], roots, rtol=1e-10)
    assert hb.destabilising[0].tolist() == [True, False]
    mid = roots.mean()
    assert not wd.routh_hurwitz(mid).stable and wd.oscillatory_abscissa(mid) > 0
    assert wd.routh_hurwitz(roots[0] / 2).stable and wd.routh_hurwitz(2 * roots[1]).stable


def test_rigid_tire_compliant_pivot_closed_form():
    # (I + m a^2) s^3 + (m a U + c) s^2 + k L^2 s + k L U: stable iff c L > U (I - m a b);
    # at the boundary w^2 = k L^2 / (I + m a^2)
    mass, inertia, a_, b_, k_ = 1.2, 0.016, 0.022, 0.058, 5e4
    L = a_ + b_
    w = TowedWheel(mass=mass, inertia=inertia, contact_behind_cm=a_, pivot_ahead_of_cm=b_, lateral_stiffness=k_)
    speeds = [0.5, 1.0, 3.0]
    hb = w.hopf_boundary("pin_damping", np.linspace(0.0, 1.0, 50), speeds)
    for u, crit, freq in zip(speeds, hb.crossings, hb.frequencies, strict=True):
        # error model: bisection bracket: brentq's rtol 1e-12 on the boundary (observed <= 5.8e-16 relative), x100; the frequency is the boundary eigenvalue's (rounding, observed 4.1e-16)
        np.testing.assert_allclose(crit, [u * (inertia - mass * a_ * b_) / L], rtol=1e-10)
        np.testing.assert_allclose(freq, [math.sqrt(k_ * L**2 / (inertia + mass * a_**2))], rtol=1e-10)
    # the centre-of-percussion condition: without damping stable iff I < m a b
    inertia_crit = mass * a_ * b_
    hb = w.hopf_boundary("inertia", np.linspace(0.2, 2.0, 20) * inertia_crit, [1.0])
    np.testing.assert_allclose(hb.crossings[0], [inertia_crit], rtol=1e-10)    # bisection bracket: brentq's rtol 1e-12 on the boundary (observed <= 5.8e-16 relative), x100


def test_time_scaling_invariant():
    # U -> lam U, k -> lam^2 k, C -> lam^2 C, c -> lam c multiplies every eigenvalue by lam
    lam = 2.5
    for rigid_pivot, rigid_tire in CASES:
        w = wheel_from(PARAMETER_SETS[1], rigid_pivot, rigid_tire)
        kw = {"pin_damping": lam * w.pin_damping}
        if not rigid_pivot:
            kw["lateral_stiffness"] = lam**2 * w.lateral_stiffness
        if not rigid_tire:
            kw["cornering_stiffness"] = lam**2 * w.cornering_stiffness
        w2 = w.replace(**kw)
        A1, A2 = w.state_matrix(0.8)[0], w2.state_matrix(lam * 0.8)[0]
        # two matrices similar to A2 = lam A1 up to the rounding of the scaled parameters (a few eps
        # relative, inside n eps ||A|| kappa_i): each side's eigenvalue bound, the first scaled by lam
        assert_eigenvalues_match(w2.eigenvalues(lam * 0.8), lam * w.eigenvalues(0.8), A2,
                                 tol_b=lam * eig_bounds(w.eigenvalues(0.8), A1), what=str(kw))


def test_routh_hurwitz_agrees_with_eigenvalues():
    rng = np.random.default_rng(13)
    for _ in range(40):
        vals = (rng.uniform(0.3, 3), rng.uniform(0.002, 0.05), rng.uniform(-0.02, 0.05), rng.uniform(0.03, 0.08),
                10 ** rng.uniform(3.5, 5.5), rng.uniform(300, 3000), rng.uniform(0.005, 0.15),
                rng.uniform(0, 0.05))
        w = wheel_from(vals, False, False)
        speed = rng.uniform(0.2, 4)
        ev = w.eigenvalues(speed)
        rh = w.routh_hurwitz(speed)
        margin = ev.real.max() / np.abs(ev).max()
        if abs(margin) > 1e-6:  # well away from the boundary
            assert rh.stable == (margin < 0)
    # Orlando: Delta_(n-1) of (s^2 + 4)(s + 1) is zero, of (s^2 + s + 4)(s + 1) positive
    # exact: np.poly gives the integer coefficients [1, 1, 4, 4] exactly and the determinant is 0 (observed 0)
    assert abs(hurwitz_determinants(np.poly([2j, -2j, -1]).real)[-2]) < 1e-12
    assert hurwitz_determinants(np.polymul([1, 1, 4], [1, 1]))[-2] > 0


def test_state_space_and_vectorised_eigenvalues():
    w = wheel_from(PARAMETER_SETS[0], False, False)
    sys_ = w.state_space(1.2)
    assert list(sys_.state_labels) == ["y", "psi", "y_dot", "psi_dot", "alpha"]
    assert list(sys_.input_labels) == ["pin_torque"]
    A = w.state_matrix(1.2)[0]
    np.testing.assert_array_equal(sys_.A, A)
    # eigenvalues of the same matrix from two calls (one batched): within n eps ||A|| kappa_i each
    assert_eigenvalues_match(np.linalg.eigvals(sys_.A), w.eigenvalues(1.2), A, A)
    many = w.eigenvalues([0.5, 1.2])
    assert many.shape == (2, 5)
    assert_eigenvalues_match(many[1], w.eigenvalues(1.2), A, A)


@pytest.mark.parametrize("kwargs,name", [
    ({"mass": 0.0}, "mass"), ({"inertia": -1.0}, "inertia"), ({"lateral_stiffness": 0.0}, "lateral_stiffness"),
    ({"cornering_stiffness": 100.0}, "relaxation_length"), ({"pin_damping": -0.1}, "pin_damping"),
    ({"pin_friction": float("nan")}, "pin_friction"), ({"mass": True}, "mass"),
])
def test_validation_names_parameter(kwargs, name):
    base = dict(mass=1.0, inertia=0.01, contact_behind_cm=0.02, pivot_ahead_of_cm=0.05)
    with pytest.raises(ValueError, match=rf"{name}=.*valid range"):
        TowedWheel(**{**base, **kwargs})
    w = TowedWheel(**base)
    with pytest.raises(ValueError, match="speed=-1.0 is invalid"):
        w.eigenvalues([1.0, -1.0])
    with pytest.raises(ValueError, match="no oscillatory mode"):
        w.hopf_boundary("speed", [0.1, 1.0])


# ---------------------------------------------------------------------------
# Coulomb friction: describing function vs stick-slip simulation

def test_simulation_without_friction_is_the_matrix_exponential():
    w = wheel_from(PARAMETER_SETS[1], False, False)
    x0 = df.shimmy_mode_state(w, 1.0, 0.05)
    sim = df.simulate(w, 1.0, x0, 0.3)
    A, _ = w.state_matrix(1.0)
    # error model: DOP853's local error control (rtol 1e-9, atol 1e-12) over 0.3 s: a global error of a few rtol
    # (observed 1.9e-11 relative, 1.3e-10 of |x0|); rtol 100 x the solver's (was 1e-6), atol margin 75
    np.testing.assert_allclose(sim.x[-1], scipy.linalg.expm(A * sim.t[-1]) @ x0, rtol=1e-7,
                               atol=1e-8 * np.abs(x0).max())


@pytest.mark.parametrize("friction, amplitude, omega", [(0.1, 0.05, 80.0), (0.35, 0.2, 12.0), (0.02, 0.01, 300.0)])
def test_equivalent_damping_dissipates_the_coulomb_energy_per_cycle(friction, amplitude, omega):
    """Energy balance, not the formula: over one cycle of psi = A sin(w t), Coulomb friction M_f sign(psi') dissipates
    the quadrature of M_f |psi'| dt, and a viscous damper c dissipates pi c A^2 w; the equivalent damping makes them
    equal.  Quadrature on 2^16 + 1 points (composite Simpson on a smooth |cos|, split at its kinks): error below
    1e-12 relative (observed ~1e-16), bound 1e-10."""
    from scipy.integrate import simpson

    period = 2.0 * math.pi / omega
    pieces = (0.0, period / 4, 3 * period / 4, period)        # |cos| is smooth between its zeros
    coulomb = 0.0
    for a, b in zip(pieces[:-1], pieces[1:], strict=True):
        t = np.linspace(a, b, 2**16 + 1)
        coulomb += simpson(friction * np.abs(amplitude * omega * np.cos(omega * t)), x=t)
    c_eq = df.equivalent_damping(friction, amplitude, omega)
    # error model: Simpson's truncation negligible; rounding of 2^16-term sums (numpy's pairwise summation,
    # ~log2(n) eps = 3.6e-15; observed 2e-16): 1e-12, margin 280 over that bound
    assert math.pi * c_eq * amplitude**2 * omega == pytest.approx(coulomb, rel=1e-12)


@pytest.mark.parametrize("rigid_pivot", [True, False])
def test_describing_function_threshold_matches_simulation(rigid_pivot):
    # unstable without friction: rigid pivot with sigma > trail, or a short-trail caster on a compliant pivot
    vals = (1.2, 0.016, 0.022 if rigid_pivot else -0.02, 0.058, 5e4, 1500.0, 0.1 if rigid_pivot else 0.02, 0.0)
    w = wheel_from(vals, rigid_pivot, False).replace(pin_friction=0.1)
    for speed in (0.5, 2.0):
        c_crit, omega = df.critical_damping(w, speed)
        assert c_crit > 0 and omega > 0
        a_star = 4 * w.pin_friction / (math.pi * omega * c_crit)      # DF amplitude of the limit cycle
        lo, hi = df.simulated_threshold(w, speed, a_star / 2, a_star * 2, iterations=9)
        assert hi / lo < 1.01
        # the stated tolerance: the simulated threshold lies within 3 % of the describing function. error model: the
        # describing function keeps the first harmonic only (the next order: the square wave's third harmonic) and
        # the bisection bracket is 0.27 %; observed 0.14-0.94 %
        assert abs(math.sqrt(lo * hi) / a_star - 1) < 0.03
        # consistency: the friction that suppresses shimmy at a_star is the wheel's own friction
        est = df.suppressing_friction(w, speed, a_star)
        # error model: rounding: the describing function inverted in closed form, a few ulp (observed 1.4e-16)
        assert est.friction == pytest.approx(w.pin_friction, rel=1e-13)


def test_friction_sticks_a_stable_wheel_and_no_friction_needed():
    w = wheel_from(PARAMETER_SETS[0], True, False).replace(pin_friction=0.5)   # trail 0.08 > sigma 0.02
    assert df.suppressing_friction(w, 1.0, math.radians(5)).friction == 0.0
    sim = df.simulate(w, 1.0, df.shimmy_mode_state(w, 1.0, 0.01), 0.5)
    assert sim.stuck.any()
    assert np.abs(sim.psi[-1]) <= 0.01


# ---------------------------------------------------------------------------
# the wheelchair caster

def test_caster_wheel_from_chair():
    from stability.chair import preset
    from stability.shimmy.chair import CasterCompliance, caster_wheel

    c = preset("ej-premier")
    w = caster_wheel(c, CasterCompliance(relaxation_length=0.03, lateral_stiffness=7e4))
    # error model: rounding of the same products and differences (observed 0)
    assert w.inertia == pytest.approx(0.02 - 1.2 * 0.058**2, rel=1e-12)
    assert w.trail == pytest.approx(0.08, rel=1e-12) and w.pivot_ahead_of_cm == 0.058
    assert (w.relaxation_length, w.lateral_stiffness, w.pin_friction) == (0.03, 7e4, 0.1)
    # thesis eq 8-3: about 25 N/deg = 1432 N/rad for an ER caster near 215 N
    assert 1200 < w.cornering_stiffness < 1800
    with pytest.raises(ValueError, match="trail=0.0 is invalid"):
        caster_wheel(c.replace(trail=0.0))
    with pytest.raises(ValueError, match="relaxation_length=-0.01 is invalid"):
        CasterCompliance(relaxation_length=-0.01)


def test_critical_trail_tends_to_relaxation_length_for_a_stiff_pin():
    # rigid pivot, no damping: shimmy iff trail < sigma (test_relaxation_wheel_rigid_pivot_hurwitz_condition)
    from stability.chair import preset
    from stability.shimmy.chair import CasterCompliance, critical_trail, friction_trail

    c = preset("ej-premier")
    stiff = CasterCompliance(relaxation_length=0.03, lateral_stiffness=1e9)
    # error model: the pin's compliance, first order in 1/k: 4.7e-5 relative at k = 1e9 N/m (4.7e-4 at 1e8,
    # 4.7e-6 at 1e10); margin 100
    assert critical_trail(c, 1.0, stiff) == pytest.approx(0.03, rel=100 * 4.7e-5)
    nominal = CasterCompliance()
    crit = [critical_trail(c, u, nominal) for u in (0.5, 2.0)]
    assert crit[0] == pytest.approx(crit[1], rel=1e-6)           # no viscous damping: speed-independent
    held = [friction_trail(c, u, math.radians(5), nominal) for u in (0.5, 2.0)]
    assert held[0] < held[1] < crit[0]                            # friction helps, less so at speed


def test_friction_trail_is_the_largest_root_over_the_whole_trail_grid():
    """The friction trail is the largest trail where the friction needed (describing function) equals the pin's
    own: recomputed here from every grid trail's excess, a root per sign change (Brent in its grid step), the
    largest kept.  The library searches from the grid's top down and stops at the highest sign change; the power
    chair at 2 m/s has several sign changes (a band), so the skipped part of the grid holds roots too."""
    from scipy.optimize import brentq

    from stability.chair import preset
    from stability.shimmy.chair import CasterCompliance, _trail_grid, caster_wheel, friction_trail

    c, speed, amplitude, comp = preset("power-fwd"), 2.0, math.radians(5), CasterCompliance()

    def excess(trail):
        w = caster_wheel(c.replace(trail=trail), comp)
        return min(df.suppressing_friction(w, speed, amplitude).friction, 1e3) - w.pin_friction

    grid = _trail_grid(c)
    values = np.array([excess(t) for t in grid])
    steps = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0]
    assert len(steps) >= 2
    roots = [brentq(excess, grid[i], grid[i + 1], xtol=1e-7) for i in steps]
    assert friction_trail(c, speed, amplitude, comp) == max(roots)      # the same Brent call: equal to the bit


def test_cli_json_and_errors(capsys):
    import json

    from stability.shimmy.__main__ import main

    assert main(["--chair", "revised", "--speeds", "1,2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["trail_m"] == 0.06 and len(data["critical_trail_m"]) == 2
    assert "estimates" in data["note"]
    assert main(["--relaxation-length", "-1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--relaxation-length -1 is invalid" in err[0]


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd"])
def test_the_trail_charts_compliance_band_is_drawn_where_the_legend_and_caption_say(name):
    """The compliance range's boundary band (issue 35: its legend entry named a hatched band nobody could see,
    and the caption told the reader to read it): each edge is a line inside the axes, or the legend says it lies
    above or below the chart and nothing is drawn; the caption's band words follow the chart's own edges (the
    E&J's highest edge is infinite at the default compliance: no trail is shimmy-free at one corner)."""
    import matplotlib.pyplot as plt

    from stability.chair import preset
    from stability.shimmy.band import CasterCompliance
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.plots import plot_trail_chart, trail_chart_caption

    trails = np.linspace(0.02, 0.12, 6)
    chart = trail_chart(preset(name), trails, [0.5, 1.5, 3.0], CasterCompliance(), math.radians(5))
    fig, ax = plt.subplots()
    plot_trail_chart(chart, ax)
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    lo_y, hi_y = ax.get_ylim()
    for edge, words in ((0, "lowest"), (1, "highest")):
        t = chart.critical_trail_range[edge] * 100
        (label,) = [k for k in lines if f"{words} over the compliance range" in k]
        if np.all(t > trails.max() * 100):
            assert label.endswith("above the chart") and len(lines[label].get_xdata()) == 0
        elif np.all(t < trails.min() * 100):
            assert label.endswith("below the chart") and len(lines[label].get_xdata()) == 0
        else:
            y = np.asarray(lines[label].get_ydata(), dtype=float)
            assert np.all((lo_y <= y) & (y <= hi_y)) and np.any((t > lo_y) & (t < hi_y))
    caption = trail_chart_caption(chart)
    hi = chart.critical_trail_range[1]
    assert ("above every trail shown" in caption) == bool(np.all(hi > trails.max()))
    assert "hatched" not in caption
    plt.close(fig)
