"""The assist's limits in its default output (issue 33): the safe top speed without fault runs, the export's
warning, disk margins beside the classical ones, the per-wheel gains and the named loop.

Independent statements used here:

* the delay margin of the sampled loop against the stability boundary of the *exact* sampled-data loop with a
  continuous input delay (zero-order hold, the delay's whole samples as a buffer and its fraction by the exact
  discretisation of a delayed held input, Astrom & Wittenmark, "Computer-Controlled Systems", 3rd ed., sec. 2.3),
  found by bisection on the closed loop's spectral radius: no Pade approximation, no frequency response;
* the balanced disk margin against closed forms (``L = 1/(s(s+1))``: alpha = 2/sqrt(5) at 1 rad/s; the discrete
  integrator ``K/(z - 1)``: alpha = 2 (2 - K)/(2 + K) at the Nyquist frequency) and, on the assist's loops, against
  its definition ``min 2|1 + L|/|1 - L|`` evaluated from the loop's own matrices, with the critical gain on the
  disk's edge (Seiler, Packard & Gahinet 2020, "An introduction to disk margins");
* the per-wheel gains against the moment of the two wheels' ground forces (Collins 1987, eq 6-3) and against the
  numbers the command line prints.
"""

from __future__ import annotations

import json
import math
import re

import control
import numpy as np
import pytest
from scipy.linalg import expm
from scipy.optimize import brentq, minimize_scalar

from stability import assist
from stability import chair as chair_mod
from stability.assist import digital, driving, tables
from stability.assist import top_speed as TS
from stability.assist.__main__ import main as assist_main
from stability.assist.design import GAIN_UNITS
from stability.assist.disk import disk_margins
from stability.schemas import bad_keys

#: The default grid, and the part of it around the 100 Hz limit that the default test run checks (every speed
#: below 1.25 m/s holds with more clearance: the slow test runs the whole grid).
SPEEDS = np.arange(0.5, 3.0001, 0.25)
NEAR_LIMIT = np.array([1.25, 1.5, 1.75, 2.0])


@pytest.fixture(scope="module")
def chair():
    return chair_mod.preset("power-fwd")


# ---------------------------------------------------------------------------
# the exact sampled-data loop with a continuous input delay
# ---------------------------------------------------------------------------
def _held_input(A: np.ndarray, B: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray]:
    """``(e^{Ah}, int_0^h e^{As} ds B)`` from one matrix exponential."""
    n = A.shape[0]
    M = np.zeros((n + 1, n + 1))
    M[:n, :n], M[:n, n:] = A, B
    E = expm(M * h)
    return E[:n, :n], E[:n, n:]


def _spectral_radius(d: assist.Design, tau: float) -> float:
    """Spectral radius of the sampled loop (plant, ZOH, the controller of ``discrete_controller``) with an extra
    continuous delay ``tau`` at the plant input.

    ``tau = k T + theta``: the held input reaches the plant ``k`` samples late, and within each sample the
    previous value acts for ``theta`` and the current one for ``T - theta``:
    ``x+ = Phi x + Gamma0 u[n-k] + Gamma1 u[n-k-1]`` with ``Gamma0 = int_0^(T-theta) e^{As} ds B`` and
    ``Gamma1 = e^{A(T-theta)} int_0^theta e^{As} ds B``.
    """
    T = d.sample_time
    idx = d.plant.internal
    A, B = d.plant.A[np.ix_(idx, idx)], d.plant.B[idx]
    C = np.eye(len(idx))[1:2]                                   # the gyro
    K = digital.discrete_controller(d, T)
    Ac, Bc, Cc = (np.asarray(x) for x in (K.A, K.B, K.C))
    k = int(math.floor(tau / T + 1e-12))
    theta = tau - k * T
    Phi, _ = _held_input(A, B, T)
    E1, G0 = _held_input(A, B, T - theta)
    G1 = E1 @ _held_input(A, B, theta)[1]
    n, nc, m = A.shape[0], Ac.shape[0], k + 1
    N = n + nc + m                                              # plant, controller, buffer u[n-1] .. u[n-m]

    def u(j: int) -> np.ndarray:                                # the plant input u[n-j] (= -controller output)
        r = np.zeros(N)
        if j == 0:
            r[n:n + nc] = -Cc[0]
        else:
            r[n + nc + j - 1] = 1.0
        return r

    M = np.zeros((N, N))
    M[:n, :n] = Phi
    M[:n] += np.outer(G0[:, 0], u(k)) + np.outer(G1[:, 0], u(k + 1))
    M[n:n + nc, :n] = Bc @ C
    M[n:n + nc, n:n + nc] = Ac
    for j in range(1, m + 1):
        M[n + nc + j - 1] = u(j - 1)
    return float(np.max(np.abs(np.linalg.eigvals(M))))


