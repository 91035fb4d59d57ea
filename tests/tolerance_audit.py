"""Every float tolerance in tests/ and whether its error model is stated next to it (issue 34).

A *tolerance* is a comparison of two floats that allows a difference:

* ``pytest.approx`` (with or without ``rel=`` / ``abs=``; its default is ``rel=1e-6``), ``math.isclose``,
  ``numpy.isclose`` / ``allclose``, ``numpy.testing.assert_allclose`` / ``assert_almost_equal`` /
  ``assert_array_almost_equal`` / ``assert_approx_equal``;
* a comparison ``<``, ``<=`` (or ``>``, ``>=`` read backwards) whose small side takes ``abs()`` / ``np.abs()``
  of a difference or of a logarithm (``abs(a - b) < tol``, ``abs(log(a / b)) < tol``), or of anything against a
  bound below 1e-3 or naming ``EPS`` (``abs(residual) < 1e-9``: "zero up to rounding").

An exact comparison is not a tolerance: every tolerance argument given is a literal 0 and the function's default
for the others is 0 (``assert_allclose(a, b, rtol=0)``), and ``==`` is not looked at.  ``abs(x) < 1.0`` against a
bound of 1e-3 or more without a difference inside is a physical threshold, not a tolerance.

A tolerance's error model is *stated* when

* a comment on a line of its statement, or a full-line comment at most :data:`ABOVE` lines above it with no
  blank line between (or the rest of that comment's block), contains one of :data:`STATED_FORMS`; or
* its tolerance expression names something from ``tests/numerics.py`` (shared tolerances, each with its error
  model there), or a name assigned in the same file on a statement whose comments state one.

The tolerances still without one are listed in ``tests/tolerances_pending.py``; ``tests/test_tolerance_audit.py``
fails on an unstated tolerance not on that list, on an entry no longer in the tests, and on more entries than
``PENDING_LIMIT`` (which may only fall).  Nothing here imports the package: the files are parsed.

Run ``python tests/tolerance_audit.py`` for the counts, ``--missing`` for the unstated tolerances, ``--pending``
for the allow-list's text.
"""

from __future__ import annotations

import ast
import functools
import io
import re
import sys
import tokenize
from collections import deque
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"

#: The stated forms of an error model (lower case; a comment containing one states the model).
STATED_FORMS: dict[str, str] = {
    "error model": "the model written out ('error model: ...')",
    "rounding": "rounding of printed/stored values or of float arithmetic (with how many roundings)",
    "round-off": "float arithmetic's round-off",
    "ulp": "a count of units in the last place",
    "eps": "a multiple of the machine epsilon (n eps cond(A), steps x eps, ...)",
    "bisection": "a bisection's bracket (the search's relative tolerance)",
    "bracket": "a search's bracket",
    "first order in": "a neglected effect entering at first order in a small parameter",
    "second order in": "a neglected effect entering at second order in a small parameter",
    "next order": "agreement up to the next order of an expansion",
    "truncation": "a discretisation's truncation error (order and step)",
    "standard error": "a Monte Carlo or fit's standard error",
    "exact": "equal in exact arithmetic: only rounding is allowed",
}

#: A full-line comment at most this many lines above a statement, with no blank line between (a comment heading a
#: block of assertions), belongs to it, and so does the rest of its comment block.
ABOVE = 8

_APPROX = {"approx"}
_NUMPY = {"isclose", "allclose", "assert_allclose", "assert_almost_equal", "assert_array_almost_equal",
          "assert_approx_equal"}
