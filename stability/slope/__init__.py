"""A chair on a slope: cross-slope veer, holding moment, stability and grades.

``model`` (forces and equations of motion on the plane) -> ``equilibrium``
(steady straight running, holding moment) -> ``uncorrected`` (the path when
nobody corrects), ``linear`` (stability about the slope equilibrium),
``grade`` (speed change and stability on a grade) -> ``plots``.  Command
line: ``python -m stability.slope``.  See ``docs/slopes.md``.
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
