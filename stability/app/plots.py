"""The explorer's Bokeh figures: each draws from ColumnDataSources the page fills, and computes nothing.

Colours: the Okabe-Ito palette (:mod:`stability.plotting.style`), colour-blind
safe; unstable regions in vermillion, stable ones in bluish green, both light.
Every axis carries its unit.
"""

from __future__ import annotations

from typing import Any

from bokeh.models import ColumnDataSource, HoverTool, Range1d
from bokeh.models.annotations import Label, Legend, LegendItem, Span
from bokeh.plotting import figure

from stability.plotting.style import MARK, OKABE_ITO, UNSTABLE

__all__ = ["STABLE", "speed_figures", "shape_figure", "top_view", "side_view", "response_figure",
           "compare_figure", "trail_figure", "MAX_BRANCHES", "MAX_CROSSINGS"]

#: Shading of stable speed ranges (Okabe-Ito bluish green).
STABLE = "#009E73"
#: Largest number of branches drawn (the free-caster model has 6 states).
MAX_BRANCHES = 6
#: Largest number of critical speeds marked.
MAX_CROSSINGS = 6
_TOOLS = "pan,wheel_zoom,box_zoom,reset,save"


def _fig(title: str, x_label: str, y_label: str, **kw: Any):
    p = figure(title=title, tools=_TOOLS, sizing_mode="stretch_width", height=kw.pop("height", 300), **kw)
    p.xaxis.axis_label, p.yaxis.axis_label = x_label, y_label
    p.toolbar.logo = None
    return p


def speed_figures(branches: list[ColumnDataSource], bands: ColumnDataSource, uncertainty: ColumnDataSource):
    """Growth rate and every eigenvalue against speed, with stable ranges shaded and critical speeds marked.

    Parameters
    ----------
    branches : list of ColumnDataSource
        One per branch (:data:`MAX_BRANCHES`), columns ``speed``, ``real``, ``imag`` and ``name``.
    bands : ColumnDataSource
        Columns ``left``, ``right``, ``kind`` (``"stable"``/``"unstable"``): speed ranges, m/s.
    uncertainty : ColumnDataSource
        Columns ``speed``, ``low``, ``high``: the growth rate's interval (empty without an uncertainty file).

    Returns
    -------
    dict
        ``"real"`` and ``"imag"`` figures, ``"crossings"`` (Spans) and ``"crossing_labels"``
        (Labels) the page moves, ``"cursor"`` (the speed slider's Spans), ``"legend"``, ``"branch_renderers"``
        (one line renderer per branch source, in order) and ``"band_item"`` (the interval's legend item).
    """
    real = _fig("Eigenvalues against speed: real parts (growth rate > 0: unstable)", "forward speed U (m/s)",
                "real part σ (1/s)", x_axis_type="log", height=340)
    imag = _fig("Imaginary parts (oscillation frequency)", "forward speed U (m/s)", "|imaginary part| ω (rad/s)",
                x_axis_type="log", height=220, x_range=real.x_range)
    for p in (real, imag):
        p.quad(left="left", right="right", bottom=-1e4, top=1e4, source=bands, fill_alpha=0.13, line_alpha=0,
               fill_color={"field": "colour"})
    band = real.varea(x="speed", y1="low", y2="high", source=uncertainty, fill_color=OKABE_ITO[0], fill_alpha=0.25)
    items, renderers = [], []
    for j, src in enumerate(branches):
        c = OKABE_ITO[j % len(OKABE_ITO)]
        dash = "solid" if j < 4 else "dashed"
        r = real.line("speed", "real", source=src, line_width=2, color=c, line_dash=dash)
        imag.line("speed", "imag", source=src, line_width=2, color=c, line_dash=dash)
        renderers.append(r)
        items.append(LegendItem(label={"field": "name"}, renderers=[r], index=0))
    band_item = LegendItem(label="95 % interval of the growth rate", renderers=[band])
    items.append(band_item)
    legend = Legend(items=items, location="top_left", click_policy="hide", label_text_font_size="9pt")
    real.add_layout(legend, "right")
    real.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    crossings, labels = [], []
    for p in (real, imag):
        for _ in range(MAX_CROSSINGS):
            s = Span(location=1.0, dimension="height", line_color=UNSTABLE, line_dash="dashed", line_width=1.5,
                     visible=False)
            p.add_layout(s)
            crossings.append(s)
    for _ in range(MAX_CROSSINGS):
        lab = Label(x=1.0, y=0.0, text="", text_color=UNSTABLE, text_font_size="9pt", x_offset=4, y_offset=6,
                    visible=False)
        real.add_layout(lab)
        labels.append(lab)
    cursor = []
    for p in (real, imag):
        s = Span(location=0.75, dimension="height", line_color=MARK, line_width=2)
        p.add_layout(s)
        cursor.append(s)
    real.add_tools(HoverTool(tooltips=[("mode", "@name"), ("U", "@speed{0.000} m/s"), ("σ", "@real{0.000} 1/s")]))
    real.y_range = Range1d(start=-10, end=2)
    imag.y_range = Range1d(start=0, end=10)
    return {"real": real, "imag": imag, "crossings": crossings, "crossing_labels": labels, "cursor": cursor,
            "legend": legend, "branch_renderers": renderers, "band_item": band_item}


