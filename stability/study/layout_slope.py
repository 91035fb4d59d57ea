"""Any wheel layout on a plane: the held straight line (statics) and the uncorrected turn (the layout simulator).

:func:`layout_equilibrium` is :func:`stability.slope.equilibrium.solve` for any layout, forward or in reverse:
steady straight running along the path (no yaw rate, casters still, no accelerations) with the drive wheels'
longitudinal forces holding the line.  Its equations are the layout simulator's, evaluated once: the generated
nonlinear equations of the layout with each body's in-plane weight (:mod:`stability.models.layout`), the tire
forces of :func:`stability.simulate.layout_forces.tire_forces` (the tire law of :mod:`stability.tires.law`,
rolling resistance, camber), the normal loads of the layout kernel's load rule under the normal weight with the
tire forces' resultant ``-m g_in`` (the weight's in-plane part is what the tires carry).  The unknowns are the
crab angle, every caster's angle and the two drive wheels' forces; the residual is the equations' forcing
(every acceleration zero), solved by ``scipy.optimize.root``.  Frictionless pins give one equilibrium; Coulomb
pin friction a range of holding moments (each caster's moment at either limit).

:func:`layout_uncorrected_path` releases the chair from the held state: the layout simulator on the plane seen
from the held heading (:func:`stability.study.veer.plane_seen_from`), no drive, no push.  The command's text and JSON
are :mod:`stability.study.layout_slope_report`'s.  See ``docs/slopes.md``.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from stability.layout.model import Layout, check_layout
from stability.layout.statics import load_rule
from stability.models.forces import slip_angle
from stability.models.layout import nonlinear as _gn
from stability.models.layout import shape_index
from stability.settings.bounds import SIGNED_SPEED
from stability.settings.run import RunSpec
from stability.simulate.layout import check_layout_run, parameter_vector, simulate_layout, tire_slots
from stability.simulate.layout_forces import tire_forces
from stability.simulate.options import LOAD_LIMIT_N, SLIP_LIMIT_DEG
from stability.slope.model import Plane
from stability.study.veer import MAX_CASTER_SWING_DEG, plane_seen_from

__all__ = ["LayoutEquilibrium", "layout_equilibrium", "layout_drive_forces", "drive_wheels", "LayoutPath",
           "layout_uncorrected_path"]

def drive_wheels(layout: Layout) -> tuple[int, int]:
    """The two fixed wheels whose longitudinal forces hold the line: the driven ones, else every fixed wheel.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    (int, int)
        Indices in ``layout.wheels``, left (``y < 0``) first.

    Raises
    ------
    ValueError
        Not exactly two such wheels (more would make the split of the holding moment indeterminate).
    """
    idx = [j for j, w in enumerate(layout.wheels) if w.driven] or list(range(len(layout.wheels)))
    if len(idx) != 2:
        raise ValueError(f"layout {layout.name!r} has {len(idx)} drive wheels; valid: 2 (the slope statics split the "
                         "holding moment between a left and a right drive wheel)")
    return tuple(sorted(idx, key=lambda j: layout.wheels[j].y))  # type: ignore[return-value]


@dataclass(frozen=True)
class LayoutEquilibrium:
    """Steady straight running of a layout on a plane.

    Attributes
    ----------
    layout : str
    cross_slope_deg, grade_deg : float
        The plane, deg (falling to the right +, uphill +).
    speed_m_s : float
        Speed along the path, m/s (negative: reverse).
    heading_deg : float
        Crab angle: the chair's heading from the path, deg (clockwise +).
    caster_angles_deg : tuple of float
        Each caster's angle from the body's forward axis, deg (about 0 forward, about 180 in reverse).
    slips_deg, lateral_forces_N, loads_N : tuple of float
        Per contact (fixed wheels, then casters): slip angle (deg), lateral tire force (N, wheel frame), normal
        load (N).
    drive_forces_N : tuple of float
        Longitudinal forces of the left and right drive wheels beyond their rolling resistance, N (forward +).
    drive_wheels : tuple of int
        Their indices in the layout's wheels.
    holding_moment_N_m : float
        Yaw moment of the drive forces, ``-sum y_j F_j``, N m (clockwise +), frictionless pins.
    friction_range_N_m : tuple of float
        ``(min, max)`` holding moment over the equilibria with each caster's Coulomb pin moment at either limit.
    problems : tuple of str
        Tire-data or lift-off problems at this equilibrium.
    """

    layout: str
    cross_slope_deg: float
    grade_deg: float
    speed_m_s: float
    heading_deg: float
    caster_angles_deg: tuple
    slips_deg: tuple
    lateral_forces_N: tuple
    loads_N: tuple
    drive_forces_N: tuple
    drive_wheels: tuple
    holding_moment_N_m: float
    friction_range_N_m: tuple
    problems: tuple

    @property
    def uncorrected_turn(self) -> str:
        """``"downhill"``, ``"uphill"`` or ``"none"``: the way the chair yaws when the holding moment is removed."""
        s = -np.sign(self.holding_moment_N_m) * np.sign(self.cross_slope_deg)
        return "downhill" if s > 0 else ("uphill" if s < 0 else "none")

    def to_mapping(self) -> dict:
        """JSON-ready dict (unit last)."""
        return {"layout": self.layout, "cross_slope_deg": self.cross_slope_deg, "grade_deg": self.grade_deg,
                "speed_m_s": self.speed_m_s, "heading_deg": self.heading_deg,
                "caster_angles_deg": list(self.caster_angles_deg), "slips_deg": list(self.slips_deg),
                "lateral_forces_N": list(self.lateral_forces_N), "loads_N": list(self.loads_N),
                "drive_forces_N": list(self.drive_forces_N), "drive_wheels": list(self.drive_wheels),
                "holding_yaw_moment_signed_N_m": self.holding_moment_N_m,
                "holding_yaw_moment_pin_friction_range_N_m": list(self.friction_range_N_m),
                "uncorrected_turn_statics": self.uncorrected_turn, "problems": list(self.problems)}


class _Statics:
    """The layout's equations at steady straight running on a plane (arrays made once)."""

    def __init__(self, layout: Layout, plane: Plane, speed: float):
        toed = [j for j, w in enumerate(layout.wheels) if w.angle_deg != 0.0]
        if toed:
            raise ValueError(f"layout {layout.name!r}: fixed wheel {toed[0]} angle_deg="
                             f"{layout.wheels[toed[0]].angle_deg!r} is invalid on a slope; valid: 0 (toe is not "
                             "modelled in the slope statics, as the short form's slope refuses it)")
        self.layout, self.plane, self.speed = layout, plane, speed
        self.shape = shape_index(layout.shape)
        self.nw, self.nc = layout.shape
        self.p = parameter_vector(layout)
        self.slots = tire_slots(layout)
        self.rule = load_rule(layout)
        self.drive = drive_wheels(layout)
        n = 3 + self.nc
        self.M, self.F = np.zeros((n, n)), np.zeros(n)

    def state(self, z: np.ndarray, pins: np.ndarray) -> tuple:
        """Residual (forcing / weight) and the contact quantities at ``z = (psi, delta..., F_left, F_right)``."""
        from stability.simulate.layout_kernel import layout_loads

        lay, nw, nc = self.layout, self.nw, self.nc
        psi, delta, fdrive = z[0], z[1:1 + nc], z[1 + nc:]
        g1, g2, gn = self.plane.gravity(lay.g, psi)
        u, v = self.speed * math.cos(psi), -self.speed * math.sin(psi)
        cs, sn, dd = np.cos(delta), np.sin(delta), np.zeros(nc)
        nt = nw + nc
        vel = np.zeros(2 * nt)
        _gn.contact_velocities(self.shape, u, v, 0.0, cs, sn, dd, self.p, vel)
        slips = np.array([slip_angle(vel[2 * i], vel[2 * i + 1]) for i in range(nt)])
        xs = np.array([w.x for w in lay.wheels] + [c.x - c.trail * cs[k] for k, c in enumerate(lay.casters)])
        ys = np.array([w.y for w in lay.wheels] + [c.y - c.trail * sn[k] for k, c in enumerate(lay.casters)])
        loads = np.zeros(nt)
        layout_loads(self.rule.mode, xs, ys, self.rule.stiffness, self.rule.line, self.rule.roll_share, lay.m * gn,
                     lay.h, -lay.m * g1, -lay.m * g2, loads)
        TK, TS, TL, LIM, CHK, RK, RC, RS, CAM = self.slots
        fw, fc = np.zeros(2 * nw), np.zeros(2 * nc)
        tire_forces(nw, nc, TK, TS, TL, LIM, RK, RC, RS, CAM, vel, slips, loads, 0, False, 0.0, cs, sn, fw, fc)
        rolling = fw[0::2].copy()
        for j, f in zip(self.drive, fdrive, strict=True):
            fw[2 * j] += f
        _gn.equations(self.shape, u, v, 0.0, cs, sn, dd, self.p, fw, fc, 0.0, 0.0, g1, g2, self.M, self.F)
        res = self.F.copy()
        res[3:] += pins
        lateral = np.concatenate([fw[1::2], fc[1::2]])
        return res / (lay.m * lay.g), slips, lateral, loads, rolling

    def holding(self, z: np.ndarray) -> float:
        return float(-sum(self.layout.wheels[j].y * f for j, f in zip(self.drive, z[1 + self.nc:], strict=True)))

    def root(self, pins: np.ndarray, guess: np.ndarray) -> tuple[np.ndarray, bool]:
        from scipy.optimize import root  # heavy optional import kept local

        def fun(z: np.ndarray) -> np.ndarray:
            return self.state(z, pins)[0]

        sol = None
        for start in (guess, 0.5 * guess, np.where(np.arange(guess.size) == 0, 0.0, guess)):
            sol = root(fun, start, method="hybr", options={"xtol": 1e-13})
            if float(np.max(np.abs(sol.fun))) < 1e-10:
                return sol.x, True
        assert sol is not None
        return sol.x, False


