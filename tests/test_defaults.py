"""One table of defaults (stability.settings.defaults): every command's parsed defaults and the API's keyword defaults equal it.

The parsers are walked through the command registry (stability.cli.commands.COMMANDS), so a new command is checked
as soon as it is registered; an option with a default that the table does not name fails here with the advice to
add it to stability.settings.defaults.TABLE (or to COMMAND_ONLY below when it is truly the command's own).
"""

from __future__ import annotations

import argparse
import inspect

import numpy as np
import pytest

from stability.cli import commands
from stability.settings import defaults as D
from stability.settings.drive import DRIVE_SETTINGS, drive_flag

#: Required arguments that let a parser produce its defaults.
REQUIRED = {"slope": ["--cross-slope", "2", "--speed", "1"], "measure": ["sheet.toml", "-o", "c.toml"],
            "compare": ["a", "b"], "chair": ["list"]}
SUBCOMMANDS = {"study": ["critical-impulse", "equal-instability"], "chair": ["export", "list"]}

#: Options whose dest differs from the table's name, per command: dest -> table name.
RENAMED = {
    "critical_speed": {"speeds": "summary_speeds", "level": "coverage"},
    "compare": {"speeds": "summary_speeds", "level": "coverage"},
    "study critical-impulse": {"speeds": "study_speeds", "level": "yaw_rate_level"},
    "shimmy": {"speeds": "shimmy_speeds"},
    "advise": {"speeds": "advise_speeds", "cross_slope": "advise_cross_slope_deg"},
    "report": {"speeds": "advise_speeds"},      # --clinician's use speeds: the advisor's
    "slope": {"wheel_radius": "handrim_wheel_radius"},
    "assist": {"chair": "power_chair", "speeds": "assist_speeds", "wheel_radius": "drive_wheel_radius", "sample_rate": "sample_rate_hz"},
}
RENAMED["bench"] = {"chair": "bench_chair", **{drive_flag(n)[2:].replace("-", "_"): n for n in DRIVE_SETTINGS}}
#: Options with a default that belongs to one command alone (no API function shares it).
COMMAND_ONLY = {
    "slope": {"drive"},
    "compare": {"pairing"},
    "assist": {"max_yaw_rate"},
    "app": {"port", "host"},
    "tipping": {"cross_slope", "grade"},
}
#: Defaults that are not values (empty lists, False flags, None) are not compared.
IGNORED_DESTS = {"help", "set", "debug", "quiet", "command", "output_formats"}


def _cases():
    for name in commands.COMMANDS:
        for sub in SUBCOMMANDS.get(name, [None]):
            yield name, sub


def _namespace(name: str, sub: str | None) -> tuple[str, argparse.Namespace, argparse.ArgumentParser]:
    parser = commands.build_parser(name)
    argv = ([sub] if sub else []) + [a for a in REQUIRED.get(name, []) if not (sub and a == sub)]
    if name == "chair" and sub == "export":
        argv = ["export", "ej-premier"]
    key = f"{name} {sub}" if sub else name
    return key, parser.parse_args(argv), parser


@pytest.mark.parametrize("name,sub", list(_cases()), ids=[f"{n}-{s}" if s else n for n, s in _cases()])
def test_parsed_defaults_equal_the_table(name, sub):
    key, ns, parser = _namespace(name, sub)
    parsers = [parser] + [p for a in parser._actions if isinstance(a, argparse._SubParsersAction)
                          for p in a.choices.values()]
    positional = {a.dest for p in parsers for a in p._actions if not a.option_strings or a.required}
    renamed = RENAMED.get(key, {})
    own = COMMAND_ONLY.get(key, set())
    checked = 0
    for dest, value in vars(ns).items():
        if dest in IGNORED_DESTS or dest in positional or value is None or value is False or value == [] or dest in own:
            continue
        table = renamed.get(dest, dest)
        if isinstance(table, tuple):
            assert tuple(value) == tuple(D.TABLE[t].value for t in table), (key, dest)
            checked += 1
            continue
        assert table in D.TABLE, (f"{key}: option {dest!r} (default {value!r}) is not in stability.settings.defaults.TABLE; "
                                  "add it there and take the parser's default from it")
        expected = D.TABLE[table].value
        if table.endswith("speeds") and isinstance(value, str):
            from stability.cli import parse_speeds

            got = parse_speeds(value)
            want = parse_speeds(expected if isinstance(expected, str) else D.speeds_text(expected))
            np.testing.assert_array_equal(got, want)   # both parsed by the same code from the same text
        else:
            assert value == expected, (key, dest, value, expected)
        checked += 1
    # commands without analysis defaults; a sweep spec names its chair and options itself
    assert checked or name in ("chair", "measure", "app", "sweep")


