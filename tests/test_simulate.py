"""The simulator: WCHAIR scheme mechanics, batches, the adaptive scheme, results, CLI.

Thesis-reproduction checks (chapter 8) are in ``test_thesis_chapter8.py``.
"""

import copy
import dataclasses
import hashlib
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numerics import assert_signals_close, run_tolerance

from stability import tires
from stability.chair import preset
from stability.models import params
from stability.models import statics as loads
from stability.models.full_width import generated, tire_resultant
from stability.models.slope import generated as slope_generated
from stability.settings.run import RunSpec
from stability.simulate import (
    ChairState,
    SimulationResult,
    StepStabilityWarning,
    kernel,
)
from stability.simulate import simulate as _simulate
from stability.simulate import simulate_batch as _simulate_batch
from stability.simulate.options import make_options as _make_options
from stability.simulate.results import COLUMNS, new_warnings

# These tests reproduce program WCHAIR: its equations (the thesis variant) and its kinetic pin friction, while the
# toolkit's defaults are the exact model and stick-slip friction; every run here names its model and law.
simulate, simulate_batch, make_options = _simulate, _simulate_batch, _make_options


EJ = preset("ej-premier")
FRONT = preset("ej-premier-front-caster")


def _slick():
    """No tire forces at all: the chair responds to the disturbances alone.

    Lateral scales of 0 lie outside the plausible range a Chair accepts, so
    the test chair is built past that check (a copy with two fields set).
    """
    c = copy.copy(EJ)
    object.__setattr__(c, "main_lateral_scale", 0.0)
    object.__setattr__(c, "caster_lateral_scale", 0.0)
    return c


SLICK = _slick()


# ---------------------------------------------------------------------------
# bad input
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, match", [
    (dict(speed=0.0), r"speed=0\.0 is invalid; valid range: 0\.01 <= \|speed\| <= 20 m/s \(negative: reverse\)"),
    (dict(speed=-25.0), r"speed=-25\.0 is invalid"),
    (dict(speed=-0.75, reverse=True), r"speed=-0\.75 is invalid with reverse=True"),
    (dict(speed=float("nan")), r"speed=nan is invalid"),
    (dict(dt=0.0), r"dt=0\.0 is invalid; valid range"),
    (dict(dt=-1e-3), r"dt=-0\.001 is invalid"),
    (dict(horizon=0.0), r"horizon=0\.0 is invalid"),
    (dict(horizon=float("inf")), r"horizon=inf is invalid"),
    (dict(scheme="euler"), r"scheme='euler' is invalid; valid values: 'wchair', 'adaptive'"),
    (dict(model="kane"), r"model='kane' is invalid; valid values: 'exact', 'thesis'"),
    (dict(casters="welded"), r"casters='welded' is invalid"),
    (dict(out_of_range="ignore"), r"out_of_range='ignore' is invalid"),
    (dict(sample=0.0015), r"sample=0\.0015 is invalid for scheme 'wchair'; valid values: a whole multiple of dt"),
    (dict(push_duration=-0.1), r"push_duration=-0\.1 is invalid"),
    (dict(push_force=float("nan")), r"push_force=nan is invalid"),
    (dict(rtol=0.0), r"rtol=0\.0 is invalid"),
    (dict(dt=0.05, horizon=0.01), r"dt=0\.05 is invalid; valid range: dt <= horizon"),
])
def test_bad_input_names_parameter_value_and_range(kwargs, match):
    args = dict(horizon=0.01)
    args.update(kwargs)
    speed = args.pop("speed", 0.75)
    with pytest.raises(ValueError, match=match):
        simulate(EJ, speed, RunSpec(**args))


def test_a_yaw_moment_that_is_not_callable_is_refused():
    with pytest.raises(ValueError, match=r"yaw_moment=3\.0 is invalid"):
        simulate(EJ, 0.75, RunSpec(horizon=0.01), yaw_moment=3.0)


def test_a_negative_speed_drives_backwards():
    """A negative speed is the reverse flag's shorthand (API, batch and command line share RunSpec's rule), and
    the reverse run obeys two invariants of the symmetric chair: with the casters trailing (180 deg) and no push
    it runs straight back at its speed, and a push to the left is the mirror image of a push to the right.

    Error model: the mirrored runs execute the same operations on negated values, except that the caster angle
    pi is not exact in binary (sin(pi) = 1.2e-16), so the two differ by rounding that accumulates at most one
    eps of the peak heading per step: n eps max|psi| (observed 1/250 of it); the straight run's heading is that
    rounding alone, n eps rad (observed 4e-16 rad against 4.4e-13)."""
    assert RunSpec(speed=-0.75) == RunSpec(speed=0.75, reverse=True)
    trailing = RunSpec(horizon=2.0, eta0_deg=180.0, beta0_deg=180.0, model="exact", friction_law="stick-slip")
    straight = simulate(EJ, -0.75, trailing.replace(push_force=0.0))
    n = straight.t.size
    assert straight.u[0] == -0.75 and straight.settings["reverse"] is True
    EPS = float(np.finfo(float).eps)
    # error models (docstring): the straight run's heading is rounding alone, n eps rad; x sums n steps of u dt,
    # n eps relative (observed 1.9e-14 against 4.4e-13)
    assert np.max(np.abs(straight.heading)) <= n * EPS
    assert straight.x[-1] == pytest.approx(-0.75 * straight.t[-1], rel=n * EPS)
    right = simulate(EJ, -0.75, trailing)
    left = simulate(EJ, -0.75, trailing.replace(push_force=-trailing.push_force))
    peak = float(np.max(np.abs(right.heading)))
    assert peak > 0.05                                  # the push turns the chair: the mirror test is not vacuous
    assert np.max(np.abs(right.heading + left.heading)) <= n * EPS * peak   # error model: docstring's n eps peak
    batch = simulate_batch(EJ, [-0.75, 0.75], run=trailing.replace(sample=0.01))
    alone = simulate(EJ, -0.75, trailing.replace(sample=0.01))
    assert batch[0].u[0] == -0.75 and batch[1].u[0] == 0.75
    np.testing.assert_array_equal(batch[0].heading, alone.heading)   # the same run, per-run sign in a batch


