"""API reference pages generated from the public ``__all__`` of every package and top-level module.

At ``builder-inited`` this writes ``api/index.rst`` and one ``api/<module>.rst``
per public module of :mod:`stability` (the packages and the modules directly
under it that declare ``__all__``), each an ``automodule`` limited to
``__all__``: the reference can neither miss a public name nor list a private one.
``public_names()`` is what ``tests/test_docs_site.py`` checks the built
``objects.inv`` against.

A cross-reference in a docstring may name an object where it is defined
(``stability.assist.plant.standstill_plant``) while the reference documents it
where it is exported (``stability.assist.standstill_plant``): the
``missing-reference`` handler resolves such a target to the documented name of
the same Python object, so ``-n`` (nitpicky) still reports every reference
that resolves to nothing.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
from pathlib import Path
from typing import Any

PACKAGE = "stability"
API_DIR = "api"


def public_modules() -> list[str]:
    """The modules whose ``__all__`` the reference documents: the package itself, its direct children, and the
    topic modules of a child package that has no ``__all__`` of its own (``runtime``, ``settings``)."""
    pkg = importlib.import_module(PACKAGE)
    out = [PACKAGE]
    for info in pkgutil.iter_modules(pkg.__path__, PACKAGE + "."):
        if info.name.rsplit(".", 1)[-1].startswith("_"):
            continue
        mod = importlib.import_module(info.name)
        if getattr(mod, "__all__", None) is not None:
            out.append(info.name)
        elif info.ispkg:
            for sub in pkgutil.iter_modules(mod.__path__, info.name + "."):
                if not sub.name.rsplit(".", 1)[-1].startswith("_") and \
                        getattr(importlib.import_module(sub.name), "__all__", None) is not None:
                    out.append(sub.name)
    return out


def public_names() -> dict[str, list[str]]:
    """``{module: [name, ...]}`` for every public module (its ``__all__``, in order)."""
    return {m: list(importlib.import_module(m).__all__) for m in public_modules()}


def _title(mod: str) -> str:
    doc = inspect.getdoc(importlib.import_module(mod)) or ""
    first = doc.strip().splitlines()[0].rstrip(".") if doc.strip() else ""
    return first


def _write_if_changed(path: Path, text: str) -> None:
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _home(obj: Any, mods: list[str]) -> str | None:
    """The public module a class is documented in: the longest one its defining module lies in."""
    where = getattr(obj, "__module__", "") or ""
    homes = [m for m in mods if where == m or where.startswith(m + ".")]
    return max(homes, key=len) if homes else None


def _data_doc(mod: str, name: str) -> list[str]:
    """The ``#:`` comment of a module-level name, looked up where it is assigned (the module or,
    for a re-export, one of its submodules)."""
    m = importlib.import_module(mod)
    places = [mod]
    if hasattr(m, "__path__"):
        places += [i.name for i in pkgutil.walk_packages(m.__path__, mod + ".")]
    from sphinx.pycode import ModuleAnalyzer  # sphinx only when the site builds: tests import this module

    for place in places:
        try:
            docs = ModuleAnalyzer.for_module(place).find_attr_docs()
        except Exception:  # noqa: BLE001 - a module without source (generated, compiled) has no comments
            continue
        if ("", name) in docs:
            return [line for line in docs[("", name)] if line.strip() or True]
    return []


def _value(obj: Any) -> str | None:
    text = repr(obj)
    return text if len(text) <= 70 and "\n" not in text else None


def _page(mod: str, mods: list[str]) -> str:
    """One module's page: automodule over ``__all__``.

    Module-level data (constants, tables) get an explicit ``py:data`` entry
    with their ``#:`` comment (automodule skips data without one). A class
    exported from a module other than its home (``stability.Chair``, home
    ``stability.chair``) gets a short alias entry, since two full descriptions
    of one class would register its canonical name twice.
    """
    m = importlib.import_module(mod)
    aliases: list[tuple[str, str]] = []
    data: list[str] = []
    submodules: list[str] = []
    for name in m.__all__:
        obj = getattr(m, name)
        if inspect.isclass(obj):
            home = _home(obj, mods)
            if home is not None and home != mod and name in getattr(importlib.import_module(home), "__all__", ()):
                aliases.append((name, f"{home}.{name}"))
        elif inspect.ismodule(obj):
            submodules.append(name)
        elif not (inspect.isfunction(obj) or inspect.isbuiltin(obj)):
            data.append(name)
    heading = f"``{mod}``"
    text = (f".. This page is generated by docs/_ext/stability_api.py; do not edit.\n\n"
            f"{heading}\n{'=' * len(heading)}\n\n"
            f".. automodule:: {mod}\n   :members:\n   :undoc-members:\n")
    excluded = [n for n, _ in aliases] + data + submodules
    if excluded:
        text += f"   :exclude-members: {', '.join(excluded)}\n"
    for name, target in aliases:
        text += (f"\n.. py:class:: {name}\n   :no-index-entry:\n\n"
                 f"   The class :class:`{target}`, exported here as well.\n")
    for name in data:
        text += f"\n.. py:data:: {name}\n"
        value = _value(getattr(m, name))
        if value is not None:
            text += f"   :value: {value}\n"
        doc = _data_doc(mod, name)
        text += "\n" + "".join(f"   {line}\n" if line.strip() else "\n" for line in doc or
                                ["(A module-level constant; see the module's description.)"])
    for name in submodules:
        sub = getattr(m, name).__name__
        head = f"``{sub}``"
        text += (f"\n{head}\n{'-' * len(head)}\n\n.. automodule:: {sub}\n   :members:\n   :undoc-members:\n"
                 f"\n.. currentmodule:: {mod}\n")
    return text


def write_pages(srcdir: Path) -> None:
    out = srcdir / API_DIR
    out.mkdir(exist_ok=True)
    mods = public_modules()
    for m in mods:
        _write_if_changed(out / f"{m}.rst", _page(m, mods))
    lines = [".. This page is generated by docs/_ext/stability_api.py; do not edit.", "",
             "API reference", "=============", "",
             "Every name in the ``__all__`` of each package and top-level module, documented from its",
             "numpydoc docstring (units in the parameter descriptions). The layers and what each",
             "package is for: :doc:`../architecture`.", "",
             ".. list-table::", "   :header-rows: 1", "   :widths: 30 70", "",
             "   * - module", "     - what it holds"]
    for m in mods:
        lines += [f"   * - :doc:`{m}`", f"     - {_title(m) or '(no summary)'}"]
    lines += ["", ".. toctree::", "   :hidden:", ""] + [f"   {m}" for m in mods] + [""]
    _write_if_changed(out / "index.rst", "\n".join(lines))
    for stale in out.glob("*.rst"):
        if stale.stem not in mods and stale.stem != "index":
            stale.unlink()


#: Per-build cache (not pickled with the environment): the documented objects, built on first use.
_CACHE: dict[str, Any] = {}


def _builder_inited(app: Any) -> None:
    _CACHE.clear()
    write_pages(Path(app.srcdir))


def _skip_member(app: Any, what: str, name: str, obj: Any, skip: bool, options: Any) -> bool | None:
    # Class data attributes (dataclass fields, constants) are documented in the class's numpydoc
    # Attributes section; listing them again as autodoc entries would only repeat it.
    if what == "class" and not (callable(obj) or isinstance(obj, property)):
        return True
    return None


def _import_target(target: str) -> Any:
    parts = target.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for attr in parts[i:]:
            obj = getattr(obj, attr)
        return obj
    raise ImportError(target)


def _documented(env: Any) -> tuple[dict[int, tuple[str, Any]], dict[str, list[tuple[str, Any]]]]:
    """Documented stability objects by identity (functions, classes) and by last name component."""
    if "documented" in _CACHE:
        return _CACHE["documented"]
    by_id: dict[int, tuple[str, Any]] = {}
    by_last: dict[str, list[tuple[str, Any]]] = {}
    objects = env.get_domain("py").objects
    for fullname, entry in sorted(objects.items(), key=lambda kv: (kv[0].count("."), kv[0])):
        if entry.objtype == "module" or not fullname.startswith(PACKAGE) or entry.aliased:
            continue
        by_last.setdefault(fullname.rsplit(".", 1)[-1], []).append((fullname, entry))
        try:
            obj = _import_target(fullname)
        except Exception:  # noqa: BLE001 - a documented name that does not import is simply not matched
            continue
        if inspect.isfunction(obj) or inspect.isclass(obj):
            by_id.setdefault(id(obj), (fullname, entry))
    _CACHE["documented"] = (by_id, by_last)
    return by_id, by_last


def _resolve(env: Any, target: str, modname: str | None) -> tuple[str, Any] | None:
    by_id, by_last = _documented(env)
    py = env.get_domain("py")
    candidates = [target] if target.startswith(PACKAGE) else []
    if modname and not target.startswith(PACKAGE):
        candidates.append(f"{modname}.{target.lstrip('.')}")
    for cand in candidates:
        try:
            obj = _import_target(cand)
        except Exception:  # noqa: BLE001 - not importable under that name
            continue
        if inspect.ismodule(obj):
            name = obj.__name__
            while name and name not in py.modules:
                name = name.rpartition(".")[0]
            if name:
                return name, py.modules[name]
            continue
        if id(obj) in by_id:
            return by_id[id(obj)]
        hits = [(n, e) for n, e in by_last.get(cand.rsplit(".", 1)[-1], []) if _is(n, obj)]
        if hits:
            return hits[0]
    # a name relative to the module that defines the docstring (which autodoc does not record):
    # the documented objects whose name ends with it, if they are all one object
    last = target.lstrip(".~").rsplit(".", 1)[-1]
    owner = target.lstrip(".~").rsplit(".", 1)[0] if "." in target.lstrip(".~") else None
    hits = [(n, e) for n, e in by_last.get(last, []) if n.endswith("." + target.lstrip(".~"))]
    if hits and len({id(_safe_import(n)) for n, _ in hits}) == 1:
        return hits[0]
    if owner is not None and not hits:
        # Class.attribute: the attribute is documented in the class's Attributes section
        found = _resolve(env, owner, modname)
        if found is not None and getattr(found[1], "objtype", None) == "class":
            return found
    return None


def _safe_import(name: str) -> Any:
    try:
        return _import_target(name)
    except Exception:  # noqa: BLE001
        return name


def _is(name: str, obj: Any) -> bool:
    return _safe_import(name) is obj


def _exists(target: str, modname: str | None) -> bool:
    """Whether a reference names a real stability object (public or not), absolutely or relative to
    the module being documented or one of its submodules."""
    target = target.lstrip(".~")
    if target.startswith(PACKAGE + "."):
        return not isinstance(_safe_import(target), str)
    if not modname or not modname.startswith(PACKAGE):
        return False
    places = [modname]
    pkg = importlib.import_module(modname)
    if hasattr(pkg, "__path__"):
        places += [i.name for i in pkgutil.walk_packages(pkg.__path__, modname + ".")]
    return any(not isinstance(_safe_import(f"{p}.{target}"), str) for p in places)


def _missing_reference(app: Any, env: Any, node: Any, contnode: Any) -> Any:
    if node.get("refdomain") != "py":
        return None
    found = _resolve(env, node.get("reftarget", ""), node.get("py:module"))
    if found is None and node.get("py:class"):    # an attribute named inside its class's methods
        found = _resolve(env, f"{node['py:class']}.{node.get('reftarget', '')}", node.get("py:module"))
    if found is None:
        # A real but unexported helper (a docstring naming the function it delegates to) stays
        # plain text; a name that does not exist at all (a typo, a rename) keeps its warning.
        return contnode if _exists(node.get("reftarget", ""), node.get("py:module")) else None
    from sphinx.util.nodes import make_refnode

    fullname, entry = found
    return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode, fullname)


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _builder_inited)
    app.connect("autodoc-skip-member", _skip_member)
    app.connect("missing-reference", _missing_reference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}

