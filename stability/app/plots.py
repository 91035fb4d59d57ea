"""The explorer's Bokeh figures: each draws from ColumnDataSources the page fills, and computes nothing.

Colours: the Okabe-Ito palette (:mod:`stability.plotting.style`), colour-blind
safe, each colour with one meaning per figure: the eigenvalue branches take
:data:`BRANCH_COLOURS` (never vermillion, which marks instability: the
shading of unstable speeds and the critical speeds), the slider's speed is a
grey dash-dot line, the mode shape's bars are grey.  Every axis carries its
unit; legends sit below or beside the drawing, never over it, and wrap into
columns so that a narrow window does not cut them.  A figure's data sources
keep their columns from one chair to the next: an edit replaces the numbers
only (no new Bokeh models).
"""

from __future__ import annotations

import html
from typing import Any

import numpy as np
from bokeh.models import ColumnDataSource, HoverTool, Range1d
from bokeh.models.annotations import Label, Legend, LegendItem, Span, Title
from bokeh.plotting import figure

from stability.plotting.style import OKABE_ITO, UNSTABLE

__all__ = ["STABLE", "BRANCH_COLOURS", "CURSOR", "BAND", "NEUTRAL", "speed_figures", "shape_figure", "top_view",
           "side_view", "response_figure", "compare_figure", "trail_figure", "MAX_BRANCHES", "MAX_CROSSINGS",
           "short_title", "replace_data", "text_div", "TextBox", "TEXT_STYLESHEET"]

#: The style of the page's per-edit text blocks (:class:`TextBox`): the look of Panel's Markdown, a compact table.
TEXT_STYLESHEET = (
    ":host { font-size: 14px; line-height: 1.45; } p { margin: 0 0 0.6em 0; } "
    "code { font-size: 12.5px; color: #1f5f8b; } "
    "table { border-collapse: collapse; font-size: 13px; margin-bottom: 0.5em; } "
    "th, td { border: 1px solid #bbb; padding: 1px 10px; text-align: right; } th { font-weight: 600; }")

#: Shading of stable speed ranges (Okabe-Ito bluish green, light).
STABLE = "#009E73"
#: Colours of the six eigenvalue branches: Okabe-Ito without vermillion (instability) and yellow (unreadable on
#: white), then black; branches 5 and 6 are also dashed.
BRANCH_COLOURS = ("#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#000000")
#: The speed slider's line on the eigenvalue plots.
CURSOR = "#666666"
#: Fill of the growth rate's 95 % interval.
BAND = "#999999"
#: Bars and marks that carry no category.
NEUTRAL = "#555555"
#: Largest number of branches drawn (the free-caster model has 6 states).
MAX_BRANCHES = 6
#: Largest number of critical speeds marked.
MAX_CROSSINGS = 6
_TOOLS = "pan,wheel_zoom,box_zoom,reset,save"
#: Longest chair name in a figure's title (characters; a name is user text and may be long).
TITLE_NAME = 60


def short_title(text: str, limit: int = TITLE_NAME) -> str:
    """``text`` on one line, cut to ``limit`` characters with an ellipsis (for a figure's title).

    Parameters
    ----------
    text : str
    limit : int

    Returns
    -------
    str
    """
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit - 1] + "…"


