"""The equal-instability speed on the signed speed axis (issue 38: negative = reverse, as every command reports it).

:meth:`EqualInstabilityInterval.signed` maps a reverse search's ``|U|`` results onto negative speeds: an involution
that keeps every interval ordered (low <= high) and turns "beyond the fast end" into "below" the signed bracket.
"""

from __future__ import annotations

import numpy as np
import pytest

from stability.study.criteria import DEFAULT_CRITERION
from stability.study.equal_instability import EqualInstability
from stability.study.intervals import EqualInstabilityInterval, FactorRange, Variant


def _point(speed, status="found"):
    return EqualInstability(chair=None, speed=speed, status=status, low=0.8, high=0.9, reference_time=3.1,
                            evaluations=((0.5, 4.0), (0.9, 2.9)), bracket=(0.1, 3.0), criterion=DEFAULT_CRITERION,
                            model="exact", scheme="wchair", impulse=(40.0, 0.5))


def _interval():
    above = Variant("push force", "80 N", "exact", 80.0, 1.0, 2.0, _point(None, "above"))
    found = Variant("pin friction", "x0.5", "exact", 40.0, 0.5, 3.0, _point(0.85))
    return EqualInstabilityInterval("c", _point(0.85), 0.85, 3.0, (FactorRange("push force", 0.85, 3.0, ("80 N",)),),
                                    "push force", (above, found, Variant("m", "l", "exact", 1.0, 1.0, 9.9, None)),
                                    "thesis")


def test_forward_is_unchanged_and_reverse_is_an_involution():
    r = _interval()
    assert r.signed(False) is r
    twice = r.signed(True).signed(True)
    assert twice.to_dict() == r.to_dict() and twice.describe() == r.describe()
    assert twice.point.evaluations == r.point.evaluations and twice.point.bracket == r.point.bracket


def test_reverse_negates_every_speed_and_keeps_the_intervals_ordered():
    s = _interval().signed(True)
    d = s.to_dict()
    assert d["speed_m_s"] == -0.85 and (d["low_m_s"], d["high_m_s"]) == (-3.0, -0.85)
    assert (d["factors"][0]["low_m_s"], d["factors"][0]["high_m_s"]) == (-3.0, -0.85)
    assert [v["speed_m_s"] for v in d["variants"]] == [None, -0.85, None]
    assert [v["status"] for v in d["variants"]] == ["below", "found", None]   # beyond the fast end: below -3 m/s
    p = s.point
    assert (p.low, p.high, p.bracket) == (-0.9, -0.8, (-3.0, -0.1))
    assert p.evaluations == ((-0.9, 2.9), (-0.5, 4.0))
    assert s.variants[0].result.describe() == "< -3 m/s"
    assert "range below -3 to -0.85 m/s" in s.describe()


def test_a_reverse_range_with_both_ends_found_reads_from_to():
    """Two negative ends joined by "-" would read "-1.1--0.85": a reverse range says "to"; a forward one keeps "-"."""
    r = _interval()
    both = EqualInstabilityInterval("c", _point(0.85), 0.85, 1.1, (), "pin friction", r.variants[1:], "thesis")
    assert both.range_text() == "range 0.85-1.1 m/s"
    assert both.signed(True).range_text() == "range -1.1 to -0.85 m/s"
    assert EqualInstabilityInterval("c", _point(None, "above"), None, None, (), "", (), "thesis").signed(
        True).range_text() == "no range: every variant is undefined"


def test_the_json_and_the_line_of_an_interval():
    """The JSON's keys (snake_case, unit last), the line naming every factor, and the results are immutable."""
    import dataclasses

    import pytest

    r = _interval()
    two = EqualInstabilityInterval("c", r.point, 0.85, 3.0, r.factors + (FactorRange("pin friction", 0.85, 0.85, ()),),
                                   "push force", r.variants, "thesis")
    d = two.signed(True).to_dict()
    assert set(d) == {"chair", "speed_m_s", "status", "low_m_s", "high_m_s", "dominant", "push", "friction_scope",
                      "factors", "variants"}
    assert (d["chair"], d["dominant"], d["push"]) == ("c", "push force", "thesis")
    assert d["factors"][0] == {"factor": "push force", "low_m_s": -3.0, "high_m_s": -0.85, "undefined": ["80 N"]}
    assert "over push force, pin friction; moved most by push force)" in two.describe()
    with pytest.raises(dataclasses.FrozenInstanceError):
        two.factors[0].low = 1.0                                      # type: ignore[misc]


@pytest.mark.parametrize("on_reference, scope", [(True, "both the chair and the reference chair"),
                                                 (False, "the chair only")])
def test_the_interval_says_which_chairs_its_pin_friction_factors_move(monkeypatch, on_reference, scope):
    """Class: words no gate test read (seed 51: the friction scope; tests/test_report.py reads it after a full
    study).  The pin-friction variants scale both the chair and the reference chair (RANGE_DEFINITION), or the
    chair only when asked: the interval says which.  The runs are stood in for (every reference time 3.1 s, every
    chair at 0.85 m/s): the words do not depend on them."""
    from stability.chair import preset
    from stability.study import intervals

    monkeypatch.setattr(intervals, "reference_times", lambda refs, *a, **k: np.full(len(refs), 3.1))
    monkeypatch.setattr(intervals, "bisect_speeds", lambda chairs, *a, **k: [_point(0.85) for _ in chairs])
    (iv,) = intervals.equal_instability_intervals([preset("ej-premier")], friction_on_reference=on_reference)
    assert iv.friction_scope == scope
    if on_reference:
        assert "(on both the chair and the reference chair)" in intervals.RANGE_DEFINITION
