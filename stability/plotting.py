"""Matplotlib figures of the toolkit: pure functions from data objects to Figures/Axes.

Every function takes data (a :class:`stability.rootlocus.SpeedLocus`, a
:class:`stability.study.StabilityMap`, a :class:`stability.chair.Chair`, ...)
and either draws on the ``ax`` it is given (and returns it) or makes a new
:class:`matplotlib.figure.Figure` (never through ``pyplot``, so nothing is
left open and no GUI backend is needed).  Nothing is computed here beyond
what drawing needs; every axis is labelled with its unit, every title names
the chair and the model.

Page helpers (:func:`page`, :func:`text_page`, :func:`table_page`) make the
A4-landscape pages of :mod:`stability.report`.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable, Sequence
from dataclasses import fields
from typing import Any

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure
from matplotlib.patches import FancyArrow, Rectangle

__all__ = [
    "PAGE_SIZE",
    "page",
    "panels_page",
    "text_page",
    "table_page",
    "chair_geometry",
    "parameter_table",
    "tire_curves",
    "cornering_stiffness_curves",
    "speed_locus",
    "speed_loci_figure",
    "eigenvalues_vs_speed",
    "parameter_locus",
    "parameter_loci_figure",
    "growth_rate_vs_parameter",
    "gain_locus",
    "yaw_rate_responses",
    "trajectories",
    "equal_instability_chart",
    "sweep_chart",
    "stability_map",
]

#: A4 landscape (inches).
PAGE_SIZE = (11.69, 8.27)
_MONO = {"family": "monospace"}


# ---------------------------------------------------------------------------
# pages
# ---------------------------------------------------------------------------
def page(title: str, subtitle: str = "", *, nrows: int = 1, ncols: int = 1, size=PAGE_SIZE, **subplot_kw):
    """A page with a title (and subtitle) and a grid of axes: ``(fig, axes)``.

    ``axes`` is a 2-D array (``squeeze=False``).  Leaves room at the top for
    the titles; call ``fig.tight_layout(rect=...)`` via :func:`finish`.
    """
    fig = Figure(figsize=size)
    fig.suptitle(title, fontsize=13 if len(title) <= 90 else max(9.0, 13 * 90 / len(title)), fontweight="bold",
                 y=0.985)
    if subtitle:
        fig.text(0.5, 0.948, "\n".join(textwrap.wrap(subtitle, 170)), ha="center", va="top", fontsize=8.5,
                 color="0.25", linespacing=1.3)
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw) if nrows * ncols else None
    return fig, axes


def finish(fig: Figure, top: float = 0.90, *, left: float = 0.065, right: float = 0.975, bottom: float = 0.08,
           wspace: float | None = None, hspace: float | None = None, tight: bool = False) -> Figure:
    """Lay the axes out below the page titles.

    Fixed margins by default (``tight_layout`` measures every tick label
    and costs more than drawing the page); ``tight=True`` uses it.
    """
    if tight:
        fig.tight_layout(rect=(0.0, 0.0, 1.0, top + 0.03))
        return fig
    axes = [a for a in fig.axes if a.get_subplotspec() is not None]
    nrows = ncols = 1
    if axes:
        gs = axes[0].get_subplotspec().get_gridspec()
        nrows, ncols = gs.get_geometry()
    fig.subplots_adjust(left=left, right=right, bottom=bottom, top=top,
                        wspace=0.32 if wspace is None else wspace,
                        hspace=(0.45 if nrows > 1 else 0.2) if hspace is None else hspace)
    return fig


def _wrap(text: str, width: int) -> list[str]:
    out: list[str] = []
    for para in str(text).split("\n"):
        if not para.strip():
            out.append("")
            continue
        indent = len(para) - len(para.lstrip())
        out.extend(textwrap.wrap(para, width=width, subsequent_indent=" " * (indent + 2 if para.lstrip().startswith(("-", "*")) else indent)) or [""])
    return out


def text_page(title: str, body: str | Sequence[str], subtitle: str = "", *, size=PAGE_SIZE,
              fontsize: float = 9.5, width: int = 120, monospace: bool = False) -> Figure:
    """A page of text (paragraphs wrapped to ``width`` characters)."""
    fig, _ = page(title, subtitle, nrows=0, ncols=0, size=size)
    if not isinstance(body, str):
        body = "\n".join(body)
    lines = _wrap(body, width)
    top, bottom = 0.90, 0.03
    step = min(0.0215 * fontsize / 9.5, (top - bottom) / max(len(lines), 1))
    fs = fontsize if step >= 0.0215 * fontsize / 9.5 * 0.999 else fontsize * step / (0.0215 * fontsize / 9.5)
    y = top
    for line in lines:
        fig.text(0.05, y, line, ha="left", va="top", fontsize=fs, **(_MONO if monospace else {}))
        y -= step
    return fig


def table_page(title: str, header: Sequence[str], rows: Sequence[Sequence[str]], subtitle: str = "", *,
               col_widths: Sequence[float] | None = None, notes: str = "", size=PAGE_SIZE,
               fontsize: float = 8.5, wrap: Sequence[int] | None = None) -> Figure:
    """A page holding one table (cells wrapped to ``wrap[i]`` characters per column) and notes below it."""
    fig, axes = page(title, subtitle, size=size)
    ax = axes[0, 0]
    ax.axis("off")
    table_axes(ax, header, rows, col_widths=col_widths, fontsize=fontsize, wrap=wrap)
    if notes:
        lines = _wrap(notes, 150)
        for i, line in enumerate(lines):
            fig.text(0.04, 0.02 + 0.018 * (len(lines) - 1 - i), line, fontsize=8, ha="left", va="bottom")
    return fig


def table_axes(ax, header, rows, *, col_widths=None, fontsize: float = 8.5, wrap=None, top: float = 1.0,
               bottom: float = 0.08):
    """Draw a table into ``ax`` (axes coordinates), wrapping long cells; returns ``ax``."""
    ncol = len(header)
    if col_widths is None:
        col_widths = [1.0 / ncol] * ncol
    tot = float(sum(col_widths))
    col_widths = [w / tot for w in col_widths]
    if wrap is None:
        wrap = [max(8, int(160 * w)) for w in col_widths]
    cells = [[_wrap(str(c), w) for c, w in zip(r, wrap)] for r in rows]
    heights = [max(len(c) for c in r) for r in cells]
    n_lines = sum(heights) + 1.6 + 0.35 * len(rows)
    line_h = min(0.045, (top - bottom) / max(n_lines, 1))
    fs = fontsize if line_h >= 0.028 else max(5.5, fontsize * line_h / 0.028)
    x0 = [sum(col_widths[:i]) for i in range(ncol)]
    y = top
    for i, h in enumerate(header):
        ax.text(x0[i] + 0.005, y, h, transform=ax.transAxes, fontsize=fs, fontweight="bold", va="top")
    y -= 1.3 * line_h
    ax.plot([0, 1], [y + 0.25 * line_h] * 2, transform=ax.transAxes, color="0.3", lw=0.8)
    for r, hgt in zip(cells, heights):
        for i, lines in enumerate(r):
            ax.text(x0[i] + 0.005, y, "\n".join(lines), transform=ax.transAxes, fontsize=fs, va="top",
                    linespacing=1.15)
        y -= (hgt * 1.0 + 0.35) * line_h
        ax.plot([0, 1], [y + 0.2 * line_h] * 2, transform=ax.transAxes, color="0.85", lw=0.5)
    return ax


# ---------------------------------------------------------------------------
# chair
# ---------------------------------------------------------------------------
def chair_geometry(chair, ax=None, *, title: str | None = None):
    """Top view of the chair: main wheels, caster pins and casters (trailing), c.g., dimensions.

    x (forward) points up the page, y (to the right) to the right.
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
        ax.plot([y], [xc], ".", color="C3", zorder=5)
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
                            color="C0"))
    ax.text(xa - 0.03, top - 0.17, "travel", color="C0", fontsize=8, rotation=90, ha="right", va="center")
    ax.set_aspect("equal")
    ax.set_xlim(xa - 0.12, off + 0.45)
    ax.set_ylim(min(xm - r_main, xp - c.trail - r_cast) - 0.08, top + 0.02)
    ax.set_xlabel("lateral position y (m, to the right)")
    ax.set_ylabel("longitudinal position x (m, forward)")
    ax.set_title(title or f"{chair.name}: top view ({chair.caster_position} casters)", fontsize=10)
    ax.grid(True, alpha=0.25)
    return ax