def _api():
    """(function or class, keyword, table name) of the public API functions the commands call."""
    from stability import linear, simulate
    from stability.assist import design, schedule, tracking
    from stability.assist.weights import GyroSensor, Weights
    from stability.chair.power import DriveTrain
    from stability.compare.compute import compare
    from stability.linear.intervals import linear_intervals
    from stability.report.document import build
    from stability.shimmy.chair_modes import chair_shimmy
    from stability.slope.equilibrium import HandRim
    from stability.study.impulse import critical_impulses
    from stability.study.intervals import equal_instability_interval
    from stability.study.uncertain import nonlinear_intervals

    rows = []
    rows += [(simulate.linearise, "model", "model"), (linear.state_space, "model", "model"),
             (linear.state_space, "casters", "casters"), (linear.analyse, "model", "model"),
             (linear.analyse, "speeds", "summary_speeds"), (linear.analyse, "max_speed", "max_speed"),
             (linear.eigenvalues_vs_speed, "model", "model")]
    for f in (linear_intervals, compare):
        rows += [(f, k, t) for k, t in [("model", "model"), ("speeds", "summary_speeds"), ("max_speed", "max_speed"),
                                        ("samples", "samples"), ("seed", "seed"), ("level", "coverage")]]
    rows += [(nonlinear_intervals, k, t) for k, t in [
        ("speed", "speed"), ("samples", "nonlinear_samples"), ("seed", "seed"), ("level", "coverage")]]
    rows += [(critical_impulses, "level", "yaw_rate_level"), (critical_impulses, "max_impulse", "max_impulse"),
             (equal_instability_interval, "reference_speed", "speed"),
             (design, "model", "model"), (design, "kind", "design"), (schedule, "model", "model"),
             (schedule, "kind", "design"), (tracking.closed_loop, "bias_time_constant", "bias_time_constant"),
             (tracking.closed_loop, "command_filter", "command_filter"), (build, "model", "model"),
             (chair_shimmy, "model", "model"),
             (GyroSensor, "sample_rate_hz", "sample_rate_hz"), (GyroSensor, "bias_time_constant_s", "bias_time_constant"),
             (GyroSensor, "noise_density_deg_s", "gyro_noise"), (GyroSensor, "bias_deg_s", "gyro_bias"),
             (Weights, "max_heading_error_deg", "max_heading_error"),
             (DriveTrain, "wheel_radius", "drive_wheel_radius"), (DriveTrain, "torque_limit", "torque_limit"),
             (DriveTrain, "motor_time_constant", "motor_lag"),
             (DriveTrain, "traction_coefficient", "traction_coefficient"),
             (HandRim, "wheel_radius", "handrim_wheel_radius"), (HandRim, "handrim_radius", "handrim_radius")]
    return rows


API = _api()


@pytest.mark.parametrize("func,keyword,table", API, ids=[f"{f.__name__}.{k}" for f, k, _ in API])
def test_api_defaults_equal_the_table(func, keyword, table):
    default = inspect.signature(func).parameters[keyword].default
    assert default is not inspect.Parameter.empty, (func, keyword)
    expected = D.TABLE[table].value
    if isinstance(expected, tuple):
        assert tuple(default) == expected
    else:
        assert default == expected, (func.__name__, keyword, default, expected)


