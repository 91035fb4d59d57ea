"""The independent checks behind the validation page, run when the site is built.

Each check computes a toolkit result and an independent reference (a number
printed in Collins 1987, a closed form, a transcription of program WCHAIR,
the Routh-Hurwitz criterion) and returns a :class:`Check` row. The page
``docs/validation-checks.md`` renders them with the ``stability-validation``
directive (``stability_validation.py``); a check that fails is shown as
failing and makes the build warn (so ``-W`` stops it). ``tests/test_docs_site.py``
runs the cheap ones in the default test suite too.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Check:
    """One row of the validation table."""

    name: str
    source: str
    reference: str
    computed: str
    criterion: str
    passed: bool


def _ej(**kw):
    import stability

    return stability.preset("ej-premier").replace(**kw)


def eq_8_2_to_8_5() -> Check:
    """Zero-width model with the thesis's 25 N/deg tires (chapter 8, 'Method Two')."""
    from stability import linear

    c = _ej(m=76.2, main_tire="linear:25", caster_tire="linear:25")
    zw = linear.zero_width(c)
    got = (zw.load_main, zw.load_caster, zw.understeer_coefficient, zw.critical_speed)
    ok = (abs(got[0] - 159) <= 1 and abs(got[1] - 215) <= 1 and abs(got[2] + 0.04) <= 0.002
          and abs(got[3] - 12) <= 0.5)
    return Check("Loads, understeer coefficient and locked-caster critical speed", "Collins 1987, eqs 8-2 to 8-5",
                 "W_f 159 N, W_r 215 N, k_us -0.04 rad, 12 m/s",
                 f"{got[0]:.1f} N, {got[1]:.1f} N, {got[2]:.4f} rad, {got[3]:.2f} m/s",
                 "printed digits (1 N, 0.002 rad, 0.5 m/s)", ok)


def figure_8_6() -> Check:
    """Locked casters: WCHAIR's stable-to-unstable transition between 11.25 and 12.5 m/s."""
    from stability import linear

    c = _ej(m=75.0)
    grid = np.linspace(5, 20, 61)
    cross = linear.critical_speeds(lambda U: linear.state_matrices(c, U, "thesis", "locked"), grid)
    u = cross[0].speed if len(cross) == 1 else float("nan")
    return Check("Locked-caster transition (thesis equations)", "Collins 1987, Figure 8-6",
                 "between 11.25 and 12.5 m/s", f"{u:.2f} m/s", "inside the bracket", 11.25 < u < 12.5)


def bicycle_closed_form() -> Check:
    """Locked casters, exact model = the zero-width characteristic equation 5-11 (coefficients eq 5-12)."""
    from stability import linear
    from stability.models.statics import static_stiffness

    c = _ej()
    st = static_stiffness(c)
    cf, cr = st["D"], st["A"]
    s1, s2, m, inertia = c.s1, c.caster_contact_distance, c.m, c.i_z
    worst = 0.0
    for u in (5.0, 12.0, 20.0, 40.0):
        a1 = (2 * cf + 2 * cr) / u
        a2 = m * u + (2 * cf * s1 - 2 * cr * s2) / u
        a3 = (2 * cf * s1 - 2 * cr * s2) / u
        a4 = (2 * cf * s1**2 + 2 * cr * s2**2) / u
        roots = np.roots([1, (a1 * inertia + a4 * m) / (inertia * m), (a1 * a4 - a2 * a3) / (inertia * m)])
        ours = np.linalg.eigvals(linear.state_matrices(c, u, "exact", "locked")[0])
        # each closed-form root against the nearest eigenvalue of the full-width model (a matching)
        worst = max(worst, max(float(np.min(np.abs(ours - r)) / max(abs(r), 1.0)) for r in roots))
    return Check("Full-width model with locked casters = two-degree-of-freedom bicycle",
                 "closed form, eqs 5-11 and 5-12", "eigenvalues of eq 5-11 at 5, 12, 20, 40 m/s",
                 f"largest relative difference {worst:.1e}", "< 1e-9 (rounding)", worst < 1e-9)


