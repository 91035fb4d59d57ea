"""``python -m stability.compare A B [C ...]``: which chair is more stable, by how much on each measure, and why.

A, B, ... are presets or chair TOML files; the first is the reference.
Prints growth rates (and times to double) at a list of speeds, the
locked-caster and zero-width critical speeds, the understeer coefficient,
the verdict against the reference on each measure, and the effect of each
differing parameter applied alone to the reference.

Examples
--------
::

    python -m stability.compare ej-premier revised ej-premier-front-caster
    python -m stability.compare ej-premier ej-premier --set 2:trail=0.06 --json
    python -m stability.compare mine.toml revised --uncertainty mine.unc.toml --uncertainty - -o cmp.pdf
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from stability.chair import Chair
from stability.cli import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_driver_options,
    add_json_options,
    add_model_option,
    add_output_option,
    announce_written,
    check_outputs,
    driver_from_args,
    emit_json,
    json_header,
    load_chair,
    load_layout,
    output_files,
    parse_speeds,
    run,
)
from stability.compare.compute import DEFAULT_SPEEDS, compare, solves_per_sample, unique_labels
from stability.compare.text import comparison_dict, format_comparison
from stability.linear.batch import check_eigen_work
from stability.settings import defaults as D
from stability.settings.bounds import SIGNED_SPEED
from stability.uncertainty import Uncertainty, load_uncertainty

__all__ = ["main", "build_parser"]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m stability.compare``."""
    p = OneLineErrorParser(prog="python -m stability.compare", description=(__doc__ or "").split("\n\n")[0])
    p.add_argument("chairs", nargs="+", metavar="CHAIR",
                   help="preset name or TOML file (two or more; the first is the reference)")
    p.add_argument("--set", action="append", default=[], metavar="K:NAME=VALUE",
                   help="override a field of the K-th chair (1-based; repeatable), e.g. 2:trail=0.06")
    add_model_option(p)
    p.add_argument("--speeds", default=D.speeds_text(DEFAULT_SPEEDS),
                   help=f"speeds of the growth-rate table, START:STOP:STEP or a list (m/s; default "
                        f"{D.speeds_text(DEFAULT_SPEEDS)})")
    p.add_argument("--max-speed", type=float, default=D.MAX_SPEED,
                   help=f"upper end of the critical-speed search (m/s, default {D.MAX_SPEED:g})")
    p.add_argument("--uncertainty", action="append", default=[], metavar="FILE",
                   help="uncertainty TOML file, one per chair in order ('-' for none): intervals and "
                        "whether each difference exceeds the uncertainty")
    p.add_argument("--samples", type=int, default=D.SAMPLES, help=f"Monte Carlo draws per chair (default {D.SAMPLES})")
    p.add_argument("--seed", type=int, default=D.SEED, help=f"seed of the draws (default {D.SEED})")
    p.add_argument("--level", type=float, default=D.COVERAGE, help=f"interval coverage (default {D.COVERAGE:g})")
    p.add_argument("--pairing", default="shared", choices=["shared", "independent"],
                   help="shared: tables of the same name get the same draw in every chair (the same unknown); "
                        "independent: separate seeds (default shared)")
    p.add_argument("--nonlinear", action="store_true",
                   help="also the critical impulse by simulation (slower; states the push convention)")
    add_driver_options(p)
    add_json_options(p)
    add_output_option(p, FIGURE_FORMATS, what="the figures (a PDF, one figure a page; a .png or .svg holds the "
                      "first, the growth rates against speed)", aliases=("--pdf",))
    return p


def _chairs(specs: Sequence[str], assignments: Sequence[str]) -> tuple[list[Chair], list[str]]:
    per: list[list[str]] = [[] for _ in specs]
    for a in assignments:
        k, sep, rest = a.partition(":")
        if not sep or not k.strip().isdigit() or not 1 <= int(k) <= len(specs):
            raise ValueError(f"--set {a!r} is invalid; expected K:NAME=VALUE with K from 1 to {len(specs)} "
                             "(the chair's position)")
        per[int(k) - 1].append(rest)
    chairs, names = [], []
    for i, (spec, sets) in enumerate(zip(specs, per, strict=True)):
        try:
            c = load_chair(spec, sets)
        except ValueError as exc:
            raise ValueError(f"chair {i + 1} ({spec!r}): {str(exc).splitlines()[0]}") from None
        chairs.append(c)
        modified = bool(sets) and c.name == load_chair(spec, []).name  # replace() may already rename it
        names.append(c.name + (f" ({', '.join(sets)})" if modified else ""))
    return chairs, names


