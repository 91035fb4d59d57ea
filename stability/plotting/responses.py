"""Nonlinear time histories: yaw-rate responses and paths after a push (Figures 8-3a, 8-4), one simulated run."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.figure import Figure

from stability.plotting.style import colour
from stability.runtime.files import save_figure

if TYPE_CHECKING:
    from stability.simulate.layout import LayoutRun
    from stability.simulate.results import SimulationResult

__all__ = ["yaw_rate_responses", "trajectories", "plot_result", "plot_layout_run", "layout_run_caption"]

def _response_sign(rs) -> float:
    """+1 or -1: the sign that makes the first run's largest yaw rate positive."""
    for r in rs.responses:
        a = np.asarray(r.yaw_rate)
        if len(a) and np.any(a != 0):
            return float(np.sign(a[int(np.argmax(np.abs(a)))]))
    return 1.0


def _cut(t: np.ndarray, v: Any) -> int:
    """Number of samples within the valid part (all when ``v`` is None or valid throughout)."""
    if v is None or v.until is None:
        return len(t)
    return int(np.searchsorted(t, v.until, side="right"))


def yaw_rate_responses(rs, ax=None, *, reference_time: float | None = None, ylim=(-0.25, 2.0),
                       title: str | None = None, label_chair: bool = False, flip: bool | None = None,
                       validity: Sequence | None = None):
    """Yaw rate against time for several runs (Figure 8-3a analogue), linear predictions dashed.

    A horizontal line marks the criterion's level and, if given, a vertical
    line the reference case's time to reach it.  Like the thesis's figures
    the curves rise: with ``flip=None`` the sign is chosen so that the first
    run's largest yaw rate is positive (the axis label says which sign is
    shown; yaw is positive clockwise seen from above).

    ``validity`` (one :class:`stability.report.validity.Validity` per run)
    ends each curve where the run leaves the model's range (a bar marks the
    end; the legend says why); nothing is drawn after it.

    Parameters
    ----------
    rs : stability.study.ResponseSet
        The runs.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    reference_time : float, optional
        The reference case's time to the level (s), drawn as a vertical line.
    ylim : tuple of float, optional
        Imaginary-axis (or y-axis) limits (automatic if omitted).
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    label_chair : bool
        Put the chair's name in each legend entry.
    flip : bool, optional
        Draw -r instead of r (None: chosen so that the first run rises).
    validity : sequence of Validity, optional
        One per run (:mod:`stability.report.validity`); curves end there.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    sgn = (_response_sign(rs) if flip is None else (-1.0 if flip else 1.0))
    cut_any = False
    for i, r in enumerate(rs.responses):
        col = colour(i)
        v = validity[i] if validity is not None else None
        n = _cut(np.asarray(r.t), v)
        lab = (f"{r.chair.name}, " if label_chair else "") + f"{r.speed:.3g} m/s"
        if math.isfinite(r.time_to_level):
            lab += f" ({r.time_to_level:.2f} s)" if v is None or v.covers(r.time_to_level) else \
                f" (level at {r.time_to_level:.2f} s, beyond validity)"
        if v is not None and v.until is not None:
            lab += f"; ends {v.until:.2f} s: {v.reason}"
        ax.plot(r.t[:n], sgn * np.asarray(r.yaw_rate)[:n], color=col, lw=1.5, label=lab)
        if n < len(r.t) and n > 0:
            cut_any = True
            ax.plot([r.t[n - 1]], [sgn * r.yaw_rate[n - 1]], "|", color=col, ms=12, mew=2)
        if r.stopped_by_warnings:
            ax.plot([r.t[-1]], [sgn * r.yaw_rate[-1]], "x", color=col, ms=7)
        if r.linear is not None:
            ax.plot(r.linear.t, sgn * np.asarray(r.linear.yaw_rate), color=col, lw=1.0, ls="--")
    ax.axhline(rs.criterion.yaw_rate, color="k", lw=0.8, ls=":")
    ax.axhline(-rs.criterion.yaw_rate, color="k", lw=0.8, ls=":")
    if reference_time is not None and math.isfinite(reference_time):
        ax.axvline(reference_time, color="k", lw=0.8, ls="-.", label=f"reference: {reference_time:.2f} s")
    if rs.linear_model:
        ax.plot([], [], color="0.3", ls="--", lw=1.0, label=f"linear ({rs.linear_model})")
    if cut_any:
        ax.plot([], [], "|", color="0.3", ms=10, mew=2, label="end of validity (nothing drawn after)")
    ax.set_ylim(*ylim)
    ax.set_xlim(0, rs.criterion.duration)
    ax.set_xlabel("time t (s)")
    ax.set_ylabel("yaw rate r (rad/s, clockwise positive)" if sgn > 0 else
                  "yaw rate -r (rad/s, counter-clockwise positive)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", ncol=1)
    f, d = rs.impulse
    ax.set_title(title or f"yaw-rate responses to {f:g} N for {d:g} s at the c.g.: "
                 f"{rs.model} model, {rs.scheme} scheme", fontsize=9)
    return ax


def trajectories(rs, ax=None, *, title: str | None = None, max_lateral: float | None = 1.5,
                 validity: Sequence | None = None):
    """Paths of the c.g. after the disturbance (Figure 8-4 analogue), linear predictions dashed.

    ``validity`` (one per run) ends each path where the run leaves the
    model's range, as in :func:`yaw_rate_responses`.

    Parameters
    ----------
    rs : stability.study.ResponseSet
        The runs.
    ax : matplotlib.axes.Axes, optional
        Where to draw (a new figure if omitted).
    title : str, optional
        Title (a default naming the chair and the model if omitted).
    max_lateral : float, optional
        Clip the lateral axis to +-this, m.
    validity : sequence of Validity, optional
        One per run (:mod:`stability.report.validity`); curves end there.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    if ax is None:
        fig = Figure(figsize=(7, 5))
        ax = fig.subplots()
    for i, r in enumerate(rs.responses):
        col = colour(i)
        v = validity[i] if validity is not None else None
        n = _cut(np.asarray(r.t), v)
        lab = f"{r.chair.name} ({r.chair.caster_position} casters)"
        if v is not None and v.until is not None:
            lab += f"; ends {v.until:.2f} s: {v.reason}"
        ax.plot(r.x[:n], r.y[:n], color=col, lw=1.6, label=lab)
        if 0 < n < len(r.t):
            ax.plot([r.x[n - 1]], [r.y[n - 1]], "|", color=col, ms=12, mew=2)
        if r.linear is not None:
            ax.plot(r.linear.x, r.linear.y, color=col, lw=1.0, ls="--")
        # position marks every second (valid part only)
        for tt in np.arange(1.0, r.t[n - 1] + 1e-9 if n else 0.0, 1.0):
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
    ax.set_title(title or f"paths after {f:g} N for {d:g} s at the c.g., {sp:g} m/s: {rs.model} model, "
                 f"{rs.scheme} scheme", fontsize=9)
    return ax


