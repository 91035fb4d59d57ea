"""The sign-flipped and the stuck-at-zero yaw-rate gyro on a wheel layout against an independent linear prediction (issue 38).

Prediction: the layout's linear model (:func:`stability.assist.layout.layout_plant`, discretised with a zero-order
hold by :func:`stability.assist.digital.discrete_loop`) closed with the firmware controller
(:class:`stability.assist.firmware.FirmwareController`, read as a linear map by stepping it from unit states: its
arithmetic is not re-typed) whose gyro input reads minus the yaw rate and whose wheel-speed input reads the yaw
rate.  The growth rate of that loop's dominant eigenvalue, ``ln|z| / T``, is compared with the divergence rate
fitted to the nonlinear layout simulator's faulted run (:class:`stability.assist.faults.FaultHook`) between the
fault and the monitor's detection.
"""

from __future__ import annotations

import dataclasses
import math

import control
import numpy as np
import pytest

from stability.assist.commands import COMMAND_FILTER
from stability.assist.digital import discrete_loop
from stability.assist.faults import FAULT_TIME, FaultHook
from stability.assist.firmware import MONITOR_THRESHOLD_DEG_S, FirmwareController, firmware_tables
from stability.assist.layout import layout_schedule
from stability.assist.weights import GyroSensor
from stability.layout.presets import layout_preset
from stability.settings.run import RunSpec
from stability.simulate.layout_batch import simulate_layout_batch
from stability.study.layout_impulse import trailing_angles


def _firmware_as_linear_map(tab, speed: float, gyro_sign: float) -> control.StateSpace:
    """The firmware controller (straight command, unsaturated, monitor quiet) as a discrete system from the yaw
    rate to minus the applied yaw moment, its gyro reading ``gyro_sign`` times the yaw rate, read by stepping
    :class:`FirmwareController` from each unit state and from a unit yaw rate (it is linear there)."""
    n = tab.n
    ns = n + 4                                  # x_hat, heading sum e, bias estimate, corrected gyro, moment
    eps = 1e-6                                  # far inside the torque limit and the monitor threshold
    fc = FirmwareController(tab, runs=ns + 1)
    S = np.zeros((ns + 1, ns))
    S[:ns] = eps * np.eye(ns)
    fc.xhat, fc.e, fc.bhat, fc.r, fc.u = S[:, :n].copy(), S[:, n].copy(), S[:, n + 1].copy(), \
        S[:, n + 2].copy(), S[:, n + 3].copy()
    fc.mz, fc.first = fc.u.copy(), False
    y = np.zeros(ns + 1)
    y[ns] = eps
    fc.step(np.full(ns + 1, speed), 0.0, gyro_sign * y, y)
    S1 = np.hstack([fc.xhat, fc.e[:, None], fc.bhat[:, None], fc.r[:, None], fc.u[:, None]]) / eps
    F, G = S1[:ns].T, S1[ns][:, None]
    H = np.zeros((1, ns))
    H[0, -1] = 1.0
    # one sample of computation delay: no feedthrough; error model: round-off of the 1e-6 probe divided by 1e-6
    # (observed 0), asserted 1e-9
    assert abs((H @ G).item()) < 1e-9
    return control.ss(F, G, -H @ F, 0.0, tab.sample_time)


