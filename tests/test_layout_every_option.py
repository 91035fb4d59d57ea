"""Issue 38, every command on any layout and in reverse: the options that were refused for wheel layouts.

``critical_speed --chair LAYOUT`` with ``--reaction-time`` (the driver's two linear limits forwards and backwards,
:func:`stability.driver.layout.layout_human_limit`), ``--uncertainty FILE`` (intervals over the file's layout fields)
and ``-o FIG``; ``study critical-impulse --chair LAYOUT --interval``; ``report --chair LAYOUT --clinician
--reaction-time``.  Independent references: the short form's own engine for the E&J Premier expanded as a layout (its
driver limits, its Monte Carlo growth-rate intervals on the same draws, its critical-impulse search), mirror symmetry,
the reverse of a layout being the turned layout driven forward, and the monotonicity of a critical speed in the one
uncertain parameter.
"""

from __future__ import annotations

import dataclasses as dc
import functools
import json

import numpy as np
import pytest
from test_layout import _turned

from stability.chair import resolve
from stability.driver import Driver, human_limit
from stability.driver.layout import layout_human_limit
from stability.layout.linear import critical_speed
from stability.layout.model import Layout
from stability.layout.presets import layout_preset

#: Two limits found by the same bisection (to 1e-3 m/s) on matrices equal to ~1e-13 relative make the same decisions,
#: so they agree exactly (observed 0); 1e-9 m/s would still flag one differing decision (>= 5e-4 m/s) by far.
SAME_DECISIONS_M_S = 1e-9


@functools.cache
def _short_limit(name: str, reaction_time: float):
    """The short form's driver limits of preset ``name`` (the reference several tests compare with; computed once,
    a frozen HumanLimit)."""
    return human_limit(resolve(name), Driver(reaction_time))


@functools.cache
def _layout_limit(layout: Layout, reaction_time: float):
    """The layout's forward driver limits (a reference several tests compare with; computed once per frozen
    layout and reaction time)."""
    return layout_human_limit(layout, Driver(reaction_time))


def _limits(h) -> tuple[float, str, float, str]:
    return h.rule_speed_m_s, h.rule_side, h.loop_speed_m_s, h.loop_side


def _assert_same(a, b) -> None:
    assert a[1] == b[1] and a[3] == b[3]
    assert a[0] == pytest.approx(b[0], abs=SAME_DECISIONS_M_S)
    assert a[2] == pytest.approx(b[2], abs=SAME_DECISIONS_M_S)


def test_the_e_and_j_premier_as_a_layout_has_the_short_forms_driver_limits():
    """The short form's engine (its own linear model) and the layout's give the same divergence rule and delayed-loop
    speeds for a 0.3 s driver: 1.79 and 1.97 m/s (docs/driver.md's)."""
    chair = resolve("ej-premier")
    short = _short_limit("ej-premier", 0.3)
    lay = layout_human_limit(Layout.from_chair(chair), Driver(0.3))
    _assert_same(_limits(lay), _limits(short))
    assert short.rule_side == short.loop_side == "="
    assert lay.to_mapping().keys() == short.to_mapping().keys()          # the short form's JSON names


def _lopsided() -> Layout:
    base = layout_preset("power-fwd-base")
    left, right = base.casters
    return dc.replace(base, name="lopsided", casters=(dc.replace(left, trail=0.04), dc.replace(right, trail=0.07)))


def test_the_mirror_image_has_the_same_driver_limits_both_ways():
    """A base with unequal trails left and right and its mirror image: the same limits forwards and backwards (a
    reflection leaves the eigenvalues and the heading loop's best abscissa unchanged)."""
    a = _lopsided()
    m = dc.replace(a, name="mirror", wheels=tuple(dc.replace(w, y=-w.y) for w in a.wheels),
                   casters=tuple(dc.replace(c, y=-c.y) for c in a.casters))
    _assert_same(_limits(_layout_limit(a, 0.4)), _limits(_layout_limit(m, 0.4)))     # forwards
    _assert_same(_limits(layout_human_limit(a, Driver(0.4), True)), _limits(layout_human_limit(m, Driver(0.4), True)))
    assert _layout_limit(a, 0.4).rule_side == "="          # a limit inside the range, not two bounds (computed once)


