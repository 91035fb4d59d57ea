"""Shimmy figures: draw what they are given, take and return ``ax``; nothing is computed here."""

from __future__ import annotations

import math

import numpy as np

from stability.shimmy.chair import TrailChart

__all__ = ["plot_trail_chart", "plot_friction_needed", "trail_chart_caption", "trail_chart_pages"]

# Okabe-Ito colour-blind-safe palette
_BLACK, _ORANGE, _BLUE, _VERMILION = "#000000", "#E69F00", "#0072B2", "#D55E00"


def plot_trail_chart(chart: TrailChart, ax):
    """Yaw divergence rate (filled contours) with the caster shimmy boundaries over speed x trail.

    Parameters
    ----------
    chart : TrailChart
        The computed chart (:func:`stability.shimmy.chair.trail_chart`).
    ax : matplotlib.axes.Axes
        Axes to draw on (speed in m/s across, trail in cm up); a colour bar is added to its figure.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    U, T = chart.speeds, chart.trails * 100
    cs = ax.contourf(U, T, chart.divergence_rate, levels=12, cmap="cividis")
    ax.figure.colorbar(cs, ax=ax, label="yaw divergence rate, max Re(eigenvalue) (1/s)")
    ax.contour(U, T, chart.friction_needed, levels=[chart.pin_friction], colors=_ORANGE, linewidths=2)
    ax.plot([], [], color=_ORANGE, lw=2,
            label=f"shimmy held by pin friction {chart.pin_friction:g} N m up to "
                  f"{math.degrees(chart.amplitude):g} deg (describing fn.)")
    ax.plot(U, np.clip(chart.critical_trail, 0, T.max() / 100) * 100, color=_VERMILION, ls="--", lw=2,
            label="linear shimmy boundary, no pin friction (nominal compliance)")
    for edge, words, style in ((0, "lowest", "-."), (1, "highest", ":")):
        t = chart.critical_trail_range[edge] * 100
        where = "above the chart" if np.all(t > T.max()) else "below the chart" if np.all(t < T.min()) else ""
        if where:                            # an edge outside the trails shown is named in the legend, not drawn
            ax.plot([], [], ls="none", label=f"linear boundary, {words} over the compliance range: {where}")
        else:
            ax.plot(U, np.clip(t, T.min(), T.max()), color=_VERMILION, ls=style, lw=1.3,
                    label=f"linear boundary, {words} over the compliance range (estimates)")
    ax.axhline(chart.chair_trail * 100, color=_BLACK, ls=":", lw=1.5,
               label=f"chair's trail {chart.chair_trail * 100:g} cm")
    ax.set_xlabel("speed (m/s)")
    ax.set_ylabel("caster trail (cm)")
    ax.set_ylim(T.min(), T.max())
    ax.set_title(f"{chart.chair_name}: yaw divergence and caster shimmy\n"
                 "(caster as towed wheel on a pin with equivalent lateral stiffness)", fontsize=10)
    ax.legend(loc="upper left", fontsize=7, framealpha=0.85)
    return ax


def plot_friction_needed(chart: TrailChart, ax, trails_cm=None):
    """Pin friction that suppresses shimmy of the chart's amplitude, against speed, for a few trails.

    Parameters
    ----------
    chart : TrailChart
        The computed chart (:func:`stability.shimmy.chair.trail_chart`).
    ax : matplotlib.axes.Axes
        Axes to draw on (speed in m/s across, friction in N m up).
    trails_cm : sequence of float or None, optional
        Trails to draw, cm (the nearest grid trail each); default every trail of the chart.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    idx = range(chart.trails.size) if trails_cm is None else [int(np.argmin(np.abs(chart.trails * 100 - t)))
                                                               for t in trails_cm]
    colours = [_BLUE, _ORANGE, _VERMILION, _BLACK, "#009E73", "#CC79A7", "#56B4E9"]
    for n, i in enumerate(idx):
        ax.plot(chart.speeds, chart.friction_needed[i], color=colours[n % len(colours)],
                label=f"trail {chart.trails[i] * 100:.1f} cm")
    ax.axhline(chart.pin_friction, color=_BLACK, ls=":", label=f"chair's pin friction {chart.pin_friction:g} N m")
    ax.set_xlabel("speed (m/s)")
    ax.set_ylabel(f"pin friction to hold {math.degrees(chart.amplitude):g} deg shimmy (N m)")
    ax.set_title(f"{chart.chair_name}: Coulomb pin friction against caster shimmy (towed-wheel caster)", fontsize=10)
    ax.legend(fontsize=7)
    return ax


