"""TireStack, the batch simulator's tire kernel, against Tire.lateral_force.

The stack must be the same force law (WCHAIR's MECHAN/POLYFT interpolation of
the cubic fits, eq 4-1), bit for bit, for every row's tire and policy.
"""

import warnings

import numpy as np
import pytest

from stability import tires


def _inputs():
    rng = np.random.default_rng(7)
    slip = rng.uniform(-11.0, 11.0, (4, 500))
    fz = rng.uniform(-30.0, 520.0, (4, 500))
    slip[:, :9] = np.arange(9.0)          # the integer knots, 0 included
    slip[1, 20] = np.nan
    fz[3, 21] = np.nan
    return slip, fz


@pytest.mark.parametrize("policy", ["clamp", "extrapolate"])
def test_stack_equals_each_tire(policy):
    row_tires = (tires.get("ER"), tires.get("PU").scaled(0.7), tires.get("EJA"), tires.get("AG").scaled(1.3))
    slip, fz = _inputs()
    got = tires.TireStack(row_tires).lateral_force(slip, fz, policy=policy)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        want = np.array([t.lateral_force(slip[j], fz[j], policy=policy) for j, t in enumerate(row_tires)])
    np.testing.assert_array_equal(got, want)
    assert np.array_equal(np.signbit(got), np.signbit(want))   # no -0.0 where the tire gives +0.0
    # and the scalar path (the single-run simulator; separate code, from the coefficient rows) to rounding
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        scalar = np.array([[t.lateral_force(float(a), float(b), policy=policy) for a, b in zip(slip[j], fz[j], strict=True)]
                           for j, t in enumerate(row_tires)])
    np.testing.assert_allclose(got, scalar, rtol=1e-12, atol=1e-9)


def test_stack_opposes_slip_and_is_zero_off_the_ground():
    er = tires.get("ER")
    f = tires.TireStack((er,)).lateral_force(np.array([[3.0, -3.0, 3.0]]), np.array([[200.0, 200.0, -5.0]]))
    assert f[0, 0] < 0.0 < f[0, 1] and f[0, 0] == -f[0, 1]
    assert f[0, 2] == 0.0


def test_stack_raise_policy_names_value_and_tire():
    eja = tires.get("EJA")
    stack = tires.TireStack((eja, eja))
    with pytest.raises(ValueError, match=r"slip angle 9\.5 deg is outside the fitted range .* \(tire EJA"):
        stack.lateral_force(np.array([[1.0], [9.5]]), np.array([[100.0], [100.0]]), policy="raise")
    with pytest.raises(ValueError, match=r"normal force 460\.0 N .* \[0, 450\] N"):
        stack.lateral_force(np.array([[1.0], [2.0]]), np.array([[460.0], [100.0]]), policy="raise")
    with pytest.raises(ValueError, match="policy"):
        stack.lateral_force(np.array([[1.0]]), np.array([[1.0]]), policy="guess")


def test_stack_refuses_linear_tires():
    with pytest.raises(ValueError, match="tires="):
        tires.TireStack((tires.get("linear:30"),))
