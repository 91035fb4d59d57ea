"""The value groups of docs/layouts.md on slopes, the assist and reversing (any wheel layout): one function per group.

As :mod:`value_groups_pages`: each function calls the toolkit's public API and returns formatted strings or
:class:`value_groups.Table`; import :mod:`value_groups`, not this module.
"""

from __future__ import annotations

from value_groups import Table, fixed, group, sig, signed

DRIVE_LAYOUTS = ("power-fwd-base", "mid-wheel-drive", "power-rwd-base")
#: The relative error within which tests/test_assist.py and tests/test_assist_layout_checks.py hold the decay.
DECAY_TOLERANCE = 0.05
SLOPE_DEG, SLOPE_SPEED = 2.0, 1.0
#: The speed of the commanded turns' table (m/s): the reference turn (1 m/s^2 lateral) below the full joystick turn.
TURN_SPEED = 2.0


@group("layout_slope", "python -m stability.slope --chair NAME --cross-slope 2 --speed 1|-1 "
       "(stability.study.layout_slope.layout_equilibrium, layout_uncorrected_path)")
def layout_slope() -> dict:
    """Holding moment, pin-friction range, the statics' turn and the simulator's heading after 1 s, per drive layout
    forward and in reverse, and the largest departure from the closed form."""
    from stability.layout.presets import layout_preset
    from stability.study.layout_slope import layout_equilibrium, layout_uncorrected_path

    rows, out = [], {}
    for name in DRIVE_LAYOUTS:
        lay = layout_preset(name)
        for speed in (SLOPE_SPEED, -SLOPE_SPEED):
            eq = layout_equilibrium(lay, SLOPE_DEG, speed)
            path = layout_uncorrected_path(lay, eq, 1.0)
            lo, hi = eq.friction_range_N_m
            direction = "forward" if speed > 0 else "reverse"
            out[f"{name}.{direction}.holding"] = fixed(eq.holding_moment_N_m, 2)
            rows.append((name, direction, fixed(eq.holding_moment_N_m, 2), f"{fixed(lo, 2)} .. {fixed(hi, 2)}",
                         eq.uncorrected_turn, f"{signed(path.heading_change_deg, 2)} at {path.report_time_s:.2f} s"))
    out["table"] = Table((f"layout ({SLOPE_DEG:g} deg, {SLOPE_SPEED:g} m/s)", "direction", "holding N m",
                          "with pin friction N m", "front turns", "simulator heading deg (pin friction)"),
                         tuple(rows))
    out["slope_deg"], out["speed"] = f"{SLOPE_DEG:g}", f"{SLOPE_SPEED:g}"
    return out


@group("layout_assist", "python -m stability.assist --chair NAME --speeds 0.5,1.5,3 --reverse "
       "(stability.assist.layout.layout_assist)")
def layout_assist_values() -> dict:
    """Open-loop growth, sampled margins and the margins' safe top speed of the gyro design, per drive layout and
    direction."""
    import warnings

    from stability.assist.layout import layout_assist
    from stability.layout.presets import layout_preset

    speeds = (0.5, 1.5, 3.0)
    rows = []
    for name in DRIVE_LAYOUTS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")    # python-control's overflow note at a huge candidate frequency
            a = layout_assist(layout_preset(name), speeds, reverse=True)
        for direction, rs, top in (("forward", a.forward, a.forward_top), ("reverse", a.reverse, a.reverse_top)):
            disc = [r.margin_pair.to_dict()["discrete"] for r in rs]
            gains = [float(d["gain_db"]) for d in disc]
            phases = [float(d["phase_deg"]) for d in disc]
            grow = ", ".join(sig(r.open_loop_growth_1_s, 2) for r in rs)
            safe = "none" if top is None or top.safe_top_speed_m_s is None else f"{top.safe_top_speed_m_s:g}"
            if top is not None and top.limited_by == "design_grid":
                safe += " (every design speed)"
            rows.append((name, direction, grow, f"{fixed(min(gains), 1)}-{fixed(max(gains), 1)}",
                         f"{fixed(min(phases), 0)}-{fixed(max(phases), 0)}", safe))
    return {"table": Table(("layout", "direction", "open-loop growth 1/s at " + ", ".join(f"{u:g}" for u in speeds)
                            + " m/s", "sampled gain margin dB", "phase margin deg", "safe top speed m/s (margins)"),
                           tuple(rows)),
            "speeds": ", ".join(f"{u:g}" for u in speeds)}