def _guess(st: _Statics) -> np.ndarray:
    lay = st.layout
    back = math.pi if st.speed < 0 else 0.0
    g2 = st.plane.gravity(lay.g)[1]
    (jl, jr) = st.drive
    x_w = lay.wheels[jl].x
    track = lay.wheels[jr].y - lay.wheels[jl].y
    f = lay.m * g2 * x_w / track                        # the leading-order holding moment, split
    return np.array([0.0] + [back] * st.nc + [f, -f])


def _free_equilibrium(layout: Layout, cross_slope_deg: float, speed: float, grade_deg: float) -> tuple:
    """The statics and the free pins' equilibrium ``(psi, delta..., F_left, F_right)``, arguments checked."""
    check_layout(layout)
    if isinstance(speed, bool) or not isinstance(speed, (int, float)) or not (
            SIGNED_SPEED.holds(speed)):
        raise ValueError(f"speed={speed!r} is invalid; valid range: {SIGNED_SPEED.text('speed')} (negative: reverse)")
    check_layout_run(RunSpec(cross_slope_deg=cross_slope_deg, grade_deg=grade_deg))   # the plane's range
    st = _Statics(layout, Plane(cross_slope_deg, grade_deg), float(speed))
    z, ok = st.root(np.zeros(st.nc), _guess(st))
    if not ok:
        raise ValueError(f"cross_slope={cross_slope_deg!r} deg: no straight-running equilibrium found for layout "
                         f"{layout.name!r} at {speed:g} m/s (the tires cannot hold the chair on this plane)")
    return st, z