class TextBox:
    """HTML the page rewrites on every edit, shown by Panel's ``HTML`` Bokeh model (not a pane, not a ``Div``).

    Why this model: a Bokeh ``Div`` re-renders itself when its text changes and then computes the layout of the
    whole page (BokehJS ``LayoutDOMView.rerender`` -> ``compute_layout``, which measures every plot and
    widget: about 15 ms per rewritten ``Div`` in chromium on the shared 2-core machine), while Panel's ``HTML``
    model only replaces its element's ``innerHTML``.  Panel's HTML *pane* would send every property of the
    pane again on each change; the bare model sends the one ``text`` property.  The model's browser side
    decodes one level of HTML escaping (``html_decode``), so the text goes out escaped once; its scripts are
    never run and TeX is off (user text with ``$`` stays text).

    Parameters
    ----------
    css_class : str
        The element's class (the browser tests find it by that).
    text : str
        Initial HTML (inert: user text through :mod:`stability.app.markup`).
    **kw
        More model properties (``width``, ``height``, ``margin``, ``sizing_mode``, ``styles``).

    Attributes
    ----------
    model : panel.models.markup.HTML
    pane : panel.pane.Bokeh
        The pane that holds it in the page's layout.
    """

    def __init__(self, css_class: str, text: str = "", **kw: Any) -> None:
        import panel as pn
        from panel.models.markup import HTML

        from stability.app.markup import PRE_STYLESHEET

        kw.setdefault("sizing_mode", "stretch_width")
        self._text = text
        props: dict[str, Any] = dict(text=html.escape(text, quote=False), run_scripts=False, disable_math=True,
                                     css_classes=[css_class], stylesheets=[TEXT_STYLESHEET, PRE_STYLESHEET], **kw)
        self.model = HTML(**props)
        self.pane = pn.pane.Bokeh(self.model, **{k: kw[k] for k in ("width", "height", "margin", "sizing_mode")
                                                 if k in kw})

    @property
    def text(self) -> str:
        """The HTML shown; setting it sends it only when it differs from what is shown."""
        return self._text

    @text.setter
    def text(self, value: str) -> None:
        if value != self._text:
            self._text = value
            self.model.text = html.escape(value, quote=False)


def text_div(css_class: str, text: str = "", **kw: Any) -> tuple[TextBox, Any]:
    """A :class:`TextBox` for HTML the page rewrites on every edit, and the Panel pane that holds it.

    Parameters
    ----------
    css_class : str
    text : str
    **kw
        See :class:`TextBox`.

    Returns
    -------
    (TextBox, panel.pane.Bokeh)
    """
    box = TextBox(css_class, text, **kw)
    return box, box.pane


def replace_data(source: ColumnDataSource, data: dict) -> bool:
    """Give ``source`` new columns unless they hold the same numbers already (an unchanged source sends nothing).

    Parameters
    ----------
    source : ColumnDataSource
    data : dict
        Column -> sequence.

    Returns
    -------
    bool
        Whether the source changed.
    """
    old = source.data
    if set(old) == set(data) and all(len(old[k]) == len(data[k]) and
                                     np.array_equal(np.asarray(old[k]), np.asarray(data[k])) for k in data):
        return False
    source.data = data
    return True


def _fig(title: str, x_label: str, y_label: str, **kw: Any):
    p = figure(title=title, tools=kw.pop("tools", _TOOLS), sizing_mode="stretch_width", height=kw.pop("height", 300),
               **kw)
    p.xaxis.axis_label, p.yaxis.axis_label = x_label, y_label
    p.toolbar.logo = None
    _title(p).text_font_size = "11pt"
    return p


def _title(p: Any) -> Title:
    title = p.title
    assert isinstance(title, Title)
    return title


def _legend_below(p, items: list, ncols: int = 3, **kw: Any) -> Legend:
    kw.setdefault("label_text_font_size", "9pt")
    legend = Legend(items=items, location="top_left", orientation="horizontal", ncols=ncols, spacing=4, margin=4,
                    **kw)
    p.add_layout(legend, "below")
    return legend


