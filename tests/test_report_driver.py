"""The user in the short-form report (``report --reaction-time S`` or the chair file's ``[user]``).

The report's decision must be the one ``python -m stability.advise`` gives the same user: the advisor weighs the
speed this driver can hold.  Before, the report ignored the driver in its decision (and the full report refused the
option), so for a user with a 0.5 s delay it recommended moving the axle 10 cm toward the c.g., a change this user
cannot hold at the intended 1 m/s.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from stability.advise.subject import apply
from stability.chair import preset
from stability.driver import Driver, HumanLimit, human_limit
from stability.driver.linear import rule_speed
from stability.linear.modes import eigenvalues_vs_speed
from stability.report.brief import compute_brief
from stability.report.clinician import clinician_text, user_sentence
from stability.report.clinician_sheet import sheet_lines
from stability.report.decision import decision_paragraphs, decision_rows

TAU = 0.5            # s: a slow user, whose limit (about 1.04 m/s by the divergence rule) is near the intended 1 m/s


def _limit(rule: float, loop: float, rule_side: str = "=", loop_side: str = "=") -> HumanLimit:
    return HumanLimit("x", "exact", 0.52, rule, rule_side, loop, loop_side, 2, 0.0)


def test_the_user_sentence_names_the_binding_limit_and_flags_a_loop_below_the_intended_speed():
    """Both limits are given and the lower one named; when the divergence rule (the advisor's check) reaches the
    intended speed but the delayed loop does not, the sentence says the speed is beyond this user."""
    d = Driver(0.52, source="--reaction-time")
    s = user_sentence(_limit(1.0004, 0.9734), d, intended=1.0)
    assert "up to 0.973 m/s (3.5 km/h), limited by the delayed loop (divergence rule 1 m/s, delayed loop 0.973 m/s" in s
    assert "delayed loop 0.973 m/s; reaction time from --reaction-time; the exact linear model" in s
    assert s.count("(") == s.count(")") and "take that speed as beyond this user" in s
    assert "beyond this user" not in user_sentence(_limit(1.0004, 0.9734), d)              # no intended speed
    assert "beyond this user" not in user_sentence(_limit(1.04, 1.019), d, intended=1.0)    # the loop reaches it
    assert "beyond this user" not in user_sentence(_limit(0.98, 0.95), d, intended=1.0)     # the rule fails too
    assert "beyond this user" not in user_sentence(_limit(6.0, 6.0, ">", ">"), d, intended=1.0)
    assert "beyond this user" in user_sentence(_limit(6.0, 0.1, ">", "<"), d, intended=1.0)    # bounds as values
    assert "beyond this user" not in user_sentence(_limit(1.2, 1.0), d, intended=1.0)     # the loop just reaches it
    assert "beyond this user" in user_sentence(_limit(1.0, 0.9), d, intended=1.0)         # the rule just reaches it
    thesis = HumanLimit("x", "thesis", 0.52, 1.07, "=", 1.0, "=", 2, 0.0)     # the model is named (the advisor's is exact)
    assert "the thesis linear model without pin friction" in user_sentence(thesis, d)
    s = user_sentence(_limit(0.9, 1.1), d)
    assert "limited by the divergence rule (divergence rule 0.9 m/s, delayed loop 1.1 m/s" in s
    s = user_sentence(_limit(6.0, 6.0, ">", ">"), d)
    assert "at every speed checked, up to 6 m/s" in s and "(divergence rule > 6 m/s, delayed loop > 6 m/s" in s


@pytest.fixture(scope="module")
def brief():
    return compute_brief(preset("ej-premier"), driver=Driver(TAU, source="--reaction-time"), progress=False)


def _rate(chair, u: float) -> float:
    """The largest real part of the free-caster linear model at ``u`` (the batched eigenvalue path)."""
    return float(np.max(eigenvalues_vs_speed(chair, [u], track=False).real))


def test_the_quick_report_recommends_what_this_user_can_hold(brief):
    """The decision weighs the driver: the recommended chair's divergence rate at the intended speed stays within
    1/tau (the divergence rule, checked on the eigenvalues directly, not through the advisor's bisection), while the
    recommendation of the committed report (no driver: axle 10 cm toward the c.g. + pin friction 0.3 N m) breaks it
    for this user."""
    a = brief.advice
    assert a.driver is not None and a.intended_speed_m_s == 1.0          # the fastest use speed, exactly
    rec = a.recommendations[0].candidate
    chosen = apply(preset("ej-premier"), [f for ch in rec.changes for f in ch.fields])
    # margins: the chosen chair's rule speed is 1.043 m/s and the committed one's 0.978 m/s, against the intended
    # 1 m/s; both far beyond the rule's bisection tolerance (stability.driver.linear.SPEED_TOL_M_S, 1e-3 m/s)
    assert _rate(chosen, a.intended_speed_m_s) * TAU <= 1.0
    text = " ".join(open("reports/ej-premier.txt", encoding="utf-8").read().split())
    m = re.search(r"RECOMMENDATION\. Axle 10 cm toward the c\.g\. at fixed s1\+s2 \(s1 ([\d.]+) -> ([\d.]+) cm\) \+ pin "
                  r"friction 0\.1 -> ([\d.]+) N m \(both pins\)", text)
    assert m, "the committed report's recommendation moved: read it again"
    ej = preset("ej-premier")
    s1, pins = float(m.group(2)) / 100, float(m.group(3))
    committed = ej.replace(s1=s1, s2=ej.s1 + ej.s2 - s1, pin_friction_left=pins, pin_friction_right=pins)
    assert _rate(committed, a.intended_speed_m_s) * TAU > 1.0
    assert "axle" not in rec.label.lower()


def test_page_one_and_the_sheet_state_the_same_user_limit(brief):
    """Page 1's decision has the advisor's driver line (the divergence rule) and its clinician paragraph the user's
    two limits; the clinician sheet states the same sentence: one value per measure in the PDF."""
    h = human_limit(preset("ej-premier"), Driver(TAU))
    assert brief.human.speed_m_s == h.speed_m_s and brief.human.limited_by == h.limited_by
    page1 = " ".join(decision_paragraphs(brief)) + " " + clinician_text(brief)
    assert f"Driver: a driver who corrects the heading {TAU:g} s late can hold this chair straight up to " \
           f"{h.rule_speed_m_s:.3g} m/s" in page1
    sentence = user_sentence(brief.human, brief.driver, brief.advice.intended_speed_m_s)
    assert f"up to {h.speed_m_s:.3g} m/s" in sentence and f"limited by the {h.limited_by}" in sentence
    assert sentence in page1
    sheet = " ".join(sheet_lines(brief.sheet)["paragraphs"])
    assert f"THE USER. {user_sentence(brief.human, brief.driver)}" in sheet


@pytest.mark.slow
def test_the_full_report_takes_the_user_and_its_json_gives_the_limits(tmp_path, capsys):
    """``report --reaction-time 0.52 --json``: the full report no longer refuses the option; its JSON (valid against
    the schema) has the option and the user's limits, the same as ``critical_speed --reaction-time``."""
    from stability.report.command import main
    from stability.schemas import validate

    assert main(["--reaction-time", "0.52", "--json", "--no-progress"]) == 0
    d = json.loads(capsys.readouterr().out)
    validate("report", d)
    h = human_limit(preset("ej-premier"), Driver(0.52))
    assert d["options"]["reaction_time_s"] == 0.52 and d["options"]["intended_speed_m_s"] == 1.0   # the fastest use
    # the same function on the same chair in this process (bit for bit); JSON writes a float's shortest repr exactly
    assert d["human_limit"]["speed_m_s"] == h.speed_m_s
    assert d["human_limit"]["limited_by"] == h.limited_by == "delayed loop"
    assert d["human_limit"]["driver"]["source"] == "--reaction-time"
    # the decision weighed the driver: the advisor's verdict has the divergence rule's speed, and the limits list it
    assert d["decision"]["verdict"]["human_limited_speed_m_s"] == h.rule_speed_m_s
    assert "human_limited_speed_m_s" in [k["name"] for k in d["decision"]["recommendation"]["constraints"]]


def test_page_ones_table_has_the_users_speed_for_each_column(brief):
    """The key-numbers table's last row is the speed this user can hold by the divergence rule, for this chair, the
    recommended chair and (not here: the chair is the reference) the reference chair, each from
    :func:`stability.driver.linear.rule_speed` on that chair."""
    header, rows = decision_rows(brief)
    assert header == ["measure (range)", "this chair", "recommended"]
    label, mine, rec = rows[-1]
    assert label == f"speed a user {TAU:g} s late holds (m/s, divergence rule)"
    ej = preset("ej-premier")
    chosen = apply(ej, [f for ch in brief.advice.recommendations[0].candidate.changes for f in ch.fields])
    assert mine == f"{rule_speed(ej, TAU)[0]:.3g}"
    assert rec.split(" (")[0] == f"{rule_speed(chosen, TAU)[0]:.3g}"


def test_a_bound_prints_as_a_bound_and_a_missing_speed_as_a_dash():
    """The row's cells: a value at 3 significant figures, a bound as "> 6", no user speed as "-"."""
    from stability.advise.measures import measure_chairs
    from stability.report.decision import _user_cell

    m = measure_chairs([preset("ej-premier")], speeds=(0.5, 0.75, 1.0), cross_slope_deg=2.0,
                       nonlinear=lambda chairs: [(None, None, "found")] * len(chairs), reaction_time=TAU)[0]
    assert _user_cell(m) == f"{rule_speed(preset('ej-premier'), TAU)[0]:.3g}"
    assert _user_cell(m.__class__(**{**m.__dict__, "human_speed_m_s": 6.0, "human_side": ">"})) == "> 6"
    assert _user_cell(m.__class__(**{**m.__dict__, "human_speed_m_s": None})) == "-"


def test_the_recommended_cell_says_better_or_worse():
    """As on every row of the table: the change's direction on the user's speed, a relative tolerance of 1e-3 (the
    table's); a bound ranks as a value beyond every found speed, and two like bounds get no word."""
    from stability.advise.measures import measure_chairs
    from stability.report.decision import user_row

    m = measure_chairs([preset("ej-premier")], speeds=(0.5, 0.75, 1.0), cross_slope_deg=2.0,
                       nonlinear=lambda chairs: [(None, None, "found")] * len(chairs), reaction_time=TAU)[0]

    def at(u, side="="):
        return m.__class__(**{**m.__dict__, "human_speed_m_s": u, "human_side": side})

    assert user_row(0.3, [at(1.794), at(1.689)], True) == ["speed a user 0.3 s late holds (m/s, divergence rule)",
                                                           "1.79", "1.69 (worse)"]
    assert user_row(0.3, [at(1.0), at(1.2)], True)[2] == "1.2 (better)"
    assert user_row(0.3, [at(1.0), at(1.0005)], True)[2] == "1"                 # within the table's tolerance
    assert user_row(0.3, [at(1.0), at(6.0, ">")], True)[2] == "> 6 (better)"    # a bound ranks as a value
    assert user_row(0.3, [at(6.0, ">"), at(1.0)], True)[2] == "1 (worse)"
    assert user_row(0.3, [at(1.0), at(0.1, "<")], True)[2] == "< 0.1 (worse)"
    assert user_row(0.3, [at(6.0, ">"), at(6.0, ">")], True)[2] == "> 6"         # two like bounds: not separable
    assert user_row(0.3, [at(1.0), at(1.2)], False)[2] == "1.2"                 # the reference column: none


@pytest.mark.slow
def test_the_reference_chair_column_has_the_users_speed_too():
    """Another chair's quick report (the revised design, whose own user speed is below the intended 1 m/s for this
    user, so the advisor recommends no change) has the reference chair's column, its user speed measured the
    same way."""
    d = compute_brief(preset("revised"), driver=Driver(0.52), progress=False)
    header, rows = decision_rows(d)
    assert header == ["measure (range)", "this chair", "ej-premier"]
    assert rows[-1] == ["speed a user 0.52 s late holds (m/s, divergence rule)",
                        f"{rule_speed(preset('revised'), 0.52)[0]:.3g}",
                        f"{rule_speed(preset('ej-premier'), 0.52)[0]:.3g}"]
    assert rule_speed(preset("revised"), 0.52)[0] < 1.0 and not d.advice.recommendations[0].candidate.changes


@pytest.mark.parametrize("args, message", [
    (["--intended-speed", "1.5", "--quick"], "--intended-speed needs --reaction-time (or a chair file with a [user]"),
    (["--intended-speed", "9", "--reaction-time", "0.5"], "--intended-speed 9"),
    (["--clinician", "--reaction-time", "0.5", "--intended-speed", "1"], "--clinician has no decision"),
])
def test_intended_speed_is_refused_in_one_line_where_it_cannot_apply(tmp_path, capsys, args, message):
    """``--intended-speed`` as ``python -m stability.advise`` takes it: needs a driver, within its range; the
    clinician sheet has no decision to weigh it. One line, exit 2, nothing written."""
    from stability.report.command import main

    out = tmp_path / "r.pdf"
    assert main([*args, "-o", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err and not out.exists()


@pytest.mark.slow
def test_the_intended_speed_reaches_the_decision():
    """A user 0.3 s late who wants 1.75 m/s: the chair as it is holds (divergence rule 1.79 m/s), the axle move the
    report recommends without a user would not (1.69 m/s), so the recommended chair must keep lambda(1.75) tau <= 1
    (on the eigenvalues)."""
    ej = preset("ej-premier")
    d = compute_brief(ej, driver=Driver(0.3), intended_speed=1.75, progress=False)
    assert d.advice.intended_speed_m_s == 1.75
    rec = d.advice.recommendations[0].candidate
    chosen = apply(ej, [f for ch in rec.changes for f in ch.fields])
    # margins: the chosen chair's rule speed is 1.797 m/s, the axle move's 1.689 m/s, against 1.75 m/s: both far
    # beyond the rule's bisection tolerance (SPEED_TOL_M_S, 1e-3 m/s)
    assert _rate(chosen, 1.75) * 0.3 <= 1.0
    assert _rate(ej.replace(s1=0.245, s2=ej.s1 + ej.s2 - 0.245), 1.75) * 0.3 > 1.0