def parameter_table(chair, ax=None, *, fontsize: float = 7.5):
    """The chair's parameters (name, symbol, value, unit, meaning) as a table in ``ax``."""
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
        rows.append([f.name, f.metadata.get("symbol", ""), vs, f.metadata.get("unit", ""), f.metadata.get("doc", "")])
    table_axes(ax, ["field", "symbol", "value", "unit", "meaning"], rows, col_widths=[0.2, 0.1, 0.17, 0.1, 0.43],
               fontsize=fontsize, wrap=[24, 10, 18, 10, 44], top=0.97, bottom=0.0)
    ax.set_title(f"{chair.name}: parameters", fontsize=10)
    return ax


# ---------------------------------------------------------------------------
# tires (Figures 4-1, 4-2)
# ---------------------------------------------------------------------------
def tire_curves(tire_name: str, ax=None, *, loads=(75.0, 150.0, 225.0, 300.0, 375.0, 450.0), mark_load=None,
                role: str = ""):
    """Cornering force against slip angle at constant normal force (Figure 4-1 analogue).

    Curves are the tire model (:meth:`stability.tires.Tire.lateral_force`:
    the cubic fits of eq 4-1, linear between integer slip angles); markers at
    the integer slip angles where the fits are defined.  ``mark_load`` (N)
    adds a dashed curve at the chair's static load.
    """
    from . import tires

    if ax is None:
        fig = Figure(figsize=(6, 4.5))
        ax = fig.subplots()
    t = tires.get(tire_name)
    slip = np.linspace(0, 8, 161)
    ints = np.arange(0, 9)
    cmap = _cmap("viridis")
    for i, fz in enumerate(loads):
        col = cmap(i / max(len(loads) - 1, 1))
        f = -np.asarray(t.lateral_force(slip, np.full_like(slip, fz), warn=False))
        fi = -np.asarray(t.lateral_force(ints.astype(float), np.full(9, fz), warn=False))
        ax.plot(slip, f, color=col, lw=1.2, label=f"{fz:g} N")
        ax.plot(ints, fi, "o", color=col, ms=3)
    if mark_load is not None:
        f = -np.asarray(t.lateral_force(slip, np.full_like(slip, mark_load), warn=False))
        ax.plot(slip, f, "k--", lw=1.2, label=f"{mark_load:.0f} N (static load)")
    ax.set_xlabel("slip angle α (deg)")
    ax.set_ylabel("cornering force F_y (N)")
    ax.set_xlim(0, 8)
    ax.set_ylim(bottom=0)
    ax.set_title(f"{tire_name}{' (' + role + ')' if role else ''}: F_y vs slip at constant F_z (Fig. 4-1)",
                 fontsize=9)
    ax.legend(title="normal force F_z", fontsize=7, title_fontsize=7, loc="upper left", ncol=2)
    ax.grid(True, alpha=0.3)
    return ax


