"""The chair on paper: a top view with its dimensions and a table of its parameters."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrow, Rectangle

from stability.chair.model import takes_chair
from stability.plotting.pages import table_axes
from stability.plotting.style import MARK, colour

__all__ = ["chair_geometry", "parameter_table"]

@takes_chair
def chair_geometry(chair, ax=None, *, title: str | None = None, overlay=None):
    """Top view of the chair: main wheels, caster pins and casters (trailing), c.g., dimensions.

    x (forward) points up the page, y (to the right) to the right.

    Parameters
    ----------
    chair : Chair
        The chair.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    overlay : Chair, optional
        A second chair drawn in dashed outline, c.g. on c.g. (the thesis's Figure 9-1 style).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(6, 7))
        ax = fig.subplots()
    c = chair
    xm, xp = c.x_main, c.x_pin
    r_main = 0.305   # 24 in wheel radius (m)
    r_cast = 0.10    # 8 in caster (m)
    # frame outline (seat) between axle and pins
    xs = sorted([xm, xp])
    ax.add_patch(Rectangle((-max(c.t1, c.t2) + 0.03, xs[0]), c.t1 + c.t2 - 0.06, xs[1] - xs[0],
                           fill=True, fc="0.93", ec="0.6", lw=0.8, zorder=0))
    for y, lab in ((-c.d1, "D"), (c.d2, "E")):
        ax.add_patch(Rectangle((y - 0.015, xm - r_main), 0.03, 2 * r_main, fc="0.35", ec="k", zorder=2))
        ax.plot([y, 0], [xm, xm], color="0.5", lw=0.8, ls="--", zorder=1)
        ax.text(y + (0.03 if y > 0 else -0.03), xm + r_main * 0.6, lab, ha="left" if y > 0 else "right",
                fontsize=8)
    for y, lab in ((-c.t1, "A"), (c.t2, "B")):
        xc = xp - c.trail
        ax.plot([y, y], [xp, xc], color="k", lw=1.5, zorder=3)
        ax.add_patch(Rectangle((y - 0.012, xc - r_cast), 0.024, 2 * r_cast, fc="0.55", ec="k", zorder=2))
        ax.plot([y], [xp], "o", ms=6, mfc="w", mec="k", zorder=4)
        ax.plot([y], [xc], ".", color=MARK, zorder=5)
        ax.text(y + (0.03 if y > 0 else -0.03), xp, lab, ha="left" if y > 0 else "right", va="center",
                fontsize=8)
    ax.plot([0], [0], marker="o", ms=10, mfc="w", mec="k", zorder=6)
    ax.plot([0], [0], marker="+", ms=10, color="k", zorder=7)
    ax.text(0.03, -0.03, "c.g.", fontsize=8, va="top")
    # dimensions
    off = max(c.d2, c.t2) + 0.12
    def dim(x0, x1, y, text):
        ax.annotate("", xy=(y, x1), xytext=(y, x0), arrowprops=dict(arrowstyle="<->", lw=0.8))
        ax.text(y + 0.015, 0.5 * (x0 + x1), text, fontsize=8, va="center")
    dim(0, xm, off, f"s1 = {c.s1:.3f} m")
    dim(0, xp, off, f"s2 = {c.s2:.3f} m")
    dim(xp, xp - c.trail, off + 0.2, f"l = {c.trail:.3f} m")
    ax.annotate("", xy=(-c.t1, xp + 0.06 * np.sign(xp - xm)), xytext=(c.t2, xp + 0.06 * np.sign(xp - xm)),
                arrowprops=dict(arrowstyle="<->", lw=0.8))
    ax.text(0, xp + 0.08 * np.sign(xp - xm), f"t1 + t2 = {c.t1 + c.t2:.3f} m", ha="center",
            va="bottom" if xp > xm else "top", fontsize=8)
    ax.text(0, xm + 0.04 * np.sign(xm - xp) - 0.0, f"d1 + d2 = {c.d1 + c.d2:.3f} m", ha="center",
            va="bottom" if xm > xp else "top", fontsize=8)
    # direction of travel
    top = max(xm + r_main, xp + r_cast) + 0.05
    xa = -off - 0.02
    ax.add_patch(FancyArrow(xa, top - 0.25, 0, 0.17, width=0.01, head_width=0.05, head_length=0.04,
                            color=colour(0)))
    ax.text(xa - 0.03, top - 0.17, "travel", color=colour(0), fontsize=8, rotation=90, ha="right", va="center")
    if overlay is not None:
        o = overlay
        col = colour(1)
        for y in (-o.d1, o.d2):
            ax.add_patch(Rectangle((y - 0.015, o.x_main - r_main), 0.03, 2 * r_main, fill=False, ec=col, ls="--",
                                   lw=1.2, zorder=8))
        for y in (-o.t1, o.t2):
            xc = o.x_pin - o.trail
            ax.plot([y, y], [o.x_pin, xc], color=col, lw=1.2, ls="--", zorder=8)
            ax.add_patch(Rectangle((y - 0.012, xc - r_cast), 0.024, 2 * r_cast, fill=False, ec=col, ls="--",
                                   lw=1.2, zorder=8))
            ax.plot([y], [o.x_pin], "o", ms=6, mfc="none", mec=col, zorder=8)
        ax.plot([], [], color="k", lw=1.5, label=chair.name)
        ax.plot([], [], color=col, lw=1.2, ls="--", label=f"{o.name} (dashed)")
        ax.legend(fontsize=8, loc="lower right")
    ax.set_aspect("equal")
    ax.set_xlim(xa - 0.12, off + 0.45)
    ax.set_ylim(min(xm - r_main, xp - c.trail - r_cast) - 0.08, top + 0.02)
    ax.set_xlabel("lateral position y (m, to the right)")
    ax.set_ylabel("longitudinal position x (m, forward)")
    ax.set_title(title or f"{chair.name}: top view ({chair.caster_position} casters)", fontsize=10)
    ax.grid(True, alpha=0.25)
    return ax


@takes_chair
def parameter_table(chair, ax=None, *, fontsize: float = 8.0):
    """The chair's parameters (name, symbol, value, unit, meaning) as a table in ``ax``.

    Parameters
    ----------
    chair : Chair
        The chair.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    fontsize : float
        Font size, points.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(6, 8))
        ax = fig.subplots()
    ax.axis("off")
    rows = []
    for f in fields(chair):
        v = getattr(chair, f.name)
        if v is None:
            vs = "tire's"
        elif isinstance(v, float):
            vs = f"{v:.6g}"
        else:
            vs = str(v)
        if vs == "tire's":
            vs = "from the tire data"
        sym = f.metadata.get("symbol", "")
        if sym.isupper() and len(sym) > 3:       # WCHAIR's Fortran names (TYMOD, ...): not a reader's symbol
            sym = ""
        rows.append([f.metadata.get("doc", f.name), sym, vs, f.metadata.get("unit", "")])
    table_axes(ax, ["parameter", "symbol", "value", "unit"], rows, col_widths=[0.55, 0.12, 0.2, 0.13],
               fontsize=fontsize, wrap=[60, 10, 20, 10], top=0.97, bottom=0.0)
    ax.set_title(f"{chair.name}: parameters", fontsize=10)
    return ax


