"""The report on a wheel layout (stability.report.layout_report): the layout commands' numbers, both directions.

Independent references: the short form's own commands for the thesis chair as a layout (its linear model and
tipping: the wiring), the layout studies run directly, and the shimmy command's rows; every section the short
form's report has and a layout does not is stated in one line.
"""

from __future__ import annotations

import json

import pytest

from stability.advise.measures import Interval
from stability.chair import resolve
from stability.layout.model import Layout
from stability.layout.presets import layout_preset
from stability.linear import eigenvalues_vs_speed
from stability.report.__main__ import main
from stability.report.layout_report import NA_TITLE, NO_BENCH, NOT_APPLICABLE, WHEELS_TITLE, compute_layout_report
from stability.study.layout_impulse import layout_critical_impulses
from stability.tipping import tip_angles


def _fake(layouts):
    """A stated stand-in for the advisor's simulations (the report's own numbers are simulated for real)."""
    return [(Interval(10.0, 9.0, 11.0), Interval(1.0, 0.9, 1.1), "found", "found", None) for _ in layouts]


@pytest.fixture(scope="module")
def ej():
    return compute_layout_report(Layout.from_chair(resolve("ej-premier")), nonlinear=_fake)


def test_the_thesis_chair_as_a_layout_reports_the_short_forms_growth_rates_and_tip_angles(ej):
    """Forward growth rates from the short form's linear model (a separate code path), to 1e-9; the smallest tip
    angle from the short form's tipping."""
    g = ej.data["growth_rates"]
    fwd = [(u, x) for u, x in zip(g["speeds_m_s"], g["growth_rate_1_s"], strict=True) if u > 0]
    short = eigenvalues_vs_speed(resolve("ej-premier"), [u for u, _ in fwd], track=False).real.max(axis=1)
    for (_, x), y in zip(fwd, short, strict=True):
        # error model: the eigenvalues' rounding, n eps ||A|| kappa ~ 2.4e-10 of the rate per computation
        # (tests/numerics.py without its margin; observed 2.6e-13)
        assert x == pytest.approx(float(y), rel=1e-9)
    text = ej.text()
    assert f"{tip_angles(resolve('ej-premier')).smallest_deg:.1f} deg" in text


def test_the_report_quotes_the_layout_studies_both_ways(ej):
    """The critical impulses forwards and backwards are those of the layout study run directly (same search,
    same runs: equal)."""
    lay = Layout.from_chair(resolve("ej-premier"))
    direct = layout_critical_impulses(lay, [0.75, -0.75])
    assert [p["impulse_Ns"] for p in ej.data["critical_impulse"]] == [p.impulse_Ns for p in direct]
    assert {e["direction"] for e in ej.data["equal_instability"]} == {"forward", "reverse"}
    assert "0.75 m/s backwards" in ej.text()


def test_sections_that_do_not_apply_say_so_in_one_line(ej):
    # the thesis chair is pushed on its hand rims: no driven wheel, so the bench cannot apply (issue 35: a page
    # that cannot apply becomes one line among the others, not a page of its own)
    assert ej.not_applicable == (*NOT_APPLICABLE, NO_BENCH)
    for title, why in ej.not_applicable:
        assert "\n" not in why and f"{title}: {why}" in ej.text()
    assert len({t for t, _ in ej.not_applicable}) == len(ej.not_applicable)
    assert "no driven wheel" in ej.text()
    assert NO_BENCH[0] not in [t for t, _ in ej.sections]
    assert [x["section"] for x in ej.data["not_applicable"]] == [t for t, _ in ej.not_applicable]


def test_results_then_the_appendix(ej):
    """Issue 35: the results first, then the appendix (the wheels and the linear model, then what does not
    apply); every appendix page says so in its title."""
    titles = [t for t, _ in ej.page_texts()]
    appendix = [i for i, t in enumerate(titles) if t.startswith("Appendix")]
    assert appendix == list(range(len(titles) - 2, len(titles))), titles
    assert titles[0].startswith("The decision") and titles[-1] == NA_TITLE and titles[-2] == WHEELS_TITLE


