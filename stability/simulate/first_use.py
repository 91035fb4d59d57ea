"""The first use of a compiled kernel in a process: one line on stderr when it compiles.

numba compiles each kernel (the WCHAIR kernel, the adaptive scheme's, the layout kernel) the first time a machine
runs it and caches the machine code; later processes load it.  A compile takes seconds of CPU with nothing to
count, so :func:`first_use` prints :data:`COMPILE_NOTICE` once per process when a block around a kernel's load
(every load, a first or a later variant's, until the notice has been said) runs past
:data:`stability.runtime.progress.NOTICE_AFTER_S` (docs/simulator.md and docs/layouts.md give the measured
first-use times, computed when the site is built)."""

from __future__ import annotations

import contextlib
import gc
import time
from collections.abc import Iterator
from typing import Any

from stability.runtime.progress import NOTICE_AFTER_S, notice_if_slow

__all__ = ["COMPILE_NOTICE", "collector_paused", "first_use", "load_kernel"]

#: The kernels' loads that are watched (a kernel's module import and its machine code are separate keys), whether
#: the notice was said, and whether a watched block is running.
_FIRST_USE = {"wchair": True, "wchair_load": True, "adaptive_load": True, "adaptive": True, "adaptive_samples": True,
              "layout": True}
#: What the first call in a process says when it takes longer than ``NOTICE_AFTER_S``.
COMPILE_NOTICE = "compiling the simulator (first use on this machine; later runs load it from numba's cache)"


@contextlib.contextmanager
def first_use(scheme: str) -> Iterator[None]:
    """Around a load of ``scheme``'s machine code (a key of the first-use table: from numba's cache, or compiled):
    say so if it runs past ``NOTICE_AFTER_S`` s (a compile), once per process; a compile inside types scalar
    operators without numpy's array rules (:func:`stability.simulate.kernel_link.scalar_operators`).  Every load
    is watched until the notice has been said: a later variant's compile (a controller's, another model's) says so
    too.

    Parameters
    ----------
    scheme : str
        The first-use table's key: ``"wchair"``, ``"wchair_load"``, ``"adaptive_load"``, ``"adaptive"``,
        ``"adaptive_samples"`` or ``"layout"``; any other key watches nothing.

    Yields
    ------
    None
        The block runs inside; the notice, if any, is printed on stderr while it runs.
    """
    from stability.simulate.kernel_link import scalar_operators  # imports numba, as the kernels do

    with scalar_operators(), collector_paused():   # numba's scalar shortcut; no cyclic collection while compiling
        if not _FIRST_USE.get(scheme, False) or _FIRST_USE.get("noticed", False) or _FIRST_USE.get("watching", False):
            yield       # not a kernel's load, said, or inside a watched block (whose notice covers this one)
            return
        start = time.perf_counter()
        _FIRST_USE["watching"] = True
        try:
            with notice_if_slow(COMPILE_NOTICE, after=NOTICE_AFTER_S):
                yield
        finally:
            _FIRST_USE["watching"] = False
        if time.perf_counter() - start >= NOTICE_AFTER_S:       # said once per process
            _FIRST_USE["noticed"] = True


@contextlib.contextmanager
def collector_paused() -> Iterator[None]:
    """Python's cyclic garbage collector off inside the block (as it was before, after it).

    A compile builds numba's IR, types and LLVM's Python objects by the hundred thousand, and the collector's passes
    over them (with every object of the process in its oldest generation: numpy's, matplotlib's, the package's)
    took about a tenth of a first use's CPU (issue 36, measured with ``gc.callbacks``).  Nothing is freed later
    than the first collection after the block; the objects a compile leaves behind are a few tens of MB at most.

    Yields
    ------
    None
        The block runs inside, without cyclic collection.
    """
    paused = gc.isenabled()
    if paused:
        gc.disable()
    try:
        yield
    finally:
        if paused:
            gc.enable()


def load_kernel(dispatcher: Any, args: tuple, scheme: str) -> None:
    """Load, or once per machine compile, ``dispatcher``'s machine code for ``args``' types before its first call.

    Under :func:`first_use` (``scheme``), so that the notice times the load or compile alone, not the run that
    follows it (a large first batch of a cached kernel says nothing).  numba types ``args`` as a call would, so the
    call then finds this code.

    Parameters
    ----------
    dispatcher : numba dispatcher
        The kernel (``@njit``), with or without machine code in this process.
    args : tuple
        The arguments of its first call, typed as numba types them (``numba.typeof``).
    scheme : str
        The first-use key the load is watched under (:func:`first_use`).
    """
    if dispatcher.signatures:
        return
    import numba

    with first_use(scheme):
        dispatcher.compile(tuple(numba.typeof(a) for a in args))
