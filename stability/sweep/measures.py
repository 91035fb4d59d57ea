"""One chunk of a sweep: its designs and draws as chairs, every measure vectorised over the whole chunk.

Rows are ordered by (design, draw, speed); a chunk holds whole (design, draw)
pairs.  Designs are the grid's points in row-major order (the first axis
varies slowest).  Draws use common random numbers: draw ``k`` is the same
standardised draw for every design (``Uncertainty.unit_draws(n, seed)``), so
designs are compared under the same users.  The linear measures come from
one :class:`stability.linear.batch.ChairBatch` for the chunk, the critical
impulse from one batched search over every (chair, speed) pair of the chunk,
the equal-instability speed from one batched bisection over its chairs.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.chair.power import drive_kind
from stability.driver.linear import rule_speed
from stability.layout.model import Layout
from stability.linear.batch import ChairBatch
from stability.models.statics import check_static_loads
from stability.settings.defaults import MAX_SPEED
from stability.shimmy.band import margin_bound, shimmy_band
from stability.slope import solve
from stability.study import critical_impulses, equal_instability_speeds
from stability.sweep.layouts import apply_layout_axis, bench_of, draw_layout, layout_chunk_values
from stability.sweep.spec import _NUMERIC, INVALID, MEASURES, SweepSpec, apply_axis
from stability.tipping import tip_angles

__all__ = ["CRITICAL_SPEED_GRID", "columns", "design_values", "chunk_pairs", "n_chunks", "compute_chunk"]

#: Speeds searched for the first critical speed, m/s (as the linear intervals search them).
CRITICAL_SPEED_GRID = np.geomspace(0.01, MAX_SPEED, 600)


def columns(spec: SweepSpec) -> list[str]:
    """Column names of the results, in order.

    Parameters
    ----------
    spec : SweepSpec

    Returns
    -------
    list of str
    """
    # a layout sweep's designs are its grid values (a layout has no fixed list of fields)
    fields = [] if isinstance(spec.chair, Layout) else list(_NUMERIC)
    cols = ["design", "draw", "speed_m_s"] + [f"grid_{a}" for a, _ in spec.grid] + fields
    for m in spec.measures:
        cols += list(MEASURES[m][0])
    return cols + ["error"]


def design_values(spec: SweepSpec) -> list[tuple[float, ...]]:
    """Every design's grid values, row-major (first axis slowest).

    Parameters
    ----------
    spec : SweepSpec

    Returns
    -------
    list of tuple of float
    """
    return list(itertools.product(*[v for _, v in spec.grid])) if spec.grid else [()]


def n_chunks(spec: SweepSpec) -> int:
    """Number of chunks.

    Parameters
    ----------
    spec : SweepSpec

    Returns
    -------
    int
    """
    per = max(1, spec.chunk_rows // len(spec.speeds))
    return math.ceil(spec.designs * spec.draws / per)


def chunk_pairs(spec: SweepSpec, index: int) -> range:
    """The (design, draw) pair numbers of chunk ``index`` (pair = design * draws + draw).

    Parameters
    ----------
    spec : SweepSpec
    index : int
        Chunk number.

    Returns
    -------
    range
    """
    per = max(1, spec.chunk_rows // len(spec.speeds))
    return range(index * per, min((index + 1) * per, spec.designs * spec.draws))


def _chair(spec: SweepSpec, values: tuple[float, ...], draw: int,
           unit: dict[str, np.ndarray] | None) -> Chair | Layout:
    if isinstance(spec.chair, Layout):
        lay = spec.chair
        for (axis, _), v in zip(spec.grid, values, strict=True):
            lay = apply_layout_axis(lay, axis, v)
        if spec.uncertainty is not None and unit is not None:
            lay = draw_layout(lay, spec.uncertainty, unit, draw)
        return dataclasses.replace(lay, name=f"{spec.chair.name} design {values}" if values else spec.chair.name)
    c = spec.chair
    for (axis, _), v in zip(spec.grid, values, strict=True):
        c = apply_axis(c, axis, v)
    if spec.uncertainty is not None and unit is not None:
        vals = spec.uncertainty.field_values(c, {k: v[draw:draw + 1] for k, v in unit.items()})
        c = c.replace(**{f: float(v[0]) for f, v in vals.items()})
    check_static_loads(c)
    return c.replace(name=f"{spec.chair.name} design {values}" if values else spec.chair.name)


def compute_chunk(spec: SweepSpec, index: int) -> list[list[Any]]:
    """The rows of chunk ``index`` (lists in :func:`columns` order).

    A pair whose chair is invalid (a grid value outside a field's range, the
    c.g. outside the wheel contacts) gives rows with every measure NaN and the
    one-line reason in ``error``.

    Parameters
    ----------
    spec : SweepSpec
    index : int

    Returns
    -------
    list of list
    """
    designs = design_values(spec)
    unit = spec.uncertainty.unit_draws(spec.draws, spec.seed) if spec.uncertainty is not None else None
    pairs = list(chunk_pairs(spec, index))
    chairs: list[Chair | Layout | None] = []
    errors: list[str] = []
    for p in pairs:
        d, k = divmod(p, spec.draws)
        try:
            chairs.append(_chair(spec, designs[d], k, unit))
            errors.append("")
        except ValueError as exc:
            chairs.append(None)
            errors.append(str(exc).splitlines()[0])
    ok = [i for i, c in enumerate(chairs) if c is not None]
    good = [c for c in chairs if c is not None]
    speeds = np.array(spec.speeds)
    if isinstance(spec.chair, Layout):
        values = layout_chunk_values(spec.measures, good, speeds, spec.run)      # type: ignore[arg-type]
    else:
        values = _measures(spec, good, speeds)        # type: ignore[arg-type]   # column -> (len(ok), K) array
    fields = [] if isinstance(spec.chair, Layout) else _NUMERIC
    rows = []
    for i, p in enumerate(pairs):
        d, k = divmod(p, spec.draws)
        c = chairs[i]
        j = ok.index(i) if c is not None else -1
        for s_i, s in enumerate(spec.speeds):
            row: list[Any] = [d, k, s, *designs[d]]
            row += [float(getattr(c, f)) if c is not None else math.nan for f in fields]
            for m in spec.measures:
                for col in MEASURES[m][0]:
                    row.append(values[col][j, s_i] if j >= 0 else (math.nan if not col.endswith("status")
                                                                      else INVALID))
            row.append(errors[i])
            rows.append(row)
    return rows


#: (chair, speed) pairs per critical-impulse call: the worst case the studies' work check assumes (80 runs of 10 s at
#: 1 ms, 1 us per step: 0.8 s per pair) stays within its 600 s budget with room for the smaller stable steps of slow
#: speeds (250 x 0.8 s = 200 s); the real cost is about 20 s of simulation, 10 ms, per pair (docs/scale.md).
SEARCH_SLICE = 250


def _measures(spec: SweepSpec, chairs: list[Chair], speeds: np.ndarray) -> dict[str, np.ndarray]:
    n, k = len(chairs), len(speeds)
    out: dict[str, np.ndarray] = {}
    if n == 0:
        return out
    batch = ChairBatch(chairs, spec.model) if {"growth_rate", "critical_speeds"} & set(spec.measures) else None
    if "growth_rate" in spec.measures and batch is not None:
        out["growth_rate_1_s"] = batch.growth_rates(speeds)
    if "critical_speeds" in spec.measures and batch is not None:
        # a bound is a value: "stable at every speed up to 30 m/s" is stored as 30 with the status "above" (the most
        # stable a design can be here), "unstable from 0.01 m/s" as 0.01 with "below"
        for col, casters in (("critical_speed", "free"), ("locked_critical_speed", "locked")):
            v, st = batch.first_critical_speed_bounded(CRITICAL_SPEED_GRID, casters)
            out[f"{col}_m_s"] = np.repeat(v[:, None], k, axis=1)
            out[f"{col}_status"] = np.repeat(st[:, None], k, axis=1)
    if "critical_impulse" in spec.measures:
        pc, ps = [c for c in chairs for _ in speeds], np.tile(speeds, n)
        # one call per SEARCH_SLICE pairs: each call's worst-case work is checked against the studies' budget
        # (study.impulse.check_study_work), and the searches of different pairs do not interact, so the answers
        # are those of one call for the whole chunk (any chunk_rows)
        res = [r for i in range(0, len(pc), SEARCH_SLICE)
               for r in critical_impulses(pc[i:i + SEARCH_SLICE], ps[i:i + SEARCH_SLICE], spec.run)]
        # a bound is a value: "never reached up to 40 N s" is stored as 40 with the status "never"
        out["critical_impulse_Ns"] = np.array([r.bound_Ns for r in res]).reshape(n, k)
        out["critical_impulse_status"] = np.array([r.status for r in res], dtype=object).reshape(n, k)
    if "equal_instability_speed" in spec.measures:
        res2 = equal_instability_speeds(chairs, spec.run, progress=False)
        v = np.array([r.value_or_bound for r in res2])          # "above 3 m/s" is stored as 3 with its status
        out["equal_instability_speed_m_s"] = np.repeat(v[:, None], k, axis=1)
        out["equal_instability_status"] = np.repeat(np.array([r.status for r in res2], dtype=object)[:, None], k,
                                                    axis=1)
    if "shimmy_margin" in spec.measures:
        margins = [_shimmy(c, speeds) for c in chairs]
        out["shimmy_margin_m"] = np.array([v for v, _ in margins]).reshape(n, k)
        out["shimmy_margin_status"] = np.array([st for _, st in margins], dtype=object).reshape(n, k)
    if "tip_angles" in spec.measures:
        tips = [tip_angles(c) for c in chairs]
        for col, get in (("static_stability_deg", lambda t: t.smallest_deg),
                         ("tip_toward_casters_deg", lambda t: t.toward_casters_deg),
                         ("tip_toward_main_wheels_deg", lambda t: t.toward_main_wheels_deg),
                         ("tip_lateral_deg", lambda t: min(t.lateral_left_deg, t.lateral_right_deg))):
            out[col] = np.repeat(np.array([get(t) for t in tips], dtype=float)[:, None], k, axis=1)
    if "human_limited_speed" in spec.measures:
        # the divergence rule (stability.driver.linear.rule_speed): beyond the speeds checked, a bound
        lim = [rule_speed(c, spec.reaction_time_s, spec.model) for c in chairs]
        status = {"=": "found", ">": "above", "<": "below"}
        out["human_limited_speed_m_s"] = np.repeat(np.array([u for u, _ in lim])[:, None], k, axis=1)
        out["human_limited_status"] = np.repeat(np.array([status[s] for _, s in lim], dtype=object)[:, None], k,
                                                axis=1)
    if "bench" in spec.measures:
        # the virtual test bench (stability.bench, default drive settings) on each powered design: the worst
        # wheel-lift score of the ISO 7176-2 matrix and the longest level-ground stop (ISO 7176-3); NaN for a chair
        # pushed on its hand rims (no drive controller to test)
        rows = [_bench(c) for c in chairs]
        out["bench_worst_score"] = np.repeat(np.array([s for s, _ in rows])[:, None], k, axis=1)
        out["level_braking_distance_m"] = np.repeat(np.array([d for _, d in rows])[:, None], k, axis=1)
    if "holding_moment" in spec.measures:
        out["holding_moment_N_m_per_deg"] = np.array([[_holding(c, float(u)) for u in speeds] for c in chairs])
    return out


def _shimmy(chair: Chair, speeds: np.ndarray) -> tuple[list[float], list[str]]:
    """Signed distance of the trail to the nearest shimmy boundary at each speed, m, and its status: a margin
    without a boundary on the trails searched as its bound (:func:`stability.shimmy.band.margin_bound`); NaN and
    ``""`` where not computable."""
    try:
        band = shimmy_band(chair, speeds)
    except ValueError:
        return [math.nan] * len(speeds), [""] * len(speeds)
    pairs = [margin_bound(float(m), band.trail_m) for m in band.margin_m]
    return [v for v, _ in pairs], [st for _, st in pairs]


def _bench(chair: Chair) -> tuple[float, float]:
    """The bench's worst score and longest level-ground stopping distance (m) of a powered chair, NaN otherwise."""
    if drive_kind(chair) != "motor":
        return math.nan, math.nan
    return bench_of(Layout.from_chair(chair))


def _holding(chair: Chair, speed: float) -> float:
    """Yaw moment that holds a straight line across a 1 deg cross slope, N m per deg (NaN: no equilibrium)."""
    try:
        return abs(solve(chair, 1.0, speed).holding_moment)
    except ValueError:
        return math.nan
