"""Suite-wide settings: how many pytest-xdist workers ``-n auto`` (pyproject's addopts) starts, and the kernels
compiled once before they start (:func:`pytest_sessionstart`).

Every worker compiles the numba kernels once on a cold cache (about 10-15 s of CPU each) and holds its own
copy of the imported stack (about 0.3 GB), so more workers than four buy little and cost memory; on the 2-core
reference machine this gives two.  ``PYTEST_XDIST_AUTO_NUM_WORKERS`` still overrides it, and ``-n 0`` runs
everything in one process.
"""

from __future__ import annotations

import contextlib
import gc
import io
import os
import subprocess
import sys
from pathlib import Path

import pytest

# One BLAS thread per process, set before anything imports numpy (OpenBLAS reads it when it loads; the workers and
# the subprocesses the tests start inherit it).  The suite's matrices are small (at most a few dozen states), so a
# second thread buys nothing and its busy-waiting doubles the CPU time: tests/test_assist_top_speed.py took
# 19.4 s of CPU with OpenBLAS's default threads and 8.8 s with one (user time, -n 0, 2-core machine).  A value
# the environment already gives is kept.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

#: Largest number of workers ``-n auto`` starts.
MAX_AUTO_WORKERS = 4


def pytest_xdist_auto_num_workers(config):
    """Cores this process may run on, at most :data:`MAX_AUTO_WORKERS` (None: the variable decides)."""
    if os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS"):
        return None
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cores, MAX_AUTO_WORKERS))


@pytest.hookimpl(tryfirst=True)
def pytest_sessionstart(session):
    """Before pytest-xdist starts its workers: compile the kernels once (tests/kernel_warmup.py).

    Each worker would otherwise compile, on a cold cache, every kernel variant it meets: about 50 s of CPU per
    worker.  The warm-up's groups run in parallel subprocesses; on a warm cache they only load the kernels (about
    2 s of CPU each).  Not in a worker, not with ``-n 0`` or one worker (nothing compiles twice), nor with
    ``STABILITY_TEST_WARMUP=0``.  A failing warm-up is only noted: the tests that use the kernel will fail on it.
    """
    config = session.config
    workers = getattr(config.option, "numprocesses", None) or 0
    if hasattr(config, "workerinput") or not isinstance(workers, int) or workers < 2:
        return
    if os.environ.get("STABILITY_TEST_WARMUP", "1") == "0":
        return
    import importlib.util

    from kernel_warmup import GROUPS

    spec = importlib.util.find_spec("stability")       # the copy the workers import (a worktree's, not the venv's)
    if spec is None or spec.origin is None:
        return
    path = [str(Path(spec.origin).parents[1]), *filter(None, [os.environ.get("PYTHONPATH")])]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(path)}
    script = str(Path(__file__).with_name("kernel_warmup.py"))
    procs = [subprocess.Popen([sys.executable, script, group], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True, env=env) for group in GROUPS]
    for group, proc in zip(GROUPS, procs, strict=True):
        _, err = proc.communicate()
        if proc.returncode:
            tail = err.strip().splitlines()[-1:] or ["(no message)"]
            sys.stderr.write(f"kernel warm-up {group!r} failed (status {proc.returncode}): {tail[0]}\n")


#: Test files whose every test is marked ``ui`` (each module's ``pytestmark``): the explorer's browser tests.
#: Importing them imports panel, bokeh and playwright's API (about 1.5 s of CPU), in every process that collects
#: them (each pytest-xdist worker collects every file), for tests a run that deselects ``ui`` never runs.
UI_ONLY = ("ui", "benchmarks/test_bench_app_browser.py")


def deselects_every(markexpr: str, mark: str) -> bool:
    """True when ``-m markexpr`` deselects every test marked ``mark`` whatever its other marks: the expression is
    a conjunction (``a and b and ...``, no ``or``, no parentheses) of which ``not mark`` is one term (the default
    run's ``not slow and not docs and not ui and not scale``).  Any other expression is taken to select some."""
    terms = markexpr.split(" and ")
    if not markexpr.strip() or "(" in markexpr or any(" or " in f" {t} " for t in terms):
        return False
    return any(t.split() == ["not", mark] for t in terms)


def pytest_ignore_collect(collection_path, config):
    """The :data:`UI_ONLY` files are not collected (not imported) when the run's ``-m`` deselects every ``ui``
    test; otherwise pytest decides (None)."""
    here = Path(__file__).parent
    if collection_path.is_relative_to(here) and \
            collection_path.relative_to(here).as_posix() in UI_ONLY and \
            deselects_every(config.getoption("markexpr") or "", "ui"):
        return True
    return None


def pytest_collection_finish(session):
    """After collection: move every object alive now (the imported stack, the collected items) to the collector's
    permanent generation (:func:`gc.freeze`), so that the full collections the tests' allocations trigger, and
    pytest's own at the end, no longer traverse them.  Nothing the tests compute changes (a collection only frees
    unreachable cycles); full collections cost about half as much: 0.88 -> 0.38-0.49 s of CPU over six of the
    heaviest test files in one process (gc.callbacks timing)."""
    gc.freeze()


@pytest.fixture(scope="session")
def shared_run():
    """``run(command, argv)``: one in-process run of ``python -m stability.COMMAND ARGV`` per session, shared by
    the tests (in any file) that read different parts of the same output; ``(status, stdout, stderr)``.

    Only for runs whose output depends on ``argv`` alone (no temporary paths, no files written, no patched
    functions): a test that checks a side effect or patches the computation runs the command itself.  The strings
    are immutable, so a test cannot change what another reads.
    """
    from stability.cli.commands import command_module

    done: dict[tuple[str, tuple[str, ...]], tuple[int, str, str]] = {}

    def run(command: str, argv: list[str]) -> tuple[int, str, str]:
        key = (command, tuple(argv))
        if key not in done:
            out, err = io.StringIO(), io.StringIO()
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                status = command_module(command).main(list(argv))
            done[key] = (status, out.getvalue(), err.getvalue())
        return done[key]

    return run


@pytest.fixture
def first_use_watches(monkeypatch):
    """Run two short E&J Premier runs as a batch on a WCHAIR kernel (``"scalar"`` or ``"lanes"``) with the
    kernel's specialisation found again, and return the first-use watches of key ``"wchair"`` they went through, as
    ``(module, key)``: ``"engine"`` (the launch) or ``"kernel"`` (``kernel.call_model`` or ``lanes_kernel._entry``, where it is
    loaded)."""
    import contextlib

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import engine, kernel, simulate_batch

    def run(which):
        seen = []

        def recorder(where):
            @contextlib.contextmanager
            def watch(scheme):
                seen.append((where, scheme))
                yield
            return watch

        monkeypatch.setattr(engine, "first_use", recorder("engine"))
        monkeypatch.setattr(kernel, "first_use", recorder("kernel"))
        monkeypatch.setattr(kernel, "_ENTRIES", {})      # the specialisation is found (loaded) again
        if which == "lanes":                             # its own entries, found at _block's address
            from stability.simulate import lanes_kernel

            monkeypatch.setattr(lanes_kernel, "first_use", recorder("kernel"))
            monkeypatch.setattr(lanes_kernel, "_ENTRIES", {})
        with engine.use_kernel(which):
            simulate_batch(preset("ej-premier"), [0.5, 0.75], RunSpec(horizon=0.01), progress=False)
        return [s for s in seen if s[1] == "wchair"]
    return run
