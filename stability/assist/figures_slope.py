"""The assist's cross-slope page: draws the :class:`~stability.assist.driving.SlopeHold` runs it is given."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from stability.assist.driving import SlopeHold
from stability.assist.schedule import Schedule
from stability.plotting import page
from stability.plotting.style import colour

__all__ = ["figure_slope_hold"]


def figure_slope_hold(sched: Schedule, holds: Sequence[SlopeHold]) -> Figure:
    """Straight command along cross slopes: heading with and without the assist, and the wheel torque.

    Parameters
    ----------
    sched : Schedule
    holds : sequence of SlopeHold
        One per cross slope (same speed).

    Returns
    -------
    Figure
        Three panels: closed-loop heading (deg) with the statics' crab angle and the controller's holding
        heading (its settled heading without pin friction), open-loop heading up to the end of its valid run (deg),
        commanded differential torque per wheel with the statics' holding torque and its pin-friction band (N m).
    """
    speed = holds[0].speed_m_s if holds else float("nan")
    limits = (f"; limits: motor {holds[0].motor_limit_N_m:g} N m, traction "
              f"{min(h.traction_limit_N_m for h in holds):.0f} N m per wheel (off scale)") if holds else ""
    fig, ax = page(f"Cross slope, straight command: {sched.kind} LQR on {sched.chair.name}, exact model, {speed:g} m/s",
                   "nonlinear simulator on the slope (WCHAIR scheme, pin friction, coasting), noise-free; both runs "
                   "start straight; open loop cut where a caster swings 30 deg or the heading passes 45 deg" + limits,
                   nrows=1, ncols=3)
    a, b, c = ax[0, 0], ax[0, 1], ax[0, 2]
    for i, h in enumerate(holds):
        lab = f"{h.cross_slope_deg:g} deg cross slope"
        a.plot(h.closed.t, np.degrees(h.closed.heading), color=colour(i), lw=1.6, label=lab)
        a.axhline(h.crab_deg, color=colour(i), ls=":", lw=0.9, label=f"{lab}: statics' crab angle")
        a.axhline(h.hold_heading_deg, color=colour(i), ls="--", lw=0.9,
                  label=f"{lab}: loop's holding heading (course {h.course_deg:+.3f} deg)")
        b.plot(h.open_t, np.degrees(h.open_heading), color=colour(i), lw=1.6, label=f"{lab} ({h.open_turn})")
        c.step(h.closed.torque_t, h.closed.torque, where="post", color=colour(i), lw=1.0, label=f"{lab}: commanded")
        c.axhline(h.holding_torque_N_m, color=colour(i), ls="--", lw=0.9,
                  label=f"{lab}: statics' holding torque {h.holding_torque_N_m:.2f} N m")
        c.axhspan(*h.holding_band_N_m, color=colour(i), alpha=0.12, label=f"{lab}: pin-friction band")
    for axis, title, ylabel in ((a, "heading, with the assist", "heading, to the right + (deg)"),
                                (b, "heading, without the assist", "heading, to the right + (deg)"),
                                (c, "differential torque per wheel", "torque per wheel (N m)")):
        axis.set_title(title)
        axis.set_xlabel("time (s)")
        axis.set_ylabel(ylabel)
        axis.grid(alpha=0.3)
        axis.legend(fontsize=7)
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.93))
    return fig
