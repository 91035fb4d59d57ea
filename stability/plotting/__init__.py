"""Matplotlib figures of the toolkit: functions from result objects to Figures/Axes.

Every function takes data (a :class:`stability.rootlocus.SpeedLocus`, a
:class:`stability.study.StabilityMap`, a :class:`stability.chair.Chair`, ...)
and draws on the ``ax`` it is given (returning it) or on a new
:class:`matplotlib.figure.Figure` (never through ``pyplot``).  Nothing is
computed here beyond what drawing needs; every axis is labelled with its
unit.  Modules: :mod:`.pages` (report pages), :mod:`.chair`, :mod:`.tires`,
:mod:`.loci`, :mod:`.responses`, :mod:`.studies`, :mod:`.sections` (slope and uncertainty
sections of the report), :mod:`.style` (colours).
"""

from __future__ import annotations

from stability.plotting.chair import chair_geometry, parameter_table
from stability.plotting.loci import (
    eigenvalues_vs_speed,
    gain_locus,
    growth_rate_vs_parameter,
    parameter_loci_figure,
    parameter_locus,
    speed_loci_figure,
    speed_locus,
)
from stability.plotting.pages import (
    PAGE_SIZE,
    finish,
    page,
    panels_page,
    plain_text,
    table_axes,
    table_page,
    text_page,
    wrap_text,
)
from stability.plotting.responses import trajectories, yaw_rate_responses
from stability.plotting.sections import drive_difference, growth_rate_band, uncorrected_heading, variance_shares
from stability.plotting.studies import (
    decision_chart,
    equal_instability_chart,
    stability_map,
    sweep_chart,
    trail_window_chart,
)
from stability.plotting.tires import cornering_stiffness_curves, tire_curves

__all__ = [
    "PAGE_SIZE", "page", "finish", "panels_page", "text_page", "table_page", "table_axes", "wrap_text", "plain_text",
    "chair_geometry", "parameter_table",
    "tire_curves", "cornering_stiffness_curves",
    "speed_locus", "speed_loci_figure", "eigenvalues_vs_speed", "parameter_locus", "parameter_loci_figure",
    "growth_rate_vs_parameter", "gain_locus",
    "yaw_rate_responses", "trajectories",
    "equal_instability_chart", "sweep_chart", "stability_map", "trail_window_chart", "decision_chart",
    "drive_difference", "uncorrected_heading", "growth_rate_band", "variance_shares",
]
