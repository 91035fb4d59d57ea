"""Measuring your own chair: pendulums, scales, anthropometry, units, measurement sheets and uncertainty.

``python -m stability.measure SHEET.toml -o CHAIR.toml`` turns a measurement
sheet into a chair file and an uncertainty file (docs/measure.md).
"""

from ..uncertainty import PropagationResult, Uncertainty, delta_method, load_uncertainty, propagate
from .bodies import Body, combine
from .pendulum import (
    bifilar_pendulum_inertia,
    compound_pendulum_inertia,
    solid_cylinder_inertia,
    torsional_pendulum_inertia,
    torsional_rigidity,
    trifilar_pendulum_inertia,
)
from .units import quantity

__all__ = ["Body", "combine", "bifilar_pendulum_inertia", "compound_pendulum_inertia", "solid_cylinder_inertia",
           "torsional_pendulum_inertia", "torsional_rigidity", "trifilar_pendulum_inertia", "PropagationResult",
           "Uncertainty", "delta_method", "load_uncertainty", "propagate", "quantity"]
