"""The torque constraint of a layout's safe top speed (stability.assist.layout, issue 38).

Independent statements used:

- the short form's chairs (the E&J Premier and the power chair) expanded as layouts need the short form's torques:
  the layout simulator's peaks per wheel for the reference push, the reference turn and the full joystick turn
  (the same sampled controller as the yaw-moment hook) equal the short form's WCHAIR-scheme runs
  (:func:`stability.assist.driving.torque_requirement`, :func:`stability.assist.top_speed.full_turn_peaks`);
- the rule of the top speed, counted here by hand: with the gains held (a fixed torque budget), a design speed
  whose unsaturated need (a run with an ample motor limit) exceeds the motor limit fails the torque constraint
  (the saturated loop reaches the limit there), one whose need is below it holds, and the safe top speed is the
  last design speed before the first failure.
"""

from __future__ import annotations

import json

import pytest
from slow_cases import one_default

from stability.assist.__main__ import main
from stability.assist.driving import torque_requirement
from stability.assist.layout import layout_assist, layout_schedule
from stability.assist.schedule import schedule
from stability.assist.top_speed import full_turn_peaks
from stability.assist.weights import Weights
from stability.chair import preset
from stability.chair.power import DriveTrain
from stability.layout import Layout
from stability.layout.presets import layout_preset


@pytest.mark.parametrize("name", one_default(["ej-premier", "power-fwd"], "ej-premier"))
@pytest.mark.parametrize("kind", ["gyro", "full-state"])
def test_the_short_forms_chairs_as_layouts_need_the_short_forms_torques(name, kind):
    """The push, the reference turn, its steady torque and the full joystick turn: same equations (another
    derivation), same step, same sampled controller: observed 6e-13 relative at most; asserted 1e-10 (margin 150,
    floating-point rounding over the 3000 steps).  The traction limits: the same static loads, two statics;
    observed 1e-16, asserted 1e-12."""
    chair = preset(name)
    speeds = (1.0, 2.0)
    short = schedule(chair, speeds, kind, standstill=False)
    mine = layout_schedule(Layout.from_chair(chair), speeds, kind)
    a, b = torque_requirement(short, speeds), torque_requirement(mine, speeds)
    fa, fb = full_turn_peaks(short, speeds), full_turn_peaks(mine, speeds)
    for x, y in zip(a, b, strict=True):
        assert y.speed_m_s == x.speed_m_s and y.motor_limit_N_m == x.motor_limit_N_m
        for key in ("push_peak_N_m", "push_rms_N_m", "turn_peak_N_m", "turn_rms_N_m", "steady_turn_N_m"):
            assert getattr(y, key) == pytest.approx(getattr(x, key), rel=1e-10)   # rounding (docstring)
        assert y.traction_limit_N_m == pytest.approx(x.traction_limit_N_m, rel=1e-12)   # statics' rounding
        assert fb[y.speed_m_s] == pytest.approx(fa[x.speed_m_s], rel=1e-10)            # rounding (docstring)
        assert 0.0 < x.push_peak_N_m < x.turn_peak_N_m <= fa[x.speed_m_s]              # the turns need more


def test_a_torque_limit_below_the_needed_peak_sets_the_top_speed():
    """power-fwd-base forward, the gains held (a 35 N m torque budget): the torque it needs (the largest of the push's, the reference turn's and the full
    joystick turn's peaks, with an ample motor limit) falls from 0.5 to 1.5 m/s (the reference turn's rate falls
    as 1/U); a motor limit between the needs at 1 and 1.5 m/s fails the torque constraint at 0.5 and 1 m/s (the
    limit reached there: saturated) and holds it at 1.5 m/s (the run never reaches the limit: the ample run's
    need), so no design speed is safe (the rule: every speed below must hold too); a limit above every need leaves
    every speed's torque within it."""
    lay, w, speeds = layout_preset("power-fwd-base"), Weights(torque_budget_nm=35.0), (0.5, 1.0, 1.5)
    ample = DriveTrain(torque_limit=1000.0)
    sched = layout_schedule(lay, speeds, weights=w, drive=ample)
    full = full_turn_peaks(sched, speeds)
    need = [max(t.push_peak_N_m, t.turn_peak_N_m, full[t.speed_m_s]) for t in torque_requirement(sched, speeds)]
    assert need[0] > need[1] > need[2] and need[0] < 100.0     # falling, far below the ample limit: unsaturated
    limit = 0.5 * (need[1] + need[2])
    res = layout_assist(lay, speeds, weights=w, drive=DriveTrain(torque_limit=limit), check=True)
    top = res.forward_top
    assert top is not None and "torque" in top.checked
    assert top.safe_top_speed_m_s is None and top.limited_by == "torque"
    (lim,) = top.limits()
    assert lim.constraint == "torque" and lim.speed_m_s == 0.5 and lim.limit == limit
    # held at the limit: the moment limit tau w / r read back per wheel (x r / w), a few ulp (~4e-16); observed 0,
    # asserted 1e-13 (margin > 100)
    assert lim.value == pytest.approx(limit, rel=1e-13)
    assert [c.values["torque"][2] for c in top.checks] == [False, False, True]
    # unsaturated at 1.5 m/s: the same runs as the ample limit's; observed 0, asserted 1e-13
    assert top.checks[2].values["torque"][0] == pytest.approx(need[2], rel=1e-13)
    free = layout_assist(lay, speeds, weights=w, drive=DriveTrain(torque_limit=2.0 * need[0]), check=True).forward_top
    assert free is not None and all(c.values["torque"][2] for c in free.checks)


def test_the_command_counts_the_torque_in_a_layouts_top_speed(capsys, tmp_path):
    """The default run counts the torque in each direction's top speed (text and JSON, schema-checked: one run
    prints the text and writes the JSON with --json-file); --no-check names it as not checked (one design speed
    serves: the words name the option, whatever the grid)."""
    from stability import schemas

    js = tmp_path / "a.json"
    assert main(["--chair", "power-fwd-base", "--speeds", "1,2", "--reverse", "--json-file", str(js)]) == 0
    out = capsys.readouterr().out
    assert "from the margins and the torque (push and turns)" in out and "a full joystick turn" in out
    d = json.loads(js.read_text())
    schemas.validate("assist_layout", d)
    for key in ("forward_top_speed", "reverse_top_speed"):
        top = d[key]
        assert "torque" in top["constraints_checked"]
        for c in top["checks"]:
            t = c["torque_N_m"]
            assert 0 < t["value"] < t["limit"] and t["ok"]
    assert main(["--chair", "power-fwd-base", "--speeds", "1", "--no-check"]) == 0
    out = capsys.readouterr().out
    assert "not checked: the torque: run without --no-check" in out
