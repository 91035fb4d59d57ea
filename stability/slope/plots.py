"""Plots of the slope results: they draw what they are given and compute nothing."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.settings.reference import CROSS_SLOPE_STUDY

__all__ = ["HoldingCurve", "holding_curve", "plot_holding"]


@dataclass(frozen=True)
class HoldingCurve:
    """Holding moment and hand-rim force difference against cross slope for one chair.

    Attributes
    ----------
    chair : str
    cross_slopes_deg : ndarray
    holding_moment : ndarray
        Magnitude (N m).
    friction_low, friction_high : ndarray
        Range of the holding-moment magnitude with Coulomb pin friction (N m).
    handrim_difference : ndarray
        Magnitude of the hand-rim force difference (N).
    """

    chair: str
    cross_slopes_deg: np.ndarray
    holding_moment: np.ndarray
    friction_low: np.ndarray
    friction_high: np.ndarray
    handrim_difference: np.ndarray


def magnitude_band(friction_range) -> tuple[float, float]:
    """The holding-moment magnitudes that some moment of a signed pin-friction range gives, N m.

    Parameters
    ----------
    friction_range : pair of float
        The signed range of yaw moments that hold the line with Coulomb pin friction, N m (low, high).

    Returns
    -------
    tuple of float
        ``(low, high)`` of ``{|m| : m in friction_range}``: from 0 when the range holds zero (the pins' friction
        alone holds the line, no drive moment needed), else the smaller and the larger of the two magnitudes.
    """
    lo, hi = sorted(float(x) for x in friction_range)
    if lo <= 0.0 <= hi:
        return 0.0, max(-lo, hi)
    return min(abs(lo), abs(hi)), max(abs(lo), abs(hi))


def holding_curve(chair, cross_slopes_deg: Sequence[float] = (0.5, 1, 2, 3, 4, 5, 6), speed: float = 0.9,
                  handrim=None) -> HoldingCurve:
    """Compute a :class:`HoldingCurve` (equilibria of :func:`stability.slope.equilibrium.solve`).

    Parameters
    ----------
    chair : Chair
        The chair.
    cross_slopes_deg : sequence of float, optional
        Cross slopes, deg (default 0.5 to 6).
    speed : float, optional
        Speed along the path, m/s (default 0.9).
    handrim : HandRim or None, optional
        Wheel and hand-rim radii for the hand-rim force difference (default :class:`HandRim`).

    Returns
    -------
    HoldingCurve
        Holding-moment magnitude (N m) with its range under Coulomb pin friction
        and the hand-rim force difference (N) at each cross slope.
    """
    from stability.slope.equilibrium import drive_report, solve

    eqs = [solve(chair, float(p), speed) for p in cross_slopes_deg]
    fr = np.array([magnitude_band(e.friction_range) for e in eqs])
    return HoldingCurve(
        chair=chair.name, cross_slopes_deg=np.asarray(cross_slopes_deg, dtype=float),
        holding_moment=np.array([abs(e.holding_moment) for e in eqs]), friction_low=fr[:, 0], friction_high=fr[:, 1],
        handrim_difference=np.array([abs(drive_report(chair, e, "handrim", handrim)["handrim_force_difference_N"])
                                     for e in eqs]))


def plot_holding(curves: Sequence[HoldingCurve], ax=None, ax_force=None, published=CROSS_SLOPE_STUDY):
    """Holding moment (and hand-rim force difference on ``ax_force``) against cross slope.

    Parameters
    ----------
    curves : sequence of HoldingCurve
        One curve per chair (:func:`holding_curve`).
    ax : matplotlib.axes.Axes or None, optional
        Axes for the holding moment (N m); a new figure if None.
    ax_force : matplotlib.axes.Axes or None, optional
        Axes for the hand-rim force difference (N); omitted if None.
    published : tuple of 3 float or None, optional
        Mean, low, high of the treadmill study (N m/deg, Richter et al. 2007),
        drawn as lines through the origin; None to omit.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots()
    for c in curves:
        line, = ax.plot(c.cross_slopes_deg, c.holding_moment, marker="o", label=c.chair)
        ax.fill_between(c.cross_slopes_deg, c.friction_low, c.friction_high, color=line.get_color(), alpha=0.2)
        if ax_force is not None:
            ax_force.plot(c.cross_slopes_deg, c.handrim_difference, marker="o", label=c.chair)
    if published is not None and curves:
        x = np.array([0.0, max(float(c.cross_slopes_deg.max()) for c in curves)])
        mean, lo, hi = published
        ax.plot(x, mean * x, "k--", label=f"treadmill mean {mean} N m/deg")
        ax.fill_between(x, lo * x, hi * x, color="k", alpha=0.08, label=f"treadmill range {lo}-{hi}")
    ax.set_xlabel("cross slope (deg)")
    ax.set_ylabel("holding yaw moment (N m)")
    ax.legend(fontsize="small")
    if ax_force is not None:
        ax_force.set_xlabel("cross slope (deg)")
        ax_force.set_ylabel("hand-rim force difference (N)")
    return ax
