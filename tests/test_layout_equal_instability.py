"""The equal-instability speed of any wheel layout (stability.study.layout_equal_instability), forward and in reverse.

Independent references: the definition's fixed point (the reference chair is as unstable as itself at the
reference speed, whichever engine runs it), the thesis engine's study of a short-form chair (the same chair as a
layout must find the same speed: the wiring), and invariants (a frame turned round and driven backwards is the
frame driven forwards; a mirror image pushed the other way).  Then the command line.
"""

from __future__ import annotations

import dataclasses as dc
import json

import pytest

from stability.chair import resolve
from stability.layout.model import Layout
from stability.layout.presets import layout_preset
from stability.settings.reference import REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study.__main__ import main
from stability.study.equal_instability import equal_instability_speed
from stability.study.intervals import equal_instability_interval
from stability.study.layout_equal_instability import (
    layout_equal_instability,
    layout_equal_instability_interval,
    scale_layout_friction,
)

#: The searches' rounding: runs equal to ~1e-15 rad (tests/test_layout_simulate.py) make the same decisions, so
#: the speeds agree to a few ulps (observed 4e-16 m/s); 1e-12 relative leaves a factor of more than 100.
ROUNDING = 1e-12


def test_the_reference_chair_as_a_layout_is_as_unstable_as_itself_at_the_reference_speed():
    """The E&J Premier is the reference case: its equal-instability speed is the reference speed, 0.75 m/s, to the
    search's final bracket (tol 5 mm/s; observed 0.750008 m/s), whichever engine runs it."""
    r = layout_equal_instability(Layout.from_chair(resolve("ej-premier")))
    assert r.status == "found"
    assert r.low <= REFERENCE_SPEED <= r.high and r.high - r.low <= 0.005 + 1e-12
    assert r.speed == pytest.approx(REFERENCE_SPEED, abs=0.005)


def test_a_short_form_chair_as_a_layout_finds_the_thesis_engines_speed():
    """The revised chair (not the reference: 1.02 m/s) on the layout runs and on the thesis engine: the same
    search on runs equal to rounding finds the same speed, and the range's variants (push, friction, step) too."""
    chair = resolve("revised")
    a, b = layout_equal_instability(Layout.from_chair(chair)), equal_instability_speed(chair)
    assert a.status == b.status == "found"
    assert a.speed == pytest.approx(b.speed, rel=ROUNDING)
    assert a.speed == pytest.approx(1.0248, abs=5e-4)                     # regression value (the thesis engine's)
    li = layout_equal_instability_interval(Layout.from_chair(chair))
    si = equal_instability_interval(chair, models=("exact",))
    assert [v.label for v in li.variants] == [v.label for v in si.variants]
    for v, w in zip(li.variants, si.variants, strict=True):
        assert (v.speed is None) == (w.speed is None)
        if v.speed is not None:
            assert v.speed == pytest.approx(w.speed, rel=ROUNDING)
    assert li.low == pytest.approx(si.low, rel=ROUNDING) and li.high == pytest.approx(si.high, rel=ROUNDING)


def _pinned(name: str) -> Layout:
    lay = layout_preset(name)
    return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))


def test_a_frame_turned_round_and_reversed_is_the_frame_driven_forward():
    """The rear-wheel-drive base turned by 180 deg is the front-wheel-drive base; with each caster's mass at its
    pin (so that casters trailing the other way move no mass) its equal-instability speed backwards is the other's
    forwards, to rounding (observed 1.6784 m/s under an 80 N push; the 40 N push leaves both above 3 m/s)."""
    run = RunSpec(push_force=80.0)
    f = layout_equal_instability(_pinned("power-fwd-base"), run)
    r = layout_equal_instability(_pinned("power-rwd-base"), run, reverse=True)
    assert f.status == r.status == "found"
    assert r.speed == pytest.approx(f.speed, rel=ROUNDING)
    assert 0.2 < f.speed < 3.0


def test_mirror_symmetry_and_the_push_side():
    """A base with unequal pin friction left and right is pushed right, its mirror image left: the same speed to
    rounding; pushed the other way it needs another speed (1.925 against 1.935 m/s observed), so the side
    reaches the runs."""
    lop = layout_preset("power-fwd-base")
    left, right = lop.casters
    lop = dc.replace(lop, casters=(dc.replace(left, pin_friction=0.1), dc.replace(right, pin_friction=0.25)))
    mirror = dc.replace(lop, wheels=tuple(dc.replace(w, y=-w.y) for w in lop.wheels),
                        casters=tuple(dc.replace(c, y=-c.y) for c in lop.casters))
    a = layout_equal_instability(lop, RunSpec(push_force=80.0))
    b = layout_equal_instability(mirror, RunSpec(push_force=-80.0))
    c = layout_equal_instability(lop, RunSpec(push_force=-80.0))
    assert a.status == b.status == c.status == "found"
    assert b.speed == pytest.approx(a.speed, rel=ROUNDING)
    assert abs(c.speed - a.speed) > 2 * 0.005                    # beyond the two searches' brackets


def test_scale_layout_friction_scales_every_pin():
    lay = layout_preset("mid-wheel-drive")
    assert scale_layout_friction(lay, 1.0) is lay
    assert [c.pin_friction for c in scale_layout_friction(lay, 0.5).casters] == [0.5 * c.pin_friction
                                                                                 for c in lay.casters]


def test_the_command_answers_a_layout_and_reverse(capsys):
    assert main(["equal-instability", "--chair", "power-fwd-base", "--push-force", "80", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["direction"] == "forward" and d["status"] == "found" and d["chair"] == "power-fwd-base"
    assert d["speed_m_s"] == pytest.approx(layout_equal_instability(layout_preset("power-fwd-base"),
                                                                    RunSpec(push_force=80.0), tol=0.01).speed,
                                           rel=ROUNDING)
    assert "model" not in {f["factor"] for f in d["factors"]}
    schemas = pytest.importorskip("stability.schemas")
    pytest.importorskip("jsonschema")
    schemas.validate("study_equal_instability", d)
    assert main(["equal-instability", "--chair", "ej-premier", "--reverse"]) == 0
    out = capsys.readouterr().out
    assert "in reverse" in out and "backwards" in out and "180 deg" in out


@pytest.mark.parametrize("argv, words", [
    (["--chair", "mid-wheel-drive", "--model", "thesis"], "--model thesis is invalid for a layout"),
    (["--chair", "mid-wheel-drive", "--set", "trail=0.06"], "'trail' is not a field of layout"),
    (["--chair", "ej-premier", "--reverse", "--model", "thesis"], "valid values: exact"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(["equal-instability", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err
