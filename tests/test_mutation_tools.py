"""The mutation runner's table of equivalent mutants stays true: each names a line still in its module (so a
changed line drops out of the table on purpose), and stands in docs/testing.md's table with the same reason."""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))

import mutation_sample  # noqa: E402


def _rows() -> list[str]:
    page = (ROOT / "docs" / "testing.md").read_text(encoding="utf-8")
    return [" ".join(line.replace("\\|", "|").split()) for line in page.splitlines() if line.startswith("| `")]


def test_every_equivalent_mutant_is_on_a_current_line_and_documented_with_its_reason():
    rows = _rows()
    assert len(rows) == len(mutation_sample.EQUIVALENT)
    for (path, old, new), why in mutation_sample.EQUIVALENT.items():
        assert path in mutation_sample.MODULES, path
        assert old in {line.strip() for line in (ROOT / path).read_text(encoding="utf-8").splitlines()}, (path, old)
        assert new != old and why, (path, old)
        row = " ".join(f"| `{path}` | `` {old} `` → `` {new} `` | {why} |".split())
        assert row in rows, row


def test_every_module_of_the_runner_has_its_tests():
    for path, tests in mutation_sample.MODULES.items():
        assert (ROOT / path).is_file(), path
        assert tests and all((ROOT / t).is_file() for t in tests), path
