"""Intervals of the geometric measures over a chair's (or a wheel layout's) uncertainty file."""

from __future__ import annotations

import numpy as np

from stability.advise.layout_axes import LayoutDraw
from stability.chair import Chair
from stability.layout.model import Layout
from stability.layout.statics import tip_angles as layout_tip_angles
from stability.tipping import tip_angles

__all__ = ["tip_interval", "SAMPLES"]

#: Draws of the uncertainty file.
SAMPLES = 200


def tip_interval(chair: Chair | Layout, uncertainty, samples: int = SAMPLES, seed: int = 0) -> tuple[float, float]:
    """2.5-97.5 % interval of the smallest static stability angle over ``samples`` seeded draws (deg).

    Parameters
    ----------
    chair : Chair or Layout
        A layout's draws name its axes (:func:`stability.advise.layout_axes.layout_axes`) and its angle is the
        smallest of the four ISO 7176-1 angles over the outermost contacts (:func:`stability.layout.statics.
        tip_angles`, the short form's for a chair expanded as a layout).
    uncertainty : stability.uncertainty.Uncertainty
    samples : int
    seed : int

    Returns
    -------
    tuple of float
        ``(low, high)``, deg.
    """
    if isinstance(chair, Layout):
        draws = uncertainty.sample(LayoutDraw(chair), samples, seed)
        angles = np.array([min(layout_tip_angles(d.layout).values()) for d in draws])
    else:
        angles = np.array([tip_angles(c).smallest_deg for c in uncertainty.sample(chair, samples, seed)])
    lo, hi = np.percentile(angles, [2.5, 97.5])
    return float(lo), float(hi)
