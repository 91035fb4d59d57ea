"""Sweeps of wheel layouts (stability.sweep.layouts), forward and in reverse.

Independent references: the short form's sweep of the same chair (a separate code path: its batched linear model,
tipping, shimmy band and critical-impulse search; the wiring), the frame turned round (a grid over the rear-wheel-
drive base backwards is the front-wheel-drive base forwards), the layout commands' own answers, and one-line
refusals.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stability.layout.linear import growth_rates
from stability.layout.presets import layout_preset
from stability.sweep.__main__ import main
from stability.sweep.measures import columns, compute_chunk
from stability.sweep.spec import loads_spec


def _rows(text: str) -> list[dict]:
    spec = loads_spec(text)
    cols = columns(spec)
    return [dict(zip(cols, r, strict=True)) for r in compute_chunk(spec, 0)]


def test_the_thesis_chair_swept_as_a_layout_gives_the_short_forms_rows():
    """The E&J Premier over its trail, at 0.75 m/s: the short form's sweep and the layout sweep (a reverse speed
    makes it one) agree on the growth rate, static stability, lateral tip angle and shimmy margin to rounding
    (1e-9) and on the critical impulse to the search's rounding (1e-12 relative: the same decisions)."""
    measures = '["growth_rate", "tip_angles", "shimmy_margin", "critical_impulse"]'
    short = _rows(f'chair = "ej-premier"\nspeeds = [0.75]\nmeasures = {measures}\nchunk_rows = 100\n'
                  '[grid]\ntrail = [0.06, 0.08]\n')
    lay = _rows(f'chair = "ej-premier"\nspeeds = [0.75, -0.75]\nmeasures = {measures}\nchunk_rows = 100\n'
                '[grid]\ntrail_rear = [0.06, 0.08]\n')
    fwd = [r for r in lay if r["speed_m_s"] > 0]
    assert len(fwd) == len(short) == 2
    for a, b in zip(fwd, short, strict=True):
        assert a["grid_trail_rear"] == b["grid_trail"] and a["error"] == b["error"] == ""
        for col in ("growth_rate_1_s", "static_stability_deg", "tip_lateral_deg", "shimmy_margin_m"):
            # error model: rounding: the eigenvalues' n eps ||A|| kappa (~2.4e-10 relative; observed 9.4e-14) and the
            # statics' few ulp (observed 0); the shimmy margins within the band's bisection bracket, 1.5e-10 m
            # (observed 0: the same decisions)
            assert a[col] == pytest.approx(b[col], rel=1e-9, abs=1e-9), col
        assert a["critical_impulse_Ns"] == pytest.approx(b["critical_impulse_Ns"], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.9e-15)
        assert a["critical_impulse_status"] == b["critical_impulse_status"]
        assert math.isnan(a["tip_toward_casters_deg"])          # no such direction on a layout