def cornering_stiffness_curves(ax=None, *, names=None, highlight: dict | None = None, table: bool = True):
    """Cornering stiffness against normal force for all tires (Figure 4-2 analogue).

    ``highlight`` maps a role (``"main"``, ``"caster"``) to ``(tire, load N)``:
    that tire's curve is drawn heavier and its static load marked.
    Markers: the published Table 4-1 values.
    """
    from . import tires

    if ax is None:
        fig = Figure(figsize=(6, 4.5))
        ax = fig.subplots()
    names = tuple(names or tires.names())
    fz = np.linspace(0, 450, 181)
    t41 = tires.table_4_1() if table else {}
    hl = {v[0]: (k, v[1]) for k, v in (highlight or {}).items()}
    for i, n in enumerate(names):
        t = tires.get(n)
        c = np.asarray(t.cornering_stiffness(fz))
        col = f"C{i % 10}"
        heavy = n in hl
        ax.plot(fz, c, color=col, lw=2.4 if heavy else 1.0, ls="-" if n in tires.MAIN_TIRES else "--",
                label=f"{n}{' (' + hl[n][0] + ')' if heavy else ''}")
        if n in t41:
            ax.plot(tires.TABLE_4_1_FZ_N, t41[n], "o", color=col, ms=3)
        if heavy:
            load = hl[n][1]
            cs = float(t.cornering_stiffness(load))
            ax.plot([load], [cs], marker="D", ms=7, mfc="w", mec=col, mew=2, zorder=5)
            ax.annotate(f"{cs:.1f} N/deg at {load:.0f} N", (load, cs), xytext=(6, -12),
                        textcoords="offset points", fontsize=7, color=col)
    ax.set_xlabel("normal force F_z (N)")
    ax.set_ylabel("cornering stiffness C_α (N/deg)")
    ax.set_xlim(0, 450)
    ax.set_ylim(bottom=0)
    ax.set_title("C_α vs F_z (Fig. 4-2; lines: fits, dots: Table 4-1)", fontsize=9)
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    ax.grid(True, alpha=0.3)
    return ax


# ---------------------------------------------------------------------------
# root loci
# ---------------------------------------------------------------------------
def _cmap(name):
    from matplotlib import colormaps

    return colormaps[name]


def _colored_branches(ax, eig: np.ndarray, values: np.ndarray, norm, cmap, lw=1.6):
    lc = None
    for j in range(eig.shape[1]):
        z = eig[:, j]
        pts = np.column_stack([z.real, z.imag])
        segs = np.stack([pts[:-1], pts[1:]], axis=1)
        lc = LineCollection(segs, cmap=cmap, norm=norm, linewidths=lw)
        lc.set_array(0.5 * (values[:-1] + values[1:]))
        ax.add_collection(lc)
    return lc


def _auto_limits(eig: np.ndarray, keep: float = 0.9, pad: float = 0.15):
    """Linear-axis limits holding the slow (dominant) part of a locus: fast caster branches may leave the box."""
    z = eig.reshape(-1)
    z = z[np.isfinite(z)]
    mag = np.abs(z)
    cut = np.quantile(mag, keep) if len(mag) else 1.0
    zz = z[mag <= cut]
    re_lo, re_hi = min(zz.real.min(), 0.0), max(zz.real.max(), 0.0)
    im = max(np.abs(zz.imag).max(), 1e-3)
    span = max(re_hi - re_lo, 1e-3)
    return (re_lo - pad * span, re_hi + pad * span), (-im * (1 + pad), im * (1 + pad))


def _symlog_limits(eig: np.ndarray, linthresh: float):
    z = eig.reshape(-1)
    z = z[np.isfinite(z)]
    lo = min(float(z.real.min()), -linthresh) if len(z) else -linthresh
    hi = max(float(z.real.max()), linthresh) if len(z) else linthresh
    im = max(float(np.abs(z.imag).max()) if len(z) else 0.0, linthresh)
    return (lo * 2.0, hi * 2.0), (-im * 2.0, im * 2.0)


