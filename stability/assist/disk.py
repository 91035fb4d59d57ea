"""Disk margins of a SISO loop (python-control's :func:`control.disk_margins`), the worst frequency refined.

The balanced disk margin (skew 0; Seiler, Packard & Gahinet 2020, "An introduction to disk margins", IEEE
Control Systems Magazine 40(5), 78-95) is the largest ``alpha`` such that the loop stays stable for every
complex gain ``f = (1 + delta / 2) / (1 - delta / 2)`` with ``|delta| < alpha`` inserted at the loop break:
simultaneous gain and phase changes, where the classical margins take one at a time.  For a SISO loop
``alpha = 1 / max_w |S(jw) - T(jw)| / 2 = min_w 2 |1 + L(jw)| / |1 - L(jw)|``; the loop then tolerates gains in
``[(1 - alpha/2) / (1 + alpha/2), (1 + alpha/2) / (1 - alpha/2)]`` (the disk gain margin, symmetric in dB) or
phase changes up to ``2 atan(alpha / 2)`` (the disk phase margin), each of which is at most the classical one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import control
import numpy as np

__all__ = ["DiskMargins", "disk_margins", "NO_DISK_MARGINS"]


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


def disk_margins(L: Any, w: np.ndarray) -> DiskMargins:
    """Balanced disk margin of the SISO loop ``L`` (nominal closed loop assumed stable).

    :func:`control.disk_margins` (skew 0) on the grid ``w``, then again on a fine grid between the neighbours
    of the grid's worst frequency, so the minimum is found to the function's own smoothness (relative 1e-8 or
    better), not to the grid's spacing.

    Parameters
    ----------
    L : control.StateSpace
        Continuous or discrete (then ``w`` up to the Nyquist frequency ``pi / dt``).
    w : ndarray
        Increasing frequencies (rad/s).

    Returns
    -------
    DiskMargins
    """
    dm = np.asarray(control.disk_margins(L, w, skew=0.0, returnall=True)[0], dtype=float)
    i = int(np.argmin(dm))
    fine = np.linspace(w[max(i - 1, 0)], w[min(i + 1, len(w) - 1)], 401)
    dm_f, dgm_f, dpm_f = (np.asarray(x, dtype=float)
                          for x in control.disk_margins(L, fine, skew=0.0, returnall=True))
    j = int(np.argmin(dm_f))
    if dm_f[j] > dm[i]:          # cannot happen for a smooth minimum inside the bracket; keep the grid's
        alpha = float(dm[i])
        return DiskMargins(alpha, _gain_db(alpha), _phase_deg(alpha), float(w[i]))
    return DiskMargins(float(dm_f[j]), float(dgm_f[j]), float(dpm_f[j]), float(fine[j]))


def _gain_db(alpha: float) -> float:
    """Disk-based gain margin (dB) of a balanced disk of radius ``alpha``."""
    return math.inf if alpha >= 2.0 else 20.0 * math.log10((1 + alpha / 2) / (1 - alpha / 2))


def _phase_deg(alpha: float) -> float:
    """Disk-based phase margin (deg) of a balanced disk of radius ``alpha``."""
    return math.degrees(2.0 * math.atan(alpha / 2.0))
