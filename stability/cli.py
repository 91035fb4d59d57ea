"""Helpers shared by the command-line entry points.

``python -m stability.critical_speed``, ``python -m stability.assist`` and
``python -m stability.report`` read a chair the same way (``--chair`` preset
or TOML file, repeatable ``--set NAME=VALUE``), parse ``--speeds`` the same way
and treat bad input the same way: one line ``error: ...`` on stderr and exit
status 2, no traceback.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from collections.abc import Callable, Sequence

import numpy as np

from . import chair as chair_mod

__all__ = ["OneLineErrorParser", "add_chair_options", "load_chair", "parse_speeds", "check_directory",
           "error", "run"]


class OneLineErrorParser(argparse.ArgumentParser):
    """An argument parser whose errors are one line on stderr and exit status 2."""

    def error(self, message: str):  # noqa: D102
        print(f"error: {message}", file=sys.stderr)
        raise SystemExit(2)


def add_chair_options(parser: argparse.ArgumentParser, default: str = "ej-premier") -> None:
    """Add ``--chair`` (preset name or TOML file) and repeatable ``--set NAME=VALUE``."""
    parser.add_argument("--chair", default=default, help=f"preset name or TOML file (default {default})")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="override a chair field (repeatable)")


def load_chair(spec: str, assignments: Sequence[str]):
    """Chair from ``--chair`` and ``--set`` options (raises ValueError with one-line messages)."""
    c = chair_mod.resolve(spec)
    changes = dict(chair_mod.parse_assignment(a) for a in assignments)
    return c.replace(**changes) if changes else c


def parse_speeds(text: str, *, increasing: bool = False) -> np.ndarray:
    """Parse ``START:STOP:STEP`` (inclusive of STOP) or a comma list into speeds (m/s).

    With ``increasing=True`` a list must also be strictly increasing.
    """
    try:
        if ":" in text:
            parts = [float(x) for x in text.split(":")]
            if len(parts) != 3:
                raise ValueError
            start, stop, step = parts
            if step <= 0 or stop < start:
                raise ValueError
            n = int(math.floor((stop - start) / step + 1e-9)) + 1
            speeds = start + step * np.arange(n)
        else:
            speeds = np.array([float(x) for x in text.split(",")])
    except ValueError:
        raise ValueError(f"--speeds {text!r} is invalid; expected START:STOP:STEP with STEP > 0 "
                         "and STOP >= START, or a comma-separated list") from None
    if np.any(speeds <= 0) or not np.all(np.isfinite(speeds)):
        raise ValueError(f"--speeds {text!r} is invalid; valid range: every speed > 0 m/s")
    if increasing and np.any(np.diff(speeds) <= 0):
        raise ValueError(f"--speeds {text!r} is invalid; speeds must be strictly increasing")
    return speeds


def check_directory(path: str | None, option: str) -> None:
    """Refuse an output ``path`` (given as ``option``) whose directory does not exist."""
    if path:
        d = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(d):
            raise ValueError(f"{option} {path!r}: directory {d!r} does not exist")


def error(exc: BaseException) -> int:
    """Print ``exc`` as one line ``error: ...`` on stderr; return exit status 2."""
    msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    print(f"error: {msg}", file=sys.stderr)
    return 2


def run(parser: argparse.ArgumentParser, argv: Sequence[str] | None,
        body: Callable[[argparse.Namespace], int | None], *,
        errors: tuple[type[BaseException], ...] = (ValueError,)) -> int:
    """Parse ``argv`` and return ``body(args)``'s exit status (``None`` counts as 0).

    Usage errors exit with status 2 through :class:`OneLineErrorParser`; an
    exception of a type in ``errors`` raised by ``body`` is bad input: one
    line on stderr, status 2.  Output piped into a reader that stops early
    (``| head``) ends quietly with status 1.
    """
    args = parser.parse_args(argv)
    try:
        return body(args) or 0
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except errors as exc:
        return error(exc)
