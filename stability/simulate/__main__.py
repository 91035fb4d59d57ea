"""Command line: ``python -m stability.simulate --chair ej-premier --speed 0.75 --json``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from stability.cli import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_chair_options,
    add_friction_law_option,
    add_json_options,
    add_model_option,
    add_output_option,
    check_outputs,
    check_work,
    emit_json,
    json_header,
    load_chair,
    output_files,
    run,
)
from stability.settings import defaults as DF
from stability.settings.reference import THESIS_PUSH
from stability.simulate.api import simulate
from stability.simulate.bounds import MAX_DURATION_S, MAX_PUSH_N, MAX_ROWS, MAX_STEPS, ROW_BYTES
from stability.simulate.options import ADAPTIVE_SAMPLE, OUT_OF_RANGE_POLICIES
from stability.simulate.options import DEFAULTS as D
from stability.simulate.plot import plot_result

__all__ = ["main", "build_parser"]


def build_parser() -> argparse.ArgumentParser:
    ap = OneLineErrorParser(prog="python -m stability.simulate",
                 description="Simulate a wheelchair disturbed from straight motion (thesis chapter 7).")
    add_chair_options(ap)
    ap.add_argument("--speed", type=float, default=DF.SPEED,
                    help=f"initial forward speed, m/s (default {DF.SPEED:g})")
    ap.add_argument("--impulse", type=float, nargs=2, metavar=("FORCE", "DURATION"), default=THESIS_PUSH.as_tuple,
                    help=f"lateral force at the c.g. (N) and its duration (s); default {THESIS_PUSH.force:g} "
                         f"{THESIS_PUSH.duration:g}")
    ap.add_argument("--tire-impulse", type=float, default=0.0, metavar="F",
                    help="lateral force on each main tire during the impulse duration, N")
    ap.add_argument("--lateral-velocity", type=float, default=0.0, metavar="V", help="initial lateral velocity, m/s")
    ap.add_argument("--eta0", type=float, default=0.0, metavar="DEG", help="initial left caster angle, deg")
    ap.add_argument("--beta0", type=float, default=0.0, metavar="DEG", help="initial right caster angle, deg")
    ap.add_argument("--scheme", default=D.scheme, help=f"wchair or adaptive (default {D.scheme})")
    add_model_option(ap)
    ap.add_argument("--cross-slope", type=float, default=D.slope[0], metavar="DEG",
                    help="cross slope, deg: the plane falls to the right of the initial heading (+); |.| <= 15")
    ap.add_argument("--grade", type=float, default=D.slope[1], metavar="DEG",
                    help="grade, deg: the plane rises ahead (+); |.| <= 15")
    ap.add_argument("--casters", default=D.casters, help=f"free or locked (default {D.casters})")
    add_friction_law_option(ap)
    ap.add_argument("--duration", type=float, default=D.duration, help=f"simulated time, s (default {D.duration:g})")
    ap.add_argument("--dt", type=float, default=D.dt, help=f"wchair time step, s (default {D.dt:g})")
    ap.add_argument("--sample", type=float, default=None, help="output interval of --json/--csv, s")
    ap.add_argument("--no-stop", action="store_true", help="do not stop at the eleventh warning")
    # deprecated: the simulator's tire policy now follows --tire-range (warn and clamp: clamp the fits at the data's
    # edge and count the warnings, as program WCHAIR; raise: stop at the first tire input outside the data)
    ap.add_argument("--out-of-range", default=None, choices=OUT_OF_RANGE_POLICIES, help=argparse.SUPPRESS)
    ap.add_argument("--rtol", type=float, default=D.rtol, help="adaptive scheme relative tolerance")
    ap.add_argument("--atol", type=float, default=D.atol, help="adaptive scheme absolute tolerance")
    ap.add_argument("--csv", metavar="FILE", help="write the time histories to a CSV file")
    add_output_option(ap, FIGURE_FORMATS, what="a plot of the run", aliases=("--plot",))
    add_json_options(ap)
    return ap


#: Bounds of the simulate command (bounded time and memory); the run's own are the API's (simulate.options).
MAX_SPEED_M_S = 20.0            # a wheelchair does not go faster
#: Rows of --csv/--json output: a CSV row of 32 columns is about 0.7 kB, so 1e5 rows = some 70 MB.
MAX_OUTPUT_ROWS = 100_000


def _check_options(args: argparse.Namespace) -> None:
    if not 0 < args.speed <= MAX_SPEED_M_S:
        raise ValueError(f"--speed {args.speed!r} is invalid; valid range: 0 < speed <= {MAX_SPEED_M_S:g} m/s")
    if not 0 < args.duration <= MAX_DURATION_S:
        raise ValueError(f"--duration {args.duration!r} is invalid; valid range: 0 < duration <= "
                         f"{MAX_DURATION_S:g} s")
    if args.scheme == "wchair":
        if not 0 < args.dt <= 0.1:
            raise ValueError(f"--dt {args.dt!r} is invalid; valid range: 0 < dt <= 0.1 s")
        check_work(f"--duration {args.duration:g} s with --dt {args.dt:g} s (time steps)", args.duration / args.dt,
                   MAX_STEPS,
                   f"use --dt >= {args.duration / MAX_STEPS:.2g} s or --duration <= {MAX_STEPS * args.dt:.4g} s")
        check_work(f"--duration {args.duration:g} s with --dt {args.dt:g} s (rows of the stored history, "
                   f"{ROW_BYTES} bytes each)", args.duration / args.dt, MAX_ROWS,
                   f"use --dt >= {args.duration / MAX_ROWS:.2g} s or --duration <= {MAX_ROWS * args.dt:.4g} s")
    if args.sample is None and (args.csv or args.json or args.json_file):     # every step is written
        check_work(f"--duration {args.duration:g} s with --dt {args.dt:g} s (output rows, one a step)",
                   args.duration / (args.dt if args.scheme == "wchair" else ADAPTIVE_SAMPLE), MAX_OUTPUT_ROWS,
                   f"give --sample >= {args.duration / MAX_OUTPUT_ROWS:.2g} s")
    if args.sample is not None:
        if args.scheme == "wchair" and args.sample < args.dt:
            raise ValueError(f"--sample {args.sample!r} is invalid; valid range: --dt ({args.dt:g} s) <= sample <= "
                             f"--duration (a finer interval only interpolates between steps)")
        check_work(f"--duration {args.duration:g} s with --sample {args.sample:g} s (output rows)",
                   args.duration / args.sample, MAX_OUTPUT_ROWS,
                   f"use --sample >= {args.duration / MAX_OUTPUT_ROWS:.2g} s")
    force, length = args.impulse
    if not (abs(force) <= MAX_PUSH_N and 0 <= length <= args.duration):
        raise ValueError(f"--impulse {force!r} {length!r} is invalid; valid range: |FORCE| <= {MAX_PUSH_N:g} N and "
                         f"0 <= DURATION <= --duration ({args.duration:g} s)")


def _sim_policy(args: argparse.Namespace) -> str:
    """The simulator's tire policy from ``--tire-range`` (or the deprecated ``--out-of-range``)."""
    if args.out_of_range is not None:
        return str(args.out_of_range)
    return "raise" if args.tire_range == "raise" else D.out_of_range


