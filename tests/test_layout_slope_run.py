"""The layout simulator on a plane, with rolling resistance and camber (stability.simulate.layout).

Independent statements used:

- wiring: the thesis's chair as a layout (two fixed wheels, two casters) on a cross slope and a grade, with the
  Appendix B rolling resistance on every wheel and 3 deg of main-wheel camber, is the thesis engine's run of the
  short form (``stability.simulate.simulate``: the thesis model's generated slope accelerations, eq 6-25 loads
  under the normal weight, MECHAN's rolling and camber forces) while the tires stay inside their data;
- on a grade with no cross slope, no push and no rolling resistance the chair runs straight and its speed changes
  at ``-g sin(theta)`` (every body's weight has the forward component ``-m_i g sin(theta)``; nothing else acts along
  the path);
- mirror symmetry: a symmetric layout on a cross slope falling to the left runs the mirror image of its run on the
  slope falling to the right.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stability.chair import preset
from stability.layout import Layout
from stability.layout.presets import layout_preset
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.simulate.layout import simulate_layout


def _premier_rolling_camber():
    return preset("ej-premier").replace(main_rolling_scale=1.0, caster_rolling_scale=1.0, camber_deg=3.0)


def _inside_data(run) -> int:
    """Rows before the first slip or load warning (the tires beyond their data), else all."""
    firsts = [w["first_time_s"] for w in run.warnings.values() if w["first_time_s"] is not None]
    if not firsts:
        return len(run.t_s)
    return int(np.searchsorted(run.t_s, min(firsts) - 0.01))


@pytest.mark.parametrize("law", ["kinetic", "stick-slip"])
@pytest.mark.parametrize("cross,grade,speed", [(2.0, 1.0, 0.75), (-3.0, 0.0, 1.0), (0.0, -2.0, 0.75),
                                               (1.5, 0.0, -0.75)])
def test_the_thesis_chair_as_a_layout_is_the_thesis_engine_on_a_slope(law, cross, grade, speed):
    """Heading, speed and caster angle after the reference push, 3 s, rolling resistance and camber on, compared
    while the tires are inside their data (before the first range warning; a tire beyond its data is clamped at
    kinks where a rounding difference changes a step's force discontinuously).  The same scheme, step, tire law
    and generated physics; the accelerations by a numeric solve of the mass matrix instead of the generated closed
    form and the loads by a linear solve instead of the stepwise elimination: about 1e-16 relative per step,
    amplified by the runs' growth (e^4.5 over 3 s).  Observed at most 2.6e-12 (rad, m/s); asserted 1e-9 (margin
    400)."""
    c = _premier_rolling_camber()
    angles = [180.0, 180.0] if speed < 0 else [0.0, 0.0]
    run = RunSpec(horizon=3.0, friction_law=law, cross_slope_deg=cross, grade_deg=grade, stop_on_warnings=False)
    ours = simulate_layout(Layout.from_chair(c), speed, run, caster_angles_deg=angles)
    theirs = simulate(c, abs(speed), run.replace(reverse=speed < 0, eta0_deg=angles[0], beta0_deg=angles[1]))
    n = _inside_data(ours)
    assert n >= 900 and len(theirs.t) == len(ours.t_s)           # at least 0.9 s inside the data
    assert np.abs(ours.heading_rad[:n]).max() > 0.05               # the slope and the push turned the chair
    assert abs(ours.u_m_s[n - 1] - ours.u_m_s[0]) > 1e-3           # rolling resistance and the grade act
    for mine, ref in ((ours.heading_rad, theirs.heading), (ours.u_m_s, theirs.u), (ours.v_m_s, theirs.v),
                      (ours.caster_angle_rad[0], theirs.eta), (ours.caster_angle_rad[1], theirs.beta)):
        # error model: rounding: ~eps per step grown by e^4.5 over 3 s (observed at most 2.6e-12, the lateral
        # speed at 2 deg cross and 1 deg grade), x400
        assert np.abs(mine[:n] - np.asarray(ref)[:n]).max() <= 1e-9


@pytest.mark.parametrize("name,speed", [("mid-wheel-drive", 1.0), ("mid-wheel-drive", -1.0),
                                        ("power-fwd-base", 0.8)])
def test_on_a_grade_alone_the_speed_changes_at_g_sin_theta(name, speed):
    """No push, no cross slope, no rolling resistance, casters trailing: the chair runs straight and
    ``du/dt = -g sin(theta)`` (the scheme integrates a constant acceleration exactly up to the rounding of 1000
    additions, about 1000 x 1e-16 m/s: observed 1.1e-13 m/s over 1 s); asserted 1e-11 m/s (margin 100), and
    heading and caster angles stay at their start (1e-12: observed 0)."""
    layout = layout_preset(name)
    theta = -2.5
    angles = [180.0 if speed < 0 else 0.0] * len(layout.casters)
    r = simulate_layout(layout, speed, RunSpec(horizon=1.0, push_force=0.0, grade_deg=theta),
                        caster_angles_deg=angles)
    expected = speed - layout.g * math.sin(math.radians(theta)) * r.t_s
    # error model: rounding of 1000 additions of a constant acceleration, ~1000 eps |u| (observed 1.1e-13 m/s), x100;
    # heading and casters: rounding of a straight run's zero side forces (observed 5.3e-17 rad and 0)
    assert np.abs(r.u_m_s - expected).max() <= 1e-11
    assert np.abs(r.heading_rad).max() <= 1e-12
    assert np.abs(r.caster_angle_rad - np.radians(angles)[:, None]).max() <= 1e-12


@pytest.mark.parametrize("name,speed", [("mid-wheel-drive", 0.8), ("mid-wheel-drive", -0.8),
                                        ("power-rwd-base", 1.0)])
def test_a_slope_to_the_left_runs_the_mirror_image_of_a_slope_to_the_right(name, speed):
    """No push: the cross slope alone turns the chair.  Falling to the left, heading and lateral path change sign
    and the mirrored casters exchange their angles with the sign changed (about pi when reversing).  The same
    arithmetic with signs changed except sums in another order: observed 1e-15 rad; asserted 1e-10 rad."""
    layout = layout_preset(name)
    angles = [180.0 if speed < 0 else 0.0] * len(layout.casters)
    run = RunSpec(horizon=2.0, push_force=0.0, cross_slope_deg=2.0, stop_on_warnings=False)
    right = simulate_layout(layout, speed, run, caster_angles_deg=angles)
    left = simulate_layout(layout, speed, run.replace(cross_slope_deg=-2.0), caster_angles_deg=angles)
    assert np.abs(right.heading_deg).max() > 1.0                  # the slope turns it
    # error model: mirror images: the same arithmetic with signs changed, rounding where sums are taken in another
    # order, grown over the run's steps (observed 2.8e-16 and 0), margin > 1e5
    np.testing.assert_allclose(right.heading_rad, -left.heading_rad, rtol=0, atol=1e-10)
    np.testing.assert_allclose(right.y_m, -left.y_m, rtol=0, atol=1e-10)
    np.testing.assert_allclose(right.u_m_s, left.u_m_s, rtol=0, atol=1e-10)
    pairs = [(i, j) for i, a in enumerate(layout.casters) for j, b in enumerate(layout.casters)
             if a.x == b.x and a.y == -b.y and a.y < 0]
    assert pairs
    for i, j in pairs:
        a, b = right.caster_angle_rad[i], left.caster_angle_rad[j]
        mirrored = np.angle(np.exp(1j * (a + b)))                  # delta -> -delta, modulo 2 pi
        np.testing.assert_allclose(mirrored, 0.0, rtol=0, atol=1e-10)     # rounding, as above (observed 0)


def test_a_fixed_wheel_on_the_centre_line_has_no_camber():
    from stability.layout import FixedWheel

    with pytest.raises(ValueError, match="camber_deg=2.0 is invalid for a wheel on the centre line"):
        FixedWheel(0.0, 0.0, camber_deg=2.0)
    with pytest.raises(ValueError, match="rolling_scale=-1.0 is invalid"):
        FixedWheel(0.0, 0.2, rolling_scale=-1.0)


def test_the_simulate_command_runs_a_layout_on_a_slope(capsys):
    import json

    from stability.simulate.__main__ import main

    assert main(["--chair", "mid-wheel-drive", "--cross-slope", "2", "--grade", "-1", "--horizon", "1",
                 "--push-force", "0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    direct = simulate_layout(layout_preset("mid-wheel-drive"), 0.75,
                             RunSpec(horizon=1.0, push_force=0.0, cross_slope_deg=2.0, grade_deg=-1.0))
    assert d["final_heading_deg"] == direct.final_heading_deg and d["settings"]["cross_slope_deg"] == 2.0
    assert main(["--chair", "mid-wheel-drive", "--cross-slope", "2", "--horizon", "1"]) == 0
    assert "on a cross slope of 2 deg and a grade of 0 deg" in capsys.readouterr().out
