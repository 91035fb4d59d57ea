"""``.. stability-command-output::``: commands and what they print, run when the site is built.

Each line of the directive's content is a command ``python -m stability.NAME ARGS``; the directive runs it in
the build's process (the command's ``main(argv)`` from :data:`stability.cli.commands.COMMANDS`, standard output
captured) and renders the command and its output as one literal block, so the numbers a page quotes are the
numbers the command gives today, shown beside it.  A command that exits non-zero is a build warning (a ``-W``
build stops).

Example (MyST)::

    ```{stability-command-output}
    python -m stability.study critical-impulse --chair power-fwd-base --speeds 1,-1
    ```
"""

from __future__ import annotations

import contextlib
import io
import shlex
import time
from typing import Any

from docutils import nodes
from sphinx.util import logging
from sphinx.util.docutils import SphinxDirective

logger = logging.getLogger(__name__)
PREFIX = ("python", "-m")


def run_command(line: str) -> tuple[int, str, str]:
    """Run ``python -m stability.NAME ARGS`` in this process: ``(exit status, standard output, standard error)``.

    Raises
    ------
    ValueError
        A line that is not such a command, or an unknown command.
    """
    from stability.cli import commands

    words = shlex.split(line)
    if len(words) < 3 or tuple(words[:2]) != PREFIX or not words[2].startswith("stability."):
        raise ValueError(f"{line!r} is not a command 'python -m stability.NAME ...'")
    module = commands.command_module(words[2].split(".", 1)[1])
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        status = module.main(words[3:])
    return int(status or 0), out.getvalue().rstrip("\n"), err.getvalue().strip()


class StabilityCommandOutput(SphinxDirective):
    has_content = True

    def run(self) -> list[nodes.Node]:
        parts = []
        for line in (x.strip() for x in self.content):
            if not line:
                continue
            start = time.perf_counter()
            try:
                status, text, err = run_command(line)
            except Exception as exc:  # noqa: BLE001  (any failure of a command is a build warning)
                status, text, err = 2, "", f"{type(exc).__name__}: {exc}"
            if status:
                logger.warning("stability-command-output: %r exited %d: %s", line, status, err,
                               location=self.get_location())
            logger.info("stability-command-output: %r took %.1f s", line, time.perf_counter() - start)
            parts.append(f"$ {line}\n{text}")
        block = nodes.literal_block("", "\n\n".join(parts))
        block["language"] = "text"
        note = nodes.paragraph(text="Run when this page was built; the output above is the commands' own.")
        return [block, note]


def setup(app: Any) -> dict[str, Any]:
    app.add_directive("stability-command-output", StabilityCommandOutput)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
