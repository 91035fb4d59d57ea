"""Root-locus figures: eigenvalues against speed, a design parameter, or a feedback gain.

The loci are computed by :mod:`stability.rootlocus`; these functions draw
them (branches coloured by the varied quantity, critical points marked).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import LogNorm, Normalize
from matplotlib.figure import Figure

from stability.plotting.pages import panels_page
from stability.plotting.style import UNSTABLE, colormap, colour

__all__ = ["speed_locus", "speed_loci_figure", "eigenvalues_vs_speed", "parameter_locus", "parameter_loci_figure",
           "growth_rate_vs_parameter", "gain_locus"]


def _colored_branches(ax, eig: np.ndarray, values: np.ndarray, norm, cmap, lw=1.6):
    lc = None
    for j in range(eig.shape[1]):
        z = eig[:, j]
        pts = np.column_stack([z.real, z.imag])
        segs = np.stack([pts[:-1], pts[1:]], axis=1)
        lc = LineCollection(list(segs), cmap=cmap, norm=norm, linewidths=lw)
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
    ax.axvspan(0, max(xlim[1], 0), color=UNSTABLE, alpha=0.06, lw=0)
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


def _label_points(ax, pts, labels, fontsize=7, min_px=14.0):
    """Annotate points, skipping any that would land within ``min_px`` pixels of one already labelled."""
    placed: list = []
    trans = ax.transData
    xlim, ylim = ax.get_xlim(), ax.get_ylim()
    pt = ax.figure.dpi / 72.0                      # display units per point
    for (x, y), lab in zip(pts, labels, strict=True):
        if not (min(xlim) <= x <= max(xlim) and min(ylim) <= y <= max(ylim)):
            continue
        px = trans.transform((x, y))
        # the label's box (about 0.62 em per character, 1.2 em high) at its 2/3-point offset, plus a margin
        x0, y0 = px[0] + 2 * pt, px[1] + 3 * pt
        box = (x0 - pt, y0 - pt, x0 + (0.62 * fontsize * len(lab) + 1) * pt, y0 + (1.2 * fontsize + 1) * pt)
        if any(np.hypot(*(px - q[:2])) < min_px or not (box[2] < q[2] or q[4] < box[0] or box[3] < q[3]
                                                          or q[5] < box[1]) for q in placed):
            continue
        placed.append((px[0], px[1], *box))
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

    Parameters
    ----------
    locus : stability.rootlocus.SpeedLocus or ParameterLocus
        The computed locus.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    marks : sequence of float
        Speeds marked (and labelled where there is room) on every branch, m/s.
    xlim : tuple of float, optional
        Real-axis limits, 1/s (automatic if omitted).
    ylim : tuple of float, optional
        Imaginary-axis (or y-axis) limits (automatic if omitted).
    scale : {"symlog", "linear"}
        Axis scale.
    linthresh : float
        Linear range of a symlog axis, 1/s.
    keep : float
        Quantile of the eigenvalue magnitudes kept in view on linear axes.
    colorbar : bool
        Draw a colour bar.
    title : str, optional
        Title (a default naming the chair and the model if omitted).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5.5))
        ax = fig.subplots()
    U, eig = locus.speeds, locus.eigenvalues
    xlim, ylim = _limits(eig, xlim, ylim, scale, keep, linthresh)
    norm = LogNorm(U[0], U[-1])
    lc = _colored_branches(ax, eig, U, norm, colormap("plasma_r", on_white=True))
    for c in locus.crossings:
        ax.plot([c.eigenvalue.real], [c.eigenvalue.imag], "*", ms=11, color=UNSTABLE, mec="k", zorder=6,
                label=f"critical {c.speed:.3g} m/s ({c.kind}, {c.direction})")
        if abs(c.eigenvalue.imag) > 0:
            ax.plot([c.eigenvalue.real], [-c.eigenvalue.imag], "*", ms=11, color=UNSTABLE, mec="k", zorder=6)
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
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title(title or f"{locus.chair.name}: {locus.model} model, {locus.casters} casters",
                 fontsize=9)
    return ax



def speed_loci_figure(loci: Sequence, title: str, subtitle: str = "") -> Figure:
    """Several speed loci on one page (e.g. free/locked x exact/thesis).

    Parameters
    ----------
    loci : sequence of loci
        One panel each.
    title : str
        Page title.
    subtitle : str
        Line(s) under the title.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    return panels_page(loci, speed_locus, title, subtitle, ncols=2 if len(loci) > 1 else 1)


