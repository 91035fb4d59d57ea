"""Issue 38's "done when": every command answers for the three drive layouts of one frame, forward and in reverse.

The walk goes over the command catalogue (:data:`stability.cli.commands.COMMANDS`) x the frame's three drive layouts
(the mid-wheel-drive base and the rear- and front-wheel-drive power bases) x {forward, reverse}, each command called
in-process (``main(argv)``) with its smallest settings that answer: exit 0 and a JSON whose speeds carry the
direction's sign (negative: reverse) wherever the command reports a speed.  Commands with no speed answer for both
directions in one run (tipping: the forward and backward tip angles; the bench: its reverse cases; a chair file).
``app`` (a web server) and the file-driven ``measure`` / ``sweep`` take no chair preset and are not walked here.

The default suite keeps the fast commands; the whole walk (the simulator's, the studies', the report's and the
advisor's runs) is ``slow``.  Independent check: driving a chair backwards is driving the chair turned round by 180
deg forwards (its casters trailing the other way), so the command's reverse growth rates of each layout equal its
forward ones of the turned layout written as a ``[[wheel]]`` file (tests/test_layout.py's ``_turned``).
"""

from __future__ import annotations

import importlib
import json
from collections.abc import Callable

import pytest
from test_layout import _turned

from stability.cli.commands import COMMANDS
from stability.layout.io import dumps
from stability.layout.presets import layout_preset

#: The frame's three drive layouts (stability.layout.presets).
LAYOUTS = ("mid-wheel-drive", "power-rwd-base", "power-fwd-base")

#: Commands the walk leaves out, and why (each takes no chair preset).
NOT_WALKED = {"measure": "a measurement sheet in, no chair", "sweep": "a sweep spec file in, no chair",
              "app": "a local web server"}

Argv = Callable[[str, str, bool], list[str]]


def _u(reverse: bool, speed: float = 0.5) -> str:
    return f"{-speed if reverse else speed:g}"


#: (command, subcommand label) -> argv for (layout, output folder, reverse): the smallest settings that answer.
CATALOGUE: dict[tuple[str, str], Argv] = {
    ("critical_speed", ""): lambda lay, d, r: ["--chair", lay, f"--speeds={_u(r)}", "--json"],
    ("compare", ""): lambda lay, d, r: [lay, "ej-premier", f"--speeds={_u(r)}", "--json"],
    ("shimmy", ""): lambda lay, d, r: ["--chair", lay, f"--speeds={_u(r)}", "--json"],
    ("assist", ""): lambda lay, d, r: ["--chair", lay, "--speeds=0.5", "--json"] + (["--reverse"] if r else []),
    ("tipping", ""): lambda lay, d, r: ["--chair", lay, "--json"],
    ("chair", "export"): lambda lay, d, r: ["export", lay, "-o", f"{d}/chair.toml"],
    ("bench", ""): lambda lay, d, r: ["--chair", lay, "--json"],
    ("simulate", ""): lambda lay, d, r: ["--chair", lay, f"--speed={_u(r)}", "--horizon", "1", "--json"],
    ("slope", ""): lambda lay, d, r: ["--chair", lay, "--cross-slope", "2", f"--speed={_u(r)}", "--sim-time", "1",
                                      "--json"],
    ("study", "critical-impulse"): lambda lay, d, r: ["critical-impulse", "--chair", lay, f"--speeds={_u(r, 1.0)}",
                                                      "--horizon", "2", "--json"],
    ("study", "equal-instability"): lambda lay, d, r: ["equal-instability", "--chair", lay, "--json"]
    + (["--reverse"] if r else []),
    ("advise", ""): lambda lay, d, r: ["--chair", lay, f"--speeds={_u(r)}", "--json", "--no-progress"],
    # the quick report of a layout has its forward and reverse rows; the clinician sheet takes the user's speeds
    ("report", ""): lambda lay, d, r: ["--chair", lay, "--no-progress", "-o", f"{d}/report.pdf"]
    + (["--clinician", f"--speeds={_u(r)}"] if r else ["--quick", "--json"]),
}

#: The fast part of the walk (each call well under a second once the numba kernels are cached), in the default suite.
FAST = {("critical_speed", ""), ("compare", ""), ("shimmy", ""), ("tipping", ""), ("chair", "export"), ("bench", "")}


def test_the_catalogue_covers_every_command():
    """A new command joins the walk (or names why not): the catalogue and :data:`COMMANDS` agree."""
    assert {c for c, _ in CATALOGUE} | set(NOT_WALKED) == set(COMMANDS)


def _speeds(d: dict) -> list[float]:
    """The signed speeds the answer is about: its top-level ``speeds_m_s`` / ``speed_m_s`` and its ``forward`` /
    ``reverse`` rows' (the assist's); else its options' (an options block echoes the run's settings, which hold
    ``|U|`` and a ``reverse`` flag: :class:`stability.settings.run.RunSpec`)."""
    def of(where: dict) -> list[float]:
        v = where.get("speeds_m_s", where.get("speed_m_s"))
        if isinstance(v, list):
            return [float(x) for x in v if x is not None]
        return [float(v)] if isinstance(v, (int, float)) and not isinstance(v, bool) else []

    out = of(d)
    for rows in (d.get("forward"), d.get("reverse")):
        if isinstance(rows, list):
            out += [u for row in rows if isinstance(row, dict) for u in of(row)]
    return out or of(d.get("options") or {})


