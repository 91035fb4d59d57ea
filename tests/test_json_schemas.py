"""One JSON convention: every command's JSON has a schema shipped in the package, real outputs validate against it,
and every key follows the convention (snake_case, unit last, no value in a key).  In-process, cheap options."""

from __future__ import annotations

import argparse

import pytest
from json_outputs import CASES, LAYOUT_CASES, SLOW, SLOW_LAYOUT, output

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
    """Each shipped schema declares draft 2020-12 and passes its metaschema: the check ``schemas.validate`` makes once
    per process (its cached validator, shared with the other tests here, which would otherwise check again)."""
    import jsonschema

    for name in schemas.schema_names():
        s = schemas.schema(name)
        assert s["$schema"] == "https://json-schema.org/draft/2020-12/schema", name
        v = schemas._validator(name)          # raises jsonschema.SchemaError on an invalid schema
        assert type(v) is jsonschema.Draft202012Validator and v.schema == s, name


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


ASSIST_OPTIONAL = ("firmware", "faults", "minimum_torque_limits")
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
    """--faults, --export-c and --min-torque together (about 15 s): every optional key present and valid."""
    data = _assist_json(["--speeds", "1,2", "--no-check", "--faults", "--min-torque", "--export-c",
                         str(tmp_path / "fw")])
    assert set(ASSIST_OPTIONAL) <= set(data)
    schemas.validate("assist", data)


# hand-written schemas (issue 34): the unit of every number in words, the settings tables' ranges as bounds
HAND_WRITTEN = ("critical_speed", "simulate", "advise", "tipping", "bench", "study_critical_impulse",
                "study_equal_instability", "measure", "chair_export", "sweep", "compare", "report", "assist",
                "shimmy", "slope", "assist_layout")
#: Key suffix -> the unit a description must name (longest suffix first); written here, not read from the schemas.
SUFFIX_UNITS = [("_N_m_per_deg", "N m/deg"), ("_kg_m", "kg m"), ("_rad_s2", "rad/s^2"), ("_m_s2", "m/s^2"), ("_kg", "kg"), ("_deg_s", "deg/s"), ("_hz", "Hz"),
                ("_N_per_m", "N/m"), ("_N_per_deg", "N/deg"), ("_rad_s", "rad/s"), ("_N_m", "N m"),
                ("_m_s", "m/s"), ("_1_s", "1/s"), ("_rad", "rad"), ("_deg", "deg"), ("_Ns", "N s"), ("_N", "N"),
                ("_m", "m"), ("_s", "s")]


def _resolve(ref, root):
    """The node a ``$ref`` names (``#/$defs/x`` in ``root``, or ``advise.json#/$defs/x`` in another shipped
    schema) and the document it sits in."""
    file, _, pointer = ref.partition("#")
    doc = schemas.schema(file.removesuffix(".json")) if file else root
    node = doc
    for part in pointer.strip("/").split("/"):
        node = node[part] if part else node
    return node, doc


def _numbers(node, path="", root=None):
    """(path, key carrying the unit, schema node) of every number in a schema; items of an array and the
    ``value``/``interval`` of a quantity take their unit from the enclosing key; the forms of a schema with
    ``if``/``then``/``else`` (a chair or a wheel layout) are walked both, and a ``$ref`` (to this schema's
    ``$defs`` or another schema's) is followed."""
    root = node if root is None else root
    if "$ref" in node:
        target, doc = _resolve(node["$ref"], root)
        yield from _numbers(target, path, doc)
    for form in ("then", "else"):
        if form in node:
            yield from _numbers(node[form], path, root)
    for alternative in node.get("anyOf", []):      # an entry of one of several shapes (a slope held or skipped)
        yield from _numbers(alternative, path, root)
    types = node.get("type") if isinstance(node.get("type"), list) else [node.get("type")]
    if ("object" in types or "$ref" in node) and "properties" in node:  # an object, or null, or a $ref extended
        for k, v in node["properties"].items():
            yield from _numbers(v, f"{path}.{k}", root)
    elif "array" in types:
        yield from _numbers(node.get("items", {}), path + "[]", root)
    elif "number" in str(node.get("type")) or "integer" in str(node.get("type")):
        keys = [k.rstrip("[]") for k in path.split(".") if k]
        unit_key = keys[-2] if keys[-1] in ("value", "interval", "main", "caster") and len(keys) > 1 else keys[-1]
        yield path, unit_key, node


