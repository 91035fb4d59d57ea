
"""Every command line answers bad input the same way (issue 16's error contract).

Each case runs one command in-process in an empty directory and asserts: exit
status 2, exactly one line on stderr that starts with ``error:`` and names the
parameter at fault, no traceback, no file left behind, and an answer within a
time limit.  The chair files and sheets a case needs are written by the test
into a separate directory.
"""

from __future__ import annotations

import importlib
import os
import re
import signal
import time
from pathlib import Path

import pytest

from stability.settings.run import RunSpec

COMMANDS = {
    "critical_speed": "stability.critical_speed.command",
    "simulate": "stability.simulate.__main__",
    "report": "stability.report.command",
    "assist": "stability.assist.__main__",
    "study": "stability.study.__main__",
    "shimmy": "stability.shimmy.__main__",
    "slope": "stability.slope.__main__",
    "measure": "stability.measure.__main__",
    "compare": "stability.compare.__main__",
    "tipping": "stability.tipping.__main__",
    "advise": "stability.advise.__main__",
}

#: A watchdog for a refusal that hangs (SIGALRM after this many seconds): not a measured time.  What "refused
#: before any work" means is asserted from what ran: no function of :data:`WORK_MODULES` was entered.
TIME_LIMIT = 5.0

#: The modules that do the work (the simulator's engines and kernels, the searches, the linear model's matrices,
#: the shimmy band's scans): a refusal enters none of them.  Imported before the refused call, so an import never
#: counts as work.
WORK_MODULES = ("stability.simulate.engine", "stability.simulate.kernel", "stability.simulate.kernel_equations",
                "stability.simulate.adaptive", "stability.simulate.adaptive_kernel", "stability.simulate.layout_kernel",
                "stability.study.search", "stability.study.summaries", "stability.study.runs",
                "stability.linear.model", "stability.shimmy.band", "stability.shimmy.towed_wheel")


def _work_entered(fn):
    """Run ``fn()`` with a profile hook; return (its result or the exception raised, the work modules entered)."""
    import sys

    files = {}
    for name in WORK_MODULES:
        mod = importlib.import_module(name)
        files[os.path.realpath(mod.__file__)] = name
    entered: set[str] = set()
    seen: dict[str, str | None] = {}   # a code object's file name -> its work module (realpath once per file)

    def hook(frame, event, arg):
        if event == "call":
            code = frame.f_code
            filename = code.co_filename
            if filename not in seen:
                seen[filename] = files.get(os.path.realpath(filename))
            name = seen[filename]
            if name is not None and code.co_name != "<module>":
                entered.add(name)

    previous = sys.getprofile()
    sys.setprofile(hook)
    try:
        result = fn()
    except (Exception, SystemExit) as exc:  # noqa: BLE001  (the caller asserts which)
        result = exc
    finally:
        sys.setprofile(previous)
    return result, entered