def plot_result(result: SimulationResult, path_or_ax: Any = None, *, title: str | None = None) -> Any:
    """Plot a run's yaw rate against time (and its path); draws what it is given, computes nothing.

    ``path_or_ax`` is a matplotlib Axes (drawn on, returned) or a file
    path (a figure with yaw rate and trajectory is written atomically;
    PDFs through :func:`stability.runtime.files.write_pdf`); ``None`` returns a
    new figure.

    Parameters
    ----------
    result : SimulationResult
        The run.
    path_or_ax : matplotlib Axes, path or None
        Where to draw.
    title : str, optional
        Title; default names the chair, model and scheme.

    Returns
    -------
    Axes, Figure or Path
        The Axes drawn on, the new figure, or the file written.
    """
    label = f"{result.chair.name}, {result.speed:g} m/s"
    if title is None:
        title = (f"{result.chair.name} ({result.chair.caster_position} casters): "
                 f"{result.settings.get('model')} model, {result.settings.get('scheme')} scheme")
    on_axes = path_or_ax is not None and hasattr(path_or_ax, "plot") and hasattr(path_or_ax, "set_xlabel")
    if on_axes:
        ax1 = path_or_ax
    else:
        fig = Figure(figsize=(8.0, 6.5))
        ax1, ax2 = fig.subplots(2, 1)
    ax1.plot(result.t, result.yaw_rate, label=label)
    if not on_axes and result.stopped_by_warnings and result.stop_time is not None:
        ax1.axvline(result.stop_time, color="k", ls=":", lw=0.8,
                    label="stopped by warnings" if result.stop_reason is None else "stopped: no load solution")
    ax1.set_xlabel("time (s)")
    ax1.set_ylabel("yaw rate (rad/s)")
    ax1.set_title(title)
    ax1.legend()
    ax1.grid(True, alpha=0.3)
    if on_axes:
        return ax1
    ax2.plot(result.x, result.y, label="c.g. path")
    ax2.set_xlabel("X (m)")
    ax2.set_ylabel("Y (m, to the right)")
    ax2.invert_yaxis()
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.legend()
    ax2.grid(True, alpha=0.3)
    fig.tight_layout()
    if path_or_ax is None:
        return fig
    return save_figure(fig, path_or_ax, title=title)


