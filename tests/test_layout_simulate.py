"""Nonlinear simulation of any wheel layout (stability.simulate.layout), forward and in reverse.

Independent statements used:

- the thesis's chair is the layout of two fixed wheels and two casters: the layout kernel (Kane's equations of
  any layout solved numerically, its own load rule and caster bookkeeping) reproduces the thesis engine's run
  (the thesis model's closed-form accelerations, eq 6-25 loads) step for step, both friction laws;
- a caster that carries no load (off the ground), has no mass, no pin friction and a vanishing inertia changes
  nothing but through that inertia;
- a mirror image (push to the left instead of the right) gives the mirrored run;
- at small amplitude the nonlinear run grows (or decays) at the rate of the linear model's dominant eigenvalue
  (stability.layout.linear), to the scheme's first-order step error;
- Guo et al. (2003, Assistive Technology 15(2)) measured the drive-direction error of a front-caster chair
  reversing: greatest with both casters starting at 90 deg, least with them "oriented forward".
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from stability.chair import preset
from stability.layout import Caster, Layout, growth_rates
from stability.layout.presets import layout_preset
from stability.layout.statics import load_rule, static_loads
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.simulate.layout import simulate_layout, simulate_layout_runs

SHORT = RunSpec(horizon=3.0)


@pytest.mark.parametrize("law", ["kinetic", "stick-slip"])
def test_the_thesis_chair_as_a_layout_is_the_thesis_engine(law):
    """Heading after the reference push (40 N for 0.1 s at 0.75 m/s), 3 s: the same scheme, step and tire law,
    the accelerations by a numeric solve of the 4 x 4 mass matrix instead of the generated closed form and the
    loads by a 4 x 4 solve instead of the stepwise elimination: rounding differs, about 1e-16 relative per step.
    Over 3000 steps of a run whose heading grows to 0.94 rad (growth about 1.5/s, amplifying a difference about
    e^4.5 = 90 fold) the observed difference is at most 3.0e-15 rad (4.0e-15 rad for the casters); asserted 5e-13
    rad (the kinetic law's chatter switches a moment's sign at rate zero, which is exact in both)."""
    chair = preset("ej-premier")
    run = SHORT.replace(friction_law=law)
    ours = simulate_layout(Layout.from_chair(chair), 0.75, run)
    theirs = simulate(chair, 0.75, run)
    assert ours.ended == "horizon" and len(ours.t_s) == len(theirs.t)
    np.testing.assert_allclose(ours.t_s, theirs.t, rtol=0, atol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert np.abs(ours.heading_rad).max() > 0.5                   # the push did something worth comparing
    # error model: rounding: ~eps per step over 3000 steps, grown ~90 fold (observed 6.7e-16 / 3.0e-15 rad heading,
    # 8.9e-16 / 4.0e-15 rad casters, kinetic / stick-slip), x100
    assert np.abs(ours.heading_rad - np.asarray(theirs.heading)).max() <= 5e-13
    assert np.abs(ours.caster_angle_rad[0] - np.asarray(theirs.eta)).max() <= 5e-13
    assert np.abs(ours.caster_angle_rad[1] - np.asarray(theirs.beta)).max() <= 5e-13


def test_the_load_rule_gives_the_static_loads():
    """At rest (no tire forces) the kernel's load rule is the statics' (lever rule, three contacts, compliance):
    the same equations solved another way, observed 1e-13 of the weight; asserted 1e-9."""
    from stability.layout.statics import contacts
    from stability.simulate.layout_kernel import layout_loads

    for layout in (Layout.from_chair(preset("ej-premier")), layout_preset("mid-wheel-drive"),
                   Layout("trike", 80.0, 4.0, 0.5, Layout.from_chair(preset("ej-premier")).wheels,
                          (Caster(-0.3, 0.0),))):
        rule = load_rule(layout)
        pts = contacts(layout)
        out = np.zeros(len(pts))
        layout_loads(rule.mode, np.array([p[1] for p in pts]), np.array([p[2] for p in pts]), rule.stiffness,
                     rule.line, rule.roll_share, layout.m * layout.g, layout.h, 0.0, 0.0, out)
        np.testing.assert_allclose(out, static_loads(layout), rtol=0, atol=1e-9 * layout.m * layout.g)  # rounding: equivalent arithmetic, a few ulp (observed 2.9e-16)


def test_the_roll_moment_is_shared_as_the_thesis_roll_coefficient_says():
    """from_chair's stiffnesses give the pairs' roll stiffnesses the ratio roll_k (eq 6-28): shares k/(k+1), 1/(k+1)."""
    for k in (0.5, 1.0, 3.0):
        rule = load_rule(Layout.from_chair(dataclasses.replace(preset("ej-premier"), roll_k=k)))
        np.testing.assert_allclose(rule.roll_share, [k / (k + 1), 1 / (k + 1)], rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 3.3e-16)
    for k, d, t in ((0.001, 1.0, 0.05), (1000.0, 0.05, 1.0)):      # the short form's extremes expand too
        c = dataclasses.replace(preset("ej-premier"), roll_k=k, d1=d, d2=d, t1=t, t2=t)
        np.testing.assert_allclose(load_rule(Layout.from_chair(c)).roll_share, [k / (k + 1), 1 / (k + 1)],
                                   rtol=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 4.3e-16)


@pytest.mark.parametrize("law", ["kinetic", "stick-slip"])
def test_a_caster_off_the_ground_without_mass_changes_nothing(law):
    """A fifth wheel: a caster with zero vertical stiffness (no load, so no tire force), no mass, no pin friction
    and an inertia of 1e-9 kg m^2 about its pin.  It swivels as the chair turns under it; its only effect is
    through that inertia, of order 1e-9 / 5.6 kg m^2 of the response (observed 3.7e-10 of the peak heading);
    asserted 1e-7 of it."""
    layout = Layout.from_chair(preset("ej-premier"))
    ghost = Caster(0.1, 0.0, trail=0.05, l=0.0, m_c=0.0, i_zp=1e-9, pin_friction=0.0, vertical_stiffness=0.0)
    plus = dataclasses.replace(layout, casters=layout.casters + (ghost,), name="with a ghost caster")
    run = SHORT.replace(friction_law=law)
    a, b = simulate_layout(layout, 0.75, run), simulate_layout(plus, 0.75, run)
    assert b.ended == "horizon"
    peak = np.abs(a.heading_rad).max()
    # error model: first order in the ghost's inertia, 1e-9 / 5.6 kg m^2 of the response (observed 3.7e-10 of the
    # peak heading, 9.4e-11 of the peak lateral path), x270 and x1000
    assert np.abs(a.heading_rad - b.heading_rad).max() <= 1e-7 * peak
    assert np.abs(a.y_m - b.y_m).max() <= 1e-7 * np.abs(a.y_m).max()


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-rwd-base"])
def test_mirror_symmetry_push_left_and_right(name):
    """A symmetric layout pushed left runs the mirror image of the run pushed right: heading and lateral path
    change sign, the casters exchange their angles with the sign changed.  The same arithmetic with signs
    changed, except for sums taken in another order: observed 2e-15 rad; asserted 1e-10 rad."""
    layout = layout_preset(name)
    run = SHORT.replace(push_force=80.0)
    right, left = simulate_layout(layout, 1.0, run), simulate_layout(layout, 1.0, run.replace(push_force=-80.0))
    assert np.abs(right.heading_rad).max() > 1e-3
    # error model (docstring): mirror images, rounding only where sums are taken in another order, grown over the
    # run's steps (observed 2.2e-16 to 7.4e-15 rad here), margin > 1e4
    np.testing.assert_allclose(right.heading_rad, -left.heading_rad, rtol=0, atol=1e-10)
    np.testing.assert_allclose(right.y_m, -left.y_m, rtol=0, atol=1e-10)
    pairs = [(i, j) for i, a in enumerate(layout.casters) for j, b in enumerate(layout.casters)
             if a.x == b.x and a.y == -b.y and a.y < 0]
    assert pairs
    for i, j in pairs:
        np.testing.assert_allclose(right.caster_angle_rad[i], -left.caster_angle_rad[j], rtol=0, atol=1e-10)


def _linear_tires(layout: Layout) -> Layout:
    """Linear tires (their force does not depend on the load) and viscous pins: the linear model's assumptions."""
    return dataclasses.replace(
        layout, wheels=tuple(dataclasses.replace(w, tire="linear:100") for w in layout.wheels),
        casters=tuple(dataclasses.replace(c, tire="linear:30", pin_friction=0.0, pin_damping=0.5)
                      for c in layout.casters))


