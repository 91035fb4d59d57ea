"""The ``python -m stability.report`` command line: parse, build, print (see :mod:`stability.report`)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from stability.cli import (
    OneLineErrorParser,
    add_chair_options,
    add_driver_options,
    add_intended_speed_option,
    add_json_options,
    add_model_option,
    add_output_option,
    check_outputs,
    driver_from_args,
    emit_json,
    intended_speed_from_args,
    json_header,
    load_chair,
    load_layout,
    output_files,
    parse_speeds,
    run,
)
from stability.report import document
from stability.report.compute import compute
from stability.report.json_data import report_mapping
from stability.report.uncertainty_data import UncertaintySpec
from stability.settings import defaults as D
from stability.settings.bounds import ADVISE_SPEED_COUNT, SAMPLES
from stability.uncertainty import load_uncertainty

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
    p.add_argument("--quick", action="store_true",
                   help="quick report: page 1 (the full report's decision), the clinician sheet and the references")
    p.add_argument("--clinician", action="store_true",
                   help="one page for a clinician instead of the report: the chair after a bump at the user's "
                        "speeds, time to correct, drift, cross-slope effort, checking pin friction, tip angles")
    p.add_argument("--speeds", default=D.ADVISE_SPEEDS, metavar="SPEEDS",
                   help=f"the user's speeds for --clinician, m/s: START:STOP:STEP or a list, 0.1 to 3 m/s "
                        f"(default {D.ADVISE_SPEEDS}, the advisor's)")
    add_driver_options(p)
    add_intended_speed_option(p)
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--text", metavar="FILE", help="also write the text of every page to FILE")
    p.add_argument("--uncertainty", metavar="FILE",
                   help="TOML file of parameter distributions: a page of linear results with 95 %% intervals "
                        "and intervals next to the key numbers")
    p.add_argument("--samples", type=int, default=D.SAMPLES,
                   help=f"Monte Carlo draws with --uncertainty ({SAMPLES.text('N')}, default {D.SAMPLES})")
    p.add_argument("--seed", type=int, default=D.SEED,
                   help=f"seed of the draws with --uncertainty (>= 0, default {D.SEED})")
    p.add_argument("--compare", metavar="BASELINE",
                   help="compare with a baseline chair (a preset or a TOML chair file): its geometry overlaid and "
                        "a side-by-side table of the key numbers, computed the same way")
    add_output_option(p, ("pdf",), what="the report (a PDF; needed unless --json or --json-file is given)",
                      metavar="FILE.pdf")
    add_json_options(p)
    p.epilog = ("JSON (--json, --json-file): every number of page 1 (the decision: verdict, recommendation, predicted "
                "numbers with their ranges, costs) and of the summary page, with the text of both; without -o no "
                "PDF is drawn.\n\n" + (p.epilog or ""))
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
    from stability.layout.io import is_layout_spec

    if not (args.output or args.json or args.json_file):
        raise ValueError("-o FILE.pdf is required (or --json / --json-file for the numbers without the PDF)")
    if is_layout_spec(args.chair):
        return _layout(args)
    return _run_chair(args)


def _run_chair(args: argparse.Namespace) -> int:
    if not (args.output or args.json or args.json_file):
        raise ValueError("-o FILE.pdf is required (or --json / --json-file for the numbers without the PDF)")
    if args.text and not args.output:
        raise ValueError(f"--text {args.text!r} needs -o FILE.pdf (the text is that of the PDF's pages)")
    if args.quick and not args.clinician:
        for flag, given in (("--json", args.json), ("--json-file", args.json_file), ("--compare", args.compare),
                            ("--uncertainty", args.uncertainty)):
            if given:
                raise ValueError(f"{flag} needs the full report: --quick is page 1, the clinician sheet and the "
                                 "references (drop --quick)")
    outputs = {"-o": args.output, "--text": args.text, "--json-file": args.json_file}
    check_outputs(outputs, {"--chair": args.chair, "--uncertainty": args.uncertainty, "--compare": args.compare})
    if args.uncertainty is None and (args.samples != D.SAMPLES or args.seed != D.SEED):
        raise ValueError("--samples and --seed need --uncertainty FILE")
    spec = None
    if args.uncertainty is not None:
        spec = UncertaintySpec(args.uncertainty, load_uncertainty(args.uncertainty), args.samples, args.seed)
    c = load_chair(args.chair, args.set)
    if args.clinician:
        return _clinician(args, c, outputs)
    if args.speeds != D.ADVISE_SPEEDS:
        raise ValueError(f"--speeds {args.speeds!r} needs --clinician (the report's speeds are its own)")
    baseline = None if args.compare is None else load_chair(args.compare, [])
    driver = driver_from_args(args)      # --reaction-time or the file's [user]: the decision weighs it, page 1 says it
    intended = intended_speed_from_args(args, driver)
    with output_files(outputs) as tmp:
        res = None
        if args.output:
            res = document.build(c, tmp["-o"], model=args.model, brief=args.quick, progress=not args.no_progress,
                                 uncertainty=spec, baseline=baseline, driver=driver, intended_speed=intended)
            data = res.data
        else:
            data = compute(c, args.model, progress=not args.no_progress, uncertainty=spec, baseline=baseline,
                           driver=driver, intended_speed=intended)
        if args.text:
            with open(tmp["--text"], "w", encoding="utf-8") as fh:
                assert res is not None          # --text needs -o (checked above)
                fh.write(res.text() + "\n")
        if args.json or args.json_file:
            options = {"quick": bool(args.quick), "uncertainty": args.uncertainty,
                       "samples": args.samples if spec else None, "seed": args.seed if spec else None,
                       "compare": args.compare, "output": args.output,
                       "reaction_time_s": None if driver is None else driver.reaction_time_s,
                       "intended_speed_m_s": data.advice.intended_speed_m_s}
            emit_json({**json_header(c, args.model, options), **report_mapping(data)}, args,
                      write_to=tmp.get("--json-file"))
    if res is not None:
        print(f"wrote {args.output} ({len(res.pages)} pages, {res.seconds:.1f} s)" +
              (f" and {args.text}" if args.text else ""), file=sys.stderr if args.json else sys.stdout)
    if args.json_file:
        print(f"wrote {args.json_file}", file=sys.stderr)
    return 0


def _layout(args: argparse.Namespace) -> int:
    """A wheel layout: its own report (:mod:`stability.report.layout_report`), forward and in reverse; with
    ``--clinician`` the short form's one-page sheet from the layout's model, with ``--quick`` the decision and that
    sheet, with ``--compare`` a comparison page (the baseline a layout or a short-form chair as a layout), with
    ``--uncertainty`` a page of the linear results' intervals over the file's layout fields."""
    from stability import __version__
    from stability.report.layout_report import compute_layout_report, write_layout_report

    outputs = _check_layout_args(args)
    layout = load_layout(args.chair, args.set)
    if args.clinician:
        from stability.report.layout_clinician import layout_clinician_sheet

        driver = driver_from_args(args)      # --reaction-time or the file's [user]: the sheet's driver line
        return _clinician(args, layout, outputs, lambda speeds: layout_clinician_sheet(layout, speeds, driver),
                          signed=True)
    if args.speeds != D.ADVISE_SPEEDS:
        raise ValueError(f"--speeds {args.speeds!r} needs --clinician (the report's speeds are its own)")
    baseline = None if args.compare is None else _layout_baseline(args.compare)
    unc = None
    if args.uncertainty is not None:
        from stability.advise.layout_axes import load_layout_uncertainty

        unc = load_layout_uncertainty(args.uncertainty, layout)
    driver = driver_from_args(args)       # --reaction-time or the file's [user]: the layout's driver limit
    intended = intended_speed_from_args(args, driver)
    r = compute_layout_report(layout, progress=not args.no_progress, quick=args.quick, baseline=baseline,
                              uncertainty=unc, samples=args.samples, seed=args.seed, driver=driver,
                              intended_speed=intended)
    n = 0
    with output_files(outputs) as tmp:
        if args.output:
            n = write_layout_report(r, tmp["-o"])
        if args.text:
            with open(tmp["--text"], "w", encoding="utf-8") as fh:
                fh.write(r.text() + "\n")
        if args.json or args.json_file:
            import dataclasses

            head = {"stability_version": __version__, "chair": layout.name,
                    "chair_parameters": dataclasses.asdict(layout), "model": "exact",
                    "options": {"output": args.output, "quick": bool(args.quick), "compare": args.compare,
                                "uncertainty": args.uncertainty, "samples": args.samples if unc else None,
                                "seed": args.seed if unc else None,
                                "reaction_time_s": None if driver is None else driver.reaction_time_s,
                                "intended_speed_m_s": r.intended_speed_m_s},
                    "schema": "stability.report.layout/1"}
            emit_json({**head, **r.data}, args, write_to=tmp.get("--json-file"))
    if args.output:
        print(f"wrote {args.output} ({n} pages)" + (f" and {args.text}" if args.text else ""),
              file=sys.stderr if args.json else sys.stdout)
    return 0


def _check_layout_args(args: argparse.Namespace) -> dict:
    """The options a layout's report refuses, each in one line; the output files."""
    if args.text and not args.output:
        raise ValueError(f"--text {args.text!r} needs -o FILE.pdf (the text is that of the PDF's pages)")
    outputs = {"-o": args.output, "--text": args.text, "--json-file": args.json_file}
    check_outputs(outputs, {"--chair": args.chair, "--uncertainty": args.uncertainty, "--compare": args.compare})
    if args.model != "exact":
        raise ValueError(f"--model {args.model} is invalid for a wheel layout; valid values: exact (the layout's "
                         "equations are the exact model's)")
    if args.uncertainty is None and (args.samples != D.SAMPLES or args.seed != D.SEED):
        raise ValueError("--samples and --seed need --uncertainty FILE")
    if args.quick and not args.clinician:
        for flag, given in (("--compare", args.compare), ("--uncertainty", args.uncertainty)):
            if given:
                raise ValueError(f"{flag} needs the full report: --quick is the decision and the clinician sheet "
                                 "(drop --quick)")
    return outputs


