"""Old import path of :mod:`stability.uncertainty` (distributions and files), kept for existing code."""

from ..uncertainty.distributions import Distribution, Uncertainty
from ..uncertainty.io import from_mapping, load_uncertainty, loads_uncertainty

__all__ = ["Distribution", "Uncertainty", "load_uncertainty", "loads_uncertainty", "from_mapping"]
