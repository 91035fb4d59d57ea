"""Run settings on the command line take a unit (the user-journey review: '--speed 3.6km/h' was refused)."""

from __future__ import annotations

import argparse

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
    ("speed", "fast", ["expected a number", "m/s"]),
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