# (command, argv, fragment the one-line message must contain); {inputs} is the folder of input files.
CASES = [
    # absurd or meaningless chair values: every field names itself, its value and the valid range
    ("critical_speed", ["--set", "m=1e308"], "m=1e+308"),
    ("critical_speed", ["--set", "m=1e-300"], "m=1e-300"),
    ("critical_speed", ["--set", "g=1e-300"], "g=1e-300"),
    ("critical_speed", ["--set", "s1=1e6"], "s1="),
    ("critical_speed", ["--set", "caster_lateral_scale=0"], "caster_lateral_scale=0"),
    ("critical_speed", ["--set", "main_lateral_scale=0"], "main_lateral_scale=0"),
    ("critical_speed", ["--set", "main_tire=linear:0"], "main_tire"),
    ("critical_speed", ["--set", "pin_friction_left=-1"], "pin_friction_left"),
    ("critical_speed", ["--set", "camber_deg=50"], "camber_deg"),
    ("critical_speed", ["--set", "h=nan"], "h="),
    ("critical_speed", ["--set", "i_zp=inf"], "i_zp"),
    ("critical_speed", ["--set", "m=abc"], "m"),
    ("critical_speed", ["--set", "nosuch=1"], "nosuch"),
    ("critical_speed", ["--set", "trail"], "NAME=VALUE"),
    ("critical_speed", ["--chair", "ej-premier-front-caster", "--set", "s2=0.05", "--set", "trail=0.1"],
     "static load"),
    ("critical_speed", ["--set", "caster_tire=PU", "--set", "caster_rolling_scale=1"], "rolling"),
    ("critical_speed", ["--set", "main_tire=linear:30", "--set", "camber_deg=2"], "camber"),
    ("critical_speed", ["--set", "m=200", "--tire-range", "raise"], "fitted range"),
    ("critical_speed", ["--tire-range", "sometimes"], "--tire-range"),
    ("tipping", ["--cross-slope", "50"], "--cross-slope"),
    ("tipping", ["--grade", "nan"], "--grade"),
    ("tipping", ["--set", "anti_tip_reach=-0.1"], "anti_tip_reach"),
    ("advise", ["--speeds", "0:1"], "--speeds"),
    ("advise", ["--min-tip-deg", "nan"], "--min-tip-deg"),
    ("advise", ["--set", "trail=2"], "trail"),
    # chair sources
    ("critical_speed", ["--chair", "nosuch"], "nosuch"),
    ("critical_speed", ["--chair", "missing.toml"], "missing.toml"),
    ("critical_speed", ["--chair", "{inputs}"], "directory"),
    ("critical_speed", ["--chair", "{inputs}/mixed.toml"], "[chair]"),
    ("critical_speed", ["--chair", "{inputs}/broken.toml"], "broken.toml"),
    # options and speeds
    ("critical_speed", ["--model", "approximate"], "--model"),
    ("critical_speed", ["--speeds", "0.1:inf:0.1"], "--speeds"),
    ("critical_speed", ["--speeds", "0.001:10000:0.001"], "at most"),
    ("critical_speed", ["--speeds", "-1:2:1"], "--speeds"),
    ("critical_speed", ["--speeds", "abc"], "--speeds"),
    ("critical_speed", ["--speeds", "1:0.5:0.1"], "--speeds"),
    ("critical_speed", ["--max-speed", "-3"], "--max-speed"),
    ("critical_speed", ["--max-speed", "1e9"], "--max-speed"),
    ("critical_speed", ["--uncertainty", "none.toml"], "none.toml"),
    ("critical_speed", ["--uncertainty", "{inputs}/u.toml", "--samples", "0"], "--samples"),
    ("critical_speed", ["--uncertainty", "{inputs}/u.toml", "--samples", "100000000"], "--samples"),
    ("critical_speed", ["--level", "1.5"], "--level"),
    # outputs: checked before any work
    ("critical_speed", ["--json-file", "/proc/x.json"], "--json-file"),
    ("critical_speed", ["--json-file", "{inputs}"], "directory"),
    ("critical_speed", ["--json-file", "nodir/x.json"], "does not exist"),
    ("critical_speed", ["--chair", "{inputs}/chair.toml", "--json-file", "{inputs}/chair.toml"], "input"),
    # simulate
    ("simulate", ["--speed", "0"], "speed"),
    ("simulate", ["--speed", "1e308"], "speed"),
    ("simulate", ["--speed", "nan"], "speed"),
    ("simulate", ["--dt", "1e-9"], "dt"),
    ("simulate", ["--dt", "0"], "dt"),
    ("simulate", ["--horizon", "1e9", "--no-stop-on-warnings"], "horizon"),
    ("simulate", ["--horizon", "-1"], "horizon"),
    ("simulate", ["--scheme", "adaptive", "--horizon", "1e5"], "horizon"),
    ("simulate", ["--scheme", "euler"], "scheme"),
    ("simulate", ["--push-force", "40", "--push-duration", "-1"], "push-duration"),
    ("simulate", ["--push-force", "1e12", "--push-duration", "0.1"], "push-force"),
    ("simulate", ["--csv", "r.png", "-o", "r.png"], "same file"),
    ("simulate", ["-o", "/proc/r.png"], "-o"),
    ("simulate", ["--csv", "nodir/r.csv"], "does not exist"),
    ("simulate", ["--set", "m_c=0", "--set", "i_zp=0", "--set", "l1=0", "--set", "m=1e-300"], "m=1e-300"),
    ("simulate", ["--model", "approximate"], "--model"),
    # report
    ("report", ["-o", "out.pdf", "--text", "out.pdf"], "same file"),
    ("report", ["-o", "out.pdf", "--text", "nodir/t.txt"], "does not exist"),
    ("report", ["-o", "/proc/out.pdf"], "/proc"),
    ("report", ["-o", "{inputs}"], "directory"),
    ("report", ["-o", "out.pdf", "--model", "approximate"], "--model"),
    ("report", ["-o", "out.pdf", "--set", "m=1e308"], "m=1e+308"),
    # assist
    ("assist", ["--torque-limit", "1e-6"], "torque"),
    ("assist", ["--torque-budget", "1e-6"], "torque"),
    ("assist", ["--speeds", "0:1:0.1", "--speeds", "-1:1:0.5"], "--speeds"),
    ("assist", ["--json-file", "/proc/g.json"], "--json-file"),
    ("assist", ["-o", "{inputs}"], "directory"),
    ("assist", ["--json-file", "g.pdf", "-o", "g.pdf"], "same file"),
    ("assist", ["--sample-rate", "0"], "sample"),
    # study
    ("study", ["critical-impulse", "--speeds", "0"], "--speeds"),
    ("study", ["critical-impulse", "--level", "-1"], "level"),
    ("study", ["nonsense"], "nonsense"),
    ("study", ["critical-impulse", "--json-file", "/proc/x.json"], "--json-file"),
    # shimmy
    ("shimmy", ["--relaxation-length", "-1"], "relaxation"),
    ("shimmy", ["--lateral-stiffness", "0"], "stiffness"),
    ("shimmy", ["--amplitude-deg", "0"], "amplitude"),
    ("shimmy", ["--speeds", "0:1:0.1"], "--speeds"),
    ("shimmy", ["--json-file", "/proc/s.json"], "--json-file"),
    # slope
    ("slope", ["--cross-slope", "15", "--speed", "0.75"], "cross"),
    ("slope", ["--cross-slope", "nan", "--speed", "0.75"], "cross"),
    ("slope", ["--cross-slope", "2", "--speed", "0"], "speed"),
    ("slope", ["--cross-slope", "2", "--speed", "0.75", "--grade", "80"], "grade"),
    ("slope", ["--cross-slope", "2"], "--speed"),
    ("slope", ["--cross-slope", "2", "--speed", "0.75", "--wheel-radius", "0"], "radius"),
    # measure
    ("measure", ["missing_sheet.toml", "-o", "c.toml"], "missing_sheet.toml"),
    ("measure", ["{inputs}/bad_sheet.toml", "-o", "c.toml"], "sheet"),
    ("measure", ["{inputs}/chair.toml", "-o", "{inputs}"], "directory"),
    # compare
    ("compare", ["ej-premier"], "two"),
    ("compare", ["ej-premier", "nosuch"], "nosuch"),
    ("compare", ["ej-premier", "revised", "--uncertainty", "{inputs}/u.toml"], "uncertainty"),
    ("compare", ["ej-premier", "revised", "--set", "3:m=90"], "3"),
    ("compare", ["ej-premier", "revised", "--json-file", "/proc/c.json"], "--json-file"),
    # issue 19: a chair whose casters have no swivel inertia (singular mass matrix) names the parameter
    ("critical_speed", ["--set", "m_c=0", "--set", "i_zp=0"], "i_zp=0"),
    ("simulate", ["--set", "i_zp=1e-300"], "i_zp=1e-300"),
    ("assist", ["--set", "m_c=0", "--set", "l1=0", "--set", "i_zp=0"], "i_zp=0"),
    # issue 19: speeds below 0.01 m/s, where the linear rates are lost in round-off (and a study's step with them)
    ("critical_speed", ["--speeds", "1e-6,1e-5"], "--speeds"),
    ("study", ["critical-impulse", "--speeds", "1e-6"], "--speeds"),
    ("simulate", ["--speed", "1e-6"], "--speed"),
    ("slope", ["--cross-slope", "2", "--speed", "1e-6"], "--speed"),
    # issue 19: work bounded by an estimate of its time (count x cost), naming the option and the largest value
    ("shimmy", ["--speeds", "0.1:50:0.01"], "--speeds"),
    ("study", ["critical-impulse", "--speeds", "0.01", "--horizon", "3600"], "--horizon"),
    ("critical_speed", ["--uncertainty", "{inputs}/u.toml", "--samples", "20000"], "--samples"),
    ("compare", ["ej-premier", "revised", "--uncertainty", "{inputs}/u.toml", "--uncertainty", "{inputs}/u.toml",
                 "--samples", "20000"], "--samples"),
    ("simulate", ["--horizon", "3600"], "--horizon"),
    ("simulate", ["--horizon", "4", "--sample", "1e-5"], "--sample"),
    ("slope", ["--cross-slope", "2", "--speed", "0.75", "--sim-time", "1e9"], "--sim-time"),
    # issue 19: every number is parsed knowing its option (the three named inputs and their class)
    ("assist", ["--seed", "-1"], "--seed"),
    ("critical_speed", ["--uncertainty", "{inputs}/u.toml", "--seed", "-1"], "--seed"),
    ("simulate", ["--tire-push-force", "1e308"], "--tire-push-force"),
    ("simulate", ["--lateral-velocity", "1e308"], "--lateral-velocity"),
    ("simulate", ["--sample", "1e-9"], "--sample"),
    ("simulate", ["--scheme", "adaptive", "--atol", "1e-300"], "--atol"),
    ("simulate", ["--scheme", "adaptive", "--rtol", "1e-300"], "--rtol"),
    ("slope", ["--cross-slope", "2", "--speed", "0.75", "--wheel-radius", "1e308"], "--wheel-radius"),
    ("assist", ["--sample-rate", "1e308"], "--sample-rate"),
    ("assist", ["--sample-rate", "1e9"], "--sample-rate"),
    ("study", ["critical-impulse", "--horizon", "1e9"], "--horizon"),
    ("study", ["critical-impulse", "--max-impulse", "inf"], "--max-impulse"),
    # inputs destroyed: no output is a file the run reads, directly or named by a chair file
    ("critical_speed", ["--chair", "{inputs}/tire_chair.toml", "--json-file", "{inputs}/good.csv"], "input"),
    ("simulate", ["--chair", "{inputs}/tire_chair.toml", "--csv", "{inputs}/good.csv"], "input"),
    ("simulate", ["--chair", "{inputs}/tire_chair.toml", "--json-file", "{inputs}/good.csv"], "input"),
    ("slope", ["--chair", "{inputs}/tire_chair.toml", "--cross-slope", "2", "--speed", "0.75",
               "--json-file", "{inputs}/good.csv"], "input"),
    ("shimmy", ["--chair", "{inputs}/tire_chair.toml", "--json-file", "{inputs}/good.csv"], "input"),
    ("assist", ["--chair", "{inputs}/tire_chair.toml", "--json-file", "{inputs}/good.csv"], "input"),
    ("study", ["critical-impulse", "--chair", "{inputs}/tire_chair.toml", "--json-file", "{inputs}/good.csv"],
     "input"),
    ("compare", ["{inputs}/tire_chair.toml", "revised", "--json-file", "{inputs}/good.csv"], "input"),
    ("critical_speed", ["--set", "caster_tire=file:{inputs}/good.csv", "--json-file", "{inputs}/good.csv"], "input"),
]


