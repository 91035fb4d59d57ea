"""Helpers shared by the command-line entry points: one way to read a chair, speeds and outputs, one error contract.

Every ``python -m stability.X`` reads a chair the same way (``--chair`` preset
or TOML file, repeatable ``--set NAME=VALUE``), checks every output path before
any work, and answers bad input with one line ``error: ...`` on stderr and exit
status 2 (a computation that fails for a valid chair: status 2 too, one line
saying what could not be computed; Ctrl-C: status 130; ``--debug`` shows the
traceback instead).  See README.md, "Errors".
"""

from __future__ import annotations

import argparse
import contextlib
import io
import math
import os
import sys
import traceback
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np

from stability import __version__, tires
from stability import chair as chair_mod
from stability.cli.chairs import (
    apply_assignments,
    apply_layout_assignments,
    load_chair,
    load_layout,
)
from stability.cli.files import announce_written, check_directory, check_outputs, output_files
from stability.cli.numbers import (
    OPTION_BOUNDS,
    Bound,
    NonFiniteResult,
    bound_for,
    check_finite_text,
    first_non_finite,
    number,
)
from stability.cli.options import (
    FIGURE_FORMATS,
    OneLineErrorParser,
    add_chair_options,
    add_common_options,
    add_driver_options,
    add_intended_speed_option,
    add_json_options,
    add_model_option,
    add_output_option,
    add_run_options,
    add_uncertainty_option,
    check_format,
    driver_from_args,
    intended_speed_from_args,
    run_flag,
    run_from_args,
)
from stability.cli.options import subparsers as _subparsers
from stability.runtime import collector, interrupts, notes, progress, readfiles
from stability.runtime.checks import MAX_SPEED, MIN_SPEED
from stability.runtime.files import distinct_notes, json_text, with_tire_range

__all__ = ["OneLineErrorParser", "add_chair_options", "add_common_options", "add_model_option",
           "add_driver_options", "driver_from_args", "add_intended_speed_option", "intended_speed_from_args",
           "add_run_options", "run_from_args", "run_flag", "add_json_options",
           "load_chair", "load_layout", "apply_layout_assignments", "apply_assignments", "parse_speeds",
           "check_directory", "check_outputs",
           "output_files", "announce_written",
           "json_header", "emit_json", "error", "run", "MAX_SPEEDS", "check_work", "add_output_option", "check_format",
           "add_uncertainty_option", "FIGURE_FORMATS", "Bound", "OPTION_BOUNDS", "number", "bound_for",
           "check_finite_text", "NonFiniteResult"]

#: Largest number of speeds a ``--speeds`` option may ask for (each costs an eigenvalue solve or a run).
MAX_SPEEDS = 10_001

def parse_speeds(text: str, *, increasing: bool = False, max_count: int = MAX_SPEEDS,
                 signed: bool = False) -> np.ndarray:
    """Parse ``START:STOP:STEP`` (inclusive of STOP), ``START:STOP`` (its ends and middle) or a comma list into
    speeds (m/s).

    Parameters
    ----------
    text : str
        The option's value.
    increasing : bool
        Require a list to be strictly increasing.
    max_count : int
        Largest number of speeds allowed (bounded work).
    signed : bool
        Accept negative speeds (reverse driving, for the commands that answer it): every ``|speed|`` in range.

    Returns
    -------
    ndarray
        The speeds, m/s, each finite and > 0 (``signed``: each finite, its size in range).
    """
    bad = (f"--speeds {text!r} is invalid; expected START:STOP:STEP with {'' if signed else '0 < '}START <= STOP "
           "and STEP > 0 (finite, m/s), START:STOP (its ends and middle) or a comma-separated list")
    count = 0
    try:
        if ":" in text:
            parts = [float(x) for x in text.split(":")]
            if len(parts) not in (2, 3) or not all(math.isfinite(x) for x in parts):
                raise ValueError
            if len(parts) == 2:                      # START:STOP: its ends and middle (one speed when equal)
                parts.append((parts[1] - parts[0]) / 2 if parts[1] > parts[0] else 1.0)
            start, stop, step = parts
            if step <= 0 or stop < start:
                raise ValueError
            count = math.floor((stop - start) / step + 1e-9) + 1
            if count <= max_count:
                speeds = start + step * np.arange(count)
        else:
            speeds = np.array([float(x) for x in text.split(",")])
            count = len(speeds)
    except (ValueError, OverflowError):
        raise ValueError(bad) from None
    if count > max_count:
        raise ValueError(f"--speeds {text!r} asks for {count} speeds; at most {max_count} are allowed "
                         "(use a larger STEP)")
    if signed:
        if not np.all(np.isfinite(speeds) & (np.abs(speeds) >= MIN_SPEED) & (np.abs(speeds) <= MAX_SPEED)):
            raise ValueError(f"--speeds {text!r} is invalid; valid range: every |speed| {MIN_SPEED:g} to "
                             f"{MAX_SPEED:g} m/s (negative: reverse)")
    elif not np.all(np.isfinite(speeds) & (speeds >= MIN_SPEED) & (speeds <= MAX_SPEED)):
        raise ValueError(f"--speeds {text!r} is invalid; valid range: every speed {MIN_SPEED:g} to {MAX_SPEED:g} m/s "
                         f"(below {MIN_SPEED:g} m/s the rates, proportional to speed there, are lost in round-off)")
    if increasing and np.any(np.diff(speeds) <= 0):
        raise ValueError(f"--speeds {text!r} is invalid; speeds must be strictly increasing")
    return speeds