def _axes_decor(ax, xlim, ylim, scale: str = "linear", linthresh: float = 1.0):
    if scale == "symlog":
        ax.set_xscale("symlog", linthresh=linthresh, linscale=0.6)
        ax.set_yscale("symlog", linthresh=linthresh, linscale=0.6)
    ax.axvline(0, color="k", lw=0.8)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.axvspan(0, max(xlim[1], 0), color="C3", alpha=0.06, lw=0)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    note = f", symlog: linear within ±{linthresh:g}" if scale == "symlog" else ""
    ax.set_xlabel(f"real part σ (1/s{note})", fontsize=8.5)
    ax.set_ylabel(f"imaginary part ω (rad/s{note})", fontsize=8.5)
    ax.tick_params(labelsize=7.5)
    ax.grid(True, alpha=0.3)


def _limits(eig, xlim, ylim, scale, keep, linthresh):
    auto = _symlog_limits(eig, linthresh) if scale == "symlog" else _auto_limits(eig, keep)
    return xlim or auto[0], ylim or auto[1]


def _label_points(ax, pts, labels, fontsize=6.5, min_px=14.0):
    """Annotate points, skipping any that would land within ``min_px`` pixels of one already labelled."""
    placed = []
    trans = ax.transData
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    for (x, y), lab in zip(pts, labels):
        if not (min(xlim) <= x <= max(xlim) and min(ylim) <= y <= max(ylim)):
            continue
        px = trans.transform((x, y))
        if any(np.hypot(*(px - q)) < min_px for q in placed):
            continue
        placed.append(px)
        ax.annotate(lab, (x, y), xytext=(2, 3), textcoords="offset points", fontsize=fontsize)


