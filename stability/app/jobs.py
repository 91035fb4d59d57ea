"""Background work of the explorer: nonlinear measures, uncertainty bands, the PDF report, the kernel warm-up.

One worker thread for the whole server: the simulator's compiled batch
kernel runs in parallel over runs by itself, two cores are all the machine
has, and one thread at a time inside the kernels is always safe.  Each session
numbers its requests; a chair change bumps the number, which cancels the
session's queued work and makes a finished result from an older chair be
dropped instead of shown (a running simulation is not interrupted; its result
is discarded).  The linear views never wait for this thread.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from concurrent.futures import Future, ThreadPoolExecutor
from dataclasses import dataclass, field
from functools import partial
from typing import Any

from stability.settings import defaults as D

__all__ = ["Jobs", "warm_up", "executor", "warm_up_done"]

_EXECUTOR: ThreadPoolExecutor | None = None
_LOCK = threading.Lock()
_WARM = threading.Event()


def executor() -> ThreadPoolExecutor:
    """The server's one background worker (created on first use).

    Returns
    -------
    ThreadPoolExecutor
    """
    global _EXECUTOR
    with _LOCK:
        if _EXECUTOR is None:
            _EXECUTOR = ThreadPoolExecutor(max_workers=1, thread_name_prefix="stability-app")
        return _EXECUTOR


def warm_up() -> Future:
    """Compile the simulator's kernels in the background (queued before any nonlinear request).

    Returns
    -------
    Future
        Done when one short WCHAIR run of the default chair has finished (first use: the numba
        compile, several seconds; later starts load the cache).
    """
    def run() -> None:
        from stability.chair import preset
        from stability.settings.run import RunSpec
        from stability.simulate import simulate

        try:
            simulate(preset(D.CHAIR), D.SPEED, RunSpec(horizon=0.05))
        finally:
            _WARM.set()

    return executor().submit(run)


def warm_up_done() -> bool:
    """Whether the start-up compile has finished.

    Returns
    -------
    bool
    """
    return _WARM.is_set()


@dataclass
class Jobs:
    """One session's background requests.

    Parameters
    ----------
    deliver : callable
        ``deliver(fn)`` runs ``fn()`` where the session may change its page (the page passes the
        Bokeh document's ``add_next_tick_callback``; tests pass ``lambda fn: fn()``).

    Attributes
    ----------
    deliver : callable
        As above.
    generation : int
        Number of the current chair; a result computed for an older number is dropped.
    """

    deliver: Callable[[Callable[[], None]], Any]
    generation: int = 0
    _futures: list[Future] = field(default_factory=list)

    def cancel(self) -> None:
        """Drop every queued request and every result not yet shown (the chair changed)."""
        self.generation += 1
        for f in self._futures:
            f.cancel()
        self._futures = [f for f in self._futures if not f.done()]

    def submit(self, work: Callable[[], Any], show: Callable[[Any], None],
               failed: Callable[[BaseException], None]) -> Future:
        """Run ``work()`` on the worker; show its result with ``show`` unless cancelled meanwhile.

        Parameters
        ----------
        work : callable
            The computation (no page access).
        show : callable
            ``show(result)``, run through ``deliver``.
        failed : callable
            ``failed(exception)``, run through ``deliver`` when ``work`` raises.

        Returns
        -------
        Future
        """
        gen = self.generation

        def run() -> None:
            if gen != self.generation:
                return
            try:
                result = work()
            except Exception as exc:  # shown on the page as one line, never a traceback
                if gen == self.generation:
                    self.deliver(partial(failed, exc))
                return
            if gen == self.generation:
                self.deliver(lambda: show(result) if gen == self.generation else None)

        fut = executor().submit(run)
        self._futures = [f for f in self._futures if not f.done()] + [fut]
        return fut

    @property
    def busy(self) -> bool:
        """Whether a request of this session is queued or running."""
        return any(not f.done() for f in self._futures)