def speed_figures(branches: ColumnDataSource, bands: ColumnDataSource, uncertainty: ColumnDataSource):
    """Every eigenvalue against speed (real and imaginary parts), stable ranges shaded, critical speeds marked.

    Parameters
    ----------
    branches : ColumnDataSource
        Columns ``speed`` (m/s), ``real0``... and ``imag0``... (1/s and rad/s), one pair per branch
        (:data:`MAX_BRANCHES`).
    bands : ColumnDataSource
        Columns ``left``, ``right`` (m/s) and ``colour``: speed ranges shaded stable or unstable.
    uncertainty : ColumnDataSource
        Columns ``speed``, ``low``, ``high``: the growth rate's interval (empty without an uncertainty file).

    Returns
    -------
    dict
        ``"real"`` and ``"imag"`` figures, ``"crossings"`` (Spans) and ``"crossing_labels"`` (Labels) the page
        moves, ``"cursor"`` (the speed slider's Spans), ``"legend"``, ``"branch_renderers"`` (one line
        renderer per branch on the real plot, in order; their ``name`` is the mode's, shown on hover) and
        ``"band_item"`` (the interval's legend item).
    """
    real = _fig("Real parts of the eigenvalues (> 0: that mode grows)", "forward speed U (m/s)",
                "real part σ (1/s)", x_axis_type="log", height=400)
    imag = _fig("Imaginary parts (oscillation frequency; 0: a real mode)", "forward speed U (m/s)",
                "|imaginary part| ω (rad/s)", x_axis_type="log", height=230, x_range=real.x_range)
    for p in (real, imag):
        p.quad(left="left", right="right", bottom=-1e6, top=1e6, source=bands, fill_alpha=0.13, line_alpha=0,
               fill_color={"field": "colour"})
    band = real.varea(x="speed", y1="low", y2="high", source=uncertainty, fill_color=BAND, fill_alpha=0.4)
    items, renderers = [], []
    for j in range(MAX_BRANCHES):
        c = BRANCH_COLOURS[j]
        dash = "solid" if j < 4 else "dashed"
        r = real.line("speed", f"real{j}", source=branches, line_width=2, color=c, line_dash=dash, name=f"mode {j}")
        imag.line("speed", f"imag{j}", source=branches, line_width=2, color=c, line_dash=dash)
        renderers.append(r)
        items.append(LegendItem(label=f"mode {j}", renderers=[r]))
        real.add_tools(HoverTool(renderers=[r], tooltips=[("mode", "$name"), ("U", "$x{0.000} m/s"),
                                                          ("σ", "$y{0.000} 1/s")]))
    band_item = LegendItem(label="95 % interval of the growth rate (uncertainty file)", renderers=[band])
    legend = _legend_below(real, items, click_policy="hide")
    real.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    crossings, labels = [], []
    for p in (real, imag):
        for _ in range(MAX_CROSSINGS):
            s = Span(location=1.0, dimension="height", line_color=UNSTABLE, line_dash="dashed", line_width=1.5,
                     visible=False)
            p.add_layout(s)
            crossings.append(s)
    for _ in range(MAX_CROSSINGS):
        lab = Label(x=1.0, y=0.0, text="", text_color=UNSTABLE, text_font_size="9pt", x_offset=-4, y_offset=6,
                    text_align="right", visible=False)
        real.add_layout(lab)
        labels.append(lab)
    cursor = []
    for p in (real, imag):
        s = Span(location=0.75, dimension="height", line_color=CURSOR, line_width=2, line_dash="dashdot")
        p.add_layout(s)
        cursor.append(s)
    real.y_range = Range1d(start=-10, end=2)
    imag.y_range = Range1d(start=0, end=10)
    return {"real": real, "imag": imag, "crossings": crossings, "crossing_labels": labels, "cursor": cursor,
            "legend": legend, "branch_renderers": renderers, "band_item": band_item}


def shape_figure(source: ColumnDataSource):
    """The mode shape at the slider's speed: magnitude of each dimensionless component, phase as text.

    Parameters
    ----------
    source : ColumnDataSource
        Columns ``component``, ``magnitude`` and ``phase`` (text, deg).

    Returns
    -------
    bokeh.plotting.figure
    """
    from stability.app.views import SHAPE_COMPONENTS

    p = _fig("Shape of the least stable mode at the slider's speed", "component (angles: rad per unit of the largest)",
             "relative magnitude (-)", x_range=list(SHAPE_COMPONENTS), height=260)
    p.vbar(x="component", top="magnitude", source=source, width=0.6, color=NEUTRAL, fill_alpha=0.7)
    p.text(x="component", y="magnitude", text="phase", source=source, text_align="center", y_offset=-4,
           text_font_size="9pt")
    p.y_range = Range1d(start=0, end=1.25)
    return p


