"""The equations of motion: the one door to the generated code in :mod:`stability._generated`.

``full_width`` (chapter 6, variants ``"exact"`` and ``"thesis"``),
``zero_width`` (chapter 5), ``slope`` (the plane), ``forces`` (contact points,
normal loads, resultant and moment of the tire forces, slip angles, pin
friction) and ``statics`` (loads and stiffness at rest).  Nothing here does symbolic algebra; the sympy
derivations live in ``derivations/``.
"""

from __future__ import annotations

from stability.models import forces, full_width, zero_width
from stability.models.full_width import (
    accelerations,
    contact_velocities,
    linear_matrices,
    tire_resultant,
    tire_yaw_moment,
    trig,
)

__all__ = [
    "forces",
    "full_width",
    "zero_width",
    "accelerations",
    "contact_velocities",
    "linear_matrices",
    "tire_resultant",
    "tire_yaw_moment",
    "trig",
]