@group("layout_guo", "stability.simulate.layout.simulate_layout(layout, -0.75, RunSpec(push_force=P, "
       "stop_on_warnings=False), caster_angles_deg=[A] * casters).heading_at(1 / 0.75)")
def layout_guo() -> dict:
    """Heading after backing 1 m at 0.75 m/s from casters at 0, +-90 and 180 deg, with and without the push."""
    from stability.chair import preset
    from stability.layout import Layout
    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.simulate.layout import simulate_layout

    speed, distance = -0.75, 1.0
    angles = (0.0, 90.0, -90.0, 180.0)
    rows = []
    for name, lay in (("ej-premier-front-caster", Layout.from_chair(preset("ej-premier-front-caster"))),
                      ("mid-wheel-drive", layout_preset("mid-wheel-drive"))):
        for push in (0.0, RunSpec().push_force):
            t = distance / abs(speed)
            run = RunSpec(horizon=t + 0.01, push_force=push, stop_on_warnings=False)
            cells = [fixed(abs(simulate_layout(lay, speed, run, caster_angles_deg=[a] * len(lay.casters))
                               .heading_at(t)), 2) for a in angles]
            rows.append((name, "none" if push == 0 else f"{push:g} N for {RunSpec().push_duration:g} s", *cells))
    return {"table": Table(("chair", "push", *(f"|heading| deg, casters at {a:g} deg" for a in angles)),
                           tuple(rows)),
            "speed": f"{abs(speed):g}", "distance": f"{distance:g}"}


@group("layout_sheet", "python -m stability.report --chair NAME --clinician --speeds 0.5,0.75,1 "
       "(stability.report.layout_clinician.layout_clinician_sheet)")
def layout_sheet() -> dict:
    """Per drive layout: what it does after the bump at each of the sheet's speeds, the cross-slope drive difference
    and the smallest tip angle; and the thesis chair's sheet as a layout against the short form's."""
    from stability.chair import preset
    from stability.layout import Layout
    from stability.layout.presets import layout_preset
    from stability.report.clinician import CLINIC_SLOPE_DEG
    from stability.report.clinician_sheet import clinician_sheet
    from stability.report.layout_clinician import layout_clinician_sheet

    speeds = (0.5, 0.75, 1.0)
    rows = []
    for name in DRIVE_LAYOUTS:
        s = layout_clinician_sheet(layout_preset(name), speeds)
        e = s.effort
        effort = "-" if e is None else (f"{sig(e.difference, 3)} N m ({e.harder_side} motor)" if e.drive == "motor"
                                        else f"{sig(e.difference, 3)} N ({e.harder_side} rim)")
        rows.append((name, "; ".join(m.kind for m in s.motions), effort, fixed(min(s.tipping.values()), 1)))
    c = preset("ej-premier")
    a, b = clinician_sheet(c, speeds), layout_clinician_sheet(Layout.from_chair(c), speeds)
    ttl = [(x.time_to_level, y.time_to_level) for x, y in zip(a.motions, b.motions, strict=True)
           if x.time_to_level != float("inf")]
    worst = max(abs(y - x) / x for x, y in ttl)
    return {"table": Table(("layout", "after the bump at " + ", ".join(f"{u:g}" for u in speeds) + " m/s",
                            f"drive difference on {CLINIC_SLOPE_DEG:g} deg", "smallest tip angle deg"), tuple(rows)),
            "speeds": ", ".join(f"{u:g}" for u in speeds), "ej_time_agreement": f"{worst:.0e}"}


@group("layout_turns", "python -m stability.assist --chair NAME --speeds 2 --reverse --json (its torque check: "
       "stability.assist.driving.torque_requirement, stability.assist.top_speed.full_turn_peaks on a layout schedule)")
