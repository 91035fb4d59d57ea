"""The driver in the loop (stability.driver): the human-limited speed against closed forms and an exact-delay
simulation of the delayed loop.

Independent statements used:

- Delayed proportional control of a one-state divergence ``x' = lam x - k x(t - tau)``: the best achievable
  rightmost root is the double root ``s* = lam - 1/tau`` at ``k* = exp(lam tau - 1) / tau`` (from ``f(s) = s - lam +
  k exp(-s tau) = 0`` and ``f'(s) = 0``), so the loop can be stabilised exactly while ``lam tau < 1``
  (Stepan & Kollar 2000).
- The Pade approximant against python-control's ``control.pade`` and against ``exp(-j w tau)`` itself.
- The delayed loop of the full linear chair simulated with the exact delay (a delay line of whole steps, the
  plant discretised exactly with a zero-order hold), not through the Pade approximant.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numerics import assert_eigenvalues_match
from scipy.linalg import expm

from stability.chair import preset
from stability.driver import Driver, human_limit, operator_fit, yaw_moment_limit
from stability.driver.linear import (
    SPEED_TOL_M_S,
    abscissa,
    best_gains,
    closed_loop_matrix,
    divergence_rate,
    heading_plant,
    pade,
)


@pytest.mark.parametrize(("lam", "tau"), [(1.0, 0.3), (2.0, 0.3), (3.0, 0.3), (1.0, 0.8), (-0.5, 0.4)])
def test_best_gain_of_a_one_state_divergence_is_the_double_root(lam, tau):
    """Nelder-Mead on a double-root optimum: observed |error| <= 1.2e-6 1/s in the abscissa and 1e-6 relative in
    the gain; asserted with a margin of about 100."""
    A, B, C = np.array([[lam]]), np.array([[1.0]]), np.array([[1.0]])
    g, a = best_gains(A, B, C, tau, log_bounds=((-3.0, 3.0),))
    # error model: the optimiser's stopping at a non-smooth (double-root) optimum: observed 1.8e-6 1/s and 1.5e-6
    # relative at most over the cases, so ~60x
    assert a == pytest.approx(lam - 1.0 / tau, abs=1e-4)
    assert g[0] == pytest.approx(math.exp(lam * tau - 1.0) / tau, rel=1e-4)
    assert (a < 0) == (lam * tau < 1)


def test_pade_is_python_controls_and_the_delay():
    """The state-space Pade approximant has python-control's transfer function, and matches exp(-j w tau) to
    the approximant's own truncation error at low frequency (order 8 at w tau <= 1: below 1e-14)."""
    import control

    tau = 0.3
    Ad, Bd, Cd, Dd = pade(tau, 8)
    num, den = control.pade(tau, 8)
    w = np.logspace(-2, 1.5, 50)
    ours = np.array([(Cd @ np.linalg.solve(1j * x * np.eye(8) - Ad, Bd) + Dd)[0, 0] for x in w])
    theirs = np.polyval(num, 1j * w) / np.polyval(den, 1j * w)
    # error model: rounding: one rational function by a solve and by polyval (observed 2.9e-15), x300
    assert np.max(np.abs(ours - theirs)) < 1e-12
    low = w * tau <= 1
    # error model: the approximant's truncation (below 1e-14 at w tau <= 1) plus rounding (observed 1.2e-15)
    assert np.max(np.abs(ours[low] - np.exp(-1j * w[low] * tau))) < 1e-12
    assert np.allclose(np.abs(ours), 1.0, atol=1e-9)             # rounding: equivalent arithmetic, a few ulp (observed 1.8e-15); all-pass
    with pytest.raises(ValueError, match="tau"):
        pade(0.0)


def test_pade_copies_are_the_callers_and_the_cached_matrices_are_read_only():
    """The cache behind pade (a limit search closes thousands of loops with one delay) cannot be changed through
    what it hands out: a default result is a fresh writeable copy, the shared one (copy=False) is read-only."""
    Ad, *_ = pade(0.3, 8)
    Ad[0, 0] += 1.0
    shared = pade(0.3, 8, copy=False)
    assert shared[0][0, 0] == Ad[0, 0] - 1.0 and not any(a.flags.writeable for a in shared)
    with pytest.raises(ValueError, match="read-only"):
        shared[1][0, 0] = 0.0
    with pytest.raises(ValueError, match="order"):
        pade(0.3, 0, copy=False)


