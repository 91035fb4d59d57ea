"""Old import path of :mod:`stability.uncertainty.propagation`, kept for existing code."""

from ..uncertainty.propagation import DeltaResult, PropagationResult, delta_method, propagate

__all__ = ["PropagationResult", "propagate", "DeltaResult", "delta_method"]
