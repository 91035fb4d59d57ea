"""Every public function and class documents itself in numpydoc form (after python-control's docstrings_test).

Public means: listed in a module's ``__all__``.  A function with parameters has
a ``Parameters`` section naming each one (``*args``/``**kwargs`` and ``self``
aside); a function that returns something has a ``Returns`` (or ``Yields``)
section; a class has a summary and documents its fields under ``Attributes`` or
``Parameters``.  Generated code is checked by its own tests.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

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
            yield f"{module_name}.{name}", obj


ITEMS = [item for m in _modules() for item in _public(m)]


def _section(doc: str, title: str) -> str | None:
    m = re.search(rf"^\s*{title}\n\s*-+\n(.*?)(?=^\s*\w[\w ]*\n\s*-+\n|\Z)", doc, re.S | re.M)
    return m.group(1) if m else None


def _documented(section: str, name: str) -> bool:
    return re.search(rf"(^|[\s,*]){re.escape(name)}\b", section) is not None


@pytest.mark.parametrize("qualname,obj", ITEMS, ids=[q for q, _ in ITEMS])
def test_numpydoc(qualname, obj):
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
