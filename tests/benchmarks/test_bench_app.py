"""The explorer's linear update: a chair edit, from the server receiving it to every linear view's data ready.

What is timed is :meth:`stability.app.page.Explorer.edit` in the server
process: the edit checked as ``--set`` is, the linear views' data computed
(:func:`stability.app.views.linear_view`: eigenvalues at 160 speeds with the
critical speeds, locked-caster critical speeds, the divergence table, mode
names), the mode shape at the slider's speed, the geometry, the compare
curves, and every Bokeh data source and text pane updated (what Bokeh then
sends to the browser).  The nonlinear measures are queued after that and not
waited for (``auto_nonlinear=False`` here so that the worker thread does not
share the two cores with the timing).

Target: 100 ms on the 2-core machine, stated as a ratio against one bare
:func:`stability.analyse` of the same chair timed interleaved in the same run
(best of 7 each): the update should cost at most :data:`RATIO` analyses (recorded and printed, not asserted:
no test asserts wall-clock time).
``analyse`` measured 133-299 ms on the 2-core machine under other jobs' load
(docs/app.md), so 0.45 analyses is within 100 ms whenever ``analyse`` takes up to
220 ms; measured: x0.25 (33 ms against 133 ms).
"""

from __future__ import annotations

import time

import pytest

import stability

#: Largest update time in units of one bare ``stability.analyse`` (see the module docstring).
RATIO = 0.45


@pytest.fixture
def bench(request):
    cfg = request.config
    if cfg.getoption("benchmark_disable", False) and not cfg.getoption("benchmark_enable", False):
        pytest.skip("benchmarks are disabled (run with --benchmark-enable)")
    return request.getfixturevalue("benchmark")


def test_bench_linear_update(bench):
    pytest.importorskip("panel")        # here, not at import: collecting this file (every run) needs no panel
    from stability.app.page import Explorer

    ex = Explorer(auto_nonlinear=False)
    values = iter(["0.05", "0.06"] * 100)

    def update():
        assert ex.edit("trail", next(values)) is None

    update()                                                     # warm-up (first calls, imports)
    bench.pedantic(update, rounds=3, iterations=1)
    t_update = t_analyse = float("inf")
    for _ in range(7):
        t0 = time.perf_counter()
        update()
        t_update = min(t_update, time.perf_counter() - t0)
        chair = ex.state.chair
        t0 = time.perf_counter()
        stability.analyse(chair)
        t_analyse = min(t_analyse, time.perf_counter() - t0)
    ratio = t_update / t_analyse
    bench.extra_info.update(update_s=t_update, analyse_s=t_analyse, ratio=ratio)
    print(f"\nexplorer linear update: {t_update * 1e3:.0f} ms; one bare stability.analyse of the same chair "
          f"{t_analyse * 1e3:.0f} ms (update = x{ratio:.2f} analyse; target x{RATIO} = about 100 ms)")
    # recorded, not asserted: a wall-clock ratio on a shared machine (issue 34)
