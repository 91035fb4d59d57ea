"""Slope model: zero slope recovers the level equations, mirror symmetry, frictionless statics,
turn directions, grades, command line (issue 12)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from stability import chair as chair_mod
from stability import linear
from stability.models import full_width as fw
from stability.models import slope as msl
from stability.models import statics
from stability.models.params import parameters
from stability.slope import equilibrium as eqm
from stability.slope.__main__ import main
from stability.slope.model import Plane
from stability.study.slope_stability import forward_gravity, grade_run, state_matrix
from stability.study.veer import uncorrected_path

RNG = np.random.default_rng(12)
PRESETS = ("ej-premier", "ej-premier-front-caster", "revised", "power-fwd", "manual-front-caster")


@pytest.mark.parametrize("name", PRESETS)
def test_zero_slope_accelerations_equal_level_model(name):
    p = parameters(chair_mod.preset(name))
    for _ in range(5):
        x = RNG.normal(size=23)
        eta, beta = x[3], x[4]
        args = (1 + abs(x[0]), x[1], x[2], math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta), x[5], x[6])
        F = tuple(50 * x[7:15])
        ref = fw.accelerations(p, *args, *F, x[15], x[16], x[17], x[18], "exact")
        got = msl.accelerations(p, *args, F, x[15], x[16], 0.0, 0.0, Fy_ext=x[17], Mz_ext=x[18])
        # error model: rounding: the slope model's generated sums and the level model's are the same terms in another
        # order, a few ulp of terms up to ~1e2 (observed 4.0e-16 relative, 5.7e-14 absolute); margins 250 and 175
        np.testing.assert_allclose(got, ref, rtol=1e-13, atol=1e-11)


@pytest.mark.parametrize("name", PRESETS)
def test_zero_slope_loads_are_eq_6_25(name):
    p = parameters(chair_mod.preset(name))
    for _ in range(5):
        fx, fy, eta, beta = 100 * RNG.normal(), 100 * RNG.normal(), 0.5 * RNG.normal(), 0.5 * RNG.normal()
        trig = (math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta))
        ref = statics.normal_loads(p, fx, fy, *trig)
        got = msl.normal_loads(p, fx / p.m, fy / p.m, 0.0, 0.0, p.g, *trig)
        # error model: rounding of the same statics in another order (observed 6.6e-16 relative, 5.7e-14 N)
        np.testing.assert_allclose(got, ref, rtol=1e-13, atol=1e-11)


def test_slope_loads_use_in_plane_weight():
    # standing still (a = 0) on a cross slope: tire forces -m g_in, loads = eq 6-25 with those forces and m gn
    c = chair_mod.preset("ej-premier")
    p = parameters(c)
    g1, g2, gn = Plane(4.0, 3.0).gravity(p.g)
    got = msl.normal_loads(p, 0.0, 0.0, g1, g2, gn)
    ref = statics.normal_loads(p._replace(g=gn), -p.m * g1, -p.m * g2)
    # error model: rounding of the same statics (observed 0) and of a four-term sum (observed 2.5e-16)
    np.testing.assert_allclose(got, ref, rtol=1e-12)
    assert sum(got) == pytest.approx(p.m * p.g * math.cos(math.radians(4)) * math.cos(math.radians(3)), rel=1e-13)
    assert got[3] > got[2] and got[1] > got[0]  # the downhill (right) wheels carry more


def test_caster_weight_generalized_forces():
    p = parameters(chair_mod.preset("ej-premier"))
    eta, beta, g1, g2 = 0.3, -0.2, 0.4, 0.9
    Q = msl.gravity_generalized_forces(p, math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta), g1, g2)
    # error model: rounding of a few products and one difference, a few ulp (observed 0)
    assert Q[0] == pytest.approx(p.m * g1, rel=1e-13) and Q[1] == pytest.approx(p.m * g2, rel=1e-13)
    # moment of the caster weight about its pin: (-l1 a1) x m_c g . c3
    assert Q[3] == pytest.approx(-p.m_c * p.l1 * (g2 * math.cos(eta) - g1 * math.sin(eta)), rel=1e-13)
    assert Q[4] == pytest.approx(-p.m_c * p.l1 * (g2 * math.cos(beta) - g1 * math.sin(beta)), rel=1e-13)


@pytest.mark.parametrize("name", PRESETS)
def test_zero_slope_equilibrium_is_straight_running(name):
    c = chair_mod.preset(name)
    e = eqm.solve(c, 0.0, 0.75)
    # error model: straight running solves the equations exactly; the root's xtol 1e-13 (observed 0)
    assert abs(e.holding_moment) < 1e-12 and abs(e.heading_deg) < 1e-12 and abs(e.eta_deg) < 1e-12
    s = statics.static_loads(c)
    # error model: rounding of the same statics (observed 0)
    np.testing.assert_allclose(e.loads, (s["caster_left"], s["caster_right"], s["main_left"], s["main_right"]),
                               rtol=1e-12)


@pytest.mark.parametrize("name", ("ej-premier", "ej-premier-front-caster"))
def test_zero_slope_linearisation_equals_linear_model(name):
    c = chair_mod.preset(name)
    A = state_matrix(c, Plane(0.0), 0.75)
    ref = linear.state_matrices(c, [0.75])[0]
    # error model: state_matrix is a central difference with h = 1e-6: rounding eps |terms| / h with terms up to
    # ~max|A| (1.9e-6 for the E&J), truncation h^2 (negligible); observed 4.3e-6 absolute, 2.8e-9 relative on
    # entries above 1e-3; atol 1e3 eps max|A| / h (1.9e-3 instead of 8.5e-3: margin 440), rtol margin 360
    np.testing.assert_allclose(A, ref, rtol=1e-6, atol=1e3 * np.finfo(float).eps * np.abs(ref).max() / 1e-6)


@pytest.mark.parametrize("name", ("ej-premier", "manual-front-caster", "power-fwd"))
def test_mirror_symmetry(name):
    c = chair_mod.preset(name)
    a, b = eqm.solve(c, 3.0, 0.8), eqm.solve(c, -3.0, 0.8)
    # error model: mirror images in exact arithmetic; the root's xtol 1e-13 and rounding (observed 0, and 2.3e-16
    # on the caster angles): 1e-11 relative keeps a margin of 100 over the root's xtol
    assert a.holding_moment == pytest.approx(-b.holding_moment, rel=1e-11)
    assert a.heading_deg == pytest.approx(-b.heading_deg, rel=1e-11)
    assert a.eta_deg == pytest.approx(-b.beta_deg, rel=1e-11) and a.beta_deg == pytest.approx(-b.eta_deg, rel=1e-11)
    np.testing.assert_allclose(a.loads, (b.loads[1], b.loads[0], b.loads[3], b.loads[2]), rtol=1e-11)
    np.testing.assert_allclose(a.drive_forces, b.drive_forces[::-1], rtol=1e-11, atol=1e-11)
    np.testing.assert_allclose(a.friction_range, [-x for x in b.friction_range[::-1]], rtol=1e-11)


def test_mirror_symmetry_with_the_main_wheels_rolling_resistance():
    """The presets roll without resistance (main_rolling_scale 0); with the main tires' rolling force on, the
    main wheels' longitudinal forces enter the drive's moment balance, and the mirror image still swaps the two
    drive forces (a chair on the mirrored slope is the mirrored chair: each wheel's rolling force moves to the
    other side, so their moment about the c.g. changes sign with the slope)."""
    c = chair_mod.preset("ej-premier").replace(main_rolling_scale=1.0)
    a, b = eqm.solve(c, 3.0, 0.8, friction_range=False), eqm.solve(c, -3.0, 0.8, friction_range=False)
    rolling_free = eqm.solve(c.replace(main_rolling_scale=0.0), 3.0, 0.8, friction_range=False)
    assert abs(sum(a.drive_forces) - sum(rolling_free.drive_forces)) > 1.0     # the premise: the rolling forces act
    # error model: as test_mirror_symmetry (mirror images in exact arithmetic; the root's xtol 1e-13), x100
    np.testing.assert_allclose(a.drive_forces, b.drive_forces[::-1], rtol=1e-11, atol=1e-11)


def test_neither_wheel_works_harder_without_a_difference_or_a_slope():
    """A zero right-minus-left difference has no harder side, and on level ground (cross slope 0) neither side is
    uphill: "neither" in both cases, whatever the other argument."""
    assert eqm.harder_side(0.0, 2.0) == eqm.harder_side(0.0, -2.0) == "neither"
    assert eqm.harder_side(5.0, 0.0) == eqm.harder_side(-5.0, 0.0) == "neither"


@pytest.mark.parametrize("name", PRESETS)
@pytest.mark.parametrize("phi", (1.0, 4.0))
def test_frictionless_statics(name, phi):
    c = chair_mod.preset(name)
    e = eqm.solve(c, phi, 0.75)
    # the solution satisfies the full equations of motion
    # error model: rounding: hybr's root (xtol 1e-13) leaves eps times the force terms per mass (observed 3.4e-14
    # m/s^2), margin 300
    assert np.max(np.abs(eqm.residual_accelerations(c, e))) < 1e-11
    # closed form with straight casters; error model: its neglected terms are second order in phi: 0.032 phi^2
    # relative at most on the presets (phi in rad; 9.4e-6 at 1 deg, 1.5e-4 at 4 deg: 16 times for 4 times the
    # slope); bound 3 phi^2, margin 100 (was a fixed 2e-3: margin 210 at 1 deg, 13 at 4 deg)
    phi2 = math.radians(phi) ** 2
    assert e.holding_moment == pytest.approx(e.closed_form, rel=3 * phi2)
    # leading order: the fixed wheels carry the slope's weight, M = m g sin(phi) x_m
    lead = c.m * c.g * math.sin(math.radians(phi)) * c.x_main
    bound = 2 * c.m_c * c.g * math.sin(math.radians(phi)) * c.l1 / c.trail * abs(c.x_main - (c.x_pin - c.trail))
    # error model: first order in the casters' weight (bound: l1/trail of it on the pin lever), plus the closed
    # form's second order in phi (2e-3 of lead); observed within 1.005 bound
    assert abs(e.holding_moment - lead) <= 1.01 * bound + 2e-3 * abs(lead)
    # frictionless casters carry only l1/trail of their own lateral weight; error model: the caster's small
    # steady swivel, O(phi^2): 4e-5 phi^2 (phi in rad) relative at most on the presets at 1 and 4 deg, margin 100
    assert abs(e.lateral_forces[0]) == pytest.approx(c.m_c * c.g * math.sin(math.radians(phi)) * c.l1 / c.trail,
                                                     rel=100 * 4e-5 * phi2)
    # Coulomb pins: the range contains the frictionless value; width from the pin-moment lever (x_m - x_c)/trail
    lo, hi = e.friction_range
    assert lo < e.holding_moment < hi
    width = 2 * (c.pin_friction_left + c.pin_friction_right) * abs(c.x_main - (c.x_pin - c.trail)) / c.trail
    # error model: the lever from straight casters, O(phi^2): at most 0.066 phi^2 (phi in rad) relative observed on
    # the presets at 1 and 4 deg (3.2e-4 at 4 deg); bound 5 phi^2, margin 75
    assert hi - lo == pytest.approx(width, rel=5 * phi2)


@pytest.mark.parametrize("name,turn", [("ej-premier", "uphill"), ("revised", "uphill"), ("power-fwd", "uphill"),
                                       ("ej-premier-front-caster", "downhill"), ("manual-front-caster", "downhill")])
def test_turn_direction(name, turn):
    c = chair_mod.preset(name)
    for phi in (2.0, -2.0):
        e = eqm.solve(c, phi, 0.75)
        assert e.uncorrected_turn == turn
        path = uncorrected_path(c, e, duration=1.0)
        assert path.turn == turn
        assert abs(path.heading_change_deg) > 1.0


def test_front_caster_turn_rate_near_free_caster_closed_form():
    # zero-width model with a free castered axle: quasi-steady yaw rate g2/U (generated closed form)
    c = chair_mod.preset("ej-premier-front-caster")
    U, phi = 1.5, 0.5
    g2 = c.g * math.sin(math.radians(phi))
    r = msl.zero_width_turn(U, c.m, g2, c.s1, c.s2, 0.0, 5000.0)[1]
    assert r == pytest.approx(g2 / U, rel=1e-12)      # rounding: one division in the closed form (observed 0)
    path = uncorrected_path(c, eqm.solve(c, phi, U), duration=4.0)
    # after the transient (~1/1.5 s) the yaw rate is within 10 % of g2/U (heading change < 10 deg). error model:
    # next order of the zero-width model: the track, the casters' own dynamics and the transient's remainder
    # (observed 4.5 %)
    assert math.radians(path.yaw_rate_deg_s) == pytest.approx(g2 / U, rel=0.1)


def test_zero_width_hold_closed_form():
    m, g2, s1, s2 = 90.0, 0.5, 0.3, 0.2
    # error model: rounding of the generated closed form's few products and sums (observed 4.0e-16), margin 250
    a, Ff, Fr, M = msl.zero_width_straight(1.0, m, g2, s1, s2, 1500.0, 0.0)
    assert M == pytest.approx(m * g2 * s1, rel=1e-13) and Ff + Fr == pytest.approx(-m * g2, rel=1e-13)
    a, Ff, Fr, M = msl.zero_width_straight(1.0, m, g2, s1, s2, 1500.0, 1000.0)
    assert M == pytest.approx(-(s1 * Ff - s2 * Fr), rel=1e-13) and Ff + Fr == pytest.approx(-m * g2, rel=1e-13)
    assert Ff / 1500.0 == pytest.approx(Fr / 1000.0, rel=1e-13)  # one body slip angle for both axles


@pytest.mark.parametrize("theta", (-4.0, 2.5))
def test_grade_forward_component(theta):
    c = chair_mod.preset("ej-premier")
    # error model: rounding of the same product (observed 0 in both)
    assert forward_gravity(c, theta) == pytest.approx(-c.m * c.g * math.sin(math.radians(theta)), rel=1e-12)
    run = grade_run(c, theta, 0.75, duration=1.0, n=3)
    assert run.acceleration == pytest.approx(-c.g * math.sin(math.radians(theta)), rel=1e-12)  # rolling off
    if theta < 0:  # downhill the rear-caster chair gets faster and diverges faster
        assert np.all(np.diff(run.max_real) > 0)


def test_the_holding_line_gives_the_moment_signed_inside_its_pin_friction_band(capsys):
    """The text's holding moment: its magnitude, the same value signed (clockwise +) and the Coulomb pin-friction
    band on the same signed axis; the frictionless moment lies inside the band (the pins' friction only adds
    moments of either sign), so the line cannot print a magnitude and a band that disagree in sign."""
    import re

    assert main(["--chair", "manual-front-caster", "--cross-slope", "2", "--speed", "1"]) == 0
    line = next(t for t in capsys.readouterr().out.splitlines() if "holding yaw moment" in t)
    m = re.search(r"holding yaw moment ([0-9.]+) N m \(([-+][0-9.]+) signed, clockwise \+; ([0-9.]+) N m/deg\); "
                  r"with Coulomb pin friction any of ([-0-9.]+) \.\. ([-0-9.]+) N m$", line)
    assert m, line
    size, signed, per_deg, lo, hi = map(float, m.groups())
    e = eqm.solve(chair_mod.preset("manual-front-caster"), 2.0, 1.0)
    assert (size, signed) == (round(abs(e.holding_moment), 3), round(e.holding_moment, 3))
    assert per_deg == round(abs(e.holding_moment) / 2, 3) and lo <= signed <= hi


def test_cli_json_and_errors(tmp_path, capsys):
    assert main(["--chair", "manual-front-caster", "--cross-slope", "2", "--speed", "0.9", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    for key in ("holding_yaw_moment_N_m", "holding_yaw_moment_N_m_per_deg", "uncorrected_turn", "heading_deg",
                "caster_angle_left_deg", "normal_loads_N", "drive_forces"):
        assert key in d
    assert d["uncorrected_turn"] == "downhill"
    assert d["holding_yaw_moment_N_m"] == 2 * d["holding_yaw_moment_N_m_per_deg"]    # / 2 deg: exact in binary
    assert d["drive_forces"]["handrim_force_difference_N"] > 0  # push the downhill (right) rim harder
    sim = d["uncorrected_simulator"]
    assert set(sim) == {f"{s}_{f}" for s in ("adaptive", "wchair") for f in ("pin_friction", "frictionless")}
    for run in sim.values():
        # error model: rounding of the time grid's sum of steps (observed 0)
        assert run["uncorrected_turn"] == "downhill" and run["report_time_s"] == pytest.approx(1.0, abs=1e-12)
    # Coulomb pin friction holds the casters back: a slower turn than frictionless pins
    for s in ("adaptive", "wchair"):
        assert 0 < sim[f"{s}_pin_friction"]["heading_change_deg"] < sim[f"{s}_frictionless"]["heading_change_deg"]
    # the uncorrected path is the simulator's adaptive run with frictionless pins (tighter tolerances): within
    # its integration error (rtol 1e-6 against 1e-8); error model: the looser run's global error, of the order of
    # its rtol (observed 2.7e-7); 1e-4 = 100 rtol
    assert sim["adaptive_frictionless"]["heading_change_deg"] == pytest.approx(
        d["uncorrected_path"]["heading_change_deg"], rel=1e-4)
    assert main(["--chair", "manual-front-caster", "--cross-slope", "2", "--speed", "0.9", "--sim-time", "0"]) == 2
    assert "--sim-time" in capsys.readouterr().err
    for argv, word in ((["--cross-slope", "25", "--speed", "1"], "cross_slope"),
                       (["--cross-slope", "2", "--speed", "0"], "speed"),     # negative: reverse (layouts)
                       (["--cross-slope", "15", "--speed", "0.75"], "cross_slope=15.0")):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and word in err and "valid" in err


def test_slope_command_notes_the_extrapolated_load_and_which_scheme_to_read(capsys):
    """power-fwd on a 6 deg cross slope at 1 m/s: the right caster carries more than the tire data's 450 N (the
    statics say so in a note), and the fixed-step runs stop at their eleventh warning while the adaptive ones run
    on: the output says why each run ends and which to read."""
    from stability.slope import solve
    from stability.slope.__main__ import main

    eq = solve(chair_mod.preset("power-fwd"), 6.0, 1.0)
    assert max(eq.loads) > 450.0
    assert main(["--chair", "power-fwd", "--cross-slope", "6", "--speed", "1"]) == 0
    out, err = capsys.readouterr()
    assert f"load {eq.loads[1]:.0f} N is outside the fitted range 0 to 450 N; extrapolated" in err
    assert "run ends: stopped:" in out and "read the adaptive scheme's runs" in out


@pytest.mark.parametrize("name", ("ej-premier", "revised"))
@pytest.mark.parametrize("phi", (2.0, 6.0))
def test_handrim_force_difference_is_the_statics_moment_over_track_and_rim(name, phi):
    """Without pin friction the main wheels supply the statics closed-form holding moment M as opposite contact
    forces +-M / d at half-track d (d1 = d2), each scaled to the rim by R / r: the rim forces differ by
    -(R / r) M / d (right minus left).  Error model: the closed form's straight-caster neglect, as
    test_frictionless_statics (rel 2e-3; observed 4e-4)."""
    from stability.slope import drive_report

    c = chair_mod.preset(name).replace(pin_friction_left=0.0, pin_friction_right=0.0)
    assert c.d1 == c.d2
    e = eqm.solve(c, phi, 0.75)
    rim = drive_report(c, e, "handrim")
    ratio = rim["wheel_radius_m"] / rim["handrim_radius_m"]
    # error model: the closed form's second order in phi (docstring; observed 4.0e-4 at 6 deg)
    assert rim["handrim_force_difference_N"] == pytest.approx(-ratio * e.closed_form / c.d1, rel=2e-3)


@pytest.mark.parametrize("phi", (2.0, 6.0))
def test_motor_torques_are_the_statics_moment_over_track_times_the_wheel_radius(phi):
    """A power chair's wheel motors supply the same holding moment M as opposite contact forces +-M / d at
    half-track d, each times the drive wheel's radius: the two torques differ by -r M / d (right minus left), and
    the differential torque per wheel is half of it.  Error model: the closed form's straight-caster neglect, as
    the hand-rim test above (rel 2e-3; observed 4e-4)."""
    from stability.chair.power import DriveTrain
    from stability.slope import drive_report

    c = chair_mod.preset("power-fwd").replace(pin_friction_left=0.0, pin_friction_right=0.0)
    assert c.d1 == c.d2
    e = eqm.solve(c, phi, 0.75)
    train = DriveTrain(wheel_radius=0.17)
    motor = drive_report(c, e, "motor", drive_train=train)
    assert motor["wheel_radius_m"] == 0.17
    difference = motor["motor_torque_right_N_m"] - motor["motor_torque_left_N_m"]
    # error model: the closed form's second order in phi (as above)
    assert difference == pytest.approx(-0.17 * e.closed_form / c.d1, rel=2e-3)
    assert motor["differential_torque_N_m"] == pytest.approx(-difference / 2, rel=1e-15)


@pytest.mark.parametrize("field", ("wheel_radius", "handrim_radius"))
def test_a_bad_hand_rim_radius_is_named(field):
    with pytest.raises(ValueError, match=rf"^hand-rim parameter {field}=-0.1 is invalid"):
        eqm.HandRim(**{field: -0.1})


def test_max_cross_slope_is_the_edge_of_the_tire_data():
    """manual-front-caster on a 6 deg grade keeps its equilibrium inside the tire data only below a fraction of a
    degree of cross slope: the answer is inside, one resolution step (hi / 2^14) beyond it is outside."""
    c = chair_mod.preset("manual-front-caster")
    best = eqm.max_cross_slope(c, 6.0, 0.75, hi=20.0)
    assert 0.0 < best < 1.0
    assert not eqm.solve(c, best, 0.75, 6.0, strict=False).problems
    assert eqm.solve(c, best + 20.0 / 2**14, 0.75, 6.0, strict=False).problems


def test_the_holding_band_of_magnitudes_includes_zero_when_the_pins_alone_hold():
    """The figure's band is ``{|m| : m in the signed pin-friction range}`` (an interval's image under abs, exact
    arithmetic on the two ends): from 0 when the signed range holds zero, as for the mid-wheel-drive base at 0 and
    2 deg (its signed range -6.15..1.65 N m at 2 deg: no drive moment needed); the two magnitudes otherwise.
    Taking the magnitudes of the two ends alone had drawn 1.65-6.15 N m there, and a zero-width band at 0 deg."""
    from stability.layout.presets import layout_preset
    from stability.report.slope_data import layout_slope_section
    from stability.slope.plots import magnitude_band
    from stability.study.layout_slope import layout_equilibrium

    assert magnitude_band((-6.0, 1.5)) == (0.0, 6.0) and magnitude_band((-1.5, 6.0)) == (0.0, 6.0)
    assert magnitude_band((1.5, 6.0)) == (1.5, 6.0) and magnitude_band((-6.0, -1.5)) == (1.5, 6.0)
    assert magnitude_band((6.0, 1.5)) == (1.5, 6.0) and magnitude_band((0.0, 0.0)) == (0.0, 0.0)
    layout = layout_preset("mid-wheel-drive")
    curve = layout_slope_section(layout, 0.9, (0.0, 2.0, 6.0), 2.0).curve
    for k, phi in enumerate((0.0, 2.0, 6.0)):
        lo, hi = layout_equilibrium(layout, phi, 0.9).friction_range_N_m
        assert lo <= -abs(curve.holding_moment[k]) <= hi or lo <= abs(curve.holding_moment[k]) <= hi
        if lo <= 0.0 <= hi:
            assert curve.friction_low[k] == 0.0 and curve.friction_high[k] == max(-lo, hi)
        else:
            assert curve.friction_low[k] == min(abs(lo), abs(hi)) > 0.0
    # which case each slope is (not a pinned value): at 2 deg the signed range holds zero, at 6 deg it does not
    assert curve.friction_low[1] == 0.0 and curve.friction_high[1] > 0.0
    assert curve.friction_low[2] > 0.0


def test_level_ground_has_no_uncorrected_turn():
    """On level ground nothing pulls the chair sideways: no holding moment, and the turn the chair would make
    without one is "none" (Equilibrium.uncorrected_turn)."""
    e = eqm.solve(chair_mod.preset("ej-premier"), 0.0, 0.8, friction_range=False)
    assert e.holding_moment == 0.0 and e.uncorrected_turn == "none"


def test_a_slope_without_equilibrium_is_refused_with_the_largest_one_unless_not_strict():
    """At 20 deg the E&J Premier's tires cannot hold it (no root).  Strict (the default), the refusal gives the
    valid range, the largest cross slope with an equilibrium inside the tire data (max_cross_slope, the same
    speed and grade); not strict, it says only that no equilibrium was found."""
    import re

    c = chair_mod.preset("ej-premier")
    lim = eqm.max_cross_slope(c, 0.0, 0.8, 1.0, hi=20.0)
    assert 0 < lim < 20
    with pytest.raises(ValueError, match=r"^cross_slope=20\.0 deg is invalid for chair ej-premier: the tires cannot "
                                         r"hold the chair \(no equilibrium\); valid range: \|cross_slope\| <= "
                                         + re.escape(f"{lim:.2f} deg (grade 0 deg, 0.8 m/s)") + "$"):
        eqm.solve(c, 20.0, 0.8)
    with pytest.raises(ValueError, match=r"^cross_slope=20\.0 deg: no straight-running equilibrium found"):
        eqm.solve(c, 20.0, 0.8, strict=False)


def test_the_harder_side_is_the_sign_of_the_difference_however_small():
    """The harder side depends only on the signs of the difference and of the slope: the smallest positive float
    difference on a slope falling to the right is downhill, its negative uphill."""
    tiny = 5e-324
    assert eqm.harder_side(tiny, 2.0) == eqm.harder_side(-tiny, -2.0) == "downhill"
    assert eqm.harder_side(-tiny, 2.0) == eqm.harder_side(tiny, -2.0) == "uphill"


def test_the_linearisation_s_operating_point_is_mirror_symmetric():
    """Class: a public function no file of the gate's tested (seed 50: ``operating_point``'s returned caster
    angles; its callers' tests are the slope-stability study's).  On the mirror-image cross slope the crab angle
    changes sign, the left and right casters swap with their signs changed and so do the drive forces: on the
    E&J (mirror-symmetric, equal pin frictions) the two casters' angles differ by 2.9e-6 rad at 5 deg, which the
    swap must carry."""
    c = chair_mod.preset("ej-premier")
    (psi, eta, beta, drive), (psi_m, eta_m, beta_m, drive_m) = (
        eqm.operating_point(c, Plane(s, 2.0), 1.0) for s in (5.0, -5.0))
    # error model: mirror images in exact arithmetic; the root's xtol 1e-13 of angles ~0.024 rad and rounding
    # (observed 3.5e-18 rad, 7e-15 N): 1e-11 relative keeps a margin of 100 over the root's xtol
    assert (psi, eta, beta) == pytest.approx((-psi_m, -beta_m, -eta_m), rel=1e-11)
    assert drive == pytest.approx(drive_m[::-1], rel=1e-11)
    assert abs(eta - beta) > 1e-6         # the swap is seen: the two casters do differ


def test_mirror_symmetry_with_unequal_pin_frictions():
    """The pin friction's holding range on a mirror-symmetric chair with unequal pins: on the mirror-image slope,
    with the pin frictions swapped left for right, the chair is the mirror image, so the range's ends change sign
    and order.  Each pin's own friction must act at its own caster for this to hold (the same friction at both
    breaks it: the ranges of 0.3 and 0.1 N m pins differ)."""
    c = chair_mod.preset("ej-premier")
    a = eqm.solve(c.replace(pin_friction_left=0.1, pin_friction_right=0.3), 3.0, 0.8)
    b = eqm.solve(c.replace(pin_friction_left=0.3, pin_friction_right=0.1), -3.0, 0.8)
    # error model: as test_mirror_symmetry (mirror images in exact arithmetic; the root's xtol 1e-13), x100
    np.testing.assert_allclose(a.friction_range, [-x for x in b.friction_range[::-1]], rtol=1e-11)
    assert a.holding_moment == pytest.approx(-b.holding_moment, rel=1e-11)
