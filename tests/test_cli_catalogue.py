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
import signal
import time
from pathlib import Path

import pytest

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

#: Seconds a refusal may take (bad input must be caught before the work starts).
TIME_LIMIT = 5.0

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
    ("simulate", ["--duration", "1e9", "--no-stop"], "duration"),
    ("simulate", ["--duration", "-1"], "duration"),
    ("simulate", ["--scheme", "adaptive", "--duration", "1e5"], "duration"),
    ("simulate", ["--scheme", "euler"], "scheme"),
    ("simulate", ["--impulse", "40", "-1"], "impulse"),
    ("simulate", ["--impulse", "1e12", "0.1"], "impulse"),
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
]


def _inputs(folder: Path) -> None:
    folder.mkdir()
    (folder / "chair.toml").write_text('name = "mine"\ntrail = 0.06\n')
    (folder / "mixed.toml").write_text('trail = 0.06\n[chair]\ns1 = 0.3\n')
    (folder / "broken.toml").write_text("trail = = 0.06\n")
    (folder / "u.toml").write_text('[s1]\ndistribution = "normal"\nstd = 0.01\n')
    (folder / "bad_sheet.toml").write_text("this is not a sheet = 1\n")


@pytest.mark.parametrize("command,argv,fragment", CASES, ids=[f"{c}:{' '.join(a)}" for c, a, _ in CASES])
def test_bad_input_is_refused_in_one_line(command, argv, fragment, tmp_path, monkeypatch, capsys):
    inputs = tmp_path / "inputs"
    _inputs(inputs)
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
    start = time.perf_counter()
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse usage errors
        code = exc.code
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    elapsed = time.perf_counter() - start
    out, err = capsys.readouterr()
    lines = [line for line in err.strip().splitlines() if line]
    assert code == 2, f"exit status {code}; stderr: {err!r}"
    assert len(lines) == 1 and lines[0].startswith("error:"), f"not one error line: {err!r}"
    assert "Traceback" not in err
    assert fragment in lines[0], f"{fragment!r} not in {lines[0]!r}"
    assert sorted(os.listdir(work)) == [], "files left behind"
    assert sorted(os.listdir(inputs)) == sorted(["chair.toml", "mixed.toml", "broken.toml", "u.toml",
                                                 "bad_sheet.toml"]), "an input was changed or an output written"
    assert elapsed < TIME_LIMIT, f"took {elapsed:.1f} s"


def test_catalogue_is_large_and_covers_every_command():
    assert len(CASES) >= 60
    assert {c for c, _, _ in CASES} == set(COMMANDS)


@pytest.mark.parametrize("command,argv", [
    ("critical_speed", ["--set", "camber_deg=10"]),       # camber up to 45 deg is a valid chair (issue 16)
    ("critical_speed", ["--speeds", "0.5,1", "--set", "m=120"]),
    ("simulate", ["--duration", "1", "--speed", "0.5", "--impulse", "-40", "0.1"]),   # a push to the left
])
def test_valid_unusual_input_is_answered(command, argv, capsys):
    main = importlib.import_module(COMMANDS[command]).main
    assert main(argv) == 0
    assert "error" not in capsys.readouterr().err