def check_work(what: str, amount: float, limit: float, advice: str) -> None:
    """Refuse work whose size ``amount`` exceeds ``limit`` before it starts (bounded time and memory).

    Parameters
    ----------
    what : str
        What is counted, e.g. ``"--duration 1e9 with --dt 0.001 (time steps)"``.
    amount, limit : float
        The size asked for and the largest allowed.
    advice : str
        How to stay within the limit, e.g. ``"use --duration <= 3600 s"``.

    Raises
    ------
    ValueError
        One line with the size, the limit and the advice.
    """
    if not amount <= limit:
        raise ValueError(f"{what} asks for {amount:.3g}; at most {limit:.3g} are allowed: {advice}")


def json_header(chair: chair_mod.Chair, model: str | None, options: Mapping[str, Any]) -> dict[str, Any]:
    """What every JSON output starts with: toolkit version, chair (name and all parameters), model, options.

    Parameters
    ----------
    chair : Chair
    model : str or None
        ``"exact"`` or ``"thesis"`` (None when the command has no model).
    options : mapping
        The options used (JSON-serialisable values).

    Returns
    -------
    dict
    """
    return {"stability_version": __version__, "chair": chair.name,
            "chair_parameters": chair_mod.to_mapping(chair), "model": model, "options": dict(options)}


def emit_json(data: Any, args: argparse.Namespace, write_to: str | None = None) -> None:
    """Print ``data`` as JSON when ``--json`` was given; write it atomically to ``--json-file`` when given.

    Parameters
    ----------
    data : Any
        JSON-serialisable result (NaN and infinity refused); a dict gains a
        ``tire_range`` entry when ``args`` carries tire-range notes.
    args : argparse.Namespace
        Parsed options; read are ``json``, ``json_file``, ``tire_range`` and ``tire_notes``.
    write_to : str, optional
        Where to write instead of ``--json-file`` (a temporary path of
        :func:`output_files`, renamed with the command's other outputs; the
        caller then says what it wrote).
    """
    from stability.runtime.files import atomic_write_text

    data = with_tire_range(data, getattr(args, "tire_notes", None), getattr(args, "tire_range", None))
    try:
        text = json_text(data)
    except ValueError:
        raise NonFiniteResult(f"a result is not finite ({first_non_finite(data)})") from None
    if getattr(args, "json", False):
        print(text)
    path = getattr(args, "json_file", None)
    if path:
        atomic_write_text(write_to or path, text + "\n")
        if write_to is None:                 # with write_to the caller renames and announces its outputs
            print(f"wrote {path}", file=sys.stderr)


def error(exc: BaseException, prefix: str = "") -> int:
    """Print ``exc`` as one line ``error: ...`` on stderr; return exit status 2.

    Parameters
    ----------
    exc : BaseException
        The exception; only the first line of its message is printed (its type name if empty).
    prefix : str, optional
        Text placed between ``"error: "`` and the message, default empty.

    Returns
    -------
    int
        Exit status 2.
    """
    msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    print(f"error: {prefix}{msg}", file=sys.stderr)
    return 2


#: Failures inside a computation for valid input (reported in one line, exit status 2).
COMPUTATION_ERRORS: tuple[type[BaseException], ...] = (ArithmeticError, np.linalg.LinAlgError, RuntimeError,
                                                      MemoryError)


def _with_tire_policy(body: Callable[[argparse.Namespace], int | None], args: argparse.Namespace) -> int:
    """Run ``body`` under the ``--tire-range`` policy; print each tire-range note once, as one line."""
    import warnings

    with tires.range_policy(getattr(args, "tire_range", None) or "warn"), tires.collect_notes() as tire_notes, \
            notes.collect() as numerical, warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        args.tire_notes = tire_notes
        status = body(args) or 0
    if not getattr(args, "quiet", False):
        for line in tires.summarise_notes(distinct_notes(tire_notes)):      # one line per tire and range
            print(f"note: {line}", file=sys.stderr)
        for line in numerical:               # library warnings, explained (stability.runtime.notes)
            print(f"note: {line}", file=sys.stderr)
    return status


