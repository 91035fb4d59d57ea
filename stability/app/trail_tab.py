"""The explorer's trail window: directional stability and caster shimmy against trail, and a cross slope.

Computed on the background worker after each chair change (a fraction of a
second: :func:`stability.app.measures.trail_window`); the old result stays
greyed until the new one arrives.  The chart's shimmy curves come from the
chair model with relaxation-length caster tires on the same compliant pins as
the shimmy-free band's towed wheel, so they cross zero at the band's
boundaries (with rigid pins they would cross at a trail equal to the
relaxation length, 2 cm: the shimmy that a stiff frame would allow).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource

from stability.app import plots
from stability.app.markup import literal
from stability.app.measures import TRAIL_SPEEDS, TrailWindow, trail_window
from stability.app.nonlinear_tab import FRESH, STALE, warnings_text
from stability.app.tabtext import TabText
from stability.app.widgets import widget
from stability.chair import Chair
from stability.plotting.style import UNSTABLE

__all__ = ["TrailTab", "trail_text", "caption"]

def caption() -> str:
    """What the trail chart shows and how to read it (the compliance estimates from
    :class:`stability.shimmy.CasterCompliance`).

    Returns
    -------
    str
        Markdown.
    """
    from stability.shimmy.compliance import CasterCompliance

    est = CasterCompliance()
    sigma, k = 1000 * est.relaxation_length, est.lateral_stiffness / 1000
    return (
        "Solid: the growth rate of the chair's yaw mode (> 0: the heading drifts away after a disturbance; in this "
        "model it hardly depends on the trail). Dashed: the real part of the casters' shimmy mode (> 0: the "
        "casters flutter). Both come from the chair model with relaxation-length caster tires and each caster pin "
        f"on a lateral spring (relaxation length {sigma:g} mm, pin stiffness {k:g} kN/m: *estimates* to be "
        "measured, `stability.shimmy.CasterCompliance`). That is the towed wheel of the shimmy-free band, so the "
        "dashed curves cross zero at the band's boundaries (dotted vermillion). On rigid pins the same model would "
        f"put the boundary at a trail equal to the relaxation length, {sigma / 10:g} cm: the frame's flexibility "
        "is what makes short trails shimmy. Black: this chair's trail. What to conclude: keep the trail inside "
        "the band, with a margin larger than the spread over the estimate ranges given below.")


def trail_text(tw: TrailWindow) -> str:
    """The band, the chair's margin and damping, and the cross slope in words (as the command lines print them).

    Parameters
    ----------
    tw : TrailWindow

    Returns
    -------
    str
        Markdown.
    """
    ch, b = tw.chart, tw.band
    bands = "; ".join(f"{u:g} m/s: {b.describe(k)} cm" for k, u in enumerate(b.speeds_m_s))
    margin = b.shimmy_margin_m
    lo, hi = b.shimmy_margin_interval_m

    def cm(x: float) -> str:          # as python -m stability.shimmy prints the margin
        return f"{100 * x:+.2f} cm" if np.isfinite(x) else ("shimmies at every trail" if x < 0 else "unbounded")

    verdict = (f"{100 * margin:+.2f} cm from the nearest boundary (margin over the estimate ranges of relaxation "
               f"length and pin stiffness: {cm(lo)} to {cm(hi)})" if np.isfinite(margin)
               else "no boundary on the searched trails")
    warn = (" The estimate range straddles a boundary: **measure pin stiffness and relaxation length first.**"
            if b.straddles else "")
    zetas = ", ".join(f"{z:.3g}" for z in b.damping_ratio)
    eq, hr = tw.slope, tw.handrim
    return (f"**Shimmy-free trail** (`python -m stability.shimmy`): {bands}. This chair's trail "
            f"{100 * ch.chair_trail:.3g} cm is {verdict}; damping ratio of the least damped caster mode there "
            f"{zetas} at {', '.join(f'{u:g}' for u in b.speeds_m_s)} m/s.{warn}\n\n"
            f"**On a {tw.cross_slope_deg:g} deg cross slope at {tw.speed:g} m/s** the chair needs a holding moment "
            f"of {eq.holding_moment:.3g} N m (clockwise positive) to run straight: hand-rim forces "
            f"{hr['handrim_force_left_N']:.3g} N left and {hr['handrim_force_right_N']:.3g} N right "
            f"(difference right - left {hr['handrim_force_difference_N']:.3g} N; wheel radius "
            f"{hr['wheel_radius_m']:g} m, hand rim {hr['handrim_radius_m']:g} m; `python -m stability.slope`).")


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
        self.sources = [ColumnDataSource({"trail_cm": [], "yaw": [], "shimmy": []}) for _ in TRAIL_SPEEDS]
        self.fig = plots.trail_figure(self.sources, TRAIL_SPEEDS)
        self.cross_slope = widget(pn.widgets.FloatInput, "cross slope (deg, falling to the right)", value=2.0,
                                                 start=-10.0, end=10.0, step=0.5, width=230)
        self.speed = widget(pn.widgets.FloatInput, "speed on the slope (m/s)", value=1.0, start=0.1, end=3.0,
                                           step=0.1, width=180)
        self.text = pn.pane.Markdown("", css_classes=["trail-text"], sizing_mode="stretch_width")
        self.texts = TabText()
        self.status = pn.pane.Markdown("", css_classes=["trail-status"], sizing_mode="stretch_width")
        self.warnings = pn.pane.Markdown("", styles={"color": UNSTABLE}, sizing_mode="stretch_width",
                                         css_classes=["trail-warnings"])
        self.chair: Chair | None = None
        self.model = "exact"
        for w in (self.cross_slope, self.speed):
            w.param.watch(on_change(lambda e: self.start(self.chair, self.model)), "value")
        self.result = pn.Column(self.warnings, pn.pane.Bokeh(self.fig["figure"], sizing_mode="stretch_width"),
                                pn.pane.Markdown(caption(), sizing_mode="stretch_width"), self.text,
                                sizing_mode="stretch_width", css_classes=["trail-result"])
        self.panel = pn.Column(
            pn.pane.Markdown("The caster trail against shimmy: too short a trail lets the casters flutter, and with "
                             "a soft frame so can a very long one (docs/shimmy.md). Below the chart: what a cross "
                             "slope asks of the user.", sizing_mode="stretch_width"),
            self.status, self.result, pn.Row(self.cross_slope, self.speed), sizing_mode="stretch_width")

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
        self.texts.set(self.status, f"computing the trail window for {literal(chair.name)}...")
        self.result.styles = STALE
        self.submit(lambda: trail_window(chair, model, phi, speed), self.show, self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why the trail window could not be computed (one line).

        Parameters
        ----------
        exc : BaseException
        """
        self.texts.set(self.status, f"error: could not compute the trail window for this chair: {literal(exc)}")

    def show(self, tw: TrailWindow) -> None:
        """Draw a computed trail window.

        Parameters
        ----------
        tw : TrailWindow
        """
        ch = tw.chart
        for j, src in enumerate(self.sources):
            src.data = {"trail_cm": 100 * ch.trails, "yaw": ch.divergence_rate[:, j],
                        "shimmy": ch.shimmy_real_part[:, j]}
        self.fig["chair"].location = 100 * ch.chair_trail
        b = tw.band
        spans = self.fig["critical"]
        bounds = sorted({round(x, 12) for bs in b.boundaries_m for x in bs})
        for k, span in enumerate(spans):
            if k < len(bounds):
                span.update(location=100 * bounds[k], visible=True)
            else:
                span.visible = False
        self.fig["figure"].title.text = (f"{plots.short_title(ch.chair_name)}: yaw growth (solid) and caster shimmy "
                                         "(dashed) against trail")
        self.texts.set(self.warnings, warnings_text(tw.warnings, "the trail window below"))
        self.texts.set(self.text, trail_text(tw))
        self.texts.set(self.status, f"Computed for {literal(ch.chair_name)}.")
        self.result.styles = FRESH
