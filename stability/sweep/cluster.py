"""Running a sweep's chunks on a Dask distributed cluster (optional extra ``[scale]``).

``--dask local:N`` starts a ``LocalCluster`` of N process workers bound to
127.0.0.1, one thread each (and one numba thread each: ``NUMBA_NUM_THREADS=1``
in the workers' environment), and closes it at the end; ``--dask ADDRESS``
connects to a running scheduler (docs/scale.md: dask-jobqueue on SLURM, a
Kubernetes Dask cluster).  The spec (with its uncertainty distributions) is
sent to every worker once; a warm-up task on every worker loads the compiled
kernels (from the worker's own on-disk numba cache, ``NUMBA_CACHE_DIR``
unless the environment sets one, compiling them there the first time)
before any chunk runs; chunks are submitted most expensive first (longest
processing time first: the estimated cost per row of each measure times the
chunk's rows), so the last chunks to finish are short ones.  A chunk computes
the same numbers on any worker: the results equal an in-process run's.
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import tempfile
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

from stability.sweep.measures import chunk_pairs
from stability.sweep.spec import SweepSpec

__all__ = ["COST_PER_ROW_S", "chunk_cost", "dask_mapper", "parse_dask", "worker_cache_dir"]

#: Measured cost per row of each measure on one core, s (docs/scale.md; shimmy margin, tip angles and holding
#: moment: 7.1, 0.12 and 2.5 ms per row of a 10-row chunk, CPU time); used only to order the chunks.  Every
#: measure of stability.sweep.spec.MEASURES has one (tests/test_sweep.py).
COST_PER_ROW_S = {"growth_rate": 2e-4, "critical_speeds": 2e-3, "critical_impulse": 0.03,
                  "equal_instability_speed": 0.016, "shimmy_margin": 7e-3, "tip_angles": 1.2e-4,
                  "holding_moment": 2.5e-3, "human_limited_speed": 1e-3, "bench": 3e-3}


def chunk_cost(spec: SweepSpec, index: int) -> float:
    """Estimated cost of chunk ``index``: its rows times the measures' cost per row.

    Parameters
    ----------
    spec : SweepSpec
    index : int
        Chunk number.

    Returns
    -------
    float
        Seconds of one core (used only to order the chunks).
    """
    rows = len(chunk_pairs(spec, index)) * len(spec.speeds)
    return rows * sum(COST_PER_ROW_S[m] for m in spec.measures)


def parse_dask(value: str) -> tuple[str, int | None]:
    """Read a ``--dask`` value.

    Parameters
    ----------
    value : str
        ``"local:N"`` or a scheduler address.

    Returns
    -------
    (str, int or None)
        ``("local", N)`` or ``(address, None)``; ValueError naming ``--dask`` otherwise.
    """
    if value.startswith("local:"):
        n = value[len("local:"):]
        if not n.isdigit() or not 1 <= int(n) <= 1024:
            raise ValueError(f"--dask {value!r} is invalid; valid: local:N with 1 <= N <= 1024, or a scheduler "
                             "address such as tcp://host:8786")
        return "local", int(n)
    if "://" not in value and ":" not in value:
        raise ValueError(f"--dask {value!r} is invalid; valid: local:N or a scheduler address (tcp://host:8786)")
    return value, None


def worker_cache_dir(environ: Mapping[str, str], worker: str) -> str | None:
    """The numba cache directory a worker should use: its own, unless the environment names one.

    Two worker processes writing the same cache index at once (a shared home
    directory on a cluster, or the package's ``__pycache__``) can leave it
    half-written; one directory per worker name avoids that.  It lives under
    the temporary directory and survives the worker, so a worker of the same
    name on the same machine (``local:N`` workers are named 0 .. N-1) loads the
    kernels instead of compiling them again (about 2 s instead of 7-13 s).

    Parameters
    ----------
    environ : mapping
        The worker's environment.
    worker : str
        The worker's name.

    Returns
    -------
    str or None
        The directory, or None when ``NUMBA_CACHE_DIR`` is already set (the user's or the cluster's choice).
    """
    if environ.get("NUMBA_CACHE_DIR"):
        return None
    user = str(os.getuid()) if hasattr(os, "getuid") else "user"
    safe = re.sub(r"[^A-Za-z0-9_.-]", "_", worker) or "worker"
    return str(Path(tempfile.gettempdir()) / f"stability-numba-{user}" / safe)


def _warm_up(dask_worker: Any = None) -> str:
    """Point numba at this worker's cache, load (or compile) the kernels with one short run; what it did.

    ``Client.run`` passes the worker as ``dask_worker``: its name (``0 .. N-1``
    for ``local:N``) keys the cache, so the next cluster's worker of that name
    loads the kernels instead of compiling them again.  (``get_worker()`` only
    works inside a task; outside one the process id, new every run, would key it.)
    """
    name = str(dask_worker.name) if dask_worker is not None else f"pid{os.getpid()}"
    cache = worker_cache_dir(os.environ, name)
    if cache is not None:
        os.environ["NUMBA_CACHE_DIR"] = cache
        if "numba" in sys.modules:             # numba read its configuration at import: read it again
            from numba.core import config

            config.reload_config()
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.simulate.kernel import get_num_threads

    simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.01), record="final")
    return f"numba threads {get_num_threads()}, cache {os.environ.get('NUMBA_CACHE_DIR', 'default')}"


def _chunk_text(spec: SweepSpec, index: int) -> str:
    from stability.sweep.measures import compute_chunk
    from stability.sweep.run import _chunk_text as text

    return text(compute_chunk(spec, index))


@contextlib.contextmanager
def dask_mapper(spec: SweepSpec, address: str) -> Iterator[Callable[[Callable[[int], str], Sequence[int]],
                                                                    Iterable[tuple[int, str]]]]:
    """A ``mapper`` for :func:`stability.sweep.run.run_sweep` that runs the chunks on a Dask cluster.

    Parameters
    ----------
    spec : SweepSpec
    address : str
        ``"local:N"`` or a scheduler address.

    Yields
    ------
    callable
        ``mapper(fn, indices)`` yielding ``(index, chunk text)`` as chunks finish (``fn`` is not
        shipped: the workers compute :func:`stability.sweep.measures.compute_chunk` themselves).
    """
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise ValueError("--dask needs dask[distributed] (pip install 'stability[scale]')") from None
    where, n = parse_dask(address)
    with contextlib.ExitStack() as stack:
        if n is not None:
            cluster = stack.enter_context(LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                                       host="127.0.0.1", dashboard_address=None,
                                                       env={"NUMBA_NUM_THREADS": "1"}))
            client = stack.enter_context(Client(cluster))
        else:
            client = stack.enter_context(Client(where))
        client.run(_warm_up)                                    # every worker, before any chunk (its own cache)
        shared = client.scatter(spec, broadcast=True)           # the spec and its distributions, sent once

        def mapper(fn: Callable[[int], str], indices: Sequence[int]) -> Iterable[tuple[int, str]]:
            order = sorted(indices, key=lambda i: -chunk_cost(spec, i))
            futures: dict[Any, int] = {client.submit(_chunk_text, shared, i, pure=False): i for i in order}
            for fut in as_completed(futures):
                yield futures[fut], fut.result()

        yield mapper
