"""Computed numbers in the Markdown pages: the ``docvalue`` role and the ``docvalue-table`` directive.

``{docvalue}`slope_holding.power-fwd.n_m_per_deg``` is replaced, when the site builds, by the value the group
``slope_holding`` of ``value_groups.py`` computes (its key ``power-fwd.n_m_per_deg``); the value links to the
page's closing list "Computed numbers on this page", which names each group's command or API call and the CPU
time it took (its hover text names the command too). ``{docvalue-table} group.key`` renders a table value.

Groups are evaluated once per build (and cached on disk across builds, keyed by the package's sources);
an unknown group or key, or a group that raises, is a warning, so a ``-W`` build stops.
"""

from __future__ import annotations

from typing import Any

import value_groups
from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective, SphinxRole

logger = logging.getLogger(__name__)
_DONE: dict[str, tuple[dict, float, bool]] = {}


def values(name: str) -> tuple[dict, float, bool]:
    """The group's values, seconds and cached flag, evaluated once per process; logs the time it took."""
    if name not in _DONE:
        vals, took, cached = value_groups.evaluate(name)
        _DONE[name] = (vals, took, cached)
        how = "read from the cache (computed in" if cached else "computed in"
        logger.info("docvalues: %s %s %.1f s of CPU%s", name, how, took, ")" if cached else "")
    return _DONE[name]


def lookup(target: str) -> tuple[str, str, Any]:
    """``group.key`` -> (group, key, value); raises KeyError naming what is missing."""
    name, _, key = target.partition(".")
    if name not in value_groups.GROUPS:
        raise KeyError(f"no value group {name!r} (groups: {', '.join(sorted(value_groups.GROUPS))})")
    vals = values(name)[0]
    if key not in vals:
        raise KeyError(f"value group {name!r} has no value {key!r} (values: {', '.join(vals)})")
    return name, key, vals[key]


def _source_ref(name: str, child: nodes.Node) -> nodes.reference:
    ref = nodes.reference("", "", refid=f"docvalues-{name}", classes=["docvalue"])
    ref["docvalue_group"] = name
    ref += child
    return ref


class DocValueRole(SphinxRole):
    """``{docvalue}`group.key```: the computed value, linked to its group's command."""

    def run(self) -> tuple[list[nodes.Node], list[nodes.system_message]]:
        try:
            name, _, value = lookup(self.text.strip())
        except Exception as exc:  # noqa: BLE001  (any failure of a group is a build warning)
            logger.warning("docvalue %s: %s", self.text, exc, location=self.get_location())
            return [nodes.problematic(self.rawtext, self.rawtext)], []
        if not isinstance(value, str):
            logger.warning("docvalue %s is a table; use the docvalue-table directive", self.text,
                           location=self.get_location())
            return [nodes.problematic(self.rawtext, self.rawtext)], []
        abbr = nodes.abbreviation(value, value, explanation=value_groups.GROUPS[name].source)
        return [_source_ref(name, abbr)], []


def table_row(cells) -> nodes.row:
    """A docutils table row of one paragraph per cell (the value tables here and ``stability_validation``'s)."""
    row = nodes.row()
    for text in cells:
        entry = nodes.entry()
        entry += nodes.paragraph(text=text)
        row += entry
    return row


class DocValueTable(SphinxDirective):
    """``{docvalue-table} group.key``: a table value, with its command beneath it."""

    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        try:
            name, _, table = lookup(self.arguments[0])
        except Exception as exc:  # noqa: BLE001
            logger.warning("docvalue-table %s: %s", self.arguments[0], exc, location=self.get_location())
            return []
        if not isinstance(table, value_groups.Table):
            logger.warning("docvalue-table %s is not a table", self.arguments[0], location=self.get_location())
            return []
        t = nodes.table(classes=["docvalue-table"])
        g = nodes.tgroup(cols=len(table.header))
        t += g
        for _ in table.header:
            g += nodes.colspec(colwidth=1)
        head = nodes.thead()
        head += table_row(table.header)
        g += head
        body = nodes.tbody()
        g += body
        for r in table.rows:
            body += table_row(r)
        note = nodes.paragraph()
        note += nodes.Text("Computed when this page was built: ")
        note += _source_ref(name, nodes.literal(text=value_groups.GROUPS[name].source))
        return [t, note]


def _append_sources(app: Any, doctree: nodes.document) -> None:
    """End the page with the list of its value groups: command or API call, CPU time."""
    used: list[str] = []
    for ref in doctree.findall(nodes.reference):
        name = ref.get("docvalue_group")
        if name and name not in used:
            used.append(name)
    if not used:
        return
    if not hasattr(app.env, "docvalue_docs"):
        app.env.docvalue_docs = set()
    app.env.docvalue_docs.add(app.env.docname)
    section = nodes.section(ids=["computed-numbers-on-this-page"], names=["computed numbers on this page"])
    section += nodes.title(text="Computed numbers on this page")
    section += nodes.paragraph(text="Every number marked as a link on this page was computed when the site was "
                                    "built, by the command or API call named here (docs/_ext/value_groups.py).")
    items = nodes.bullet_list()
    for name in used:
        _vals, took, cached = values(name)
        item = nodes.list_item()
        para = nodes.paragraph(ids=[f"docvalues-{name}"])
        para += nodes.strong(text=name)
        para += nodes.Text(": ")
        para += nodes.literal(text=value_groups.GROUPS[name].source)
        para += nodes.Text(f" ({took:.1f} s of CPU{', read from the cache' if cached else ''})")
        item += para
        items += item
    section += items
    top = next(iter(doctree.findall(nodes.section)), None)
    (top if top is not None else doctree).append(section)


def _outdated(app: Any, env: Any, added: set, changed: set, removed: set) -> list[str]:
    """Pages that quote computed values are read again when the package's sources changed since the last build
    (an incremental build would otherwise keep the old numbers of an unchanged page)."""
    key = value_groups.source_hash()
    old, env.docvalues_hash = getattr(env, "docvalues_hash", None), key
    if old == key:
        return []
    return sorted(d for d in getattr(env, "docvalue_docs", set()) if d in env.found_docs)


def _purge(app: Any, env: Any, docname: str) -> None:
    getattr(env, "docvalue_docs", set()).discard(docname)


def _merge(app: Any, env: Any, docnames: set, other: Any) -> None:
    if not hasattr(env, "docvalue_docs"):
        env.docvalue_docs = set()
    env.docvalue_docs |= getattr(other, "docvalue_docs", set())


def setup(app: Any) -> dict[str, Any]:
    app.connect("env-get-outdated", _outdated)
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    app.add_role("docvalue", DocValueRole())
    app.add_directive("docvalue-table", DocValueTable)
    app.connect("doctree-read", _append_sources)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