def top_view(sources: dict[str, ColumnDataSource], compact: bool = False):
    """Plan view: c.g., main-wheel contacts, caster pins and contacts (with the trail); the push and tip lines.

    Parameters
    ----------
    sources : dict
        ``"cg"``, ``"main"``, ``"pins"``, ``"casters"`` (columns ``x``, ``y``), ``"trail"`` (segments
        ``x0, y0, x1, y1``), ``"outline"`` (``x``, ``y``), ``"push"`` (``x0, y0, x1, y1``) and ``"tip"`` (``x0, y0,
        x1, y1, label``: c.g. to each tipping line).
    compact : bool
        The small sketch beside the fields: no push, no tipping lines, a smaller legend.

    Returns
    -------
    bokeh.plotting.figure
    """
    p = _fig("The chair from above (forward to the right)", "x, forward from the c.g. (m)", "lateral, left up (m)",
             match_aspect=True, height=300 if compact else 380, tools="save" if compact else _TOOLS)
    items = [
        ("wheel contacts", p.patch("x", "y", source=sources["outline"], fill_alpha=0.06, fill_color="grey",
                                   line_color="grey")),
        ("trail" if compact else "caster trail (pin to contact)",
         p.segment("x0", "y0", "x1", "y1", source=sources["trail"], line_width=3, color=OKABE_ITO[1])),
        ("main wheels" if compact else "main-wheel contacts",
         p.scatter("x", "y", source=sources["main"], size=12, marker="square", color=OKABE_ITO[0])),
        ("caster pins", p.scatter("x", "y", source=sources["pins"], size=8, marker="circle", color=OKABE_ITO[1])),
        ("caster contacts", p.scatter("x", "y", source=sources["casters"], size=10, marker="triangle",
                                      color=OKABE_ITO[2])),
        ("c.g." if compact else "centre of gravity",
         p.scatter("x", "y", source=sources["cg"], size=15, marker="circle_cross", color="black", fill_alpha=0)),
    ]
    if not compact:
        items.append(("push (lateral force at the c.g., to the right)",
                      p.segment("x0", "y0", "x1", "y1", source=sources["push"], line_width=3, color="black",
                                line_dash="dashed")))
        items.append(("to the tipping lines (ISO 7176-1 angle)",
                      p.segment("x0", "y0", "x1", "y1", source=sources["tip"], line_dash="dotted", color=UNSTABLE,
                                line_width=2)))
        p.text("x1", "y1", text="label", source=sources["tip"], text_font_size="9pt", x_offset=3, y_offset=-3)
    _title(p).text_font_size = "10pt" if compact else "11pt"
    _legend_below(p, [LegendItem(label=k, renderers=[r]) for k, r in items], ncols=2,
                  label_text_font_size="8pt" if compact else "9pt")
    return p


def side_view(sources: dict[str, ColumnDataSource]):
    """Side view: ground, c.g. height, main-wheel and caster contacts, caster pins; tip lines when known.

    Parameters
    ----------
    sources : dict
        ``"cg"``, ``"contacts"``, ``"pins"`` (``x``, ``y``), ``"tip"`` (``x0, y0, x1, y1, label``).

    Returns
    -------
    bokeh.plotting.figure
    """
    p = _fig("Side view (forward to the right)", "x, forward from the c.g. (m)", "height (m)", match_aspect=True,
             height=300)
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1.5))
    items = [
        ("c.g. to the tipping contacts (ISO 7176-1 angle)",
         p.segment("x0", "y0", "x1", "y1", source=sources["tip"], line_dash="dotted", color=UNSTABLE, line_width=2)),
        ("wheel contacts", p.scatter("x", "y", source=sources["contacts"], size=12, marker="triangle",
                                     color=OKABE_ITO[0])),
        ("caster pins (at ground)", p.scatter("x", "y", source=sources["pins"], size=9, color=OKABE_ITO[1])),
        ("centre of gravity", p.scatter("x", "y", source=sources["cg"], size=15, marker="circle_cross",
                                        color="black", fill_alpha=0)),
    ]
    p.text("x1", "y1", text="label", source=sources["tip"], text_font_size="9pt", x_offset=4, y_offset=-4)
    _legend_below(p, [LegendItem(label=k, renderers=[r]) for k, r in items], ncols=2)
    return p


