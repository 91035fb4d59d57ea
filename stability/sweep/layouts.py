"""Sweeps of a wheel layout, forward and in reverse: the layout's grid axes and its measures.

A spec whose ``chair`` is a layout (a layout preset or a ``[[wheel]]`` file), or whose speeds include a negative one
(reverse; a short-form chair is then expanded with :meth:`stability.layout.Layout.from_chair`), sweeps the layout.
Its grid axes are the layout's axes (:mod:`stability.advise.layout_axes`, the one set every layout command's
uncertainty file uses): ``caster_K_FIELD`` and ``wheel_J_FIELD`` (one wheel's field, 1-based), ``trail_ROW`` (every
caster of a row), ``drive_x`` (the driven wheels) and the body's ``m``, ``i_z``, ``h``.

Random draws (``[draws]``): the uncertainty file's tables name these axes instead of the short form's fields
(``[trail_front]``, ``[m]``, ``[caster_1_pin_friction]`` ...; ``relative = true`` as a fraction of the layout's own
value, :func:`layout_axis_value`); each draw sets them in file order after the grid's values
(:func:`draw_layout`), with the short form's common random numbers across designs.  A draw that makes an invalid
layout (outside a field's range, a base that no longer stands) is a row with the reason in ``error``.

The measures are the layout commands' (each row in the direction of its speed's sign): ``growth_rate`` (the layout's
linear model), ``critical_speeds`` (``critical_speed_m_s``: the speed up to which the layout is stable,
:func:`stability.compare.layouts.stable_up_to_bounded`, the search's ends as bounds with ``critical_speed_status``;
no locked-caster model of a layout: NaN), ``critical_impulse``
and ``equal_instability_speed`` (the layout studies), ``shimmy_margin`` (the smallest over the caster rows),
``tip_angles`` (the ISO 7176-1 angles over the outermost contacts: the smallest and the smaller lateral one; the
short form's toward-casters and toward-main-wheels columns are NaN), ``bench``.  The human-limited speed and the holding
moment are the short form's only.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.advise.layout_axes import (
    apply_layout_axis,
    check_layout_axis,
    check_layout_uncertainty,
    draw_layout,
    layout_axes,
    layout_axis_value,
)
from stability.advise.layout_levers import caster_rows
from stability.bench import run_bench
from stability.compare.layouts import stable_up_to_bounded
from stability.layout.linear import growth_rates
from stability.layout.model import Layout
from stability.layout.statics import tip_angles
from stability.shimmy.band import margin_bound, shimmy_band
from stability.shimmy.layout_caster import LayoutCaster
from stability.study.layout_equal_instability import layout_equal_instability
from stability.study.layout_impulse import layout_critical_impulses

__all__ = ["LAYOUT_MEASURES", "check_layout_axis", "layout_axes", "apply_layout_axis", "layout_chunk_values",
           "bench_of",
           "layout_axis_value", "check_layout_uncertainty", "draw_layout"]

#: The measures a layout sweep computes.
LAYOUT_MEASURES = ("growth_rate", "critical_speeds", "critical_impulse", "equal_instability_speed", "shimmy_margin",
                   "tip_angles", "bench")


def bench_of(layout: Layout) -> tuple[float, float]:
    """The virtual bench's worst score and longest level-ground stop (m) of a powered layout, NaN otherwise.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    (float, float)
    """
    if not any(w.driven for w in layout.wheels):
        return math.nan, math.nan
    r = run_bench(layout)
    return float(r.worst_score), max(float(c.braking_distance_m) for c in r.cases
                                     if c.family == "stop" and c.slope == "level")


def _shimmy(layout: Layout, speeds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The smallest margin over the caster rows at each speed, m, and its status (NaN and ``""``: none computable);
    a negative speed's at its size with the casters swung round (the reversed statics' loads, as
    ``python -m stability.shimmy``).  A row's margin without a boundary on the trails searched counts as its bound
    (:func:`stability.shimmy.band.margin_bound`); the smallest row's value and status are the layout's (a lower
    bound there holds for the smallest, which lies between it and the other rows' values)."""
    out, status = np.full(len(speeds), math.nan), np.full(len(speeds), "", dtype=object)
    rows = caster_rows(layout)
    if not rows:
        return out, status
    for reverse in (False, True):
        sel = (speeds < 0) == reverse
        if not sel.any():
            continue
        try:
            bands = [shimmy_band(LayoutCaster(layout, r[0], reverse), np.abs(speeds[sel])) for r in rows]
        except ValueError:
            continue
        per_row = [[margin_bound(float(m), b.trail_m) for m in b.margin_m] for b in bands]
        worst = [min((row[j] for row in per_row), key=lambda p: p[0]) for j in range(int(sel.sum()))]
        out[sel] = [v for v, _ in worst]
        status[sel] = [st for _, st in worst]
    return out, status


