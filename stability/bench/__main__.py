"""``python -m stability.bench``: the virtual test bench (ISO 7176-2 wheel lift, ISO 7176-3 braking) for a chair."""

from __future__ import annotations

import argparse
import dataclasses
import sys
from collections.abc import Sequence

from stability import cli
from stability.bench.matrix import Drive, run_bench
from stability.bench.text import bench_text
from stability.settings.drive import BENCH_CHAIR, DRIVE_SETTINGS, drive_flag

__all__ = ["main", "build_parser"]


def build_parser() -> argparse.ArgumentParser:
    """The command-line parser (one option per drive setting, from :data:`DRIVE_SETTINGS`)."""
    p = cli.OneLineErrorParser(prog="python -m stability.bench", description=(__doc__ or "").splitlines()[0])
    p.add_argument("--chair", default=BENCH_CHAIR,
                   help="a layout preset (mid-wheel-drive, power-fwd-base, power-rwd-base), a [[wheel]] chair file, "
                        "or a chair in the short form (default mid-wheel-drive)")
    defaults = Drive()
    for name, (_, unit, (lo, hi), text) in DRIVE_SETTINGS.items():
        p.add_argument(drive_flag(name), type=float, default=getattr(defaults, name), metavar="X",
                       help=f"{text}, {unit or 'no unit'} ({lo:g} to {hi:g}; default {getattr(defaults, name):g})")
    cli.add_json_options(p)
    cli.add_output_option(p, ("pdf",), what="one page per manoeuvre family (starts, stops, turns) as a PDF")
    return p


def _body(a: argparse.Namespace) -> int:
    from stability.layout.io import resolve_layout

    outputs = {"--json-file": a.json_file, "-o": a.output}
    cli.check_outputs(outputs, {"--chair": a.chair})
    values = {}
    for name, (_, unit, (lo, hi), _) in DRIVE_SETTINGS.items():
        v = getattr(a, drive_flag(name)[2:].replace("-", "_"))
        if not (lo <= v <= hi):
            raise ValueError(f"{drive_flag(name)} {v!r} is invalid; valid range: {lo:g} to {hi:g} {unit}".rstrip())
        values[name] = v
    drive = dataclasses.replace(Drive(), **values)
    layout = resolve_layout(a.chair)
    result = run_bench(layout, drive)
    with cli.output_files(outputs) as tmp:
        if a.json or a.json_file:
            from stability import __version__

            cli.emit_json({"stability_version": __version__, "chair": layout.name, **result.to_mapping()}, a,
                          write_to=tmp.get("--json-file"))
        if not a.json:
            print(bench_text(result))
        if a.output:
            from stability.bench.plots import bench_pages
            from stability.runtime.files import write_pdf

            write_pdf(bench_pages(result), tmp["-o"], title=f"virtual bench: {layout.name}")
    for path in outputs.values():
        if path:
            print(f"wrote {path}", file=sys.stderr)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return cli.run(build_parser(), argv, _body)


if __name__ == "__main__":
    raise SystemExit(main())
