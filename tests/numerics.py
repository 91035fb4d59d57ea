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
import os
import sys

import numpy as np
import scipy.linalg
from scipy.optimize import linear_sum_assignment

EPS = float(np.finfo(float).eps)
#: factor between a first-order rounding estimate and the tolerance a test uses (developers' guide: a
#: margin of at least 100 over what is observed)
SAFETY = 100.0


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


def match_eigenvalues(a, b, subset: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Pair two eigenvalue sets by the assignment minimising the sum of ``|a_i - b_j|``.

    ``subset``: ``a`` may be a subset of ``b`` (each value of ``a`` paired with a distinct one of ``b``).
    """
    a = np.asarray(a, dtype=complex).ravel()
    b = np.asarray(b, dtype=complex).ravel()
    ok = a.size <= b.size if subset else a.size == b.size
    assert ok, f"eigenvalue sets of sizes {a.size} and {b.size}"
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
        r, c = match_eigenvalues(values, w, subset=True)
        out[r] += bound[c]
    return out


def assert_eigenvalues_match(a, b, A: np.ndarray | None = None, B: np.ndarray | None = None, *,
                             tol_a=None, tol_b=None, safety: float = SAFETY, what: str = "") -> float:
    """Assert that eigenvalue sets ``a`` and ``b`` agree within their rounding-error bounds.

    The sets are paired by a minimum-cost matching (not by sorting, which reorders near-ties);
    pair ``k`` may differ by the sum of the bounds of its two members: ``eig_tolerance`` of the
    matrix each set was computed from (``A`` for ``a``, ``B`` for ``b``), plus any explicit per-value
    bounds ``tol_a`` / ``tol_b`` (for values from other computations), times ``safety``.  The
    first-order bounds estimate the size of the rounding error rather than bound it strictly (the
    backward-error constant of LAPACK's QR algorithm is a modest function of n, taken as n); observed
    differences reach 0.3 of them (the time-scaled towed wheel), so the default ``safety`` = 100 keeps
    a margin of more than 100 over every difference observed in the suite.

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
    if os.environ.get("NUMERICS_REPORT"):                   # margins for the record: difference / bound
        print(f"numerics-ratio {ratio:.3g} {what}", file=sys.stderr)
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


def poly_root_tolerance(coeffs, roots, coeff_error=None) -> np.ndarray:
    """First-order bound on the error of each root of ``p(s) = sum_k c_k s^(n-k)`` (numpy order).

    A root moves by ``sum_k |dc_k| |lambda|^(n-k) / |p'(lambda)|`` when the coefficients move by
    ``dc_k``.  ``coeff_error`` (absolute, per coefficient) defaults to the rounding of coefficients
    accumulated from the roots, ``n eps`` times the coefficients of ``prod (s + |lambda_i|)`` (each
    coefficient is a sum of products of roots; this bounds the sum of the magnitudes of its terms),
    which also covers ``numpy.roots`` (eigenvalues of the companion matrix, backward stable in the
    coefficients up to a factor of order n).
    """
    c = np.asarray(coeffs, dtype=complex).ravel()
    lam = np.asarray(roots, dtype=complex).ravel()
    n = c.size - 1
    if coeff_error is None:
        coeff_error = 4 * n * EPS * np.abs(c[0]) * np.abs(np.poly(-np.abs(lam)))
    dp = np.polyval(np.polyder(c), lam)
    powers = np.abs(lam)[:, None] ** np.arange(n, -1, -1)[None, :]
    return (powers @ np.asarray(coeff_error, dtype=float)) / np.abs(dp)


def fixed_step_tolerance(A: np.ndarray, dt: float, duration: float) -> float:
    """Relative bound for two fixed-step runs (step ``dt``) whose arithmetic differs only in rounding.

    Each step ``y + dt f(y)`` rounds at the level ``eps (1 + dt ||A||_2)`` of the state (``A`` the
    linearisation, ``||A||`` bounding ``|f| / |y|``); a difference made at step k is amplified by at most
    ``kappa exp(a (T - t_k))`` (:func:`transient_bound`), so after ``T / dt`` steps the runs differ by at
    most ``(T / dt) eps (1 + dt ||A||) kappa exp(max(a, 0) T)`` of the state's size, times :data:`SAFETY`.
    """
    a, kappa = transient_bound(A)
    steps = math.ceil(duration / dt - 1e-9)
    norm = float(np.linalg.norm(np.asarray(A, dtype=float), 2))
    return SAFETY * rounding_steps_tolerance(steps, a, duration, kappa, ops_per_step=1.0 + dt * norm)


def run_tolerance(chair, speed: float, duration: float, dt: float = 0.001, model: str = "thesis",
                  casters: str = "free") -> float:
    """:func:`fixed_step_tolerance` for a simulator run of ``chair`` at ``speed`` (its linearisation)."""
    from stability.linear import state_matrices

    return fixed_step_tolerance(state_matrices(chair, speed, model=model, casters=casters)[0], dt, duration)


def assert_signals_close(a, b, names, tol: float, what: str = "") -> float:
    """Each named signal of results ``a`` and ``b`` agrees to ``tol`` of its largest magnitude.

    Returns the largest ratio difference / allowed difference (< 1 passes; printed when
    ``NUMERICS_REPORT`` is set).
    """
    worst = 0.0
    for name in names:
        x, y = np.asarray(getattr(a, name), dtype=float), np.asarray(getattr(b, name), dtype=float)
        assert x.shape == y.shape, (name, x.shape, y.shape)
        scale = max(float(np.max(np.abs(y), initial=0.0)), float(np.max(np.abs(x), initial=0.0)), 1e-300)
        ratio = float(np.max(np.abs(x - y), initial=0.0)) / (tol * scale)
        worst = max(worst, ratio)
        assert ratio <= 1.0, f"{what} {name}: differ by {ratio * tol:.3g} of the signal's size > {tol:.3g}"
    if os.environ.get("NUMERICS_REPORT"):
        print(f"numerics-ratio {worst:.3g} {what}", file=sys.stderr)
    return worst


def adaptive_run_tolerance(chair, speed: float, duration: float, rtol: float, steps: int, model: str = "thesis",
                           casters: str = "free") -> float:
    """Relative bound for two error-controlled runs of the same equations that may take different steps.

    LSODA keeps each step's local error within ``rtol`` of the state; a rounding-level difference can
    change its step decisions, after which the runs differ by up to the sum of their global errors:
    ``2 steps rtol kappa exp(max(a, 0) T)`` of the state's size (each local error grown by at most
    ``kappa exp(a (T - t))``; ``steps`` at most the number of right-hand-side evaluations).
    """
    from stability.linear import state_matrices

    a, kappa = transient_bound(state_matrices(chair, speed, model=model, casters=casters)[0])
    return float(2 * steps * rtol * kappa * math.exp(max(a, 0.0) * duration))


def growth_rate_tolerance(A: np.ndarray) -> float:
    """Bound on the difference of two computations of ``max Re lambda(A)`` (the growth rate, 1/s).

    The largest real part moves by at most the largest move of a matched eigenvalue, each within
    ``n eps ||A|| kappa_i`` (:func:`eig_tolerance`) per computation: ``2 SAFETY max_i bound_i``.
    """
    return float(2 * SAFETY * np.max(eig_tolerance(A)[1]))