def _inputs(folder: Path) -> None:
    folder.mkdir()
    (folder / "chair.toml").write_text('name = "mine"\ntrail = 0.06\n')
    (folder / "mixed.toml").write_text('trail = 0.06\n[chair]\ns1 = 0.3\n')
    (folder / "broken.toml").write_text("trail = = 0.06\n")
    (folder / "u.toml").write_text('[s1]\ndistribution = "normal"\nstd = 0.01\n')
    (folder / "bad_sheet.toml").write_text("this is not a sheet = 1\n")
    _tire_csv(folder / "good.csv")
    (folder / "tire_chair.toml").write_text('name = "mine"\ncaster_tire = "file:good.csv"\n')


INPUT_FILES = ["chair.toml", "mixed.toml", "broken.toml", "u.toml", "bad_sheet.toml", "good.csv", "tire_chair.toml"]


def _tire_csv(path: Path, bom: bool = False) -> None:
    """The thesis's ER caster tire (the preset's) as a user's CSV of measured forces (Appendix B raw data)."""
    import numpy as np

    from stability import tires

    raw = tires.raw_cornering("ER")
    ok = np.isfinite(raw["Fz_N"]) & np.isfinite(raw["Fy_N"])
    rows = [f"{int(s)},{float(z)!r},{float(y)!r}" for s, z, y in zip(raw["slip_deg"][ok], raw["Fz_N"][ok], raw["Fy_N"][ok],
                                                      strict=True)]
    path.write_text(("\ufeff" if bom else "") + "# name = my ER\nslip_deg,Fz_N,Fy_N\n" + "\n".join(rows) + "\n",
                    encoding="utf-8")


