"""Run settings on the command line take a unit (the user-journey review: '--speed 3.6km/h' was refused)."""

from __future__ import annotations

import argparse
import math
import re

import pytest

from stability.cli.options import _run_value
from stability.settings.run import RUN_SETTINGS


def parse(name: str, text: str):
    return _run_value("--" + name.replace("_", "-"), RUN_SETTINGS[name])(text)


@pytest.mark.parametrize(("name", "text", "want"), [
    ("speed", "3.6km/h", 1.0),                 # 3600 m / 3600 s
    ("speed", "3.6 km/h", 1.0),
    ("speed", "1.5", 1.5),
    ("speed", "100 cm/s", 1.0),
    ("speed", "2 mi/h", 2 * 1609.344 / 3600),   # the international mile, exact
    ("horizon", "200 ms", 0.2),
    ("horizon", "1 min", 60.0),
    ("push_force", "1 kgf", 9.80665),          # standard gravity, exact
])
def test_a_value_with_a_unit_is_converted_to_the_settings_unit(name, text, want):
    # error model: the number, two unit factors (each a product of at most two exact constants) and one
    # division round at most 5 times, 5 ulp = 1.1e-15 relative; tolerance about 100 times that
    assert parse(name, text) == pytest.approx(want, rel=1e-13)


@pytest.mark.parametrize(("name", "text", "words"), [
    ("speed", "2 s", ["--speed", "time", "speed", "m/s", "valid range"]),
    ("speed", "3.6 furlong/h", ["unknown unit 'furlong'"]),
    ("speed", "fast", ["expected a finite number", "m/s"]),
    ("speed", "80 km/h", ["valid range", "20 m/s"]),         # 22.2 m/s: converted, then checked against the range
])
def test_a_wrong_unit_is_refused_in_one_line(name, text, words):
    with pytest.raises(argparse.ArgumentTypeError) as err:
        parse(name, text)
    msg = str(err.value)
    assert "\n" not in msg and all(w in msg for w in words)


