"""Plot of a :class:`~stability.simulate.SimulationResult` (yaw rate and c.g. path).

Lives here only until ``stability.plotting`` takes it; matplotlib is imported lazily.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from stability.runtime.files import save_figure

if TYPE_CHECKING:
    from stability.simulate.results import SimulationResult

__all__ = ["plot_result"]


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
        from matplotlib.figure import Figure

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