def speed_locus(locus, ax=None, *, marks=(0.1, 0.25, 0.5, 0.75, 1.0, 2.0, 5.0, 10.0), xlim=None, ylim=None,
                scale: str = "symlog", linthresh: float = 1.0, keep: float = 0.85, colorbar: bool = True,
                title: str | None = None):
    """Eigenvalues in the complex plane as speed varies (parametric root locus).

    Each tracked branch is drawn coloured by speed (log scale, colour bar);
    dots mark the speeds in ``marks`` on every branch (labelled where there
    is room); stars mark the critical speeds (crossings of the imaginary
    axis).  Both axes are symmetric-log by default (linear within
    ``±linthresh``): the caster modes lie two to three decades further from
    the origin than the yaw modes.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5.5))
        ax = fig.subplots()
    U, eig = locus.speeds, locus.eigenvalues
    xlim, ylim = _limits(eig, xlim, ylim, scale, keep, linthresh)
    norm = LogNorm(U[0], U[-1])
    lc = _colored_branches(ax, eig, U, norm, _cmap("plasma_r"))
    for c in locus.crossings:
        ax.plot([c.eigenvalue.real], [c.eigenvalue.imag], "*", ms=11, color="C3", mec="k", zorder=6,
                label=f"critical {c.speed:.3g} m/s ({c.kind}, {c.direction})")
        if abs(c.eigenvalue.imag) > 0:
            ax.plot([c.eigenvalue.real], [-c.eigenvalue.imag], "*", ms=11, color="C3", mec="k", zorder=6)
    ax.plot(eig[0].real, eig[0].imag, "x", color="k", ms=5, label=f"U = {U[0]:g} m/s (start)")
    _axes_decor(ax, xlim, ylim, scale, linthresh)
    pts, labs = [], []
    for s in marks:
        if not U[0] <= s <= U[-1]:
            continue
        k = int(np.argmin(np.abs(U - s)))
        ax.plot(eig[k].real, eig[k].imag, "o", ms=2.5, color="k", zorder=4)
        for z in eig[k]:
            if z.imag >= 0:
                pts.append((z.real, z.imag))
                labs.append(f"{s:g}")
    ax.plot([], [], "o", ms=2.5, color="k", label="speed marks (m/s)")
    _label_points(ax, pts, labs)
    if colorbar and lc is not None:
        cb = ax.figure.colorbar(lc, ax=ax, pad=0.01)
        cb.set_label("forward speed U (m/s)", fontsize=8)
        cb.ax.tick_params(labelsize=7)
    ax.legend(fontsize=6.5, loc="lower left")
    ax.set_title(title or f"{locus.chair.name}: {locus.model} model, {locus.casters} casters",
                 fontsize=9)
    return ax


def panels_page(items: Sequence, draw: Callable[[Any, Any], Any], title: str, subtitle: str = "",
                ncols: int = 2) -> Figure:
    """A page with one panel per item, ``ncols`` to a row: ``draw(item, ax)`` fills each, spare panels blank."""
    n = len(items)
    nrows = int(math.ceil(n / ncols))
    fig, axes = page(title, subtitle, nrows=nrows, ncols=ncols)
    for ax, item in zip(axes.flat, items):
        draw(item, ax)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    return finish(fig)


def speed_loci_figure(loci: Sequence, title: str, subtitle: str = "") -> Figure:
    """Several speed loci on one page (e.g. free/locked x exact/thesis)."""
    return panels_page(loci, speed_locus, title, subtitle, ncols=2 if len(loci) > 1 else 1)


def eigenvalues_vs_speed(locus, axes=None, *, title: str | None = None, log_speed: bool = True,
                         xlim=None):
    """Real and imaginary parts of the eigenvalues against speed, unstable regions shaded, critical speeds marked."""
    if axes is None:
        fig = Figure(figsize=(7, 6))
        axes = fig.subplots(2, 1)
    ax1, ax2 = axes
    U, eig = locus.speeds, locus.eigenvalues
    re_all = eig.real
    lim = max(float(np.abs(re_all).max()) * 2.0, 2.0)
    for j in range(eig.shape[1]):
        ax1.plot(U, eig[:, j].real, lw=1.2, color=f"C{j % 10}", label=f"branch {j + 1}")
        ax2.plot(U, np.abs(eig[:, j].imag), lw=1.2, color=f"C{j % 10}")
    for lo, hi in locus.unstable_intervals():
        for ax in (ax1, ax2):
            ax.axvspan(lo, hi, color="C3", alpha=0.12, lw=0)
    for c in locus.crossings:
        for ax in (ax1, ax2):
            ax.axvline(c.speed, color="C3", lw=1.0, ls="--")
        ax1.annotate(f"{c.speed:.3g} m/s", (c.speed, 0), xytext=(4, 6), textcoords="offset points",
                     fontsize=8, color="C3")
    ax1.axhline(0, color="k", lw=0.8)
    ax1.set_yscale("symlog", linthresh=1.0, linscale=0.6)
    ax1.set_ylim(-lim, max(float(re_all.max()) * 2.0, 2.0))
    ax1.set_ylabel("real part σ (1/s, symlog)", fontsize=8.5)
    ax2.set_ylabel("|imaginary part| ω (rad/s)", fontsize=8.5)
    ax1.set_xlabel("forward speed U (m/s)", fontsize=8.5)
    ax2.set_xlabel("forward speed U (m/s)", fontsize=8.5)
    ims = np.abs(eig.imag)
    ax2.set_ylim(0, max(float(ims.max()) * 1.15, 1.0))
    for ax in (ax1, ax2):
        if log_speed:
            ax.set_xscale("log")
        ax.set_xlim(*(xlim or (U[0], U[-1])))
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3, which="both")
    ax1.legend(fontsize=7, ncol=3, loc="lower left")
    ax1.set_title(title or f"{locus.chair.name}: {locus.model} model, {locus.casters} casters (shaded: unstable)",
                  fontsize=9)
    ax2.set_title("imaginary parts (oscillation frequencies)", fontsize=8)
    return axes


def parameter_locus(locus, ax=None, *, xlim=None, ylim=None, scale: str = "symlog", linthresh: float = 1.0,
                    keep: float = 0.85, colorbar: bool = True, title: str | None = None):
    """Root locus against a design parameter at fixed speed (branches coloured by the parameter).

    The chair's own value is marked with black squares; a categorical
    parameter (the main tire) is drawn as labelled points.
    """
    if ax is None:
        fig = Figure(figsize=(6, 5))
        ax = fig.subplots()
    v, eig = locus.values, locus.eigenvalues
    xlim, ylim = _limits(eig, xlim, ylim, scale, keep, linthresh)
    _axes_decor(ax, xlim, ylim, scale, linthresh)
    if locus.categorical:
        for i, lab in enumerate(locus.labels):
            ax.plot(eig[i].real, eig[i].imag, "o", ms=5, color=f"C{i % 10}", label=lab)
        ax.legend(fontsize=7, loc="lower left", title="main tire", title_fontsize=7)
    else:
        norm = Normalize(v.min(), v.max())
        lc = _colored_branches(ax, eig, v, norm, _cmap("viridis"))
        ax.plot(eig[0].real, eig[0].imag, "x", color="k", ms=4)
        if colorbar and lc is not None:
            cb = ax.figure.colorbar(lc, ax=ax, pad=0.01)
            cb.set_label(locus.axis_label(), fontsize=8)
            cb.ax.tick_params(labelsize=7)
        if np.isfinite(locus.nominal):
            k = int(np.argmin(np.abs(v - locus.nominal)))
            ax.plot(eig[k].real, eig[k].imag, "s", ms=5, mfc="none", mec="k", mew=1.2,
                    label=f"chair: {locus.nominal:.4g} (largest σ {locus.max_real[k]:.3g} 1/s)")
        ax.plot([], [], " ", label=f"largest σ {locus.max_real.min():.3g} .. {locus.max_real.max():.3g} 1/s")
        for b in locus.stability_boundaries():
            ax.plot([], [], " ", label=f"crosses σ = 0 at {b:.4g}")
        ax.legend(fontsize=6.5, loc="lower left")
    ax.set_title(title or f"vs {locus.label}", fontsize=9)
    return ax


def parameter_loci_figure(loci: Sequence, title: str, subtitle: str = "", ncols: int = 2) -> Figure:
    """Several parameter loci on one page."""
    return panels_page(loci, parameter_locus, title, subtitle, ncols)


def _growth_rate_panel(loc, ax) -> None:
    a = loc.max_real
    if loc.categorical:
        ax.bar(range(len(loc.labels)), a, color=[f"C{i % 10}" for i in range(len(loc.labels))])
        ax.set_xticks(range(len(loc.labels)), loc.labels, fontsize=8)
    else:
        ax.plot(loc.values, a, color="C0")
        if np.isfinite(loc.nominal):
            ax.axvline(loc.nominal, color="k", ls=":", lw=0.8, label="chair")
        for b in loc.stability_boundaries():
            ax.axvline(b, color="C3", ls="--", lw=0.8)
        ax.fill_between(loc.values, 0, np.maximum(a, 0), color="C3", alpha=0.15, lw=0)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel(loc.axis_label(), fontsize=8)
    ax.set_ylabel("largest real part (1/s)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, alpha=0.3)


def growth_rate_vs_parameter(loci: Sequence, title: str, subtitle: str = "", ncols: int = 4) -> Figure:
    """Largest real part (growth rate of the least stable mode) against each parameter."""
    return panels_page(loci, _growth_rate_panel, title, subtitle, ncols)


def gain_locus(locus, ax=None, *, xlim=None, ylim=None, scale: str = "symlog", linthresh: float = 1.0,
               keep: float = 0.9, title: str | None = None):
    """Classical root locus of yaw-rate feedback ``Mz = -K r`` (branches coloured by K, log scale)."""
    if ax is None:
        fig = Figure(figsize=(7, 5.5))
        ax = fig.subplots()
    K, L = locus.gains, locus.loci
    xlim, ylim = _limits(np.concatenate([L, locus.poles[None, :]], axis=0), xlim, ylim, scale, keep, linthresh)
    _axes_decor(ax, xlim, ylim, scale, linthresh)
    pos = K > 0
    norm = LogNorm(K[pos].min(), K.max())
    lc = _colored_branches(ax, L[pos], K[pos], norm, _cmap("cividis"))
    ax.plot(locus.poles.real, locus.poles.imag, "x", ms=8, mew=2, color="k", label="open-loop poles (K = 0)")
    if len(locus.zeros):
        ax.plot(locus.zeros.real, locus.zeros.imag, "o", ms=7, mfc="none", mec="k", mew=1.5,
                label="open-loop zeros")
    if locus.stabilising_gain is not None and locus.stabilising_gain > 0:
        from .rootlocus import closed_loop_matrices

        lam = np.linalg.eigvals(closed_loop_matrices(locus.chair, locus.speed, [locus.stabilising_gain],
                                                     model=locus.model, casters=locus.casters)[0])
        ax.plot(lam.real, lam.imag, "D", ms=5, color="C2", mec="k",
                label=f"K = {locus.stabilising_gain:.3g} N m s/rad (stable above)")
    pts, labs = [], []
    for kk in (1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0):
        if not K[pos].min() <= kk <= K.max():
            continue
        k = int(np.argmin(np.abs(np.log(K[pos]) - math.log(kk))))
        row = L[pos][k]
        ax.plot(row.real, row.imag, "o", ms=2.5, color="k", zorder=4)
        for z in row:
            if z.imag >= 0:
                pts.append((z.real, z.imag))
                labs.append(f"{kk:g}")
    ax.plot([], [], "o", ms=2.5, color="k", label="gain marks (N m s/rad)")
    _label_points(ax, pts, labs)
    cb = ax.figure.colorbar(lc, ax=ax, pad=0.01)
    cb.set_label("feedback gain K (N m s/rad)", fontsize=8)
    cb.ax.tick_params(labelsize=7)
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title(title or f"{locus.chair.name}: yaw-rate feedback Mz = -K r, {locus.model} model, "
                 f"{locus.casters} casters, U = {locus.speed:g} m/s", fontsize=9)
    return ax


# ---------------------------------------------------------------------------
# nonlinear studies
# ---------------------------------------------------------------------------
def _response_sign(rs) -> float:
    """+1 or -1: the sign that makes the first run's largest yaw rate positive."""
    for r in rs.responses:
        a = np.asarray(r.yaw_rate)
        if len(a) and np.any(a != 0):
            return float(np.sign(a[int(np.argmax(np.abs(a)))]))
    return 1.0


