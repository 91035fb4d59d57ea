"""Command-line reference generated from the argparse parsers at build time.

``.. stability-commands::`` writes one section per command of the registry
:data:`stability.cli.commands.COMMANDS` (a new command appears by itself), each
with the ``--help`` text of its parser and of every sub-command, as literal
blocks: the page cannot fall behind the options the commands really accept.
``.. stability-cli:: stability.simulate`` renders one command.
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
    """The argparse parser of ``python -m <command>`` (``stability.simulate``)."""
    try:
        from stability.cli import commands
    except ImportError:          # before the command registry existed
        commands = None
    if commands is not None and command.startswith("stability."):
        name = command.split(".", 1)[1]
        if name in commands.COMMANDS:
            return commands.build_parser(name)
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


class StabilityCommands(SphinxDirective):
    has_content = False

    def run(self) -> list[nodes.Node]:
        from stability.cli import commands

        out: list[nodes.Node] = []
        for name in commands.COMMANDS:
            command = f"stability.{name}"
            title = f"python -m {command}"
            section = nodes.section(ids=[nodes.make_id(f"cli-{name}")], names=[nodes.fully_normalize_name(title)])
            section += nodes.title("", "", nodes.literal(text=title))
            mod = commands.command_module(name)
            doc = (mod.__doc__ or "").strip().splitlines()
            if doc:
                section += nodes.paragraph(text=doc[0])
            for i, (prog, text) in enumerate(_help_texts(parser_for(command))):
                if i:
                    section += nodes.paragraph("", "", nodes.literal(text=prog))
                block = nodes.literal_block(text, text)
                block["language"] = "text"
                section += block
            self.state.document.note_implicit_target(section, section)
            out.append(section)
        return out


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("stability-cli", StabilityCli)
    app.add_directive("stability-commands", StabilityCommands)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
