"""Caster compliance estimates (relaxation length, pin lateral stiffness) that the thesis does not give."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

__all__ = ["CasterCompliance", "ESTIMATE_NOTE"]

ESTIMATE_NOTE = ("caster tire relaxation length and frame lateral stiffness at the pin are not in Collins (1987): "
                 "the values used are literature-based estimates (relaxation length after Pacejka, Tyre and Vehicle "
                 "Dynamics, 2006; the shimmy documentation gives the sources)")


@dataclass(frozen=True)
class CasterCompliance:
    """Caster properties the thesis does not give: typical values, estimates.

    Attributes
    ----------
    relaxation_length : float
        Caster tire relaxation length sigma (m).  Default 0.02 m for the
        thesis's solid 7 3/4 x 1 1/8 in rubber casters (Table 3-1), from
        Pacejka's estimate ``sigma ~ C_alpha / C_y`` (cornering over lateral
        tire stiffness; Pacejka, *Tyre and Vehicle Dynamics*, 2006, sec. 5.3
        and ch. 7) with C_alpha ~ 1.5 kN/rad (Table 4-1) and C_y ~ 50-150
        kN/m for a solid 29 mm rubber tread, and from the brush model's lower
        bound ``sigma >= a`` (half contact length ~ 1 cm).  Range
        ``relaxation_length_range``: 0.01-0.04 m solid, 0.03-0.08 m for small
        pneumatic casters (carcass compliance raises C_y^-1).
    lateral_stiffness : float
        Lateral stiffness of frame, caster housing and fork at the pin (N/m).
        Default 5e4 N/m, range 2e4-2e5 N/m: a 22 x 1.5 mm steel tube
        cantilevered 0.3 m gives 3EI/l^3 ~ 1e5 N/m, fork and bearing play
        lower it.  Kauzlarich, Bruning and Thacker (J Rehabil Res Dev 37(3),
        2000, "Wheelchair caster shimmy II: Damping") stress that frame and
        fork compliance and tire flexibility govern caster shimmy; they give
        no value for this chair.
    relaxation_length_range : tuple of float
        ``(low, high)`` plausible relaxation lengths (m), default (0.01, 0.04):
        the range a design conclusion must be stated over.
    lateral_stiffness_range : tuple of float
        ``(low, high)`` plausible lateral stiffnesses at the pin (N/m),
        default (2e4, 2e5).
    """

    relaxation_length: float = 0.02
    lateral_stiffness: float = 5e4
    relaxation_length_range: tuple[float, float] = (0.01, 0.04)
    lateral_stiffness_range: tuple[float, float] = (2e4, 2e5)

    def __post_init__(self) -> None:
        for name in ("relaxation_length", "lateral_stiffness"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (v > 0):
                raise ValueError(f"caster compliance {name}={v!r} is invalid; valid range: > 0")
            lo, hi = getattr(self, name + "_range")
            if not 0 < lo <= hi:
                raise ValueError(f"caster compliance {name}_range=({lo!r}, {hi!r}) is invalid; valid: 0 < low <= high")

    def corners(self) -> list[CasterCompliance]:
        """The four combinations of the range limits (for stating a range, not a point)."""
        return [dataclasses.replace(self, relaxation_length=s, lateral_stiffness=k)
                for s in self.relaxation_length_range for k in self.lateral_stiffness_range]
