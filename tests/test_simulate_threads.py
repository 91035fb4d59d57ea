"""The compiled simulator called from several Python threads at once (stability.simulate.engine).

numba's fallback threading layer ``workqueue`` aborts the process (exit 134) when two threads enter a
``parallel=True`` function at once; the engine serialises entry under it (engine.kernel_entry_guard).
Each run is computed by one thread with no reduction across runs, so results do not depend on what
else runs at the same time: two threads at once must give bit-identical results to the same calls one
after the other (no tolerance).  A threading layer is chosen once per process, so each layer is tried
in a subprocess; the layer this process picked is tried in-process.
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import simulate, simulate_batch

EJ = preset("ej-premier")
NAMES = ("t", "yaw_rate", "v", "eta", "beta", "fy", "normal_load")

# batches (parallel kernel), single runs (the same kernel on one thread) and the adaptive scheme
SCRIPT = textwrap.dedent("""
    import sys, threading
    import numpy as np
    import numba
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import simulate, simulate_batch

    EJ = preset("ej-premier")
    NAMES = {names!r}
    JOBS = [
        lambda: simulate_batch(EJ, np.linspace(0.5, 1.0, 6), RunSpec(horizon=1.0), progress=False, workers=1),
        lambda: simulate_batch(EJ.replace(trail=0.06), np.linspace(0.6, 0.9, 5), RunSpec(horizon=1.0),
                               progress=False, workers=1),
        lambda: [simulate(EJ, 0.8, RunSpec(horizon=1.0))],
        lambda: [simulate(EJ, 0.75, RunSpec(horizon=1.0, scheme="adaptive"))],
    ]
    try:
        alone = [job() for job in JOBS]
    except ValueError as exc:          # numba: "No threading layer could be loaded"
        print("unavailable:", exc)
        sys.exit(3)
    layer = numba.threading_layer()
    for rep in range(3):
        together = [None] * len(JOBS)
        def work(i):
            together[i] = JOBS[i]()
        threads = [threading.Thread(target=work, args=(i,)) for i in range(len(JOBS))]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        for a, b in zip(alone, together):
            assert b is not None and len(a) == len(b)
            for ra, rb in zip(a, b):
                for name in NAMES:
                    assert np.array_equal(getattr(ra, name), getattr(rb, name)), name
    print("layer", layer)
""").format(names=NAMES)


def _run_under(layer: str) -> subprocess.CompletedProcess:
    env = dict(os.environ, NUMBA_THREADING_LAYER=layer)
    return subprocess.run([sys.executable, "-c", SCRIPT], env=env, capture_output=True, text=True, timeout=900)


@pytest.mark.parametrize("layer", [
    "workqueue",                                       # the layer that aborted: always in the default run
    pytest.param("omp", marks=pytest.mark.slow),       # thread-safe layers: the slow step
    pytest.param("tbb", marks=pytest.mark.slow),
])
def test_threads_at_once_equal_one_after_the_other(layer):
    """Four jobs (two batches, a single run, an adaptive run) in four threads at once, three times,
    equal bit for bit the same jobs one after the other, under numba threading layer ``layer``."""
    proc = _run_under(layer)
    if proc.returncode == 3 and "unavailable" in proc.stdout:
        if os.environ.get("STABILITY_REQUIRE_THREADING_LAYERS"):     # CI installs libtbb12: no silent skip
            pytest.fail(f"numba cannot load the {layer} threading layer: {proc.stdout.strip()[:300]}")
        pytest.skip(f"numba cannot load the {layer} threading layer here: {proc.stdout.strip()[:300]}")
    assert proc.returncode == 0, (proc.returncode, proc.stdout[-2000:], proc.stderr[-2000:])
    assert proc.stdout.split()[-1] == layer                    # the layer asked for is the one that ran


def test_threads_at_once_in_this_process():
    """The same in this process, under whichever threading layer numba picked here."""
    jobs = [
        lambda: simulate_batch(EJ, np.linspace(0.5, 1.0, 4), run=RunSpec(horizon=0.5, friction_law="kinetic"), progress=False, workers=1),
        lambda: [simulate(EJ, 0.8, run=RunSpec(horizon=0.5, friction_law="kinetic"))],
        lambda: [simulate(EJ, 0.75, run=RunSpec(horizon=0.5, scheme="adaptive"))],
    ]
    alone = [job() for job in jobs]
    together: list = [None] * len(jobs)

    def work(i):
        together[i] = jobs[i]()

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(jobs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, together, strict=True):
        for ra, rb in zip(a, b, strict=True):
            for name in NAMES:
                np.testing.assert_array_equal(getattr(ra, name), getattr(rb, name), err_msg=name)


def test_a_one_thread_round_leaves_the_thread_count_as_it_was():
    """A search's small rounds run on one thread (study.summaries.SERIAL_BELOW); the thread count numba uses
    afterwards is the one before, so later batches keep every thread (before the fix a critical-impulse search
    left the process on one thread: the 2000-run benchmark then ran at 2.2x the numpy reference instead of 3.7x)."""
    import numba

    from stability.study import critical_impulses

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("one thread only on this machine")
    before = numba.get_num_threads()
    critical_impulses(EJ, [0.75])              # its rounds (one or two runs, fewer than 4) ask for one thread
    assert numba.get_num_threads() == before
