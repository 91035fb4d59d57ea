"""The explorer's session state (no browser, no Panel): edits, bad values, undo, URL, pins, downloads."""

from __future__ import annotations

import ast
import csv
import io
import json
import pathlib

import numpy as np
import pytest

from stability import chair as chair_mod
from stability.app import MAX_PINNED, AppState
from stability.app.views import GRID, eigenvalues_csv, linear_view, mode_shape
from stability.critical_speed import main as critical_speed_main
from stability.linear import divergence, state_matrices


def cli_error(capsys, *args: str) -> str:
    """The one line ``python -m stability.critical_speed ARGS`` prints on stderr (run in-process)."""
    assert critical_speed_main(list(args)) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    return err[0]


@pytest.mark.parametrize("name, text", [("trail", "0.7"), ("trail", "abc"), ("m", "-3"), ("i_zp", "0.0001"),
                                        ("caster_position", "middle"), ("main_tire", "XYZ"), ("camber_deg", "nan")])
def test_bad_value_gives_the_command_line_message_and_keeps_the_last_valid_chair(capsys, name, text):
    s = AppState("revised")
    assert s.set_field("trail", "0.06") is None
    before = s.chair
    msg = s.set_field(name, text)
    assert msg == cli_error(capsys, "--chair", "revised", "--set", "trail=0.06", "--set", f"{name}={text}")
    assert msg.startswith("error: ") and name in msg
    assert s.errors[name] == msg
    assert s.chair == before
    # the next accepted edit of that field clears its message
    assert s.set_field(name, s.value_text(name)) is None and name not in s.errors


def test_edit_applies_like_set_and_names_the_chair():
    s = AppState("revised")
    assert s.set_field("trail", "0.055") is None
    assert s.set_field("s1", "0.25") is None
    assert s.chair == chair_mod.preset("revised").replace(trail=0.055).replace(s1=0.25)
    assert s.chair.name == "revised (modified: trail=0.055, s1=0.25)"


def test_url_query_round_trip():
    s = AppState("revised")
    s.set_field("trail", "0.055")
    s.set_field("s1", "0.25")
    assert s.url_query() == "chair=revised&trail=0.055&s1=0.25"
    t = AppState.from_query("?" + s.url_query())
    assert t.chair == s.chair and t.url_query() == s.url_query()
    # the example URL opens that chair
    u = AppState.from_query({"chair": ["revised"], "trail": ["0.06"], "s1": ["0.25"]})
    assert u.chair == chair_mod.preset("revised").replace(trail=0.06, s1=0.25)
    # a value set back to the preset's leaves the query
    s.set_field("trail", repr(chair_mod.preset("revised").trail))
    assert s.url_query() == "chair=revised&s1=0.25"
    # the model travels too
    assert AppState.from_query("chair=revised&model=thesis").model == "thesis"


def test_float_values_survive_the_url_exactly():
    s = AppState()
    assert s.set_field("h", str(0.1 + 0.2)) is None          # 0.30000000000000004
    assert AppState.from_query(s.url_query()).chair.h == 0.1 + 0.2


@pytest.mark.parametrize("query, fragment, want", [
    ("chair=nope", "nope", ("ej-premier", {})),
    ("chair=nope&trail=0.05", "nope", ("ej-premier", {"trail": 0.05})),
    ("chair=revised&trail=9", "trail=9.0", ("revised", {})),
    ("chair=revised&trail=abc&s1=0.25", "trail needs a number", ("revised", {"s1": 0.25})),
    ("chair=revised&wheels=5", "wheels", ("revised", {})),
    ("chair=revised&model=fancy", "fancy", ("revised", {}))])
def test_bad_url_parts_are_dropped_with_a_message_and_the_rest_kept(query, fragment, want):
    """A link with a typo opens the chair its valid part names (the explorer review's item 5: it showed
    ej-premier under a URL that said revised), and the message names the dropped part."""
    s = AppState.from_query(query)
    preset, changes = want
    assert s.chair == chair_mod.preset(preset).replace(**changes)
    assert s.errors["url"].startswith("error: ") and fragment in s.errors["url"]
    assert s.model == "exact"
    assert AppState.from_query(s.url_query()).chair == s.chair       # the rewritten URL is that chair's


