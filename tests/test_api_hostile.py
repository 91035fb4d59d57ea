"""The public API answers hostile input as the command lines do (issue 34): one exception naming the argument,
its value and the valid range, raised before any work.

Each case names the function, its arguments, the exception and the words its message must contain; the
compute entry the function would reach is monkeypatched to raise, so a refusal is proved to come before any
work (not timed).  The ranges quoted are read from the same tables the command lines use.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import stability
from stability import tires
from stability.chair import LIMITS, valid_range
from stability.linear.batch import MAX_MATRICES
from stability.runtime.readfiles import MAX_INPUT_BYTES
from stability.settings.bounds import SEARCH_MAX_SPEED
from stability.settings.run import RUN_SETTINGS
from stability.simulate.api import MAX_WORKERS


class WorkStarted(AssertionError):
    """A compute entry was reached: the refusal came too late."""


#: The entries the public functions compute through (module, attribute).
COMPUTE = [("stability.linear.model", "_matrices"), ("stability.linear.summary", "state_matrices"),
           ("stability.linear.modes", "state_matrices"), ("stability.simulate.api", "_run"),
           ("stability.tires.user", "fit_per_angle")]


@pytest.fixture
def no_work(monkeypatch):
    import importlib

    def stop(*args, **kwargs):
        raise WorkStarted("work started before the refusal")

    for module, attr in COMPUTE:
        monkeypatch.setattr(importlib.import_module(module), attr, stop)


def _c():
    return stability.preset("ej-premier")


# (id, call, exception, words the message must contain)
CASES = [
    ("Chair huge int", lambda: stability.Chair(m=10**400), ValueError, ["m=1.000e+400", valid_range("m")]),
    ("Chair nan", lambda: stability.Chair(h=float("nan")), ValueError, ["h=nan", valid_range("h")]),
    ("Chair string", lambda: stability.Chair(trail="long"), ValueError, ["trail='long'", valid_range("trail")]),
    ("Chair negative", lambda: stability.Chair(i_z=-1.0), ValueError, ["i_z=-1.0", valid_range("i_z")]),
    ("preset type", lambda: stability.preset(3), TypeError, ["name=3", "ej-premier"]),
    ("load_chair type", lambda: stability.load_chair(None), TypeError, ["spec=None", "ej-premier"]),
    ("analyse preset name", lambda: stability.analyse("ej-premier"), TypeError,
     ["chair='ej-premier'", "stability.preset('ej-premier')"]),
    ("analyse max_speed nan", lambda: stability.analyse(_c(), max_speed=float("nan")), ValueError,
     ["max_speed=nan", SEARCH_MAX_SPEED.text("max_speed")]),
    ("analyse max_speed huge", lambda: stability.analyse(_c(), max_speed=10**400), ValueError,
     ["max_speed=1.000e+400", SEARCH_MAX_SPEED.text("max_speed")]),
    ("analyse n_grid huge", lambda: stability.analyse(_c(), n_grid=10**9), ValueError,
     ["n_grid=1000000000", f"<= {MAX_MATRICES}"]),
    ("analyse n_grid negative", lambda: stability.analyse(_c(), n_grid=-1), ValueError, ["n_grid=-1"]),
    ("analyse n_grid float", lambda: stability.analyse(_c(), n_grid=2.5), TypeError, ["n_grid=2.5", "integer"]),
    ("analyse speeds huge int", lambda: stability.analyse(_c(), speeds=[0.5, 10**400]), ValueError,
     ["speeds=1.000e+400", "0.01 <= speed <= 100 m/s"]),
    ("analyse speeds string", lambda: stability.analyse(_c(), speeds="abc"), ValueError, ["speeds='abc'"]),
    ("analyse speeds huge array", lambda: stability.analyse(_c(), speeds=np.full(10**7, 0.75)), ValueError,
     ["speeds has 10000000 values", f"at most {MAX_MATRICES}"]),
    ("analyse model", lambda: stability.analyse(_c(), model=["x"]), ValueError, ["model=['x']", "'exact'"]),
    ("state_space preset name", lambda: stability.state_space("ej-premier", 0.75), TypeError, ["chair="]),
    ("state_space speed huge", lambda: stability.state_space(_c(), 10**400), ValueError,
     ["speed=1.000e+400", "0.01 <= speed <= 100 m/s"]),
    ("state_space casters", lambda: stability.state_space(_c(), 0.75, casters=3), ValueError,
     ["casters=3", "'free'"]),
    ("eigenvalues_vs_speed preset name", lambda: stability.eigenvalues_vs_speed("ej-premier", [0.75]), TypeError,
     ["chair="]),
    ("eigenvalues_vs_speed speeds 2-D", lambda: stability.eigenvalues_vs_speed(_c(), np.full((3, 3), 0.75)), ValueError,
     ["speeds=", "1-D"]),
    ("eigenvalues_vs_speed speeds huge array", lambda: stability.eigenvalues_vs_speed(_c(), np.full(10**7, 0.75)),
     ValueError, ["speeds has 10000000 values"]),
    ("eigenvalues_vs_speed speed negative", lambda: stability.eigenvalues_vs_speed(_c(), [-1.0]), ValueError,
     ["speeds=-1.0"]),
    ("eigenvalues_vs_speed track", lambda: stability.eigenvalues_vs_speed(_c(), [0.75], track="yes"), TypeError,
     ["track='yes'"]),
    ("RunSpec huge int", lambda: stability.RunSpec(speed=10**400), ValueError,
     ["speed=1.000e+400", RUN_SETTINGS["speed"].range_text("speed")]),
    ("RunSpec string", lambda: stability.RunSpec(horizon="x"), TypeError, ["horizon='x'", "number"]),
    ("run_simulation preset name", lambda: stability.run_simulation("ej-premier", 0.75), TypeError,
     ["chair='ej-premier'"]),
    ("run_simulation speed huge", lambda: stability.run_simulation(_c(), 10**400), ValueError,
     ["speed=1.000e+400", RUN_SETTINGS["speed"].range_text("speed")]),
    ("run_simulation record", lambda: stability.run_simulation(_c(), 0.75, record="x"), ValueError,
     ["record='x'", "'final'"]),
    ("run_batch preset name", lambda: stability.run_batch("ej-premier", [0.75]), TypeError, ["chairs='ej-premier'"]),
    ("run_batch speeds string", lambda: stability.run_batch(_c(), "abc"), ValueError, ["speeds='abc'"]),
    ("run_batch speeds huge int", lambda: stability.run_batch(_c(), [10**400]), ValueError,
     ["speeds", RUN_SETTINGS["speed"].range_text("speed")]),
    ("run_batch speeds nan", lambda: stability.run_batch(_c(), [0.75, float("nan")]), ValueError,
     ["speeds", "speed=nan"]),
    ("run_batch push huge int", lambda: stability.run_batch(_c(), [0.75], push_forces=[10**400]), ValueError,
     ["push_forces", RUN_SETTINGS["push_force"].range_text("push_force")]),
    ("run_batch a million runs", lambda: stability.run_batch(_c(), np.full(10**6, 0.75), record="final",
                                                             run=stability.RunSpec(horizon=0.01)),
     ValueError, ["speeds asks for 1000000 runs", "the largest allowed is"]),
    ("run_batch workers", lambda: stability.run_batch(_c(), [0.75], workers=-1), ValueError, ["workers=-1"]),
    ("run_batch workers huge", lambda: stability.run_batch(_c(), [0.75], workers=10**400), ValueError,
     ["workers=1.000e+400", f"1 to {MAX_WORKERS}"]),
    ("run_batch workers float", lambda: stability.run_batch(_c(), [0.75], workers=2.0), ValueError,
     ["workers=2.0", f"1 to {MAX_WORKERS}"]),
    ("load_tire_data type", lambda: tires.load_tire_data(None), TypeError, ["path=None"]),
]


@pytest.mark.parametrize("call,exc,words", [c[1:] for c in CASES], ids=[c[0] for c in CASES])
def test_the_api_refuses_hostile_input_naming_the_argument_before_any_work(call, exc, words, no_work):
    with pytest.raises(exc) as info:
        call()
    msg = str(info.value)
    assert "\n" not in msg and len(msg) < 600, msg
    for w in words:
        assert w in msg, f"{w!r} not in {msg!r}"


def test_the_table_covers_every_public_function():
    covered = {c[0].split()[0] for c in CASES}
    public = set(stability.__all__) - {"__version__", "preset_names"}     # preset_names takes no argument
    assert public <= covered | {"Chair"}, public - covered
    assert set(LIMITS) >= {"m", "h", "trail", "i_z"}


def _tire_rows(fy) -> str:
    return "\n".join(f"{s},{z},{fy(s, z)!r}" for s in range(1, 9) for z in (100.0, 200.0, 300.0, 400.0, 450.0))


@pytest.mark.parametrize("text,words", [
    ("slip_deg,Fz_N,Fy_N\n" + _tire_rows(lambda s, z: 0.0), ["slip angle 1 deg", "0 N at every load"]),
    ("slip_deg,Fz_N,Fy_N,Fy_N\n" + "\n".join(r + ",0" for r in _tire_rows(lambda s, z: 0.1 * s * z).splitlines()),
     ["line 1", "named twice"]),
])
def test_a_tire_csv_that_cannot_be_fitted_is_one_value_error_naming_the_file(text, words, tmp_path, no_work):
    path = tmp_path / "t.csv"
    path.write_text(text + "\n")
    with pytest.raises(ValueError) as info:
        tires.load_tire_data(path)
    assert str(path) in str(info.value)
    for w in words:
        assert w in str(info.value)


_BOUNDED = """
import resource, sys
limit = 512 * 2**20 + {extra}
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
{call}
"""


@pytest.mark.parametrize("call,words", [
    ("from stability.tires import load_tire_data\n"
     "try:\n    load_tire_data('/dev/zero')\nexcept ValueError as e:\n    print(e)", "'/dev/zero' has more than"),
    ("import stability\n"
     "try:\n    stability.load_chair('/dev/zero')\nexcept ValueError as e:\n    print(e)", "'/dev/zero' has more than"),
])
def test_an_endless_input_file_is_refused_in_bounded_memory(call, words):
    """Read at most MAX_INPUT_BYTES + 1 bytes: the process runs under an address-space limit (numpy and the
    package need about 400 MB of it), so an unbounded read would end in MemoryError, not in the refusal."""
    if not os.path.exists("/dev/zero"):
        pytest.skip("no /dev/zero")
    pytest.importorskip("resource")
    p = subprocess.run([sys.executable, "-c", _BOUNDED.format(extra=4 * MAX_INPUT_BYTES, call=call)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0 and words in p.stdout, (p.stdout, p.stderr[-2000:])


def test_outputs_renamed_together_under_a_signal(tmp_path):
    """A signal between two renames waits until all are in place; one before the renames leaves none."""
    from stability.cli import files as cli_files
    from stability.runtime import interrupts

    real = os.replace
    calls: list[str] = []

    def replace_then_signal(src, dst):
        real(src, dst)
        calls.append(dst)
        if len(calls) == 1:
            os.kill(os.getpid(), signal.SIGTERM)

    outs = {"--csv": str(tmp_path / "r.csv"), "-o": str(tmp_path / "r.png"), "--json-file": str(tmp_path / "r.json")}
    with pytest.raises(KeyboardInterrupt), interrupts.interruptible():
        cli_files.os.replace = replace_then_signal
        try:
            with cli_files.output_files(outs) as tmp:
                for t in tmp.values():
                    Path(t).write_text("done")
        finally:
            cli_files.os.replace = real
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r.csv", "r.json", "r.png"]

    fresh = tmp_path / "second"
    fresh.mkdir()
    outs = {k: str(fresh / Path(v).name) for k, v in outs.items()}
    with pytest.raises(KeyboardInterrupt), interrupts.interruptible():
        with cli_files.output_files(outs) as tmp:
            for t in tmp.values():
                Path(t).write_text("done")
            os.kill(os.getpid(), signal.SIGTERM)
    assert list(fresh.iterdir()) == []


@pytest.mark.parametrize("module, argv", [
    ("stability.slope.__main__", ["--cross-slope", "2", "--speed", "1", "-o", "f.png"]),
    ("stability.slope.__main__", ["--chair", "mid-wheel-drive", "--cross-slope", "2", "--speed", "1", "-o", "f.png"]),
    ("stability.critical_speed.command", ["--speeds", "0.5,1", "-o", "f.png"]),
    ("stability.critical_speed.command", ["--chair", "mid-wheel-drive", "--speeds", "0.5,1", "-o", "f.png"]),
    ("stability.compare.__main__", ["ej-premier", "revised", "--speeds", "0.75", "-o", "f.png"]),
    ("stability.compare.__main__", ["ej-premier", "mid-wheel-drive", "--speeds", "0.75", "-o", "f.pdf"]),
    ("stability.sweep.__main__", ["g.toml", "-o", "g.csv"]),
])
def test_the_figures_and_the_json_file_are_written_all_or_none(module, argv, tmp_path, monkeypatch):
    """A command's figures (-o; the sweep's summary and PDF) and --json-file are renamed together: when the JSON
    fails after the figures were drawn, none appears (the figures used to be renamed into place before the JSON was
    written); without the failure all do.  The sweep's rows file is written chunk by chunk for --resume and stays."""
    import importlib

    mod = importlib.import_module(module)
    main = importlib.import_module(module.rsplit(".", 1)[0] + ".__main__").main
    monkeypatch.chdir(tmp_path)
    Path("g.toml").write_text('speeds = [0.5]\nmeasures = ["growth_rate"]\n[grid]\ntrail = [0.05, 0.07]\n')
    argv = [*argv, "--json-file", "f.json"]

    def fail(*_a, **_k):
        raise OSError(28, "No space left on device")

    with monkeypatch.context() as m:
        m.setattr(mod, "emit_json", fail)
        assert main(argv) != 0
    assert sorted(p.name for p in tmp_path.iterdir()) == (["g.csv", "g.toml"] if "g.csv" in argv else ["g.toml"])
    assert main(argv) == 0
    made = {p.name: p.stat().st_size for p in tmp_path.iterdir()}
    want = {"f.json"} | ({"g.csv", "g.summary.json", "g.pdf"} if "g.csv" in argv else {argv[argv.index("-o") + 1]})
    assert want <= set(made) and all(made[n] > 0 for n in want)


@pytest.mark.parametrize("then", [RuntimeError("no compiled object yet for <Library '_consistent'>"),
                                  ValueError("speed=nan is invalid"), OSError("disk gone")])
def test_a_signal_a_library_swallowed_still_exits_130(then, capsys):
    """Ctrl-C during numba's first compile: its LLVM object-cache callback (a ctypes callback) swallows the
    KeyboardInterrupt ("Exception ignored on calling ctypes callback function") and the compile then fails with
    another error.  The command still ends as interrupted (status 130, the one line), not as a computation error
    (status 2), because the signal was remembered (the slow test_cli_interrupt.py saw status 2 with a cold cache)."""
    import argparse

    from stability.cli.contract import run

    def body(args):
        try:
            os.kill(os.getpid(), signal.SIGINT)      # the contract's handler raises KeyboardInterrupt here ...
        except KeyboardInterrupt:                     # ... which a library swallows
            pass
        raise then                                    # and then fails with its own error

    assert run(argparse.ArgumentParser(), [], body) == 130
    assert capsys.readouterr().err == "error: interrupted\n"
    # without a signal the same error is the computation's or the input's: status 2
    assert run(argparse.ArgumentParser(), [], lambda a: (_ for _ in ()).throw(then)) == 2
