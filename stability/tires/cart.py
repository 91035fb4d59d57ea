"""The single-wheel test cart of Collins (1987), Appendix A: load-cell reading to tire forces.

Eqs A-7 and A-10..A-16 (the six statics equations A-8 with rolling resistance
``F_x = f_r F_z``, eq A-9), solved in the order the thesis gives. Readings of
the OCR text are settled in ``docs/tires.md`` (the test derives A-10 from A-8).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from stability.runtime.checks import check_nonnegative, check_positive

__all__ = ["CartForces", "CartGeometry", "cart_forces"]


@dataclass(frozen=True)
class CartGeometry:
    """Dimensions of the test cart (Figure A-1) and the tire's rolling coefficient.

    Attributes
    ----------
    half_width_m : float
        ``d``: lateral distance from the tire contact to the cart centre line
        (the pin and the c.g. lie on it), m.
    wheel_radius_m : float
        ``r``: height of the axle (and the load cell) above the ground, m.
    cg_offset_m : float
        ``x_c``: longitudinal distance from the axle to the cart's c.g., m.
    pin_distance_m : float
        ``l``: longitudinal distance from the axle to the forward support pin, m.
    pin_height_m : float
        ``h``: height of the forward support rod (pin), m.
    cable_offset_m : float
        ``s``: lateral distance from the tire contact to the vertical support
        cable (where the removed right wheel was, about ``2 d``), m.
    rolling_coefficient : float
        ``f_r`` of eq A-9 (Table 3-2); 0 gives the approximation A-17/A-18.
    """

    half_width_m: float
    wheel_radius_m: float
    cg_offset_m: float
    pin_distance_m: float
    pin_height_m: float
    cable_offset_m: float
    rolling_coefficient: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in ("cg_offset_m", "rolling_coefficient"):
                check_nonnegative(f.name, value, prefix="cart ")
            else:
                check_positive(f.name, value, prefix="cart ")
        if self.cable_offset_m <= self.half_width_m:
            raise ValueError(f"cart cable_offset_m={self.cable_offset_m!r} is invalid; valid range: "
                             f"> half_width_m = {self.half_width_m:g} m (the cable is beyond the cart centre)")

    @classmethod
    def from_mapping(cls, values: dict[str, Any]) -> CartGeometry:
        """Build from a mapping of field names to numbers (e.g. a CSV header's ``# cart.*`` lines)."""
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(values) - known)
        if unknown:
            raise ValueError(f"unknown cart dimension(s) {unknown}; valid names: {sorted(known)}")
        return cls(**{k: float(v) for k, v in values.items()})


@dataclass(frozen=True)
class CartForces:
    """Forces on the tested tire and the cart's reactions (N), eqs A-10..A-16.

    Attributes
    ----------
    fz, fy, fx : float or ndarray
        Normal, lateral (cornering) and longitudinal (rolling) force on the tire.
    rx, ry, rz : float or ndarray
        Reactions at the forward support pin.
    tension : float or ndarray
        Tension in the vertical support cable (compare with a spring-scale
        reading: the thesis found agreement within 7 %).
    """

    fz: Any
    fy: Any
    fx: Any
    rx: Any
    ry: Any
    rz: Any
    tension: Any


def cart_forces(weight: ArrayLike, side_force: ArrayLike, slip_deg: ArrayLike, cart: CartGeometry) -> CartForces:
    """Tire forces from the cart weight and the load-cell side force, Appendix A.

    ``F_sx = F_s sin(alpha)``, ``F_sy = F_s cos(alpha)`` (A-7), then

    ``F_z = [W (l - x_c)(s - d) + F_sy r l + F_sx (r s - h s - r d)] /
    [f_r (h s + r d - s r) + l s]`` (A-10), ``F_x = f_r F_z`` (A-11),
    ``R_x = F_x + F_sx`` (A-12), ``R_y = R_x d / l`` (A-13),
    ``F_y = F_sy - R_y`` (A-14), ``R_z = (R_x h + W x_c - F_sx r - F_x r) / l``
    (A-15), ``T = W - R_z - F_z`` (A-16).

    Parameters
    ----------
    weight : float or array_like
        Total cart weight ``W``, N.
    side_force : float or array_like
        Load-cell side force ``F_s``, N.
    slip_deg : float or array_like
        Slip angle ``alpha`` of the cart, deg (0 for the camber tests).
    cart : CartGeometry

    Returns
    -------
    CartForces
    """
    w = np.asarray(weight, dtype=float)
    fs = np.asarray(side_force, dtype=float)
    alpha = np.radians(np.asarray(slip_deg, dtype=float))
    fsx, fsy = fs * np.sin(alpha), fs * np.cos(alpha)
    d, r, xc = cart.half_width_m, cart.wheel_radius_m, cart.cg_offset_m
    ll, h, s, fr = cart.pin_distance_m, cart.pin_height_m, cart.cable_offset_m, cart.rolling_coefficient
    fz = ((w * (ll - xc) * (s - d) + fsy * r * ll + fsx * (r * s - h * s - r * d))
          / (fr * (h * s + r * d - s * r) + ll * s))
    fx = fr * fz
    rx = fx + fsx
    ry = rx * d / ll
    fy = fsy - ry
    rz = (rx * h + w * xc - fsx * r - fx * r) / ll
    tension = w - rz - fz
    out = [fz, fy, fx, rx, ry, rz, tension]
    if all(np.ndim(v) == 0 for v in (weight, side_force, slip_deg)):
        out = [float(v) for v in out]
    return CartForces(*out)