def test_closed_loop_without_delay_effect_at_zero_gain_is_the_plant():
    """At zero gains the closed loop's eigenvalues are the plant's and the Pade block's own poles."""
    A, B, C = heading_plant(preset("ej-premier"), 1.0)
    M = closed_loop_matrix(A, B, C, np.zeros(2), 0.3)
    ev = np.linalg.eigvals(M)
    expected = np.concatenate([np.linalg.eigvals(A), np.linalg.eigvals(pade(0.3)[0])])
    # error model: n eps ||M|| kappa_i of each eigenvalue (tests/numerics.py; observed 8.0e-12); M is block
    # triangular at zero gain, so its eigenvalues are exactly the blocks'
    assert_eigenvalues_match(ev, expected, M, M, what="zero-gain closed loop")


def test_divergence_rule_speed_is_where_lambda_tau_is_one():
    """lambda(U_rule) tau = 1 to the search's speed tolerance times the rate's slope (about 2 1/s per m/s).

    Error model: bisection bracket: SPEED_TOL_M_S x slope x tau (observed 0.03 and 0.23 of it; asserted 20 times
    it, ~90x the larger observed)."""
    from stability.driver.linear import rule_speed

    c = preset("ej-premier")
    for tau in (0.3, 0.4):
        speed, side = rule_speed(c, tau)
        h = type("H", (), {"rule_speed_m_s": speed, "rule_side": side})
        assert h.rule_side == "="
        # error model: bisection bracket (docstring)
        assert divergence_rate(c, h.rule_speed_m_s) * tau == pytest.approx(1.0, abs=20 * SPEED_TOL_M_S * 2.0 * tau)
        assert divergence_rate(c, h.rule_speed_m_s - 0.05) * tau < 1 < divergence_rate(c, h.rule_speed_m_s + 0.05) * tau


def _simulate_delayed_loop(A, B, C, gains, tau, t_end=12.0, dt=1e-3):
    """The delayed loop with the exact delay: ZOH plant, the operator's output delayed by tau/dt whole steps."""
    n = A.shape[0]
    Phi = expm(A * dt)
    Gam = np.linalg.solve(A, (Phi - np.eye(n))) @ B if abs(np.linalg.det(A)) > 1e-12 else \
        sum(np.linalg.matrix_power(A * dt, k) / math.factorial(k + 1) for k in range(20)) @ B * dt
    steps, lag = int(round(t_end / dt)), int(round(tau / dt))
    x = np.zeros(n)
    x[1] = 0.01                               # a small yaw-rate disturbance
    buf = np.zeros(lag)
    norms = np.empty(steps)
    for k in range(steps):
        u = -buf[k % lag]
        buf[k % lag] = float(gains @ C @ x)
        x = Phi @ x + Gam[:, 0] * u
        norms[k] = np.linalg.norm(x)
    return np.arange(1, steps + 1) * dt, norms


def _characteristic(s, A, B, C, gains, tau):
    """det(s I - A + exp(-s tau) B K C): the exact delayed loop's characteristic function."""
    return np.linalg.det(s * np.eye(A.shape[0]) - A + np.exp(-s * tau) * (B @ (gains @ C)[None, :]))


def _newton(s, *args):
    for _ in range(60):
        h = 1e-6 * (1 + abs(s))
        d = (_characteristic(s + h, *args) - _characteristic(s - h, *args)) / (2 * h)
        step = _characteristic(s, *args) / d
        s -= step
        if abs(step) < 1e-13 * (1 + abs(s)):        # converged: a step of ~450 eps, rounding's level
            break
    return s


def _rhp_zeros(*args, radius=200.0, n=6000):
    """Zeros of the exact characteristic function in the right half-disk (argument principle; the loop is
    retarded, so its right-half-plane roots are bounded and a large half-disk holds them all)."""
    w = radius * np.sinh(np.linspace(-1, 1, n) * np.arcsinh(radius)) / radius     # dense near the origin
    up = 1e-9 + 1j * w
    back = radius * np.exp(1j * np.linspace(np.pi / 2, -np.pi / 2, n))
    phase = np.unwrap(np.angle([_characteristic(x, *args) for x in np.concatenate([up, back])]))
    return -round((phase[-1] - phase[0]) / (2 * np.pi))      # the contour runs clockwise


