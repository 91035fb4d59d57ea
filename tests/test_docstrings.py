"""Every public function and class documents itself in numpydoc form (after python-control's docstrings_test).

Public means: listed in a module's ``__all__``.  A function with parameters has
a ``Parameters`` section naming each one (``*args``/``**kwargs`` and ``self``
aside); a function that returns something has a ``Returns`` (or ``Yields``)
section; a class has a summary and documents its fields under ``Attributes`` or
``Parameters``.  Generated code is checked by its own tests.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import inspect
import pkgutil
import re
from pathlib import Path

import pytest

import stability

SKIP_MODULES = ("stability._generated",)
# Modules that need an optional extra (the explorer needs [app]: panel, bokeh; the sweep engine [scale]).
# Without it installed they are reported as skipped here, and CI checks them in its browser step, which
# installs [ui] and runs this file again.
OPTIONAL_IMPORTS = {"panel", "bokeh", "dask", "distributed", "pyarrow"}
UNAVAILABLE: dict[str, str] = {}


def _modules():
    out = []
    for info in pkgutil.walk_packages(stability.__path__, "stability."):
        name = info.name
        if name.startswith(SKIP_MODULES) or name.endswith("__main__"):
            continue
        out.append(name)
    return sorted(out)


def _public(module_name):
    try:
        mod = importlib.import_module(module_name)
    except ModuleNotFoundError as exc:
        if (exc.name or "").split(".")[0] not in OPTIONAL_IMPORTS:
            raise
        UNAVAILABLE[module_name] = exc.name or ""
        return
    for name in getattr(mod, "__all__", ()):
        obj = getattr(mod, name, None)
        if obj is None or getattr(obj, "__module__", None) != module_name:
            continue  # re-exports are checked where they are defined
        if inspect.isfunction(obj) or inspect.isclass(obj):
            yield f"{module_name}.{name}"


#: Modules listed from their source at collection, not imported: the explorer's, most of which import panel and
#: bokeh (about 1.5 s of CPU in every process that collects this file, and each pytest-xdist worker collects every
#: file, while the file runs on one).  The test imports each object it checks, and the listing is held to the
#: imported modules' own by test_the_source_listing_is_the_imported_listing.
FROM_SOURCE = ("stability.app",)


def _listed(module_name):
    """:func:`_public`'s names read from the module's source: the names of its literal ``__all__`` that it defines
    at its top level with ``def`` or ``class``; a module whose source imports an optional extra that is not
    installed is noted in :data:`UNAVAILABLE` instead."""
    spec = importlib.util.find_spec(module_name.rsplit(".", 1)[0])
    path = Path(spec.origin).parent / (module_name.rsplit(".", 1)[1] + ".py")
    if not path.exists():                                   # the package itself
        path = Path(spec.origin).parent / module_name.rsplit(".", 1)[1] / "__init__.py"
    tree = ast.parse(path.read_text(), str(path))
    for node in tree.body:
        roots = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                 [node.module] if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module else [])
        for root in (r.split(".")[0] for r in roots):
            if root in OPTIONAL_IMPORTS and importlib.util.find_spec(root) is None:
                UNAVAILABLE[module_name] = root
                return
    names = []
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in node.targets):
            names = list(ast.literal_eval(node.value))
    defined = {node.name for node in tree.body
               if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))}
    yield from (f"{module_name}.{name}" for name in names if name in defined)


def _items(module_name):
    return _listed(module_name) if module_name.startswith(FROM_SOURCE) else _public(module_name)


ITEMS = [item for m in _modules() for item in _items(m)]


def _object(qualname):
    module_name, _, name = qualname.rpartition(".")
    try:
        return getattr(importlib.import_module(module_name), name)
    except ModuleNotFoundError as exc:                  # an optional extra a listed module imports through another
        if (exc.name or "").split(".")[0] not in OPTIONAL_IMPORTS:
            raise
        pytest.skip(f"{module_name} needs {exc.name!r} (an optional extra); checked in CI's browser step")


def _section(doc: str, title: str) -> str | None:
    m = re.search(rf"^\s*{title}\n\s*-+\n(.*?)(?=^\s*\w[\w ]*\n\s*-+\n|\Z)", doc, re.S | re.M)
    return m.group(1) if m else None


def _documented(section: str, name: str) -> bool:
    return re.search(rf"(^|[\s,*]){re.escape(name)}\b", section) is not None


def test_the_source_listing_is_the_imported_listing():
    """The modules of :data:`FROM_SOURCE`, imported, list the same public objects in the same order as their
    source gave at collection (a public object defined otherwise than by a top-level def or class, or an
    ``__all__`` built otherwise than as a literal, would be missed by the listing: this fails first)."""
    pytest.importorskip("panel")
    pytest.importorskip("bokeh")
    listed = [m for m in _modules() if m.startswith(FROM_SOURCE)]
    assert listed
    for m in listed:
        assert list(_public(m)) == list(_listed(m)), m


@pytest.mark.parametrize("qualname", ITEMS)
def test_numpydoc(qualname):
    obj = _object(qualname)
    doc = inspect.getdoc(obj)
    assert doc and doc.strip(), f"{qualname}: no docstring"
    if inspect.isclass(obj):
        fields = getattr(obj, "__dataclass_fields__", {})
        public = [f for f in fields if not f.startswith("_")]
        if public:
            sec = _section(doc, "Attributes") or _section(doc, "Parameters")
            assert sec is not None, f"{qualname}: dataclass without an Attributes section"
            missing = [f for f in public if not _documented(sec, f)]
            assert not missing, f"{qualname}: fields not documented: {missing}"
        return
    sig = inspect.signature(obj)
    params = [p for p in sig.parameters.values()
              if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]
    if params:
        sec = _section(doc, "Parameters")
        assert sec is not None, f"{qualname}: no Parameters section"
        missing = [p.name for p in params if not _documented(sec, p.name)]
        assert not missing, f"{qualname}: parameters not documented: {missing}"
    ret = sig.return_annotation
    if ret not in (inspect.Signature.empty, None, "None", "NoReturn"):
        assert _section(doc, "Returns") is not None or _section(doc, "Yields") is not None, \
            f"{qualname}: no Returns section"


@pytest.mark.parametrize("module_name", sorted(UNAVAILABLE) or ["(none)"])
def test_modules_needing_an_optional_extra(module_name):
    """A module skipped above because its optional extra is not installed is reported, not hidden."""
    if module_name == "(none)":
        assert not UNAVAILABLE
        return
    pytest.skip(f"{module_name} needs {UNAVAILABLE[module_name]!r} (an optional extra); checked in CI's browser step")
