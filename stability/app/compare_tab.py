"""The explorer's Compare tab: the growth-rate curves of the current and the pinned chairs, and why they differ.

The pinned chairs' curves are computed when the pins change
(:func:`stability.compare.growth_curves`); :func:`stability.compare.compare`'s
table (which chair is more stable on each measure, by how much, and which
parameter difference causes it; with the session's user, the speed that user
holds on each chair) runs on the background worker.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import panel as pn
from bokeh.core.properties import value
from bokeh.models import ColumnDataSource

from stability.app import plots
from stability.app.markup import PRE_STYLESHEET, literal, pre
from stability.app.tabtext import TabText
from stability.app.views import LinearView
from stability.app.widgets import widget

__all__ = ["CompareTab", "NOTHING_PINNED", "COMPARE_MAX_SPEED"]

NOTHING_PINNED = ("Nothing pinned yet: press *pin this chair for the Compare tab*, change the chair, and come back "
                  "here.")
#: Highest speed of the compare plot, m/s (walking and pushing speeds).
COMPARE_MAX_SPEED = 3.0
_CURVES = 4


class CompareTab:
    """The Compare tab of one session.

    Parameters
    ----------
    submit : callable
        ``submit(work, show, failed)`` of the session's :class:`~stability.app.jobs.Jobs`.
    """

    def __init__(self, submit: Any) -> None:
        self.submit = submit
        self.src = ColumnDataSource({"speed": [], **{f"rate{j}": [] for j in range(_CURVES)}})
        self.fig, self.legend = plots.compare_figure(self.src, _CURVES)
        self.texts = TabText()
        self.text = pn.pane.Markdown(NOTHING_PINNED, css_classes=["compare-text"], sizing_mode="stretch_width",
                                     stylesheets=[PRE_STYLESHEET])
        self.unpin = widget(pn.widgets.Select, "pinned chairs", options=[], sizing_mode="stretch_width")
        self.unpin_button = widget(pn.widgets.Button, "unpin the selected chair", width=190, align="end")
        self._pinned: tuple[Any, list] = (None, [])
        self.panel = pn.Column(
            pn.pane.Markdown("Pin up to three chairs (the button under the presets); their curves are overlaid on "
                             "the current chair's, and the table says on each measure which chair is more stable, "
                             "by how much, and which parameter difference causes it (`python -m stability.compare`).",
                             sizing_mode="stretch_width"),
            pn.Row(self.unpin, self.unpin_button, sizing_mode="stretch_width"),
            pn.pane.Bokeh(self.fig, sizing_mode="stretch_width"), self.text, sizing_mode="stretch_width")

    def failed(self, exc: BaseException) -> None:
        """Show why the comparison could not be made (one line).

        Parameters
        ----------
        exc : BaseException
        """
        self.texts.set(self.text, f"error: could not compare these chairs: {literal(exc)}")

    def show(self, v: LinearView, pinned: list, model: str, user: dict | None = None) -> None:
        """Draw the current chair's curve with the pinned ones and queue the comparison table.

        Parameters
        ----------
        v : LinearView
            The current chair's.
        pinned : list of Chair
        model : {"exact", "thesis"}
        user : dict, optional
            The session's ``[user]`` table: the table adds the speed that user holds on each chair, as
            ``python -m stability.compare --reaction-time`` does.
        """
        from stability.compare import compare, format_comparison, growth_curves

        keep = v.locus.speeds <= COMPARE_MAX_SPEED
        speeds = v.locus.speeds[keep]
        options = [f"{i + 1}: {c.name}" for i, c in enumerate(pinned)]
        if self.unpin.options != options:
            self.unpin.options = options
        key = (model, tuple(pinned))
        if self._pinned[0] != key:           # pinned chairs' curves: computed when the pins change
            rates = list(growth_curves(pinned, model, [float(x) for x in speeds])) if pinned else []
            self._pinned = (key, rates)
        curves = [v.growth_rate[keep], *self._pinned[1]]
        chairs = [v.chair, *pinned]
        data: dict[str, Any] = {"speed": speeds}
        for j in range(_CURVES):
            data[f"rate{j}"] = np.asarray(curves[j]) if j < len(curves) else np.full(len(speeds), np.nan)
        self.src.data = data
        for j, item in enumerate(self.legend.items):
            label = (("current: " if j == 0 else f"pinned {j}: ") + plots.short_title(chairs[j].name)
                     if j < len(chairs) else "")
            if item.label != value(label) or item.visible != (j < len(chairs)):
                item.update(label=value(label), visible=j < len(chairs))
        if pinned:
            labels = ["current", *[f"pinned {i + 1}" for i in range(len(pinned))]]
            self.texts.set(self.text, "comparing...")
            from stability.driver import Driver

            tau = None if not user else Driver.from_mapping(user).reaction_time_s     # read as the commands read it
            self.submit(lambda: format_comparison(compare(chairs, labels=labels, model=model, reaction_time=tau)),
                        lambda text: self.texts.set(self.text, pre(text)), self.failed)
        else:
            self.texts.set(self.text, NOTHING_PINNED)

    def selected(self) -> int | None:
        """Index (0-based) of the pinned chair selected for unpinning, or None.

        Returns
        -------
        int or None
        """
        if self.unpin.value in self.unpin.options:
            return list(self.unpin.options).index(self.unpin.value)
        return None
