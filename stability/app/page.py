"""The explorer's page: Panel widgets and Bokeh figures around one :class:`~stability.app.state.AppState`.

:class:`Explorer` is one browser session.  An edit goes to the state (checked
as ``--set`` is); an accepted one redraws every linear view at once
(:meth:`Explorer.refresh`, what the benchmark times) and queues the nonlinear
measures in the background (:mod:`stability.app.jobs`); a refused one shows the
command line's one-line message next to the field and keeps the last valid
chair.  The URL follows the chair.
"""

from __future__ import annotations

import traceback
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource
from bokeh.models.annotations import LegendItem

from stability import chair as chair_mod
from stability import tires
from stability.app import plots
from stability.app.advice_tab import AdviceTab
from stability.app.assist_tab import AssistTab
from stability.app.jobs import Jobs, warm_up_done
from stability.app.markup import literal, pre
from stability.app.state import AppState, error_line
from stability.app.text import downloads, field_rows, geometry_text, summary_text
from stability.app.trail_tab import TrailTab
from stability.app.views import LinearView, geometry_points, linear_view, mode_shape, nonlinear_view
from stability.plotting.style import OKABE_ITO, UNSTABLE
from stability.settings import defaults as D

__all__ = ["Explorer"]

_NOTHING_PINNED = "Nothing pinned yet: pin the current chair, change it, and compare."
_ERROR_STYLE = {"color": UNSTABLE, "font-size": "12px"}