def test_a_sign_flipped_gyro_diverges_at_the_linear_loops_rate():
    """mid-wheel-drive at 1 m/s, noise-free gyro, pins without friction, the thesis push at t = 0: the healthy
    loop (probed firmware) has the design's sampled closed-loop eigenvalues; after the sign flip at FAULT_TIME the
    yaw rate grows at the faulted linear loop's rate until the monitor detects it.  Error model of the fit: the
    next mode (1.0 /s against 17.4 /s) contaminates the log-amplitude by at most its relative size at the window's
    start, and the nonlinear terms by the amplitude squared (|r| < 0.06 rad/s); observed 0.5 % (17.34 against 17.42 /s), asserted 10 % (a fit: margin 20, not 100)."""
    lay = layout_preset("mid-wheel-drive")
    lay = dataclasses.replace(lay, casters=tuple(dataclasses.replace(c, pin_friction=0.0) for c in lay.casters))
    u = 1.0
    sched = layout_schedule(lay, [u], gyro=GyroSensor(noise_density_deg_s=0.0, bias_deg_s=0.0))
    tab = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    d = sched.designs[0]
    T = tab.sample_time
    healthy = discrete_loop(d, controller=_firmware_as_linear_map(tab, u, 1.0))
    ev_h = np.linalg.eigvals(healthy.A - healthy.B @ healthy.C)
    design = discrete_loop(d)
    ev_d = np.linalg.eigvals(design.A - design.B @ design.C)
    # the design's loop is inside the probed one; error model: round-off of the probe (1e-16 / 1e-6 = 1e-10 per
    # entry) through the eigenvalues of a well-separated spectrum, observed below 1e-9, asserted 1e-6
    for z in ev_d:
        assert np.min(np.abs(ev_h - z)) < 1e-6
    flipped = discrete_loop(d, controller=_firmware_as_linear_map(tab, u, -1.0))
    z = np.linalg.eigvals(flipped.A - flipped.B @ flipped.C)
    want = math.log(float(np.max(np.abs(z)))) / T
    hook = FaultHook(tab, sched, np.array([u]), ["sign"], np.zeros(1))
    spec = RunSpec(horizon=FAULT_TIME + 0.9, stop_on_warnings=False, sample=T)
    run, = simulate_layout_batch(lay, [u], spec, yaw_moment=hook, caster_angles_deg=[trailing_angles(lay, u)])
    t_det = int(hook.detect_k[0]) * T
    assert int(hook.detect_k[0]) > 0
    t, r = run.t_s, run.yaw_rate_rad_s
    sel = (t > FAULT_TIME + 0.15) & (t < t_det - 0.05)
    assert sel.sum() > 20
    got = np.polyfit(t[sel], np.log(np.abs(r[sel])), 1)[0]
    assert got == pytest.approx(want, rel=0.10)     # error model: docstring (observed 0.5 %)


