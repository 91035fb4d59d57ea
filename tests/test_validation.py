"""Linear versus nonlinear (issue: simulator, section 'Linear versus nonlinear').

With frictionless pins and a small disturbance the yaw-rate growth or decay rate
measured from the simulation must agree with the dominant eigenvalue of the linear
model of the same variant within 2 %.
"""

import numpy as np
import pytest

from stability import chair as chair_mod
from stability.validation import linear_vs_nonlinear, measured_rate


@pytest.mark.parametrize("model", ["thesis", "exact"])
@pytest.mark.parametrize("speed", [0.3, 0.75, 1.25, 2.0])
def test_free_casters_growth_rate_matches_eigenvalue(model, speed):
    c = chair_mod.preset("ej-premier")
    cmp = linear_vs_nonlinear(c, speed, model=model, casters="free")
    assert cmp.max_slip_deg < 1.0, "the comparison must stay in the tire model's linear range"
    assert cmp.relative_error < 0.02, cmp


@pytest.mark.parametrize("speed", [6.0, 10.0, 14.0])
def test_locked_casters_rate_matches_eigenvalue(speed):
    """Locked casters: decay below the critical speed (~12 m/s, Figure 8-6), growth above."""
    c = chair_mod.preset("ej-premier")
    cmp = linear_vs_nonlinear(c, speed, model="exact", casters="locked")
    assert cmp.max_slip_deg < 1.0
    assert cmp.relative_error < 0.02, cmp


def test_adaptive_scheme_agrees_too():
    cmp = linear_vs_nonlinear(chair_mod.preset("ej-premier"), 0.75, model="exact", scheme="adaptive")
    assert cmp.relative_error < 0.02, cmp


def test_measured_rate_on_known_signals():
    t = np.linspace(0, 10, 2001)
    assert measured_rate(t, 3e-4 * np.exp(0.7 * t), False, (1, 9)) == pytest.approx(0.7, rel=1e-9)
    y = np.exp(-0.4 * t) * np.cos(5 * t + 0.3)
    assert measured_rate(t, y, True, (1, 9)) == pytest.approx(-0.4, rel=1e-6)
    with pytest.raises(ValueError, match="sign"):
        measured_rate(t, y, False, (1, 9))
