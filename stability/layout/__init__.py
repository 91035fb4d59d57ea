"""Chairs as people ride them: any wheel layout (fixed wheels and casters), forward and in reverse.

``model`` (a chair as a body and its wheels; the short form of :class:`stability.chair.Chair` expands into it)
-> ``statics`` (static loads: the lever rule on two support lines, vertical compliance on more) -> ``linear``
(the linear model of any layout from the generated equations) -> ``presets`` (power bases of one frame: front-,
mid- and rear-wheel drive).  See ``docs/layouts.md``.
"""

from __future__ import annotations

from stability.layout.linear import LayoutSummary, analyse_layout, growth_rates, input_matrices, state_matrices
from stability.layout.model import Caster, FixedWheel, Layout
from stability.layout.statics import static_loads

__all__ = ["Layout", "FixedWheel", "Caster", "static_loads", "state_matrices", "input_matrices", "growth_rates",
           "LayoutSummary", "analyse_layout"]
