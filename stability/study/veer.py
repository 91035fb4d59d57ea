"""The uncorrected path: which way and how fast the chair turns when nobody holds it straight.

Starts from the held equilibrium (:func:`stability.slope.equilibrium.solve`)
and removes the drive: the simulator (:func:`stability.simulate.simulate`
with ``slope=``) from that state, coasting.  :func:`uncorrected_path` is its
adaptive scheme with frictionless pins (the statics' own assumption);
:func:`simulator_path` runs either scheme, with or without the chair's
Coulomb pin friction.  See ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.settings.defaults import SLOPE_SIM_TIME
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.slope.equilibrium import Equilibrium
from stability.slope.model import Plane

__all__ = ["UncorrectedPath", "uncorrected_path", "simulator_path", "simulator_slope", "plane_seen_from", "VEER_RUN"]

#: Tolerances of the uncorrected path's adaptive run (those of the slope package's former solve_ivp path).
PATH_RTOL, PATH_ATOL = 1e-8, 1e-10
#: The simulator path's default run: the adaptive scheme for 2 s (the speed, the initial state and the slope come
#: from the equilibrium; no push).
VEER_RUN = RunSpec(scheme="adaptive", horizon=2.0)

#: a caster swung this far from its held angle ends a run (beyond the tire data), deg
MAX_CASTER_SWING_DEG = 30.0

#: Default time of the uncorrected path's summary, s (the slope command's --sim-time default).
REPORT_TIME = SLOPE_SIM_TIME


@dataclass(frozen=True)
class UncorrectedPath:
    """Time history of the uncorrected chair.

    Attributes
    ----------
    t : ndarray
        Time (s).
    x, y : ndarray
        c.g. along the path direction and to its right (m).
    heading : ndarray
        Heading from the path direction (rad, clockwise +).
    yaw_rate : ndarray
        Yaw rate (rad/s, clockwise +).
    speed : ndarray
        Forward body velocity u (m/s).
    turn : str
        ``"downhill"`` or ``"uphill"``: sign of the heading change at the end relative to the fall line.
    report_time : float
        ``min(1 s, end of the run)``: the time of the three numbers below (s).
    heading_change_deg : float
        Heading change at ``report_time`` (deg, downhill +).
    yaw_rate_deg_s : float
        Yaw rate at ``report_time`` (deg/s, downhill +).
    lateral_offset : float
        Sideways drift of the c.g. from the intended line at ``report_time`` (m, downhill +).
    time_to_10deg : float or None
        Time until the heading has changed by 10 deg (s); None if it did not within the run.
    quasi_steady_rate_deg_s : float
        ``g2/U`` (deg/s): the free-castered zero-width model's quasi-steady yaw rate.
    ended : str
        Why the path ends: ``"horizon"``, ``"heading past 45 deg"``, ``"a caster swung 30 deg"``, or the
        simulator's stop (e.g. its eleventh slip warning beyond the tire data).
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heading: np.ndarray
    yaw_rate: np.ndarray
    speed: np.ndarray
    turn: str
    report_time: float
    heading_change_deg: float
    yaw_rate_deg_s: float
    lateral_offset: float
    time_to_10deg: float | None
    quasi_steady_rate_deg_s: float
    ended: str = "horizon"

    def to_dict(self) -> dict:
        """Summary numbers for JSON (no time histories)."""
        return {"uncorrected_turn": self.turn, "report_time_s": self.report_time,
                "heading_change_deg": self.heading_change_deg, "yaw_rate_deg_s": self.yaw_rate_deg_s,
                "lateral_offset_m": self.lateral_offset, "time_to_10deg_s": self.time_to_10deg,
                "quasi_steady_yaw_rate_deg_s": self.quasi_steady_rate_deg_s,
                "duration_s": float(self.t[-1]), "ended": self.ended}


