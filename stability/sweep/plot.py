"""Figures of a sweep: each measure over the first two grid axes (median over the draws), one panel per speed."""

from __future__ import annotations

from typing import Any

import numpy as np

from stability.study.censored import quantile
from stability.sweep.run import STATUS_OF, row_sides
from stability.sweep.spec import GRID_UNITS, MEASURES, SweepSpec

__all__ = ["UNITS", "measure_figures"]

#: Axis and colour-bar labels of the measure columns.
UNITS = {"growth_rate_1_s": "growth rate (1/s)", "critical_speed_m_s": "first critical speed (m/s)",
         "locked_critical_speed_m_s": "locked-caster critical speed (m/s)",
         "critical_impulse_Ns": "critical impulse (N s)",
         "equal_instability_speed_m_s": "equal-instability speed (m/s)",
         "shimmy_margin_m": "shimmy margin of the trail (m)", "static_stability_deg": "static stability (deg)",
         "tip_toward_casters_deg": "tip angle toward the casters (deg)",
         "tip_toward_main_wheels_deg": "tip angle toward the main wheels (deg)",
         "tip_lateral_deg": "lateral tip angle (deg)", "holding_moment_N_m_per_deg": "holding moment (N m/deg)",
         "human_limited_speed_m_s": "speed the driver can hold (m/s)",
         "bench_worst_score": "worst ISO 7176-2 wheel-lift score (0-3)",
         "level_braking_distance_m": "longest level-ground stop (m)"}
_CAPTION = {"growth_rate_1_s": "lower is more stable (negative: disturbances decay)",
            "critical_speed_m_s": "higher is better: the chair is stable below it",
            "locked_critical_speed_m_s": "higher is better: with the casters locked the chair is stable below it",
            "critical_impulse_Ns": "higher is better: the smallest push that spins the chair",
            "equal_instability_speed_m_s": "higher is better: the speed at which it is as unstable as the reference",
            "shimmy_margin_m": "higher is better: distance of the trail to the nearest shimmy boundary (< 0: shimmies)",
            "static_stability_deg": "higher is better: the smallest ISO 7176-1 static tip angle",
            "tip_toward_casters_deg": "higher is better: the static tip angle toward the casters",
            "tip_toward_main_wheels_deg": "higher is better: the static tip angle toward the main wheels",
            "tip_lateral_deg": "higher is better: the smaller lateral static tip angle",
            "holding_moment_N_m_per_deg": "lower is better: the yaw moment that holds a line across a cross slope",
            "human_limited_speed_m_s": "higher is better: the speed up to which a driver of the spec's reaction time "
                                       "holds the chair (divergence rule)",
            "bench_worst_score": "lower is better: 0 no wheel lifts, 1 a wheel lifts, 2 held by anti-tip devices, "
                                 "3 tips over (quasi-static bench, default drive settings)",
            "level_braking_distance_m": "lower is better: the longest ISO 7176-3 stop on level ground (quasi-static "
                                        "bench, default drive settings)"}
_GRID_UNITS = GRID_UNITS


def _axis_label(axis: str) -> str:
    unit = _GRID_UNITS.get(axis, "-")
    return f"{axis} ({unit})"