def _uncertainties(files: Sequence[str], n: int) -> list[Uncertainty | None] | None:
    if not files:
        return None
    if len(files) != n:
        raise ValueError(f"--uncertainty given {len(files)} times for {n} chairs; valid: once per chair "
                         "in order ('-' for a chair without one)")
    return [None if f == "-" else load_uncertainty(f) for f in files]


def _driver(args: argparse.Namespace):
    """The user of ``--reaction-time``, else of the reference (first) chair file's ``[user]``: one user compared
    on every chair."""
    return driver_from_args(argparse.Namespace(reaction_time=args.reaction_time, chair=args.chairs[0]))


def _run(args: argparse.Namespace) -> int:
    if len(args.chairs) < 2:
        raise ValueError(f"CHAIR: {len(args.chairs)} given ({args.chairs[0]!r}); valid: at least two chairs")
    inputs = {f"CHAIR {i + 1}": s for i, s in enumerate(args.chairs)}
    inputs.update({f"--uncertainty {i + 1}": f for i, f in enumerate(args.uncertainty) if f != "-"})
    check_outputs({"--json-file": args.json_file, "-o": args.output}, inputs)
    if args.uncertainty and len(args.uncertainty) != len(args.chairs):
        raise ValueError(f"--uncertainty given {len(args.uncertainty)} times for {len(args.chairs)} chairs; "
                         "valid: once per chair in order ('-' for a chair without one)")
    from stability.layout.io import is_layout_spec

    signed = parse_speeds(args.speeds, max_count=200, signed=True)
    if any(is_layout_spec(s) for s in args.chairs) or bool((signed < 0).any()):
        return _run_layouts(args, signed)
    speeds = parse_speeds(args.speeds, max_count=200)
    chairs, names = _chairs(args.chairs, args.set)
    uncs = _uncertainties(args.uncertainty, len(chairs))
    n_uncertain = sum(u is not None for u in uncs) if uncs else 0
    check_eigen_work("--samples", args.samples, solves_per_sample(n_uncertain, len(speeds)))
    driver = _driver(args)
    result = compare(chairs, labels=unique_labels(names), model=args.model, speeds=speeds.tolist(),
                     max_speed=args.max_speed, uncertainties=uncs, samples=args.samples, seed=args.seed,
                     level=args.level, pairing=args.pairing, nonlinear=args.nonlinear,
                     reaction_time=None if driver is None else driver.reaction_time_s)
    options = {"speeds_m_s": [float(x) for x in speeds], "max_speed_m_s": args.max_speed, "set": args.set,
               "uncertainty": args.uncertainty, "samples": args.samples, "seed": args.seed,
               "level": args.level, "pairing": args.pairing, "nonlinear": args.nonlinear,
               "reaction_time_s": None if driver is None else driver.reaction_time_s}
    _write_outputs(result, args, lambda: comparison_dict(result, json_header(chairs[0], args.model, options)))
    if not args.json:
        print(format_comparison(result))
    return 0


