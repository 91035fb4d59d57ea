"""``python -m stability.assist``: gain schedule, margins, robustness and nonlinear checks of the motor assist."""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.assist._format import fmt
from stability.assist.destabilising import destabilising_moment, destabilising_summary, valid_until
from stability.assist.digital import margin_curves
from stability.assist.driving import (
    COMMAND_FILTER,
    CROSS_SLOPES,
    TRACKING_SPEED,
    SlopeHold,
    TorqueRow,
    slope_hold,
    torque_requirement,
    tracking_runs,
    traction_limit,
)
from stability.assist.export_run import check_export, run_export
from stability.assist.faults import FaultRow, fault_runs, format_faults
from stability.assist.firmware import Q_FORMATS
from stability.assist.recovery import (
    CHECK_SPEEDS,
    STRONG_FORCE,
    decay_agreement,
    minimum_torque_json,
    minimum_torque_limit,
    recovery,
    recovery_runs,
)
from stability.assist.robustness import Robustness, robustness
from stability.assist.schedule import Schedule, schedule
from stability.assist.settling import recovery_rule
from stability.assist.tables import (
    format_margins,
    format_recovery,
    format_slope_holds,
    format_table,
    gain_table,
    pole_curves,
    reverse_table,
)
from stability.assist.top_speed import TopSpeed, check_top_speed, format_top_speed
from stability.assist.tracking import drift_curves
from stability.assist.weights import DESIGNS, GyroSensor, Weights
from stability.chair import Chair
from stability.chair.power import DriveTrain
from stability.cli import (
    OneLineErrorParser,
    add_chair_options,
    add_json_options,
    add_model_option,
    add_output_option,
    check_outputs,
    emit_json,
    json_header,
    load_chair,
    output_files,
    parse_speeds,
    run,
)
from stability.runtime.files import write_pdf
from stability.settings import defaults as D
from stability.settings.reference import THESIS_PUSH

__all__ = ["build_parser", "main"]


def build_parser() -> argparse.ArgumentParser:
    """The command-line parser.

    Returns
    -------
    argparse.ArgumentParser
    """
    p = OneLineErrorParser(prog="python -m stability.assist",
                           description="LQR motor assist (differential drive torque) for a power chair: "
                                       "gain schedule, margins, robustness and a nonlinear check.")
    add_chair_options(p, default=D.POWER_CHAIR)
    p.add_argument("--speeds", default=D.ASSIST_SPEEDS,
                   help=f"design speeds START:STOP:STEP or a list (m/s; default {D.ASSIST_SPEEDS})")
    p.add_argument("--design", default=D.ASSIST_DESIGN, choices=list(DESIGNS),
                   help=f"feedback structure (default {D.ASSIST_DESIGN})")
    add_model_option(p)
    p.add_argument("--max-heading-error", type=float, default=Weights.max_heading_error_deg, metavar="DEG",
                   help="Bryson weight: acceptable heading error (deg, default 2)")
    p.add_argument("--max-yaw-rate", type=float, default=0.0, metavar="DEG_S",
                   help="Bryson weight: acceptable yaw rate (deg/s; default 0 = unweighted)")
    p.add_argument("--torque-limit", type=float, default=DriveTrain.torque_limit, metavar="NM",
                   help="motor torque limit per drive wheel (N m, default 70)")
    p.add_argument("--torque-budget", type=float, default=None, metavar="NM",
                   help="Bryson weight: torque budget per wheel (N m, default half the limit)")
    p.add_argument("--wheel-radius", type=float, default=DriveTrain.wheel_radius, metavar="M",
                   help="drive-wheel radius (m, default 0.178)")
    p.add_argument("--gyro-noise", type=float, default=GyroSensor.noise_density_deg_s, metavar="DEG_S_RTHZ",
                   help="gyro noise density incl. vibration (deg/s/sqrt(Hz), default 0.05)")
    p.add_argument("--gyro-bias", type=float, default=GyroSensor.bias_deg_s, metavar="DEG_S",
                   help="gyro bias after calibration (deg/s, default 0.1)")
    p.add_argument("--sample-rate", type=float, default=GyroSensor.sample_rate_hz, metavar="HZ",
                   help="controller sample rate (Hz, default 200)")
    p.add_argument("--seed", type=int, default=0, help="seed of the gyro noise (default 0)")
    p.add_argument("--no-check", action="store_true",
                   help="skip the nonlinear simulations (the safe top speed is then checked on the margins alone)")
    p.add_argument("--min-torque", action="store_true",
                   help="also find the smallest torque limit that recovers from the 400 N disturbance "
                        "at 1, 2, 3 m/s (a layout: at each direction's check speeds; bisection, ~1 min)")
    p.add_argument("--bias-time-constant", type=float, default=GyroSensor.bias_time_constant_s, metavar="S",
                   help="time constant of the gyro-bias estimate from the wheel speeds (s, default 1; 0: off)")
    p.add_argument("--motor-lag", type=float, default=DriveTrain.motor_time_constant, metavar="S",
                   help="first-order motor/speed-loop lag (s, default 0.02; 0: none)")
    p.add_argument("--reverse", action="store_true", help="also give the reverse-driving rows (open-loop stability)")
    add_json_options(p)
    add_output_option(p, ("pdf",), what="the figures (a PDF, one figure a page)", aliases=("--pdf",))
    p.add_argument("--export-c", metavar="DIR", default=None,
                   help="write the gyro design as C99 firmware into DIR (assist.h, assist.c, assist_vectors.json, "
                        "README.txt; created if missing) at --sample-rate, and report the number format's margins")
    p.add_argument("--faults", action="store_true",
                   help="simulate every single sensor fault at every design speed on level ground and a 2 deg cross "
                        "slope (monitor, detection, degraded mode) and add them to the safe top speed's constraints "
                        "(gyro design; a few minutes)")
    p.add_argument("--q-format", default=D.Q_FORMAT, choices=list(Q_FORMATS),
                   help=f"number format of the exported tables (default {D.Q_FORMAT})")
    return p


