"""One JSON convention: every command's JSON has a schema shipped in the package, real outputs validate against it,
and every key follows the convention (snake_case, unit last, no value in a key).  In-process, cheap options."""

from __future__ import annotations

import argparse

import pytest
from json_outputs import CASES, SLOW, output

from stability import schemas
from stability.cli import commands
from stability.cli.options import schema_name

pytest.importorskip("jsonschema")


def _json_parsers():
    for name in commands.COMMANDS:
        parser = commands.build_parser(name)
        subs = [p for a in parser._actions if isinstance(a, argparse._SubParsersAction) for p in a.choices.values()]
        for p in [parser, *subs]:
            if any("--json" in a.option_strings for a in p._actions):
                yield p


def test_every_parser_with_json_has_a_schema_named_in_its_help():
    names = []
    for p in _json_parsers():
        name = schema_name(p.prog)
        names.append(name)
        assert name in schemas.schema_names(), p.prog
        assert f"stability/schemas/{name}.json" in " ".join(p.format_help().split()), p.prog
        assert name in CASES, f"{p.prog}: add a cheap case to tests/json_outputs.py"
    assert len(names) >= 9


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in CASES])
def test_real_output_matches_its_schema_and_the_key_convention(name, tmp_path):
    schemas.validate(name, output(name, str(tmp_path)))


def test_every_schema_is_a_valid_draft_2020_12_schema():
    import jsonschema

    for name in schemas.schema_names():
        jsonschema.Draft202012Validator.check_schema(schemas.schema(name))


def test_key_checker_refuses_values_in_keys_and_raw_units():
    bad = {"growth_rate_1_s@0.25": 1, "peak_torque_Nm": 1, "speeds_m_per_s": [], "lateral_stiffness_n_per_m": 1,
           "first_time": {"0.5": 1.0}, "Heading": 0, "friction_needed_n_m": 1, "rate_per_s": 1}
    assert sorted(schemas.bad_keys(bad)) == sorted(["growth_rate_1_s@0.25", "peak_torque_Nm", "speeds_m_per_s",
                                                    "lateral_stiffness_n_per_m", "first_time.0.5", "Heading",
                                                    "friction_needed_n_m", "rate_per_s"])
    good = {"growth_rate_1_s": 1, "peak_torque_N_m": 1, "speeds_m_s": [], "lateral_stiffness_N_per_m": 1,
            "critical_impulse_Ns": 1, "gain_db": 1, "sample_rate_hz": 1, "fy_caster_left_N": [], "t_s": []}
    assert schemas.bad_keys(good) == []


def test_schema_refuses_a_renamed_key(tmp_path):
    data = output("slope", str(tmp_path))
    data["holding_moment"] = data.pop("holding_yaw_moment_N_m")
    with pytest.raises(ValueError, match="holding_yaw_moment_N_m"):
        schemas.validate("slope", data)


ASSIST_OPTIONAL = ("firmware", "faults")
#: The safe top speed is in every assist output (issue 33), not only with --faults.
ASSIST_TOP_SPEED = ("safe_top_speed_m_s", "limited_by", "top_speed_constraints", "top_speed_limits", "top_speed_checks")


def _assist_json(argv):
    import contextlib
    import io
    import json

    from stability.assist.__main__ import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(argv + ["--json", "--quiet"]) == 0
    return json.loads(buf.getvalue())


def test_assist_schema_declares_every_optional_key_and_refuses_others():
    s = schemas.schema("assist")
    assert set(ASSIST_OPTIONAL) <= set(s["properties"]) and not set(ASSIST_OPTIONAL) & set(s["required"])
    assert set(ASSIST_TOP_SPEED) <= set(s["required"])
    assert s["additionalProperties"] is False


def test_assist_firmware_output_matches_its_schema(tmp_path):
    """--export-c adds ``firmware`` (margins per speed and number format as rows: no format or speed in a key)."""
    data = _assist_json(["--speeds", "1,2", "--no-check", "--export-c", str(tmp_path / "fw")])
    assert "firmware" in data and {t["format"] for t in data["firmware"]["margins"][0]["tables"]} == \
        {"ideal", "float", "Q15", "Q31"}
    schemas.validate("assist", data)
    data["unexpected"] = 1
    with pytest.raises(ValueError, match="unexpected"):
        schemas.validate("assist", data)


@pytest.mark.slow
def test_assist_output_with_every_optional_key_matches_its_schema(tmp_path):
    """--faults and --export-c together (about 10 s): every optional key present and valid."""
    data = _assist_json(["--speeds", "1,2", "--no-check", "--faults", "--export-c", str(tmp_path / "fw")])
    assert set(ASSIST_OPTIONAL) <= set(data)
    schemas.validate("assist", data)