def test_undo_walks_back_every_accepted_change():
    s = AppState()
    start = s.chair
    assert not s.can_undo and s.undo() is False
    s.set_field("trail", "0.05")
    after_trail = s.chair
    s.set_field("trail", "9")                                   # refused: not a change
    s.select_preset("revised")
    s.set_field("m", "80")
    assert s.undo() and s.chair == chair_mod.preset("revised")
    assert s.undo() and s.chair == after_trail
    assert s.undo() and s.chair == start
    assert s.undo() is False


def test_apply_several_fields_all_or_none():
    s = AppState()
    before = s.chair
    msg = s.set_fields({"trail": "0.05", "s1": "7"})
    assert msg is not None and "s1=7.0" in msg and s.chair == before
    assert s.set_fields({"trail": "0.05", "s1": "0.3"}) is None
    assert (s.chair.trail, s.chair.s1) == (0.05, 0.3)


def test_toml_download_reloads_to_the_same_chair(tmp_path):
    s = AppState("revised")
    s.set_field("trail", "0.0612345678901")
    s.set_field("camber_coefficient", "0.07")
    text = s.chair_toml()
    path = tmp_path / "mine.toml"
    path.write_text(text)
    assert chair_mod.load(path) == s.chair                      # as --chair FILE reads it
    t = AppState()
    assert t.load_toml(text.encode(), "mine.toml") is None
    assert t.chair == s.chair and t.current.base == "file:mine.toml"
    # an uploaded chair's URL rebuilds it from the default preset
    assert AppState.from_query(t.url_query()).chair == s.chair
    assert t.undo() and t.chair == chair_mod.preset("ej-premier")


def test_bad_upload_is_one_line_and_changes_nothing():
    s = AppState()
    assert s.load_toml(b"trail = 'x", "bad.toml").startswith("error: chair file ")
    assert s.load_toml(b"trail = 3.0\n", "far.toml") == ("error: chair parameter trail=3.0 is invalid; "
                                                          "valid range: 0 to 0.5 m")
    assert s.load_toml(b"\xff\xfe", "binary.toml").startswith("error: ")
    assert s.chair == chair_mod.preset("ej-premier")
    assert s.load_uncertainty(b"[trail]\nkind = 'banana'\n", "u.toml").startswith("error: ")
    assert s.uncertainty is None


def test_uncertainty_upload(tmp_path):
    example = pathlib.Path(__file__).parents[1] / "docs" / "examples" / "measured_chair.uncertainty.toml"
    s = AppState()
    assert s.load_uncertainty(example.read_bytes(), example.name) is None
    assert s.uncertainty is not None and s.uncertainty_name == example.name and s.uncertainty.names


@pytest.mark.parametrize("model", ["exact", "thesis"])
def test_results_json_equals_the_command_lines(tmp_path, capsys, model):
    s = AppState.from_query(f"chair=revised&trail=0.06&model={model}")
    path = tmp_path / "c.toml"
    path.write_text(s.chair_toml())
    out = tmp_path / "r.json"
    assert critical_speed_main(["--chair", str(path), "--model", model, "--json-file", str(out)]) == 0
    capsys.readouterr()
    assert json.loads(s.results_json()) == json.loads(out.read_text())


def test_eigenvalues_csv_holds_the_linear_models_eigenvalues():
    s = AppState()
    view = linear_view(s.chair, s.model)
    rows = [r for r in csv.reader(io.StringIO(eigenvalues_csv(view))) if not r[0].startswith("#")]
    header, body = rows[0], np.array(rows[1:], dtype=float)
    assert header[0] == "speed_m_s" and len(header) == 1 + 2 * 6
    assert np.array_equal(body[:, 0], GRID)
    k = int(np.argmin(np.abs(GRID - 0.75)))
    got = body[k, 1::2] + 1j * body[k, 2::2]
    A = state_matrices(s.chair, GRID[k])[0]
    want = np.linalg.eigvals(A)
    # the same matrix through the same LAPACK routine, batched or not: equal to rounding; match as sets.
    # Error model: eps * ||A|| * (eigenvector condition number, below 1e3 for these well-separated modes).
    tol = 1e3 * np.finfo(float).eps * np.linalg.norm(A) * 100
    from scipy.optimize import linear_sum_assignment
    cost = np.abs(got[:, None] - want[None, :])
    r, c = linear_sum_assignment(cost)
    assert cost[r, c].max() <= tol


