"""Read a PDF's text back with an independent reader (pdfminer.six) and list layout defects: text outside the
page, text over text, and text under a minimum font size.

A glyph's box is pdfminer's: its advance width by the font's height (ascent to descent).  Two glyphs of one word
touch but do not overlap; glyphs of lines set at matplotlib's 1.15 line spacing overlap by at most the part of
the font's height above 1.15 em.  So a collision is two glyphs whose boxes share more than :data:`OVERLAP` of the
smaller box's area: 0.35 is about 3x the largest share two neighbouring lines of one text give (observed 0.1) and
well below the share two texts drawn on top of each other give (0.5-1).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

#: Share of the smaller glyph box two glyphs may have in common (see the module docstring).
OVERLAP = 0.35
#: Slack at the page edge, points (anti-aliasing and the font's side bearings).
EDGE_PT = 0.5


@dataclass(frozen=True)
class Glyph:
    page: int
    text: str
    x0: float
    y0: float
    x1: float
    y1: float
    size: float
    line: int


def glyphs(path: str | Path) -> Iterator[tuple[int, tuple[float, float, float, float], list[Glyph]]]:
    """Per page: (page number from 1, media box, glyphs)."""
    from pdfminer.high_level import extract_pages
    from pdfminer.layout import LAParams, LTChar, LTTextContainer, LTTextLine

    def walk(obj, out, line_id):
        if isinstance(obj, LTTextLine):
            line_id[0] += 1
            for ch in obj:
                if isinstance(ch, LTChar) and ch.get_text().strip():
                    a, b = ch.matrix[0], ch.matrix[1]
                    # the font size is the box's extent across the writing direction (rotated labels: its width)
                    size = ch.height if abs(a) >= abs(b) else ch.width
                    out.append(Glyph(0, ch.get_text(), ch.x0, ch.y0, ch.x1, ch.y1, size, line_id[0]))
            return
        if isinstance(obj, LTTextContainer) or hasattr(obj, "__iter__"):
            for x in obj:
                walk(x, out, line_id)

    for i, page in enumerate(extract_pages(str(path), laparams=LAParams(all_texts=True)), start=1):
        out: list[Glyph] = []
        walk(page, out, [0])
        yield i, tuple(page.bbox), [Glyph(i, g.text, g.x0, g.y0, g.x1, g.y1, g.size, g.line) for g in out]


def _context(gs: list[Glyph], g: Glyph) -> str:
    return "".join(x.text for x in gs if x.line == g.line)[:60]


def layout_problems(path: str | Path, *, min_font: float = 7.0) -> list[str]:
    """Every layout defect of the PDF at ``path``, one line each (empty: none).

    Parameters
    ----------
    path : path-like
    min_font : float
        Smallest font size allowed, points.

    Returns
    -------
    list of str
    """
    out = []
    for n, (px0, py0, px1, py1), gs in glyphs(path):
        if not gs:
            continue
        b = np.array([(g.x0, g.y0, g.x1, g.y1) for g in gs])
        outside = ((b[:, 0] < px0 - EDGE_PT) | (b[:, 2] > px1 + EDGE_PT) | (b[:, 1] < py0 - EDGE_PT)
                   | (b[:, 3] > py1 + EDGE_PT))
        for k in np.flatnonzero(outside)[:3]:
            out.append(f"page {n}: text outside the page: {_context(gs, gs[k])!r}")
        # a line's size is its largest glyph's (an exponent in a "10^2" tick label is smaller by design)
        line_size: dict[int, float] = {}
        for g in gs:
            line_size[g.line] = max(line_size.get(g.line, 0.0), g.size)
        small = [(s, ln) for ln, s in line_size.items() if s < min_font - 0.05]
        for size, line in small[:3]:
            g = next(x for x in gs if x.line == line)
            out.append(f"page {n}: {size:.1f} pt text (< {min_font:g} pt): {_context(gs, g)!r}")
        # pairwise glyph overlaps (only between glyphs of different lines: one line's glyphs are adjacent)
        area = np.maximum((b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1]), 1e-9)
        lines = np.array([g.line for g in gs])
        ix0, iy0 = np.maximum(b[:, None, 0], b[None, :, 0]), np.maximum(b[:, None, 1], b[None, :, 1])
        ix1, iy1 = np.minimum(b[:, None, 2], b[None, :, 2]), np.minimum(b[:, None, 3], b[None, :, 3])
        inter = np.clip(ix1 - ix0, 0, None) * np.clip(iy1 - iy0, 0, None)
        share = inter / np.minimum(area[:, None], area[None, :])
        hit = np.triu((share > OVERLAP) & (lines[:, None] != lines[None, :]), 1)
        seen = set()
        for i, j in zip(*np.nonzero(hit), strict=True):
            key = (gs[i].line, gs[j].line)
            if key in seen:
                continue
            seen.add(key)
            out.append(f"page {n}: overlapping text: {_context(gs, gs[i])!r} and {_context(gs, gs[j])!r}")
    return out


if __name__ == "__main__":
    import sys

    for p in sys.argv[1:]:
        probs = layout_problems(p)
        print(f"{p}: {len(probs)} problems")
        for line in probs:
            print("  " + line)
