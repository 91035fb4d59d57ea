"""Forces and equations of motion of a chair on a plane (cross slope, grade).

The exact full-width model with gravity (:mod:`stability.models.slope`), the
tested tire fits at the quasi-static normal loads of the plane (eq 6-25
extended, solved consistently with the tire forces), optional rolling
resistance, drive forces at the main-wheel contacts.  Camber and toe are not
modelled on the plane (refused).  See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.models import full_width as fw
from stability.models import slope as sl
from stability.models.params import parameters
from stability.runtime.checks import check_choice
from stability.tires import FZ_MAX_N, SLIP_MAX_DEG, LinearTire, get_policy

__all__ = ["Plane", "SlopeModel", "Forces", "MAX_ANGLE_DEG"]

#: Largest cross slope or grade accepted (deg); steeper planes are outside any tire data.
MAX_ANGLE_DEG = 20.0


def _check_angle(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is invalid; valid range: -{MAX_ANGLE_DEG:g} to {MAX_ANGLE_DEG:g} deg"
                         ) from None
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


@dataclass(frozen=True)
class Forces:
    """Tire forces, loads and slips at one state.

    Attributes
    ----------
    F : tuple
        ``(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy)`` in wheel frames (N); ``FDx``, ``FEx``
        include the drive forces.
    loads : tuple
        ``(N_A, N_B, N_D, N_E)`` (N).
    slips_deg : tuple
        Signed slip angles ``atan2(vy, |vx|)`` of A, B, D, E (deg).
    """

    F: tuple
    loads: tuple
    slips_deg: tuple


class SlopeModel:
    """A chair on a plane: tire forces and accelerations (exact model with gravity).

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
        self.main = chair.main_tire_model()
        self.caster = chair.caster_tire_model()
        self.rolling = (chair.caster_rolling_scale > 0, chair.main_rolling_scale > 0)
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
        for k, (tire, s, n) in enumerate(zip((self.caster, self.caster, self.main, self.main),
                                             f.slips_deg, f.loads, strict=True)):
            wheel = ("left caster", "right caster", "left main wheel", "right main wheel")[k]
            if n <= 0.0:
                out.append(f"the {wheel} lifts off (normal load {n:.1f} N)")
                continue
            if isinstance(tire, LinearTire):
                continue
            if self.clamp:
                if abs(s) > SLIP_MAX_DEG or n > FZ_MAX_N:   # a note under the clamp policy (tires.collect_notes)
                    tire.lateral_force(s, n, policy="clamp")
                continue
            if self.policy == "warn" and abs(s) <= SLIP_MAX_DEG:
                if n > FZ_MAX_N:        # warn: the load polynomial extrapolated, with a note (tires.collect_notes)
                    tire.lateral_force(s, n, policy="extrapolate")
                continue
            if abs(s) > SLIP_MAX_DEG:
                out.append(f"{wheel} slip {abs(s):.2f} deg beyond the tire data (|slip| <= {SLIP_MAX_DEG:g} deg)")
            if n > FZ_MAX_N:
                out.append(f"{wheel} load {n:.0f} N beyond the tire data (<= {FZ_MAX_N:g} N)")
        return out

    # -- forces ----------------------------------------------------------------
    def lateral(self, slips_deg, loads) -> tuple[float, float, float, float]:
        """Lateral tire forces of A, B, D, E (N) from the fits (WCHAIR's law, extrapolated in slip)."""
        c, mtire = self.caster, self.main
        pol = self._policy
        return (c.lateral_force(slips_deg[0], loads[0], policy=pol, warn=False),
                c.lateral_force(slips_deg[1], loads[1], policy=pol, warn=False),
                mtire.lateral_force(slips_deg[2], loads[2], policy=pol, warn=False),
                mtire.lateral_force(slips_deg[3], loads[3], policy=pol, warn=False))

    def rolling_forces(self, loads, vx) -> tuple[float, ...]:
        """Rolling-resistance forces along each wheel's heading (N), opposing its rolling velocity."""
        out = []
        for k in range(4):
            on = self.rolling[0] if k < 2 else self.rolling[1]
            tire = self.caster if k < 2 else self.main
            out.append(math.copysign(tire.rolling_resistance(float(loads[k])), -vx[k]) if on else 0.0)
        return tuple(out)

    def forces(self, u, v, r, ce, se, cb, sb, eta_d, beta_d, drive: tuple[float, float], g: tuple,
               loads: tuple | None = None, tol: float = 1e-9) -> Forces:
        """Tire forces at a state; the normal loads are solved consistently with them.

        ``drive = (FDx_drive, FEx_drive)`` (N) are added to the main wheels;
        ``g = (g1, g2, gn)``.  With ``loads`` given they are used as they are
        (no load transfer iteration).
        """
        p = self.p
        vel = fw.contact_velocities(p, u, v, r, ce, se, cb, sb, eta_d, beta_d, "exact")
        vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
        slips = tuple(math.degrees(math.atan2(vy, abs(vx)))
                      for vx, vy in ((vAx, vAy), (vBx, vBy), (vDx, vDy), (vEx, vEy)))
        g1, g2, gn = g
        fixed = loads is not None
        N: tuple = loads if loads is not None else sl.normal_loads(p, 0.0, 0.0, g1, g2, gn, ce, se, cb, sb)
        for it in range(400):
            FAy, FBy, FDy, FEy = self.lateral(slips, N)
            RA, RB, RD, RE = self.rolling_forces(N, (vAx, vBx, vDx, vEx))
            F = (RA, FAy, RB, FBy, RD + drive[0], FDy, RE + drive[1], FEy)
            if fixed:
                break
            fx, fy = fw.tire_resultant(F, ce, se, cb, sb)
            new = sl.normal_loads(p, fx / p.m + g1, fy / p.m + g2, g1, g2, gn, ce, se, cb, sb)
            done = max(abs(a - b) for a, b in zip(new, N, strict=True)) < tol
            # under-relax when plain iteration does not contract (large slips, high c.g.)
            w = 1.0 if it < 20 else 0.25
            N = tuple(b + w * (a - b) for a, b in zip(new, N, strict=True))
            if done:
                break
        else:  # pragma: no cover - the load transfer is a strong contraction
            raise RuntimeError("normal loads did not converge")
        return Forces(F=F, loads=tuple(float(n) for n in N), slips_deg=slips)

    def accelerations(self, u, v, r, eta, eta_d, beta, beta_d, heading, drive, M_pins=(0.0, 0.0),
                      Mz_ext: float = 0.0):
        """``((u_dot, v_dot, r_dot, eta_dd, beta_dd), Forces)`` at a state.

        ``heading`` (rad) sets gravity's body components; pin moments
        ``M_pins`` (N m) act on the casters (viscous damping ``pin_damping`` is added).
        """
        ce, se, cb, sb = math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta)
        g = self.plane.gravity(self.p.g, heading)
        f = self.forces(u, v, r, ce, se, cb, sb, eta_d, beta_d, drive, g)
        c = self.p.pin_damping
        acc = sl.accelerations(self.p, u, v, r, ce, se, cb, sb, eta_d, beta_d, f.F,
                               M_pins[0] - c * eta_d, M_pins[1] - c * beta_d, g[0], g[1], 0.0, Mz_ext)
        return acc, f

    def rhs(self, drive: tuple[float, float]):
        """Right-hand side ``f(t, y)`` for ``y = [X, Y, psi, u, v, r, eta, eta_d, beta, beta_d]``.

        ``X, Y`` (m) the c.g. along and to the right of the path direction,
        ``psi`` the heading (rad, clockwise); constant drive forces (N).
        """
        def f(t, y):
            _, _, psi, u, v, r, eta, eta_d, beta, beta_d = y
            acc, _ = self.accelerations(u, v, r, eta, eta_d, beta, beta_d, psi, drive)
            c, s = math.cos(psi), math.sin(psi)
            return np.array([u * c - v * s, u * s + v * c, r, acc[0], acc[1], acc[2], eta_d, acc[3],
                             beta_d, acc[4]])
        return f


def check_drive(kind: str) -> str:
    """Drive kind, ``"handrim"`` or ``"motor"``."""
    return check_choice("drive", kind, ("handrim", "motor"))
