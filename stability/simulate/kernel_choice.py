"""Which WCHAIR kernel runs: the scalar kernel (the default) or the lanes kernel (opt-in), and the lanes' blocks.

:func:`use_kernel` switches process-wide (tests, benchmarks measure both kernels
in one process); :func:`lane_block` sizes the blocks; :func:`run_lanes` steps
runs on the lanes kernel with a given thread count.  Used by
:mod:`stability.simulate.engine`.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from typing import Any

__all__ = ["KERNELS", "use_kernel", "choice", "lanes_kernel", "lane_block", "run_lanes"]

#: The WCHAIR kernels: ``"scalar"`` (:func:`.kernel.run_batch`, one run per thread: the default, whose numbers
#: every test, report and document states) or ``"lanes"`` (:mod:`.lanes_kernel`, runs as SIMD lanes: more batch
#: throughput per core, equal to the scalar kernel within its polynomial trig's rounding bound, but a chaotic
#: spin-out may stop at another time and a critical impulse move within the search's bracket; one run alone is
#: slower on it and its first compile costs more: docs/simulator.md, "Runs as lanes", gives the figures measured
#: when the site is built).  Chosen for the process by the environment variable
#: ``STABILITY_KERNEL`` (``lanes`` or ``scalar``) or inside a block by :func:`use_kernel`.
KERNELS = ("scalar", "lanes")
_ENV = os.environ.get("STABILITY_KERNEL", "scalar").strip().lower() or "scalar"
if _ENV not in KERNELS:
    raise ValueError(f"STABILITY_KERNEL={_ENV!r} is invalid; valid: {', '.join(KERNELS)}")
_CHOICE = {"kernel": _ENV}


@contextlib.contextmanager
def use_kernel(name: str) -> Iterator[None]:
    """Run the WCHAIR scheme on kernel ``name`` (:data:`KERNELS`) inside the block (process-wide; tests, benchmarks).

    Parameters
    ----------
    name : {"lanes", "scalar"}
        The kernel.

    Yields
    ------
    None
    """
    if name not in KERNELS:
        raise ValueError(f"kernel={name!r} is invalid; valid: {', '.join(KERNELS)}")
    before = _CHOICE["kernel"]
    _CHOICE["kernel"] = name
    try:
        yield
    finally:
        _CHOICE["kernel"] = before


def lanes_kernel() -> Any:
    """The lanes kernel module, imported (numba, the compiled code) on first use.

    Returns
    -------
    module
        :mod:`stability.simulate.lanes_kernel`.
    """
    from stability.simulate import lanes_kernel as lk

    return lk


def choice() -> str:
    """The kernel in use.

    Returns
    -------
    str
        One of :data:`KERNELS`.
    """
    return _CHOICE["kernel"]


def lane_block(n_runs: int, nthreads: int) -> int:
    """Runs per block of the lanes kernel: up to :data:`.lanes_kernel.LANES`, at least 8 (one AVX-512 vector of
    doubles) unless fewer runs, and about four blocks per thread so that runs stopping early do not leave a thread
    idle.  The numbers do not depend on it.

    Parameters
    ----------
    n_runs : int
        Runs in the call.
    nthreads : int
        Kernel threads.

    Returns
    -------
    int
        Block size.
    """
    per = -(-n_runs // (4 * max(1, nthreads)))
    return int(max(1, min(lanes_kernel().LANES, max(8, per), n_runs)))


def run_lanes(k0: int, k1: int, args: tuple, nthreads: int, n_runs: int) -> None:
    """Steps ``k0 .. k1 - 1`` of every run on the lanes kernel with ``nthreads`` threads.

    The caller holds the engine's entry guard (:func:`stability.simulate.engine.kernel_entry_guard`).

    Parameters
    ----------
    k0, k1 : int
        First step and the step after the last.
    args : tuple
        The kernel's arrays (:func:`stability.simulate.kernel.run_batch`'s arguments after the steps).
    nthreads : int
        Threads (>= 1).
    n_runs : int
        Runs in ``args``.
    """
    lk = lanes_kernel()
    before = lk.get_num_threads()
    lk.set_num_threads(max(1, min(nthreads, before)))
    try:
        with lk.parallel_chunksize(1):
            lk.run_lanes(k0, k1, *args, lane_block(n_runs, nthreads))
    finally:
        lk.set_num_threads(before)
