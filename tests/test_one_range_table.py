"""One table of valid ranges: a command line and the API refuse a value with the same range, from one Bound.

Before this file, commands re-checked numbers the parser had already checked against
:data:`stability.cli.numbers.OPTION_BOUNDS`, with ranges typed again that disagreed with the table: ``--min-tip-deg
60`` passed the table (0 < D <= 60) and was refused by the advisor's command (0 <= D < 60), ``--min-tip-deg 0`` (no
tip-angle limit, as the API takes it) the other way round; ``--nonlinear-samples
5000`` passed the table (to 20,000) and was refused by ``critical_speed`` (to 2,000); ``--gyro-bias -1`` and
``--wheel-radius 0.7`` passed the table and were refused by the assist command with other ranges; ``tipping
--grade 45`` passed the table and was refused (-45 < DEG < 45).  The API's ``advise`` checked none of its
cross slope and tip angle.  Each check here is a refusal (or an acceptance) at a range's end, where two typed
copies of a range differ.
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from stability.cli import numbers
from stability.settings import bounds

ROOT = Path(__file__).resolve().parents[1]

#: A range typed into a refusal's text: "valid range: 0 to 8", "valid range: 0 <= D < 60", "valid range: > 0 s".
_TYPED_RANGE = re.compile(r"valid range: *(?:[<>=]+ *)?-?\d")


def _command_modules() -> list[Path]:
    return sorted(p for p in (ROOT / "stability").rglob("*.py")
                  if p.name in ("__main__.py", "command.py") and "_generated" not in p.parts)


def test_command_modules_type_no_range_the_table_has():
    """A command module's refusal of a number quotes a Bound's text, never a range typed again.

    The command lines' numbers are parsed within :data:`OPTION_BOUNDS` before any command body runs; a range
    typed in a command module is a second copy that can (and did) disagree.  Allowed: the app server's port (not a
    physical setting).
    """
    allowed = {("stability/app/server.py", "0 to 65535")}
    found = []
    for path in _command_modules() + [ROOT / "stability/app/server.py"]:
        rel = str(path.relative_to(ROOT))
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and _TYPED_RANGE.search(node.value):
                if not any(rel == f and text in node.value for f, text in allowed):
                    found.append(f"{rel}:{node.lineno}: {node.value.strip()[:80]}")
    assert not found, "ranges typed in command modules (use a Bound of stability.settings.bounds):\n" + "\n".join(found)


@pytest.mark.parametrize(("command", "argv", "bound"), [
    # each value lies just outside the one range, inside the old typed copy (or the other way round)
    ("stability.critical_speed", ["--uncertainty", "u.toml", "--nonlinear", "--nonlinear-samples", "2001"],
     bounds.NONLINEAR_SAMPLES),
    ("stability.assist", ["--gyro-bias", "-1"], numbers.OPTION_BOUNDS["--gyro-bias"]),
    ("stability.assist", ["--wheel-radius", "0.7"], bounds.DRIVE_WHEEL_RADIUS),
    ("stability.advise", ["--min-tip-deg", "60.5"], bounds.MIN_TIP_ANGLE),
    ("stability.advise", ["--cross-slope", "8.5"], bounds.ADVISE_CROSS_SLOPE),
    ("stability.advise", ["--reaction-time", "0.3", "--intended-speed", "6.5"], bounds.HUMAN_SPEED),
    ("stability.compare", ["ej-premier", "revised", "--samples", "20001"], bounds.SAMPLES),
    ("stability.compare", ["ej-premier", "revised", "--level", "1"], bounds.CONFIDENCE_LEVEL),
])
def test_a_refusal_quotes_the_one_range(command, argv, bound, capsys):
    import importlib

    main = importlib.import_module(command + ".__main__").main if command != "stability.critical_speed" else \
        importlib.import_module("stability.critical_speed.command").main
    try:
        code = main(argv)
    except SystemExit as e:                 # a parser's refusal
        code = e.code
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and f"valid range: {bound.text()}" in err, err


def test_the_range_ends_are_accepted_where_the_copies_refused_them(monkeypatch, capsys):
    """The closed ends the old typed copies refused now reach the work: ``--min-tip-deg 60`` (and 0) and
    ``--cross-slope 8`` reach the advisor (stood in by a stub that records its arguments), ``tipping --grade 45``
    answers."""
    import stability.advise.__main__ as advise_main
    from stability.tipping.__main__ import main as tipping_main

    seen = {}

    class Reached(Exception):
        pass

    def stub(chair, **kw):
        seen.update(kw)
        raise Reached

    monkeypatch.setattr(advise_main, "advise", stub)
    with pytest.raises(Reached):
        advise_main.main(["--min-tip-deg", "60", "--cross-slope", "8", "--no-progress"])
    assert seen["min_tip_deg"] == 60.0 and seen["cross_slope_deg"] == 8.0
    with pytest.raises(Reached):
        advise_main.main(["--min-tip-deg", "0", "--no-progress"])
    assert seen["min_tip_deg"] == 0.0
    assert tipping_main(["--cross-slope", "-45", "--grade", "45"]) == 0
    out = capsys.readouterr().out
    # the combined tilt of a -45 deg cross slope and a 45 deg grade: cos(tilt) = cos(45 deg)^2, tilt = 60 deg
    assert "tilt 60.00 deg" in out


@pytest.mark.parametrize(("keyword", "value", "bound"), [
    ("cross_slope_deg", 8.5, bounds.ADVISE_CROSS_SLOPE),
    ("cross_slope_deg", float("nan"), bounds.ADVISE_CROSS_SLOPE),
    ("min_tip_deg", -1.0, bounds.MIN_TIP_ANGLE),
    ("min_tip_deg", 61.0, bounds.MIN_TIP_ANGLE),
    ("intended_speed", 6.5, bounds.HUMAN_SPEED),
])
def test_advise_api_refuses_before_any_work(keyword, value, bound, monkeypatch):
    """``advise`` refuses with the command line's range, naming the keyword, before measuring anything."""
    import stability.advise.advisor as advisor
    from stability.chair import preset
    from stability.driver import Driver

    def no_work(*a, **k):
        raise AssertionError("measured a chair before checking the arguments")

    monkeypatch.setattr(advisor, "measure_chairs", no_work)
    extra = {"driver": Driver(0.3)} if keyword == "intended_speed" else {}
    with pytest.raises(ValueError, match=re.escape(f"valid range: {bound.text(keyword)}")) as e:
        advisor.advise(preset("ej-premier"), **{keyword: value}, **extra)
    assert str(e.value).startswith(f"{keyword}=")


