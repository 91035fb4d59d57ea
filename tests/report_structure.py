"""The report's structure checked from the chair's data (issue 35): the results, at most about 14 pages, then the
appendix after its own heading; page 1 and the appendix's contents say where every page is; no page or panel
that cannot apply to the chair.

Which pages apply is computed here independently of the report's own rules where the chair's data decide it:

- a manual chair has no motor, so no yaw-rate feedback locus (there is no controller to close the loop);
- a caster setting whose linear model is stable at every speed has no critical speed, so no speed locus: the
  linear page says so in one line (eigenvalues of the state matrices computed here on a finer grid than the
  report's locus);
- a comparison page exactly when a baseline was given, an uncertainty page exactly when a file was.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from stability.linear.model import state_matrices

#: The issue's "about 14 pages of results, then the appendix".
RESULTS_LIMIT = 14

#: The speed span of the report's speed loci, m/s (stability.rootlocus.speed_locus's default span).
LOCUS_SPEEDS = np.linspace(0.05, 15.0, 600)


def stable_at_every_speed(chair, casters: str, model: str = "exact") -> bool:
    """Every eigenvalue of the linear model has a negative real part at every speed of the locus span."""
    a = state_matrices(chair, LOCUS_SPEEDS, model=model, casters=casters)
    return bool(np.linalg.eigvals(a).real.max() < 0.0)


def read_text_dump(path: Path) -> list[tuple[str, str]]:
    """(short title, page text) of each page of a report's ``--text`` dump (``=== page i: title`` headers)."""
    pages: list[tuple[str, str]] = []
    for block in re.split(r"^=== page \d+: ", Path(path).read_text(encoding="utf-8"), flags=re.M)[1:]:
        title, _, body = block.partition("\n")
        pages.append((title.strip(), body))
    return pages


def check_structure(pages: list[tuple[str, str]], chair, *, manual: bool, compare: bool, uncertainty: bool,
                    model: str = "exact") -> None:
    """Assert the issue-35 structure of one full report.

    Parameters
    ----------
    pages : list of (str, str)
        Each page's short title and its text, in order.
    chair : Chair
        The report's chair.
    manual : bool
        The chair is pushed on its hand rims (no motor): stated by the caller from what the chair is.
    compare, uncertainty : bool
        Whether the report was asked for with ``--compare`` / ``--uncertainty``.
    """
    titles = [t for t, _ in pages]
    n = len(titles)
    # the appendix: every page whose drawn title says "appendix", all after the results
    appendix = [i for i, (_, text) in enumerate(pages, start=1) if re.search(r"\| appendix", text)]
    results = [i for i in range(1, n + 1) if i not in appendix]
    assert appendix and results == list(range(1, appendix[0])) and appendix == list(range(appendix[0], n + 1)), \
        (results, appendix)
    assert len(results) <= RESULTS_LIMIT, f"{len(results)} pages of results: {titles[:len(results)]}"
    # page 1 says where the parts are; the appendix opens with the contents of every page
    page1 = " ".join(pages[0][1].split())
    assert f"Results: pp. 1-{len(results)}" in page1, page1[-400:]
    assert f"pp. {appendix[0]}-{n}" in page1 and f"on p. {appendix[0]}" in page1
    contents = pages[appendix[0] - 1][1]
    assert f"RESULTS (pp. 1-{len(results)})" in contents and f"APPENDIX (pp. {appendix[0]}-{n})" in contents
    for i, t in enumerate(titles, start=1):
        assert re.search(rf"p\. {i}  {re.escape(t)}", contents), (i, t)
    # pages that cannot apply are left out, decided from the chair's data
    assert ("comparison" in titles) == compare
    assert ("parameter uncertainty" in titles) == uncertainty
    if manual:
        assert "yaw-rate feedback root locus" not in titles
        assert "manual chair" in contents                        # ... and the contents page says why
    linear = dict(pages)["linear stability: critical speeds"]
    for cs in ("free", "locked"):
        one_line = f"{cs.capitalize()} casters: every eigenvalue has a negative real part at every speed" in linear
        assert one_line == stable_at_every_speed(chair, cs, model), cs
