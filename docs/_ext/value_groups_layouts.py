"""The value groups of docs/layouts.md on slopes, the assist and reversing (any wheel layout): one function per group.

As :mod:`value_groups_pages`: each function calls the toolkit's public API and returns formatted strings or
:class:`value_groups.Table`; import :mod:`value_groups`, not this module.
"""

from __future__ import annotations

from value_groups import Table, fixed, group, sig, signed

DRIVE_LAYOUTS = ("power-fwd-base", "mid-wheel-drive", "power-rwd-base")
SLOPE_DEG, SLOPE_SPEED = 2.0, 1.0


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
