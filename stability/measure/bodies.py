"""Rigid bodies in the plane and their parallel-axis combination (Collins 1987, Appendix D).

Coordinates: x forward, y to the right (m), any common origin; ``i_z`` is the
yaw inertia about the body's own centre of gravity (kg m^2).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

__all__ = ["Body", "combine", "parallel_axis_correction", "separation_for_total_inertia"]


@dataclass(frozen=True)
class Body:
    """A rigid body in the plane: mass, c.g. position and yaw inertia about its own c.g.

    Attributes
    ----------
    mass : float
        Mass, kg (> 0).
    x : float
        c.g. x coordinate (forward), m; default 0.
    y : float
        c.g. y coordinate (to the right), m; default 0.
    i_z : float
        Yaw inertia about a vertical axis through the body's own c.g., kg m^2 (>= 0); default 0.
    name : str
        Label used in error messages and reports; default empty.
    """

    mass: float
    x: float = 0.0
    y: float = 0.0
    i_z: float = 0.0
    name: str = ""

    def __post_init__(self) -> None:
        for attr in ("mass", "x", "y", "i_z"):
            v = getattr(self, attr)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"body {self.name or '?'}: {attr}={v!r} is invalid; valid range: a finite number")
        if self.mass <= 0:
            raise ValueError(f"body {self.name or '?'}: mass={self.mass!r} is invalid; valid range: > 0 kg")
        if self.i_z < 0:
            raise ValueError(f"body {self.name or '?'}: i_z={self.i_z!r} is invalid; valid range: >= 0 kg m^2")


def combine(bodies: Iterable[Body], name: str = "combined") -> Body:
    """Total mass, c.g. and yaw inertia about the combined c.g. (parallel-axis theorem).

    ``I = sum_i [I_i + m_i ((x_i - x_G)^2 + (y_i - y_G)^2)]`` with
    ``x_G = sum m_i x_i / sum m_i`` (and y likewise).

    Parameters
    ----------
    bodies : iterable of Body
        At least one body.
    name : str
        Name of the result.

    Returns
    -------
    Body
        The combination.

    Examples
    --------
    Collins (1987) Appendix D: the 75 kg ISO dummy (3.1 kg m^2) and a 20 kg
    chair (2.3 kg m^2) with c.g.s 0.1125 m apart make 5.6 kg m^2:

    >>> round(combine([Body(75, 0.0, 0, 3.1), Body(20, -0.1125, 0, 2.3)]).i_z, 3)
    5.6
    """
    bodies = list(bodies)
    if not bodies:
        raise ValueError("combine() needs at least one body")
    m = sum(b.mass for b in bodies)
    x = sum(b.mass * b.x for b in bodies) / m
    y = sum(b.mass * b.y for b in bodies) / m
    i_z = sum(b.i_z + b.mass * ((b.x - x) ** 2 + (b.y - y) ** 2) for b in bodies)
    return Body(m, x, y, i_z, name)


def parallel_axis_correction(bodies: Iterable[Body]) -> float:
    """How much the combined yaw inertia exceeds the plain sum of the bodies' own (Appendix D).

    ``sum_i m_i ((x_i - x_G)^2 + (y_i - y_G)^2)``: the parallel-axis terms of :func:`combine`.

    Parameters
    ----------
    bodies : iterable of Body
        At least one body.

    Returns
    -------
    float
        The correction, kg m^2 (>= 0; 0 for one body).
    """
    bodies = list(bodies)
    return combine(bodies).i_z - sum(b.i_z for b in bodies)


def separation_for_total_inertia(mass_a: float, mass_b: float, i_a: float, i_b: float, total: float) -> float:
    """Distance between two bodies' c.g.s that makes their combined yaw inertia ``total``.

    For two bodies the parallel-axis correction is ``mu D^2`` with the reduced
    mass ``mu = m_a m_b / (m_a + m_b)``, so ``D = sqrt((I - I_a - I_b) / mu)``.

    Parameters
    ----------
    mass_a, mass_b : float
        Masses (kg).
    i_a, i_b : float
        Own yaw inertias (kg m^2).
    total : float
        Combined yaw inertia (kg m^2), at least ``i_a + i_b``.

    Returns
    -------
    float
        Separation D (m).
    """
    if total < i_a + i_b:
        raise ValueError(f"total={total!r} is invalid; valid range: >= i_a + i_b = {i_a + i_b:g} kg m^2")
    mu = mass_a * mass_b / (mass_a + mass_b)
    return math.sqrt((total - i_a - i_b) / mu)
