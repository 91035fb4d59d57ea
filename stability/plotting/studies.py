"""Study figures: equal-instability chart (chapter 9), parameter sweeps (chapter 8), stability maps."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.figure import Figure

from stability.plotting.pages import PAGE_SIZE
from stability.plotting.style import UNSTABLE, colormap, colour

__all__ = ["equal_instability_chart", "sweep_chart", "stability_map", "trail_window_chart", "decision_chart"]


def equal_instability_chart(results: Sequence, ax=None, *, thesis: dict | None = None, title: str | None = None,
                            errors: dict | None = None, error_label: str = "range"):
    """Horizontal bars: equal-instability speed of several chairs (censored ones hatched), thesis values as markers.

    ``thesis`` maps a chair name to a (low, high) speed range of the thesis (m/s).

    Parameters
    ----------
    results : sequence of EqualInstability
        One bar each.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    thesis : dict, optional
        Chair name -> (low, high) speed range read from the thesis, m/s.
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    errors : dict, optional
        Chair name -> (low, high) range of its speed, m/s, drawn as an error bar.
    error_label : str
        Legend entry of the error bars (what the range spans).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(7, 4))
        ax = fig.subplots()
    names = [r.chair.name for r in results]
    vals = [r.value_or_bound for r in results]
    y = np.arange(len(results))[::-1]
    thesis = thesis or {}
    first = True
    first_err = True
    for yi, r, v, n in zip(y, results, vals, names, strict=True):
        ax.barh(yi, v, height=0.6, color=colour(0) if r.status == "found" else "0.8",
                hatch="" if r.status == "found" else "//", ec="k", lw=0.5)
        right = v
        if errors and n in errors:
            lo, hi = errors[n]
            ax.errorbar([v], [yi], xerr=[[max(v - lo, 0.0)], [max(hi - v, 0.0)]], fmt="none", ecolor="k",
                        elinewidth=1.2, capsize=4, label=error_label if first_err else None)
            first_err = False
            right = max(right, hi)
        if n in thesis:
            lo, hi = thesis[n]
            ax.plot([lo, hi], [yi + 0.38, yi + 0.38], color=UNSTABLE, lw=3, solid_capstyle="butt")
            ax.plot([0.5 * (lo + hi)], [yi + 0.38], "v", color=UNSTABLE, ms=6,
                    label="thesis (Figures 8-3a, 8-14, 9-2, 9-3)" if first else None)
            first = False
            right = max(right, hi)
        ax.text(right + 0.03, yi, r.describe(), va="center", fontsize=8)
    if not first or not first_err:
        ax.legend(fontsize=8, loc="lower right")
    ax.set_yticks(y, names, fontsize=8)
    ax.set_ylabel("chair")
    ax.set_xlabel("equal-instability speed (m/s)")
    ax.set_xlim(0, max(vals + [1.0]) * 1.25)
    ax.grid(True, axis="x", alpha=0.3)
    if results:
        r0 = results[0]
        ax.set_title(title or f"speed with the same instability as {r0.reference}: {r0.model} model, "
                     f"{r0.scheme} scheme", fontsize=9)
    return ax


