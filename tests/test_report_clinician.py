"""``report --clinician``: the one-page sheet's numbers against the analyses they come from and closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stability import run_simulation, study
from stability.chair import preset
from stability.report import command as report_command
from stability.report.clinician_sheet import SPRING_LEVER_M, G, clinician_sheet, sheet_lines
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.tipping import tip_angles


@pytest.fixture(scope="module")
def sheet():
    return clinician_sheet(preset("ej-premier"), (0.5, 0.75, 1.0))


def test_bump_times_are_the_simulators(sheet):
    """The 0.75 m/s row is the thesis's reference case: one stick-slip run of the simulator after the push, its
    time to |yaw rate| = 1 rad/s read independently off the recorded arrays (linear interpolation, error < dt)."""
    c = preset("ej-premier")
    res = run_simulation(c, 0.75, RunSpec(friction_law="stick-slip", horizon=10.0, push_force=THESIS_PUSH.force,
                                          push_duration=THESIS_PUSH.duration))
    r, t = np.abs(np.asarray(res.yaw_rate)), np.asarray(res.t)
    k = int(np.argmax(r >= 1.0))
    t_level = t[k - 1] + (1.0 - r[k - 1]) / (r[k] - r[k - 1]) * (t[k] - t[k - 1])
    m = sheet.motions[1]
    assert m.kind == "spins up"
    # error model: the linear interpolation between samples, within one 1 ms step (observed 6.3e-6 s), x160
    assert m.time_to_level == pytest.approx(t_level, abs=1e-3)
    rows = sheet_lines(sheet)["bump_rows"]
    assert f"{float(f'{m.time_to_level:.3g}'):g} s to 1 rad/s" in rows[1][2]


def test_slow_speed_drift_is_a_steady_turn(sheet):
    """At 0.5 m/s the chair does not spin up within 10 s but keeps turning (review change 6: 'does not within
    10 s' hid a 43 deg turn); the sheet prints the turn in deg per 10 s = 10 x final yaw rate."""
    m = sheet.motions[0]
    assert m.kind == "keeps turning"
    row = sheet_lines(sheet)["bump_rows"][0]
    assert f"{float(f'{math.degrees(abs(m.final_rate)) * 10:.3g}'):g} deg in 10 s" in row[1]


def test_spring_scale_tip_angles_and_slope_numbers(sheet):
    text = " ".join(sheet_lines(sheet)["paragraphs"])
    # closed form: F = M_f / r; 0.3 N m at 10 cm = 3 N = 306 g; the E&J's 0.1 N m = 1 N = 102 g
    assert SPRING_LEVER_M == 0.10
    assert f"{1000 * 0.3 / 0.1 / G:.0f} g (3 N)" in text and "306 g" in text
    assert "102 g (1 N)" in text
    t = tip_angles(preset("ej-premier"))
    for v in (t.toward_main_wheels_deg, t.toward_casters_deg, t.lateral_left_deg):
        assert f"{v:.1f} deg" in text
    sl = sheet.slope
    k = int(np.argmin(np.abs(np.asarray(sl.curve.cross_slopes_deg) - 2.0)))
    assert f"push {abs(sl.drive_difference[k]):.0f} N harder" in text
    assert "PEAK" in text and "sustained" in text


def test_cli_clinician_writes_one_page(tmp_path, capsys):
    """The command's --clinician run (in process: the ``python -m stability.report`` entry point itself is run by
    tests/test_cli_interrupt.py and tests/test_report_layout.py) writes a one-page PDF and its text."""
    out, txt = tmp_path / "c.pdf", tmp_path / "c.txt"
    status = report_command.main(["--chair", "ej-premier-front-caster", "--clinician", "--speeds", "0.75", "-o",
                                  str(out), "--text", str(txt)])
    assert status == 0, capsys.readouterr().err
    pages = txt.read_text().count("=== page")
    assert pages == 1 and out.read_bytes().startswith(b"%PDF")
    assert "keeps turning" in txt.read_text() or "returns to its line" in txt.read_text()


@pytest.mark.parametrize("argv, needle", [
    (["--clinician", "--speeds", "5"], "--speeds '5' is invalid; valid range: 0.1 to 3 m/s"),
    (["--clinician", "--compare", "revised"], "--compare cannot be combined with --clinician"),
    (["--speeds", "0.5"], "--speeds '0.5' needs --clinician"),
])
def test_clinician_bad_input_is_one_line(argv, needle, tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        raise SystemExit(report_command.main(["--chair", "ej-premier", "-o", str(tmp_path / "x.pdf"), *argv]))
    err = capsys.readouterr().err.strip()
    assert e.value.code == 2 and len(err.splitlines()) == 1 and needle in err
    assert not (tmp_path / "x.pdf").exists()


def test_study_runs_are_stick_slip():
    """The sheet names its pin-friction law (review error 17): the report's runs default to stick-slip."""
    from stability.report.compute import report_run
    from stability.report.settings import Settings

    assert report_run("exact", Settings.for_mode(False), "wchair").friction_law == "stick-slip"
    assert study.Criterion().yaw_rate == 1.0


@pytest.fixture(scope="module")
def brief(tmp_path_factory):
    from stability.report import document

    path = tmp_path_factory.mktemp("brief") / "q.pdf"
    return document.build(preset("ej-premier"), path, brief=True, progress=False)


def test_quick_report_is_the_decision_the_sheet_and_the_references(brief):
    """``--quick`` (issue 35): page 1 with the full report's decision (the advisor's paragraphs verbatim, the
    same function the full report calls), the clinician sheet and the references; nothing coarsened, so no
    dagger marks, and every time to 1 rad/s it prints is the advisor's (one value per measure)."""
    from stability.advise.decision import decide
    from stability.report.quick import MARK

    assert [p.title for p in brief.pages] == ["decision", "for the clinician", "glossary and references"]
    d = brief.data
    def squash(t: str) -> str:          # wrapped lines break at spaces and hyphens: compare without whitespace
        return "".join(t.split())

    page1 = " ".join(" ".join(brief.pages[0].texts).split())
    for para in decide(d.advice).paragraphs():
        assert squash(para) in squash(page1)
    whole = " ".join(" ".join(t for p in brief.pages for t in p.texts).split())
    assert MARK not in whole and "QUICK REPORT." in page1
    # the sheet's runs are the advisor's reference-push runs: the same times, to the digits either prints
    for u, t, m in zip(d.advice.speeds_m_s, d.advice.time_to_correct_s, d.sheet.motions, strict=True):
        assert m.speed == pytest.approx(u, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        if t is None:
            assert m.kind != "spins up"
        else:
            assert m.time_to_level == pytest.approx(t, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_quick_cli_refuses_what_needs_the_full_report(tmp_path, capsys):
    for extra in (["--compare", "revised"], ["--json"]):
        with pytest.raises(SystemExit) as e:
            raise SystemExit(report_command.main(["--quick", "-o", str(tmp_path / "q.pdf"), *extra]))
        assert e.value.code == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "needs the full report" in err


def test_the_sheet_says_up_to_which_speed_this_user_holds_the_chair(tmp_path):
    """--reaction-time (issue 37: the clinician sheet uses U_h): the sheet's USER line is the driver's human-limited
    speed (stability.driver.human_limit), and a speed of use above it is named."""
    from stability.chair import preset
    from stability.driver import Driver, human_limit
    from stability.report.command import main as report_main

    pdf, txt = tmp_path / "s.pdf", tmp_path / "s.txt"
    assert report_main(["--clinician", "--reaction-time", "1.5", "--speeds", "0.5,1", "-o", str(pdf),
                        "--text", str(txt)]) == 0
    text = " ".join(txt.read_text().split())
    h = human_limit(preset("ej-premier"), Driver(1.5))
    assert h.side == "=" and h.speed_m_s < 1.0
    assert f"up to {h.speed_m_s:.3g} m/s" in text and "1.5 s late" in text
    assert "at 1.8 km/h, 3.6 km/h this user cannot hold it" in text          # both speeds above 0.291 m/s


@pytest.mark.slow               # a whole quick report through the command (the decision itself: test_report_driver.py)
def test_the_chair_files_user_reaches_the_reports_decision(tmp_path):
    """A chair file's ``[user]`` (no option given) reaches the report's decision, as it reaches
    ``python -m stability.advise``: page 1 has the advisor's driver line with the file as its source and the
    recommendation this user can hold (tests/test_report_driver.py checks that decision); before, the report
    ignored the file's user in its decision and the full report refused ``--reaction-time``."""
    from stability.chair.io import save
    from stability.driver.linear import rule_speed
    from stability.report.command import main as report_main

    chair = tmp_path / "ej.toml"
    save(preset("ej-premier"), chair)
    with open(chair, "a", encoding="utf-8") as fh:
        fh.write('\n[user]\nreaction_time_s = 0.5\nsource = "clinic test"\n')
    pdf, txt = tmp_path / "q.pdf", tmp_path / "q.txt"
    assert report_main(["--chair", str(chair), "--quick", "--no-progress", "-o", str(pdf), "--text", str(txt)]) == 0
    text = " ".join(txt.read_text().split())
    u = rule_speed(preset("ej-premier"), 0.5)[0]
    assert f"Driver: a driver who corrects the heading 0.5 s late can hold this chair straight up to {u:.3g} m/s" in text
    # without the user the report recommends moving the axle, which this user cannot hold at 1 m/s
    assert "RECOMMENDATION. " in text and "RECOMMENDATION. Axle 10 cm toward" not in text
    assert "reaction time from clinic test;" in text            # the [user] table's own source
