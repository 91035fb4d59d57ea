"""Figures of the report's slope and uncertainty sections: they draw what they are given and compute nothing."""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from stability.plotting.style import UNSTABLE, colour

__all__ = ["drive_difference", "uncorrected_heading", "growth_rate_band", "variance_shares"]


def drive_difference(slopes_deg: Sequence[float] | np.ndarray, difference: Sequence[float] | np.ndarray, label: str,
                     ax, *, chair: str = ""):
    """The drive difference that holds a straight line against cross slope.

    Parameters
    ----------
    slopes_deg : sequence of float
        Cross slopes, deg.
    difference : sequence of float
        Hand-rim force difference (N) or motor torque difference (N m) at each slope.
    label : str
        Y-axis label with its unit.
    ax : matplotlib.axes.Axes
    chair : str, optional
        Legend label.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax.plot(slopes_deg, difference, marker="o", color=colour(0), label=chair or None)
    ax.set_xlabel("cross slope (deg)")
    ax.set_ylabel(label)
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    ax.grid(alpha=0.3)
    if chair:
        ax.legend(fontsize="small")
    return ax


def uncorrected_heading(t: np.ndarray, heading_change_deg: np.ndarray, ax, *, title: str = "",
                        quasi_steady_deg_s: float | None = None):
    """Heading change (downhill +) of the chair released on the slope, against time.

    Parameters
    ----------
    t : ndarray
        Time, s.
    heading_change_deg : ndarray
        Heading change from the held equilibrium, deg (downhill +).
    ax : matplotlib.axes.Axes
    title : str, optional
    quasi_steady_deg_s : float, optional
        The zero-width model's ``g2/U`` (deg/s), drawn as a dashed line through the origin (downhill).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax.plot(t, heading_change_deg, color=colour(0), label="heading change (exact model, free casters)")
    if quasi_steady_deg_s is not None and len(t):
        ax.plot([0.0, t[-1]], [0.0, quasi_steady_deg_s * t[-1]], "k--", lw=1,
                label=f"g2/U = {quasi_steady_deg_s:.3g} deg/s (zero-width, sliding-mass rate)")
    ax.axhline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("heading change, downhill + (deg)")
    ax.legend(fontsize="small")
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def growth_rate_band(speeds: Sequence[float], nominal: Sequence[float] | np.ndarray, low: Sequence[float],
                     high: Sequence[float],
                     ax, *, level: float = 0.95, delta: tuple | None = None, title: str = ""):
    """Growth rate of the least stable mode against speed with its central interval.

    Parameters
    ----------
    speeds : sequence of float
        m/s.
    nominal, low, high : sequence of float
        Point value and interval ends, 1/s.
    ax : matplotlib.axes.Axes
    level : float
        Coverage of the band (for the legend).
    delta : tuple of (low, high) sequences, optional
        The delta-method interval (dotted), a check on the Monte Carlo band.
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax.fill_between(speeds, low, high, color=colour(0), alpha=0.25,
                    label=f"{100 * level:g} % interval (Monte Carlo)")
    ax.plot(speeds, nominal, color=colour(0), marker="o", ms=3, label="the chair's own parameters")
    if delta is not None:
        ax.plot(speeds, delta[0], ":", color=colour(1), label="delta method (first order)")
        ax.plot(speeds, delta[1], ":", color=colour(1))
    ax.axhline(0.0, color=UNSTABLE, lw=0.8)
    ax.set_xlabel("forward speed U (m/s)")
    ax.set_ylabel("growth rate, largest real part (1/s)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small")
    if title:
        ax.set_title(title, fontsize=9)
    return ax


def variance_shares(names: Sequence[str], shares: Sequence[float], ax, *, title: str = ""):
    """Each uncertain parameter's first-order share of the output variance (horizontal bars).

    Parameters
    ----------
    names : sequence of str
        Parameters (the uncertainty file's tables).
    shares : sequence of float
        Shares, 0-1.
    ax : matplotlib.axes.Axes
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    y = np.arange(len(names))
    ax.barh(y, [100 * s for s in shares], color=[colour(i) for i in range(len(names))])
    ax.set_yticks(y, list(names))
    ax.invert_yaxis()
    ax.set_xlabel("share of the variance (%)")
    ax.set_ylabel("uncertain parameter (table)")
    ax.set_xlim(0, 100 if not len(shares) else max(100.0, math.ceil(100 * max(shares))))
    if title:
        ax.set_title(title, fontsize=9)
    return ax
