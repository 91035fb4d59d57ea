"""A hypothetical load-independent linear tire (``"linear:<C>"``), for chairs whose tires were never tested."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stability.tires import law
from stability.tires.base import TireCapabilities, _CamberForce
from stability.tires.model import _DEG_PER_RAD, Tire, law_on_arrays
from stability.tires.ranges import POLICIES, Policy, _check_policy, resolve

__all__ = ["AnyTire", "LinearTire"]


@dataclass(frozen=True)
class LinearTire(_CamberForce):
    """A hypothetical linear tire: ``F_y = -C * slip`` independent of load.

    For chairs whose tires were never tested (``get("linear:<C>")``). Same
    methods as :class:`Tire`; nothing is out of range for a linear tire
    (``policy`` only validates its argument), and ``fz <= 0`` still gives
    zero force.

    Attributes
    ----------
    stiffness_N_per_deg : float
        Cornering stiffness ``C`` (N/deg).
    f_r : float
        Linear coefficient of rolling resistance (eq 3-2), default 0.
    camber_coef : float or None
        Camber coefficient ``f_c``; None means none given.
    lateral_scale, rolling_scale : float
        Force multipliers as for :class:`Tire`.
    """

    stiffness_N_per_deg: float
    f_r: float = 0.0
    camber_coef: float | None = None
    lateral_scale: float = 1.0
    rolling_scale: float = 1.0

    @property
    def name(self) -> str:
        """``"linear:<C>"``."""
        return f"linear:{self.stiffness_N_per_deg:g}"

    #: Nothing is out of range for a linear tire.
    slip_max_deg = math.inf
    fz_max_N = math.inf
    source = "hypothetical linear tire"
    is_thesis_tire = False

    @property
    def capabilities(self) -> TireCapabilities:
        """Cornering and rolling (``f_r``, default 0) always; camber only when ``camber_coef`` is given."""
        return TireCapabilities(name=self.name, camber=self.camber_coef is not None, rolling=True)

    @property
    def is_caster(self) -> bool:
        """Always False (a linear tire is not one of the tested casters)."""
        return False

    @property
    def coefficients(self) -> NDArray[np.float64]:
        """``(9, 3)`` equivalent table: ``F_k = C k``, not a cubic in ``F_z``.

        A linear tire has no load dependence, so no ``(a, b, c)`` exist;
        this returns NaN except the zero row.
        """
        arr = np.full((9, 3), np.nan)
        arr[0] = 0.0
        return arr

    def lateral_force(
        self,
        slip_deg: ArrayLike,
        fz: ArrayLike,
        *,
        policy: Policy = "clamp",
        warn: bool = True,
    ) -> Any:
        """Lateral force ``-C * slip * lateral_scale`` (N); 0 where ``fz <= 0``."""
        if policy not in POLICIES:
            _check_policy(policy)
        k = self.stiffness_N_per_deg * self.lateral_scale
        scalar = isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float))
        return law_on_arrays(lambda x, y: law.lateral_force(law.LINEAR, None, k, None, x, y, 0)[0],
                             np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float), scalar=scalar)

    def cornering_stiffness(self, fz: ArrayLike, *, include_intercept: bool = False,
                            policy: str | None = None, wheel: str | None = None) -> Any:
        """``C * lateral_scale`` (N/deg) wherever ``fz > 0``; ``policy`` is only validated (no range)."""
        resolve(policy)
        k = self.stiffness_N_per_deg * self.lateral_scale
        if isinstance(fz, (int, float)):
            return k if fz > 0.0 else 0.0
        return np.where(np.asarray(fz, dtype=float) > 0.0, k, 0.0)

    def cornering_stiffness_per_rad(self, fz: ArrayLike, *, include_intercept: bool = False,
                                    policy: str | None = None, wheel: str | None = None) -> Any:
        """Cornering stiffness in N/rad."""
        return self.cornering_stiffness(fz, policy=policy) * _DEG_PER_RAD

    @property
    def has_camber_data(self) -> bool:
        """True when a camber coefficient was given."""
        return self.camber_coef is not None

    @property
    def camber_coefficient(self) -> float:
        """The given camber coefficient; ValueError when none was given."""
        if self.camber_coef is None:
            raise ValueError(f"tire {self.name!r} (a linear tire) has no camber coefficient; "
                             "pass camber_coefficient= explicitly")
        return self.camber_coef

    def rolling_resistance(self, fz: ArrayLike) -> Any:
        """``f_r * fz * rolling_scale`` (N), eq (3-2); 0 where ``fz <= 0``."""
        coef, scale = (self.f_r, 0.0, 0.0), self.rolling_scale
        return law_on_arrays(lambda f: law.rolling_resistance(law.ROLLING_LINEAR, coef, scale, f),
                             np.asarray(fz, dtype=float), scalar=isinstance(fz, (int, float)))

    def rolling_force(self, fz: float, vx: float) -> float:
        """Rolling-resistance force (N) opposing the rolling velocity ``vx`` (m/s): ``-sign(vx) f_r fz``."""
        return float(law.rolling_force(law.ROLLING_LINEAR, (self.f_r, 0.0, 0.0), self.rolling_scale, float(fz),
                                       float(vx)))

    @property
    def rolling_coefficient_linear(self) -> float:
        """``f_r``."""
        return self.f_r

    def scaled(self, lateral: float = 1.0, rolling: float = 1.0) -> LinearTire:
        """A copy with the force multipliers compounded (TYMOD/TXMOD)."""
        return LinearTire(
            stiffness_N_per_deg=self.stiffness_N_per_deg,
            f_r=self.f_r,
            camber_coef=self.camber_coef,
            lateral_scale=self.lateral_scale * float(lateral),
            rolling_scale=self.rolling_scale * float(rolling),
        )


#: Either kind of tire (what :func:`stability.tires.get` returns).
AnyTire = Tire | LinearTire
