"""The assist's safe-top-speed page: each constraint's slack against speed, and the single-fault outcomes."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from stability.assist.faults import DRIFT_BOUND_M, HEADING_BOUND_DEG, FaultRow
from stability.assist.schedule import Schedule
from stability.assist.top_speed import CONSTRAINTS, DESCRIPTIONS, ENABLE, TopSpeed
from stability.plotting import page
from stability.plotting.style import colour

__all__ = ["figure_top_speed"]


def figure_top_speed(sched: Schedule, ts: TopSpeed, faults: Sequence[FaultRow] | None = None,
                     enable: Mapping[str, str] = ENABLE) -> Figure:
    """Constraint ratios against speed with the safe top speed, and (with faults) the worst fault response per speed.

    Parameters
    ----------
    sched : Schedule
    ts : TopSpeed
    faults : sequence of FaultRow, optional
        ``--faults``'s runs (None: one panel).
    enable : mapping
        Constraint -> how to check it, for the caption's "not checked" (default the short form's
        :data:`~stability.assist.top_speed.ENABLE`).

    Returns
    -------
    Figure
        Left: each checked constraint's value over its limit (margins: value / minimum, torque: limit / peak;
        above 1 holds), the safe top speed marked.  Right (with faults): the largest peak heading error and drift
        over all faults per speed and slope, against the stated bounds.
    """
    top = "none" if ts.safe_top_speed_m_s is None else f"{ts.safe_top_speed_m_s:g} m/s"
    lim = ts.limits()
    why = "; ".join(x.describe() for x in lim) if lim else "every checked constraint holds on the design grid"
    caption = (f"{why}. A constraint holds above ratio 1; the top speed is the highest design speed where all hold "
               "there and below" + (". Not checked: " + ", ".join(enable[k] for k in ts.not_checked)
                                    if ts.not_checked else ""))
    if faults is not None:
        caption += (". Right: worst single sensor fault (injected at 1 s, straight command) per speed, against the "
                    "stated bounds")
    fig, ax = page(f"Safe top speed of the {sched.kind} LQR on {sched.chair.name} (exact model, "
                   f"{sched.gyro.sample_rate_hz:g} Hz): {top}", caption, nrows=1, ncols=2 if faults is not None else 1)
    a = ax[0, 0]
    s = np.array([c.speed_m_s for c in ts.checks])
    for i, k in enumerate(c for c in CONSTRAINTS if c != "faults"):
        vals = [c.values.get(k) for c in ts.checks]
        if all(v is None for v in vals):
            continue
        ratio = [np.nan if v is None else (v[1] / v[0] if k == "torque" else v[0] / v[1]) for v in vals]
        a.plot(s, ratio, "o-", color=colour(i), label=DESCRIPTIONS[k][0])
    a.axhline(1.0, color="k", lw=0.9, ls="--", label="limit")
    if ts.safe_top_speed_m_s is not None:
        a.axvline(ts.safe_top_speed_m_s, color="0.4", lw=1.2, ls=":", label=f"safe top speed {top}")
    a.set_xlabel("speed (m/s)")
    a.set_ylabel("value / limit (torque: limit / peak) (-)")
    a.set_title("constraints")
    a.grid(alpha=0.3)
    a.legend(fontsize=7)
    if faults is not None:
        _faults_panel(ax[0, 1], faults)
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 0.93))
    return fig


def _faults_panel(b: Any, faults: Sequence[FaultRow]) -> None:
    """The worst fault response per speed and slope against the bounds."""
    slopes = sorted({f.slope_deg for f in faults})
    for j, phi in enumerate(slopes):
        sp = sorted({f.speed_m_s for f in faults if f.slope_deg == phi})
        he = [max(f.peak_heading_error_deg for f in faults if f.slope_deg == phi and f.speed_m_s == x) for x in sp]
        dr = [max(f.drift_m for f in faults if f.slope_deg == phi and f.speed_m_s == x) for x in sp]
        b.plot(sp, np.array(he) / HEADING_BOUND_DEG, "o-", color=colour(j), label=f"heading error, {phi:g} deg slope")
        b.plot(sp, np.array(dr) / DRIFT_BOUND_M, "s--", color=colour(j), label=f"drift, {phi:g} deg slope")
    b.axhline(1.0, color="k", lw=0.9, ls="--", label=f"bounds {HEADING_BOUND_DEG:g} deg / {DRIFT_BOUND_M:g} m")
    b.set_xlabel("speed (m/s)")
    b.set_ylabel("worst fault response / bound (-)")
    b.set_title("single sensor faults (worst over all faults)")
    b.grid(alpha=0.3)
    b.legend(fontsize=7)
