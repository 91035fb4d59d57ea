"""Batches of the WCHAIR scheme split over forked worker processes."""

from __future__ import annotations

import os

import numpy as np

from ..progress import ProgressBar
from .options import Options, n_steps
from .results import SimulationResult
from .wchair import wchair_batch

__all__ = ["auto_workers", "check_workers", "fork_context", "wchair_batch_processes"]

_RUNS_PER_WORKER = 250


def _usable_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - non-Linux
        return os.cpu_count() or 1


def auto_workers(n_runs: int, opts: Options) -> int:
    if opts.yaw_moment is not None:
        return 1
    return max(1, min(_usable_cpus(), n_runs // _RUNS_PER_WORKER))


def check_workers(workers) -> int:
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers={workers!r} is invalid; valid range: an integer >= 1, or None (automatic)")
    return int(workers)


def fork_context():
    import multiprocessing as mp

    if "fork" not in mp.get_all_start_methods():  # pragma: no cover - Windows
        return None
    return mp.get_context("fork")


class _CounterBar:
    """Progress sink of a worker process: a shared counter of steps done."""

    def __init__(self, counter):
        self.counter = counter

    def update(self, n: int = 1) -> None:
        self.counter.value += n


def _batch_worker(conn, chairs, speeds, opts, counter, forces) -> None:  # pragma: no cover - runs in a child
    try:
        res = wchair_batch(chairs, speeds, opts, False, bar=_CounterBar(counter), forces=forces)
        conn.send(("ok", res))
    except BaseException as exc:
        try:
            conn.send(("error", exc))
        except Exception:
            conn.send(("error", RuntimeError(f"{type(exc).__name__}: {exc}")))
    finally:
        conn.close()


def wchair_batch_processes(chairs, speeds, opts, progress, workers, forces=None) -> list[SimulationResult]:
    from multiprocessing.connection import wait

    ctx = fork_context()
    n = len(chairs)
    chunks = [np.arange(w, n, workers) for w in range(workers)]  # interleaved: balances early stops
    steps = n_steps(opts)
    procs, conns, counters = [], [], []
    for idx in chunks:
        parent, child = ctx.Pipe(duplex=False)
        counter = ctx.Value("q", 0, lock=False)
        pr = ctx.Process(target=_batch_worker, daemon=True,
                         args=(child, [chairs[i] for i in idx], speeds[idx], opts, counter,
                               None if forces is None else forces[idx]))
        pr.start()
        child.close()
        procs.append(pr)
        conns.append(parent)
        counters.append(counter)
    results: list = [None] * workers
    pending = dict(zip(conns, range(workers), strict=False))
    shown = 0
    try:
        with ProgressBar(steps * workers, "simulate (wchair batch)", enabled=progress, unit="step") as bar:
            while pending:
                for conn in wait(list(pending), timeout=0.1):
                    w = pending.pop(conn)
                    try:
                        status, payload = conn.recv()
                    except EOFError:
                        raise RuntimeError(f"batch worker {w} died (exit code {procs[w].exitcode})") from None
                    if status != "ok":
                        raise payload
                    results[w] = payload
                total = sum(c.value for c in counters)
                bar.update(total - shown)
                shown = total
    finally:
        for pr in procs:
            if pr.is_alive():
                pr.terminate()
            pr.join()
    out: list = [None] * n
    for idx, res in zip(chunks, results, strict=False):
        for i, r in zip(idx, res, strict=False):
            out[int(i)] = r
    return out
