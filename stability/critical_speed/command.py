"""``python -m stability.critical_speed``: how stable is this chair, and at which speeds?

Prints, for one chair and one model variant, the static loads and tire
stiffnesses, the zero-width (locked casters) understeer coefficient and
critical speed (eqs 5-15, 5-16), the full-width critical speeds and the
divergence rate and time-to-double of the least stable mode at a list of speeds.

Examples
--------
::

    python -m stability.critical_speed
    python -m stability.critical_speed --chair revised --model thesis --json
    python -m stability.critical_speed --set trail=0.05 --set pin_damping=0.02 --speeds 0.5:2:0.25
"""

from __future__ import annotations

import argparse
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from stability.chair.power import drive_kind
from stability.cli import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_chair_options,
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
from stability.driver import Driver, HumanLimit, human_limit
from stability.driver.text import human_text
from stability.linear import StabilitySummary, analyse
from stability.linear.batch import check_eigen_work
from stability.linear.intervals import GRID_POINTS, solves_per_draw
from stability.runtime.checks import MIN_SPEED
from stability.settings import defaults as D
from stability.settings.bounds import LAYOUT_MAX_SPEED
from stability.study.summary_text import format_summary, simulator_checks, summary_dict

if TYPE_CHECKING:
    from stability.linear.intervals import LinearIntervals
    from stability.study.uncertain import NonlinearIntervals

__all__ = ["main", "build_parser", "document", "driver_limits", "with_driver_extras", "layout_summary",
           "layout_document", "layout_figure"]



def build_parser() -> argparse.ArgumentParser:
    """Command-line parser of ``python -m stability.critical_speed``.

    Options: the chair options (:func:`stability.cli.add_chair_options`), ``--model``,
    ``--speeds`` (divergence table, m/s), ``--max-speed`` (upper end of the
    critical-speed search, m/s), ``--uncertainty FILE`` with ``--samples``,
    ``--seed`` and ``--level`` (and ``--nonlinear`` with ``--nonlinear-samples``), and the JSON options.

    Returns
    -------
    argparse.ArgumentParser
        The parser (one-line errors, exit status 2).
    """
    p = OneLineErrorParser(prog="python -m stability.critical_speed", description=(__doc__ or "").split("\n\n")[0])
    add_chair_options(p)
    add_model_option(p)
    p.add_argument("--speeds", default=D.speeds_text(D.SUMMARY_SPEEDS),
                   help=f"speeds for the divergence table, START:STOP:STEP or a list (m/s; default "
                        f"{D.speeds_text(D.SUMMARY_SPEEDS)})")
    p.add_argument("--max-speed", type=float, default=D.MAX_SPEED,
                   help=f"upper end of the critical-speed search (m/s, default {D.MAX_SPEED:g})")
    p.add_argument("--uncertainty", metavar="FILE",
                   help="TOML file of parameter distributions: print 95 %% intervals (Monte Carlo) next to the values")
    p.add_argument("--samples", type=int, default=D.SAMPLES,
                   help=f"Monte Carlo draws with --uncertainty (default {D.SAMPLES})")
    p.add_argument("--seed", type=int, default=D.SEED, help=f"seed of the draws (default {D.SEED})")
    p.add_argument("--level", type=float, default=D.COVERAGE, help=f"interval coverage (default {D.COVERAGE:g})")
    p.add_argument("--nonlinear", action="store_true",
                   help="with --uncertainty: also the intervals of the critical impulse at 0.75 m/s and the "
                        "equal-instability speed (simulations; about 0.05-0.1 s per draw)")
    p.add_argument("--nonlinear-samples", type=int, default=D.NONLINEAR_SAMPLES,
                   help=f"Monte Carlo draws of the nonlinear measures (1 to 2000, default {D.NONLINEAR_SAMPLES})")
    add_driver_options(p)
    add_json_options(p)
    add_output_option(p, FIGURE_FORMATS, what="a figure: eigenvalues against speed up to --max-speed, free and "
                      "locked casters, unstable speeds shaded and critical speeds marked")
    return p


