"""Report pages: A4-landscape figures with a title, a subtitle and axes, text or a table.

Figures are made with :class:`matplotlib.figure.Figure` (never through
``pyplot``): nothing is left open and no GUI backend is needed.
"""

from __future__ import annotations

import math
import textwrap
from collections.abc import Callable, Sequence
from typing import Any

from matplotlib.figure import Figure

__all__ = ["PAGE_SIZE", "page", "finish", "wrap_text", "text_page", "table_page", "table_axes", "panels_page",
           "plain_text"]

#: A4 landscape (inches).
PAGE_SIZE = (11.69, 8.27)
_MONO = {"family": "monospace"}


# ---------------------------------------------------------------------------
# pages
# ---------------------------------------------------------------------------
def page(title: str, subtitle: str = "", *, nrows: int = 1, ncols: int = 1, size=PAGE_SIZE, **subplot_kw):
    """A page with a title (and subtitle) and a grid of axes: ``(fig, axes)``.

    ``axes`` is a 2-D array (``squeeze=False``).  Leaves room at the top for
    the titles; call ``fig.tight_layout(rect=...)`` via :func:`finish`.

    Parameters
    ----------
    title : str
        Page title (bold, shrunk when long).
    subtitle : str
        Line(s) under the title.
    nrows : int
        Rows of axes (0 with ``ncols=0``: no axes).
    ncols : int
        Panels per row.
    size : tuple of float
        Page size, inches.
    **subplot_kw
        Passed to :meth:`matplotlib.figure.Figure.subplots`.

    Returns
    -------
    tuple
        (fig, axes): the page and a 2-D array of axes (None without axes).
    """
    fig = Figure(figsize=size)
    fig.suptitle(title, fontsize=13 if len(title) <= 90 else max(9.0, 13 * 90 / len(title)), fontweight="bold",
                 y=0.985)
    if subtitle:
        fig.text(0.5, 0.948, "\n".join(textwrap.wrap(subtitle, 170)), ha="center", va="top", fontsize=8.5,
                 color="0.25", linespacing=1.3)
    axes = fig.subplots(nrows, ncols, squeeze=False, **subplot_kw) if nrows * ncols else None
    return fig, axes


