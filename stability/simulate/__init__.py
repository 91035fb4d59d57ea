"""Nonlinear simulation of a freely rolling wheelchair (Collins 1987, chapter 7, program WCHAIR).

One compiled engine with two schemes on one physics (the generated equations
and contact forces of :mod:`stability.models` and the tire law of
:mod:`stability.tires.law`, compiled as they are): program WCHAIR's fixed-step
scheme (:mod:`.kernel`) and an error-controlled adaptive scheme with stick-slip
pin friction (:mod:`.adaptive`, its right-hand side in :mod:`.adaptive_kernel`).
Every setting of a run, its default and its valid range are one frozen object,
:class:`~stability.settings.run.RunSpec` (``run=``).  Schemes, conventions and
performance are described in ``docs/simulator.md``.

Examples
--------
>>> from stability.chair import preset
>>> from stability.simulate import RunSpec, simulate
>>> res = simulate(preset("ej-premier"), 0.75, RunSpec(horizon=4.0))   # doctest: +SKIP
>>> round(res.first_time_abs_yaw_rate(1.0), 2)                   # doctest: +SKIP
3.2
"""

from stability.settings.run import CASTERS, MODELS, OUT_OF_RANGE_POLICIES, SCHEMES, RunSpec
from stability.simulate.api import simulate, simulate_batch
from stability.simulate.controller import SampledController
from stability.simulate.engine import RECORDS, STATS_LEVELS
from stability.simulate.layout import LayoutRun, simulate_layout
from stability.simulate.linearise import linearise
from stability.simulate.options import (
    ADAPTIVE_METHOD,
    LOAD_LIMIT_N,
    SLIP_LIMIT_DEG,
    WARNING_LIMIT,
    WHEEL_LABELS,
    WHEELS,
)
from stability.simulate.results import ChairState, RunStats, SimulationResult
from stability.simulate.stepcheck import StepStabilityWarning

__all__ = ["SCHEMES", "MODELS", "CASTERS", "OUT_OF_RANGE_POLICIES", "WHEELS", "WHEEL_LABELS", "SLIP_LIMIT_DEG",
           "LOAD_LIMIT_N", "WARNING_LIMIT", "ADAPTIVE_METHOD", "RunSpec", "ChairState", "SimulationResult", "simulate",
           "simulate_batch", "linearise", "SampledController", "RunStats", "RECORDS", "STATS_LEVELS",
           "StepStabilityWarning", "simulate_layout", "LayoutRun"]
