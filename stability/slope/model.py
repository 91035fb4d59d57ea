"""The plane (cross slope, grade) and the tire forces of a chair on it at given normal loads: the statics.

What the equilibrium of :mod:`stability.slope.equilibrium` needs: gravity in
body axes (:mod:`stability.models.slope`), the contact velocities and slip
angles (generated), the tire fits (:mod:`stability.tires`), rolling resistance
and drive forces at the main-wheel contacts, and the tire-data range of the
result.  The chair's motion on a plane is the simulator's
(:func:`stability.simulate.simulate` with ``slope=``): one nonlinear model.
Camber and toe are not modelled on the plane (refused).  See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from stability.chair import Chair
from stability.models import full_width as fw
from stability.models import slope as sl
from stability.models.forces import slip_angle
from stability.models.params import parameters
from stability.tires import FZ_MAX_N, SLIP_MAX_DEG, WHEELS, LinearTire, get_policy
from stability.tires.ranges import RangeNote, limit_load, record

__all__ = ["Plane", "SlopeModel", "Forces", "MAX_ANGLE_DEG"]

#: Largest cross slope or grade accepted (deg); steeper planes are outside any tire data.
MAX_ANGLE_DEG = 20.0


def _check_angle(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = math.nan
    if not (math.isfinite(v) and abs(v) <= MAX_ANGLE_DEG):
        raise ValueError(f"{name}={value!r} is invalid; valid range: -{MAX_ANGLE_DEG:g} to {MAX_ANGLE_DEG:g} deg")
    return v


@dataclass(frozen=True)
class Plane:
    """The running surface.

    Attributes
    ----------
    cross_slope_deg : float
        Cross slope phi (deg); positive: the surface falls to the right of the path.
    grade_deg : float
        Grade theta (deg); positive: uphill along the path.
    """

    cross_slope_deg: float = 0.0
    grade_deg: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "cross_slope_deg", _check_angle("cross_slope", self.cross_slope_deg))
        object.__setattr__(self, "grade_deg", _check_angle("grade", self.grade_deg))

    def gravity(self, g: float, heading: float = 0.0) -> tuple[float, float, float]:
        """``(g1, g2, gn)`` (m/s^2) in body axes for a chair headed ``heading`` (rad) from the path."""
        return sl.gravity(g, math.radians(self.cross_slope_deg), math.radians(self.grade_deg), heading)


class Forces(NamedTuple):
    """Tire forces, normal loads and slip angles at one state (wheels A, B, D, E)."""

    F: tuple            #: ``(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy)`` in wheel frames, N (FDx, FEx with the drive)
    loads: tuple        #: normal loads, N
    slips_deg: tuple    #: signed slip angles ``atan2(vy, |vx|)``, deg


class SlopeModel:
    """A chair on a plane: its parameters, tires and the tire forces of a state at given loads (statics).

    Parameters
    ----------
    chair : Chair
        Camber and toe must be zero (not modelled on the plane).
    plane : Plane
    """

    def __init__(self, chair: Chair, plane: Plane):
        for name in ("camber_deg", "toe_deg"):
            if getattr(chair, name) != 0:
                raise ValueError(f"chair parameter {name}={getattr(chair, name)!r} is invalid for the slope "
                                 "model; valid range: 0 (camber and toe are not modelled on a slope)")
        self.chair = chair
        self.plane = plane
        self.p = parameters(chair)
        main, caster = chair.main_tire_model(), chair.caster_tire_model()
        self.tires = (caster, caster, main, main)       # wheels A, B, D, E
        self.rolling = (chair.caster_rolling_scale > 0,) * 2 + (chair.main_rolling_scale > 0,) * 2
        # --tire-range: clamp holds the forces at the data's edge, warn extrapolates the fits; both note a
        # load or slip beyond the data and answer; only raise refuses it (a range problem)
        self.policy = get_policy().name
        self.clamp = self.policy == "clamp"
        self._policy = "clamp" if self.clamp else "extrapolate"

    # -- tire data range -----------------------------------------------------
    def range_problems(self, f: Forces) -> list[str]:
        """Lifted wheels, slips beyond 8 deg and loads beyond 450 N of tested tires that the policy refuses.

        Under ``clamp`` a load or slip beyond the data is a tire-range note (the force held at the edge);
        under ``warn`` a load beyond it is a note (the smooth load polynomial extrapolated) but a slip
        beyond 8 deg stays a problem: the force saturates there, and whether the tires can hold the chair
        at all would rest on the extrapolated fit.
        """
        out = []
        labels = ("left caster", "right caster", "left main wheel", "right main wheel")
        for (key, _), wheel, tire, s, n in zip(WHEELS, labels, self.tires, f.slips_deg, f.loads, strict=True):
            if n <= 0.0:
                out.append(f"the {wheel} lifts off (normal load {n:.1f} N)")
                continue
            if isinstance(tire, LinearTire):
                continue
            if self.clamp:              # a note under the clamp policy (tires.collect_notes): the force held
                if n > FZ_MAX_N:
                    limit_load(tire, n, "clamp", wheel=key)
                if abs(s) > SLIP_MAX_DEG:
                    record(RangeNote(tire.name, "slip", abs(s), 0.0, SLIP_MAX_DEG, "clamp", key))
                continue
            if self.policy == "warn" and abs(s) <= SLIP_MAX_DEG:
                if n > FZ_MAX_N:        # warn: the load polynomial extrapolated, with a note (tires.collect_notes)
                    limit_load(tire, n, "warn", wheel=key)
                continue
            if abs(s) > SLIP_MAX_DEG:
                out.append(f"{wheel} slip {abs(s):.2f} deg beyond the tire data (|slip| <= {SLIP_MAX_DEG:g} deg)")
            if n > FZ_MAX_N:
                out.append(f"{wheel} load {n:.0f} N beyond the tire data (<= {FZ_MAX_N:g} N)")
        return out

    # -- forces ----------------------------------------------------------------
    def forces(self, u, v, r, ce, se, cb, sb, eta_d, beta_d, drive: tuple[float, float], loads: tuple) -> Forces:
        """Tire forces at a state and normal loads (N): the fits at the slip angles, rolling resistance and the
        drive forces ``drive = (FDx_drive, FEx_drive)`` (N) on the main wheels."""
        vel = fw.contact_velocities(self.p, u, v, r, ce, se, cb, sb, eta_d, beta_d, "exact")
        vx, vy = vel[0::2], vel[1::2]
        slips = tuple(slip_angle(a, b) for a, b in zip(vx, vy, strict=True))
        lat = [t.lateral_force(s, n, policy=self._policy, warn=False)
               for t, s, n in zip(self.tires, slips, loads, strict=True)]
        roll = [t.rolling_force(float(n), w) if k else 0.0
                for t, n, w, k in zip(self.tires, loads, vx, self.rolling, strict=True)]
        F = (roll[0], lat[0], roll[1], lat[1], roll[2] + drive[0], lat[2], roll[3] + drive[1], lat[3])
        return Forces(F=F, loads=tuple(float(n) for n in loads), slips_deg=slips)
