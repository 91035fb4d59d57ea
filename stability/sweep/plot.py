"""Figures of a sweep: each measure over the first two grid axes (median over the draws), one panel per speed."""

from __future__ import annotations

from typing import Any

import numpy as np

from stability.sweep.spec import MEASURES, SweepSpec

__all__ = ["UNITS", "measure_figures"]

#: Axis and colour-bar labels of the measure columns.
UNITS = {"growth_rate_1_s": "growth rate (1/s)", "critical_speed_m_s": "first critical speed (m/s)",
         "locked_critical_speed_m_s": "locked-caster critical speed (m/s)",
         "critical_impulse_Ns": "critical impulse (N s)",
         "equal_instability_speed_m_s": "equal-instability speed (m/s)",
         "shimmy_margin_m": "shimmy margin of the trail (m)", "static_stability_deg": "static stability (deg)",
         "tip_toward_casters_deg": "tip angle toward the casters (deg)",
         "tip_toward_main_wheels_deg": "tip angle toward the main wheels (deg)",
         "tip_lateral_deg": "lateral tip angle (deg)", "holding_moment_N_m_per_deg": "holding moment (N m/deg)"}
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
            "holding_moment_N_m_per_deg": "lower is better: the yaw moment that holds a line across a cross slope"}
_GRID_UNITS = {"pin_friction": "N m", "trail": "m", "s1": "m", "s2": "m", "l1": "m", "h": "m", "m": "kg",
               "i_z": "kg m^2", "d1": "m", "d2": "m", "t1": "m", "t2": "m", "pin_friction_left": "N m",
               "pin_friction_right": "N m", "toe_deg": "deg", "camber_deg": "deg", "m_c": "kg", "i_zp": "kg m^2"}


def _axis_label(axis: str) -> str:
    unit = _GRID_UNITS.get(axis, "-")
    return f"{axis} ({unit})"


def measure_figures(spec: SweepSpec, data: dict[str, list]) -> list[Any]:
    """One figure per measure column: the median over the draws against the first two grid axes.

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
            fig = Figure(figsize=(4.0 * len(spec.speeds) + 1.0, 4.2), layout="constrained")
            panels = fig.subplots(1, len(spec.speeds), squeeze=False)[0]
            for ax, s in zip(panels, spec.speeds, strict=True):
                _panel(ax, fig, spec, data, vals, speed == s, axes, col)
                ax.set_title(f"{s:g} m/s")
            fig.suptitle(f"{UNITS[col]}: {spec.chair.name}, {spec.model} model, median of {spec.draws} draw(s)")
            fig.text(0.01, 0.005, _CAPTION[col] + "; blank: no value (invalid chair or not found)", fontsize=8)
            figs.append(fig)
    return figs


def _panel(ax, fig, spec: SweepSpec, data: dict[str, list], vals: np.ndarray, sel: np.ndarray, axes: list[str],
           col: str) -> None:
    if not axes:
        ax.bar([0], [np.nanmedian(vals[sel]) if np.isfinite(vals[sel]).any() else np.nan], color="#0072B2")
        ax.set_xticks([0], [spec.chair.name])
        ax.set_ylabel(UNITS[col])
        return
    x = np.asarray(data[f"grid_{axes[0]}"], dtype=float)
    xs = np.unique(x[sel])
    if len(axes) == 1:
        med = [np.nanmedian(vals[sel & (x == v)]) if np.isfinite(vals[sel & (x == v)]).any() else np.nan for v in xs]
        ax.plot(xs, med, "o-", color="#0072B2", label="median over draws")
        ax.set_xlabel(_axis_label(axes[0]))
        ax.set_ylabel(UNITS[col])
        ax.legend(fontsize=8)
        return
    y = np.asarray(data[f"grid_{axes[1]}"], dtype=float)
    ys = np.unique(y[sel])
    z = np.full((len(ys), len(xs)), np.nan)
    for i, yv in enumerate(ys):
        for j, xv in enumerate(xs):
            v = vals[sel & (x == xv) & (y == yv)]
            if np.isfinite(v).any():
                z[i, j] = np.nanmedian(v)
    mesh = ax.pcolormesh(_edges(xs), _edges(ys), np.ma.masked_invalid(z), cmap="cividis", shading="flat")
    fig.colorbar(mesh, ax=ax, label=UNITS[col])
    ax.set_xlabel(_axis_label(axes[0]))
    ax.set_ylabel(_axis_label(axes[1]))


def _edges(v: np.ndarray) -> np.ndarray:
    if len(v) == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5]) if v[0] == 0 else np.array([v[0] * 0.95, v[0] * 1.05])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - (mid[0] - v[0])], mid, [v[-1] + (v[-1] - mid[-1])]])
