"""``python -m stability.slope``: holding moment, equilibrium and uncorrected turn on a cross slope.

A wheel layout (``--chair mid-wheel-drive``, a ``[[wheel]]`` file) or a negative ``--speed`` (reverse, any chair)
is answered by the layout model (:func:`stability.study.layout_slope_report.layout_slope_report`).
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Sequence

from stability.chair.power import drive_kind
from stability.cli import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_chair_options,
    add_json_options,
    add_output_option,
    announce_written,
    check_outputs,
    emit_json,
    json_header,
    load_chair,
    load_layout,
    output_files,
    run,
)
from stability.settings import defaults as D
from stability.slope.equilibrium import HandRim, drive_report, solve
from stability.study.veer import VEER_RUN, simulator_path, uncorrected_path
from stability.tires import WHEELS


def build_parser() -> argparse.ArgumentParser:
    p = OneLineErrorParser(prog="python -m stability.slope", description=__doc__)
    add_chair_options(p)
    p.add_argument("--cross-slope", type=float, required=True, metavar="DEG",
                   help="cross slope (deg, or 2%%, 1:50), positive falling to the right")
    p.add_argument("--grade", type=float, default=0.0, metavar="DEG",
                   help="grade (deg, or 8%%, 1:12), uphill + (default 0)")
    p.add_argument("--speed", type=float, required=True, metavar="U",
                   help="speed along the path (m/s; negative: reverse, answered by the layout model)")
    p.add_argument("--sim-time", type=float, default=D.SLOPE_SIM_TIME, metavar="T",
                   help=f"simulator runs of the uncorrected turn: report time (s, 0 < T <= 10; "
                        f"default {D.SLOPE_SIM_TIME:g})")
    p.add_argument("--drive", choices=("auto", "handrim", "motor"), default="auto",
                   help="report hand-rim forces or motor torques (auto: motor for power-* chairs)")
    p.add_argument("--wheel-radius", type=float, default=D.HANDRIM_WHEEL_RADIUS,
                   help=f"hand-rim drive: wheel radius (m, default {D.HANDRIM_WHEEL_RADIUS:g})")
    p.add_argument("--handrim-radius", type=float, default=D.HANDRIM_RADIUS,
                   help=f"hand-rim radius (m, default {D.HANDRIM_RADIUS:g})")
    add_json_options(p)
    add_output_option(p, FIGURE_FORMATS, what="a figure (holding moment and drive difference against cross slope "
                      "from 0 to 6 deg and this slope, and the uncorrected heading at this slope)")
    return p


def _finite(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    return x


def _simulated(chair, eq, t_end: float) -> dict:
    """The simulator's uncorrected turn, both schemes, with the chair's Coulomb pin friction and without."""
    out: dict = {}
    for scheme in ("adaptive", "wchair"):
        for friction in (True, False):
            key = f"{scheme}_{'pin_friction' if friction else 'frictionless'}"
            try:
                path = simulator_path(chair, eq, VEER_RUN.replace(scheme=scheme, horizon=t_end),
                                      pin_friction=friction, report_time=t_end)
            except ValueError as exc:   # e.g. viscous pin damping, a slope beyond the simulator's 15 deg
                out[key] = {"error": str(exc)}
                continue
            d = path.to_dict()
            d.pop("quasi_steady_yaw_rate_deg_s")
            out[key] = d
    return out


def _schemes_verdict(sim: dict, t_end: float) -> str:
    """Which of the two schemes' uncorrected turns to read when they end at different times (one sentence)."""
    ends = {k: d for k, d in sim.items() if "error" not in d}
    short = [k for k, d in ends.items() if k.startswith("wchair") and "warning" in d["ended"]
             and d["report_time_s"] < 0.5 * t_end]
    if not short:
        return ""
    return ("the fixed-step (wchair) runs stop at their eleventh warning beyond the tire data, before the report "
            "time; read the adaptive scheme's runs (event-located, no warning stop), and note that the turn they "
            "show runs on extrapolated tire data past that point")


def _run_layout(a: argparse.Namespace) -> int:
    """A wheel layout, or any chair in reverse: the layout model's statics and the layout simulator."""
    from stability import __version__
    from stability.study.layout_slope_report import layout_slope_report

    layout = load_layout(a.chair, a.set)
    data, lines = layout_slope_report(layout, a.cross_slope, a.speed, a.grade, a.sim_time, a.drive,
                                      HandRim(a.wheel_radius, a.handrim_radius))
    with output_files({"-o": a.output, "--json-file": a.json_file}) as tmp:    # renamed together: all or none
        if a.output:
            from stability.report.slope_figure import layout_slope_figure
            from stability.runtime.files import save_figure

            save_figure(layout_slope_figure(layout, a.cross_slope, a.speed, a.grade, a.drive, a.sim_time), tmp["-o"],
                        title=f"stability slope: {layout.name}, {a.cross_slope:g} deg")
        if a.json or a.json_file:
            options = {"cross_slope_deg": a.cross_slope, "grade_deg": a.grade, "speed_m_s": a.speed, "drive": a.drive,
                       "sim_time_s": a.sim_time}
            emit_json({"stability_version": __version__, "chair": layout.name, "model": "exact", "options": options,
                       **_finite(data)}, a, write_to=tmp.get("--json-file"))
    announce_written(a.output, a.json_file)
    if not a.json:
        print("\n".join(lines))
    return 0