@pytest.mark.parametrize("name", ["ej-premier", pytest.param("power-fwd", marks=pytest.mark.slow)])
def test_loop_limit_against_the_exact_delay(name):
    """Below the loop limit the best gains hold the chair, above it they cannot, checked without the Pade
    approximant: (1) the exact delayed characteristic function has no right-half-plane zero below and at least
    one above (argument principle); (2) the Pade loop's rightmost roots, refined by Newton on the exact
    characteristic function, move by < 5e-9 (observed 4.5e-11: Pade [8/8] is exact to ~1e-14 at |s tau| < 0.3);
    (3) a simulation with the exact delay (a delay line of whole 1 ms steps) decays below and grows above."""
    c = preset(name)
    tau = 0.3
    h = human_limit(c, Driver(tau))
    assert h.loop_side == "=" and h.pade_error_m_s < 0.01
    for factor in (0.85, 1.15):
        u = factor * h.loop_speed_m_s
        fit = operator_fit(c, u, Driver(tau))
        A, B, C = heading_plant(c, u)
        g = np.array([fit.kp_N_m_per_rad, fit.kd_N_m_s_per_rad])
        args = (A, B, C, g, tau)
        assert (_rhp_zeros(*args) == 0) == (factor < 1)
        ev = np.linalg.eigvals(closed_loop_matrix(A, B, C, g, tau))
        for root in ev[np.argsort(-ev.real)][:3]:
            # error model: the approximant's truncation and rounding (docstring; observed 4.5e-11), x100
            assert abs(_newton(root, *args) - root) < 5e-9
        t, norms = _simulate_delayed_loop(A, B, C, g, tau)
        late = t > t[-1] / 2
        growth = float(np.polyfit(t[late], np.log(norms[late]), 1)[0])
        assert (growth < 0) == (factor < 1), (factor, growth)
        assert fit.holds == (factor < 1)


def test_the_loop_scan_searches_only_where_the_last_gains_no_longer_hold():
    """The delayed loop's grid scan skips the gain search at a speed where the last gains found still make the loop
    stable (one eigenvalue problem: the best gains' abscissa is at most theirs, so the limit lies higher).  Against
    the scan that searches at every speed: each skipped speed is one where the search finds the loop stable, and
    the limit is the same to the bit (the bisection starts from the same crossing step and the same gains)."""
    from stability.driver.linear import _GRID, _first_crossing, _LoopAbscissa

    c, tau = preset("ej-premier"), 0.3

    def plant(u):
        return heading_plant(c, u)

    def recorded(f, log):
        def g(u):
            log[u] = f(u)
            return log[u]
        return g

    every, short = {}, {}
    full = _first_crossing(recorded(_LoopAbscissa(plant, tau, 8), every), _GRID)
    loop = _LoopAbscissa(plant, tau, 8)
    quick = _first_crossing(recorded(loop, short), _GRID, loop.holds)
    assert quick == full and full[1] == "="
    skipped = [float(u) for u in _GRID if float(u) in every and float(u) not in short]
    assert len(skipped) >= 2 and all(every[u] < 0 for u in skipped)     # observed: 0.35 and 0.59 m/s


def test_slower_driver_lower_speed_and_a_bound_is_a_bound():
    """The rule's speed falls as the reaction time grows (the divergence rate rises with speed); a stable chair's
    limit is the searched range's end, a bound."""
    from stability.driver.linear import rule_speed

    c = preset("revised")
    speeds = [rule_speed(c, t)[0] for t in (0.2, 0.3, 0.45)]
    assert speeds[0] > speeds[1] > speeds[2]
    front = rule_speed(preset("ej-premier-front-caster"), 0.3)     # stable: no limit in the range
    assert front == (6.0, ">")


@pytest.mark.slow       # three delayed-loop searches and a stable chair's full scan: about 5 s of CPU
def test_slower_driver_lower_loop_speed_and_a_bound_is_a_bound():
    c = preset("revised")
    speeds = [human_limit(c, Driver(t)).loop_speed_m_s for t in (0.2, 0.3, 0.45)]
    assert speeds[0] > speeds[1] > speeds[2]
    front = human_limit(preset("ej-premier-front-caster"), Driver(0.3))
    assert front.rule_side == ">" and front.loop_side == ">" and front.loop_speed_m_s == front.speed_range_m_s[1]


