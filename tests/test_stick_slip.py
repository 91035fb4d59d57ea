"""The fixed-step scheme's stick-slip pin friction (``friction_law="stick-slip"``, docs/simulator.md).

Program WCHAIR's law applies the kinetic moment against the swivel rate at
every step, switching with its sign; where a caster mode is fast the rate
chatters about zero and the answers depend on the step (power-fwd's
critical impulse: < 1e-6 N s at 1 and 0.5 ms, 2.1 N s at 0.25 ms, 4.4 N s at
0.125 ms).  The stick-slip law stops a caster whose rate would change sign
within a step and keeps it at rest while the friction limit can hold it.
The independent check is the adaptive scheme, which locates every stick
and slip as a solve_ivp event (stability/simulate/adaptive.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from numerics import assert_signals_close, run_tolerance

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import simulate, simulate_batch
from stability.study import critical_impulse

PUSH = dict(push_force=20.0, push_duration=0.1)     # 2 N s: below the E&J's critical push at 0.75 m/s
RUN = dict(horizon=3.0, sample=0.01, stop_on_warnings=False)


def _yaw(chair, speed, **kw):
    kw.setdefault("friction_law", "kinetic")
    return np.asarray(simulate(chair, speed, RunSpec(**PUSH, **RUN, **kw)).yaw_rate)


def test_without_pin_friction_the_two_laws_are_the_same_run():
    chair = preset("ej-premier").replace(pin_friction_left=0.0, pin_friction_right=0.0)
    a = simulate(chair, 0.75, run=RunSpec(stop_on_warnings=False, friction_law="kinetic"))
    b = simulate(chair, 0.75, run=RunSpec(stop_on_warnings=False, friction_law="stick-slip"))
    assert b.settings["friction_law"] == "stick-slip" and a.settings["friction_law"] == "kinetic"
    np.testing.assert_array_equal(a.yaw_rate, b.yaw_rate)     # no friction: nothing to stick, bit for bit
    np.testing.assert_array_equal(a.eta, b.eta)


def test_stick_slip_converges_at_first_order_to_the_event_located_solution():
    """E&J Premier, 0.75 m/s, 2 N s: the difference from the adaptive scheme halves with the step (measured
    5.6e-4, 2.8e-4, 1.4e-4 rad/s at 1, 0.5, 0.25 ms: the Euler velocity update is first order), while the kinetic
    law at 1 ms is 9.9e-3 rad/s off, 30 % of the 0.033 rad/s peak.  The adaptive run's own error (rtol 1e-6) is
    below 1e-7 rad/s, far under the smallest difference."""
    chair = preset("ej-premier")
    ref = np.asarray(simulate(chair, 0.75, RunSpec(scheme="adaptive", **PUSH, horizon=3.0, sample=0.01)).yaw_rate)
    err = [np.abs(_yaw(chair, 0.75, dt=dt, friction_law="stick-slip") - ref).max() for dt in (1e-3, 5e-4, 2.5e-4)]
    peak = np.abs(ref).max()
    assert err[0] < 0.05 * peak
    for coarse, fine in zip(err[:-1], err[1:], strict=True):
        assert 0.35 < fine / coarse < 0.65, err                # first order: 0.5
    kinetic = np.abs(_yaw(chair, 0.75) - ref).max()
    assert kinetic > 10 * err[0]


def test_stick_slip_is_mirror_symmetric():
    chair = preset("ej-premier")
    right = simulate(chair, 0.75, RunSpec(friction_law="stick-slip", **RUN))
    left = simulate(chair, 0.75, RunSpec(friction_law="stick-slip", **RUN, push_force=-40.0))
    # the left and right casters are solved in the same operations with the roles swapped: equal to rounding,
    # amplified by the unstable mode (growth e^{1.45 x 3} ~ 80) over 3000 steps
    scale = np.abs(right.yaw_rate).max()
    np.testing.assert_allclose(left.yaw_rate, -np.asarray(right.yaw_rate), rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(left.eta, -np.asarray(right.beta), rtol=0, atol=1e-9 * np.abs(right.beta).max())


def test_critical_impulse_is_step_converged_with_stick_slip():
    """power-fwd at 1.5 m/s: 7.82 N s at 1 ms, 7.81 N s at 0.25 ms (the kinetic law: < 1e-6 N s, then 2.1 N s
    at 0.25 ms).  Each answer is a 0.5 % bracket; the step moves it by O(dt) (0.13 % here)."""
    chair = preset("power-fwd")
    coarse = critical_impulse(chair, 1.5, run=RunSpec(friction_law="stick-slip"))
    fine = critical_impulse(chair, 1.5, run=RunSpec(friction_law="stick-slip", dt=2.5e-4))
    assert coarse.status == fine.status == "found"
    assert abs(math.log(coarse.impulse_Ns / fine.impulse_Ns)) < 0.01
    assert 5.0 < coarse.impulse_Ns < 12.0        # a real push (a 4 N s push gives |r| <= 0.02 rad/s, adaptive)
    assert critical_impulse(chair, 1.5, run=RunSpec(friction_law="kinetic")).status == "below"   # at 1 ms any push "suffices"
    assert critical_impulse(chair, 1.5).impulse_Ns == coarse.impulse_Ns     # the measures' default law


def test_critical_impulse_with_stick_slip_equals_the_adaptive_schemes():
    """E&J Premier at 1.0 m/s: 2.53 N s with stick-slip at 1 ms and with the adaptive scheme (the kinetic law at
    1 ms: 2.16 N s, docs/simulator.md).  Two 0.5 % brackets around the same threshold: within 1 %."""
    chair = preset("ej-premier")
    fixed = critical_impulse(chair, 1.0, run=RunSpec(friction_law="stick-slip"))
    adaptive = critical_impulse(chair, 1.0, run=RunSpec(scheme="adaptive"))
    assert abs(math.log(fixed.impulse_Ns / adaptive.impulse_Ns)) < 0.01
    kinetic = critical_impulse(chair, 1.0, run=RunSpec(friction_law="kinetic"))
    assert abs(math.log(kinetic.impulse_Ns / adaptive.impulse_Ns)) > 0.1


@pytest.mark.parametrize("kw,match", [
    (dict(scheme="adaptive", friction_law="kinetic"), "friction_law='kinetic' is invalid for scheme 'adaptive'"),
    (dict(friction_law="sticky"), "friction_law='sticky' is invalid; valid values"),
])
def test_bad_friction_law_is_refused_naming_it(kw, match):
    with pytest.raises(ValueError, match=match):
        simulate(preset("ej-premier"), 0.75, RunSpec(horizon=0.1, **kw))


def _ci(chair, speed, dt):
    run = RunSpec(scheme="adaptive") if dt is None else RunSpec(dt=dt, friction_law="stick-slip")
    return critical_impulse(chair, speed, run).impulse_Ns


def _ei(chair, model, dt):
    from stability.study import equal_instability_speeds

    run = RunSpec(scheme="adaptive", model=model) if dt is None else RunSpec(dt=dt, friction_law="stick-slip",
                                                                            model=model)
    r = equal_instability_speeds([chair], run, progress=False)[0]
    return "above 3" if r.status == "above" else r.speed


# docs/simulator.md, "The stick-slip law": each row's cells (steps in ms; None: the adaptive scheme)
DOC_ROWS = [
    ("E&J Premier, critical impulse at 0.75 m/s (N s)", "{:.3g}", lambda dt: _ci(preset("ej-premier"), 0.75, dt)),
    ("E&J Premier, critical impulse at 1.0 m/s (N s)", "{:.3g}", lambda dt: _ci(preset("ej-premier"), 1.0, dt)),
    ("E&J Premier, critical impulse at 1.2 m/s (N s)", "{:.3g}", lambda dt: _ci(preset("ej-premier"), 1.2, dt)),
    ("power-fwd, critical impulse at 1.5 m/s (N s)", "{:.3g}", lambda dt: _ci(preset("power-fwd"), 1.5, dt)),
    ("power-fwd with a 6 cm trail, critical impulse at 0.75 m/s (N s)", "{:.3g}",
     lambda dt: _ci(preset("power-fwd").replace(trail=0.06), 0.75, dt)),
    ("revised, equal-instability speed (m/s, thesis model)", "{:.4g}", lambda dt: _ei(preset("revised"), "thesis", dt)),
    ("power-fwd, equal-instability speed (m/s, exact model)", "{:.3g}", lambda dt: _ei(preset("power-fwd"), "exact", dt)),
]


def doc_line(row) -> str:
    """The table line of docs/simulator.md for one row, recomputed (stick-slip at 1, 0.5, 0.25 ms; adaptive)."""
    label, fmt, compute = row
    cells = []
    for ms in (1.0, 0.5, 0.25, None):
        v = compute(None if ms is None else ms * 1e-3)
        cells.append(v if isinstance(v, str) else fmt.format(v))
    return " ".join(f"| {label} | {' | '.join(cells)} |".split())


@pytest.mark.slow       # about 10 s: fine steps and the adaptive scheme
@pytest.mark.parametrize("row", DOC_ROWS, ids=[r[0] for r in DOC_ROWS])
def test_docs_stick_slip_table_is_what_the_studies_give(row):
    """Each cell of docs/simulator.md's stick-slip table is recomputed (the searches' 0.5 % brackets are below the
    printed digits except where a value sits on a rounding edge, which a regeneration would show)."""
    from pathlib import Path

    text = (Path(__file__).parents[1] / "docs" / "simulator.md").read_text(encoding="utf-8")
    line = doc_line(row)
    assert line in [" ".join(t.split()) for t in text.splitlines()], line


# ---------------------------------------------------------------------------
# the Python paths (wchair.py's scalar loop, reference.py's numpy batch) against the compiled kernel
# ---------------------------------------------------------------------------
EJ, PF = preset("ej-premier"), preset("power-fwd")
#: (chair, speed m/s, push N for 0.1 s): long stick phases (E&J 0.75 m/s, power-fwd), a spin-out (E&J 1.0 m/s),
#: one caster without pin friction (it never rests); in one batch, each run holds and frees its own casters
CASES = ((EJ, 0.75, 20.0), (EJ, 1.0, 40.0), (PF, 1.0, 40.0), (PF, 1.5, 60.0), (EJ.replace(pin_friction_right=0.0), 1.0,
                                                                              30.0))
SIGNALS = ("x", "y", "heading", "yaw_rate", "v", "eta", "beta", "eta_dot", "beta_dot", "fy", "normal_load",
           "pin_moment", "yaw_acceleration")


def _decision_margins(monkeypatch):
    """Record, in the scalar path, how far each hold/break-away and each rest decision is from its threshold."""
    from stability.simulate import pin_friction, wchair

    hold: list[float] = []      # | |holding moment| - limit | / limit
    rest: list[float] = []      # |rate + acc dt| of a moving caster with friction, rad/s
    held = pin_friction.held_accelerations

    def held_logged(K, state, F, ma, mb, fy_ext, mz, hold_a, hold_b, rdc, grav):
        out = held(K, state, F, ma, mb, fy_ext, mz, hold_a, hold_b, rdc, grav)
        hold.extend(abs(abs(m) - lim) / lim for m, lim, h in ((out[1], K.maf, hold_a), (out[2], K.mbf, hold_b)) if h and lim > 0.0)
        return out

    def rest_logged(rate, acc, dt, limit):
        if rate != 0.0 and limit > 0.0:
            rest.append(abs(rate + acc * dt))
        return pin_friction.rest_rate(rate, acc, dt, limit)

    monkeypatch.setattr(pin_friction, "held_accelerations", held_logged)
    monkeypatch.setattr(wchair, "rest_rate", rest_logged)
    return hold, rest


@pytest.mark.parametrize("model", ["thesis", "exact"])
def test_python_paths_take_the_compiled_kernels_stick_slip_steps(model, monkeypatch):
    """Compiled kernel = numpy batch reference = scalar Python loop, stick-slip, to rounding, 1.5 s.

    Same operations in the same order (kernel.stick_slip / held_pins and the rate update, pin_friction.py);
    they differ in libm against numpy's SIMD cos/sin/atan2 (last bit).  Error model: fixed-step rounding grown by
    the linearisation (tests/numerics.py run_tolerance); a run switches between free and held casters, so the
    larger of the free and the locked chair's bounds: 1.1e-7 to 4.9e-6 of each signal's size here, observed
    <= 2.1e-14 (ratio <= 6e-8).  The law's decisions are discrete: the paths agree only while they take the same
    holds, break-aways and rests, so the test asserts the same rest steps (rate exactly 0.0) on every path and that
    no decision in these runs lies within the tolerance of its threshold (measured: holding moments >= 0.3 % of the
    limit from it, new rates at a rest check >= 3e-4 of the largest rate from zero, against tolerances <= 4.9e-6):
    rounding cannot flip one, so the agreement holds on any CPU.
    """
    from stability.simulate.options import make_options
    from stability.simulate.reference import wchair_batch
    from stability.simulate.wchair import wchair_single

    duration = 1.5
    chairs, speeds, forces = (list(c) for c in zip(*CASES, strict=True))
    run = RunSpec(model=model, horizon=duration, sample=0.001, friction_law="stick-slip", stop_on_warnings=False)
    compiled = simulate_batch(chairs, np.array(speeds), run, push_forces=forces, progress=False)
    batch = wchair_batch(chairs, np.array(speeds), make_options(run, batch=True), False, forces=np.array(forces))
    for i, (chair, speed, force) in enumerate(CASES):
        hold, rest = _decision_margins(monkeypatch)
        single = wchair_single(chair, speed, make_options(run.replace(push_force=force)))
        monkeypatch.undo()
        got = compiled[i]
        assert got.settings["engine"] == "compiled" and single.settings["friction_law"] == "stick-slip"
        # error model: fixed-step rounding, free or held casters (the larger bound)
        tol = max(run_tolerance(chair, speed, duration, model=model, casters=c) for c in ("free", "locked"))
        for ref, what in ((batch[i], "reference batch"), (single, "scalar loop")):
            assert_signals_close(got, ref, SIGNALS, tol, what=f"{what} {model} {i}")
            for rate in ("eta_dot", "beta_dot"):     # the same rest steps
                np.testing.assert_array_equal(getattr(got, rate) == 0.0, getattr(ref, rate) == 0.0)
        at_rest = np.asarray(got.eta_dot) == 0.0
        assert at_rest.sum() > 2 and np.isfinite(got.yaw_rate).all()       # the law acted (beyond t = 0)
        rate_scale = max(np.abs(got.eta_dot).max(), np.abs(got.beta_dot).max())
        assert hold and min(hold) > tol, (i, min(hold))
        assert rest and min(rest) > tol * rate_scale, (i, min(rest) / rate_scale)


def test_python_yaw_moment_with_stick_slip_equals_the_compiled_controller():
    """A Python yaw_moment hook (scalar loop, and a batch through the numpy reference) = the same law as a
    compiled SampledController (Ts = dt), stick-slip; and a zero hook = the compiled run without input.
    Error model as above (free or held casters, 3 s): bounds 3.9e-6 and 1.5e-5 of the signal at 0.75 and 1.0 m/s;
    observed <= 1.2e-14 (ratio <= 3e-9)."""
    from stability.simulate import SampledController

    gains = np.array([0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    ctl = SampledController.state_feedback(gains, 0.001, limit=15.0)

    def hook(t, s):
        return np.clip(-20.0 * s.yaw_rate, -15.0, 15.0)

    kw = dict(run=RunSpec(horizon=3.0, sample=0.01, friction_law="stick-slip", **PUSH))
    speeds = (0.75, 1.0)
    batch = simulate_batch([EJ, EJ], list(speeds), yaw_moment=hook, progress=False, **kw)
    for speed, c in zip(speeds, batch, strict=True):
        tol = max(run_tolerance(EJ, speed, 3.0, model="exact", casters=k) for k in ("free", "locked"))
        a = simulate(EJ, speed, controller=ctl, **kw)
        b = simulate(EJ, speed, yaw_moment=hook, **kw)
        assert a.settings["engine"] == "compiled" and b.settings["engine"] == c.settings["engine"] == "python"
        assert np.any(np.asarray(b.eta_dot) == 0.0) and np.any(np.abs(b.yaw_moment_input) > 0.0)
        for ref in (b, c):
            assert_signals_close(a, ref, ("yaw_rate", "eta_dot", "pin_moment", "yaw_moment_input"), tol,
                                 what=f"controller {speed}")
        free = simulate(EJ, speed, **kw)
        zero = simulate(EJ, speed, yaw_moment=lambda t, s: 0.0, **kw)
        assert zero.settings["friction_law"] == "stick-slip"
        assert_signals_close(free, zero, ("yaw_rate", "eta", "eta_dot", "beta_dot", "pin_moment"), tol,
                             what=f"zero yaw moment {speed}")


def test_reference_engine_critical_impulse_with_stick_slip():
    """Inside reference_engine() (the benchmarks' baseline) the search runs the numpy reference with the same law:
    E&J Premier at 0.75 m/s, the compiled answer to the search's 0.5 % bracket, which holds the threshold."""
    from stability.simulate import reference_engine

    compiled = critical_impulse(EJ, 0.75, run=RunSpec(friction_law="stick-slip"))
    with reference_engine():
        ref = critical_impulse(EJ, 0.75, run=RunSpec(friction_law="stick-slip"))
    assert compiled.status == ref.status == "found"
    # the threshold measured on a 0.1 % grid (docs/studies.md): misses at 3.253 N s, reaches at 3.257 N s; another
    # CPU's rounding may move a stick/slip decision near the threshold, so the band is widened by that grid's 0.1 %
    assert compiled.low_Ns <= 3.257 * 1.001 and compiled.high_Ns >= 3.253 / 1.001
    assert abs(math.log(ref.impulse_Ns / compiled.impulse_Ns)) < 0.005


def _problems():
    """(chair, speed) pairs of the settle-stop check: the presets around the thesis's speeds and a few designs."""
    ej = preset("ej-premier")
    pairs = [(preset(n), v) for n in ("ej-premier", "revised", "power-fwd") for v in (0.5, 0.75, 1.0, 1.5)]
    pairs += [(ej.replace(trail=tr, pin_friction_left=f, pin_friction_right=f), 0.9)
              for tr in (0.04, 0.06) for f in (0.05, 0.2)]
    return pairs


def test_settled_runs_stop_early_and_change_no_answer(monkeypatch):
    """A search run with both casters stuck for 0.5 s, after the push, with neither |yaw rate| nor a holding moment
    growing, stops there (kernel.settled).  Every critical impulse is the same with and without that stop (the
    runs below the threshold settle into a steady coast or turn; the equality is exact because the same runs are
    made, only shorter: 249 sweep problems measured, 45.6 -> 22.1 s simulated per answer, docs/scale.md)."""
    from stability.simulate import engine
    from stability.study import critical_impulses

    chairs, speeds = zip(*_problems(), strict=True)
    monkeypatch.setattr(engine, "SETTLE_STOP", False)
    full = critical_impulses(list(chairs), list(speeds))
    monkeypatch.setattr(engine, "SETTLE_STOP", True)
    short = critical_impulses(list(chairs), list(speeds))
    assert [(r.status, r.low_Ns, r.high_Ns) for r in short] == [(r.status, r.low_Ns, r.high_Ns) for r in full]
    assert sum(r.status == "found" for r in short) >= 12


def test_a_settled_run_never_reaches_the_level():
    """Independently of the stop: the E&J Premier at 0.75 m/s pushed just below its critical impulse (3.2 vs 3.25
    N s) has both casters stuck from 0.64 s and turns steadily at 0.060 rad/s to the end of the 10 s horizon,
    its holding moments (0.098 and 0.094 N m) inside the 0.1 N m limit; the search's run of that push stops
    settled before 2 s."""
    from stability.study.summaries import SummaryRunner

    chair = preset("ej-premier")
    r = simulate(chair, 0.75, run=RunSpec(friction_law="stick-slip", push_force=3.2 / 0.101, push_duration=0.1, horizon=10.0, stop_on_warnings=False))
    y = np.abs(np.asarray(r.yaw_rate))
    assert y.max() < 0.1 and abs(y[-1] - y[len(y) // 2]) < 1e-3
    stuck = (np.asarray(r.eta_dot) == 0.0) & (np.asarray(r.beta_dot) == 0.0)
    assert stuck[np.asarray(r.t) > 1.0].all()
    assert np.abs(np.asarray(r.pin_moment))[np.asarray(r.t) > 1.0].max() < chair.pin_friction_left
    runner = SummaryRunner([chair], [0.75], RunSpec(model="exact", push_duration=0.1, dt=0.001, horizon=10.0,
                                                    friction_law="stick-slip", stop_on_warnings=False), level=1.0)
    s = runner([0], [3.2 / 0.101])
    assert not np.isfinite(s.t_level[0]) and s.sim_time[0] < 2.0
