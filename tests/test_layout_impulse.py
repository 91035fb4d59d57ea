"""The critical impulse of any wheel layout (stability.study.layout_impulse), forward and in reverse.

Independent references: the thesis chair's own study on the thesis engine (the E&J Premier as a layout must
find the same bracket), invariants (a mirror image pushed the other way, a frame turned round and driven
backwards), the outcome's monotonicity in the push around the bracket (what the search assumes), and the
command line's one-line refusals.
"""

from __future__ import annotations

import dataclasses as dc
import json
import math

import numpy as np
import pytest
from numerics import growth_rate_tolerance
from slow_cases import one_default

from stability.chair import resolve
from stability.layout.model import Layout
from stability.layout.presets import layout_preset
from stability.settings.run import RunSpec
from stability.simulate.layout import simulate_layout
from stability.simulate.signals import time_to_level
from stability.study.__main__ import main
from stability.study.impulse import critical_impulses, push_impulse
from stability.study.layout_impulse import layout_critical_impulses, trailing_angles

#: The searches' rounding: the same search on runs equal to ~1e-15 rad (tests/test_layout_simulate.py) makes the
#: same decisions, so the brackets agree to a few ulps of their logarithms; 1e-12 leaves a factor ~100.
ROUNDING = 1e-12


def _bracket(p):
    return np.array([p.low_Ns, p.high_Ns])


def test_the_e_and_j_premier_as_a_layout_finds_the_thesis_chairs_critical_impulse():
    """The thesis chair's study (its engine, its rates and steps) and the layout study (the layout kernel, the
    layout's linear model) bracket the same push at the thesis's reference speed: 3.2558 N s in
    [3.2479, 3.2638] N s, the bracket 0.5 % wide."""
    chair = resolve("ej-premier")
    thesis = critical_impulses(chair, 0.75)[0]
    layout = layout_critical_impulses(Layout.from_chair(chair), 0.75)[0]
    assert thesis.status == layout.status == "found"
    np.testing.assert_allclose(_bracket(layout), _bracket(thesis), rtol=ROUNDING)
    # regression value (the thesis study's); rounding of its 4 typed decimals (5e-5; observed 5.9e-6)
    assert layout.impulse_Ns == pytest.approx(3.2558, abs=5e-5)
    assert layout.high_Ns / layout.low_Ns - 1.0 <= 0.005 * (1 + 1e-9)      # the stop criterion
    assert layout.push == thesis.push and layout.runs == thesis.runs


def test_the_e_and_j_premier_as_a_layout_brackets_the_same_push_at_other_speeds():
    """At 0.5 and 1 m/s the runs near the threshold agree to rounding only until a stick-slip decision differs, so
    the searches may pick other points: each bracket (0.5 % wide) must still hold the other's critical push, i.e.
    the two brackets overlap."""
    chair = resolve("ej-premier")
    speeds = [0.5, 1.0]
    for p, q in zip(critical_impulses(chair, speeds), layout_critical_impulses(Layout.from_chair(chair), speeds),
                    strict=True):
        assert p.status == q.status == "found"
        assert max(p.low_Ns, q.low_Ns) < min(p.high_Ns, q.high_Ns)


def _lopsided() -> Layout:
    base = layout_preset("power-fwd-base")
    left, right = base.casters
    return dc.replace(base, name="lopsided", casters=(dc.replace(left, pin_friction=0.15),
                                                      dc.replace(right, pin_friction=0.4)))


def _mirror(layout: Layout) -> Layout:
    return dc.replace(layout, name="mirror", wheels=tuple(dc.replace(w, y=-w.y) for w in layout.wheels),
                      casters=tuple(dc.replace(c, y=-c.y) for c in layout.casters))