def yaw_rate_responses(rs, ax=None, *, reference_time: float | None = None, ylim=(-0.25, 2.0),
                       title: str | None = None, label_chair: bool = False, flip: bool | None = None):
    """Yaw rate against time for several runs (Figure 8-3a analogue), linear predictions dashed.

    A horizontal line marks the criterion's level and, if given, a vertical
    line the reference case's time to reach it.  Like the thesis's figures
    the curves rise: with ``flip=None`` the sign is chosen so that the first
    run's largest yaw rate is positive (the axis label says which sign is
    shown; yaw is positive clockwise seen from above).
    """
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    sgn = (_response_sign(rs) if flip is None else (-1.0 if flip else 1.0))
    for i, r in enumerate(rs.responses):
        col = f"C{i % 10}"
        lab = (f"{r.chair.name}, " if label_chair else "") + f"{r.speed:.3g} m/s"
        if math.isfinite(r.time_to_level):
            lab += f" ({r.time_to_level:.2f} s)"
        ax.plot(r.t, sgn * np.asarray(r.yaw_rate), color=col, lw=1.5, label=lab)
        if r.stopped_by_warnings:
            ax.plot([r.t[-1]], [sgn * r.yaw_rate[-1]], "x", color=col, ms=7)
        if r.linear is not None:
            ax.plot(r.linear["t"], sgn * np.asarray(r.linear["yaw_rate"]), color=col, lw=1.0, ls="--")
    ax.axhline(rs.criterion.yaw_rate, color="k", lw=0.8, ls=":")
    ax.axhline(-rs.criterion.yaw_rate, color="k", lw=0.8, ls=":")
    if reference_time is not None and math.isfinite(reference_time):
        ax.axvline(reference_time, color="k", lw=0.8, ls="-.", label=f"reference: {reference_time:.2f} s")
    if rs.linear_model:
        ax.plot([], [], color="0.3", ls="--", lw=1.0, label=f"linear ({rs.linear_model})")
    ax.set_ylim(*ylim)
    ax.set_xlim(0, rs.criterion.duration)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("yaw rate r (rad/s, clockwise positive)" if sgn > 0 else
                  "yaw rate -r (rad/s, counter-clockwise positive)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", ncol=2)
    f, d = rs.impulse
    ax.set_title(title or f"yaw-rate responses to {f:g} N for {d:g} s at the c.g. ({f * d:g} N s): "
                 f"{rs.model} model, {rs.scheme} scheme", fontsize=9)
    return ax


