"""The report's options on a wheel layout: ``--clinician``, ``--quick`` and ``--compare`` (issue 38).

Independent references: the short form's clinician sheet of the thesis's chairs (its own simulator, linear model,
slope statics and tipping: a separate code path) against the same chairs as layouts; the comparison of
``python -m stability.compare`` run directly; the PDF read back by an independent reader (tests/pdf_layout.py).
Error model of the sheet's agreement: the two simulators integrate the same equations with the same step, their
yaw-rate records differ in the last bits and by one recorded row at the end (observed: time to 1 rad/s within
3e-6 relative, doubling times within 1e-12): the times are held to 5e-4 (about 100x), the linear ones to 1e-9.
"""

from __future__ import annotations

import json

import pytest
from slow_cases import one_default

from stability.advise.measures import Interval
from stability.chair import resolve
from stability.layout.model import Layout
from stability.layout.presets import layout_preset
from stability.report.__main__ import main
from stability.report.clinician_sheet import clinician_sheet, sheet_lines
from stability.report.layout_clinician import layout_clinician_sheet
from stability.report.layout_report import comparison_caption, compute_layout_report

SPEEDS = (0.5, 0.75, 1.0)


def _fake(layouts):
    """A stated stand-in for the advisor's simulations (the sheet's and comparison's runs are real)."""
    return [(Interval(10.0, 9.0, 11.0), Interval(1.0, 0.9, 1.1), "found", "found", None) for _ in layouts]


