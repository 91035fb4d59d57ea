"""Files and figures of the commands for any wheel layout: ``simulate --csv/-o``, ``slope -o``, ``shimmy -o``.

Independent statements used:

- the thesis's chair (the E&J Premier) written out as a ``[[wheel]]`` file is the short form in another form: its
  CSV columns, slope curves and trail chart are the short form's (the thesis engine and its generated statics,
  the thesis model's eigenvalues, the generated eq 6-25 loads) to the rounding of the other equations;
- mirror symmetry: a symmetric layout pushed to the left runs the mirror image of the push to the right, a slope
  falling to the left needs the holding moment of the one falling to the right, and a caster's mirror image on
  the other side has the same trail chart;
- the files are what their suffix says (PNG, SVG and PDF signatures, an SVG that parses as XML) and their data,
  read back from the CSV or the figure's artists, are the result's.
"""

from __future__ import annotations

import csv
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from slow_cases import one_default

from stability.chair import preset
from stability.layout import Layout
from stability.layout.io import dumps, load_layout
from stability.layout.presets import layout_preset

EJ = preset("ej-premier")
TRAILS = np.linspace(0.03, 0.09, 4)


def _read_csv(path) -> dict[str, np.ndarray]:
    rows = [r for r in csv.reader(line for line in path.read_text().splitlines() if not line.startswith("#"))]
    return {name: np.array([float(r[i]) for r in rows[1:]]) for i, name in enumerate(rows[0])}


@pytest.fixture(scope="module")
def ej_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("ej") / "ej-layout.toml"
    path.write_text(dumps(Layout.from_chair(EJ)))
    assert load_layout(path) == Layout.from_chair(EJ)          # the file is the expanded chair, exactly
    return path


def test_the_csv_of_the_thesis_chair_as_a_layout_is_the_short_forms(ej_file, tmp_path, capsys):
    """The layout kernel against the thesis engine, both written by the command: the same scheme and step, the
    accelerations by a numeric 4 x 4 solve instead of the generated closed form (rounding about 1e-16 relative
    per step, amplified about e^3 = 20 fold by the run's growth over 2 s): observed 6.5e-15 of a column's largest
    value; asserted 1e-12 (margin 150).  The CSV holds floats by repr, so it adds no error."""
    from stability.simulate.__main__ import main

    lay, short = tmp_path / "layout.csv", tmp_path / "short.csv"
    assert main(["--chair", str(ej_file), "--horizon", "2", "--csv", str(lay)]) == 0
    assert main(["--chair", "ej-premier", "--horizon", "2", "--csv", str(short)]) == 0
    capsys.readouterr()
    a, b = _read_csv(lay), _read_csv(short)
    assert list(a) == ["t", "x", "y", "heading", "yaw_rate", "u", "v",
                       "delta_caster_1_rear_left", "delta_dot_caster_1_rear_left",
                       "delta_caster_2_rear_right", "delta_dot_caster_2_rear_right"]
    assert EJ.caster_position == "rear"           # the thesis chair's casters behind the c.g.: named "rear"
    assert len(a["t"]) == len(b["t"]) and np.abs(b["heading"]).max() > 0.1    # a run worth comparing
    pairs = {"delta_caster_1_rear_left": "eta", "delta_dot_caster_1_rear_left": "eta_dot",
             "delta_caster_2_rear_right": "beta", "delta_dot_caster_2_rear_right": "beta_dot"}
    for name in a:
        theirs = b[pairs.get(name, name)]
        scale = max(np.abs(theirs).max(), 1e-3)
        # error model: rounding: the same equations in another order, grown over 2 s (observed 6.5e-15), x150
        assert np.abs(a[name] - theirs).max() <= 1e-12 * scale, name


