"""Tolerances from error models, for comparing two floating-point computations in the tests.

A test that compares two computations of the same quantity (compiled vs Python, batch vs single,
two LAPACK calls, eigenvalues of matrices equal in exact arithmetic) takes its tolerance from here,
so that the bound follows from the conditioning of the problem and the machine epsilon, not from a
guess that happened to pass on the processor the test was written on.

Error models
------------
eigenvalues
    A backward-stable eigensolver (LAPACK's QR algorithm) returns the exact eigenvalues of
    ``A + E`` with ``||E||_2 <= p(n) eps ||A||_2``; to first order eigenvalue ``i`` moves by at most
    ``kappa_i ||E||_2`` with ``kappa_i = 1 / |y_i^H x_i|`` (unit left and right eigenvectors
    ``y_i``, ``x_i``: Wilkinson's condition number).  ``p(n) = n`` here.
linear solves / matrix functions
    ``cond(A) * eps`` relative (forward error of a backward-stable solve).
trajectories
    Two integrations whose right-hand sides differ by at most ``delta`` (units of the state per
    second) differ at time T by at most ``kappa * delta * (exp(a T) - 1) / a`` (``delta T`` for
    a <= 0): variation of constants with ``||exp(A t)|| <= kappa exp(a t)``, ``a`` the growth rate
    and ``kappa`` the eigenvector-matrix condition number of the linearisation.  Fixed-step schemes
    whose arithmetic differs only in rounding have ``delta ~ eps * ||A|| * |y|`` per step, i.e. the
    per-step rounding grows as ``steps * eps`` times the growth factor.

Every helper returns the *bound*; the tests state next to each call what they observed, so the
margin (at least 100) is visible.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg
from scipy.optimize import linear_sum_assignment

EPS = float(np.finfo(float).eps)


def eig_condition_numbers(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues of ``A`` and their condition numbers ``kappa_i = 1 / |y_i^H x_i|`` (>= 1)."""
    w, vl, vr = scipy.linalg.eig(np.asarray(A, dtype=float), left=True, right=True)
    vl = vl / np.linalg.norm(vl, axis=0)
    vr = vr / np.linalg.norm(vr, axis=0)
    s = np.abs(np.sum(vl.conj() * vr, axis=0))
    with np.errstate(divide="ignore"):
        kappa = np.where(s > 0, 1.0 / s, np.inf)
    return w, kappa


def eig_tolerance(A: np.ndarray) -> np.ndarray:
    """First-order bound on the rounding error of each computed eigenvalue of ``A``.

    ``n * eps * ||A||_2 * kappa_i`` for eigenvalue ``i`` (the order of ``numpy.linalg.eigvals(A)``
    is not implied: the bounds are matched with :func:`assert_eigenvalues_match`).

    Returns
    -------
    (eigenvalues, bounds) : tuple of ndarray
    """
    A = np.asarray(A, dtype=float)
    w, kappa = eig_condition_numbers(A)
    return w, A.shape[0] * EPS * np.linalg.norm(A, 2) * kappa


def match_eigenvalues(a, b) -> tuple[np.ndarray, np.ndarray]:
    """Pair two eigenvalue sets by the assignment minimising the sum of ``|a_i - b_j|``."""
    a = np.asarray(a, dtype=complex).ravel()
    b = np.asarray(b, dtype=complex).ravel()
    assert a.shape == b.shape, f"eigenvalue sets of different sizes: {a.size} and {b.size}"
    rows, cols = linear_sum_assignment(np.abs(a[:, None] - b[None, :]))
    return rows, cols


def eig_bounds(values, A: np.ndarray | None, tol=None) -> np.ndarray:
    """Per-value rounding bounds for ``values``, eigenvalues of ``A`` computed anywhere, in their order.

    Each value takes the :func:`eig_tolerance` bound of the eigenvalue of ``A`` it is matched to,
    plus the explicit bounds ``tol`` if given.
    """
    values = np.asarray(values, dtype=complex).ravel()
    out = np.zeros(values.size)
    if tol is not None:
        out = out + np.broadcast_to(np.asarray(tol, dtype=float), values.shape)
    if A is not None:
        w, bound = eig_tolerance(A)
        # the bound belongs to the eigenvalue of A nearest each value
        r, c = match_eigenvalues(values, w)
        out[r] += bound[c]
    return out


