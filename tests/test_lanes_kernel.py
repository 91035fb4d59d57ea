"""The lanes kernel (runs as SIMD lanes) against the scalar kernel, and its independence of the block and the batch.

Error model of the comparison: the two kernels execute the same operations (the scalar kernel's helpers and the
generated physics, compiled again) except the sine and cosine of the caster angles and the heading and the slip
angles' arctangent, which the lanes kernel takes from :mod:`stability.simulate.lanemath` (within
``SIN_COS_ULP`` and ``ATAN2_ULP`` units in the last place of libm's exact values; tests/test_lanemath.py).  Each
step therefore perturbs the state by at most ``(SIN_COS_ULP + ATAN2_ULP + 2) eps`` relative (libm's own 1 ulp on
each side), and in a run that neither grows (below its critical speed or push) nor crosses a discontinuity of the
step (a warning count, the rest rule's sign test, a stick condition within rounding of its limit) the perturbations
add at most linearly: after ``n`` steps a column differs by at most ``n (SIN_COS_ULP + ATAN2_ULP + 2) eps`` times
its largest magnitude.  That bound is the tolerance (``_bound``); observed over 3 s: 1/20 (thesis model) to 1/600
of it (the rounding errors do not all add with one sign).  On a slope the heading's sine and cosine enter the
gravity terms, whose size is not the columns' own: the bound does not apply there (observed 0.55 of it after
0.1 s), and the slope runs are checked by tests/test_simulate_slope.py's invariants instead, on the lanes kernel.  A spinning-out run amplifies any perturbation exponentially, as it
does a change of compiler; such runs are compared by the quantity they are used for (the critical impulse, below).
"""

import dataclasses

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import engine, kernel_choice, lanemath, simulate, simulate_batch

# The lanes kernel is opt-in (STABILITY_KERNEL=lanes): its first compile costs about 25 s of CPU, more than any
# other module of the default suite with an empty numba cache, so its tests run in CI's slow step.
pytestmark = pytest.mark.slow

#: the recorded quantities of a result
FIELDS = ("x", "y", "heading", "yaw_rate", "u", "v", "eta", "eta_dot", "beta", "beta_dot", "fx", "fy", "normal_load",
          "slip_deg", "tire_yaw_moment", "yaw_moment_input", "yaw_acceleration", "pin_moment")
EPS = np.finfo(float).eps
#: relative perturbation per step (lanes against scalar): both polynomial bounds and libm's own ulp on each side
PER_STEP = (lanemath.SIN_COS_ULP + lanemath.ATAN2_ULP + 2.0) * EPS

EJ = preset("ej-premier")
CASES = {
    "ej stick-slip, 2 N s push at 0.75 m/s": (EJ, 0.75, RunSpec(push_force=20.0, push_duration=0.1)),
    "ej kinetic (WCHAIR), 0.5 m/s, 1 N s": (EJ, 0.5, RunSpec(friction_law="kinetic", push_force=10.0,
                                                           push_duration=0.1)),
    "ej thesis model, kinetic, 0.9 m/s": (EJ, 0.9, RunSpec(model="thesis", friction_law="kinetic",
                                                         push_force=5.0, push_duration=0.1)),
    "ej locked casters, 1.0 m/s": (EJ, 1.0, RunSpec(casters="locked", push_force=40.0, push_duration=0.1)),
    "power-fwd stick-slip, 1.2 m/s": (preset("power-fwd"), 1.2, RunSpec(push_force=30.0, push_duration=0.1)),
    "revised thesis, 1.0 m/s": (preset("revised"), 1.0, RunSpec(model="thesis", push_force=20.0, push_duration=0.1)),
    "front-caster, 0.6 m/s": (preset("ej-premier-front-caster"), 0.6, RunSpec(push_force=10.0, push_duration=0.1)),
    "ej toe, camber, rolling resistance": (dataclasses.replace(EJ, toe_deg=0.5, camber_deg=2.0,
                                                               main_rolling_scale=1.0, caster_rolling_scale=1.0),
                                           0.75, RunSpec(push_force=10.0, push_duration=0.1)),
}