@pytest.mark.parametrize("name", ["power-fwd-base", "ej-premier-front-caster"])
def test_the_limit_in_reverse_is_the_turned_layouts_forward_limit(name):
    """Driving a layout backwards (casters trailing at 180 deg) is driving the layout turned by 180 deg forwards
    (tests/test_layout.py: the same eigenvalues to 1e-13): the same driver limits.  The rear-caster base in reverse
    becomes a front-caster one and the front-caster E&J a rear-caster one."""
    lay = layout_preset(name) if name == "power-fwd-base" else Layout.from_chair(resolve(name))
    back = layout_human_limit(lay, Driver(0.3), reverse=True)
    turned = layout_human_limit(_turned(lay), Driver(0.3))
    _assert_same(_limits(back), _limits(turned))


def test_the_rear_wheel_drive_base_backwards_is_the_front_wheel_drive_base_forwards():
    """The two bases are one frame turned round; with each caster's mass at its pin (l = 0) the reverse of one is the
    other forward: the front-wheel-drive base's limit found (1.83 m/s for 0.3 s) is the other's backwards."""
    def pinned(name: str) -> Layout:
        lay = layout_preset(name)
        return dc.replace(lay, casters=tuple(dc.replace(c, l=0.0) for c in lay.casters))

    fwd = layout_human_limit(pinned("power-fwd-base"), Driver(0.3))
    rwd_back = layout_human_limit(pinned("power-rwd-base"), Driver(0.3), reverse=True)
    _assert_same(_limits(fwd), _limits(rwd_back))
    assert fwd.rule_side == "=" and fwd.loop_side == "="


