"""Monte Carlo intervals of the nonlinear measures (critical impulse, equal-instability speed), issue 14."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from stability.chair import preset
from stability.linear.intervals import linear_intervals
from stability.settings.reference import LEVEL, REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.study import Criterion, critical_impulse, equal_instability_speed
from stability.study.uncertain import MAX_NONLINEAR_SAMPLES, nonlinear_intervals
from stability.uncertainty import loads_uncertainty

# coarse but honest settings so that the file runs in a few seconds (the level is reached after ~3 s)
HORIZON = 6.0
FAST = dict(run=RunSpec(horizon=HORIZON), rel_tol=0.01, bracket=(0.3, 2.5), tol=0.02, candidates=9)
EJ = preset("ej-premier")


def friction(fraction: float) -> str:
    return (f'[pin_friction]\nfields = ["pin_friction_left", "pin_friction_right"]\ndistribution = "uniform"\n'
            f"low = {-fraction}\nhigh = {fraction}\nrelative = true\n")


def test_zero_spread_gives_exactly_the_nominal_values():
    u = loads_uncertainty('[s1]\ndistribution = "normal"\nstd = 0.0\n')
    iv = nonlinear_intervals(EJ, u, samples=4, seed=1, **FAST)
    ci = critical_impulse(EJ, REFERENCE_SPEED, run=RunSpec(model="exact", horizon=HORIZON), rel_tol=FAST["rel_tol"])
    eq = equal_instability_speed(EJ, run=RunSpec(model="exact"), criterion=Criterion(LEVEL, HORIZON), bracket=FAST["bracket"], tol=FAST["tol"], candidates=FAST["candidates"], progress=False)
    assert ci.status == "found" and eq.status == "found"
    k, e = iv.critical_impulse, iv.equal_instability
    assert e is not None
    assert (k.nominal, k.low, k.median, k.high) == (ci.impulse_Ns,) * 4
    assert (e.nominal, e.low, e.median, e.high) == (eq.speed,) * 4
    assert k.finite_fraction == e.finite_fraction == 1.0
    assert k.dominant is None and e.dominant is None
    # the reference is this chair's own nominal case: equal instability at the reference speed, to the tolerance.
    # error model: bisection bracket: the search's tol (observed 1.3e-4 m/s)
    assert abs(eq.speed - REFERENCE_SPEED) < FAST["tol"]
    assert iv.push == THESIS_PUSH.describe(0.001) and "fixed" in iv.reference


def test_seeded_runs_are_reproducible_and_seeds_differ():
    u = loads_uncertainty(friction(0.3))
    a = nonlinear_intervals(EJ, u, samples=6, seed=5, equal_instability=False, **FAST)
    b = nonlinear_intervals(EJ, u, samples=6, seed=5, equal_instability=False, **FAST)
    c = nonlinear_intervals(EJ, u, samples=6, seed=6, equal_instability=False, **FAST)
    assert a.to_dict() == b.to_dict()
    assert (a.critical_impulse.low, a.critical_impulse.high) != (c.critical_impulse.low, c.critical_impulse.high)


def test_small_spread_lies_between_the_end_chairs_and_widens_with_the_spread():
    # independent check: every draw's pin friction lies in [0.9, 1.1] x nominal, and the critical impulse grows
    # with pin friction, so the Monte Carlo values lie between the two end chairs' impulses computed directly
    tight = dict(FAST, rel_tol=0.002)
    f = EJ.pin_friction_left
    ends = [critical_impulse(EJ.replace(pin_friction_left=x * f, pin_friction_right=x * f), REFERENCE_SPEED, run=RunSpec(horizon=HORIZON), rel_tol=tight["rel_tol"]).impulse_Ns for x in (0.9, 1.1)]
    nominal = critical_impulse(EJ, REFERENCE_SPEED, run=RunSpec(horizon=HORIZON), rel_tol=tight["rel_tol"]).impulse_Ns
    assert ends[0] < nominal < ends[1]
    slack = 2 * tight["rel_tol"] * nominal                        # two bisection brackets
    narrow = nonlinear_intervals(EJ, loads_uncertainty(friction(0.05)), samples=10, equal_instability=False,
                                 **tight).critical_impulse
    wide = nonlinear_intervals(EJ, loads_uncertainty(friction(0.1)), samples=10, equal_instability=False,
                               **tight).critical_impulse
    assert ends[0] - slack <= wide.low < wide.high <= ends[1] + slack
    # error model: first order in the friction: a +-5 % spread spans about half the +-10 % end chairs' range around
    # the nominal chair, plus two bisection brackets (observed 0.090 N s against 0.175 N s allowed)
    assert abs(narrow.median - nominal) <= (ends[1] - ends[0]) / 4 + slack
    w1, w2 = narrow.high - narrow.low, wide.high - wide.low
    assert w1 > 4 * slack                                         # resolved, not bisection noise
    assert 1.5 * w1 < w2 < 2.5 * w1                               # same seed: the draws scale with the spread


def test_pin_friction_drives_the_nonlinear_measures_but_not_the_linear_ones():
    u = loads_uncertainty(friction(0.3) + '[i_z]\ndistribution = "normal"\nstd = 0.3\n')
    nl = nonlinear_intervals(EJ, u, samples=12, **FAST)
    lin = linear_intervals(EJ, u, model="exact", speeds=(REFERENCE_SPEED,), samples=200)
    assert nl.equal_instability is not None
    for m in (nl.critical_impulse, nl.equal_instability):
        assert m.dominant is not None and m.dominant[0] == "pin_friction" and m.dominant[1] > 0.8
        assert m.finite_fraction == 1.0
    shares = dict(lin.dominant_parameters)
    assert shares["pin_friction"] < 1e-3 and lin.dominant_parameters[0][0] == "i_z"
    # friction lowers the draws' impulses and speeds on both sides of the nominal chair
    k = nl.critical_impulse
    assert k.low < k.nominal < k.high


def test_bad_arguments_name_the_parameter():
    u = loads_uncertainty(friction(0.3))
    with pytest.raises(ValueError, match="samples=0"):
        nonlinear_intervals(EJ, u, samples=0)
    with pytest.raises(ValueError, match=f"samples={MAX_NONLINEAR_SAMPLES + 1}"):
        nonlinear_intervals(EJ, u, samples=MAX_NONLINEAR_SAMPLES + 1)
    with pytest.raises(ValueError, match="model"):
        nonlinear_intervals(EJ, u, run=RunSpec(model="linear"))


def test_to_dict_is_json_ready():
    import json

    u = loads_uncertainty(friction(0.3))
    iv = nonlinear_intervals(EJ, u, samples=3, equal_instability=False, **FAST)
    d = json.loads(json.dumps(iv.to_dict()))
    assert d["equal_instability_speed_m_s"] is None and d["samples"] == 3
    assert d["critical_impulse_Ns"]["interval"] == [iv.critical_impulse.low, iv.critical_impulse.high]
    assert np.isnan(iv.reference_time)
    assert dataclasses.replace(iv, samples=3) == iv


def test_critical_speed_command_prints_the_nonlinear_intervals(tmp_path, capsys):
    import json

    from stability.critical_speed.command import main

    unc = tmp_path / "unc.toml"
    unc.write_text(friction(0.3))
    out = tmp_path / "out.json"
    args = ["--chair", "ej-premier", "--uncertainty", str(unc), "--samples", "20", "--seed", "3"]
    assert main(args + ["--nonlinear", "--nonlinear-samples", "4", "--json-file", str(out)]) == 0
    u = json.loads(out.read_text())["uncertainty"]
    nl = nonlinear_intervals(EJ, loads_uncertainty(friction(0.3)), samples=4, seed=3)   # the command's defaults
    assert u["critical_impulse_Ns_interval"] == [nl.critical_impulse.low, nl.critical_impulse.high]
    assert nl.equal_instability is not None
    assert u["equal_instability_speed_m_s_interval"] == [nl.equal_instability.low, nl.equal_instability.high]
    assert u["nonlinear"]["critical_impulse_Ns"]["shares"]["pin_friction"] == pytest.approx(1.0, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    text = capsys.readouterr().out
    assert f"{nl.critical_impulse.low:.4g} to {nl.critical_impulse.high:.4g} N s" in text
    assert main(["--nonlinear"]) == 2
    assert "--nonlinear needs --uncertainty FILE" in capsys.readouterr().err