def trajectories(rs, ax=None, *, title: str | None = None, max_lateral: float | None = 1.5):
    """Paths of the c.g. after the disturbance (Figure 8-4 analogue), linear predictions dashed."""
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    for i, r in enumerate(rs.responses):
        col = f"C{i % 10}"
        ax.plot(r.x, r.y, color=col, lw=1.6, label=f"{r.chair.name} ({r.chair.caster_position} casters)")
        if r.linear is not None:
            ax.plot(r.linear["x"], r.linear["y"], color=col, lw=1.0, ls="--")
        # heading ticks every second
        for tt in np.arange(1.0, r.t[-1] + 1e-9, 1.0):
            k = int(np.argmin(np.abs(r.t - tt)))
            ax.plot(r.x[k], r.y[k], "o", color=col, ms=3)
    if rs.linear_model:
        ax.plot([], [], color="0.3", ls="--", lw=1.0, label=f"linear ({rs.linear_model})")
    ax.plot([], [], "o", color="0.3", ms=3, label="every 1 s")
    ax.set_xlabel("distance travelled X (m)")
    ax.set_ylabel("lateral displacement Y (m, to the right)")
    if max_lateral is not None:
        ylo, yhi = ax.get_ylim()
        ax.set_ylim(max(ylo, -max_lateral), min(yhi, max_lateral))
    ax.invert_yaxis()
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    sp = rs.responses[0].speed if rs.responses else float("nan")
    f, d = rs.impulse
    ax.set_title(title or f"paths after {f * d:g} N s at the c.g., {sp:g} m/s: {rs.model} model, {rs.scheme} scheme",
                 fontsize=9)
    return ax


def equal_instability_chart(results: Sequence, ax=None, *, thesis: dict | None = None, title: str | None = None):
    """Horizontal bars: equal-instability speed of several chairs (censored ones hatched), thesis values as markers.

    ``thesis`` maps a chair name to a (low, high) speed range of the thesis (m/s).
    """
    if ax is None:
        fig = Figure(figsize=(7, 4))
        ax = fig.subplots()
    names = [r.chair.name for r in results]
    vals = [r.value_or_bound for r in results]
    y = np.arange(len(results))[::-1]
    thesis = thesis or {}
    first = True
    for yi, r, v, n in zip(y, results, vals, names):
        ax.barh(yi, v, height=0.6, color="C0" if r.status == "found" else "0.8",
                hatch="" if r.status == "found" else "//", ec="k", lw=0.5)
        right = v
        if n in thesis:
            lo, hi = thesis[n]
            ax.plot([lo, hi], [yi + 0.38, yi + 0.38], color="C3", lw=3, solid_capstyle="butt")
            ax.plot([0.5 * (lo + hi)], [yi + 0.38], "v", color="C3", ms=6,
                    label="thesis (Figures 9-2, 9-3)" if first else None)
            first = False
            right = max(right, hi)
        ax.text(right + 0.03, yi, r.describe(), va="center", fontsize=8)
    if not first:
        ax.legend(fontsize=7, loc="lower right")
    ax.set_yticks(y, names, fontsize=8)
    ax.set_ylabel("chair")
    ax.set_xlabel("equal-instability speed (m/s)")
    ax.set_xlim(0, max(vals + [1.0]) * 1.25)
    ax.grid(True, axis="x", alpha=0.3)
    if results:
        r0 = results[0]
        ax.set_title(title or f"speed with the same instability as {r0.reference}: {r0.model} model, "
                     f"{r0.scheme} scheme", fontsize=9)
    return ax


