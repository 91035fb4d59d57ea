"""Static tip stability: ISO 7176-1 stability angles of the rigid chair with brakes locked.

``angles`` computes the angles toward the main wheels, toward the casters and to
each side (casters in their least stable swivel orientation), the anti-tip
angle and tipping on a combined grade and cross slope.  Command line:
``python -m stability.tipping``.  See ``docs/tipping.md``.
"""

from __future__ import annotations

from stability.tipping.angles import (
           DIRECTIONS,
           LOANE_KIRBY_REAR_DEG,
           FallLine,
           SlopeTip,
           TipAngles,
           anti_tip_angle,
           fall_distance,
           slope_tip,
           tip_angles,
)

__all__ = ["TipAngles", "SlopeTip", "FallLine", "tip_angles", "slope_tip", "fall_distance", "anti_tip_angle",
           "DIRECTIONS", "LOANE_KIRBY_REAR_DEG"]
