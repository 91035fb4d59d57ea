"""Shimmy figures: draw what they are given, take and return ``ax``; nothing is computed here."""

from __future__ import annotations

import math

import numpy as np

from stability.shimmy.chair import TrailChart

__all__ = ["plot_trail_chart", "plot_friction_needed"]

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
    lo = np.clip(chart.critical_trail_range[0], 0, T.max() / 100) * 100
    hi = np.clip(chart.critical_trail_range[1], 0, T.max() / 100) * 100
    ax.fill_between(U, lo, hi, color=_VERMILION, alpha=0.15, hatch="//",
                    label="linear boundary over the compliance range (estimates)")
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