def response_figure(source: ColumnDataSource, linear: ColumnDataSource):
    """Yaw rate against time after the push: the nonlinear run and the linear model's response.

    Parameters
    ----------
    source, linear : ColumnDataSource
        Columns ``t`` (s) and ``r`` (rad/s).

    Returns
    -------
    bokeh.plotting.figure
    """
    p = _fig("Yaw rate after the push (dashed vermillion: |r| = 1 rad/s)", "time t (s)", "yaw rate r (rad/s)",
             height=340, x_range=Range1d(start=0, end=4))
    items = [("nonlinear (simulator, WCHAIR scheme)",
              p.line("t", "r", source=source, line_width=2, color=OKABE_ITO[0])),
             ("linear model", p.line("t", "r", source=linear, line_width=2, color=OKABE_ITO[1], line_dash="dashed"))]
    for y in (-1.0, 1.0):
        p.add_layout(Span(location=y, dimension="width", line_color=UNSTABLE, line_dash="dashed"))
    p.y_range = Range1d(start=-1.5, end=1.5)
    _legend_below(p, [LegendItem(label=k, renderers=[r]) for k, r in items], ncols=2)
    return p


def compare_figure(source: ColumnDataSource, n: int = 4):
    """Growth rate of the least stable mode against speed for the current and the pinned chairs.

    Parameters
    ----------
    source : ColumnDataSource
        Columns ``speed`` (m/s) and ``rate0``... (1/s), the first the current chair's.
    n : int
        Number of curves.

    Returns
    -------
    (bokeh.plotting.figure, Legend)
        The legend's items are the curves in order; the page sets their labels.
    """
    p = _fig("Growth rate of the least stable mode: current and pinned chairs", "forward speed U (m/s)",
             "growth rate (1/s; > 0 unstable)", height=400)
    items = []
    for j in range(n):
        r = p.line("speed", f"rate{j}", source=source, line_width=3 if j == 0 else 2, color=OKABE_ITO[j],
                   line_dash=["solid", "dashed", "dotdash", "dotted"][j % 4])
        items.append(LegendItem(label=f"chair {j}", renderers=[r], visible=j == 0))
    legend = _legend_below(p, items, ncols=1)
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    return p, legend


def trail_figure(sources: list[ColumnDataSource], speeds: tuple):
    """Growth rate of the yaw mode and real part of the caster-shimmy mode against trail, one colour per speed.

    Parameters
    ----------
    sources : list of ColumnDataSource
        One per speed: columns ``trail_cm`` (cm), ``yaw`` and ``shimmy`` (1/s).
    speeds : tuple of float
        The speeds of ``sources``, m/s (legend labels).

    Returns
    -------
    dict
        ``"figure"``, ``"chair"`` (the chair's trail, a Span) and ``"critical"`` (Spans for the boundaries of the
        shimmy-free trail band).
    """
    p = _fig("Trail trade-off: yaw growth (solid) and caster shimmy (dashed) against trail", "caster trail (cm)",
             "growth rate (1/s; > 0: grows / shimmies)", height=400)
    items = []
    for j, (src, u) in enumerate(zip(sources, speeds, strict=True)):
        c = OKABE_ITO[j]
        r1 = p.line("trail_cm", "yaw", source=src, color=c, line_width=2)
        r2 = p.line("trail_cm", "shimmy", source=src, color=c, line_width=2, line_dash="dashed")
        items.append(LegendItem(label=f"{u:g} m/s", renderers=[r1, r2]))
    critical = []
    for _ in range(MAX_CROSSINGS):
        s = Span(location=0.0, dimension="height", line_color=UNSTABLE, line_dash="dotted", line_width=2,
                 visible=False)
        p.add_layout(s)
        critical.append(s)
    chair = Span(location=0.0, dimension="height", line_color="black", line_width=2)
    p.add_layout(chair)
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    _legend_below(p, items, ncols=3)
    return {"figure": p, "chair": chair, "critical": critical}