def test_the_simulate_command_writes_a_layout_run_mirrored_by_the_push(tmp_path, capsys):
    """Pushed left instead of right, the mid-wheel-drive base runs the mirror image: heading, yaw rate, y and v
    change sign, x and u do not, and each caster exchanges its angle with its mirror image's, sign changed (the
    same arithmetic with signs changed except for the order of sums: observed 2.5e-15 of a column's largest
    value; asserted 3e-13, margin 120).  The figure is written in each format and its artists hold the run's data."""
    from stability.simulate.__main__ import main

    right, left = tmp_path / "right.csv", tmp_path / "left.csv"
    png = tmp_path / "run.png"
    assert main(["--chair", "mid-wheel-drive", "--horizon", "1.5", "--push-force", "80", "--csv", str(right),
                 "-o", str(png)]) == 0
    out = capsys.readouterr().out
    assert f"wrote {right}" in out and f"wrote {png}" in out
    assert main(["--chair", "mid-wheel-drive", "--horizon", "1.5", "--push-force", "-80", "--csv", str(left)]) == 0
    a, b = _read_csv(right), _read_csv(left)
    assert np.abs(a["heading"]).max() > 1e-3

    def same(p, q, sign):
        scale = max(np.abs(p).max(), 1e-12)
        # error model: rounding of the mirrored sums (docstring: observed 2.5e-15, margin 120)
        assert np.abs(p - sign * q).max() <= 3e-13 * scale

    for name in ("t", "x", "u"):
        same(a[name], b[name], 1.0)
    for name in ("heading", "yaw_rate", "y", "v"):
        same(a[name], b[name], -1.0)
    for front_back in ("1_front", "3_rear"):
        k = int(front_back[0])
        for kind in ("delta", "delta_dot"):
            same(a[f"{kind}_caster_{front_back}_left"], b[f"{kind}_caster_{k + 1}_{front_back[2:]}_right"], -1.0)
    assert png.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_the_layout_run_figure_holds_the_run(tmp_path):
    """The figure's lines are the run's arrays (path, heading in deg, yaw rate, each caster's angle in deg,
    labelled by the layout's caster labels); SVG and PDF files are valid; the caption's numbers are the run's."""
    from stability.plotting.responses import layout_run_caption, plot_layout_run
    from stability.settings.run import RunSpec
    from stability.simulate.layout import simulate_layout

    layout = layout_preset("mid-wheel-drive")
    run = simulate_layout(layout, -0.75, RunSpec(horizon=1.0, push_force=80.0), caster_angles_deg=[90.0] * 4)
    fig = plot_layout_run(run, layout.caster_labels)
    ax_path, ax_head, ax_rate, ax_caster = fig.axes
    np.testing.assert_array_equal(ax_path.lines[0].get_xydata(), np.column_stack([run.x_m, run.y_m]))
    np.testing.assert_array_equal(ax_head.lines[0].get_ydata(), np.degrees(run.heading_rad))
    np.testing.assert_array_equal(ax_rate.lines[0].get_ydata(), run.yaw_rate_rad_s)
    casters = [line for line in ax_caster.lines if line.get_label() in layout.caster_labels]
    assert [line.get_label() for line in casters] == list(layout.caster_labels)
    for line, a in zip(casters, run.caster_angle_rad, strict=True):
        np.testing.assert_array_equal(line.get_ydata(), np.degrees(a))
    assert "mid-wheel-drive" in fig.get_suptitle() and "layout model" in fig.get_suptitle()
    assert "backwards" in fig.get_suptitle()
    assert {"time t (s)"} <= {ax.get_xlabel() for ax in fig.axes}
    assert any("What to conclude" in t.get_text() for t in fig.texts)
    assert f"{run.final_heading_deg:+.1f} deg" in layout_run_caption(run, layout.caster_labels)
    svg, pdf = tmp_path / "r.svg", tmp_path / "r.pdf"
    plot_layout_run(run, layout.caster_labels, svg)
    plot_layout_run(run, layout.caster_labels, pdf)
    assert ET.parse(svg).getroot().tag.endswith("svg")
    assert pdf.read_bytes().startswith(b"%PDF")


def test_a_layout_name_from_a_file_is_never_markup():
    """A dollar in a user's layout name is drawn as typed in every figure (no text of the figure parses
    mathtext), and the figure renders."""
    import dataclasses

    from matplotlib.text import Text

    from stability.plotting.responses import plot_layout_run
    from stability.report.slope_figure import layout_slope_figure
    from stability.settings.run import RunSpec
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.layout_caster import LayoutCaster
    from stability.shimmy.plots import trail_chart_pages
    from stability.simulate.layout import simulate_layout

    layout = dataclasses.replace(layout_preset("power-fwd-base"), name="my $x^2$ chair")
    run = simulate_layout(layout, 0.75, RunSpec(horizon=0.2))
    figures = [plot_layout_run(run, layout.caster_labels), layout_slope_figure(layout, 2.0, 1.0, sim_time=0.2),
               *trail_chart_pages(trail_chart(LayoutCaster(layout, 0), TRAILS, [1.0, 1.5]), "towed wheel")]
    for fig in figures:
        assert fig.get_suptitle().startswith("my $x^2$ chair")
        texts = fig.findobj(Text)
        assert any("$x^2$" in t.get_text() for t in texts)
        assert not any(t.get_parse_math() for t in texts)
        fig.canvas.draw()


