"""Command line: ``python -m stability.simulate --chair ej-premier --speed 0.75 --json``."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence

from ..cli import OneLineErrorParser, add_chair_options, check_directory, load_chair, run
from ..reference import REFERENCE_SPEED, THESIS_PUSH
from .api import simulate
from .options import DEFAULTS as D
from .plot import plot_result

__all__ = ["main"]


def _parser() -> argparse.ArgumentParser:
    ap = OneLineErrorParser(prog="python -m stability.simulate",
                 description="Simulate a wheelchair disturbed from straight motion (thesis chapter 7).")
    add_chair_options(ap)
    ap.add_argument("--speed", type=float, default=REFERENCE_SPEED,
                    help=f"initial forward speed, m/s (default {REFERENCE_SPEED:g})")
    ap.add_argument("--impulse", type=float, nargs=2, metavar=("FORCE", "DURATION"), default=THESIS_PUSH.as_tuple,
                    help=f"lateral force at the c.g. (N) and its duration (s); default {THESIS_PUSH.force:g} "
                         f"{THESIS_PUSH.duration:g}")
    ap.add_argument("--tire-impulse", type=float, default=0.0, metavar="F",
                    help="lateral force on each main tire during the impulse duration, N")
    ap.add_argument("--lateral-velocity", type=float, default=0.0, metavar="V", help="initial lateral velocity, m/s")
    ap.add_argument("--eta0", type=float, default=0.0, metavar="DEG", help="initial left caster angle, deg")
    ap.add_argument("--beta0", type=float, default=0.0, metavar="DEG", help="initial right caster angle, deg")
    ap.add_argument("--scheme", default=D.scheme, help=f"wchair or adaptive (default {D.scheme})")
    ap.add_argument("--model", default=D.model, help=f"thesis or exact (default {D.model})")
    ap.add_argument("--casters", default=D.casters, help=f"free or locked (default {D.casters})")
    ap.add_argument("--duration", type=float, default=D.duration, help=f"simulated time, s (default {D.duration:g})")
    ap.add_argument("--dt", type=float, default=D.dt, help=f"wchair time step, s (default {D.dt:g})")
    ap.add_argument("--sample", type=float, default=None, help="output interval of --json/--csv, s")
    ap.add_argument("--no-stop", action="store_true", help="do not stop at the eleventh warning")
    ap.add_argument("--out-of-range", default=D.out_of_range,
                    help=f"clamp, extrapolate or raise (default {D.out_of_range})")
    ap.add_argument("--rtol", type=float, default=D.rtol, help="adaptive scheme relative tolerance")
    ap.add_argument("--atol", type=float, default=D.atol, help="adaptive scheme absolute tolerance")
    ap.add_argument("--csv", metavar="FILE", help="write the time histories to a CSV file")
    ap.add_argument("--plot", metavar="FILE", help="write a plot (pdf, png, svg)")
    ap.add_argument("--json", action="store_true", help="print results as JSON")
    return ap


def _run_cli(args: argparse.Namespace) -> int:
    c = load_chair(args.chair, args.set)
    check_directory(args.csv, "--csv")
    check_directory(args.plot, "--plot")
    res = simulate(c, args.speed, duration=args.duration, scheme=args.scheme, model=args.model, dt=args.dt,
                   impulse_force=args.impulse[0], impulse_duration=args.impulse[1],
                   tire_impulse=args.tire_impulse, lateral_velocity=args.lateral_velocity,
                   eta0_deg=args.eta0, beta0_deg=args.beta0, casters=args.casters,
                   stop_on_warnings=False if args.no_stop else None, out_of_range=args.out_of_range,
                   rtol=args.rtol, atol=args.atol)
    times = {str(v): res.first_time_abs_yaw_rate(v) for v in (0.5, 1.0)}
    out = res.resample(args.sample) if args.sample is not None else res
    if args.csv:
        out.to_csv(args.csv)
    if args.plot:
        plot_result(res, args.plot)
    if args.json:
        d = out.to_dict()
        d["first_time_abs_yaw_rate_s"] = times
        print(json.dumps(d, allow_nan=False))
    else:
        print(res.summary())
        if args.csv:
            print(f"wrote {args.csv}")
        if args.plot:
            print(f"wrote {args.plot}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Command-line entry point; returns the exit status (2 on bad input)."""
    return run(_parser(), argv, _run_cli, errors=(ValueError, OSError))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