def _unit(key):
    return next((u for suffix, u in SUFFIX_UNITS if key.endswith(suffix)), None)


@pytest.mark.parametrize("name", HAND_WRITTEN)
def test_hand_written_schema_states_every_numbers_unit(name):
    leaves = list(_numbers(schemas.schema(name)))
    assert len(leaves) >= (0 if name == "chair_export" else 4)      # chair_export carries no number
    for path, key, node in leaves:
        desc = node.get("description", "")
        assert "; unit: " in desc, (name, path)
        unit = _unit(key)
        if unit is not None:
            assert desc.split("; unit: ")[1].split(";")[0] == unit, (name, path, desc)


def _option_bounds():
    from stability.cli.numbers import OPTION_BOUNDS
    from stability.settings.run import RUN_SETTINGS, RunSpec

    simulate = {f".options.{k}": RUN_SETTINGS[f].bound for k, f in
                zip(RunSpec().to_dict(), RUN_SETTINGS, strict=True) if RUN_SETTINGS[f].bound is not None}
    simulate[".speed_m_s"] = RUN_SETTINGS["speed"].bound
    o = OPTION_BOUNDS
    return {"simulate": simulate,
            "critical_speed": {".options.speeds_m_s[]": o["--speed"], ".options.max_speed_m_s": o["--max-speed"],
                               ".options.samples": o["--samples"], ".options.seed": o["--seed"],
                               ".options.level": o["--level"], ".options.reaction_time_s": o["--reaction-time"],
                               ".options.nonlinear_samples": o["--nonlinear-samples"]},
            "tipping": {".options.cross_slope_deg": o["--cross-slope"], ".options.grade_deg": o["--grade"]},
            "bench": {f".drive.{k}": o[f"bench:--{f}"] for k, f in
                      (("max_speed_m_s", "max-speed"), ("reverse_speed_m_s", "reverse-speed"), ("accel_m_s2", "accel"),
                       ("decel_m_s2", "decel"), ("brake_delay_s", "brake-delay"), ("turn_rate_rad_s", "turn-rate"),
                       ("traction", "traction"), ("max_slope_deg", "max-slope"))},
            "study_critical_impulse": {".options.yaw_rate_level_rad_s": o["study:--level"],
                                       ".options.horizon_s": o["study:--horizon"],
                                       ".options.max_impulse_Ns": o["--max-impulse"],
                                       ".options.speeds_m_s[]": o["study:--speed"]},
            "study_equal_instability": {".options.push_force_N": o["--force"]},
            "sweep": {".spec.speeds_m_s[]": o["slope:--speed"]},
            "compare": {".options.speeds_m_s[]": o["slope:--speed"], ".options.max_speed_m_s": o["--max-speed"],
                        ".options.samples": o["--samples"], ".options.seed": o["--seed"],
                        ".options.level": o["--level"], ".speeds_m_s[]": o["slope:--speed"]},   # signed: reverse      # the same signed range (the spec's check)
            "report": {".options.samples": o["--samples"], ".options.seed": o["--seed"],
                       ".options.reaction_time_s": o["--reaction-time"], ".driver.reaction_time_s": o["--reaction-time"],
                       ".summary.uncertainty.samples": o["--samples"], ".summary.uncertainty.seed": o["--seed"],
                       ".summary.uncertainty.nonlinear.samples": o["--samples"], ".uncertainty.samples": o["--samples"],
                       ".uncertainty.seed": o["--seed"], ".decision.limits.min_tip_deg": o["--min-tip-deg"]},
            "assist": {".options.speeds_m_s[]": o["--speed"], ".options.max_heading_error_deg": o["--max-heading-error"],
                       ".options.max_yaw_rate_deg_s": o["--max-yaw-rate"], ".options.torque_limit_N_m": o["--torque-limit"],
                       ".options.torque_budget_N_m": o["--torque-budget"], ".options.wheel_radius_m": o["--wheel-radius"],
                       ".options.gyro_noise_deg_s_rthz": o["--gyro-noise"], ".options.gyro_bias_deg_s": o["--gyro-bias"],
                       ".options.sample_rate_hz": o["--sample-rate"], ".options.seed": o["--seed"],
                       ".options.motor_lag_s": o["--motor-lag"],
                       ".options.bias_time_constant_s": o["--bias-time-constant"]},
            "assist_layout": {".options.speeds_m_s[]": o["slope:--speed"], ".options.torque_limit_N_m": o["--torque-limit"],
                              ".options.wheel_radius_m": o["--wheel-radius"], ".options.sample_rate_hz": o["--sample-rate"],
                              ".options.seed": o["--seed"], ".options.motor_lag_s": o["--motor-lag"]},
            "shimmy": {".options.speeds_m_s[]": o["--speed"], ".options.relaxation_length_m": o["--relaxation-length"],
                       ".options.lateral_stiffness_N_per_m": o["--lateral-stiffness"],
                       ".options.amplitude_deg": o["--amplitude-deg"]},
            "slope": {".options.cross_slope_deg": o["--cross-slope"], ".options.grade_deg": o["--grade"],
                      ".options.speed_m_s": o["--speed"], ".options.wheel_radius_m": o["--wheel-radius"],
                      ".options.handrim_radius_m": o["--handrim-radius"], ".options.sim_time_s": o["slope:--sim-time"]},
            "advise": {".options.speeds_m_s[]": RUN_SETTINGS["speed"].bound, ".options.cross_slope_deg": o["--cross-slope"],
                       ".limits.min_tip_deg": o["--min-tip-deg"], ".shimmy_hold.amplitude_deg": o["--amplitude-deg"]}}