def _run_cli(args: argparse.Namespace) -> int:
    outputs = {"--csv": args.csv, "-o": args.output, "--json-file": args.json_file}
    check_outputs(outputs, {"--chair": args.chair})
    _check_options(args)
    c = load_chair(args.chair, args.set)
    res = simulate(c, args.speed, duration=args.duration, scheme=args.scheme, model=args.model, dt=args.dt,
                   impulse_force=args.impulse[0], impulse_duration=args.impulse[1],
                   tire_impulse=args.tire_impulse, lateral_velocity=args.lateral_velocity,
                   eta0_deg=args.eta0, beta0_deg=args.beta0, casters=args.casters,
                   friction_law=args.friction_law, stop_on_warnings=False if args.no_stop else None,
                   out_of_range=_sim_policy(args),
                   rtol=args.rtol, atol=args.atol, slope=(args.cross_slope, args.grade))
    levels = (0.5, 1.0)
    times = [res.first_time_abs_yaw_rate(v) for v in levels]
    out = res.resample(args.sample) if args.sample is not None else res
    options = {"speed_m_s": args.speed, "push_force_N": args.impulse[0], "push_duration_s": args.impulse[1],
               "tire_impulse_N": args.tire_impulse, "lateral_velocity_m_s": args.lateral_velocity,
               "eta0_deg": args.eta0, "beta0_deg": args.beta0, "scheme": args.scheme, "casters": args.casters,
               "friction_law": res.settings.get("friction_law", "kinetic" if args.scheme == "wchair" else "stick-slip"),
               "duration_s": args.duration, "dt_s": args.dt, "sample_s": args.sample, "no_stop": args.no_stop,
               "rtol": args.rtol, "atol": args.atol, "out_of_range": _sim_policy(args),
               "cross_slope_deg": args.cross_slope, "grade_deg": args.grade}
    with output_files({"--csv": args.csv, "-o": args.output}) as tmp:
        if args.csv:
            out.to_csv(tmp["--csv"])
        if args.output:
            plot_result(res, tmp["-o"])
    if args.json or args.json_file:
        d = {**json_header(c, args.model, options), **out.to_dict()}
        d["yaw_rate_levels_rad_s"] = list(levels)
        d["first_time_at_level_s"] = times
        emit_json(d, args)
    if not args.json:
        print(res.summary())
        for path in (args.csv, args.output):
            if path:
                print(f"wrote {path}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Command-line entry point; returns the exit status (2 on bad input)."""
    return run(build_parser(), argv, _run_cli, errors=(ValueError, OSError))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