@pytest.mark.parametrize("speed", [0.75, 1.5])
def test_the_slope_curves_of_the_thesis_chair_as_a_layout_are_the_short_forms(speed):
    """The figure's curves: the layout's held line at each slope against the short form's generated statics
    (stability.slope.solve), the same root finder on other equations: observed 1.4e-14 N m and N; asserted 2e-12
    (margin 140).  The uncorrected release is the thesis engine's fixed-step run
    (stability.study.veer.simulator_path): observed bit-identical at the report time; asserted 1e-12 deg."""
    from stability.report.slope_data import layout_slope_section, slope_section
    from stability.slope import solve
    from stability.study.veer import VEER_RUN, simulator_path

    slopes = (0.0, 1.0, 2.0, 4.0)
    short = slope_section(EJ, speed=speed, slopes=slopes, path_slope=2.0)
    lay = layout_slope_section(Layout.from_chair(EJ), speed, slopes, 2.0)
    assert lay.drive == short.drive == "handrim" and lay.refused == short.refused == ()
    np.testing.assert_array_equal(lay.curve.cross_slopes_deg, short.curve.cross_slopes_deg)
    assert short.curve.holding_moment[-1] > 1.0
    # error model: rounding: two statics solvers on equal geometry (observed 1.4e-14 N m of 94 N m), x140
    for name in ("holding_moment", "friction_low", "friction_high", "handrim_difference"):
        np.testing.assert_allclose(getattr(lay.curve, name), getattr(short.curve, name), rtol=0, atol=2e-12,
                                   err_msg=name)
    np.testing.assert_allclose(lay.drive_difference, short.drive_difference, rtol=0, atol=2e-12)
    assert lay.harder_side == short.harder_side
    theirs = simulator_path(EJ, solve(EJ, 2.0, speed), VEER_RUN.replace(scheme="wchair", horizon=1.0),
                            pin_friction=True, report_time=1.0)
    assert lay.path is not None and lay.path.turn == theirs.turn
    # error model: rounding: the same run (observed bit-identical), 1e-12 deg of 18.6 deg is ~240 ulp
    assert lay.path.heading_change_deg == pytest.approx(theirs.heading_change_deg, abs=1e-12)
    h = lay.path.heading_change_history_deg
    # rounding, as above (observed 0)
    assert h[0] == 0.0 and h[-1] == pytest.approx(lay.path.heading_change_deg, abs=1e-12)


def test_a_slope_to_the_left_draws_the_same_curves():
    """Mirror symmetry of the mid-wheel-drive base: the magnitudes at slopes falling left and right agree to the
    rounding of the mirrored sums (the root finder stops at 1e-10 of the weight on both sides alike): observed
    1.8e-15 N m and 6e-17 deg; asserted 2e-13 (margin 100)."""
    from stability.report.slope_data import layout_slope_section

    layout = layout_preset("mid-wheel-drive")
    right = layout_slope_section(layout, 1.0, (1.0, 3.0), 3.0, side=1.0)
    left = layout_slope_section(layout, 1.0, (1.0, 3.0), 3.0, side=-1.0)
    assert right.curve.holding_moment[-1] > 1.0
    # error model: rounding of the mirrored sums (docstring: observed 1.8e-15 N m and 6e-17 deg, margin 100)
    for name in ("holding_moment", "friction_low", "friction_high"):
        np.testing.assert_allclose(getattr(left.curve, name), getattr(right.curve, name), rtol=0, atol=2e-13)
    np.testing.assert_allclose(left.drive_difference, right.drive_difference, rtol=0, atol=2e-13)
    assert left.path is not None and right.path is not None and left.path.turn == right.path.turn == "downhill"
    np.testing.assert_allclose(left.path.heading_change_history_deg, right.path.heading_change_history_deg,
                               rtol=0, atol=2e-13)


