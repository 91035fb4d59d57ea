"""README.md's computed numbers: ``python -m docs._ext.readme_values`` rewrites them, ``--check`` compares.

README.md is not built by Sphinx, so its numbers are written into the file: each is
``<!--dv group.key-->VALUE<!--/dv-->`` (a value of ``value_groups.py``), and the block between
``<!--dv-sources-->`` and ``<!--/dv-sources-->`` lists the command or API call of every group used. README's
groups are cheap ones (``cheap=True``), so ``tests/test_docs_values.py`` recomputes them in the default run.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

import value_groups  # noqa: E402

README = HERE.parents[1] / "README.md"
MARKER = re.compile(r"<!--dv ([\w.-]+)-->(.*?)<!--/dv-->")
SOURCES = re.compile(r"(<!--dv-sources-->\n)(.*?)(<!--/dv-sources-->)", re.DOTALL)


def render(text: str) -> str:
    """``text`` with every marker's value and the sources block recomputed (without the disk cache)."""
    used: list[str] = []
    done: dict[str, dict] = {}

    def value(m: re.Match) -> str:
        name, _, key = m.group(1).partition(".")
        if not value_groups.GROUPS[name].cheap:
            raise ValueError(f"README.md: value group {name!r} is not cheap; README may only use cheap groups")
        if name not in done:
            done[name] = value_groups.evaluate(name, use_cache=False)[0]
        if name not in used:
            used.append(name)
        return f"<!--dv {m.group(1)}-->{done[name][key]}<!--/dv-->"

    out = MARKER.sub(value, text)
    lines = "".join(f"- `{n}`: `{value_groups.GROUPS[n].source}`\n" for n in used)
    return SOURCES.sub(lambda m: m.group(1) + lines + m.group(3), out)


def main(argv: list[str] | None = None) -> int:
    """Rewrite README.md (or, with ``--check``, exit 1 naming the first line that differs)."""
    argv = sys.argv[1:] if argv is None else argv
    text = README.read_text(encoding="utf-8")
    new = render(text)
    if "--check" in argv:
        if new == text:
            return 0
        for i, (a, b) in enumerate(zip(text.splitlines(), new.splitlines(), strict=False), 1):
            if a != b:
                print(f"README.md:{i}: is\n  {a}\nshould be\n  {b}\n"
                      "(run python -m docs._ext.readme_values)", file=sys.stderr)
                break
        return 1
    if new != text:
        README.write_text(new, encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