def sweep_chart(table, axes=None, *, title: str | None = None, limits: dict | None = None,
                sweeps: Sequence | None = None):
    """The parametric study: equal-instability speed against each parameter (small multiples).

    ``table`` is a :class:`stability.study.SweepTable`.  Returns the axes array.

    Parameters
    ----------
    table : stability.study.SweepTable
        The parametric study.
    axes : array of matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    limits : dict, optional
        Parameter name -> ``(value, label)``: a constraint drawn as a vertical line (e.g. where the chair
        tips over at the minimum stability angle).
    sweeps : sequence of stability.study.Sweep, optional
        The panels to draw (default every sweep of ``table``, ranked); the speed scale is theirs and the
        chair's.

    Returns
    -------
    array of matplotlib.axes.Axes
        ``axes``.
    """
    sweeps = table.ranked() if sweeps is None else list(sweeps)
    limits = limits or {}
    n = len(sweeps)
    if axes is None:
        ncols = 4
        nrows = int(math.ceil(n / ncols))
        fig = Figure(figsize=PAGE_SIZE)
        axes = fig.subplots(nrows, ncols, squeeze=False)
    flat = list(np.asarray(axes).flat)
    allv = np.concatenate([sw.speeds for sw in sweeps] + [[table.nominal.value_or_bound]])
    ylo, yhi = float(allv.min()), float(allv.max())
    pad = max(0.08 * (yhi - ylo), 0.05)
    for ax, s in zip(flat, sweeps, strict=False):
        sp = s.speeds
        cens = np.array([r.status != "found" for r in s.results])
        if s.labels is not None:
            x = np.arange(len(s.values))
            ax.bar(x, sp, color=["0.8" if c else colour(0) for c in cens], ec="k", lw=0.5)
            ax.set_xticks(x, s.labels, fontsize=7)
            cur = table.chair.main_tire
            if cur in s.labels:
                ax.get_xticklabels()[s.labels.index(cur)].set_fontweight("bold")
        else:
            x = np.asarray(s.values)
            ax.plot(x, sp, "-o", ms=3.5, color=colour(0))
            if cens.any():
                ax.plot(x[cens], sp[cens], "o", ms=6, mfc="w", mec=UNSTABLE, label="outside bracket")
                ax.legend(fontsize=7)
            if math.isfinite(s.nominal_value):
                ax.axvline(s.nominal_value, color="k", ls=":", lw=0.8)
            if s.parameter in limits:
                v, lab = limits[s.parameter]
                ax.axvline(v, color=UNSTABLE, lw=1.5, ls="-.", label=lab)
                ax.legend(fontsize=7, loc="best")
        ax.axhline(table.nominal.value_or_bound, color="k", lw=0.6, ls="--")
        ax.set_ylim(max(0.0, ylo - pad) if s.labels is None else 0.0, yhi + pad)
        if cens.all():
            ax.text(0.5, 0.5, "all " + s.results[0].describe() if len({r.describe() for r in s.results}) == 1
                    else "all outside the bracket", transform=ax.transAxes, ha="center", va="center", fontsize=8,
                    bbox=dict(fc="w", ec="0.7"))
        ax.set_xlabel(f"{s.label} ({s.unit})" if s.labels is None else s.label, fontsize=8)
        ax.set_ylabel("equal-instability speed (m/s)", fontsize=8)
        ax.tick_params(labelsize=8)
        ax.set_title(f"{s.label}: spread {s.effect_percent:.0f} %{' (censored)' if s.censored else ''}",
                     fontsize=8)
        ax.grid(True, alpha=0.3)
    for ax in flat[n:]:
        ax.axis("off")
    return axes


