"""``python -m stability.measure SHEET.toml -o CHAIR.toml``: measurement sheet -> chair file + uncertainty file.

Writes both files atomically, all or none (the uncertainty file defaults to
``CHAIR.uncertainty.toml`` beside the chair file) and prints what it wrote.
Bad or inconsistent readings: one line naming the reading, its value and
the valid range; exit status 2, nothing written.

Examples
--------
::

    python -m stability.measure docs/examples/measured_chair_sheet.toml -o my_chair.toml
    python -m stability.critical_speed --chair my_chair.toml
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import os
import sys
from collections.abc import Sequence

from stability import __version__
from stability import chair as chair_mod
from stability.cli import OneLineErrorParser, add_json_options, check_directory, check_outputs, emit_json, run
from stability.measure.provenance import provenance_comment
from stability.measure.sheet import load_sheet
from stability.runtime.files import atomic_path

__all__ = ["main", "build_parser", "default_uncertainty_path"]


def build_parser() -> argparse.ArgumentParser:
    """The command-line parser."""
    p = OneLineErrorParser(prog="python -m stability.measure", description=__doc__.splitlines()[0])
    p.add_argument("sheet", help="measurement sheet (TOML; see docs/measure.md)")
    p.add_argument("-o", "--output", required=True, metavar="CHAIR.toml", help="chair file to write")
    p.add_argument("--uncertainty", metavar="U.toml", dest="uncertainty_file",
                   help="uncertainty file to write (default: CHAIR.uncertainty.toml beside the chair file)")
    p.add_argument("--uncertainty-file", dest="uncertainty_file", help=argparse.SUPPRESS)   # deprecated spelling
    add_json_options(p)
    return p


def default_uncertainty_path(chair_path: str) -> str:
    """``my_chair.toml`` -> ``my_chair.uncertainty.toml``."""
    root, ext = os.path.splitext(chair_path)
    return f"{root}.uncertainty{ext or '.toml'}"


def _run(args: argparse.Namespace) -> int:
    unc_path = args.uncertainty_file or default_uncertainty_path(args.output)
    check_directory(args.output, "-o")
    check_directory(unc_path, "--uncertainty")
    check_outputs({"--json-file": args.json_file}, {"sheet": args.sheet, "-o": args.output, "--uncertainty": unc_path})
    paths = [os.path.abspath(p) for p in (args.sheet, args.output, unc_path)]
    if len(set(paths)) < 3:
        raise ValueError(f"-o {args.output!r} and --uncertainty {unc_path!r} must differ from each other "
                         f"and from the sheet {args.sheet!r}")
    result = load_sheet(args.sheet)
    source = os.path.basename(args.sheet)
    chair_text = provenance_comment(result, source) + chair_mod.dumps(result.chair)
    unc_text = (f"# uncertainty of {os.path.basename(args.output)}, first order from the readings of {source}\n"
                "# (fields treated as independent: s1, s2, d1, ... share readings and are in fact correlated)\n"
                + result.uncertainty.dumps())
    with contextlib.ExitStack() as stack:  # both temporary files written before either is renamed
        tmp_chair = stack.enter_context(atomic_path(args.output))
        tmp_unc = stack.enter_context(atomic_path(unc_path))
        for tmp, text in ((tmp_chair, chair_text), (tmp_unc, unc_text)):
            with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
                fh.write(text)
    if args.json or args.json_file:
        emit_json({"stability_version": __version__, "sheet": args.sheet, "chair_file": args.output,
                   "uncertainty_file": unc_path, "chair": result.chair.name,
                   "chair_parameters": chair_mod.to_mapping(result.chair),
                   "fields": [{"field": r.field, "value": float(r.value), "std": float(r.std),
                               "readings": len(r.readings)} for r in result.provenance],
                   "notes": [str(n) for n in result.notes],
                   "uncertain_parameters": len(result.uncertainty.distributions)}, args)
        if args.json:
            return 0
    out = sys.stderr if args.json else sys.stdout
    print(f"wrote {args.output}: chair {result.chair.name!r} from {source}", file=out)
    units = {f.name: f.metadata["unit"] for f in dataclasses.fields(chair_mod.Chair)}
    for row in result.provenance:
        n = len(row.readings)
        unit = units.get(row.field, "-")
        print(f"  {row.field:<20s} {row.value:10.4g} +- {row.std:<8.2g} {'' if unit == '-' else unit:<7s}"
              f"({n} reading{'' if n == 1 else 's'})", file=out)
    for note in result.notes:
        print(f"  note: {note}", file=out)
    print(f"wrote {unc_path}: {len(result.uncertainty.distributions)} uncertain parameters", file=out)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return run(build_parser(), argv, _run, errors=(ValueError, OSError))


if __name__ == "__main__":
    sys.exit(main())
