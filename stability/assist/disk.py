"""Disk margins of a SISO loop, the worst frequency refined, and the loop's frequency response in one solve.

The balanced disk margin (skew 0; Seiler, Packard & Gahinet 2020, "An introduction to disk margins", IEEE
Control Systems Magazine 40(5), 78-95) is the largest ``alpha`` such that the loop stays stable for every
complex gain ``f = (1 + delta / 2) / (1 - delta / 2)`` with ``|delta| < alpha`` inserted at the loop break:
simultaneous gain and phase changes, where the classical margins take one at a time.  For a SISO loop
``alpha = 1 / max_w |S(jw) - T(jw)| / 2 = min_w 2 |1 + L(jw)| / |1 - L(jw)|``; the loop then tolerates gains in
``[(1 - alpha/2) / (1 + alpha/2), (1 + alpha/2) / (1 - alpha/2)]`` (the disk gain margin, symmetric in dB) or
phase changes up to ``2 atan(alpha / 2)`` (the disk phase margin), each of which is at most the classical one.

The margin is that closed form on the loop's frequency response (:func:`frequency_response`: every frequency in
one batched solve of the resolvent, where :func:`control.disk_margins` and a state-space system's ``__call__``
without Slycot solve one frequency at a time, about ten times slower); python-control's own
:func:`control.disk_margins` is the independent check (tests/test_assist_top_speed.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import control
import numpy as np

__all__ = ["DiskMargins", "disk_margins", "NO_DISK_MARGINS", "frequency_response"]


@dataclass(frozen=True)
class DiskMargins:
    """Balanced (skew 0) disk margin of a loop and the gain and phase it guarantees.

    Attributes
    ----------
    alpha : float
        The disk margin (-): the radius of the largest disk of ``delta`` the loop tolerates.
    gain_db : float
        Disk-based gain margin (dB): the gain may rise or fall by this much.
    phase_deg : float
        Disk-based phase margin (deg).
    frequency_rad_s : float or None
        Frequency of the worst case (rad/s; None when the loop has no margin to report).
    """

    alpha: float
    gain_db: float
    phase_deg: float
    frequency_rad_s: float | None


#: What an unstable nominal loop has: no margin.
NO_DISK_MARGINS = DiskMargins(0.0, 0.0, 0.0, None)


def frequency_response(L: Any, w: Any) -> np.ndarray:
    """``L`` of a SISO state-space loop at the frequencies ``w``: ``C (x I - A)^-1 B + D`` with ``x = j w``
    (continuous) or ``x = exp(j w dt)`` (discrete), every frequency in one batched solve.

    Parameters
    ----------
    L : control.StateSpace
        One input, one output.
    w : array_like
        Frequencies, rad/s.

    Returns
    -------
    ndarray
        Complex, the shape of ``w`` (flattened to 1-D).
    """
    A, B, C, D = (np.asarray(m, dtype=float) for m in (L.A, L.B, L.C, L.D))
    w = np.atleast_1d(np.asarray(w, dtype=float)).reshape(-1)
    x = np.exp(1j * w * float(L.dt)) if control.isdtime(L, strict=True) else 1j * w
    n = A.shape[0]
    if n == 0:
        return np.full(w.shape, D[0, 0], dtype=complex)
    X = np.linalg.solve(x[:, None, None] * np.eye(n) - A, np.broadcast_to(B[:, :1], (x.size, n, 1)))
    return (X[:, :, 0] @ C[0]) + D[0, 0]


def _alpha(L: Any, w: np.ndarray, response: np.ndarray | None = None) -> np.ndarray:
    """``2 |1 + L| / |1 - L|`` at the frequencies ``w`` (inf where ``L = 1``; ``response``: ``L`` there if known)."""
    Lw = frequency_response(L, w) if response is None else response
    with np.errstate(divide="ignore"):
        return 2.0 * np.abs(1.0 + Lw) / np.abs(1.0 - Lw)


def disk_margins(L: Any, w: np.ndarray, response: np.ndarray | None = None) -> DiskMargins:
    """Balanced disk margin of the SISO loop ``L`` (nominal closed loop assumed stable).

    ``alpha = min 2 |1 + L| / |1 - L|`` (the module's closed form, python-control's :func:`control.disk_margins`
    at skew 0) on the grid ``w``, then on a fine grid between the neighbours of the grid's worst frequency, so
    the minimum is found to the function's own smoothness (relative 1e-8 or better), not to the grid's spacing.

    Parameters
    ----------
    L : control.StateSpace
        Continuous or discrete (then ``w`` up to the Nyquist frequency ``pi / dt``).
    w : ndarray
        Increasing frequencies (rad/s).
    response : ndarray, optional
        :func:`frequency_response` of ``L`` at ``w`` when the caller has it (complex, the shape of ``w``).

    Returns
    -------
    DiskMargins
    """
    dm = _alpha(L, w, response)
    i = int(np.argmin(dm))
    fine = np.linspace(w[max(i - 1, 0)], w[min(i + 1, len(w) - 1)], 401)
    dm_f = _alpha(L, fine)
    j = int(np.argmin(dm_f))
    best, at = (float(dm[i]), float(w[i])) if dm_f[j] > dm[i] else (float(dm_f[j]), float(fine[j]))
    return DiskMargins(best, _gain_db(best), _phase_deg(best), at)   # the grid's when the bracket holds no less


def _gain_db(alpha: float) -> float:
    """Disk-based gain margin (dB) of a balanced disk of radius ``alpha``."""
    return math.inf if alpha >= 2.0 else 20.0 * math.log10((1 + alpha / 2) / (1 - alpha / 2))


def _phase_deg(alpha: float) -> float:
    """Disk-based phase margin (deg) of a balanced disk of radius ``alpha``."""
    return math.degrees(2.0 * math.atan(alpha / 2.0))