def assert_eigenvalues_match(a, b, A: np.ndarray | None = None, B: np.ndarray | None = None, *,
                             tol_a=None, tol_b=None, safety: float = 1.0, what: str = "") -> float:
    """Assert that eigenvalue sets ``a`` and ``b`` agree within their rounding-error bounds.

    The sets are paired by a minimum-cost matching (not by sorting, which reorders near-ties);
    pair ``k`` may differ by the sum of the bounds of its two members: ``eig_tolerance`` of the
    matrix each set was computed from (``A`` for ``a``, ``B`` for ``b``), plus any explicit per-value
    bounds ``tol_a`` / ``tol_b`` (for values from other computations), times ``safety``.

    Returns
    -------
    float
        The largest ratio difference / bound (the margin actually used; < 1 passes).
    """
    a = np.asarray(a, dtype=complex).ravel()
    b = np.asarray(b, dtype=complex).ravel()
    r, c = match_eigenvalues(a, b)
    bound = safety * (eig_bounds(a, A, tol_a)[r] + eig_bounds(b, B, tol_b)[c])
    diff = np.abs(a[r] - b[c])
    assert np.all(np.isfinite(bound)) and np.all(bound > 0), f"{what}: no error bound for some eigenvalue"
    worst = int(np.argmax(diff / bound))
    ratio = float(diff[worst] / bound[worst])
    assert ratio <= 1.0, (f"{what}: eigenvalue {a[r][worst]} vs {b[c][worst]} differ by {diff[worst]:.3g} "
                          f"> bound {bound[worst]:.3g}")
    return ratio


def solve_tolerance(A: np.ndarray) -> float:
    """Relative forward-error bound ``n * eps * cond(A)`` of a backward-stable solve with ``A``."""
    A = np.asarray(A, dtype=float)
    return A.shape[0] * EPS * float(np.linalg.cond(A))


def transient_bound(A: np.ndarray) -> tuple[float, float]:
    """Growth rate ``a = max Re lambda`` and ``kappa = cond(V)`` with ``||exp(A t)|| <= kappa exp(a t)``."""
    w, V = np.linalg.eig(np.asarray(A, dtype=float))
    return float(np.max(w.real)), float(np.linalg.cond(V))


def trajectory_tolerance(rhs_error: float, duration: float, growth_rate: float = 0.0,
                         kappa: float = 1.0) -> float:
    """Bound on the difference of two trajectories whose right-hand sides differ by ``rhs_error``.

    ``kappa * rhs_error * (exp(a T) - 1) / a`` with ``a = growth_rate`` (``kappa * rhs_error * T``
    when ``a <= 0``), from the variation-of-constants formula for the linearisation with
    ``||exp(A t)|| <= kappa exp(a t)``.  ``rhs_error`` in units of the compared quantity per second
    (or relative to its size per second, giving a relative bound).
    """
    a = max(float(growth_rate), 0.0)
    grow = duration if a * duration < 1e-12 else math.expm1(a * duration) / a
    return float(kappa * rhs_error * grow)


def rounding_steps_tolerance(steps: int, growth_rate: float, duration: float, kappa: float = 1.0,
                             ops_per_step: float = 1.0) -> float:
    """Relative bound for two fixed-step integrations whose arithmetic differs only in rounding.

    Each step adds at most ``ops_per_step * eps`` (relative) of rounding, amplified afterwards by at
    most ``kappa * exp(a (T - t))``: ``steps * ops_per_step * eps * kappa * exp(max(a, 0) T)``.
    """
    return float(steps * ops_per_step * EPS * kappa * math.exp(max(float(growth_rate), 0.0) * duration))