@pytest.mark.parametrize("name,speed", [("power-fwd-base", 1.0), ("mid-wheel-drive", 1.0),
                                        ("mid-wheel-drive", -1.0), ("power-rwd-base", -1.0)])
def test_the_linear_growth_rate_is_recovered_from_the_nonlinear_run(name, speed):
    """A 0.01 N push, 4 s: the slope of log|yaw rate| over 1.5-4 s is the dominant eigenvalue of the linear
    model (stability.layout.linear), forward and in reverse (casters starting at 180 deg), growing or decaying.
    Error model: the scheme's first-order step error, at most lambda^2 dt / 2 (7e-4 of lambda at 1.47/s and 1 ms;
    observed 0.74-0.79 of it at both steps); the other modes, decayed by e^(-16 x 1.5) at 1.5 s; the nonlinearity
    at headings below 0.1 deg (slip angles ~1e-3 rad: atan and the load transfer second order).  Asserted: the
    error within lambda^2 dt / 2 at each step, halving with the step, and the Richardson extrapolation
    2 fit(dt/2) - fit(dt) equal to lambda within 10 |lambda|^3 dt^2 (the second-order term; observed at most 0.11
    of |lambda|^3 dt^2, i.e. 3.5e-7 1/s)."""
    layout = _linear_tires(layout_preset(name))
    lam = float(growth_rates(layout, [speed])[0])
    angles = [180.0] * len(layout.casters) if speed < 0 else None
    fits = []
    for dt in (0.001, 0.0005):
        r = simulate_layout(layout, speed, RunSpec(horizon=4.0, push_force=0.01, dt=dt, friction_law="kinetic"),
                            caster_angles_deg=angles)
        assert np.abs(r.heading_deg).max() < 0.1
        sel = r.t_s >= 1.5
        fits.append(float(np.polyfit(r.t_s[sel], np.log(np.abs(r.yaw_rate_rad_s[sel])), 1)[0]))
        # error model: truncation, first order in dt: lambda^2 dt / 2 (observed 0.74-0.79 of it)
        assert abs(fits[-1] - lam) <= lam ** 2 * dt / 2, (fits[-1], lam)
    errors = [abs(f - lam) for f in fits]
    assert 1.5 < errors[0] / errors[1] < 2.5, errors
    # error model: truncation, second order in dt once the first-order term is extrapolated away: |lambda|^3 dt^2
    # (observed at most 0.11 of it), x90
    assert abs(2 * fits[1] - fits[0] - lam) <= 10 * abs(lam) ** 3 * 0.001 ** 2, (fits, lam)


