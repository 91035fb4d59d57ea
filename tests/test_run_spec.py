"""One run specification (stability.settings.run.RunSpec): the API and the command lines refuse the same values
with the same ranges, by construction; the settings round-trip through JSON; every simulation records them."""

from __future__ import annotations

import contextlib
import io
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stability.chair import preset
from stability.schemas import bad_keys
from stability.settings.bounds import number_text
from stability.settings.run import RUN_SETTINGS, RunSpec, json_key
from stability.simulate import simulate
from stability.simulate.__main__ import RUN_OPTIONS
from stability.simulate.__main__ import main as simulate_main

NUMERIC = [n for n, s in RUN_SETTINGS.items() if s.bound is not None]
CHOICES = [n for n, s in RUN_SETTINGS.items() if s.choices is not None and not set(s.choices) <= {True, False, None}]


def _beyond(name: str) -> float:
    """A value just outside the setting's valid range (above its top, or below its bottom when the top is open)."""
    b = RUN_SETTINGS[name].bound
    assert b is not None
    return b.hi * 2 + 1 if math.isfinite(b.hi) else b.lo - 1


def _cli_error(argv: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        status = simulate_main(argv)
    return status, err.getvalue().strip()


@pytest.mark.parametrize("name", NUMERIC)
def test_the_api_and_the_command_line_refuse_the_same_value_with_the_same_range(name):
    """One limit per setting: both paths state the bound's numbers and unit (issue 32: the API accepted 100 m/s
    where the command line refused 20 m/s)."""
    setting, value = RUN_SETTINGS[name], _beyond(name)
    b = setting.bound
    with pytest.raises(ValueError) as api:
        RunSpec(**{name: value})
    assert str(api.value).startswith(f"{name}=") and "valid range" in str(api.value)
    assert name in RUN_OPTIONS
    status, line = _cli_error([setting.flag or "--" + name.replace("_", "-"), repr(value)])
    assert status == 2 and "\n" not in line and line.startswith("error: --")
    for part in (number_text(b.lo), number_text(b.hi) if math.isfinite(b.hi) else "", b.unit):
        assert part in str(api.value) and part in line, (part, str(api.value), line)


@pytest.mark.parametrize("name", CHOICES)
def test_a_choice_outside_its_values_is_refused_by_both(name):
    with pytest.raises(ValueError, match=f"{name}='bogus' is invalid; valid values"):
        RunSpec(**{name: "bogus"})
    if name in RUN_OPTIONS:
        status, line = _cli_error(["--" + name.replace("_", "-"), "bogus"])
        assert status == 2 and "invalid choice: 'bogus'" in line


@pytest.mark.parametrize("fields, words", [
    (dict(scheme="adaptive", friction_law="kinetic"), "friction_law='kinetic' is invalid for scheme 'adaptive'"),
    (dict(model="thesis", grade_deg=2.0), "model='thesis' is invalid on a slope"),
    (dict(dt=0.01, horizon=0.005), "dt=0.01 is invalid; valid range: dt <= horizon"),
    (dict(sample=0.0015), "a whole multiple of dt"),
    (dict(horizon=3600.0, dt=1e-4), "steps; at most"),
    (dict(horizon=3600.0), "rows"),
])
def test_settings_that_do_not_go_together_are_refused_naming_them(fields, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(".", r"\.")):
        RunSpec(**fields)


def test_the_command_line_names_its_options_in_a_combined_refusal():
    status, line = _cli_error(["--scheme", "adaptive", "--friction-law", "kinetic"])
    assert status == 2 and line.startswith("error: --friction-law 'kinetic' is invalid for scheme 'adaptive'")


def test_wrong_types_and_unknown_fields():
    with pytest.raises(TypeError, match="speed='fast' is invalid; expected a number"):
        RunSpec(speed="fast")
    with pytest.raises(ValueError, match=r"reverse=1 is invalid; valid values: False, True"):
        RunSpec(reverse=1)
    with pytest.raises(ValueError, match=r"unknown run setting\(s\) \['duration'\]"):
        RunSpec().replace(duration=3.0)
    with pytest.raises(TypeError, match="run=.* is invalid; expected a stability.settings.run.RunSpec"):
        simulate(preset("ej-premier"), 0.75, run={"horizon": 1.0})


_values = st.fixed_dictionaries({
    "speed": st.floats(0.01, 20.0), "push_force": st.floats(-1e4, 1e4), "push_duration": st.floats(0.0, 5.0),
    "lateral_velocity": st.floats(-5.0, 5.0), "eta0_deg": st.floats(-180.0, 180.0),
    "horizon": st.floats(0.5, 20.0), "scheme": st.sampled_from(["wchair", "adaptive"]),
    "model": st.sampled_from(["exact", "thesis"]), "casters": st.sampled_from(["free", "locked"]),
    "reverse": st.booleans(), "stop_on_warnings": st.sampled_from([None, True, False])})


@settings(max_examples=200, deadline=None, derandomize=True)
@given(_values)
def test_json_keys_round_trip_and_follow_the_convention(fields):
    spec = RunSpec(**fields)
    data = spec.to_dict()
    assert RunSpec.from_dict(data) == spec
    assert bad_keys(data) == []                           # the JSON convention: snake_case, the unit last
    assert data["speed_m_s"] == spec.speed and data["horizon_s"] == spec.horizon
    assert data["push_force_N"] == spec.push_force


def test_json_keys_carry_the_unit_last():
    assert json_key("speed", "m/s") == "speed_m_s" and json_key("eta0_deg", "deg") == "eta0_deg"
    assert json_key("rtol", "") == "rtol" and json_key("push_duration", "s") == "push_duration_s"


def test_a_run_records_its_settings_and_the_default_law_is_stick_slip():
    """The run's settings are what the spec says (model, scheme, step, friction law), and the default law, the
    one every study and command uses, is the step-converged stick-slip law."""
    r = simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.2))
    assert r.settings["friction_law"] == "stick-slip" and r.settings["model"] == "exact"
    assert r.settings["scheme"] == "wchair" and r.settings["dt"] == 0.001
    k = simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.2, friction_law="kinetic", model="thesis"))
    assert k.settings["friction_law"] == "kinetic" and k.settings["model"] == "thesis"
    assert "kinetic pin friction" in k.summary() and "stick-slip pin friction" in r.summary()


def test_an_infinite_push_duration_is_null_in_json_and_reads_back():
    """JSON has no infinity: the constant force (push_duration inf, the setting's special value) is written as
    null and read back as inf; the simulate command's JSON with it validates against its schema."""
    import json
    import subprocess
    import sys

    from stability import schemas

    run = RunSpec(push_duration=math.inf, horizon=0.5)
    assert run.to_dict()["push_duration_s"] is None and RunSpec.from_dict(run.to_dict()) == run
    with pytest.raises(TypeError, match="horizon=None is invalid"):
        RunSpec.from_dict({"horizon_s": None})          # null is inf only where inf is allowed
    r = subprocess.run([sys.executable, "-m", "stability.simulate", "--push-duration", "inf", "--horizon", "0.5",
                        "--json"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["options"]["push_duration_s"] is None
    schemas.validate("simulate", out)