def test_bad_batch_input():
    with pytest.raises(ValueError, match="chairs=\\[\\] is invalid"):
        simulate_batch([], [0.75])
    with pytest.raises(ValueError, match="cannot broadcast 2 chairs against 3 speeds"):
        simulate_batch([EJ, EJ], [0.5, 0.6, 0.7], run=RunSpec(horizon=0.01, friction_law="kinetic", model="thesis"))
    with pytest.raises(ValueError, match="speed=-21.0 is invalid"):
        simulate_batch(EJ, [0.5, -21.0], run=RunSpec(horizon=0.01, friction_law="kinetic", model="thesis"))
    with pytest.raises(TypeError, match="unexpected keyword argument 'speed_mps'"):
        simulate_batch(EJ, [0.5], run=RunSpec(friction_law="kinetic", model="thesis"), speed_mps=3)
    with pytest.raises(ValueError, match="workers=0 is invalid"):
        simulate_batch(EJ, [0.5], run=RunSpec(horizon=0.01, friction_law="kinetic", model="thesis"), workers=0)
    with pytest.raises(TypeError, match="chair='ej-premier' is invalid"):     # a type: the API's one contract
        simulate("ej-premier", 0.75)


# ---------------------------------------------------------------------------
# WCHAIR scheme mechanics (Appendix C)
# ---------------------------------------------------------------------------
def test_time_loop_is_wchairs_do_loop():
    """DO 99 T = 0, TTOTAL+TSTEP, TSTEP: samples at 0, dt, ..., TTOTAL + dt."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.05, dt=0.001, friction_law="kinetic", model="thesis"))
    assert len(r.t) == 52
    # error model: rounding of the time loop's sum, n eps t = 5.9e-16 s for 52 steps (observed 6.9e-18), x100; the
    # steps are differences of such times, 2 ulp of t / dt = 1.4e-14 relative (observed 6.1e-15), x100
    assert r.t[0] == 0.0 and r.t[-1] == pytest.approx(0.051, abs=6e-14)
    np.testing.assert_allclose(np.diff(r.t), 0.001, rtol=1.4e-12)
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.05, dt=0.001, sample=0.01, friction_law="kinetic", model="thesis"))
    np.testing.assert_allclose(r.t, np.arange(6) * 0.01, rtol=0, atol=1e-12)       # rounding, as above (0)


def test_impulse_at_cg_acts_while_t_le_duimp_with_constant_acceleration_update():
    """MECHAN/DYNAM test T .LE. DUIMP: 40 N acts at t = 0, ..., 0.100 s (101 steps).

    Without tire forces the chair only translates: VDD = FC2/M while the
    force acts (thesis variant), UPDATE/ITRATE integrate it exactly, so
    v = 40 * 0.101 / 95 afterwards and X = u t, Y = sum of the steps.
    """
    r = simulate(SLICK, 0.75, run=RunSpec(horizon=0.2, dt=0.001, friction_law="kinetic", model="thesis"))
    i = np.searchsorted(r.t, 0.15)
    # error model: rounding: 101 additions of a dt, n eps = 2.2e-14 (observed 6.6e-16), x50
    assert r.v[i] == pytest.approx(40.0 * 0.101 / 95.0, rel=1e-12)
    assert r.v[100] == pytest.approx(40.0 * 0.100 / 95.0, rel=1e-12)   # before the 101st step
    assert np.all(r.yaw_rate == 0.0) and np.all(r.heading == 0.0)
    # error model: rounding: x and y sum n steps, n eps relative (200 steps: 4.4e-14; observed 8.9e-16 and 4.1e-16)
    np.testing.assert_allclose(r.x, 0.75 * r.t, rtol=1e-12, atol=1e-15)
    a = 40.0 / 95.0
    k = 50  # constant acceleration from rest: y = a t^2 / 2 exactly
    assert r.y[k] == pytest.approx(0.5 * a * r.t[k] ** 2, rel=1e-12)


def test_statics_uses_previous_steps_total_force_including_fcimp():
    """STATICS is called before MECHAN/DYNAM with FC1, FC2 of the previous step (FCIMP included)."""
    r = simulate(SLICK, 0.75, run=RunSpec(horizon=0.01, friction_law="kinetic", model="thesis"))
    p = params.parameters(SLICK)
    # error model: rounding: the same statics compiled and in Python, a few ulp (observed 0)
    np.testing.assert_allclose(r.normal_load[0], loads.normal_loads(p), rtol=1e-12)      # FC = 0 at t = 0
    np.testing.assert_allclose(r.normal_load[1], loads.normal_loads(p, 0.0, 40.0), rtol=1e-12)


def test_thesis_caster_equations_use_previous_yaw_acceleration():
    """DYNAM forms Z10 = M*THEDD before updating THEDD: the caster rows lag one step (THEDD = 0 in BLOCK DATA).

    The kernel's caster acceleration of each step, recovered from its own update ``ED += EDD dt``, against the
    generated equations evaluated at the recorded state, forces and pin moments with the previous step's yaw
    acceleration (thesis) or the current one (exact).  Error model: the recovery loses 2 eps |ED| / dt, the
    evaluation a few eps of its terms; times 100."""
    from stability._generated import full_width

    eps = np.finfo(float).eps
    for model in ("thesis", "exact"):
        r = simulate(EJ, 0.75, RunSpec(horizon=0.02, model=model, friction_law="kinetic"))
        p = params.parameters(EJ)
        edd = np.diff(r.eta_dot) / r.settings["dt"]
        lagged, current = [], []
        for k in range(len(edd)):
            args = (r.u[k], r.v[k], r.yaw_rate[k], math.cos(r.eta[k]), math.sin(r.eta[k]), math.cos(r.beta[k]),
                    math.sin(r.beta[k]), r.eta_dot[k], r.beta_dot[k], r.fx[k, 0], r.fy[k, 0], r.fx[k, 1],
                    r.fy[k, 1], r.fx[k, 2], r.fy[k, 2], r.fx[k, 3], r.fy[k, 3], r.pin_moment[k, 0],
                    r.pin_moment[k, 1], 40.0, 0.0, *p.inertia)
            if model == "thesis":
                lagged.append(full_width.accelerations_thesis(*args, r_dot_casters=r.yaw_acceleration[k - 1]
                                                              if k else 0.0)[3])
                current.append(full_width.accelerations_thesis(*args)[3])
            else:
                lagged.append(full_width.accelerations_exact(*args)[3])
        tol = 100 * (2 * eps * np.max(np.abs(r.eta_dot)) / r.settings["dt"] + 10 * eps * np.max(np.abs(edd)))
        np.testing.assert_allclose(edd, lagged, rtol=0, atol=tol, err_msg=model)
        if model == "thesis":            # the lag is visible: the current yaw acceleration gives other steps
            assert np.max(np.abs(np.array(current) - edd)) > 100 * tol


def test_pin_friction_opposes_caster_rate_and_is_zero_at_rest():
    """DYNAM 0810-0819: SIGN(MAF, -ED), exactly zero when ED == 0."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, friction_law="kinetic", model="thesis"))
    assert r.eta_dot[0] == 0.0 and np.all(r.pin_moment[0] == 0.0)
    moving = r.eta_dot != 0.0
    np.testing.assert_array_equal(r.pin_moment[moving, 0], -0.1 * np.sign(r.eta_dot[moving]))
    moving = r.beta_dot != 0.0
    np.testing.assert_array_equal(r.pin_moment[moving, 1], -0.1 * np.sign(r.beta_dot[moving]))