def layout_turns() -> dict:
    """Per drive layout and direction at 2 m/s: the peak torque per wheel of the reference push, the reference turn
    (its steady torque) and the full joystick turn, in the layout simulator (the short form's commanded runs)."""
    from stability.assist.commands import MAX_YAW_RATE, reference_command
    from stability.assist.driving import torque_requirement
    from stability.assist.layout import layout_schedule
    from stability.assist.top_speed import full_turn_peaks
    from stability.layout.presets import layout_preset

    rows = []
    for name in DRIVE_LAYOUTS:
        for speed in (TURN_SPEED, -TURN_SPEED):
            sched = layout_schedule(layout_preset(name), [speed])
            (t,) = torque_requirement(sched, (speed,))
            full = full_turn_peaks(sched, [speed])[speed]
            rows.append((name, "forward" if speed > 0 else "reverse", fixed(t.push_peak_N_m, 1),
                         fixed(t.turn_peak_N_m, 1), signed(t.steady_turn_N_m, 1), fixed(full, 1)))
    return {"table": Table((f"layout ({TURN_SPEED:g} m/s)", "direction", "push peak N m", "reference turn peak N m",
                            "steady turn N m", "full joystick turn peak N m"), tuple(rows)),
            "reference": f"{reference_command(TURN_SPEED):g}", "speed": f"{TURN_SPEED:g}", "full": f"{MAX_YAW_RATE:g}"}


@group("layout_assist_checks", "python -m stability.assist --chair NAME --speeds 1 --reverse "
       "(stability.assist.layout_checks.layout_checks)")
def layout_assist_checks() -> dict:
    """Per drive layout and direction at 1 m/s: the peak torque after the reference and the strong push, the
    peak heading error after the strong push, and the decay against the linear prediction; the power chair as a
    layout against the short form's checks."""
    import warnings

    import numpy as np

    from stability.assist.controller import DigitalController
    from stability.assist.layout import layout_design
    from stability.assist.layout_checks import CHECK_SPEEDS, layout_checks, layout_decay_agreement, layout_recovery
    from stability.assist.recovery import STRONG_FORCE, decay_agreement, recovery
    from stability.assist.schedule import schedule
    from stability.chair import preset
    from stability.chair.power import DriveTrain
    from stability.layout import Layout
    from stability.layout.presets import layout_preset

    drive, rows = DriveTrain(), []
    for name in DRIVE_LAYOUTS:
        lay = layout_preset(name)
        for speed in (1.0, -1.0):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                chk = layout_checks(lay, [layout_design(lay, speed, "gyro", drive=drive)], drive)
            ref, strong = chk.recoveries
            a = chk.decays[0]
            rows.append((name, "forward" if speed > 0 else "reverse", fixed(ref.peak_torque_N_m, 1),
                         fixed(strong.peak_torque_N_m, 1), fixed(strong.peak_heading_error_deg, 2),
                         f"{fixed(a.predicted_1_s, 2)} / {fixed(a.fitted_1_s, 2)}"))
    c = preset("power-fwd")
    sched = schedule(c, np.array([1.0]), "gyro")
    d = sched.at(1.0)
    lay = Layout.from_chair(c)
    dl = layout_design(lay, 1.0, "gyro", drive=sched.drive, gyro=sched.gyro)
    short = recovery(c, 1.0, DigitalController(d, c, sched.drive, gyro=sched.gyro, noise=False),
                     impulse_force=STRONG_FORCE)
    mine = layout_recovery(lay, dl, sched.drive, push=STRONG_FORCE)
    da, db = decay_agreement(sched, 1.0), layout_decay_agreement(lay, dl, sched.drive)
    return {"table": Table(("layout (1 m/s)", "direction", "peak torque N m, reference push",
                            "peak torque N m, strong push", "peak heading error deg, strong push",
                            "decay 1/s linear / simulated"), tuple(rows)),
            "short_torque": fixed(short.peak_torque_N_m, 2), "layout_torque": fixed(mine.peak_torque_N_m, 2),
            "short_heading": fixed(short.peak_heading_error_deg, 3),
            "layout_heading": fixed(mine.peak_heading_error_deg, 3),
            "decay_agreement": f"{abs(db.fitted_1_s - da.fitted_1_s) / abs(da.fitted_1_s):.0e}",
            "strong": f"{STRONG_FORCE:g}",
            "check_speeds": ", ".join(f"{u:g}" for u in CHECK_SPEEDS[:-1]) + f" and {CHECK_SPEEDS[-1]:g}",
            "decay_tolerance": f"{100 * DECAY_TOLERANCE:g}"}


