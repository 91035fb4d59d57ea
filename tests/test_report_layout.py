"""How the reports look, read back from the PDF by an independent reader (pdfminer.six, tests/pdf_layout.py):
no text outside the page, no text over text, no text under 7 pt (issue 35; the review found clipped or
colliding text on 3-7 pages of every report)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pdfminer")

from pdf_layout import layout_problems  # noqa: E402  (tests/ is on sys.path, as for numerics)

ROOT = Path(__file__).resolve().parents[1]


def _page_pdf(path: Path, draw) -> Path:
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.figure import Figure

    fig = Figure(figsize=(11.69, 8.27))
    draw(fig)
    with PdfPages(path) as pdf:
        pdf.savefig(fig)
    return path


def test_the_checker_finds_each_defect(tmp_path):
    """Each defect drawn on purpose is found, and a clean page passes (the checker can fail)."""
    clean = _page_pdf(tmp_path / "clean.pdf", lambda f: (f.text(0.1, 0.8, "a line of text", fontsize=9),
                                                          f.text(0.1, 0.7, "another line\nand a second", fontsize=9)))
    assert layout_problems(clean) == []
    over = _page_pdf(tmp_path / "over.pdf", lambda f: (f.text(0.1, 0.8, "header one", fontsize=9),
                                                        f.text(0.12, 0.8, "header two", fontsize=9)))
    assert any("overlapping" in p for p in layout_problems(over))
    out = _page_pdf(tmp_path / "out.pdf", lambda f: f.text(0.95, 0.5, "runs past the right edge", fontsize=9))
    assert any("outside the page" in p for p in layout_problems(out))
    small = _page_pdf(tmp_path / "small.pdf", lambda f: f.text(0.1, 0.5, "tiny table cell", fontsize=6))
    assert any("6.0 pt" in p for p in layout_problems(small))
    rotated = _page_pdf(tmp_path / "rot.pdf", lambda f: f.text(0.1, 0.5, "an axis label", fontsize=8, rotation=90))
    assert layout_problems(rotated) == []          # a rotated label's size is read across its direction


@pytest.mark.slow
@pytest.mark.parametrize("name", ["ej-premier", "revised", "ej-premier-front-caster", "measured-chair"])
def test_committed_reports_layout(name):
    problems = layout_problems(ROOT / "reports" / f"{name}.pdf")
    assert not problems, "\n".join(problems[:30])


def _random_chair(seed: int, caster_position: str):
    """A valid chair drawn around a preset: every design parameter within its stated span."""
    from stability.chair import preset
    from stability.chair.design import get_parameter

    rng = np.random.default_rng(seed)
    base = preset("ej-premier" if caster_position == "rear" else "ej-premier-front-caster")
    c = base.replace(name=f"random-{caster_position}-{seed}")
    for name in ("trail", "pin_friction", "s1"):
        p = get_parameter(name)
        lo, hi = p.span(c)
        c = p.apply(c, float(lo + (hi - lo) * rng.uniform(0.25, 0.75)))
    return c.replace(name=f"random-{caster_position}-{seed}")


@pytest.mark.slow
@pytest.mark.parametrize("caster_position, extra", [("rear", ["--compare", "ej-premier"]), ("front", []),
                                                    ("rear", ["--quick"]), ("rear", ["--clinician"]),
                                                    ("rear", ["--reaction-time", "0.52"]),
                                                    ("front", ["--quick", "--reaction-time", "0.52"])])
def test_random_chair_report_layout(caster_position, extra, tmp_path):
    """A seeded random valid chair, rear and front casters, with and without --compare, the quick report and
    the clinician sheet, and with a user (--reaction-time: page 1's driver line and the user's limits)."""
    c = _random_chair(35, caster_position)
    from stability.chair.io import dumps

    toml = tmp_path / "chair.toml"
    toml.write_text(dumps(c))
    out, txt = tmp_path / "r.pdf", tmp_path / "r.txt"
    subprocess.run([sys.executable, "-m", "stability.report", "--chair", str(toml), "--no-progress", "-o", str(out),
                    *extra, *([] if {"--quick", "--clinician"} & set(extra) else ["--text", str(txt)])], cwd=ROOT,
                   check=True, capture_output=True)
    problems = layout_problems(out)
    assert not problems, "\n".join(problems[:30])
    if txt.exists():         # the full report's structure from the chair's data (issue 35; a manual chair)
        from report_structure import check_structure, read_text_dump

        check_structure(read_text_dump(txt), c, manual=True, compare="--compare" in extra, uncertainty=False)
