"""Side-by-side comparison of chairs: which is more stable, by how much, and why.

``compute`` (measures, differences, single-parameter effects) -> ``text``
(text and JSON) -> ``plots`` (figures); ``python -m stability.compare``.
Rationale: docs/compare.md.
"""

from __future__ import annotations

from stability.compare.compute import (
           DEFAULT_SPEEDS,
           Comparison,
           Difference,
           EffectSet,
           Quantity,
           SingleEffect,
           compare,
           growth_curves,
           single_effects,
           unique_labels,
)
from stability.compare.text import comparison_dict, format_comparison

__all__ = ["DEFAULT_SPEEDS", "Comparison", "Difference", "EffectSet", "Quantity", "SingleEffect", "compare",
           "growth_curves", "single_effects", "unique_labels", "comparison_dict", "format_comparison"]