def eigenvalues_vs_speed(locus, axes=None, *, mode_names=None, title: str | None = None, log_speed: bool = True,
                         xlim=None):
    """Real and imaginary parts of the eigenvalues against speed, unstable regions shaded, critical speeds marked.

    The real parts are on a linear axis that holds the slow modes (down to
    three times the largest growth rate, at least 10 1/s): branches that stay
    below it at every speed are listed in the legend as off scale.

    Parameters
    ----------
    locus : stability.rootlocus.SpeedLocus
    axes : pair of matplotlib.axes.Axes, optional
        Axes for the real and the imaginary parts (a new figure if omitted); the second may be None (no
        frequency panel, e.g. when every mode is non-oscillatory).
    mode_names : sequence of str, optional
        A name per branch (column of ``locus.eigenvalues``), e.g. from
        :func:`stability.linear.names.mode_names`; branches with the same
        name share one legend entry.  Default "branch 1", "branch 2", ...
    title : str, optional
    log_speed : bool
        Logarithmic speed axis.
    xlim : tuple of float, optional
        Speed range, m/s.

    Returns
    -------
    pair of matplotlib.axes.Axes
    """
    if axes is None:
        fig = Figure(figsize=(7, 6))
        axes = fig.subplots(2, 1)
    ax1, ax2 = axes
    U, eig = locus.speeds, locus.eigenvalues
    names = list(mode_names) if mode_names is not None else [f"branch {j + 1}" for j in range(eig.shape[1])]
    hi = max(1.15 * float(eig.real.max()), 0.5)
    lo = -max(3.0 * hi, 10.0)
    seen: dict[str, int] = {}
    off: list[str] = []
    labelled: set[str] = set()
    for j in range(eig.shape[1]):
        k = seen.setdefault(names[j], len(seen))
        below = bool(np.all(eig[:, j].real < lo))
        if below and names[j] not in off:
            off.append(names[j])
        label = None if (below or names[j] in labelled) else names[j]
        if label:
            labelled.add(label)
        ax1.plot(U, eig[:, j].real, lw=1.4, color=colour(k), label=label)
        if ax2 is not None:
            ax2.plot(U, np.abs(eig[:, j].imag), lw=1.4, color=colour(k))
    both = [ax for ax in (ax1, ax2) if ax is not None]
    for lo_u, hi_u in locus.unstable_intervals():
        for ax in both:
            ax.axvspan(lo_u, hi_u, color=UNSTABLE, alpha=0.12, lw=0)
    for c in locus.crossings:
        for ax in both:
            ax.axvline(c.speed, color=UNSTABLE, lw=1.0, ls="--")
        # near the right edge the label goes to the left of its line, so it stays on the page
        x0, x1 = xlim or (U[0], U[-1])
        f = np.log if log_speed else (lambda v: v)
        right = (f(c.speed) - f(x0)) / (f(x1) - f(x0)) > 0.8
        ax1.annotate(f"{c.speed:.3g} m/s", (c.speed, 0), xytext=(-4 if right else 4, 6), textcoords="offset points",
                     fontsize=8, color=UNSTABLE, ha="right" if right else "left")
    if off:
        ax1.plot([], [], " ", label=f"below {lo:.3g} 1/s at every speed (off scale): " + ", ".join(off))
    ax1.axhline(0, color="k", lw=0.8)
    ax1.set_ylim(lo, hi)
    ax1.set_ylabel("real part σ (1/s)", fontsize=8.5)
    ax1.set_xlabel("forward speed U (m/s)", fontsize=8.5)
    if ax2 is not None:
        ax2.set_ylabel("|imaginary part| ω (rad/s)", fontsize=8.5)
        ax2.set_xlabel("forward speed U (m/s)", fontsize=8.5)
        ax2.set_ylim(0, max(float(np.abs(eig.imag).max()) * 1.15, 1.0))
        ax2.set_title("imaginary parts (oscillation frequencies)", fontsize=8)
    for ax in both:
        if log_speed:
            ax.set_xscale("log")
        ax.set_xlim(*(xlim or (U[0], U[-1])))
        ax.grid(True, alpha=0.3, which="both")
    ax1.legend(fontsize=7, ncol=2, loc="lower left")
    ax1.set_title(title or f"{locus.chair.name}: {locus.model} model, {locus.casters} casters (shaded: unstable)",
                  fontsize=9)
    return axes


