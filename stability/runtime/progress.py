"""A tiny progress bar: tqdm when it is installed, else a plain text bar on stderr.

On a terminal the bar is drawn in place.  When stderr is not a terminal (a
pipe, a log file, CI) long work still shows progress, as plain lines: one
after :data:`LINE_EVERY_S` seconds and then every :data:`LINE_EVERY_S`
seconds, and a last one when such work ends; short work prints nothing.
``enabled=False`` or :func:`quiet` (``--quiet``) silence both.

Examples
--------
>>> from stability.runtime.progress import ProgressBar
>>> with ProgressBar(total=3, desc="runs", enabled=False) as bar:
...     for _ in range(3):
...         bar.update()
"""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Iterable, Iterator
from typing import IO, TypeVar

__all__ = ["ProgressBar", "track", "should_show", "quiet", "is_quiet", "notice_if_slow", "NOTICE_AFTER_S",
           "LINE_EVERY_S"]

#: Work that takes longer than this says so on stderr (s).
NOTICE_AFTER_S = 2.0
#: Off a terminal, a progress line at most this often (s), the first after as long.
LINE_EVERY_S = 10.0

_QUIET = [False]


@contextlib.contextmanager
def quiet(on: bool = True) -> Iterator[None]:
    """Within the block, no progress is drawn (``--quiet`` of the command lines); nests.

    Parameters
    ----------
    on : bool
        Silence progress (True) or leave it as it is (False).

    Yields
    ------
    None
    """
    _QUIET.append(bool(on) or _QUIET[-1])
    try:
        yield
    finally:
        _QUIET.pop()


@contextlib.contextmanager
def notice_if_slow(message: str, after: float = NOTICE_AFTER_S, file: IO[str] | None = None) -> Iterator[None]:
    """Print ``message`` once on stderr if the block is still running after ``after`` seconds.

    For work whose length cannot be known in advance and that has no steps
    to count, such as numba compiling the simulator on first use: a cache hit
    returns at once and prints nothing; a compile says what is happening.
    Silent under :func:`quiet`.

    Parameters
    ----------
    message : str
        What is happening, e.g. ``"compiling the simulator (first use, ...)"``.
    after : float, optional
        Seconds before the message appears (default :data:`NOTICE_AFTER_S`).
    file : text stream, optional
        Where to print (default ``sys.stderr``).

    Yields
    ------
    None
    """
    import threading

    if is_quiet():
        yield
        return
    stream = sys.stderr if file is None else file

    def say() -> None:
        try:
            stream.write(message + "\n")
            stream.flush()
        except (OSError, ValueError):  # pragma: no cover - stream closed
            pass

    timer = threading.Timer(after, say)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()


def is_quiet() -> bool:
    """Whether progress is silenced by :func:`quiet`.

    Returns
    -------
    bool
    """
    return _QUIET[-1]

T = TypeVar("T")


def should_show(enabled: bool = True, force: bool = False, file: IO[str] | None = None) -> bool:
    """Whether a bar should be drawn: ``force``, or ``enabled`` and ``file`` (stderr) is a TTY.

    Parameters
    ----------
    enabled : bool
        False disables the bar.
    force : bool
        Draw even when stderr is not a terminal.
    file : text stream, optional
        Where to draw (default ``sys.stderr``).

    Returns
    -------
    bool
    """
    if is_quiet():
        return False
    if force:
        return True
    if not enabled:
        return False
    stream = sys.stderr if file is None else file
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError):
        return False