def _exact_delay_margin(d: assist.Design, guess: float) -> float:
    """The smallest extra input delay (s) at which the exact sampled-data loop loses stability.

    ``guess`` (e.g. the frequency statement's margin) only places the search: the loop is checked stable at ten
    delays from 0 to 0.9 ``guess`` (a quarter sample apart at most), and the boundary is bracketed in
    [0.9, 1.1] ``guess`` by a sign change of ``rho - 1`` before it is refined."""
    T = d.sample_time
    below = np.linspace(0.0, 0.9 * guess, max(10, int(np.ceil(0.9 * guess / (T / 4))) + 1))
    assert all(_spectral_radius(d, t) < 1.0 for t in below)
    lo, hi = 0.9 * guess, 1.1 * guess
    assert _spectral_radius(d, lo) < 1.0 <= _spectral_radius(d, hi)
    return brentq(lambda t: _spectral_radius(d, t) - 1.0, lo, hi, xtol=1e-12)


def test_exact_loop_at_whole_samples_is_the_sampled_loop_with_pure_delay():
    """The helper's check: with ``tau = k T`` (theta = 0) the exact loop is the sampled loop ``discrete_loop``
    behind ``k`` samples of pure delay ``z^-k``, so the spectral radii of the two closed loops agree (similar
    matrices from the same exponentials; 1e-9 is ~1e6 times the rounding of a 25-state eigenvalue problem)."""
    d = assist.design(chair_mod.preset("power-fwd"), 1.0, "gyro", gyro=assist.GyroSensor(sample_rate_hz=100.0))
    Ld = digital.discrete_loop(d)
    for k in range(5):
        Lk = Ld if k == 0 else control.series(
            control.ss(np.diag(np.ones(k - 1), -1), np.eye(k)[:, :1], np.eye(k)[-1:], 0, Ld.dt), Ld)
        rho = float(np.max(np.abs(np.linalg.eigvals(control.feedback(Lk, 1).A))))
        assert _spectral_radius(d, k * d.sample_time) == pytest.approx(rho, abs=1e-9), k  # rounding: equivalent arithmetic, a few ulp (observed 4.2e-15)


@pytest.mark.parametrize("rate", [100.0, 200.0])
def test_delay_margin_is_the_exact_sampled_data_boundary(chair, rate):
    """pm / w_gc of the sampled loop (what the top speed compares with the loop's delay) is where the exact
    sampled-data loop with a continuous input delay loses stability.  Error model: the frequency statement
    applies ``e^{-jw tau}`` to ``L(e^{jwT})``, exact for whole samples; a fraction theta of a sample reaches the
    plant through the hold as two partial pulses, whose response differs from ``e^{-jw theta}`` at second order
    in ``w T`` (``w_gc T`` <= 0.19 here).  Observed <= 2.3e-4 T (100 Hz) and 3.5e-5 T (200 Hz); tolerance
    0.025 T, about 100 times the larger."""
    for s in (0.5, 1.75, 3.0):
        d = assist.design(chair, s, "gyro", gyro=assist.GyroSensor(sample_rate_hz=rate))
        dm = digital.discrete_margins(d).delay_margin_s
        # error model: the docstring's, second order in w T (observed 1.5e-4 T at most)
        assert _exact_delay_margin(d, dm) == pytest.approx(dm, abs=0.025 * d.sample_time), (rate, s)