def stability_map(smap, ax=None, *, title: str | None = None, nominal: float | None = None,
                  thesis_points: Sequence | None = None):
    """Contour plot of the time to the yaw-rate level over speed x (friction or disturbance size).

    The heavy contour is the reference case's time: left of it (slower)
    the chair is more stable than the reference, right of it less.  Runs
    that never reach the level are shown at the simulated duration.

    Parameters
    ----------
    smap : stability.study.StabilityMap
        The map.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    nominal : float, optional
        The chair's own value of the map's y quantity, drawn as a dotted line.
    thesis_points : sequence of (float, float, str), optional
        Points (x, y, label) from the thesis.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    T = np.where(np.isfinite(smap.times), smap.times, smap.criterion.duration)
    T = np.minimum(T, smap.criterion.duration)
    X, Y = np.meshgrid(smap.speeds, smap.y_values)
    levels = np.linspace(0, smap.criterion.duration, 21)
    cs = ax.contourf(X, Y, T, levels=levels, cmap=colormap("cividis"))
    cb = ax.figure.colorbar(cs, ax=ax, pad=0.01)
    cb.set_label(f"time to |r| = {smap.criterion.yaw_rate:g} rad/s (s; {smap.criterion.duration:g} = never)")
    ref = smap.reference_time
    if T.min() < ref < T.max():
        ax.contour(X, Y, T, levels=[ref], colors="k", linewidths=2.0)
        # named in the legend, not on the line: an inline label on a staircase contour collides with itself
        ax.plot([], [], color="k", lw=2.0, label=f"reference case's time, {ref:.2f} s")
    if nominal is not None:
        ax.axhline(nominal, color="k", ls=":", lw=0.8, label=f"chair: {nominal:g} {smap.y_unit}")
    if thesis_points:
        for i, (x, y, lab) in enumerate(thesis_points):
            ax.plot([x], [y], "D", ms=6, mfc="w", mec="k", label=lab if i == 0 else None)
    ax.plot(X.reshape(-1), Y.reshape(-1), ".", color="k", ms=1.2, alpha=0.5)
    ax.set_xlabel("forward speed U (m/s)")
    ax.set_ylabel(f"{smap.y_label} ({smap.y_unit})")
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(fontsize=7, loc="upper left")
    f, d = smap.impulse
    dist = f"{f:g} N for {d:g} s at the c.g." if smap.y_name != "impulse" else f"force held {d:g} s"
    ax.set_title(title or f"{smap.chair.name}: speed x {smap.y_name.replace('_', ' ')} ({dist}), "
                 f"{smap.model} model", fontsize=9)
    return ax



def trail_window_chart(w, ax=None, *, title: str | None = None, model: str = "exact"):
    """Equal-instability speed against caster trail over the shimmy-free window (the trail design chart).

    Parameters
    ----------
    w : stability.report.trail_window.TrailWindow
        What to draw.
    ax : matplotlib.axes.Axes, optional
    title : str, optional
    model : str
        Equation variant, for the default title.

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        fig = Figure(figsize=(8, 5))
        ax = fig.subplots()
    x = 100 * w.trails_m
    lo_x, hi_x = 0.0, max(15.0, float(x.max()) + 3.0)
    # shimmy zones: everything outside the nominal window; hatched where only some estimates shimmy
    edges = [0.0] + [v for iv in w.nominal_m for v in iv] + [np.inf]
    for a, b in zip(edges[0::2], edges[1::2], strict=False):
        if b > a:
            ax.axvspan(100 * a, min(100 * b, hi_x), color=UNSTABLE, alpha=0.18, lw=0,
                       label="caster shimmies (nominal estimates)" if a == 0.0 else None)
    first = True
    for lo, hi in w.nominal_m:
        for a, b in _gaps((lo, hi), w.robust_m):
            ax.axvspan(100 * a, min(100 * b, hi_x), facecolor="none", edgecolor=UNSTABLE, hatch="///", lw=0,
                       label="shimmies for some estimates" if first else None)
            first = False
    for lo, hi in w.robust_m:
        ax.axvspan(100 * lo, min(100 * hi, hi_x), color=colour(2), alpha=0.15, lw=0,
                   label="window: shimmy-free for every estimate" if lo == w.robust_m[0][0] else None)
    ax.plot(x[w.found], w.speeds_m_s[w.found], "o-", color=colour(0), lw=2, label="equal-instability speed")
    if (~w.found).any():
        ax.plot(x[~w.found], w.speeds_m_s[~w.found], "o", mfc="w", mec=colour(0), label="bound (outside the bracket)")
    ax.axvline(100 * w.chair_trail_m, color="k", ls=":", lw=1.2, label=f"{w.chair}: {100 * w.chair_trail_m:.3g} cm")
    ax.set_xlim(lo_x, hi_x)
    ax.set_ylim(0, max(1.0, float(np.nanmax(w.speeds_m_s)) * 1.25))
    ax.set_xlabel("caster trail (cm)")
    ax.set_ylabel("equal-instability speed (m/s; higher: more stable)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title(title or f"{w.chair}: directional stability and caster shimmy against trail ({model} model)",
                 fontsize=10)
    return ax