def _reverse_heading_error_deg(push: float, angle: float, speed: float = -0.75, distance: float = 1.0) -> float:
    chair = Layout.from_chair(preset("ej-premier-front-caster"))
    run = RunSpec(horizon=distance / abs(speed) + 0.01, push_force=push, stop_on_warnings=False)
    return abs(simulate_layout(chair, speed, run, caster_angles_deg=[angle, angle]).heading_at(distance / abs(speed)))


def test_reversing_a_front_caster_chair_casters_at_90_deg_are_worse_than_trailing():
    """Guo et al. 2003: the drive-direction error when reversing is greatest with both casters at 90 deg (to the
    left or right).  The model agrees against the casters already trailing for the reverse (180 deg): after 1 m
    backwards at 0.75 m/s with no other disturbance, the 90 deg start turns the chair (its casters' side forces
    while they swing round: 18 deg) and the 180 deg start does not (straight running: 0 by symmetry); with the
    reference push too, the worse of the two 90 deg starts ends further off than the 180 deg start.

    Where the model differs (stated in docs/layouts.md): casters starting at 0 deg (trailing for forward driving,
    leading when reversing) are an equilibrium without a disturbance (no error), and after the reference push
    both flip through 180 deg together and give the largest error (regression values at 0.75 m/s: 28.6 deg, against
    35.1 and 3.0 deg for the casters at -90 and +90 deg, 3.9 deg at 180: the 90 deg starts depend on the push's
    side, the mean of the two is below the 0 deg start).  Guo et al.'s chair was a rear-wheel-drive power chair
    whose error came from the motors' unequal loads (caster drag), which this free-rolling model has not."""
    quiet = {a: _reverse_heading_error_deg(0.0, a) for a in (0.0, 90.0, -90.0, 180.0)}
    assert quiet[90.0] > 1.0 and quiet[-90.0] > 1.0         # degrees: the swinging casters steer the chair
    assert quiet[180.0] < 1e-9 and quiet[0.0] < 1e-9
    pushed = {a: _reverse_heading_error_deg(40.0, a) for a in (0.0, 90.0, -90.0, 180.0)}
    assert max(pushed[90.0], pushed[-90.0]) > pushed[180.0]
    assert pushed[0.0] > pushed[180.0]
    assert pushed[0.0] > 0.5 * (pushed[90.0] + pushed[-90.0])     # the model's own finding (regression)