def parameter_locus(locus, ax=None, *, xlim=None, ylim=None, scale: str = "symlog", linthresh: float = 1.0,
                    keep: float = 0.85, colorbar: bool = True, title: str | None = None):
    """Root locus against a design parameter at fixed speed (branches coloured by the parameter).

    The chair's own value is marked with black squares; a categorical
    parameter (the main tire) is drawn as labelled points.

    Parameters
    ----------
    locus : stability.rootlocus.SpeedLocus or ParameterLocus
        The computed locus.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    xlim : tuple of float, optional
        Real-axis limits, 1/s (automatic if omitted).
    ylim : tuple of float, optional
        Imaginary-axis (or y-axis) limits (automatic if omitted).
    scale : {"symlog", "linear"}
        Axis scale.
    linthresh : float
        Linear range of a symlog axis, 1/s.
    keep : float
        Quantile of the eigenvalue magnitudes kept in view on linear axes.
    colorbar : bool
        Draw a colour bar.
    title : str, optional
        Title (a default naming the chair and the model if omitted).

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(6, 5))
        ax = fig.subplots()
    v, eig = locus.values, locus.eigenvalues
    xlim, ylim = _limits(eig, xlim, ylim, scale, keep, linthresh)
    _axes_decor(ax, xlim, ylim, scale, linthresh)
    if locus.categorical:
        for i, lab in enumerate(locus.labels):
            ax.plot(eig[i].real, eig[i].imag, "o", ms=5, color=colour(i), label=lab)
        ax.legend(fontsize=7, loc="lower left", title="main tire", title_fontsize=7)
    else:
        norm = Normalize(v.min(), v.max())
        lc = _colored_branches(ax, eig, v, norm, colormap("viridis", on_white=True))
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
        ax.legend(fontsize=7, loc="lower left")
    ax.set_title(title or f"vs {locus.label}", fontsize=9)
    return ax


def parameter_loci_figure(loci: Sequence, title: str, subtitle: str = "", ncols: int = 2) -> Figure:
    """Several parameter loci on one page.

    Parameters
    ----------
    loci : sequence of loci
        One panel each.
    title : str
        Page title.
    subtitle : str
        Line(s) under the title.
    ncols : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    return panels_page(loci, parameter_locus, title, subtitle, ncols)


def _growth_rate_panel(loc, ax) -> None:
    a = loc.max_real
    if loc.categorical:
        ax.bar(range(len(loc.labels)), a, color=[colour(i) for i in range(len(loc.labels))])
        ax.set_xticks(range(len(loc.labels)), loc.labels, fontsize=8)
    else:
        ax.plot(loc.values, a, color=colour(0))
        ax.set_title(f"{loc.label}: {a.min():.3g} to {a.max():.3g} 1/s", fontsize=8)
        if np.isfinite(loc.nominal):
            ax.axvline(loc.nominal, color="k", ls=":", lw=0.8, label="chair")
        for b in loc.stability_boundaries():
            ax.axvline(b, color=UNSTABLE, ls="--", lw=0.8)
        ax.fill_between(loc.values, 0, np.maximum(a, 0), color=UNSTABLE, alpha=0.15, lw=0)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel(loc.axis_label(), fontsize=8)
    ax.set_ylabel("largest real part (1/s)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, alpha=0.3)


def growth_rate_vs_parameter(loci: Sequence, title: str, subtitle: str = "", ncols: int = 4) -> Figure:
    """Largest real part (growth rate of the least stable mode) against each parameter.

    Parameters
    ----------
    loci : sequence of loci
        One panel each.
    title : str
        Page title.
    subtitle : str
        Line(s) under the title.
    ncols : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    return panels_page(loci, _growth_rate_panel, title, subtitle, ncols)


def gain_locus(locus, ax=None, *, stabilising_poles=None, xlim=None, ylim=None, scale: str = "symlog",
               linthresh: float = 1.0, keep: float = 0.9, title: str | None = None):
    """Classical root locus of yaw-rate feedback ``Mz = -K r`` (branches coloured by K, log scale).

    Parameters
    ----------
    locus : stability.rootlocus.GainLocus
        Gains (N m s/rad), closed-loop eigenvalues per gain, open-loop poles and zeros.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    stabilising_poles : array of complex, optional
        Closed-loop eigenvalues (1/s) at ``locus.stabilising_gain``, marked
        with diamonds (computed by the caller, e.g.
        :func:`stability.report.compute.stabilising_poles`).
    xlim, ylim : tuple of float, optional
        Axis limits (1/s, rad/s); automatic if omitted.
    scale : {"symlog", "linear"}
        Axis scale.
    linthresh : float
        Linear range of a symlog axis, 1/s.
    keep : float
        Quantile of eigenvalue magnitudes kept in view on linear axes.
    title : str, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        fig = Figure(figsize=(7, 5.5))
        ax = fig.subplots()
    K, L = locus.gains, locus.loci
    xlim, ylim = _limits(np.concatenate([L, locus.poles[None, :]], axis=0), xlim, ylim, scale, keep, linthresh)
    _axes_decor(ax, xlim, ylim, scale, linthresh)
    pos = K > 0
    norm = LogNorm(K[pos].min(), K.max())
    lc = _colored_branches(ax, L[pos], K[pos], norm, colormap("cividis", on_white=True))
    ax.plot(locus.poles.real, locus.poles.imag, "x", ms=8, mew=2, color="k", label="open-loop poles (K = 0)")
    if len(locus.zeros):
        ax.plot(locus.zeros.real, locus.zeros.imag, "o", ms=7, mfc="none", mec="k", mew=1.5,
                label="open-loop zeros")
    if stabilising_poles is not None and locus.stabilising_gain is not None and locus.stabilising_gain > 0:
        lam = np.asarray(stabilising_poles)
        ax.plot(lam.real, lam.imag, "D", ms=5, color=colour(2), mec="k",
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


