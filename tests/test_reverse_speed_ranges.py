"""Reverse speeds spelled as ranges (issue 38's audit): ``critical_speed --speeds=-1:-0.5:0.25`` and ``advise
--speeds=-1:-0.5`` answer, as a list of negative speeds already did and as ``shimmy`` / ``study`` take them.

Before, ``critical_speed`` read a layout's (or a reverse run's) ``--speeds`` as a comma list only (a negative
``START:STOP:STEP`` was refused, "valid: a list of signed speeds"), and ``advise`` refused ``-1:-0.5`` with a message
naming forward ranges only.  Independent check of the answer: the reverse growth rates are those of the layout turned
round by 180 deg driven forward (``tests/test_layout.py::_turned``, built by hand).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_layout import _turned

from stability.advise.__main__ import _speeds as advise_speeds
from stability.chair import resolve
from stability.critical_speed.command import main as critical_speed
from stability.layout.linear import growth_rates
from stability.layout.model import Layout
from stability.layout.presets import layout_preset

#: The reverse linearisation and the hand-turned layout's forward one are the same matrices up to the turned layout's
#: rounding (tests/test_layout.py observes ~1e-13 relative on the eigenvalues, rates ~0.1-10 1/s): 1e-9 1/s is a
#: margin of ~1e3 and far below any sign or geometry slip (>= 1e-3 1/s).
TURNED_1_S = 1e-9


@pytest.mark.parametrize("name", ["mid-wheel-drive", "ej-premier"])
def test_a_reverse_range_answers_the_turned_chair_forward(name, capsys):
    """A negative START:STOP:STEP on a layout preset and on a short-form chair (expanded as its layout)."""
    assert critical_speed(["--chair", name, "--speeds=-1:-0.5:0.25", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["speeds_m_s"] == [-1.0, -0.75, -0.5]
    lay = layout_preset(name) if name == "mid-wheel-drive" else Layout.from_chair(resolve(name))
    np.testing.assert_allclose(d["growth_rate_1_s"], growth_rates(_turned(lay), [1.0, 0.75, 0.5]), rtol=0,
                               atol=TURNED_1_S)


@pytest.mark.parametrize("speeds,fragment", [
    ("-30,-1", "--speeds '-30,-1' is invalid for a layout or reverse speeds; valid range: every |speed| 0.01 to 20"),
    ("-1:1:0.5", "--speeds '-1:1:0.5' is invalid; valid range: every |speed|"),   # crosses zero
    ("a,b", "--speeds 'a,b' is invalid"),
])
def test_a_bad_reverse_speed_is_refused_naming_the_option(speeds, fragment, capsys):
    assert critical_speed(["--chair", "mid-wheel-drive", f"--speeds={speeds}"]) == 2
    err = capsys.readouterr().err.strip()
    assert fragment in err and len(err.splitlines()) == 1


def test_the_advisors_reverse_range_has_both_spellings():
    """``-A:B`` (the range A:B backwards) and ``-B:-A`` (its signed ends) are the same speeds: ends and middle."""
    assert advise_speeds("-1:-0.5") == advise_speeds("-0.5:1") == (-0.5, -0.75, -1.0)
    for bad in ("-0.5:-1", "-5:-1"):
        with pytest.raises(ValueError, match=f"--speeds '{bad}' is invalid; valid: -B:-A with 0 < A <= B"):
            advise_speeds(bad)
