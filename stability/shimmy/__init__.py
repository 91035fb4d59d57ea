"""Caster shimmy: the towed wheel, Coulomb pin friction, the caster on the chair and the trail chart.

See docs/shimmy.md.
"""

from .towed_wheel import PARAMETERS, HopfBoundary, RouthHurwitz, TowedWheel, hurwitz_determinants

__all__ = ["TowedWheel", "RouthHurwitz", "HopfBoundary", "hurwitz_determinants", "PARAMETERS"]
