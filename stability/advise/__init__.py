"""The advisor: what to change on a chair, what it buys and what it costs.

``measures`` (every measure of many chairs, one batch per study: the one place the advisor calls
the studies) -> ``levers`` (the design changes) -> ``limits`` (the constraints a change must meet, what
pin friction buys against shimmy) -> ``advisor`` (verdict, constraints, ranking on the
low ends of the intervals, recommendation) -> ``text`` (plain language) and ``python -m
stability.advise``.  See ``docs/advise.md``.
"""

from __future__ import annotations

from stability.advise.advisor import (
           DEFAULT_CROSS_SLOPE_DEG,
           DEFAULT_SPEEDS,
           MAX_PIN_FRICTION_N_M,
           MIN_SHIMMY_MARGIN_M,
           Advice,
           Candidate,
           Constraint,
           Recommendation,
           advise,
)
from stability.advise.levers import LEVERS, Change, lever_changes
from stability.advise.measures import IMPULSE_SPEED, Interval, Measures, measure_chairs

__all__ = ["advise", "Advice", "Candidate", "Constraint", "Recommendation", "Measures", "Interval", "measure_chairs",
           "Change", "LEVERS", "lever_changes", "IMPULSE_SPEED", "DEFAULT_SPEEDS", "DEFAULT_CROSS_SLOPE_DEG",
           "MAX_PIN_FRICTION_N_M", "MIN_SHIMMY_MARGIN_M"]