def _layout_baseline(spec: str):
    """``--compare`` next to a layout: a layout, or a short-form chair as a layout
    (:meth:`stability.layout.Layout.from_chair`)."""
    from stability.layout.io import is_layout_spec, resolve_layout
    from stability.layout.model import Layout

    if is_layout_spec(spec):
        return resolve_layout(spec)
    return Layout.from_chair(load_chair(spec, []))


def _clinician(args: argparse.Namespace, c, outputs: dict, make_sheet=None, signed: bool = False) -> int:
    """``--clinician``: the one-page sheet of ``c`` (a chair, or a layout with its ``make_sheet(speeds)``; a
    layout's speeds may be negative: ``signed``, their magnitudes in range)."""
    from stability.report.clinician_sheet import clinician_sheet, sheet_figure
    from stability.report.document import figure_texts
    from stability.runtime.files import write_pdf

    for flag, given in (("--compare", args.compare), ("--uncertainty", args.uncertainty), ("--json", args.json),
                        ("--json-file", args.json_file), ("--quick", args.quick)):
        if given:
            raise ValueError(f"{flag} cannot be combined with --clinician (a one-page sheet at full resolution)")
    if args.intended_speed is not None:
        raise ValueError("--intended-speed is for the report's decision (the advisor's limit with a driver); "
                         "--clinician has no decision: drop it, the sheet names the speeds this user cannot hold")
    if not args.output:
        raise ValueError("--clinician needs -o FILE.pdf")
    speeds = tuple(float(u) for u in parse_speeds(args.speeds, max_count=ADVISE_SPEED_COUNT, signed=signed))
    mags = [abs(u) for u in speeds]
    if not speeds or min(mags) < 0.1 or max(mags) > 3.0:
        raise ValueError(f"--speeds {args.speeds!r} is invalid; valid range: "
                         + ("0.1 <= |U| <= 3 m/s (negative: reverse)" if signed else "0.1 to 3 m/s"))
    sheet = (clinician_sheet(c, speeds, args.model, driver_from_args(args)) if make_sheet is None
             else make_sheet(speeds))
    texts: list[str] = []

    def figs():
        fig = sheet_figure(sheet, args.model)
        texts.extend(figure_texts(fig))
        yield fig

    with output_files(outputs) as tmp:
        write_pdf(figs(), tmp["-o"], title=f"stability clinician sheet: {c.name} ({args.model} model)",
                  outline=[("for the clinician", 0)])
        if args.text:
            with open(tmp["--text"], "w", encoding="utf-8") as fh:
                fh.write("=== page 1: for the clinician\n" + "\n".join(texts) + "\n")
    print(f"wrote {args.output} (1 page)" + (f" and {args.text}" if args.text else ""))
    return 0
