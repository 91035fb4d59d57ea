"""The ``python -m stability.report`` command line: parse, build, print (see :mod:`stability.report`)."""

from __future__ import annotations

import argparse
from collections.abc import Sequence

from .. import defaults as D
from ..cli import (
    OneLineErrorParser,
    add_chair_options,
    add_model_option,
    add_output_option,
    check_outputs,
    load_chair,
    output_files,
    run,
)
from ..linear.intervals import MAX_SAMPLES
from ..uncertainty import load_uncertainty
from . import document
from .uncertainty_data import UncertaintySpec

__all__ = ["build_parser", "main"]

_DESCRIPTION = "``python -m stability.report``: a multi-page PDF report on one chair."


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m stability.report``.

    Returns
    -------
    argparse.ArgumentParser
    """
    p = OneLineErrorParser(prog="python -m stability.report", description=_DESCRIPTION)
    add_chair_options(p)
    add_model_option(p)
    p.add_argument("--quick", action="store_true", help="coarse version in seconds")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--text", metavar="FILE", help="also write the text of every page to FILE")
    p.add_argument("--uncertainty", metavar="FILE",
                   help="TOML file of parameter distributions: a page of linear results with 95 %% intervals "
                        "and intervals next to the key numbers")
    p.add_argument("--samples", type=int, default=D.SAMPLES,
                   help=f"Monte Carlo draws with --uncertainty (1 to {MAX_SAMPLES}, default {D.SAMPLES})")
    p.add_argument("--seed", type=int, default=D.SEED,
                   help=f"seed of the draws with --uncertainty (>= 0, default {D.SEED})")
    p.add_argument("--compare", metavar="BASELINE",
                   help="compare with a baseline chair (a preset or a TOML chair file): its geometry overlaid and "
                        "a side-by-side table of the key numbers, computed the same way")
    add_output_option(p, ("pdf",), what="the report (a PDF)", required=True, metavar="FILE.pdf")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.report``.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (2 on bad input, with one line on stderr).
    """
    return run(build_parser(), argv, _run, errors=(ValueError, OSError))


def _run(args: argparse.Namespace) -> int:
    check_outputs({"-o": args.output, "--text": args.text}, {"--chair": args.chair, "--uncertainty": args.uncertainty,
                                                           "--compare": args.compare})
    if args.uncertainty is None and (args.samples != D.SAMPLES or args.seed != D.SEED):
        raise ValueError("--samples and --seed need --uncertainty FILE")
    spec = None
    if args.uncertainty is not None:
        spec = UncertaintySpec(args.uncertainty, load_uncertainty(args.uncertainty), args.samples, args.seed)
    c = load_chair(args.chair, args.set)
    baseline = None if args.compare is None else load_chair(args.compare, [])
    with output_files({"-o": args.output, "--text": args.text}) as tmp:
        res = document.build(c, tmp["-o"], model=args.model, quick=args.quick, progress=not args.no_progress,
                             uncertainty=spec, baseline=baseline)
        if args.text:
            with open(tmp["--text"], "w", encoding="utf-8") as fh:
                fh.write(res.text() + "\n")
    print(f"wrote {args.output} ({len(res.pages)} pages, {res.seconds:.1f} s)" +
          (f" and {args.text}" if args.text else ""))
    return 0