@pytest.fixture(autouse=True)
def _lanes_kernel():
    """Every run of this module on the lanes kernel (the scalar kernel is the default) unless a block says
    ``use_kernel("scalar")``."""
    with engine.use_kernel("lanes"):
        yield


def _both(chair, speed, run, **kw):
    lanes = simulate_batch(chair, [speed], run=run, progress=False, **kw)[0]
    with engine.use_kernel("scalar"):
        scalar = simulate_batch(chair, [speed], run=run, progress=False, **kw)[0]
    return lanes, scalar


def _bound(n_steps, col):
    """The linear accumulation bound of the module docstring for a column."""
    return n_steps * PER_STEP * max(float(np.nanmax(np.abs(col))), 1e-300)


@pytest.mark.parametrize("case", list(CASES))
def test_lanes_equal_the_scalar_kernel_within_the_rounding_bound(case):
    chair, speed, run = CASES[case]
    run = dataclasses.replace(run, horizon=min(run.horizon, 3.0))
    lanes, scalar = _both(chair, speed, run)
    assert lanes.t.shape == scalar.t.shape
    assert lanes.warnings == scalar.warnings
    assert lanes.stopped_by_warnings == scalar.stopped_by_warnings and lanes.stop_time == scalar.stop_time
    n = len(lanes.t)
    worst = 0.0
    for name in FIELDS:
        a, b = np.asarray(getattr(lanes, name), float), np.asarray(getattr(scalar, name), float)
        if a.ndim == 1:
            a, b = a[:, None], b[:, None]
        for j in range(a.shape[1]):
            diff = float(np.nanmax(np.abs(a[:, j] - b[:, j])))
            bound = _bound(n, b[:, j])
            assert diff <= bound, (name, j, diff, bound)
            worst = max(worst, diff / bound)
    # error model: the module docstring's rounding bound, n (SIN_COS_ULP + ATAN2_ULP + 2) eps of the column
    # (observed 1.4e-14 relative)
    assert lanes.stats.peak_abs_yaw_rate == pytest.approx(scalar.stats.peak_abs_yaw_rate,
                                                          abs=_bound(n, scalar.yaw_rate))


@pytest.mark.parametrize("casters", ["free", "locked"])
def test_a_run_is_the_same_in_any_block_and_batch(monkeypatch, casters):
    """Bit for bit: alone, at several places of a 70-run batch, with blocks of 1, 8 and 64 lanes (a block of 1
    solves its held casters lane by lane, larger ones vectorised: the same arithmetic)."""
    speeds = np.linspace(0.4, 1.3, 70)
    forces = np.where(np.arange(70) % 3 == 0, 30.0, 10.0)
    run = RunSpec(horizon=2.0, push_duration=0.1, casters=casters)
    ref = simulate_batch(EJ, speeds, run=run, push_forces=forces, progress=False, record="states")
    for block in (1, 8, 64):
        monkeypatch.setattr(kernel_choice, "lane_block", lambda n, t, b=block: min(b, n))
        got = simulate_batch(EJ, speeds, run=run, push_forces=forces, progress=False, record="states")
        for r, g in zip(ref, got, strict=True):
            np.testing.assert_array_equal(r.yaw_rate, g.yaw_rate)
            np.testing.assert_array_equal(r.eta, g.eta)
            assert r.stats == g.stats
    monkeypatch.undo()
    for i in (0, 37, 69):
        alone = simulate(EJ, float(speeds[i]), run=dataclasses.replace(run, push_force=float(forces[i])))
        stride = (len(alone.t) - 1) // (len(ref[i].t) - 1)
        np.testing.assert_array_equal(alone.yaw_rate[::stride], ref[i].yaw_rate)
        np.testing.assert_array_equal(alone.x[::stride], ref[i].x)


