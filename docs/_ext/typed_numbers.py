"""Find numbers typed by hand into docs/*.md and README.md.

A computed number on a page must come from a value group (``{docvalue}`group.key``` in the Sphinx pages,
``<!--dv group.key-->...<!--/dv-->`` in README.md; see ``value_groups.py``). Everything else that looks like a
number is either one of the kinds the rules below let through, or an entry of the allow-list
``typed_numbers_allowed.py`` (a snippet of the page and the reason the number may stay typed).

What the rules let through (each is a kind of number that is not a computed result of the toolkit):

- code: fenced code blocks and inline code spans (commands, their arguments, API calls, file names; the
  transcripts' output lines are compared with what the command prints by ``tests/test_docs_examples.py``);
- math: ``$...$`` and ``$$...$$`` (constants of equations);
- the number of a numbered list item or heading (``1. **One way.**``, ``## 2. How large``);
- markup: MyST roles and directives (``{docvalue}`...```), HTML comments, link targets and URLs, images;
- references: years (1900-2099), and the number after ``issue``, ``eq``/``equation``, ``Figure``/``Fig.``,
  ``Table``, ``chapter``, ``section``, ``Appendix``, ``p.``/``pp.``/``page``, ``ISO``, ``IEEE``, ``Python``,
  ``version``, ``sec.``, ``exit status``, ``step``/``steps N-M`` of a list, and citation forms ``88:76-80``,
  ``40(5)``, ``31(4-5):199-205``;
  the lines of a ``References`` section;
- a default of the settings table: a number followed by its unit that equals a default of
  ``stability.settings.defaults.TABLE`` in that unit (``200 Hz``, ``0.75 m/s``, ``70 N m``, ``95 %`` for a
  coverage of 0.95), or the tire data's fitted range (``8 deg``, ``450 N``).

Run ``python docs/_ext/typed_numbers.py`` to list what remains per page, and
``python docs/_ext/typed_numbers.py --update-pending`` after converting a page (the allow-list loses the
entries whose numbers are now computed; a number typed anew is listed as "pending" and fails the test).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

NUMBER = re.compile(r"(?<![A-Za-z_\d.^])\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![A-Za-z_\d]|/s\b)")
_FENCE = re.compile(r"^\s*(```|~~~)")
_INLINE = [
    re.compile(r"<!--dv [^>]*-->.*?<!--/dv-->"),     # README's computed values
    re.compile(r"\{[\w:-]+\}`[^`]*`"),               # MyST roles
    re.compile(r"``[^`]*``|`[^`]*`"),                # inline code
    re.compile(r"\$\$.*?\$\$|\$[^$\s][^$]*?\$"),     # math
    re.compile(r"<!--.*?-->"),                        # HTML comments (README's value markers' names)
    re.compile(r"\]\([^)]*\)"),                       # link targets
    re.compile(r"https?://\S+"),                      # URLs
]
_REFERENCE_WORDS = (r"issues?|eqs?\.?|equations?|figures?|figs?\.?|tables?|chapters?|sections?|appendix|"
                    r"pp?\.|pages?|sec\.|ISO(?:/TS)?|IEEE|Python|version|v|doi|hfe|steps?|rule|status")
_REFERENCE = re.compile(rf"(?:\b(?:{_REFERENCE_WORDS})\s*[-/]?\s*)((?:\d+[-.,/]?\s*(?:and|to|or|&)?\s*)+)$",
                        re.IGNORECASE)
_CITATION = re.compile(r"\d+\s*\(\s*\d+(?:-\d+)?\s*\)(?::\s*\d+(?:-\d+)?)?|\d+:\d+(?:-\d+)?")
_LIST_NUMBER = re.compile(r"^\s*(?:#+\s*)?\d+\.(?=\s)")
_YEAR = re.compile(r"(?:19|20)\d\d")


@dataclass(frozen=True)
class Hit:
    """A typed number: the page, the line (1-based), the number and the line's text."""

    page: str
    line: int
    number: str
    column: int
    text: str

    def snippet(self, before: int = 28, after: int = 8) -> str:
        """A piece of the line around the number, cut at spaces: what the allow-list names."""
        s = max(0, self.column - before)
        while s > 0 and self.text[s - 1] != " ":
            s -= 1
        e = min(len(self.text), self.column + len(self.number) + after)
        while e < len(self.text) and self.text[e] != " ":
            e += 1
        return self.text[s:e].strip()


def _blank(text: str, pattern: re.Pattern) -> str:
    return pattern.sub(lambda m: " " * len(m.group(0)), text)


def _setting_numbers() -> set[tuple[float, str]]:
    """(value, unit) of every numeric default of the settings table, with ms for seconds."""
    sys.path.insert(0, str(ROOT))
    from stability.settings import defaults
    from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

    out: set[tuple[float, str]] = {(FZ_MAX_N, "N"), (SLIP_MAX_DEG, "deg")}      # the tire data's fitted range
    for d in defaults.TABLE.values():
        vals = d.value if isinstance(d.value, tuple) else (d.value,)
        for v in vals:
            if isinstance(v, (int, float)) and not isinstance(v, bool) and not d.unit:
                out.add((round(100 * float(v), 9), "%"))          # a fraction quoted as a percentage
            if isinstance(v, (int, float)) and not isinstance(v, bool) and d.unit:
                out.add((float(v), d.unit))
                if d.unit == "s":
                    out.add((round(1e3 * float(v), 9), "ms"))
    return out


def _unit_after(rest: str) -> str:
    m = re.match(r"\s*(N m/deg|N m|N s|m/s\^2|m/s|rad/s|deg/s|Hz|ms|s|m|N|deg|kg|%)(?![\w/])", rest)
    return m.group(1) if m else ""


