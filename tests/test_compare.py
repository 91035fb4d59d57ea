"""Tests of stability.compare: wiring against stability.linear, closed forms, invariants, the command line."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
from numerics import growth_rate_tolerance

from stability import chair
from stability.compare import compare, format_comparison, single_effects
from stability.compare.__main__ import main
from stability.linear import analyse, divergence, state_matrices, zero_width
from stability.settings.reference import REFERENCE_SPEED

SPEEDS = (0.25, 0.75, 1.5, 3.0)


@pytest.fixture(scope="module")
def premier_revised():
    return compare([chair.preset("ej-premier"), chair.preset("revised")], speeds=SPEEDS)


def _diffs(c):
    return {(d.key, d.chair): d for d in c.differences}


def test_chair_against_itself_has_no_difference():
    a = chair.preset("ej-premier")
    c = compare([a, a], speeds=SPEEDS)
    assert len(set(c.labels)) == 2
    for d in c.differences:
        assert d.more_stable == "equal", d
        assert d.absolute in (0.0, None)  # None only for a critical speed that exists for neither
    assert c.effects[0].effects == ()
    assert c.effects[0].total_growth_rate == 0.0


def test_numbers_equal_stability_linear(premier_revised):
    c = premier_revised
    for i, ch in enumerate(c.chairs):
        rates = [r.rate for r in divergence(ch, SPEEDS)]
        got = [c.quantity(f"growth_rate_1_s@{s:g}").values[i] for s in SPEEDS]
        # growth rates from two eigenvalue computations of the same matrices; error model: n eps ||A|| kappa
        # (tests/numerics.py)
        tol = [growth_rate_tolerance(A) for A in state_matrices(ch, SPEEDS)]
        assert np.all(np.abs(np.asarray(got) - rates) <= tol), (got, rates, tol)
        locked = [x.speed for x in analyse(ch, speeds=SPEEDS).locked_crossings if x.direction == "destabilising"]
        # error model: bisection bracket: the batch search stops at 1e-6 m/s, Brent at 1e-10 (observed 4.0e-8)
        assert c.quantity("locked_critical_speed_m_s").values[i] == pytest.approx(locked[0], abs=2e-6)
        z = zero_width(ch)
        assert c.quantity("understeer_coefficient_rad").values[i] == z.understeer_coefficient
        assert c.quantity("zero_width_critical_speed_m_s").values[i] == z.critical_speed


def test_locked_critical_speed_matches_eq_5_15_by_hand(premier_revised):
    # Independent route: for a left-right symmetric chair the full-width locked-caster model
    # reduces to the bicycle model, whose critical speed is sqrt(-g s / k_us) (eqs 5-13..5-16).
    for i, ch in enumerate(premier_revised.chairs):
        s = ch.s1 + ch.s2 + ch.trail
        w_main = ch.m * ch.g * (ch.s2 + ch.trail) / (2 * s)     # one main wheel, N
        w_cast = ch.m * ch.g * ch.s1 / (2 * s)                 # one caster, N
        c_main = ch.main_tire_model().cornering_stiffness_per_rad(w_main)
        c_cast = ch.caster_tire_model().cornering_stiffness_per_rad(w_cast)
        k_us = w_main / c_main - w_cast / c_cast                # main axle is the front axle (rear casters)
        assert k_us < 0
        expected = math.sqrt(-ch.g * s / k_us)
        # error model: bisection bracket: the batch search stops at 1e-6 m/s; the reduction to eq 5-15 is exact
        # (observed 4.0e-8 m/s, 2.9e-9 relative)
        assert premier_revised.quantity("locked_critical_speed_m_s").values[i] == pytest.approx(expected, abs=2e-6)


def test_verdict_premier_vs_revised(premier_revised):
    d = _diffs(premier_revised)
    crit = d[("locked_critical_speed_m_s", "revised")]
    q = premier_revised.quantity("locked_critical_speed_m_s").values
    assert crit.more_stable == "revised" and crit.absolute == q[1] - q[0]
    assert crit.percent == pytest.approx(100 * (q[1] - q[0]) / q[0], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # the linear free-caster model (no pin friction) ranks the revised design slightly less stable
    g = d[("growth_rate_1_s@0.75", "revised")]
    assert g.absolute > 0 and g.more_stable == "ej-premier"


def test_single_parameter_difference_is_the_whole_effect():
    a = chair.preset("ej-premier")
    b = a.replace(trail=0.06)
    e = single_effects(a, b, "short trail")
    assert [s.field for s in e.effects] == ["trail"]
    assert e.effects[0].growth_rate == e.total_growth_rate
    assert e.effects[0].locked_critical_speed == e.total_locked_critical_speed
    assert e.remainder_growth_rate == 0.0 and e.remainder_locked_critical_speed == 0.0
    # and the total is the difference the comparison reports
    c = compare([a, b], speeds=(REFERENCE_SPEED,))
    assert _diffs(c)[(f"growth_rate_1_s@{REFERENCE_SPEED:g}", c.labels[1])].absolute == e.total_growth_rate


def test_effects_of_revised_sum_with_remainder(premier_revised):
    e = premier_revised.effects[0]
    assert [s.field for s in e.effects] == ["s1", "s2", "trail"]
    total = sum(s.growth_rate for s in e.effects) + e.remainder_growth_rate
    assert total == pytest.approx(e.total_growth_rate, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_mirror_invariant():
    a, b = chair.preset("ej-premier"), chair.preset("revised")
    ab, ba = compare([a, b], speeds=SPEEDS), compare([b, a], speeds=SPEEDS)
    for d1 in ab.differences:
        d2 = _diffs(ba)[(d1.key, "ej-premier")]
        assert d2.absolute == -d1.absolute
        assert d2.more_stable == d1.more_stable


def test_front_caster_stable_and_ranked_more_stable():
    c = compare([chair.preset("ej-premier"), chair.preset("ej-premier-front-caster")])
    front = c.labels[1]
    assert max(c.curves[1]) < 0
    for s in c.speeds:
        assert c.quantity(f"growth_rate_1_s@{s:g}").values[1] < 0
        assert _diffs(c)[(f"growth_rate_1_s@{s:g}", front)].more_stable == front
    assert c.quantity("locked_critical_speed_m_s").values[1] == math.inf
    assert _diffs(c)[("locked_critical_speed_m_s", front)].more_stable == front
    assert "none < 30 m/s" in format_comparison(c)


def test_uncertainty_shared_draws_cancel_for_the_same_chair(tmp_path):
    u = tmp_path / "u.toml"
    u.write_text('[i_z]\ndistribution = "normal"\nstd = 0.5\n[s1]\ndistribution = "normal"\nstd = 0.01\n')
    from stability.uncertainty import load_uncertainty

    a = chair.preset("ej-premier")
    unc = load_uncertainty(u)
    shared = compare([a, a], speeds=(REFERENCE_SPEED,), uncertainties=[unc, unc], samples=60)
    d = _diffs(shared)[(f"growth_rate_1_s@{REFERENCE_SPEED:g}", shared.labels[1])]
    assert d.interval == (0.0, 0.0) and d.distinguishable is False
    iv = shared.quantity(f"growth_rate_1_s@{REFERENCE_SPEED:g}").intervals[0]
    assert iv[0] < shared.quantity(f"growth_rate_1_s@{REFERENCE_SPEED:g}").values[0] < iv[1]
    indep = compare([a, a], speeds=(REFERENCE_SPEED,), uncertainties=[unc, unc], samples=60, pairing="independent")
    d = _diffs(indep)[(f"growth_rate_1_s@{REFERENCE_SPEED:g}", indep.labels[1])]
    assert d.interval[0] < 0 < d.interval[1] and d.distinguishable is False


def test_cli_json_keys(capsys, tmp_path):
    out_file = tmp_path / "c.json"
    code = main(["ej-premier", "revised", "--speeds", "0.75", "--json", "--json-file", str(out_file)])
    out, err = capsys.readouterr()
    assert code == 0
    data = json.loads(out)
    assert data == json.loads(out_file.read_text())
    for key in ("stability_version", "model", "options", "chairs", "reference", "measures", "verdicts",
                "single_effects", "uncertainty", "push"):
        assert key in data
    assert [c["label"] for c in data["chairs"]] == ["ej-premier", "revised"]
    assert data["chairs"][1]["parameters"]["s1"] == 0.245
    locked = next(m for m in data["measures"] if m["measure"] == "locked_critical_speed_m_s")
    assert locked["speed_m_s"] is None and locked["chairs"][1]["chair"] == "revised" and locked["chairs"][1]["value"] > 13
    assert {(v["measure"], v["speed_m_s"]) for v in data["verdicts"]} >= {("growth_rate_1_s", 0.75),
                                                                            ("locked_critical_speed_m_s", None)}
    assert [e["field"] for e in data["single_effects"][0]["effects"]] == ["s1", "s2", "trail"]


def test_cli_set_and_pdf(capsys, tmp_path):
    pdf = tmp_path / "c.pdf"
    code = main(["ej-premier", "ej-premier", "--set", "2:trail=0.06", "--speeds", "0.75", "--pdf", str(pdf)])
    out, _ = capsys.readouterr()
    assert code == 0 and pdf.read_bytes()[:4] == b"%PDF"
    assert "trail=0.06" in out.splitlines()[0]  # the modified chair's label says so
    assert "trail                  0.08 -> 0.06" in out


@pytest.mark.parametrize("argv, fragment", [
    (["ej-premier"], "at least two chairs"),
    (["ej-premier", "no-such-chair"], "no-such-chair"),
    (["ej-premier", "revised", "--uncertainty", "-"], "--uncertainty"),
    (["ej-premier", "revised", "--set", "3:trail=0.06"], "--set"),
    (["ej-premier", "revised", "--set", "2:trail=7"], "trail"),
    (["ej-premier", "revised", "--samples", "0"], "--samples"),
    (["ej-premier", "revised", "--speeds", "0:1:0"], "--speeds"),
    (["ej-premier", "revised", "--json-file", "NODIR/x.json"], "--json-file"),
    (["ej-premier", "revised", "-o", "OUT.pdf", "--json-file", "OUT.pdf"], "same file"),
    (["ej-premier", "revised", "--pdf", "OUT.jpg"], "valid: .pdf, .png, .svg"),
])
def test_bad_input_one_line_exit_2(capsys, tmp_path, argv, fragment):
    argv = [a.replace("NODIR", str(tmp_path / "missing")).replace("OUT", str(tmp_path / "out")) for a in argv]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2
    assert err.count("\n") == 1 and err.startswith("error: ") and fragment in err, err
    assert "Traceback" not in err
    assert os.listdir(tmp_path) == []


@pytest.mark.slow
def test_nonlinear_critical_impulse_states_the_push():
    c = compare([chair.preset("ej-premier"), chair.preset("ej-premier-front-caster")], speeds=(REFERENCE_SPEED,),
                nonlinear=True)
    q = c.quantity(f"critical_impulse_Ns@{REFERENCE_SPEED:g}")
    assert 0 < q.values[0] < math.inf          # the rear-caster chair is tipped over by a finite push
    assert q.values[1] == math.inf and "N s" in q.none_means
    assert "101 steps of 1 ms" in c.push       # WCHAIR applies the force while t <= 0.1 s
    assert _diffs(c)[(q.key, c.labels[1])].more_stable == c.labels[1]


def test_no_percentage_of_a_quantity_that_crosses_zero():
    """A stable front-caster chair against an unstable rear-caster one: their growth rates and understeer
    coefficients have opposite signs, so the difference is printed without a percentage (the user-journey review
    found '+283 %' and '-1.03e+03 %'); same-sign quantities keep theirs."""
    cmp = compare([chair.preset("manual-front-caster"), chair.preset("ej-premier")], speeds=[0.75])
    d = _diffs(cmp)
    g = d[("growth_rate_1_s@0.75", "ej-premier")]
    assert g.absolute > 0 and g.percent is None
    k = [v for (key, _), v in d.items() if key == "understeer_coefficient_rad"]
    assert k and all(v.percent is None for v in k)


def test_the_comparison_figure_as_png(tmp_path, capsys):
    """-o FILE.png writes the growth-rate figure (the review: the three-chair figure was PDF-only)."""
    out = tmp_path / "three.png"
    assert main(["manual-front-caster", "ej-premier", "--speeds", "0.75", "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "the growth rates" in capsys.readouterr().err


def test_a_user_adds_the_speed_that_user_holds_on_each_chair():
    """``reaction_time``: one user compared on every chair.  Each chair's value is where its divergence rate (the
    linear model's eigenvalues, computed here directly) reaches 1/tau; the higher speed is the more stable chair for
    this user; a chair stable everywhere checked is a bound (inf), which outranks any found speed."""
    tau = 0.5
    c = compare([chair.preset("ej-premier"), chair.preset("revised"), chair.preset("ej-premier-front-caster")],
                reaction_time=tau)
    q = next(x for x in c.quantities if x.key == "human_limited_speed_m_s")
    assert q.higher_is_more_stable and q.unit == "m/s" and q.intervals == (None, None, None)
    for ch, u in zip(c.chairs[:2], q.values[:2], strict=True):
        rate = lambda v, ch=ch: float(np.max(np.linalg.eigvals(state_matrices(ch, v)[0]).real))   # noqa: E731
        # the rule's bisection ends within its tolerance of the crossing (SPEED_TOL_M_S, below 0.01 m/s)
        assert rate(u - 0.01) * tau < 1 < rate(u + 0.01) * tau
    assert math.isinf(q.values[2])                                 # the front-caster chair: never diverges
    d = {x.chair: x for x in c.differences if x.key == "human_limited_speed_m_s"}
    assert d["revised"].more_stable == "ej-premier"                # 1.04 > 0.98 m/s for this user
    assert d["ej-premier-front-caster"].more_stable == "ej-premier-front-caster"
    text = format_comparison(c)
    assert "speed a user 0.5 s late holds" in text and "held at every speed checked, up to 6 m/s" in text


def test_the_cli_takes_a_user_or_the_first_chair_files(capsys, tmp_path):
    """``--reaction-time`` (in the JSON's options), else the reference chair file's ``[user]``; refused in one line
    for wheel layouts."""
    from stability.chair.io import save
    from stability.schemas import validate

    assert main(["ej-premier", "revised", "--reaction-time", "0.5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    validate("compare", d)
    assert d["options"]["reaction_time_s"] == 0.5
    assert any(m["measure"] == "human_limited_speed_m_s" for m in d["measures"])
    f = tmp_path / "mine.toml"
    save(chair.preset("ej-premier"), f)
    with open(f, "a", encoding="utf-8") as fh:
        fh.write('\n[user]\nreaction_time_s = 0.45\n')
    assert main([str(f), "revised", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["options"]["reaction_time_s"] == 0.45
    assert main(["ej-premier", "revised", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["options"]["reaction_time_s"] is None and all(m["measure"] != "human_limited_speed_m_s"
                                                          for m in d["measures"])
    assert main(["ej-premier", "mid-wheel-drive", "--reaction-time", "0.5"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--reaction-time is not compared across wheel layouts" in err
