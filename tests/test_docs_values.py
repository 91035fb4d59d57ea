"""No hand-typed computed number in docs/*.md or README.md; README's computed numbers are current.

The pages quote computed numbers through the value groups of ``docs/_ext/value_groups.py`` (evaluated when the
site builds). ``docs/_ext/typed_numbers.py`` finds every other number on the pages; what its rules do not let
through must be on the allow-list ``docs/_ext/typed_numbers_allowed.py`` with one of its documented reasons.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXT = ROOT / "docs" / "_ext"
sys.path.insert(0, str(EXT))

import typed_numbers  # noqa: E402
from typed_numbers_allowed import ALLOWED, PENDING_LIMIT, REASONS  # noqa: E402

ROLE = re.compile(r"\{docvalue\}`([^`]+)`|```\{docvalue-table\}\s+(\S+)")


def test_no_typed_number_outside_the_allow_list():
    left = typed_numbers.uncovered(typed_numbers.scan_all(), ALLOWED)
    shown = "\n".join(f"{h.page}:{h.line}: {h.number} in '{h.snippet()}'" for h in left[:30])
    assert not left, (f"{len(left)} typed numbers: compute them with a value group ({{docvalue}}`group.key`, "
                      f"docs/_ext/value_groups.py) or, if one of typed_numbers_allowed.REASONS applies, allow-list "
                      f"them:\n{shown}")


def test_allow_list_entries_are_on_their_pages_with_a_documented_reason():
    for page, entries in ALLOWED.items():
        text = (ROOT / page).read_text(encoding="utf-8")
        for snippet, reason in entries:
            assert reason in REASONS, (page, snippet, reason)
            assert snippet in text, f"{page}: allow-list snippet no longer on the page: {snippet!r}"


def test_pending_entries_only_shrink():
    """Every page is converted (issue 35): PENDING_LIMIT is 0, so any 'pending' entry fails."""
    assert PENDING_LIMIT == 0
    pending = sum(1 for entries in ALLOWED.values() for _s, r in entries if r == "pending")
    assert pending <= PENDING_LIMIT, f"{pending} pending entries > {PENDING_LIMIT}: new typed numbers were added"


@pytest.mark.parametrize(("text", "expected"), [
    ("The chair turns at 6.41 N m/deg.", ["6.41"]),
    ("Collins 1987, eq 6-25 and Figure 8-6 (issue 26, 33).", []),
    ("run `python -m stability.slope --cross-slope 2` now", []),
    ("a {docvalue}`slope_holding.table` value, $x^2 + 3$", []),
    ("```\n12.5 m/s\n```\nbut 7.5 m/s here", ["7.5"]),
    ("at 200 Hz with 70 N m", []),            # defaults of the settings table, with their units
    ("at 201 Hz", ["201"]),                    # not a default
    ("Q15 and x86, 1e-6 N m", ["1e-6"]),
    ("## References\n- Smith (2000) Journal 31(4-5):199-205.\n## Next\n3 s", ["3"]),
])
def test_scanner_rules(text, expected):
    assert [h.number for h in typed_numbers.scan_text("page.md", text)] == expected


def test_readme_numbers_are_current():
    """README.md's ``<!--dv ...-->`` values equal what their (cheap) value groups compute now."""
    from docs._ext import readme_values

    text = readme_values.README.read_text(encoding="utf-8")
    assert "<!--dv " in text
    assert readme_values.render(text) == text, "README.md is stale: run python -m docs._ext.readme_values"


def _references() -> list[tuple[str, str]]:
    out = []
    for page in sorted((ROOT / "docs").glob("*.md")):
        text = re.sub(r"``.*?``", "", page.read_text(encoding="utf-8"))     # a role shown as code is not one
        for m in ROLE.finditer(text):
            out.append((page.name, m.group(1) or m.group(2)))
    return out


def test_every_docvalue_names_a_group():
    import value_groups

    refs = _references()
    assert refs
    missing = [(p, r) for p, r in refs if r.split(".", 1)[0] not in value_groups.GROUPS]
    assert not missing


@pytest.mark.slow
def test_every_docvalue_key_exists():
    """Every group the pages use evaluates, and has every key the pages name (the site build checks this too)."""
    import value_groups

    values = {}
    for page, ref in _references():
        name, _, key = ref.partition(".")
        if name not in values:
            values[name] = value_groups.evaluate(name)[0]
        assert key in values[name], (page, ref)