def locked_critical_speed() -> Check:
    """Full-width locked-caster critical speed = eq 5-15 of the zero-width model."""
    from stability import linear

    c = _ej()
    grid = np.linspace(1, 40, 200)
    cross = linear.critical_speeds(lambda U: linear.state_matrices(c, U, "exact", "locked"), grid)
    zw = linear.zero_width(c).critical_speed
    rel = abs(cross[0].speed - zw) / zw
    return Check("Locked-caster critical speed, full-width vs zero-width", "closed form, eq 5-15",
                 f"{zw:.4f} m/s (eq 5-15)", f"{cross[0].speed:.4f} m/s", "relative 1e-8", rel < 1e-8)


def reference_time() -> Check:
    """The reference case reaches 1 rad/s 'in slightly over 3 seconds' (WCHAIR's equations)."""
    import stability

    run = stability.run_simulation(_ej(), 0.75, stability.RunSpec(model="thesis", friction_law="kinetic"))
    t1 = run.first_time_abs_yaw_rate(1.0)
    return Check("Reference case: E&J Premier, 0.75 m/s, 40 N for 0.1 s", "Collins 1987, Figure 8-3a",
                 "1 rad/s in slightly over 3 s", f"{t1:.3f} s", "3.0-3.6 s", 3.0 < t1 < 3.6)


def linear_vs_nonlinear() -> Check:
    """The simulated growth rate equals the dominant eigenvalue while slips stay below 1 deg."""
    from stability.study.validation import linear_vs_nonlinear as lvn

    rows = [lvn(_ej(), u, model=m, casters="free") for m in ("thesis", "exact") for u in (0.3, 0.75, 2.0)]
    worst = max(r.relative_error for r in rows)
    slip = max(r.max_slip_deg for r in rows)
    return Check("Nonlinear simulation vs linear eigenvalue (free casters)", "independent: two models",
                 "real part of the dominant eigenvalue, 0.3/0.75/2 m/s, both variants",
                 f"largest relative difference {100 * worst:.2f} % (slips <= {slip:.2f} deg)", "< 2 %",
                 worst < 0.02 and slip < 1.0)


def simulator_linearisation() -> Check:
    """Central differences of the simulator's right-hand side = the symbolic linear model."""
    import stability
    from stability.study.validation import linearisation_check

    rows = [linearisation_check(stability.preset(n), 0.75, model=m) for n in ("ej-premier", "power-fwd")
            for m in ("thesis", "exact")]
    worst = max(r.matrix_difference for r in rows)
    return Check("Simulator's own linearisation vs the symbolic state matrix", "independent: two derivations",
                 "linear.state_space, two chairs, both variants", f"largest difference {worst:.1e}",
                 "< 1e-6 (central differences)", worst < 1e-6)


def fixed_step_vs_events() -> Check:
    """The fixed-step scheme converges at first order to the adaptive scheme's event-located solution."""
    from stability.settings.run import RunSpec
    from stability.simulate import simulate

    chair = _ej()
    push = RunSpec(push_force=20.0, push_duration=0.1, horizon=3.0, sample=0.01)
    ref = np.asarray(simulate(chair, 0.75, push.replace(scheme="adaptive", rtol=1e-9, atol=1e-12)).yaw_rate)
    err = [float(np.max(np.abs(np.asarray(simulate(chair, 0.75, push.replace(dt=dt, stop_on_warnings=False)
                                                   ).yaw_rate) - ref)))
           for dt in (1e-3, 5e-4)]
    ratio = err[1] / err[0]
    return Check("Fixed-step scheme (stick-slip pins) vs the adaptive event-located scheme",
                 "independent: two integrators", "E&J Premier, 0.75 m/s, 2 N s push, 3 s, steps 1 and 0.5 ms",
                 f"largest yaw-rate difference {err[0]:.1e} rad/s at 1 ms, x{ratio:.2f} at half the step",
                 "first order: x0.35-0.65", 0.35 < ratio < 0.65)


def towed_wheel() -> Check:
    """Towed-wheel shimmy (the E&J Premier's caster): Routh-Hurwitz agrees with the eigenvalues."""
    from stability.shimmy.chair import caster_wheel

    wheel = caster_wheel(_ej())
    agree = total = unstable = 0
    trail = wheel.contact_behind_cm + wheel.pivot_ahead_of_cm
    for u in np.linspace(0.2, 4.0, 20):
        for new_trail in np.linspace(0.005, 0.08, 16):       # m; shorter trails shimmy
            w = dataclasses.replace(wheel, contact_behind_cm=wheel.contact_behind_cm + float(new_trail) - trail)
            ev = w.eigenvalues(float(u))
            margin = ev.real.max() / np.abs(ev).max()
            if abs(margin) > 1e-6:            # well away from the boundary, where both are decisive
                total += 1
                unstable += bool(margin > 0)
                agree += w.routh_hurwitz(float(u)).stable == bool(margin < 0)
    return Check("Towed-wheel shimmy of the E&J caster: stability by Routh-Hurwitz vs by eigenvalues",
                 "Pacejka 2006 sec. 5.3; Schwab & Meijaard 2003", "the same verdict (speed x trail grid)",
                 f"{agree} of {total} grid points agree ({unstable} shimmy)", "all",
                 agree == total and 0 < unstable < total)


