"""The motor assist of any wheel layout, forward and in reverse (stability.assist.layout).

Independent statements used:

- wiring: the power chair as a layout gives the short form's LQR gains (:func:`stability.assist.design.design`, on
  the thesis model's linear matrices) to rounding;
- reverse: a layout driving backwards (casters trailing at 180 deg) is the same chair turned round, driving
  forwards: its body axes turned by 180 deg about z and its reference point moved to the c.g. with the casters
  swung round (parallel-axis theorem).  The eigenvalues agree, and the LQR gains map by the change of state
  ``v' = -(v + dx r)`` (the other states unchanged), the heading weight being the only one;
- Bryson's LQR on the heading alone gives the heading gain ``sqrt(Q_psi / R) = Mz_max / psi_max`` whatever the
  plant (the return-difference identity at zero frequency, where the heading's integrator dominates: the chair's
  own yaw-rate response to a steady yaw moment is finite and nonzero);
- the separation principle: the gyro design's closed-loop eigenvalues are those of the state feedback and of
  the estimator.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from stability.assist.__main__ import main
from stability.assist.design import closed_loop_poles, design
from stability.assist.layout import drive_lever, layout_assist, layout_design
from stability.assist.weights import DEFAULT_WEIGHTS
from stability.chair import preset
from stability.chair.power import DriveTrain
from stability.layout import Layout
from stability.layout.linear import state_matrices
from stability.layout.presets import layout_preset


@pytest.mark.parametrize("speed", [0.5, 1.5, 3.0])
def test_the_power_chair_as_a_layout_has_the_short_forms_gains(speed):
    """The same plant from another derivation (the layout's Kane equations against the thesis model's) and the
    same Riccati solver: observed 2e-12 of the largest gain; asserted 1e-9 (margin 500)."""
    c = preset("power-fwd")
    short, lay = design(c, speed, "full-state"), layout_design(Layout.from_chair(c), speed, "full-state")
    assert np.abs(lay.K - short.K).max() <= 1e-9 * np.abs(short.K).max()   # error model: docstring's (rounding)


def _turned(layout: Layout) -> Layout:
    """The layout seen from behind with its casters swung round: trailing forwards in the new frame."""
    dx = sum(2.0 * c.m_c * c.l for c in layout.casters) / layout.m       # the c.g. moves with the casters' mass
    i_z = (layout.i_z + sum(c.m_c * ((c.x + c.l) ** 2 - (c.x - c.l) ** 2) for c in layout.casters)
           - layout.m * dx ** 2)
    return dataclasses.replace(
        layout, name=f"{layout.name} turned", i_z=i_z,
        wheels=tuple(dataclasses.replace(w, x=-(w.x - dx), y=-w.y) for w in layout.wheels),
        casters=tuple(dataclasses.replace(c, x=-(c.x - dx), y=-c.y) for c in layout.casters))


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base"])
@pytest.mark.parametrize("speed", [0.5, 2.0])
def test_reversing_is_driving_the_turned_chair_forwards(name, speed):
    """Eigenvalues: the same physics in other coordinates, observed 2e-15 of the largest (up to 1250 1/s);
    asserted 1e-9 of it.  Gains: ``K_reverse = K_turned T``, observed 7e-12 of the largest; asserted
    1e-8 (the Riccati solution's conditioning on these plants, margin 1000)."""
    layout = layout_preset(name)
    turned = _turned(layout)
    a = np.sort_complex(np.linalg.eigvals(state_matrices(layout, [-speed])[0]))
    b = np.sort_complex(np.linalg.eigvals(state_matrices(turned, [speed])[0]))
    assert np.abs(a - b).max() <= 1e-9 * np.abs(a).max()        # error model: docstring's (eigenvalue rounding)
    rev, fwd = layout_design(layout, -speed, "full-state"), layout_design(turned, speed, "full-state")
    dx = sum(2.0 * c.m_c * c.l for c in layout.casters) / layout.m
    T = np.eye(rev.K.shape[1])
    T[0, 0], T[0, 1] = -1.0, -dx
    # error model: docstring's (the Riccati solution's conditioning: 7e-12 observed, margin 1000)
    assert np.abs(rev.K - fwd.K @ T).max() <= 1e-8 * np.abs(rev.K).max()


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base", "power-rwd-base"])
@pytest.mark.parametrize("speed", [-2.0, -0.5, 0.5, 2.0])
def test_the_heading_gain_is_brysons_ratio_and_the_loop_separates(name, speed):
    """Heading gain ``Mz_max / psi_max`` (N m/rad of yaw moment): observed 2e-12 relative; asserted 1e-9 (margin
    500).  Separation: observed 7e-13 of the largest eigenvalue; asserted 1e-8 (the eigenvalue solver on up to a
    23-state matrix)."""
    layout = layout_preset(name)
    drive = DriveTrain()
    d = layout_design(layout, speed, "gyro")
    mz_max = DEFAULT_WEIGHTS.budget(drive) * drive_lever(layout) / drive.wheel_radius
    k_psi = mz_max / math.radians(DEFAULT_WEIGHTS.max_heading_error_deg)
    # error model: the heading gain is sqrt(Q/R) exactly; the Riccati solve's rounding (observed 7.0e-13), margin 140
    assert d.gains_dict()["psi"] == pytest.approx(k_psi, rel=1e-10)
    p = d.plant
    C = np.zeros((1, p.psi))
    C[0, 1] = 1.0
    assert d.L is not None
    expected = np.concatenate([np.linalg.eigvals(p.A - p.B @ d.K),
                               np.linalg.eigvals(p.A[:p.psi, :p.psi] - d.L @ C)])
    motor = [p.n - 1] if p.has_motor else []
    if motor:      # the estimator models the motor state too: its own mode, -1/tau, is the third set
        expected = np.concatenate([expected, [p.A[motor[0], motor[0]]]])
    got = np.sort_complex(closed_loop_poles(d))
    want = np.sort_complex(expected)
    assert got.shape == want.shape
    # error model: eigenvalue rounding of the closed-loop matrices, n eps ||A|| kappa with the loops' kappa (the
    # separation principle is exact)
    assert np.abs(got - want).max() <= 1e-8 * np.abs(want).max()
    assert got.real.max() < 0


def _command_matches_api(name: str, speeds: list[float], capsys) -> None:
    assert main(["--chair", name, "--speeds", ",".join(map(str, speeds)), "--reverse", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert [r["speed_m_s"] for r in d["forward"]] == speeds
    assert [r["speed_m_s"] for r in d["reverse"]] == [-u for u in speeds]
    direct = layout_assist(layout_preset(name), speeds, reverse=True)
    assert direct.forward_top is not None
    assert d["forward_top_speed"]["safe_top_speed_m_s"] == direct.forward_top.safe_top_speed_m_s
    assert d["reverse"][0]["wheel_torque_gains"]["r"] == direct.reverse[0].wheel_torque_gains["r"]


def test_the_assist_command_answers_a_layout_and_reverse(capsys, shared_run):
    """The command's gains are the design's: the heading gain per wheel is Bryson's ratio (1e-9 as above).  The
    --json run is shared with test_assist_layout_commands (tests/conftest.py's shared_run)."""
    status, out, _ = shared_run("assist", ["--chair", "mid-wheel-drive", "--speeds", "1", "--reverse", "--json"])
    assert status == 0
    d = json.loads(out)
    drive = DriveTrain()
    per_wheel = (DEFAULT_WEIGHTS.budget(drive) / math.radians(DEFAULT_WEIGHTS.max_heading_error_deg))
    for rows in (d["forward"], d["reverse"]):
        assert rows[0]["wheel_torque_gains"]["psi"] == pytest.approx(per_wheel, rel=1e-11)  # Riccati rounding (observed 9.7e-14), margin 100
        assert rows[0]["closed_loop_growth_rate_1_s"] < 0
    assert [r["speed_m_s"] for r in d["reverse"]] == [-1.0]
    assert d["forward_top_speed"]["constraints_checked"] == ["gain_margin", "phase_margin", "delay_margin", "torque"]
    assert main(["--chair", "power-fwd", "--speeds=-1", "--design", "full-state"]) == 0
    out = capsys.readouterr().out
    assert "power-fwd: motor assist (full-state design)" in out and "reverse: safe top speed" in out


@pytest.mark.slow
@pytest.mark.parametrize("name", ["power-fwd-base", "power-rwd-base"])
def test_the_assist_command_answers_every_drive_layout(name, capsys):
    _command_matches_api(name, [0.5, 1.5], capsys)


@pytest.mark.parametrize("argv,words", [
    (["--chair", "mid-wheel-drive", "--faults", "--design", "full-state"], "--faults needs --design gyro"),
    (["--chair", "mid-wheel-drive", "--set", "trail=0.06"], "'trail' is not a field of layout"),
    (["--chair", "mid-wheel-drive", "--speeds", "0,1"], "--speeds '0,1' is invalid"),
    (["--chair", "mid-wheel-drive", "--model", "thesis"], "--model thesis is invalid for a layout"),
    (["--chair", "mid-wheel-drive", "--speeds", "1,25"], "--speeds '1,25' is invalid for a layout"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