def run(parser: argparse.ArgumentParser, argv: Sequence[str] | None,
        body: Callable[[argparse.Namespace], int | None], *,
        errors: tuple[type[BaseException], ...] = (ValueError,)) -> int:
    """Parse ``argv`` and return ``body(args)``'s exit status (``None`` counts as 0), under the error contract.

    * usage errors and an exception of a type in ``errors`` (bad input): one line, status 2;
    * a computation that fails (singular matrix, no convergence, overflow, a result that is NaN
      or infinite, out of memory): one line ``error: could not compute ...``, status 2; standard
      output is held until the work has ended and refused if it prints a NaN or an infinity,
      and numpy's floating-point warnings are not printed;
    * a file that cannot be read or written (disk full, read-only, no permission): one line
      naming it, status 2, no temporary file left;
    * SIGINT (Ctrl-C), SIGTERM or SIGHUP: ``error: interrupted``, status 130 (outputs are atomic:
      nothing half-written is left, and none is renamed into place after a signal);
    * an output that is a file the run reads (directly, or named by a chair file or sheet):
      refused as bad input;
    * output piped into a reader that stops early (``| head``): quiet, status 1;
    * ``--debug`` (added to every parser): the traceback instead of the one line.

    In a command line's process the objects the imports made are frozen out of the garbage collector's
    traversals first (:func:`stability.runtime.collector.settle`; nothing in a library or test process).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser; ``--debug`` and ``--quiet`` are added if missing.
    argv : sequence of str or None
        Arguments without the program name; ``None`` reads ``sys.argv[1:]``.
    body : callable
        ``body(args) -> int or None``: the command's work on the parsed options.
    errors : tuple of exception types, optional
        Exceptions treated as bad input (default ``(ValueError,)``).

    Returns
    -------
    int
        Exit status: ``body``'s (0 for ``None``), 1, 2 or 130 as listed above.
    """
    collector.settle()
    with interrupts.interruptible(), readfiles.session():
        return _run(parser, argv, body, errors)


#: numpy's floating-point warnings: never printed (a non-finite result is refused by the finiteness checks).
_FLOAT_WARNINGS = r"(invalid value|divide by zero|overflow|underflow) encountered"


def _interrupted(debug: bool) -> int:
    """An interrupted command's line and status.  Also when a library turned the signal's KeyboardInterrupt into
    another error: numba's LLVM object-cache callback, a ctypes callback, swallows it during a compile, and the
    compile then fails with a RuntimeError; the signal was remembered (:func:`interrupts.pending`)."""
    if debug:
        traceback.print_exc()
    print(interrupts.MESSAGE, file=sys.stderr)
    return interrupts.EXIT_STATUS


def _run(parser: argparse.ArgumentParser, argv: Sequence[str] | None,
         body: Callable[[argparse.Namespace], int | None], errors: tuple[type[BaseException], ...]) -> int:
    """:func:`run` inside the signal handlers and the input/output session."""
    for p in (parser, *_subparsers(parser)):
        add_common_options(p)
    debug = "--debug" in (sys.argv[1:] if argv is None else argv)
    try:
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:           # --help (0) or a usage error (2, its one line printed)
            return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
        args.debug = bool(getattr(args, "debug", False))
        args.quiet = bool(getattr(args, "quiet", False))
        debug = args.debug
        check_format(getattr(args, "output", None), getattr(args, "output_formats", None) or (), "-o") \
            if hasattr(args, "output_formats") else None
        with progress.quiet(args.quiet), contextlib.redirect_stdout(io.StringIO()) as out, \
                warnings.catch_warnings():
            warnings.filterwarnings("ignore", message=_FLOAT_WARNINGS, category=RuntimeWarning)
            status = _with_tire_policy(body, args)
        interrupts.check()                  # a signal swallowed by a library still interrupts
        text = out.getvalue()
        check_finite_text(text)             # no NaN or infinity is printed as a result
        sys.stdout.write(text)
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1
    except KeyboardInterrupt:
        return _interrupted(debug)
    except COMPUTATION_ERRORS as exc:       # before ``errors``: LinAlgError is a ValueError
        if debug:
            traceback.print_exc()
        if interrupts.pending():
            return _interrupted(False)
        return error(exc, "could not compute the result for this chair and these options: ")
    except errors as exc:
        if debug:
            traceback.print_exc()
        if interrupts.pending():
            return _interrupted(False)
        return error(exc)
    except OSError as exc:
        if debug:
            traceback.print_exc()
        if interrupts.pending():
            return _interrupted(False)
        where = f" {exc.filename!r}" if exc.filename else ""
        return error(exc, f"file{where}: ") if not where else error(ValueError(f"{exc.strerror}"), f"file{where}: ")
