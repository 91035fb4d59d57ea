"""The explorer's nonlinear tab: the response to a push, the time to the criterion, the critical impulse, the
equal-instability speed (with the ranges the command lines print) and the simulator's warnings.

Computed on the background worker (:func:`stability.app.measures.nonlinear_view`)
after each chair change; until the new result arrives the old one stays on the
page greyed out, under a line saying it is being recomputed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource

from stability.app import plots
from stability.app.jobs import warm_up_done
from stability.app.markup import literal
from stability.app.measures import NonlinearView, nonlinear_view
from stability.app.tabtext import TabText
from stability.app.widgets import widget
from stability.chair import Chair
from stability.plotting.style import UNSTABLE
from stability.settings import defaults as D

__all__ = ["NonlinearTab", "nonlinear_text", "warnings_text", "busy_bar", "show_busy", "STALE", "FRESH"]

#: Styles of a result computed for an earlier chair (kept until the new one arrives) and of a current one.
STALE = {"opacity": "0.4", "filter": "grayscale(1)"}
FRESH = {"opacity": "1", "filter": "none"}


def busy_bar() -> Any:
    """An indeterminate progress bar shown while background work runs (hidden by style: no layout change).

    Returns
    -------
    panel.indicators.Progress
    """
    return pn.indicators.Progress(active=False, value=-1, width=300, height=8, bar_color="primary",
                                  css_classes=["progress"], styles={"visibility": "hidden"}, margin=(2, 10))


def show_busy(bar: Any, busy: bool) -> None:
    """Show (and animate) or hide a :func:`busy_bar`.

    Parameters
    ----------
    bar : panel.indicators.Progress
    busy : bool
    """
    bar.param.update(active=busy, styles={"visibility": "visible" if busy else "hidden"})


def warnings_text(lines: tuple[str, ...], what: str) -> str:
    """The page's note about warnings raised while computing a result (empty when none).

    Parameters
    ----------
    lines : tuple of str
        ``"Kind: message"`` lines (:func:`stability.app.measures.warning_lines`); user text, shown literally.
    what : str
        What they qualify (the page's own words).

    Returns
    -------
    str
        Markdown.
    """
    if not lines:
        return ""
    return (f"**Warning: {what} may be a numerical artefact.** The computation reported: "
            + "; ".join(literal(line) for line in lines))


def nonlinear_text(nv: NonlinearView) -> str:
    """The nonlinear results in words: the time to the criterion, the critical impulse and the equal-instability
    speed, each with its range (the command lines' ``describe``).

    Parameters
    ----------
    nv : NonlinearView

    Returns
    -------
    str
        Markdown.
    """
    t = nv.time_to_level
    reach = (f"{t:.3g} s after the push starts" if math.isfinite(t) else
             f"not within the {nv.t[-1]:.3g} s simulated" if len(nv.t) else "not computed")
    eq = nv.equal_instability
    eq_text = "not computed" if eq is None else eq.describe() + (
        f" ({3.6 * float(eq.point.speed):.3g} km/h)" if eq.point.status == "found" else "")
    return (f"**Time to |yaw rate| = {D.YAW_RATE_LEVEL:g} rad/s** (the thesis's criterion) after the push shown: "
            f"{reach}.\n\n"
            f"**Critical impulse at {nv.speed:g} m/s** (the smallest push at the c.g. that spins the chair to "
            f"{D.YAW_RATE_LEVEL:g} rad/s within {D.HORIZON_S:g} s): {nv.critical_impulse.describe()}; "
            f"{literal(nv.critical_impulse.point.push)}.\n\n"
            f"**Equal-instability speed** (as unstable as the E&J Premier at 0.75 m/s after the thesis's 40 N / "
            f"0.1 s push): {eq_text}.\n\n"
            f"Push shown: {nv.push[0]:g} N for {nv.push[1]:g} s at the c.g., at {nv.speed:g} m/s. The ranges are "
            "over the inputs each result rests on, one at a time (`python -m stability.study critical-impulse "
            "--interval`, `... equal-instability`): not statistical intervals.")


class NonlinearTab:
    """The nonlinear tab of one session.

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
        self.push_force = widget(pn.widgets.FloatInput, "push force (N)", value=D.PUSH_FORCE, start=0.0, end=1000.0,
                                                width=130)
        self.push_duration = widget(pn.widgets.FloatInput, "push duration (s)", value=D.PUSH_DURATION, start=0.001,
                                                   end=2.0, width=130)
        self.push_speed = widget(pn.widgets.FloatInput, "speed (m/s)", value=D.SPEED, start=0.05, end=3.0, width=110)
        self.run_button = widget(pn.widgets.Button, "compute again", kind="primary", width=140,
                                            css_classes=["run-nonlinear"], align="end")
        self.run_button.on_click(on_change(lambda e: self.start(*self.current())))
        self.busy = busy_bar()
        self.texts = TabText()
        self.status = pn.pane.Markdown("", css_classes=["nonlinear-status"], sizing_mode="stretch_width")
        self.text = pn.pane.Markdown("", css_classes=["nonlinear-text"], sizing_mode="stretch_width")
        self.warnings = pn.pane.Markdown("", css_classes=["nonlinear-warnings"], styles={"color": UNSTABLE},
                                         sizing_mode="stretch_width")
        self.src = ColumnDataSource({"t": [], "r": []})
        self.lin_src = ColumnDataSource({"t": [], "r": []})
        self.fig = plots.response_figure(self.src, self.lin_src)
        self.result = pn.Column(self.warnings, self.text, pn.pane.Bokeh(self.fig, sizing_mode="stretch_width"),
                                sizing_mode="stretch_width", css_classes=["nonlinear-result"])
        self.panel = pn.Column(
            pn.pane.Markdown("The compiled WCHAIR simulator in the background after each change; a change cancels "
                             "the runs for the old chair, whose results stay greyed until the new ones arrive. The "
                             "linear views never wait for them.", sizing_mode="stretch_width"),
            pn.Row(self.push_force, self.push_duration, self.push_speed, self.run_button),
            self.busy, self.status, self.result, sizing_mode="stretch_width")

    def start(self, chair: Chair, model: str) -> None:
        """Queue the response, the critical impulse and the equal-instability speed for ``chair``.

        Parameters
        ----------
        chair : Chair
        model : {"exact", "thesis"}
        """
        push = (float(self.push_force.value or 0.0), float(self.push_duration.value or D.PUSH_DURATION))
        speed = float(self.push_speed.value or D.SPEED)
        show_busy(self.busy, True)
        self.result.styles = STALE
        self.texts.set(self.status, f"computing for {literal(chair.name)} (compiling the simulator first, once per "
                       "start)..." if not warm_up_done() else
                       f"computing the response, the critical impulse and the equal-instability speed, with "
                       f"their ranges, for {literal(chair.name)}...")
        self.submit(lambda: nonlinear_view(chair, model, speed, push), self.show, self.failed)

    def failed(self, exc: BaseException) -> None:
        """Show why the nonlinear measures could not be computed (one line).

        Parameters
        ----------
        exc : BaseException
        """
        show_busy(self.busy, False)
        self.texts.set(self.status, f"error: could not compute the nonlinear measures for this chair: {literal(exc)}")

    def show(self, nv: NonlinearView) -> None:
        """Draw a computed result (and its warnings).

        Parameters
        ----------
        nv : NonlinearView
        """
        show_busy(self.busy, False)
        self.src.data = {"t": nv.t, "r": nv.yaw_rate}
        keep = nv.linear_t <= (nv.t[-1] if len(nv.t) else D.HORIZON_S)     # the simulator's span (it may stop early)
        self.lin_src.data = {"t": nv.linear_t[keep], "r": nv.linear_yaw_rate[keep]}
        # the nonlinear run and the criterion in view; the linear response may leave it (it grows without bound)
        finite = np.abs(nv.yaw_rate[np.isfinite(nv.yaw_rate)])
        top = max(1.5, 1.3 * float(finite.max()) if finite.size else 1.5)
        self.fig.y_range.update(start=-top, end=top)
        self.fig.x_range.update(start=0.0, end=float(nv.t[-1]) if len(nv.t) else D.HORIZON_S)
        self.fig.title.text = (f"{plots.short_title(nv.chair.name, 40)}, {nv.model} model: yaw rate after the push "
                               "(dashed: |r| = 1 rad/s)")
        self.texts.set(self.warnings, warnings_text(nv.warnings, "the response, the time and the critical impulse "
                                                     "below"))
        self.texts.set(self.text, nonlinear_text(nv))
        self.texts.set(self.status, f"Computed for {literal(nv.chair.name)} ({nv.model} model).")
        self.result.styles = FRESH
