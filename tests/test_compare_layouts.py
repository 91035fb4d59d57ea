"""Comparing chairs as wheel layouts (stability.compare.layouts), forward and in reverse.

Independent references: the short form's comparison of the same chairs (its linear model and tipping, a separate
code path: the wiring), invariants (a frame turned round and driven backwards is the frame driven forwards; a chair
compared with itself is equal on every measure), and the command's one-line refusals.
"""

from __future__ import annotations

import dataclasses as dc
import json
import math

import pytest

from stability.chair import resolve
from stability.compare.__main__ import main
from stability.compare.compute import compare
from stability.compare.layouts import compare_layouts, stable_up_to
from stability.layout.model import Layout
from stability.layout.presets import layout_preset
from stability.tipping import tip_angles


def test_the_thesis_chairs_as_layouts_get_the_short_forms_growth_rates_and_tip_angles():
    """The E&J Premier and the revised chair: growth rates at 0.5-1.5 m/s from the layout's linear model against
    the short form's (same arithmetic to rounding: 1e-9 relative), the smallest ISO angle against the short form's
    tipping, and the same verdicts."""
    chairs = [resolve("ej-premier"), resolve("revised")]
    speeds = [0.5, 0.75, 1.0, 1.5]
    short = compare(chairs, speeds=speeds)
    mine = compare_layouts([Layout.from_chair(c) for c in chairs], speeds=speeds)
    for u in speeds:
        key = f"growth_rate_1_s@{u:g}"
        a, b = mine.quantity(key), short.quantity(key)
        for x, y in zip(a.values, b.values, strict=True):
            assert x == pytest.approx(y, rel=1e-9)
        da = next(d for d in mine.differences if d.key == key)
        db = next(d for d in short.differences if d.key == key)
        assert da.more_stable == db.more_stable
    tips = mine.quantity("static_stability_deg").values
    for c, t in zip(chairs, tips, strict=True):
        assert t == pytest.approx(tip_angles(c).smallest_deg, rel=1e-9)


def _pinned(name: str) -> Layout:
    lay = layout_preset(name)
    return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))


def test_a_frame_turned_round_compares_backwards_as_it_does_forwards():
    """The rear-wheel-drive base is the front-wheel-drive base turned round (casters' mass at their pins): its
    growth rate at -U is the other's at +U (1e-9 relative), its stable-up-to speeds swap directions, its static
    stability is the same (the tip lines are mirrored front to back)."""
    c = compare_layouts([_pinned("power-fwd-base"), _pinned("power-rwd-base")], speeds=[1.0, -1.0, 2.0, -2.0])
    for u in (1.0, 2.0):
        f, r = c.quantity(f"growth_rate_1_s@{u:g}").values, c.quantity(f"growth_rate_1_s@{-u:g}").values
        assert f[0] == pytest.approx(r[1], rel=1e-9) and r[0] == pytest.approx(f[1], rel=1e-9)
    fwd, rev = c.quantity("stable_up_to_forward_m_s").values, c.quantity("stable_up_to_reverse_m_s").values
    assert (fwd[0], rev[0]) == (rev[1], fwd[1])
    s = c.quantity("static_stability_deg").values
    assert s[0] == pytest.approx(s[1], rel=1e-12)


def test_a_chair_compared_with_itself_is_equal_on_every_measure():
    lay = layout_preset("mid-wheel-drive")
    c = compare_layouts([lay, dc.replace(lay, name="again")], speeds=[0.75, -0.75])
    assert c.differences and all(d.more_stable == "equal" for d in c.differences)
    assert all(d.absolute in (0.0, None) for d in c.differences)


def test_stable_up_to_is_the_critical_speed_or_its_bounds():
    """The mid-wheel-drive base is stable forwards at every speed searched and unstable backwards from the
    slowest (docs/layouts.md): inf and 0."""
    lay = layout_preset("mid-wheel-drive")
    assert math.isinf(stable_up_to(lay)) and stable_up_to(lay, reverse=True) == 0.0


def test_the_command_compares_any_form_forward_and_in_reverse(capsys):
    assert main(["ej-premier", "mid-wheel-drive", "--speeds", "0.75,-0.75", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert [c["label"] for c in d["chairs"]] == ["ej-premier", "mid-wheel-drive"]
    keys = {(m["measure"], m["speed_m_s"]) for m in d["measures"]}
    assert ("growth_rate_1_s", -0.75) in keys and ("stable_up_to_reverse_m_s", None) in keys
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("compare", d)


@pytest.mark.parametrize("argv, words", [
    (["ej-premier", "mid-wheel-drive", "--model", "thesis"], "--model thesis is invalid for wheel layouts"),
    (["ej-premier", "mid-wheel-drive", "--set", "2:trail=0.06"], "'trail' is not a field of layout"),
    (["ej-premier", "revised", "--speeds", "-0.75", "--uncertainty", "-", "--uncertainty", "-"],
     "--uncertainty is not available"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


def test_a_push_search_that_never_reaches_the_level_compares_as_a_bound():
    """Backing or driving a mid-wheel-drive base at 0.75 m/s, no push up to the search's largest spins it: the
    comparison carries that as a bound (inf, "level not reached with pushes up to 40 N s"), as the short form's
    comparison does, never as the largest push tried (a number that would rank it as if measured); a chair the
    search does spin keeps its found value, and the base ranks above it (bounds are values, issue 33)."""
    from stability.study.layout_impulse import layout_critical_impulses

    mwd, fwd = layout_preset("mid-wheel-drive"), layout_preset("power-fwd-base")
    c = compare_layouts([mwd, fwd], nonlinear=True)
    q = next(q for q in c.quantities if q.key.startswith("critical_impulse_Ns@0.75"))
    found = layout_critical_impulses(fwd, 0.75)[0]
    assert layout_critical_impulses(mwd, 0.75)[0].status == "never" and found.status == "found"
    assert math.isinf(q.values[0]) and q.values[1] == float(found.bound_Ns)
    assert "pushes up to 40 N s" in q.none_means
    d = next(d for d in c.differences if d.key == q.key)
    assert d.more_stable == c.labels[0]