@group("layout_assist_options", "python -m stability.assist --chair NAME --speeds 1 --reverse --min-torque; "
       "--export-c (stability.assist.layout_checks.layout_minimum_torque_limit, "
       "stability.assist.layout.layout_schedule)")
def layout_assist_options() -> dict:
    """Per drive layout and direction at 1 m/s: the smallest torque limit that recovers from the strong push and
    the order of the exported estimator; the power chair as a layout against the short form (its smallest torque
    at 2 m/s, its firmware tables)."""
    import math
    from inspect import signature

    import numpy as np

    from stability.assist.commands import COMMAND_FILTER
    from stability.assist.firmware import firmware_tables
    from stability.assist.layout import layout_design, layout_schedule
    from stability.assist.layout_checks import layout_minimum_torque_limit
    from stability.assist.recovery import SETTLE_FRACTION, minimum_torque_limit
    from stability.assist.schedule import schedule
    from stability.chair import preset
    from stability.chair.power import DriveTrain
    from stability.layout import Layout
    from stability.layout.presets import layout_preset

    drive, rows = DriveTrain(), []

    def torque(x: float) -> str:
        return fixed(x, 1) if math.isfinite(x) else f"none up to {drive.torque_limit:g}"

    for name in DRIVE_LAYOUTS:
        lay = layout_preset(name)
        for speed in (1.0, -1.0):
            least = layout_minimum_torque_limit(lay, layout_design(lay, speed, "gyro", drive=drive), drive)
            order = firmware_tables(layout_schedule(lay, [speed]), command_filter_s=COMMAND_FILTER).n
            rows.append((name, "forward" if speed > 0 else "reverse", torque(least), str(order)))
    c = preset("power-fwd")
    sched = schedule(c, np.array([1.0, 2.0, 3.0]), "gyro", standstill=False)
    lay = Layout.from_chair(c)
    short_t = minimum_torque_limit(sched, 2.0)
    mine_t = layout_minimum_torque_limit(lay, layout_design(lay, 2.0, "gyro", drive=sched.drive, gyro=sched.gyro),
                                         sched.drive)
    a = firmware_tables(layout_schedule(lay, [1.0, 2.0, 3.0]), command_filter_s=COMMAND_FILTER)
    b = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    worst = max(float(np.abs(getattr(a, k) - getattr(b, k)).max() / np.abs(getattr(b, k)).max()) for k in b.TABLES)
    return {"table": Table(("layout (1 m/s)", "direction", "smallest torque limit N m per wheel, strong push",
                            "estimator order of the firmware"), tuple(rows)),
            "short_torque": torque(short_t), "layout_torque": torque(mine_t), "table_agreement": f"{worst:.0e}",
            "settle_pct": f"{100 * SETTLE_FRACTION:g}",
            "max_heading": f"{signature(layout_minimum_torque_limit).parameters['max_heading_deg'].default:g}"}


@group("layout_assist_faults", "python -m stability.assist --chair NAME --speeds 1:3:0.5 --reverse --no-check "
       "--faults (stability.assist.layout.layout_assist, stability.assist.faults.fault_runs)")
