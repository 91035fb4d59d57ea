"""Caster shimmy for any wheel layout (stability.shimmy.layout_caster, ``shimmy --chair mid-wheel-drive``)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from slow_cases import one_default

from stability import chair as chair_mod
from stability.layout import Layout
from stability.layout.presets import layout_preset
from stability.shimmy.__main__ import main
from stability.shimmy.band import shimmy_band
from stability.shimmy.chair import caster_summary, caster_wheel
from stability.shimmy.layout_caster import LayoutCaster, layout_casters

EJ = chair_mod.preset("ej-premier")
SPEEDS = [0.5, 1.0, 2.0]


def test_the_thesis_chair_as_a_layout_has_its_own_shimmy_answer():
    """The E&J Premier expanded into a layout: the caster's static load at every trail equals the short form's
    generated eq 6-25 loads (the layout's lever rule on two support lines, an independent statics), so the
    towed wheel, its bands, margins and friction trails are the short form's exactly (the same arithmetic on
    equal inputs: tolerance 1e-9 relative)."""
    lc = layout_casters(Layout.from_chair(EJ))
    assert len(lc) == 2
    from stability.models.params import parameters
    from stability.models.statics import normal_loads

    trails = np.array([0.01, 0.05, 0.1, 0.2])
    assert lc[0].loads(trails) == pytest.approx(normal_loads(parameters(EJ)._replace(trail=trails))[0], rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    a, b = shimmy_band(EJ, SPEEDS), shimmy_band(lc[0], SPEEDS)
    assert np.array(b.intervals_m, dtype=object).shape == np.array(a.intervals_m, dtype=object).shape
    for ia, ib in zip(a.intervals_m, b.intervals_m, strict=True):
        assert np.array(ib) == pytest.approx(np.array(ia), rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert b.margin_m == pytest.approx(a.margin_m, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    sa, sb = caster_summary(EJ, [1.0]), caster_summary(lc[1], [1.0])
    assert sb.friction_trail == pytest.approx(sa.friction_trail, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_layout_caster_is_the_towed_wheel_at_its_own_load():
    """Each caster row of the mid-wheel-drive base is a towed wheel at its own static load: the lighter rear
    casters have the smaller cornering stiffness, and the statics' loads add up to the weight."""
    lay = layout_preset("mid-wheel-drive")
    lc = layout_casters(lay)
    loads = [c.static_load() for c in lc]
    from stability.layout import static_loads

    assert sum(static_loads(lay)) == pytest.approx(lay.m * lay.g, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    front = [c for c in lc if lay.casters[c.index].x > 0]
    rear = [c for c in lc if lay.casters[c.index].x < 0]
    assert front and rear and max(c.static_load() for c in rear) < min(c.static_load() for c in front)
    w_front, w_rear = caster_wheel(front[0]), caster_wheel(rear[0])
    tire = front[0].caster_tire_model()
    assert w_front.cornering_stiffness == pytest.approx(tire.cornering_stiffness_per_rad(front[0].static_load()), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert w_rear.cornering_stiffness < w_front.cornering_stiffness
    assert all(n > 0 for n in loads)


def test_a_row_changes_its_trail_together():
    """Varying a caster's trail moves its left-right partner too (a chair's trail is the pair's): the base stays
    symmetric, so both casters of the row keep equal loads."""
    lay = layout_preset("mid-wheel-drive")
    c0 = LayoutCaster(lay, 0).replace(trail=0.08)
    xs = [(c.x, c.trail) for c in c0.layout.casters]
    # error model: rounding: a row's casters keep the pin x as given, to a few ulp (rows lie centimetres apart)
    same_row = [t for x, t in xs if abs(x - lay.casters[0].x) < 1e-9]
    assert same_row == [0.08, 0.08]
    assert c0.static_load() == pytest.approx(LayoutCaster(c0.layout, 1).static_load(), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    with pytest.raises(ValueError, match="index=9"):
        LayoutCaster(lay, 9)
    with pytest.raises(ValueError, match="cannot be replaced"):
        LayoutCaster(lay, 0).replace(m_c=2.0)


def test_shimmy_command_answers_a_layout(capsys):
    assert main(["--chair", "mid-wheel-drive", "--speeds", "0.5,1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["layout"] == "mid-wheel-drive"
    assert len(doc["casters"]) == 2                          # front pair and rear pair, one answer each
    assert all(math.isfinite(c["static_load_N"]) for c in doc["casters"])
    assert main(["--chair", "mid-wheel-drive", "--chair-model"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--chair-model" in err


def test_every_caster_field_reaches_the_towed_wheel():
    """A chair with non-default caster mass, tire scale and pin friction, expanded into a layout, gives the same
    towed wheel as the short form (each field travels: mass, inertia, c.g., trail, cornering stiffness, damping,
    friction)."""
    c = EJ.replace(m_c=1.5, i_zp=0.009, caster_lateral_scale=0.8, pin_friction_left=0.25, pin_friction_right=0.25,
                   pin_damping=0.02)
    lc = layout_casters(Layout.from_chair(c))[0]
    a, b = caster_wheel(c), caster_wheel(lc)
    for name in ("mass", "inertia", "contact_behind_cm", "pivot_ahead_of_cm", "cornering_stiffness", "pin_damping",
                 "pin_friction"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-12), name  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert (b.mass, b.pin_friction) == (1.5, 0.25)


def _turned(lay: Layout) -> Layout:
    """``lay`` turned by 180 deg about the vertical (x and y flip), its origin moved so that it is again the
    system's centre of mass with every caster trailing forward in the turned frame: driving the turned layout
    backwards puts every contact and mass where driving ``lay`` forwards does."""
    from dataclasses import replace

    e = sum(c.m_c * 2.0 * c.l for c in lay.casters) / lay.m
    return replace(lay, name=lay.name + " turned",
                   wheels=tuple(replace(w, x=-w.x + e, y=-w.y) for w in lay.wheels),
                   casters=tuple(replace(c, x=-c.x + e, y=-c.y) for c in lay.casters),
                   anti_tip=tuple((-x + e, -y) for x, y in lay.anti_tip))


@pytest.mark.parametrize("name", one_default(["mid-wheel-drive", "ej-premier"], "mid-wheel-drive"))
def test_reversing_the_turned_chair_is_driving_it_forwards(name):
    """Invariant: a chair turned round and driven backwards is the chair driven forwards.  Every caster of the
    turned layout in reverse has the forward caster's static load and so its whole shimmy answer (band, margin,
    frequency, friction trail); the arithmetic differs (reversed statics about a moved origin), so equality is to
    round-off (observed about 1e-13 relative; asserted 1e-9)."""
    lay = layout_preset(name) if name != "ej-premier" else Layout.from_chair(EJ)
    fwd, rev = layout_casters(lay), layout_casters(_turned(lay), reverse=True)
    for a, b in zip(fwd, rev, strict=True):
        assert b.static_load() == pytest.approx(a.static_load(), rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 4.9e-16)
        trails = np.array([0.02, 0.05, 0.09])
        assert b.loads(trails) == pytest.approx(a.loads(trails), rel=1e-9, nan_ok=True)  # rounding: equivalent arithmetic, a few ulp (observed 4.9e-16)
    sa, sb = caster_summary(fwd[0], [1.0]), caster_summary(rev[0], [1.0])
    for field in ("shimmy_frequency_hz", "shimmy_growth_rate", "critical_trail", "friction_trail"):
        assert getattr(sb, field) == pytest.approx(getattr(sa, field), rel=1e-9), field  # rounding: equivalent arithmetic, a few ulp (observed 0)
    ba, bb = shimmy_band(fwd[0], SPEEDS), shimmy_band(rev[0], SPEEDS)
    assert bb.margin_m == pytest.approx(ba.margin_m, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_reverse_loads_follow_the_lever_rule():
    """The E&J in reverse: its casters swing round, each contact moves ``2 trail`` toward the main wheels and each
    caster's mass ``2 l1`` with it; on two support lines the caster pair carries the weight times the c.g.'s
    distance from the main-wheel line over the contact line's (the lever rule, computed here by hand from the
    chair's fields).  A 1e-9 relative tolerance (round-off)."""
    lay = Layout.from_chair(EJ)
    x_cg = 2 * EJ.m_c * 2 * EJ.l1 / EJ.m
    x_contact = EJ.x_pin + EJ.trail
    pair = EJ.m * EJ.g * (EJ.x_main - x_cg) / (EJ.x_main - x_contact)
    rev = layout_casters(lay, reverse=True)
    assert rev[0].static_load() + rev[1].static_load() == pytest.approx(pair, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 1.6e-16)
    assert rev[0].static_load() > layout_casters(lay)[0].static_load()   # rear casters: contacts move inward


def test_a_leading_caster_diverges_at_speed_over_trail():
    """Just after reversing a caster leads its pin: the generated rigid-pin rigid-tire towed wheel at ``-|U|``
    has the one eigenvalue ``|U| / trail`` (the no-side-slip constraint ``L psi_dot = U psi`` solved by hand)."""
    from stability.shimmy.layout_caster import leading_divergence_rate

    u = np.array([-0.5, -1.0, -3.0])
    assert leading_divergence_rate(0.05, u) == pytest.approx(np.abs(u) / 0.05, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert leading_divergence_rate(0.08, [2.0]) == pytest.approx([2.0 / 0.08], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_shimmy_command_answers_reverse(capsys):
    """Negative speeds: each caster row forward and swung round in reverse; the forward answers of a mixed run are
    those of a forward-only run (the forward path unchanged), the reverse ones carry signed speeds and the
    leading caster's divergence rate."""
    assert main(["--chair", "mid-wheel-drive", "--speeds", "-1,1", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert [c["direction"] for c in doc["casters"]] == ["forward", "forward", "reverse", "reverse"]
    assert main(["--chair", "mid-wheel-drive", "--speeds", "1", "--json"]) == 0
    only = json.loads(capsys.readouterr().out)
    assert doc["casters"][:2] == [{**c, "direction": "forward"} for c in only["casters"]]
    rev = doc["casters"][2]
    assert rev["speeds_m_s"] == [-1.0] and rev["shimmy_band"]["speeds_m_s"] == [-1.0]
    assert rev["leading_divergence_rate_1_s"] == pytest.approx([1.0 / rev["trail_m"]], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    lay = layout_preset("mid-wheel-drive")
    assert rev["static_load_N"] == pytest.approx(LayoutCaster(lay, 0, reverse=True).static_load(), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # the short form in reverse answers through its layout
    assert main(["--chair", "ej-premier", "--speeds", "-1", "--json"]) == 0
    ej = json.loads(capsys.readouterr().out)
    assert ej["layout"] == "ej-premier" and {c["direction"] for c in ej["casters"]} == {"reverse"}
    assert main(["--chair", "ej-premier", "--speeds", "-1", "--chair-model"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "reverse" in err and "valid: --chair-model with speeds > 0" in err


def test_the_memoised_loads_are_each_casters_own_statics():
    """``LayoutCaster.loads`` memoises each (caster, trail) by value: after one layout was asked, another (a heavier
    chair, the next caster, the reverse) still gets its own statics, each equal to its row's trail replaced and the
    statics solved afresh (exact: the same arithmetic), asked twice (the second answer from the memo)."""
    from dataclasses import replace

    lay = layout_preset("mid-wheel-drive")
    heavy = replace(lay, m=lay.m * 1.2)
    trails = np.array([0.03, 0.05, 0.03])
    for c in (LayoutCaster(lay, 0), LayoutCaster(heavy, 0), LayoutCaster(lay, 2), LayoutCaster(lay, 0, reverse=True)):
        want = [c.replace(trail=float(t)).static_load() for t in trails]
        assert np.array_equal(c.loads(trails), want) and np.array_equal(c.loads(trails), want)
    # the heavier chair's casters carry 1.2 times the load: rounding of one product (a few ulp), asserted 1e-12
    assert LayoutCaster(heavy, 0).loads(trails) == pytest.approx(1.2 * LayoutCaster(lay, 0).loads(trails), rel=1e-12)


def test_the_loads_without_a_layout_per_trail_are_the_replaced_layouts_statics():
    """``LayoutCaster.loads`` moves the row's contacts in the contact list instead of building a layout per trail:
    at every preset (forward and reverse), every caster and trails from below zero to beyond the caster's range
    (0 to 0.5 m) and where the base no longer stands, its answer is the row's trail replaced and the statics solved
    (exact: the same arithmetic), NaN exactly where that layout is refused (the trail's check or a load <= 0)."""
    from stability.layout.presets import layout_preset_names

    trails = np.concatenate([np.linspace(-0.01, 0.6, 62), [0.0, 0.5, np.nextafter(0.5, 1.0)]])
    refused = 0
    for name in layout_preset_names():
        for reverse in (False, True):
            for c in layout_casters(layout_preset(name), reverse):
                want = []
                for t in trails:
                    try:
                        want.append(c.replace(trail=float(t)).static_load())
                    except ValueError:
                        want.append(math.nan)
                refused += int(np.isnan(want).sum())
                assert np.array_equal(c.loads(trails), want, equal_nan=True)
    assert refused > 0           # the refusals were exercised
