"""``python -m stability.assist`` on a wheel layout, or any chair at negative (reverse) speeds.

The layout's linear model (:func:`stability.assist.layout.layout_assist`: designs, margins and the safe top speed
forward and in reverse, the nonlinear checks with the layout simulator) and the options the layout simulator
answers: ``--min-torque`` (:func:`stability.assist.layout_checks.layout_minimum_torque_limit`), ``--export-c``
(one direction's :func:`stability.assist.layout.layout_schedule` through the short form's exporter) and ``-o``
(:mod:`stability.assist.figures_layout` and the short form's margin and top-speed pages) and ``--faults`` (the
single sensor faults at every design speed of each direction in the layout simulator, counted in its safe top
speed: :func:`stability.assist.layout.layout_assist`).  Without ``--no-check`` the safe top speed counts the
torque too (the reference push's peak torque per drive wheel at every design speed, in the layout simulator).
``--model thesis`` is refused in one line saying why.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace

import numpy as np

from stability.assist.digital import margin_curves
from stability.assist.export_run import FirmwareReport, run_export
from stability.assist.layout import LayoutAssist, LayoutSchedule
from stability.assist.recovery import STRONG_FORCE, minimum_torque_json
from stability.assist.settling import recovery_rule
from stability.assist.weights import GyroSensor, Weights
from stability.chair.power import DriveTrain
from stability.cli import emit_json, load_layout, output_files
from stability.layout.model import Layout
from stability.runtime.files import write_pdf
from stability.settings.reference import THESIS_PUSH

__all__ = ["run_layout"]

#: How a layout's unchecked top-speed constraints are checked (the caption of its top-speed page).
_LAYOUT_ENABLE = {"torque": "the torque (run without --no-check; with --design full-state, --motor-lag 0)",
                  "faults": "the single sensor faults (add --faults)"}


def run_layout(args: argparse.Namespace, speeds: np.ndarray, weights: Weights, drive: DriveTrain,
                gyro: GyroSensor) -> int:
    """A wheel layout, or any chair at negative (reverse) speeds (the module's docstring).

    Parameters
    ----------
    args : argparse.Namespace
        The command's options.
    speeds : ndarray
        Signed design speeds, m/s.
    weights, drive, gyro
        The design's options.

    Returns
    -------
    int
        Exit status.
    """
    if args.model == "thesis":
        raise ValueError("--model thesis is invalid for a layout or reverse speeds: it is program WCHAIR's printed "
                         "equations of the thesis's two-caster chair driven forwards (caster slip from the relative "
                         "swivel rate alone, I_zp eta_ddot), while a layout's, and any chair's in reverse, are derived "
                         "from first principles only; valid: --model exact")
    if np.any(np.abs(speeds) > 20.0):
        raise ValueError(f"--speeds {args.speeds!r} is invalid for a layout or reverse speeds; valid range: every "
                         "0.01 <= |U| <= 20 m/s (negative: reverse)")
    if args.export_c and (args.reverse or (np.any(speeds > 0) and np.any(speeds < 0))):
        raise ValueError(f"--export-c with --speeds {args.speeds!r}{' --reverse' if args.reverse else ''} is invalid: "
                         "a table over speed cannot pass through 0 m/s, where a layout's casters swing round (no "
                         "linear model there); valid: the speeds of one direction, all positive (forward) or all "
                         "negative (reverse), without --reverse")
    layout = load_layout(args.chair, args.set)
    with output_files({"--json-file": args.json_file, "-o": args.output}) as tmp:
        return _layout_work(args, layout, speeds, weights, drive, gyro, tmp)


def _layout_work(args: argparse.Namespace, layout: Layout, speeds: np.ndarray, weights: Weights, drive: DriveTrain,
                 gyro: GyroSensor, tmp: dict[str, str]) -> int:
    from stability import __version__
    from stability.assist.layout import format_layout_assist, layout_assist

    # the full-state controller measures the motor's applied moment, which the layout simulator does not give it
    simulable = args.design == "gyro" or drive.motor_time_constant == 0
    res = layout_assist(layout, [float(u) for u in speeds], args.design, reverse=args.reverse, weights=weights,
                        drive=drive, gyro=gyro, check=not args.no_check and simulable, faults=args.faults,
                        seed=args.seed)
    least = _layout_min_torque(layout, res, weights, drive, gyro) if args.min_torque else None
    fw = _layout_firmware(args, layout, res, weights, drive, gyro) if args.export_c else None
    if args.json or args.json_file:
        options = {"speeds_m_s": [float(u) for u in speeds], "design": args.design, "reverse": args.reverse,
                   "wheel_radius_m": drive.wheel_radius, "torque_limit_N_m": drive.torque_limit,
                   "motor_lag_s": drive.motor_time_constant, "sample_rate_hz": gyro.sample_rate_hz,
                   "no_check": args.no_check, "min_torque": args.min_torque, "export_c": args.export_c,
                   "q_format": args.q_format, "seed": args.seed, "faults": args.faults}
        extra: dict = {} if least is None else {"minimum_torque_limits": minimum_torque_json(least)}
        if fw is not None:
            extra["firmware"] = fw.to_dict()
        emit_json({"stability_version": __version__, "chair": layout.name, "model": "exact", "options": options,
                   **res.to_mapping(), **extra}, args, write_to=tmp["--json-file"] if args.json_file else None)
    if not args.json:
        print(format_layout_assist(res))
        for u, t in least or []:
            least_words = (f"{t:.1f} N m per wheel" if math.isfinite(t) else
                           f"none up to the drive's {drive.torque_limit:g} N m per wheel")
            print(f"smallest torque limit that recovers from {STRONG_FORCE:g} N x {THESIS_PUSH.duration:g} s at "
                  f"{abs(u):g} m/s {'backwards' if u < 0 else 'forwards'}: {least_words} (layout simulator, "
                  f"noise-free, same gains; recovers: {recovery_rule()})")
        if fw is not None:
            print(fw.format())
        if not args.no_check and not simulable:
            print(f"nonlinear checks: not run for --design full-state with a motor lag ({drive.motor_time_constant:g} "
                  "s; the controller would measure the motor's applied moment, which the layout simulator does not "
                  "give it): --design gyro or --motor-lag 0 runs them")
    if args.output:
        _write_layout_pdf(layout, res, weights, drive, gyro, tmp["-o"])
    for option, path in (("--json-file", args.json_file), ("-o", args.output)):
        if option in tmp:
            print(f"wrote {path}", file=sys.stderr if args.json else sys.stdout)
    return 0


def _write_layout_pdf(layout: Layout, res: LayoutAssist, weights: Weights, drive: DriveTrain, gyro: GyroSensor,
                      path: str) -> None:
    """``-o`` on a layout: the gains and growth rates of both directions, then per direction the short form's
    continuous-vs-sampled margins and safe-top-speed pages on the direction's schedule, then the recoveries."""
    from stability.assist import figures
    from stability.assist.figures_layout import figure_layout_gains, figure_layout_recovery
    from stability.assist.figures_safety import figure_top_speed
    from stability.assist.layout import LAYOUT_TORQUE_WORDS, layout_schedule

    figs = [figure_layout_gains(res)]
    for rows, top, bad in ((res.forward, res.forward_top, res.forward_faults),
                           (res.reverse, res.reverse_top, res.reverse_faults)):
        if not rows:
            continue
        sched = _schedule_of(res, rows, res.kind) or layout_schedule(layout, [r.speed_m_s for r in rows], res.kind,
                                                                     weights=weights, drive=drive, gyro=gyro)
        figs.append(figures.figure_margin_pair(sched, margin_curves([r.speed_m_s for r in rows],
                                                                    [r.margin_pair for r in rows])))
        if top is not None:
            figs.append(figure_top_speed(sched, top, None if bad is None else
                                         [replace(f, speed_m_s=abs(f.speed_m_s)) for f in bad], _LAYOUT_ENABLE,
                                         LAYOUT_TORQUE_WORDS))
    rec = figure_layout_recovery(res)
    if rec is not None:
        figs.append(rec)
    write_pdf(figs, path, title=f"stability.assist: {res.kind} LQR for {layout.name}")


def _schedule_of(res: LayoutAssist, rows: tuple, kind: str) -> LayoutSchedule | None:
    """The schedule ``res`` read ``rows`` (its forward or reverse rows) from, when it is of design ``kind`` (the
    one :func:`~stability.assist.layout.layout_schedule` call on the same options; None: build it)."""
    sched = res.schedules[0 if rows is res.forward else 1]
    return sched if sched is not None and rows and res.kind == kind else None


def _layout_firmware(args: argparse.Namespace, layout: Layout, res: LayoutAssist, weights: Weights,
                     drive: DriveTrain, gyro: GyroSensor) -> FirmwareReport:
    """``--export-c`` on a layout: the gyro schedule of the one direction asked
    (:func:`~stability.assist.layout.layout_schedule`) written as firmware, its vectors recorded with the layout
    simulator (:func:`~stability.assist.layout_checks.layout_vector_loop`); a warning as the short form's when the
    schedule goes beyond the direction's safe top speed."""
    from stability.assist.layout import layout_schedule
    from stability.assist.layout_checks import layout_vector_loop

    rows, top = (res.forward, res.forward_top) if res.forward else (res.reverse, res.reverse_top)
    sched = _schedule_of(res, rows, "gyro") or layout_schedule(layout, [r.speed_m_s for r in rows], "gyro",
                                                               weights=weights, drive=drive, gyro=gyro)
    report = run_export(sched, args.export_c, args.q_format, seed=args.seed, top=top,
                        closed_loop=layout_vector_loop(layout, sched))
    if report.warning:
        print(f"warning: --export-c: {report.warning}", file=sys.stderr)
    return report


def _layout_min_torque(layout: Layout, res: LayoutAssist, weights: Weights, drive: DriveTrain,
                       gyro: GyroSensor) -> list[tuple[float, float]]:
    """``--min-torque`` on a layout: :func:`~stability.assist.layout_checks.layout_minimum_torque_limit` at each
    direction's check speeds (:func:`~stability.assist.layout_checks.check_speeds`), signed m/s and N m per wheel."""
    from stability.assist.layout import layout_design
    from stability.assist.layout_checks import check_speeds, layout_minimum_torque_limit

    out = []
    for rows in (res.forward, res.reverse):
        for u in check_speeds([r.speed_m_s for r in rows]):
            d = layout_design(layout, u, res.kind, weights=weights, drive=drive, gyro=gyro)
            out.append((u, layout_minimum_torque_limit(layout, d, drive)))
    return out
