"""``report --quick`` prints the full report's decision (issue 35): page 1 of the quick report, word for word, on the
presets the issue names and on a wheel layout.

A wiring test (both reports call the same advisor; it checks that the quick path passes it the same chair, speeds
and reference chair, and computes page 1 from the same data), so it runs the real advisor and the full report:
about a minute of CPU per chair, hence ``slow``.  The quick report's speed is measured, not asserted, by
``tests/benchmarks/test_bench_report_quick.py``.
"""

from __future__ import annotations

import pytest

from stability.chair import preset
from stability.layout.presets import layout_preset
from stability.report.brief import compute_brief
from stability.report.compute import compute
from stability.report.decision import decision_paragraphs
from stability.report.layout_report import compute_layout_report

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("name", ["ej-premier", "ej-premier-front-caster", "power-fwd"])
def test_quick_decision_is_the_full_reports(name):
    c = preset(name)
    brief, full = compute_brief(c, progress=False), compute(c, progress=False)
    quick_page, full_page = decision_paragraphs(brief), decision_paragraphs(full)
    assert quick_page and quick_page == full_page
    # the same recommendation and the same numbers under it (what page 1 prints from)
    assert ([r.to_mapping() for r in brief.advice.recommendations]
            == [r.to_mapping() for r in full.advice.recommendations])
    assert brief.reference_measures == full.reference_measures


def test_quick_layout_decision_is_the_full_reports():
    layout = layout_preset("power-fwd-base")
    quick, full = compute_layout_report(layout, quick=True), compute_layout_report(layout)
    assert quick.data["decision"] == full.data["decision"]
    assert quick.sections[0] == full.sections[0]            # the decision section, word for word
