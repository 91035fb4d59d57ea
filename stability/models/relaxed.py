"""Linear full-width model with relaxation-length caster tires: the one door to its generated code.

Derived in ``derivations/full_width_relaxed.py`` and generated into
:mod:`stability._generated.full_width_relaxed`.  Variants ``"exact"`` and
``"thesis"`` (rigid pins, 8 states) and ``"pin_exact"`` (exact model, each
caster pin on a lateral spring, 12 states).  See docs/shimmy.md.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from stability._generated import full_width_relaxed as _gen
from stability.models.params import Params

__all__ = ["VARIANTS", "STATES", "relaxed_matrices"]

STATES: dict[str, tuple[str, ...]] = dict(_gen.STATES)
VARIANTS: tuple[str, ...] = tuple(STATES)


def relaxed_matrices(p: Params, speeds: Any, stiffness: dict[str, Any], relaxation_length: Any,
                     variant: str = "exact", pin_stiffness: Any = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Matrices of ``M acc = K x + Bm Mz`` and ``[F_A_dot, F_B_dot] = T x``, broadcast over speeds.

    Parameters
    ----------
    p : Params
        Chair parameters (one chair or a batch).
    speeds : float or array_like
        Forward speeds U > 0 (m/s).
    stiffness : dict
        Cornering stiffness at the static load, keys ``"A", "B", "D", "E"`` (N/rad).
    relaxation_length : float or array_like
        Caster tire relaxation length sigma (m), > 0.
    variant : {"exact", "thesis", "pin_exact"}
        Equations (see module docstring).
    pin_stiffness : float or array_like, optional
        Lateral pin stiffness (N/m); required for ``"pin_exact"``.

    Returns
    -------
    M : ndarray, shape (N, k, k)
    K : ndarray, shape (N, k, n)
    Bm : ndarray, shape (N, k)
    T : ndarray, shape (N, 2, n)
        ``k`` accelerations (4, or 6 with pins), ``n`` states :data:`STATES`.
    """
    if variant not in STATES:
        raise ValueError(f"variant={variant!r} is invalid; valid choices: {list(VARIANTS)}")
    U = np.atleast_1d(np.asarray(speeds, dtype=float))
    args: list[Any] = [U, stiffness["A"], stiffness["B"], stiffness["D"], stiffness["E"], p.pin_damping,
                       relaxation_length]
    if variant == "pin_exact":
        if pin_stiffness is None:
            raise ValueError("pin_stiffness=None is invalid for variant 'pin_exact'; valid range: > 0 N/m")
        args.append(pin_stiffness)
    M, K, Bm, T = getattr(_gen, f"linear_relaxed_{variant}")(*args, *p.inertia)
    entries = [e for row in (*M, *K, *T) for e in row] + list(Bm)
    shape = np.broadcast_shapes(U.shape, *(np.shape(e) for e in entries))

    def stack(rows):
        return np.stack([np.stack([np.broadcast_to(np.asarray(e, dtype=float), shape) for e in row], -1)
                         for row in rows], -2)

    Bv = np.stack([np.broadcast_to(np.asarray(e, dtype=float), shape) for e in Bm], -1)
    return stack(M), stack(K), Bv, stack(T)
