"""Signals at the command lines: SIGINT, SIGTERM and SIGHUP end a command with ``error: interrupted``, status 130.

Two stages, so that a signal is handled the same way from the first line of
an entry point to its last:

* :func:`install_early` (called by ``stability/__init__.py`` when the package
  is imported by ``python -m stability.X``, i.e. before numpy and the other
  imports): a signal ends the process at once with the one line and status
  130.  Nothing has been written yet, and nothing is written after the
  command's work has finished either.
* :func:`interruptible` (entered by :func:`stability.cli.run` around the
  command's work): a signal raises :class:`KeyboardInterrupt`, so that every
  ``finally`` and every atomic output (:mod:`stability.runtime.files`) removes its
  temporary files, and remembers that it came (:func:`pending`), so that an
  output is never renamed into place after a signal even if a library
  swallowed the exception.

This module imports only the standard library.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["SIGNALS", "EXIT_STATUS", "MESSAGE", "install_early", "interruptible", "pending", "check", "held"]

#: The signals that interrupt a command: Ctrl-C, ``kill`` and a closed terminal (where the platform has them).
SIGNALS: tuple[signal.Signals, ...] = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM", "SIGHUP")
                                             if hasattr(signal, n))
#: Exit status of an interrupted command (128 + SIGINT, the shell's convention for Ctrl-C).
EXIT_STATUS = 130
#: The one line an interrupted command prints on standard error.
MESSAGE = "error: interrupted"

_state = {"pending": False}


def _exit_now(signum: int, frame: Any) -> None:
    """Before or after the work: print the line and end the process (nothing is being written)."""
    os.write(2, (MESSAGE + "\n").encode())
    os._exit(EXIT_STATUS)


def _raise(signum: int, frame: Any) -> None:
    """During the work: remember the signal and unwind (temporary files removed on the way)."""
    _state["pending"] = True
    raise KeyboardInterrupt


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def install_early() -> None:
    """End the process with ``error: interrupted`` (status 130) on any of :data:`SIGNALS` from now on.

    Does nothing outside the main thread (where Python cannot set handlers).
    """
    if _main_thread():
        for sig in SIGNALS:
            signal.signal(sig, _exit_now)


def pending() -> bool:
    """True when a signal arrived during :func:`interruptible` (its work must not be kept).

    Returns
    -------
    bool
    """
    return _state["pending"]


def check() -> None:
    """Raise :class:`KeyboardInterrupt` if a signal arrived (called before an output is renamed into place)."""
    if _state["pending"]:
        raise KeyboardInterrupt


@contextlib.contextmanager
def interruptible() -> Iterator[None]:
    """Inside: every signal of :data:`SIGNALS` raises :class:`KeyboardInterrupt`; the handlers before are restored.

    Yields
    ------
    None
    """
    if not _main_thread():
        yield
        return
    previous = {sig: signal.getsignal(sig) for sig in SIGNALS}
    _state["pending"] = False
    for sig in SIGNALS:
        signal.signal(sig, _raise)
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        _state["pending"] = False


@contextlib.contextmanager
def held() -> Iterator[None]:
    """Inside: :data:`SIGNALS` wait until the end (several outputs renamed into place all or none).

    On entry a signal that already came (or is waiting) raises :class:`KeyboardInterrupt`, so nothing inside
    runs; one that comes inside is delivered on leaving, after the block has finished.

    Yields
    ------
    None

    Raises
    ------
    KeyboardInterrupt
        A signal came before the block.
    """
    check()
    if not _main_thread():
        yield
        return
    previous = {sig: signal.getsignal(sig) for sig in SIGNALS}
    came: list[int] = []
    for sig in SIGNALS:          # Python handlers run in the main thread whichever thread the kernel picks
        signal.signal(sig, lambda signum, frame: came.append(signum))
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        if came:                 # delivered now, to the handler it was meant for
            handler = previous[signal.Signals(came[0])]
            if callable(handler):
                handler(came[0], None)
            else:
                raise KeyboardInterrupt
