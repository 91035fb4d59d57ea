"""Issue 38's "every command answers for the three drive layouts and for reverse", walked over the command catalogue.

Every command of :data:`stability.cli.commands.COMMANDS` that takes a chair is run in-process (``main(argv)``) on the
three drive layouts of one frame (the mid-wheel-drive base and the rear- and front-wheel-drive power bases) forward
and in reverse (a negative speed; ``--reverse`` where the command has no speed), with the smallest settings that
answer.  Each must exit 0 and, where it reports a speed, report it signed (negative: reverse), the one convention of
every command (``study equal-instability --reverse``: its speed and bracket negative).  The commands without a chair or a direction are named in :data:`NOT_WALKED` with the reason.

The physical check is independent of the reverse machinery: driving a layout backwards is driving the layout turned by
180 deg forwards (``tests/test_layout.py::_turned`` builds it by hand: positions negated, the c.g. and the yaw inertia
moved by the casters' swing), so the growth rates ``critical_speed --json`` reports at negative speeds are the turned
layout's at the positive ones, and its reverse critical speed is the turned layout's forward one.

The representative (``critical_speed`` and ``study equal-instability`` on the three layouts both ways) is in the
default suite; the full walk (simulations, reports, the advisor: about a minute of CPU) is ``slow``.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from test_layout import _turned

from stability.cli.commands import COMMANDS, command_module
from stability.layout.linear import critical_speed, growth_rates
from stability.layout.presets import layout_preset

#: The three drive layouts of one frame (docs/power-chair.md): mid-, rear- and front-wheel drive.
LAYOUTS = ("mid-wheel-drive", "power-rwd-base", "power-fwd-base")

#: Commands the walk does not run, and why (none of them takes a chair and a direction).
NOT_WALKED = {
    "measure": "reads a four-scale measurement sheet (the short form's fields); no chair, no speed",
    "sweep": "its spec names the chair and signed speeds (tests/test_sweep_layouts.py sweeps layouts both ways)",
    "app": "a web server; its layout page is tested in tests/test_app_state.py",
    "chair": "walked as 'chair export' below (no direction: a file)",
}

Speeds = Callable[[dict], list]


def _case(command: str, argv: Callable[[str, int], list[str]], speeds: Speeds | None, fast: bool = False):
    return command, argv, speeds, fast


def _sp(sign: int, *values: float) -> str:
    """``--speeds=`` text of ``values`` in the direction ``sign``."""
    return ",".join(f"{sign * v:g}" for v in values)


#: command, argv(layout, sign), the signed speeds its JSON reports (None: no speed), in the default suite or slow.
CASES = [
    _case("critical_speed", lambda lay, s: ["--chair", lay, f"--speeds={_sp(s, 0.5, 1)}"],
          lambda j: j["speeds_m_s"], fast=True),
    _case("compare", lambda lay, s: [lay, "ej-premier", f"--speeds={_sp(s, 0.5, 1)}"], lambda j: j["speeds_m_s"]),
    _case("simulate", lambda lay, s: ["--chair", lay, f"--speed={s}", "--horizon", "1"], lambda j: [j["speed_m_s"]]),
    _case("study", lambda lay, s: ["critical-impulse", "--chair", lay, f"--speeds={s}"],
          lambda j: [p["speed_m_s"] for p in j["points"]]),
    _case("study", lambda lay, s: ["equal-instability", "--chair", lay] + (["--reverse"] if s < 0 else []),
          lambda j: [j["speed_m_s"], j["low_m_s"], j["high_m_s"]], fast=True),
    _case("shimmy", lambda lay, s: ["--chair", lay, f"--speeds={s}"], lambda j: j["options"]["speeds_m_s"]),
    _case("slope", lambda lay, s: ["--chair", lay, "--cross-slope", "2", f"--speed={s}", "--sim-time", "2"],
          lambda j: [j["speed_m_s"]]),
    _case("assist", lambda lay, s: ["--chair", lay, "--speeds", "1"] + (["--reverse"] if s < 0 else []),
          lambda j: [r["speed_m_s"] for r in (j["reverse"] if j["reverse"] else j["forward"])]),
    _case("report", lambda lay, s: ["--chair", lay, "--quick", f"--speeds={_sp(s, 0.5, 1)}", "--no-progress",
                                    "-o", "{tmp}/r.pdf"], None),
    _case("advise", lambda lay, s: ["--chair", lay, f"--speeds={s * 0.5:g}:{s:g}" if s > 0 else "--speeds=-1:-0.5",
                                    "--no-progress"], lambda j: j["options"]["speeds_m_s"]),
    _case("tipping", lambda lay, s: ["--chair", lay], None),
    _case("bench", lambda lay, s: ["--chair", lay], None),
    _case("chair", lambda lay, s: ["export", lay, "-o", "{tmp}/c.toml"], None),
]


def _params(fast: bool):
    out = []
    for command, argv, speeds, is_fast in CASES:
        if is_fast != fast:
            continue
        for lay in LAYOUTS:
            for sign in (1, -1):
                words = argv(lay, sign)
                label = f"{command}:{words[0] if not words[0].startswith('-') else ''}:{lay}:{sign:+d}"
                out.append(pytest.param(command, words, speeds, sign, id=label))
    return out


def _run(command: str, argv: list[str], tmp_path: Path, capsys) -> tuple[int, dict | None, str]:
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    out = tmp_path / "out.json"
    json_args = [] if command == "chair" else ["--json-file", str(out)]
    code = command_module(command).main(["--quiet", *argv, *json_args])
    err = capsys.readouterr().err
    return int(code or 0), (json.loads(out.read_text()) if out.exists() else None), err


def _check(command, argv, speeds, sign, tmp_path, capsys):
    code, data, err = _run(command, argv, tmp_path, capsys)
    assert code == 0, f"{command} {' '.join(argv)} exited {code}: {err.strip()}"
    if command != "chair":
        assert data is not None
    if speeds is not None:
        got = [u for u in speeds(data) if u is not None]
        assert got, f"{command} reports no speed"
        # the run's direction is there, signed (a layout's linear analysis adds the other direction's mirror speeds)
        assert sign in {int(np.sign(u)) for u in got}, f"{command}: speeds {got} not signed {sign:+d}"
        assert all(u != 0 for u in got)


def test_the_walk_covers_the_catalogue():
    """Every command is walked or named with the reason it is not."""
    assert {c for c, *_ in CASES} | set(NOT_WALKED) == set(COMMANDS)


@pytest.mark.parametrize("command,argv,speeds,sign", _params(fast=True))
def test_every_drive_layout_answers_both_ways(command, argv, speeds, sign, tmp_path, capsys):
    _check(command, argv, speeds, sign, tmp_path, capsys)


@pytest.mark.slow
@pytest.mark.parametrize("command,argv,speeds,sign", _params(fast=False))
def test_every_command_answers_every_drive_layout_both_ways(command, argv, speeds, sign, tmp_path, capsys):
    _check(command, argv, speeds, sign, tmp_path, capsys)


#: Growth rates of the layout backwards and of its hand-turned copy forwards: the same matrices up to the turned
#: layout's rounding (positions and inertia recomputed, ~1e-16 relative, tests/test_layout.py observes 1e-13 on the
#: eigenvalues); 1e-9 1/s is ~1e4 over that and far below any physical difference (a rate of ~0.1-10 1/s).
TURNED_RATE_1_S = 1e-9


@pytest.mark.parametrize("name", LAYOUTS)
def test_the_command_in_reverse_answers_the_turned_layout_forwards(name, tmp_path, capsys):
    """``critical_speed --chair NAME`` at negative speeds: the growth rates are those of the layout turned by 180 deg
    at the positive speeds (computed on the turned layout, independent of the command's reverse path), and its reverse
    critical speed (a magnitude with its kind, the schema's convention) is the turned layout's forward one."""
    speeds = (0.5, 1.0, 2.0)
    code, data, err = _run("critical_speed", ["--chair", name, f"--speeds={_sp(-1, *speeds)}"], tmp_path, capsys)
    assert code == 0, err
    turned = _turned(layout_preset(name))
    assert data["speeds_m_s"] == [-u for u in speeds]
    np.testing.assert_allclose(data["growth_rate_1_s"], growth_rates(turned, speeds),
                               rtol=0, atol=TURNED_RATE_1_S)
    fwd = critical_speed(turned)
    assert data["reverse_critical"]["kind"] == fwd[1]
    assert data["reverse_critical"]["speed_m_s"] == pytest.approx(fwd[0], abs=1e-3)    # bisection to 1e-3 m/s
