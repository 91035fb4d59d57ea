"""Measuring your own chair: pendulums, scales, anthropometry, units, measurement sheets and uncertainty.

``python -m stability.measure SHEET.toml -o CHAIR.toml`` turns a measurement
sheet into a chair file and an uncertainty file (docs/measure.md).
"""

from stability.chair.units import quantity
from stability.measure.bodies import Body, combine
from stability.measure.pendulum import (
           bifilar_pendulum_inertia,
           compound_pendulum_inertia,
           solid_cylinder_inertia,
           torsional_pendulum_inertia,
           torsional_rigidity,
           trifilar_pendulum_inertia,
)
from stability.uncertainty import PropagationResult, Uncertainty, delta_method, load_uncertainty, propagate

__all__ = ["Body", "combine", "bifilar_pendulum_inertia", "compound_pendulum_inertia", "solid_cylinder_inertia",
           "torsional_pendulum_inertia", "torsional_rigidity", "trifilar_pendulum_inertia", "PropagationResult",
           "Uncertainty", "delta_method", "load_uncertainty", "propagate", "quantity"]
