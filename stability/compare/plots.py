"""Figures of a comparison: growth rate against speed for every chair, single-parameter effects (draw only)."""

from __future__ import annotations

from typing import Any

import numpy as np

from stability.compare.compute import Comparison, EffectSet
from stability.plotting.style import OKABE_ITO, UNSTABLE
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["plot_growth_rates", "plot_effects", "comparison_figures", "growth_caption"]


def plot_growth_rates(ax: Any, c: Comparison) -> Any:
    """Growth rate of the least stable free-caster mode against speed, one line per chair.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    c : Comparison
        Its ``curves`` are drawn; the table speeds carry error bars when intervals were computed.

    Returns
    -------
    matplotlib.axes.Axes
    """
    styles = ("-", "--", "-.", ":")
    rates = [q for q in c.quantities if q.key.startswith("growth_rate_1_s@")]
    layout = c.model == "layout"
    for i, (label, row) in enumerate(zip(c.labels, c.curves, strict=True)):
        colour = OKABE_ITO[i % len(OKABE_ITO)]
        ax.plot(c.curve_speeds, row, color=colour, ls=styles[i % len(styles)], label=label)
        # the table speeds' intervals (with uncertainty files): the quantities' own, short form and layouts alike
        bars = [(float(q.key.split("@")[1]), iv) for q in rates if (iv := q.intervals[i]) is not None]
        if bars:
            lo = np.array([b[0] for _, b in bars])
            hi = np.array([b[1] for _, b in bars])
            mid = 0.5 * (lo + hi)
            ax.errorbar([u for u, _ in bars], mid, yerr=[mid - lo, hi - mid], fmt="none", ecolor=colour, capsize=3)
    ax.axhline(0.0, color="black", lw=0.8)
    ax.axvline(REFERENCE_SPEED, color=UNSTABLE, lw=0.8, ls=":",
               label=f"{REFERENCE_SPEED:g} m/s, the thesis's reference speed")
    if min(c.curve_speeds) < 0:
        ax.axvline(-REFERENCE_SPEED, color=UNSTABLE, lw=0.8, ls="-.",
                   label=f"{-REFERENCE_SPEED:g} m/s, the reference speed in reverse")
    ax.set_xlabel("speed U (m/s; negative: in reverse, the casters trailing backwards)" if min(c.curve_speeds) < 0
                  else "forward speed U (m/s)")
    ax.set_ylabel("growth rate of least stable mode (1/s)\n(> 0: the heading error grows by itself)")
    model = "the layouts' linear model, free frictionless casters" if layout else f"{c.model} model"
    ax.set_title(f"Free-caster growth rate: {' vs '.join(c.labels)}\n({model})", fontsize="medium")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, alpha=0.3)
    return ax


def plot_effects(axes: Any, e: EffectSet, reference: str, model: str) -> Any:
    """Bar charts of single-parameter effects: change of growth rate and of locked critical speed.

    Parameters
    ----------
    axes : pair of matplotlib.axes.Axes
    e : EffectSet
    reference : str
        Label of the reference chair.
    model : str

    Returns
    -------
    pair of matplotlib.axes.Axes
    """
    names = [s.field for s in e.effects] + ["sum of singles", "interaction", "total"]

    def values(single: list[float | None], total: float | None, rem: float | None) -> np.ndarray:
        parts = [np.nan if v is None else v for v in single]
        whole = sum(parts) if all(np.isfinite(parts)) else np.nan  # n/a when any single effect is n/a
        return np.array(parts + [whole, np.nan if rem is None else rem, np.nan if total is None else total])

    data = ((values([s.growth_rate for s in e.effects], e.total_growth_rate, e.remainder_growth_rate),
             f"change of growth rate at {REFERENCE_SPEED:g} m/s (1/s)"),
            (values([s.locked_critical_speed for s in e.effects], e.total_locked_critical_speed,
                    e.remainder_locked_critical_speed), "change of locked-caster critical speed (m/s)"))
    y = np.arange(len(names))
    colours = [OKABE_ITO[0]] * len(e.effects) + [OKABE_ITO[7], OKABE_ITO[1], "black"]
    for ax, (v, xlabel) in zip(axes, data, strict=True):
        ax.barh(y, np.nan_to_num(v), color=colours)
        for k in np.flatnonzero(~np.isfinite(v)):
            ax.text(0, y[k], " n/a (invalid chair or no finite value)", va="center", fontsize="small")
        ax.set_yticks(y, names)
        ax.invert_yaxis()
        ax.axvline(0.0, color="black", lw=0.8)
        ax.set_xlabel(xlabel)
        ax.grid(True, axis="x", alpha=0.3)
    axes[0].set_title(f"{e.chair} vs {reference}: each difference alone ({model} model)", loc="left")
    return axes


def growth_caption(c: Comparison) -> str:
    """What to conclude from the growth-rate figure, in one or two sentences (the figure's caption).

    Parameters
    ----------
    c : Comparison

    Returns
    -------
    str
    """
    q = next((q for q in c.quantities if q.key == f"growth_rate_1_s@{REFERENCE_SPEED:g}"), None)
    text = ("Below the zero line a heading error dies out by itself, above it grows; at any speed the lower curve is "
            "the more stable chair.")
    if q is not None and all(np.isfinite(q.values)):
        best = c.labels[int(np.argmin(q.values))]
        text += f" At {REFERENCE_SPEED:g} m/s the lowest is {best}."
    if any(iv is not None for q2 in c.quantities for iv in q2.intervals):
        text += " Bars: central intervals over the uncertainty files' draws."
    return text


def comparison_figures(c: Comparison) -> list[Any]:
    """The figures of a comparison: the growth-rate curves, then one effects figure per compared chair.

    Parameters
    ----------
    c : Comparison

    Returns
    -------
    list of matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure  # matplotlib is imported only when figures are asked for

    fig = Figure(figsize=(8.27, 5.8), layout="constrained")
    plot_growth_rates(fig.add_subplot(1, 1, 1), c)
    fig.supxlabel(growth_caption(c), fontsize="small", wrap=True)
    figs = [fig]
    for e in c.effects:
        f = Figure(figsize=(8.27, 2.0 + 0.35 * (len(e.effects) + 3)), layout="constrained")
        plot_effects(f.subplots(1, 2, sharey=True), e, c.labels[0], c.model)
        figs.append(f)
    return figs