#: tolerance keywords per function, with their positional index (after the two compared values) and default
_TOL_ARGS: dict[str, tuple[tuple[str, int | None, float], ...]] = {
    "approx": (("rel", None, 1e-6), ("abs", None, 1e-12)),
    "isclose": (("rtol", 2, 1e-5), ("atol", 3, 1e-8), ("rel_tol", None, 1e-9), ("abs_tol", None, 0.0)),
    "allclose": (("rtol", 2, 1e-5), ("atol", 3, 1e-8)),
    "assert_allclose": (("rtol", 2, 1e-7), ("atol", 3, 0.0)),
    "assert_almost_equal": (("decimal", 2, 7.0),),
    "assert_array_almost_equal": (("decimal", 2, 6.0),),
    "assert_approx_equal": (("significant", 2, 7.0),),
}
_SMALL_BOUND = 1e-3


@dataclass(frozen=True)
class Tolerance:
    """One tolerance: where it is, its comparison's text (the allow-list's key) and whether its model is stated."""

    path: str          # relative to the repository root
    line: int
    function: str      # enclosing test function ("Class.method", "<module>")
    snippet: str       # the comparison's source, whitespace collapsed, at most 90 characters
    stated: bool

    @property
    def key(self) -> tuple[str, str, str]:
        return self.path, self.function, self.snippet


def _name(func: ast.expr) -> str | None:
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute):
        return func.attr
    return None


def _is_zero(node: ast.expr) -> bool:
    return isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and node.value == 0


def _call_tolerance(call: ast.Call) -> tuple[list[ast.expr], bool] | None:
    """(tolerance argument expressions, exact?) of a comparison call, or None when it is not one."""
    name = _name(call.func)
    if name not in _TOL_ARGS:
        return None
    if name == "isclose" and isinstance(call.func, ast.Attribute) and _name(call.func.value) == "math":
        spec = tuple(s for s in _TOL_ARGS[name] if s[0] in ("rel_tol", "abs_tol"))
    elif name == "isclose":
        spec = _TOL_ARGS[name][:2]
    else:
        spec = _TOL_ARGS[name]
    given = {k.arg: k.value for k in call.keywords if k.arg}
    exprs: list[ast.expr] = []
    exact = True
    for arg, pos, default in spec:
        expr = given.get(arg)
        if expr is None and pos is not None and pos < len(call.args):
            expr = call.args[pos]
        if expr is None:
            exact = exact and default == 0.0
        else:
            exprs.append(expr)
            exact = exact and _is_zero(expr)
    if name in ("assert_almost_equal", "assert_array_almost_equal", "assert_approx_equal"):
        exact = False
    return exprs, exact


def _has_float_below(node: ast.expr, limit: float) -> bool:
    for n in ast.walk(node):
        if isinstance(n, ast.Constant) and isinstance(n.value, float) and 0 < abs(n.value) < limit:
            return True
        if isinstance(n, ast.Name) and n.id == "EPS":
            return True
    return False


def _compare_tolerance(cmp: ast.Compare) -> ast.expr | None:
    """The bound of an ``abs(...) < bound`` tolerance, or None."""
    if len(cmp.ops) != 1:
        return None
    op = cmp.ops[0]
    if isinstance(op, (ast.Lt, ast.LtE)):
        small, bound = cmp.left, cmp.comparators[0]
    elif isinstance(op, (ast.Gt, ast.GtE)):
        small, bound = cmp.comparators[0], cmp.left
    else:
        return None
    absolutes = [c for c in ast.walk(small) if isinstance(c, ast.Call) and _name(c.func) in ("abs", "fabs")]
    if not absolutes or _is_zero(bound):
        return None
    inner = [n for c in absolutes for n in ast.walk(c)]
    difference = any(isinstance(n, ast.BinOp) and isinstance(n.op, ast.Sub) for n in inner)
    logarithm = any(isinstance(n, ast.Call) and _name(n.func) in ("log", "log1p", "log10") for n in inner)
    if difference or logarithm or _has_float_below(bound, _SMALL_BOUND):
        return bound
    return None