def layout_run_caption(run: LayoutRun, caster_labels: Sequence[str]) -> str:
    """What to conclude from a layout's run (:func:`plot_layout_run`'s caption), from the run's own numbers.

    Parameters
    ----------
    run : LayoutRun
    caster_labels : sequence of str
        One per caster (:attr:`stability.layout.Layout.caster_labels`).

    Returns
    -------
    str
    """
    f, d = run.settings.get("push_force_N", 0.0), run.settings.get("push_duration_s", 0.0)
    swing = [float(np.degrees(np.abs(np.angle(np.exp(1j * (a - a[0])))).max())) for a in run.caster_angle_rad]
    round_ = [lab for lab, w in zip(caster_labels, swing, strict=True) if w > 90.0]
    words = [f"What to conclude: after the push of {f:g} N for {d:g} s the chair's heading ends "
             f"{run.final_heading_deg:+.1f} deg from its start (peak {np.abs(run.heading_deg).max():.1f} deg) and its "
             f"path {run.y_m[-1]:+.3f} m to the side after {abs(run.x_m[-1]):.2f} m of travel: the smaller these, the "
             "better this layout holds its line at this speed and push."]
    if round_:
        words.append(f" The casters that swing more than 90 deg from where they started ({', '.join(round_)}) "
                     "turned round to trail: while they swing the chair is pulled off its line.")
    else:
        words.append(f" No caster swings more than 90 deg (largest {max(swing, default=0.0):.1f} deg): they stay "
                     "near the trailing angle they started at.")
    if run.ended != "horizon":
        words.append(f" The run ended early at {run.end_time_s:.2f} s ({run.ended}): read nothing after it.")
    return "".join(words)


def plot_layout_run(run: LayoutRun, caster_labels: Sequence[str], path: Any = None) -> Any:
    """A layout's run on one page: the path, the heading, the yaw rate and every caster's angle against time.

    Draws what it is given and computes nothing but the caption's maxima (:func:`layout_run_caption`).

    Parameters
    ----------
    run : LayoutRun
        The run (:func:`stability.simulate.layout.simulate_layout`).
    caster_labels : sequence of str
        One per caster (:attr:`stability.layout.Layout.caster_labels`), the legend's names.
    path : path-like, optional
        File to write (the suffix names the format: png, svg, pdf); None returns the figure.

    Returns
    -------
    Figure or Path
    """
    from stability.plotting.pages import finish, page, plain_text, wrap_text

    direction = "backwards" if run.speed_m_s < 0 else "forwards"
    title = (f"{run.layout} | layout model (exact equations, wchair scheme) | {abs(run.speed_m_s):g} m/s "
             f"{direction}")
    f, d = run.settings.get("push_force_N", 0.0), run.settings.get("push_duration_s", 0.0)
    fig, axes = page(title, f"a push of {f:g} N for {d:g} s at the c.g. to the right; casters start at "
                     + ", ".join(f"{a:g}" for a in run.settings.get("caster_angles_deg", []))
                     + " deg (0: trailing for forward driving, 180: for reversing)", nrows=2, ncols=2,
                     size=(11.0, 8.5))
    (ax_path, ax_head), (ax_rate, ax_caster) = axes
    ax_path.plot(run.x_m, run.y_m, color=colour(0), lw=1.6, label="c.g. path")
    ax_path.plot(run.x_m[:1], run.y_m[:1], "o", color="k", ms=4, label="start")
    ax_path.set_xlabel("distance along the initial heading X (m)")
    ax_path.set_ylabel("lateral displacement Y (m, to the right)")
    ax_path.invert_yaxis()
    ax_path.set_title("path of the c.g.", fontsize=9)
    ax_head.plot(run.t_s, run.heading_deg, color=colour(0), lw=1.6, label="heading")
    ax_head.set_ylabel("heading (deg, clockwise +)")
    ax_head.set_title("heading", fontsize=9)
    ax_rate.plot(run.t_s, run.yaw_rate_rad_s, color=colour(0), lw=1.6, label="yaw rate")
    ax_rate.set_ylabel("yaw rate (rad/s, clockwise +)")
    ax_rate.set_title("yaw rate", fontsize=9)
    for k, (a, lab) in enumerate(zip(run.caster_angle_rad, caster_labels, strict=True)):
        ax_caster.plot(run.t_s, np.degrees(a), color=colour(k + 1), lw=1.4, ls=("-", "--", "-.", ":")[k % 4],
                       label=lab)
    ax_caster.set_ylabel("caster angle (deg, 0 trailing forward)")
    ax_caster.set_title("caster swivel angles", fontsize=9)
    for ax in (ax_head, ax_rate, ax_caster):
        ax.set_xlabel("time t (s)")
        ax.axhline(0.0, color="0.5", lw=0.6)
    for ax in (ax_path, ax_head, ax_rate, ax_caster):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    lines = wrap_text(layout_run_caption(run, caster_labels), 150)
    fig.text(0.5, 0.015, "\n".join(lines), ha="center", va="bottom", fontsize=8.5, fontweight="bold", color="0.1",
             linespacing=1.4)
    finish(fig, top=0.88, left=0.09, bottom=0.10 + 0.03 * len(lines), hspace=0.4)
    plain_text(fig)                                  # the layout's name may come from a user's file
    if path is None:
        return fig
    return save_figure(fig, path, title=f"stability simulate: {run.layout}")