def test_growth_rate_shown_is_the_command_lines():
    s = AppState.from_query("chair=ej-premier&trail=0.05")
    view = linear_view(s.chair, s.model)
    doc = json.loads(s.results_json())
    printed = {r["speed_m_s"]: r["rate_1_s"] for r in doc["free_casters"]["divergence"]}
    assert {r.speed: r.rate for r in view.table} == printed
    assert [c.speed for c in view.locked_crossings] == pytest.approx(
        [c["speed_m_s"] for c in doc["locked_casters"]["crossings"]], abs=1e-8)  # rounding: equivalent arithmetic, a few ulp (observed 6.1e-16); both refined to xtol 1e-10 m/s
    assert divergence(s.chair, [0.75])[0].rate == printed[0.75]


def test_mode_shape_is_an_eigenvector():
    """The mode shape is computed at the slider's speed itself (the explorer review: it snapped to the plot's
    grid, 0.76 m/s for 0.75, and never matched the table): its eigenvalue is the table's growth rate."""
    view = linear_view(chair_mod.preset("ej-premier"))
    shape = mode_shape(view, 0.75)
    assert shape.speed == 0.75
    row = next(r for r in view.table if r.speed == 0.75)
    # the same matrix through the same LAPACK routine: equal to rounding (error model: eps * ||A|| * 1e3)
    A = state_matrices(view.chair, 0.75)[0]
    assert abs(shape.eigenvalue.real - row.rate) <= 1e3 * np.finfo(float).eps * np.linalg.norm(A)
    for u in (0.06, 0.08, 1.234):
        assert mode_shape(view, u).speed == u
    assert max(shape.magnitude) == 1.0 and sum(shape.shares.values()) == pytest.approx(1.0, abs=1e-12)
    # the ej-premier's least stable mode: both casters swing together (mirror symmetry), no opposed part
    assert shape.shares["casters opposed"] < 1e-20
    assert shape.magnitude[2] == pytest.approx(shape.magnitude[3], rel=1e-9)


def test_pins_at_most_three_no_duplicates():
    s = AppState()
    assert s.pin() is None
    assert s.pin().startswith("error: ") and "already pinned" in s.errors["pin"]
    for trail in ("0.05", "0.06"):
        s.set_field("trail", trail)
        assert s.pin() is None
    s.set_field("trail", "0.07")
    assert "at most 3" in s.pin() and len(s.pinned) == MAX_PINNED
    s.unpin(0)
    assert s.pin() is None and s.pinned[-1] == s.chair


def test_sessions_share_nothing():
    a, b = AppState(), AppState()
    a.set_field("trail", "0.05")
    a.pin()
    a.set_field("m", "bad")
    assert b.chair == chair_mod.preset("ej-premier") and not b.pinned and not b.errors and not b.can_undo


APP = pathlib.Path(__file__).parents[1] / "stability" / "app"


def test_the_app_adds_no_physics():
    """The app imports no equations (models/, _generated/, sympy) and defines no physical constants."""
    for path in APP.glob("*.py"):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                mod = "." * node.level + (node.module or "")
                if not mod.startswith("."):
                    continue                                    # third-party (bokeh.models is not ours)
                assert not any(p in mod.split(".") for p in ("models", "_generated", "derivations", "params")), \
                    (path.name, mod)
                assert "sympy" not in mod
            if isinstance(node, ast.Import):
                assert not any("sympy" in a.name or "_generated" in a.name for a in node.names), path.name
            if isinstance(node, ast.Constant) and isinstance(node.value, float):
                assert node.value not in (9.81, 9.80665), (path.name, node.value)