def test_forces_oppose_contact_velocity_and_follow_the_tire_fits():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, friction_law="kinetic", model="thesis"))
    main, caster = EJ.main_tire_model(), EJ.caster_tire_model()
    k = 500
    for w, tire in zip(range(4), (caster, caster, main, main), strict=False):
        expect = tire.lateral_force(float(r.slip_deg[k, w]), float(r.normal_load[k, w]), warn=False)
        # error model: rounding: the same fit compiled and in Python, a few ulp (observed 0)
        assert r.fy[k, w] == pytest.approx(expect, rel=1e-12, abs=1e-12)
    assert np.all(r.fy[1:] * r.slip_deg[1:] <= 0.0)
    assert np.all(r.fx == 0.0)        # TXMOD = CXMOD = 0 by default


def test_tire_impulse_replaces_main_tire_lateral_forces():
    """MECHAN 0704-0706: FDY = FEY = FTIMP while t <= DUIMP."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.3, push_force=0.0, tire_push_force=25.0, push_duration=0.05, friction_law="kinetic", model="thesis"))
    on = r.t <= 0.05 + 1e-12
    assert on.sum() == 51
    np.testing.assert_array_equal(r.fy[on, 2], 25.0)
    np.testing.assert_array_equal(r.fy[on, 3], 25.0)
    k = int(np.flatnonzero(~on)[0])      # afterwards the tire fits again
    main = EJ.main_tire_model()
    # error model: rounding: the same fit compiled and in Python, a few ulp (observed 0)
    assert r.fy[k, 2] == pytest.approx(main.lateral_force(float(r.slip_deg[k, 2]), float(r.normal_load[k, 2])),
                                       rel=1e-12)
    assert r.yaw_rate[-1] != 0.0


def test_initial_lateral_velocity_and_caster_angles():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.01, push_force=0.0, lateral_velocity=0.04, eta0_deg=5.0, beta0_deg=-3.0, friction_law="kinetic", model="thesis"))
    assert r.v[0] == 0.04 and r.u[0] == 0.75
    # error model: rounding of a degree conversion and of an atan, a few ulp (observed 0 and 1.5e-16)
    assert r.eta[0] == pytest.approx(math.radians(5.0), rel=1e-13)
    assert r.beta[0] == pytest.approx(math.radians(-3.0), rel=1e-13)
    # eq 5-7: 0.04 m/s at 0.75 m/s is about 3 deg at the main wheels
    assert abs(r.slip_deg[0, 2]) == pytest.approx(math.degrees(math.atan(0.04 / 0.75)), rel=1e-12)


def test_no_disturbance_means_straight_motion():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, push_force=0.0, friction_law="kinetic", model="thesis"))
    assert np.all(r.yaw_rate == 0.0) and np.all(r.y == 0.0) and np.all(r.eta == 0.0)
    assert r.x[-1] == pytest.approx(0.75 * r.t[-1], rel=1e-11)   # rounding: 1001 steps' sum, n eps (8.9e-16 seen)


def test_toe_and_camber_as_slip_and_mechan_apply_them():
    """SLIP turns the right wheel frame by +toe and the left by -toe; MECHAN adds
    CAMCOF*POLYFT(TIRY, INT(CAMANG), FZ) to the left wheel and subtracts it on the right."""
    c = EJ.replace(toe_deg=1.0)
    r = simulate(c, 0.75, run=RunSpec(horizon=0.002, push_force=0.0, friction_law="kinetic", model="thesis"))
    # error model: rounding: a degree conversion both ways and a sum, a few ulp (observed 2.2e-16 and 0)
    assert r.slip_deg[0, 2] == pytest.approx(1.0, rel=1e-13)
    assert r.slip_deg[0, 3] == pytest.approx(-1.0, rel=1e-13)
    assert r.fy[0, 2] == pytest.approx(-r.fy[0, 3], rel=1e-12)
    assert abs(r.yaw_rate[-1]) < 1e-15                 # symmetric toe: no yaw (to rounding)
    c = EJ.replace(camber_deg=2.7, camber_coefficient=0.2, main_lateral_scale=0.5)
    r = simulate(c, 0.75, run=RunSpec(horizon=0.002, push_force=0.0, friction_law="kinetic", model="thesis"))
    fz = r.normal_load[0, 2]
    expect = tires.get("EJA").camber_force(2.0, fz, 0.2)   # whole degrees, unscaled, as WCHAIR
    assert expect > 0
    # error model: rounding: the same fit compiled and in Python (observed 0)
    assert r.fy[0, 2] == pytest.approx(expect, rel=1e-12)
    assert r.fy[0, 3] == pytest.approx(-expect, rel=1e-12)


def test_rolling_resistance_when_switched_on():
    c = EJ.replace(main_rolling_scale=1.0, caster_rolling_scale=1.0)
    r = simulate(c, 0.75, run=RunSpec(horizon=2.0, push_force=0.0, friction_law="kinetic", model="thesis"))
    fz = r.normal_load[0]
    # error model: rounding: the same fit compiled and in Python (observed 0)
    assert r.fx[0, 2] == pytest.approx(-c.main_tire_model().rolling_resistance(float(fz[2])), rel=1e-12)
    assert r.fx[0, 0] == pytest.approx(-c.caster_tire_model().rolling_resistance(float(fz[0])), rel=1e-12)
    assert r.u[-1] < 0.75 - 0.05                          # the chair slows down (chapter 8)


def test_warning_rule_stops_at_the_eleventh_warning():
    """NWARN > 10: STOP 'TEST CASE TERMINATED' (MECHAN 0682-0683); the stopping step is not recorded."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, push_force=0.0, lateral_velocity=0.3, friction_law="kinetic", model="thesis"))   # ~22 deg slip
    assert r.stopped_by_warnings
    assert r.warnings["slip"]["count"] == 11 and r.warnings["slip"]["first_time"] == 0.0
    assert r.stop_time == pytest.approx(0.010, abs=1e-12) and len(r.t) == 10   # rounding of 10 steps' sum (0)
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.05, push_force=0.0, lateral_velocity=0.3, stop_on_warnings=False, friction_law="kinetic", model="thesis"))
    assert not r.stopped_by_warnings and len(r.t) == 52
    assert r.warnings["slip"]["count"] > 11
    with pytest.raises(ValueError, match="slip angle .* outside the fitted range"):
        simulate(EJ, 0.75, run=RunSpec(horizon=0.05, push_force=0.0, lateral_velocity=0.3, out_of_range="raise", friction_law="kinetic", model="thesis"))