def _write_outputs(result, args: argparse.Namespace, document) -> None:
    """The comparison's figures into ``-o`` (a PDF: every figure; a .png or .svg: the growth rates) and its JSON
    (``document()``, built only when asked), renamed together: all or none."""
    with output_files({"-o": args.output, "--json-file": args.json_file}) as tmp:
        n_figs = 0
        if args.output:
            from stability.compare.plots import comparison_figures
            from stability.runtime.files import save_figure, write_pdf  # matplotlib only when figures are asked for

            figs = comparison_figures(result)
            n_figs = len(figs)
            title = f"stability compare: {' vs '.join(result.labels)}"
            if args.output.lower().endswith(".pdf"):
                write_pdf(figs, tmp["-o"], title=title, close=False)
            else:
                save_figure(figs[0], tmp["-o"], title=title)
        if args.json or args.json_file:
            emit_json(document(), args, write_to=tmp.get("--json-file"))
    if args.output:
        only_first = n_figs > 1 and not args.output.lower().endswith(".pdf")
        print(f"wrote {args.output}" + (" (the growth rates; the effects figures are in the PDF: -o FILE.pdf)"
                                        if only_first else ""), file=sys.stderr)
    announce_written(args.json_file)


def _run_layouts(args: argparse.Namespace, speeds) -> int:
    """Any chair a wheel layout, or a negative speed: every chair compared as a layout
    (:func:`stability.compare.layouts.compare_layouts`)."""
    import dataclasses

    from stability import __version__
    from stability.compare.layouts import compare_layouts

    if args.model != "exact":
        raise ValueError(f"--model {args.model} is invalid for wheel layouts; valid values: exact (the layout's "
                         "equations are the exact model's)")
    if args.reaction_time is not None:
        raise ValueError("--reaction-time is not compared across wheel layouts yet; python -m "
                         "stability.critical_speed --chair LAYOUT --reaction-time S gives each layout's limits")
    if not all(SIGNED_SPEED.holds(u) for u in speeds):
        raise ValueError(f"--speeds {args.speeds!r} is invalid for wheel layouts; valid range: "
                         f"{SIGNED_SPEED.text('speed')} (negative: reverse)")
    per: list[list[str]] = [[] for _ in args.chairs]
    for a in args.set:
        k, sep, rest = a.partition(":")
        if not sep or not k.strip().isdigit() or not 1 <= int(k) <= len(args.chairs):
            raise ValueError(f"--set {a!r} is invalid; expected K:NAME=VALUE with K from 1 to {len(args.chairs)} "
                             "(the chair's position)")
        per[int(k) - 1].append(rest)
    layouts, names = [], []
    for i, (spec, sets) in enumerate(zip(args.chairs, per, strict=True)):
        try:
            layouts.append(load_layout(spec, sets))
        except ValueError as exc:
            raise ValueError(f"chair {i + 1} ({spec!r}): {str(exc).splitlines()[0]}") from None
        names.append(layouts[-1].name + (f" ({', '.join(sets)})" if sets else ""))
    uncs = None
    if args.uncertainty:                  # each file's tables name that layout's axes (stability.advise.layout_axes)
        from stability.advise.layout_axes import load_layout_uncertainty

        uncs = []
        for i, (f, lay) in enumerate(zip(args.uncertainty, layouts, strict=True)):
            try:
                uncs.append(None if f == "-" else load_layout_uncertainty(f, lay))
            except ValueError as exc:
                raise ValueError(f"--uncertainty {i + 1} ({f!r}): {str(exc).splitlines()[0]}") from None
    result = compare_layouts(layouts, labels=unique_labels(names), speeds=[float(u) for u in speeds],
                             nonlinear=args.nonlinear, uncertainties=uncs, samples=args.samples, seed=args.seed,
                             level=args.level, pairing=args.pairing)
    given = uncs is not None
    options = {"speeds_m_s": [float(x) for x in speeds], "max_speed_m_s": result.max_speed, "set": args.set,
               "uncertainty": args.uncertainty, "samples": args.samples if given else None,
               "seed": args.seed if given else None, "level": args.level if given else None,
               "pairing": args.pairing if given else None, "nonlinear": args.nonlinear, "layouts": True,
               "reaction_time_s": None}
    header = {"stability_version": __version__, "chair": layouts[0].name,
              "chair_parameters": dataclasses.asdict(layouts[0]), "model": "layout", "options": options}
    _write_outputs(result, args, lambda: comparison_dict(result, header))
    if not args.json:
        print(format_comparison(result))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.compare``; returns the exit status (2 on bad input)."""
    return run(build_parser(), argv, _run)


if __name__ == "__main__":
    sys.exit(main())