def test_a_run_is_the_same_beside_a_cambered_run():
    """Bit for bit: a block none of whose runs has camber gives MECHAN a zero camber table (never looked up where
    the camber angle is zero), a block with one cambered run every lane's own; an uncambered run is the same in
    either, and a cambered run the same in a block of cambered runs only."""
    cambered = dataclasses.replace(EJ, camber_deg=2.0)
    speeds = np.linspace(0.4, 1.3, 16)
    run = RunSpec(horizon=1.0, push_force=20.0, push_duration=0.1)
    plain = simulate_batch(EJ, speeds, run=run, progress=False, record="states")
    tilted = simulate_batch(cambered, speeds, run=run, progress=False, record="states")
    mixed = simulate_batch([EJ, cambered] * 8, speeds, run=run, progress=False, record="states")
    for i, m in enumerate(mixed):
        ref = (plain if i % 2 == 0 else tilted)[i]
        for name in ("yaw_rate", "eta", "fy"):
            np.testing.assert_array_equal(np.asarray(getattr(ref, name)), np.asarray(getattr(m, name)))
        assert ref.stats == m.stats
    assert not np.array_equal(np.asarray(plain[1].fy), np.asarray(tilted[1].fy))     # the camber force acts


def test_final_record_and_summaries_equal_the_full_record():
    """record="final" (kept in the block, written at the end) is the last row of record="all", bit for bit."""
    speeds = np.array([0.5, 0.9, 1.4])
    run = RunSpec(horizon=4.0, push_force=40.0, push_duration=0.1, sample=0.001)
    full = simulate_batch(EJ, speeds, run=run, progress=False, record="all")
    final = simulate_batch(EJ, speeds, run=run, progress=False, record="final")
    for a, b in zip(full, final, strict=True):
        for name in FIELDS:
            np.testing.assert_array_equal(np.asarray(getattr(a, name))[-1], np.asarray(getattr(b, name))[0])
        assert a.stats == b.stats


@pytest.mark.slow
def test_critical_impulse_is_the_same_with_either_kernel():
    """The quantity the spinning-out runs serve: the critical impulse (E&J, 0.75 and 1.0 m/s; docs/simulator.md:
    3.25 and 2.53 N s with stick-slip friction, regression values of this code, not the thesis's) agrees between
    the kernels within the search's 0.5 % bracket."""
    from stability.study.impulse import critical_impulse

    for speed, docs in ((0.75, 3.25), (1.0, 2.53)):
        lanes = critical_impulse(EJ, speed)
        with engine.use_kernel("scalar"):
            scalar = critical_impulse(EJ, speed)
        assert lanes.status == scalar.status == "found"
        a, b = lanes.impulse_Ns, scalar.impulse_Ns
        # error model: bisection bracket: rounding-level differences of the kernels can flip a run near the
        # threshold, moving the answer by up to the search's 0.5 % bracket (observed 2.7e-16)
        assert a == pytest.approx(b, rel=0.005)
        # error model: rounding of the docs' 2 decimals (0.15-0.2 %) plus the search's 0.5 % bracket (observed 0.22 %)
        assert a == pytest.approx(docs, rel=0.01)


def test_the_lanes_kernels_load_is_watched_where_it_is_found(first_use_watches):
    """The lanes kernel's specialisation for the runs' model is loaded where it is found (lanes_kernel._entry), under
    the same notice as the scalar kernel's, and the launch itself is not watched."""
    assert first_use_watches("lanes") == [("kernel", "wchair")]


def test_one_block_runs_without_the_parallel_entry(monkeypatch):
    """One block runs through the serial entry, so a first run does not compile the parallel one; three blocks on
    two threads run through the parallel entry; both call the block at the same address, and a run is the same,
    bit for bit, alone or in a batch (the block's arithmetic does not depend on the entry)."""
    from stability.simulate import lanes_kernel

    monkeypatch.setattr(lanes_kernel, "_ENTRIES", {})
    run = RunSpec(horizon=0.2, push_force=40.0, push_duration=0.1)
    alone = simulate_batch(EJ, [0.75], run=run, progress=False)[0]
    assert [k[0] for k in lanes_kernel._ENTRIES] == [True]
    speeds = np.array([0.5, 0.75] * 9)          # 18 runs: blocks of 8 on two threads (lane_block), three blocks
    many = simulate_batch(EJ, speeds, run=run, progress=False, workers=2)
    assert sorted(k[0] for k in lanes_kernel._ENTRIES) == ([False, True] if lanes_kernel.get_num_threads() > 1
                                                           else [True])
    assert len({step for (model, _), step in lanes_kernel._STEPS.items() if model == 1}) == 1
    np.testing.assert_array_equal(np.asarray(alone.yaw_rate), np.asarray(many[1].yaw_rate))


