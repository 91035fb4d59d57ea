"""Caster shimmy for any wheel layout (stability.shimmy.layout_caster, ``shimmy --chair mid-wheel-drive``)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

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
    assert lc[0].loads(trails) == pytest.approx(normal_loads(parameters(EJ)._replace(trail=trails))[0], rel=1e-9)
    a, b = shimmy_band(EJ, SPEEDS), shimmy_band(lc[0], SPEEDS)
    assert np.array(b.intervals_m, dtype=object).shape == np.array(a.intervals_m, dtype=object).shape
    for ia, ib in zip(a.intervals_m, b.intervals_m, strict=True):
        assert np.array(ib) == pytest.approx(np.array(ia), rel=1e-9)
    assert b.margin_m == pytest.approx(a.margin_m, rel=1e-9)
    sa, sb = caster_summary(EJ, [1.0]), caster_summary(lc[1], [1.0])
    assert sb.friction_trail == pytest.approx(sa.friction_trail, rel=1e-9)


def test_a_layout_caster_is_the_towed_wheel_at_its_own_load():
    """Each caster row of the mid-wheel-drive base is a towed wheel at its own static load: the lighter rear
    casters have the smaller cornering stiffness, and the statics' loads add up to the weight."""
    lay = layout_preset("mid-wheel-drive")
    lc = layout_casters(lay)
    loads = [c.static_load() for c in lc]
    from stability.layout import static_loads

    assert sum(static_loads(lay)) == pytest.approx(lay.m * lay.g, rel=1e-12)
    front = [c for c in lc if lay.casters[c.index].x > 0]
    rear = [c for c in lc if lay.casters[c.index].x < 0]
    assert front and rear and max(c.static_load() for c in rear) < min(c.static_load() for c in front)
    w_front, w_rear = caster_wheel(front[0]), caster_wheel(rear[0])
    tire = front[0].caster_tire_model()
    assert w_front.cornering_stiffness == pytest.approx(tire.cornering_stiffness_per_rad(front[0].static_load()))
    assert w_rear.cornering_stiffness < w_front.cornering_stiffness
    assert all(n > 0 for n in loads)


def test_a_row_changes_its_trail_together():
    """Varying a caster's trail moves its left-right partner too (a chair's trail is the pair's): the base stays
    symmetric, so both casters of the row keep equal loads."""
    lay = layout_preset("mid-wheel-drive")
    c0 = LayoutCaster(lay, 0).replace(trail=0.08)
    xs = [(c.x, c.trail) for c in c0.layout.casters]
    same_row = [t for x, t in xs if abs(x - lay.casters[0].x) < 1e-9]
    assert same_row == [0.08, 0.08]
    assert c0.static_load() == pytest.approx(LayoutCaster(c0.layout, 1).static_load(), rel=1e-12)
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
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-12), name
    assert (b.mass, b.pin_friction) == (1.5, 0.25)
