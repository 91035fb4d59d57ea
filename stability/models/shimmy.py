"""Towed-wheel shimmy equations: the one door to :mod:`stability._generated.shimmy`.

The derivation is ``derivations/shimmy.py`` (Lagrange's equations with a
multiplier for the no-side-slip tire, linearised).  Four configurations
(``"<pivot>_<tire>"``, each ``rigid`` or ``compliant``) are available; every
function broadcasts over an array of speeds.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from stability._generated import shimmy as _gen

__all__ = ["CASES", "STATES", "case_name", "state_matrices", "characteristic_coefficients"]

STATES: dict[str, tuple[str, ...]] = dict(_gen.STATES)
CASES: tuple[str, ...] = tuple(STATES)
ARGUMENTS = ("mass", "inertia", "a", "b", "k", "C", "sigma", "c")


def case_name(rigid_pivot: bool, rigid_tire: bool) -> str:
    """Configuration key, e.g. ``"compliant_rigid"`` (compliant pivot, rigid tire).

    Parameters
    ----------
    rigid_pivot : bool
        True for a pivot fixed laterally, False for a pivot on a lateral spring k (N/m).
    rigid_tire : bool
        True for a tire without side slip, False for a tire with relaxation length sigma (m).

    Returns
    -------
    str
        ``"<pivot>_<tire>"``, each ``rigid`` or ``compliant``: one of :data:`CASES`.
    """
    return f"{'rigid' if rigid_pivot else 'compliant'}_{'rigid' if rigid_tire else 'compliant'}"


def _function(prefix: str, case: str) -> Callable[..., Any]:
    if case not in STATES:
        raise ValueError(f"case={case!r} is invalid; valid choices: {list(CASES)}")
    return getattr(_gen, f"{prefix}_{case}")


def _stack(entries, shape: tuple[int, ...]) -> np.ndarray:
    """The entries (scalars or arrays broadcasting to ``shape``) along a last axis, as floats: each written into its
    slot (the same values as stacking their broadcasts, without an array view per entry)."""
    entries = list(entries)
    out = np.empty(shape + (len(entries),))
    for i, e in enumerate(entries):
        out[..., i] = e
    return out


def _matrix(rows, shape: tuple[int, ...]) -> np.ndarray:
    """:func:`_stack` of each row along the second-last axis: shape ``shape + (rows, columns)``."""
    rows = [list(r) for r in rows]
    out = np.empty(shape + (len(rows), len(rows[0]) if rows else 0))
    for i, r in enumerate(rows):
        for j, e in enumerate(r):
            out[..., i, j] = e
    return out


def _shape(params: dict[str, Any], U: np.ndarray) -> tuple[int, ...]:
    return np.broadcast_shapes(U.shape, *(np.shape(params[k]) for k in ARGUMENTS))


def state_matrices(case: str, params: dict[str, float], speeds: Any) -> tuple[np.ndarray, np.ndarray]:
    """State matrix and pin-torque input column, ``x_dot = A x + B T``.

    Parameters
    ----------
    case : str
        One of :data:`CASES`.
    params : dict
        ``mass`` (kg), ``inertia`` (about the c.g., kg m^2), ``a`` (c.g. to
        contact, m), ``b`` (pivot to c.g., m), ``k`` (pivot lateral
        stiffness, N/m), ``C`` (cornering stiffness, N/rad), ``sigma``
        (relaxation length, m), ``c`` (viscous pin damping, N m s/rad);
        entries a case does not use may hold any finite placeholder.  Every
        entry may be an array; all broadcast together with ``speeds``.
    speeds : float or array_like
        Forward speeds (m/s).

    Returns
    -------
    A : ndarray, shape (..., n, n)
    B : ndarray, shape (..., n)
    """
    U = np.asarray(speeds, dtype=float)
    rows, col = _function("state_space", case)(*(params[k] for k in ARGUMENTS), U)
    shape = _shape(params, U)
    return _matrix(rows, shape), _stack(col, shape)


def characteristic_coefficients(case: str, params: dict[str, float], speeds: Any) -> np.ndarray:
    """Characteristic polynomial coefficients, highest power first, shape (..., n + 1).

    The leading coefficient is a positive product of parameters (the
    polynomial is ``det(s I - A)`` cleared of denominators).

    Parameters
    ----------
    case : str
        One of :data:`CASES` (see :func:`case_name`).
    params : dict of str to float or ndarray
        ``mass`` (kg), ``inertia`` (kg m^2), ``a``, ``b`` (m), ``k`` (N/m), ``C``
        (N/rad), ``sigma`` (m), ``c`` (N m s/rad), as for :func:`state_matrices`.
    speeds : float or array_like
        Forward speeds (m/s), broadcast with the parameters.

    Returns
    -------
    numpy.ndarray
        Shape (..., n + 1) with n the case's number of states; the roots (1/s)
        are the eigenvalues of :func:`state_matrices`' A.
    """
    U = np.asarray(speeds, dtype=float)
    coeffs = _function("characteristic", case)(*(params[k] for k in ARGUMENTS), U)
    return _stack(coeffs, _shape(params, U))
