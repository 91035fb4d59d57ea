"""The virtual test bench (stability.bench): statics, closed forms and symmetry.

Independent statements used:

- at zero acceleration on level ground the bench's loads are the layout's static loads;
- tilting the plane with no acceleration, the chair tips (score 3) exactly where the gravity line through the c.g.
  reaches the edge of its support polygon: ``tan(alpha) = rho / h`` with ``rho`` from
  :func:`stability.tipping.angles.support_fall_distance` (the tipping module's gauge minimisation over fixed
  contacts, not the bench's polygon test);
- an acceleration is a tilt: ``(a_x, 0)`` on level ground moves the effective centre as a grade of
  ``atan(a_x / g)`` does, with the normal load scaled by ``cos``;
- the braking distance of a constant deceleration ``a`` from ``v`` after a delay ``t`` is ``v t + v^2 / (2 a)``;
- turning left is the mirror image of turning right.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stability.bench import Drive, braking_distance, case_loads, run_bench
from stability.bench.loads import polygon_margin
from stability.layout import Layout, static_loads
from stability.layout.presets import layout_preset, layout_preset_names
from stability.layout.statics import contacts
from stability.tipping.angles import support_fall_distance


@pytest.mark.parametrize("name", layout_preset_names())
def test_level_and_still_is_the_static_loads(name):
    layout = layout_preset(name)
    c = case_loads(layout)
    assert c.score == 0 and c.lifted == ()
    assert np.allclose(c.loads_N, static_loads(layout), rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def _tip_grade(layout: Layout, direction: str) -> float:
    """The plane angle at which the bench first scores 3 (bisection to 1e-6 deg)."""
    lo, hi = 0.0, 89.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        grade = {"forward": -mid, "backward": mid}.get(direction, 0.0)
        cross = {"right": mid, "left": -mid}.get(direction, 0.0)
        if case_loads(layout, 0.0, 0.0, grade, cross).score == 3:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("name", layout_preset_names())
@pytest.mark.parametrize("direction", ["forward", "backward", "right"])
def test_tipping_on_a_slope_is_where_the_gravity_line_leaves_the_support(name, direction):
    """The bench's tip angle against the tipping module's gauge over the same (trailing) contacts: tan(alpha) =
    rho / h exactly on a grade; on a cross slope the grade of the bench is the plane's full tilt (observed
    agreement 1e-6 deg, the bisection's; asserted 1e-4)."""
    layout = layout_preset(name)
    pts = [(x, y, 0.0) for _, x, y, _ in contacts(layout)]
    e = {"forward": (1.0, 0.0), "backward": (-1.0, 0.0), "right": (0.0, 1.0)}[direction]
    expected = support_fall_distance(pts, layout.h, *e).angle_deg
    assert _tip_grade(layout, direction) == pytest.approx(expected, abs=1e-4)  # rounding: equivalent arithmetic, a few ulp (observed 3.7e-16)