@pytest.mark.parametrize(("speeds", "named", "says"), [
    ([], "speeds", "has no values"),
    ([0.5] * (bounds.ADVISE_SPEED_COUNT + 1), "speeds", f"more than {bounds.ADVISE_SPEED_COUNT} values"),
    (iter([0.5] * 10**7), "speeds", f"more than {bounds.ADVISE_SPEED_COUNT} values"),    # not copied whole
    ([0.5, bounds.ADVISE_SPEED.hi + 0.01], "speeds[1]", "valid range: 0.1 <= speed <= 3 m/s in size"),
    ([bounds.ADVISE_SPEED.lo - 0.01], "speeds[0]", "valid range: 0.1 <= speed <= 3 m/s in size"),
    ([-(bounds.ADVISE_SPEED.hi + 0.01)], "speeds[0]", "valid range"),
    ([float("nan")], "speeds[0]", "valid range"),
    (["0.5"], "speeds[0]", "valid range"),
    ([True], "speeds[0]", "valid range"),
    ([0.5, -0.5], "speeds", "all forward (> 0) or all in reverse (< 0)"),
    (0.5, "speeds", "valid values: a sequence of 1 to 12 speeds"),
    ("0.5", "speeds", "valid values: a sequence"),
])
def test_advise_api_refuses_use_speeds_with_the_command_range(speeds, named, says, monkeypatch):
    """``advise(speeds=)`` keeps ``--speeds``' range (0.1-3 m/s in size, 1-12 of them, one sign) and refuses before
    any work, naming the element; before, 5 m/s and 0 m/s were advised on, an empty list measured for 7 s and then
    failed in ``min()``, NaN reached the eigenvalue solver."""
    import stability.advise.advisor as advisor
    from stability.chair import preset

    def no_work(*a, **k):
        raise AssertionError("measured a chair before checking the arguments")

    monkeypatch.setattr(advisor, "measure_chairs", no_work)
    monkeypatch.setattr(advisor, "lever_changes", no_work)
    with pytest.raises(ValueError, match=re.escape(says)) as e:
        advisor.advise(preset("ej-premier"), speeds=speeds)
    assert re.match(re.escape(named) + "[= ]", str(e.value)), str(e.value)     # the argument or its element first


def test_advise_use_speeds_at_the_range_ends_are_accepted():
    """Both ends of the range, either sign, and numpy scalars pass the check unchanged (order kept)."""
    import numpy as np

    from stability.advise.subject import use_speeds
    lo, hi = bounds.ADVISE_SPEED.lo, bounds.ADVISE_SPEED.hi
    assert use_speeds([hi, lo]) == (hi, lo)
    assert use_speeds((-lo, -hi)) == (-lo, -hi)
    assert use_speeds(np.array([0.5, 1.0])) == (0.5, 1.0)
    assert use_speeds([np.float32(0.5)] * bounds.ADVISE_SPEED_COUNT) == (0.5,) * bounds.ADVISE_SPEED_COUNT


@pytest.mark.parametrize(("call", "bound"), [
    ("linear_intervals", bounds.SAMPLES), ("nonlinear_intervals", bounds.NONLINEAR_SAMPLES)])
def test_interval_apis_refuse_samples_with_the_command_range(call, bound):
    """``samples`` one past the end is refused with the same range as ``--samples`` / ``--nonlinear-samples``;
    a fractional count is a TypeError (it was silently truncated by ``int()``)."""
    from stability.chair import preset
    from stability.linear.intervals import linear_intervals
    from stability.study.uncertain import nonlinear_intervals
    from stability.uncertainty import Uncertainty

    fn = {"linear_intervals": linear_intervals, "nonlinear_intervals": nonlinear_intervals}[call]
    unc = Uncertainty(())
    with pytest.raises(ValueError, match=re.escape(bound.text("samples"))):
        fn(preset("ej-premier"), unc, samples=int(bound.hi) + 1)
    with pytest.raises(TypeError, match="samples=2.5"):
        fn(preset("ej-premier"), unc, samples=2.5)
