"""The explorer's trail window: directional stability and caster shimmy against trail, and a cross slope.

Computed on the background worker after each chair change (about half a
second: :func:`stability.shimmy.chair_trail_chart` over 40 trails at three
speeds, :func:`stability.slope.solve` on the cross slope).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource

from stability.app import plots
from stability.app.markup import literal
from stability.app.views import TRAIL_SPEEDS, TrailWindow, trail_window
from stability.chair import Chair

__all__ = ["TrailTab"]


class TrailTab:
    """The trail-window tab of one session.

    Parameters
    ----------
    submit : callable
        ``submit(work, show, failed)`` of the session's :class:`~stability.app.jobs.Jobs`.
    on_change : callable
        Wraps a widget callback as the page does (runs it on the document's tick).
    """

    def __init__(self, submit: Any, on_change: Any) -> None:
        self.submit = submit
        self.sources = [ColumnDataSource({"trail": [], "yaw": [], "shimmy": [], "name": []}) for _ in TRAIL_SPEEDS]
        self.fig = plots.trail_figure(self.sources)
        self.cross_slope = pn.widgets.FloatInput(name="cross slope (deg, falling to the right)", value=2.0,
                                                 start=-10.0, end=10.0, step=0.5, width=230)
        self.speed = pn.widgets.FloatInput(name="speed on the slope (m/s)", value=1.0, start=0.1, end=3.0,
                                           step=0.1, width=180)
        self.text = pn.pane.Markdown("", css_classes=["trail-text"], sizing_mode="stretch_width")
        self.chair: Chair | None = None
        self.model = "exact"
        for w in (self.cross_slope, self.speed):
            w.param.watch(on_change(lambda e: self.start(self.chair, self.model)), "value")
        self.panel = pn.Column(
            pn.pane.Markdown("A longer trail steadies the chair's heading but moves the casters towards shimmy; "
                             "both against trail, from the toolkit's chair model with caster compliance "
                             "(docs/shimmy.md). Below: what a cross slope asks of the user."),
            pn.pane.Bokeh(self.fig["figure"], sizing_mode="stretch_width"),
            pn.Row(self.cross_slope, self.speed), self.text, sizing_mode="stretch_width")

    def start(self, chair: Chair | None, model: str) -> None:
        """Queue the trail window of ``chair``.

        Parameters
        ----------
        chair : Chair or None
        model : {"exact", "thesis"}
        """
        if chair is None:
            return
        self.chair, self.model = chair, model
        phi, speed = float(self.cross_slope.value or 0.0), float(self.speed.value or 1.0)
        self.text.object = "computing the trail window..."
        self.submit(lambda: trail_window(chair, model, phi, speed), self.show, self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why the trail window could not be computed (one line)."""
        self.text.object = f"error: could not compute the trail window for this chair: {literal(exc)}"

    def show(self, tw: TrailWindow) -> None:
        """Draw a computed trail window.

        Parameters
        ----------
        tw : TrailWindow
        """
        ch = tw.chart
        for j, src in enumerate(self.sources):
            src.data = {"trail": ch.trails, "yaw": ch.divergence_rate[:, j], "shimmy": ch.shimmy_real_part[:, j],
                        "name": [f"{ch.speeds[j]:g} m/s"] * len(ch.trails)}
        self.fig["chair"].location = ch.chair_trail
        b = tw.band
        spans = self.fig["critical"]
        bounds = sorted({round(x, 12) for bs in b.boundaries_m for x in bs})
        for k, span in enumerate(spans):
            span.visible = k < len(bounds)
            if k < len(bounds):
                span.location = bounds[k]
        bands = "; ".join(f"{u:g} m/s: {b.describe(k)} cm" for k, u in enumerate(b.speeds_m_s))
        margin = b.shimmy_margin_m
        lo, hi = b.shimmy_margin_interval_m
        verdict = (f"{100 * margin:+.2g} cm from the nearest boundary ({100 * lo:+.2g} to {100 * hi:+.2g} cm over "
                   "the estimate ranges of relaxation length and pin stiffness)" if np.isfinite(margin)
                   else "no boundary on the searched trails")
        warn = (" The estimate range straddles a boundary: **measure pin stiffness and relaxation length first.**"
                if b.straddles else "")
        zetas = ", ".join(f"{z:.3g}" for z in b.damping_ratio)
        eq, hr = tw.slope, tw.handrim
        self.text.object = (
            f"**Shimmy-free trail** (`python -m stability.shimmy`): {bands}. This chair's trail "
            f"{100 * ch.chair_trail:.3g} cm is {verdict}; damping ratio of the least damped caster mode there "
            f"{zetas} at {', '.join(f'{u:g}' for u in b.speeds_m_s)} m/s.{warn}\n\n"
            f"**On a {tw.cross_slope_deg:g} deg cross slope at {tw.speed:g} m/s** the chair needs a holding moment "
            f"of {eq.holding_moment:.3g} N m (clockwise positive) to run straight: hand-rim forces "
            f"{hr['handrim_force_left_N']:.3g} N left and {hr['handrim_force_right_N']:.3g} N right "
            f"(difference right - left {hr['handrim_force_difference_N']:.3g} N; wheel radius "
            f"{hr['wheel_radius_m']:g} m, hand rim {hr['handrim_radius_m']:g} m; `python -m stability.slope`).")