def test_mirror_symmetry_push_left_equals_the_mirror_image_pushed_right():
    """A chair with unequal pin friction left and right needs a different push each way (19.4-19.5 against
    20.0-20.1 N s at 1 m/s), and its mirror image needs exactly the other one: the push's side reaches the
    runs, and the layout equations, loads and search are mirror-symmetric."""
    a, m = _lopsided(), _mirror(_lopsided())
    speeds = [1.0]
    a_right, a_left = (layout_critical_impulses(a, speeds, side=s, max_impulse=200.0) for s in ("right", "left"))
    m_right, m_left = (layout_critical_impulses(m, speeds, side=s, max_impulse=200.0) for s in ("right", "left"))
    for x, y in ((a_right, m_left), (a_left, m_right)):
        for p, q in zip(x, y, strict=True):
            assert p.status == q.status == "found"
            np.testing.assert_allclose(_bracket(p), _bracket(q), rtol=ROUNDING)
    assert a_left[0].low_Ns > a_right[0].high_Ns * 1.02     # the two sides differ by far more than a bracket
    assert "to the left" in a_left[0].push and "to the left" not in a_right[0].push
    sym = layout_preset("power-fwd-base")                   # a symmetric chair: both sides alike
    np.testing.assert_allclose(_bracket(layout_critical_impulses(sym, 1.0, side="left")[0]),
                               _bracket(layout_critical_impulses(sym, 1.0)[0]), rtol=ROUNDING)


def test_a_frame_turned_round_and_reversed_is_the_frame_driven_forward():
    """The rear-wheel-drive base is the front-wheel-drive base turned by 180 deg; with each caster's mass at its
    pin (l = 0, so that the casters trailing the other way move no mass), driving it backwards with its casters
    trailing for the reverse is driving the front-wheel-drive base forwards, the push to its right being to the
    other's left (mirror symmetry): the same critical impulse both ways, to rounding."""
    def pinned(name: str) -> Layout:
        lay = layout_preset(name)
        return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))

    fwd = layout_critical_impulses(pinned("power-fwd-base"), [1.0, -1.0], max_impulse=200.0)
    rwd = layout_critical_impulses(pinned("power-rwd-base"), [-1.0, 1.0], max_impulse=200.0)
    for p, q in zip(fwd, rwd, strict=True):
        assert p.status == q.status == "found" and p.speed == -q.speed
        np.testing.assert_allclose(_bracket(p), _bracket(q), rtol=ROUNDING)


def _reaches(layout: Layout, speed: float, impulse: float) -> tuple[bool, float]:
    run = RunSpec(stop_on_warnings=False, sample=0.001, push_force=impulse / push_impulse(1.0, 0.1))
    r = simulate_layout(layout, speed, run, caster_angles_deg=trailing_angles(layout, speed))
    t = time_to_level(r.t_s, r.yaw_rate_rad_s, 1.0)
    return t <= run.horizon, t


@pytest.mark.parametrize(("name", "speed"), one_default([("power-fwd-base", 1.0), ("power-rwd-base", -1.0),
                                                          ("mid-wheel-drive", -1.0)], ("mid-wheel-drive", -1.0)))
def test_the_outcome_is_monotone_in_the_push_around_the_bracket(name, speed):
    """What the search assumes: below the bracket's low end no push reaches the level, from its high end up every
    push does (checked at 0.5, 0.9 and 1 x low and 1, 1.1, 1.5 and 2 x high)."""
    lay = layout_preset(name)
    p = layout_critical_impulses(lay, speed, max_impulse=1000.0)[0]
    assert p.status == "found"
    assert [_reaches(lay, speed, f * p.low_Ns)[0] for f in (0.5, 0.9, 1.0)] == [False] * 3
    assert [_reaches(lay, speed, f * p.high_Ns)[0] for f in (1.0, 1.1, 1.5, 2.0)] == [True] * 4


@pytest.mark.slow
def test_drive_layouts_the_axle_leading_the_cg_diverges_after_a_nudge():
    """The three drive layouts at +-1 m/s: where the fixed axle is ahead of the c.g. in the direction of travel
    (front-wheel drive forward, rear-wheel drive in reverse; the casters trail) a push of about 11 N s (a
    sideways kick of 0.05 m/s) frees the casters and the chair diverges (the level is reached seconds after the
    push); everywhere else it takes ten times more and more, and the level is reached during the push's own
    transient: the push turns the chair, the chair does not diverge."""
    speeds = [1.0, -1.0]
    got = {n: layout_critical_impulses(layout_preset(n), speeds, max_impulse=1000.0)
           for n in ("power-fwd-base", "mid-wheel-drive", "power-rwd-base")}
    leading = [got["power-fwd-base"][0], got["power-rwd-base"][1]]
    others = [got["power-fwd-base"][1], got["power-rwd-base"][0], *got["mid-wheel-drive"]]
    assert all(p.status == "found" for p in leading + others)
    assert max(p.impulse_Ns for p in leading) * 10 < min(p.impulse_Ns for p in others)
    for p in leading:
        assert _reaches(layout_preset(p.chair_name), p.speed, 1.02 * p.high_Ns)[1] > 1.0      # diverging later
    for n, p in (("power-fwd-base", others[0]), ("power-rwd-base", others[1])):
        assert _reaches(layout_preset(n), p.speed, 1.02 * p.high_Ns)[1] < 0.5                 # the push's transient