class ProgressBar:
    """Progress over ``total`` units of work.

    Parameters
    ----------
    total : int
        Units of work (runs, steps, ...).
    desc : str
        Label shown before the bar.
    enabled : bool
        ``False`` disables the bar entirely (the ``progress=False`` option of
        the public functions).
    force : bool
        Draw even when stderr is not a terminal.
    file : text stream, optional
        Where to draw (default ``sys.stderr``).
    unit : str
        Name of one unit of work.
    """

    def __init__(self, total: int, desc: str = "", *, enabled: bool = True, force: bool = False,
                 file: IO[str] | None = None, unit: str = "it") -> None:
        self.total = max(int(total), 0)
        self.desc = desc
        self.unit = unit
        self.n = 0
        self._file = sys.stderr if file is None else file
        self._show = should_show(enabled, force, self._file)
        # off a terminal: plain lines for long work (not drawn in place)
        self._lines = not self._show and enabled and not is_quiet()
        self._lines_written = 0
        self._tqdm = None
        self._last_draw = 0.0
        self._start = time.perf_counter()
        self._last_line = self._start
        self._closed = False
        if self._show:
            try:
                from tqdm import tqdm
            except ImportError:  # pragma: no cover - depends on the environment
                tqdm = None
            if tqdm is not None:
                self._tqdm = tqdm(total=self.total, desc=desc or None, file=self._file, unit=unit,
                                  leave=False, dynamic_ncols=True)

    # -- context manager ---------------------------------------------------
    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    @property
    def shown(self) -> bool:
        """Whether anything is being drawn."""
        return self._show

    def update(self, n: int = 1) -> None:
        """Advance by ``n`` units."""
        self.n += n
        if self._lines and not self._closed:
            now = time.perf_counter()
            if now - self._last_line >= LINE_EVERY_S:
                self._last_line = now
                self._line()
            return
        if not self._show or self._closed:
            return
        if self._tqdm is not None:
            self._tqdm.update(n)
            return
        now = time.perf_counter()
        if now - self._last_draw >= 0.1 or self.n >= self.total:
            self._last_draw = now
            self._draw()

    def _draw(self) -> None:
        width = 30
        frac = min(self.n / self.total, 1.0) if self.total else 1.0
        filled = int(round(width * frac))
        elapsed = time.perf_counter() - self._start
        label = f"{self.desc}: " if self.desc else ""
        self._file.write(f"\r{label}[{'#' * filled}{'.' * (width - filled)}] "
                         f"{self.n}/{self.total} {self.unit} {elapsed:5.1f} s")
        self._file.flush()

    def _line(self) -> None:
        label = f"{self.desc}: " if self.desc else ""
        of = f"/{self.total}" if self.total else ""
        try:
            self._file.write(f"{label}{self.n}{of} {self.unit}, {time.perf_counter() - self._start:.0f} s\n")
            self._file.flush()
            self._lines_written += 1
        except (OSError, ValueError):  # pragma: no cover - stream closed
            self._lines = False

    def close(self) -> None:
        """Finish the bar (idempotent)."""
        if self._closed:
            return
        self._closed = True
        if self._lines and self._lines_written:
            self._line()                      # long work off a terminal: say where it ended
        if not self._show:
            return
        if self._tqdm is not None:
            self._tqdm.close()
        else:
            self._draw()
            self._file.write("\n")
            self._file.flush()


def track(iterable: Iterable[T], total: int | None = None, desc: str = "", *, enabled: bool = True,
          force: bool = False, file: IO[str] | None = None, unit: str = "it") -> Iterator[T]:
    """Iterate over ``iterable`` with a :class:`ProgressBar`.

    Parameters
    ----------
    iterable : iterable
        Items to iterate over.
    total : int, optional
        Number of items (``len(iterable)`` if omitted).
    desc : str
        Label before the bar.
    enabled : bool
        False disables the bar.
    force : bool
        Draw even when stderr is not a terminal.
    file : text stream, optional
        Where to draw (default ``sys.stderr``).
    unit : str
        Name of one unit of work.

    Yields
    ------
    object
        The items of ``iterable``.
    """
    if total is None:
        try:
            total = len(iterable)  # type: ignore[arg-type]
        except TypeError:
            total = 0
    with ProgressBar(total, desc, enabled=enabled, force=force, file=file, unit=unit) as bar:
        for item in iterable:
            yield item
            bar.update()
