"""Caster shimmy: the towed wheel, Coulomb pin friction, the caster on the chair and the trail chart.

See docs/shimmy.md.
"""

from stability.shimmy.chair_modes import (
           ChairShimmy,
           ChairTrailChart,
           chair_critical_trail,
           chair_shimmy,
           chair_trail_chart,
           relaxed_state_matrices,
           relaxed_state_space,
           shimmy_mode,
)
from stability.shimmy.towed_wheel import PARAMETERS, HopfBoundary, RouthHurwitz, TowedWheel, hurwitz_determinants

__all__ = ["TowedWheel", "RouthHurwitz", "HopfBoundary", "hurwitz_determinants", "PARAMETERS",
           "relaxed_state_matrices", "relaxed_state_space", "shimmy_mode", "ChairShimmy", "chair_shimmy",
           "chair_critical_trail", "ChairTrailChart", "chair_trail_chart"]
