"""``python -m stability.chair``: chair files: export a preset (or a chair file with changes) to start from.

Examples
--------
::

    python -m stability.chair export ej-premier -o my_chair.toml
    python -m stability.chair export power-fwd --set trail=6cm -o my_power.toml
    python -m stability.chair export mid-wheel-drive -o my_base.toml   # a wheel layout: the [[wheel]] form
    python -m stability.chair list
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from stability import chair as chair_mod
from stability.cli import (
    OneLineErrorParser,
    add_common_options,
    add_json_options,
    check_outputs,
    emit_json,
    json_header,
    load_chair,
    load_layout,
    run,
)
from stability.layout.io import is_layout_spec
from stability.layout.presets import layout_preset_names
from stability.runtime.files import atomic_write_text

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m stability.chair``.

    Returns
    -------
    argparse.ArgumentParser
    """
    p = OneLineErrorParser(prog="python -m stability.chair", description=(__doc__ or "").split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineErrorParser)
    ex = sub.add_parser("export", help="write a preset or chair file, with --set changes, as a chair TOML file")
    ex.add_argument("chair", metavar="CHAIR", help=f"preset name ({', '.join(chair_mod.preset_names())}), layout "
                    f"preset ({', '.join(layout_preset_names())}: written in the [[wheel]] form) or TOML file")
    ex.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                    help="override a chair field (repeatable; units allowed, e.g. trail=5cm)")
    ex.add_argument("--wheels", action="store_true",
                    help="write a short-form chair in the [[wheel]] form (its layout: two main wheels, a caster "
                         "pair, its anti-tip contacts), to add or move wheels; a layout is always written so")
    ex.add_argument("-o", "--output", metavar="FILE.toml",
                    help="chair file to write (default: print the TOML on standard output)")
    add_json_options(ex)
    ls = sub.add_parser("list", help="the presets, one a line (the short form's, then the wheel layouts)")
    for s in (ex, ls):
        add_common_options(s)
    return p


def _run(args: argparse.Namespace) -> int:
    if args.command == "list":
        for name in chair_mod.preset_names():
            print(name)
        for name in layout_preset_names():
            print(name)
        return 0
    output = args.output
    if output is not None and not output.lower().endswith(".toml"):
        raise ValueError(f"-o {output!r} is invalid; a chair file ends in .toml")
    check_outputs({"-o": output, "--json-file": args.json_file}, {"CHAIR": args.chair})
    if args.wheels or is_layout_spec(args.chair):
        return _export_layout(args, output)
    c = load_chair(args.chair, args.set)
    if args.json or args.json_file:
        # the chair as every command's JSON header gives it (name and every parameter, key convention)
        emit_json(json_header(c, None, {"set": list(args.set)}), args)
        if args.json_file and not args.quiet:
            print(f"wrote {args.json_file}", file=sys.stderr)
        if args.json and output is None:
            return 0
    return _write(chair_mod.dumps(c), output, args, f"chair {c.name!r}")


def _write(text: str, output: str | None, args: argparse.Namespace, what: str) -> int:
    """The chair file on standard output, or written to ``output`` atomically with one note."""
    if output is None:
        sys.stdout.write(text)
    else:
        atomic_write_text(output, text)
        if not args.quiet:
            print(f"wrote {output}: {what}", file=sys.stderr)
    return 0


def _export_layout(args: argparse.Namespace, output: str | None) -> int:
    """A wheel layout (a layout preset or a ``[[wheel]]`` file) written in the ``[[wheel]]`` form."""
    from stability.layout.io import dumps

    if args.json or args.json_file:
        raise ValueError("--json is for the short form's chair; a wheel layout's file is its own record (read it "
                         "with python -m stability.critical_speed --chair FILE --json)")
    layout = load_layout(args.chair, args.set)
    return _write(dumps(layout), output, args, f"wheel layout {layout.name!r}")


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.chair``.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (2 on bad input).
    """
    return run(build_parser(), argv, _run)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