@pytest.mark.parametrize("name", HAND_WRITTEN)
def test_hand_written_schema_bounds_the_options_by_the_settings_tables(name):
    """Every option echoed in the output carries the range its command line refuses outside of (the settings
    tables stability.settings.run.RunSpec and stability.cli.numbers.OPTION_BOUNDS), stated in words too."""
    leaves = {path: node for path, _, node in _numbers(schemas.schema(name))}
    bounds = _option_bounds().get(name, {})
    assert len(bounds) >= {"measure": 0, "chair_export": 0, "study_equal_instability": 1, "tipping": 2,
                           "sweep": 1}.get(name, 4)
    for path, b in bounds.items():
        node = leaves[path]
        if getattr(b, "signed", False):             # lo <= |value| <= hi: either sign, not near zero
            assert (node["minimum"], node["maximum"]) == (-b.hi, b.hi), (name, path)
            assert node["not"] == {"exclusiveMinimum": -b.lo, "exclusiveMaximum": b.lo}, (name, path)
        else:
            assert node["exclusiveMinimum" if b.open_lo else "minimum"] == b.lo, (name, path)
            assert node["exclusiveMaximum" if b.open_hi else "maximum"] == b.hi, (name, path)
        assert b.text() in node["description"], (name, path)


def _refused(name, data, message):
    with pytest.raises(ValueError, match=message):
        schemas.validate(name, data)


def test_hand_written_schemas_refuse_a_value_outside_its_range(tmp_path):
    """Real outputs pass; the same outputs with one number moved beyond the settings table's range fail."""
    import copy

    from stability.cli.numbers import OPTION_BOUNDS
    from stability.settings.run import RUN_SETTINGS

    cs = output("critical_speed", str(tmp_path))
    schemas.validate("critical_speed", cs)
    bad = copy.deepcopy(cs)
    bad["options"]["speeds_m_s"][0] = OPTION_BOUNDS["--speed"].hi * 1.5
    _refused("critical_speed", bad, "options/speeds_m_s/0.*maximum")
    bad = copy.deepcopy(cs)
    bad["search_range_m_s"][0] = -1.0
    _refused("critical_speed", bad, "search_range_m_s/0.*minimum")

    sim = output("simulate", str(tmp_path))
    schemas.validate("simulate", sim)
    for key, value in (("dt_s", RUN_SETTINGS["dt"].bound.hi * 2), ("speed_m_s", 0.0),
                       ("cross_slope_deg", RUN_SETTINGS["cross_slope_deg"].bound.lo - 1)):
        bad = copy.deepcopy(sim)
        bad["options"][key] = value
        _refused("simulate", bad, f"options/{key}")
    bad = copy.deepcopy(sim)
    bad["t_s"][0] = -0.001
    _refused("simulate", bad, "t_s/0.*minimum")


def test_write_schemas_keeps_the_hand_written_ones():
    from json_outputs import HAND_WRITTEN as KEPT

    assert set(HAND_WRITTEN) <= set(KEPT)