def shape_figure(source: ColumnDataSource):
    """The mode shape at the slider's speed: magnitude of each dimensionless component, phase as text.

    Parameters
    ----------
    source : ColumnDataSource
        Columns ``component``, ``magnitude``, ``phase`` (text, deg) and ``colour``.

    Returns
    -------
    bokeh.plotting.figure
    """
    from stability.app.views import SHAPE_COMPONENTS

    p = _fig("Mode shape at the slider's speed", "component (angles: rad per unit of the largest)",
             "relative magnitude (-)", x_range=list(SHAPE_COMPONENTS), height=260)
    p.vbar(x="component", top="magnitude", source=source, width=0.6, color="colour")
    p.text(x="component", y="magnitude", text="phase", source=source, text_align="center", y_offset=-4,
           text_font_size="9pt")
    p.y_range = Range1d(start=0, end=1.25)
    return p


def top_view(sources: dict[str, ColumnDataSource]):
    """Plan view: c.g., main-wheel contacts, caster pins and contacts (with the trail), the push.

    Parameters
    ----------
    sources : dict
        ``"cg"``, ``"main"``, ``"pins"``, ``"casters"`` (columns ``x``, ``y``), ``"trail"`` (segments
        ``x0, y0, x1, y1``), ``"push"`` (``x0, y0, x1, y1``), ``"outline"`` (``x``, ``y``), ``"tip"`` (``x0, y0,
        x1, y1, label``: c.g. to each tipping line).

    Returns
    -------
    bokeh.plotting.figure
    """
    p = _fig("Top view (forward to the right)", "x, forward from the c.g. (m)", "lateral, left up (m)",
             match_aspect=True, height=320)
    p.patch("x", "y", source=sources["outline"], fill_alpha=0.06, fill_color="grey", line_color="grey",
            legend_label="wheel contacts")
    p.segment("x0", "y0", "x1", "y1", source=sources["trail"], line_width=3, color=OKABE_ITO[1],
              legend_label="caster trail (pin to contact)")
    p.scatter("x", "y", source=sources["main"], size=14, marker="square", color=OKABE_ITO[0],
              legend_label="main-wheel contacts")
    p.scatter("x", "y", source=sources["pins"], size=9, marker="circle", color=OKABE_ITO[1],
              legend_label="caster pins")
    p.scatter("x", "y", source=sources["casters"], size=11, marker="triangle", color=OKABE_ITO[2],
              legend_label="caster contacts")
    p.scatter("x", "y", source=sources["cg"], size=16, marker="circle_cross", color="black", fill_alpha=0,
              legend_label="centre of gravity")
    p.segment("x0", "y0", "x1", "y1", source=sources["push"], line_width=3, color=UNSTABLE,
              legend_label="push (lateral force at the c.g., to the right)")
    p.segment("x0", "y0", "x1", "y1", source=sources["tip"], line_dash="dotted", color=MARK, line_width=2,
              legend_label="to the tipping lines (ISO 7176-1 angle)")
    p.text("x1", "y1", text="label", source=sources["tip"], text_font_size="9pt", x_offset=3, y_offset=-3)
    _legend_outside(p)
    return p


