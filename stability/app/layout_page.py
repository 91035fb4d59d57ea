"""The explorer for a wheel layout: ``?chair=mid-wheel-drive`` (any preset of :mod:`stability.layout.presets`).

A layout is a list of wheels (:class:`stability.layout.Layout`), not the short
form's fields, so this page has no field editor: it shows what the layout
commands compute for the preset and draws it from above.

* **Stability vs speed** (drawn at once): every eigenvalue's real part of the
  layout's linear model against signed speed (negative: reverse, casters
  trailing the other way), from :func:`stability.layout.linear.state_matrices`,
  with the critical speeds of :func:`stability.layout.linear.critical_speed`
  marked, and the text ``python -m stability.critical_speed --chair NAME``
  prints (:func:`stability.layout.text.layout_text`, the same call).
* **Geometry**, **Nonlinear**, **Trail window**, **Advice**, **Compare** and
  **Power assist**: the output of the commands ``tipping``, ``study
  critical-impulse`` (forward and in reverse), ``shimmy`` (one table per caster
  row), ``advise``, ``compare`` (against the frame's other drive layouts) and
  ``assist`` for the layout, run in the background when the tab is first shown,
  each headed by its command line.  They run as the commands themselves (a
  child process of the server), so the page shows exactly what a user at the
  command line gets.
* **Downloads**: the layout as a ``[[wheel]]`` chair file (the file to start
  from), the results JSON of ``critical_speed --json`` and the plotted
  eigenvalues as CSV (:func:`stability.app.downloads.layout_buttons`).
* **Tracking** says in one line why it does not apply to a layout.

Nothing here is user text except the URL's other fields, which are named (as
text) in the one-line message that says they were ignored.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable, Mapping
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource, Range1d
from bokeh.models.annotations import Label, LegendItem, Span

from stability.app import plots
from stability.app.editor import EDITOR_WIDTH
from stability.app.jobs import Jobs
from stability.app.markup import literal, pre
from stability.layout.linear import analyse_layout, state_matrices
from stability.layout.model import Layout
from stability.layout.presets import layout_preset, layout_preset_names
from stability.layout.statics import contacts, static_loads
from stability.layout.text import layout_text
from stability.plotting.style import OKABE_ITO, UNSTABLE
from stability.settings import defaults as D

__all__ = ["LayoutExplorer", "layout_in_query", "COMMANDS", "NOT_FOR_LAYOUTS", "SPEEDS", "command_line",
           "run_command"]

#: Signed speeds of the eigenvalue plot, m/s: 60 geometrically spaced from 0.05 to 3 m/s each way.
SPEEDS = np.concatenate([-np.geomspace(0.05, 3.0, 60)[::-1], np.geomspace(0.05, 3.0, 60)])
#: The background tabs: tab name -> the command's arguments after ``python -m`` (``{chair}``: the layout's name).
COMMANDS: dict[str, tuple[str, ...]] = {
    "Geometry": ("stability.tipping", "--chair", "{chair}"),
    "Nonlinear": ("stability.study", "critical-impulse", "--chair", "{chair}", "--speeds=-0.75,0.75"),
    "Trail window": ("stability.shimmy", "--chair", "{chair}"),
    "Advice": ("stability.advise", "--chair", "{chair}"),
    "Compare": ("stability.compare", "{chair}", "{others}"),
    "Power assist": ("stability.assist", "--chair", "{chair}"),
}
#: The one line of each tab that does not apply to a wheel layout.
NOT_FOR_LAYOUTS = {
    "Tracking": "The tracking task measures the driver, not the chair: open it from a short-form chair.",
}
#: Longest a background command may run, s.
COMMAND_TIMEOUT_S = 900


def layout_in_query(query: Mapping[str, Any] | str | None) -> str | None:
    """The layout preset a URL query opens (its ``chair``), or None for a short-form chair.

    Parameters
    ----------
    query : mapping or str or None
        The session's arguments (values: lists of bytes) or a query string.

    Returns
    -------
    str or None
    """
    from stability.app.links import _items

    if not query:
        return None
    chair = _items(query).get("chair")
    return chair if chair in layout_preset_names() else None


def command_line(tab: str, name: str) -> list[str]:
    """The command of a background tab for layout ``name``: ``python -m ...`` arguments.

    Parameters
    ----------
    tab : str
        A key of :data:`COMMANDS`.
    name : str
        A layout preset's name (``{chair}``); ``{others}`` stands for the other layout presets, in order.

    Returns
    -------
    list of str
    """
    others = [n for n in layout_preset_names() if n != name]
    return [b for a in COMMANDS[tab] for b in (others if a == "{others}" else [a.format(chair=name)])]


def run_command(args: list[str]) -> str:
    """Run ``python -m ARGS`` (this package, this interpreter) and return what it prints.

    Parameters
    ----------
    args : list of str

    Returns
    -------
    str
        Its standard output, then its warnings (standard error) if any.

    Raises
    ------
    ValueError
        The command failed (its last line of standard error).
    """
    root = str(Path(__file__).resolve().parents[2])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([root, *filter(None, [os.environ.get("PYTHONPATH")])])}
    done = subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, env=env,
                          timeout=COMMAND_TIMEOUT_S, check=False)
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or [f"exit status {done.returncode}"])[-1]
        raise ValueError(last)
    return done.stdout.rstrip() + (f"\n\n{done.stderr.rstrip()}" if done.stderr.strip() else "")


def _held(fn: Callable[..., Any], *args: Any) -> None:
    from panel.io import hold

    with hold():
        fn(*args)


def top_view(layout: Layout):
    """The layout from above: fixed wheels (filled: driven), caster pins and contacts with their trail, c.g.,
    anti-tip contacts, the support polygon and each contact's static load.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    bokeh.plotting.figure
    """
    p = plots._fig(f"{plots.short_title(layout.name, 30)} from above: loads, N",
                   "x, forward from the c.g. (m)", "lateral, left up (m)", match_aspect=True, height=380)
    pts = contacts(layout)
    loads = static_loads(layout)
    nf = len(layout.wheels)
    wx = [w.x for w in layout.wheels]
    wy = [-w.y for w in layout.wheels]                    # plotted with the chair's left up
    driven = [w.driven for w in layout.wheels]
    px = [c.x for c in layout.casters]
    py = [-c.y for c in layout.casters]
    cx = [x for _, x, _, _ in pts[nf:]]
    # the support polygon: the convex hull of the contacts (ISO 7176-1 tips about its edges)
    from scipy.spatial import ConvexHull

    xy = np.array([[x, -y] for _, x, y, _ in pts])
    hull = xy[ConvexHull(xy).vertices]
    items = [
        ("support polygon", p.patch(list(hull[:, 0]), list(hull[:, 1]), fill_alpha=0.06, fill_color="grey",
                                    line_color="grey", line_dash="dashed")),
        ("trail (pin to contact)", p.segment(px, py, cx, py, line_width=3, color=OKABE_ITO[1])),
        ("drive wheels", p.scatter([x for x, d in zip(wx, driven, strict=True) if d],
                                   [y for y, d in zip(wy, driven, strict=True) if d], size=14, marker="square",
                                   color=OKABE_ITO[0])),
        ("caster pins", p.scatter(px, py, size=8, marker="circle", color=OKABE_ITO[1])),
        ("caster contacts", p.scatter(cx, py, size=10, marker="triangle", color=OKABE_ITO[2])),
        ("c.g.", p.scatter([0.0], [0.0], size=15, marker="circle_cross", color="black", fill_alpha=0)),
    ]
    if not all(driven):
        items.insert(2, ("fixed wheels (not driven)", p.scatter(
            [x for x, d in zip(wx, driven, strict=True) if not d], [y for y, d in zip(wy, driven, strict=True)
                                                                     if not d],
            size=14, marker="square", color=OKABE_ITO[0], fill_alpha=0)))
    if layout.anti_tip:
        items.append(("anti-tip contacts (when tipped)", p.scatter([x for x, _ in layout.anti_tip],
                                                                   [-y for _, y in layout.anti_tip], size=10,
                                                                   marker="x", color=UNSTABLE)))
    lx = [x for _, x, _, _ in pts]
    ly = [-y for _, _, y, _ in pts]
    p.text(lx, ly, text=[f"{n:.0f}" for n in loads], text_font_size="8pt", x_offset=6, y_offset=-2)
    plots._legend_below(p, [LegendItem(label=k, renderers=[r]) for k, r in items], ncols=2)
    return p


def speed_figure(layout: Layout, crossings: list[tuple[float, str]]):
    """Real part of every eigenvalue of the layout's linear model against signed speed, the largest as a line.

    Parameters
    ----------
    layout : Layout
    crossings : list of (float, str)
        Signed critical speeds (m/s) with their label.

    Returns
    -------
    (bokeh.plotting.figure, ColumnDataSource, ColumnDataSource)
        The figure, the eigenvalues' source (``speed``, ``real``) and the growth rate's (``speed``, ``rate``).
    """
    lam = np.linalg.eigvals(state_matrices(layout, SPEEDS))
    rate = lam.real.max(axis=1)
    eig = ColumnDataSource({"speed": np.repeat(SPEEDS, lam.shape[1]), "real": lam.real.reshape(-1)})
    growth = ColumnDataSource({"speed": SPEEDS, "rate": rate})
    p = plots._fig(f"{plots.short_title(layout.name)}: real parts of the eigenvalues (> 0: that mode grows)",
                   "speed U (m/s; negative: reverse, casters trailing the other way)", "real part σ (1/s)",
                   height=400)
    items = [("every eigenvalue", p.scatter("speed", "real", source=eig, size=3, color=OKABE_ITO[4])),
             ("largest: the growth rate", p.line("speed", "rate", source=growth, line_width=2, color="black"))]
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    p.add_layout(Span(location=0, dimension="height", line_color="grey", line_width=1))
    for u, text in crossings:
        p.add_layout(Span(location=u, dimension="height", line_color=UNSTABLE, line_dash="dashed", line_width=1.5))
        p.add_layout(Label(x=u, y=0.0, text=text, text_color=UNSTABLE, text_font_size="9pt", x_offset=4,
                           y_offset=6))
    lo = float(rate.min())
    p.y_range = Range1d(start=min(-1.0, 3.0 * lo), end=max(1.0, 1.3 * float(rate.max())))
    plots._legend_below(p, [LegendItem(label=k, renderers=[r]) for k, r in items], ncols=2)
    return p, eig, growth


class LayoutExplorer:
    """One session's page for a wheel layout preset.

    Parameters
    ----------
    name : str
        A layout preset (:func:`stability.layout.presets.layout_preset_names`).
    query : mapping or str, optional
        The URL query (its fields other than ``chair`` are named as ignored).
    deliver : callable, optional
        As :class:`stability.app.page.Explorer`'s (default: at once).

    Attributes
    ----------
    layout : panel layout
        The page.
    wheels : Layout
    texts : dict
        Tab name -> its text pane (:class:`stability.app.plots.TextBox`).
    downloads : dict
        Kind -> its download button (:func:`stability.app.downloads.layout_buttons`).
    """

    def __init__(self, name: str, query: Any = None, deliver: Callable[[Callable[[], None]], Any] | None = None
                 ) -> None:
        from stability.app.links import _items
        from stability.app.page import TAB_NAMES

        self.name = name
        self.wheels = layout_preset(name)
        self._deliver = deliver or (lambda fn: fn())
        self.jobs = Jobs(lambda fn: self._deliver(partial(_held, fn)))
        self.summary = analyse_layout(self.wheels, [-u for u in reversed(D.SUMMARY_SPEEDS)] + list(D.SUMMARY_SPEEDS))
        ignored = sorted(k for k in (_items(query) if query else {}) if k != "chair")
        self.texts: dict[str, plots.TextBox] = {}
        self._started: set[str] = set()
        crossings = []
        for c, way in ((self.summary.forward_critical, 1.0), (self.summary.reverse_critical, -1.0)):
            if c and c[1] in ("destabilising", "stabilising"):
                crossings.append((way * c[0], f"critical {way * c[0]:+.3g} m/s"))
        fig, self.eig_src, self.rate_src = speed_figure(self.wheels, crossings)
        n_f, n_c = self.wheels.shape
        title = plots.TextBox("chair-title", f"<b>{literal(name)}</b> (wheel layout: {n_f} fixed wheels, {n_c} "
                                             "casters; exact model)")
        message = plots.TextBox("app-message", ("ignored for a wheel layout (its wheels are set in a [[wheel]] "
                                                "chair file, not by fields): " + literal(", ".join(ignored)))
                                if ignored else "")
        others = ", ".join(f'<a href="?chair={n}">{n}</a>' for n in layout_preset_names() if n != name)
        about = plots.TextBox("layout-about", (
            "<p>A wheel layout (stability/layout/presets.py; docs/layouts.md): its wheels are data, not the short "
            "form's fields, so there is nothing to edit here (Downloads gives its [[wheel]] file to edit).  Other "
            "layouts: " + others + ".  The thesis's "
            f'chairs, with the field editor: <a href="?chair={D.CHAIR}">{D.CHAIR}</a>.</p>'))
        speed_text = plots.TextBox("summary", pre(layout_text(self.wheels, self.summary)))
        self.texts["Stability vs speed"] = speed_text
        panels: list[Any] = []
        for tab in TAB_NAMES:
            if tab == "Stability vs speed":
                panels.append(pn.Column(pn.pane.Bokeh(fig, sizing_mode="stretch_width"), speed_text.pane,
                                        sizing_mode="stretch_width"))
            elif tab == "Downloads":
                from stability.app.downloads import layout_buttons

                self.downloads = layout_buttons(self.wheels, self.eig_src)
                box = plots.TextBox("layout-downloads", (
                    "<p>The layout as a chair file in the [[wheel]] form (edit its wheels, then give it to any "
                    "command as <code>--chair FILE</code>), the results as <code>python -m stability.critical_speed "
                    "--chair FILE --json</code> prints them, and the eigenvalues drawn on Stability vs speed.</p>"))
                self.texts[tab] = box
                panels.append(pn.Column(box.pane, *self.downloads.values(), sizing_mode="stretch_width"))
            elif tab in COMMANDS:
                box = plots.TextBox(f"layout-{tab.lower().replace(' ', '-')}",
                                    f"<p>computing <code>python -m {' '.join(command_line(tab, name))}</code>...</p>")
                self.texts[tab] = box
                panels.append(pn.Column(box.pane, sizing_mode="stretch_width"))
            else:
                box = plots.TextBox("not-for-layouts", f"<p>{NOT_FOR_LAYOUTS[tab]}</p>")
                self.texts[tab] = box
                panels.append(pn.Column(box.pane, sizing_mode="stretch_width"))
        self.tabs = pn.Tabs(*zip(TAB_NAMES, panels, strict=True), dynamic=True, sizing_mode="stretch_width",
                            css_classes=["views"], min_width=560, stylesheets=[".bk-tab { padding: 4px 9px; }"])
        self.tabs.param.watch(lambda e: self._deliver(partial(_held, self._tab_shown)), "active")
        self.top = top_view(self.wheels)
        left = pn.Column(pn.pane.Bokeh(self.top, sizing_mode="stretch_width", css_classes=["chair-sketch"]),
                         about.pane, width=EDITOR_WIDTH)       # the explorer's left column: the tabs fit at 1024 px
        header = pn.Column(pn.Row(pn.pane.Markdown("### stability explorer", margin=(0, 10), width=400),
                                  title.pane, sizing_mode="stretch_width"), message.pane, sizing_mode="stretch_width")
        self.layout = pn.Column(header, pn.Row(left, pn.Column(self.tabs, sizing_mode="stretch_width",
                                                               min_width=560), sizing_mode="stretch_width"),
                                sizing_mode="stretch_width")

    def _tab_shown(self) -> None:
        """Start the shown tab's command (once per page)."""
        from stability.app.page import TAB_NAMES

        tab = TAB_NAMES[self.tabs.active]
        if tab in COMMANDS and tab not in self._started:
            self._started.add(tab)
            self.start(tab)

    def start(self, tab: str) -> Any:
        """Run a background tab's command and show its output there.

        Parameters
        ----------
        tab : str
            A key of :data:`COMMANDS`.

        Returns
        -------
        concurrent.futures.Future
        """
        args = command_line(tab, self.name)
        head = f"$ python -m {' '.join(args)}\n\n"
        box = self.texts[tab]

        def show(text: str) -> None:
            box.text = pre(head + text)

        def failed(exc: BaseException) -> None:
            box.text = f"<p>error: the command failed: {literal(exc)}</p>"

        return self.jobs.submit(partial(run_command, args), show, failed)