@pytest.mark.parametrize("speeds", [NEAR_LIMIT, pytest.param(SPEEDS, marks=pytest.mark.slow)], ids=["near", "all"])
def test_default_top_speed_power_fwd_100_hz(chair, speeds):
    """power-fwd at 100 Hz, the default check (margins and torque, no fault runs): the safe top speed and its limit
    follow from the exact sampled-data boundary alone.  The loop's own delay is 1.5 samples (computation and
    hold) plus the 20 ms motor lag: 35 ms at 100 Hz.  The first design speed whose exact delay boundary is not
    above it is the first above the reported top speed; the limiting constraint meets its limit at the top
    speed and fails at the next design speed; every other constraint holds up to there."""
    sched100 = assist.schedule(chair, speeds, "gyro", gyro=assist.GyroSensor(sample_rate_hz=100.0))
    rows100 = tables.gain_table(sched100, check=False)
    torque = driving.torque_requirement(sched100, tuple(float(s) for s in sched100.speeds))
    ts = TS.check_top_speed(sched100, rows100, torque_rows=torque)
    assert ts.checked == ("gain_margin", "phase_margin", "delay_margin", "torque")
    own = 1.5 / 100.0 + sched100.drive.motor_time_constant
    assert TS.loop_delay(sched100) == pytest.approx(own, rel=1e-15) and own == pytest.approx(0.035, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    exact = [_exact_delay_margin(d, r.margin_pair.discrete.delay_margin_s) for d, r in zip(sched100.designs, rows100,
                                                                                             strict=True)]
    first_bad = next(i for i, x in enumerate(exact) if x <= own)
    assert first_bad > 0
    assert ts.safe_top_speed_m_s == pytest.approx(speeds[first_bad - 1], rel=1e-12) and ts.limited_by == "delay_margin"  # rounding: equivalent arithmetic, a few ulp (observed 0)
    [lim] = ts.limits()
    assert (lim.constraint, lim.speed_m_s, lim.unit) == ("delay_margin", pytest.approx(speeds[first_bad], rel=1e-12), "ms")  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert lim.limit == pytest.approx(1e3 * own, rel=1e-12) and lim.value < lim.limit  # rounding: equivalent arithmetic, a few ulp (observed 0)
    at_top = ts.checks[first_bad - 1].values["delay_margin"]
    assert at_top[2] and at_top[0] > at_top[1]
    # the exact boundary is on the same side of 35 ms as the reported margin at both speeds (clearance 0.7 and
    # 0.18 ms, against the 0.25 ms agreement of the test above: decided by the exact computation itself)
    assert exact[first_bad - 1] > own > exact[first_bad]
    for c in ts.checks[:first_bad + 1]:
        assert all(c.values[k][2] for k in ("gain_margin", "phase_margin", "torque")), c
    text = TS.format_top_speed(ts)
    assert text.splitlines()[-1] == (
        f"Safe top speed {speeds[first_bad - 1]:g} m/s: at {speeds[first_bad]:g} m/s the sampled delay margin is "
        f"{lim.value:.3g} ms, not above the loop's own delay of 35 ms (not checked: the single sensor faults "
        "(add --faults)).")


def test_margin_top_speed_at_200_hz_holds_on_the_whole_grid(chair):
    """At 200 Hz the loop's own delay is 27.5 ms and the exact boundary is above it at 1 and 3 m/s: the margins
    limit nothing on the default grid (``design_grid``), and the export of that schedule carries no warning."""
    sched = assist.schedule(chair, [1.0, 3.0], "gyro")
    ts = TS.margin_top_speed(sched)
    assert ts.checked == ("gain_margin", "phase_margin", "delay_margin")
    exact = [_exact_delay_margin(d, c.values["delay_margin"][0] / 1e3) for d, c in zip(sched.designs, ts.checks,
                                                                                        strict=True)]
    assert min(exact) > TS.loop_delay(sched) == pytest.approx(0.0275, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert ts.safe_top_speed_m_s == 3.0 and ts.limited_by == "design_grid" and ts.warning() is None
    assert ts.limits() == [] and "every checked constraint holds up to the last design speed 3 m/s" in ts.sentence()


# ---------------------------------------------------------------------------
# the export's warning
# ---------------------------------------------------------------------------
def test_export_warns_beyond_the_safe_top_speed(tmp_path, capsys):
    """--export-c of a 100 Hz schedule to 1.75 m/s: one warning line on stderr naming the delay margin against
    the loop's own delay, the same warning first in README.txt and in the JSON; the files are written."""
    out, js = tmp_path / "fw", tmp_path / "a.json"
    argv = ["--speeds", "1.5,1.75", "--sample-rate", "100", "--no-check", "--export-c", str(out),
            "--json-file", str(js)]
    assert assist_main(argv) == 0
    cap = capsys.readouterr()
    warn = [x for x in cap.err.splitlines() if x.startswith("warning:")]
    assert len(warn) == 1
    m = re.fullmatch(r"warning: --export-c: the exported schedule runs to 1\.75 m/s, beyond the safe top speed "
                     r"1\.5 m/s: at 1\.75 m/s the sampled delay margin is ([0-9.]+) ms, not above the loop's own "
                     r"delay of 35 ms \(not checked: the torque \(run without --no-check\), the single sensor "
                     r"faults \(add --faults\)\)", warn[0])
    assert m, warn[0]
    d = assist.design(chair_mod.preset("power-fwd"), 1.75, "gyro", gyro=assist.GyroSensor(sample_rate_hz=100.0))
    # error model: rounding of the printed 3 significant digits (34.8 ms: half a unit, 0.05 ms; observed 0.0195)
    assert float(m.group(1)) == pytest.approx(1e3 * digital.discrete_margins(d).delay_margin_s, abs=0.05)
    readme = (out / "README.txt").read_text()
    assert readme.splitlines()[2].startswith("WARNING: " + warn[0].split("--export-c: ", 1)[1])
    assert sorted(p.name for p in out.iterdir()) == ["README.txt", "assist.c", "assist.h", "assist_vectors.json"]
    data = json.loads(js.read_text())
    assert data["firmware"]["warning"] == warn[0].split("--export-c: ", 1)[1]
    assert data["safe_top_speed_m_s"] == 1.5 and data["limited_by"] == "delay_margin"
    # rounding: 1e3 (1.5 T + motor lag), a few ulp (observed 0)
    assert data["top_speed_limits"][0]["constraint"] == "delay_margin" and data["top_speed_limits"][0]["limit"] == \
        pytest.approx(35.0, rel=1e-12)
    lines = cap.out.splitlines()
    assert any(x.startswith("  WARNING (also in README.txt): the exported schedule runs to 1.75 m/s") for x in lines)
    assert lines[-2].startswith("Safe top speed 1.5 m/s: at 1.75 m/s the sampled delay margin") and \
        lines[-1].startswith("wrote ")
    assert bad_keys(data) == []


# ---------------------------------------------------------------------------
# disk margins
# ---------------------------------------------------------------------------
def test_disk_margin_closed_forms():
    """Balanced disk margin (python-control, worst frequency refined) against closed forms.

    ``L = 1/(s(s+1))``: ``|1+L|^2/|1-L|^2 = (x^2 - x + 1)/(x^2 + 3x + 1)`` with ``x = w^2``, least at x = 1, so
    alpha = 2/sqrt(5) at 1 rad/s, gain margin ``(3 + sqrt 5)/2`` (8.36 dB), phase ``2 atan(1/sqrt 5)``.  Error
    model: the minimum is refined on 401 points between the grid's neighbours (spacing 2e-5 relative), so alpha
    is off by the square of that (< 1e-9; observed 3.6e-11); tolerance 1e-8.  The frequency is found to the
    refinement's bracket, 2e-5 relative (observed 4.7e-6); tolerance 1e-4.

    Discrete integrator ``K/(z - 1)``: ``alpha(w) = 2 |z - 1 + K| / |z - 1 - K|`` grows with ``cos(wT)``, least at
    the Nyquist frequency: ``alpha = 2 (2 - K)/(2 + K)``; the grid ends 1e-9 short of it, where the slope is 0."""
    L = control.ss(control.tf([1.0], [1.0, 1.0, 0.0]))
    dk = disk_margins(L, np.geomspace(1e-3, 1e4, 2000))
    r5 = math.sqrt(5.0)
    # error model: second order in the refinement's spacing (docstring; observed 3.6e-11, 4.2e-11, 3.2e-11)
    assert dk.alpha == pytest.approx(2 / r5, rel=1e-8)
    assert dk.gain_db == pytest.approx(20 * math.log10((3 + r5) / 2), rel=1e-8)
    assert dk.phase_deg == pytest.approx(math.degrees(2 * math.atan(1 / r5)), rel=1e-8)
    assert dk.frequency_rad_s == pytest.approx(1.0, rel=1e-4)     # the refinement's bracket (docstring)
    T = 0.01
    for K in (0.5, 1.0, 1.5):
        dk = disk_margins(control.ss(control.tf([K], [1.0, -1.0], T)), np.geomspace(1e-3, math.pi / T * (1 - 1e-9),
                                                                                     2000))
        assert dk.alpha == pytest.approx(2 * (2 - K) / (2 + K), rel=1e-9), K  # rounding: equivalent arithmetic, a few ulp (observed 1.9e-16)


@pytest.mark.parametrize("rate", [100.0, 200.0])
def test_the_batched_response_and_disk_margin_are_python_controls(chair, rate):
    """``frequency_response`` (all frequencies in one batched solve) against python-control's state-space
    ``__call__`` (one solve per frequency), and the disk margin per frequency against :func:`control.disk_margins`
    (skew 0), on the continuous and the sampled assist loops.  Error model: the same LU factorisations, summed in
    another order: a few ulp of |L| (observed 6.4e-16 relative) and of alpha (observed 7.3e-15); tolerances 1e-13
    and 1e-12."""
    from stability.assist.disk import frequency_response

    d = assist.design(chair, 2.0, "gyro", gyro=assist.GyroSensor(sample_rate_hz=rate))
    for L in (d.loop(), digital.discrete_loop(d)):
        T = float(L.dt)
        w = np.geomspace(1e-3, math.pi / T * (1 - 1e-9) if T else 1e4, 500)
        ours = frequency_response(L, w)
        theirs = np.asarray(L(np.exp(1j * w * T) if T else 1j * w)).reshape(-1)
        # error model: the same LU factorisations summed in another order, a few ulp (observed 6.4e-16); 100x+
        assert np.max(np.abs(ours - theirs) / np.abs(theirs)) < 1e-13
        alpha = np.asarray(control.disk_margins(L, w, skew=0.0, returnall=True)[0], dtype=float)
        # error model: those ulp through |1 + L| / |1 - L| near the worst frequency (observed 7.3e-15); 100x+
        assert np.max(np.abs(2 * np.abs(1 + ours) / np.abs(1 - ours) - alpha) / alpha) < 1e-12
        assert disk_margins(L, w).alpha <= alpha.min() * (1 + 1e-12)     # the refinement only lowers the grid's


@pytest.mark.parametrize("rate", [100.0, 200.0])
def test_disk_margins_of_the_assist_loops(chair, rate):
    """On the sampled loop (and the continuous one): alpha equals ``min 2|1 + L|/|1 - L|`` evaluated from the
    loop's own state-space matrices (resolvent, dense grid then bounded minimisation: the two minimisations agree
    to second order in their brackets, observed 5.2e-11 relative, tolerance 1e-8); the critical gain ``f = -1/L`` at the worst frequency lies on the disk's
    edge ``|2 (f - 1)/(f + 1)| = alpha``; and the disk's gain and phase are inside the classical margins (the
    disk contains the real-gain and unit-circle perturbations the classical margins take one at a time)."""
    d = assist.design(chair, 2.0, "gyro", gyro=assist.GyroSensor(sample_rate_hz=rate))
    for L, m, T in ((digital.discrete_loop(d), digital.discrete_margins(d), d.sample_time),
                    (d.loop(), assist.loop_margins(d), 0.0)):
        A, B, C = np.asarray(L.A), np.asarray(L.B)[:, 0], np.asarray(L.C)[0]
        n = A.shape[0]

        def resp(w: float, A=A, B=B, C=C, n=n, T=T) -> complex:
            z = np.exp(1j * w * T) if T else 1j * w
            return complex(C @ np.linalg.solve(z * np.eye(n) - A, B))

        def alpha(w: float, resp=resp) -> float:
            Lw = resp(w)
            return 2 * abs(1 + Lw) / abs(1 - Lw)

        top = math.pi / T * (1 - 1e-9) if T else 1e4
        w = np.geomspace(1e-3, top, 4000)
        a = np.array([alpha(x) for x in w])
        i = int(np.argmin(a))
        best = minimize_scalar(alpha, bounds=(w[max(i - 1, 0)], w[min(i + 1, len(w) - 1)]), method="bounded",
                               options={"xatol": 1e-10 * w[i]})
        # error model: second order in each minimisation's bracket (docstring; observed 5.2e-11)
        assert m.disk_margin == pytest.approx(best.fun, rel=1e-8)
        f = -1.0 / resp(m.disk_frequency_rad_s)
        assert abs(2 * (f - 1) / (f + 1)) == pytest.approx(m.disk_margin, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 4.3e-16)
        gm_classical = min(20 * math.log10(m.gain_margin_upper), -20 * math.log10(m.gain_margin_lower))
        assert m.disk_gain_margin_db <= gm_classical + 1e-9
        assert m.disk_phase_margin_deg <= m.phase_margin_deg + 1e-6
        assert m.disk_phase_margin_deg == pytest.approx(math.degrees(2 * math.atan(m.disk_margin / 2)), rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 5.1e-16)


# ---------------------------------------------------------------------------
# per-wheel gains and the named loop
# ---------------------------------------------------------------------------
def test_per_wheel_gains_are_the_command_lines_and_make_the_yaw_moment(chair, tmp_path, capsys):
    """``Design.wheel_torque_gains``: (1) the state feedback ``tau = -k x`` per wheel, applied as the ground
    forces ``F_left = tau / r`` forward at ``d1`` to the left and ``F_right = -tau / r`` at ``d2`` to the right
    (``DriveTrain.wheel_forces``), has the moment ``F_left d1 - F_right d2`` about the c.g. (Collins 1987,
    eq 6-3), which is the design's yaw moment ``-K x`` for every state; (2) the numbers equal the command
    line's gain table (printed to 4 significant digits) and its JSON's ``wheel_torque_gains``; (3) the yaw
    moment per wheel torque is the preset's (d1 + d2)/r = 0.55/0.178."""
    assert assist_main(["--speeds", "1,2", "--no-check", "--json-file", str(tmp_path / "a.json")]) == 0
    data = json.loads((tmp_path / "a.json").read_text())
    text = capsys.readouterr().out
    drive = chair_mod.power.drive_train()
    for row in data["rows"]:
        d = assist.design(chair, row["speed_m_s"], "gyro")
        assert d.yaw_moment_per_wheel_torque == pytest.approx((chair.d1 + chair.d2) / drive.wheel_radius,
                                                              rel=1e-15)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        assert (chair.d1 + chair.d2, drive.wheel_radius) == (pytest.approx(0.55, rel=1e-12), 0.178)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        k = d.wheel_torque_gains[0]
        for j in range(d.plant.n):
            x = np.eye(d.plant.n)[j]
            tau = -float(k @ x)
            f_left, f_right = drive.wheel_forces(chair, tau)
            assert f_left * chair.d1 - f_right * chair.d2 == pytest.approx(-float(d.K[0] @ x), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.9e-16)
        assert row["wheel_torque_gains"] == pytest.approx(list(k), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.0e-16)
        assert row["gains"] == pytest.approx(list(d.K[0]), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        line = next(x for x in text.splitlines() if x.startswith(f"{row['speed_m_s']:5.2f} ") and "|" in x)
        printed = [float(v) for v in line.split("|")[0].split()[1:]]
        assert printed == pytest.approx(list(k), rel=5e-4)   # rounding to %8.4g: half a unit in the 4th digit
        assert d.gains_dict(per_wheel=True) == pytest.approx(dict(zip(d.plant.states, k, strict=True)), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert set(GAIN_UNITS) == set(assist.design(chair, 1.0).plant.states)


def test_scheduled_design_between_grid_speeds_has_the_drive(chair):
    """A design interpolated by the schedule keeps the drive's geometry, so its per-wheel gains are its own K
    converted (and the full-state design too)."""
    for kind in assist.DESIGNS:
        sched = assist.schedule(chair, [1.0, 2.0], kind)
        d = sched.at(1.5)
        assert d.track_width == pytest.approx(0.55, rel=1e-12) and d.wheel_radius == 0.178  # rounding: equivalent arithmetic, a few ulp (observed 0)
        assert d.wheel_torque_gains == pytest.approx(d.K * 0.178 / 0.55, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.4e-16)


# ---------------------------------------------------------------------------
# the key convention of the checked output
# ---------------------------------------------------------------------------
def test_recovery_rows_follow_the_key_convention(chair):
    """The recovery pairs (what ``--no-check`` leaves out of the schema case) carry ``peak_torque_N_m``, not
    ``peak_torque_Nm``."""
    sched = assist.schedule(chair, [1.0], "gyro")
    pair = assist.recovery_runs(sched, speeds=(1.0,), impulses=(40.0,), duration=1.0)[0].to_dict()
    assert "peak_torque_N_m" in pair["closed"] and "peak_torque_N_m" in pair["open"]
    assert bad_keys(pair) == []