def layout_drive_forces(layout: Layout, cross_slope_deg: float, speed: float, grade_deg: float = 0.0
                        ) -> tuple[float, float]:
    """The drive forces of :func:`layout_equilibrium`, bit for bit, from its free-pin solve alone.

    The same numbers as ``layout_equilibrium(...).drive_forces_N`` without the pin-friction range's ``2^casters``
    further root solves (the advisor's cross-slope effort reads only the forces).

    Parameters
    ----------
    layout : Layout
        Any generated shape with two drive wheels (:func:`drive_wheels`).
    cross_slope_deg : float
        Cross slope, deg (falling to the right +; |phi| <= 15).
    speed : float
        Speed along the path, m/s; negative: reverse.
    grade_deg : float
        Grade, deg (uphill +).

    Returns
    -------
    tuple of float
        Drive forces of the left and right wheels along the path, N.

    Raises
    ------
    ValueError
        As :func:`layout_equilibrium` (inputs out of range, no equilibrium).
    """
    st, z = _free_equilibrium(layout, cross_slope_deg, speed, grade_deg)
    left, right = (float(f) for f in z[1 + st.nc:])
    return left, right


def layout_equilibrium(layout: Layout, cross_slope_deg: float, speed: float, grade_deg: float = 0.0
                       ) -> LayoutEquilibrium:
    """Steady straight running of a layout along the path on a plane, forward or in reverse.

    Parameters
    ----------
    layout : Layout
        Any generated shape with two drive wheels (:func:`drive_wheels`).
    cross_slope_deg : float
        Cross slope, deg (falling to the right +; the simulator's range, |phi| <= 15).
    speed : float
        Speed along the path, m/s; negative: reverse (casters trailing at about 180 deg).
    grade_deg : float
        Grade, deg (uphill +).

    Returns
    -------
    LayoutEquilibrium

    Raises
    ------
    ValueError
        A bad argument (named, with its value and the valid range), or no equilibrium found.
    """
    st, z = _free_equilibrium(layout, cross_slope_deg, speed, grade_deg)
    free = np.zeros(st.nc)
    _, slips, lateral, loads, _ = st.state(z, free)
    held = []
    for signs in itertools.product((1.0, -1.0), repeat=st.nc):
        pins = np.array([s * c.pin_friction for s, c in zip(signs, layout.casters, strict=True)])
        zf, okf = st.root(pins, z)
        if okf:
            held.append(st.holding(zf))
    problems = []
    for i, (s, n) in enumerate(zip(slips, loads, strict=True)):
        tested = bool(st.slots[4][i])
        if n < 0:
            problems.append(f"contact {i + 1} lifts off (load {n:.1f} N)")
        elif tested and abs(s) > SLIP_LIMIT_DEG:
            problems.append(f"contact {i + 1} slips {s:.2f} deg, beyond the tire data ({SLIP_LIMIT_DEG:g} deg)")
        elif tested and n > LOAD_LIMIT_N:
            problems.append(f"contact {i + 1} carries {n:.1f} N, beyond the tire data ({LOAD_LIMIT_N:g} N)")
    back = 180.0 if speed < 0 else 0.0
    angles = tuple(back + math.degrees(math.remainder(d - math.radians(back), 2 * math.pi)) for d in z[1:1 + st.nc])
    return LayoutEquilibrium(
        layout=layout.name, cross_slope_deg=float(cross_slope_deg), grade_deg=float(grade_deg),
        speed_m_s=float(speed), heading_deg=math.degrees(z[0]), caster_angles_deg=angles,
        slips_deg=tuple(float(s) for s in slips), lateral_forces_N=tuple(float(f) for f in lateral),
        loads_N=tuple(float(n) for n in loads), drive_forces_N=tuple(float(f) for f in z[1 + st.nc:]),
        drive_wheels=st.drive, holding_moment_N_m=st.holding(z),
        friction_range_N_m=(min(held), max(held)) if held else (math.nan, math.nan), problems=tuple(problems))


