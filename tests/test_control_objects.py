"""python-control objects that behave: named signals, finite DC gain, dt given once, usable with bode_plot,
step_response and margin (what a controls engineer does first)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

control = pytest.importorskip("control")

from stability import assist, preset  # noqa: E402
from stability.settings import defaults  # noqa: E402


@pytest.fixture(scope="module")
def design():
    return assist.design(preset("power-fwd"), 1.0, "gyro", gyro=assist.GyroSensor(sample_rate_hz=100.0))


def test_closed_loop_defaults_are_the_command_lines_and_behave(design):
    """Defaults: bias estimate (1 s) and the 200 ms reference model, as python -m stability.assist. DC gain from
    r_cmd to r is exactly 1 (integral action; final-value theorem) and finite everywhere; the step does not
    overshoot (first-order reference model into a loop with integral action; the CLI reports 0 %)."""
    sys = assist.closed_loop(design)
    assert sys.input_labels == ["r_cmd", "bias", "Fy"] and sys.output_labels == ["r", "Mz", "e"]
    assert "r_ref" in sys.state_labels and "b_hat" in sys.state_labels and "r" in sys.state_labels
    assert sys.name == "gyro_closed_loop_U1"
    G = np.asarray(control.dcgain(sys))
    assert np.all(np.isfinite(G))
    # DC gain r_cmd -> r: 1 up to the solve's rounding (cond(A) ~ 1e6 times eps, margin x100)
    assert G[0, 0] == pytest.approx(1.0, abs=1e-7)
    assert G[0, 1] == pytest.approx(0.0, abs=1e-7)      # the bias estimate removes a constant gyro bias
    t = np.linspace(0.0, 5.0, 2001)
    r = control.step_response(sys, T=t, input=0, output=0).outputs
    assert r.max() <= 1.0 + 1e-6 and r[-1] == pytest.approx(1.0, abs=2e-3)
    raw = assist.closed_loop(design, command_filter=0.0, bias_time_constant=0.0)
    assert control.step_response(raw, T=t, input=0, output=0).outputs.max() > 1.05   # what the API used to give


def test_bode_and_margin_of_the_loop_transfer(design):
    """The continuous loop L(s) (Design.loop) and the discrete one (dt taken from the design, given once) go into
    bode_plot and margin; the discrete loop is labelled and named, and its dt is the gyro's sample time."""
    import matplotlib

    matplotlib.use("Agg")
    L = design.loop()
    Ld = assist.discrete_loop(design)
    assert Ld.dt == pytest.approx(1 / 100.0, rel=1e-15) and design.sample_time == Ld.dt  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert Ld.input_labels == ["Mz_N_m"] and Ld.output_labels == ["u_N_m"] and Ld.name == "gyro_loop_U1"
    # the continuous loop is named and labelled the same way, its states those of the plant and the estimator
    assert L.input_labels == ["Mz_N_m"] and L.output_labels == ["u_N_m"] and L.name == "gyro_loop_U1"
    assert L.state_labels[:8] == list(design.plant.states) and L.state_labels[8] == "xhat_v"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")        # python-control's own frequency-grid notes
        gm, pm, wcg, wcp = control.margin(L)
        control.bode_plot([L, Ld])
    assert np.isfinite(pm) and 20 < pm < 90
    m = assist.discrete_margins(design)
    assert m.phase_margin_deg < pm and np.isfinite(m.delay_margin_s)   # sampling costs phase


def test_sample_rate_defaults_to_the_table():
    d = assist.design(preset("power-fwd"), 1.0, "gyro")
    assert d.sample_time == pytest.approx(1 / defaults.SAMPLE_RATE_HZ, rel=1e-15)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def _with_delay(L, k):
    """L in series with k extra samples of pure delay (z^-k)."""
    if k == 0:
        return L
    A = np.diag(np.ones(k - 1), -1)
    B = np.eye(k)[:, :1]
    C = np.eye(k)[-1:]
    return control.series(control.ss(A, B, C, 0, L.dt), L)


def _stable(L):
    cl = control.feedback(L, 1)       # negative feedback, as the margins assume
    return np.max(np.abs(np.linalg.eigvals(cl.A))) < 1.0


@pytest.mark.parametrize("rate", [20.0, 200.0])
def test_sampled_delay_margin_is_finite_or_the_loop_is_unstable(rate):
    """At 20 Hz the sampled loop of power-fwd is unstable (a closed-loop pole outside the unit circle): its delay
    margin is 0 and its phase margin negative, where it printed inf next to a positive phase margin. At 200 Hz
    the delay margin is finite and right to the sample: a delay of floor(DM/T) samples keeps the loop stable,
    one of ceil(DM/T) + 1 samples destabilises it (the margin is a continuous delay; whole samples bracket it)."""
    d = assist.design(preset("power-fwd"), 1.0, "gyro", gyro=assist.GyroSensor(sample_rate_hz=rate))
    L = assist.discrete_loop(d)
    m = assist.discrete_margins(d)
    if rate == 20.0:
        assert not _stable(L) and m.delay_margin_s == 0.0 and m.phase_margin_deg < 0
        return
    assert _stable(L) and 0 < m.delay_margin_s < 1.0
    k = m.delay_margin_s / L.dt
    assert _stable(_with_delay(L, int(np.floor(k))))
    assert not _stable(_with_delay(L, int(np.ceil(k)) + 1))
