"""The tested range of the tire fits and what happens outside it (policies, warnings).

See ``docs/tires.md`` ("Outside the data").
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from .data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = ["POLICIES", "Policy", "TireRangeWarning", "out_of_range"]

#: Out-of-range policies of :meth:`Tire.lateral_force`.
POLICIES: tuple[str, ...] = ("clamp", "extrapolate", "raise")

Policy = Literal["clamp", "extrapolate", "raise"]


class TireRangeWarning(UserWarning):
    """Warning: a tire force was asked for outside the tested range.

    Emitted at most once per call of :meth:`Tire.lateral_force` (and the
    methods built on it) when ``|slip| > 8 deg`` or ``F_z > 450 N`` and the
    policy is ``"clamp"`` or ``"extrapolate"``.
    """



def out_of_range(slip_deg: ArrayLike, fz: ArrayLike) -> tuple[Any, Any]:
    """Masks of inputs outside the tested range, without warnings.

    Parameters
    ----------
    slip_deg : array_like
        Slip angle(s), deg.
    fz : array_like
        Normal force(s), N.

    Returns
    -------
    slip_mask, fz_mask : bool or ndarray of bool
        ``|slip| > 8 deg`` and ``fz > 450 N`` (broadcast together). Python
        bools for scalar inputs.
    """
    if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
        return abs(slip_deg) > SLIP_MAX_DEG, fz > FZ_MAX_N
    s, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
    return np.abs(s) > SLIP_MAX_DEG, f > FZ_MAX_N


def _check_policy(policy: str) -> None:
    if policy not in POLICIES:
        raise ValueError(f"policy={policy!r} is not valid; choose one of {POLICIES}")


def _range_message(n_slip: int, n_fz: int, n_total: int, policy: str) -> str:
    return (
        f"{n_slip + n_fz} out-of-range input(s) among {n_total} point(s) "
        f"(|slip| > {SLIP_MAX_DEG:g} deg: {n_slip}, Fz > {FZ_MAX_N:g} N: {n_fz}); "
        f"policy {policy!r} applied"
    )