@pytest.mark.parametrize("command,argv,fragment", CASES, ids=[f"{c}:{' '.join(a)}" for c, a, _ in CASES])
def test_bad_input_is_refused_in_one_line(command, argv, fragment, tmp_path, monkeypatch, capsys):
    inputs = tmp_path / "inputs"
    _inputs(inputs)
    good = (inputs / "good.csv").read_text(encoding="utf-8")
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    argv = [a.replace("{inputs}", str(inputs)) for a in argv]
    fragment = fragment.replace("{inputs}", str(inputs))
    main = importlib.import_module(COMMANDS[command]).main

    def too_slow(signum, frame):
        raise TimeoutError(f"no answer within {3 * TIME_LIMIT:g} s")

    previous = signal.signal(signal.SIGALRM, too_slow)
    signal.alarm(int(3 * TIME_LIMIT))
    try:
        result, entered = _work_entered(lambda: main(argv))
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    if isinstance(result, SystemExit):  # argparse usage errors
        code = result.code
    elif isinstance(result, BaseException):
        raise result
    else:
        code = result
    out, err = capsys.readouterr()
    lines = [line for line in err.strip().splitlines() if line]
    assert code == 2, f"exit status {code}; stderr: {err!r}"
    assert len(lines) == 1 and lines[0].startswith("error:"), f"not one error line: {err!r}"
    assert "Traceback" not in err
    assert fragment in lines[0], f"{fragment!r} not in {lines[0]!r}"
    assert sorted(os.listdir(work)) == [], "files left behind"
    assert sorted(os.listdir(inputs)) == sorted(INPUT_FILES), "an output was written next to the inputs"
    assert (inputs / "good.csv").read_text(encoding="utf-8") == good, "an input was changed"
    assert not entered, f"refused after work started in {sorted(entered)}"


