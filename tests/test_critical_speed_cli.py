"""`python -m stability.critical_speed`: output structure, options and bad input."""

import json
import subprocess
import sys

import pytest

from stability import chair as chair_mod
from stability import critical_speed, linear


def run(capsys, *argv):
    try:
        code = critical_speed.main(list(argv))
    except SystemExit as exc:  # argparse errors
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def test_json_structure_and_values(capsys):
    code, out, err = run(capsys, "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["chair"] == "ej-premier" and d["model"] == "exact"
    assert set(d["static_load_N"]) == {"main", "caster"}
    assert set(d["cornering_stiffness_N_per_deg"]) == {"main", "caster"}
    assert set(d["zero_width"]) >= {"understeer_coefficient_rad", "critical_speed_m_s"}
    assert "critical_speed_m_s" in d["locked_casters"]
    fc = d["free_casters"]
    assert set(fc) >= {"critical_speed_m_s", "stable_at_all_speeds", "unstable_at_all_speeds", "divergence"}
    assert fc["unstable_at_all_speeds"] is True and fc["stable_at_all_speeds"] is False
    assert fc["critical_speed_m_s"] is None
    row = fc["divergence"][0]
    assert set(row) == {"speed_m_s", "rate_1_s", "time_to_double_s"}
    # numbers trace to the analysis functions
    c = chair_mod.preset("ej-premier")
    assert d["zero_width"]["critical_speed_m_s"] == pytest.approx(linear.zero_width(c).critical_speed, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    rate = linear.divergence(c, [row["speed_m_s"]])[0].rate
    assert row["rate_1_s"] == pytest.approx(rate, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert row["time_to_double_s"] == pytest.approx(0.6931471805599453 / rate, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_options(capsys):
    code, out, _ = run(capsys, "--chair", "ej-premier-front-caster", "--model", "thesis",
                       "--speeds", "0.5:1.5:0.5", "--max-speed", "10", "--json")
    d = json.loads(out)
    assert code == 0 and d["model"] == "thesis" and d["free_casters"]["stable_at_all_speeds"] is True
    assert [r["speed_m_s"] for r in d["free_casters"]["divergence"]] == [0.5, 1.0, 1.5]
    assert all(r["time_to_double_s"] is None for r in d["free_casters"]["divergence"])
    code, out, _ = run(capsys, "--set", "trail=0.05", "--set", "main_tire=AG")
    assert code == 0 and "Critical speeds" in out and "AG" in out


def test_toml_chair(tmp_path, capsys):
    path = tmp_path / "c.toml"
    chair_mod.save(chair_mod.preset("revised"), path)
    code, out, _ = run(capsys, "--chair", str(path), "--json")
    assert code == 0 and json.loads(out)["chair"] == "revised"


@pytest.mark.parametrize("argv,fragment", [
    (["--chair", "nope"], "unknown chair"),
    (["--set", "wheel=3"], "unknown chair parameter"),
    (["--set", "trail=abc"], "needs a number"),
    (["--set", "m=-5"], "m=-5.0"),
    (["--speeds", "1:0:0.1"], "--speeds"),
    (["--model", "bicycle"], "invalid choice"),
    (["--max-speed", "-3"], "--max-speed"),
])
def test_bad_input_one_line_exit_2(capsys, argv, fragment):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert fragment in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_module_entry_point_runs():
    res = subprocess.run([sys.executable, "-m", "stability.critical_speed", "--chair", "nope"],
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 2 and "Traceback" not in res.stderr
    res = subprocess.run([sys.executable, "-m", "stability.critical_speed"], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0 and "unstable" in res.stdout


def test_omitted_effects_reported_with_the_simulator_linearisation(capsys):
    """A chair with rolling resistance: the linear model leaves it out, and the CLI says so
    with the simulator's own linearisation at each table speed."""
    from stability.study.validation import linearisation_check

    code, out, err = run(capsys, "--set", "caster_rolling_scale=1", "--speeds", "0.5,1", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["omitted_effects"] == ["rolling resistance"]
    rows = d["simulator_linearisation"]
    assert [r["speed_m_s"] for r in rows] == [0.5, 1.0]
    c = chair_mod.preset("ej-premier").replace(caster_rolling_scale=1.0)
    assert rows[0]["rate_simulator_1_s"] == pytest.approx(linearisation_check(c, 0.5).eigenvalue_simulator.real, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert rows[0]["rate_linear_1_s"] == pytest.approx(d["free_casters"]["divergence"][0]["rate_1_s"], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    code, out, err = run(capsys, "--set", "caster_rolling_scale=1", "--speeds", "0.5,1")
    assert "leaves out rolling resistance" in out and "simulator" in out
    code, out, err = run(capsys, "--json")
    d = json.loads(out)
    assert d["omitted_effects"] == [] and d["simulator_linearisation"] == []
