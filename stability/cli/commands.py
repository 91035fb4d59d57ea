"""The command lines, registered once: ``stability NAME ...`` and ``python -m stability.NAME ...``.

:data:`COMMANDS` maps each command's name to the module that holds its
``build_parser()`` and ``main(argv)``.  The console script ``stability``
(``pip install`` puts it on the PATH) dispatches ``stability critical-speed
--chair revised`` to ``python -m stability.critical_speed --chair revised``;
the tests walk :data:`COMMANDS` to check every parser (the shared options,
the defaults of :mod:`stability.settings.defaults`, the JSON schemas of
:mod:`stability.schemas`).  A new command adds one line here.

Examples
--------
>>> from stability.cli.commands import COMMANDS, build_parser
>>> "simulate" in COMMANDS
True
>>> build_parser("simulate").prog
'python -m stability.simulate'
"""

from __future__ import annotations

import argparse
import importlib
import sys
from collections.abc import Sequence
from types import ModuleType

__all__ = ["COMMANDS", "command_module", "build_parser", "main"]

#: Command name (as ``python -m stability.NAME`` spells it) -> module with ``build_parser()`` and ``main(argv)``.
COMMANDS: dict[str, str] = {
    "critical_speed": "stability.critical_speed.command",
    "compare": "stability.compare.__main__",
    "simulate": "stability.simulate.__main__",
    "study": "stability.study.__main__",
    "shimmy": "stability.shimmy.__main__",
    "slope": "stability.slope.__main__",
    "assist": "stability.assist.__main__",
    "measure": "stability.measure.__main__",
    "report": "stability.report.command",
    "chair": "stability.chair.__main__",
    "sweep": "stability.sweep.__main__",
    "tipping": "stability.tipping.__main__",
    "advise": "stability.advise.__main__",
    "bench": "stability.bench.__main__",
    "app": "stability.app.server",
}


def _canonical(name: str) -> str:
    key = name.replace("-", "_")
    if key not in COMMANDS:
        raise ValueError(f"command {name!r} is unknown; valid commands: {', '.join(_spelled())}")
    return key


def _spelled() -> list[str]:
    return [n.replace("_", "-") for n in COMMANDS]


def command_module(name: str) -> ModuleType:
    """The module of command ``name`` (``"critical-speed"`` or ``"critical_speed"``).

    Parameters
    ----------
    name : str
        A key of :data:`COMMANDS`, with ``-`` or ``_``.

    Returns
    -------
    module
        It has ``build_parser()`` and ``main(argv)``.
    """
    return importlib.import_module(COMMANDS[_canonical(name)])


def build_parser(name: str) -> argparse.ArgumentParser:
    """The argument parser of command ``name``.

    Parameters
    ----------
    name : str
        A key of :data:`COMMANDS`.

    Returns
    -------
    argparse.ArgumentParser
    """
    module = command_module(name)
    return (getattr(module, "build_parser", None) or module._parser)()


_USAGE = """usage: stability COMMAND [options]   (the same as python -m stability.COMMAND [options])

commands:
  critical-speed  how stable is this chair, and at which speeds (linear analysis)
  compare         which chair is more stable, by how much, and why
  simulate        simulate a chair disturbed from straight motion (nonlinear)
  study           critical impulse and equal-instability speed (robust measures)
  shimmy          caster shimmy: critical trail and the pin friction that holds it
  slope           cross slope: holding moment, hand-rim forces, uncorrected turn
  assist          motor assist for a power chair: gains, margins, checks
  measure         measurement sheet -> chair file and uncertainty file
  report          a multi-page PDF report on one chair
  chair           chair files: export a preset to start from (chair export PRESET -o chair.toml)
  tipping         static tip angles (ISO 7176-1) of the rigid chair
  advise          what to change on this chair, and what it costs
  bench           virtual test bench: ISO 7176-2 wheel lift and ISO 7176-3 braking distance (power chairs)
  app             the interactive explorer: a local web page (127.0.0.1)

stability COMMAND --help shows a command's options."""


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``stability`` console script: ``stability COMMAND [options]``.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The command's exit status; 2 for an unknown command (one line on stderr), 0 for ``--help``.
    """
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or args[0] in ("-h", "--help"):
        print(_USAGE)
        return 0 if args else 2
    if args[0] == "--version":
        from stability import __version__

        print(f"stability {__version__}")
        return 0
    try:
        module = command_module(args[0])
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return int(module.main(args[1:]) or 0)
