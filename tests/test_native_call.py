"""``native_call.call_at``: a jitted function called at its address is the function called directly.

The batch entries of the WCHAIR kernel call ``run_one``'s specialisation this way (docs/simulator.md, "Compile
time").  The independent truths here are the callee's own results (called from Python, and through numba's
ordinary call) on values chosen to exercise every argument: arrays read and written, integer literals passed as
their integers, a float result, and an exception raised in the callee reaching the caller.
"""

from __future__ import annotations

import numpy as np
import pytest
from numba import literally, njit, typeof, types

from stability.simulate.native_call import address, call_at, call_none_at, row_types


@njit(nogil=True)
def _callee(lit, k, a, out):
    """Writes ``a * lit + k`` into ``out`` (``lit`` a literal), raises for ``k < 0``; returns ``len(a) + lit``."""
    if k < 0:
        raise ValueError("negative k")
    for i in range(a.shape[0]):
        out[i] = a[i] * lit + k
    return np.int64(a.shape[0] + lit)


@njit
def _through(fp, lit, k, A, O):
    n = 0
    for i in range(A.shape[0]):
        n += call_at(fp, lit, k, A[i], O[i])
    return n


@njit
def _direct(lit, k, A, O):
    literally(lit)
    n = 0
    for i in range(A.shape[0]):
        n += _callee(lit, k, A[i], O[i])
    return n


def _address(lit, k, A, O):
    rows = row_types((typeof(A), typeof(O)), (0, 1))
    return address(_callee, (types.literal(lit), typeof(k), *rows))


def test_call_at_is_the_direct_call():
    A = np.linspace(-2.0, 3.0, 12).reshape(3, 4)
    fp = _address(3, 5, A, A)
    out_at, out_direct = np.full_like(A, np.nan), np.full_like(A, np.nan)
    n_at = _through(fp, 3, 5, A, out_at)
    n_direct = _direct(3, 5, A, out_direct)
    assert n_at == n_direct == 3 * (4 + 3)
    # exact: the same compiled code, and numpy's one rounding of each multiply and add (IEEE, no contraction)
    assert out_at.tobytes() == out_direct.tobytes()
    assert np.array_equal(out_at, A * 3 + 5)


def test_call_at_propagates_the_callee_exception():
    A = np.ones((2, 3))
    fp = _address(3, 5, A, A)
    with pytest.raises(ValueError, match="negative k"):
        _through(fp, 3, -1, A, np.empty_like(A))


@njit(nogil=True)
def _writer(k, a, out):
    """Writes ``a + k`` into ``out``; raises for ``k < 0``; returns nothing."""
    if k < 0:
        raise ValueError("negative k")
    for i in range(a.shape[0]):
        out[i] = a[i] + k


@njit
def _through_none(fp, k, A, O):
    for i in range(A.shape[0]):
        call_none_at(fp, k, A[i], O[i])


def test_call_none_at_is_the_direct_call():
    """A function returning nothing (the layout kernel's generated equations) called at its address writes what
    it writes when called directly, and its exception reaches the caller."""
    A = np.linspace(-2.0, 3.0, 12).reshape(3, 4)
    fp = address(_writer, (typeof(5), *row_types((typeof(A), typeof(A)), (0, 1))), types.none)
    out_at, out_direct = np.full_like(A, np.nan), np.full_like(A, np.nan)
    _through_none(fp, 5, A, out_at)
    for i in range(3):
        _writer(5, A[i], out_direct[i])
    assert out_at.tobytes() == out_direct.tobytes()       # exact: the same compiled code
    assert np.array_equal(out_at, A + 5)                  # numpy's one rounding of each add (IEEE)
    with pytest.raises(ValueError, match="negative k"):
        _through_none(fp, -1, A, np.empty_like(A))
    with pytest.raises(TypeError, match="not int64"):     # call_at's return type is int64
        address(_writer, (typeof(5), *row_types((typeof(A), typeof(A)), (0, 1))))


def test_address_refuses_another_return_type():
    @njit
    def f(x):
        return x + 0.5
    with pytest.raises(TypeError, match="not int64"):
        address(f, (types.float64,))


def test_row_types_are_numbas_getitem():
    A = np.zeros((3, 4))
    F = np.asfortranarray(np.zeros((3, 4)))
    ro = np.zeros((2, 5, 6))
    ro.flags.writeable = False
    got = row_types((typeof(A), typeof(F), typeof(ro), types.int64), (0, 1, 2))
    assert got == (typeof(A[0]), types.Array(types.float64, 1, "A"), types.Array(types.float64, 2, "C", readonly=True),
                   types.int64)
