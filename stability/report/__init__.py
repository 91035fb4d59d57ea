"""``python -m stability.report``: a multi-page PDF report on one chair.

:mod:`.compute` runs every analysis once (:class:`ReportData`),
:mod:`.findings` words the results, :mod:`.builders` draws the pages with
:mod:`stability.plotting`, :mod:`.document` writes one atomic,
byte-reproducible PDF, :mod:`.command` is the command line.  What each page
shows and why: ``docs/report.md``.

Examples
--------
::

    python -m stability.report --chair ej-premier -o reports/ej-premier.pdf
    python -m stability.report --chair revised --model thesis --quick -o /tmp/revised.pdf
    python -m stability.report --chair my_chair.toml --set trail=0.05 -o chair.pdf
"""

from __future__ import annotations

from stability.report.builders import page_builders
from stability.report.compute import ReportData, Settings, compute, counterpart, response_speeds, stabilising_poles
from stability.report.document import Page, ReportResult, build, figure_texts, pages
from stability.report.findings import findings

__all__ = ["Settings", "ReportData", "Page", "ReportResult", "compute", "pages", "build", "findings",
           "figure_texts", "page_builders", "counterpart", "response_speeds", "stabilising_poles"]
