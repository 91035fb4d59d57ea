"""Tires by name: the seven tested tires of Table 3-1 and ``"linear:<C>"``."""

from __future__ import annotations

import functools
import math

from .data import _ALL, _cornering_coefficients, _rolling_coefficients, _table_3_2
from .linear_tire import AnyTire, LinearTire
from .model import Tire

__all__ = ["get", "names"]


def names() -> tuple[str, ...]:
    """Names of the tested tires, main wheels first (Table 3-1)."""
    return _ALL


@functools.cache
def _tested(name: str) -> Tire:
    rows, d, _ = _cornering_coefficients()[name]
    return Tire(
        name=name,
        rows=rows,
        intercepts=d,
        rolling=_rolling_coefficients().get(name),
        f_r=_table_3_2().get(name),
    )


def get(spec: str) -> AnyTire:
    """A tire by name or a linear tire by stiffness.

    Parameters
    ----------
    spec : str
        One of :func:`names` (case-insensitive), or ``"linear:<C>"`` with
        ``C`` the cornering stiffness in N/deg (load-independent).

    Returns
    -------
    Tire or LinearTire

    Raises
    ------
    ValueError
        Naming the parameter, the value and the valid choices.
    """
    if isinstance(spec, str):
        key = spec.strip()
        if key.lower().startswith("linear:"):
            text = key.split(":", 1)[1].strip()
            try:
                c = float(text)
            except ValueError:
                c = math.nan
            if not math.isfinite(c) or c < 0.0:
                raise ValueError(
                    f"spec={spec!r} is not valid: 'linear:<C>' needs a finite C >= 0 in N/deg"
                )
            return LinearTire(stiffness_N_per_deg=c)
        if key.upper() in _ALL:
            return _tested(key.upper())
    raise ValueError(
        f"spec={spec!r} is not valid; choose one of {_ALL} (any case) or 'linear:<C>' "
        "with C in N/deg"
    )
