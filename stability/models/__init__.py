"""The equations of motion: the one door to the generated code in :mod:`stability._generated`.

``full_width`` (chapter 6, variants ``"exact"`` and ``"thesis"``) and
``zero_width`` (chapter 5).  Nothing here does symbolic algebra; the sympy
derivations live in ``derivations/``.
"""

from __future__ import annotations

from stability.models import full_width, zero_width
from stability.models.full_width import (
    accelerations,
    contact_velocities,
    linear_matrices,
    tire_resultant,
    tire_yaw_moment,
    trig,
)

__all__ = [
    "full_width",
    "zero_width",
    "accelerations",
    "contact_velocities",
    "linear_matrices",
    "tire_resultant",
    "tire_yaw_moment",
    "trig",
]