def _body(a: argparse.Namespace) -> int:
    from stability.layout.io import is_layout_spec

    check_outputs({"--json-file": a.json_file, "-o": a.output}, {"--chair": a.chair})
    if is_layout_spec(a.chair) or a.speed < 0:
        return _run_layout(a)
    chair = load_chair(a.chair, a.set)
    eq = solve(chair, a.cross_slope, a.speed, a.grade)
    per_deg_eq = eq if a.cross_slope != 0 else solve(chair, 1.0, a.speed, a.grade)
    per_deg = abs(per_deg_eq.holding_moment) / abs(per_deg_eq.cross_slope_deg)
    kind = a.drive if a.drive != "auto" else drive_kind(chair)
    drive = drive_report(chair, eq, kind, HandRim(a.wheel_radius, a.handrim_radius) if kind == "handrim" else None)
    path, why = None, None
    if a.cross_slope != 0:
        try:
            path = uncorrected_path(chair, eq, report_time=a.sim_time)
        except ValueError as exc:     # e.g. viscous pin damping, which the simulator does not have
            why = str(exc)
    sim = _simulated(chair, eq, a.sim_time) if a.cross_slope != 0 else None
    data = {
        "chair": chair.name, "cross_slope_deg": eq.cross_slope_deg, "grade_deg": eq.grade_deg, "speed_m_s": eq.speed,
        "holding_yaw_moment_N_m": abs(eq.holding_moment),
        "holding_yaw_moment_signed_N_m": eq.holding_moment,
        "holding_yaw_moment_N_m_per_deg": per_deg,
        "holding_yaw_moment_closed_form_N_m": abs(eq.closed_form),
        "holding_yaw_moment_pin_friction_range_N_m": list(eq.friction_range),
        "uncorrected_turn": path.turn if path else "none",
        "uncorrected_turn_statics": eq.uncorrected_turn,
        "uncorrected_path": path.to_dict() if path else None,
        "uncorrected_simulator": sim,
        "heading_deg": eq.heading_deg, "caster_angle_left_deg": eq.eta_deg, "caster_angle_right_deg": eq.beta_deg,
        **{key: {w: x for (w, _), x in zip(WHEELS, values, strict=True)} for key, values in (
            ("slip_angles_deg", eq.slips_deg), ("lateral_forces_N", eq.lateral_forces), ("normal_loads_N", eq.loads))},
        "drive_forces": drive,
        "problems": list(eq.problems),
    }
    data = _finite(data)
    with output_files({"-o": a.output, "--json-file": a.json_file}) as tmp:    # renamed together: all or none
        if a.output:
            from stability.report.slope_figure import slope_figure
            from stability.runtime.files import save_figure

            save_figure(slope_figure(chair, a.cross_slope, a.speed), tmp["-o"],
                        title=f"stability slope: {chair.name}, {a.cross_slope:g} deg")
        if a.json or a.json_file:
            options = {"cross_slope_deg": a.cross_slope, "grade_deg": a.grade, "speed_m_s": a.speed, "drive": kind,
                       "wheel_radius_m": a.wheel_radius, "handrim_radius_m": a.handrim_radius,
                       "sim_time_s": a.sim_time}
            emit_json({**json_header(chair, "exact", options), **data}, a, write_to=tmp.get("--json-file"))
    announce_written(a.output, a.json_file)
    if a.json:
        return 0
    turn = data["uncorrected_turn"]
    print(f"{chair.name}: cross slope {eq.cross_slope_deg:.3g} deg, grade {eq.grade_deg:.3g} deg, {eq.speed:g} m/s")
    print(f"  holding yaw moment {abs(eq.holding_moment):.3f} N m ({eq.holding_moment:+.3f} signed, clockwise +; "
          f"{per_deg:.3f} N m/deg); with Coulomb pin friction any of {eq.friction_range[0]:.3f} .. "
          f"{eq.friction_range[1]:.3f} N m")
    extra = (f", heading {path.heading_change_deg:+.1f} deg (downhill +) after {path.report_time:.2f} s"
             if path else "")
    print(f"  uncorrected: turns {turn}{extra}" if why is None else f"  uncorrected: not run ({why})")
    for key, d in (sim or {}).items():
        if "error" in d:
            print(f"  simulator {key.replace('_', ' ')}: not run ({d['error']})")
            continue
        print(f"  simulator {key.replace('_', ' ')}: turns {d['uncorrected_turn']}, heading "
              f"{d['heading_change_deg']:+.2f} deg, yaw rate {d['yaw_rate_deg_s']:+.1f} deg/s "
              f"at {d['report_time_s']:.2f} s" + ("" if d["ended"] == "horizon" else f" (run ends: {d['ended']})"))
    verdict = _schemes_verdict(sim or {}, a.sim_time)
    if verdict:
        print(f"  {verdict}")
    print(f"  crab {eq.heading_deg:+.3f} deg, casters {eq.eta_deg:+.3f} / {eq.beta_deg:+.3f} deg; loads "
          + ", ".join(f"{x:.1f}" for x in eq.loads) + " N (A, B, D, E)")
    if kind == "handrim":
        print(f"  hand-rim forces left {drive['handrim_force_left_N']:.2f} N, "
              f"right {drive['handrim_force_right_N']:.2f} N (right - left "
              f"{drive['handrim_force_difference_N']:+.2f} N: the {drive['harder_side']} rim works harder)")
    else:
        print(f"  motor torques left {drive['motor_torque_left_N_m']:.2f}, right {drive['motor_torque_right_N_m']:.2f}"
              f" N m (differential (left - right)/2 {drive['differential_torque_N_m']:+.2f} N m: the "
              f"{drive['harder_side']} wheel works harder)")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    return run(build_parser(), argv, _body)


if __name__ == "__main__":
    raise SystemExit(main())