def test_catalogue_is_large_and_covers_every_command():
    assert len(CASES) >= 60
    assert {c for c, _, _ in CASES} == set(COMMANDS)


@pytest.mark.parametrize("command,argv", [
    ("critical_speed", ["--set", "camber_deg=10"]),       # camber up to 45 deg is a valid chair (issue 16)
    ("critical_speed", ["--speeds", "0.5,1", "--set", "m=120"]),
    ("simulate", ["--horizon", "1", "--speed", "0.5", "--push-force", "-40", "--push-duration", "0.1"]),   # a push to the left
])
def test_valid_unusual_input_is_answered(command, argv, capsys):
    main = importlib.import_module(COMMANDS[command]).main
    assert main(argv) == 0
    assert "error" not in capsys.readouterr().err


# ---------------------------------------------------------------------------------------------------------------
# issue 19: each class of the attack, for every command (not only the example that found it)
# ---------------------------------------------------------------------------------------------------------------
def _parser_of(command: str):
    module = importlib.import_module(COMMANDS[command])
    build = getattr(module, "build_parser", None) or module._parser
    return module.main, build()


def _numeric_options():
    """(command, subcommand prefix, option, nargs) of every option of every parser that takes a number."""
    import argparse

    from stability.cli import OPTION_BOUNDS  # noqa: F401  (the table every number is checked against)

    out = []
    for command in COMMANDS:
        _, parser = _parser_of(command)
        parsers = [([], parser)]
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                parsers += [([name], sub) for name, sub in action.choices.items()]
        for prefix, p in parsers:
            for action in p._actions:
                if action.option_strings and getattr(action.type, "__name__", "") in ("float", "int"):
                    out.append((command, prefix, action.option_strings[-1], action.nargs))
    return out


NUMERIC = _numeric_options()


def test_every_numeric_option_is_parsed_by_name_with_a_plausibility_bound():
    """Every number of every command is parsed by cli.number (knows its option) with a bound from OPTION_BOUNDS."""
    from stability.cli.numbers import bound_for as _bound_for

    assert len(NUMERIC) >= 40
    for command, prefix, option, _ in NUMERIC:
        _, parser = _parser_of(command)
        prog = f"python -m stability.{command}" + (f" {prefix[0]}" if prefix else "")
        assert _bound_for(prog, option) is not None, f"{command} {option}: no plausibility bound"


@pytest.mark.parametrize("value", ["nan", "-1e308", "1e308"])
@pytest.mark.parametrize("command,prefix,option,nargs", NUMERIC,
                         ids=[f"{c}:{' '.join(p)}{o}" for c, p, o, _ in NUMERIC])
def test_every_numeric_option_refuses_extremes_naming_itself(command, prefix, option, nargs, value, capsys):
    main, _ = _parser_of(command)
    argv = [*prefix, option, *([value] * (nargs if isinstance(nargs, int) else 1))]
    try:
        code = main(argv)
    except SystemExit as exc:
        code = exc.code
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1, err
    assert err[0].startswith(f"error: {option} "), err[0]