def layout_assist_faults() -> dict:
    """Per drive layout and direction: the safe top speed with the single sensor faults (speeds 1 to 3 m/s), what
    limits it, the unsafe fault runs; the power chair as a layout against the short form's fault rows."""

    from stability.assist.faults import fault_runs
    from stability.assist.layout import layout_assist, layout_schedule
    from stability.assist.schedule import schedule
    from stability.chair import preset
    from stability.layout import Layout
    from stability.layout.presets import layout_preset

    grid = [1.0, 1.5, 2.0, 2.5, 3.0]
    rows = []
    for name in DRIVE_LAYOUTS:
        res = layout_assist(layout_preset(name), grid, "gyro", reverse=True, faults=True)
        for what, top, bad in (("forward", res.forward_top, res.forward_faults),
                               ("reverse", res.reverse_top, res.reverse_faults)):
            unsafe = sorted({f"{f.fault} ({abs(f.speed_m_s):g} m/s, {f.slope_deg:g} deg)" for f in bad
                             if f.outcome != "safe"})
            speed = "none" if top.safe_top_speed_m_s is None else f"{top.safe_top_speed_m_s:g}"
            rows.append((name, what, speed, top.limited_by.replace("_", " "), "; ".join(unsafe[:3]) +
                         (f"; and {len(unsafe) - 3} more" if len(unsafe) > 3 else "") or "none"))
    c = preset("power-fwd")
    short = fault_runs(schedule(c, [1.0, 2.0], standstill=False))
    mine = fault_runs(layout_schedule(Layout.from_chair(c), [1.0, 2.0]))
    pairs = list(zip(short, mine, strict=True))
    worst = max(max(abs(a.peak_heading_error_deg - b.peak_heading_error_deg),
                    abs(a.peak_yaw_rate_deg_s - b.peak_yaw_rate_deg_s)) for a, b in pairs)
    same = all((a.detected, a.outcome) == (b.detected, b.outcome) for a, b in pairs)
    return {"table": Table(("layout", "direction", f"safe top speed m/s ({grid[0]:g} to {grid[-1]:g} m/s)",
                            "limited by", "unsafe fault runs (speed, cross slope)"), tuple(rows)),
            "short_agreement": f"{worst:.0e}", "short_same": "the same" if same else "NOT the same",
            "short_runs": f"{len(short)}", "grid": f"{grid[0]:g} to {grid[-1]:g}"}


@group("layout_files", "python -m stability.simulate --chair NAME --csv FILE -o FILE; python -m stability.slope "
       "--chair NAME -o FILE; python -m stability.shimmy --chair NAME -o FILE (stability.simulate.layout, "
       "stability.report.slope_data.layout_slope_section, stability.shimmy.chair.trail_chart)")
def layout_files() -> dict:
    """The E&J Premier as a layout against the short form in the three commands' files (largest relative
    difference of the CSV columns, largest difference of the slope figure's curves and of the trail chart's yaw
    divergence), and per drive layout the simulate figure's caption numbers after the reference push."""
    import numpy as np

    from stability.chair import preset
    from stability.layout import Layout
    from stability.layout.presets import layout_preset
    from stability.report.slope_data import layout_slope_section, slope_section
    from stability.settings.run import RunSpec
    from stability.shimmy.chair import trail_chart
    from stability.shimmy.layout_caster import LayoutCaster
    from stability.simulate import simulate
    from stability.simulate.layout import simulate_layout

    ej = preset("ej-premier")
    run = RunSpec(horizon=2.0)
    lay, short = simulate_layout(Layout.from_chair(ej), None, run), simulate(ej, run=run)
    pairs = ((lay.heading_rad, short.heading), (lay.yaw_rate_rad_s, short.yaw_rate), (lay.y_m, short.y),
             (lay.caster_angle_rad[0], short.eta), (lay.caster_angle_rad[1], short.beta))
    csv_rel = max(float(np.abs(a - np.asarray(b)).max() / np.abs(np.asarray(b)).max()) for a, b in pairs)
    slopes = (0.0, 1.0, 2.0, 4.0)
    s_short = slope_section(ej, speed=1.0, slopes=slopes, path_slope=2.0)
    s_lay = layout_slope_section(Layout.from_chair(ej), 1.0, slopes, 2.0)
    slope_diff = float(np.abs(s_lay.curve.holding_moment - s_short.curve.holding_moment).max())
    trails = np.linspace(0.03, 0.09, 4)
    c_short = trail_chart(ej, trails, [0.5, 2.0])
    c_lay = trail_chart(LayoutCaster(Layout.from_chair(ej), 0), trails, [0.5, 2.0])
    chart_diff = float(np.abs(c_lay.divergence_rate - c_short.divergence_rate).max())
    rows = []
    for name in DRIVE_LAYOUTS:
        layout = layout_preset(name)
        for speed, angle in ((0.75, 0.0), (-0.75, 180.0)):
            r = simulate_layout(layout, speed, RunSpec(horizon=3.0), caster_angles_deg=[angle] * len(layout.casters))
            swing = max(float(np.degrees(np.abs(np.angle(np.exp(1j * (a - a[0])))).max()))
                        for a in r.caster_angle_rad)
            rows.append((name, "forward" if speed > 0 else "reverse", signed(r.final_heading_deg, 2),
                         signed(float(r.y_m[-1]), 3), fixed(swing, 1)))
    return {"csv_rel": f"{csv_rel:.0e}", "csv_horizon": f"{run.horizon:g}", "slope_diff": f"{slope_diff:.0e}",
            "chart_diff": f"{chart_diff:.0e}",
            "table": Table(("layout (0.75 m/s, reference push, 3 s)", "direction", "heading at 3 s deg",
                            "lateral offset m", "largest caster swing deg"), tuple(rows))}