def test_bad_input_is_refused_with_the_parameter_named():
    layout = Layout.from_chair(preset("ej-premier"))
    with pytest.raises(ValueError, match=r"speed=0.001 is invalid; valid range: 0.01 <= \|speed\| <= 20"):
        simulate_layout(layout, 0.001)
    with pytest.raises(ValueError, match="caster_angles_deg=.* 2 angles"):
        simulate_layout(layout, 1.0, caster_angles_deg=[0.0])
    with pytest.raises(ValueError, match="scheme='adaptive' is invalid for a layout"):
        simulate_layout(layout, 1.0, RunSpec(scheme="adaptive"))
    with pytest.raises(ValueError, match="model='thesis' is invalid for a layout"):
        simulate_layout(layout, 1.0, RunSpec(model="thesis"))
    with pytest.raises(TypeError, match="run="):
        simulate_layout(layout, 1.0, {"speed": 1.0})          # type: ignore[arg-type]


def test_reverse_by_a_negative_speed_or_by_the_run_is_the_same_run():
    layout = layout_preset("mid-wheel-drive")
    a = simulate_layout(layout, -0.8, SHORT, caster_angles_deg=[180.0] * 4)
    b = simulate_layout(layout, None, SHORT.replace(speed=0.8, reverse=True), caster_angles_deg=[180.0] * 4)
    assert a.speed_m_s == b.speed_m_s == -0.8
    np.testing.assert_array_equal(a.heading_rad, b.heading_rad)
    assert a.u_m_s[0] == -0.8 and a.settings["reverse"] is True


def test_runs_stepped_together_are_each_run_on_its_own():
    """``simulate_layout_runs`` steps several runs of a layout in one kernel call: each is its own
    ``simulate_layout`` run exactly (the kernel advances every run of a batch on its own; same arithmetic), whatever
    its speed, direction and caster angles, including a run the warning rule stops early among runs that go on."""
    from dataclasses import fields

    layout = layout_preset("mid-wheel-drive")
    run = SHORT.replace(horizon=1.0, push_force=200.0)
    speeds, angles = [0.8, -3.0, 3.0, -0.8], [None, [0.0] * 4, [0.0] * 4, [180.0] * 4]
    batch = simulate_layout_runs(layout, speeds, run, caster_angles_deg=angles)
    assert [r.ended for r in batch] == ["horizon", "slip warnings", "horizon", "horizon"]   # the cases exercised
    for r, u, a in zip(batch, speeds, angles, strict=True):
        one = simulate_layout(layout, u, run, caster_angles_deg=a)
        for f in fields(one):
            x, y = getattr(r, f.name), getattr(one, f.name)
            assert np.array_equal(x, y, equal_nan=True) if isinstance(x, np.ndarray) else x == y, f.name
    with pytest.raises(ValueError, match="one row of angles per speed"):
        simulate_layout_runs(layout, [0.8, 1.0], run, caster_angles_deg=[None])


def test_the_simulate_command_runs_a_layout_in_reverse(capsys):
    import json

    from stability.simulate.__main__ import main

    assert main(["--chair", "mid-wheel-drive", "--reverse", "--eta0", "180", "--beta0", "180", "--horizon", "2",
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    direct = simulate_layout(layout_preset("mid-wheel-drive"), -0.75, RunSpec(horizon=2.0),
                             caster_angles_deg=[180.0] * 4)
    assert d["chair"] == "mid-wheel-drive" and d["speed_m_s"] == -0.75 and d["ended"] == "horizon"
    assert d["final_heading_deg"] == direct.final_heading_deg
    assert d["settings"]["caster_angles_deg"] == [180.0] * 4
    assert main(["--chair", "power-fwd-base", "--horizon", "1"]) == 0
    assert "power-fwd-base: 0.75 m/s forwards" in capsys.readouterr().out
    assert main(["--chair", "mid-wheel-drive", "--set", "caster_5_trail=0.06"]) == 2     # it has four casters
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "caster_K_FIELD (K 1-4)" in err


@pytest.mark.slow
def test_the_generated_nonlinear_layout_module_is_current():
    from pathlib import Path

    from derivations import layout as L

    path = Path(__file__).resolve().parents[1] / "stability" / "_generated" / "layout_nonlinear.py"
    assert path.read_text(encoding="utf-8") == L.render_nonlinear(), "regenerate: python derivations/layout.py"