@pytest.mark.parametrize("name", sorted(LAYOUT_CASES))
def test_the_layout_form_states_every_numbers_unit(name):
    """The wheel-layout forms are hand-written: each number's unit in its description (by the key's suffix)."""
    s = schemas.schema(name)
    leaves = list(_numbers(s.get("then", s)))
    assert len(leaves) >= 4
    for path, key, node in leaves:
        desc = node.get("description", "")
        assert "; unit: " in desc, (name, path)
        unit = _unit(key)
        if unit is not None:
            assert desc.split("; unit: ")[1].split(";")[0] == unit, (name, path, desc)


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW_LAYOUT else n
                                  for n in sorted(LAYOUT_CASES)])
def test_the_layout_form_of_a_command_matches_its_schema(name, tmp_path):
    """The wheel-layout form of a command (``--chair mid-wheel-drive`` etc.) validates against the command's schema."""
    schemas.validate(name, output(name, str(tmp_path), layout=True))


#: (schema, form, path to a number, a value outside its range, the message's pattern): one per hand-written schema
#: with numbers, each beyond the range its description states (an option's table range or a physical range).
OUT_OF_RANGE = [
    ("compare", "chair", ("options", "level"), 1.0, "options/level.*maximum"),
    ("compare", "chair", ("speeds_m_s", 0), 25.0, "speeds_m_s/0.*maximum"),
    ("compare", "layout", ("measures", 0, "chairs", 0, "time_to_double_s"), 0.0, "time_to_double_s.*minimum"),
    ("sweep", "chair", ("level",), 1.0, "level.*maximum"),
    ("sweep", "chair", ("measures", "growth_rate_1_s", "best", 0, 0, "missing"), -1, "missing.*minimum"),
    ("sweep", "chair", ("spec", "draws"), 0, "draws.*minimum"),
    ("shimmy", "layout", ("casters", 0, "critical_trail_m", 0), 0.25, "critical_trail_m/0.*maximum"),
    ("shimmy", "layout", ("options", "amplitude_deg"), 45.0, "amplitude_deg.*maximum"),
    ("slope", "layout", ("loads_N", 0), -1.0, "loads_N/0.*minimum"),
    ("slope", "chair", ("normal_loads_N", "main_left"), -1.0, "normal_loads_N/main_left.*minimum"),
    ("slope", "chair", ("options", "handrim_radius_m"), 1.5, "options/handrim_radius_m.*maximum"),
    ("slope", "chair", ("drive_forces", "harder_side"), "left", "harder_side.*is not one of"),
    ("shimmy", "chair", ("critical_trail_m", 0), 0.25, "critical_trail_m/0.*maximum"),
    ("shimmy", "chair", ("chair_model", "rigid_pin", "shimmy_frequency_hz", 0), -1.0, "shimmy_frequency_hz/0.*minimum"),
    ("slope", "layout", ("options", "sim_time_s"), 11.0, "sim_time_s.*maximum"),
    ("critical_speed", "layout", ("speeds_m_s", 0), 0.005, "speeds_m_s/0.*should not be valid"),
    ("critical_speed", "layout", ("forward_critical", "speed_m_s"), 25.0, "forward_critical/speed_m_s.*maximum"),
    ("tipping", "chair", ("static_stability_deg",), 91.0, "static_stability_deg.*maximum"),
    ("tipping", "chair", ("options", "grade_deg"), -46.0, "options/grade_deg.*minimum"),
    ("tipping", "chair", ("tipping_lines", "lateral_left", "normal", 0), 1.5, "normal/0.*maximum"),
    ("tipping", "layout", ("smallest_deg",), -1.0, "smallest_deg.*minimum"),
    ("tipping", "layout", ("slope", "margin_deg"), 95.0, "margin_deg.*maximum"),
    ("bench", "chair", ("drive", "traction"), 3.0, "drive/traction.*maximum"),
    ("bench", "chair", ("worst_score",), 4, "worst_score.*maximum"),
    ("bench", "chair", ("cases", 0, "loads_N", 0), -1.0, "loads_N/0.*minimum"),
    ("study_critical_impulse", "chair", ("options", "max_impulse_Ns"), 0.0, "max_impulse_Ns.*minimum"),
    ("study_critical_impulse", "chair", ("points", 0, "impulse_Ns"), 1001.0, "impulse_Ns.*maximum"),
    ("study_critical_impulse", "layout", ("points", 0, "runs"), 1.5, "runs.*integer"),
    ("measure", "chair", ("fields", 0, "std"), -0.1, "std.*minimum"),
    ("measure", "chair", ("uncertain_parameters",), -1, "uncertain_parameters.*minimum"),
    ("assist", "chair", ("options", "sample_rate_hz"), 5.0, "options/sample_rate_hz.*minimum"),
    ("assist", "chair", ("options", "torque_budget_N_m"), 2000.0, "options/torque_budget_N_m.*maximum"),
    ("assist", "chair", ("rows", 0, "speed_m_s"), 0.0, "rows/0/speed_m_s.*less than or equal to the minimum"),
    ("assist", "chair", ("top_speed_checks", 0, "gain_margin_db", "value"), "infinite", "value.*does not match"),
    ("assist_layout", "layout", ("options", "speeds_m_s", 0), 0.005, "speeds_m_s/0.*should not be valid"),
    ("assist_layout", "layout", ("options", "sample_rate_hz"), 5.0, "options/sample_rate_hz.*minimum"),
    ("assist_layout", "layout", ("reverse", 0, "speed_m_s"), -25.0, "reverse/0/speed_m_s.*minimum"),
    ("assist_layout", "layout", ("forward", 0, "margins", "discrete", "gain_db"), "infinite", "gain_db.*does not match"),
    ("assist_layout", "layout", ("forward", 0, "wheel_torque_gains", "eta"), 1.0, "wheel_torque_gains.*eta"),
    ("assist_layout", "layout", ("reverse_top_speed", "checks", 0, "speed_m_s"), -1.0, "checks/0/speed_m_s.*minimum"),
    ("report", "chair", ("options", "samples"), 0, "options/samples.*minimum"),
    ("report", "chair", ("decision", "verdict", "critical_impulse_Ns", "value"), 1001.0, "critical_impulse_Ns/value.*maximum"),
    ("report", "chair", ("decision", "clinician", "speeds_m_s", 0), 0.0, "clinician/speeds_m_s/0.*minimum"),
    ("report", "chair", ("summary", "shimmy", "critical_trail_m"), -0.01, "critical_trail_m.*minimum"),
    ("report", "layout", ("options", "reaction_time_s"), 2.5, "options/reaction_time_s.*maximum"),
    ("report", "layout", ("clinician", "tip_angles_deg", "left"), 91.0, "tip_angles_deg/left.*maximum"),
    ("report", "layout", ("clinician", "bump", 0, "travel_m"), -1.0, "bump/0/travel_m.*minimum"),
    ("report", "layout", ("clinician", "pin_friction_N_m", 0), -0.1, "pin_friction_N_m/0.*minimum"),
]


