"""Numeric chair parameters: a :class:`~stability.chair.Chair` packed for the equations.

Signed body coordinates (x forward, y right, SAE axes), SI units; one chair
gives floats, a sequence of chairs gives arrays of shape (N,).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np

from stability.chair import Chair

__all__ = ["Params", "parameters"]


class Params(NamedTuple):
    """Numeric chair parameters in signed body coordinates (SI units).

    Each field is a float (one chair) or an ndarray (a batch of chairs).
    ``x_m`` and ``x_p`` are the signed x coordinates of the main axle and
    of the caster pins relative to the centre of gravity (positive forward).
    """

    x_m: Any
    x_p: Any
    d1: Any
    d2: Any
    t1: Any
    t2: Any
    trail: Any
    l1: Any
    h: Any
    m: Any
    m_c: Any
    i_z: Any
    i_zp: Any
    g: Any
    roll_k: Any
    pin_damping: Any
    pin_friction_left: Any
    pin_friction_right: Any

    @property
    def geometry(self) -> tuple:
        """(x_m, x_p, d1, d2, t1, t2, trail): arguments of the kinematics."""
        return (self.x_m, self.x_p, self.d1, self.d2, self.t1, self.t2, self.trail)

    @property
    def inertia(self) -> tuple:
        """(x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp): arguments of the dynamics."""
        return self.geometry + (self.l1, self.m, self.m_c, self.i_z, self.i_zp)


def _one(c: Chair) -> Params:
    return Params(
        float(c.x_main), float(c.x_pin), float(c.d1), float(c.d2), float(c.t1), float(c.t2),
        float(c.trail), float(c.l1), float(c.h), float(c.m), float(c.m_c), float(c.i_z),
        float(c.i_zp), float(c.g), float(c.roll_k), float(c.pin_damping),
        float(c.pin_friction_left), float(c.pin_friction_right),
    )


def parameters(chairs: Chair | Sequence[Chair]) -> Params:
    """Pack one chair (floats) or a sequence of chairs (arrays of shape (N,)) for the equations.

    Parameters
    ----------
    chairs : Chair or sequence of Chair
        One chair, or N >= 1 chairs to evaluate as a batch.

    Returns
    -------
    Params
        Signed body coordinates (m), masses (kg), inertias (kg m^2) and gravity
        (m/s^2): floats for one chair, arrays of shape (N,) for a sequence.

    Raises
    ------
    ValueError
        If ``chairs`` is an empty sequence.
    """
    if isinstance(chairs, Chair):
        return _one(chairs)
    rows = [_one(c) for c in chairs]
    if not rows:
        raise ValueError("chairs: expected a Chair or a non-empty sequence of Chair")
    return Params(*(np.array(col, dtype=float) for col in zip(*rows, strict=True)))