def _gaps(span: tuple[float, float], inside) -> list[tuple[float, float]]:
    """Parts of ``span`` not covered by the intervals ``inside``."""
    out, lo = [], span[0]
    for a, b in sorted(inside):
        if b <= lo or a >= span[1]:
            continue
        if a > lo:
            out.append((lo, a))
        lo = max(lo, b)
    if lo < span[1]:
        out.append((lo, span[1]))
    return out


def decision_chart(names: Sequence[str], values: Sequence[float], lows: Sequence[float], highs: Sequence[float],
                   ax=None, *, reference_speed: float | None = None, title: str | None = None,
                   beyond: Sequence[bool] | None = None):
    """Equal-instability speed of a few chairs with their ranges (page 1 of the report).

    Parameters
    ----------
    names : sequence of str
    values, lows, highs : sequence of float
        Speeds and range ends, m/s.
    beyond : sequence of bool, optional
        Values that are the end of the searched bracket, the speed lying above it (labelled "> ...").
    ax : matplotlib.axes.Axes, optional
    reference_speed : float, optional
        The thesis's reference speed (m/s), drawn as a line.
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        fig = Figure(figsize=(6, 3))
        ax = fig.subplots()
    y = np.arange(len(names))[::-1]
    v = np.asarray(values, float)
    lo, hi = np.asarray(lows, float), np.asarray(highs, float)
    bound = np.asarray(beyond if beyond is not None else [False] * len(v), bool)
    bars = ax.barh(y, v, height=0.55, color=[colour(i) for i in range(len(names))], ec="k", lw=0.5)
    for bar, b in zip(bars, bound, strict=True):
        if b:       # a bound: the speed lies beyond the bar's end (hatched, with an arrow past the end)
            bar.set_hatch("///")
            ax.annotate("", xy=(bar.get_width() * 1.12, bar.get_y() + bar.get_height() / 2),
                        xytext=(bar.get_width(), bar.get_y() + bar.get_height() / 2),
                        arrowprops={"arrowstyle": "->", "lw": 1.5, "color": "k"})
    ax.errorbar(v, y, xerr=[np.maximum(v - lo, 0), np.maximum(hi - v, 0)], fmt="none", ecolor="k", capsize=4,
                elinewidth=1.2, label="range: push, pin friction, model")
    for yi, vi, above in zip(y, v, beyond if beyond is not None else [False] * len(v), strict=True):
        ax.text(vi + 0.02, yi + 0.3, f"{'> ' if above else ''}{vi:.2f} m/s ({3.6 * vi:.1f} km/h)", fontsize=8.5,
                va="bottom")
    if reference_speed is not None:
        ax.axvline(reference_speed, color="0.3", ls="--", lw=1, label=f"thesis reference {reference_speed:g} m/s")
    ax.set_yticks(y, names, fontsize=9)
    ax.set_ylabel("chair", fontsize=9)
    ax.set_xlabel("equal-instability speed (m/s; higher: more stable)", fontsize=9)
    ax.set_xlim(0, max(1.0, float(np.nanmax(hi)) * 1.3, float(np.nanmax(v)) * 1.6))     # room for the labels
    ax.grid(True, axis="x", alpha=0.3)
    handles, _ = ax.get_legend_handles_labels()
    if bound.any():
        from matplotlib.patches import Patch

        handles.append(Patch(facecolor="white", edgecolor="k", hatch="///",
                             label="a bound: the speed lies beyond the bar's end"))
    ax.legend(handles=handles, fontsize=8, loc="lower right")
    ax.set_ylim(-0.6, len(names) - 0.2)
    ax.set_title(title or "how fast it can go before it is as unstable as the thesis's reference case", fontsize=9.5)
    return ax