def _options(args: argparse.Namespace) -> tuple[Weights, DriveTrain, GyroSensor]:
    # every number was parsed within its range by the parser (stability.cli.numbers.OPTION_BOUNDS)
    w = Weights(max_heading_error_deg=args.max_heading_error,
                max_yaw_rate_deg_s=args.max_yaw_rate or None, torque_budget_nm=args.torque_budget)
    drive = DriveTrain(wheel_radius=args.wheel_radius, torque_limit=args.torque_limit,
                       motor_time_constant=args.motor_lag)
    gyro = GyroSensor(noise_density_deg_s=args.gyro_noise, bias_deg_s=args.gyro_bias,
                      sample_rate_hz=args.sample_rate, bias_time_constant_s=args.bias_time_constant)
    return w, drive, gyro


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.assist``.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status (2 on bad input).
    """
    return run(build_parser(), argv, _run)


def _run(args: argparse.Namespace) -> int:
    check_outputs({"--json-file": args.json_file, "-o": args.output}, {"--chair": args.chair})
    check_export(args.export_c, args.design)
    if args.faults and args.design != "gyro":
        raise ValueError(f"--faults needs --design gyro (got {args.design!r}): the faults are those of the gyro "
                         "and wheel-speed sensors")
    from stability.layout.io import is_layout_spec

    signed = parse_speeds(args.speeds, max_count=50, signed=True)
    if is_layout_spec(args.chair) or np.any(signed < 0):
        from stability.assist.command import run_layout

        return run_layout(args, signed, *_options(args))
    speeds = parse_speeds(args.speeds, increasing=True, max_count=50)
    weights, drive, gyro = _options(args)
    c = load_chair(args.chair, args.set)
    with output_files({"--json-file": args.json_file, "-o": args.output}) as tmp:
        return _work(args, c, speeds, weights, drive, gyro, tmp)


def _work(args: argparse.Namespace, c: Chair, speeds: np.ndarray, weights: Weights, drive: DriveTrain, gyro: GyroSensor,
          tmp: dict[str, str]) -> int:
    sched = schedule(c, speeds, args.design, weights=weights, drive=drive, gyro=gyro, model=args.model)
    rows = gain_table(sched, check=not args.no_check, seed=args.seed)
    rev = reverse_table(sched) if args.reverse else []
    holds = [] if args.no_check else _slope_holds(sched)
    # the safe top speed: the sampled margins always, the torque (nonlinear runs at the design speeds) unless
    # --no-check, the single sensor faults with --faults; the export's README and warning need it
    torques = None if args.no_check else torque_requirement(sched, tuple(float(s) for s in sched.speeds))
    faults = fault_runs(sched, seed=args.seed, progress=True) if args.faults else None
    top = check_top_speed(sched, rows, torque_rows=torques, fault_rows=faults)
    fw_json, fw_text = _firmware(args, sched, top)
    fw_json.update(_top_speed_json(top, faults))
    rob = robustness(sched)
    checks = None if args.no_check else _nonlinear_checks(sched, args.seed, torques or [])
    # --min-torque: the thesis's chapter-9 question at 1, 2, 3 m/s, computed once for the text and the JSON
    least = [(s_, minimum_torque_limit(sched, s_)) for s_ in CHECK_SPEEDS] if args.min_torque else None
    if args.json or args.json_file:
        options = {"speeds_m_s": [float(s) for s in speeds], "design": args.design,
                   "max_heading_error_deg": args.max_heading_error, "max_yaw_rate_deg_s": args.max_yaw_rate,
                   "torque_limit_N_m": args.torque_limit, "torque_budget_N_m": args.torque_budget,
                   "wheel_radius_m": args.wheel_radius, "gyro_noise_deg_s_rthz": args.gyro_noise,
                   "gyro_bias_deg_s": args.gyro_bias, "sample_rate_hz": args.sample_rate, "seed": args.seed,
                   "no_check": args.no_check, "reverse": args.reverse, "motor_lag_s": args.motor_lag,
                   "bias_time_constant_s": args.bias_time_constant, "export_c": args.export_c,
                   "q_format": args.q_format, "faults": args.faults, "min_torque": args.min_torque}
        w = rob.worst
        data = {**json_header(c, args.model, options), "rows": [r.to_dict() for r in rows],
                "reverse": [r.to_dict() for r in rev],
                "robustness": {"box_fraction": rob.box, "stable": bool(rob.stable),
                               "worst_max_real_1_s": float(w.max_real_1_s), "worst_speed_m_s": float(w.speed_m_s),
                               "worst_corner": w.describe()},
                "cross_slope": [h.to_dict() if isinstance(h, SlopeHold) else h for h in holds],
                **(checks.to_dict() if checks else {"recovery": [], "figure_9_4": [], "torque_requirement": None,
                                                    "decay": []}),
                **fw_json,
                **({} if least is None else {"minimum_torque_limits": minimum_torque_json(least)})}
        # the shared writer: NaN or infinity refused (error: could not compute), tire-range notes, atomic file
        emit_json(data, args, write_to=tmp["--json-file"] if args.json_file else None)
        if args.json and not args.output:
            return 0
    print(format_table(sched, rows))
    print(f"\nMargins at the plant input, continuous / sampled at {sched.gyro.sample_rate_hz:g} Hz (ZOH, one-sample "
          f"computation delay, {1e3 * sched.drive.motor_time_constant:g} ms motor lag in both): classical (GM: the "
          "smaller of the gain increase and decrease that destabilises) and balanced disk margins (alpha, and the "
          "gain and phase change it tolerates together; Seiler, Packard & Gahinet 2020); yaw-rate step "
          f"(nonlinear loop, {1e3 * COMMAND_FILTER:g} ms reference model):")
    print(format_margins(rows))
    if rev:
        print("\nReversing (the chair as seen in the direction of travel), open loop: "
              + "; ".join(f"{r.speed_m_s:g} m/s {'stable' if r.stable else 'UNSTABLE'} ({r.max_real_1_s:.3f} 1/s)"
                          for r in rev))
    w = rob.worst
    print(f"\nRobustness, +/-{rob.box:.0%} in mass, yaw inertia, main and caster cornering stiffness (16 corners x "
          f"{len(sched.speeds)} speeds): {'all stable' if rob.stable else 'UNSTABLE corners'}; worst largest real part "
          f"{w.max_real_1_s:.4f} 1/s at {w.speed_m_s:g} m/s, corner " + w.describe())
    runs = None
    if checks is not None:
        runs = checks.runs
        print("\nNonlinear recovery (10 s, WCHAIR scheme, exact model, pin friction, torque limit"
              + (", gyro noise and bias" if sched.kind == "gyro" else "") + "): closed loop vs open loop")
        print(format_recovery(runs))
        print("\nFigure 9-4 criterion, open loop (destabilising yaw moment of the tire forces vs the motors' "
              f"{sched.drive.max_yaw_moment(sched.chair):.0f} N m of yaw moment at {sched.drive.torque_limit:g} N m "
              "per wheel):")
        for closed, d_ in checks.figure_9_4:
            print(f"  {closed.speed:g} m/s, {closed.impulse_force:g} N: peak {d_.peak_moment_N_m:.0f} N m "
                  f"({d_.fraction_of_capacity:.0%}) up to {d_.valid_until_s:.2f} s (heading "
                  f"{d_.heading_at_end_deg:.0f} deg; a slip angle reaches 8 deg or the heading 90 deg)"
                  + ("" if d_.exceeds_capacity_at_s is None else
                     f"; exceeds the motors at {d_.exceeds_capacity_at_s:.2f} s"))
        print("\nTorque requirement (differential torque per wheel, nonlinear loop, noise-free): reference push "
              f"recovery (2 s) and yaw-rate step (3 s); motor limit {sched.drive.torque_limit:g} N m, traction limit "
              f"mu N r = {checks.traction_limit_N_m:.0f} N m (mu = {sched.drive.traction_coefficient:g}, static load)")
        for t_ in checks.torque:
            print(f"  {t_.speed_m_s:g} m/s: push peak {t_.push_peak_N_m:.1f} / RMS {t_.push_rms_N_m:.1f} N m; "
                  f"turn peak {t_.turn_peak_N_m:.1f} / RMS {t_.turn_rms_N_m:.1f} N m, steady turn "
                  f"{t_.steady_turn_N_m:.1f} N m")
        agree = checks.decay
        print("\nLinear vs nonlinear decay (4 N x 0.1 s, pin friction off, 1 kHz): "
              + "; ".join(f"{a.speed_m_s:g} m/s: predicted {a.predicted_1_s:.3f}, fitted "
                          f"{a.fitted_1_s:.3f} 1/s ({a.relative_error:.2%})" for a in agree))
        print(format_slope_holds(holds))
    sys.stdout.write(fw_text)
    if faults is not None:
        print("\n" + format_faults(faults))
    for s_, mt in least or []:
        print(f"smallest torque limit that recovers from {STRONG_FORCE:g} N x {THESIS_PUSH.duration:g} s at {s_:g} "
              f"m/s: {fmt(mt, '.1f')} N m per wheel (noise-free, same gains; recovers: {recovery_rule()})")
    print("\n" + format_top_speed(top))
    if args.output:
        _write_pdf(sched, rows, rob, runs, tmp["-o"], [h for h in holds if isinstance(h, SlopeHold)], top, faults,
                   torques)
    for option, path in (("--json-file", args.json_file), ("-o", args.output)):
        if option in tmp:
            print(f"wrote {path}", file=sys.stderr if args.json else sys.stdout)
    return 0


def _firmware(args: argparse.Namespace, sched: Schedule, top: TopSpeed) -> tuple[dict, str]:
    """``--export-c``: write the firmware; its JSON entry (``{"firmware": ...}`` or empty) and its text block.

    A schedule beyond the safe top speed is written with a warning: one line on stderr and in the README."""
    if not args.export_c:
        return {}, ""
    report = run_export(sched, args.export_c, args.q_format, seed=args.seed, top=top)
    if report.warning:
        print(f"warning: --export-c: {report.warning}", file=sys.stderr)
    return {"firmware": report.to_dict()}, "\n" + report.format() + "\n"


def _top_speed_json(top: TopSpeed, faults: list[FaultRow] | None) -> dict:
    """The top-speed keys of the JSON (and ``faults`` with --faults)."""
    t = top.to_dict()
    out = {"safe_top_speed_m_s": t["safe_top_speed_m_s"], "limited_by": t["limited_by"],
           "top_speed_constraints": t["constraints_checked"], "top_speed_limits": t["limits"],
           "top_speed_checks": t["checks"]}
    return {**out, "faults": [f.to_dict() for f in faults]} if faults is not None else out


@dataclass(frozen=True)
class _Checks:
    """The nonlinear checks the text prints, computed once for the text and the JSON."""

    runs: list
    figure_9_4: list
    torque: list
    traction_limit_N_m: float
    decay: list

    def to_dict(self) -> dict:
        return {
            "recovery": [pair.to_dict() for pair in self.runs],
            "figure_9_4": [{"speed_m_s": closed.speed, "impulse_N": closed.impulse_force, **d.to_dict()}
                           for closed, d in self.figure_9_4],
            "torque_requirement": {"traction_limit_N_m": self.traction_limit_N_m,
                                   "rows": [t.to_dict() for t in self.torque]},
            "decay": [{"speed_m_s": a.speed_m_s, "predicted_1_s": a.predicted_1_s, "fitted_1_s": a.fitted_1_s,
                       "relative_error": a.relative_error} for a in self.decay],
        }


def _nonlinear_checks(sched: Schedule, seed: int, torques: list[TorqueRow]) -> _Checks:
    runs = recovery_runs(sched, seed=seed)
    fig = [(closed, destabilising_summary(opened.result, sched.drive, sched.chair))
           for closed, opened in runs if opened is not None]
    return _Checks(runs, fig, torques, traction_limit(sched), [decay_agreement(sched, s) for s in CHECK_SPEEDS])


def _slope_holds(sched: Schedule) -> list[SlopeHold | dict]:
    """:func:`slope_hold` at :data:`TRACKING_SPEED` on each of :data:`CROSS_SLOPES`; a slope the chair's tires
    cannot hold (no equilibrium inside the tire data) gives ``{"cross_slope_deg", "skipped"}`` instead."""
    out: list[SlopeHold | dict] = []
    for phi in CROSS_SLOPES:
        try:
            out.append(slope_hold(sched, TRACKING_SPEED, phi))
        except ValueError as exc:
            out.append({"cross_slope_deg": phi, "skipped": str(exc)})
    return out


def _write_pdf(sched: Schedule, rows: list, rob: Robustness, runs: list | None, path: str,
               holds: list[SlopeHold], top: TopSpeed, faults: list[FaultRow] | None,
               torques: list[TorqueRow] | None) -> None:
    """The assist figures as a PDF at ``path`` (matplotlib is imported only here)."""
    # matplotlib is imported only when a PDF is asked for
    from stability.assist import figures, figures_slope
    from stability.assist.figures_safety import figure_top_speed

    figs = [figures.figure_gains(sched, rows), figures.figure_poles(sched, rows, pole_curves(sched), rob),
            figures.figure_margins(sched, rows), figures.figure_robustness(rob, sched)]
    ref = destabilising_moment()
    ol = [r.open for r in runs if r.open is not None and r.open.impulse_force == THESIS_PUSH.force] if runs \
        else [recovery(sched.chair, s, None, model=sched.model) for s in CHECK_SPEEDS]
    summ = [destabilising_summary(o.result, sched.drive, sched.chair) for o in ol]
    figs.append(figures.figure_destabilising(
        ref, valid_until(ref, max_heading_deg=math.inf), ol, summ, [valid_until(o.result) for o in ol],
        sched.drive.max_yaw_moment(sched.chair), sched.chair.name))
    if runs is not None:
        figs.append(figures.figure_recovery(runs, sched))
        figs.append(figures.figure_recovery_table(runs, sched))
    # the driving pages are in every PDF, like the Figure 9-4 page: a few short simulations
    tb = sched.gyro.bias_time_constant_s or GyroSensor.bias_time_constant_s
    figs += [figures.figure_tracking(sched, tracking_runs(sched)),
             figures.figure_drift(sched, drift_curves(sched.at(TRACKING_SPEED), bias_time_constant=tb)),
             figures.figure_margin_pair(sched, margin_curves(sched.speeds, [r.margin_pair for r in rows])),
             figures.figure_torque(sched, torques if torques is not None
                                   else torque_requirement(sched, tuple(float(s) for s in sched.speeds)))]
    if holds:
        figs.append(figures_slope.figure_slope_hold(sched, holds))
    figs.append(figure_top_speed(sched, top, faults))
    write_pdf(figs, path, title=f"stability.assist: {sched.kind} LQR for {sched.chair.name}")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
