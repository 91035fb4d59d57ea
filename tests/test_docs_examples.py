"""Docs that cannot drift: every code block of docs/*.md and every ``>>>`` docstring example runs.

The Markdown pages are read with a small fence parser (no extra dependency);
each fenced block is classified by its info string and its content:

* ``python`` blocks run in order in one namespace per page, and ``pycon``
  blocks (or any block of ``>>>`` lines) run as doctests in that namespace,
  so their printed output is checked -- in the default run;
* ``toml`` blocks must parse -- default run;
* command lines (``python -m stability...`` or ``python docs/examples/...``,
  with or without a ``$`` prompt, ``\\``-continued, in ``bash`` or unlabeled
  blocks) run in a temporary directory (with a copy of ``docs/examples``, so
  the pages' relative paths work and nothing is written into the repository) and
  must exit 0 -- marked ``docs`` (they take minutes together);
* set-up lines (``python3 -m venv``, ``pip install``, ``python -m pytest``,
  ``python -m sphinx``) are what CI's own steps run, synopses with
  ``[optional]`` parts are not runnable, and ``python -m stability.app``
  serves a page until stopped (its own tests drive it in a browser); all
  three are left out, by rule.

A block that cannot run stand-alone is preceded by
``<!-- docs-test: skip REASON -->``; a block that is a file the next blocks
need by ``<!-- docs-test: file NAME -->`` (written into the page's working
directory). Every docstring of the package with a ``>>>`` example runs
through :mod:`doctest` in the default run.
"""

from __future__ import annotations

import doctest
import importlib
import os
import pkgutil
import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

import stability

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
FENCE = re.compile(r"^(?P<fence>```+)(?P<info>[^\n`]*)\n(?P<body>.*?)^(?P=fence)[ \t]*$", re.S | re.M)
MARK = re.compile(r"<!--\s*docs-test:\s*(?P<what>skip|file)\s*(?P<arg>.*?)\s*-->\s*$")
COMMAND = re.compile(r"^(\$\s+)?python3?\s+(-m\s+stability\b|docs/examples/)")
#: Commands that serve a web page until stopped (not one-shot): tests/test_app*.py start them in a browser.
SERVERS = re.compile(r"^python3?\s+-m\s+stability\.app\b(?!.*--help)")
SETUP = re.compile(r"^(\$\s+)?(python3?\s+-m\s+(venv|pip|pytest|sphinx)\b|pip\s|\.\s|source\s)")
DOCTEST_FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE


@dataclass(frozen=True)
class Block:
    page: str
    line: int
    info: str
    body: str
    mark: tuple[str, str] | None

    @property
    def id(self) -> str:
        return f"{self.page}:{self.line}"