def _line_hits(page: str, no: int, raw: str, tail: str, settings: set[tuple[float, str]]) -> list[Hit]:
    """The typed numbers of one line of prose (``tail``: the end of the line before, for a reference)."""
    line = _blank(raw, _LIST_NUMBER)
    for p in _INLINE:
        line = _blank(line, p)
    line = _blank(line, _CITATION)
    hits = []
    for m in NUMBER.finditer(line):
        num = m.group(0)
        if _YEAR.fullmatch(num) or _REFERENCE.search(tail + " " + line[:m.end()]):
            continue
        unit = _unit_after(line[m.end():])
        if unit and (float(num), unit) in settings:
            continue
        hits.append(Hit(page, no, num, m.start(), raw))
    return hits


def scan_text(page: str, text: str, settings: set[tuple[float, str]] | None = None) -> list[Hit]:
    """Every typed number of one page that the rules do not let through."""
    settings = _setting_numbers() if settings is None else settings
    hits: list[Hit] = []
    in_fence = False
    in_refs = False
    in_comment = False
    in_math = False
    previous = ""
    for no, raw in enumerate(text.splitlines(), 1):
        tail, previous = previous[-24:], raw
        if _FENCE.match(raw):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        if raw.count("$$") == 1:
            in_math = not in_math
            continue
        if in_math:
            continue
        if in_comment:
            if "-->" in raw:
                in_comment = False
            continue
        if raw.lstrip().startswith("<!--") and "-->" not in raw:
            in_comment = True
            continue
        if raw.startswith("#"):
            in_refs = bool(re.match(r"#+\s*references\b", raw, re.IGNORECASE))
        if in_refs or raw.lstrip().startswith(("```{", ":::", "![", ".. ")):
            continue
        hits += _line_hits(page, no, raw, tail, settings)
    return hits


def pages() -> list[Path]:
    """README.md and every docs/*.md (docs/report.md included)."""
    return [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]


def uncovered(hits: list[Hit], allowed: dict[str, list[tuple[str, str]]]) -> list[Hit]:
    """The hits no allow-list snippet of their page covers (a snippet covers the numbers inside it)."""
    out = []
    for h in hits:
        covered = False
        for snip, _why in allowed.get(h.page, []):
            start = h.text.find(snip)
            while start >= 0:
                if start <= h.column and h.column + len(h.number) <= start + len(snip):
                    covered = True
                    break
                start = h.text.find(snip, start + 1)
            if covered:
                break
        if not covered:
            out.append(h)
    return out


def scan_all() -> list[Hit]:
    """The hits of every page."""
    settings = _setting_numbers()
    out: list[Hit] = []
    for p in pages():
        rel = p.relative_to(ROOT).as_posix()
        out += scan_text(rel, p.read_text(encoding="utf-8"), settings)
    return out


def update_pending() -> int:
    """Rewrite ``typed_numbers_allowed.py`` after pages were converted: drop the entries no longer on their page,
    keep the others, and list any typed number still uncovered as "pending". ``PENDING_LIMIT`` only falls: if the
    pending entries grew, it stays, and ``tests/test_docs_values.py`` fails. Returns the pending count."""
    import typed_numbers_allowed as A

    path = Path(A.__file__)
    hits = scan_all()
    keep: dict[str, list[tuple[str, str]]] = {}
    for page, entries in A.ALLOWED.items():
        text = (ROOT / page).read_text(encoding="utf-8")
        keep[page] = [(snip, why) for snip, why in entries if snip in text]
    for h in uncovered(hits, keep):
        if uncovered([h], keep):          # an earlier new entry may cover it
            keep.setdefault(h.page, []).append((h.snippet(), "pending"))
    # drop entries that cover no hit any more (the number inside was converted)
    for page, entries in keep.items():
        page_hits = [h for h in hits if h.page == page]
        keep[page] = [e for e in entries if len(uncovered(page_hits, {page: [e]})) < len(page_hits)]
    pending = sum(1 for entries in keep.values() for _s, why in entries if why == "pending")
    src = path.read_text(encoding="utf-8")
    head = src[:src.index("PENDING_LIMIT = ")]
    body = [f"PENDING_LIMIT = {min(pending, A.PENDING_LIMIT)}\n\n",
            "ALLOWED: dict[str, list[tuple[str, str]]] = {\n"]
    for page in sorted(keep, key=lambda p: (p != "README.md", p)):
        if keep[page]:
            rows = "".join(f"        ({s!r}, {w!r}),\n" for s, w in keep[page])
            body.append(f"    {page!r}: [\n{rows}    ],\n")
    body.append("}\n")
    path.write_text(head + "".join(body), encoding="utf-8")
    return pending


def main(argv: list[str] | None = None) -> int:
    """Print every typed number the rules and the allow-list do not cover, per page (exit 1 if any).

    ``--update-pending`` rewrites the allow-list instead (:func:`update_pending`).
    """
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from typed_numbers_allowed import ALLOWED

    if "--update-pending" in (sys.argv[1:] if argv is None else argv):
        print(f"{update_pending()} pending entries", file=sys.stderr)
        return 0

    argv = sys.argv[1:] if argv is None else argv
    hits = scan_all()
    left = hits if "--all" in argv else uncovered(hits, ALLOWED)
    counts: dict[str, int] = {}
    for h in left:
        counts[h.page] = counts.get(h.page, 0) + 1
        if "--count" not in argv:
            print(f"{h.page}:{h.line}: {h.number}: {h.snippet()}")
    for page, n in sorted(counts.items(), key=lambda kv: -kv[1]):
        print(f"{n:5d} {page}", file=sys.stderr)
    print(f"{len(left)} typed numbers", file=sys.stderr)
    return 1 if left else 0


if __name__ == "__main__":
    raise SystemExit(main())