def sweep_chart(table, axes=None, *, title: str | None = None):
    """The parametric study: equal-instability speed against each parameter (small multiples).

    ``table`` is a :class:`stability.study.SweepTable`.  Returns the axes array.
    """
    sweeps = table.ranked()
    n = len(sweeps)
    if axes is None:
        ncols = 4
        nrows = int(math.ceil(n / ncols))
        fig = Figure(figsize=PAGE_SIZE)
        axes = fig.subplots(nrows, ncols, squeeze=False)
    flat = list(np.asarray(axes).flat)
    allv = np.concatenate([sw.speeds for sw in sweeps] + [[table.nominal.value_or_bound]])
    ylo, yhi = float(allv.min()), float(allv.max())
    pad = max(0.08 * (yhi - ylo), 0.05)
    for ax, s in zip(flat, sweeps):
        sp = s.speeds
        cens = np.array([r.status != "found" for r in s.results])
        if s.labels is not None:
            x = np.arange(len(s.values))
            ax.bar(x, sp, color=["0.8" if c else "C0" for c in cens], ec="k", lw=0.5)
            ax.set_xticks(x, s.labels, fontsize=7)
            cur = table.chair.main_tire
            if cur in s.labels:
                ax.get_xticklabels()[s.labels.index(cur)].set_fontweight("bold")
        else:
            x = np.asarray(s.values)
            ax.plot(x, sp, "-o", ms=3.5, color="C0")
            if cens.any():
                ax.plot(x[cens], sp[cens], "o", ms=6, mfc="w", mec="C3", label="outside bracket")
                ax.legend(fontsize=6)
            if math.isfinite(s.nominal_value):
                ax.axvline(s.nominal_value, color="k", ls=":", lw=0.8)
        ax.axhline(table.nominal.value_or_bound, color="k", lw=0.6, ls="--")
        ax.set_ylim(max(0.0, ylo - pad) if s.labels is None else 0.0, yhi + pad)
        if cens.all():
            ax.text(0.5, 0.5, "all " + s.results[0].describe() if len({r.describe() for r in s.results}) == 1
                    else "all outside the bracket", transform=ax.transAxes, ha="center", va="center", fontsize=8,
                    bbox=dict(fc="w", ec="0.7"))
        ax.set_xlabel(f"{s.label} ({s.unit})" if s.labels is None else s.label, fontsize=7.5)
        ax.set_ylabel("equal-instability speed (m/s)", fontsize=7.5)
        ax.tick_params(labelsize=7)
        ax.set_title(f"{s.parameter}: spread {s.effect_percent:.0f} %{' (censored)' if s.censored else ''}",
                     fontsize=8)
        ax.grid(True, alpha=0.3)
    for ax in flat[n:]:
        ax.axis("off")
    return axes


def stability_map(smap, ax=None, *, title: str | None = None, nominal: float | None = None,
                  thesis_points: Sequence | None = None):
    """Contour plot of the time to the yaw-rate level over speed x (friction or disturbance size).

    The heavy contour is the reference case's time: left of it (slower)
    the chair is more stable than the reference, right of it less.  Runs
    that never reach the level are shown at the simulated duration.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    T = np.where(np.isfinite(smap.times), smap.times, smap.criterion.duration)
    T = np.minimum(T, smap.criterion.duration)
    X, Y = np.meshgrid(smap.speeds, smap.y_values)
    levels = np.linspace(0, smap.criterion.duration, 21)
    cs = ax.contourf(X, Y, T, levels=levels, cmap=_cmap("RdYlGn"))
    cb = ax.figure.colorbar(cs, ax=ax, pad=0.01)
    cb.set_label(f"time to |r| = {smap.criterion.yaw_rate:g} rad/s (s; {smap.criterion.duration:g} = never)")
    ref = smap.reference_time
    if T.min() < ref < T.max():
        c = ax.contour(X, Y, T, levels=[ref], colors="k", linewidths=2.0)
        ax.clabel(c, fmt={ref: f"reference {ref:.2f} s"}, fontsize=7)
    if nominal is not None:
        ax.axhline(nominal, color="k", ls=":", lw=0.8, label=f"chair: {nominal:g} {smap.y_unit}")
    if thesis_points:
        for i, (x, y, lab) in enumerate(thesis_points):
            ax.plot([x], [y], "D", ms=6, mfc="w", mec="k", label=lab if i == 0 else None)
    ax.plot(X.reshape(-1), Y.reshape(-1), ".", color="k", ms=1.2, alpha=0.5)
    ax.set_xlabel("forward speed U (m/s)")
    ax.set_ylabel(f"{smap.y_label} ({smap.y_unit})")
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(fontsize=7, loc="upper left")
    f, d = smap.impulse
    dist = f"{f * d:g} N s at the c.g." if smap.y_name != "impulse" else f"force held {d:g} s"
    ax.set_title(title or f"{smap.chair.name}: speed x {smap.y_name.replace('_', ' ')} ({dist}), "
                 f"{smap.model} model", fontsize=9)
    return ax