def test_critical_speed_prints_the_drivers_limits_of_a_layout_both_ways(capsys):
    """``--chair ej-premier --speeds -0.5,0.5`` goes through the layout's model (a negative speed): its forward
    limits are the short form's (:func:`stability.driver.human_limit`, the short-form command's), in its JSON names,
    and the JSON validates against the hand-written schema."""
    from stability.critical_speed.command import main

    assert main(["--chair", "ej-premier", "--speeds=-0.5,0.5", "--reaction-time", "0.3", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    short = _short_limit("ej-premier", 0.3).to_mapping()
    h = d["human_limit"]
    for key in ("divergence_rule_speed_m_s", "delayed_loop_speed_m_s", "speed_m_s"):
        assert h[key] == pytest.approx(short[key], abs=SAME_DECISIONS_M_S)
    turned = layout_human_limit(_turned(Layout.from_chair(resolve("ej-premier"))), Driver(0.3))
    assert h["reverse"]["speed_m_s"] == pytest.approx(turned.speed_m_s, abs=SAME_DECISIONS_M_S)
    assert h["driver"]["source"] == "--reaction-time" and d["options"]["reaction_time_s"] == 0.3
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("critical_speed", d)
    assert main(["--chair", "power-fwd-base", "--reaction-time", "0.3"]) == 0
    out = capsys.readouterr().out
    fwd = _layout_limit(layout_preset("power-fwd-base"), 0.3)
    assert f"forwards: A driver who corrects the heading 0.3 s late can hold this chair straight up to " \
           f"{fwd.speed_m_s:.3g} m/s" in out and "backwards: " in out


def _file(tmp_path, text: str):
    p = tmp_path / "u.toml"
    p.write_text(text)
    return str(p)


def test_the_e_and_j_as_a_layout_has_the_short_forms_growth_rate_intervals(tmp_path, capsys):
    """Same file, seed and draws: the layout's Monte Carlo intervals of the growth rate are the short form's
    (:func:`stability.linear.intervals.linear_intervals` on its own engine) to rounding (the matrices agree to
    ~1e-13; the interval ends observed 4.1e-13 relative at most, 2.6e-13 with 100 draws; 1e-9 asserted).  Both the
    agreement and "no draw crosses" hold draw by draw, so 40 draws test them as 100 would."""
    from stability.critical_speed.command import main
    from stability.linear.intervals import linear_intervals
    from stability.uncertainty import load_uncertainty

    path = _file(tmp_path, '[m]\ndistribution = "normal"\nstd = 10.0\n[i_z]\ndistribution = "uniform"\n'
                           'low = -0.2\nhigh = 0.2\nrelative = true\n')
    assert main(["--chair", "ej-premier", "--speeds=-0.5,0.5,1", "--uncertainty", path, "--samples", "40",
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    rows = {(m["measure"], m["speed_m_s"]): m for m in d["uncertainty"]["measures"]}
    short = linear_intervals(resolve("ej-premier"), load_uncertainty(path), speeds=np.array([0.5, 1.0]), samples=40,
                             seed=0)
    for u, (lo, hi) in zip((0.5, 1.0), short.rate, strict=True):
        row = rows[("growth_rate_1_s", u)]
        # rounding: two engines' matrices equal to ~1e-13 relative on the same draws (observed 4.1e-13); 1e-9 allowed
        assert (row["low"], row["high"]) == pytest.approx((lo, hi), rel=1e-9)
    assert rows[("critical_speed_forward_m_s", None)]["finite_fraction"] == 0.0     # no crossing, as the short form
    assert short.free_critical[2] == 0.0
    pytest.importorskip("jsonschema")
    from stability import schemas

    schemas.validate("critical_speed", d)


def test_a_critical_speeds_interval_lies_between_its_values_at_the_parameters_ends(tmp_path):
    """A mid-wheel-drive variant (5 mm trail, five times the casters' swivel inertia) loses stability forwards near
    10.8 m/s; with the body mass uniform over +/- 5 %, every draw's critical speed lies between those of the two
    ends (the critical speed is monotone in the mass there, checked), so the interval does too, and the nominal is
    the layout's own."""
    from stability.advise.layout_axes import load_layout_uncertainty
    from stability.report.layout_uncertainty import layout_uncertainty

    base = layout_preset("mid-wheel-drive")
    lay = dc.replace(base, casters=tuple(dc.replace(c, trail=0.005, i_zp=5 * c.i_zp) for c in base.casters))
    unc = load_layout_uncertainty(_file(tmp_path, '[m]\ndistribution = "uniform"\nlow = -0.05\nhigh = 0.05\n'
                                                  'relative = true\n'), lay)
    r = layout_uncertainty(lay, unc, [1.0], samples=40, seed=0, critical=True)
    row = {k: (nom, lo, hi, fin) for k, _, nom, lo, hi, fin in r.rows()}["critical_speed_forward_m_s"]
    ends = sorted(critical_speed(dc.replace(lay, m=lay.m * f))[0] for f in (0.95, 1.0, 1.05))
    assert ends[0] < ends[1] < ends[2]                                   # monotone (checked at the ends and middle)
    nom, lo, hi, fin = row
    assert nom == critical_speed(lay)[0] and fin == 1.0
    # the bisection's 1e-6 m/s bracket on each draw and end
    assert ends[0] - 1e-6 <= lo < nom < hi <= ends[2] + 1e-6
    assert "critical speed forward" in "\n".join(r.lines())


def test_the_layout_figure_names_chair_model_and_units(tmp_path, capsys):
    from stability.critical_speed.command import layout_figure, layout_summary, main

    lay = layout_preset("mid-wheel-drive")
    fig = layout_figure(lay, layout_summary(lay, [0.5, 1.0]), 5.0, n=60)
    texts = [t.get_text() for t in fig.texts]
    assert any("mid-wheel-drive | layout model" in t for t in texts)
    assert any(t.startswith("What to conclude: forwards: stable at every speed up to 20 m/s") for t in texts)
    labels = [ax.get_xlabel() + ax.get_ylabel() for ax in fig.axes]
    assert any("(m/s)" in x and "(1/s)" in x for x in labels) and any("reverse speed" in x for x in labels)
    out = tmp_path / "f.png"
    assert main(["--chair", "power-rwd-base", "-o", str(out), "--max-speed", "3"]) == 0
    assert out.stat().st_size > 0


@pytest.mark.parametrize("argv, words", [
    (["--chair", "mid-wheel-drive", "--model", "thesis"], "--model thesis is invalid for a layout"),
    (["--chair", "mid-wheel-drive", "--reaction-time", "9"], "--reaction-time 9"),
    (["--chair", "mid-wheel-drive", "--nonlinear", "--uncertainty", "docs/examples/mid_wheel_drive.uncertainty.toml"],
     "--nonlinear is not available for a layout"),
    (["--chair", "mid-wheel-drive", "--uncertainty", "docs/examples/measured_chair.uncertainty.toml"],
     "numeric layout field"),
    (["--chair", "mid-wheel-drive", "--uncertainty", "docs/examples/mid_wheel_drive.uncertainty.toml", "--samples",
      "0"], "--samples 0 is invalid; valid range"),
])
def test_bad_input_is_refused_in_one_line(argv, words, capsys):
    from stability.critical_speed.command import main

    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err, err


def test_the_clinician_sheet_of_a_layout_has_the_drivers_line(tmp_path, capsys):
    """``report --chair LAYOUT --clinician --reaction-time``: the sheet says up to which speed the user holds the
    base forwards and backwards, and names the user's speeds above the forward limit."""
    from stability.report.__main__ import main

    pdf, txt = tmp_path / "s.pdf", tmp_path / "s.txt"
    assert main(["--chair", "power-fwd-base", "--clinician", "--reaction-time", "0.3", "--speeds=0.75,2,-2",
                 "-o", str(pdf), "--text", str(txt)]) == 0
    text = " ".join(txt.read_text().split())
    fwd = _layout_limit(layout_preset("power-fwd-base"), 0.3)
    assert fwd.speed_m_s < 2.0
    assert (f"THE USER. A driver who corrects the heading 0.3 s late can hold this chair straight up to "
            f"{fwd.speed_m_s:.3g} m/s") in text
    assert "backwards" in text and "at 7.2 km/h this user cannot hold it" in text


def test_the_e_and_j_as_a_layout_has_the_short_forms_critical_impulse_interval():
    """``study critical-impulse --interval`` on a layout is the short form's interval less the model variant: for the
    E&J Premier at 0.75 m/s the nominal bracket is the short form's to rounding (tests/test_layout_impulse.py) and
    every variant's bracket overlaps the short form's (stick-slip decisions near the threshold may differ)."""
    from stability.study.impulse_intervals import critical_impulse_intervals
    from stability.study.layout_impulse_intervals import layout_critical_impulse_intervals

    chair = resolve("ej-premier")
    short = critical_impulse_intervals([chair], 0.75, models=("exact",))[0]
    lay = layout_critical_impulse_intervals(Layout.from_chair(chair), 0.75)[0]
    assert [label for label, _ in lay.variants] == [label for label, _ in short.variants]
    np.testing.assert_allclose([lay.point.low_Ns, lay.point.high_Ns], [short.point.low_Ns, short.point.high_Ns],
                               rtol=1e-12)              # tests/test_layout_impulse.py's ROUNDING
    for (_, p), (_, q) in zip(lay.variants, short.variants, strict=True):
        assert max(p.low_Ns, q.low_Ns) < min(p.high_Ns, q.high_Ns)


def test_study_interval_on_a_layout_prints_its_range(capsys):
    from stability.study.__main__ import main

    assert main(["critical-impulse", "--chair", "power-fwd-base", "--speeds", "1", "--horizon", "4", "--interval",
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    iv = d["intervals"][0]
    assert [v["label"] for v in iv["variants"]] == ["x0.5 pin friction", "x1.5 pin friction", "0.5 ms step"]
    bounds = [iv["impulse_Ns"] if iv["status"] == "found" else None] + [v["bound_Ns"] for v in iv["variants"]]
    assert iv["low_Ns"] == min(b for b in bounds[1:] + [iv["low_Ns"]]) and iv["low_Ns"] <= iv["high_Ns"]


def test_a_wheel_file_with_a_user_table_gets_that_users_limits(tmp_path, capsys):
    """A ``[[wheel]]`` file (the front-wheel-drive base exported) with ``[user] reaction_time_s = 0.4``: critical_speed
    uses the file's driver, and its limit forwards is the base's for a 0.4 s driver (the same layout read back)."""
    from stability.chair.__main__ import main as chair_main
    from stability.critical_speed.command import main

    path = tmp_path / "fwd.toml"
    assert chair_main(["export", "power-fwd-base"]) == 0
    path.write_text(capsys.readouterr().out + '\n[user]\nreaction_time_s = 0.4\n')
    assert main(["--chair", str(path), "--json"]) == 0
    h = json.loads(capsys.readouterr().out)["human_limit"]
    assert h["driver"]["reaction_time_s"] == 0.4 and h["driver"]["source"].endswith("[user]")
    expected = layout_human_limit(layout_preset("power-fwd-base"), Driver(0.4))
    assert h["speed_m_s"] == pytest.approx(expected.speed_m_s, abs=SAME_DECISIONS_M_S)
    assert h["limited_by"] == expected.limited_by
