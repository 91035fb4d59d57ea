"""What ``python -m stability.slope`` answers for a wheel layout: the drive quantities of the held line and the
text and JSON of the statics and the uncorrected runs (:mod:`stability.study.layout_slope` computes them).
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

from stability.layout.model import Layout
from stability.study.layout_slope import LayoutEquilibrium, layout_equilibrium, layout_uncorrected_path

__all__ = ["layout_drive_kind", "layout_drive_report", "layout_slope_report"]


def layout_drive_kind(layout: Layout, drive: str = "auto") -> str:
    """``drive``, or for ``"auto"`` ``"motor"`` when the layout has driven wheels, else ``"handrim"``.

    Parameters
    ----------
    layout : Layout
    drive : {"auto", "handrim", "motor"}

    Returns
    -------
    str
    """
    return drive if drive != "auto" else ("motor" if any(w.driven for w in layout.wheels) else "handrim")


def layout_drive_report(eq: LayoutEquilibrium, kind: str, handrim: Any = None) -> dict:
    """The drive quantities of a layout's held line: :func:`stability.slope.equilibrium.drive_report` of its two
    drive wheels' forces.

    Parameters
    ----------
    eq : LayoutEquilibrium
    kind : {"handrim", "motor"}
    handrim : HandRim, optional
        Radii of the hand-rim drive (default :class:`stability.slope.equilibrium.HandRim`).

    Returns
    -------
    dict
        As :func:`~stability.slope.equilibrium.drive_report`.
    """
    from typing import cast

    from stability.slope.equilibrium import Equilibrium, HandRim, drive_report

    shim = cast(Equilibrium, SimpleNamespace(drive_forces=eq.drive_forces_N, cross_slope_deg=eq.cross_slope_deg))
    return drive_report(cast(Any, None), shim, kind, (handrim or HandRim()) if kind == "handrim" else None)


def layout_slope_report(layout: Layout, cross_slope_deg: float, speed: float, grade_deg: float = 0.0,
                        sim_time: float = 1.0, drive: str = "auto", handrim: Any = None) -> tuple[dict, list[str]]:
    """What ``python -m stability.slope`` answers for a layout (or any chair at a negative speed).

    Parameters
    ----------
    layout : Layout
    cross_slope_deg, speed, grade_deg : float
        As :func:`~stability.study.layout_slope.layout_equilibrium` (speed negative: reverse).
    sim_time : float
        Report time of the uncorrected runs, s.
    drive : {"auto", "handrim", "motor"}
        Report hand-rim forces or motor torques (auto: motor when the layout has driven wheels).
    handrim : HandRim, optional
        Radii of the hand-rim drive (default :class:`stability.slope.equilibrium.HandRim`).

    Returns
    -------
    (dict, list of str)
        The JSON keys (unit last) and the text lines.
    """
    eq = layout_equilibrium(layout, cross_slope_deg, speed, grade_deg)
    kind = layout_drive_kind(layout, drive)
    drive_q = layout_drive_report(eq, kind, handrim)
    paths: dict = {}
    if cross_slope_deg != 0:
        for friction in (True, False):
            key = "pin_friction" if friction else "frictionless"
            try:
                paths[key] = layout_uncorrected_path(layout, eq, sim_time, pin_friction=friction).to_mapping()
            except ValueError as exc:
                paths[key] = {"error": str(exc)}
    data = {**eq.to_mapping(), "holding_yaw_moment_N_m": abs(eq.holding_moment_N_m), "drive_forces": drive_q,
            "uncorrected_simulator": paths or None}
    direction = "backwards (casters trailing at about 180 deg)" if speed < 0 else "forwards"
    lo, hi = eq.friction_range_N_m
    lines = [f"{layout.name}: cross slope {eq.cross_slope_deg:g} deg, grade {eq.grade_deg:g} deg, {abs(speed):g} m/s "
             f"{direction} (layout model)",
             f"  holding yaw moment {abs(eq.holding_moment_N_m):.3f} N m ({eq.holding_moment_N_m:+.3f} signed, "
             f"clockwise +); with Coulomb pin friction any of {lo:.3f} .. {hi:.3f} N m",
             f"  uncorrected (statics): turns {eq.uncorrected_turn}"]
    if speed < 0:
        lines.append("  (reverse: downhill/uphill name the way the chair's front turns; backing, its path bends the "
                     "other way)")
    for key, d in paths.items():
        if "error" in d:
            lines.append(f"  simulator {key.replace('_', ' ')}: not run ({d['error']})")
            continue
        end = "" if d["ended"] == "horizon" else f" (run ends: {d['ended']})"
        lines.append(f"  simulator {key.replace('_', ' ')}: turns {d['uncorrected_turn']}, heading "
                     f"{d['heading_change_deg']:+.2f} deg, yaw rate {d['yaw_rate_deg_s']:+.1f} deg/s at "
                     f"{d['report_time_s']:.2f} s{end}")
    lines.append(f"  crab {eq.heading_deg:+.3f} deg, casters " + " / ".join(f"{a:+.3f}" for a in eq.caster_angles_deg)
                 + " deg; loads " + ", ".join(f"{x:.1f}" for x in eq.loads_N) + " N (fixed wheels, then casters)")
    if kind == "handrim":
        diff = drive_q["handrim_force_difference_N"]
        lines.append(f"  hand-rim forces left {drive_q['handrim_force_left_N']:.2f} N, right "
                     f"{drive_q['handrim_force_right_N']:.2f} N (right - left {diff:+.2f} N: the "
                     f"{drive_q['harder_side']} rim works harder)")
    else:
        lines.append(f"  motor torques left {drive_q['motor_torque_left_N_m']:.2f}, right "
                     f"{drive_q['motor_torque_right_N_m']:.2f} N m (differential (left - right)/2 "
                     f"{drive_q['differential_torque_N_m']:+.2f} N m: the {drive_q['harder_side']} wheel works harder)")
    for p in eq.problems:
        lines.append(f"  note: {p}")
    return data, lines