def test_range_rules_skip_linear_tires():
    """A linear tire has no treadmill range: no warnings for its wheels."""
    c = EJ.replace(main_tire="linear:25", caster_tire="linear:25")
    r = simulate(c, 0.75, run=RunSpec(horizon=0.05, push_force=0.0, lateral_velocity=0.3, friction_law="kinetic", model="thesis"))
    assert r.warnings["slip"]["count"] == 0 and not r.stopped_by_warnings


def test_locked_casters_hold_their_angle_with_a_reaction_moment():
    for model in ("thesis", "exact"):
        r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, casters="locked", model=model, friction_law="kinetic"))
        assert np.all(r.eta == 0.0) and np.all(r.beta == 0.0) and np.all(r.eta_dot == 0.0)
        assert np.max(np.abs(r.pin_moment)) > 0.01
        assert np.max(np.abs(r.yaw_rate)) > 0.0


def test_yaw_moment_input_reaches_the_yaw_equation():
    seen = []

    def mz(t, state):
        assert isinstance(state, ChairState)
        seen.append(t)
        return 5.0

    r = simulate(SLICK, 0.75, RunSpec(horizon=0.1, push_force=0.0, friction_law="kinetic", model="thesis"),
                 yaw_moment=mz)
    assert seen[0] == 0.0 and len(seen) == len(r.t)          # sampled once per step, at the step's start
    np.testing.assert_array_equal(r.yaw_moment_input, 5.0)
    np.testing.assert_allclose(r.yaw_acceleration, 5.0 / EJ.i_z, rtol=1e-12)   # rounding: one division (0)


def test_tire_yaw_moment_is_the_yaw_equation_of_the_thesis_variant():
    """Table 6-1's yaw row is I_z THEDD = moment of the tire forces (Figure 9-4)."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=3.0, friction_law="kinetic", model="thesis"))
    # error model: rounding: I_z times the acceleration the kernel formed from that moment, a few ulp (observed
    # 1.8e-15 N m on moments of ~10 N m); margins 500
    np.testing.assert_allclose(EJ.i_z * r.yaw_acceleration, r.tire_yaw_moment, rtol=1e-13, atol=1e-12)


# ---------------------------------------------------------------------------
# batches
# ---------------------------------------------------------------------------
_SIGNALS = ("x", "y", "heading", "yaw_rate", "u", "v", "eta", "beta", "eta_dot", "beta_dot", "fy", "normal_load",
            "slip_deg")


def _close(a: SimulationResult, b: SimulationResult, t_end: float, tol: float, what: str = "") -> None:
    """The runs agree up to ``t_end`` to ``tol`` of each signal's size (``tol`` from an error model)."""
    sel = a.t <= t_end + 1e-12
    n = int(sel.sum())

    class _Cut:
        def __init__(self, r):
            self.r = r

        def __getattr__(self, name):
            return getattr(self.r, name)[:n]

    assert_signals_close(_Cut(a), _Cut(b), _SIGNALS, tol, what=what)


def test_batch_equals_single_runs():
    """The vectorised path reproduces the float path (to rounding: the chair is unstable)."""
    speeds = [0.55, 0.75, 0.95]
    res = simulate_batch(EJ, speeds, run=RunSpec(horizon=3.0, sample=0.01, friction_law="kinetic", model="thesis"), progress=False, workers=1)
    for s, rb in zip(speeds, res, strict=False):
        r1 = simulate(EJ, s, run=RunSpec(horizon=3.0, sample=0.01, friction_law="kinetic", model="thesis"))
        assert rb.speed == s and rb.chair is EJ
        # error model: fixed-step rounding grown over 2.5 s of the unstable chair (tests/numerics.py)
        tol = run_tolerance(EJ, s, 2.5)
        _close(rb, r1, 2.5, tol, what=f"batch vs single {s} m/s")
        t1 = r1.first_time_abs_yaw_rate(0.5)
        tb = rb.first_time_abs_yaw_rate(0.5)
        assert (t1 is None) == (tb is None)
        if t1 is not None:
            # a yaw-rate difference dr moves the level crossing by dr / |dr/dt| there
            k = int(np.searchsorted(r1.t, t1))
            slope = abs(r1.yaw_rate[k] - r1.yaw_rate[k - 1]) / (r1.t[k] - r1.t[k - 1])
            assert abs(tb - t1) <= tol * np.max(np.abs(r1.yaw_rate)) / slope


def test_batch_mixed_chairs_groups_tires_and_stops_runs_individually():
    chairs = [EJ, EJ.replace(main_tire="AG"), FRONT, EJ.replace(camber_deg=2.0, toe_deg=0.5)]
    res = simulate_batch(chairs, 0.75, run=RunSpec(horizon=1.0, sample=0.001, lateral_velocity=0.03, push_force=0.0, friction_law="kinetic", model="thesis"), progress=False, workers=1)
    for c, rb in zip(chairs, res, strict=False):
        r1 = simulate(c, 0.75, run=RunSpec(horizon=1.0, lateral_velocity=0.03, push_force=0.0, friction_law="kinetic", model="thesis"))
        _close(rb, r1, 1.0, run_tolerance(c, 0.75, 1.0), what=c.main_tire)


def test_batch_stops_runs_individually():
    # a 0.3 m/s lateral velocity makes ~20 deg slip angles: stops at step 10; 0.01 m/s does not
    res = simulate_batch([EJ, EJ], 0.75, run=RunSpec(horizon=0.5, push_force=0.0, sample=0.001, lateral_velocity=0.3, friction_law="kinetic", model="thesis"), progress=False, workers=1)
    assert all(r.stopped_by_warnings and len(r.t) == 10 for r in res)
    mixed = simulate_batch([EJ, EJ.replace(main_tire="linear:25", caster_tire="linear:25")], 0.75, run=RunSpec(horizon=0.5, push_force=0.0, sample=0.001, lateral_velocity=0.3, friction_law="kinetic", model="thesis"), progress=False, workers=1)
    # rounding of 10 steps' sum (observed 0)
    assert mixed[0].stopped_by_warnings and mixed[0].stop_time == pytest.approx(0.01, abs=1e-12)
    assert not mixed[1].stopped_by_warnings and len(mixed[1].t) == 502
    r1 = simulate(EJ.replace(main_tire="linear:25", caster_tire="linear:25"), 0.75, run=RunSpec(horizon=0.5, push_force=0.0, lateral_velocity=0.3, friction_law="kinetic", model="thesis"))
    _close(mixed[1], r1, 0.5, run_tolerance(r1.chair, 0.75, 0.5), what="linear tires")


