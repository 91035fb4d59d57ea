"""The driver in the nonlinear run (stability.study.lane): the delay, the kinematics the lane operator assumes,
the saturation, and the limit's order in the reaction time."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from stability import chair as chair_mod
from stability.driver import Driver
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.study.lane import (
    LANE_HALF_WIDTH_M,
    LANE_HEADING_LIMIT_DEG,
    SAMPLE_TIME_S,
    LaneLimit,
    LaneRange,
    lane_controller,
    lane_gains,
    lane_limit,
    lane_plant,
    lane_range,
    lane_run,
)

EJ = chair_mod.preset("ej-premier")


@functools.cache
def _ej_range(tau: float) -> LaneRange:
    """The E&J's lane range for a driver of delay ``tau``, computed once for the tests that read it (frozen
    inputs)."""
    return lane_range(EJ, Driver(tau))


def _ej_limit(tau: float) -> LaneLimit:
    """``lane_limit(EJ, Driver(tau))``; at 0.5 s the range's nominal limit, which is that very call
    (``lane_range`` takes ``lane_limit`` at the default run's push), so it is not computed twice."""
    return _ej_range(tau).nominal if tau == 0.5 else lane_limit(EJ, Driver(tau))


def _kinematic_residual(dt: float) -> tuple[float, float]:
    res = simulate(EJ, 1.0, RunSpec(speed=1.0, horizon=2.0, dt=dt, stop_on_warnings=False))
    t, Y = np.asarray(res.t), np.asarray(res.y)
    psi, u, v = (np.asarray(a) for a in (res.heading, res.u, res.v))
    dY = (Y[2:] - Y[:-2]) / (t[2:] - t[:-2])
    kin = u[1:-1] * np.sin(psi[1:-1]) + v[1:-1] * np.cos(psi[1:-1])
    return float(np.max(np.abs(dY - kin))), float(np.max(np.abs(kin)))


def test_lane_plant_row_is_the_simulators_kinematics():
    """The operator's lateral offset obeys the simulator's own kinematics ``Y' = u sin psi + v cos psi``, whose
    linearisation about the straight line is the plant's row ``y' = U psi + v``.

    Error model: the fixed-step scheme updates the position to first order, so the central difference of the
    recorded ``Y`` differs from the kinematics by about ``dt max|d/dt (u sin psi + v cos psi)|`` (observed
    5.7e-4 m/s at dt = 1 ms, 1.4 dt x 0.42 m/s^2): tolerance 100 times that, 0.06 m/s, still a quarter of the
    lateral speed a sign error would leave (2 x 0.24 m/s); and the residual halves with the step (first order:
    ratio 1.6-2.5 between 1 ms and 0.5 ms)."""
    A, _B, C = lane_plant(EJ, 1.0)
    assert A[7].tolist() == [1.0, 0, 0, 0, 0, 0, 1.0, 0]            # y' = v + U psi at U = 1 m/s
    assert C[0, 7] == 1.0 and C[1, 6] == 1.0 and C[2, 1] == 1.0
    err1, peak = _kinematic_residual(1e-3)
    err2, _ = _kinematic_residual(5e-4)
    assert peak > 0.2                                                 # the run does drift sideways
    assert err1 < 0.06
    assert 1.6 < err1 / err2 < 2.5


def test_the_driver_acts_on_what_it_saw_one_delay_ago():
    """``Mz(t_k) = sat(-(k_y Y + k_p psi + k_d r)(t_{k-n}))`` with ``n = tau / T``, read off the recorded run
    (not the controller's matrices): the delay is exact in samples."""
    g = lane_gains(EJ, 1.0, Driver(0.3))
    ctl = lane_controller(EJ, g, Driver(0.3))
    n = int(round(0.3 / SAMPLE_TIME_S))
    assert ctl.Az.shape == (n, n)
    res = simulate(EJ, 1.0, RunSpec(speed=1.0, horizon=1.5, stop_on_warnings=False), controller=ctl)
    t = np.asarray(res.t)
    s = np.stack([np.asarray(res.y), np.asarray(res.heading), np.asarray(res.yaw_rate)])
    mz = np.asarray(res.yaw_moment_input)
    T = SAMPLE_TIME_S
    checked = 0
    for k in range(n + 1, int(1.4 / T)):
        i_now = int(np.searchsorted(t, k * T - 1e-9))             # the first step at or after the sample
        i_then = int(np.searchsorted(t, (k - n) * T - 1e-9))
        want = float(np.clip(-g.gains @ s[:, i_then], -ctl.limit, ctl.limit))
        assert mz[i_now] == pytest.approx(want, rel=1e-9, abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.2e-16)
        checked += 1
    assert checked > 100
    assert np.all(mz[t < n * T - 1e-9] == 0.0)                      # nothing before the first delayed sample
    assert np.max(np.abs(mz)) > 0.1


def test_the_driver_never_exceeds_what_a_hand_has():
    """A weak driver saturates: the largest moment equals the hand-rim limit F r_h / r_w (d1 + d2)."""
    weak = Driver(0.3, hand_force_N=2.0)
    r = lane_run(EJ, 1.5, weak)
    from stability.settings import defaults as D

    # eq 6-3: one hand pushes, the other pulls, F r_h / r_w at each wheel's contact, d1 + d2 apart (the radii are
    # the settings table's inputs); a few roundings of the same product: rel 1e-13 (~100 times 4 ulp)
    limit = 2.0 * D.HANDRIM_RADIUS / D.HANDRIM_WHEEL_RADIUS * (EJ.d1 + EJ.d2)
    assert r.moment_limit_N_m == pytest.approx(limit, rel=1e-13)
    assert r.peak_moment_N_m <= r.moment_limit_N_m * (1 + 1e-12)


def _check_kept_runs(lim: LaneLimit) -> None:
    """Every reported kept run lies within the lane, and the first run above the limit did not keep it."""
    assert lim.side == "="
    kept = [r for r in lim.runs if r.kept]
    assert all(r.peak_offset_m <= LANE_HALF_WIDTH_M for r in kept)
    assert all(r.peak_heading_deg < LANE_HEADING_LIMIT_DEG for r in kept)
    above = [r for r in lim.runs if r.speed_m_s > lim.speed_m_s]
    assert above and not above[0].kept


def _first_failure(lim: LaneLimit) -> float:
    """The lowest speed tried above the limit (not kept), m/s."""
    return min(r.speed_m_s for r in lim.runs if r.speed_m_s > lim.speed_m_s)


def test_lane_limit_falls_with_the_reaction_time():
    """A slower driver keeps the lane only at lower speeds (the issue's monotonicity test), on a coarse speed grid
    (the statement needs no finer one: the E&J's limits at 0.2, 0.3 and 0.5 s are 2.94, 1.41 and 1.01 m/s today).
    The 0.3 s driver's limit (speeds 1, 1.5 m/s, bisected to 0.1 m/s) lies above the first speed at which the
    0.5 s driver fails; the 0.2 s driver keeps the lane at the first speed at which the 0.3 s driver fails, so its
    limit lies above it (``lane_limit`` takes the outcome to change once with the speed).  Every reported kept run
    lies within the lane while the first failure above each limit does not.  The same at the bisection's
    tolerance, three limits: the slow test below."""
    slow = _ej_limit(0.5)                                 # shared with the push range's tests
    mid = lane_limit(EJ, Driver(0.3), speeds=(1.0, 1.5), tol=0.1)
    for lim in (slow, mid):
        _check_kept_runs(lim)
    assert mid.speed_m_s > _first_failure(slow)
    fast = lane_run(EJ, _first_failure(mid), Driver(0.2))
    assert fast.kept and fast.peak_offset_m <= LANE_HALF_WIDTH_M


@pytest.mark.slow      # three lane limits at the bisection's tolerance (about 11 s); the default test above holds
def test_lane_limit_falls_with_the_reaction_time_at_the_bisections_tolerance():   # the statement on a coarse grid
    """A slower driver keeps the lane only at lower speeds: the limits at 0.2, 0.3 and 0.5 s, each bisected to
    the default tolerance, fall (the issue's monotonicity test)."""
    speeds = []
    for tau in (0.2, 0.3, 0.5):
        lim = _ej_limit(tau)
        _check_kept_runs(lim)
        speeds.append(lim.speed_m_s)
    assert speeds[0] > speeds[1] > speeds[2]


def test_a_stable_chair_is_kept_everywhere():
    """The front-caster chair is directionally stable at every speed: the lane is kept up to the last speed
    tried, reported as the bound ``>``."""
    lim = lane_limit(chair_mod.preset("ej-premier-front-caster"), Driver(0.3), speeds=(0.5, 1.5, 3.0))
    assert lim.side == ">" and lim.speed_m_s == 3.0
    assert math.isfinite(lim.runs[-1].peak_offset_m)


def test_bad_speed_grid_is_refused():
    with pytest.raises(ValueError, match="speeds="):
        lane_limit(EJ, Driver(0.3), speeds=(1.0, 0.5))


def test_a_gentle_driver_is_trapped_by_the_stuck_casters_and_a_firmer_one_is_not():
    """E&J Premier at 1 m/s, tau 0.3 s: the most stable linear gains (stable linear loop, abscissa < 0) cannot
    break the friction-held casters loose in time, and the chair weaves out of the lane; the same driver pushing
    harder (the family's larger gains) keeps it.  Regression values for the peaks (1.03 m and 0.14 m today): the
    assertion is the side of the lane each run ends on."""
    g = lane_gains(EJ, 1.0, Driver(0.3))
    assert g.abscissa_1_s < 0
    gentle = lane_run(EJ, 1.0, Driver(0.3), gains=g)
    best = lane_run(EJ, 1.0, Driver(0.3))
    assert not gentle.kept and gentle.peak_offset_m > LANE_HALF_WIDTH_M
    assert best.kept and best.gains.kp_N_m_per_rad > g.kp_N_m_per_rad


def test_a_chair_that_spins_round_within_the_lanes_width_has_not_kept_it():
    """E&J Premier, 0.5 s driver at 2 m/s with four times the lane operator's gains (whose loop is unstable, worst
    abscissa +1.76 1/s today): the chair turns past 90 deg, so it no longer advances along the line, while its offset
    stays within the lane's half width; the run does not keep the lane."""
    from dataclasses import replace

    d = Driver(0.5)
    g = lane_gains(EJ, 2.0, d)
    assert g.abscissa_1_s > 0
    r = lane_run(EJ, 2.0, d, gains=replace(g, ky_N_m_per_m=4 * g.ky_N_m_per_m, kp_N_m_per_rad=4 * g.kp_N_m_per_rad,
                                           kd_N_m_s_per_rad=4 * g.kd_N_m_s_per_rad))
    assert r.peak_heading_deg > 90 and r.peak_offset_m <= LANE_HALF_WIDTH_M and not r.stop_reason
    assert not r.kept


def _by_push(rng: LaneRange) -> list[LaneLimit]:
    by = sorted((rng.nominal, *rng.others), key=lambda x: x.push_N_s)
    assert [x.push_N_s for x in by] == pytest.approx([2.0, 4.0, 8.0], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    return by


def test_a_harder_push_never_lets_the_driver_go_faster():
    """The lane limit over half, once and twice the reference push (the range ``critical_speed`` prints): more
    disturbance is not easier, so the limit does not rise with the push.  E&J Premier, 0.5 s driver: the robust
    operator (``lane_gains``'s default) holds it; the notch operator (``spread=0``) failed it, 0.38 m/s after 2 N s
    against 1.01 m/s after 4 N s.  Error model: each limit is resolved to the bisection's tolerance (the last kept
    speed, within ``tol`` below the first failure), so two limits are ordered to within ``tol``."""
    from stability.study.lane import LANE_SPEED_TOL_M_S, lane_text

    tol = LANE_SPEED_TOL_M_S                              # lane_limit's default bisection tolerance
    rng = _ej_range(0.5)
    by = _by_push(rng)
    assert by[0].speed_m_s >= by[1].speed_m_s - tol and by[1].speed_m_s >= by[2].speed_m_s - tol
    assert rng.low_m_s == by[2].speed_m_s and rng.high_m_s == by[0].speed_m_s
    assert "after 2 N s" in lane_text(rng) and "after 8 N s" in lane_text(rng)


def _stuck_stretches(t: np.ndarray, held: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges ``[i, j]`` (inclusive) of the runs of ``held`` samples."""
    edges = np.flatnonzero(np.diff(np.concatenate(([0], held.astype(int), [0]))))
    return [(int(i), int(j) - 1) for i, j in zip(edges[::2], edges[1::2], strict=True)]


@pytest.mark.slow      # four more runs of the lane operator (about 4 s); the mechanism behind the push's order
def test_a_small_push_leaves_the_casters_stuck_while_the_chair_leaves_the_lane():
    """Why the E&J's lane limit at 0.3 s rises with the push (1.21 m/s after 2 N s, 1.41 after 4 N s: the limit
    does not obey "more disturbance is not easier" here, docs/driver.md, Limits), read from the runs themselves at
    1.3 m/s, between the two limits, with the operator ``lane_run`` chooses.  After the 2 N s push both casters'
    pins hold them (both caster rates exactly zero: the stuck mode) over a stretch of at least 2 s within which
    the chair drifts from inside the lane to beyond its half width: the driver's correction never breaks them
    loose.  After the 4 N s push the casters swing: no stretch with both held lasts 0.5 s, and the chair keeps the
    lane.  (Observed: held from 0.94 s to the end, 7.8 s, the offset 0.006 -> 0.60 m; after 4 N s the longest
    held stretch is 0.03 s and the peak offset 0.30 m.)"""
    from stability.study.lane import _lane_simulation

    d, speed = Driver(0.3), 1.3
    base = RunSpec()
    runs = {}
    for factor in (0.5, 1.0):
        spec = base.replace(push_force=factor * base.push_force)
        r = lane_run(EJ, speed, d, spec)
        res = _lane_simulation(EJ, speed, d, spec, r.gains)[0]
        t = np.asarray(res.t)
        held = (np.asarray(res.eta_dot) == 0.0) & (np.asarray(res.beta_dot) == 0.0) & (t > spec.push_duration)
        y = np.abs(np.asarray(res.y) - float(res.y[0]))
        runs[r.push_N_s] = (r, t, held, y)
    assert sorted(runs) == pytest.approx([2.0, 4.0], rel=1e-12)  # rounding: equivalent arithmetic (observed 0)
    r, t, held, y = runs[min(runs)]
    assert not r.kept
    exits = [(i, j) for i, j in _stuck_stretches(t, held)
             if t[j] - t[i] >= 2.0 and y[i] < LANE_HALF_WIDTH_M < y[j]]
    assert exits                                       # held throughout while the chair leaves the lane
    r, t, held, y = runs[max(runs)]
    assert r.kept
    assert all(t[j] - t[i] < 0.5 for i, j in _stuck_stretches(t, held))
