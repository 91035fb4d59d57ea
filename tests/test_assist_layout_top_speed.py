"""The torque constraint of a layout's safe top speed (stability.assist.layout, issue 38).

Independent statements used:

- the power chair expanded as a layout needs the short form's push torque: the layout simulator's peak torque per
  wheel after the reference push equals the short form's WCHAIR-scheme run
  (:func:`stability.assist.commands.command_run`, the short form's push run of the torque requirement);
- the rule of the top speed, counted here by hand: with the gains held (a fixed torque budget), the design speed
  where the peak torque the unsaturated loop needs (a run with an ample motor limit) first exceeds the motor limit
  is the first where the torque constraint fails (the saturated loop reaches the limit there), and the safe top
  speed is the design speed before it.
"""

from __future__ import annotations

import json

import pytest

from stability.assist.__main__ import main
from stability.assist.commands import command_run, step_command
from stability.assist.layout import layout_assist, layout_design
from stability.assist.layout_checks import layout_push_torques, layout_recovery
from stability.assist.schedule import schedule
from stability.assist.weights import Weights
from stability.chair import preset
from stability.chair.power import DriveTrain
from stability.layout import Layout
from stability.layout.presets import layout_preset
from stability.settings.reference import THESIS_PUSH


def test_the_power_chair_as_a_layout_needs_the_short_forms_push_torque():
    """Same equations, same step, same sampled controller: observed 2.5e-13 relative; asserted 1e-10 (margin
    400, floating-point rounding over the 2100 steps)."""
    chair, drive = preset("power-fwd"), DriveTrain()
    lay = Layout.from_chair(chair)
    sched = schedule(chair, [1.0, 3.0])
    rows = layout_push_torques(lay, [layout_design(lay, u, drive=drive) for u in (1.0, 3.0)], drive)
    for u, row in zip((1.0, 3.0), rows, strict=True):
        short = command_run(sched, u, step_command(0.0), duration=2.0, impulse_force=THESIS_PUSH.force)
        assert row.push_peak_N_m == pytest.approx(short.peak_torque_N_m, rel=1e-10)   # rounding (docstring)
        assert row.speed_m_s == u and row.motor_limit_N_m == drive.torque_limit


def test_a_torque_limit_below_the_needed_peak_sets_the_top_speed():
    """mid-wheel-drive forward: the push torque it needs rises from 0.5 to 1.5 m/s; a motor limit between the
    needs at 0.5 and 1 m/s makes the top speed 0.5 m/s, limited by the torque at 1 m/s, the limit reached there
    (saturated); a limit above every need leaves the margins' top speed."""
    lay, w, speeds = layout_preset("mid-wheel-drive"), Weights(torque_budget_nm=35.0), (0.5, 1.0, 1.5)
    ample = DriveTrain(torque_limit=1000.0)
    need = [layout_recovery(lay, layout_design(lay, u, weights=w, drive=ample), ample).peak_torque_N_m
            for u in speeds]
    assert need[0] < need[1] < need[2] < 1.0       # rising, far below the ample limit: unsaturated
    limit = 0.5 * (need[0] + need[1])
    res = layout_assist(lay, speeds, weights=w, drive=DriveTrain(torque_limit=limit), check=True)
    top = res.forward_top
    assert top is not None and "torque" in top.checked
    assert top.safe_top_speed_m_s == 0.5 and top.limited_by == "torque"
    (lim,) = top.limits()
    assert lim.constraint == "torque" and lim.speed_m_s == 1.0 and lim.limit == limit
    # held at the limit: the moment limit tau w / r read back per wheel (x r / w), a few ulp (~4e-16); observed 0,
    # asserted 1e-13 (margin > 100)
    assert lim.value == pytest.approx(limit, rel=1e-13)
    # unsaturated at 0.5 m/s: the same run as the ample limit's over its first 2.1 s; observed 0, asserted 1e-13
    assert top.checks[0].values["torque"][0] == pytest.approx(need[0], rel=1e-13)
    free = layout_assist(lay, speeds, weights=w, drive=DriveTrain(torque_limit=2.0 * need[2]), check=True).forward_top
    assert free is not None and all(c.values["torque"][2] for c in free.checks)


def test_the_command_counts_the_torque_in_a_layouts_top_speed(capsys):
    """The default run counts the torque in each direction's top speed (text and JSON, schema-checked);
    --no-check names it as not checked."""
    from stability import schemas

    assert main(["--chair", "power-fwd-base", "--speeds", "1,2", "--reverse", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    schemas.validate("assist_layout", d)
    for key in ("forward_top_speed", "reverse_top_speed"):
        top = d[key]
        assert "torque" in top["constraints_checked"]
        for c in top["checks"]:
            t = c["torque_N_m"]
            assert 0 < t["value"] < t["limit"] and t["ok"]
    assert main(["--chair", "power-fwd-base", "--speeds", "1,2"]) == 0
    out = capsys.readouterr().out
    assert "from the margins and the push torque" in out and "commanded turns are not run on a layout" in out
    assert main(["--chair", "power-fwd-base", "--speeds", "1,2", "--no-check"]) == 0
    out = capsys.readouterr().out
    assert "not checked: the torque: run without --no-check" in out
