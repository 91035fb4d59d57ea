"""The explorer's page object without a browser (needs the ``app`` extra; runs in the ui step)."""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from stability import chair as chair_mod

pytestmark = pytest.mark.ui
pytest.importorskip("panel")

EXAMPLES = pathlib.Path(__file__).parents[2] / "docs" / "examples"


def test_uncertainty_band_is_the_linear_intervals():
    from stability.app.page import Explorer
    from stability.linear.intervals import linear_intervals
    from stability.measure.uncertainty import load_uncertainty

    ex = Explorer(auto_nonlinear=False)
    path = EXAMPLES / "measured_chair.uncertainty.toml"
    assert ex.state.load_uncertainty(path.read_bytes(), path.name) is None
    ex._start_bands()
    ex.jobs._futures[-1].result(timeout=600)
    data = ex.unc_src.data
    speeds = np.asarray(data["speed"])
    want = linear_intervals(chair_mod.preset("ej-premier"), load_uncertainty(path), speeds=speeds, samples=300,
                            seed=0)
    assert list(data["low"]) == [a for a, _ in want.rate] and list(data["high"]) == [b for _, b in want.rate]
    assert np.all(np.asarray(data["low"]) <= np.asarray(data["high"]))


def test_a_chair_change_drops_the_old_chairs_results():
    """A result computed for an older chair is never shown (the jobs' generation moved on)."""
    import threading

    from stability.app.jobs import executor
    from stability.app.page import Explorer

    shown: list = []
    gate = threading.Event()
    blocker = executor().submit(gate.wait)      # the worker is busy: the old chair's request waits in the queue
    ex = Explorer(auto_nonlinear=False)
    ex.jobs.submit(lambda: "old chair's result", shown.append, shown.append)
    ex.edit("trail", "0.05")                    # the chair changes: its queued work is dropped
    ex.jobs.submit(lambda: "new chair's result", shown.append, shown.append)
    gate.set()
    blocker.result(timeout=60)
    for f in list(ex.jobs._futures):
        if not f.cancelled():
            f.result(timeout=600)
    assert shown == ["new chair's result"]
