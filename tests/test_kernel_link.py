"""The kernels' compile shortcuts (stability.simulate.kernel_link): helpers compiled for linking only, and scalar
operators typed without numpy's array rules.  Each must leave numba's answers unchanged; the kernels' own answers
are checked bit for bit elsewhere (tests/test_simulate.py and the benchmarks)."""

from __future__ import annotations

import numpy as np
from numba import njit, types
from numba.core.typing import npydecl

from stability.simulate.kernel_equations import _NOREF, _NOWRAP
from stability.simulate.kernel_link import LinkOnlyCompiler, LinkOnlyLibrary, scalar_operators
from stability.simulate.native_call import address


def _helpers():
    """A link-only helper and a Python-callable caller, compiled afresh (no cache)."""
    @njit(nogil=True, **_NOWRAP, **_NOREF, pipeline_class=LinkOnlyCompiler)
    def helper(a, b):
        return a * b + 1.0

    @njit
    def caller(x):
        return helper(x, 3.0) - helper(2.0, x)

    return helper, caller


def test_link_only_helper_runs_in_its_caller_without_its_own_machine_code():
    helper, caller = _helpers()
    # x*3 + 1 - (2x + 1) = x, exactly in binary floating point for these x
    for x in (0.5, -4.0, 1024.0):
        assert caller(x) == x
    (cres,) = helper.overloads.values()
    assert isinstance(cres.library, LinkOnlyLibrary)
    assert not cres.library._emitted        # linked into the caller only: never optimised as a module nor emitted


def test_link_only_helper_is_emitted_when_its_address_is_asked_for():
    helper, caller = _helpers()
    assert caller(2.0) == 2.0
    ptr = address(helper, (types.float64, types.float64), types.float64)
    (cres,) = helper.overloads.values()
    assert ptr != 0 and cres.library._emitted


def test_scalar_operators_give_numbas_answers_and_restore_its_rule():
    original = npydecl.NumpyRulesArrayOperator.__dict__["generic"]
    with scalar_operators():
        assert npydecl.NumpyRulesArrayOperator.__dict__["generic"] is not original

        @njit
        def mixed(a, s, k):
            # scalar float and int operators, an array with a scalar, two arrays, in place
            t = s * 2.0 - k // 3 + (k % 4) * s
            b = a * t + a
            b += 1.0
            return b, t, k + 1, -s, s > 0.0

        a = np.arange(4.0)
        b, t, k1, ns, pos = mixed(a, 1.5, 7)
    assert npydecl.NumpyRulesArrayOperator.__dict__["generic"] is original
    t_ref = 1.5 * 2.0 - 7 // 3 + (7 % 4) * 1.5
    assert t == t_ref and k1 == 8 and ns == -1.5 and pos
    np.testing.assert_array_equal(b, a * t_ref + a + 1.0)
    assert b.dtype == np.float64 and isinstance(k1, int)
