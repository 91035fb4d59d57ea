"""docs/architecture.md is true: its layer order, its one door to the generated code, no import cycles, every
package placed (the rules are stated there; this test reads them from that page)."""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "stability"
DOC = ROOT / "docs" / "architecture.md"


def _blocks() -> list[str]:
    return re.findall(r"```text\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)


def layers() -> list[tuple[str, list[str]]]:
    """(layer, entries) from the bottom up, as the page lists them."""
    block = next(b for b in _blocks() if b.lstrip().startswith("runtime"))
    out = []
    for line in block.strip().splitlines():
        name, *entries = line.split()
        out.append((name, entries))
    return out


def exceptions() -> set[tuple[str, str]]:
    block = next(b for b in _blocks() if " -> " in b)
    return {(a, b.split()[0]) for a, b in (line.split(" -> ", 1) for line in block.strip().splitlines())}


def modules() -> dict[str, Path]:
    out = {}
    for path in PKG.rglob("*.py"):
        if "__pycache__" in path.parts:
            continue
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def _type_checking(node: ast.AST) -> bool:
    return isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)


def imports(path: Path, known: set[str]) -> set[str]:
    """The package modules ``path`` imports (inside functions too; not under ``if TYPE_CHECKING``): for
    ``from a import n`` the module ``a.n`` when it is one, else ``a``."""

    def resolve(name: str) -> str | None:
        parts = name.split(".")
        for i in range(len(parts), 0, -1):
            if ".".join(parts[:i]) in known:
                return ".".join(parts[:i])
        return None

    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        for child in ast.iter_child_nodes(node):
            if _type_checking(child):
                for c in child.orelse:       # type: ignore[attr-defined]
                    visit(c)
                continue
            if isinstance(child, ast.ImportFrom):
                assert child.level == 0, f"{path}: relative import (the package uses absolute imports)"
                for a in child.names:
                    if child.module == "stability" and a.name.startswith("__"):
                        continue                     # __version__: the facade's own constant, no dependency
                    r = resolve(f"{child.module}.{a.name}") or resolve(child.module or "")
                    if r:
                        found.add(r)
            elif isinstance(child, ast.Import):
                found.update(r for a in child.names if (r := resolve(a.name)))
            visit(child)

    visit(ast.parse(path.read_text(encoding="utf-8")))
    return found


@functools.lru_cache(maxsize=1)
def graph() -> dict[str, frozenset[str]]:
    """Every package module -> the package modules it imports (:func:`imports`), parsed once for the tests here."""
    mods = modules()
    return {m: frozenset(imports(path, set(mods))) for m, path in mods.items()}


def layer_of(module: str, table: list[tuple[str, list[str]]]) -> int:
    """Index of ``module``'s layer (0 = bottom); the package facade ``stability`` is above every layer."""
    parts = module.split(".")
    if len(parts) == 1:
        return len(table)
    by_package = {e.rstrip("/"): i for i, (_, es) in enumerate(table) for e in es if e.endswith("/")
                  and not e.startswith("*")}
    own = by_package[parts[1]]
    leaf = parts[-1] if len(parts) > 2 else ""
    for i, (_, entries) in enumerate(table):
        for e in entries:
            if e.startswith("*/") and re.fullmatch(e[2:].replace(".py", "").replace("*", ".*"), leaf) and i > own:
                return i
    return own


def _name(module: str, table: list[tuple[str, list[str]]]) -> str:
    i = layer_of(module, table)
    return table[i][0] if i < len(table) else "the package facade"


def test_every_package_is_placed_once():
    listed = [e.rstrip("/") for _, es in layers() for e in es if not e.startswith("*")]
    on_disk = {p.name for p in PKG.iterdir() if (p / "__init__.py").exists() or p.name == "data"}
    loose = sorted(p.name for p in PKG.glob("*.py") if p.name != "__init__.py")
    assert not loose, f"modules loose at the top of stability/ (give each its layer's package): {loose}"
    assert len(listed) == len(set(listed))
    assert set(listed) == on_disk, (sorted(set(listed) - on_disk), sorted(on_disk - set(listed)))


def test_imports_go_down_the_layers_only():
    table, allowed = layers(), exceptions()
    wrong = []
    for m, targets in graph().items():
        for t in targets:
            if t != m and layer_of(t, table) > layer_of(m, table) and (m, t) not in allowed:
                wrong.append(f"{m} ({_name(m, table)}) imports {t} ({_name(t, table)})")
    assert not wrong, "\n".join(wrong)


def test_the_exceptions_are_still_needed():
    for a, b in exceptions():
        assert b in graph()[a], f"{a} -> {b} is listed but no longer imported: remove it"


def test_only_models_open_the_generated_code():
    wrong = [m for m, targets in graph().items() if not m.startswith(("stability.models", "stability._generated"))
             and any(t.startswith("stability._generated") for t in targets)]
    assert not wrong, wrong


def test_no_import_cycles():
    deps = {m: targets - {m} for m, targets in graph().items()}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    cycles: list[list[str]] = []

    def strong(v: str) -> None:          # Tarjan's strongly connected components
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in deps[v]:
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in deps:
        if v not in index:
            strong(v)
    assert not cycles, cycles


def test_the_checker_sees_an_upward_import():
    """The layer test is not vacuous: a study imported by the linear layer is caught."""
    table = layers()
    assert layer_of("stability.study.impulse", table) > layer_of("stability.linear.model", table)
    assert layer_of("stability.simulate.plot", table) > layer_of("stability.simulate.api", table)
    assert layer_of("stability.simulate.__main__", table) == len(table) - 1
    assert layer_of("stability.app.plots", table) == len(table) - 1        # the app stays in its own layer