@group("layout_every_command", "python -m stability.advise|compare|report --chair NAME --uncertainty "
       "docs/examples/mid_wheel_drive.uncertainty.toml / --reaction-time 0.6 (stability.advise.uncertain.tip_interval, "
       "stability.compare.layouts.compare_layouts, stability.advise.layout_measures.layout_shimmy_rows, "
       "layout_rule_speed)")
def layout_every_command() -> dict:
    """Issue 38: the mid-wheel-drive base's intervals over the docs' uncertainty file (advise's static stability,
    compare's growth rates both ways), each drive layout's shimmy margin per row forwards and backwards, and the
    divergence rule's speed of a 0.6 s driver both ways."""
    from pathlib import Path

    from stability.advise.layout_axes import load_layout_uncertainty
    from stability.advise.layout_measures import layout_rule_speed, layout_shimmy_rows
    from stability.advise.uncertain import SAMPLES, tip_interval
    from stability.compare.layouts import compare_layouts
    from stability.layout.linear import SEARCH_SPEEDS_M_S
    from stability.layout.presets import layout_preset

    root = Path(__file__).resolve().parents[2]
    mwd = layout_preset("mid-wheel-drive")
    unc = load_layout_uncertainty(root / "docs" / "examples" / "mid_wheel_drive.uncertainty.toml", mwd)
    out: dict = {}
    lo, hi = tip_interval(mwd, unc)
    out["tip_low"], out["tip_high"], out["tip_samples"] = fixed(lo, 1), fixed(hi, 1), str(SAMPLES)
    c = compare_layouts([mwd, layout_preset("power-fwd-base")], speeds=[0.75, -0.75], uncertainties=[unc, None])
    for u, key in ((0.75, "fwd"), (-0.75, "rev")):
        q = c.quantity(f"growth_rate_1_s@{u:g}")
        a, b = q.intervals[0]
        out[f"rate_{key}"] = signed(q.values[0], 3)
        out[f"rate_{key}_interval"] = f"{signed(a, 3)} to {signed(b, 3)}"
    rows, speeds = [], (0.5, 0.75, 1.0)
    for name in DRIVE_LAYOUTS:
        lay = layout_preset(name)
        fwd = layout_shimmy_rows(lay, speeds)
        rev = layout_shimmy_rows(lay, tuple(-u for u in speeds))
        for (row, _, f), (_, _, r) in zip(fwd, rev, strict=True):
            rows.append((name, row, signed(100 * f.shimmy_margin_m, 2), signed(100 * r.shimmy_margin_m, 2)))
        if name == "mid-wheel-drive":
            out["mwd_front_fwd"], out["mwd_front_rev"] = rows[-2][2], rows[-2][3]
    out["shimmy_table"] = Table(("layout", "caster row", "margin forwards cm", "margin backwards cm"), tuple(rows))
    drv, tau = [], 0.6
    for name in DRIVE_LAYOUTS:
        cells = []
        for reverse in (False, True):
            u, side = layout_rule_speed(layout_preset(name), tau, reverse)
            cells.append(("" if side == "=" else f"{side} ") + sig(u, 3))
        drv.append((name, *cells))
    out["driver_table"] = Table(("layout", f"{tau:g} s driver holds forwards m/s", "backwards m/s"), tuple(drv))
    out["speeds"] = ", ".join(f"{u:g}" for u in speeds)
    out["tau"], out["search_top"] = f"{tau:g}", f"{SEARCH_SPEEDS_M_S[-1]:g}"
    return out