def test_equal_instability_criterion_is_the_tables():
    from stability.study.intervals import equal_instability_interval

    crit = inspect.signature(equal_instability_interval).parameters["criterion"].default
    assert (crit.yaw_rate, crit.duration) == (D.YAW_RATE_LEVEL, D.HORIZON_S)


def _simulating_apis():
    from stability import simulate, study
    from stability.study import runs, summaries, veer

    return [simulate.simulate, simulate.simulate_batch, study.critical_impulse, study.critical_impulses,
            study.critical_impulse_curve, study.critical_impulse_intervals, study.equal_instability_speed,
            study.equal_instability_speeds, study.equal_instability_interval, study.equal_instability_intervals,
            study.reference_time, study.yaw_rate_responses, study.trajectories, study.stability_map,
            study.disturbance_map, study.nonlinear_intervals, study.elasticities, study.steady_turn,
            study.equal_friction_comparison, study.friction_exponent, study.thesis_study, summaries.run_summaries,
            summaries.SummaryRunner, runs.simulate_runs, veer.simulator_path]


#: Keywords the run settings used to travel as (keyword soup): none of them may come back beside ``run``.
_OLD_RUN_KEYWORDS = {"duration", "impulse_force", "impulse_duration", "tire_impulse", "slope", "impulse", "push",
                     "sim_options", "scheme", "model", "dt", "horizon", "friction_law", "casters", "stop_on_warnings",
                     "out_of_range", "sample", "rtol", "atol", "reverse", "eta0_deg", "beta0_deg", "lateral_velocity"}


@pytest.mark.parametrize("func", _simulating_apis(), ids=lambda f: f.__name__)
def test_every_simulating_api_takes_one_run_spec(func):
    """Every function that simulates takes its run settings as one ``run`` (a RunSpec whose defaults are the
    table's), never as loose keywords or ``**sim_options``."""
    params = inspect.signature(func).parameters
    assert "run" in params, func
    loose = sorted(_OLD_RUN_KEYWORDS & set(params))
    assert not loose, (func.__name__, loose)
    assert not any(p.kind is inspect.Parameter.VAR_KEYWORD and p.name in ("sim_options", "options", "kw")
                   and func.__name__ in ("simulate", "simulate_batch") for p in params.values())


def test_the_run_defaults_are_the_tables():
    """The table's run rows are the RunSpec's defaults, and the simulator's reference push is the thesis's."""
    from stability.settings.reference import HORIZON, THESIS_PUSH
    from stability.settings.run import RUN_SETTINGS, RunSpec

    run = RunSpec()
    for name in RUN_SETTINGS:
        assert D.TABLE[name].value == getattr(run, name), name
    assert run.push == THESIS_PUSH and run.horizon == HORIZON and run.friction_law == "stick-slip"


def test_readme_snippet_runs_the_command_lines_model():
    """stability.run_simulation(chair, 0.75) is the same run as python -m stability.simulate --speed 0.75 (the
    README's snippet ran the thesis model while the command ran the exact one: 3.21 s vs 2.92 s to 1 rad/s)."""
    import stability
    from stability.settings.run import RunSpec
    from stability.simulate.__main__ import build_parser

    args = build_parser().parse_args(["--speed", "0.75"])
    run = stability.run_simulation(stability.preset("ej-premier"), 0.75, RunSpec(horizon=0.01))
    assert run.settings["model"] == args.model == "exact"
    assert run.settings["scheme"] == args.scheme and run.settings["dt"] == args.dt
    assert run.settings["friction_law"] == args.friction_law == "stick-slip"


def test_every_table_entry_has_a_unit_and_meaning():
    for name, entry in D.TABLE.items():
        assert name.isidentifier() and entry.doc, name
        assert isinstance(entry.unit, str)
