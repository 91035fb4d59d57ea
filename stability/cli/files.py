"""Output files of the command lines: checked before any work, written all or none, never an input.

:func:`check_outputs` refuses an output path that cannot be written, that two
options share or that the run reads (directly, or named by a chair file or
sheet: :mod:`stability.runtime.readfiles`); :func:`output_files` writes several outputs
all or none, names the user's file in a write failure (disk full, read-only,
no permission) and renames nothing after a signal (:mod:`stability.runtime.interrupts`).
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator, Mapping

from stability.runtime import interrupts, readfiles

__all__ = ["check_directory", "check_outputs", "output_files", "announce_written"]

_FORBIDDEN_ROOTS = ("/proc", "/sys", "/dev")


def check_directory(path: str | None, option: str) -> None:
    """Refuse an output ``path`` (given as ``option``) that cannot be written as a new file.

    The directory must exist and be writable; the path must not be a directory
    nor lie under ``/proc``, ``/sys`` or ``/dev``.

    Parameters
    ----------
    path : str or None
        Output file name; ``None`` or empty means no output file (nothing checked).
    option : str
        Option that gave the path (e.g. ``"--json-file"``), used in the error message.

    Raises
    ------
    ValueError
        One line naming the option, the path and the fault.
    """
    if not path:
        return
    full = os.path.realpath(os.path.abspath(path))
    if os.path.isdir(full):
        raise ValueError(f"{option} {path!r} is a directory; expected a file name")
    if any(full == r or full.startswith(r + "/") for r in _FORBIDDEN_ROOTS):
        raise ValueError(f"{option} {path!r} is not a place for output files (under /proc, /sys or /dev)")
    d = os.path.dirname(full)
    if not os.path.isdir(d):
        raise ValueError(f"{option} {path!r}: directory {os.path.dirname(os.path.abspath(path))!r} does not exist")
    if not os.access(d, os.W_OK):
        raise ValueError(f"{option} {path!r}: directory {d!r} is not writable")


def check_outputs(outputs: Mapping[str, str | None], inputs: Mapping[str, str | None] | None = None) -> None:
    """Check every output path of a command before any work (see :func:`check_directory`).

    Parameters
    ----------
    outputs : mapping
        Option name -> path (None for an option not given).
    inputs : mapping, optional
        Option name -> input path; no output may overwrite an input.

    Raises
    ------
    ValueError
        One line naming the options at fault.
    """
    seen: dict[str, str] = {}
    for option, path in outputs.items():
        if not path:
            continue
        check_directory(path, option)
        key = os.path.realpath(os.path.abspath(path))
        if key in seen:
            raise ValueError(f"{option} and {seen[key]} name the same file {path!r}; give each output its own file")
        seen[key] = option
    for option, path in (inputs or {}).items():
        if path and os.path.exists(path):
            key = os.path.realpath(os.path.abspath(path))
            if key in seen:
                raise ValueError(f"{seen[key]} {path!r} would overwrite the input {option}")
    for option, path in outputs.items():      # and no output is a file read, now or later in the run
        if path:
            readfiles.claim_output(path, option)


@contextlib.contextmanager
def output_files(outputs: Mapping[str, str | None]) -> Iterator[dict[str, str]]:
    """Write several outputs all or none: yield temporary paths, rename them all at the end.

    Parameters
    ----------
    outputs : mapping
        Option name -> final path (None: not asked for).

    Yields
    ------
    dict
        Option name -> temporary path in the same directory, with the same
        extension (so writers that infer a format from it still work).  On
        success every temporary file replaces its final path; on any error
        (or Ctrl-C) every temporary file is removed and no output appears.
    """
    from stability.runtime.files import failed_write, write_error

    temps: dict[str, str] = {}
    try:
        for option, path in outputs.items():
            if not path:
                continue
            d = os.path.dirname(os.path.abspath(path))
            base = os.path.basename(path)
            try:
                fd, tmp = tempfile.mkstemp(dir=d, prefix=f".{base}.", suffix=os.path.splitext(base)[1] or ".tmp")
            except OSError as exc:
                raise write_error(exc, path) from exc
            os.close(fd)
            temps[option] = tmp
        try:
            yield dict(temps)
        except Exception as exc:       # a write failure names the user's file, not the temporary one
            named = {tmp: outputs[o] for o, tmp in temps.items()}
            failed = failed_write(exc)
            if failed is not None and (failed.filename in named or failed.filename is None):
                first = next(p for p in outputs.values() if p)
                raise write_error(failed, str(named.get(failed.filename) or first)) from exc
            raise
        umask = os.umask(0)
        os.umask(umask)
        with interrupts.held():          # after a signal none is renamed; one that comes now waits until all are
            for option, tmp in temps.items():
                os.chmod(tmp, 0o666 & ~umask)
                os.replace(tmp, str(outputs[option]))
    finally:
        for tmp in temps.values():
            with contextlib.suppress(OSError):
                os.unlink(tmp)


def announce_written(*paths: str | None) -> None:
    """Say on standard error which of ``paths`` were written (after :func:`output_files` renamed them together).

    Parameters
    ----------
    *paths : str or None
        The outputs' final paths; None (not asked for) is skipped.
    """
    import sys

    for path in paths:
        if path:
            print(f"wrote {path}", file=sys.stderr)
