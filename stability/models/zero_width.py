"""Zero-width (bicycle) model of chapter 5: the generated closed forms, eqs 5-9..5-17.

Derived in ``derivations/zero_width.py``; see :mod:`stability._generated.zero_width`
for each function's parameters and units.
"""

from __future__ import annotations

from stability._generated.zero_width import (
    a_coefficients,
    characteristic_coefficients,
    critical_speed_squared,
    routh_hurwitz_margin,
    state_matrix,
    understeer_coefficient,
)

__all__ = [
    "a_coefficients",
    "characteristic_coefficients",
    "critical_speed_squared",
    "routh_hurwitz_margin",
    "state_matrix",
    "understeer_coefficient",
]