class Explorer:
    """One session's page.

    Parameters
    ----------
    query : str or mapping, optional
        The URL query the page was opened with (restores the chair it describes).
    deliver : callable, optional
        How background results reach the page: the Bokeh document's ``add_next_tick_callback``
        in a served session; default: at once (tests).
    location : panel.io.location.Location, optional
        The session's URL, updated after each accepted change.
    auto_nonlinear : bool
        Queue the nonlinear measures and the trail window after each change (default True).
    """

    def __init__(self, query: Any = None, deliver: Callable[[Callable[[], None]], Any] | None = None,
                 location: Any = None, auto_nonlinear: bool = True) -> None:
        self.state = AppState.from_query(query) if query else AppState()
        self._deliver = deliver or (lambda fn: fn())
        self.jobs = Jobs(self._deliver)
        self.location = location
        self.auto_nonlinear = auto_nonlinear
        self.view: LinearView | None = None
        self._pinned_curves: tuple[Any, list] = (None, [])
        self._view_errors: dict[str, str] = {}
        self._building = True
        self._widgets()
        self._figures()
        self.layout = self._layout()
        self._building = False
        self.refresh()

    # ------------------------------------------------------------------ widgets
    def _widgets(self) -> None:
        s = self.state
        presets = list(chair_mod.preset_names())
        self.preset = pn.widgets.Select(name="preset", options=presets,
                                        value=s.current.base if s.current.base in presets else presets[0],
                                        css_classes=["preset"], width=200)
        self.preset.param.watch(self._on(lambda e: self._after(self.state.select_preset(e.new))), "value")
        self.model = pn.widgets.Select(name="model", options=["exact", "thesis"], value=s.model, width=110,
                                       css_classes=["model"])
        self.model.param.watch(self._on(self._set_model), "value")
        self.undo_button = pn.widgets.Button(name="undo", button_type="default", width=80, css_classes=["undo"])
        self.undo_button.on_click(self._on(lambda e: self._after(None if self.state.undo() else "nothing to undo")))
        self.pin_button = pn.widgets.Button(name="pin for compare", width=140, css_classes=["pin"])
        self.pin_button.on_click(self._on(lambda e: self._pin()))
        self.upload = pn.widgets.FileInput(accept=".toml", css_classes=["upload-chair"], width=260)
        self.upload.param.watch(self._on(lambda e: self._after(self.state.load_toml(
            e.new, self.upload.filename or "chair.toml")) if e.new else None), "value")
        self.upload_unc = pn.widgets.FileInput(accept=".toml", css_classes=["upload-uncertainty"], width=260)
        self.upload_unc.param.watch(self._on(self._load_uncertainty), "value")
        self.message = pn.pane.HTML("", css_classes=["app-message"], styles=_ERROR_STYLE, sizing_mode="stretch_width")
        self.title = pn.pane.Markdown("", css_classes=["chair-title"], sizing_mode="stretch_width")
        # how many times the page has settled after a change (sent last, so a browser can tell the page is done)
        self.settled = pn.pane.HTML("0", css_classes=["page-settled"], width=1, height=1, margin=0,
                                    styles={"overflow": "hidden", "opacity": "0"})
        self._settled = 0
        self.inputs: dict[str, Any] = {}
        self.field_errors: dict[str, Any] = {}
        tire_names = list(tires.names())
        for row in field_rows():
            name, unit = row["name"], row["unit"]
            label = f"{name} ({unit})" if unit != "-" else name
            tip = row["doc"] + (f"; valid range {row['range']}" if row["range"] else "")
            w: Any
            if name == "caster_position":
                w = pn.widgets.Select(name=label, options=["rear", "front"], description=tip)
            elif name in ("main_tire", "caster_tire"):
                w = pn.widgets.Select(name=label, options=tire_names, description=tip)
            else:
                w = pn.widgets.TextInput(name=label, description=tip, placeholder=row["range"])
            w.css_classes = [f"field-{name}"]
            w.width = 210
            w.param.watch(self._on(partial(self._field_event, name)), "value")
            self.inputs[name] = w
            self.field_errors[name] = pn.pane.HTML("", visible=False, styles=_ERROR_STYLE, width=220,
                                                   css_classes=[f"error-{name}"])
        self.speed = pn.widgets.FloatSlider(name="speed U (m/s) for the mode shape", start=0.05, end=3.0, step=0.01,
                                            value=D.SPEED, css_classes=["speed"], sizing_mode="stretch_width")
        self.speed.param.watch(self._on(lambda e: self._show_shape()), "value_throttled")
        self.summary = pn.pane.Markdown("", css_classes=["summary"], sizing_mode="stretch_width")
        self.shape_text = pn.pane.Markdown("", css_classes=["shape-text"], sizing_mode="stretch_width")
        self.loads = pn.pane.Markdown("", sizing_mode="stretch_width")
        # nonlinear
        self.push_force = pn.widgets.FloatInput(name="push force (N)", value=D.PUSH_FORCE, start=0.0, end=1000.0,
                                                width=140)
        self.push_duration = pn.widgets.FloatInput(name="push duration (s)", value=D.PUSH_DURATION, start=0.001,
                                                   end=2.0, width=140)
        self.push_speed = pn.widgets.FloatInput(name="speed (m/s)", value=D.SPEED, start=0.05, end=3.0, width=120)
        self.run_button = pn.widgets.Button(name="compute", button_type="primary", width=100,
                                            css_classes=["run-nonlinear"])
        self.run_button.on_click(self._on(lambda e: self.start_nonlinear()))
        self.progress = pn.indicators.Progress(active=False, value=0, max=100, width=300, bar_color="primary",
                                               visible=False, css_classes=["progress"])
        self.nl_text = pn.pane.Markdown("", css_classes=["nonlinear-text"], sizing_mode="stretch_width")
        self.trail = TrailTab(self.jobs.submit, self._on)
        self.assist = AssistTab(self.jobs.submit, self._on, lambda: (self.state.chair, self.state.model))
        self.advice = AdviceTab(self.jobs.submit, self._on, lambda: self.state.chair, self.apply_fields)
        self.compare_text = pn.pane.Markdown("", css_classes=["compare-text"], sizing_mode="stretch_width")
        self.unpin = pn.widgets.Select(name="unpin", options=[], width=260)
        self.unpin_button = pn.widgets.Button(name="unpin", width=80)
        self.unpin_button.on_click(self._on(lambda e: self._unpin()))
        self.downloads = downloads(self.state, self._view)

    # ------------------------------------------------------------------ figures
    def _figures(self) -> None:
        self.branch_src = [ColumnDataSource({"speed": [], "real": [], "imag": [], "name": []})
                           for _ in range(plots.MAX_BRANCHES)]
        self.bands_src = ColumnDataSource({"left": [], "right": [], "colour": []})
        self.unc_src = ColumnDataSource({"speed": [], "low": [], "high": []})
        self.speed_figs = plots.speed_figures(self.branch_src, self.bands_src, self.unc_src)
        self.shape_src = ColumnDataSource({"component": [], "magnitude": [], "phase": [], "colour": []})
        self.shape_fig = plots.shape_figure(self.shape_src)
        self.geo_src = {k: ColumnDataSource({"x": [], "y": []}) for k in ("cg", "main", "pins", "casters", "outline")}
        for k in ("trail", "push"):
            self.geo_src[k] = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": []})
        self.geo_src["tip"] = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "label": []})
        self.side_src = {"cg": ColumnDataSource({"x": [], "y": []}), "contacts": ColumnDataSource({"x": [], "y": []}),
                         "pins": ColumnDataSource({"x": [], "y": []}),
                         "tip": ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "label": []})}
        self.top_fig = plots.top_view(self.geo_src)
        self.side_fig = plots.side_view(self.side_src)
        self.resp_src = ColumnDataSource({"t": [], "r": []})
        self.resp_lin_src = ColumnDataSource({"t": [], "r": []})
        self.resp_fig = plots.response_figure(self.resp_src, self.resp_lin_src)
        self.cmp_src = [ColumnDataSource({"speed": [], "rate": [], "name": []}) for _ in range(4)]
        self.cmp_fig = plots.compare_figure(self.cmp_src)

    def _layout(self) -> Any:
        rows = []
        for name, w in self.inputs.items():
            rows.append(pn.Column(w, self.field_errors[name], margin=0))
        editor = pn.Column(
            pn.pane.Markdown("### Chair\nEvery field in SI units; hover a field for its meaning and valid range. "
                             "Press Enter (or leave the field) to apply."),
            pn.Row(self.preset, self.model), pn.Row(self.undo_button, self.pin_button),
            pn.pane.Markdown("chair file (TOML):"), self.upload,
            pn.pane.Markdown("uncertainty file (TOML):"), self.upload_unc,
            pn.GridBox(*rows, ncols=2), width=470, scroll=True, height=1100)
        f = self.speed_figs
        stability_tab = pn.Column(self.summary, self.speed, pn.pane.Bokeh(f["real"], sizing_mode="stretch_width"),
                                  pn.pane.Bokeh(f["imag"], sizing_mode="stretch_width"),
                                  pn.Row(pn.pane.Bokeh(self.shape_fig, sizing_mode="stretch_width"), self.shape_text),
                                  sizing_mode="stretch_width")
        geometry_tab = pn.Column(pn.pane.Bokeh(self.top_fig, sizing_mode="stretch_width"),
                                 pn.pane.Bokeh(self.side_fig, sizing_mode="stretch_width"), self.loads,
                                 sizing_mode="stretch_width")
        nonlinear_tab = pn.Column(
            pn.pane.Markdown("Simulated with the compiled WCHAIR scheme in the background; a chair change cancels "
                             "the runs for the old chair. The linear views never wait for them."),
            pn.Row(self.push_force, self.push_duration, self.push_speed, self.run_button), self.progress,
            self.nl_text, pn.pane.Bokeh(self.resp_fig, sizing_mode="stretch_width"), sizing_mode="stretch_width")
        compare_tab = pn.Column(
            pn.pane.Markdown("Pin up to three chairs (button under the presets); their curves are overlaid on the "
                             "current chair's and the table says which parameter causes each difference."),
            pn.Row(self.unpin, self.unpin_button), pn.pane.Bokeh(self.cmp_fig, sizing_mode="stretch_width"),
            self.compare_text, sizing_mode="stretch_width")
        self.tabs = pn.Tabs(("Stability vs speed", stability_tab), ("Geometry", geometry_tab),
                            ("Nonlinear response", nonlinear_tab), ("Trail window", self.trail.panel),
                            ("Advice", self.advice.panel),
                            ("Compare", compare_tab), ("Power-chair assist", self.assist.panel),
                            ("Downloads", pn.Column(self.downloads)), dynamic=False, sizing_mode="stretch_width")
        header = pn.Column(pn.pane.Markdown("## stability explorer: directional stability of a wheelchair"),
                           self.title, self.message, self.settled, sizing_mode="stretch_width")
        return pn.Column(header, pn.Row(editor, self.tabs, sizing_mode="stretch_width"), sizing_mode="stretch_width")

    # ------------------------------------------------------------------ events
    _syncing = False

    def _on(self, handler: Callable[[Any], Any]) -> Callable[[Any], None]:
        """A widget callback that runs ``handler(event)`` where Bokeh models may change (the document's next
        tick, which holds its lock); events caused by the page's own updates are ignored."""
        def callback(event: Any) -> None:
            if not (self._building or self._syncing):
                self._deliver(partial(handler, event))
        return callback

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
        self._after(msg, refresh=msg is None)
        return msg

    def apply_fields(self, texts: dict[str, str]) -> str | None:
        """Set several fields as one edit (a recommendation); returns the message or None."""
        msg = self.state.set_fields(texts)
        self._after(msg, refresh=msg is None)
        return msg

    def _after(self, msg: str | None, refresh: bool = True) -> None:
        if self._building:
            return
        if refresh and msg is None:
            self.refresh()
        else:
            self._show_messages()

    def _set_model(self, event: Any) -> None:
        self.state._history.append(self.state.current)
        self.state.model = event.new
        self.refresh()

    def _pin(self) -> None:
        self.state.pin()
        self._show_compare()
        self._show_messages()

    def _unpin(self) -> None:
        if self.unpin.value in self.unpin.options:
            self.state.unpin(list(self.unpin.options).index(self.unpin.value))
        self._show_compare()

    def _load_uncertainty(self, event: Any) -> None:
        if event.new:
            if self.state.load_uncertainty(event.new, self.upload_unc.filename or "uncertainty.toml") is None:
                self._start_bands()
            self._show_messages()

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
            self._guarded("fields", self._sync_inputs)
            self._show_messages()
            return
        self.view = v
        self._view_errors.clear()
        self.sync_location()
        self._guarded("fields", self._sync_inputs)
        self._guarded("stability", partial(self._show_linear, v))
        self._guarded("geometry", self._show_geometry)
        self._guarded("mode shape", self._show_shape)
        self._guarded("compare", self._show_compare)
        self._guarded("advice", partial(self.advice.chair_changed, self.state.chair))
        self.unc_src.data = {"speed": [], "low": [], "high": []}
        if self.state.uncertainty is not None:
            self._start_bands()
        if self.auto_nonlinear:
            self.start_nonlinear()
            self.trail.start(self.state.chair, self.state.model)
        self._show_messages()

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

    def _sync_inputs(self) -> None:
        self._syncing = True
        try:
            for name, w in self.inputs.items():
                text = self.state.value_text(name)
                if isinstance(w, pn.widgets.Select) and text not in w.options:
                    w.options = [*w.options, text]
                if w.value != text:
                    w.value = text
            if self.state.current.base in self.preset.options and self.preset.value != self.state.current.base:
                self.preset.value = self.state.current.base
            if self.model.value != self.state.model:
                self.model.value = self.state.model
        finally:
            self._syncing = False

    def _show_messages(self) -> None:
        errs = self.state.errors
        for name, pane in self.field_errors.items():
            msg = literal(errs.get(name, ""))
            if pane.object != msg:
                pane.param.update(object=msg, visible=bool(msg))
        other = "<br>".join(literal(m) for k, m in [*errs.items(), *self._view_errors.items()]
                            if k not in self.field_errors)
        if self.message.object != other:
            self.message.object = other
        c = self.state.current
        title = (f"**{literal(c.chair.name)}** ({c.chair.caster_position} casters; base {literal(c.base)}; "
                 f"{self.state.model} model)" + (f"; uncertainty file {literal(self.state.uncertainty_name)}"
                                                  if self.state.uncertainty is not None else ""))
        if self.title.object != title:
            self.title.object = title
        if self.undo_button.disabled == self.state.can_undo:
            self.undo_button.disabled = not self.state.can_undo
        self._settled += 1
        self.settled.object = str(self._settled)

    def _show_linear(self, v: LinearView) -> None:
        U, eig = v.locus.speeds, v.locus.eigenvalues
        f = self.speed_figs
        renderers = f["branch_renderers"]            # fixed at build time: never read back from the legend
        groups: dict[str, list] = {}                 # one legend entry per mode name, hiding all its branches
        for j, src in enumerate(self.branch_src):
            if j < eig.shape[1]:
                src.data = {"speed": U, "real": eig[:, j].real, "imag": np.abs(eig[:, j].imag),
                            "name": [v.names[j]] * len(U)}
                groups.setdefault(v.names[j], []).append(renderers[j])
            else:
                src.data = {"speed": [], "real": [], "imag": [], "name": []}
        items = [LegendItem(label=name, renderers=rs) for name, rs in groups.items()]
        if self.state.uncertainty is not None:
            items.append(f["band_item"])
        f["legend"].items = items
        hi = max(1.15 * float(eig.real.max()), 0.5)
        lo = -max(3.0 * hi, 10.0)
        f["real"].y_range.start, f["real"].y_range.end = lo, hi
        shown = np.any(eig.real >= lo, axis=0)
        top = float(np.abs(eig.imag[:, shown]).max()) if shown.any() else 1.0
        f["imag"].y_range.start, f["imag"].y_range.end = 0.0, max(1.15 * top, 1.0)
        left, right, colour = [], [], []
        for kind, ranges in (("stable", v.stable_intervals()), ("unstable", v.locus.unstable_intervals())):
            for a, b in ranges:
                left.append(a)
                right.append(b)
                colour.append(plots.STABLE if kind == "stable" else UNSTABLE)
        self.bands_src.data = {"left": left, "right": right, "colour": colour}
        cr = v.free_crossings[:plots.MAX_CROSSINGS]
        n = plots.MAX_CROSSINGS
        for i, span in enumerate(f["crossings"]):
            k = i % n
            span.visible = k < len(cr)
            if k < len(cr):
                span.location = cr[k].speed
        for k, lab in enumerate(f["crossing_labels"]):
            lab.visible = k < len(cr)
            if k < len(cr):
                lab.x, lab.y, lab.text = cr[k].speed, 0.0, f"critical {cr[k].speed:.4g} m/s"
        self.summary.object = summary_text(v)

    def _show_shape(self) -> None:
        v = self.view
        if v is None:
            return
        sh = mode_shape(v, float(self.speed.value or D.SPEED))
        for span in self.speed_figs["cursor"]:
            span.location = sh.speed
        self.shape_src.data = {"component": list(sh.components), "magnitude": list(sh.magnitude),
                               "phase": [f"{p:+.0f}°" for p in sh.phase_deg],
                               "colour": [OKABE_ITO[i] for i in range(len(sh.components))]}
        lam = sh.eigenvalue
        t2 = f"; a heading error doubles every {np.log(2) / lam.real:.3g} s" if lam.real > 0 else ""
        shares = ", ".join(f"{k} {100 * x:.0f} %" for k, x in sh.shares.items())
        self.shape_text.object = (f"**At {sh.speed:.3g} m/s** the least stable mode is *{sh.name}*: eigenvalue "
                                  f"{lam.real:.4f} {'+' if lam.imag >= 0 else '-'} {abs(lam.imag):.3g}j 1/s{t2}."
                                  f"\n\nShares of its motion: {shares}. Phases are relative to the largest component.")

    def _show_geometry(self) -> None:
        c = self.state.chair
        pts = geometry_points(c)

        def xy(key: str) -> dict:
            x, y = pts[key]
            return {"x": x, "y": -y}      # plotted with the chair's left up

        for k in ("cg", "main", "pins", "casters"):
            self.geo_src[k].data = xy(k)
        mx, my = pts["main"]
        cx, cy = pts["casters"]
        self.geo_src["outline"].data = {"x": [mx[0], mx[1], cx[1], cx[0]], "y": [-my[0], -my[1], -cy[1], -cy[0]]}
        px, py = pts["pins"]
        self.geo_src["trail"].data = {"x0": px, "y0": -py, "x1": cx, "y1": -cy}
        self.geo_src["push"].data = {"x0": [0.0], "y0": [0.0], "x1": [0.0], "y1": [-0.15]}
        self.side_src["cg"].data = {"x": [0.0], "y": [c.h]}
        self.side_src["contacts"].data = {"x": [mx[0], cx[0]], "y": [0.0, 0.0]}
        self.side_src["pins"].data = {"x": [px[0]], "y": [0.0]}
        tip = self._view().tip
        rays = {k: (ln.distance_m * ln.normal[0], ln.distance_m * ln.normal[1], ln.angle_deg)
                for k, ln in tip.lines.items()}
        self.geo_src["tip"].data = {"x0": [0.0] * 4, "y0": [0.0] * 4, "x1": [r[0] for r in rays.values()],
                                    "y1": [-r[1] for r in rays.values()],
                                    "label": [f"{r[2]:.1f}°" for r in rays.values()]}
        fwd = [rays["toward_main_wheels"], rays["toward_casters"]]
        self.side_src["tip"].data = {"x0": [0.0, 0.0], "y0": [c.h, c.h], "x1": [r[0] for r in fwd], "y1": [0.0, 0.0],
                                     "label": [f"{r[2]:.1f}°" for r in fwd]}
        self.loads.object = geometry_text(c, self._view())

    # ------------------------------------------------------------------ background work
    def start_nonlinear(self) -> None:
        """Queue the yaw-rate response, the critical impulse and the equal-instability speed for this chair."""
        chair, model = self.state.chair, self.state.model
        push = (float(self.push_force.value or 0.0), float(self.push_duration.value or 0.1))
        speed = float(self.push_speed.value or D.SPEED)
        self.progress.visible, self.progress.active = True, True
        self.nl_text.object = ("computing (compiling the simulator first, once per start)..." if not warm_up_done()
                               else "computing the response, the critical impulse and the equal-instability speed...")
        self.jobs.submit(lambda: nonlinear_view(chair, model, speed, push), self._show_nonlinear, self._failed)

    def _failed(self, exc: BaseException) -> None:
        self.progress.visible, self.progress.active = False, False
        self.nl_text.object = f"error: could not compute the nonlinear measures for this chair: {literal(exc)}"

    def _show_nonlinear(self, nv: Any) -> None:
        self.progress.visible, self.progress.active = False, False
        self.resp_src.data = {"t": nv.t, "r": nv.yaw_rate}
        self.resp_lin_src.data = {"t": nv.linear_t, "r": nv.linear_yaw_rate}
        # the nonlinear run and the criterion in view; the linear response may leave it (it grows without bound)
        top = max(1.5, 1.3 * float(np.max(np.abs(nv.yaw_rate))))
        self.resp_fig.y_range.start, self.resp_fig.y_range.end = -top, top
        ci = nv.critical_impulse
        eq = nv.equal_instability
        eq_text = "not computed" if eq is None else eq.describe() + (
            f" ({3.6 * float(eq.speed):.3g} km/h)" if eq.status == "found" else "")
        self.nl_text.object = (
            f"**Critical impulse at {nv.speed:g} m/s:** {ci.describe()} "
            f"({ci.push}).\n\n**Equal-instability speed** (as unstable as the E&J Premier at 0.75 m/s after the "
            f"thesis's 40 N / 0.1 s push): {eq_text}.\n\nPush shown: {nv.push[0]:g} N for {nv.push[1]:g} s at the c.g.")

    def _start_bands(self) -> None:
        from stability.linear.intervals import linear_intervals

        chair, model, unc = self.state.chair, self.state.model, self.state.uncertainty
        speeds = np.geomspace(0.05, D.MAX_SPEED, 40)

        def work():
            return speeds, linear_intervals(chair, unc, model=model, speeds=speeds, samples=300, seed=0)

        def show(res):
            sp, iv = res
            self.unc_src.data = {"speed": sp, "low": [a for a, _ in iv.rate], "high": [b for _, b in iv.rate]}

        self.jobs.submit(work, show, self._failed)

    def _show_compare(self) -> None:
        from stability.compare import compare, format_comparison, growth_curves

        v = self._view()
        keep = v.locus.speeds <= 3.0
        speeds = v.locus.speeds[keep]
        pinned = self.state.pinned
        self.unpin.options = [f"{i + 1}: {c.name}" for i, c in enumerate(pinned)]
        key = (self.state.model, tuple(pinned))
        if self._pinned_curves[0] != key:           # pinned chairs' curves: computed when the pins change
            rates: list = list(growth_curves(pinned, self.state.model, [float(x) for x in speeds])) if pinned else []
            self._pinned_curves = (key, rates)
        curves = [v.growth_rate[keep], *self._pinned_curves[1]]
        chairs = [self.state.chair, *pinned]
        for j, src in enumerate(self.cmp_src):
            if j < len(chairs):
                label = ("current: " if j == 0 else f"pinned {j}: ") + chairs[j].name
                src.data = {"speed": speeds, "rate": curves[j], "name": [label] * len(speeds)}
            elif len(src.data["speed"]):
                src.data = {"speed": [], "rate": [], "name": []}
        if pinned:
            labels = ["current", *[f"pinned {i + 1}" for i in range(len(pinned))]]
            model = self.state.model
            self.compare_text.object = "comparing..."
            self.jobs.submit(lambda: format_comparison(compare(chairs, labels=labels, model=model)),
                             lambda text: setattr(self.compare_text, "object", pre(text)),
                             self._failed)
        elif self.compare_text.object != _NOTHING_PINNED:
            self.compare_text.object = _NOTHING_PINNED
