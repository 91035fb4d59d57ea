"""The adaptive scheme ends a run whose normal loads lose their solution instead of raising.

Late in a spin-out (power-fwd at 1.5 m/s after a 400 N, 0.1 s push, exact model) the chair pivots about its
left main wheel and the left caster lifts off; at t = 1.0114 s the load-transfer fixed point stops converging
(a trial state of LSODA swings the left wheels between lifted and loaded, period 2).  Before, the run raised
``RuntimeError("normal loads and tire forces did not converge ...")`` and the command line and the
critical-impulse search (whose first push is this one) crashed.  Now the run ends at the last time it could
integrate, marked ``stopped_by_warnings`` with ``stop_time`` and a one-line ``stop_reason``.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.simulate.adaptive import NoLoadSolution

POWER_FWD = preset("power-fwd")
PUSH = RunSpec(scheme="adaptive", model="exact", push_force=400.0, push_duration=0.1, stop_on_warnings=False)
FAIL = re.compile(r"no converging solution at t = (\d+\.\d+) s \(the left caster lifts off: load (-?\d+) N, "
                  r"yaw rate ([-+]\d+\.\d+) rad/s at (\d+\.\d+) s, the last time integrated\)")


@pytest.fixture(scope="module")
def stopped():
    return simulate(POWER_FWD, 1.5, PUSH.replace(horizon=10.0))


def test_the_run_ends_before_the_failure_and_says_why(stopped):
    r = stopped
    assert r.stopped_by_warnings and r.stop_time == r.t[-1]
    m = FAIL.search(r.stop_reason)
    assert m, r.stop_reason
    t_fail, load, rate, t_last = float(m[1]), float(m[2]), float(m[3]), float(m[4])
    # the run reached past 1.0 s (the samples up to there are kept) and stops before the failing evaluation; error
    # model: rounding of the reason's time to 4 decimals (half a unit, 5e-5 s; a strict bound, plus the parse's ulp)
    assert 1.0 < r.t[-1] < t_fail < 1.02 and t_last == pytest.approx(r.t[-1], abs=5e-5 + 1e-12)
    # every regular sample up to the stop, then the stop itself
    np.testing.assert_array_equal(r.t[:-1], 0.01 * np.arange(len(r.t) - 1))
    assert r.t[-1] - r.t[-2] < 0.01
    # the reason's numbers are the last sample's: the left caster's load is negative, the chair spins
    assert r.normal_load[-1, 0] < 0 and load == round(r.normal_load[-1, 0])
    assert rate == round(r.yaw_rate[-1], 2) and abs(rate) > 3.0
    # no digits of LSODA's trial points (the failing evaluation's time depends on the integrator's step choice):
    # the physical event is what is asserted above (a caster lifts off, the chair spins); the push's effect before
    # it is an integrator-independent fact: 1 rad/s is reached well before the stop
    assert 0.0 < r.first_time_abs_yaw_rate(1.0) < r.t[-1]
    assert r.warnings["lift_off"]["count"] >= 1 and r.to_dict()["stop_reason"] == r.stop_reason


def test_the_samples_before_the_stop_are_those_of_a_run_that_ends_earlier(stopped):
    """Up to 1.0 s the stopped run and a 1.0 s run solve the same ODE with the same solver and tolerances;
    they differ only in the last segment's step sequence (LSODA's first step and its tcrit clipping depend on
    the segment's end).

    Error model: LSODA keeps each step's local error within rtol |y| + atol, so a run's global error is
    proportional to the tolerance: e(tol) ~= 2 |y(tol) - y(tol / 2)| (the same run at halved rtol and atol).
    Two runs at the same tolerance then differ by at most e_a + e_b ~= 4 |y(tol) - y(tol / 2)|.  Observed:
    5.1e-9 rad/s against 4 x 1.16e-6 = 4.6e-6 rad/s (margin ~900)."""
    short = simulate(POWER_FWD, 1.5, PUSH.replace(horizon=1.0))
    half = simulate(POWER_FWD, 1.5, PUSH.replace(horizon=1.0, rtol=0.5e-6, atol=0.5e-9))
    assert short.t[-1] == 1.0 and not short.stopped_by_warnings and short.stop_reason is None
    bound = 4.0 * abs(short.yaw_rate[-1] - half.yaw_rate[-1])
    assert 0 < bound < 1e-4                                  # the bound still sees an error of 1e-4 rad/s
    i = int(np.flatnonzero(stopped.t == 1.0)[0])
    # error model: the docstring's, two runs' global errors, each ~2 |y(tol) - y(tol / 2)|
    assert abs(stopped.yaw_rate[i] - short.yaw_rate[-1]) <= bound
    assert np.max(np.abs(stopped.yaw_rate[:i + 1] - short.yaw_rate)) <= bound


def test_a_run_with_a_python_input_stops_as_without(stopped):
    """A Python yaw_moment input (here 0 N m) goes through the same compiled right-hand side: the same
    NoLoadSolution from its load loop, the same stop, bit for bit."""
    p = simulate(POWER_FWD, 1.5, PUSH.replace(horizon=10.0), yaw_moment=lambda t, s: 0.0)
    assert p.stopped_by_warnings and FAIL.search(p.stop_reason) and p.stop_reason == stopped.stop_reason
    np.testing.assert_array_equal(p.yaw_rate, stopped.yaw_rate)


def test_no_load_solution_is_a_runtime_error_with_its_time():
    e = NoLoadSolution(np.array([1.5, 1.25]))
    assert isinstance(e, RuntimeError) and e.t == 1.25 and "did not converge" in str(e)


def test_the_searches_count_a_stopped_run_at_its_crossing_or_at_its_stop(stopped):
    """A run stopped after reaching the level reaches it at its crossing; one stopped before reaching it
    reaches at the stop (as the kernel path's runs stopped by the warning rule, summaries._summaries)."""
    from stability.study.summaries import run_summaries

    kw = dict(run=RunSpec(model="exact", scheme="adaptive", push_duration=0.1, horizon=10.0))
    reach = run_summaries([POWER_FWD], [1.5], [400.0], level=1.0, **kw)
    assert reach.t_level[0] == pytest.approx(stopped.first_time_abs_yaw_rate(1.0), abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert reach.t_half[0] == pytest.approx(stopped.first_time_abs_yaw_rate(0.5), abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert reach.sim_time[0] == stopped.t[-1] and reach.peak[0] == np.max(np.abs(stopped.yaw_rate))
    never = run_summaries([POWER_FWD], [1.5], [400.0], level=5.0, **kw)   # peak 3.62 rad/s < 5 before the stop
    assert never.peak[0] < 5.0 and never.t_level[0] == stopped.stop_time
    assert never.margin(5.0, 10.0)[0] > 0                                   # counted as reaching


def test_critical_impulse_on_the_adaptive_path_and_its_bracket():
    """The search runs (its first push, 40 N s, is the run above); an independent check of its answer: full
    10 s adaptive runs at the bracket's pushes, the low one never reaching 1 rad/s (nor stopping early), the
    high one reaching it."""
    from stability.study import critical_impulse

    res = critical_impulse(POWER_FWD, 1.5, run=RunSpec(scheme="adaptive"))
    assert res.status == "found" and res.largest_tried_Ns == 40.0
    assert res.high_Ns / res.low_Ns - 1 <= 0.005 * (1 + 1e-9) and res.low_Ns <= res.impulse_Ns <= res.high_Ns
    kw = PUSH.replace(horizon=10.0)
    low = simulate(POWER_FWD, 1.5, kw.replace(push_force=res.low_Ns / 0.1))
    high = simulate(POWER_FWD, 1.5, kw.replace(push_force=res.high_Ns / 0.1))
    assert low.t[-1] == 10.0 and not low.stopped_by_warnings and low.first_time_abs_yaw_rate(1.0) is None
    t_high = high.first_time_abs_yaw_rate(1.0)
    assert t_high is not None and t_high <= 10.0


def test_the_command_line_prints_the_reason_and_exits_0(capsys):
    from stability.simulate.__main__ import main

    rc = main(["--chair", "power-fwd", "--speed", "1.5", "--scheme", "adaptive", "--model", "exact",
               "--push-force", "400", "--push-duration", "0.1", "--no-stop-on-warnings"])
    out = capsys.readouterr().out
    assert rc == 0
    line = next(ln for ln in out.splitlines() if ln.startswith("STOPPED"))
    assert line.startswith("STOPPED at t = 1.010 s: normal loads and tire forces") and FAIL.search(line)
    assert "simulated 0.000 .. 1.010 s" in out


def test_an_unaffected_run_is_unchanged():
    """A run whose loads always converge takes the unchanged path: the same solve_ivp calls and the same sample
    evaluations (checked bit for bit against main before this change on E&J Premier at 0.75 m/s, thesis and
    exact models, the default push, and a Python yaw_moment run); here its regular sample grid and no stop."""
    r = simulate(preset("ej-premier"), 0.75, run=RunSpec(scheme="adaptive", horizon=2.0))
    np.testing.assert_array_equal(r.t, 0.01 * np.arange(201))
    assert not r.stopped_by_warnings and r.stop_time is None and r.stop_reason is None
    assert "stop_reason" in r.to_dict() and "STOPPED" not in r.summary()
