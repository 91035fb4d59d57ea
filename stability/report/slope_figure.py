"""The slope command's figure: the report's cross-slope section at one speed and slope, on one page.

``python -m stability.slope -o FILE`` draws it; its curves are :func:`stability.report.slope_data.slope_section`'s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from stability import plotting as P
from stability.report.slope_data import TREADMILL, layout_slope_section, slope_section
from stability.slope.plots import plot_holding

__all__ = ["slope_figure", "layout_slope_figure", "FIGURE_SLOPES"]


#: Cross slopes of the figure's curves (deg; the command's own slope is added).
FIGURE_SLOPES = (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)


def slope_figure(chair, cross_slope: float, speed: float):
    """The slope command's figure (``python -m stability.slope -o``): holding moment, drive difference and
    the uncorrected heading on one page.

    The curves come from :func:`stability.report.slope_data.slope_section` (the report's cross-slope page, at
    this speed, over :data:`FIGURE_SLOPES` and ``|cross_slope|``); the drawing from :mod:`stability.plotting`
    and :func:`stability.slope.plots.plot_holding`.

    Parameters
    ----------
    chair : Chair
    cross_slope : float
        Cross slope, deg (its magnitude: the side does not change the magnitudes).
    speed : float
        m/s.

    Returns
    -------
    matplotlib.figure.Figure
    """
    phi = abs(float(cross_slope))
    s = slope_section(chair, speed=speed, slopes=sorted(set(FIGURE_SLOPES) | {phi}), path_slope=phi)
    path = None
    if s.path is not None:
        path = _Path(s.path.t, s.path_heading_deg, s.path.turn, s.path.heading_change_deg, s.path.report_time,
                     f"uncorrected at {s.path_slope:g} deg: turns {s.path.turn}", s.path.quasi_steady_rate_deg_s)
    return _page(f"{chair.name} | exact model | cross slope {phi:g} deg at {speed:g} m/s", chair.name, phi,
                 f"{speed:g} m/s", s, path, "no uncorrected run: level ground or every slope refused")


@dataclass(frozen=True)
class _Path:
    """What the figure draws of an uncorrected path."""

    t: Any
    heading_deg: Any
    turn: str
    change_deg: float
    report_time: float
    title: str
    quasi_steady_deg_s: float | None = None


def _page(title: str, name: str, phi: float, speed_words: str, s: Any, path: _Path | None, no_path: str,
          side_words: str = "") -> Any:
    """The slope page: holding moment, drive difference, uncorrected heading and the caption (``s``: a
    :class:`~stability.report.slope_data.SlopeSection` or :class:`~stability.report.slope_data.LayoutSlopeSection`)."""
    fig, axes = P.page(title,
                       "steady straight running across a slope: what holds the line, and what happens without it",
                       nrows=1, ncols=3, size=(13.0, 5.6))
    plot_holding([s.curve], axes[0, 0], published=TREADMILL)
    axes[0, 0].set_title("holding yaw moment\n(band: Coulomb pin friction; grey: treadmill study)", fontsize=9)
    P.drive_difference(s.curve.cross_slopes_deg, s.drive_difference, s.drive_label, axes[0, 1], chair=name)
    axes[0, 1].set_title("drive difference that holds a straight line", fontsize=9)
    if side_words:
        for ax in axes[0, :2]:
            ax.set_xlabel(f"cross slope (deg, {side_words})")
    if path is not None:
        P.uncorrected_heading(path.t, path.heading_deg, axes[0, 2], title=path.title,
                              quasi_steady_deg_s=path.quasi_steady_deg_s)
    else:
        axes[0, 2].axis("off")
        axes[0, 2].text(0.0, 0.5, "\n".join(P.wrap_text(no_path, 50)), fontsize=9)
    k = [float(x) for x in s.curve.cross_slopes_deg].index(phi) if phi in s.curve.cross_slopes_deg else None
    what = "hand-rim force" if s.drive == "handrim" else "motor torque"
    unit = "N" if s.drive == "handrim" else "N m"
    words = [f"What to conclude: to run straight at {speed_words} on a {phi:g} deg cross slope"]
    if k is not None:
        words.append(f" the drive must supply {s.curve.holding_moment[k]:.3g} N m of yaw moment, a {what} difference "
                     f"of {s.drive_difference[k]:.3g} {unit} with the {s.harder_side[k]} wheel working harder")
    else:
        words.append(" the statics refuse this slope (" + "; ".join(r for p, r in s.refused if p == phi) + ")")
    if path is not None:
        words.append(f"; let go, the chair turns {path.turn} ({path.change_deg:+.1f} deg after "
                     f"{path.report_time:.2f} s, downhill +)")
    words.append(". Above the grey band the chair needs more holding than the manual chairs of the treadmill study.")
    lines = P.wrap_text("".join(words), 170)
    fig.text(0.5, 0.02, "\n".join(lines), ha="center", va="bottom", fontsize=8.5, fontweight="bold", color="0.1",
             linespacing=1.4)
    P.finish(fig, top=0.82, bottom=0.16 + 0.035 * (len(lines) - 1))
    return P.plain_text(fig)                          # a name from a user's file is never markup


def layout_slope_figure(layout: Any, cross_slope: float, speed: float, grade: float = 0.0, drive: str = "auto",
                        sim_time: float = 1.0) -> Any:
    """The slope command's figure for any wheel layout, forward or in reverse (``python -m stability.slope
    --chair mid-wheel-drive -o``): :func:`slope_figure`'s page from
    :func:`stability.report.slope_data.layout_slope_section` (the layout model's statics and simulator).

    Parameters
    ----------
    layout : Layout
    cross_slope : float
        Cross slope, deg (falling to the right +); the curves run over :data:`FIGURE_SLOPES` and ``|cross_slope|``
        on the same side.
    speed : float
        m/s (negative: reverse).
    grade : float
        deg (uphill +).
    drive : {"auto", "handrim", "motor"}
    sim_time : float
        Report time of the uncorrected run, s.

    Returns
    -------
    matplotlib.figure.Figure
    """
    phi = abs(float(cross_slope))
    side = -1.0 if cross_slope < 0 else 1.0
    s = layout_slope_section(layout, speed, sorted(set(FIGURE_SLOPES) | {phi}), phi, side, grade, drive, sim_time)
    path = None
    if s.path is not None:
        path = _Path(s.path.t_s, s.path.heading_change_history_deg, s.path.turn, s.path.heading_change_deg,
                     s.path.report_time_s, f"uncorrected at {s.path_slope:g} deg: turns {s.path.turn}\n(layout "
                     "simulator, wchair scheme, Coulomb pin friction)")
    direction = "backwards" if speed < 0 else "forwards"
    grade_words = f", grade {grade:g} deg" if grade else ""
    no_path = ("no uncorrected run: " + (s.path_error or "level ground or every slope refused"))
    return _page(f"{layout.name} | layout model | cross slope {phi:g} deg{grade_words} at {abs(speed):g} m/s "
                 f"{direction}", layout.name, phi, f"{abs(speed):g} m/s {direction}", s, path, no_path,
                 "falling to the left" if side < 0 else "falling to the right")
