"""Command line: ``python -m stability.study critical-impulse|equal-instability --chair X ...``."""

from __future__ import annotations

import argparse
import dataclasses
import sys
from collections.abc import Sequence

import numpy as np

from stability.chair import Chair
from stability.cli import (
    OneLineErrorParser,
    add_chair_options,
    add_json_options,
    add_run_options,
    check_outputs,
    emit_json,
    json_header,
    load_chair,
    load_layout,
    parse_speeds,
    run,
    run_from_args,
)
from stability.settings import defaults as D
from stability.study.impulse import check_study_work, critical_impulse_curve, runs_per_speed
from stability.study.impulse_intervals import critical_impulse_intervals
from stability.study.intervals import RANGE_DEFINITION, equal_instability_interval

#: The run settings each subcommand offers (options generated from the RunSpec's table): the critical impulse
#: varies the push force, the equal-instability speed the speed.
CRITICAL_RUN = ("model", "friction_law", "push_duration", "horizon", "dt")
EQUAL_RUN = ("model", "friction_law", "push_force", "reverse")


def build_parser() -> argparse.ArgumentParser:
    p = OneLineErrorParser(prog="python -m stability.study", description="Robust stability measures.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineErrorParser)
    ci = sub.add_parser("critical-impulse", help="smallest push (N s) after which |yaw rate| reaches the level")
    ei = sub.add_parser("equal-instability", help="equal-instability speed with its interval")
    for s, names in ((ci, CRITICAL_RUN), (ei, EQUAL_RUN)):
        add_chair_options(s)
        add_run_options(s, names)
        add_json_options(s)
    ci.add_argument("--speeds", default=D.STUDY_SPEEDS,
                    help=f"START:STOP:STEP or a list, m/s (default {D.STUDY_SPEEDS}); negative: reverse (the "
                         "layout simulator, as for a layout --chair)")
    ci.add_argument("--level", type=float, default=D.YAW_RATE_LEVEL,
                    help=f"|yaw rate| level of the instability criterion, rad/s (default {D.YAW_RATE_LEVEL:g})")
    ci.add_argument("--max-impulse", type=float, default=D.MAX_IMPULSE,
                    help=f"largest push tried, N s (default {D.MAX_IMPULSE:g})")
    ci.add_argument("--interval", action="store_true",
                    help="also the range over pin friction x0.5 and x1.5, half the step and the other model (a "
                         "layout or reverse speeds: no model variant, the layout's equations are the exact model's)")
    ei.add_argument("--chair-friction-only", action="store_true",
                    help="apply the pin-friction factors to the chair only (default: to the reference chair too)")
    return p


def _emit(args: argparse.Namespace, data: dict, text: str, chair: Chair | None,
          header: dict | None = None) -> None:
    """Print ``text`` and/or the JSON (``header``, else the chair's :func:`json_header`, then ``data``)."""
    if args.json or args.json_file:
        units = {"push_duration": "push_duration_s", "level": "yaw_rate_level_rad_s", "horizon": "horizon_s",
             "max_impulse": "max_impulse_Ns", "push_force": "push_force_N", "dt": "dt_s"}
        options = {units.get(k, k): v for k, v in vars(args).items()
                   if k not in ("chair", "set", "json", "json_file", "debug", "quiet", "tire_notes", "speeds",
                                "model")}
        if getattr(args, "speeds", None) is not None:
            options["speeds_m_s"] = [float(s) for s in parse_speeds(args.speeds, signed=True)]
        head = json_header(chair, getattr(args, "model", None), options) if chair is not None else \
            {**(header or {}), "options": options}
        emit_json({**head, **data}, args)
    if not args.json:
        print(text)


def _critical(args: argparse.Namespace) -> None:
    from stability.layout.io import is_layout_spec

    try:
        signed = parse_speeds(args.speeds, signed=True)
    except ValueError:
        if not is_layout_spec(args.chair):
            parse_speeds(args.speeds)            # the short form's message where it refuses the value too
        raise
    if is_layout_spec(args.chair) or bool(np.any(signed < 0)):
        _critical_layout(args, signed)
        return
    chair = load_chair(args.chair, args.set)
    speeds = parse_speeds(args.speeds)
    run_spec = run_from_args(args, CRITICAL_RUN)
    check_study_work([chair] * len(speeds), speeds, run_spec.model, run_spec.horizon,
                     0.001 if run_spec.dt == "auto" else float(run_spec.dt),
                     runs_per_speed(max_impulse=args.max_impulse), "--horizon")
    curve = critical_impulse_curve(chair, speeds, run_spec, level=args.level, max_impulse=args.max_impulse)
    lines = [f"{chair.name}, {run_spec.model} model, {run_spec.friction_law} pin friction: critical impulse for "
             f"|yaw rate| >= {args.level:g} rad/s within {run_spec.horizon:g} s", f"push: {curve.points[0].push}",
             "kick: the sideways speed the push gives the chair (impulse / mass)"]
    ivs = [critical_impulse_intervals([chair], float(u), run_spec, level=args.level,
                                      max_impulse=args.max_impulse)[0] for u in speeds] if args.interval else []
    for k, p in enumerate(curve.points):
        kick = f"{p.kick_m_s:.3g} m/s" if p.kick_m_s is not None else "-"
        rng = _range_words(ivs[k]) if ivs else ""
        lines.append(f"  {p.speed:6.3g} m/s  {p.describe():>12s}  (kick {kick}){rng}")
    data = curve.to_dict()
    if ivs:
        data["intervals"] = [iv.to_dict() for iv in ivs]
    _emit(args, data, "\n".join(lines), chair)


def _range_words(iv) -> str:
    """A critical impulse's range over its variants; the same value in every variant (a bound at the search's end)
    says so, not "range 40-40" (issue 35: degenerate ranges are not printed)."""
    labels = ", ".join(label for label, _ in iv.variants)
    if iv.low_Ns == iv.high_Ns:
        return f"  the same in every variant ({labels})"
    return f"  range {iv.low_Ns:.3g}-{iv.high_Ns:.3g} N s over {labels}"


def _critical_layout(args: argparse.Namespace, speeds: np.ndarray) -> None:
    """A layout preset or ``[[wheel]]`` file, or any chair at negative speeds: the layout simulator's runs
    (:func:`stability.study.layout_impulse.layout_critical_impulses`)."""
    from stability import __version__
    from stability.study.layout_impulse import (
        SPEED_RANGE_M_S,
        check_layout_work,
        layout_critical_impulse_curve,
        layout_step_limits_and_growth,
        slow_divergences,
    )
    from stability.study.summaries import run_steps

    layout = load_layout(args.chair, args.set)
    lo, hi = SPEED_RANGE_M_S
    if np.any(np.abs(speeds) > hi):
        raise ValueError(f"--speeds {args.speeds!r} is invalid for a layout; valid range: every |speed| {lo:g} to "
                         f"{hi:g} m/s (negative: reverse)")
    run_spec = run_from_args(args, CRITICAL_RUN)
    if run_spec.model != "exact":
        raise ValueError(f"--model {run_spec.model} is invalid for a layout or reverse speeds; valid values: exact "
                         "(the layout's equations are the exact model's)")
    dt = 0.001 if run_spec.dt == "auto" else float(run_spec.dt)
    limits, _ = layout_step_limits_and_growth(layout, speeds)
    # with --interval every case again: the friction factors at the step, the step factors at theirs
    steps = [float(h) for h in run_steps([], speeds, dt, "exact", "free", limits=limits)]
    if args.interval:
        from stability.study.layout_impulse_intervals import layout_interval_specs

        steps = [h * step / dt for _, _, step in layout_interval_specs(run_spec) for h in steps]
    check_layout_work(steps, run_spec.horizon, runs_per_speed(max_impulse=args.max_impulse), "--horizon")
    curve = layout_critical_impulse_curve(layout, speeds, run_spec, level=args.level, max_impulse=args.max_impulse)
    ivs = []
    if args.interval:
        from stability.study.layout_impulse_intervals import layout_critical_impulse_intervals

        ivs = layout_critical_impulse_intervals(layout, speeds, run_spec, level=args.level,
                                                max_impulse=args.max_impulse)
    lines = [f"{layout.name} (layout: {layout.shape[0]} fixed wheels, {layout.shape[1]} casters), layout model, "
             f"{run_spec.friction_law} pin friction: critical impulse for |yaw rate| >= {args.level:g} rad/s within "
             f"{run_spec.horizon:g} s", f"push: {curve.points[0].push}",
             "casters start trailing the direction of travel (0 deg forward, 180 deg in reverse)",
             "kick: the sideways speed the push gives the chair (impulse / mass)"]
    for k, p in enumerate(curve.points):
        kick = f"{p.kick_m_s:.3g} m/s" if p.kick_m_s is not None else "-"
        way = "reverse" if p.speed < 0 else "forward"
        rng = _range_words(ivs[k]) if ivs else ""
        lines.append(f"  {p.speed:+6.3g} m/s {way:7s}  {p.describe():>12s}  (kick {kick}){rng}")
    slow = slow_divergences(layout, curve.points, run_spec)
    lines += [f"note: {d.text()}" for d in slow]
    header = {"stability_version": __version__, "chair": layout.name,
              "chair_parameters": dataclasses.asdict(layout), "model": "exact"}
    data = {**curve.to_dict(), "caster_start": "trailing the direction of travel (0 deg forward, 180 deg in "
            "reverse)", "slow_divergences": [d.to_dict() for d in slow]}
    if ivs:
        data["intervals"] = [iv.to_dict() for iv in ivs]
    _emit(args, data, "\n".join(lines), None, header)


def _interval(args: argparse.Namespace) -> None:
    from stability.layout.io import is_layout_spec

    run_spec = run_from_args(args, EQUAL_RUN)
    if is_layout_spec(args.chair) or run_spec.reverse:
        _interval_layout(args, run_spec)
        return
    chair = load_chair(args.chair, args.set)
    r = equal_instability_interval(chair, run_spec, friction_on_reference=not args.chair_friction_only)
    definition = _EQUAL_INSTABILITY.format(level=D.YAW_RATE_LEVEL, speed=D.SPEED) + (
        RANGE_DEFINITION if not args.chair_friction_only else
        RANGE_DEFINITION.replace("(on both the chair and the reference chair)", "(on the chair only: "
                                 "--chair-friction-only, not the report's and the advisor's range)"))
    lines = [f"{chair.name}: equal-instability speed {r.describe()}", f"push: {r.push}; pin friction factors "
             f"applied to {r.friction_scope}; {run_spec.friction_law} pin friction", definition]
    for v in r.variants:
        sp = "undefined (reference never reaches the level)" if v.result is None else v.result.describe()
        lines.append(f"  {v.factor:12s} {v.label:28s} {sp}")
    _emit(args, {**r.to_dict(), "definition": lines[2]}, "\n".join(lines), chair)


def _interval_layout(args: argparse.Namespace, run_spec) -> None:
    """A layout preset or ``[[wheel]]`` file, or any chair with ``--reverse``: the layout simulator's runs
    (:func:`stability.study.layout_equal_instability.layout_equal_instability_interval`)."""
    from stability import __version__
    from stability.study.layout_equal_instability import (
        LAYOUT_RANGE_DEFINITION,
        direction_words,
        layout_equal_instability_interval,
    )

    layout = load_layout(args.chair, args.set)
    if run_spec.model != "exact":
        raise ValueError(f"--model {run_spec.model} is invalid for a layout or --reverse; valid values: exact "
                         "(the layout's equations are the exact model's)")
    reverse = run_spec.reverse
    r = layout_equal_instability_interval(layout, run_spec.replace(reverse=False), reverse=reverse,
                                          friction_on_reference=not args.chair_friction_only).signed(reverse)
    way = direction_words(reverse)
    definition = (_EQUAL_INSTABILITY.format(level=D.YAW_RATE_LEVEL, speed=D.SPEED)
                  + ("driving backwards, every caster starting trailing (180 deg), against the reference case "
                     "forwards; " if reverse else "") + LAYOUT_RANGE_DEFINITION)
    if args.chair_friction_only:
        definition = definition.replace("(on both the layout's casters and the reference chair)",
                                        "(on the layout only: --chair-friction-only)")
    lines = [f"{layout.name} (layout: {layout.shape[0]} fixed wheels, {layout.shape[1]} casters) {way}: "
             f"equal-instability speed {r.describe()}" + (" (negative: backwards)" if reverse else ""),
             f"push: {r.push}; pin friction factors applied to {r.friction_scope}; {run_spec.friction_law} pin "
             "friction; layout model", definition]
    for v in r.variants:
        sp = "undefined (reference never reaches the level)" if v.result is None else v.result.describe()
        lines.append(f"  {v.factor:12s} {v.label:28s} {sp}")
    header = {"stability_version": __version__, "chair": layout.name,
              "chair_parameters": dataclasses.asdict(layout), "model": "exact"}
    _emit(args, {**r.to_dict(), "direction": "reverse" if reverse else "forward", "definition": lines[2]},
          "\n".join(lines), None, header)


#: What the equal-instability speed means (printed with it, followed by the range's one definition,
#: stability.study.RANGE_DEFINITION, which the report and the advisor share).
_EQUAL_INSTABILITY = ("equal-instability speed: the speed at which this chair, after the push, reaches |yaw rate| "
                      "{level:g} rad/s as soon as the reference chair does at {speed:g} m/s (thesis chapter 9); ")


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status (2 on bad input, with one line on stderr)."""
    parser = build_parser()

    def body(args: argparse.Namespace) -> None:
        check_outputs({"--json-file": args.json_file}, {"--chair": getattr(args, "chair", None)})
        (_critical if args.command == "critical-impulse" else _interval)(args)

    return run(parser, argv, body)


if __name__ == "__main__":
    sys.exit(main())