def finish(fig: Figure, top: float = 0.90, *, left: float = 0.065, right: float = 0.975, bottom: float = 0.08,
           wspace: float | None = None, hspace: float | None = None, tight: bool = False) -> Figure:
    """Lay the axes out below the page titles.

    Fixed margins by default (``tight_layout`` measures every tick label
    and costs more than drawing the page); ``tight=True`` uses it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The page.
    top, left, right, bottom : float
        Figure-fraction margins.
    wspace, hspace : float, optional
        Spacing between panels.
    tight : bool
        Use ``tight_layout`` instead of fixed margins.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    if tight:
        fig.tight_layout(rect=(0.0, 0.0, 1.0, top + 0.03))
        return fig
    specs = [spec for a in fig.axes if (spec := a.get_subplotspec()) is not None]
    nrows = ncols = 1
    if specs:
        nrows, ncols = specs[0].get_gridspec().get_geometry()
    fig.subplots_adjust(left=left, right=right, bottom=bottom, top=top,
                        wspace=0.32 if wspace is None else wspace,
                        hspace=(0.45 if nrows > 1 else 0.2) if hspace is None else hspace)
    return fig


def plain_text(fig: Figure) -> Figure:
    """Draw every text of ``fig`` as typed, never as mathtext (a name from a user's file is never markup).

    Call it once the figure is drawn (titles, labels, legends and captions made).  The walk makes each axis's
    ticks for its current locations (the draw reuses them) so that their labels too are drawn as typed; a walk
    that skips the ticks not yet made only moves their cost to the draw (a layout run's figure: plot and PDF
    0.19 s either way) and leaves the labels made there parsing mathtext.

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    matplotlib.figure.Figure
        ``fig``.
    """
    from matplotlib.text import Text

    for t in fig.findobj(Text):
        t.set_parse_math(False)
    return fig


def wrap_text(text: str, width: int) -> list[str]:
    """Wrap each paragraph (line) of ``text`` to ``width`` characters; list items get a hanging indent.

    Parameters
    ----------
    text : str
        Paragraphs separated by newlines; blank lines are kept.
    width : int
        Characters per line.

    Returns
    -------
    list of str
        The wrapped lines.
    """
    out: list[str] = []
    for para in str(text).split("\n"):
        if not para.strip():
            out.append("")
            continue
        indent = len(para) - len(para.lstrip())
        hang = indent + 2 if para.lstrip().startswith(("-", "*")) else indent
        out.extend(textwrap.wrap(para, width=width, subsequent_indent=" " * hang) or [""])
    return out


def text_page(title: str, body: str | Sequence[str], subtitle: str = "", *, size=PAGE_SIZE,
              fontsize: float = 9.5, width: int = 120, monospace: bool = False) -> Figure:
    """A page of text (paragraphs wrapped to ``width`` characters).

    Parameters
    ----------
    title : str
        Page title (bold, shrunk when long).
    body : str or sequence of str
        Paragraphs (newline-separated).
    subtitle : str
        Line(s) under the title.
    size : tuple of float
        Page size, inches.
    fontsize : float
        Font size, points.
    width : int
        Characters per line.
    monospace : bool
        Monospaced font.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    fig, _ = page(title, subtitle, nrows=0, ncols=0, size=size)
    if not isinstance(body, str):
        body = "\n".join(body)
    lines = wrap_text(body, width)
    top, bottom = 0.90, 0.03
    step = min(0.0215 * fontsize / 9.5, (top - bottom) / max(len(lines), 1))
    fs = fontsize if step >= 0.0215 * fontsize / 9.5 * 0.999 else fontsize * step / (0.0215 * fontsize / 9.5)
    y = top
    for line in lines:
        fig.text(0.05, y, line, ha="left", va="top", fontsize=fs, **(_MONO if monospace else {}))
        y -= step
    return fig


#: Smallest font a table is drawn in, points (the layout test's floor).
MIN_TABLE_FONT = 7.0


def table_page(title: str, header: Sequence[str], rows: Sequence[Sequence[str]], subtitle: str = "", *,
               col_widths: Sequence[float] | None = None, notes: str = "", size=PAGE_SIZE,
               fontsize: float = 8.5, wrap: Sequence[int] | None = None) -> Figure:
    """A page holding one table (cells wrapped to ``wrap[i]`` characters per column) and notes below it.

    Parameters
    ----------
    title : str
        Page title (bold, shrunk when long).
    header : sequence of str
        Column headings.
    rows : sequence of sequence of str
        Table cells.
    subtitle : str
        Line(s) under the title.
    col_widths : sequence of float, optional
        Relative column widths.
    notes : str
        Text below the table.
    size : tuple of float
        Page size, inches.
    fontsize : float
        Font size, points.
    wrap : sequence of int, optional
        Characters per line in each column.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    fig, axes = page(title, subtitle, size=size)
    ax = axes[0, 0]
    ax.axis("off")
    table_axes(ax, header, rows, col_widths=col_widths, fontsize=fontsize, wrap=wrap)
    if notes:
        lines = wrap_text(notes, 150)
        for i, line in enumerate(lines):
            fig.text(0.04, 0.02 + 0.018 * (len(lines) - 1 - i), line, fontsize=8, ha="left", va="bottom")
    return fig


def table_axes(ax, header, rows, *, col_widths=None, fontsize: float = 8.5, wrap=None, top: float = 1.0,
               bottom: float = 0.08):
    """Draw a table into ``ax`` (axes coordinates), wrapping long cells; returns ``ax``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Where to draw (axis switched off by the caller).
    header : sequence of str
        Column headings.
    rows : sequence of sequence of str
        Table cells.
    col_widths : sequence of float, optional
        Relative column widths.
    fontsize : float
        Font size, points.
    wrap : sequence of int, optional
        Characters per line in each column.
    top, bottom : float
        Vertical extent of the table, axes fraction.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax``.
    """
    ncol = len(header)
    if col_widths is None:
        col_widths = [1.0 / ncol] * ncol
    tot = float(sum(col_widths))
    col_widths = [w / tot for w in col_widths]
    if wrap is None:
        wrap = [max(8, int(160 * w)) for w in col_widths]
    # shrink the font (never below MIN_TABLE_FONT) until the rows fit, widening the wrap as the font shrinks;
    # a line takes 1.15 font sizes (matplotlib's linespacing) and the rows 0.35 line of padding each
    height_pt = ax.get_position().height * ax.figure.get_figheight() * 72.0 * (top - bottom)
    fs = fontsize
    while True:
        widths = [max(3, int(w * fontsize / fs)) for w in wrap]
        cells = [[wrap_text(str(c), w) for c, w in zip(r, widths, strict=True)] for r in rows]
        heads = [wrap_text(str(h), w) or [""] for h, w in zip(header, widths, strict=True)]
        head_lines = max(len(h) for h in heads)
        heights = [max(len(c) for c in r) for r in cells]
        n_lines = sum(heights) + head_lines + 0.6 + 0.35 * len(rows)
        if n_lines * 1.2 * fs <= height_pt or fs <= MIN_TABLE_FONT:
            break
        fs = max(MIN_TABLE_FONT, fs - 0.25)
    need = 1.2 * fs / 72.0 / (ax.get_position().height * ax.figure.get_figheight())   # one line, axes fraction
    line_h = max(need, min(0.045, (top - bottom) / max(n_lines, 1)))
    x0 = [sum(col_widths[:i]) for i in range(ncol)]
    y = top
    for i, h in enumerate(heads):
        ax.text(x0[i] + 0.005, y, "\n".join(h), transform=ax.transAxes, fontsize=fs, fontweight="bold", va="top",
                linespacing=1.15)
    y -= (head_lines + 0.3) * line_h
    ax.plot([0, 1], [y + 0.25 * line_h] * 2, transform=ax.transAxes, color="0.3", lw=0.8)
    for r, hgt in zip(cells, heights, strict=True):
        for i, lines in enumerate(r):
            ax.text(x0[i] + 0.005, y, "\n".join(lines), transform=ax.transAxes, fontsize=fs, va="top",
                    linespacing=1.15)
        y -= (hgt * 1.0 + 0.35) * line_h
        ax.plot([0, 1], [y + 0.2 * line_h] * 2, transform=ax.transAxes, color="0.85", lw=0.5)
    return ax



def panels_page(items: Sequence, draw: Callable[[Any, Any], Any], title: str, subtitle: str = "",
                ncols: int = 2) -> Figure:
    """A page with one panel per item, ``ncols`` to a row: ``draw(item, ax)`` fills each, spare panels blank.

    Parameters
    ----------
    items : sequence
        One panel each.
    draw : callable
        ``draw(item, ax)`` fills a panel.
    title : str
        Page title (bold, shrunk when long).
    subtitle : str
        Line(s) under the title.
    ncols : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
        The page.
    """
    n = len(items)
    nrows = int(math.ceil(n / ncols))
    fig, axes = page(title, subtitle, nrows=nrows, ncols=ncols)
    for ax, item in zip(axes.flat, items, strict=False):
        draw(item, ax)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    return finish(fig)