@pytest.mark.parametrize("fmt", one_default(["svg", "pdf"], "svg"))
def test_the_slope_command_draws_a_layout_and_reverse(fmt, tmp_path, capsys):
    """``slope -o`` for a layout and for a reverse speed: a valid file, whose figure (drawn again here from the
    same inputs) plots the section's numbers with the layout named and a caption."""
    from stability.report.slope_data import layout_slope_section
    from stability.report.slope_figure import layout_slope_figure
    from stability.slope.__main__ import main

    out = tmp_path / f"slope.{fmt}"
    assert main(["--chair", "mid-wheel-drive", "--cross-slope", "-3", "--speed", "-1", "-o", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().err
    data = out.read_bytes()
    assert data.startswith(b"%PDF") if fmt == "pdf" else ET.parse(out).getroot().tag.endswith("svg")
    layout = layout_preset("mid-wheel-drive")
    fig = layout_slope_figure(layout, -3.0, -1.0)
    s = layout_slope_section(layout, -1.0, (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0), 3.0, side=-1.0)
    ax_hold, ax_drive, ax_path = fig.axes[:3]
    np.testing.assert_array_equal(ax_hold.lines[0].get_ydata(), s.curve.holding_moment)
    np.testing.assert_array_equal(ax_drive.lines[0].get_ydata(), s.drive_difference)
    assert s.path is not None
    np.testing.assert_array_equal(ax_path.lines[0].get_ydata(), s.path.heading_change_history_deg)
    title = fig.get_suptitle()
    assert "mid-wheel-drive" in title and "layout model" in title and "backwards" in title
    assert ax_hold.get_xlabel() == "cross slope (deg, falling to the left)"
    assert any("What to conclude" in t.get_text() for t in fig.texts)


def test_the_trail_chart_of_the_thesis_chair_as_a_layout_is_the_short_forms():
    """The chart of the E&J's left caster as a layout's caster 1: the towed wheel at the static load of the
    layout's lever rule (equal to the short form's generated eq 6-25 loads to 1e-12 relative) and the yaw
    divergence of the layout's linear model against the thesis model's eigenvalues (another derivation: observed
    2.1e-13 1/s, asserted 2e-11 1/s).  The towed-wheel quantities came out bit-identical (equal loads give equal
    functions, whose roots the same root finder finds alike); asserted 1e-12 relative."""
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.layout_caster import LayoutCaster

    speeds = [0.5, 2.0]
    short = trail_chart(EJ, TRAILS, speeds)
    lay = trail_chart(LayoutCaster(Layout.from_chair(EJ), 0), TRAILS, speeds)
    assert lay.chair_trail == short.chair_trail and lay.pin_friction == short.pin_friction
    # error model: rounding: two derivations' eigenvalues (docstring: observed 2.1e-13 1/s, x100); the towed-wheel
    # quantities are the same functions of equal loads (observed bit-identical; 1e-12 relative)
    np.testing.assert_allclose(lay.divergence_rate, short.divergence_rate, rtol=0, atol=2e-11)
    for name in ("friction_needed", "critical_trail", "critical_trail_range", "friction_trail"):
        np.testing.assert_allclose(getattr(lay, name), getattr(short, name), rtol=1e-12, atol=1e-15, err_msg=name)
    assert np.any(short.friction_needed > 0)


def test_mirror_image_casters_have_the_same_trail_chart():
    """The mid-wheel-drive base's rear left and rear right casters: mirror images, the same load and row: the
    same arithmetic, so the same chart (observed bit-identical; asserted 1e-12 relative); the front row carries another load, so another
    chart (its friction needed differs)."""
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.layout_caster import LayoutCaster

    layout = layout_preset("mid-wheel-drive")
    left, right, front = (trail_chart(LayoutCaster(layout, k), TRAILS, [1.0]) for k in (2, 3, 0))
    # error model: rounding: the same arithmetic on mirrored numbers (observed bit-identical)
    for name in ("divergence_rate", "friction_needed", "critical_trail", "friction_trail"):
        np.testing.assert_allclose(getattr(left, name), getattr(right, name), rtol=1e-12, atol=1e-15)
    # error model: rounding is ~1e-15; the front row's other load moves the friction needed by 0.16 (observed)
    assert not np.allclose(left.friction_needed, front.friction_needed, rtol=1e-3)


def test_the_shimmy_command_draws_every_caster_row(tmp_path, capsys):
    """``shimmy -o`` for a layout: two pages per caster row and direction (the mid-wheel-drive base forwards and
    backwards: two rows each, eight pages), with the caster and the models named and a caption; the chart pages
    draw the chart's numbers."""
    from stability.shimmy.__main__ import LAYOUT_MODELS, main
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.layout_caster import LayoutCaster
    from stability.shimmy.plots import trail_chart_pages

    out = tmp_path / "shimmy.pdf"
    assert main(["--chair", "mid-wheel-drive", "--speeds", "-1.5,-1,1,1.5", "-o", str(out)]) == 0
    assert f"wrote {out}" in capsys.readouterr().err
    data = out.read_bytes()
    assert data.startswith(b"%PDF") and len(re.findall(rb"/Type\s*/Page(?![a-zA-Z])", data)) == 8
    ej = tmp_path / "ej.pdf"                                # the short form: two pages, as before
    assert main(["--chair", "ej-premier", "--speeds", "1,2", "-o", str(ej)]) == 0
    assert len(re.findall(rb"/Type\s*/Page(?![a-zA-Z])", ej.read_bytes())) == 2
    chart = trail_chart(LayoutCaster(layout_preset("mid-wheel-drive"), 2, reverse=True), TRAILS, [1.0, 1.5])
    pages = trail_chart_pages(chart, LAYOUT_MODELS)
    assert len(pages) == 2
    for fig in pages:
        assert "mid-wheel-drive caster 3 (rear left, reverse)" in fig.get_suptitle()
        assert "layout linear model" in fig.get_suptitle()
        caption = [t.get_text() for t in fig.texts if "What to conclude" in t.get_text()]
        assert len(caption) == 1 and f"{chart.chair_trail * 100:g} cm" in caption[0]
    boundary = [line for line in pages[0].axes[0].lines if "linear shimmy boundary" in str(line.get_label())]
    # rounding: the plotted values are the chart's, in cm (observed 0)
    np.testing.assert_allclose(boundary[0].get_ydata(), np.clip(chart.critical_trail, 0, TRAILS.max()) * 100,
                               rtol=0, atol=1e-12)


def test_a_chart_of_one_speed_is_refused_before_any_work(tmp_path, capsys):
    """A trail x speed chart needs two speeds in each direction drawn: one line, status 2, no file."""
    from stability.shimmy.__main__ import main

    for chair, speeds in (("mid-wheel-drive", "-1,1,2"), ("ej-premier", "1")):
        out = tmp_path / "x.pdf"
        assert main(["--chair", chair, "--speeds", speeds, "-o", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "gives 1 speed" in err and "at least 2 speeds" in err
        assert not out.exists()


def test_the_full_chair_shimmy_model_is_refused_for_a_layout_with_the_reason(capsys):
    from stability.shimmy.__main__ import main

    for argv in (["--chair", "mid-wheel-drive", "--chair-model"], ["--chair", "ej-premier", "--speeds", "-1",
                                                                   "--chair-model"]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "--chair-model" in err and "valid: --chair-model with" in err
        assert "caster" in err


def test_set_on_a_layout_file_is_set_on_the_short_form(ej_file, tmp_path, capsys):
    """``--set`` by the advisor's names on the E&J written as a ``[[wheel]]`` file is the short form's ``--set``:
    both casters' trail (the short form's one ``trail``) through the slope command's held line (the short form's
    generated statics; 1.4e-14 N m observed above, asserted 2e-12), and the mass through the simulate command's
    CSV (the thesis engine; the error model of the CSV test above, 1e-12 of a column's largest value)."""
    import json

    from stability.simulate.__main__ import main as simulate_main
    from stability.slope.__main__ import main as slope_main

    common = ["--cross-slope", "2", "--speed", "1", "--json"]
    assert slope_main(["--chair", str(ej_file), "--set", "caster_1_trail=0.06", "--set", "caster_2_trail=0.06",
                       *common]) == 0
    lay = json.loads(capsys.readouterr().out)
    assert slope_main(["--chair", "ej-premier", "--set", "trail=0.06", *common]) == 0
    short = json.loads(capsys.readouterr().out)
    assert slope_main(["--chair", "ej-premier", *common]) == 0
    unset = json.loads(capsys.readouterr().out)
    key = "holding_yaw_moment_signed_N_m"
    assert abs(short[key] - unset[key]) > 1e-3                       # the trail matters to the held line
    assert lay[key] == pytest.approx(short[key], abs=2e-13)    # rounding: two statics solvers (observed 1.8e-15 N m)
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert simulate_main(["--chair", str(ej_file), "--set", "m=100", "--horizon", "1", "--csv", str(a)]) == 0
    assert simulate_main(["--chair", "ej-premier", "--set", "m=100", "--horizon", "1", "--csv", str(b)]) == 0
    capsys.readouterr()
    x, y = _read_csv(a), _read_csv(b)
    assert len(x["t"]) == len(y["t"])
    for name, theirs in (("heading", "heading"), ("y", "y"), ("delta_caster_1_rear_left", "eta")):
        # error model: rounding: the same run by two models' arithmetic over 1 s (observed 3.5e-16), x140
        assert np.abs(x[name] - y[theirs]).max() <= 5e-14 * np.abs(y[theirs]).max()
