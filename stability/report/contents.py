"""The report's two parts: the results, then the appendix, and the contents that say where each page is.

Which part a page belongs to is decided here once (:data:`APPENDIX_PAGES`); which pages a chair's report has is
decided by :func:`stability.report.summary.dropped_pages` from the chair's data. Page 1 says where the parts
are (:func:`contents_line`); the appendix opens with the contents of the whole report (:func:`contents_text`:
every page with its number and, for a result, the first sentence of what it concludes).
"""

from __future__ import annotations

from collections.abc import Sequence

from stability.report.captions import caption
from stability.report.compute import ReportData

__all__ = ["APPENDIX_PAGES", "CONTENTS_TITLE", "RESULTS_LIMIT", "parts", "contents_line", "contents_text"]

#: The title of the appendix's first page: its heading and the contents of the whole report.
CONTENTS_TITLE = "appendix: contents"

#: The pages of the appendix, in order (every other page of a report is a result and comes before them).
APPENDIX_PAGES = (CONTENTS_TITLE, "method", "chair parameters and geometry", "findings",
                  "linear stability: critical speeds", "tires", "growth rate against design parameters",
                  "yaw-rate feedback root locus", "parametric study table", "glossary and references")

#: Most pages the results part may have (issue 35: "about 14 pages of results, then the appendix").
RESULTS_LIMIT = 14


def parts(titles: Sequence[str]) -> tuple[list[int], list[int]]:
    """The 1-based page numbers of the results and of the appendix.

    Parameters
    ----------
    titles : sequence of str
        The report's page titles, in order (:func:`stability.report.builders.page_builders`).

    Returns
    -------
    results, appendix : list of int

    Raises
    ------
    ValueError
        When a result follows an appendix page.
    """
    results = [i for i, t in enumerate(titles, start=1) if t not in APPENDIX_PAGES]
    appendix = [i for i, t in enumerate(titles, start=1) if t in APPENDIX_PAGES]
    if results and appendix and max(results) > min(appendix):
        raise ValueError(f"page {max(results)} ({titles[max(results) - 1]!r}) is a result after the appendix")
    return results, appendix


def _span(pages: list[int]) -> str:
    return f"p. {pages[0]}" if len(pages) == 1 else f"pp. {pages[0]}-{pages[-1]}"


def contents_line(titles: Sequence[str]) -> str:
    """Page 1's paragraph saying where the parts are.

    Parameters
    ----------
    titles : sequence of str

    Returns
    -------
    str
    """
    results, appendix = parts(titles)
    if not appendix:
        return f"CONTENTS. Results: {_span(results)}."
    return f"CONTENTS. Results: {_span(results)}. Appendix: {_span(appendix)} (every page listed on p. {appendix[0]})."


#: A contents line quotes a caption up to its first ". ", ": " or "; " after at least this many characters.
_MIN_HEAD = 40


def _first_sentence(text: str) -> str:
    head = text.removeprefix("What to conclude: ")
    cuts = [k for k in (head.find(s, _MIN_HEAD) for s in (". ", ": ", "; ")) if k >= 0]
    return head if not cuts else head[:min(cuts)] + ("." if head[min(cuts)] == "." else " ...")


def contents_text(d: ReportData, titles: Sequence[str]) -> list[str]:
    """The appendix's first page: the report's two parts, each page with its number (a result with the first
    sentence of its concluding caption), and the pages left out with why.

    Parameters
    ----------
    d : ReportData
    titles : sequence of str
        The report's page titles, in order.

    Returns
    -------
    list of str
        Paragraphs.
    """
    from stability.report.summary import dropped_text

    results, appendix = parts(titles)
    out = [f"RESULTS ({_span(results)}): the decision and the evidence for it."]
    for i in results:
        cap = caption(d, titles[i - 1])
        out.append(f"  p. {i}  {titles[i - 1]}" + ("" if cap is None else f": {_first_sentence(cap)}"))
    out += ["", f"APPENDIX ({_span(appendix)}): how the results were computed, and reference material."]
    out += [f"  p. {i}  {titles[i - 1]}" for i in appendix]
    gone = dropped_text(d)
    if gone:
        out += ["", "Pages left out of this report, and why (they cannot apply to this chair):", *gone]
    return out