def test_the_command_answers_a_layout_forward_and_in_reverse(capsys):
    """Text and JSON for a layout at signed speeds; the JSON keeps the study's schema."""
    assert main(["critical-impulse", "--chair", "power-rwd-base", "--speeds", "-1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    p = doc["points"][0]
    assert doc["chair"] == "power-rwd-base" and doc["chair_parameters"]["casters"][0]["x"] == 0.32
    assert p["speed_m_s"] == -1.0 and p["status"] == "found" and 10.7 < p["impulse_Ns"] < 10.9
    assert doc["options"]["speeds_m_s"] == [-1.0]
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("study_critical_impulse", doc)
    assert main(["critical-impulse", "--chair", "mid-wheel-drive", "--speeds", "0.75,-0.75"]) == 0
    out = capsys.readouterr().out
    assert "layout model" in out and "+0.75 m/s forward" in out and "-0.75 m/s reverse" in out
    assert "> 40 N s" in out and "180 deg in reverse" in out


def test_a_short_form_chair_at_a_negative_speed_runs_as_its_layout(capsys):
    assert main(["critical-impulse", "--chair", "ej-premier", "--speeds", "0.75,-0.75", "--json"]) == 0
    pts = json.loads(capsys.readouterr().out)["points"]
    # rounding of the regression value's 4 typed decimals, as above
    assert pts[0]["impulse_Ns"] == pytest.approx(3.2558, abs=5e-5) and pts[1]["speed_m_s"] == -0.75


@pytest.mark.parametrize(("argv", "words"), [
    (["--chair", "mid-wheel-drive", "--speeds", "0.75,25"], ["--speeds '0.75,25'", "0.01 to 20 m/s"]),
    (["--chair", "mid-wheel-drive", "--speeds", "0"], ["--speeds '0'", "|speed| 0.01 to 100 m/s"]),
    (["--chair", "mid-wheel-drive", "--set", "trail=0.06"], ["--set", "caster_K_FIELD"]),
    # --interval runs every case again (pin friction x0.5 and x1.5, half the step): a horizon allowed without it
    # (up to 250 s here) is refused with it, before any run
    (["--chair", "mid-wheel-drive", "--interval", "--horizon", "100"], ["--horizon=100 s", "largest allowed --horizon"]),
    (["--chair", "mid-wheel-drive", "--model", "thesis"], ["--model thesis", "valid values: exact"]),
    (["--chair", "ej-premier", "--speeds", "-0.75", "--model", "thesis"], ["--model thesis", "exact"]),
    (["--chair", "mid-wheel-drive", "--horizon", "1000"], ["--horizon=1000 s", "largest allowed --horizon"]),
    (["--chair", "ej-premier", "--speeds", "0"], ["--speeds '0'", "every speed 0.01 to 100 m/s"]),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(["critical-impulse", *argv]) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err.count("\n") == 1
    assert all(w in captured.err for w in words), captured.err


@pytest.mark.parametrize(("kwargs", "words"), [
    ({"speeds": -25.0}, "speed=-25.0"), ({"speeds": 0.0}, "speed=0.0"), ({"side": "up"}, "side='up'"),
    ({"max_impulse": 2000.0}, "max_impulse=2000.0"), ({"run": RunSpec(model="thesis")}, "model='thesis'"),
    ({"run": RunSpec(cross_slope_deg=3.0)}, "cross_slope_deg=3"), ({"min_impulse": 50.0}, "min_impulse=50.0"),
])
def test_the_api_refuses_bad_arguments_naming_them(kwargs, words):
    args = {"speeds": 1.0, **kwargs}
    with pytest.raises(ValueError, match=r"is invalid") as e:
        layout_critical_impulses(layout_preset("mid-wheel-drive"), **args)
    assert words in str(e.value) and "\n" not in str(e.value)


def test_reverse_casters_start_trailing_for_the_reverse():
    lay = layout_preset("mid-wheel-drive")
    assert trailing_angles(lay, -0.5) == [180.0] * 4 and trailing_angles(lay, 0.5) == [0.0] * 4
    # error model: rounding: 1 N x (101 steps x 0.001 s), two roundings of values near 0.1 (2 eps; observed 0), x100
    assert math.isclose(push_impulse(1.0, 0.1), 0.101, rel_tol=1e-13)


@pytest.mark.docs  # the directive imports docutils: the [docs] extra, installed in CI's docs step
def test_the_docs_directive_shows_what_the_command_prints(capsys):
    """docs/layouts.md's numbers come from docs/_ext/stability_command_output.py running the commands it shows:
    its output is the command's own, and a line that is not a command is refused."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "docs" / "_ext"))
    import stability_command_output as directive

    line = "python -m stability.study critical-impulse --chair power-fwd-base --speeds 1"
    status, text, err = directive.run_command(line)
    assert main(line.split()[3:]) == 0 and status == 0
    assert text == capsys.readouterr().out.rstrip("\n") and "+1 m/s forward      10.8 N s" in text
    assert directive.run_command("python -m stability.study critical-impulse --speeds x")[0] == 2
    with pytest.raises(ValueError, match="not a command"):
        directive.run_command("ls -l")


def test_a_slow_divergence_is_not_reported_as_robustness(capsys):
    """Backing the mid-wheel-drive base at 0.75 m/s: its linear model diverges (an eigenvalue with a positive real
    part, computed here from the state matrices), yet no push up to 40 N s spins it up to 1 rad/s. The search's
    "> 40 N s" then comes with the run that shows the divergence: the chair keeps turning away from its line (the
    heading grows over the run, past 10 deg, while the yaw rate stays below the level). Forward at 1 m/s the
    linear model is stable and nothing is added."""
    from stability.layout.linear import state_matrices
    from stability.study.layout_impulse import slow_divergences

    lay = layout_preset("mid-wheel-drive")
    a_rev, a_fwd = state_matrices(lay, [-0.75, 1.0])
    growth = float(np.max(np.linalg.eigvals(a_rev).real))
    assert growth > 0.1 and float(np.max(np.linalg.eigvals(a_fwd).real)) < 0.0
    points = layout_critical_impulses(lay, [-0.75, 1.0])
    assert [p.status for p in points] == ["never", "never"]
    (slow,) = slow_divergences(lay, points)
    # error model: the eigenvalues' rounding, n eps ||A|| kappa_i per computation (tests/numerics.py: 6.9e-7 1/s
    # with its margin of 100; observed 0, the same matrix through the same LAPACK call)
    assert slow.speed == -0.75 and math.isclose(slow.growth_rate, growth, rel_tol=0,
                                                abs_tol=growth_rate_tolerance(a_rev))
    assert slow.push_Ns == points[0].largest_tried_Ns and slow.peak_yaw_rate < 1.0
    # error model: the step grid: the run's last sample is the first step at or past the 10 s horizon, within one
    # 1 ms step of it (observed 1.0e-3 past it); the rounding of the summed time is n eps t ~ 2e-11 s
    assert abs(slow.heading_deg) > 10.0 and slow.end_time_s == pytest.approx(10.0, abs=2e-3)
    force = slow.push_Ns / push_impulse(1.0, 0.1)
    half = simulate_layout(lay, -0.75, RunSpec(push_force=force, horizon=5.0),
                           caster_angles_deg=trailing_angles(lay, -0.75))
    assert abs(half.heading_deg[-1]) < abs(slow.heading_deg)          # still turning away at the end
    assert main(["critical-impulse", "--chair", "mid-wheel-drive", "--speeds=-0.75", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["slow_divergences"] == [slow.to_dict()]