def _legend_outside(p) -> None:
    """Move a figure's legend to its right, off the drawing."""
    leg = p.legend[0]
    leg.label_text_font_size = "8pt"
    p.add_layout(leg, "right")


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
             height=260)
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1.5))
    p.segment("x0", "y0", "x1", "y1", source=sources["tip"], line_dash="dotted", color=MARK, line_width=2,
              legend_label="c.g. to the tipping contacts (ISO 7176-1 angle)")
    p.scatter("x", "y", source=sources["contacts"], size=12, marker="triangle", color=OKABE_ITO[0],
              legend_label="wheel contacts")
    p.scatter("x", "y", source=sources["pins"], size=9, color=OKABE_ITO[1], legend_label="caster pins (at ground)")
    p.scatter("x", "y", source=sources["cg"], size=16, marker="circle_cross", color="black", fill_alpha=0,
              legend_label="centre of gravity")
    p.text("x1", "y1", text="label", source=sources["tip"], text_font_size="9pt", x_offset=4, y_offset=-4)
    _legend_outside(p)
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
    p = _fig("Yaw rate after the push (dotted: |r| = 1 rad/s, the thesis's criterion)", "time t (s)",
             "yaw rate r (rad/s)", height=300)
    p.line("t", "r", source=source, line_width=2, color=OKABE_ITO[0], legend_label="nonlinear (simulator)")
    p.line("t", "r", source=linear, line_width=2, color=OKABE_ITO[1], line_dash="dashed",
           legend_label="linear model")
    for y in (-1.0, 1.0):
        p.add_layout(Span(location=y, dimension="width", line_color=UNSTABLE, line_dash="dotted"))
    p.y_range = Range1d(start=-1.5, end=1.5)
    _legend_outside(p)
    return p


def compare_figure(sources: list[ColumnDataSource]):
    """Growth rate of the least stable mode against speed for the current and the pinned chairs.

    Parameters
    ----------
    sources : list of ColumnDataSource
        Columns ``speed`` (m/s), ``rate`` (1/s) and ``name``; the first is the current chair.

    Returns
    -------
    bokeh.plotting.figure
    """
    p = _fig("Growth rate of the least stable mode: current and pinned chairs", "forward speed U (m/s)",
             "growth rate (1/s)", height=320)
    items = []
    for j, src in enumerate(sources):
        r = p.line("speed", "rate", source=src, line_width=3 if j == 0 else 2, color=OKABE_ITO[j],
                   line_dash=["solid", "dashed", "dotdash", "dotted"][j % 4])
        items.append(LegendItem(label={"field": "name"}, renderers=[r], index=0))
    p.add_layout(Legend(items=items, location="top_left", label_text_font_size="9pt"), "below")
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    return p


def trail_figure(sources: list[ColumnDataSource]):
    """Growth rate of the yaw mode and real part of the caster-shimmy mode against trail, one colour per speed.

    Parameters
    ----------
    sources : list of ColumnDataSource
        One per speed: columns ``trail`` (m), ``yaw`` and ``shimmy`` (1/s) and ``name``.

    Returns
    -------
    dict
        ``"figure"``, ``"chair"`` (the chair's trail, a Span) and ``"critical"`` (Spans for the boundaries of the
        shimmy-free trail band).
    """
    p = _fig("Trail trade-off: yaw growth (solid), caster shimmy (dashed); black: this chair's trail; "
             "dotted: shimmy-free band's boundaries",
             "caster trail (m)", "growth rate (1/s; > 0: unstable / shimmies)", height=360)
    items = []
    for j, src in enumerate(sources):
        c = OKABE_ITO[j]
        r1 = p.line("trail", "yaw", source=src, color=c, line_width=2)
        r2 = p.line("trail", "shimmy", source=src, color=c, line_width=2, line_dash="dashed")
        items.append(LegendItem(label={"field": "name"}, renderers=[r1, r2], index=0))
    critical = []
    for _ in range(MAX_CROSSINGS):
        s = Span(location=0.0, dimension="height", line_color=UNSTABLE, line_dash="dotted", line_width=2,
                 visible=False)
        p.add_layout(s)
        critical.append(s)
    chair = Span(location=0.0, dimension="height", line_color="black", line_width=2)
    p.add_layout(chair)
    p.add_layout(Span(location=0, dimension="width", line_color="black", line_width=1))
    p.add_layout(Legend(items=items, location="top_left", label_text_font_size="8pt"), "right")
    return {"figure": p, "chair": chair, "critical": critical}
