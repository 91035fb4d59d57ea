"""Notes: what a computation wants its user to know that is not a result (one line each, de-duplicated).

A library warning that a computation understands (e.g. the overflow python-control's polynomial margin search
meets at very high frequencies, whose candidates the caller discards) is caught where it arises
(:func:`library_warnings`) and turned into one note saying what happened and what it means.  Inside a
command line (:func:`collect`, opened by :func:`stability.cli.run`) the notes are printed as ``note: ...`` lines
on stderr (not with ``--quiet``); from the Python API each note is one :class:`NumericalNote` warning.

Examples
--------
>>> with collect() as notes:
...     with library_warnings("a sum", "the sum is not used"):
...         warnings.warn("overflow encountered in multiply", RuntimeWarning)
>>> notes
['a sum: overflow encountered in multiply; the sum is not used']
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Iterator

__all__ = ["NumericalNote", "collect", "note", "library_warnings"]


class NumericalNote(UserWarning):
    """A note from a computation (a library warning understood and explained), outside a command line."""


_COLLECTORS: list[list[str]] = []


@contextlib.contextmanager
def collect() -> Iterator[list[str]]:
    """Collect the notes issued inside the block (innermost collector wins) instead of warning.

    Yields
    ------
    list of str
        The distinct notes, in order of first appearance.
    """
    notes: list[str] = []
    _COLLECTORS.append(notes)
    try:
        yield notes
    finally:
        _COLLECTORS.remove(notes)


def note(message: str) -> None:
    """Issue a note: to the innermost :func:`collect` block (once), else as a :class:`NumericalNote` warning.

    Parameters
    ----------
    message : str
        One line.
    """
    if _COLLECTORS:
        if message not in _COLLECTORS[-1]:
            _COLLECTORS[-1].append(message)
    else:
        warnings.warn(message, NumericalNote, stacklevel=3)


@contextlib.contextmanager
def library_warnings(what: str, consequence: str) -> Iterator[None]:
    """Turn the ``RuntimeWarning`` s raised inside the block (numpy's floating-point warnings, as raised through
    python-control or scipy) into one note per distinct message.

    Other warnings pass through unchanged.

    Parameters
    ----------
    what : str
        The computation, e.g. ``"stability margins (python-control)"``.
    consequence : str
        What the warning means for the result, e.g. ``"those candidates are discarded"``.

    Yields
    ------
    None
        Inside the block; the notes are issued when it ends.
    """
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    for message in dict.fromkeys(str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)):
        note(f"{what}: {message}; {consequence}")
    for w in caught:
        if not issubclass(w.category, RuntimeWarning):
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno, source=w.source)