@pytest.mark.parametrize("name", one_default(["ej-premier", "ej-premier-front-caster"], "ej-premier"))
def test_the_thesis_chairs_sheet_as_a_layout_is_the_short_forms(name):
    """Same behaviour words, times to 1 rad/s, doubling times, tip angles and cross-slope paragraph."""
    c = resolve(name)
    a, b = clinician_sheet(c, SPEEDS), layout_clinician_sheet(Layout.from_chair(c), SPEEDS)
    assert [m.kind for m in a.motions] == [m.kind for m in b.motions]
    for m, n in zip(a.motions, b.motions, strict=True):
        if m.time_to_level != float("inf"):
            # error model: rounding: the two engines' (mass matrix solved vs closed form) grown over the run and
            # shifted by stick-slip switches (observed 2.2e-6 and 7.5e-6 relative), x66
            assert n.time_to_level == pytest.approx(m.time_to_level, rel=5e-4)
    for x, y in zip(a.doubling, b.doubling, strict=True):
        # error model: the eigenvalues' rounding, n eps ||A|| kappa ~ 2.4e-10 of the rate per computation
        # (tests/numerics.py without its margin; observed 2.6e-13)
        assert (x is None and y is None) or y == pytest.approx(x, rel=1e-9)
    t = a.tipping
    fwd, bwd = ((t.toward_main_wheels_deg, t.toward_casters_deg) if c.caster_position == "rear"
                else (t.toward_casters_deg, t.toward_main_wheels_deg))
    assert b.tipping["forward_deg"] == pytest.approx(fwd, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert b.tipping["backward_deg"] == pytest.approx(bwd, rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    cross = [p for p in sheet_lines(a)["paragraphs"] if p.startswith("CROSS SLOPE")]
    assert cross and cross == [p for p in sheet_lines(b)["paragraphs"] if p.startswith("CROSS SLOPE")]
    # the rows' words come from the same function: identical
    assert [r[1:3] for r in sheet_lines(a)["bump_rows"]] == [r[1:3] for r in sheet_lines(b)["bump_rows"]]


def test_a_mid_wheel_drive_sheet_names_every_caster_and_the_motors():
    s = layout_clinician_sheet(layout_preset("mid-wheel-drive"), (0.75,))
    text = "\n".join(sheet_lines(s)["paragraphs"])
    assert "front left / front right / rear left / rear right" in text
    assert "motor must give" in text                      # driven wheels: torque, not hand-rim force
    assert f"forward {s.tipping['forward_deg']:.1f} deg" in text


def test_bad_layout_options_are_refused_in_one_line(tmp_path, capsys):
    for argv, words in (
            (["--chair", "mid-wheel-drive", "--clinician", "-o", str(tmp_path / "a.pdf"), "--speeds", "5"],
             "0.1 <= |U| <= 3 m/s"),
            (["--chair", "mid-wheel-drive", "--quick", "--compare", "ej-premier", "--json"],
             "--compare needs the full report"),
            (["--chair", "mid-wheel-drive", "--json", "--uncertainty", "docs/examples/measured_chair.uncertainty.toml"],
             "numeric layout field"),
            (["--chair", "mid-wheel-drive", "--json", "--quick", "--uncertainty",
              "docs/examples/mid_wheel_drive.uncertainty.toml"], "--uncertainty needs the full report"),
            (["--chair", "mid-wheel-drive", "--json", "--samples", "0", "--uncertainty",
              "docs/examples/mid_wheel_drive.uncertainty.toml"], "--samples 0 is invalid"),
            (["--chair", "mid-wheel-drive", "--json", "--set", "caster_9_trail=0.05"],
             "is not a field of layout"),
            (["--chair", "mid-wheel-drive", "--clinician", "-o", str(tmp_path / "b.pdf"), "--reaction-time", "3"],
             "--reaction-time 3 is invalid; valid range")):
        assert main(argv) == 2, argv
        err = capsys.readouterr().err.strip()
        assert words in err and "\n" not in err, err


@pytest.mark.slow
def test_quick_is_the_decision_and_the_sheet(tmp_path):
    from pdf_layout import layout_problems

    r = compute_layout_report(layout_preset("mid-wheel-drive"), nonlinear=_fake, quick=True)
    assert [t for t, _ in r.page_texts()] == ["The decision (forward driving)", "For the clinician"]
    assert [row["speed_m_s"] for row in r.data["clinician"]["bump"]] == list(SPEEDS)
    from stability.report.layout_report import write_layout_report

    assert write_layout_report(r, tmp_path / "q.pdf") == 2
    assert layout_problems(tmp_path / "q.pdf") == []


@pytest.mark.slow
def test_compare_a_layout_with_the_short_form_and_with_a_layout(tmp_path):
    """The comparison is the compare command's (run directly: equal), and its caption's winner is the lower
    growth rate."""
    from pdf_layout import layout_problems

    from stability.compare.layouts import compare_layouts
    from stability.report.layout_report import COMPARE_SPEEDS, write_layout_report

    lay = layout_preset("mid-wheel-drive")
    for base in (Layout.from_chair(resolve("ej-premier")), layout_preset("power-rwd-base")):
        r = compute_layout_report(lay, nonlinear=_fake, baseline=base)
        direct = compare_layouts([lay, base], speeds=COMPARE_SPEEDS, nonlinear=True)
        assert [q.values for q in r.comparison.quantities] == [q.values for q in direct.quantities]
        g = {q.key: q.values for q in direct.quantities}["growth_rate_1_s@0.75"]
        winner = r.comparison.labels[0 if g[0] < g[1] else 1]
        assert f"forwards {winner}'s heading error grows more slowly" in comparison_caption(r.comparison)
    assert write_layout_report(r, tmp_path / "c.pdf") == 9          # 6 sections, table, curves, not applicable
    assert layout_problems(tmp_path / "c.pdf") == []
    json.dumps(r.data["comparison"], allow_nan=False)


@pytest.mark.slow
def test_the_clinician_command_on_a_layout(tmp_path, capsys):
    from pdf_layout import layout_problems

    out, txt = tmp_path / "s.pdf", tmp_path / "s.txt"
    assert main(["--chair", "power-fwd-base", "--clinician", "--speeds", "0.5,-0.5", "-o", str(out), "--text",
                 str(txt)]) == 0
    assert "1 page" in capsys.readouterr().out and layout_problems(out) == []
    assert "-0.5 m/s" in txt.read_text()


def test_layout_uncertainty_fields_are_the_layouts_and_a_bad_one_is_named(tmp_path):
    """One set of uncertain layout fields for every command (the sweep's axes): the body's, every wheel's numeric
    fields, a caster row's trail and the drive axle; a short-form name, or a field with no value of its own (a
    camber coefficient left to the tire), is refused in one line naming it."""
    from stability.advise.layout_axes import layout_axes, load_layout_uncertainty

    lay = layout_preset("mid-wheel-drive")
    assert {"m", "i_z", "h", "caster_1_trail", "wheel_2_x", "trail_front", "trail_rear", "drive_x"} <= \
        layout_axes(lay)
    assert not {"caster_1_tire", "wheel_1_driven"} & layout_axes(lay)
    bad = tmp_path / "u.toml"
    bad.write_text('[s1]\ndistribution = "normal"\nstd = 0.01\n')
    with pytest.raises(ValueError, match="s1.*numeric layout field"):
        load_layout_uncertainty(bad, lay)
    none = tmp_path / "n.toml"
    none.write_text('[wheel_1_camber_coefficient]\ndistribution = "normal"\nstd = 0.01\n')
    with pytest.raises(ValueError, match="wheel_1_camber_coefficient.*a value of its own"):
        load_layout_uncertainty(none, lay)


def test_a_row_trail_draw_moves_every_caster_of_the_row():
    """``trail_front`` (a row axis, once only the sweep's) drawn in the report's propagation: both front casters
    get the one draw, so every draw has them equal and within the uniform's bounds."""
    from stability.advise.layout_axes import LayoutDraw
    from stability.uncertainty import Distribution, Uncertainty

    lay = layout_preset("mid-wheel-drive")
    front = [k for k, c in enumerate(lay.casters) if c.x > 0]
    t0 = lay.casters[front[0]].trail
    unc = Uncertainty((Distribution("trail_front", ("trail_front",), "uniform", low=t0 - 0.01, high=t0 + 0.01,
                                    valid_fields=frozenset({"trail_front"})),))
    for d in unc.sample(LayoutDraw(lay), 20, seed=1):  # type: ignore[arg-type]
        trails = {d.layout.casters[k].trail for k in front}
        assert len(trails) == 1 and t0 - 0.01 <= trails.pop() <= t0 + 0.01


def test_layout_uncertainty_interval_follows_the_parameter_it_draws():
    """A uniform drive-axle position x0 +/- 1 cm (one draw for both wheels): the growth rate is monotone in it,
    so the 95 % interval lies inside the growth rates at x0 -/+ 1 cm (computed directly) and spans more than those
    at x0 -/+ 0.9 cm (the 2.5 and 97.5 % quantiles of 1000 uniform draws are at +/- 0.95 cm, sampling SD 0.01 cm)."""
    from stability.advise.layout_levers import apply_layout
    from stability.layout.linear import growth_rates
    from stability.report.layout_uncertainty import layout_uncertainty
    from stability.uncertainty import Distribution, Uncertainty

    lay = layout_preset("mid-wheel-drive")
    x0 = lay.wheels[0].x
    fields = ("wheel_1_x", "wheel_2_x")
    unc = Uncertainty((Distribution("axle", fields, "uniform", low=x0 - 0.01, high=x0 + 0.01,
                                    valid_fields=frozenset(fields)),))
    r = layout_uncertainty(lay, unc, (0.75,), samples=1000, seed=0)
    key, _, nom, lo, hi, fin = r.rows()[0]

    def g(dx):
        return float(growth_rates(apply_layout(lay, [(f, x0 + dx) for f in fields]), [0.75])[0])

    outer = sorted((g(-0.01), g(0.01)))
    inner = sorted((g(-0.009), g(0.009)))
    assert key == "growth_rate_1_s@0.75" and nom == pytest.approx(g(0.0), rel=1e-12) and fin == 1.0  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert outer[0] <= lo < inner[0] and inner[1] < hi <= outer[1]
    assert r.result.dominant_parameters[0][0] == "axle"


@pytest.mark.slow
def test_the_uncertainty_page_of_a_layout_report(tmp_path, capsys, monkeypatch):
    from pdf_layout import layout_problems

    import stability.report.layout_report as lr

    real = lr.compute_layout_report
    monkeypatch.setattr(lr, "compute_layout_report", lambda layout, **kw: real(layout, **{**kw, "nonlinear": _fake}))
    out = tmp_path / "u.pdf"
    assert main(["--chair", "mid-wheel-drive", "--uncertainty", "docs/examples/mid_wheel_drive.uncertainty.toml",
                 "--samples", "200", "-o", str(out), "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["uncertainty"]["samples"] == 200 and d["options"]["samples"] == 200
    assert [m["measure"] for m in d["uncertainty"]["measures"]][-1] == "static_stability_deg"
    assert layout_problems(out) == []


def test_a_reverse_bump_run_is_valid_while_it_backs():
    """Backing at 0.75 m/s the run is valid while it keeps backing (the short form's speed-reversal rule along the
    direction of travel): it travels about 7.5 m in 10 s, not 0."""
    s = layout_clinician_sheet(layout_preset("power-fwd-base"), (-0.75,))
    m = s.motions[0]
    # error model: the step grid: the run's last sample is within one 1 ms step past 10 s (observed 1.0e-3 s); the
    # travel is 0.75 m/s x 10 s up to the heading's cosine and that step, first order in the step (observed 1.3e-4
    # relative), x77
    assert m.until == pytest.approx(10.0, abs=2e-3) and m.travel == pytest.approx(7.5, rel=0.01)
