"""One interface: the ``stability`` console script, the shared options of every command, chair export.

All in-process (``main(argv)``), no subprocess: the default run stays fast.
"""

from __future__ import annotations

import argparse

import pytest

from stability import chair as chair_mod
from stability.cli import commands


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
    from stability.cli import contract as cli

    parser = commands.build_parser(name)
    for p in (parser, *cli._subparsers(parser)):
        cli.add_common_options(p)
    for p in [parser, *cli._subparsers(parser)]:
        opts = {s for a in p._actions for s in a.option_strings}
        assert {"--debug", "--quiet"} <= opts, (name, p.prog)


def test_study_debug_after_subcommand_parses(capsys):
    from stability.study.__main__ import main

    assert main(["critical-impulse", "--speeds", "0", "--debug", "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "unrecognized arguments" not in err and "Traceback" in err and "error: --speeds '0'" in err


def test_chair_export_round_trips(tmp_path, capsys):
    from stability.chair.__main__ import main

    out = tmp_path / "mine.toml"
    assert main(["export", "revised", "--set", "trail=0.06", "-o", str(out)]) == 0
    c = chair_mod.load(out)
    assert c == chair_mod.preset("revised").replace(trail=0.06)
    assert main(["export", "revised", "-o", str(tmp_path / "x.pdf")]) == 2
    assert "ends in .toml" in capsys.readouterr().err
    assert not (tmp_path / "x.pdf").exists()


def test_set_groups_and_units():
    """--set pin_friction=0.2 sets both casters (and d=, t= both sides); a value may carry a unit of the field's
    kind (the measurement sheet's parser): trail=5cm is 0.05 m, m=210 lb is 95.254 kg (1 lb = 0.45359237 kg
    exactly), 0.1 ft lbf = 0.13558 N m; a unit of another kind is refused naming the field."""
    from stability.cli import load_chair

    c = load_chair("ej-premier", ["pin_friction=0.2", "trail=5cm", "m=210 lb", "d=27cm"])
    assert (c.pin_friction_left, c.pin_friction_right) == (0.2, 0.2)
    assert c.trail == pytest.approx(0.05, rel=1e-15) and c.m == pytest.approx(210 * 0.45359237, rel=1e-15)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert c.d1 == c.d2 == pytest.approx(0.27, rel=1e-15)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert chair_mod.parse_assignments(["pin_friction_left=0.1 ft lbf"])["pin_friction_left"] == \
        pytest.approx(0.1 * 0.3048 * 0.45359237 * 9.80665, rel=1e-15)   # rounding: 3 products each side, 6 eps/2
    with pytest.raises(ValueError, match="trail is in m; 'kg' is not a unit of that kind"):
        load_chair("ej-premier", ["trail=5kg"])
    with pytest.raises(ValueError, match="pin_friction \\(pin_friction_left and pin_friction_right\\)"):
        load_chair("ej-premier", ["pin_frict=0.2"])


def test_output_suffix_names_the_format_and_unknown_is_refused(tmp_path, capsys):
    """compare --pdf x.png wrote a PDF named x.png; now -o (and the hidden --pdf) refuse a suffix the command
    cannot write, in one line, before any work, and write nothing."""
    from stability.compare.__main__ import main

    out = tmp_path / "x.jpg"
    assert main(["ej-premier", "revised", "--pdf", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == f"error: -o {str(out)!r} is invalid; the suffix names the format, valid: .pdf, .png, .svg"
    assert not out.exists()
    from stability.simulate.__main__ import main as sim

    assert sim(["--speed", "0.75", "-o", str(tmp_path / "run.jpg")]) == 2
    assert "valid: .pdf, .png, .svg" in capsys.readouterr().err


@pytest.mark.parametrize("name", list(commands.COMMANDS))
def test_json_and_json_file_together_are_accepted(name):
    parser = commands.build_parser(name)
    from stability.cli import contract as cli

    for p in [parser, *cli._subparsers(parser)]:
        opts = {s for a in p._actions for s in a.option_strings}
        if "--json" in opts:
            groups = [g for g in p._mutually_exclusive_groups
                      if {s for a in g._group_actions for s in a.option_strings} & {"--json", "--json-file"}]
            assert not groups, (name, p.prog)
            assert "--json-file" in opts


def test_measure_takes_uncertainty_and_json(tmp_path, capsys):
    import json
    from pathlib import Path

    from stability.measure.__main__ import main

    sheet = Path(__file__).resolve().parents[1] / "docs" / "examples" / "measured_chair_sheet.toml"
    out, unc = tmp_path / "c.toml", tmp_path / "u.toml"
    assert main([str(sheet), "-o", str(out), "--uncertainty", str(unc), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["chair_file"] == str(out) and data["uncertainty_file"] == str(unc) and out.exists() and unc.exists()
    assert {r["field"] for r in data["fields"]} >= {"m", "i_z"}


def test_tire_range_notes_are_one_line_per_tire_and_range():
    """The report printed one note per load (19-51 lines); now one line per tire, quantity and fitted range, with
    how often, how far and on which wheels."""
    from stability.tires import RangeNote, summarise_notes

    notes = [RangeNote("ER", "load", 450.0 + i, 0.0, 450.0, "warn", w)
             for i, w in zip(range(1, 20), ["caster_left", "caster_right"] * 10, strict=False)]
    notes.append(RangeNote("EJA", "slip", 9.0, -8.0, 8.0, "warn", "main_left"))
    lines = summarise_notes(notes)
    assert len(lines) == 2
    assert lines[0].startswith("tire ER: load up to 469 N (19 uses, 451-469 N; wheels caster_left, caster_right)")
    assert lines[1] == str(notes[-1])