def test_a_gyro_stuck_at_zero_diverges_through_the_bias_estimate():
    """mid-wheel-drive at 1 m/s (stable unassisted) with the gyro stuck at zero: the controller does not go open
    loop, its bias estimate learns the gyro minus the wheel-speed yaw rate, ``-r``, so the corrected gyro reads the
    low-passed yaw rate with the wrong sign and the faulted linear loop has an oscillatory unstable pair (about
    1.9 /s at 5.6 rad/s).  The simulated yaw rate's second-order recurrence (Prony, least squares over 2-6 s)
    has that pair.  Error model: the fast modes (< -5 /s) are 1e-2 of the pair 1 s after the fault, the
    amplitude stays below 3e-3 rad/s (nonlinear terms ~1e-3 relative); observed 1.8865 against 1.8810 /s and
    5.5619 against 5.5654 rad/s, asserted 0.2 /s and 0.2 rad/s (margin 36 and 57).

    Detection (issue 38, monitor38): the monitor's residual, the 0.05 s low-pass of ``g - w = -w`` less the bias
    estimate of the sample before (the 1 s low-pass of ``-w``), is the yaw rate through the discrete filter
    difference ``H(z) = g_m z / (z - 1 + g_m) - g_b / (z - 1 + g_b)``; on the growing oscillation ``z_d`` its
    envelope is ``|H(z_d)|`` times the yaw rate's (0.80), so the alarm (residual beyond the 3 deg/s threshold)
    comes once the yaw-rate envelope reaches ``A_det = threshold / |H(z_d)|`` (0.066 rad/s), within half a period
    ``pi / omega`` (0.56 s) after the envelope fitted to the peaks crosses it (a residual peak lies in every half
    period).  Observed: detection at 7.77 s against the crossing 7.58 s, the largest yaw rate before it 0.072 rad/s
    (1.09 ``A_det``; bound ``A_det exp(+-sigma pi / omega)``, a factor 2.9 either side).  The 6 s run layout38 used
    ended before it: the fault starts from a 1e-6 rad/s yaw rate, so the time to detection is ``ln(A_det / A_0) /
    sigma``, set by the disturbance, while the yaw rate at detection is bounded by the rule.  After the alarm the
    latched mode 1 feeds the wheel-speed yaw rate to both inputs: the healthy loop (the linear map with the gyro
    reading ``+r``), whose slowest rate bounds the decay."""
    lay = layout_preset("mid-wheel-drive")
    lay = dataclasses.replace(lay, casters=tuple(dataclasses.replace(c, pin_friction=0.0) for c in lay.casters))
    u = 1.0
    sched = layout_schedule(lay, [u], gyro=GyroSensor(noise_density_deg_s=0.0, bias_deg_s=0.0))
    tab = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    T = tab.sample_time
    stuck = discrete_loop(sched.designs[0], controller=_firmware_as_linear_map(tab, u, 0.0))
    z = np.linalg.eigvals(stuck.A - stuck.B @ stuck.C)
    zd = z[np.argmax(np.abs(z))]
    hook = FaultHook(tab, sched, np.array([u]), ["stuck_zero"], np.zeros(1))
    spec = RunSpec(horizon=12.0, stop_on_warnings=False, sample=T)
    run, = simulate_layout_batch(lay, [u], spec, yaw_moment=hook, caster_angles_deg=[trailing_angles(lay, u)])
    t, r = run.t_s, run.yaw_rate_rad_s
    t_det = int(hook.detect_k[0]) * T
    assert 6.0 < t_det < 12.0 and int(hook.fc.mode[0]) == 1
    y = r[(t > 2.0) & (t < 6.0)]
    a = np.linalg.lstsq(np.column_stack([y[1:-1], y[:-2]]), y[2:], rcond=None)[0]
    zs = np.roots([1.0, -a[0], -a[1]])
    zs = zs[np.argmax(np.abs(zs))]
    # error model: docstring (fast modes' contamination and second order in the amplitude), margin 36 and 57
    assert np.log(abs(zs)) / T == pytest.approx(np.log(abs(zd)) / T, abs=0.2)
    assert abs(np.angle(zs)) / T == pytest.approx(abs(np.angle(zd)) / T, abs=0.2)
    # detection from the rule: residual envelope |H(z_d)| times the yaw rate's, alarm at the threshold
    gm, gb = tab.monitor_gain, tab.bias_gain
    gain = abs(gm * zd / (zd - 1.0 + gm) - gb / (zd - 1.0 + gb))
    a_det = MONITOR_THRESHOLD_DEG_S * math.pi / 180.0 / gain
    sigma, omega = np.log(abs(zd)) / T, abs(np.angle(zd)) / T
    peaks = np.flatnonzero((np.abs(r[1:-1]) > np.abs(r[:-2])) & (np.abs(r[1:-1]) >= np.abs(r[2:]))) + 1
    peaks = peaks[(t[peaks] > 2.0) & (t[peaks] < t_det)]
    slope, icept = np.polyfit(t[peaks], np.log(np.abs(r[peaks])), 1)
    t_cross = (np.log(a_det) - icept) / slope
    # bound: a residual peak in every half period after the envelope crosses (observed 0.19 s of 0.56 s); the fit's
    # extrapolation error ~1e-2 s (slope 1.886 against 1.881 /s over ln(A_det/A) ~ 4)
    assert t_cross - 0.05 < t_det < t_cross + math.pi / omega
    # bound: the envelope within a factor exp(sigma pi / omega) of A_det at the alarm (observed 1.09 of 2.9)
    peak_before = np.abs(r[t <= t_det]).max()
    assert a_det * math.exp(-sigma * math.pi / omega) < peak_before < a_det * math.exp(sigma * math.pi / omega)
    # fallback: mode 1 is the healthy loop; its slowest mode bounds the decay from the peak after the alarm
    healthy = discrete_loop(sched.designs[0], controller=_firmware_as_linear_map(tab, u, 1.0))
    rate = np.log(np.abs(np.linalg.eigvals(healthy.A - healthy.B @ healthy.C))).max() / T
    assert rate < 0.0
    after = t > t_det
    k_pk = np.argmax(np.abs(r) * after)
    late = t > t[k_pk] + 3.0
    # error model: the other modes' transient constants (factor 10 allowed; observed 0.0029 against exp(-3) = 0.050)
    assert np.abs(r[late]).max() < 10.0 * np.abs(r[k_pk]) * math.exp(rate * 3.0)
