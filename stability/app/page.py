"""The explorer's page: one :class:`Explorer` per browser session, around one :class:`~stability.app.state.AppState`.

An edit goes to the state (checked as ``--set`` is); an accepted one redraws
every linear view at once (:meth:`Explorer.refresh`, what the benchmarks time)
and queues the background work (:mod:`stability.app.jobs`); a refused one
shows the command line's one-line message next to the field and keeps the last
valid chair.  The URL follows the chair.

How an edit reaches the browser quickly:

* **One document change per edit.**  Widget events are queued and run on the
  document's next tick inside :func:`panel.io.hold` (``combine``): every Bokeh
  model an edit changes goes to the browser in one PATCH-DOC message.
* **The latest edit wins.**  Events that arrive before the queue is drained
  (fast typing, a slow machine) are applied to the state in order, and the
  views are computed and drawn once, for the last chair.
* **Data, not models.**  An edit replaces numbers in the figures' existing data
  sources and moves existing annotations; no layout property (size,
  visibility, CSS classes) changes, so the browser does not lay the page out
  again.  Tabs are rendered when shown (``dynamic``): a hidden tab costs
  nothing per edit, and the simulations of the Nonlinear and Trail window
  tabs run only for the tab shown (a tab shown later starts its own).
* **Background work stays in the background**, its old result greyed until
  the new one arrives.

The page marks each settled change with a counter (css class ``page-settled``)
sent last, which the browser tests and the browser benchmark watch.
"""

from __future__ import annotations

import traceback
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
import panel as pn

from stability.app import plots
from stability.app.advice_tab import AdviceTab
from stability.app.assist_tab import AssistTab
from stability.app.compare_tab import CompareTab
from stability.app.downloads import download_buttons, file_names
from stability.app.editor import EDITOR_WIDTH, ERROR_STYLE, Editor
from stability.app.geometry_tab import GeometryTab
from stability.app.jobs import Jobs
from stability.app.markup import literal
from stability.app.nonlinear_tab import NonlinearTab
from stability.app.speed_tab import SpeedTab
from stability.app.state import AppState, error_line
from stability.app.tracking_tab import TrackingTab
from stability.app.trail_tab import TrailTab
from stability.app.views import LinearView, linear_view
from stability.settings import defaults as D

__all__ = ["Explorer", "TAB_NAMES", "BACKGROUND_DELAY_MS"]

#: The tabs, in order.
TAB_NAMES = ("Stability vs speed", "Geometry", "Nonlinear", "Trail window", "Advice", "Compare",
             "Power assist", "Tracking", "Downloads")


#: How long after an edit the background work starts, ms: the edit's answer reaches the browser and is painted
#: first (the simulator's batch kernel runs on every core and would otherwise compete with it), and a burst of
#: edits starts the work once.
BACKGROUND_DELAY_MS = 300


def _held(fn: Callable[..., Any], *args: Any) -> None:
    """Run ``fn(*args)`` with the session's document held: its model changes leave as one message."""
    from panel.io import hold

    with hold():
        fn(*args)


