"""Parameter uncertainty (data layer): distributions of chair fields, uncertainty files, seeded sampling, propagation.

``stability.measure`` writes uncertainty files; ``linear``, ``study`` and the
sweep read them.  This package imports only the chair (nothing above the data
layer).  File format: one table per uncertain chair field (docs/measure.md)::

    [s1]
    distribution = "normal"   # around the chair's own value; optional mean
    std = 0.01

    [pin_friction]            # a label: one draw shared by several fields
    fields = ["pin_friction_left", "pin_friction_right"]
    distribution = "uniform"
    low = -0.5
    high = 0.5
    relative = true           # low/high are fractions of each field's own value

Draws of each table come from their own stream seeded by (seed, table name),
so adding a table leaves the others' draws unchanged.
"""

from stability.uncertainty.distributions import Distribution, Uncertainty
from stability.uncertainty.io import from_mapping, load_uncertainty, loads_uncertainty
from stability.uncertainty.propagation import DeltaResult, PropagationResult, delta_method, propagate

__all__ = ["Distribution", "Uncertainty", "from_mapping", "load_uncertainty", "loads_uncertainty", "DeltaResult",
           "PropagationResult", "delta_method", "propagate"]