@pytest.mark.parametrize("name", chair_mod.preset_names())
def test_critical_speeds_shown_are_the_command_lines(name):
    """The explorer searches a coarser grid than ``critical_speed`` (100 vs 600 speeds); same crossings."""
    from stability.linear import analyse

    c = chair_mod.preset(name)
    view, summary = linear_view(c), analyse(c)
    for got, want in ((view.free_crossings, summary.free_crossings), (view.locked_crossings, summary.locked_crossings)):
        assert [x.direction for x in got] == [x.direction for x in want]
        # both refined by Brent's method to xtol 1e-10 m/s from different brackets; error model: bisection bracket:
        # two answers within 2e-10 m/s (observed 1.9e-11; 2e-9 is 100x)
        assert [x.speed for x in got] == pytest.approx([x.speed for x in want], abs=2e-9)


def test_applying_a_recommendation_is_its_set_assignments():
    """The advice tab (via stability.app.state.assignments, which needs no panel) applies a recommendation's fields as one edit; the chair is the one ``--set`` gives."""
    from stability.advise import Change
    from stability.app.state import assignments
    from stability.cli import load_chair

    changes = (Change("pin_friction", "pin friction 0.1 -> 0.3 N m", (("pin_friction_left", 0.3),
                                                                     ("pin_friction_right", 0.3))),
               Change("trail", "trail 8 -> 6 cm", (("trail", 0.06),)))
    fields = {k: v for ch in changes for k, v in ch.fields}
    s = AppState()
    assert s.set_fields(assignments(fields)) is None
    assert s.chair == load_chair("ej-premier", [a for ch in changes for a in ch.assignments])
    assert s.undo() and s.chair == chair_mod.preset("ej-premier")       # one edit, one undo


def test_reset_drops_every_change_and_undo_takes_it_back():
    s = AppState("revised")
    assert s.reset() is False                                   # nothing changed yet
    s.set_field("trail", "0.05")
    s.set_field("s1", "0.25")
    changed = s.chair
    assert s.reset() and s.chair == chair_mod.preset("revised") and s.url_query() == "chair=revised"
    assert s.undo() and s.chair == changed


def test_undo_restores_the_model_too():
    s = AppState()
    s.set_field("trail", "0.05")
    s.set_model("thesis")
    assert s.url_query() == "chair=ej-premier&trail=0.05&model=thesis"
    assert s.undo() and s.model == "exact" and s.chair.trail == 0.05


def test_upload_messages_name_the_file_not_the_servers_copy(tmp_path):
    import tempfile

    s = AppState()
    msg = s.load_toml(b"trail = 'x", "my chair.toml")
    assert msg.startswith("error: chair file 'my chair.toml' is not valid TOML")
    assert tempfile.gettempdir() not in msg
    msg = s.load_uncertainty(b"[trail\n", "u.toml")
    assert msg.startswith("error: uncertainty file 'u.toml' is not valid TOML")       # the CLI's words
    assert tempfile.gettempdir() not in msg


def test_download_file_names_carry_the_chair_and_no_markup():
    from stability.app.downloads import file_names, file_stem

    s = AppState("revised")
    s.set_field("trail", "0.055")
    names = file_names(s.chair.name)
    assert names["toml"] == "revised-modified-trail-0.055.toml" and names["png"].endswith(".eigenvalues.png")
    for hostile in ("<script>alert(1)</script>", "../../etc/passwd", "", "a" * 500, "é/ü"):
        stem = file_stem(hostile)
        assert stem and len(stem) <= 60 and all(c.isascii() and (c.isalnum() or c in "._-") for c in stem)
        assert not stem.startswith(".")


def test_every_field_is_in_one_editor_group_with_a_label_in_words():
    from stability.app.text import FIELD_GROUPS, field_label, field_rows

    grouped = [f for _, fields, _ in FIELD_GROUPS for f in fields]
    assert sorted(grouped) == sorted(chair_mod.field_names()) and len(grouped) == len(set(grouped))
    labels = {r["name"]: field_label(r) for r in field_rows()}
    assert labels["trail"] == "Caster trail, pin to contact: trail (m)"
    assert labels["roll_k"].startswith("Roll coefficient") and labels["roll_k"].endswith(": roll_k")