@group("layout_critical_options", "python -m stability.critical_speed --chair NAME --reaction-time 0.3 / "
       "--uncertainty docs/examples/mid_wheel_drive.uncertainty.toml (stability.driver.layout.layout_human_limit, "
       "stability.driver.human_limit, stability.report.layout_uncertainty.layout_uncertainty)")
def layout_critical_options() -> dict:
    """Issue 38, critical_speed on a layout: a 0.3 s driver's two limits per drive layout forwards and backwards, the
    E&J Premier as a layout against the short form, and the mid-wheel-drive base's growth-rate intervals at the
    reference speed both ways over the docs' uncertainty file (the command's default draws and seed)."""
    from pathlib import Path

    from stability.advise.layout_axes import load_layout_uncertainty
    from stability.chair import resolve
    from stability.driver import Driver, human_limit
    from stability.driver.layout import layout_human_limit
    from stability.layout.model import Layout
    from stability.layout.presets import layout_preset
    from stability.report.layout_uncertainty import layout_uncertainty
    from stability.settings import defaults as D

    tau = 0.3

    def bound(u: float, side: str) -> str:
        return ("" if side == "=" else f"{side} ") + sig(u, 3)

    rows = []
    for name in DRIVE_LAYOUTS:
        for reverse in (False, True):
            h = layout_human_limit(layout_preset(name), Driver(tau), reverse)
            rows.append((name, "backwards" if reverse else "forwards", bound(h.rule_speed_m_s, h.rule_side),
                         bound(h.loop_speed_m_s, h.loop_side)))
    ej = resolve("ej-premier")
    short, lay = human_limit(ej, Driver(tau)), layout_human_limit(Layout.from_chair(ej), Driver(tau))
    root = Path(__file__).resolve().parents[2]
    mwd = layout_preset("mid-wheel-drive")
    unc = load_layout_uncertainty(root / "docs" / "examples" / "mid_wheel_drive.uncertainty.toml", mwd)
    r = layout_uncertainty(mwd, unc, [0.75, -0.75], samples=D.SAMPLES, seed=D.SEED, critical=True)
    rs = {k: (nom, lo, hi, fin) for k, _, nom, lo, hi, fin in r.rows()}
    out = {"tau": f"{tau:g}", "samples": str(D.SAMPLES),
           "table": Table(("layout", "direction", "divergence rule m/s", "delayed loop m/s"), tuple(rows)),
           "ej_rule_short": sig(short.rule_speed_m_s, 3), "ej_loop_short": sig(short.loop_speed_m_s, 3),
           "ej_rule_layout": sig(lay.rule_speed_m_s, 3), "ej_loop_layout": sig(lay.loop_speed_m_s, 3),
           "crit_defined_pct": f"{100 * rs['critical_speed_forward_m_s'][3]:.0f}"}
    for key, u in (("fwd", 0.75), ("rev", -0.75)):
        nom, lo, hi, _ = rs[f"growth_rate_1_s@{u:g}"]
        out[f"rate_{key}"], out[f"rate_{key}_interval"] = signed(nom, 3), f"{signed(lo, 3)} to {signed(hi, 3)}"
    return out
