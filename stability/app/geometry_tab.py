"""The explorer's chair drawings: the sketch from above beside the fields, and the Geometry tab.

Both are drawn from the chair's fields (:func:`stability.app.views.geometry_points`)
and the tip angles of its linear view; the sketch and the tab's top view share
their data sources, so an edit sends each number once.
"""

from __future__ import annotations

from typing import Any

import panel as pn
from bokeh.models import ColumnDataSource

from stability.app import plots
from stability.app.tabtext import TabText
from stability.app.text import geometry_text
from stability.app.views import LinearView, geometry_points
from stability.chair import Chair

__all__ = ["GeometryTab"]


class GeometryTab:
    """The chair drawn from above (sketch and tab) and from the side, with its tipping lines and static loads.

    Attributes
    ----------
    sketch : panel.pane.Bokeh
        The compact top view for the editor column.
    panel : panel.Column
        The Geometry tab.
    """

    def __init__(self) -> None:
        self.top_src = {k: ColumnDataSource({"x": [], "y": []}) for k in ("cg", "main", "pins", "casters", "outline")}
        for k in ("trail", "push"):
            self.top_src[k] = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": []})
        self.top_src["tip"] = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "label": []})
        self.side_src = {"cg": ColumnDataSource({"x": [], "y": []}), "contacts": ColumnDataSource({"x": [], "y": []}),
                         "pins": ColumnDataSource({"x": [], "y": []}),
                         "tip": ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "label": []})}
        self.top_fig = plots.top_view(self.top_src)
        self.sketch_fig = plots.top_view(self.top_src, compact=True)
        self.side_fig = plots.side_view(self.side_src)
        self.sketch = pn.pane.Bokeh(self.sketch_fig, sizing_mode="stretch_width", css_classes=["chair-sketch"])
        self.texts = TabText()
        self.loads = pn.pane.Markdown("", sizing_mode="stretch_width", css_classes=["geometry-text"])
        self.panel = pn.Column(pn.pane.Bokeh(self.top_fig, sizing_mode="stretch_width"),
                               pn.pane.Bokeh(self.side_fig, sizing_mode="stretch_width"), self.loads,
                               sizing_mode="stretch_width")

    def show(self, c: Chair, v: LinearView) -> None:
        """Draw ``c`` (data only).

        Parameters
        ----------
        c : Chair
        v : LinearView
            Its linear view (tip angles and static loads).
        """
        pts = geometry_points(c)

        def xy(key: str) -> dict:
            x, y = pts[key]
            return {"x": x, "y": -y}      # plotted with the chair's left up

        src, side, put = self.top_src, self.side_src, plots.replace_data
        for k in ("cg", "main", "pins", "casters"):
            put(src[k], xy(k))
        mx, my = pts["main"]
        cx, cy = pts["casters"]
        put(src["outline"], {"x": [mx[0], mx[1], cx[1], cx[0]], "y": [-my[0], -my[1], -cy[1], -cy[0]]})
        px, py = pts["pins"]
        put(src["trail"], {"x0": px, "y0": -py, "x1": cx, "y1": -cy})
        put(src["push"], {"x0": [0.0], "y0": [0.0], "x1": [0.0], "y1": [-0.15]})
        put(side["cg"], {"x": [0.0], "y": [c.h]})
        put(side["contacts"], {"x": [mx[0], cx[0]], "y": [0.0, 0.0]})
        put(side["pins"], {"x": [px[0]], "y": [0.0]})
        rays = {k: (ln.distance_m * ln.normal[0], ln.distance_m * ln.normal[1], ln.angle_deg)
                for k, ln in v.tip.lines.items()}
        put(src["tip"], {"x0": [0.0] * len(rays), "y0": [0.0] * len(rays), "x1": [r[0] for r in rays.values()],
                         "y1": [-r[1] for r in rays.values()], "label": [f"{r[2]:.1f}°" for r in rays.values()]})
        fwd = [rays["toward_main_wheels"], rays["toward_casters"]]
        put(side["tip"], {"x0": [0.0, 0.0], "y0": [c.h, c.h], "x1": [r[0] for r in fwd], "y1": [0.0, 0.0],
                          "label": [f"{r[2]:.1f}°" for r in fwd]})
        self.texts.set(self.loads, geometry_text(c, v))

    def sources(self) -> list[Any]:
        """Every data source of the drawings (for tests).

        Returns
        -------
        list of ColumnDataSource
        """
        return [*self.top_src.values(), *self.side_src.values()]