@dataclass(frozen=True)
class LayoutPath:
    """The uncorrected chair released from the held line (a summary; the run is the layout simulator's).

    Attributes
    ----------
    turn : str
        ``"downhill"`` or ``"uphill"`` (the heading change at the report time, relative to the fall line) or
        ``"none"``.
    report_time_s : float
        When the numbers are taken: the requested time or the run's end, s.
    heading_change_deg : float
        Heading change from the held heading, deg (downhill +).
    yaw_rate_deg_s : float
        deg/s (downhill +).
    lateral_offset_m : float
        Drift of the c.g. from the held line, m (downhill +).
    ended : str
        ``"horizon"``, ``"heading past 45 deg"``, ``"a caster swung 30 deg"`` or the simulator's stop.
    caster_angles_deg : tuple of float
        Where the casters started (the held angles), deg.
    t_s : ndarray
        Times of the run up to where the path ends, s (the time history behind the summary).
    heading_change_history_deg : ndarray
        Heading change from the held heading at ``t_s``, deg (downhill +).
    """

    turn: str
    report_time_s: float
    heading_change_deg: float
    yaw_rate_deg_s: float
    lateral_offset_m: float
    ended: str
    caster_angles_deg: tuple
    t_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    heading_change_history_deg: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"uncorrected_turn": self.turn, "report_time_s": self.report_time_s,
                "heading_change_deg": self.heading_change_deg, "yaw_rate_deg_s": self.yaw_rate_deg_s,
                "lateral_offset_m": self.lateral_offset_m, "ended": self.ended,
                "caster_angles_deg": list(self.caster_angles_deg)}