def test_batch_processes_equal_in_process():
    speeds = np.linspace(0.6, 0.9, 7)
    a = simulate_batch(EJ, speeds, run=RunSpec(horizon=1.0, friction_law="kinetic", model="thesis"), progress=False, workers=1)
    b = simulate_batch(EJ, speeds, run=RunSpec(horizon=1.0, friction_law="kinetic", model="thesis"), progress=False, workers=3)
    for ra, rb in zip(a, b, strict=False):
        assert ra.speed == rb.speed
        # the same compiled code in another process: rounding-level at most (fixed-step model)
        assert_signals_close(ra, rb, ("yaw_rate",), run_tolerance(EJ, ra.speed, 1.0), what="processes")


def test_batch_yaw_moment_gets_arrays_with_run_indices():
    runs = []

    def mz(t, state):
        runs.append(np.array(state.run))
        return -2.0 * state.yaw_rate

    res = simulate_batch(EJ, [0.7, 0.8], run=RunSpec(horizon=0.2, friction_law="kinetic", model="thesis"), progress=False, yaw_moment=mz)
    np.testing.assert_array_equal(runs[0], [0, 1])
    one = simulate(EJ, 0.8, run=RunSpec(horizon=0.2, sample=0.01, friction_law="kinetic", model="thesis"), yaw_moment=lambda t, s: -2.0 * s.yaw_rate)
    # fixed-step rounding model, with the open-loop linearisation (the -2 r feedback only damps it)
    assert_signals_close(res[1], one, ("yaw_rate",), run_tolerance(EJ, 0.8, 0.2), what="batch hook")


# ---------------------------------------------------------------------------
# adaptive scheme
# ---------------------------------------------------------------------------
@pytest.fixture(scope="module")
def adaptive_pair():
    kw = dict(horizon=4.0, scheme="adaptive", model="thesis")
    a = simulate(EJ, 0.75, RunSpec(rtol=1e-6, atol=1e-9, **kw))
    b = simulate(EJ, 0.75, RunSpec(rtol=0.5e-6, atol=0.5e-9, **kw))
    return a, b


def test_adaptive_converges_when_tolerances_are_halved(adaptive_pair):
    """Halving rtol/atol changes the reported quantities by less than 1e-4 relative."""
    a, b = adaptive_pair
    # error model: the integrator's global error, proportional to its rtol (1e-6) grown over the run: halving the
    # tolerances moves the values by about that (observed 9.4e-8 and 7.6e-7 for the times, 9.4e-7 for the rate), x100
    for v in (0.5, 1.0):
        ta, tb = a.first_time_abs_yaw_rate(v), b.first_time_abs_yaw_rate(v)
        assert ta is not None and abs(ta - tb) < 1e-4 * tb
    ra, rb = a.at(3.0)["yaw_rate"], b.at(3.0)["yaw_rate"]
    assert abs(ra - rb) < 1e-4 * abs(rb)


def test_adaptive_stick_slip(adaptive_pair):
    """Casters stick while the holding moment is within the friction limit, else slip with friction opposing."""
    r = adaptive_pair[0]
    for side, rate in ((0, r.eta_dot), (1, r.beta_dot)):
        m = r.pin_moment[:, side]
        stuck = rate == 0.0
        assert stuck[0] and m[0] == 0.0                        # at rest at t = 0, nothing to hold: stuck
        slipping = ~stuck
        assert slipping.any()
        np.testing.assert_allclose(m[slipping], -0.1 * np.sign(rate[slipping]), rtol=1e-12)    # rounding (0)
    assert r.settings["switches"] >= 2
    # at 0.1 N m the pins stick only at the start; at 0.3 N m they stick for most of the run (380 of 400 samples
    # after t = 0), holding moments up to 90 % of the limit: the recorded moment of a stuck pin is its holding
    # reaction, within the limit, and of a turning one the friction against its rate
    sticky = EJ.replace(pin_friction_left=0.3, pin_friction_right=0.3)
    h = simulate(sticky, 0.75, RunSpec(rtol=1e-6, atol=1e-9, horizon=4.0, scheme="adaptive", model="thesis"))
    t = np.asarray(h.t)
    for side, rate in ((0, np.asarray(h.eta_dot)), (1, np.asarray(h.beta_dot))):
        m = np.asarray(h.pin_moment)[:, side]
        held = (rate == 0.0) & (t > 0)
        assert held.sum() > 0.5 * t.size and np.abs(m[held]).max() > 0.5 * 0.3
        # error model: the stick event fires where |holding| reaches the limit, to the event solver's 1e-6 relative
        # rounding of that root; observed at most 0.90 of the limit
        assert np.all(np.abs(m[held]) <= 0.3 * (1 + 1e-6))
        np.testing.assert_allclose(m[rate != 0.0], -0.3 * np.sign(rate[rate != 0.0]), rtol=1e-12)   # rounding (0)
    # close to the WCHAIR scheme (different load lag and friction model: a few per cent). error model: truncation:
    # the WCHAIR scheme's first-order step error and one-step load lag, and its kinetic against the adaptive's
    # stick-slip friction (observed 1.45 %)
    w = simulate(EJ, 0.75, run=RunSpec(horizon=4.0, friction_law="kinetic", model="thesis"))
    assert r.first_time_abs_yaw_rate(1.0) == pytest.approx(w.first_time_abs_yaw_rate(1.0), rel=0.05)


def test_adaptive_yaw_moment_sees_floats_and_acts():
    def mz(t, state):
        assert type(t) is float and type(state.yaw_rate) is float
        return -20.0 * state.yaw_rate

    free = simulate(EJ, 0.75, run=RunSpec(horizon=3.0, scheme="adaptive", model="thesis"))
    damped = simulate(EJ, 0.75, run=RunSpec(horizon=3.0, scheme="adaptive", model="thesis"), yaw_moment=mz)
    np.testing.assert_allclose(damped.yaw_moment_input, -20.0 * damped.yaw_rate, rtol=1e-12)   # rounding (0)
    assert abs(damped.yaw_rate[-1]) < 0.2 * abs(free.yaw_rate[-1])


def test_adaptive_locked_and_samples():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, scheme="adaptive", casters="locked", sample=0.05, model="thesis"))
    np.testing.assert_allclose(r.t, np.arange(21) * 0.05, rtol=0, atol=1e-12)   # rounding of the sample times (0)
    assert np.all(r.eta == 0.0) and np.all(r.beta == 0.0)
    assert not r.stopped_by_warnings and r.settings["switches"] == 0


