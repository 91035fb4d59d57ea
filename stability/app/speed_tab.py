"""The explorer's first tab: stability against speed (the table ``critical_speed`` prints, the eigenvalues, a mode).

An edit replaces the numbers of the tab's data sources (the eigenvalues' real
and imaginary parts at the fixed speed grid, the shaded ranges) and moves its
annotations; the legend is rebuilt only when the modes' names change, from the
line renderers made when the figure was built (never read back from the
legend: two modes of one name, as at a 3 cm trail, once froze the session).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import panel as pn
from bokeh.core.properties import value
from bokeh.models import ColumnDataSource
from bokeh.models.annotations import LegendItem

from stability.app import plots
from stability.app.markup import literal
from stability.app.tabtext import TabText
from stability.app.text import summary_html
from stability.app.views import GRID, LinearView, mode_shape
from stability.app.widgets import widget
from stability.plotting.style import UNSTABLE
from stability.settings import defaults as D

__all__ = ["SpeedTab", "real_range"]




def real_range(eig: np.ndarray) -> tuple[float, float]:
    """The real-part axis of the eigenvalue plot: the slow modes in view (as the toolkit's figure draws them).

    Parameters
    ----------
    eig : ndarray of complex, shape (speeds, branches)

    Returns
    -------
    (float, float)
        Bottom and top, 1/s: up to 1.15 times the largest growth rate (at least 0.5) and down to three times
        that (at least 10 1/s below zero), as :func:`stability.plotting.loci.eigenvalues_vs_speed`.
    """
    hi = max(1.15 * float(eig.real.max()), 0.5)
    return -max(3.0 * hi, 10.0), hi


class SpeedTab:
    """The stability-against-speed tab of one session.

    Attributes
    ----------
    summary : bokeh.models.Div
        The verdict, the critical speeds and the table ``python -m stability.critical_speed`` prints.
    speed : panel.widgets.FloatSlider
        The speed of the mode shape, m/s.
    figs : dict
        :func:`stability.app.plots.speed_figures`.
    panel : panel.Column
    """

    def __init__(self) -> None:
        empty = np.full(len(GRID), np.nan)
        cols: dict[str, Any] = {"speed": GRID}
        for j in range(plots.MAX_BRANCHES):
            cols[f"real{j}"], cols[f"imag{j}"] = empty, empty
        self.branch_src = ColumnDataSource(cols)
        self.bands_src = ColumnDataSource({"left": [], "right": [], "colour": []})
        self.unc_src = ColumnDataSource({"speed": [], "low": [], "high": []})
        self.figs = plots.speed_figures(self.branch_src, self.bands_src, self.unc_src)
        self.shape_src = ColumnDataSource({"component": [], "magnitude": [], "phase": []})
        self.shape_fig = plots.shape_figure(self.shape_src)
        self.summary, summary_pane = plots.text_div("summary")
        self.speed = widget(pn.widgets.FloatSlider, "speed U (m/s) of the mode shape below", start=0.05, end=3.0,
                                            step=0.01, value=D.SPEED, css_classes=["speed"],
                                            sizing_mode="stretch_width")
        self.shape_text, shape_pane = plots.text_div("shape-text")
        self._legend_key: Any = None
        self.texts = TabText(shown=True)
        self._band = False
        f = self.figs
        self.panel = pn.Column(
            summary_pane,
            pn.pane.Bokeh(f["real"], sizing_mode="stretch_width"),
            pn.pane.Bokeh(f["imag"], sizing_mode="stretch_width"),
            pn.pane.Markdown("What to conclude: where the vermillion shading is, the chair's heading drifts away by "
                             "itself after a disturbance (the growth rate is how fast: it doubles every ln 2 / σ "
                             "seconds); dashed vermillion lines mark the critical speeds where that starts or stops. "
                             "Click a legend entry to hide that mode.", sizing_mode="stretch_width"),
            self.speed, shape_pane, pn.pane.Bokeh(self.shape_fig, sizing_mode="stretch_width"),
            sizing_mode="stretch_width")

    def show(self, v: LinearView, band: bool) -> None:
        """Draw a chair's linear views (data and annotations only).

        Parameters
        ----------
        v : LinearView
        band : bool
            Whether an uncertainty band is drawn (its legend entry).
        """
        eig = v.locus.eigenvalues
        f = self.figs
        lo, hi = real_range(eig)
        update: dict[str, Any] = {}
        # single precision on the wire (half the bytes; 7 digits, far below a pixel): the numbers shown as text
        # (table, critical speeds, CSV) come from the view, not from these columns
        for j in range(plots.MAX_BRANCHES):
            if j < eig.shape[1]:
                update[f"real{j}"] = eig[:, j].real.astype(np.float32)
                update[f"imag{j}"] = np.abs(eig[:, j].imag).astype(np.float32)
            else:
                update[f"real{j}"] = update[f"imag{j}"] = np.full(len(GRID), np.nan, dtype=np.float32)
        self.branch_src.data.update(update)
        off = [bool(np.all(eig[:, j].real < lo)) for j in range(eig.shape[1])]
        for j, r in enumerate(f["branch_renderers"]):
            name = v.names[j] if j < len(v.names) else ""
            if r.name != name:
                r.name = name
        self._legend(v.names, off, band)
        f["real"].y_range.update(start=lo, end=hi)
        shown = np.any(eig.real >= lo, axis=0)
        top = float(np.abs(eig.imag[:, shown]).max()) if shown.any() else 1.0
        f["imag"].y_range.update(start=0.0, end=max(1.15 * top, 1.0))
        left, right, colour = [], [], []
        for colour_, ranges in ((plots.STABLE, v.stable_intervals()), (UNSTABLE, v.locus.unstable_intervals())):
            for a, b in ranges:
                left.append(a)
                right.append(b)
                colour.append(colour_)
        data = {"left": left, "right": right, "colour": colour}
        if dict(self.bands_src.data) != data:
            self.bands_src.data = data
        cr = v.free_crossings[:plots.MAX_CROSSINGS]
        n = plots.MAX_CROSSINGS
        for i, span in enumerate(f["crossings"]):
            k = i % n
            if k < len(cr):
                span.update(location=cr[k].speed, visible=True)
            else:
                span.visible = False
        for k, lab in enumerate(f["crossing_labels"]):
            if k < len(cr):
                lab.update(x=cr[k].speed, y=0.0, text=f"critical {cr[k].speed:.4g} m/s", visible=True)
            else:
                lab.visible = False
        title = (f"{plots.short_title(v.chair.name)}, {v.model} model: real parts of the eigenvalues "
                 "(> 0: that mode grows)")
        if f["real"].title.text != title:
            f["real"].title.text = title
        html = summary_html(v)
        if self.summary.text != html:
            self.summary.text = html

    def show_band_entry(self, band: bool) -> None:
        """Add (or drop) the 95 % interval's legend entry.

        Parameters
        ----------
        band : bool
        """
        if self._legend_key is not None:
            names, off, _ = self._legend_key
            self._legend(names, list(off), band)

    def _legend(self, names: tuple[str, ...], off: list[bool], band: bool) -> None:
        """One legend entry per mode name (hiding all its branches), rebuilt only when the names change."""
        key = (tuple(names), tuple(off), band)
        if key == self._legend_key:
            return
        self._legend_key = key
        renderers = self.figs["branch_renderers"]
        groups: dict[str, list] = {}
        below: dict[str, bool] = {}
        for j, name in enumerate(names):
            groups.setdefault(name, []).append(renderers[j])
            below[name] = below.get(name, True) and off[j]
        items = [LegendItem(label=value(name + (" (below the plot at every speed)" if below[name] else "")),
                            renderers=rs) for name, rs in groups.items()]
        if band:
            items.append(self.figs["band_item"])
        self.figs["legend"].items = items

    def show_shape(self, v: LinearView, speed: float) -> None:
        """The least stable mode at ``speed`` (the slider's), computed at that speed.

        Parameters
        ----------
        v : LinearView
        speed : float
            m/s.
        """
        sh = mode_shape(v, speed)
        for span in self.figs["cursor"]:
            span.location = sh.speed
        self.shape_src.data = {"component": list(sh.components), "magnitude": list(sh.magnitude),
                               "phase": [f"{p:+.0f}°" for p in sh.phase_deg]}
        lam = sh.eigenvalue
        t2 = f"; a heading error doubles every {np.log(2) / lam.real:.3g} s" if lam.real > 0 else ""
        shares = ", ".join(f"{k} {100 * x:.0f} %" for k, x in sh.shares.items())
        self.shape_text.text = (f"<p><b>At {sh.speed:.3g} m/s</b> the least stable mode is <i>{literal(sh.name)}</i>: "
                                f"eigenvalue {lam.real:.4f} {'+' if lam.imag >= 0 else '-'} {abs(lam.imag):.3g}j "
                                f"1/s{t2}. Shares of its motion: {shares}. The bars give each component's size "
                                "relative to the largest, the numbers its phase relative to it.</p>")

    def show_band(self, speeds: Any, low: Any, high: Any) -> None:
        """Draw the growth rate's 95 % interval (empty arrays: none).

        Parameters
        ----------
        speeds, low, high : array_like
            m/s and 1/s.
        """
        self.unc_src.data = {"speed": list(speeds), "low": list(low), "high": list(high)}
