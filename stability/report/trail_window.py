"""The trail design chart's data: directional stability against trail, and the shimmy-free trail window.

The equal-instability speeds come from the report's parametric study (trail at constant l1) and the
shimmy-free intervals from :func:`stability.shimmy.band.shimmy_band`; this module only intersects them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.shimmy.band import ShimmyBand
from stability.study.censored import sort_key

__all__ = ["TrailWindow", "intersect", "trail_window"]


def intersect(a: Sequence[tuple[float, float]], b: Sequence[tuple[float, float]]) -> list[tuple[float, float]]:
    """Intersection of two unions of closed intervals (each sorted, disjoint).

    Parameters
    ----------
    a, b : sequence of (float, float)

    Returns
    -------
    list of (float, float)
    """
    out = []
    for lo1, hi1 in a:
        for lo2, hi2 in b:
            lo, hi = max(lo1, lo2), min(hi1, hi2)
            if lo < hi:
                out.append((lo, hi))
    return sorted(out)


@dataclass(frozen=True)
class TrailWindow:
    """Directional stability against trail with the shimmy-free window.

    Attributes
    ----------
    chair : str
    chair_trail_m : float
    trails_m : numpy.ndarray
        Trails of the parametric study, m.
    speeds_m_s : numpy.ndarray
        Equal-instability speed at each trail (bracket bound where not found), m/s.
    found : numpy.ndarray of bool
        Whether each speed was found inside the bracket.
    nominal_m : tuple of (float, float)
        Shimmy-free trail intervals at every use speed with the nominal caster-compliance estimates, m.
    robust_m : tuple of (float, float)
        Shimmy-free at every use speed and every corner of the estimate ranges, m (may be empty).
    use_speeds_m_s : tuple of float
    """

    chair: str
    chair_trail_m: float
    trails_m: np.ndarray
    speeds_m_s: np.ndarray
    found: np.ndarray
    nominal_m: tuple
    robust_m: tuple
    use_speeds_m_s: tuple

    @property
    def chair_in_window(self) -> str:
        """``"robust"``, ``"nominal"`` (only with the nominal estimates) or ``"outside"``."""
        t = self.chair_trail_m
        if any(lo <= t <= hi for lo, hi in self.robust_m):
            return "robust"
        if any(lo <= t <= hi for lo, hi in self.nominal_m):
            return "nominal"
        return "outside"

    @property
    def shortest_safe_m(self) -> float | None:
        """The shortest trail that is shimmy-free with the nominal estimates (m), None if none."""
        return min((lo for lo, _ in self.nominal_m), default=None)

    @property
    def nearest_safe_m(self) -> float | None:
        """The shimmy-free trail (nominal estimates) nearest the chair's (m): the chair's own when it is inside the
        window, else the nearest edge of an interval (None: no shimmy-free trail)."""
        t = self.chair_trail_m
        best: float | None = None
        for lo, hi in self.nominal_m:
            x = min(max(t, lo), hi)
            if best is None or abs(x - t) < abs(best - t):
                best = float(x)
        return best

    def best_in_window(self) -> tuple[float, float, bool] | None:
        """The study's trail inside the nominal window with the highest equal-instability speed.

        Returns
        -------
        (trail m, speed m/s, found) or None
            ``found`` False: the speed is the bracket's end (the speed lies above it; a bound counts as its value
            and ranks ahead of the same value found, :func:`stability.study.censored.sort_key`).  None: no trail of
            the study lies in the window.
        """
        inside = [i for i, t in enumerate(self.trails_m) if any(lo <= t <= hi for lo, hi in self.nominal_m)
                  and np.isfinite(self.speeds_m_s[i])]
        if not inside:
            return None
        i = min(inside, key=lambda k: sort_key(float(self.speeds_m_s[k]), "=" if self.found[k] else ">", True))
        return float(self.trails_m[i]), float(self.speeds_m_s[i]), bool(self.found[i])


def trail_window(chair_name: str, chair_trail: float, sweep, band: ShimmyBand) -> TrailWindow:
    """Collect the trail design chart's data.

    Parameters
    ----------
    chair_name : str
    chair_trail : float
        The chair's trail, m.
    sweep : stability.study.Sweep
        The parametric study's trail sweep.
    band : ShimmyBand
        The chair's shimmy band at its use speeds.

    Returns
    -------
    TrailWindow
    """
    order = np.argsort(sweep.values)
    trails = np.asarray(sweep.values, float)[order]
    speeds = sweep.speeds[order]
    found = np.array([sweep.results[i].status == "found" for i in order])
    nominal: list = [(0.0, np.inf)]
    for iv in band.intervals_m:
        nominal = intersect(nominal, iv)
    robust = list(nominal)
    for corner in band.corner_intervals_m:
        for iv in corner:
            robust = intersect(robust, iv)
    return TrailWindow(chair_name, float(chair_trail), trails, speeds, found, tuple(nominal), tuple(robust),
                       tuple(band.speeds_m_s))