class Explorer:
    """One session's page.

    Parameters
    ----------
    query : str or mapping, optional
        The URL query the page was opened with (restores the chair it describes).
    deliver : callable, optional
        How widget events and background results reach the page: the Bokeh document's
        ``add_next_tick_callback`` in a served session; default: at once (tests).
    location : panel.io.location.Location, optional
        The session's URL, updated after each accepted change.
    auto_nonlinear : bool
        Queue the nonlinear measures and the trail window after each change (default True).
    later : callable, optional
        ``later(fn, ms)`` runs ``fn()`` after ``ms`` milliseconds where the session may change its page: the
        document's ``add_timeout_callback`` in a served session; default: at once (tests).

    Attributes
    ----------
    state : AppState
    view : LinearView or None
        The linear view of the chair shown.
    layout : panel layout
        The page.
    """

    def __init__(self, query: Any = None, deliver: Callable[[Callable[[], None]], Any] | None = None,
                 location: Any = None, auto_nonlinear: bool = True,
                 later: Callable[[Callable[[], None], int], Any] | None = None) -> None:
        self.state = AppState.from_query(query) if query else AppState()
        self._deliver = deliver or (lambda fn: fn())
        self._later = later or (lambda fn, ms: fn())
        self.jobs = Jobs(lambda fn: self._deliver(partial(_held, fn)))
        self.location = location
        self.auto_nonlinear = auto_nonlinear
        self.view: LinearView | None = None
        self._view_errors: dict[str, str] = {}
        self._building = True
        self._queue: list[Callable[[], None]] = []
        self._draining = self._scheduled = self._dirty = False
        self._settled = 0
        self._stale: set[str] = set()       # background results (tab names) for an older chair, not yet restarted
        self._started: dict[str, int] = {}  # tab name -> the chair generation its background work was started for
        self._build()
        self._building = False
        self.refresh()
        if location is not None:
            # the browser reports its own address when it connects (it may still carry a dropped part of the
            # link, and it may arrive after the page's onload): whenever the address differs from the chair
            # shown, it is rewritten
            location.param.watch(lambda e: self._deliver(partial(_held, self.sync_location)), "search")

    # ------------------------------------------------------------------ building
    def _build(self) -> None:
        on = self._on
        self.editor = Editor(self.state)
        ed = self.editor
        ed.preset.param.watch(on(self._set_preset), "value")
        ed.model.param.watch(on(self._set_model), "value")
        ed.undo_button.on_click(on(lambda e: self._after(None if self.state.undo() else "nothing to undo")))
        ed.reset_button.on_click(on(lambda e: self._after(None if self.state.reset() else "nothing to reset")))
        ed.pin_button.on_click(on(lambda e: self._pin()))
        ed.upload.param.watch(on(lambda e: self._after(self.state.load_toml(
            e.new, ed.upload.filename or "chair.toml")) if e.new else None), "value")
        ed.upload_unc.param.watch(on(self._load_uncertainty), "value")
        ed.watch(lambda name, e: on(partial(self._field_event, name))(e))
        self.message = pn.pane.HTML("", css_classes=["app-message"], styles=ERROR_STYLE, sizing_mode="stretch_width")
        self.title, title_pane = plots.text_div("chair-title")
        # how many times the page has settled after a change (sent last, so a browser can tell the page is done)
        self.settled, settled_pane = plots.text_div("page-settled", "0", width=1, height=1, margin=0,
                                                    sizing_mode="fixed", styles={"overflow": "hidden",
                                                                                 "opacity": "0"})
        self.speed_tab = SpeedTab()
        self.speed_tab.speed.param.watch(on(lambda e: self._show_shape()), "value_throttled")
        self.geometry = GeometryTab()
        self.nonlinear = NonlinearTab(self.jobs.submit, on, lambda: (self.state.chair, self.state.model))
        self.trail = TrailTab(self.jobs.submit, on)
        self.compare = CompareTab(self.jobs.submit)
        self.compare.unpin_button.on_click(on(lambda e: self._unpin()))
        self.assist = AssistTab(self.jobs.submit, on, lambda: (self.state.chair, self.state.model))
        self.advice = AdviceTab(self.jobs.submit, on, lambda: self.state.chair, self.apply_fields,
                                lambda: self.state.user)
        self.tracking = TrackingTab(on, self._measured, self._meaning)
        self.downloads = download_buttons(self.state, self._view)
        self.tabs = pn.Tabs(*zip(TAB_NAMES, (
            self.speed_tab.panel, self.geometry.panel, self.nonlinear.panel, self.trail.panel, self.advice.panel,
            self.compare.panel, self.assist.panel, self.tracking.panel,
            pn.Column(pn.pane.Markdown("Files named after the chair; the results JSON is exactly what "
                                       "`python -m stability.critical_speed --chair FILE --json` prints.",
                                       sizing_mode="stretch_width"),
                      *self.downloads.values(), sizing_mode="stretch_width")), strict=True),
            dynamic=True, sizing_mode="stretch_width", css_classes=["views"], min_width=560,
            stylesheets=[".bk-tab { padding: 4px 9px; }"])
        self._texts = [self.speed_tab.texts, self.geometry.texts, self.nonlinear.texts, self.trail.texts,
                       self.advice.texts, self.compare.texts, self.assist.texts, None, None]
        self.tabs.param.watch(on(self._tab_shown), "active")
        header = pn.Column(pn.Row(pn.pane.Markdown("### stability explorer", margin=(0, 10), width=EDITOR_WIDTH - 20),
                                  title_pane, sizing_mode="stretch_width"),
                           self.message, settled_pane, sizing_mode="stretch_width")
        views = pn.Column(self.tabs, sizing_mode="stretch_width", min_width=560, css_classes=["views-column"])
        self.layout = pn.Column(header, pn.Row(self.editor.panel(self.geometry.sketch), views,
                                               sizing_mode="stretch_width"),
                                sizing_mode="stretch_width", min_width=EDITOR_WIDTH + 560)

    # ------------------------------------------------------------------ events
    def _on(self, handler: Callable[[Any], Any]) -> Callable[[Any], None]:
        """A widget callback that queues ``handler(event)``; the queue is drained on the document's next tick
        (which holds its lock) with the document held, so everything it changes leaves as one message, and the
        views are drawn once for the latest chair.  Events caused by the page's own updates are ignored."""
        def callback(event: Any) -> None:
            if self._building or self.editor.syncing:
                return
            self._queue.append(partial(handler, event))
            if not self._scheduled:
                self._scheduled = True
                self._deliver(partial(_held, self._drain))
        return callback

    def _drain(self) -> None:
        """Apply every queued event in order, then draw once."""
        self._scheduled = False
        queue, self._queue = self._queue, []
        self._draining, self._dirty = True, False
        try:
            for fn in queue:
                fn()
        finally:
            self._draining = False
        if self._dirty:
            self.refresh()
        else:
            self._show_messages()

    def _field_event(self, name: str, event: Any) -> None:
        self.edit(name, "" if event.new is None else str(event.new))

    def edit(self, name: str, text: str) -> str | None:
        """Apply one field edit (as the page does when a field changes); returns the message or None.

        Parameters
        ----------
        name : str
        text : str

        Returns
        -------
        str or None
        """
        msg = self.state.set_field(name, text)
        self._after(msg)
        return msg

    def apply_fields(self, texts: dict[str, str]) -> str | None:
        """Set several fields as one edit (a recommendation); returns the message or None.

        Parameters
        ----------
        texts : dict
            Field -> value text.

        Returns
        -------
        str or None
        """
        msg = self.state.set_fields(texts)
        self._after(msg)
        return msg

    def _after(self, msg: str | None) -> None:
        """After a change to the state: redraw (now, or once the queue is drained) or show the message."""
        if self._building:
            return
        if self._draining:
            self._dirty = self._dirty or msg is None
        elif msg is None:
            self.refresh()
        else:
            self._show_messages()

    def _tab_shown(self, event: Any) -> None:
        """A tab was shown: its text panes get the texts that waited while it was hidden
        (:class:`stability.app.tabtext.TabText`)."""
        for i, texts in enumerate(self._texts):
            if texts is not None:
                texts.shown = i == self.tabs.active
        texts = self._texts[self.tabs.active]
        if texts is not None:
            texts.flush()
        if self.view is not None:
            self._start_shown()

    def _set_model(self, event: Any) -> None:
        self.state.set_model(event.new)
        self._after(None)

    def _set_preset(self, event: Any) -> None:
        if event.new != self.state.current.base:           # the uploaded file's own entry: nothing to do
            self._after(self.state.select_preset(event.new))

    def _pin(self) -> None:
        self.state.pin()
        self._guarded("compare", self._show_compare)
        self._show_messages()

    def _unpin(self) -> None:
        k = self.compare.selected()
        if k is not None:
            self.state.unpin(k)
        self._guarded("compare", self._show_compare)

    def _load_uncertainty(self, event: Any) -> None:
        if event.new:
            if self.state.load_uncertainty(event.new, self.editor.upload_unc.filename or "uncertainty.toml") is None:
                self.speed_tab.show_band_entry(True)
                self._start_bands()
            self._show_messages()

    def _measured(self, user: dict | None) -> str:
        """The Tracking tab's result: the chair's ``[user]`` table (the TOML download carries it); returns what it
        means for the chair being edited (the human-limited speed of :mod:`stability.driver`, as plain text)."""
        self.state.user = user
        return self._meaning(user)

    def _meaning(self, user: dict | None) -> str:
        """What a measured ``[user]`` table means for the chair and model being edited (plain text); when the
        session's user is another (a chair file loaded since), says which one the other tabs and downloads use."""
        if not user:
            return ""
        from stability.driver import Driver
        from stability.driver.linear import rule_speed
        from stability.driver.text import held_where

        def tau(table: dict) -> float:           # read as the commands and the other tabs read it
            return Driver.from_mapping(table).reaction_time_s

        c = self.state.chair
        where = held_where(*rule_speed(c, tau(user), self.state.model))
        text = (f"With this delay, {c.name} can be held straight {where} (the divergence rule: its divergence rate "
                "reaches 1/tau there; critical_speed --reaction-time gives the delayed loop and the lane limit too).")
        kept = self.state.user
        if kept != user:
            other = (f"its own [user] (reaction_time_s = {tau(kept):g} s)" if kept
                     else "no [user] table")
            text += (f" The chair file loaded since carries {other}, which the other tabs and the downloads use; "
                     "the next trial keeps this result with the chair again.")
        return text

    def _view(self) -> LinearView:
        assert self.view is not None
        return self.view

    # ------------------------------------------------------------------ drawing
    def refresh(self) -> None:
        """Redraw every linear view for the current chair (and queue the background work).

        A chair whose linear analysis fails is not kept (the edit is undone and the message shown), so every
        view always describes one chair; a view that fails to draw shows its one-line error in the page and
        leaves the others and the next edit working.
        """
        self.jobs.cancel()
        try:
            v = linear_view(self.state.chair, self.state.model)
        except Exception as exc:       # noqa: BLE001 - any failure of the analysis is the chair's, shown in the page
            traceback.print_exc()
            undone = self.view is not None and self.state.undo()
            self.state.errors["chair"] = (f"{error_line(exc)} (linear analysis of this chair; "
                                          + ("the edit was undone)" if undone else "no view can be drawn)"))
            self._guarded("fields", partial(self.editor.sync, self.state))
            self._show_messages()
            return
        self.view = v
        self._view_errors.clear()
        chair, model = self.state.chair, self.state.model
        self.sync_location()
        self._guarded("fields", partial(self.editor.sync, self.state))
        self._guarded("stability", partial(self.speed_tab.show, v, self.state.uncertainty is not None))
        self._guarded("geometry", partial(self.geometry.show, chair, v))
        self._guarded("mode shape", self._show_shape)
        self._guarded("compare", self._show_compare)
        self._guarded("advice", partial(self.advice.chair_changed, chair))
        self._guarded("assist", partial(self.assist.chair_changed, chair, model))
        self._guarded("tracking", self.tracking.chair_changed)
        self._guarded("downloads", self._name_downloads)
        if self.state.uncertainty is not None:
            self.speed_tab.show_band([], [], [])
        self._later(partial(_held, partial(self._start_background, self.jobs.generation)), BACKGROUND_DELAY_MS)
        self._show_messages()

    def _start_background(self, generation: int) -> None:
        """Queue the background work of the chair drawn at ``generation`` (nothing if the chair changed since)."""
        if generation != self.jobs.generation:
            return
        if self.state.uncertainty is not None:
            self._start_bands()
        if self.auto_nonlinear:
            # only the tab shown: a hidden tab's simulations would take both cores from the next edit's answer
            # for a result nobody looks at; a tab shown later starts its own (:meth:`_tab_shown`)
            self._stale = {k for k in ("nonlinear", "trail") if self._started.get(k) != generation}
            self._start_shown()

    def _start_shown(self) -> None:
        """Start the background work of the tab shown, if its result is for an older chair."""
        name = {TAB_NAMES.index("Nonlinear"): "nonlinear", TAB_NAMES.index("Trail window"): "trail"}.get(
            self.tabs.active)
        if name in self._stale:
            self._stale.discard(name)
            self._started[name] = self.jobs.generation
            tab = self.nonlinear if name == "nonlinear" else self.trail
            tab.start(self.state.chair, self.state.model)

    def sync_location(self) -> None:
        """Set the address bar's query to the chair shown (the page calls it again once the browser is connected:
        Panel's location takes the browser's own URL when it connects, which may still carry a dropped part)."""
        if self.location is not None:
            want = "?" + self.state.url_query()
            if self.location.search != want:
                self.location.search = want

    def _guarded(self, name: str, step: Callable[[], Any]) -> None:
        """Run one view's update; a failure becomes that view's one-line message (the traceback goes to the
        server's log)."""
        try:
            step()
        except Exception as exc:       # noqa: BLE001 - one view's failure must not stop the others
            traceback.print_exc()
            self._view_errors[name] = f"error: the {name} view could not be drawn for this chair: " + \
                error_line(exc).removeprefix("error: ")

    def _show_messages(self) -> None:
        errs = self.state.errors
        self.editor.show_errors(errs, literal)
        other = "<br>".join(literal(m) for k, m in [*errs.items(), *self._view_errors.items()]
                            if k not in self.editor.field_errors)
        if self.message.object != other:
            self.message.object = other
        c = self.state.current
        title = (f"<b>{literal(c.chair.name)}</b> ({c.chair.caster_position} casters; base {literal(c.base)}; "
                 f"{self.state.model} model)" + (f"; uncertainty file {literal(self.state.uncertainty_name)}"
                                                  if self.state.uncertainty is not None else ""))
        if self.title.text != title:
            self.title.text = title
        self._settled += 1
        self.settled.text = str(self._settled)

    def _show_shape(self) -> None:
        if self.view is not None:
            self.speed_tab.show_shape(self.view, float(self.speed_tab.speed.value or D.SPEED))

    def _show_compare(self) -> None:
        self.compare.show(self._view(), self.state.pinned, self.state.model, self.state.user)

    def _name_downloads(self) -> None:
        names = file_names(self.state.chair.name)
        for kind, button in self.downloads.items():
            if button.filename != names[kind]:
                button.filename = names[kind]

    # ------------------------------------------------------------------ background work
    def start_nonlinear(self) -> None:
        """Queue the yaw-rate response, the critical impulse and the equal-instability speed for this chair."""
        self.nonlinear.start(self.state.chair, self.state.model)

    def _start_bands(self) -> None:
        from stability.linear.intervals import linear_intervals

        chair, model, unc = self.state.chair, self.state.model, self.state.uncertainty
        speeds = np.geomspace(0.05, D.MAX_SPEED, 40)

        def work():
            return linear_intervals(chair, unc, model=model, speeds=speeds, samples=300, seed=0)

        def show(iv):
            self.speed_tab.show_band(speeds, [a for a, _ in iv.rate], [b for _, b in iv.rate])

        self.jobs.submit(work, show, self._band_failed)

    def _band_failed(self, exc: BaseException) -> None:
        self._view_errors["uncertainty band"] = ("error: the 95 % interval could not be computed for this chair: "
                                                 + error_line(exc).removeprefix("error: "))
        self._show_messages()
