"""Resolution of every computation in the report: full or ``--quick``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stability import study
from stability.settings.reference import HORIZON

__all__ = ["Settings"]


@dataclass(frozen=True)
class Settings:
    """Resolution of every computation in the report (``full`` or ``quick``).

    Attributes
    ----------
    quick : bool
        Coarse grids (marked QUICK on every page).
    speed_points, locus_points, gain_points : int
        Points of the speed, parameter and feedback-gain loci.
    duration, dt : float
        Simulated time and step of the nonlinear runs (s).
    tol : float
        Bisection tolerance of equal-instability speeds (m/s).
    candidates : int
        Candidate speeds per bisection round (one batch each).
    bracket : tuple of float
        Speed bracket of the bisection (m/s).
    plan : dict or None
        Parametric-study plan (None: ``study.DEFAULT_PLAN``).
    map_speeds, map_frictions, map_impulses : tuple of float
        Grids of the stability maps (m/s, N m, N s).
    impulse_tol : float
        Relative tolerance of the critical impulses and of the elasticities' impulses.
    impulse_rel_tol : float
        Relative bisection tolerance of the critical impulse on the summary and uncertainty pages.
    shimmy_trails, shimmy_speeds : tuple of float
        Grid of the trail trade-off chart (m, m/s).
    """

    quick: bool = False
    speed_points: int = 700
    locus_points: int = 121
    gain_points: int = 300
    duration: float = HORIZON
    dt: float = 0.001
    tol: float = 0.005
    candidates: int = 7
    bracket: tuple = (0.2, 3.0)
    plan: dict | None = None           # None: study.DEFAULT_PLAN
    map_speeds: tuple = tuple(np.round(np.linspace(0.3, 2.0, 18), 3))
    map_frictions: tuple = tuple(np.round(np.linspace(0.0, 0.3, 13), 3))
    map_impulses: tuple = tuple(np.round(np.linspace(1.0, 10.0, 10), 3))
    impulse_tol: float = 0.001
    impulse_rel_tol: float = 0.005
    shimmy_trails: tuple = tuple(np.round(np.linspace(0.02, 0.12, 21), 4))
    shimmy_speeds: tuple = tuple(np.round(np.linspace(0.25, 3.0, 12), 4))

    @classmethod
    def for_mode(cls, quick: bool) -> Settings:
        """The full settings, or the coarse ``--quick`` ones.

        Parameters
        ----------
        quick : bool

        Returns
        -------
        Settings
        """
        if not quick:
            return cls()
        return cls(quick=True, speed_points=150, locus_points=41, gain_points=80, duration=6.0, dt=0.001,
                   tol=0.05, candidates=9, bracket=(0.3, 2.5), plan=study.QUICK_PLAN,
                   map_speeds=(0.4, 0.8, 1.2, 1.6, 2.0), map_frictions=(0.0, 0.1, 0.2, 0.3),
                   map_impulses=(2.0, 4.0, 8.0), impulse_tol=0.01, impulse_rel_tol=0.05,
                   shimmy_trails=(0.02, 0.04, 0.06, 0.08, 0.1, 0.12), shimmy_speeds=(0.5, 1.5, 3.0))