def _comments(src: str) -> dict[int, tuple[str, bool]]:
    """line -> (comment text lower-cased, full-line?)"""
    out: dict[int, tuple[str, bool]] = {}
    lines = src.splitlines()
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        if tok.type == tokenize.COMMENT:
            row = tok.start[0]
            out[row] = (tok.string.lower(), lines[row - 1].strip().startswith("#"))
    return out


def states_model(text: str) -> bool:
    """Whether a comment's text states an error model (one of :data:`STATED_FORMS`)."""
    text = text.lower()
    return any(re.search(r"(?<![a-z])" + re.escape(form) + r"(?![a-z])", text) for form in STATED_FORMS)


class _FileScan:
    def __init__(self, path: Path, src: str | None = None):
        self.path = path
        self.rel = path.relative_to(ROOT).as_posix()
        self.src = path.read_text(encoding="utf-8") if src is None else src
        self.tree = ast.parse(self.src, str(path))
        self.comments = _comments(self.src)
        self.parents: dict[ast.AST, ast.AST] = {}
        #: every node in ``ast.walk``'s order (breadth first), listed in the one walk that finds the parents: the
        #: scans below read this list instead of walking the tree again (most of a scan's time)
        self.nodes: list[ast.AST] = []
        todo = deque([self.tree])
        while todo:
            node = todo.popleft()
            self.nodes.append(node)
            for child in ast.iter_child_nodes(node):
                self.parents[child] = node
                todo.append(child)
        self.numerics_names = {a.asname or a.name for n in self.nodes if isinstance(n, ast.ImportFrom)
                               and n.module == "numerics" for a in n.names}
        self.stated_names = self._stated_names()

    def _window_stated(self, first: int, last: int) -> bool:
        for row in range(first, last + 1):
            if row in self.comments and states_model(self.comments[row][0]):
                return True
        lines = self.lines
        row = first - 1
        while row >= max(1, first - ABOVE) and lines[row - 1].strip():
            if row in self.comments and self.comments[row][1] and states_model(self.comments[row][0]):
                return True
            row -= 1
        while row >= 1 and row in self.comments and self.comments[row][1]:     # the rest of a comment block
            if states_model(self.comments[row][0]):
                return True
            row -= 1
        return False

    @functools.cached_property
    def lines(self) -> list[str]:
        """The source's lines, split once (splitting it per tolerance was most of a scan's time)."""
        return self.src.splitlines()

    @functools.cached_property
    def _rows(self) -> list[bytes] | None:
        """The source's rows as ast splits them (at newlines only), UTF-8; None if it has a carriage return."""
        return None if "\r" in self.src else [r.encode("utf-8") for r in self.src.split("\n")]

    def _segment(self, node: ast.AST) -> str:
        """``ast.get_source_segment(self.src, node)``, without splitting the whole source again for each node."""
        rows = self._rows
        if rows is None:
            return ast.get_source_segment(self.src, node) or ""
        first, last = node.lineno - 1, (node.end_lineno or node.lineno) - 1      # type: ignore[attr-defined]
        start, end = node.col_offset, node.end_col_offset                          # type: ignore[attr-defined]
        if first == last:
            return rows[first][start:end].decode("utf-8")
        parts = [rows[first][start:], *rows[first + 1:last], rows[last][:end]]
        return b"\n".join(parts).decode("utf-8")

    def _statement(self, node: ast.AST) -> tuple[int, int]:
        """Lines of the simple statement holding ``node`` (of ``node`` itself inside a compound header)."""
        cur: ast.AST | None = node
        while cur is not None and not isinstance(cur, ast.stmt):
            cur = self.parents.get(cur)
        if cur is None or isinstance(cur, (ast.If, ast.For, ast.While, ast.With, ast.Try, ast.FunctionDef,
                                           ast.AsyncFunctionDef, ast.ClassDef, ast.AsyncFor, ast.AsyncWith)):
            return node.lineno, node.end_lineno or node.lineno  # type: ignore[attr-defined]
        return cur.lineno, cur.end_lineno or cur.lineno

    def _stated_names(self) -> set[str]:
        names: set[str] = set()
        for node in self.nodes:
            targets: list[ast.expr] = []
            if isinstance(node, ast.Assign):
                targets = node.targets
            elif isinstance(node, (ast.AnnAssign, ast.AugAssign)):
                targets = [node.target]
            elif isinstance(node, (ast.For, ast.comprehension)):
                targets = [node.target]
            if not targets:
                continue
            first, last = (node.iter.lineno, node.iter.end_lineno) if isinstance(node, (ast.For, ast.comprehension)) \
                else (node.lineno, node.end_lineno)
            if isinstance(node, ast.comprehension):
                first, last = self._statement(node.iter)
            elif isinstance(node, ast.For):
                first = node.lineno
            if self._window_stated(first, last or first):
                names.update(n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name))
        return names

    def _by_name(self, exprs: list[ast.expr]) -> bool:
        for expr in exprs:
            for n in ast.walk(expr):
                if isinstance(n, ast.Name) and (n.id in self.numerics_names or n.id in self.stated_names):
                    return True
                if isinstance(n, ast.Attribute) and _name(n.value) == "numerics":
                    return True
        return False

    def _function(self, node: ast.AST) -> str:
        names = []
        cur = self.parents.get(node)
        while cur is not None:
            if isinstance(cur, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names.append(cur.name)
            cur = self.parents.get(cur)
        return ".".join(reversed(names)) or "<module>"

    def tolerances(self) -> list[Tolerance]:
        out = []
        for node in self.nodes:
            exprs: list[ast.expr]
            if isinstance(node, ast.Call):
                found = _call_tolerance(node)
                if found is None or found[1]:
                    continue
                exprs = found[0]
            elif isinstance(node, ast.Compare):
                bound = _compare_tolerance(node)
                if bound is None:
                    continue
                exprs = [bound]
            else:
                continue
            first, last = self._statement(node)
            stated = self._window_stated(first, last) or self._by_name(exprs)
            text = " ".join(self._segment(node).split())
            out.append(Tolerance(self.rel, node.lineno, self._function(node), text[:90], stated))
        return sorted(out, key=lambda t: (t.path, t.line, t.snippet))


def test_files() -> list[Path]:
    """Every Python file under tests/ (helpers, benchmarks and UI tests included)."""
    return sorted(p for p in TESTS.rglob("*.py") if "__pycache__" not in p.parts)


def scan(paths: list[Path] | None = None) -> list[Tolerance]:
    """Every tolerance in ``paths`` (default: :func:`test_files`)."""
    return [t for p in (paths or test_files()) for t in _FileScan(p).tolerances()]


def scan_source(src: str, name: str = "tests/test_example.py") -> list[Tolerance]:
    """The tolerances of one source text (for the scanner's own tests)."""
    scanner = _FileScan(ROOT / name, src)
    return scanner.tolerances()


def pending_text(found: list[Tolerance]) -> str:
    """The ``PENDING`` dict of ``tests/tolerances_pending.py`` for the unstated tolerances in ``found``."""
    lines = ["PENDING: dict[str, list[tuple[str, str]]] = {"]
    by_path: dict[str, list[Tolerance]] = {}
    for t in found:
        if not t.stated:
            by_path.setdefault(t.path, []).append(t)
    for path, items in by_path.items():
        lines.append(f"    {path!r}: [")
        lines.extend(f"        ({t.function!r}, {t.snippet!r})," for t in items)
        lines.append("    ],")
    lines.append("}")
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    found = scan()
    stated = sum(t.stated for t in found)
    if "--missing" in argv:
        for t in found:
            if not t.stated:
                print(f"{t.path}:{t.line}: {t.function}: {t.snippet}")
    if "--pending" in argv:
        print(pending_text(found))
    print(f"{len(found)} tolerances, {stated} with a stated error model, {len(found) - stated} without",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