@pytest.mark.parametrize(("record", "sample"), [("final", None), ("states", None), ("all", 0.25)])
def test_a_block_whose_runs_stop_apart_steps_its_running_runs_only(monkeypatch, record, sample):
    """Bit for bit: 64 runs in random speed order in one block, where runs stop at different times (spin-outs at the
    level, warnings, settled casters) and the block moves its running lanes to its first columns once a vector's
    worth has stopped (lanes_kernel._compact), against each run in a block of its own (which never moves a lane);
    summaries, stop times and the recorded rows alike (a coarse sample: a moved lane may stop before it records
    again, so its count of rows must move with it)."""
    from stability.simulate import lanes_kernel

    speeds = np.random.default_rng(36).permutation(np.linspace(0.3, 1.5, 64))
    run = RunSpec(horizon=6.0, sample=sample)
    monkeypatch.setattr(kernel_choice, "lane_block", lambda n, t: min(64, n))
    block = simulate_batch(EJ, speeds, run=run, progress=False, record=record, workers=1)
    monkeypatch.setattr(kernel_choice, "lane_block", lambda n, t: 1)
    alone = simulate_batch(EJ, speeds, run=run, progress=False, record=record, workers=1)
    stops = sorted(r.stop_time for r in alone if r.stop_time is not None)
    # the case exercises the move twice: two vectors' worth stop at least a second (1,000 steps) before the
    # horizon, to which a vector's worth of runs go on
    assert len(stops) >= 2 * lanes_kernel.COMPACT_AFTER and stops[2 * lanes_kernel.COMPACT_AFTER - 1] < run.horizon - 1.0
    assert sum(r.stop_time is None for r in alone) >= lanes_kernel.COMPACT_AFTER
    for a, b in zip(alone, block, strict=True):
        assert a.stop_time == b.stop_time and a.stats == b.stats and a.warnings == b.warnings
        for name in ("t", "x", "heading", "yaw_rate", "eta", "beta_dot", "fy", "tire_yaw_moment", "pin_moment"):
            np.testing.assert_array_equal(np.asarray(getattr(a, name)), np.asarray(getattr(b, name)))


def test_moved_lanes_under_a_python_yaw_moment():
    """A Python yaw-moment input steps the block one call per step (each call loads and writes back every run);
    a block whose lanes stopped apart moves them in every call, and each run is still the same, bit for bit, as
    in a block of its own."""
    speeds = np.random.default_rng(36).permutation(np.linspace(0.3, 1.5, 64))
    run = RunSpec(horizon=4.5)

    def yaw_moment(t, s):
        return 0.5 * np.sin(3.0 * t) * np.ones_like(s.yaw_rate)      # N m, the same on every run

    kw = dict(run=run, progress=False, record="states", yaw_moment=yaw_moment)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(kernel_choice, "lane_block", lambda n, t: min(64, n))
        block = simulate_batch(EJ, speeds, **kw)
        mp.setattr(kernel_choice, "lane_block", lambda n, t: 1)
        alone = simulate_batch(EJ, speeds, **kw)
    from stability.simulate import lanes_kernel

    assert sum(r.stop_time is not None and r.stop_time < run.horizon - 0.5 for r in alone) >= \
        lanes_kernel.COMPACT_AFTER
    for a, b in zip(alone, block, strict=True):
        assert a.stop_time == b.stop_time and a.stats == b.stats
        for name in ("t", "x", "yaw_rate", "eta", "beta_dot"):
            np.testing.assert_array_equal(np.asarray(getattr(a, name)), np.asarray(getattr(b, name)))
