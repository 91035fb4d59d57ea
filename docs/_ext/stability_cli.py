"""Command-line reference generated from the argparse parsers at build time.

``.. stability-cli:: stability.simulate`` imports the command's parser
builder (``build_parser`` or ``_parser`` in ``<module>.__main__`` or
``<module>.command``) and renders its ``--help`` text, and that of every
sub-command, as literal blocks: the page cannot fall behind the options the
command really accepts.
"""

from __future__ import annotations

import argparse
import importlib
import os
from typing import Any

from docutils import nodes
from sphinx.util.docutils import SphinxDirective

#: Width of the rendered help (argparse reads COLUMNS).
HELP_WIDTH = 100
BUILDERS = ("build_parser", "_parser")


def parser_for(command: str) -> argparse.ArgumentParser:
    """The argparse parser of ``python -m <command>``."""
    for suffix in ("__main__", "command"):
        try:
            mod = importlib.import_module(f"{command}.{suffix}")
        except ImportError:
            continue
        for name in BUILDERS:
            builder = getattr(mod, name, None)
            if callable(builder):
                return builder()
    raise LookupError(f"{command}: no parser builder ({' or '.join(BUILDERS)}) in __main__ or command")


def _help_texts(parser: argparse.ArgumentParser) -> list[tuple[str, str]]:
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = str(HELP_WIDTH)
    try:
        out = [(parser.prog, parser.format_help())]
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for sub in action.choices.values():
                    out.append((sub.prog, sub.format_help()))
        return out
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


class StabilityCli(SphinxDirective):
    required_arguments = 1
    has_content = False

    def run(self) -> list[nodes.Node]:
        command = self.arguments[0]
        out: list[nodes.Node] = []
        texts = _help_texts(parser_for(command))
        for i, (prog, text) in enumerate(texts):
            if i:
                out.append(nodes.paragraph(text="", children=[nodes.literal(text=prog)]))
            block = nodes.literal_block(text, text)
            block["language"] = "text"
            out.append(block)
        return out


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("stability-cli", StabilityCli)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