def test_adaptive_loads_are_consistent_with_the_forces():
    """Instantaneous (not lagged) load transfer, without the c.g. force."""
    r = simulate(EJ, 0.75, run=RunSpec(horizon=2.0, scheme="adaptive", sample=0.25, model="thesis"))
    p = params.parameters(EJ)
    for k in range(len(r.t)):
        ce, se, cb, sb = math.cos(r.eta[k]), math.sin(r.eta[k]), math.cos(r.beta[k]), math.sin(r.beta[k])
        fx, fy = r.fx[k], r.fy[k]
        sfx, sfy = tire_resultant((fx[0], fy[0], fx[1], fy[1], fx[2], fy[2], fx[3], fy[3]), ce, se, cb, sb)
        # error model: rounding of the same statics on the recorded state, amplified where a load is a small
        # difference of O(m g) terms (observed 9.9e-12), margin 100
        np.testing.assert_allclose(r.normal_load[k], loads.normal_loads(p, sfx, sfy, ce, se, cb, sb), rtol=1e-9)


@pytest.mark.parametrize("scheme", ["wchair", "adaptive"])
def test_a_zero_yaw_moment_input_changes_nothing(scheme):
    """A Python yaw-moment input that returns 0 N m runs the same arithmetic as no input, bit for bit: the
    kernel takes the input between its steps (wchair) or at each evaluation (adaptive) and adds it where the
    equations take Mz_ext."""
    run = RunSpec(horizon=2.0, scheme=scheme, model="exact", lateral_velocity=0.02)
    a = simulate(EJ, 0.5, run)
    b = simulate(EJ, 0.5, run, yaw_moment=lambda t, s: 0.0)
    for name in ("yaw_rate", "eta", "beta_dot", "fy", "normal_load", "pin_moment"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name), err_msg=name)


def test_adaptive_compiled_raise_policy_raises_the_tire_error():
    """A refused tire input inside the compiled right-hand side raises the tire's own error."""
    with pytest.raises(ValueError, match=r"outside the fitted range \[-8, 8\] deg \(tire EJA\)"):
        simulate(EJ, 0.75, run=RunSpec(scheme="adaptive", out_of_range="raise", model="thesis"))


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
def _synthetic(t, r):
    rec = np.zeros((len(t), len(COLUMNS)))
    rec[:, 0] = t
    rec[:, COLUMNS.index("yaw_rate")] = r
    return SimulationResult._from_records(rec, warnings=new_warnings(), stopped=False, stop_time=None,
                                          chair=EJ, speed=0.75, settings={"scheme": "wchair", "model": "thesis"})


def test_first_time_abs_yaw_rate_interpolates():
    res = _synthetic(np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, -0.4, -0.8, -1.6]))
    # rounding: linear interpolation of exact binary fractions (observed 0)
    assert res.first_time_abs_yaw_rate(0.6) == pytest.approx(1.5, abs=1e-12)
    assert res.first_time_abs_yaw_rate(1.2) == pytest.approx(2.5, abs=1e-12)
    assert res.first_time_abs_yaw_rate(0.0) == 0.0
    assert res.first_time_abs_yaw_rate(2.0) is None
    with pytest.raises(ValueError, match="value=-1.0 is invalid"):
        res.first_time_abs_yaw_rate(-1.0)


def test_result_is_frozen_and_resamples():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.5, friction_law="kinetic", model="thesis"))
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.speed = 1.0
    with pytest.raises(ValueError):
        r.yaw_rate[0] = 1.0
    q = r.resample(0.05)
    np.testing.assert_allclose(q.t, np.arange(11) * 0.05, rtol=0, atol=1e-12)   # rounding of sample times (0)
    np.testing.assert_array_equal(q.yaw_rate, np.interp(q.t, r.t, r.yaw_rate))   # the same interpolation
    assert q.fy.shape == (11, 4) and q.pin_moment.shape == (11, 2)
    d = r.to_dict()
    json.dumps(d, allow_nan=False)
    assert d["t_s"][-1] == pytest.approx(0.501, abs=1e-12)      # rounding of 501 steps' sum (observed 0)


def test_to_csv_and_plot(tmp_path):
    r = simulate(EJ, 0.75, run=RunSpec(horizon=0.5, sample=0.01, friction_law="kinetic", model="thesis"))
    path = r.to_csv(tmp_path / "run.csv")
    data = np.loadtxt(path, delimiter=",", comments="#", skiprows=5)
    header = path.read_text().splitlines()[4].split(",")
    assert header[:5] == ["t", "x", "y", "heading", "yaw_rate"] and "fy_A" in header
    # rounding: the CSV's printed digits round-trip to within an ulp (observed 0)
    np.testing.assert_allclose(data[:, header.index("yaw_rate")], r.yaw_rate, rtol=1e-15)
    assert not list(tmp_path.glob(".*tmp"))
    pdf = r.plot(tmp_path / "run.pdf")
    assert pdf.read_bytes()[:4] == b"%PDF"
    png = r.plot(tmp_path / "run.png")
    assert png.read_bytes()[:4] == b"\x89PNG"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    assert r.plot(ax) is ax
    assert ax.get_xlabel() == "time (s)" and ax.get_ylabel() == "yaw rate (rad/s)"
    assert "ej-premier" in ax.get_title() and "thesis" in ax.get_title()
    plt.close(fig)
    with pytest.raises(ValueError, match="does not exist"):
        r.plot(tmp_path / "nope" / "x.pdf")


def test_summary_mentions_the_essentials():
    r = simulate(EJ, 0.75, run=RunSpec(horizon=1.0, friction_law="kinetic", model="thesis"))
    text = r.summary()
    assert "ej-premier" in text and "0.75 m/s" in text and "warnings" in text


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------
def _cli(*args):
    return subprocess.run([sys.executable, "-m", "stability.simulate", *args], capture_output=True, text=True,
                          timeout=120)


def test_cli_json(tmp_path):
    p = _cli("--chair", "ej-premier", "--speed", "0.75", "--push-force", "40", "--push-duration", "0.1", "--horizon", "4",
             "--model", "thesis", "--friction-law", "kinetic", "--sample", "0.1", "--json", "--csv", str(tmp_path / "a.csv"), "--plot", str(tmp_path / "a.pdf"))
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    for key in ("t_s", "yaw_rate_rad_s", "heading_rad", "x_m", "y_m", "fy_caster_left_N", "slip_main_right_deg",
                "stopped_by_warnings", "warnings", "yaw_rate_levels_rad_s", "first_time_at_level_s"):
        assert key in d
    assert d["stopped_by_warnings"] is True and d["warnings"]["slip"]["count"] == 11   # at about 3.64 s
    np.testing.assert_allclose(d["t_s"], np.arange(len(d["t_s"])) * 0.1, rtol=0, atol=1e-12)   # rounding (0)
    assert 3.5 <= d["t_s"][-1] < 3.7 and len(d["yaw_rate_rad_s"]) == len(d["t_s"])
    assert d["yaw_rate_levels_rad_s"] == [0.5, 1.0]
    # rounding: the same run in another process, bit for bit here (observed 0)
    assert d["first_time_at_level_s"][1] == pytest.approx(simulate(EJ, 0.75, run=RunSpec(horizon=4, friction_law="kinetic", model="thesis")).first_time_abs_yaw_rate(1.0), rel=1e-12)
    assert (tmp_path / "a.csv").exists() and (tmp_path / "a.pdf").exists()