#: Commands whose one answer holds both directions (a layout's critical speeds; the assist's forward rows with
#: ``--reverse``'s reverse rows): the asked direction's speeds must be there, the other's may be too.
BOTH_WAYS = {"critical_speed", "assist"}


def _answer(key: tuple[str, str], layout: str, reverse: bool, tmp_path, capsys) -> dict:
    """The command's JSON; ``{}`` for a call without ``--json`` (its ``-o`` file written instead)."""
    main = importlib.import_module(COMMANDS[key[0]]).main
    capsys.readouterr()
    argv = CATALOGUE[key](layout, str(tmp_path), reverse)
    status = main(argv)
    out = capsys.readouterr()
    assert status == 0, f"{key} {layout} reverse={reverse}: exit {status}; stderr: {out.err.strip()[-300:]}"
    if "--json" not in argv:
        written = argv[argv.index("-o") + 1]
        assert (tmp_path / written.rsplit("/", 1)[1]).stat().st_size > 0
        return {}
    d = json.loads(out.out)
    assert isinstance(d, dict)
    return d


def _check(key: tuple[str, str], layout: str, reverse: bool, tmp_path, capsys) -> None:
    d = _answer(key, layout, reverse, tmp_path, capsys)
    if not d:
        return                                           # a file written (checked by _answer), no JSON
    speeds = _speeds(d)
    if key == ("study", "equal-instability"):
        # its searched speed is the answer itself (None: beyond the bracket); the direction is named too
        assert d["direction"] == ("reverse" if reverse else "forward")
    elif key[0] in ("tipping", "chair", "bench") or (key[0] == "report" and not reverse):
        return                                           # no speed asked for: one answer for both directions
    else:
        assert speeds, f"{key}: no speed in the answer"
    if not speeds:
        return                                           # beyond the searched bracket: no speed to sign (its status)
    # the asked direction's signed speeds are there (BOTH_WAYS add the other direction)
    assert any((s < 0) == reverse for s in speeds if s != 0), f"{key} {layout} reverse={reverse}: speeds {speeds}"
    if key[0] not in BOTH_WAYS:
        assert all((s < 0) == reverse for s in speeds if s != 0), f"{key} {layout} reverse={reverse}: {speeds}"


@pytest.mark.parametrize("reverse", [False, True], ids=["forward", "reverse"])
@pytest.mark.parametrize("layout", LAYOUTS)
@pytest.mark.parametrize("key", sorted(FAST), ids=lambda k: " ".join(k).strip())
def test_every_fast_command_answers(key, layout, reverse, tmp_path, capsys):
    _check(key, layout, reverse, tmp_path, capsys)


@pytest.mark.slow
@pytest.mark.parametrize("reverse", [False, True], ids=["forward", "reverse"])
@pytest.mark.parametrize("layout", LAYOUTS)
@pytest.mark.parametrize("key", sorted(set(CATALOGUE) - FAST), ids=lambda k: " ".join(k).strip())
def test_every_command_answers(key, layout, reverse, tmp_path, capsys):
    _check(key, layout, reverse, tmp_path, capsys)


#: The reverse linearisation and the turned layout's forward one are the same matrices to rounding (tests/test_layout:
#: eigenvalues equal to ~2e-15 of the largest); the file's floats round-trip exactly (repr), so the growth rates agree
#: to ~1e-14 1/s; 1e-11 1/s is a margin of ~1000 that still flags any sign or geometry slip (>= 1e-3 1/s).
TURNED_1_S = 1e-11


@pytest.mark.parametrize("layout", LAYOUTS)
def test_reverse_is_the_turned_layout_forward_through_the_command(layout, tmp_path, capsys):
    """``critical_speed --chair LAYOUT --speeds=-1,-0.5`` gives the growth rates of the layout turned round by 180
    deg driven forward at 1 and 0.5 m/s (the turned layout written as a ``[[wheel]]`` chair file)."""
    path = tmp_path / "turned.toml"
    path.write_text(dumps(_turned(layout_preset(layout))))
    main = importlib.import_module(COMMANDS["critical_speed"]).main
    capsys.readouterr()
    assert main(["--chair", layout, "--speeds=-1,-0.5", "--json"]) == 0
    back = json.loads(capsys.readouterr().out)
    assert main(["--chair", str(path), "--speeds=1,0.5", "--json"]) == 0
    turned = json.loads(capsys.readouterr().out)
    rate_back = dict(zip(back["speeds_m_s"], back["growth_rate_1_s"], strict=True))
    rate_turned = dict(zip(turned["speeds_m_s"], turned["growth_rate_1_s"], strict=True))
    for u in (1.0, 0.5):
        assert rate_back[-u] == pytest.approx(rate_turned[u], abs=TURNED_1_S)
