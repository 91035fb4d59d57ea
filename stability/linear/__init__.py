"""Linear stability analysis: state-space models, eigenvalues against speed, critical speeds.

``model`` (matrices, :class:`control.StateSpace`, input columns) ->
``modes`` (eigenvalues against speed, mode tracking) -> ``critical``
(zero crossings of the largest real part) -> ``summary`` (zero-width closed
forms, divergence rates, :func:`analyse`).
"""

from __future__ import annotations

from stability.linear.critical import Crossing, critical_speeds, max_real_part
from stability.linear.model import (
    STATES_FREE,
    STATES_LOCKED,
    input_matrices,
    lateral_force_input,
    state_matrices,
    state_space,
)
from stability.linear.modes import eigenvalues_vs_speed, track_modes
from stability.linear.summary import (
    Divergence,
    StabilitySummary,
    ZeroWidthResult,
    analyse,
    divergence,
    massless_caster_rate,
    zero_width,
)

__all__ = [
    "STATES_FREE",
    "STATES_LOCKED",
    "state_matrices",
    "input_matrices",
    "state_space",
    "lateral_force_input",
    "eigenvalues_vs_speed",
    "track_modes",
    "Crossing",
    "critical_speeds",
    "max_real_part",
    "zero_width",
    "ZeroWidthResult",
    "Divergence",
    "divergence",
    "massless_caster_rate",
    "StabilitySummary",
    "analyse",
]