@pytest.mark.parametrize("name, form, path, value, message",
                         [pytest.param(*c, marks=pytest.mark.slow) if c[0] in SLOW | SLOW_LAYOUT else c
                          for c in OUT_OF_RANGE],
                         ids=[f"{n}-{f}-{'.'.join(map(str, p))}" for n, f, p, _, _ in OUT_OF_RANGE])
def test_hand_written_schemas_refuse_a_number_outside_its_stated_range(name, form, path, value, message, tmp_path):
    """A real output passes; the same output with one number moved beyond its stated range is refused, naming it."""
    import copy

    data = output(name, str(tmp_path), layout=form == "layout")
    schemas.validate(name, data)
    bad = copy.deepcopy(data)
    node = bad
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    _refused(name, bad, message)


@pytest.mark.slow
def test_every_form_of_the_layout_report_matches_its_schema(tmp_path):
    """The wheel-layout report's JSON in full, with --compare, --uncertainty and a driver (--reaction-time) at once
    (several minutes of CPU), and its two forms kept apart: a quick report's keys in a full one are refused."""
    import contextlib
    import io
    import json

    from json_outputs import ROOT

    from stability.report.command import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["--chair", "mid-wheel-drive", "--compare", "power-fwd-base", "--reaction-time", "0.3",
                     "--uncertainty", str(ROOT / "docs" / "examples" / "mid_wheel_drive.uncertainty.toml"),
                     "--no-progress", "--json", "--quiet"]) == 0
    data = json.loads(buf.getvalue())
    assert {"comparison", "uncertainty", "driver"} <= set(data) and data["driver"]["reaction_time_s"] == 0.3
    schemas.validate("report", data)
    quick = output("report", str(tmp_path), layout=True)
    _refused("report", {**data, "clinician": quick["clinician"]}, "not valid under any")
    _refused("report", {**data, "uncertainty": {**data["uncertainty"], "level": 1.0}}, "uncertainty/level.*maximum")
    _refused("report", {**data, "driver": {**data["driver"], "reaction_time_s": 0.01}},
             "driver/reaction_time_s.*minimum")