def layout_uncorrected_path(layout: Layout, eq: LayoutEquilibrium, report_time: float = 1.0,
                            pin_friction: bool = True, max_heading_deg: float = 45.0) -> LayoutPath:
    """The layout released from the held equilibrium ``eq``: the layout simulator, no drive and no push.

    Parameters
    ----------
    layout : Layout
        The layout ``eq`` was solved for.
    eq : LayoutEquilibrium
    report_time : float
        When the summary is taken, s (0 < T <= 10).
    pin_friction : bool
        Keep the casters' Coulomb pin friction (stick-slip law); False: frictionless pins.
    max_heading_deg : float
        Heading change that ends the path, deg.

    Returns
    -------
    LayoutPath
    """
    if not 0.0 < report_time <= 10.0:
        raise ValueError(f"report_time={report_time!r} is invalid; valid range: 0 < T <= 10 s")
    run_layout = layout
    if not pin_friction:
        from dataclasses import replace

        run_layout = replace(layout, casters=tuple(replace(c, pin_friction=0.0) for c in layout.casters))
    psi0 = math.radians(eq.heading_deg)
    u0, v0 = eq.speed_m_s * math.cos(psi0), -eq.speed_m_s * math.sin(psi0)
    cross, grade = plane_seen_from(layout, Plane(eq.cross_slope_deg, eq.grade_deg), psi0)   # type: ignore[arg-type]
    run = RunSpec(horizon=report_time, push_force=0.0, lateral_velocity=v0, cross_slope_deg=cross, grade_deg=grade)
    res = simulate_layout(run_layout, u0, run, caster_angles_deg=[math.remainder(a, 360.0)
                                                                  for a in eq.caster_angles_deg])
    t, dpsi = res.t_s, res.heading_rad
    held = np.radians(np.asarray(eq.caster_angles_deg))[:, None]
    swing = np.abs(np.angle(np.exp(1j * (res.caster_angle_rad - held)))).max(axis=0)
    out = np.flatnonzero((np.abs(dpsi) > math.radians(max_heading_deg)) | (swing > math.radians(MAX_CASTER_SWING_DEG)))
    n = int(out[0]) + 1 if out.size else t.size
    ended = res.ended if not out.size else (f"heading past {max_heading_deg:g} deg"
                                             if abs(dpsi[out[0]]) > math.radians(max_heading_deg)
                                             else f"a caster swung {MAX_CASTER_SWING_DEG:g} deg")
    side = math.copysign(1.0, eq.cross_slope_deg) if eq.cross_slope_deg != 0 else 1.0
    t_rep = min(report_time, float(t[n - 1]))

    def at(a: np.ndarray) -> float:
        return float(np.interp(t_rep, t[:n], a[:n]))

    # the simulator's y is to the right of the held heading; the path's lateral offset turns it back by psi0
    y_path = res.x_m * math.sin(psi0) + res.y_m * math.cos(psi0)
    change = at(dpsi) * side
    return LayoutPath("downhill" if change > 0 else ("uphill" if change < 0 else "none"), t_rep,
                      math.degrees(change), math.degrees(at(res.yaw_rate_rad_s) * side), at(y_path) * side, ended,
                      tuple(eq.caster_angles_deg), t[:n], np.degrees(dpsi[:n] * side))