def _main(capsys, *args):
    """The command in this process (its answer, not its entry point: test_cli_json runs that): status, out, err."""
    from stability.simulate.__main__ import main

    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def test_cli_summary_and_set(capsys):
    status, out, err = _main(capsys, "--chair", "ej-premier", "--set", "pin_friction_left=0.2", "--set",
                             "pin_friction_right=0.2", "--horizon", "1", "--scheme", "adaptive")
    assert status == 0, err
    assert "ej-premier" in out and "adaptive" in out


@pytest.mark.parametrize("args, words", [
    (("--speed", "-21"), "--speed -21 is invalid; valid range: 0.01 <= |value| <= 20 m/s (negative: reverse)"),
    (("--speed", "-1", "--reverse"), "--speed -1.0 is invalid with --reverse True"),
    (("--chair", "nope"), "unknown chair 'nope'"),
    (("--set", "s9=1"), "unknown chair parameter 's9'"),
    (("--scheme", "rk4"), "invalid choice: 'rk4' (choose from 'wchair', 'adaptive')"),
    (("--speed", "fast"), "--speed 'fast' is invalid; expected a finite number (or a number with a unit of m/s); valid range: 0.01 <= |value| <= 20 m/s (negative: reverse)"),
    (("--csv", "/nonexistent/dir/x.csv"), "does not exist"),
])
def test_cli_bad_input_one_line_status_2(args, words, capsys):
    status, _, err = _main(capsys, *args, "--horizon", "0.1")
    assert status == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and words in lines[0] and "Traceback" not in err


def test_cli_bad_input_exits_2_from_the_entry_point():
    """``python -m stability.simulate`` itself: bad input leaves the interpreter with status 2 and one line."""
    p = _cli("--speed", "-21", "--horizon", "0.1")
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and "--speed -21 is invalid" in lines[0] and "Traceback" not in p.stderr


# ---------------------------------------------------------------------------
# progress bar helper
# ---------------------------------------------------------------------------
def test_progress_bar_silent_unless_tty_or_forced(monkeypatch):
    import io

    from stability.runtime.progress import ProgressBar, track

    buf = io.StringIO()                                   # not a TTY
    with ProgressBar(10, "x", file=buf) as bar:
        bar.update(10)
    assert buf.getvalue() == "" and not bar.shown
    with ProgressBar(10, "x", file=buf, enabled=False, force=False) as bar:
        bar.update(5)
    assert buf.getvalue() == ""
    monkeypatch.setitem(sys.modules, "tqdm", None)       # plain fallback
    with ProgressBar(4, "runs", file=buf, force=True, unit="run") as bar:
        for _ in range(4):
            bar.update()
    out = buf.getvalue()
    assert "runs: [" in out and "4/4 run" in out and out.endswith("\n")
    assert list(track(range(3), enabled=False)) == [0, 1, 2]


def test_batch_per_run_impulse_force_equals_separate_batches():
    """impulse_force as an array: one disturbance per run, same results as one batch per force."""
    speeds = np.array([0.6, 0.75, 0.9, 0.6, 0.75, 0.9])
    forces = np.array([20.0, 20.0, 20.0, 80.0, 80.0, 80.0])
    for workers in (1, 2):
        mixed = simulate_batch(EJ, speeds, run=RunSpec(horizon=3.0, sample=0.01, friction_law="kinetic", model="thesis"), push_forces=forces, progress=False, workers=workers)
        for f in (20.0, 80.0):
            sel = np.flatnonzero(forces == f)
            same = simulate_batch(EJ, speeds[sel], run=RunSpec(horizon=3.0, sample=0.01, friction_law="kinetic", model="thesis",
                                                                push_force=f), progress=False, workers=1)
            for i, r in zip(sel, same, strict=False):
                assert mixed[i].settings["impulse_force"] == f
                np.testing.assert_array_equal(mixed[i].yaw_rate, r.yaw_rate)
    # a bigger push turns the chair faster (Figure 8-2's disturbance scaling)
    assert np.max(np.abs(mixed[4].yaw_rate)) > np.max(np.abs(mixed[1].yaw_rate))


def test_batch_per_run_impulse_force_bad_input():
    with pytest.raises(ValueError, match=r"3 push forces"):
        simulate_batch(EJ, [0.5, 0.6], run=RunSpec(friction_law="kinetic", model="thesis"), push_forces=[1.0, 2.0, 3.0], progress=False)
    with pytest.raises(ValueError, match=r"push_forces: push_force=nan is invalid; valid range: .* N"):
        simulate_batch(EJ, [0.5, 0.6], run=RunSpec(friction_law="kinetic", model="thesis"), push_forces=[1.0, float("nan")], progress=False)


# ---------------------------------------------------------------------------
# the compiled kernel (issue 10)
# ---------------------------------------------------------------------------
def test_single_run_is_bit_identical_to_its_batch_run():
    """One kernel: a run alone and the same run inside a batch (any threads) are the same arithmetic."""
    speeds = np.array([0.55, 0.75, 0.95])
    batch = simulate_batch(EJ, speeds, run=RunSpec(sample=0.001, friction_law="kinetic", model="thesis"), progress=False, workers=2, push_forces=[20.0, 40.0, 60.0])
    for s, f, rb in zip(speeds, (20.0, 40.0, 60.0), batch, strict=False):
        r1 = simulate(EJ, float(s), run=RunSpec(push_force=f, friction_law="kinetic", model="thesis"))
        for name in ("t", "yaw_rate", "heading", "x", "y", "fy", "normal_load", "pin_moment"):
            np.testing.assert_array_equal(getattr(rb, name), getattr(r1, name), err_msg=name)
        assert rb.stop_time == r1.stop_time and rb.stats == r1.stats


def test_record_modes_and_stats():
    full = simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False, horizon=4.0, friction_law="kinetic", model="thesis"))
    states = simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False, horizon=4.0, sample=0.01, friction_law="kinetic", model="thesis"), record="states")
    final = simulate(EJ, 0.75, run=RunSpec(stop_on_warnings=False, horizon=4.0, friction_law="kinetic", model="thesis"), record="final")
    np.testing.assert_array_equal(states.yaw_rate, full.yaw_rate[::10])
    assert np.all(np.isnan(states.fy)) and states.fy.shape == (len(states.t), 4)
    assert len(final.t) == 1 and final.t[0] == full.t[-1] and final.yaw_rate[0] == full.yaw_rate[-1]
    for r in (states, final):      # summaries over every step, whatever is recorded
        assert r.stats == full.stats
    # rounding: the kernel's running interpolation and the recorded one (observed 0)
    assert full.stats.time_to_level[1] == pytest.approx(full.first_time_abs_yaw_rate(1.0), abs=1e-12)
    assert full.stats.peak_abs_yaw_rate == np.max(np.abs(full.yaw_rate))
    json.dumps(final.to_dict(), allow_nan=False)


