"""The single sensor faults of the assist on wheel layouts and in reverse, and the recovery criterion (issue 38).

Independent statements used:

- the power chair (``power-fwd``) expanded as a layout (:meth:`stability.layout.Layout.from_chair`) is the short
  form's chair: its fault runs (another derivation of the plant and its firmware tables, another simulator: the
  layout kernel stepped with the firmware hook against the thesis engine's) give the short form's fault rows;
- stepping the layout kernel one step at a time from its saved state is the uninterrupted kernel (the same
  arithmetic: bit for bit);
- closed forms of settling: ``c + A exp(-t / tau)`` settles about ``c`` at ``tau ln(1 / 0.05)``; a heading that
  drifts at a constant rate has no final value;
- a chair that is stable without the assist recovers with no torque at all (0 N m); a torque limit above the
  peak torque of the unsaturated recovery never binds, so the smallest recovering limit is at most that peak.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from slow_cases import one_default

from stability.assist.__main__ import main
from stability.assist.faults import FAULTS, fault_runs
from stability.assist.layout import layout_design, layout_schedule
from stability.assist.layout_checks import layout_minimum_torque_limit, layout_recovery
from stability.assist.recovery import STRONG_FORCE
from stability.assist.schedule import schedule
from stability.assist.settling import SETTLE_FRACTION, settle_time, settled_value
from stability.chair import preset
from stability.chair.power import DriveTrain
from stability.layout import Layout
from stability.layout.presets import layout_preset
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate.controller import SampledController
from stability.simulate.layout import layout_state_order, simulate_layout
from stability.simulate.layout_batch import simulate_layout_batch
from stability.study.layout_impulse import trailing_angles


def test_the_power_chair_as_a_layout_gives_the_short_forms_fault_rows():
    """Every fault at 1 and 2 m/s on level ground and the 2 deg cross slope: the same detections (to the sample),
    outcomes, and peaks.  Error model: the two derivations' firmware tables agree to 1e-11 (relative,
    test_assist_layout_options) and the simulators to rounding on level ground and to 4e-7 rad/s of yaw rate on
    the slope (stick-slip pins decided on rounded moments); through the closed loop the assisted rows agree to
    6e-13 deg, 2e-11 deg/s and 2e-14 m (observed), asserted 1e-8 deg, 1e-8 deg/s and 1e-8 m.  The unassisted
    reference spins out on the slope (260-340 deg), amplifying the slope difference to 6e-3 deg: asserted on level
    ground only, to 1e-8."""
    c = preset("power-fwd")
    short = fault_runs(schedule(c, [1.0, 2.0], standstill=False))
    mine = fault_runs(layout_schedule(Layout.from_chair(c), [1.0, 2.0]))
    assert len(mine) == len(short) == 2 * 2 * len(FAULTS)
    for a, b in zip(short, mine, strict=True):
        assert (a.fault, a.speed_m_s, a.slope_deg, a.detected, a.outcome) == \
            (b.fault, b.speed_m_s, b.slope_deg, b.detected, b.outcome)
        assert (a.detection_time_s is None) == (b.detection_time_s is None)
        if a.detected:
            assert b.detection_time_s == pytest.approx(a.detection_time_s, abs=1e-12)   # whole samples: rounding
        # error model (docstring): two derivations' and two simulators' rounding through the closed loop, observed
        # 6e-13 deg, 2e-11 deg/s, 2e-14 m; the unassisted reference on level ground only (the slope's spin-out
        # amplifies the simulators' slope difference)
        assert b.peak_heading_error_deg == pytest.approx(a.peak_heading_error_deg, abs=1e-8)
        assert b.peak_yaw_rate_deg_s == pytest.approx(a.peak_yaw_rate_deg_s, abs=1e-8)
        assert b.drift_m == pytest.approx(a.drift_m, abs=1e-8)
        if a.slope_deg == 0.0:
            assert b.unassisted_heading_error_deg == pytest.approx(a.unassisted_heading_error_deg, abs=1e-8)
            assert b.unassisted_drift_m == pytest.approx(a.unassisted_drift_m, abs=1e-8)


def test_stepping_the_layout_kernel_with_a_python_moment_is_the_uninterrupted_kernel():
    """A constant yaw moment through the motor lag, forward and in reverse on a cross slope: the kernel run once
    with a compiled controller of constant output (no measurement, an offset) and the batch stepped one step at a
    time with a Python hook returning the same moment give the same rows, bit for bit (the same arithmetic on the
    saved state)."""
    lay = layout_preset("mid-wheel-drive")
    spec = RunSpec(horizon=1.5, stop_on_warnings=False, cross_slope_deg=2.0, sample=0.001)
    moment, lag = 12.5, 0.02
    const = SampledController(0.005, np.zeros((1, len(layout_state_order(lay)))), np.array([1.0]),
                              offset=np.array([moment]), state_names=layout_state_order(lay))
    speeds = [1.5, -1.0]
    angles = [trailing_angles(lay, u) for u in speeds]
    batch = simulate_layout_batch(lay, speeds, spec, yaw_moment=lambda t, s: np.full(len(s.run), moment),
                                  caster_angles_deg=angles, motor_lag_s=lag)
    for u, a, b in zip(speeds, angles, batch, strict=True):
        one = simulate_layout(lay, u, spec, caster_angles_deg=a, controller=const, motor_lag_s=lag)
        for name in ("t_s", "heading_rad", "yaw_rate_rad_s", "x_m", "y_m", "u_m_s", "v_m_s", "caster_angle_rad"):
            assert np.array_equal(getattr(one, name), getattr(b, name)), name
        assert b.speed_m_s == u and b.ended == "horizon"


def test_a_run_that_ends_early_leaves_the_others_of_its_batch_as_they_run_alone():
    """A batch's runs are independent: the middle one of three, pushed by a growing moment on a cross slope,
    stops at its eleventh load warning; the hook then sees the other two alone (``state.run`` 0 and 2) and each
    run, the stopped one too, is the run simulated in a batch of one, bit for bit (the same arithmetic per run:
    the hook's moment is elementwise in the run's own state)."""
    lay = layout_preset("mid-wheel-drive")
    spec = RunSpec(horizon=2.0, stop_on_warnings=True, cross_slope_deg=3.0, sample=0.002)
    speeds = [1.0, 3.0, -1.5]
    seen = []

    def hook(t, s):
        seen.append(tuple(int(i) for i in s.run))
        return np.where(np.abs(s.u) > 2.0, 400.0 * t, 0.0) + 3.0 * s.yaw_rate - 0.01 * s.delta.sum(axis=0)

    angles = [trailing_angles(lay, u) for u in speeds]
    batch = simulate_layout_batch(lay, speeds, spec, yaw_moment=hook, caster_angles_deg=angles, motor_lag_s=0.02)
    assert [r.ended for r in batch] == ["horizon", "load warnings", "horizon"]
    assert sorted(set(seen)) == [(0, 1, 2), (0, 2)] and seen[-1] == (0, 2)
    for u, a, b in zip(speeds, angles, batch, strict=True):
        (one,) = simulate_layout_batch(lay, [u], spec, yaw_moment=hook, caster_angles_deg=[a], motor_lag_s=0.02)
        for name in ("t_s", "heading_rad", "yaw_rate_rad_s", "x_m", "y_m", "u_m_s", "v_m_s", "caster_angle_rad",
                     "caster_rate_rad_s", "yaw_moment_N_m"):
            assert np.array_equal(getattr(one, name), getattr(b, name)), (u, name)
        assert (one.ended, one.end_time_s) == (b.ended, b.end_time_s)


def test_settling_is_about_the_final_value():
    """``2 + 3 exp(-t / 0.5)`` over 10 s settles about 2 at ``0.5 ln(1 / 0.05)`` (to the 1 ms sample, plus the
    final mean's offset from 2, 3 exp(-16) ~ 3e-7); a constant drift of 1 deg/s over 10 s never settles (it departs
    from its final mean by 1 deg within the last 2 s, the band being 5 % of 9 deg); a response already at its
    final value settles at 0."""
    t = np.linspace(0.0, 10.0, 10001)
    y = 2.0 + 3.0 * np.exp(-t / 0.5)
    want = 0.5 * math.log(1.0 / SETTLE_FRACTION)
    assert settle_time(t, y) == pytest.approx(want, abs=2e-3)       # one sample (1 ms) plus rounding, margin 2
    assert settled_value(t, y) == pytest.approx(2.0, abs=1e-6)      # error model: the tail mean is 3e-8 off 2
    assert settle_time(t, 1.0 * t) is None and settled_value(t, 1.0 * t) is None
    assert settle_time(t, np.full_like(t, 0.7)) == 0.0


def test_a_chair_stable_without_the_assist_recovers_with_no_torque():
    """The mid-wheel-drive base forwards at 1 m/s is stable unassisted (open-loop growth rate < 0): after the
    reference push it settles on a new heading within 10 deg, so the smallest torque limit is 0 exactly."""
    lay = layout_preset("mid-wheel-drive")
    d = layout_design(lay, 1.0, "gyro")
    assert np.linalg.eigvals(d.plant.A6).real.max() < 0
    assert layout_minimum_torque_limit(lay, d, DriveTrain(), impulse_force=THESIS_PUSH.force) == 0.0


def test_the_mid_wheel_drive_base_in_reverse_recovers_within_its_unsaturated_peak():
    """The mid-wheel-drive base at 1 m/s in reverse (unstable unassisted) after the strong push: the assisted
    heading settles on a new constant heading (not zero: the controller holds the running sum of the sampled
    gyro), so a finite smallest limit is found, at most the unsaturated run's peak torque per wheel plus one
    bisection bracket (0.25 N m), and above 0 (unassisted it does not recover)."""
    lay = layout_preset("mid-wheel-drive")
    drive = DriveTrain()
    d = layout_design(lay, -1.0, "gyro", drive=drive)
    rec = layout_recovery(lay, d, drive, push=STRONG_FORCE)
    assert rec.saturated_fraction == 0.0 and abs(rec.final_heading_deg) > 0.05
    least = layout_minimum_torque_limit(lay, d, drive)
    assert 0.0 < least <= rec.peak_torque_N_m + 0.25


def test_the_command_counts_the_faults_in_a_layouts_top_speed(tmp_path, capsys):
    """--faults on a layout in reverse: the JSON's fault rows (validated against the schema) set the safe top
    speed: the highest design speed with every fault safe there and below (counted here from the rows); the PDF
    (with its fault panel) is written."""
    from stability import schemas

    js, pdf = tmp_path / "a.json", tmp_path / "a.pdf"
    assert main(["--chair", "power-fwd-base", "--speeds=-2,-2.25,-2.5", "--no-check", "--faults",
                 "--json-file", str(js), "-o", str(pdf)]) == 0
    out = capsys.readouterr().out
    assert pdf.read_bytes().startswith(b"%PDF")
    assert "reverse, Single sensor faults" in out and "from the margins and the single sensor faults" in out
    data = json.loads(js.read_text())
    schemas.validate("assist_layout", data)
    rows = data["reverse_faults"]
    assert data["forward_faults"] is None and data["options"]["faults"] is True
    assert len(rows) == 3 * 2 * len(FAULTS) and {r["speed_m_s"] for r in rows} == {-2.0, -2.25, -2.5}
    top = data["reverse_top_speed"]
    assert "faults" in top["constraints_checked"]
    safe = None
    for u in (2.0, 2.25, 2.5):
        if any(r["outcome"] != "safe" for r in rows if abs(r["speed_m_s"]) == u):
            break
        safe = u
    margins_ok = all(c["gain_margin_db"]["ok"] and c["phase_margin_deg"]["ok"] and c["delay_margin_ms"]["ok"]
                     for c in top["checks"])
    if margins_ok:
        assert top["safe_top_speed_m_s"] == safe
    for c in top["checks"]:
        bad = sum(1 for r in rows if abs(r["speed_m_s"]) == c["speed_m_s"] and r["outcome"] != "safe")
        assert c["unsafe_fault_count"]["value"] == bad


@pytest.mark.parametrize("name", one_default(["power-fwd-base", "mid-wheel-drive", "power-rwd-base"], "mid-wheel-drive"))
def test_a_gyro_bias_turns_every_layout_by_the_bias_estimators_closed_form(name):
    """A 1 deg/s gyro bias from the fault time, below the monitor's threshold (not detected), noise-free gyro, pins
    without friction, forward and in reverse: the firmware's bias estimate learns it from the wheel speeds exactly,
    ``b_k = b (1 - (1 - g_b)^k)`` (the wheel-speed yaw rate is the chair's), and the integral action drives the
    running sum of the corrected gyro back to zero, so the chair turns by ``-T sum_k (b - b_k) = -b T (1 - (1 -
    g_b)^N) / g_b`` over the N samples of the window, whatever the layout (-0.996 deg).  Error model (a derived
    bound, not a fitted one): the sum counts the rate at the samples while the heading integrates it (at most
    ``b T`` for a rate that changes sign at most once) plus the one sample of computation delay (``b T``):
    ``2 b T`` = 0.01 deg; observed 0.0046-0.0051 deg.  With Coulomb pin friction the stuck casters' holding moment
    leaves the heading within the friction's band instead (0.07 deg for the two unstable directions)."""
    import dataclasses

    from stability.assist.commands import COMMAND_FILTER
    from stability.assist.faults import FAULT_TIME, WINDOW, FaultHook
    from stability.assist.firmware import firmware_tables
    from stability.assist.layout_checks import layout_traction_limit
    from stability.assist.weights import GyroSensor

    lay = layout_preset(name)
    lay = dataclasses.replace(lay, casters=tuple(dataclasses.replace(c, pin_friction=0.0) for c in lay.casters))
    b = 1.0
    for u in (2.0, -2.0):
        sched = layout_schedule(lay, [u], gyro=GyroSensor(noise_density_deg_s=0.0, bias_deg_s=0.0))
        tab = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
        T, gb = tab.sample_time, tab.bias_gain
        hook = FaultHook(tab, sched, np.array([u, u]), ["bias", ""], np.array([b, 0.0]),
                         traction_limit_N_m=layout_traction_limit(lay, sched.drive, u < 0))
        spec = RunSpec(horizon=FAULT_TIME + WINDOW, stop_on_warnings=False, push_force=0.0)
        biased, healthy = simulate_layout_batch(lay, [u, u], spec, yaw_moment=hook,
                                                caster_angles_deg=[trailing_angles(lay, u)] * 2)
        want = -b * T / gb * (1.0 - (1.0 - gb) ** int(round(WINDOW / T)))
        got = math.degrees(biased.heading_rad[-1] - healthy.heading_rad[-1])
        # error model: the healthy run goes straight but for rounding (observed 1e-18 deg); the biased one within
        # the derived bound 2 b T (docstring: the rate sum's truncation plus one sample of delay)
        assert int(hook.detect_k[0]) < 0 and abs(math.degrees(healthy.heading_rad[-1])) < 1e-9
        assert got == pytest.approx(want, abs=2 * b * T)