def holding_moment() -> Check:
    """Cross slope: the equilibrium solver's holding moment = the frictionless closed form."""
    from stability import slope

    c = _ej(pin_friction_left=0.0, pin_friction_right=0.0)
    worst = 0.0
    for phi in (1.0, 2.0, 4.0):
        eq = slope.solve(c, phi, 0.9)
        worst = max(worst, abs(eq.holding_moment - eq.closed_form) / abs(eq.closed_form))
    return Check("Cross-slope holding moment, solver vs closed form", "closed form (statics on the plane)",
                 "g cos(theta) sin(phi) (m x_m - 2 m_c (l1/trail)(x_m - x_c))",
                 f"largest relative difference {100 * worst:.2f} %", "< 1 % (caster steer and crab angle)",
                 worst < 0.01)


#: Every check, in the page's order: (function, cheap enough for the default test run).
def layout_is_the_engine() -> Check:
    """The layout simulator on the thesis's chair as a layout against the thesis engine (reference push, 3 s)."""
    from stability import preset
    from stability.layout import Layout
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.simulate.layout import simulate_layout

    c = preset("ej-premier")
    worst, peak = 0.0, 0.0
    for law in ("kinetic", "stick-slip"):
        run = RunSpec(horizon=3.0, friction_law=law)
        ours, theirs = simulate_layout(Layout.from_chair(c), 0.75, run), simulate(c, 0.75, run)
        worst = max(worst, float(np.abs(ours.heading_rad - np.asarray(theirs.heading)).max()))
        peak = max(peak, float(np.abs(ours.heading_deg).max()))
    return Check("Any-layout simulator = thesis engine (the E&J Premier as a layout, both pin-friction laws)",
                 "simulate(), the thesis engine", f"heading up to {peak:.1f} deg over 3 s",
                 f"largest heading difference {worst:.1e} rad", "1e-11 rad (rounding)", worst <= 1e-11)


def layout_growth_rate() -> Check:
    """A mid-wheel-drive base reversing: the nonlinear run's growth at small amplitude = the linear model's."""
    import dataclasses

    from stability.layout import growth_rates
    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.simulate.layout import simulate_layout

    b = layout_preset("mid-wheel-drive")
    b = dataclasses.replace(b, wheels=tuple(dataclasses.replace(w, tire="linear:100") for w in b.wheels),
                            casters=tuple(dataclasses.replace(k, tire="linear:30", pin_friction=0.0,
                                                              pin_damping=0.5) for k in b.casters))
    lam = float(growth_rates(b, [-1.0])[0])
    r = simulate_layout(b, -1.0, RunSpec(horizon=4.0, push_force=0.01, friction_law="kinetic"),
                        caster_angles_deg=[180.0] * len(b.casters))
    sel = r.t_s >= 1.5
    fit = float(np.polyfit(r.t_s[sel], np.log(np.abs(r.yaw_rate_rad_s[sel])), 1)[0])
    return Check("Layout simulator's small-amplitude growth = linear eigenvalue (mid-wheel drive, -1 m/s)",
                 "stability.layout.linear", f"{lam:.4f} 1/s", f"{fit:.4f} 1/s", "1 % (first-order step error)",
                 abs(fit - lam) <= 0.01 * abs(lam))


CHECKS: tuple[tuple[Callable[[], Check], bool], ...] = (
    (eq_8_2_to_8_5, True),
    (figure_8_6, True),
    (reference_time, False),
    (bicycle_closed_form, True),
    (locked_critical_speed, True),
    (holding_moment, True),
    (towed_wheel, True),
    (linear_vs_nonlinear, False),
    (simulator_linearisation, False),
    (fixed_step_vs_events, False),
    (layout_is_the_engine, False),
    (layout_growth_rate, False),
)