def test_an_acceleration_is_a_tilt():
    """Braking at a on level ground shifts the effective centre as the plane tilted forward by atan(a/g) does
    (the normal load differs by cos, the centre not at all): the loads agree after scaling."""
    layout = layout_preset("mid-wheel-drive")
    a = 1.2
    braking = case_loads(layout, -a, 0.0, 0.0, 0.0)
    tilt = case_loads(layout, 0.0, 0.0, -math.degrees(math.atan(a / layout.g)), 0.0)
    assert braking.centre_m == pytest.approx(tilt.centre_m, abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.2e-16)
    scale = braking.loads_N.sum() / tilt.loads_N.sum()
    assert scale == pytest.approx(1.0 / math.cos(math.atan(a / layout.g)), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert np.allclose(braking.loads_N, tilt.loads_N * scale, rtol=1e-10)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_braking_distance_closed_form_and_the_bench_stops():
    assert braking_distance(2.0, 2.0) == pytest.approx(1.0, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert braking_distance(2.0, 2.0, delay=0.5) == pytest.approx(2.0, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert braking_distance(2.0, 9.81 * math.sin(math.radians(6.0)), downhill_deg=6.0) == math.inf
    drive = Drive(max_speed_m_s=2.0, decel_m_s2=1.0, traction=2.0)
    r = run_bench(layout_preset("power-rwd-base"), drive)
    stop = next(c for c in r.cases if c.name == "forward stop, control released" and c.slope == "level")
    assert stop.limited_by == "" and stop.braking_distance_m == pytest.approx(2.0 ** 2 / (2 * 1.0), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    cut = next(c for c in r.cases if c.name == "forward stop, power cut" and c.slope == "downhill")
    a = drive.brake_decel_m_s2 - 9.81 * math.sin(math.radians(drive.max_slope_deg))
    assert cut.braking_distance_m == pytest.approx(2.0 * drive.brake_delay_s + 2.0 ** 2 / (2 * a), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_turning_left_mirrors_turning_right():
    r = run_bench(layout_preset("mid-wheel-drive"))
    right = [c for c in r.cases if c.name.startswith("turn right")]
    left = [c for c in r.cases if c.name.startswith("turn left")]
    for a, b in zip(right, left, strict=True):
        assert a.score == b.score
        assert a.loads.centre_m[1] == pytest.approx(-b.loads.centre_m[1], abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_stopping_pitches_a_mid_wheel_drive_base_forward():
    """Stopping forward moves the load forward: the rear casters unload first (a mid-wheel-drive base rocks onto its
    front casters), and the worst case is a stop."""
    layout = layout_preset("mid-wheel-drive")
    loads = [case_loads(layout, -a).loads_N for a in (0.0, 1.0, 2.0)]
    rear = [x[4] + x[5] for x in loads]
    front = [x[2] + x[3] for x in loads]
    assert rear[0] > rear[1] > rear[2] >= 0 and front[0] < front[1] < front[2]


def test_polygon_margin_of_a_square():
    sq = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    assert polygon_margin(sq, (0.5, 0.5)) == pytest.approx(0.5, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert polygon_margin(sq, (0.5, 1.25)) == pytest.approx(-0.25, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert polygon_margin(sq, (2.0, 2.0)) == pytest.approx(-math.sqrt(2), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_anti_tip_devices_catch_the_chair():
    """A rear-caster chair tipping toward its main wheels with anti-tip devices beyond them scores 2 where it
    would score 3 without."""
    from stability.chair import preset

    bare = Layout.from_chair(preset("ej-premier"))
    guarded = Layout.from_chair(preset("ej-premier").replace(anti_tip_reach=0.3))
    grade = -(_tip_grade(bare, "forward") + 2.0)           # past the main wheels' edge
    assert case_loads(bare, 0.0, 0.0, grade, 0.0).score == 3
    assert case_loads(guarded, 0.0, 0.0, grade, 0.0).score == 2


def test_bench_command_and_refusals(capsys):
    from stability.bench.__main__ import main

    assert main(["--chair", "mid-wheel-drive"]) == 0
    out = capsys.readouterr().out
    assert "forward stop, power cut" in out and "Worst score" in out
    assert main(["--max-speed", "50"]) == 2
    assert "--max-speed 50 is invalid; valid range: 0.1 <= value <= 10 m/s" in capsys.readouterr().err
    with pytest.raises(ValueError, match="traction"):
        Drive(traction=0.0)


@pytest.mark.parametrize("name", layout_preset_names())
def test_a_traction_limited_stop_is_held_by_the_grip_of_its_own_state(name):
    """Where traction limits a start or stop, the drive force equals the drive wheels' grip in the state it
    produces, ``m |a + g sin(grade)| = mu N_driven(a)`` (an invariant of the quasi-static balance, checked from the
    case's own loads); the tolerance is the root's ``xtol`` 1e-12 m/s^2 times the mass, times 100.  And braking
    harder never stops a chair later: a reverse command asking for more than the released control's deceleration
    stops it at least as soon, on every slope (the limit is the grip, whatever is asked beyond it)."""
    layout = layout_preset(name)
    drive = Drive(reverse_decel_m_s2=8.0)
    r = run_bench(layout, drive)
    driven = {f"wheel {j}" for j, w in enumerate(layout.wheels) if w.driven}
    limited = [c for c in r.cases if c.limited_by == "traction of the drive wheels"]
    assert limited
    for c in limited:
        grip = drive.traction * sum(n for (lab, *_), n in zip(contacts(layout), c.loads.loads_N, strict=True)
                                    if lab in driven)
        force = layout.m * abs(c.ax_m_s2 + layout.g * math.sin(math.radians(c.grade_deg)))
        assert force == pytest.approx(grip, rel=0, abs=100 * 1e-12 * layout.m + 1e-9 * grip)  # rounding: equivalent arithmetic, a few ulp (observed 4.6e-16)
    for direction in ("forward", "rearward"):
        for slope in {c.slope for c in r.cases if c.name.startswith(f"{direction} stop")}:
            rel = next(c for c in r.cases if c.name == f"{direction} stop, control released" and c.slope == slope)
            rev = next(c for c in r.cases if c.name == f"{direction} stop, reverse command" and c.slope == slope)
            assert rev.braking_distance_m <= rel.braking_distance_m * (1 + 1e-12)


def test_a_chair_cannot_brake_itself_over_an_edge_its_braking_wheels_leave():
    """Quasi-statically a chair tips forward over its front contacts only if the braking force survives to the
    tip: a rear-wheel-drive base braking on its rear wheels unloads them as it pitches onto its front casters, so
    however hard the stop is asked (15 m/s^2, grip 2) it stays on its wheels, limited by traction; a front-wheel-
    drive chair brakes on the wheels of its tipping edge, keeps its grip to the tip, and goes over."""
    hard = Drive(reverse_decel_m_s2=15.0, brake_decel_m_s2=15.0, traction=2.0)
    rwd = run_bench(layout_preset("power-rwd-base"), hard)
    for c in (c for c in rwd.cases if c.name.startswith("forward stop")):
        assert c.score <= 1 and c.limited_by in ("", "traction of the drive wheels"), c
    assert any(c.limited_by == "traction of the drive wheels" for c in rwd.cases if c.name.startswith("forward stop"))
    fwd = run_bench(layout_preset("power-fwd-base"), hard)
    assert any(c.score >= 2 for c in fwd.cases if c.name.startswith("forward stop"))


def test_bench_pdf_one_page_per_family_with_its_conclusion(tmp_path, capsys):
    """``-o FILE.pdf``: a page per manoeuvre family, each titled with the chair and saying what to conclude from its
    own cases (the worst case and its score); a suffix that is not .pdf is refused before any work, nothing written."""
    from pypdf import PdfReader

    from stability.bench.__main__ import main

    out = tmp_path / "bench.pdf"
    assert main(["--chair", "power-fwd", "-o", str(out)]) == 0
    pages = [p.extract_text() for p in PdfReader(out).pages]
    assert len(pages) == 3
    r = run_bench(Layout.from_chair(__import__("stability.chair", fromlist=["preset"]).preset("power-fwd")))
    for text, family in zip(pages, ("start", "stop", "turn"), strict=True):
        worst = max(c.score for c in r.cases if c.family == family)
        assert "power-fwd: virtual bench" in text and f"scores {worst}" in text.replace("\n", " ")
    assert "braking distance" in pages[1]
    capsys.readouterr()
    assert main(["--chair", "power-fwd", "-o", str(tmp_path / "bench.png")]) == 2
    assert "valid: .pdf" in capsys.readouterr().err and not (tmp_path / "bench.png").exists()