def uncorrected_path(chair: Chair, eq: Equilibrium, duration: float = 2.0, max_heading_deg: float = 45.0,
                     report_time: float = REPORT_TIME) -> UncorrectedPath:
    """The chair released from the held equilibrium ``eq``: the simulator's adaptive scheme, frictionless pins.

    :func:`simulator_path` with ``scheme="adaptive"``, ``pin_friction=False``
    and tolerances :data:`PATH_RTOL`, :data:`PATH_ATOL`: the chair coasts (no
    drive force) from the held state (crab angle, caster angles, speed).

    Parameters
    ----------
    chair : Chair
        The chair ``eq`` was solved for (``pin_damping`` 0: the simulator has
        no viscous pin damping).
    eq : Equilibrium
        The held equilibrium (:func:`stability.slope.equilibrium.solve`).
    duration : float
        Length of the run (s); the path is cut when the heading change exceeds ``max_heading_deg``
        or a caster swings more than 30 deg from its held angle.
    max_heading_deg : float
        Heading change that ends the path (deg, default 45).
    report_time : float
        When the summary is taken (s, default 1; ``duration`` is raised to it if shorter).

    Returns
    -------
    UncorrectedPath
        Time history (s, m, rad, rad/s, m/s), turn direction and the summary
        at ``report_time`` or the path's end if earlier (heading change, deg; yaw rate, deg/s; lateral offset, m).

    Raises
    ------
    ValueError
        ``chair.pin_damping`` nonzero.
    """
    return simulator_path(chair, eq, VEER_RUN.replace(horizon=duration, rtol=PATH_RTOL, atol=PATH_ATOL),
                          pin_friction=False, max_heading_deg=max_heading_deg, report_time=report_time)


def _summarise(eq: Equilibrium, t, x, y, heading, yaw_rate, speed, g2: float,
               report_time: float = 1.0, ended: str = "horizon") -> UncorrectedPath:
    """The :class:`UncorrectedPath` of a time history (path frame, heading from the path direction)."""
    psi0 = math.radians(eq.heading_deg)
    side = math.copysign(1.0, eq.cross_slope_deg) if eq.cross_slope_deg != 0 else 1.0
    dpsi = (heading - psi0) * side
    turn = "downhill" if dpsi[-1] > 0 else ("uphill" if dpsi[-1] < 0 else "none")
    t_rep = min(report_time, float(t[-1]))

    def at1(a: np.ndarray) -> float:
        return float(np.interp(t_rep, t, a))

    big = np.flatnonzero(np.abs(dpsi) >= math.radians(10.0))
    t10 = float(np.interp(math.radians(10.0), np.abs(dpsi[:big[0] + 1]), t[:big[0] + 1])) if big.size else None
    return UncorrectedPath(
        t=t, x=x, y=y, heading=heading, yaw_rate=yaw_rate, speed=speed, turn=turn,
        report_time=t_rep, heading_change_deg=math.degrees(at1(dpsi)),
        yaw_rate_deg_s=math.degrees(at1(yaw_rate * side)), lateral_offset=at1(y * side), time_to_10deg=t10,
        quasi_steady_rate_deg_s=math.degrees(g2 / eq.speed), ended=ended)


def simulator_slope(chair: Chair, eq: Equilibrium) -> tuple[float, float]:
    """The plane of ``eq`` seen from the chair's held heading: ``(cross_slope_deg, grade_deg)`` for the simulator.

    The simulator measures heading and position from the chair's initial
    heading, the held crab angle ``psi0`` here.  The same plane in that frame
    has the in-plane gravity of the held chair, ``(g1, g2) = gravity(psi0)``
    (:func:`stability.models.slope.gravity`): grade ``asin(-g1/g)``, cross
    slope ``atan2(g2, gn)`` (``gn`` is unchanged).

    Parameters
    ----------
    chair : Chair
        The chair (its ``g``).
    eq : Equilibrium
        The held equilibrium (cross slope, grade, crab angle in deg).

    Returns
    -------
    tuple of float
        Cross slope and grade in the chair's initial frame, deg.
    """
    return plane_seen_from(chair, Plane(eq.cross_slope_deg, eq.grade_deg), math.radians(eq.heading_deg))