def test_batch_memory_scales_with_the_record():
    """2,000 runs x 10 s recorded every 10 ms, states only: under 200 MB (10 columns x 1,002 rows x 8 B)."""
    from stability.simulate import engine

    n, rows = 2000, 1002
    assert n * rows * engine.__dict__.get("NREC_STATES", 10) * 8 < 200e6
    res = simulate_batch(EJ, np.linspace(0.5, 1.0, 20), run=RunSpec(stop_on_warnings=False, friction_law="kinetic", model="thesis"), record="states", progress=False)
    base = res[0].yaw_rate.base
    while base is not None and base.base is not None:
        base = base.base
    assert base is not None and base.nbytes <= 20 * 10 * rows * 8      # one buffer, no per-result copies


def test_sampled_controller_equals_the_python_callable():
    """A compiled state-feedback controller = the same law as a Python yaw_moment hook (Ts = dt)."""
    from stability.simulate import SampledController

    K = np.array([0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    ctl = SampledController.state_feedback(K, 0.001, limit=15.0)

    def hook(t, s):
        return min(max(-20.0 * s.yaw_rate, -15.0), 15.0)

    a = simulate(EJ, 0.75, RunSpec(horizon=3.0, friction_law="kinetic", model="thesis"), controller=ctl)
    b = simulate(EJ, 0.75, RunSpec(horizon=3.0, friction_law="kinetic", model="thesis"), yaw_moment=hook)
    # fixed-step rounding model with the open-loop linearisation (the feedback only damps)
    assert_signals_close(a, b, ("yaw_rate",), run_tolerance(EJ, 0.75, 3.0), what="sampled controller")
    np.testing.assert_allclose(a.yaw_moment_input, -20.0 * a.yaw_rate.clip(-0.75, 0.75), rtol=1e-12, atol=1e-15)
    free = simulate(EJ, 0.75, run=RunSpec(horizon=3.0, friction_law="kinetic", model="thesis"))
    assert np.max(np.abs(a.yaw_rate)) < 0.5 * np.max(np.abs(free.yaw_rate))
    with pytest.raises(ValueError, match="choose one"):
        simulate(EJ, 0.75, run=RunSpec(horizon=0.1, friction_law="kinetic", model="thesis"), controller=ctl, yaw_moment=hook)


@pytest.mark.parametrize("speed", [0.1, 0.2, 0.25, 0.3])
def test_step_stability_limit_against_the_adaptive_scheme(speed):
    """At low speed the caster modes are stiff (~ -2000 1/s at 0.25 m/s): 1 ms is outside the limit below ~0.28 m/s.

    Such runs are flagged and warned about; dt="auto" picks a stable step and
    then agrees with the adaptive scheme (issue 10: 0.072 rad/s peak at 0.25 m/s).
    """
    kw = dict(horizon=3.0, stop_on_warnings=False, model="thesis")
    ada = simulate(EJ, speed, RunSpec(scheme="adaptive", **kw))
    auto = simulate(EJ, speed, RunSpec(dt="auto", friction_law="kinetic", **kw))
    assert not auto.step_unstable and auto.settings["dt"] <= auto.settings["stable_dt"]
    peak_ada = np.max(np.abs(ada.yaw_rate))
    # error model: truncation, first order in the auto step (0.25-0.5 ms), and kinetic against stick-slip friction
    # (observed 0.65-1.0 %)
    assert np.max(np.abs(auto.yaw_rate)) == pytest.approx(peak_ada, rel=0.08)
    if speed < 0.27:
        with pytest.warns(StepStabilityWarning, match=r"dt=0\.001 s exceeds .*largest safe step"):
            fixed = simulate(EJ, speed, RunSpec(friction_law="kinetic", **kw))
        assert fixed.step_unstable and fixed.to_dict()["step_unstable"] is True
    else:
        fixed = simulate(EJ, speed, RunSpec(friction_law="kinetic", **kw))
        assert not fixed.step_unstable


def test_range_rules_count_only_the_tested_wheels_of_a_mixed_chair():
    """Linear casters, tested main wheels: a slip warning is a step where a main wheel's |slip| exceeds 8 deg
    (WCHAIR's MECHAN rule); the eleventh stops the run before recording its step.  Tested casters, linear main
    wheels: the main wheels' slips beyond 8 deg are no warning."""
    chair = EJ.replace(caster_tire="linear:25")
    r = simulate(chair, 0.5, RunSpec(push_force=150.0, horizon=2.5, friction_law="kinetic", model="thesis"))
    over = np.flatnonzero(np.max(np.abs(r.slip_deg[:, 2:4]), axis=1) > 8.0)
    assert r.warning_counts["slip"] == 11 and len(over) == 10 and r.stopped_by_warnings
    assert r.warnings["slip"]["first_time"] == r.t[over[0]]
    assert r.stop_time == pytest.approx(r.t[-1] + r.settings["dt"], abs=1e-12)    # rounding of one sum (0)
    other = simulate(EJ.replace(main_tire="linear:30"), 0.5, RunSpec(push_force=150.0, horizon=2.5,
                                                                       friction_law="kinetic", model="thesis"))
    assert np.max(np.abs(other.slip_deg[:, 2:4])) > 8.0 and np.max(np.abs(other.slip_deg[:, 0:2])) <= 8.0
    assert other.warning_counts["slip"] == 0


def test_compile_cache_stamp_is_the_generated_equations_hash():
    """The stale-cache stamp next to the numba cache is the SHA-256 of the modules the kernels compile as they are
    (the generated equations, level and slope, and the tire law) and of the kernel modules whose functions other
    kernels call (numba keys a cache on its own file only)."""
    from stability.models import forces
    from stability.simulate.cache_stamp import COMPILED_MODULES, KERNEL_SOURCES
    from stability.tires import law

    here = Path(kernel.__file__).parent
    digest = hashlib.sha256(b"".join(Path(m.__file__).read_bytes() for m in COMPILED_MODULES)
                            + b"".join((here / name).read_bytes() for name in KERNEL_SOURCES)).hexdigest()
    assert {"kernel.py", "kernel_equations.py", "kernel_controller.py", "adaptive_kernel.py"} <= set(KERNEL_SOURCES)
    assert {generated, slope_generated, forces.generated, law} <= set(COMPILED_MODULES)
    stamp = Path(kernel.run_batch._cache.cache_path) / "kernel.equations.sha256"
    if not stamp.exists():
        pytest.skip("no writable cache directory")
    assert stamp.read_text() == digest
