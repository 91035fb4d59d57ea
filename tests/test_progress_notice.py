"""Long work says so: a block that runs past the notice time prints its message once on stderr; a quick one, or
one under --quiet, prints nothing (the first-use compile of the simulator uses this)."""

from __future__ import annotations

import io
import time

from stability.runtime import progress


def test_notice_only_when_slow_and_not_quiet():
    out = io.StringIO()
    with progress.notice_if_slow("compiling", after=0.05, file=out):
        time.sleep(0.3)
    assert out.getvalue() == "compiling\n"
    out = io.StringIO()
    with progress.notice_if_slow("compiling", after=5.0, file=out):
        pass
    time.sleep(0.05)
    assert out.getvalue() == ""
    out = io.StringIO()
    with progress.quiet(), progress.notice_if_slow("compiling", after=0.01, file=out):
        time.sleep(0.1)
    assert out.getvalue() == ""


def test_simulator_says_compiling_once_per_process(monkeypatch):
    from stability.simulate import first_use

    monkeypatch.setattr(first_use, "_FIRST_USE", {"wchair": True, "wchair_load": True, "adaptive_load": True,
                                                  "layout": True})
    monkeypatch.setattr(first_use, "NOTICE_AFTER_S", 0.0)     # every block runs past it: no waiting needed
    said = []
    monkeypatch.setattr(first_use, "notice_if_slow", lambda msg, after: _Recorder(said, msg))
    with first_use.first_use("wchair_load"):
        pass
    with first_use.first_use("wchair"):
        pass
    with first_use.first_use("layout"):
        pass
    assert said == [first_use.COMPILE_NOTICE]       # the later blocks are silent: one notice per process
    assert "first use" in first_use.COMPILE_NOTICE


def test_a_watched_block_inside_another_adds_no_notice(monkeypatch):
    """A kernel's load inside a block already watched (the lanes kernel's specialisation found inside a launch) is
    covered by the outer block's notice: one watch, so one line at most."""
    from stability.simulate import first_use

    monkeypatch.setattr(first_use, "_FIRST_USE", {"wchair": True, "layout": True})
    said = []
    monkeypatch.setattr(first_use, "notice_if_slow", lambda msg, after: _Recorder(said, msg))
    with first_use.first_use("wchair"), first_use.first_use("layout"):
        pass
    assert said == [first_use.COMPILE_NOTICE]
    assert first_use._FIRST_USE["layout"]       # the inner key was not watched, so its own first use is still ahead


def test_a_later_load_is_watched_while_nothing_has_been_said(monkeypatch):
    """A quick load (from the cache) says nothing and leaves the notice armed: a later compile (another variant of
    the kernel, the same key) that runs past the notice time says so, once."""
    from stability.simulate import first_use

    monkeypatch.setattr(first_use, "_FIRST_USE", {"wchair": True})
    monkeypatch.setattr(first_use, "NOTICE_AFTER_S", 3600.0)
    with first_use.first_use("wchair"):
        pass                                         # a load from the cache: quicker than that, nothing said
    monkeypatch.setattr(first_use, "NOTICE_AFTER_S", 0.0)     # the later blocks run past it: no waiting needed
    said = []
    monkeypatch.setattr(first_use, "notice_if_slow", lambda msg, after: _Recorder(said, msg))
    with first_use.first_use("wchair"):
        pass                                         # a later variant's compile
    with first_use.first_use("wchair"):
        pass
    assert said == [first_use.COMPILE_NOTICE]


def test_a_kernels_load_is_watched_without_the_run_after_it(monkeypatch):
    """The layout kernel is loaded (or compiled) under the notice before its first call, for the types numba gives
    the call's arguments; a loaded kernel is not loaded again."""
    import numba
    import numpy as np

    from stability.simulate import first_use

    monkeypatch.setattr(first_use, "_FIRST_USE", {"layout": True})
    said = []
    monkeypatch.setattr(first_use, "notice_if_slow", lambda msg, after: _Recorder(said, msg))

    class Dispatcher:
        signatures: list = []

        def compile(self, sig):
            self.signatures = [sig]

    d = Dispatcher()
    first_use.load_kernel(d, (0, 1.5, np.zeros((2, 3))), "layout")
    assert d.signatures == [(numba.int64, numba.float64, numba.float64[:, ::1])]
    assert said == [first_use.COMPILE_NOTICE]
    first_use.load_kernel(d, (0, 1.5, np.zeros((2, 3))), "layout")
    assert d.signatures == [(numba.int64, numba.float64, numba.float64[:, ::1])] and len(said) == 1


def test_one_layout_run_and_a_hooked_batch_share_the_kernel_they_load():
    """The load before the first call types the arguments as the call does: the layout kernel has one signature
    after a run and a stepped batch (a mismatch would compile it twice: about 11 s more on a first use)."""
    import numpy as np

    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.simulate import layout_kernel
    from stability.simulate.layout import simulate_layout
    from stability.simulate.layout_batch import simulate_layout_batch

    lay, spec = layout_preset("mid-wheel-drive"), RunSpec(horizon=0.01, stop_on_warnings=False)
    simulate_layout(lay, 1.0, spec)
    simulate_layout_batch(lay, [1.0, -1.0], spec, yaw_moment=lambda t, s: np.zeros(len(s.run)))
    assert len(layout_kernel.step_layouts.signatures) == 1


class _Recorder:
    def __init__(self, said, msg):
        self.said, self.msg = said, msg

    def __enter__(self):
        self.said.append(self.msg)

    def __exit__(self, *exc):
        return False


def test_the_scalar_kernels_load_is_watched_apart_from_its_runs(first_use_watches):
    """The WCHAIR kernel's first-use notice watches the load of its specialisation (kernel.call_model), not the
    launch that runs the batch: a large first batch of a cached kernel runs past the notice time without compiling."""
    assert first_use_watches("scalar") == [("kernel", "wchair")]



def test_the_adaptive_schemes_kernels_are_loaded_as_their_calls_type_them():
    """The adaptive scheme's right-hand side and samples are loaded under the notice before their first calls, for
    the types the calls give: one signature each after runs of both models (a mismatch would compile them twice)."""
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import adaptive_kernel, simulate

    simulate(preset("ej-premier"), 0.75, RunSpec(scheme="adaptive", horizon=0.05))
    simulate(preset("ej-premier"), 1.0, RunSpec(scheme="adaptive", horizon=0.05, model="thesis"))
    assert len(adaptive_kernel.evaluate.signatures) == 1
    assert len(adaptive_kernel.samples.signatures) == 1


def test_a_layout_shapes_equations_load_under_the_notice(monkeypatch):
    """A layout's shape compiles its generated equations on its own (at their addresses) the first time a process
    runs it: that load is watched too, not only the step's."""
    import contextlib

    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.simulate import layout_kernel
    from stability.simulate.layout import simulate_layout

    seen = []

    @contextlib.contextmanager
    def watch(scheme):
        seen.append(scheme)
        yield

    monkeypatch.setattr(layout_kernel, "first_use", watch)
    monkeypatch.setattr(layout_kernel, "_ADDRESSES", {})      # the shape's addresses are taken again
    simulate_layout(layout_preset("mid-wheel-drive"), 1.0, RunSpec(horizon=0.01, stop_on_warnings=False))
    assert seen == ["layout"]
