"""Command line: ``python -m stability.simulate --chair ej-premier --speed 0.75 --json``.

A layout (``--chair mid-wheel-drive``, a ``[[wheel]]`` file) runs the layout simulator
(:func:`stability.simulate.layout.simulate_layout`): ``python -m stability.simulate --chair mid-wheel-drive
--reverse --eta0 180 --beta0 180``.
"""

from __future__ import annotations

import argparse
import gc
import sys
from collections.abc import Sequence
from typing import Any

from stability.cli import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_chair_options,
    add_json_options,
    add_output_option,
    add_run_options,
    check_outputs,
    check_work,
    emit_json,
    json_header,
    load_chair,
    load_layout,
    output_files,
    run,
    run_from_args,
)
from stability.plotting.responses import plot_result
from stability.settings.run import RunSpec
from stability.simulate.api import simulate
from stability.simulate.options import ADAPTIVE_SAMPLE

__all__ = ["main", "build_parser"]


#: The run settings the simulate command offers (every RunSpec field but the tire fits' policy, which follows
#: --tire-range); their options, defaults and ranges are generated from the RunSpec's table.
RUN_OPTIONS = ("speed", "push_force", "push_duration", "tire_push_force", "lateral_velocity", "eta0_deg", "beta0_deg",
               "scheme", "model", "cross_slope_deg", "grade_deg", "casters", "friction_law", "horizon", "dt", "sample",
               "stop_on_warnings", "rtol", "atol", "reverse")


def build_parser() -> argparse.ArgumentParser:
    ap = OneLineErrorParser(prog="python -m stability.simulate",
                            description="Simulate a wheelchair disturbed from straight motion (thesis chapter 7). "
                                        "The run's settings and their valid ranges are the API's RunSpec's.")
    add_chair_options(ap)
    add_run_options(ap, RUN_OPTIONS)
    ap.add_argument("--csv", metavar="FILE", help="write the time histories to a CSV file")
    add_output_option(ap, FIGURE_FORMATS, what="a plot of the run", aliases=("--plot",))
    add_json_options(ap)
    return ap


#: Rows of --csv/--json output: a CSV row of 32 columns is about 0.7 kB, so 1e5 rows = some 70 MB.
MAX_OUTPUT_ROWS = 100_000


def _check_output(args: argparse.Namespace, run: RunSpec) -> None:
    """The output's size (rows of --csv/--json) within :data:`MAX_OUTPUT_ROWS`, before any work."""
    step = run.fixed_step if run.scheme == "wchair" else ADAPTIVE_SAMPLE
    interval = run.sample if run.sample is not None else step
    if args.csv or args.json or args.json_file:
        check_work(f"--horizon {run.horizon:g} s every {interval:g} s (output rows)", run.horizon / interval,
                   MAX_OUTPUT_ROWS, f"give --sample >= {run.horizon / MAX_OUTPUT_ROWS:.2g} s")


def _run_layout(args: argparse.Namespace, run_spec: RunSpec) -> int:
    """A chair in the ``[[wheel]]`` form or a layout preset: :func:`stability.simulate.layout.simulate_layout`
    (casters on the left start at ``--eta0``, on the right at ``--beta0``); ``--csv`` and ``-o`` as the short
    form's (the casters named by :attr:`stability.layout.Layout.caster_labels`)."""
    from stability import __version__
    from stability.plotting.responses import plot_layout_run
    from stability.simulate.layout import simulate_layout

    layout = load_layout(args.chair, args.set)      # --set: the short form's only (the one line says so)
    res = simulate_layout(layout, None, run_spec)
    labels = layout.caster_labels
    with output_files({"--csv": args.csv, "-o": args.output, "--json-file": args.json_file}) as tmp:
        if args.csv:
            res.to_csv(tmp["--csv"], labels)
        if args.output:
            plot_layout_run(res, labels, tmp["-o"])
        if args.json or args.json_file:
            emit_json({"stability_version": __version__, "chair": res.layout, "model": "exact",
                       "options": run_spec.to_dict(), **res.to_mapping()}, args, write_to=tmp.get("--json-file"))
    _announce(args, res)
    return 0


def _announce(args: argparse.Namespace, res: Any) -> None:
    """The summary and the outputs written (all renamed together by :func:`output_files`)."""
    if args.json_file:
        print(f"wrote {args.json_file}", file=sys.stderr)
    if not args.json:
        print(res.summary())
        for path in (args.csv, args.output):
            if path:
                print(f"wrote {path}")


def _run_cli(args: argparse.Namespace) -> int:
    from stability.layout.io import is_layout_spec

    outputs = {"--csv": args.csv, "-o": args.output, "--json-file": args.json_file}
    check_outputs(outputs, {"--chair": args.chair})
    # the tire policy from --tire-range: raise stops a run; warn and clamp clamp the fits at the data's edge and
    # count the warnings, as program WCHAIR
    policy = "raise" if args.tire_range == "raise" else RunSpec().out_of_range
    run_spec = run_from_args(args, RUN_OPTIONS, out_of_range=policy)
    _check_output(args, run_spec)
    if is_layout_spec(args.chair):
        return _run_layout(args, run_spec)
    c = load_chair(args.chair, args.set)
    res = simulate(c, run=run_spec.replace(sample=None))     # every step: the level times exact; --sample resamples
    levels = (0.5, 1.0)
    times = [res.first_time_abs_yaw_rate(v) for v in levels]
    out = res.resample(run_spec.sample) if run_spec.sample is not None else res
    with output_files({"--csv": args.csv, "-o": args.output, "--json-file": args.json_file}) as tmp:
        if args.csv:
            out.to_csv(tmp["--csv"])
        if args.output:
            plot_result(res, tmp["-o"])
        if args.json or args.json_file:
            d = {**json_header(c, run_spec.model, run_spec.to_dict()), **out.to_dict()}
            d["yaw_rate_levels_rad_s"] = list(levels)
            d["first_time_at_level_s"] = times
            emit_json(d, args, write_to=tmp.get("--json-file"))
    _announce(args, res)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Command-line entry point; returns the exit status (2 on bad input)."""
    return run(build_parser(), argv, _run_cli, errors=(ValueError, OSError))


if __name__ == "__main__":  # pragma: no cover
    # one run in a process that ends with it: no cyclic collection (its passes over numpy's, matplotlib's and numba's
    # objects after a first use's compile and while the plot is drawn cost a few tenths of a second of CPU, for
    # garbage the exit frees; issue 36)
    gc.disable()
    sys.exit(main())