def plane_seen_from(chair: Chair, plane: Plane, heading: float) -> tuple[float, float]:
    """``plane`` seen from a chair headed ``heading`` (rad) from the path: ``(cross_slope_deg, grade_deg)``.

    The plane whose in-plane gravity at heading 0 is ``plane``'s at ``heading``
    (grade ``asin(-g1/g)``, cross slope ``atan2(g2, gn)``).

    Parameters
    ----------
    chair : Chair
        The chair (its ``g``).
    plane : Plane
        Cross slope and grade, deg.
    heading : float
        Heading from the path direction, rad (clockwise +).

    Returns
    -------
    tuple of float
        Cross slope and grade, deg.
    """
    g1, g2, gn = plane.gravity(chair.g, heading)
    return math.degrees(math.atan2(g2, gn)), math.degrees(math.asin(-g1 / chair.g))


def simulator_path(chair: Chair, eq: Equilibrium, run: RunSpec = VEER_RUN, *, pin_friction: bool = True,
                   max_heading_deg: float = 45.0, report_time: float = REPORT_TIME) -> UncorrectedPath:
    """The uncorrected path from the simulator (:func:`stability.simulate.simulate`) on the slope.

    Released from the held equilibrium ``eq`` (crab angle, caster angles,
    speed along the path) with no drive force (the simulator has none: the
    chair coasts), no push, the exact model.  The run is cut where
    :func:`uncorrected_path` stops (heading change beyond ``max_heading_deg``,
    a caster swung more than 30 deg).

    Parameters
    ----------
    chair : Chair
        The chair ``eq`` was solved for; viscous ``pin_damping`` must be 0
        (the simulator has only Coulomb pin friction).
    eq : Equilibrium
        The held equilibrium (:func:`stability.slope.equilibrium.solve`).
    run : RunSpec
        The run's scheme, step, tolerances and length (``horizon``, s); the speed, initial state, push (none),
        model (exact) and slope come from ``eq``.
    pin_friction : bool
        Keep the chair's Coulomb pin friction (N m); False: frictionless pins.
    max_heading_deg : float
        Heading change that ends the path (deg).
    report_time : float
        When the summary is taken (s, default 1; the horizon is raised to it if shorter).

    Returns
    -------
    UncorrectedPath
        As :func:`uncorrected_path` (path frame: x along the path, y to its right).

    Raises
    ------
    ValueError
        ``chair.pin_damping`` nonzero, or a bad simulator option.
    """
    if chair.pin_damping != 0.0:
        raise ValueError(f"pin_damping={chair.pin_damping!r} is invalid for the simulator path; valid range: 0 "
                         "(the simulator has Coulomb pin friction only)")
    duration = max(run.horizon, report_time)
    run_chair = chair if pin_friction else chair.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    psi0 = math.radians(eq.heading_deg)
    u0, v0 = eq.speed * math.cos(psi0), -eq.speed * math.sin(psi0)
    cross, grade = simulator_slope(chair, eq)
    res = simulate(run_chair, u0, run.replace(horizon=duration, model="exact", push_force=0.0, lateral_velocity=v0,
                                              eta0_deg=eq.eta_deg, beta0_deg=eq.beta_deg, cross_slope_deg=cross,
                                              grade_deg=grade))
    t, dpsi = res.t, res.heading
    swing = np.maximum(np.abs(res.eta - math.radians(eq.eta_deg)), np.abs(res.beta - math.radians(eq.beta_deg)))
    turned = np.abs(dpsi) > math.radians(max_heading_deg)
    swung = swing > math.radians(MAX_CASTER_SWING_DEG)
    out = np.flatnonzero(turned | swung)
    n = int(out[0]) + 1 if out.size else t.size
    if out.size:
        ended = f"heading past {max_heading_deg:g} deg" if turned[out[0]] else \
            f"a caster swung {MAX_CASTER_SWING_DEG:g} deg"
    elif res.stop_reason is not None or res.stopped_by_warnings:
        ended = res.stop_reason or "stopped: " + ", ".join(f"{v} {k} warnings" for k, v in res.warning_counts.items()
                                                            if v) + " (beyond the tire data)"
    else:
        ended = "horizon"
    c, s = math.cos(psi0), math.sin(psi0)
    X, Y = res.x[:n], res.y[:n]
    g2 = Plane(eq.cross_slope_deg, eq.grade_deg).gravity(chair.g)[1]
    return _summarise(eq, t[:n], X * c - Y * s, X * s + Y * c, psi0 + dpsi[:n], res.yaw_rate[:n], res.u[:n], g2,
                      report_time, ended)
