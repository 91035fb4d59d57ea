"""The explorer's power-chair tab: the motor assist's gain schedule and margins for the current chair.

On request (a button: the design takes a few seconds), on the background
worker: :func:`stability.assist.schedule` at ``python -m stability.assist``'s
default design speeds (gyro design, the command line's defaults) and
:func:`stability.assist.tables.gain_table` without the nonlinear check; the
tab shows the gains against speed and the command line's own tables (gains,
continuous and sampled margins).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import panel as pn
from bokeh.core.properties import value
from bokeh.models import ColumnDataSource
from bokeh.models.annotations import Legend, LegendItem
from bokeh.plotting import figure

from stability.app.markup import PRE_STYLESHEET, literal, pre
from stability.app.measures import warning_lines
from stability.app.nonlinear_tab import FRESH, STALE
from stability.app.plots import BRANCH_COLOURS
from stability.app.tabtext import TabText
from stability.app.widgets import widget
from stability.chair import Chair
from stability.settings import defaults as D

__all__ = ["AssistTab", "assist_schedule"]


def assist_schedule(chair: Chair, model: str = D.MODEL) -> tuple[Any, list, str]:
    """The gain schedule, its rows and the command line's text tables for ``chair``.

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}

    Returns
    -------
    (Schedule, list of GainRow, str)
        The text ends with every warning raised while designing (``note: Kind: message``).
    """
    from stability.assist import schedule
    from stability.assist.tables import format_margins, format_table, gain_table
    from stability.cli import parse_speeds

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sched = schedule(chair, parse_speeds(D.ASSIST_SPEEDS, increasing=True), "gyro", model=model)
        rows = gain_table(sched, check=False)
    notes = "".join(f"\nnote: {line}" for line in warning_lines(caught))
    caption = (f"Margins at the plant input, continuous / sampled at {sched.gyro.sample_rate_hz:g} Hz (ZOH, one-sample "
               f"computation delay, {1e3 * sched.drive.motor_time_constant:g} ms motor lag in both); the yaw-rate "
               "step columns (a nonlinear simulation) are '-' here: python -m stability.assist runs it.")
    return sched, rows, format_table(sched, rows) + "\n\n" + caption + "\n" + format_margins(rows) + notes


class AssistTab:
    """The power-chair tab of one session.

    Parameters
    ----------
    submit : callable
        ``submit(work, show, failed)`` of the session's :class:`~stability.app.jobs.Jobs`.
    on_change : callable
        Wraps a widget callback as the page does.
    current : callable
        ``current() -> (chair, model)``: the session's chair now.
    """

    def __init__(self, submit: Any, on_change: Any, current: Any) -> None:
        self.submit, self.current = submit, current
        self.button = widget(pn.widgets.Button, "design the motor assist", kind="primary", width=220,
                                        css_classes=["run-assist"])
        self.button.on_click(on_change(lambda e: self.start()))
        self.texts = TabText()
        self.text = pn.pane.Markdown("Press the button: an LQR yaw-rate assist with a gyro (the thesis's chapter 9, "
                                     "`python -m stability.assist`) is designed at every speed from 0.5 to 3 m/s.",
                                     css_classes=["assist-text"], sizing_mode="stretch_width",
                                     stylesheets=[PRE_STYLESHEET])
        self.sources: list[ColumnDataSource] = []
        self.fig = figure(title="Assist gains against speed, each relative to its largest |k| (in the legend)",
                          height=420,
                          sizing_mode="stretch_width", tools="pan,wheel_zoom,box_zoom,reset,save")
        self.fig.xaxis.axis_label = "design speed U (m/s)"
        self.fig.yaxis.axis_label = "gain k / its largest |k| over speed (-)"
        self.fig.toolbar.logo = None
        self.legend = Legend(items=[], location="top_left", label_text_font_size="9pt", click_policy="hide", ncols=2,
                             title="gain on (largest |k|: N m per wheel per SI unit of the state)",
                             title_text_font_size="9pt")
        self.fig.add_layout(self.legend, "below")
        self.designed: tuple[Chair, str] | None = None
        self.result = pn.Column(pn.pane.Bokeh(self.fig, sizing_mode="stretch_width"), self.text,
                                sizing_mode="stretch_width")
        self.panel = pn.Column(self.button, self.result, sizing_mode="stretch_width")

    def chair_changed(self, chair: Chair, model: str) -> None:
        """Grey a design made for another chair (or model) until it is designed again.

        Parameters
        ----------
        chair : Chair
        model : {"exact", "thesis"}
        """
        if self.designed is not None:
            self.result.styles = FRESH if self.designed == (chair, model) else STALE

    def start(self) -> None:
        """Queue the design for the session's current chair."""
        chair, model = self.current()
        self.designed = None
        self.result.styles = FRESH
        self.texts.set(self.text, f"designing the assist for {literal(chair.name)} (several seconds)...")
        self.submit(lambda: assist_schedule(chair, model), lambda r: self.show(r, (chair, model)), self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why no assist could be designed (one line)."""
        self.texts.set(self.text, f"error: could not design the assist for this chair: {literal(exc)}")

    def show(self, result: tuple[Any, list, str], designed: tuple[Chair, str] | None = None) -> None:
        """Draw a computed schedule.

        Parameters
        ----------
        result : tuple
            :func:`assist_schedule`'s.
        designed : (Chair, str), optional
            The chair and model it was designed for.
        """
        self.designed = designed
        _, rows, text = result
        speeds = [r.speed_m_s for r in rows]
        names = rows[0].gain_states
        gains = np.array([r.wheel_torque_gains for r in rows], dtype=float)      # speeds x states
        scale = np.max(np.abs(gains), axis=0)
        while len(self.sources) < len(names):
            j = len(self.sources)
            src = ColumnDataSource({"speed": [], "gain": []})
            colours = BRANCH_COLOURS            # no yellow (unreadable on white), no vermillion (instability)
            line: Any = self.fig.line("speed", "gain", source=src, line_width=2, color=colours[j % len(colours)],
                                      line_dash=["solid", "dashed", "dotdash", "dotted"][(j // len(colours)) % 4])
            self.sources.append(src)
            self.legend.items = [*self.legend.items, LegendItem(label=value(""), renderers=[line])]
        for j, src in enumerate(self.sources):
            shown = j < len(names) and scale[j] > 0
            src.data = {"speed": speeds, "gain": list(gains[:, j] / scale[j])} if shown else {"speed": [], "gain": []}
            label = f"{names[j]}: largest |k| {scale[j]:.3g}" if j < len(names) else ""
            item = self.legend.items[j]
            assert isinstance(item, LegendItem)
            item.update(label=value(label), visible=j < len(names))
        self.texts.set(self.text, pre(text))
