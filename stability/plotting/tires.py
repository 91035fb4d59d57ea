"""Tire figures: cornering force against slip (Figure 4-1) and stiffness against load (Figure 4-2).

The curves are computed by :mod:`stability.report.tire_data` (from
:mod:`stability.tires`); these functions only draw them.
"""

from __future__ import annotations

from typing import Any

from matplotlib.axes import Axes
from matplotlib.figure import Figure

from stability.plotting.style import colormap, colour

__all__ = ["tire_curves", "cornering_stiffness_curves"]


def _axes(ax: Axes | None, size: tuple[float, float]) -> Axes:
    if ax is None:
        ax = Figure(figsize=size).subplots()
    return ax


def tire_curves(curves: Any, ax: Axes | None = None) -> Axes:
    """Cornering force against slip angle at constant normal force (Figure 4-1 analogue).

    Parameters
    ----------
    curves : stability.report.tire_data.ForceCurves
        ``tire``, ``role``, ``slip_deg`` (deg), ``loads`` (N), ``force``
        (N, one row per load), ``slip_points``/``force_points`` (the integer
        slip angles where the cubic fits of eq 4-1 are defined), and
        optionally ``mark_load`` (N) with ``mark_force`` (N): the chair's
        tire (with its lateral scale) at its static load, drawn dashed.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax, (6, 4.5))
    cmap = colormap("viridis")
    n = len(curves.loads)
    for i, fz in enumerate(curves.loads):
        col = cmap(i / max(n - 1, 1))
        ax.plot(curves.slip_deg, curves.force[i], color=col, lw=1.2, label=f"{fz:g} N")
        ax.plot(curves.slip_points, curves.force_points[i], "o", color=col, ms=3)
    if curves.mark_load is not None:
        scale = "" if curves.lateral_scale == 1.0 else f", lateral scale {curves.lateral_scale:g}"
        ax.plot(curves.slip_deg, curves.mark_force, "k--", lw=1.2,
                label=f"{curves.mark_load:.0f} N (static load{scale})")
    ax.set_xlabel("slip angle α (deg)")
    ax.set_ylabel("cornering force F_y (N)")
    ax.set_xlim(0, 8)
    ax.set_ylim(bottom=0)
    role = f" ({curves.role})" if curves.role else ""
    ax.set_title(f"{curves.tire}{role}: F_y vs slip at constant F_z (Fig. 4-1)", fontsize=9)
    ax.legend(title="normal force F_z", fontsize=7, title_fontsize=7, loc="upper left", ncol=2)
    ax.grid(True, alpha=0.3)
    return ax


def cornering_stiffness_curves(curves: Any, ax: Axes | None = None) -> Axes:
    """Cornering stiffness against normal force for all tires (Figure 4-2 analogue).

    Parameters
    ----------
    curves : stability.report.tire_data.StiffnessCurves
        ``names``, ``main_names`` (drawn solid; casters dashed), ``fz`` (N),
        ``stiffness`` (N/deg, one row per tire), ``table_fz`` and ``table``
        (the published Table 4-1 values, drawn as dots), and ``highlight``:
        tire name -> :class:`~stability.report.tire_data.StaticPoint` (role,
        static load N, stiffness N/deg WITH the chair's lateral scale, that
        scale); a highlighted tire is drawn heavier with its static point
        marked (and the scaled curve dotted when the scale is not 1).
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = _axes(ax, (6, 4.5))
    for i, n in enumerate(curves.names):
        col = colour(i)
        hp = curves.highlight.get(n)
        ax.plot(curves.fz, curves.stiffness[i], color=col, lw=2.4 if hp else 1.0,
                ls="-" if n in curves.main_names else "--", label=f"{n}{' (' + hp.role + ')' if hp else ''}")
        if n in curves.table:
            ax.plot(curves.table_fz, curves.table[n], "o", color=col, ms=3)
        if hp:
            if hp.lateral_scale != 1.0:
                ax.plot(curves.fz, hp.lateral_scale * curves.stiffness[i], color=col, lw=1.2, ls=":",
                        label=f"{n} x {hp.lateral_scale:g} (this chair's lateral scale)")
            ax.plot([hp.load], [hp.stiffness], marker="D", ms=7, mfc="w", mec=col, mew=2, zorder=5)
            ax.annotate(f"{hp.stiffness:.1f} N/deg at {hp.load:.0f} N", (hp.load, hp.stiffness), xytext=(6, -12),
                        textcoords="offset points", fontsize=7, color=col)
    ax.set_xlabel("normal force F_z (N)")
    ax.set_ylabel("cornering stiffness C_α (N/deg)")
    ax.set_xlim(0, 450)
    ax.set_ylim(bottom=0)
    ax.set_title("C_α vs F_z (Fig. 4-2; lines: fits, dots: Table 4-1)", fontsize=9)
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    ax.grid(True, alpha=0.3)
    return ax
