"""The files a command has read as inputs (chair files, tire CSVs, sheets, uncertainty files).

Inside :func:`session` (entered by :func:`stability.cli.run` around a
command's work) every reader of a user's file notes it here (:func:`note`),
every output is claimed (:func:`claim_output`, by
:func:`stability.cli.check_outputs`), and the two may not meet: no output may
be a file the run reads, directly or through a chair file or a sheet, in
whichever order the two are named; :mod:`stability.runtime.files` refuses to replace
a file read (:func:`was_read`).  Outside a session (the Python API) nothing is
recorded: a notebook may read a chair file and save it back.  :func:`read_text` and
:func:`load_toml` read a user's file the one way: noted, and with a UTF-8
byte-order mark (what spreadsheet programs and Windows editors write)
accepted.  This module imports only the
standard library.
"""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Iterator
from typing import Any, Union

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["MAX_INPUT_BYTES", "note", "was_read", "paths", "read_text", "load_toml", "claim_output", "session"]

#: Largest input file read (bytes): a measured tire has some hundred rows and a chair file some dozen lines
#: (a few kB); 16 MiB is a thousand times the largest real one and keeps a mistaken multi-GB file from
#: exhausting memory.
MAX_INPUT_BYTES = 16 * 2**20

_READ: set[str] = set()
_CLAIMED: dict[str, str] = {}
_ACTIVE = [False]

PathLike = Union[str, "os.PathLike[str]"]


def _key(path: PathLike) -> str:
    return os.path.realpath(os.path.abspath(os.fspath(path)))


def note(path: PathLike) -> None:
    """Remember that ``path`` is an input of this process.

    Parameters
    ----------
    path : path-like
        A file that was (or is about to be) read.

    Raises
    ------
    ValueError
        ``path`` is an output of the running command (:func:`claim_output`).
    """
    if not _ACTIVE[0]:
        return
    key = _key(path)
    if key in _CLAIMED:
        raise ValueError(f"{_CLAIMED[key]} {os.fspath(path)!r} is also an input of this run "
                         "(read directly or named by a chair file or sheet); an input is never overwritten")
    _READ.add(key)


def claim_output(path: PathLike, option: str) -> None:
    """Declare ``path`` an output of the running command, given as ``option``.

    Reading it later (:func:`note`) is refused, as is claiming a file already read.

    Parameters
    ----------
    path : path-like
    option : str
        The option that named it (``"--json-file"``), used in messages.

    Raises
    ------
    ValueError
        ``path`` has been read as an input.
    """
    if not _ACTIVE[0]:
        return
    key = _key(path)
    if key in _READ:
        raise ValueError(f"{option} {os.fspath(path)!r} is a file this run reads (directly or named by a "
                         "chair file or sheet); an input is never overwritten")
    _CLAIMED[key] = option


@contextlib.contextmanager
def session() -> Iterator[None]:
    """Record inputs and outputs of one command inside; forget them at the end.

    Yields
    ------
    None
    """
    _READ.clear()
    _CLAIMED.clear()
    _ACTIVE[0] = True
    try:
        yield
    finally:
        _ACTIVE[0] = False
        _READ.clear()
        _CLAIMED.clear()


def was_read(path: PathLike) -> bool:
    """True when ``path`` (after resolving links) is a file noted by :func:`note` in the running session.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    bool
    """
    return _key(path) in _READ


def paths() -> frozenset[str]:
    """Every input noted so far (absolute, links resolved).

    Returns
    -------
    frozenset of str
    """
    return frozenset(_READ)


def _too_large(path: PathLike, size: int | str) -> ValueError:
    return ValueError(f"input file {os.fspath(path)!r} has {size} bytes; at most {MAX_INPUT_BYTES} are allowed "
                      "(a chair file, tire CSV or sheet has a few kB)")


def _read_bytes(path: PathLike) -> bytes:
    """The bytes of ``path``, at most :data:`MAX_INPUT_BYTES`: the size is checked before the read (a regular
    file) and the read stops one byte past the bound (a device or pipe that states no size: /dev/zero)."""
    size = os.stat(path).st_size
    if size > MAX_INPUT_BYTES:
        raise _too_large(path, size)
    with open(path, "rb") as fh:
        data = fh.read(MAX_INPUT_BYTES + 1)
    if len(data) > MAX_INPUT_BYTES:
        raise _too_large(path, "more than " + str(MAX_INPUT_BYTES))
    return data


def read_text(path: PathLike) -> str:
    """A user's text file, noted as an input, decoded as UTF-8 with an optional byte-order mark.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    str
        The text without the byte-order mark.

    Raises
    ------
    OSError
        The file cannot be read.
    UnicodeDecodeError
        The file is not UTF-8 text.
    ValueError
        The file is larger than :data:`MAX_INPUT_BYTES`.
    """
    note(path)
    text = _read_bytes(path).decode("utf-8-sig")
    return text.replace("\r\n", "\n").replace("\r", "\n")      # universal newlines, as text-mode open()


def load_toml(path: PathLike) -> dict[str, Any]:
    """A user's TOML file (noted as an input; a UTF-8 byte-order mark accepted).

    Parameters
    ----------
    path : path-like

    Returns
    -------
    dict

    Raises
    ------
    OSError
        The file cannot be read.
    tomllib.TOMLDecodeError
        The file is not valid TOML (not UTF-8 text included).
    ValueError
        The file is larger than :data:`MAX_INPUT_BYTES`.
    """
    note(path)
    data = _read_bytes(path)
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise tomllib.TOMLDecodeError(f"not UTF-8 text ({exc.reason} at byte {exc.start})") from None
    return tomllib.loads(text)