def measure_figures(spec: SweepSpec, data: dict[str, list]) -> list[Any]:
    """One figure per measure column: the median over the draws against the first two grid axes.

    A median that is a bound (the search ended beyond its range: "above 3 m/s") is drawn at the bound and
    hatched (a bound is a value, never a blank).  Colour ranges narrower than 1 % of the values are widened to
    1 % so that rounding-level differences do not look like design differences (the caption says so).

    Parameters
    ----------
    spec : SweepSpec
    data : dict
        Result columns (:func:`stability.sweep.run.read_rows`).

    Returns
    -------
    list of matplotlib.figure.Figure
    """
    from matplotlib.figure import Figure

    figs = []
    axes = [a for a, _ in spec.grid][:2]
    speed = np.asarray(data["speed_m_s"], dtype=float)
    for m in spec.measures:
        for col in MEASURES[m][0]:
            if col not in UNITS:
                continue
            vals = np.asarray(data[col], dtype=float)
            sides = row_sides(data, col)
            fig = Figure(figsize=(4.0 * len(spec.speeds) + 1.0, 4.6), layout="constrained")
            panels = fig.subplots(1, len(spec.speeds), squeeze=False)[0]
            narrow = False
            for ax, sp in zip(panels, spec.speeds, strict=True):
                narrow |= _panel(ax, fig, spec, data, vals, sides, speed == sp, axes, col)
                ax.set_title(f"{sp:g} m/s")
            fig.suptitle(f"{UNITS[col]}: {spec.chair.name}, {spec.model} model, median of {spec.draws} draw(s)")
            caption = _CAPTION[col] + ("; hatched: beyond the searched range (drawn at the range's end, a bound)"
                                       if col in STATUS_OF else "") + "; blank: no value (invalid chair)"
            if narrow:
                caption += "; the designs differ by less than 1 % (colour range widened to 1 %)"
            fig.text(0.01, 0.005, caption, fontsize=8, wrap=True)
            figs.append(fig)
    return figs


def _cell(vals: np.ndarray, sides: np.ndarray, sel: np.ndarray) -> tuple[float, str]:
    return quantile(vals[sel], sides[sel], 0.5) if np.isfinite(vals[sel]).any() else (np.nan, "=")


def _panel(ax, fig, spec: SweepSpec, data: dict[str, list], vals: np.ndarray, sides: np.ndarray, sel: np.ndarray,
           axes: list[str], col: str) -> bool:
    """Draw one speed's panel; returns whether its colour range was widened (values within 1 %)."""
    if not axes:
        v, side = _cell(vals, sides, sel)
        ax.bar([0], [v], color="#0072B2", hatch="//" if side != "=" else None, edgecolor="white")
        ax.set_xticks([0], [spec.chair.name])
        ax.set_ylabel(UNITS[col])
        return False
    x = np.asarray(data[f"grid_{axes[0]}"], dtype=float)
    xs = np.unique(x[sel])
    if len(axes) == 1:
        cells = [_cell(vals, sides, sel & (x == v)) for v in xs]
        med = np.array([c[0] for c in cells])
        ax.plot(xs, med, "o-", color="#0072B2", label="median over draws")
        bound = np.array([c[1] != "=" for c in cells])
        if bound.any():
            ax.plot(xs[bound], med[bound], "^", color="#D55E00", markersize=9, label="a bound (beyond the range)")
        ax.set_xlabel(_axis_label(axes[0]))
        ax.set_ylabel(UNITS[col])
        ax.legend(fontsize=8)
        return False
    y = np.asarray(data[f"grid_{axes[1]}"], dtype=float)
    ys = np.unique(y[sel])
    z = np.full((len(ys), len(xs)), np.nan)
    hatched = np.zeros_like(z, dtype=bool)
    for i, yv in enumerate(ys):
        for j, xv in enumerate(xs):
            z[i, j], side = _cell(vals, sides, sel & (x == xv) & (y == yv))
            hatched[i, j] = side != "="
    lo, hi = (float(np.nanmin(z)), float(np.nanmax(z))) if np.isfinite(z).any() else (0.0, 1.0)
    mid = 0.5 * (lo + hi)
    narrow = hi - lo < 0.01 * max(abs(mid), 1e-12)
    if narrow:
        lo, hi = mid - 0.005 * abs(mid) - 1e-12, mid + 0.005 * abs(mid) + 1e-12
    xe, ye = _edges(xs), _edges(ys)
    mesh = ax.pcolormesh(xe, ye, np.ma.masked_invalid(z), cmap="cividis", shading="flat", vmin=lo, vmax=hi)
    if hatched.any():
        ax.pcolor(xe, ye, np.ma.masked_where(~hatched, np.ones_like(z)), hatch="//", alpha=0.0, shading="flat")
    fig.colorbar(mesh, ax=ax, label=UNITS[col])
    ax.set_xlabel(_axis_label(axes[0]))
    ax.set_ylabel(_axis_label(axes[1]))
    return narrow


def _edges(v: np.ndarray) -> np.ndarray:
    if len(v) == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5]) if v[0] == 0 else np.array([v[0] * 0.95, v[0] * 1.05])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
