"""A chair on a slope: the statics of straight running, holding moment, drive forces.

``model`` (the plane; tire forces at given loads) -> ``equilibrium``
(steady straight running, holding moment, drive report) -> ``plots``.
The motion on a slope is the simulator's: the uncorrected path
(:mod:`stability.study.veer`) and the stability about the equilibrium and on
grades (:mod:`stability.study.slope_stability`).  Command line:
``python -m stability.slope``.  See ``docs/slopes.md``.
"""

from __future__ import annotations

from stability.slope.equilibrium import (
           Equilibrium,
           HandRim,
           drive_report,
           holding_moment_closed_form,
           max_cross_slope,
           solve,
)
from stability.slope.model import Plane, SlopeModel

__all__ = ["Plane", "SlopeModel", "HandRim", "Equilibrium", "solve", "drive_report",
           "holding_moment_closed_form", "max_cross_slope"]