def blocks(path: Path) -> list[Block]:
    """The fenced code blocks of one Markdown page (MyST directives ``{...}`` aside)."""
    text = path.read_text(encoding="utf-8")
    out = []
    for m in FENCE.finditer(text):
        info = m.group("info").strip()
        if info.startswith("{"):
            continue
        before = text[:m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        mark = MARK.search(before)
        out.append(Block(path.name, text.count("\n", 0, m.start()) + 1, info.split()[0] if info else "",
                         m.group("body"), (mark.group("what"), mark.group("arg")) if mark else None))
    return out


def commands(block: Block) -> list[tuple[str, list[str]]]:
    """The runnable command lines of a shell or unlabeled block (continuations joined, prompts removed),
    each with the output a ``$``-prompted transcript shows after it (the lines up to the next prompt)."""
    if block.info not in ("", "bash", "sh", "console", "shell"):
        return []
    joined = re.sub(r"\\\n\s*", " ", block.body)
    out: list[tuple[str, list[str]]] = []
    expected: list[str] | None = None
    for line in joined.splitlines():
        stripped = line.strip()
        parts = [p.strip() for p in re.split(r"\s+&&\s+", stripped)]
        if line.startswith("$ ") or not line.startswith(" ") and any(COMMAND.match(p) for p in parts):
            expected = None
            for part in parts:
                part = part.split(" #", 1)[0].strip()          # an inline shell comment
                if SETUP.match(part) or not COMMAND.match(part) or re.search(r"\[-", part) or SERVERS.match(part):
                    continue
                expected = [] if stripped.startswith("$") else None
                command = " ".join(re.sub(r"^\$\s+", "", part).split())
                out.append((command, expected if expected is not None else []))
        elif expected is not None and stripped:
            expected.append(" ".join(stripped.split()))
    return out


def _is_subsequence(expected: list[str], actual: list[str]) -> str | None:
    """None if every expected line occurs in ``actual`` in order, else the first one that does not."""
    it = iter(actual)
    for line in expected:
        if not any(line == a for a in it):
            return line
    return None


PAGES = sorted(DOCS.glob("*.md"))
ALL = [b for p in PAGES for b in blocks(p)]
PY_PAGES = [p.name for p in PAGES if any(b.info in ("python", "pycon") or ">>>" in b.body for b in blocks(p))]
TOMLS = [b for b in ALL if b.info == "toml"]
COMMANDS = [(b, c, out) for b in ALL if not b.mark for c, out in commands(b)]
CMD_PAGES = sorted({b.page for b, _, _ in COMMANDS})


def _workdir(tmp_path: Path, page_blocks: list[Block]) -> Path:
    # a copy of docs/examples (the pages' relative paths work, and a command that writes there, like
    # the measurement example, writes into the copy, never into the repository)
    shutil.copytree(DOCS / "examples", tmp_path / "docs" / "examples",
                    ignore=shutil.ignore_patterns("__pycache__", "*.so", "build"))
    for b in page_blocks:
        if b.mark and b.mark[0] == "file":
            (tmp_path / b.mark[1]).write_text(b.body, encoding="utf-8")
    return tmp_path


@pytest.mark.parametrize("page", PY_PAGES)
def test_markdown_python_blocks_run(page, tmp_path, monkeypatch):
    """The page's Python blocks, in order, in one namespace; its ``>>>`` blocks are doctests."""
    page_blocks = blocks(DOCS / page)
    monkeypatch.chdir(_workdir(tmp_path, page_blocks))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace: dict = {"__name__": f"docs_{Path(page).stem}"}
    parser, runner = doctest.DocTestParser(), doctest.DocTestRunner(optionflags=DOCTEST_FLAGS)
    ran = 0
    for b in page_blocks:
        if b.mark and b.mark[0] == "skip":
            continue
        if b.info == "pycon" or (b.info in ("python", "") and ">>>" in b.body):
            test = parser.get_doctest(b.body, namespace, b.id, str(DOCS / page), b.line)
            result = runner.run(test, clear_globs=False)
            namespace.update(test.globs)            # DocTest works on a copy; later blocks see its names
            assert result.failed == 0, f"{b.id}: {result.failed} of {result.attempted} examples failed (above)"
            ran += 1
        elif b.info == "python":
            exec(compile(b.body, f"{b.id}", "exec"), namespace)   # noqa: S102 - the page's own example
            ran += 1
    if ran == 0:
        pytest.skip(f"{page}: every Python block is marked skip")


@pytest.mark.parametrize("block", TOMLS, ids=[b.id for b in TOMLS])
def test_markdown_toml_blocks_parse(block):
    tomllib.loads(block.body)


@pytest.mark.docs
@pytest.mark.parametrize("page", CMD_PAGES)
def test_markdown_command_lines_run(page, tmp_path):
    """Each command line a page shows exits 0; a page's commands run in order in one scratch directory
    (a copy of docs/examples in it), so a worked job's later steps read what its earlier steps wrote."""
    cwd = _workdir(tmp_path, blocks(DOCS / page))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]))
    for block, command, expected in COMMANDS:
        if block.page != page:
            continue
        argv = shlex.split(command)
        argv[0] = sys.executable
        proc = subprocess.run(argv, cwd=cwd, env=env, capture_output=True, text=True, timeout=900)
        assert proc.returncode == 0, f"{block.id}: `{command}` exited {proc.returncode}:\n{proc.stderr[-2000:]}"
        # a transcript's output lines must all appear, in order, in what the command prints now
        actual = [" ".join(line.split()) for line in (proc.stdout + proc.stderr).splitlines() if line.strip()]
        missing = _is_subsequence(expected, actual)
        assert missing is None, f"{block.id}: `{command}` no longer prints:\n  {missing}\nit prints:\n{proc.stdout[-3000:]}"


def test_the_pages_show_runnable_examples():
    """The collector finds the pages' examples (a parser that silently finds nothing would pass everything)."""
    assert "getting-started.md" in PY_PAGES
    assert any(b.page == "getting-started.md" and b.info == "pycon" for b in ALL)
    assert len(COMMANDS) >= 10, COMMANDS
    assert any(expected for _, _, expected in COMMANDS), "no transcript output found"
    block = Block("x.md", 1, "", "$ python -m stability.x --a \\\n   --b\n out  put\n\n$ python -m stability.y\n", None)
    assert commands(block) == [("python -m stability.x --a --b", ["out put"]), ("python -m stability.y", [])]


# ---------------------------------------------------------------------------
# docstring examples
# ---------------------------------------------------------------------------
def _modules_with_examples() -> list[str]:
    out = []
    for info in pkgutil.walk_packages(stability.__path__, "stability."):
        if info.name.startswith("stability._generated") or info.name.endswith("__main__"):
            continue
        spec = importlib.util.find_spec(info.name)
        if spec and spec.origin and ">>>" in Path(spec.origin).read_text(encoding="utf-8"):
            out.append(info.name)
    return sorted(["stability", *out])


DOCTEST_MODULES = _modules_with_examples()


@pytest.mark.parametrize("module", DOCTEST_MODULES)
def test_docstring_examples(module, tmp_path, monkeypatch):
    """Every ``>>>`` example in the module's docstrings (doctest, ELLIPSIS and NORMALIZE_WHITESPACE)."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    mod = importlib.import_module(module)
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=DOCTEST_FLAGS)
    tests = [t for t in finder.find(mod, module) if t.examples]
    if not tests:
        pytest.skip(f"{module}: no examples in its docstrings (only in comments or strings)")
    for t in tests:
        result = runner.run(t)
        assert result.failed == 0, f"{t.name}: {result.failed} of {result.attempted} examples failed (above)"
