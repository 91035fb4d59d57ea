"""The appendix's linear-analysis page: the critical speeds, the least stable mode and the speed root loci."""

from __future__ import annotations

from matplotlib.figure import Figure

from stability import plotting as P
from stability.report.compute import ReportData
from stability.report.findings import _first
from stability.report.panels import stable_everywhere
from stability.report.sections import footer as _footer
from stability.study.summary_text import format_summary

__all__ = ["linear_page"]


def _linear_text(d: ReportData) -> str:
    c = d.chair
    txt = format_summary(d.summary)
    so = d.summary_other
    txt += ("\n\nOther model variant (" + so.model + "): free casters "
            + ("unstable at all speeds searched" if so.free_unstable_at_all_speeds else
               "stable at all speeds searched" if so.free_stable_at_all_speeds else
               "critical speeds " + ", ".join(f"{x.speed:.4g} m/s ({x.direction})" for x in so.free_crossings))
            + "; locked casters critical speed "
            + (f"{_first(so.locked_crossings):.4g} m/s" if _first(so.locked_crossings) is not None else "none in range")
            + ".\n\nLinear models: straight-line motion, tire forces linear in slip with the cornering stiffness "
              "at the static load (Table 4-1 method), viscous pin damping "
              f"{c.pin_damping:g} N m s/rad; Coulomb pin friction has no linearisation (it appears only in the "
              "nonlinear simulations of the later pages).")
    return txt


def linear_page(d: ReportData, title: str, subtitle: str) -> Figure:
    """The linear analysis in one appendix page: the critical speeds and the least stable mode (text, top) and
    the eigenvalues as speed varies, free and locked casters (parametric root loci, bottom); a caster setting
    stable at every speed of its locus has no critical speed, so its panel is one line
    (:func:`~stability.report.panels.stable_everywhere`).

    Parameters
    ----------
    d : ReportData
    title, subtitle : str
        The page's title and subtitle.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = P.page(title, subtitle, nrows=1, ncols=2)
    fs = 7.5
    y, step = 0.905, 0.0215 * fs / 9.5
    for line in P.wrap_text(_linear_text(d), 150):
        fig.text(0.05, y, line, ha="left", va="top", fontsize=fs, fontfamily="monospace")
        y -= step
    drawn = 0
    for ax, cs in zip(axes[0], ("free", "locked"), strict=True):
        locus = d.speed_loci[(d.model, cs)]
        if stable_everywhere(locus):       # no critical speed: the locus has nothing to locate, one line instead
            ax.axis("off")
            ax.text(0.5, 0.6, f"{cs.capitalize()} casters: every eigenvalue has a negative real part at every speed"
                    f"\nsearched ({locus.speeds[0]:g}-{locus.speeds[-1]:g} m/s), so there is no critical speed\nand no "
                    "locus to draw.", ha="center", va="center", fontsize=8.5, transform=ax.transAxes)
            continue
        P.speed_locus(locus, ax, scale="linear", keep=0.6, marks=(0.25, 0.75, 2.0, 5.0, 10.0))
        drawn += 1
    if not drawn:
        return P.finish(fig, top=y - 0.05)
    bottom = _footer(fig, "Root loci: linear axes around the slow modes, which decide directional stability; the fast "
                     "caster modes (large negative real parts) leave the frame. The other model variant is compared "
                     "in the method appendix.")
    return P.finish(fig, top=y - 0.05, bottom=bottom)
