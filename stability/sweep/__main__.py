"""``python -m stability.sweep SPEC.toml -o RESULTS.parquet``: a design sweep under uncertainty, resumable.

One row per (design, draw, speed) with the chair's fields and every measure,
in Parquet (needs pyarrow: ``pip install 'stability[scale]'``) or CSV (by the
suffix).  Also writes ``RESULTS.summary.json`` (the best designs by the
conservative end of each measure's interval over the draws, printed too) and
``RESULTS.pdf`` (each measure over the first two grid axes).  Chunks are
written as they finish; after an interruption ``--resume`` computes only the
missing ones, and the result is the same file as an uninterrupted run's.
Spec format and JSON Schema: docs/sweep.md, ``--schema``.

Examples
--------
::

    python -m stability.sweep docs/examples/sweep.toml -o sweep.csv
    python -m stability.sweep docs/examples/sweep.toml -o sweep.csv --resume
    python -m stability.sweep docs/examples/sweep.toml -o sweep.parquet --dask local:2
"""

from __future__ import annotations

import argparse
import contextlib
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from stability.cli import (
    OneLineErrorParser,
    add_json_options,
    announce_written,
    check_outputs,
    emit_json,
    output_files,
    run,
)
from stability.runtime.files import atomic_write_text, write_pdf
from stability.runtime.progress import is_quiet
from stability.sweep.cluster import dask_mapper, parse_dask
from stability.sweep.measures import n_chunks
from stability.sweep.plot import measure_figures
from stability.sweep.run import check_output_format, read_rows, run_sweep, summary, summary_text
from stability.sweep.spec import SCHEMA, load_spec

__all__ = ["main", "build_parser"]


def build_parser() -> argparse.ArgumentParser:
    """The command-line parser."""
    p = OneLineErrorParser(prog="python -m stability.sweep", description=__doc__.splitlines()[0])
    p.add_argument("spec", nargs="?", help="sweep spec (TOML; see docs/sweep.md)")
    p.add_argument("-o", "--output", metavar="RESULTS", help="results file: .parquet or .csv")
    p.add_argument("--resume", action="store_true", help="keep the finished chunks of an interrupted run")
    p.add_argument("--schema", action="store_true", help="print the spec's JSON Schema and exit")
    p.add_argument("--dask", metavar="ADDRESS", help="run the chunks on a Dask cluster: a scheduler address "
                   "(tcp://host:8786) or local:N for N local process workers (needs the [scale] extra)")
    add_json_options(p)
    return p


def _progress(done: int, total: int, rows: int, seconds: float) -> None:
    if is_quiet():
        return
    rate = rows / seconds if seconds > 0 else 0.0
    left = (total - done) * seconds / max(done, 1) if rate else float("nan")
    print(f"sweep: {done}/{total} chunks, {rate:.3g} rows/s, about {left:.0f} s left", file=sys.stderr)


def _run(args: argparse.Namespace) -> int:
    if args.schema:
        print(json.dumps(SCHEMA, indent=2))
        return 0
    if not args.spec or not args.output:
        raise ValueError("spec and -o RESULTS are required (or --schema); valid: SPEC.toml -o RESULTS.parquet|.csv")
    out = Path(args.output)
    if out.suffix.lower() not in (".parquet", ".csv"):
        raise ValueError(f"-o {args.output!r} is invalid; valid: a .parquet or .csv file")
    summary_path, pdf_path = out.with_name(out.stem + ".summary.json"), out.with_suffix(".pdf")
    check_outputs({"-o": args.output, "summary": str(summary_path), "figures": str(pdf_path),
                   "--json-file": args.json_file}, {"spec": args.spec})
    if args.dask:
        parse_dask(args.dask)
    spec = load_spec(args.spec)
    check_output_format(out)
    print(f"sweep: {spec.designs} design(s) x {spec.draws} draw(s) x {len(spec.speeds)} speed(s) = {spec.rows} "
          f"rows in {n_chunks(spec)} chunk(s); measures {', '.join(spec.measures)}", file=sys.stderr)
    with contextlib.ExitStack() as stack:
        mapper = stack.enter_context(dask_mapper(spec, args.dask)) if args.dask else None
        run_sweep(spec, out, resume=args.resume, progress=_progress, mapper=mapper)
    data = _read(out)
    s = summary(spec, data)
    doc = {"spec": spec.to_dict(), **s}
    # the summary, the figures and --json-file renamed together (all or none); the rows file is written chunk by
    # chunk, so that --resume can go on after an interruption
    with output_files({"summary": str(summary_path), "figures": str(pdf_path), "--json-file": args.json_file}) as tmp:
        atomic_write_text(tmp["summary"], json.dumps(doc, indent=2) + "\n")
        write_pdf(measure_figures(spec, data), tmp["figures"], title=f"sweep of {spec.chair.name}")
        if args.json or args.json_file:
            emit_json(doc, args, write_to=tmp.get("--json-file"))
    announce_written(args.json_file)
    if not args.json:
        print(summary_text(spec, s))
    print(f"wrote {out}, {summary_path}, {pdf_path}", file=sys.stderr)
    return 0


def _read(out: Path) -> dict[str, list]:
    if out.suffix.lower() == ".parquet":
        import pyarrow.parquet as pq

        return {k: list(v) for k, v in pq.read_table(out).to_pydict().items()}
    return read_rows(out.read_text())


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return run(build_parser(), argv, _run, errors=(ValueError, OSError))


if __name__ == "__main__":
    sys.exit(main())
