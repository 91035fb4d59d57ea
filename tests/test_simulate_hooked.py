"""A Python yaw-moment input on a compiled batch whose runs stop at different times (stability.simulate.hooked)."""

from __future__ import annotations

import dataclasses

import numpy as np

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import simulate_batch

EJ = preset("ej-premier")
SPEC = RunSpec(horizon=2.0, stop_on_warnings=True, model="thesis", friction_law="kinetic")
SPEEDS, PUSHES = [0.3, 3.0, 1.0], [50.0, 600.0, 150.0]     # m/s, N: the warning rule stops each at its own time


def _destabilising(seen: list) -> object:
    """A yaw moment that feeds the yaw rate back with the wrong sign (N m), recording what it is handed."""

    def hook(t, s):
        seen.append((t, np.array(s.run)))
        return 40.0 * s.yaw_rate + 5.0
    return hook


def test_runs_stopping_at_different_times_leave_the_others_as_they_run_alone():
    """The kernel steps each run on its own state and the hook acts on each run's own state, so every run of a
    batch is, bit for bit, the same run alone in a batch; the hook is handed, at time t, exactly the runs not stopped
    before t (a run's stop time is that of the step that stopped it: it is handed that step's state).  The three runs
    stop at three different times, so the runs still going change twice."""
    seen: list = []
    runs = simulate_batch(EJ, SPEEDS, SPEC, yaw_moment=_destabilising(seen), progress=False, push_forces=PUSHES)
    stops = [r.stop_time for r in runs]
    assert all(r.stopped_by_warnings for r in runs) and len(set(stops)) == 3
    for i, (u, f) in enumerate(zip(SPEEDS, PUSHES, strict=True)):
        (alone,) = simulate_batch(EJ, [u], SPEC, yaw_moment=_destabilising([]), progress=False, push_forces=[f])
        for field in dataclasses.fields(alone):
            a, b = getattr(alone, field.name), getattr(runs[i], field.name)
            if isinstance(a, np.ndarray):
                assert np.array_equal(a, b, equal_nan=True), (i, field.name)
        assert alone.stop_time == runs[i].stop_time and alone.warnings == runs[i].warnings
    dt = SPEC.dt
    for t, going in seen:
        expected = [i for i, s in enumerate(stops) if t <= s + 0.5 * dt]    # half a step: the times' rounding
        assert going.tolist() == expected, t
    assert seen[-1][0] == max(stops)


def test_a_hooked_run_finds_the_kernels_specialisation_once(monkeypatch):
    """The step-by-step loop resolves the scalar kernel's specialisation through ``kernel.call_model`` at the first
    step only and calls it directly after (the per-step cost the loop was rid of); a change to call_model's memo
    would silently fall back to one call_model per step, which this counts.  The run's numbers do not depend on it
    (the first test)."""
    from stability.simulate import kernel

    calls = []
    real = kernel.call_model

    def counted(entry, var, *args):
        calls.append(entry)
        return real(entry, var, *args)

    monkeypatch.setattr(kernel, "call_model", counted)
    (run,) = simulate_batch(EJ, [1.0], RunSpec(horizon=0.05, model="thesis", friction_law="kinetic"),
                            yaw_moment=lambda t, s: 0.0, progress=False)
    assert len(run.t) == 6 and calls == [kernel.run_serial]     # 0.05 s recorded every 0.01 s (a batch)