def test_simulator_warnings_reach_the_nonlinear_view():
    """The explorer review: trail=0.5 raised StepStabilityWarning on the server's stderr only."""
    from stability.app.measures import nonlinear_view

    nv = nonlinear_view(chair_mod.preset("ej-premier").replace(trail=0.5), "exact", 0.75, (40.0, 0.1),
                        equal_instability=False)
    assert any(w.startswith("StepStabilityWarning: ") for w in nv.warnings), nv.warnings
    quiet = nonlinear_view(chair_mod.preset("ej-premier"), "exact", 0.75, (40.0, 0.1), equal_instability=False)
    assert quiet.warnings == ()
    assert 2.0 < quiet.time_to_level < 4.0                         # the criterion's time, from the run itself
    assert quiet.critical_impulse.low_Ns <= quiet.critical_impulse.point.bound_Ns <= quiet.critical_impulse.high_Ns


@pytest.mark.parametrize("name", ["ej-premier", "revised"])
def test_trail_chart_crosses_zero_at_the_bands_boundary(name):
    """The explorer review: the chart's dashed shimmy curves crossed zero at 2 cm (rigid pins) while the band's
    boundary drawn on it was at 4.9 cm (the towed wheel on its pin spring).  The chart now uses the compliant pins:
    for a symmetric chair its least damped caster mode is the towed wheel's (docs/shimmy.md), so the crossings
    coincide (the chart's bisection stops at 0.01 mm)."""
    from stability.app.measures import TRAIL_SPEEDS, trail_window

    tw = trail_window(chair_mod.preset(name))
    lower = [min(bs) for bs in tw.band.boundaries_m]
    assert len(lower) == len(TRAIL_SPEEDS)
    # error model: bisection bracket: the chart's search stops at 1e-5 m, the band's at 1e-9 m; two widths of the
    # chart's (observed 2.5e-6 m)
    assert np.allclose(tw.chart.critical_trail, lower, rtol=0, atol=2e-5)


def test_summary_verdict_names_the_speeds_searched():
    """The summary's one-line verdict, for chairs whose free-caster rates keep one sign on the whole grid: rear
    swivelling casters without pin friction are unstable at every speed (the thesis's free-caster result, docs and
    ``critical_speed``: no stabilising speed), front casters stable at every speed; the words name the grid's ends
    (settings.defaults.MAX_SPEED), not a typed range."""
    from stability.app.text import summary_html
    from stability.settings import defaults as D

    searched = f"from {GRID[0]:g} to {D.MAX_SPEED:g} m/s"
    rear = summary_html(linear_view(chair_mod.preset("ej-premier")))
    front = summary_html(linear_view(chair_mod.preset("ej-premier-front-caster")))
    assert f"Free casters: unstable at every speed {searched}." in rear
    assert f"Free casters: stable at every speed {searched}." in front
    assert searched == "from 0.01 to 30 m/s"     # what the page said before the words were computed


@pytest.mark.slow
def test_results_json_with_the_sessions_user_equals_the_command_on_the_toml_download(tmp_path, capsys, monkeypatch):
    """With a user (the Tracking tab's table, no source of its own), the results download is what
    ``critical_speed --chair <the TOML download> --json`` prints: the user's linear limits, the assisted limit
    (null: a manual chair) and the nonlinear lane limit, the source naming the downloaded file as the command does."""
    from stability.app.downloads import file_names

    s = AppState.from_query("chair=revised&trail=0.06")
    s.user = {"reaction_time_s": 0.4}
    monkeypatch.chdir(tmp_path)
    name = file_names(s.chair.name)["toml"]
    (tmp_path / name).write_text(s.chair_toml())
    assert critical_speed_main(["--chair", name, "--json-file", "r.json"]) == 0
    capsys.readouterr()
    mine, theirs = json.loads(s.results_json()), json.loads((tmp_path / "r.json").read_text())
    assert mine == theirs
    assert mine["human_limit"]["driver"]["source"] == f"{name} [user]" and mine["options"]["reaction_time_s"] == 0.4
    assert mine["human_limit"]["nonlinear"] is not None and mine["human_limit"]["with_assist"] is None
