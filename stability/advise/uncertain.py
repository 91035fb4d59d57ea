"""Intervals of the geometric measures over a chair's uncertainty file."""

from __future__ import annotations

import numpy as np

from stability.chair import Chair
from stability.tipping import tip_angles

__all__ = ["tip_interval", "SAMPLES"]

#: Draws of the uncertainty file.
SAMPLES = 200


def tip_interval(chair: Chair, uncertainty, samples: int = SAMPLES, seed: int = 0) -> tuple[float, float]:
    """2.5-97.5 % interval of the smallest static stability angle over ``samples`` seeded draws (deg).

    Parameters
    ----------
    chair : Chair
    uncertainty : stability.uncertainty.Uncertainty
    samples : int
    seed : int

    Returns
    -------
    tuple of float
        ``(low, high)``, deg.
    """
    angles = np.array([tip_angles(c).smallest_deg for c in uncertainty.sample(chair, samples, seed)])
    lo, hi = np.percentile(angles, [2.5, 97.5])
    return float(lo), float(hi)