def _run_body(body, argv=()):
    """cli.run with a trivial parser around ``body`` (the shared error contract, in-process)."""
    from stability.cli import OneLineErrorParser, run

    return run(OneLineErrorParser(prog="python -m stability.test"), list(argv), body)


@pytest.mark.parametrize("signum", ["SIGINT", "SIGTERM", "SIGHUP"])
def test_signals_during_the_work_exit_130_and_leave_no_file(signum, tmp_path, capsys):
    """A signal while an output is being written: one line, status 130, neither the file nor a temporary one."""
    from stability.cli import output_files

    out = tmp_path / "out.json"

    def body(args):
        with output_files({"--json-file": str(out)}) as tmp:
            with open(tmp["--json-file"], "w") as fh:
                fh.write("{partial")
            os.kill(os.getpid(), getattr(signal, signum))
            time.sleep(1.0)                       # the handler raises before this ends ...
            after.append("slept")                 # ... so this line never runs
        return 0

    after: list[str] = []
    assert _run_body(body) == 130
    assert after == []
    assert capsys.readouterr().err.strip().splitlines() == ["error: interrupted"]
    assert os.listdir(tmp_path) == []


def test_a_signal_swallowed_by_a_library_still_interrupts_and_keeps_no_output(tmp_path, capsys):
    from stability.runtime.files import atomic_write_text

    def body(args):
        try:
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(1.0)
        except KeyboardInterrupt:
            pass                                   # e.g. a library that catches it
        atomic_write_text(tmp_path / "out.txt", "finished")
        print("done")
        return 0

    assert _run_body(body) == 130
    out, err = capsys.readouterr()
    assert out == "" and err.strip().splitlines() == ["error: interrupted"]
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("text", ["growth rate nan 1/s", "hand-rim forces left inf N", "margin: -inf deg",
                                  "rate=NaN", "[1.0, inf]"])
def test_a_non_finite_result_is_never_printed(text, capsys):
    def body(args):
        print("a finite line 1.5 s")
        print(text)
        return 0

    assert _run_body(body) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.startswith("error: could not compute") and len(err.strip().splitlines()) == 1, err


@pytest.mark.parametrize("text", ["info: infinite speed range", "nanometre", "/tmp/inf/x.json", "Infeasible"])
def test_words_that_contain_nan_or_inf_are_printed(text, capsys):
    assert _run_body(lambda args: print(text)) == 0
    assert capsys.readouterr().out.strip() == text


def test_non_finite_json_is_could_not_compute(capsys, tmp_path):
    import argparse

    from stability.cli import emit_json

    def body(args):
        emit_json({"rows": [{"growth_rate_1_s": float("nan")}]},
                  argparse.Namespace(json=True, json_file=str(tmp_path / "r.json")))
        return 0

    assert _run_body(body) == 2
    out, err = capsys.readouterr()
    assert out == "" and "could not compute" in err and "growth_rate_1_s" in err
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("exc", ["LinAlgError", "FloatingPointError", "MemoryError"])
def test_a_failed_computation_is_could_not_compute_not_bad_input(exc, capsys):
    import numpy as np

    kinds = {"LinAlgError": np.linalg.LinAlgError, "FloatingPointError": FloatingPointError,
             "MemoryError": MemoryError}

    def body(args):
        raise kinds[exc]("Singular matrix")

    assert _run_body(body) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: could not compute"), err


def test_numpy_floating_point_warnings_are_not_printed(capsys):
    import numpy as np

    def body(args):
        np.log(np.zeros(2))          # divide by zero encountered
        print(float(np.sqrt(4.0)))
        return 0

    assert _run_body(body) == 0
    out, err = capsys.readouterr()
    assert out.strip() == "2.0" and err == ""


