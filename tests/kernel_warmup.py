"""Compile the numba kernels the default tests use, once, before pytest-xdist starts its workers.

On a cold cache every worker compiled each kernel variant it met (the layout kernel about 30 s of CPU, each
WCHAIR variant 5-15 s), so two workers compiled most of them twice.  :func:`warm` runs a few very short runs that
reach every variant the default tests compile; ``tests/conftest.py`` runs the :data:`GROUPS` in parallel
subprocesses (``python tests/kernel_warmup.py GROUP``) and the workers then load the kernels from the cache.  On a
warm cache each group only loads them (about 2 s of CPU).  The runs' results are not checked: this is not a test.
"""

from __future__ import annotations

import sys


def _layout() -> None:
    """The layout kernel (``step_layouts``): one run, stepped to its end, and a stepped batch with a Python hook;
    then one run of each other shape the tests run (two fixed wheels and one to four casters), whose equations are
    compiled on their own (the kernel calls them at their addresses), and a run with a sampled controller."""
    import dataclasses

    import numpy as np

    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.simulate.controller import SampledController
    from stability.simulate.layout import layout_state_order, simulate_layout
    from stability.simulate.layout_batch import simulate_layout_batch

    lay = layout_preset("mid-wheel-drive")
    spec = RunSpec(horizon=0.01, stop_on_warnings=False)
    simulate_layout(lay, 1.0, spec)
    simulate_layout_batch(lay, [1.0, -1.0], spec, yaw_moment=lambda t, s: np.zeros(len(s.run)))
    for nc in (1, 2, 3):       # its first casters: the shapes (2, 1) to (2, 3)
        simulate_layout(dataclasses.replace(lay, casters=lay.casters[:nc]), 1.0, spec)
    # a sampled controller (compiled on its own, called at its address: a run without one compiles none)
    const = SampledController(0.005, np.zeros((1, len(layout_state_order(lay)))), np.array([1.0]),
                              state_names=layout_state_order(lay))
    simulate_layout(lay, 1.0, spec, controller=const, motor_lag_s=0.02)


def _wchair() -> None:
    """The WCHAIR kernel's variants the default tests use (thesis, exact and slope models, one run and a batch;
    thesis and exact with a sampled controller; stepped with a Python hook)."""
    import numpy as np

    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import SampledController, simulate, simulate_batch

    chair = preset("ej-premier")
    ctl = SampledController.state_feedback(np.zeros(7), 0.001)
    for model in ("thesis", "exact"):
        run = RunSpec(horizon=0.01, model=model)
        simulate(chair, 0.75, run)
        simulate(chair, 0.75, run, controller=ctl)
        simulate(chair, 0.75, run, yaw_moment=lambda t, s: 0.0)
        simulate_batch(chair, [0.5, 0.75], run, progress=False)
    slope = RunSpec(horizon=0.01, cross_slope_deg=2.0)
    simulate(chair, 0.75, slope)
    simulate(chair, 0.75, slope, yaw_moment=lambda t, s: 0.0)
    simulate_batch(chair, [0.5, 0.75], slope, progress=False)


def _adaptive() -> None:
    """The adaptive scheme (its own compiled right-hand side; nothing of the WCHAIR kernel's step)."""
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import simulate

    simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.01, scheme="adaptive"))


#: Groups of about equal compile cost, one subprocess each (the suite's start waits for the longest).  Measured
#: with an empty cache, process CPU, one at a time: the WCHAIR variants about 23 s, the adaptive scheme 5.9 s alone
#: and the layout kernel 12 s after it (15.6 s alone).  With the adaptive scheme in the WCHAIR group it was 29.5 s
#: against the layout's 15.6 s, so on two cores one sat idle for about 14 s.
GROUPS = {"layout": (_adaptive, _layout), "wchair": (_wchair,)}


def warm(group: str) -> None:
    """Run group ``group``'s short runs (compiling, or loading from the cache, what they use)."""
    for part in GROUPS[group]:
        part()


if __name__ == "__main__":
    for name in sys.argv[1:]:
        warm(name)
