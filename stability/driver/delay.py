"""The driver's reaction delay as a linear system: the ``[n/n]`` Pade approximant of ``exp(-s tau)`` in state-space
form, kept per (delay, order) because a limit search closes thousands of loops with one delay."""

from __future__ import annotations

import functools
import math
from math import factorial

import numpy as np

__all__ = ["PADE_ORDER", "pade"]

#: Order of the Pade approximant of the driver's delay (numerator and denominator degree).
PADE_ORDER = 8


def pade(tau: float, order: int = PADE_ORDER, *, copy: bool = True
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """State-space form of the ``[order/order]`` Pade approximant of the delay ``exp(-s tau)``.

    Parameters
    ----------
    tau : float
        Delay, s (> 0).
    order : int
        Degree of numerator and denominator (>= 1).
    copy : bool
        Fresh writeable arrays (default), or the cached ones, shared and read-only (for loops that only read them).

    Returns
    -------
    (Ad, Bd, Cd, Dd)
        Shapes ``(n, n)``, ``(n, 1)``, ``(1, n)``, ``(1, 1)``: ``z' = Ad z + Bd w``, ``w(t - tau) ~ Cd z + Dd w``.
    """
    mats = _pade(*_checked(tau, order))
    return tuple(a.copy() for a in mats) if copy else mats  # type: ignore[return-value]


def _checked(tau: float, order: int) -> tuple[float, int]:
    """``(tau, order)`` as a float and an int, or ValueError naming the bad one."""
    if not (math.isfinite(tau) and tau > 0):
        raise ValueError(f"tau={tau!r} is invalid; valid range: > 0 s")
    if int(order) != order or order < 1:
        raise ValueError(f"order={order!r} is invalid; valid range: an integer >= 1")
    return float(tau), int(order)


@functools.lru_cache(maxsize=64)
def _pade(tau: float, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`pade`'s matrices, read-only, kept per (delay, order): a limit search evaluates thousands of closed
    loops with one delay, and ``tf2ss`` was half of each evaluation's time."""
    c = [factorial(2 * n - k) * factorial(n) / (factorial(2 * n) * factorial(k) * factorial(n - k))
         for k in range(n + 1)]
    num = [c[k] * (-tau) ** k for k in range(n, -1, -1)]
    den = [c[k] * tau**k for k in range(n, -1, -1)]
    from scipy.signal import tf2ss  # imported here: scipy.signal costs ~0.5 s CPU to import (every CLI)

    Ad, Bd, Cd, Dd = (np.asarray(a, dtype=float) for a in tf2ss(num, den))
    for a in (Ad, Bd, Cd, Dd):
        a.flags.writeable = False
    return Ad, Bd, Cd, Dd