@pytest.mark.parametrize("command,argv,option", [
    ("simulate", ["--horizon", "0.5", "--csv", "out.csv"], "out.csv"),
    ("simulate", ["--horizon", "0.5", "-o", "out.pdf"], "out.pdf"),
    ("critical_speed", ["--speeds", "0.5,1", "--json-file", "out.json"], "out.json"),
])
def test_a_full_disk_is_one_line_naming_the_file_and_nothing_is_left(command, argv, option, tmp_path, monkeypatch,
                                                                     capsys):
    """A real write failure: the process may write at most 64 bytes per file (RLIMIT_FSIZE -> EFBIG, as ENOSPC)."""
    resource = pytest.importorskip("resource")
    monkeypatch.chdir(tmp_path)
    main = importlib.import_module(COMMANDS[command]).main
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    previous = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (64, hard))
    try:
        code = main(argv)
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))
        signal.signal(signal.SIGXFSZ, previous)
    err = capsys.readouterr().err.strip().splitlines()
    errors = [line for line in err if line.startswith("error:")]
    assert code == 2 and len(errors) == 1 and "Traceback" not in "\n".join(err), err
    assert repr(option) in errors[0] and "cannot write" in errors[0], errors[0]
    assert os.listdir(tmp_path) == [], "a partial or temporary file was left behind"


def test_utf8_byte_order_mark_is_accepted_in_tire_csv_and_chair_files(tmp_path):
    """What spreadsheet programs write: the same tire and chair as without the mark."""
    from stability import chair as chair_mod
    from stability import tires

    _tire_csv(tmp_path / "plain.csv")
    _tire_csv(tmp_path / "bom.csv", bom=True)
    plain, bom = tires.load_tire_data(tmp_path / "plain.csv"), tires.load_tire_data(tmp_path / "bom.csv")
    assert bom.name == plain.name == "my ER"
    assert (bom.coefficients == plain.coefficients).all()
    (tmp_path / "c.toml").write_text('\ufeffname = "mine"\ntrail = 0.06\ncaster_tire = "file:bom.csv"\n',
                                     encoding="utf-8")
    c = chair_mod.load(tmp_path / "c.toml")
    assert c.trail == 0.06 and c.caster_tire.endswith("bom.csv")


def test_numpy_scalars_are_real_numbers_in_a_chair():
    import numpy as np

    from stability import chair as chair_mod

    ref = chair_mod.preset("ej-premier").replace(m=95.0, trail=0.05, h=1.0)
    c = chair_mod.preset("ej-premier").replace(m=np.float32(95), trail=np.float64(0.05), h=np.int64(1))
    assert (c.m, c.trail, c.h) == (ref.m, ref.trail, ref.h)
    assert all(type(v) is float for v in (c.m, c.trail, c.h))
    with pytest.raises(ValueError, match="parameter m="):
        chair_mod.preset("ej-premier").replace(m=np.bool_(True))


def test_the_smallest_caster_swivel_inertia_answers_the_massless_caster_limit():
    """i_zp -> 0 is a regular limit (the swivel mode runs off to -infinity, the caster trails its contact point):
    the rates are linear in i_zp near 0, so at the bound 1e-6 kg m^2 they equal the limit extrapolated from
    1e-6 and 2e-6 within 1e-4 relative (the O(i_zp) term is 2e-7 of the rate per 1e-6; the eigenvalue's
    rounding, eps ||A|| kappa, about 1e-6 relative at this inertia)."""
    import numpy as np

    import stability
    from stability import chair as chair_mod

    def rates(i_zp):
        c = chair_mod.preset("ej-premier").replace(m_c=0.0, i_zp=i_zp)
        return np.array([d.rate for d in stability.analyse(c).divergence])

    r1, r2 = rates(1e-6), rates(2e-6)
    limit = 2 * r1 - r2                                 # linear extrapolation to i_zp = 0
    # error model: the docstring's: the eigenvalue's rounding, eps ||A|| kappa ~1e-6 relative, x100 (observed 1.3e-7)
    np.testing.assert_allclose(r1, limit, rtol=1e-4)
    assert chair_mod.LIMITS["i_zp"][0] == 1e-6


def test_small_speed_limit_rates_are_proportional_to_speed_and_below_it_refused():
    """At low speed the slow modes' rates are proportional to speed (rate = mu U + O(U^2)): at the bound,
    0.01 m/s, rate/U agrees with 0.02 m/s within 1e-3 (the O(U) term, observed 2e-5); the API refuses below."""
    import numpy as np

    import stability
    from stability import chair as chair_mod
    from stability.runtime.checks import MIN_SPEED

    c = chair_mod.preset("ej-premier")
    r = np.array([d.rate for d in stability.analyse(c, speeds=(MIN_SPEED, 2 * MIN_SPEED)).divergence])
    mu = r / np.array([MIN_SPEED, 2 * MIN_SPEED])
    # error model: rate/U = mu + O(U): first order in U (observed 2e-5 at 0.01-0.02 m/s, x50)
    assert mu[0] > 0 and abs(mu[0] - mu[1]) < 1e-3 * abs(mu[0])
    with pytest.raises(ValueError, match=r"speeds=1e-06 is invalid; valid range: 0\.01 <= speed"):
        stability.analyse(c, speeds=(1e-6,))