@pytest.mark.slow
def test_the_shimmy_rows_of_a_mid_wheel_drive_base():
    """Two rows with their own margins (the shimmy command's rows; docs/layouts.md)."""
    r = compute_layout_report(layout_preset("mid-wheel-drive"), nonlinear=_fake)
    rows = [x for x in r.data["shimmy_rows"] if x["direction"] == "forward"]
    assert [x["row"] for x in rows] == ["front", "rear"] and rows[0]["shimmy_margin_m"] != rows[1]["shimmy_margin_m"]
    assert r.data["bench"] is not None
    assert r.not_applicable == NOT_APPLICABLE              # its wheels are driven: the bench is a result page
    assert NO_BENCH[0] in [t for t, _ in r.sections]


@pytest.mark.slow
def test_the_command_writes_a_layout_report(tmp_path, capsys):
    out, txt = tmp_path / "r.pdf", tmp_path / "r.txt"
    assert main(["--chair", "power-rwd-base", "-o", str(out), "--text", str(txt), "--no-progress"]) == 0
    assert out.read_bytes().startswith(b"%PDF") and "Appendix: not applicable to a wheel layout" in txt.read_text()


@pytest.mark.parametrize("argv, words", [
    (["--chair", "mid-wheel-drive", "--json", "--quick", "--compare", "ej-premier"],
     "--compare needs the full report"),
    (["--chair", "mid-wheel-drive", "--json", "--model", "thesis"], "--model thesis is invalid for a wheel layout"),
    (["--chair", "mid-wheel-drive", "--json", "--set", "zz=90"],
     "--set 'zz=90': 'zz' is not a field of layout"),
    (["--chair", "mid-wheel-drive", "--clinician", "-o", "x.pdf", "--reaction-time", "0.01"],
     "--reaction-time 0.01 is invalid; valid range"),
    (["--chair", "mid-wheel-drive", "--json", "--reaction-time", "9"], "--reaction-time 9 is invalid; valid range"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


@pytest.mark.slow
def test_the_json_of_a_layout_report(monkeypatch, capsys):
    import stability.report.layout_report as lr

    real = lr.compute_layout_report
    monkeypatch.setattr(lr, "compute_layout_report", lambda layout, **kw: real(layout, nonlinear=_fake))
    assert main(["--chair", "power-fwd-base", "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["schema"] == "stability.report.layout/1" and d["chair"] == "power-fwd-base"
    assert [x["section"] for x in d["not_applicable"]] == [t for t, _ in NOT_APPLICABLE]
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("report", d)           # a front-wheel-drive base: the layout form of the report's schema


def test_the_reverse_shimmy_rows_are_the_reverse_computation():
    """The mid-wheel-drive base's rows carry different loads backwards (its casters swung round, the reversed
    statics): the report's reverse margins are the towed wheel's with ``reverse=True`` computed directly
    (stability.shimmy: the same band, so equal), they differ from the forward ones, and the text prints them under
    'Backwards' (never 'the same answer')."""
    import math

    from stability.advise.layout_levers import caster_rows
    from stability.report.layout_report import _shimmy
    from stability.shimmy.band import shimmy_band
    from stability.shimmy.layout_caster import LayoutCaster

    lay = layout_preset("mid-wheel-drive")
    speeds = (0.5, 0.75, 1.0)
    lines, data = _shimmy(lay, speeds)
    for reverse, way in ((False, "forward"), (True, "reverse")):
        mine = [x["shimmy_margin_m"] for x in data if x["direction"] == way]
        direct = [float(shimmy_band(LayoutCaster(lay, r[0], reverse), list(speeds)).shimmy_margin_m)
                  for r in caster_rows(lay)]
        assert mine == direct
    fwd = [x["shimmy_margin_m"] for x in data if x["direction"] == "forward"]
    rev = [x["shimmy_margin_m"] for x in data if x["direction"] == "reverse"]
    assert all(math.isfinite(x) for x in fwd + rev) and fwd != rev
    text = "\n".join(lines)
    assert "the same answer" not in text
    back = text.split("Backwards:")[1]
    assert f"{rev[0] * 100:+.2f} cm" in back and f"{rev[1] * 100:+.2f} cm" in back


def test_a_frame_turned_round_has_its_shimmy_rows_swapped_between_directions():
    """Mirror front to back: the front-wheel-drive base (casters' mass at their pins) driven backwards is the
    rear-wheel-drive base driven forwards, so the reverse row of one is the forward row of the other (the same
    towed wheel at the same load: equal to 1e-12 relative, mirrored arithmetic) and vice versa."""
    import dataclasses as dc

    from stability.report.layout_report import _shimmy

    def pinned(name):
        lay = layout_preset(name)
        return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))

    a = {x["direction"]: x for x in _shimmy(pinned("power-fwd-base"), (0.5, 0.75, 1.0))[1]}
    b = {x["direction"]: x for x in _shimmy(pinned("power-rwd-base"), (0.5, 0.75, 1.0))[1]}
    assert a["reverse"]["interval_m"][1] != a["forward"]["interval_m"][1]
    for one, other in (("reverse", "forward"), ("forward", "reverse")):
        # error model: bisection bracket: mirrored arithmetic on the same grid (observed 0); a rounding-level
        # difference could flip a step only within rounding of the boundary, leaving the final 1.5e-10 m bracket
        assert a[one]["interval_m"][1] == pytest.approx(b[other]["interval_m"][1], rel=0, abs=1e-9)
        assert a[one]["shimmy_margin_m"] == b[other]["shimmy_margin_m"]


def test_the_driver_section_is_the_short_forms_rule_for_the_thesis_chair_and_mirrors_for_a_turned_frame():
    """``report --reaction-time`` on a layout: the divergence rule and the delayed loop on the layout's linear model.
    The E&J Premier as a layout gets the short form's rule speed, delayed-loop speed and limiting rule forwards (stability.driver.human_limit on the chair, a separate
    linear model: its rates agree to ~1e-13 relative and the same bisection returns the same point, observed
    identical; within the bisection's 1e-3 m/s).  The front-wheel-drive base (casters' mass at their pins) backwards is the
    rear-wheel-drive base forwards: the same speed and side (mirrored arithmetic, within the bisection's 1e-3 m/s)."""
    import dataclasses as dc

    from stability.driver import human_limit
    from stability.driver.linear import SPEED_TOL_M_S
    from stability.driver.model import Driver
    from stability.report.layout_report import _driver

    drv = Driver(0.6, source="--reaction-time")
    chair = resolve("ej-premier")
    lines, data = _driver(Layout.from_chair(chair), drv)
    h = human_limit(chair, drv)
    fwd = data["limits"][0]
    assert fwd["direction"] == "forward" and fwd["side"] == h.rule_side == "="
    # error model: bisection bracket: both bisect to SPEED_TOL_M_S on rates equal to rounding (observed identical;
    # a rounding-level difference could flip one step, within the final bracket)
    assert fwd["rule_speed_m_s"] == pytest.approx(h.rule_speed_m_s, rel=0, abs=SPEED_TOL_M_S)
    # the delayed loop: the same heading plant from another derivation, the same gain search and bisection
    # (error model: the bisection's bracket, as above)
    assert fwd["delayed_loop_side"] == h.loop_side and fwd["limited_by"] == h.limited_by
    assert fwd["delayed_loop_speed_m_s"] == pytest.approx(h.loop_speed_m_s, rel=0, abs=SPEED_TOL_M_S)
    assert fwd["speed_m_s"] == min(fwd["rule_speed_m_s"], fwd["delayed_loop_speed_m_s"])
    assert f"forwards: {fwd['speed_m_s']:.3g} m/s, limited by the {h.limited_by}" in "\n".join(lines)

    def pinned(name):
        lay = layout_preset(name)
        return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))

    a = {x["direction"]: x for x in _driver(pinned("power-fwd-base"), drv)[1]["limits"]}
    b = {x["direction"]: x for x in _driver(pinned("power-rwd-base"), drv)[1]["limits"]}
    assert a["reverse"]["side"] == b["forward"]["side"] and a["forward"]["side"] == b["reverse"]["side"]
    # error model: bisection bracket, as above (mirrored arithmetic; observed identical)
    assert a["reverse"]["rule_speed_m_s"] == pytest.approx(b["forward"]["rule_speed_m_s"], rel=0, abs=SPEED_TOL_M_S)
    assert a["forward"]["rule_speed_m_s"] == pytest.approx(b["reverse"]["rule_speed_m_s"], rel=0, abs=SPEED_TOL_M_S)


def test_the_command_takes_a_reaction_time_for_a_layout(monkeypatch, capsys):
    """``report --chair power-fwd-base --reaction-time 0.6 --json``: the option is in the JSON, the driver section's
    numbers are there, and the advisor's decision saw the driver (issue 38)."""
    import stability.report.layout_report as lr

    real = lr.compute_layout_report
    seen = {}

    def compute(layout, **kw):
        seen.update(kw)
        return real(layout, **{**kw, "nonlinear": _fake})

    monkeypatch.setattr(lr, "compute_layout_report", compute)
    assert main(["--chair", "power-fwd-base", "--json", "--no-progress", "--reaction-time", "0.6",
                 "--intended-speed", "0.8"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["options"]["reaction_time_s"] == 0.6 and seen["driver"].reaction_time_s == 0.6
    assert d["options"]["intended_speed_m_s"] == 0.8 == seen["intended_speed"]
    assert d["driver"]["reaction_time_s"] == 0.6 and [x["direction"] for x in d["driver"]["limits"]] == [
        "forward", "reverse"]


def test_set_on_a_layout_file_reaches_the_report_as_the_short_forms_set(monkeypatch, capsys, tmp_path):
    """``report --chair EJ-AS-[[wheel]]-FILE --set m=100``: the report's forward growth rates are the short form's
    linear model of the E&J with ``--set m=100`` (a separate code path), to 1e-9 relative as in the test above
    (two numeric eigenvalue solves of the same 8-state matrix rounded differently: observed below 1e-12), and
    they differ from the unset chair's by far more, so an ignored ``--set`` fails."""
    import stability.report.layout_report as lr
    from stability.cli import load_chair
    from stability.layout.io import dumps

    path = tmp_path / "ej-layout.toml"
    path.write_text(dumps(Layout.from_chair(resolve("ej-premier"))))
    real = lr.compute_layout_report
    monkeypatch.setattr(lr, "compute_layout_report", lambda layout, **kw: real(layout, nonlinear=_fake))
    assert main(["--chair", str(path), "--set", "m=100", "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    g = d["growth_rates"]
    fwd = [(u, x) for u, x in zip(g["speeds_m_s"], g["growth_rate_1_s"], strict=True) if u > 0]
    speeds = [u for u, _ in fwd]
    heavy = eigenvalues_vs_speed(load_chair("ej-premier", ["m=100"]), speeds, track=False).real.max(axis=1)
    plain = eigenvalues_vs_speed(resolve("ej-premier"), speeds, track=False).real.max(axis=1)
    for (_, x), y, z in zip(fwd, heavy, plain, strict=True):
        # error model: the eigenvalues' rounding, n eps ||A|| kappa ~ 2.4e-10 of the rate per computation
        # (tests/numerics.py without its margin; observed 2.6e-13)
        assert x == pytest.approx(float(y), rel=1e-9)
        assert abs(x - float(z)) > 1e-3 * abs(float(z))
    assert d["chair_parameters"]["m"] == 100.0