def test_driver_refuses_bad_values_naming_them():
    with pytest.raises(ValueError, match=r"reaction_time_s=5.0 is invalid; valid range: 0.05 to 2 s"):
        Driver(5.0)
    with pytest.raises(TypeError, match="reaction_time_s"):
        Driver("0.3")          # type: ignore[arg-type]
    with pytest.raises(ValueError, match="hand_force_N"):
        Driver(0.3, hand_force_N=-1.0)


def test_yaw_moment_limit_closed_form():
    """Manual: F (r_rim / R) (d1 + d2); power: T (d1 + d2) / r (docs/power-chair.md)."""
    from stability.settings import defaults as D

    c = preset("ej-premier")
    assert yaw_moment_limit(c, Driver(hand_force_N=50.0)) == pytest.approx(
        50.0 * D.HANDRIM_RADIUS / D.HANDRIM_WHEEL_RADIUS * (c.d1 + c.d2), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    p = preset("power-fwd")
    assert yaw_moment_limit(p, Driver()) == pytest.approx(D.TORQUE_LIMIT * (p.d1 + p.d2) / D.DRIVE_WHEEL_RADIUS, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_abscissa_batches():
    A, B, C = heading_plant(preset("ej-premier"), 0.75)
    g = np.array([[10.0, 5.0], [100.0, 20.0]])
    batch = abscissa(A, B, C, g, 0.3)
    one = [abscissa(A, B, C, g[i][None, :], 0.3)[0] for i in range(2)]
    assert np.allclose(batch, one, rtol=0, atol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_searchs_single_loop_is_the_batchs_and_a_kept_answer_is_the_searchs():
    """The search's one-gain abscissa is the batch's to the bit (the same matrix, the same LAPACK call), and
    :func:`best_gains` asked twice returns the uncached search's answer both times, in a fresh array each time
    (a caller changing its copy does not change the next answer)."""
    from stability.driver.loop import _Loop, _search_gains

    A, B, C = heading_plant(preset("ej-premier"), 1.3)
    loop = _Loop(A, B, C, 0.3, 8)
    rng = np.random.default_rng(45)
    for g in 10.0 ** rng.uniform([-1.0, -2.0], [4.5, 3.5], size=(50, 2)):
        assert loop.abscissa_one(g) == loop.abscissa(g[None, :])[0]
    bounds = ((-1.0, 4.5), (-2.0, 3.5))
    g0, a0 = _search_gains(loop, bounds, 21, None)
    g1, a1 = best_gains(A, B, C, 0.3)
    g1[:] = 0.0
    g2, a2 = best_gains(A, B, C, 0.3)
    assert a0 == a1 == a2 and g2.tolist() == g0.tolist()


def test_with_the_assist_the_driver_limit_is_the_assisted_loops_divergence(monkeypatch):
    """With the assist on, the divergence rule reads the assisted closed loop's slowest pole: power-fwd's default
    gyro design is Hurwitz at every schedule speed (its closed-loop matrix's spectrum, here through
    python-control's ``ss.poles``), so the driver's limit is a bound at the schedule's top ('>'); and where the
    slowest pole does cross 1/tau (a stand-in loop diverging at 2 U 1/s) the limit is the first schedule speed with
    2 U tau >= 1: for tau = 0.3 s, 2 U >= 3.33 1/s, U >= 1.67 m/s: 1.75 m/s on the 0.25 m/s grid."""
    import control

    from stability.assist import human
    from stability.assist.schedule import schedule

    c = preset("power-fwd")
    r = human.assisted_driver_limit(c, 0.3)
    s = schedule(c, np.asarray(human.ASSIST_SPEEDS), "gyro")
    for d, p in zip(s.designs, r.slowest_pole_1_s, strict=True):
        A = d.closed_loop_matrix()
        assert max(control.ss(A, np.zeros((A.shape[0], 1)), np.zeros((1, A.shape[0])), 0).poles().real) < 0
        assert p < 0
    assert r.side == ">" and r.speed_m_s == human.ASSIST_SPEEDS[-1] and "above 3 m/s" in r.sentence()
    monkeypatch.setattr(human, "closed_loop_poles", lambda d: np.array([2.0 * d.speed + 0j, -1.0 + 0j]))
    r2 = human.assisted_driver_limit(c, 0.3)
    assert r2.side == "=" and r2.speed_m_s == 1.75 and "up to 1.75 m/s (6.3 km/h)" in r2.sentence()
    with pytest.raises(ValueError, match="reaction_time"):
        human.assisted_driver_limit(c, 0.0)
