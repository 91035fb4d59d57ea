"""The ``critical_speed`` command line: ``python -m stability.critical_speed --help``."""

from stability.critical_speed.command import build_parser, main

__all__ = ["main", "build_parser"]