def test_a_frame_turned_round_sweeps_backwards_as_it_does_forwards():
    """Every caster's mass at its pin (grid caster_K_l = 0), the drive axle swept: the rear-wheel-drive base at
    -1 m/s is the front-wheel-drive base at +1 m/s with the axle mirrored (growth rate 1e-9 relative; the speed up
    to which it is stable; the static stability)."""
    def rows(name: str, xs: str, speed: float) -> list[dict]:
        return _rows(f'chair = "{name}"\nspeeds = [{speed}]\nmeasures = ["growth_rate", "critical_speeds", '
                     f'"tip_angles"]\n[grid]\ndrive_x = {xs}\ncaster_1_l = [0.0]\ncaster_2_l = [0.0]\n')

    fwd = rows("power-fwd-base", "[0.18, 0.13]", 1.0)
    rwd = rows("power-rwd-base", "[-0.18, -0.13]", -1.0)
    for a, b in zip(fwd, rwd, strict=True):
        assert a["growth_rate_1_s"] == pytest.approx(b["growth_rate_1_s"], rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        assert a["critical_speed_m_s"] == b["critical_speed_m_s"]
        assert a["static_stability_deg"] == pytest.approx(b["static_stability_deg"], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # the axis reaches it. error model: rounding moves a rate by ~1e-13 of it; the 5 cm axle move far more than 1e-3
    assert fwd[0]["growth_rate_1_s"] != pytest.approx(fwd[1]["growth_rate_1_s"], rel=1e-3)


def test_a_grid_axis_is_the_layout_changed():
    """``caster_3_trail`` of the mid-wheel-drive base changes that caster alone (its growth rates are the layout's
    with that caster's trail changed, computed directly); an invalid design gets its one-line error."""
    import dataclasses as dc

    lay = layout_preset("mid-wheel-drive")
    rows = _rows('chair = "mid-wheel-drive"\nspeeds = [1.0, -1.0]\nmeasures = ["growth_rate"]\n'
                 '[grid]\ncaster_3_trail = [0.04, 0.9]\n')
    changed = dc.replace(lay, casters=tuple(dc.replace(c, trail=0.04) if k == 2 else c
                                            for k, c in enumerate(lay.casters)))
    np.testing.assert_allclose([r["growth_rate_1_s"] for r in rows[:2]], growth_rates(changed, [1.0, -1.0]),
                               rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert "trail" in rows[2]["error"] and math.isnan(rows[2]["growth_rate_1_s"])


@pytest.mark.parametrize("text, words", [
    ('chair = "mid-wheel-drive"\nspeeds = [1.0]\nmeasures = ["holding_moment"]\n', "for a layout or reverse"),
    ('chair = "mid-wheel-drive"\nspeeds = [1.0]\nmeasures = ["growth_rate"]\n[grid]\ntrail = [0.05]\n',
     "grid='trail' is invalid for the layout"),
    ('chair = "mid-wheel-drive"\nspeeds = [1.0]\nmodel = "thesis"\nmeasures = ["growth_rate"]\n', "'exact'"),
    ('chair = "ej-premier"\nspeeds = [0.0]\nmeasures = ["growth_rate"]\n', "numbers > 0"),
    ('chair = "ej-premier"\nspeeds = [-30.0]\nmeasures = ["growth_rate"]\n', "0.01 <= |speed| <= 20"),
])
def test_bad_specs_are_refused_in_one_line(text, words):
    with pytest.raises(ValueError, match=None) as exc:
        loads_spec(text)
    assert words in str(exc.value) and "\n" not in str(exc.value)


@pytest.mark.slow
def test_the_command_sweeps_a_layout(tmp_path, capsys):
    spec = tmp_path / "s.toml"
    spec.write_text('chair = "power-rwd-base"\nspeeds = [0.75, -0.75]\nmeasures = ["growth_rate", "tip_angles"]\n'
                    '[grid]\ntrail_front = [0.04, 0.05]\n')
    out = tmp_path / "r.csv"
    assert main([str(spec), "-o", str(out), "--quiet"]) == 0
    lines = out.read_text().splitlines()
    assert lines[0].startswith("design,draw,speed_m_s,grid_trail_front,growth_rate_1_s")
    assert len(lines) == 1 + 4


def _rows_at(tmp_path, text: str, unc: str) -> list[dict]:
    (tmp_path / "u.toml").write_text(unc)
    (tmp_path / "s.toml").write_text(text + '[draws]\nn = 4\nseed = 3\nuncertainty = "u.toml"\n')
    from stability.sweep.spec import load_spec

    spec = load_spec(tmp_path / "s.toml")
    cols = columns(spec)
    return [dict(zip(cols, r, strict=True)) for r in compute_chunk(spec, 0)]


def test_random_draws_of_a_layout_are_the_short_forms_draws(tmp_path):
    """Draws of the E&J's trail (one table, the same name and seed: the same standardised draws) around each
    design: the layout sweep (axis ``trail_rear``, a reverse speed makes it one) gives the short form's sweep
    (field ``trail``) its rows: growth rate, static stability and shimmy margin per (design, draw) to rounding
    (1e-9; the same arithmetic as the grid test above), with the designs sharing their draws (common random
    numbers).  A drawn mass, relative to the layout's own, reaches the layout too."""
    measures = '["growth_rate", "tip_angles", "shimmy_margin"]'
    unc = '[trail_draw]\nfields = ["{f}"]\ndistribution = "normal"\nstd = 0.004\n'
    short = _rows_at(tmp_path, f'chair = "ej-premier"\nspeeds = [0.75]\nmeasures = {measures}\nchunk_rows = 100\n'
                     '[grid]\ntrail = [0.06, 0.08]\n', unc.format(f="trail"))
    lay = _rows_at(tmp_path, f'chair = "ej-premier"\nspeeds = [0.75, -0.75]\nmeasures = {measures}\n'
                   'chunk_rows = 100\n[grid]\ntrail_rear = [0.06, 0.08]\n', unc.format(f="trail_rear"))
    fwd = [r for r in lay if r["speed_m_s"] > 0]
    assert len(fwd) == len(short) == 8                              # 2 designs x 4 draws
    for a, b in zip(fwd, short, strict=True):
        assert (a["design"], a["draw"], a["error"]) == (b["design"], b["draw"], b["error"])
        for col in ("growth_rate_1_s", "static_stability_deg", "shimmy_margin_m"):
            # error model: rounding and the band's bisection bracket, as in the grid test above
            assert a[col] == pytest.approx(b[col], rel=1e-9, abs=1e-9), col
    trail_of = {(r["design"], r["draw"]): r["trail"] for r in short}
    assert len({v for v in trail_of.values()}) == 8                 # every draw moves the trail
    for k in range(4):                                              # common random numbers: the same offset
        assert trail_of[(1, k)] - trail_of[(0, k)] == pytest.approx(0.02, abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.7e-16)
    heavy = _rows_at(tmp_path, 'chair = "mid-wheel-drive"\nspeeds = [1.0]\nmeasures = ["growth_rate"]\n',
                     '[m]\ndistribution = "uniform"\nlow = 0.1\nhigh = 0.2\nrelative = true\n')
    from stability.sweep.layouts import draw_layout
    from stability.uncertainty import loads_uncertainty

    base = layout_preset("mid-wheel-drive")
    u = loads_uncertainty('[m]\ndistribution = "uniform"\nlow = 0.1\nhigh = 0.2\nrelative = true\n')
    assert u.distributions[0].valid_fields is None                  # a chair field name reads as one
    from stability.sweep.layouts import layout_axes
    from stability.uncertainty.io import from_mapping

    u = from_mapping({"m": {"distribution": "uniform", "low": 0.1, "high": 0.2, "relative": True}},
                     layout_axes(base))
    unit = u.unit_draws(4, 3)
    for r in heavy:
        drawn = draw_layout(base, u, unit, r["draw"])
        assert 1.1 * base.m <= drawn.m <= 1.2 * base.m
        assert r["growth_rate_1_s"] == pytest.approx(float(growth_rates(drawn, [1.0])[0]), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_draw_that_breaks_the_layout_is_a_row_with_its_reason(tmp_path):
    rows = _rows_at(tmp_path, 'chair = "mid-wheel-drive"\nspeeds = [1.0]\nmeasures = ["growth_rate"]\n',
                    '[trail_front]\ndistribution = "uniform"\nlow = 0.5\nhigh = 0.6\n')
    assert all("trail" in r["error"] and math.isnan(r["growth_rate_1_s"]) for r in rows)


def test_an_uncertainty_field_the_layout_does_not_have_is_refused_in_one_line(tmp_path):
    (tmp_path / "u.toml").write_text('[trail]\ndistribution = "normal"\nstd = 0.01\n')
    text = 'chair = "mid-wheel-drive"\nspeeds = [1.0]\nmeasures = ["growth_rate"]\n[draws]\nn = 2\n' \
           'uncertainty = "u.toml"\n'
    with pytest.raises(ValueError) as exc:
        loads_spec(text, tmp_path)
    msg = str(exc.value)
    assert "uncertainty [trail] table='trail' is invalid; valid range: a numeric layout field" in msg
    assert "\n" not in msg
    assert "trail_front" in msg                                     # the valid axes named


def test_a_layouts_critical_speed_is_a_value_or_a_bound_with_its_status():
    """The rear-caster E&J Premier as a layout is unstable from the slowest speed searched forwards (the thesis's
    finding with free casters) and, turned round (in reverse its casters lead), stable at every speed searched.
    Each is stored as the search's end with its side (0.02 m/s "below", 20 m/s "above"), so a sweep ranks the
    stable one first (the layout commands' search, SEARCH_SPEEDS_M_S, 0.02-20 m/s)."""
    from stability.chair import preset
    from stability.layout.linear import SEARCH_SPEEDS_M_S
    from stability.layout.model import Layout

    rates = growth_rates(Layout.from_chair(preset("ej-premier")), [0.02, -0.02, -20.0])
    assert rates[0] > 0 and rates[1] < 0 and rates[2] < 0
    rows = _rows('chair = "ej-premier"\nspeeds = [0.75, -0.75]\nmeasures = ["critical_speeds"]\n')
    got = {r["speed_m_s"]: (r["critical_speed_m_s"], r["critical_speed_status"]) for r in rows}
    assert got == {0.75: (float(SEARCH_SPEEDS_M_S[0]), "below"), -0.75: (float(SEARCH_SPEEDS_M_S[-1]), "above")}
    assert all(math.isnan(r["locked_critical_speed_m_s"]) and r["locked_critical_speed_status"] == "" for r in rows)