def _speeds_words(speeds: np.ndarray) -> str:
    return ", ".join(f"{u:g}" for u in speeds) + " m/s"


def trail_chart_caption(chart: TrailChart) -> str:
    """What to conclude from a trail chart, at the caster's own trail, from the chart's own numbers.

    Parameters
    ----------
    chart : TrailChart

    Returns
    -------
    str
    """
    U, trail = chart.speeds, chart.chair_trail
    linear = U[trail < chart.critical_trail]
    held = U[trail < chart.friction_trail]
    words = [f"What to conclude: at its trail of {trail * 100:g} cm (dotted line) this caster "]
    words.append("is clear of the linear shimmy boundary at every speed shown" if not linear.size else
                 f"lies below the linear shimmy boundary (it shimmies without pin friction) at {_speeds_words(linear)}")
    words.append(f"; its pin friction of {chart.pin_friction:g} N m ")
    words.append(f"holds {math.degrees(chart.amplitude):g} deg shimmy at every speed shown" if not held.size else
                 f"does not hold {math.degrees(chart.amplitude):g} deg shimmy at {_speeds_words(held)}")
    k = int(np.argmin(np.abs(chart.trails - trail)))
    peak = float(np.max(chart.divergence_rate[k]))
    words.append(f". The whole chair's yaw divergence at this trail peaks at {peak:.2f} 1/s "
                 + ("(> 0: a yaw disturbance grows at this rate until the user steers)" if peak > 0
                    else "(<= 0: no yaw divergence)")
                 + ". ")
    words.append(_range_words(chart))
    return "".join(words)


def _range_words(chart: TrailChart) -> str:
    """The caption's sentence on the compliance range: where its boundary band lies against the chair's trail."""
    lo, hi = chart.critical_trail_range
    trail, U = chart.chair_trail, chart.speeds
    top = "above every trail shown" if np.all(hi > chart.trails.max()) else f"up to {np.nanmax(hi) * 100:.3g} cm"
    band = (f"Compliance values are estimates: over their range the linear boundary lies from "
            f"{np.nanmin(lo) * 100:.3g} cm {top}")
    inside = U[(trail >= lo) & (trail < hi)]
    if not inside.size:
        return band + ", so the trail's verdict holds over the whole range."
    at = "every speed shown" if inside.size == U.size else _speeds_words(inside)
    return band + (f"; the chair's trail lies inside that band at {at}: whether it shimmies "
                   "without pin friction there depends on the caster's compliance, so measure it or rely on the pin "
                   "friction.")


def trail_chart_pages(chart: TrailChart, model: str, trails_cm=(3, 4, 5, 6, 8)) -> list:
    """The shimmy command's two pages of one caster: the trail x speed chart and the friction needed, each with
    a title naming the caster and the models and a caption (:func:`trail_chart_caption`).

    Parameters
    ----------
    chart : TrailChart
    model : str
        The models' words for the title (which linear model gives the yaw divergence).
    trails_cm : sequence of float
        Trails of the friction page, cm.

    Returns
    -------
    list of matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    from stability.plotting.pages import plain_text, wrap_text

    caption = wrap_text(trail_chart_caption(chart), 120)
    pages = []
    for draw, size in ((lambda ax: plot_trail_chart(chart, ax), (8.5, 7.2)),
                       (lambda ax: plot_friction_needed(chart, ax, trails_cm=list(trails_cm)), (8.5, 6.4))):
        fig = Figure(figsize=size)
        ax = fig.subplots()
        draw(ax)
        fig.suptitle(f"{chart.chair_name}\n" + "\n".join(wrap_text(model, 100)), fontsize=9.5, fontweight="bold")
        fig.text(0.5, 0.01, "\n".join(caption), ha="center", va="bottom", fontsize=8, fontweight="bold",
                 color="0.1", linespacing=1.35)
        fig.subplots_adjust(top=0.84, bottom=0.13 + 0.028 * len(caption))
        pages.append(plain_text(fig))                  # a name from a user's file is never markup
    return pages