@pytest.mark.parametrize("call,argument", [
    ("simulate_duration", "horizon"), ("simulate_dt", "dt"), ("simulate_push", "tire_push_force"),
    ("simulate_atol", "atol"), ("intervals", "samples"), ("shimmy", "speeds"), ("study", "horizon"),
])
def test_the_python_api_bounds_work_naming_the_argument_and_the_largest_value(call, argument):
    """The API refuses what the command lines refuse, by estimate (count x cost), before any work."""
    import numpy as np

    from stability import chair as chair_mod
    from stability.linear.intervals import linear_intervals
    from stability.shimmy.chair import caster_summary
    from stability.simulate import simulate
    from stability.study.impulse import critical_impulses
    from stability.uncertainty import from_mapping

    c = chair_mod.preset("ej-premier")
    calls = {
        "simulate_duration": lambda: simulate(c, 0.75, run=RunSpec(horizon=3600.0, friction_law="kinetic")),
        "simulate_dt": lambda: simulate(c, 0.75, run=RunSpec(dt=1e-7, friction_law="kinetic")),
        "simulate_push": lambda: simulate(c, 0.75, run=RunSpec(tire_push_force=1e308, friction_law="kinetic")),
        "simulate_atol": lambda: simulate(c, 0.75, run=RunSpec(scheme="adaptive", atol=1e-300)),
        "intervals": lambda: linear_intervals(c, from_mapping({"s1": {"distribution": "normal", "std": 0.01}}),
                                              samples=20_000),
        "shimmy": lambda: caster_summary(c, np.linspace(0.1, 50, 5000)),
        "study": lambda: critical_impulses(c, [0.01], run=RunSpec(horizon=3600.0)),
    }
    result, work = _work_entered(calls[call])
    assert isinstance(result, ValueError) and re.search(rf"\b{argument}\b", str(result)), result
    assert not work, f"refused after work started in {sorted(work)}"


def test_report_keeps_a_caster_tire_without_rolling_data_valid():
    """The report switches rolling resistance on only for tires that have rolling data (PU has none)."""
    from stability import chair as chair_mod
    from stability.study.validation import with_rolling_resistance

    c = with_rolling_resistance(chair_mod.preset("ej-premier").replace(caster_tire="PU"))
    assert (c.main_rolling_scale, c.caster_rolling_scale) == (1.0, 0.0)


def test_slope_answers_a_heavy_chair_under_the_clamp_and_warn_policies(capsys):
    """200 kg loads the casters beyond the 450 N of the tire data: refused under raise, answered with clamp
    (forces held at the edge) and with warn (the fits extrapolated), each with a note naming the wheels."""
    import json

    from stability.slope.__main__ import main

    argv = ["--cross-slope", "2", "--speed", "0.75", "--set", "m=200", "--json"]
    assert main(argv + ["--tire-range", "raise"]) == 2
    capsys.readouterr()
    loads = {}
    for policy, word in (("clamp", "clamped"), ("warn", "extrapolated")):
        assert main(argv + ["--tire-range", policy]) == 0
        out, err = capsys.readouterr()
        assert '"cross_slope' in out and "error" not in err
        assert word in err and "caster_left" in err, err
        loads[policy] = json.loads(out)["normal_loads_N"]
    # the loads follow from statics and the lateral forces' small moments: the two policies move the
    # caster forces only beyond the data, so the loads agree to well under 1 N of about 500 N; error model: first
    # order in the lateral forces' moments (observed 1.7e-3 N), x100
    assert loads["warn"]["caster_left"] > 450.0
    for k, v in loads["clamp"].items():
        assert loads["warn"][k] == pytest.approx(v, abs=0.2)


def test_a_tire_loaders_precise_error_reaches_the_user(tmp_path, capsys):
    """A broken tire CSV named by --set: the line and column of the fault, not a generic list of tire names."""
    from stability.critical_speed.command import main

    (tmp_path / "bad.csv").write_text("slip_deg,Fz_N,Fy_N\n1,200,x\n", encoding="utf-8")
    assert main(["--set", f"caster_tire=file:{tmp_path / 'bad.csv'}"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "caster_tire" in err[0] and "line 2, column 'Fy_N'" in err[0], err
