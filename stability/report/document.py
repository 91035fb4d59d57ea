"""Writing the report: pages in order, their texts, one atomic and byte-reproducible PDF."""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from matplotlib.figure import Figure
from matplotlib.text import Text

from stability import plotting as P
from stability.chair import Chair
from stability.report import builders
from stability.report.brief import compute_brief
from stability.report.captions import caption
from stability.report.compute import ReportData, Settings, compute
from stability.report.uncertainty_data import UncertaintySpec
from stability.runtime.checks import check_model
from stability.runtime.files import write_pdf
from stability.runtime.progress import ProgressBar

__all__ = ["Page", "ReportResult", "figure_texts", "pages", "build"]


@dataclass
class Page:
    """One page: its title and all its text (for tests and the text dump).

    Attributes
    ----------
    title : str
    texts : list of str
        Every text drawn on the page.
    """

    title: str
    texts: list = field(default_factory=list)


@dataclass
class ReportResult:
    """A written report.

    Attributes
    ----------
    path : pathlib.Path or None
    pages : list of Page
    data : ReportData
    seconds : float
        Time taken, s.
    """

    path: Path | None
    pages: list
    data: ReportData
    seconds: float = 0.0

    def text(self) -> str:
        """All page texts, page by page."""
        out = []
        for i, p in enumerate(self.pages, start=1):
            out.append(f"=== page {i}: {p.title}")
            out.extend(t for t in p.texts)
        return "\n".join(out)


def figure_texts(fig: Figure) -> list[str]:
    """Every non-empty text string drawn on a figure (titles, labels, tick labels, legends, annotations).

    Parameters
    ----------
    fig : matplotlib.figure.Figure

    Returns
    -------
    list of str
    """
    if getattr(fig, "canvas", None) is not None and hasattr(fig.canvas, "draw"):
        fig.canvas.draw()
    out = []
    for t in fig.findobj(Text):
        s = t.get_text()
        if s and t.get_visible():
            out.append(s)
    return out


#: Caption font size (pt) and characters per caption line.
CAPTION_FONTSIZE, CAPTION_WIDTH = 9.0, 150


def add_caption(fig: Figure, text: str) -> None:
    """Draw a concluding caption at the foot of a page, moving the page's content up to make room.

    Every axes and every figure-level text is mapped ``y -> h + y (1 - h)``, where ``h`` is the caption's
    height, so nothing the page drew is covered or clipped.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    text : str
    """
    lines = P.wrap_text(text, CAPTION_WIDTH)
    h = 0.012 + 0.021 * len(lines)
    for ax in fig.axes:
        p = ax.get_position()
        ax.set_position((p.x0, h + p.y0 * (1 - h), p.width, p.height * (1 - h)))
    sup = getattr(fig, "_suptitle", None)      # matplotlib keeps the suptitle outside fig.texts
    texts = list(fig.texts) + ([sup] if sup is not None else [])
    for t in texts:
        x, y = t.get_position()
        t.set_position((x, h + y * (1 - h)))
    fig.text(0.015, 0.008, "\n".join(lines), ha="left", va="bottom", fontsize=CAPTION_FONTSIZE,
             fontweight="bold", color="0.1", linespacing=1.35)


def pages(d: ReportData, record: list | None = None) -> Iterator[Figure]:
    """Build the figures one at a time; append a :class:`Page` (title, texts) to ``record`` for each.

    Parameters
    ----------
    d : ReportData
    record : list, optional
        Receives one :class:`Page` per figure built.

    Yields
    ------
    matplotlib.figure.Figure
        Each page, numbered ("page i of n", bottom right).
    """
    plan = builders.page_builders(d)
    for i, (title, build_fig) in enumerate(plan, start=1):
        fig = build_fig()
        cap = caption(d, title)
        if cap is not None:
            add_caption(fig, cap)
        fig.text(0.985, 0.006, f"page {i} of {len(plan)}", ha="right", va="bottom", fontsize=7.5, color="0.35")
        if record is not None:
            record.append(Page(title, figure_texts(fig)))
        yield fig


def build(c: Chair, path: str | os.PathLike[str], *, model: str = "exact", quick: bool = False, progress: bool = True,
          settings: Settings | None = None, data: ReportData | None = None,
          uncertainty: UncertaintySpec | None = None, baseline: Chair | None = None,
          brief: bool = False, driver: Any = None, intended_speed: float | None = None) -> ReportResult:
    """Compute and write the report for chair ``c`` to ``path`` (atomically, reproducibly).

    Parameters
    ----------
    c : Chair
    path : path-like
        Output PDF; its directory must exist.  Nothing is written if a page fails.  The PDF
        has an outline (one bookmark per page, :func:`stability.runtime.files.add_outline`).
    model : {"exact", "thesis"}
    quick : bool
        Coarse settings.
    progress : bool
        Progress bars on a terminal.
    settings : Settings, optional
    data : ReportData, optional
        Already computed data (skips :func:`~stability.report.compute.compute`).
    uncertainty : UncertaintySpec, optional
        Parameter distributions for the uncertainty page and the intervals on the summary.
    baseline : Chair, optional
        Compare with this chair: an overlaid geometry and a side-by-side table of the key numbers.
    brief : bool
        The quick report of ``python -m stability.report --quick``: page 1 (the same decision as the full
        report), the clinician sheet and the references (:func:`~stability.report.brief.compute_brief`).
    driver : stability.driver.Driver, optional
        The user's reaction time: the advisor's decision weighs the speed this user can hold (as
        ``python -m stability.advise`` with the same driver), page 1 states the user's limits and, with ``brief``,
        the clinician sheet too.
    intended_speed : float, optional
        With ``driver``: the speed the user wants to drive at, m/s (the advisor's ``intended_speed``; default the
        fastest use speed).

    Returns
    -------
    ReportResult
    """
    t0 = time.perf_counter()
    check_model(model)
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():
        raise ValueError(f"output directory {str(directory)!r} does not exist")
    if data is not None:
        d = data
    elif brief:
        if uncertainty is not None or baseline is not None:
            raise ValueError("the quick report is page 1, the clinician sheet and the references: drop --quick to "
                             "use --uncertainty or --compare")
        d = compute_brief(c, model, progress=progress, driver=driver, intended_speed=intended_speed)
    else:
        d = compute(c, model, quick=quick, progress=progress, settings=settings, uncertainty=uncertainty,
                    baseline=baseline, driver=driver, intended_speed=intended_speed)
    record: list[Page] = []
    n_pages = len(builders.page_builders(d))
    with ProgressBar(n_pages, "pages", enabled=progress, unit="page") as bar:
        write_pdf(pages(d, record), path, title=f"stability report: {c.name} ({model} model)",
                  on_page=lambda i: bar.update(),
                  outline=lambda: [(f"{i + 1}. {p.title}", i) for i, p in enumerate(record)])
    return ReportResult(path, record, d, time.perf_counter() - t0)
