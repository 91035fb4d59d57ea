"""The lanes kernel's polynomial sine, cosine and arctangent against numpy (libm), over the ranges the kernel uses.

Error model: :mod:`stability.simulate.lanemath` states its bounds against the exact values (``SIN_COS_ULP``,
``ATAN2_ULP`` units in the last place, plus ``SIN_COS_ABS`` absolute for the reduction near the zeros of sine and
cosine away from 0); numpy's own functions (glibc) are within 1 ulp of the exact values, so the two may differ by
the stated bound plus 1 ulp.  Observed (2e6 random inputs per range): at most 1 ulp below 100 rad, 2 ulp up to
the reduction limit, 1 ulp for the arctangent.
"""

import math

import numpy as np
import pytest
from numba import njit

from stability.simulate import lanemath as lm


@njit(cache=False)
def _sin_cos(x):
    s = np.empty_like(x)
    c = np.empty_like(x)
    for i in range(x.size):
        s[i], c[i] = lm.sin_cos(x[i])
    return s, c


@njit(cache=False)
def _atan2(y, x):
    out = np.empty_like(x)
    for i in range(x.size):
        out[i] = lm.atan2_pos(y[i], x[i])
    return out


def _ulps(got, ref):
    """|got - ref| in units of the last place of ref (at least the smallest normal's spacing)."""
    return np.abs(got - ref) / np.spacing(np.maximum(np.abs(ref), np.finfo(float).tiny))


@pytest.mark.parametrize("span", [math.pi, 4 * math.pi, 1e3, lm.REDUCTION_LIMIT])
def test_sin_cos_within_the_stated_bound(span):
    """Caster angles (a few turns), headings (spins: hundreds of rad) and the reduction's limit."""
    x = np.random.default_rng(7).uniform(-span, span, 400_000)
    s, c = _sin_cos(x)
    bound = lm.SIN_COS_ULP + 1.0            # against libm, itself within 1 ulp
    for got, ref in ((s, np.sin(x)), (c, np.cos(x))):
        excess = np.abs(got - ref) - lm.SIN_COS_ABS
        assert np.all(excess <= bound * np.spacing(np.abs(ref))), float(np.max(_ulps(got, ref)))


def test_sin_cos_near_the_zeros_and_exact_points():
    """Near multiples of pi/2 the result is tiny: the reduction's absolute bound holds; 0 and symmetry are exact."""
    k = np.arange(-400, 401) * (math.pi / 2)
    x = np.concatenate([k, k + 1e-9, k - 3e-12])
    s, c = _sin_cos(x)
    for got, ref in ((s, np.sin(x)), (c, np.cos(x))):
        # error model: the lane functions' stated ulp bound plus libm's own ulp on the reference
        assert np.all(np.abs(got - ref) <= (lm.SIN_COS_ULP + 1.0) * np.spacing(np.abs(ref)) + lm.SIN_COS_ABS)
    s0, c0 = _sin_cos(np.array([0.0]))
    assert s0[0] == 0.0 and c0[0] == 1.0
    y = np.random.default_rng(3).uniform(0, 20, 1000)
    sp, cp = _sin_cos(y)
    sn, cn = _sin_cos(-y)
    np.testing.assert_array_equal(sn, -sp)
    np.testing.assert_array_equal(cn, cp)


@pytest.mark.parametrize("scale", [1e-6, 1e-2, 1.0, 1e2])
def test_atan2_within_the_stated_bound(scale):
    """Contact velocities of 1 um/s to 100 m/s, every ratio (log-uniform over 12 decades), x >= 0 as SLIP gives."""
    rng = np.random.default_rng(11)
    n = 400_000
    y = rng.standard_normal(n) * scale * np.exp(rng.uniform(-14, 14, n))
    x = np.abs(rng.standard_normal(n)) * scale * np.exp(rng.uniform(-14, 14, n))
    got, ref = _atan2(y, x), np.arctan2(y, x)
    # error model: the stated ulp bound plus libm's own ulp on the reference
    assert np.all(np.abs(got - ref) <= (lm.ATAN2_ULP + 1.0) * np.spacing(np.abs(ref))), float(np.max(_ulps(got, ref)))


def test_atan2_exact_cases():
    """atan2(0, x) = 0 (straight running gives exactly zero slip), odd in y, +-pi/2 at x = 0, 0 at the origin."""
    y = np.array([0.0, 1.0, -1.0, 0.0, 2.5, -2.5])
    x = np.array([3.0, 0.0, 0.0, 0.0, 2.5, 2.5])
    got = _atan2(y, x)
    np.testing.assert_array_equal(got[:4], np.arctan2(y[:4], x[:4]))
    assert got[4] == -got[5]
    assert abs(got[4] - math.pi / 4) <= np.spacing(math.pi / 4)      # exact case: within one ulp of pi/4
