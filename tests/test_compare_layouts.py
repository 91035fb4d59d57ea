"""Comparing chairs as wheel layouts (stability.compare.layouts), forward and in reverse.

Independent references: the short form's comparison of the same chairs (its linear model and tipping, a separate
code path: the wiring), invariants (a frame turned round and driven backwards is the frame driven forwards; a chair
compared with itself is equal on every measure), and the command's one-line refusals.
"""

from __future__ import annotations

import dataclasses as dc
import json
import math

import numpy as np
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
    the short form's (same arithmetic to rounding: observed 3.7e-14 relative, asserted 1e-11), the smallest ISO angle against the short form's
    tipping, and the same verdicts."""
    chairs = [resolve("ej-premier"), resolve("revised")]
    speeds = [0.5, 0.75, 1.0, 1.5]
    short = compare(chairs, speeds=speeds)
    mine = compare_layouts([Layout.from_chair(c) for c in chairs], speeds=speeds)
    for u in speeds:
        key = f"growth_rate_1_s@{u:g}"
        a, b = mine.quantity(key), short.quantity(key)
        for x, y in zip(a.values, b.values, strict=True):
            assert x == pytest.approx(y, rel=1e-11)      # rounding (docstring)
        da = next(d for d in mine.differences if d.key == key)
        db = next(d for d in short.differences if d.key == key)
        assert da.more_stable == db.more_stable
    tips = mine.quantity("static_stability_deg").values
    for c, t in zip(chairs, tips, strict=True):
        assert t == pytest.approx(tip_angles(c).smallest_deg, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


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
        assert f[0] == pytest.approx(r[1], rel=1e-9) and r[0] == pytest.approx(f[1], rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    fwd, rev = c.quantity("stable_up_to_forward_m_s").values, c.quantity("stable_up_to_reverse_m_s").values
    assert (fwd[0], rev[0]) == (rev[1], fwd[1])
    s = c.quantity("static_stability_deg").values
    assert s[0] == pytest.approx(s[1], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_chair_compared_with_itself_is_equal_on_every_measure():
    """Equal on every measured value; where both values are the same search's bound (the base is stable forwards
    up to the searched 20 m/s), 'not separable': a bound is not a tie."""
    lay = layout_preset("mid-wheel-drive")
    c = compare_layouts([lay, dc.replace(lay, name="again")], speeds=[0.75, -0.75])
    bounds = {q.key for q in c.quantities if all(math.isinf(v) for v in q.values)}
    assert bounds == {"stable_up_to_forward_m_s"}
    assert c.differences and all(d.more_stable == ("not separable" if d.key in bounds else "equal")
                                 for d in c.differences)
    assert all(d.absolute in (0.0, None) for d in c.differences)


def test_two_bounds_are_not_separable_and_a_bound_ranks_above_a_smaller_value():
    """Two critical impulses whose level no push up to 40 N s reached (both stored as inf, the search's bound) are
    not 'equal': each is somewhere above 40 N s, so the verdict says the two cannot be separated and names the
    bound; a bound against a value below it still ranks (the bound is the larger)."""
    from stability.compare.compute import Quantity, _difference
    from stability.compare.text import _verdict

    words = "level not reached with pushes up to 40 N s"
    both = Quantity("critical_impulse_Ns@0.75", "critical impulse at 0.75 m/s", "N s", True,
                    (math.inf, math.inf), (None, None), words)
    d = _difference(both, 1, "b", "a", None, 0.95)
    assert d.more_stable == "not separable" and d.absolute is None
    assert _verdict(d, both) == f"not separable (both bounds: {words})"
    one = dc.replace(both, values=(math.inf, 12.5))
    assert _difference(one, 1, "b", "a", None, 0.95).more_stable == "a"
    # a quantity whose infinity is not a search's bound keeps the plain comparison
    plain = dc.replace(both, none_means="")
    assert _difference(plain, 1, "b", "a", None, 0.95).more_stable == "equal"


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
    (["ej-premier", "revised", "--speeds", "-0.75", "--uncertainty", "-"],
     "--uncertainty given 1 times for 2 chairs"),
    (["mid-wheel-drive", "revised", "--uncertainty", "-", "--uncertainty", "-", "--samples", "0"],
     "--samples 0 is invalid; valid range: 1 <= value <="),
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
    # a heavier base that no push spins either: two bounds, not separable (not "equal", issue 38)
    heavy = dc.replace(mwd, name="heavier", m=1.1 * mwd.m)
    assert layout_critical_impulses(heavy, 0.75)[0].status == "never"
    c2 = compare_layouts([mwd, heavy], speeds=[0.75], nonlinear=True)
    d2 = next(d for d in c2.differences if d.key == q.key)
    assert d2.more_stable == "not separable" and d2.absolute is None


_UNC = ('[m]\ndistribution = "normal"\nstd = 0.05\nrelative = true\n'
        '[i_z]\ndistribution = "uniform"\nlow = -0.1\nhigh = 0.1\nrelative = true\n'
        '[trail]\nfields = ["{trail}"]\ndistribution = "uniform"\nlow = -0.2\nhigh = 0.2\nrelative = true\n')


def _layout_unc(lay: Layout, text: str):
    import tomllib

    from stability.advise.layout_axes import layout_axes
    from stability.uncertainty.io import from_mapping

    return from_mapping(tomllib.loads(text), layout_axes(lay))


def test_the_thesis_chair_as_a_layout_gets_the_short_forms_intervals_and_difference_intervals():
    """The E&J Premier with an uncertain mass, yaw inertia and trail against the exact revised chair, compared by
    the short form and as layouts (the same table names: the same seeded draws; the short form's ``trail`` is the
    layout's one caster row ``trail_ROW``): each growth rate's interval and each difference's interval agree.  Error
    model: the two linear models agree to ~1e-13 relative per draw (observed: intervals 1e-13 relative, difference
    ends 1.3e-13 1/s); tolerances 1e-11 relative and 1e-10 1/s (a margin of ~100).  The agreement holds draw by
    draw (the same seeded draws through two models), so 40 draws test it as 300 would (observed with 40: 9.6e-14
    relative, 5.9e-14 1/s; with 300: 1.1e-13 and 1.3e-13)."""
    from stability.uncertainty import loads_uncertainty

    a, b = resolve("ej-premier"), resolve("revised")
    la, lb = Layout.from_chair(a), Layout.from_chair(b)
    (row,) = [x for x in __import__("stability.advise.layout_axes", fromlist=["x"]).layout_axes(la)
              if x.startswith("trail_")]
    speeds = [0.5, 0.75, 1.0]
    short = compare([a, b], speeds=speeds, uncertainties=[loads_uncertainty(_UNC.format(trail="trail")), None],
                    samples=40)
    mine = compare_layouts([la, lb], speeds=speeds, uncertainties=[_layout_unc(la, _UNC.format(trail=row)), None],
                           samples=40)
    assert mine.uncertainty == short.uncertainty
    for u in speeds:
        key = f"growth_rate_1_s@{u:g}"
        (lo, hi), none = mine.quantity(key).intervals
        # error model: rounding: per draw the same growth rate to a few ulp, the percentiles of the same draws
        # (observed 1.1e-13 relative, 1.3e-13 1/s for the differences)
        assert none is None and (lo, hi) == pytest.approx(short.quantity(key).intervals[0], rel=1e-11)
        da = next(d for d in mine.differences if d.key == key)
        db = next(d for d in short.differences if d.key == key)
        assert da.interval == pytest.approx(db.interval, abs=2e-11)
        assert da.distinguishable == db.distinguishable


def test_a_mirrored_layout_is_not_distinguishable_and_a_higher_cg_tips_sooner():
    """Mirror symmetry: the mid-wheel-drive base against itself reflected left to right, both with the same
    uncertainty (shared draws): the same intervals (1e-12 relative: mirrored arithmetic) and every difference
    interval [0, 0], so not distinguishable.  Monotonicity: a c.g. drawn only higher (h + 10 to 20 %) gives a
    static stability interval wholly below the nominal angle.  Both hold draw by draw, so 40 draws test them as
    200 would."""
    lay = layout_preset("mid-wheel-drive")
    mirror = dc.replace(lay, name="mirrored", wheels=tuple(dc.replace(w, y=-w.y) for w in lay.wheels),
                        casters=tuple(dc.replace(k, y=-k.y) for k in lay.casters))
    text = _UNC.format(trail="trail_front")
    c = compare_layouts([lay, mirror], speeds=[0.75, -0.75], uncertainties=[_layout_unc(lay, text),
                                                                           _layout_unc(mirror, text)], samples=40)
    # rounding: the same arithmetic on mirrored numbers (observed 0)
    for q in c.quantities:
        if q.intervals[0] is not None:
            assert q.intervals[1] == pytest.approx(q.intervals[0], rel=1e-12)
    for d in c.differences:
        if d.interval is not None:
            # rounding: differences of equal numbers (observed 0)
            assert d.interval == pytest.approx((0.0, 0.0), abs=1e-12) and d.distinguishable is False
    up = '[h]\ndistribution = "uniform"\nlow = 0.1\nhigh = 0.2\nrelative = true\n'
    c = compare_layouts([lay, mirror], speeds=[0.75], uncertainties=[_layout_unc(lay, up), None], samples=40)
    q = c.quantity("static_stability_deg")
    assert q.intervals[0][0] < q.intervals[0][1] < q.values[0]


def test_the_command_draws_the_layouts_figure_and_their_intervals(tmp_path, capsys):
    """``compare`` with a layout, reverse speeds, ``--uncertainty`` and ``-o`` (issue 38): the JSON carries the
    intervals and matches its schema, the PDF and the PNG are written (titles naming the chairs and the model, the
    0.75 m/s lines labelled); a file naming a short-form field is refused in one line naming the layout's."""
    pytest.importorskip("matplotlib")
    from stability.compare.plots import comparison_figures

    f = tmp_path / "u.toml"
    f.write_text(_UNC.format(trail="trail_front"))
    pdf, png = tmp_path / "c.pdf", tmp_path / "c.png"
    argv = ["mid-wheel-drive", "power-fwd-base", "--speeds", "0.75,-0.75", "--uncertainty", str(f),
            "--uncertainty", "-", "--samples", "40"]
    assert main([*argv, "--json", "-o", str(pdf)]) == 0
    d = json.loads(capsys.readouterr().out)
    assert pdf.stat().st_size > 0
    assert d["options"]["uncertainty"] == [str(f), "-"] and d["uncertainty"]["samples"] == 40
    rate = next(m for m in d["measures"] if m["measure"] == "growth_rate_1_s" and m["speed_m_s"] == -0.75)
    lo, hi = rate["chairs"][0]["interval"]
    assert lo < rate["chairs"][0]["value"] < hi and "interval" not in rate["chairs"][1]
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("compare", d)
    assert main([*argv, "-o", str(png)]) == 0
    assert png.stat().st_size > 0 and "not propagated" in capsys.readouterr().out
    c = compare_layouts([layout_preset("mid-wheel-drive"), layout_preset("power-fwd-base")], speeds=[0.75, -0.75])
    ax = comparison_figures(c)[0].axes[0]
    assert "mid-wheel-drive vs power-fwd-base" in ax.get_title() and "linear model" in ax.get_title()
    labels = ax.get_legend_handles_labels()[1]
    assert any(lab.startswith("0.75 m/s") for lab in labels) and any(lab.startswith("-0.75 m/s") for lab in labels)
    bad = tmp_path / "s.toml"
    bad.write_text('[s1]\ndistribution = "normal"\nstd = 0.01\n')
    assert main(["mid-wheel-drive", "power-fwd-base", "--uncertainty", str(bad), "--uncertainty", "-"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--uncertainty 1" in err and "numeric layout field" in err


def test_a_bound_draw_counts_as_the_searched_speed_in_the_interval_and_the_difference():
    """Censored order statistics by hand (:func:`stability.study.censored.quantile`'s rule): 10 draws unstable
    from the start (0 m/s) and 30 stable up to the searched 20 m/s (bounds).  The 25 % quantile falls between a
    value and a bound, so takes the value below (0); the 75 % one among the bounds (a bound: infinite).  A paired
    difference of a value from a bound is a bound itself (0 - ">= 20" is "<= -20"); pairs of two bounds say
    nothing, and when they are most pairs there is no interval.  Exact: order statistics of exact inputs."""
    from stability.compare.layouts import bounded_difference, bounded_interval

    draws = np.array([0.0] * 10 + [math.inf] * 30)
    assert bounded_interval(draws, 0.5, 20.0) == (0.0, math.inf)
    assert bounded_interval(np.full(8, math.inf), 0.95, 20.0) == (math.inf, math.inf)
    finite = np.linspace(1.0, 3.0, 9)
    assert bounded_interval(finite, 0.5, 20.0) == tuple(np.percentile(finite, [25, 75]))
    a = np.array([0.0] * 4 + [5.0] * 4)
    r = np.array([math.inf] * 4 + [3.0] * 4)
    assert bounded_difference(a, r, 0.5, 20.0) == ((-20.0, 2.0), ("<", "="))
    assert bounded_difference(r, a, 0.5, 20.0) == ((-2.0, 20.0), ("=", ">"))
    assert bounded_difference(np.full(4, math.inf), np.full(4, math.inf), 0.5, 20.0) is None


def _drive_x_flip(lay: Layout) -> float:
    """The drive axle's position at which the layout's growth rate at 0.75 m/s changes sign (brentq)."""
    from scipy.optimize import brentq

    from stability.advise.layout_axes import apply_layout_axis
    from stability.layout.linear import growth_rates

    return brentq(lambda x: growth_rates(apply_layout_axis(lay, "drive_x", x), [0.75])[0], -0.05, 0.05, xtol=1e-9)


def test_a_drive_axle_drawn_across_its_neutral_point_makes_the_stable_speeds_uncertain_each_way():
    """A mid-wheel-drive base with its drive axle drawn uniformly from x* - 0.06 to x* + 0.02 m, x* the position at
    which the frictionless linear model's growth rate changes sign (stable forward, unstable in reverse behind it;
    the reverse in front): a quarter of the draws (closed form of the uniform law: 0.02 / 0.08) sit in front.  At
    95 % both ends of each interval differ (0 and the bound "> 20 m/s"); at 20 % (the 40-60 % quantiles) both lie
    in the three quarters behind x* (forward "> 20", reverse 0).  Against the front-wheel-drive base (unstable
    forward from the start, stable in reverse up to 20 m/s) the forward difference is "<= -20" to 0 m/s: not
    distinguishable, since a quarter of the draws are unstable forward too.  Sampling error: 200 draws put the
    fraction 0.25 within +-0.031 (one standard deviation), 4.9 of them from the 0.4 quantile's edge and 7 from the
    0.025 one's."""
    lay = layout_preset("mid-wheel-drive")
    x = _drive_x_flip(lay)
    text = (f'[drive]\nfields = ["drive_x"]\ndistribution = "uniform"\nlow = {x - 0.06!r}\nhigh = {x + 0.02!r}\n')
    unc = _layout_unc(lay, text)
    c = compare_layouts([lay, layout_preset("power-fwd-base")], speeds=[0.75], uncertainties=[unc, None],
                        samples=200)
    fwd, rev = c.quantity("stable_up_to_forward_m_s"), c.quantity("stable_up_to_reverse_m_s")
    assert fwd.intervals == ((0.0, math.inf), None) and rev.intervals == ((0.0, math.inf), None)
    d = next(d for d in c.differences if d.key == "stable_up_to_forward_m_s")
    assert d.interval == (-20.0, 0.0) and d.interval_sides == ("<", "=") and d.distinguishable is False
    narrow = compare_layouts([lay, layout_preset("power-fwd-base")], speeds=[0.75], uncertainties=[unc, None],
                             samples=200, level=0.2)
    assert narrow.quantity("stable_up_to_forward_m_s").intervals[0] == (math.inf, math.inf)
    assert narrow.quantity("stable_up_to_reverse_m_s").intervals[0] == (0.0, 0.0)
    from stability.compare.text import format_comparison

    out = format_comparison(c)
    assert "[0, > 20]" in out and "[<= -20, +0] m/s: NOT distinguishable" in out
    assert "[the same over the interval]" in format_comparison(narrow)


def test_a_kept_critical_speed_is_the_searchs_for_an_equal_layout():
    """The critical speed is kept per equal (frozen) layout and direction: a layout rebuilt field by field gets
    the uncached search's answer exactly, each way, from the kept one; a changed field is searched again."""
    from stability.layout.linear import _critical_speed, critical_speed

    lay = dc.replace(layout_preset("mid-wheel-drive"), name="kept")
    again = dc.replace(lay, casters=tuple(dc.replace(c) for c in lay.casters))
    moved = dc.replace(lay, casters=(dc.replace(lay.casters[0], trail=lay.casters[0].trail + 0.01),
                                     *lay.casters[1:]))
    assert again == lay and again is not lay and moved != lay
    for reverse in (False, True):
        first = critical_speed(lay, reverse)
        hits = _critical_speed.cache_info().hits
        assert critical_speed(again, reverse) == first == _critical_speed.__wrapped__(lay, reverse, ())
        assert _critical_speed.cache_info().hits == hits + 1
        misses = _critical_speed.cache_info().misses
        assert critical_speed(moved, reverse) == _critical_speed.__wrapped__(moved, reverse, ())
        assert _critical_speed.cache_info().misses == misses + 1


def test_a_kept_critical_speed_follows_a_replaced_registered_tire():
    """A wheel's tire is a name: after the name is registered again with another tire, the critical speed is
    searched again (the uncached search's answer), not read from the answer kept for the old tire."""
    from stability import tires
    from stability.layout.linear import _critical_speed, critical_speed

    base = layout_preset("mid-wheel-drive")
    soft, stiff = tires.get("linear:2"), tires.get("linear:20")
    try:
        tires.register("KEPT-TEST", soft)
        lay = dc.replace(base, name="tire kept", casters=tuple(dc.replace(c, tire="KEPT-TEST") for c in base.casters))
        critical_speed(lay)
        critical_speed(lay)                         # the same tire: the kept answer
        info = _critical_speed.cache_info()
        tires.register("KEPT-TEST", stiff, replace=True)
        assert critical_speed(lay) == _critical_speed.__wrapped__(lay, False, ())
        # searched again, not read from the old tire's entry (on the presets the layout's linear stability change
        # does not depend on the tires' stiffness, so the miss is what shows it)
        assert _critical_speed.cache_info().misses == info.misses + 1
        assert _critical_speed.cache_info().hits == info.hits
    finally:
        tires.unregister("KEPT-TEST")
