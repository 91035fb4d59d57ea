"""The assist's figures for a wheel layout, forward and in reverse: gains and growth rates, nonlinear recoveries.

Each draws the data it is given (:class:`stability.assist.layout.LayoutAssist`) and returns the Figure; the short
form's margin and top-speed pages (:func:`stability.assist.figures.figure_margin_pair`,
:func:`stability.assist.figures_safety.figure_top_speed`) take a layout's schedule
(:func:`stability.assist.layout.layout_schedule`) as they are.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from stability.assist.figures import flat_axis, label_axes
from stability.plotting import page
from stability.plotting.style import colour
from stability.settings.reference import THESIS_PUSH

__all__ = ["figure_layout_gains", "figure_layout_recovery"]

#: The gains drawn (state, unit of the gain per wheel).
_GAINS = (("psi", "N m/rad"), ("r", "N m/(rad/s)"), ("v", "N m/(m/s)"))


def _directions(a: Any) -> list[tuple[str, tuple]]:
    return [(what, rows) for what, rows in (("forward", a.forward), ("reverse", a.reverse)) if rows]


def figure_layout_gains(a: Any) -> Figure:
    """Heading, yaw-rate and lateral-velocity gains per wheel, and the open- and closed-loop growth rates, against
    the magnitude of the speed, forward and in reverse.

    Parameters
    ----------
    a : stability.assist.layout.LayoutAssist

    Returns
    -------
    Figure
    """
    dirs = _directions(a)
    worst = max(r.closed_loop_growth_1_s for _, rows in dirs for r in rows)
    fig, ax = page(f"Gain schedule and growth rates: {a.kind} LQR on {a.layout} (layout model, exact)",
                   f"differential torque per drive wheel, tau = -(k . x); drive wheels {a.lever_m:g} m apart, radius "
                   f"{a.wheel_radius_m:g} m; reverse: casters trailing at 180 deg. The assist "
                   + ("stabilises every design speed shown (closed-loop growth rate below zero, largest "
                      f"{worst:.3g} 1/s)" if worst < 0 else
                      f"leaves a growing mode (largest closed-loop growth rate {worst:.3g} 1/s)")
                   + " whatever the chair alone does (dashed)", nrows=1, ncols=len(_GAINS) + 1)
    for j, (state, unit) in enumerate(_GAINS):
        b = ax[0, j]
        for i, (what, rows) in enumerate(dirs):
            b.plot([abs(r.speed_m_s) for r in rows], [r.wheel_torque_gains[state] for r in rows], "os"[i] + "-",
                   color=colour(i), ms=4, label=what)
        flat_axis(b, [r.wheel_torque_gains[state] for _, rows in dirs for r in rows])
        b.set_title(f"k_{state}")
        label_axes(b, "|speed| (m/s)", f"gain per wheel ({unit})")
    c = ax[0, len(_GAINS)]
    for i, (what, rows) in enumerate(dirs):
        s = [abs(r.speed_m_s) for r in rows]
        c.plot(s, [r.open_loop_growth_1_s for r in rows], "--", color=colour(i), marker="os"[i], ms=3,
               mfc="none", label=f"{what}, chair alone")
        c.plot(s, [r.closed_loop_growth_1_s for r in rows], "-", color=colour(i), marker="os"[i], ms=4,
               label=f"{what}, assisted")
    c.axhline(0.0, color="k", lw=0.8)
    c.set_title("growth rate")
    label_axes(c, "|speed| (m/s)", "growth rate (1/s)")
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.9))
    return fig


def figure_layout_recovery(a: Any) -> Figure | None:
    """Heading after the reference and the strong push, assisted and unassisted, in the layout simulator.

    Parameters
    ----------
    a : stability.assist.layout.LayoutAssist
        With its nonlinear checks (``check=True``).

    Returns
    -------
    Figure or None
        None when no checks were run.
    """
    recs = [r for chk in (a.forward_checks, a.reverse_checks) if chk is not None for r in chk.recoveries]
    if not recs:
        return None
    back = [r.straight for r in recs]
    fig, ax = page(f"Recovery after a push in the layout simulator: {a.kind} LQR on {a.layout} (exact model)",
                   f"lateral push at the c.g. for {THESIS_PUSH.duration:g} s; the sampled controller compiled in, "
                   "torque limit, motor lag, noise-free. Assisted (solid) the chair returns to a straight line in "
                   f"{sum(back)} of {len(back)} runs; unassisted (dashed) it keeps turning where its open loop grows",
                   nrows=1, ncols=2)
    for j, push in enumerate(sorted({r.push_N for r in recs})):
        b = ax[0, j]
        for i, r in enumerate(x for x in recs if x.push_N == push):
            way = "backwards" if r.speed_m_s < 0 else "forwards"
            for run, ls, what in ((r.closed, "-", "assisted"), (r.opened, "--", "unassisted")):
                if run is not None:
                    b.plot(np.asarray(run.t_s), np.degrees(np.asarray(run.heading_rad)), ls, color=colour(i),
                           label=f"{abs(r.speed_m_s):g} m/s {way}, {what}")
        b.set_title(f"{push:g} N x {THESIS_PUSH.duration:g} s")
        label_axes(b, "time (s)", "heading (deg)")
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.9))
    return fig
