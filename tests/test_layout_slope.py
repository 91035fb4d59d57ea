"""Any wheel layout on a cross slope: the held line (stability.study.layout_slope) and the slope command.

Independent statements used:

- wiring: the thesis's chair as a layout gives the short form's statics (:func:`stability.slope.equilibrium.solve`:
  the thesis model's generated hold statics, eq 6-25 loads, its own root finder) to rounding;
- the statics closed form (:func:`stability.slope.equilibrium.holding_moment_closed_form`: the fixed wheels carry
  the slope's lateral weight but the fraction ``l/trail`` of each caster's own weight that its tire carries),
  generalised here to any layout with one drive axle and to reverse (derived in
  :func:`_closed_form`): within the crab and caster angles it neglects;
- mirror symmetry: the slope falling to the left needs the opposite holding moment, with the same magnitude.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from stability.chair import preset
from stability.layout import Layout
from stability.layout.presets import layout_preset
from stability.slope.__main__ import main
from stability.slope.equilibrium import holding_moment_closed_form, solve
from stability.slope.model import Plane
from stability.study.layout_slope import drive_wheels, layout_equilibrium


@pytest.mark.parametrize("phi,grade,speed", [(2.0, 0.0, 0.75), (-3.0, 1.0, 1.0), (4.0, -2.0, 1.5)])
def test_the_thesis_chair_as_a_layout_holds_the_line_as_the_short_form(phi, grade, speed):
    """The same equilibrium solved from other equations (the layout's Kane equations with gravity, the kernel's
    load rule) by the same root finder to 1e-10 of the weight: observed 9e-14 N (moments N m, loads and drive
    forces N) and 4e-16 deg; asserted 1e-8 N m and 1e-8 deg (the root's residual tolerance, 1e-10 of m g = 1e-7 N, over stiffnesses of
    ~1e4 N/rad)."""
    c = preset("ej-premier")
    short = solve(c, phi, speed, grade)
    lay = layout_equilibrium(Layout.from_chair(c), phi, speed, grade)
    assert abs(short.holding_moment) > 1.0
    assert lay.holding_moment_N_m == pytest.approx(short.holding_moment, abs=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 4.9e-16)
    assert lay.heading_deg == pytest.approx(short.heading_deg, abs=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 4.7e-16)
    np.testing.assert_allclose(lay.caster_angles_deg, [short.eta_deg, short.beta_deg], rtol=0, atol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 4.8e-16)
    np.testing.assert_allclose(lay.friction_range_N_m, short.friction_range, rtol=0, atol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 5.7e-16)
    # the layout lists the fixed wheels first (D, E), then the casters (A, B)
    np.testing.assert_allclose(lay.loads_N, np.asarray(short.loads)[[2, 3, 0, 1]], rtol=0, atol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 4.1e-16)
    np.testing.assert_allclose(lay.drive_forces_N, short.drive_forces, rtol=0, atol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 6.9e-16)


@pytest.mark.parametrize("pin_friction", [True, False])
def test_the_thesis_chair_as_a_layout_turns_as_the_short_form_when_let_go(pin_friction):
    """The uncorrected path from the held line: the layout simulator against the thesis engine's fixed-step run
    (:func:`stability.study.veer.simulator_path`, the same release, plane and cut rules): the same arithmetic up
    to the order of sums, observed 1e-14 deg; asserted 1e-9 deg, 1e-9 deg/s and 1e-12 m, the same end."""
    from stability.study.layout_slope import layout_uncorrected_path
    from stability.study.veer import VEER_RUN, simulator_path

    c = preset("ej-premier")
    short = simulator_path(c, solve(c, 2.0, 0.75), VEER_RUN.replace(scheme="wchair", horizon=1.0),
                           pin_friction=pin_friction, report_time=1.0)
    lay = Layout.from_chair(c)
    mine = layout_uncorrected_path(lay, layout_equilibrium(lay, 2.0, 0.75), 1.0, pin_friction=pin_friction)
    assert abs(short.heading_change_deg) > 5.0 and mine.turn == short.turn == "uphill"
    assert mine.ended == short.ended and mine.report_time_s == short.report_time
    assert mine.heading_change_deg == pytest.approx(short.heading_change_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert mine.yaw_rate_deg_s == pytest.approx(short.yaw_rate_deg_s, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 1.7e-16)
    assert mine.lateral_offset_m == pytest.approx(short.lateral_offset, abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.8e-16)


def _closed_form(layout: Layout, phi_deg: float, reverse: bool) -> float:
    """Holding moment with the casters straight (trailing at 0, or at 180 deg in reverse) and no crab, one drive
    axle at ``x_w``: each caster's tire carries ``F_k = -(l/trail) m_c g2`` (its pin moment balance), the axle
    the rest of ``-m g2``; the yaw balance about C (the c.g. with the casters trailing forward) then needs
    ``M = g2 (m x_w - sum m_c (l/trail)(x_w - x_ck)) - g2 sum 2 m_c l`` (reverse only: the casters' mass swung
    ``2 l`` ahead of where C counts it), ``x_ck`` the contact, ``x_p -+ trail``."""
    g2 = layout.g * math.sin(math.radians(phi_deg))
    xw = layout.wheels[drive_wheels(layout)[0]].x
    s = -1.0 if reverse else 1.0
    m = g2 * layout.m * xw
    for c in layout.casters:
        m -= g2 * c.m_c * (c.l / c.trail) * (xw - (c.x - s * c.trail))
        if reverse:
            m -= g2 * 2.0 * c.m_c * c.l
    return m


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base", "power-rwd-base"])
@pytest.mark.parametrize("speed", [1.0, -1.0])
def test_the_holding_moment_is_the_statics_closed_form(name, speed):
    """Mid-wheel drive, front- and rear-wheel drive of one frame, forward and in reverse, 2 deg.  The closed form
    neglects the crab and caster angles (about 0.3 deg: second order in the casters' share, as the short form's
    test states for its 2e-3): observed at most 1.9e-5 relative; asserted 2e-3 (margin 100, the short form's
    tolerance)."""
    layout = layout_preset(name)
    eq = layout_equilibrium(layout, 2.0, speed)
    # error model: second order in the casters' share: the neglected crab and caster angles (observed 1.5e-5 to
    # 1.9e-5 relative), x100
    assert eq.holding_moment_N_m == pytest.approx(_closed_form(layout, 2.0, speed < 0), rel=2e-3)
    assert not eq.problems
    back = 180.0 if speed < 0 else 0.0
    # error model: first order in the casters' share of the side load: the casters swing 0.31-0.32 deg off trailing
    # (observed), the "casters straight" the closed form assumes, to within 1 deg (not a rounding bound)
    assert all(abs(a - back) < 1.0 for a in eq.caster_angles_deg)
    lo, hi = eq.friction_range_N_m
    assert lo < eq.holding_moment_N_m < hi


def test_the_thesis_chair_closed_form_is_the_short_forms():
    """The test's closed form is :func:`holding_moment_closed_form` on the thesis's chair (the same statement):
    observed 2e-16 relative; asserted 1e-12."""
    c = preset("ej-premier")
    assert _closed_form(Layout.from_chair(c), 3.0, False) == pytest.approx(
        holding_moment_closed_form(c, Plane(3.0, 0.0)), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.2e-16)


@pytest.mark.parametrize("name,speed", [("mid-wheel-drive", 1.0), ("mid-wheel-drive", -1.0),
                                        ("power-fwd-base", -0.8)])
def test_a_slope_to_the_left_needs_the_opposite_holding_moment(name, speed):
    """Mirror symmetry: crab, casters and holding moment change sign (casters about 180 deg: their offset from it),
    the friction range mirrors.  The same equations with signs changed, solved to 1e-10 of the weight: observed
    4e-15 (N m, deg) and 2.8e-14 deg for casters near 180 deg; asserted 1e-11 N m and deg, 3e-12 deg."""
    layout = layout_preset(name)
    right, left = layout_equilibrium(layout, 2.5, speed), layout_equilibrium(layout, -2.5, speed)
    assert right.holding_moment_N_m == pytest.approx(-left.holding_moment_N_m, abs=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 3.2e-16)
    assert right.heading_deg == pytest.approx(-left.heading_deg, abs=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 1.4e-16)
    np.testing.assert_allclose(right.friction_range_N_m, -np.asarray(left.friction_range_N_m)[::-1], rtol=0,
                               atol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 6.1e-16)
    back = 180.0 if speed < 0 else 0.0
    mirror = {i: j for i, a in enumerate(layout.casters) for j, b in enumerate(layout.casters)
              if a.x == b.x and a.y == -b.y}
    for i, j in mirror.items():
        # error model: rounding: the same equations with signs changed; angles near 180 deg carry ulp(180) =
        # 2.8e-14 deg (observed 2.8e-14 deg), x100
        assert right.caster_angles_deg[i] - back == pytest.approx(-(left.caster_angles_deg[j] - back), abs=3e-12)


def test_the_slope_command_answers_a_layout_and_reverse(capsys):
    assert main(["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "-1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    eq = layout_equilibrium(layout_preset("mid-wheel-drive"), 2.0, -1.0)
    assert d["chair"] == "mid-wheel-drive" and d["speed_m_s"] == -1.0
    assert d["holding_yaw_moment_signed_N_m"] == eq.holding_moment_N_m
    assert d["drive_forces"]["drive"] == "motor"
    assert set(d["uncorrected_simulator"]) == {"pin_friction", "frictionless"}
    assert main(["--chair", "ej-premier", "--cross-slope", "2", "--speed", "-0.75"]) == 0
    out = capsys.readouterr().out
    assert "0.75 m/s backwards" in out and "hand-rim forces" in out and "backing, its path bends" in out


@pytest.mark.parametrize("argv,words", [
    (["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "0"], "--speed 0 is invalid; valid range: 0.01 <= |value| <= 20 m/s"),
    (["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "1", "--set", "trail=0.06"],
     "'trail' is not a field of layout"),
    (["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "1", "-o", "x.txt"], "x.txt"),
    (["--chair", "ej-premier", "--cross-slope", "2", "--speed", "-25"], "--speed -25"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base"])
def test_the_drive_forces_alone_are_the_equilibriums(name):
    """``layout_drive_forces`` is the equilibrium's free-pin solve without the pin-friction range: the same drive
    forces exactly (the same arithmetic), forward and in reverse, and the same refusal where no equilibrium holds."""
    from stability.study.layout_slope import layout_drive_forces

    lay = layout_preset(name)
    for speed in (0.75, -0.75):
        assert layout_drive_forces(lay, 4.0, speed) == layout_equilibrium(lay, 4.0, speed).drive_forces_N
    toed = Layout(lay.name, lay.m, lay.i_z, lay.h, tuple(dataclasses.replace(w, angle_deg=1.0) for w in lay.wheels),
                  lay.casters)
    for f in (layout_drive_forces, layout_equilibrium):
        with pytest.raises(ValueError, match="angle_deg=1.0 is invalid on a slope"):
            f(toed, 4.0, 0.75)