def layout_chunk_values(measures: tuple, layouts: list[Layout], speeds: np.ndarray, run: Any) -> dict[str, np.ndarray]:
    """Every measure of the chunk's layouts at the spec's signed speeds: column -> ``(layouts, speeds)`` array.

    Parameters
    ----------
    measures : tuple of str
    layouts : list of Layout
    speeds : ndarray
        m/s (negative: reverse).
    run : RunSpec
        The nonlinear measures' settings.

    Returns
    -------
    dict
    """
    n, k = len(layouts), len(speeds)
    out: dict[str, np.ndarray] = {}
    if n == 0:
        return out
    rev = speeds < 0
    if "growth_rate" in measures:
        out["growth_rate_1_s"] = np.array([growth_rates(lay, speeds) for lay in layouts])
    if "critical_speeds" in measures:
        found = [[stable_up_to_bounded(lay, bool(r)) for r in rev] for lay in layouts]
        out["critical_speed_m_s"] = np.array([[v for v, _ in row] for row in found]).reshape(n, k)
        out["critical_speed_status"] = np.array([[st for _, st in row] for row in found], dtype=object).reshape(n, k)
        out["locked_critical_speed_m_s"] = np.full((n, k), math.nan)
        out["locked_critical_speed_status"] = np.full((n, k), "", dtype=object)
    if "critical_impulse" in measures:
        res = [layout_critical_impulses(lay, speeds, run) for lay in layouts]
        out["critical_impulse_Ns"] = np.array([[r.bound_Ns for r in row] for row in res])
        out["critical_impulse_status"] = np.array([[r.status for r in row] for row in res], dtype=object)
    if "equal_instability_speed" in measures:
        v, st = np.full((n, k), math.nan), np.full((n, k), "", dtype=object)
        for i, lay in enumerate(layouts):
            for reverse in sorted(set(rev.tolist())):
                r = layout_equal_instability(lay, run, reverse=reverse)
                v[i, rev == reverse], st[i, rev == reverse] = r.value_or_bound, r.status
        out["equal_instability_speed_m_s"], out["equal_instability_status"] = v, st
    if "shimmy_margin" in measures:
        margins = [_shimmy(lay, speeds) for lay in layouts]
        out["shimmy_margin_m"] = np.array([v for v, _ in margins]).reshape(n, k)
        out["shimmy_margin_status"] = np.array([st for _, st in margins], dtype=object).reshape(n, k)
    if "tip_angles" in measures:
        tips = [tip_angles(lay) for lay in layouts]
        for col, get in (("static_stability_deg", lambda t: min(t.values())),
                         ("tip_toward_casters_deg", lambda t: math.nan),
                         ("tip_toward_main_wheels_deg", lambda t: math.nan),
                         ("tip_lateral_deg", lambda t: min(t["left_deg"], t["right_deg"]))):
            out[col] = np.repeat(np.array([get(t) for t in tips], dtype=float)[:, None], k, axis=1)
    if "bench" in measures:
        rows = [bench_of(lay) for lay in layouts]
        out["bench_worst_score"] = np.repeat(np.array([s for s, _ in rows])[:, None], k, axis=1)
        out["level_braking_distance_m"] = np.repeat(np.array([d for _, d in rows])[:, None], k, axis=1)
    return out