def test_the_command_line_takes_it(capsys):
    from stability.simulate.__main__ import main

    assert main(["--speed", "2 s"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--speed '2 s' is invalid" in err


# ---------------------------------------------------------------------------------------------------------------
# every numeric option, not only the run settings (the user-journey review, friction points 8 and 11)
# ---------------------------------------------------------------------------------------------------------------
def parse_option(command: str, option: str, text: str):
    from stability.cli.numbers import bound_for, number

    return number(option, float, bound_for(f"python -m stability.{command}", option))(text)


@pytest.mark.parametrize(("command", "option", "text", "want"), [
    ("slope", "--speed", "3.6km/h", 1.0),
    ("critical_speed", "--max-speed", "36 km/h", 10.0),
    ("assist", "--sample-rate", "100Hz", 100.0),
    ("assist", "--motor-lag", "20 ms", 0.02),
    ("study", "--max-impulse", "2 lbf s", 2 * 4.4482216152605),   # the pound-force, exact (units.py)
    ("tipping", "--grade", "0.1 rad", 0.1 * 180 / math.pi),
])
def test_any_numeric_option_takes_a_unit_of_its_dimension(command, option, text, want):
    # error model: as above, at most 5 roundings of the number and the unit factors; 100 times that
    assert parse_option(command, option, text) == pytest.approx(want, rel=1e-13)


@pytest.mark.parametrize(("text", "rise", "run"), [
    ("8%", 8.0, 100.0), ("8 %", 8.0, 100.0), ("-2%", -2.0, 100.0), ("1:12", 1.0, 12.0), ("1 : 50", 1.0, 50.0),
    ("-1:12", -1.0, 12.0),
])
def test_a_grade_or_cross_slope_takes_a_percentage_or_a_ramp_ratio(text, rise, run):
    """``8%`` and ``1:12`` are rise over run: the angle is atan(rise / run) (1:12, an accessible ramp, 4.76 deg)."""
    want = math.degrees(math.atan(rise / run))
    # error model: one division, one atan (libm, within 1 ulp) and one scaling: a few ulp; 100 times that
    for option in ("--grade", "--cross-slope"):
        assert parse_option("tipping", option, text) == pytest.approx(want, rel=1e-13, abs=1e-13)


@pytest.mark.parametrize(("command", "option", "text", "words"), [
    ("slope", "--speed", "8%", ["--speed '8%' is invalid", "unknown unit '%'"]),      # a percentage is a slope's
    ("assist", "--sample-rate", "100kg", ["'kg' is a mass unit; expected a frequency (Hz)"]),
    ("tipping", "--grade", "8kg", ["'kg' is a mass unit; expected an angle (deg)"]),
    ("tipping", "--grade", "1:0", ["a rise:run ratio with run > 0", "valid range: -45 <= value <= 45 deg"]),
    ("tipping", "--grade", "fast", ["expected a finite number (or a number with a unit of deg)"]),
    ("tipping", "--grade", "101%", ["--grade 101% is invalid; valid range: -45 <= value <= 45 deg"]),  # 100%: 45
    ("assist", "--gyro-noise", "1 deg/s", ["expected a finite number; valid range"]),   # deg/s/sqrt(Hz): no units
])
def test_a_wrong_unit_or_slope_is_refused_naming_the_option(command, option, text, words):
    with pytest.raises(argparse.ArgumentTypeError) as err:
        parse_option(command, option, text)
    msg = str(err.value)
    assert "\n" not in msg and all(w in msg for w in words), msg


def test_a_ramp_ratio_gives_the_answer_of_its_angle(capsys):
    """``tipping --grade 1:12`` answers exactly as the same grade typed in degrees (to the digits printed)."""
    import json

    from stability.tipping.__main__ import main

    angle = math.degrees(math.atan2(1, 12))
    assert main(["--chair", "manual-front-caster", "--grade", "1:12", "--json"]) == 0
    ramp = json.loads(capsys.readouterr().out)
    assert main(["--chair", "manual-front-caster", "--grade", repr(angle), "--json"]) == 0
    typed = json.loads(capsys.readouterr().out)
    assert ramp == typed and ramp["options"]["grade_deg"] == angle


def test_a_speed_range_of_two_ends_is_its_ends_and_middle_in_every_command(capsys):
    """``START:STOP`` means the ends and the middle wherever speeds are read (the advisor read it so, critical_speed
    refused it)."""
    import json

    from stability.cli import parse_speeds
    from stability.critical_speed.command import main

    assert list(parse_speeds("0.5:2")) == [0.5, 1.25, 2.0]
    assert list(parse_speeds("1:1")) == [1.0]
    assert list(parse_speeds("-2:-1", signed=True)) == [-2.0, -1.5, -1.0]
    with pytest.raises(ValueError, match="START:STOP"):
        parse_speeds("2:1")
    assert main(["--speeds", "0.5:2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["options"]["speeds_m_s"] == [0.5, 1.25, 2.0]


def test_a_mistyped_preset_is_named_with_the_closest_preset(capsys):
    from stability.critical_speed.command import main

    assert main(["--chair", "mid-wheel-drve"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "did you mean 'mid-wheel-drive'?" in err and "'ej-premier'" in err


# exact unit definitions (SI brochure; the international pound and foot, 1959): the conversions must give them
_LB_KG, _FT_M, _LBF_N = 0.45359237, 0.3048, 0.45359237 * 9.80665


@pytest.mark.parametrize(("assignment", "read", "want"), [
    ("caster_1_trail=6cm", lambda L: L.casters[0].trail, 6 * 0.01),
    ("m=210 lb", lambda L: L.m, 210 * _LB_KG),
    ("caster_1_pin_friction=0.1 ft lbf", lambda L: L.casters[0].pin_friction, 0.1 * _FT_M * _LBF_N),
    ("h=50cm", lambda L: L.h, 50 * 0.01),
    ("wheel_1_camber_deg=0.05rad", lambda L: L.wheels[0].camber_deg, math.degrees(0.05)),
    ("caster_2_trail=0.07", lambda L: L.casters[1].trail, 0.07),
])
def test_a_layout_set_takes_a_unit_of_its_field(assignment, read, want):
    """``--set`` on a layout converts a unit of the field's kind to the field's unit (layout.model.FIELD_UNITS),
    as a chair's ``--set`` does; before, only SI numbers were taken."""
    from stability.cli.chairs import load_layout

    got = read(load_layout("mid-wheel-drive", [assignment]))
    # error model: the unit factor's and the field factor's rounding, one product and one quotient: a few ulp;
    # 100 times that margin is 1e-13 relative
    assert got == pytest.approx(want, rel=1e-13, abs=0)


@pytest.mark.parametrize(("assignment", "words"), [
    ("caster_1_trail=6 kg", "layout field caster_1_trail is in m; 'kg' is not a unit of that kind"),
    ("caster_1_lateral_scale=2 m", "layout field caster_1_lateral_scale has no unit"),
    ("caster_1_trail=abc", "needs a number in m or a number with a unit of the same kind"),
    ("i_z=3 furlong", "needs a number in kg m^2"),
])
def test_a_layout_set_with_a_wrong_unit_is_refused_in_one_line(assignment, words):
    from stability.cli.chairs import load_layout

    with pytest.raises(ValueError, match=re.escape(words)) as e:
        load_layout("mid-wheel-drive", [assignment])
    assert str(e.value).startswith(f"--set {assignment!r}: ") and "\n" not in str(e.value)