def figure(summary: StabilitySummary, n: int = 400) -> Any:
    """The figure of ``-o``: real and imaginary parts of the eigenvalues against speed, free and locked casters.

    Drawn by :func:`stability.plotting.eigenvalues_vs_speed` from :func:`stability.rootlocus.speed_locus`
    (``n`` speeds from 0.05 m/s to the top of the summary's ``search_range``), branches named from their eigenvectors at
    0.75 m/s (:func:`stability.linear.names.mode_names`), with a caption from the summary's critical speeds.

    Parameters
    ----------
    summary : StabilitySummary
    n : int
        Speeds per locus.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from stability import plotting as P
    from stability.linear.names import mode_names
    from stability.rootlocus import speed_locus

    c, model = summary.chair, summary.model
    fig, axes = P.page(f"{c.name} | {model} model | eigenvalues against speed (shaded: unstable)",
                       f"linear model, straight running; critical speeds (dashed) where a real part crosses zero; "
                       f"0.05 to {summary.search_range[1]:g} m/s", nrows=2, ncols=2, size=(12.0, 8.0))
    for j, casters in enumerate(("free", "locked")):
        locus = speed_locus(c, model=model, casters=casters, max_speed=summary.search_range[1], n=n)
        P.eigenvalues_vs_speed(locus, [axes[0, j], axes[1, j]], mode_names=mode_names(locus))

    def crossings(cs: list) -> str:
        return ", ".join(f"{x.speed:.3g} m/s" for x in cs) or "none"

    free = ("unstable at every speed" if summary.free_unstable_at_all_speeds else
            "stable at every speed" if summary.free_stable_at_all_speeds else
            f"stability changes at {crossings(summary.free_crossings)}")
    text = (f"What to conclude: with free, frictionless casters the chair is {free}; with locked casters its "
            f"critical speeds are {crossings(summary.locked_crossings)}. Where a real part is above zero (shaded) "
            "a heading error grows by itself at that rate (1/s); Coulomb pin friction, which has no linearisation, "
            "can hold the casters (python -m stability.study for the nonlinear measures).")
    lines = P.wrap_text(text, 175)
    fig.text(0.5, 0.015, "\n".join(lines), ha="center", va="bottom", fontsize=8.5, fontweight="bold", color="0.1",
             linespacing=1.4)
    return P.finish(fig, top=0.86, bottom=0.1 + 0.026 * (len(lines) - 1), hspace=0.35)


def document(summary: StabilitySummary, checks: list, args: argparse.Namespace, speeds: np.ndarray,
             intervals: LinearIntervals | None = None, nonlinear: NonlinearIntervals | None = None,
             human: HumanLimit | None = None, driver: Driver | None = None) -> dict[str, Any]:
    """The JSON document of ``--json`` (without its ``tire_range`` entry, which :func:`stability.cli.emit_json` adds).

    The interactive explorer's results download is this document too.

    Parameters
    ----------
    summary : StabilitySummary
        :func:`stability.linear.analyse` of the chair.
    checks : list
        :func:`stability.study.summary_text.simulator_checks` of ``summary``.
    args : argparse.Namespace
        The parsed options (``build_parser().parse_args([])`` gives the defaults).
    speeds : ndarray
        The divergence-table speeds parsed from ``args.speeds``, m/s.
    intervals, nonlinear : optional
        The uncertainty results, when ``--uncertainty`` (and ``--nonlinear``) were given.
    human, driver : optional
        The human-limited speed and its driver (``--reaction-time`` or the chair file's ``[user]``).

    Returns
    -------
    dict
        Common header (:func:`stability.cli.json_header`) plus :func:`stability.study.summary_text.summary_dict`,
        and ``human_limit`` (null without a driver).
    """
    options = {"speeds_m_s": [float(x) for x in speeds], "max_speed_m_s": args.max_speed,
               "uncertainty": args.uncertainty, "samples": args.samples, "seed": args.seed, "level": args.level,
               "nonlinear": args.nonlinear, "nonlinear_samples": args.nonlinear_samples if args.nonlinear else None,
               "reaction_time_s": None if driver is None else driver.reaction_time_s}
    limit = None if human is None or driver is None else {**human.to_mapping(), "driver": driver.to_mapping()}
    return {**json_header(summary.chair, summary.model, options),
            **summary_dict(summary, checks, intervals, nonlinear), "human_limit": limit}


def _driver(c: Any, args: argparse.Namespace) -> tuple:
    """The driver (``--reaction-time`` or the chair file's ``[user]``) and :func:`driver_limits`; Nones without."""
    driver = driver_from_args(args)
    if driver is None:
        return None, None, (None, None)
    return (driver, *driver_limits(c, driver, args.model))


def driver_limits(c: Any, driver: Driver, model: str) -> tuple:
    """The human-limited speed and the extras: for a powered chair the limit with the assist on
    (:mod:`stability.assist.human`), and the nonlinear lane limit (:mod:`stability.driver.lane`).

    The explorer's results download computes a session's user with it (:mod:`stability.app.downloads`).

    Parameters
    ----------
    c : Chair
    driver : Driver
    model : {"exact", "thesis"}

    Returns
    -------
    tuple
        ``(HumanLimit, (assisted or None, lane))``, as :func:`document` and :func:`with_driver_extras` take them.
    """
    assisted = None
    if drive_kind(c) == "motor":
        from stability.assist.human import assisted_driver_limit

        assisted = assisted_driver_limit(c, driver.reaction_time_s)
    from stability.settings.run import RunSpec
    from stability.study.lane import lane_range

    lane = lane_range(c, driver, RunSpec(model=model))
    return human_limit(c, driver, model), (assisted, lane)


def _print_driver(human: HumanLimit | None, driver: Driver | None, extras: tuple) -> None:
    """The driver's limits as text (nothing without a driver)."""
    assisted, lane = extras
    if human is not None and driver is not None:
        from stability.study.lane import lane_text

        print(human_text(human, driver, None if lane is None else lane_text(lane)))
    if assisted is not None:
        print("  " + assisted.sentence() + ".")


def with_driver_extras(doc: dict[str, Any], extras: tuple) -> dict[str, Any]:
    """``doc`` with the driver's limit under the assist (``human_limit.with_assist``; null for a manual chair)
    and the nonlinear lane limit (``human_limit.nonlinear``).

    Parameters
    ----------
    doc : dict
        :func:`document`'s.
    extras : tuple
        :func:`driver_limits`' second item.

    Returns
    -------
    dict
        ``doc``, changed in place.
    """
    assisted, lane = extras
    if doc["human_limit"] is not None:
        doc["human_limit"]["with_assist"] = None if assisted is None else assisted.to_mapping()
        doc["human_limit"]["nonlinear"] = None if lane is None else lane.to_mapping()
    return doc


def _run(args: argparse.Namespace) -> int:
    check_outputs({"--json-file": args.json_file, "-o": args.output},
                  {"--chair": args.chair, "--uncertainty": args.uncertainty})
    if args.nonlinear and not args.uncertainty:
        raise ValueError("--nonlinear needs --uncertainty FILE")
    from stability.layout.io import is_layout_spec

    try:                                        # a list or a START:STOP:STEP range, either direction
        raw_speeds = [float(u) for u in parse_speeds(args.speeds, signed=True)]
    except ValueError:
        raw_speeds = None                       # parse_speeds below says what is wrong
    if is_layout_spec(args.chair) or (raw_speeds is not None and any(u < 0 for u in raw_speeds)):
        return _run_layout(args)
    c = load_chair(args.chair, args.set)
    speeds = parse_speeds(args.speeds)
    unc = None
    if args.uncertainty:
        check_eigen_work("--samples", args.samples, solves_per_draw(len(speeds), GRID_POINTS))
        from stability.uncertainty import load_uncertainty

        unc = load_uncertainty(args.uncertainty)        # a bad file is refused before any work
    summary = analyse(c, model=args.model, speeds=speeds, max_speed=args.max_speed)
    checks = simulator_checks(summary)
    driver, human, assisted = _driver(c, args)
    intervals = nonlinear = None
    if unc is not None:
        # deferred: the uncertainty machinery (and the simulator) cost start-up time the plain summary does not need
        from stability.linear.intervals import linear_intervals
        from stability.study.uncertain import nonlinear_intervals

        intervals = linear_intervals(c, unc, model=args.model, speeds=speeds, max_speed=args.max_speed,
                                     samples=args.samples, seed=args.seed, level=args.level)
        if args.nonlinear:
            from stability.settings.run import RunSpec

            nonlinear = nonlinear_intervals(c, unc, RunSpec(model=args.model), samples=args.nonlinear_samples,
                                            seed=args.seed, level=args.level)
    with output_files({"-o": args.output, "--json-file": args.json_file}) as tmp:   # renamed together: all or none
        if args.output:
            from stability.runtime.files import save_figure

            save_figure(figure(summary), tmp["-o"], title=f"stability critical_speed: {c.name}, {args.model} model")
        if args.json or args.json_file:
            doc = document(summary, checks, args, speeds, intervals, nonlinear, human, driver)
            emit_json(with_driver_extras(doc, assisted), args, write_to=tmp.get("--json-file"))
    announce_written(args.output, args.json_file)
    if not args.json:
        print(format_summary(summary, checks, intervals, nonlinear))
        _print_driver(human, driver, assisted)
    return 0


def _run_layout(args: argparse.Namespace) -> int:
    """Any wheel layout, forward and in reverse: the layout's linear model (:mod:`stability.layout`), with the driver's
    limits both ways (:func:`stability.driver.layout.layout_human_limit`), the intervals over an uncertainty file's
    layout fields (:func:`stability.report.layout_uncertainty.layout_uncertainty`) and the figure of ``-o``
    (:func:`layout_figure`)."""
    from stability.layout.linear import SEARCH_SPEEDS_M_S
    from stability.layout.text import layout_text

    if args.model != "exact":
        raise ValueError(f"--model {args.model} is invalid for a layout or reverse speeds; valid values: exact (the "
                         "layout's equations are the exact model's)")
    if args.nonlinear:
        raise ValueError("--nonlinear is not available for a layout or reverse speeds: the critical impulse and the "
                         "equal-instability speed are a simulator search per draw; valid: drop --nonlinear (python -m "
                         "stability.study critical-impulse --chair LAYOUT --interval gives their range)")
    if not LAYOUT_MAX_SPEED.holds(args.max_speed):
        raise ValueError(f"--max-speed {args.max_speed!r} is invalid for a layout; valid range: "
                         f"{LAYOUT_MAX_SPEED.text()} (the figure draws up to 20 m/s)")
    layout = load_layout(args.chair, args.set)
    speeds = [float(u) for u in parse_speeds(args.speeds, signed=True)]
    top = float(SEARCH_SPEEDS_M_S[-1])                                    # the layout model's fastest speed
    if max(abs(u) for u in speeds) > top:
        raise ValueError(f"--speeds {args.speeds!r} is invalid for a layout or reverse speeds; valid range: every "
                         f"|speed| {MIN_SPEED:g} to {top:g} m/s (negative: reverse)")
    unc = None
    if args.uncertainty:
        from stability.advise.layout_axes import load_layout_uncertainty

        table = speeds if any(u < 0 for u in speeds) else [-u for u in reversed(speeds)] + speeds
        check_eigen_work("--samples", args.samples, len(table) + 2 * (len(SEARCH_SPEEDS_M_S) + 50))
        unc = load_layout_uncertainty(args.uncertainty, layout)      # a bad file is refused before any work
    driver = driver_from_args(args)
    summary = layout_summary(layout, speeds)
    human = None
    if driver is not None:
        from stability.driver.layout import layout_human_limit

        human = tuple(layout_human_limit(layout, driver, reverse) for reverse in (False, True))
    intervals = None
    if unc is not None:
        from stability.report.layout_uncertainty import layout_uncertainty

        intervals = layout_uncertainty(layout, unc, [float(u) for u in summary.speeds_m_s], samples=args.samples,
                                       seed=args.seed, critical=True, level=args.level)
    with output_files({"-o": args.output, "--json-file": args.json_file}) as tmp:   # renamed together: all or none
        if args.output:
            from stability.runtime.files import save_figure

            save_figure(layout_figure(layout, summary, min(args.max_speed, 20.0)), tmp["-o"],
                        title=f"stability critical_speed: {layout.name}, layout model")
        if args.json or args.json_file:
            doc = layout_document(layout, summary, speeds)
            doc["options"].update({"uncertainty": args.uncertainty, "samples": args.samples if unc else None,
                                   "seed": args.seed if unc else None, "level": args.level if unc else None,
                                   "reaction_time_s": None if driver is None else driver.reaction_time_s})
            doc["human_limit"] = None if human is None or driver is None else {
                **human[0].to_mapping(), "driver": driver.to_mapping(), "reverse": human[1].to_mapping()}
            doc["uncertainty"] = None if intervals is None else intervals.to_mapping()
            emit_json(doc, args, write_to=tmp.get("--json-file"))
    announce_written(args.output, args.json_file)
    if not args.json:
        print(layout_text(layout, summary))
        if intervals is not None:
            print("\nParameter uncertainty: " + "\n".join(intervals.lines()))
        if human is not None and driver is not None:
            from stability.driver.text import layout_human_text

            print(layout_human_text(human[0], human[1], driver))
    return 0


def layout_figure(layout: Any, summary: Any, max_speed: float = 20.0, n: int = 400) -> Any:
    """The figure of ``-o`` for a wheel layout: real and imaginary parts of the eigenvalues against the speed's size,
    forwards and in reverse.

    Drawn by :func:`stability.plotting.eigenvalues_vs_speed` from
    :func:`stability.rootlocus.speed.layout_speed_locus` (``n`` speeds from 0.05 m/s to ``max_speed`` each way),
    with a caption from the summary's critical speeds.

    Parameters
    ----------
    layout : stability.layout.Layout
    summary : stability.layout.LayoutSummary
        :func:`layout_summary`'s.
    max_speed : float
        Largest speed drawn, m/s (at most 20).
    n : int
        Speeds per locus.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from stability import plotting as P
    from stability.layout.text import critical_words
    from stability.rootlocus.speed import layout_speed_locus

    fig, axes = P.page(f"{layout.name} | layout model | eigenvalues against speed, forwards and in reverse "
                       "(shaded: unstable)",
                       f"linear model of the wheel layout ({layout.shape[0]} fixed wheels, {layout.shape[1]} casters), "
                       f"free frictionless casters, straight running; 0.05 to {max_speed:g} m/s each way",
                       nrows=2, ncols=2, size=(12.0, 8.0))
    for j, reverse in enumerate((False, True)):
        locus = layout_speed_locus(layout, reverse=reverse, max_speed=max_speed, n=n)
        way = ("in reverse (casters trailing at 180 deg)" if reverse else "forwards (casters trailing at 0 deg)")
        P.eigenvalues_vs_speed(locus, [axes[0, j], axes[1, j]],
                               title=f"free casters, {way}")
        for ax in axes[:, j]:
            ax.set_xlabel(f"{'reverse' if reverse else 'forward'} speed |U| (m/s)", fontsize=8.5)
    text = ("What to conclude: " + critical_words(summary.forward_critical, "forwards") + "; "
            + critical_words(summary.reverse_critical, "in reverse") + ". Where a real part is above zero (shaded) a "
            "heading error grows by itself at that rate (1/s); Coulomb pin friction, which has no linearisation, can "
            "hold the casters (python -m stability.study critical-impulse --chair "
            f"{layout.name} for the nonlinear measure).")
    lines = P.wrap_text(text, 175)
    fig.text(0.5, 0.015, "\n".join(lines), ha="center", va="bottom", fontsize=8.5, fontweight="bold", color="0.1",
             linespacing=1.4)
    return P.finish(fig, top=0.86, bottom=0.1 + 0.026 * (len(lines) - 1), hspace=0.35)


def layout_summary(layout: Any, speeds: Sequence[float]) -> Any:
    """The layout's linear summary at ``speeds``, and at the same speeds in reverse when all are forward.

    Parameters
    ----------
    layout : stability.layout.Layout
    speeds : sequence of float
        Signed speeds, m/s (negative: reverse).

    Returns
    -------
    stability.layout.LayoutSummary
    """
    from stability.layout import analyse_layout

    speeds = list(speeds)
    return analyse_layout(layout, speeds if any(u < 0 for u in speeds) else [-u for u in reversed(speeds)] + speeds)


def layout_document(layout: Any, summary: Any, speeds: Sequence[float]) -> dict:
    """The JSON document ``--chair LAYOUT --json`` prints.

    Parameters
    ----------
    layout : stability.layout.Layout
    summary : stability.layout.LayoutSummary
        :func:`layout_summary`'s.
    speeds : sequence of float
        The ``--speeds`` asked for, m/s.

    Returns
    -------
    dict
        Without ``--uncertainty`` or ``--reaction-time``: their options, ``human_limit`` and ``uncertainty`` null
        (the command fills them in when given; the explorer's download is this document).
    """
    from stability import __version__
    from stability.layout.text import layout_mapping

    options = {"speeds_m_s": list(speeds), "uncertainty": None, "samples": None, "seed": None, "level": None,
               "reaction_time_s": None}
    return {"stability_version": __version__, "chair": layout.name, "model": "exact", "options": options,
            **layout_mapping(layout, summary), "human_limit": None, "uncertainty": None}


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.critical_speed``; returns the exit status (2 on bad input).

    Parameters
    ----------
    argv : sequence of str or None, optional
        Command-line arguments without the program name; ``None`` reads ``sys.argv[1:]``.

    Returns
    -------
    int
        Exit status: 0 on success, 2 on bad input or a failed computation (see :func:`stability.cli.run`).
    """
    return run(build_parser(), argv, _run)
