"""The report's words from its numbers (stability.report.behaviour, .ranges): closed-form runs, one
classification, ranges that say what they span (issue 35, review errors 1, 3, 16 and change 7)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from stability.report.behaviour import STEADY_YAW_RATE, better_word, friction_role, motion, sig3
from stability.report.ranges import value_range
from stability.report.validity import Validity


def _circle(u: float, r0: float, t_end: float = 6.0, dt: float = 0.001, ttl: float = math.inf):
    """A chair turning steadily at yaw rate r0 (rad/s) at speed u (m/s): heading r0 t on a circle of radius u/r0."""
    t = np.arange(0.0, t_end + dt / 2, dt)
    psi = r0 * t
    x = (u / r0) * np.sin(psi) if r0 else u * t
    y = (u / r0) * (1 - np.cos(psi)) if r0 else 0 * t
    return SimpleNamespace(speed=u, t=t, x=x, y=y, heading=psi, yaw_rate=np.full_like(t, r0), time_to_level=ttl)


def test_steady_turn_is_read_from_the_valid_part_only():
    """Closed form: after T s on the circle, sideways (u/r0)(1 - cos r0 T), travel u T, heading r0 T."""
    u, r0 = 0.75, 0.05
    m = motion(_circle(u, r0), Validity(3.0, "slip > 8 deg"))
    assert m.until == pytest.approx(3.0, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert m.sideways == pytest.approx((u / r0) * (1 - math.cos(r0 * 3.0)), rel=1e-6)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # error model: truncation: chords of a circle fall short of the arc by (r0 dt)^2 / 24 = 1.04e-10 relative at
    # dt = 1 ms (observed 1.04e-10), x100
    assert m.travel == pytest.approx(u * 3.0, rel=1e-8)
    assert m.heading_deg == pytest.approx(math.degrees(r0 * 3.0), rel=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert m.final_rate == pytest.approx(r0, rel=1e-12) and m.kind == "keeps turning"  # rounding: equivalent arithmetic, a few ulp (observed 1.4e-16)
    assert "3 s" in m.where() and "slip > 8 deg" in m.where()
    whole = motion(_circle(u, r0))                             # no validity end: the whole 6 s
    assert whole.until == pytest.approx(6.0, rel=1e-12) and whole.reason == "" and "valid" not in whole.where()  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_one_classification_for_every_sentence():
    assert motion(_circle(0.75, 0.0)).kind == "straight"
    assert motion(_circle(0.75, 0.5 * STEADY_YAW_RATE, t_end=2.0)).kind == "straight"    # 0.57 deg: below 5 deg
    assert motion(_circle(0.75, 2 * STEADY_YAW_RATE)).kind == "keeps turning"
    spin = motion(_circle(0.75, 1.2, t_end=3.0, ttl=1.0))
    assert spin.kind == "spins up" and "1 s" in spin.words()
    # a level reached only after the validity end is not a result: the valid part decides
    late = motion(_circle(0.75, 0.05, ttl=5.0), Validity(3.0, "slip > 8 deg"))
    assert late.kind == "keeps turning"


def test_friction_role_follows_the_frictionless_twin():
    """Review error 3: friction that keeps a chair turning (its frictionless twin runs straight) must not be
    called 'holds the chair'."""
    turning, straight = motion(_circle(0.75, 0.04)), motion(_circle(0.75, 0.0))
    spin = motion(_circle(0.75, 1.2, t_end=3.0, ttl=1.0))
    late = motion(_circle(0.75, 1.2, t_end=3.0, ttl=2.0))
    assert friction_role(turning, straight) == "keeps it turning"
    assert friction_role(straight, spin) == "holds it"
    assert friction_role(late, spin) == "delays the spin"
    assert friction_role(straight, straight) == "changes little"


def test_better_word_and_significant_figures():
    assert better_word(+0.1, True) == "better" and better_word(-0.1, True) == "worse"
    assert better_word(-0.1, False) == "better" and better_word(0.001, True, tolerance=0.01) == "no change"
    assert [sig3(x) for x in (0.0750, 3.2617, 1234.5, 0.000123456)] == ["0.075", "3.26", "1230", "0.000123"]


def test_ranges_say_what_they_span_and_bounds_print_as_bounds():
    """Review change 7: '(0.75-0.75)', 'range 3-3 m/s' and '> 40 (40-40)' never print."""
    assert value_range(0.75, 0.75, 0.75, "m/s") == "0.75 m/s"
    assert value_range(3.0, 3.0, 3.0, "m/s", bound="above") == "> 3 m/s"
    assert value_range(40.0, 40.0, 40.0, "N s", bound="never") == "> 40 N s"
    assert value_range(1.02, 0.779, 1.12, "m/s", spans="push") == "1.02 m/s (0.779-1.12 m/s over push)"
    assert value_range(None, None, None) == "undefined"
