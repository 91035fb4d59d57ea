"""One interface: the ``stability`` console script, the shared options of every command, chair export.

All in-process (``main(argv)``), no subprocess: the default run stays fast.
"""

from __future__ import annotations

import argparse

import pytest

from stability import chair as chair_mod
from stability import commands


def _all_parsers():
    for name in commands.COMMANDS:
        parser = commands.build_parser(name)
        subs = [p for a in parser._actions if isinstance(a, argparse._SubParsersAction) for p in a.choices.values()]
        yield name, parser, subs


def test_console_script_dispatches_and_refuses_unknown(capsys):
    assert commands.main(["chair", "list"]) == 0
    assert "ej-premier" in capsys.readouterr().out.split()
    assert commands.main(["critical-spee"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: command 'critical-spee' is unknown") and "critical-speed" in err
    assert commands.main(["--help"]) == 0 and "stability COMMAND" in capsys.readouterr().out


@pytest.mark.parametrize("name", list(commands.COMMANDS))
def test_debug_and_quiet_accepted_after_every_subcommand(name):
    """--debug and --quiet are added by cli.run to a command's parser and to each subcommand's parser (study
    critical-impulse --debug was refused)."""
    from stability import cli

    parser = commands.build_parser(name)
    for p in (parser, *cli._subparsers(parser)):
        cli.add_common_options(p)
    for p in [parser, *cli._subparsers(parser)]:
        opts = {s for a in p._actions for s in a.option_strings}
        assert {"--debug", "--quiet"} <= opts, (name, p.prog)


def test_study_debug_after_subcommand_parses(capsys):
    from stability.study.__main__ import main

    assert main(["critical-impulse", "--speeds", "-1", "--debug", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "unrecognized arguments" not in err and "Traceback" in err and "error: --speeds '-1'" in err


def test_chair_export_round_trips(tmp_path, capsys):
    from stability.chair.__main__ import main

    out = tmp_path / "mine.toml"
    assert main(["export", "revised", "--set", "trail=0.06", "-o", str(out)]) == 0
    c = chair_mod.load(out)
    assert c == chair_mod.preset("revised").replace(trail=0.06)
    assert main(["export", "revised", "-o", str(tmp_path / "x.pdf")]) == 2
    assert "ends in .toml" in capsys.readouterr().err
    assert not (tmp_path / "x.pdf").exists()
