"""The uncorrected path: which way and how fast the chair turns when nobody holds it straight.

Starts from the held equilibrium (:func:`stability.slope.equilibrium.solve`)
and removes the differential drive (both wheels keep the mean drive force),
then integrates the exact equations with gravity (:class:`~stability.slope.model.SlopeModel`)
with :func:`scipy.integrate.solve_ivp`.  Viscous pin damping only (no
Coulomb pin friction).  The simulator (:mod:`stability.simulate`) does not
know slopes yet; see ``docs/slopes.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..chair import Chair
from .equilibrium import Equilibrium
from .model import Plane, SlopeModel

__all__ = ["UncorrectedPath", "uncorrected_path"]


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

    def to_dict(self) -> dict:
        """Summary numbers for JSON (no time histories)."""
        return {"uncorrected_turn": self.turn, "report_time_s": self.report_time,
                "heading_change_deg": self.heading_change_deg, "yaw_rate_deg_s": self.yaw_rate_deg_s,
                "lateral_offset_m": self.lateral_offset, "time_to_10deg_s": self.time_to_10deg,
                "quasi_steady_yaw_rate_deg_s": self.quasi_steady_rate_deg_s,
                "duration_s": float(self.t[-1])}


def uncorrected_path(chair: Chair, eq: Equilibrium, duration: float = 2.0, max_heading_deg: float = 45.0,
                     n_out: int = 201) -> UncorrectedPath:
    """Integrate the chair released from the held equilibrium ``eq``.

    Parameters
    ----------
    chair : Chair
        The chair ``eq`` was solved for.
    eq : Equilibrium
        The held equilibrium (:func:`stability.slope.equilibrium.solve`): the
        run starts from it with both main wheels driven by the mean of its
        drive forces (N), i.e. without the holding moment.
    duration : float
        Length of the run (s); it stops early when the heading change exceeds ``max_heading_deg``
        or a caster swings more than 30 deg from its held angle.
    max_heading_deg : float
        Heading change that ends the run (deg, default 45).
    n_out : int
        Output samples.

    Returns
    -------
    UncorrectedPath
        Time history (s, m, rad, rad/s, m/s), turn direction and the summary
        at 1 s or the run's end if earlier (heading change, deg; yaw rate, deg/s; lateral offset, m).
    """
    from scipy.integrate import solve_ivp  # heavy optional import kept local

    plane = Plane(eq.cross_slope_deg, eq.grade_deg)
    model = SlopeModel(chair, plane)
    mean = 0.5 * (eq.drive_forces[0] + eq.drive_forces[1])
    f = model.rhs((mean, mean))
    psi0 = math.radians(eq.heading_deg)
    y0 = [0.0, 0.0, psi0, eq.speed * math.cos(psi0), -eq.speed * math.sin(psi0), 0.0,
          math.radians(eq.eta_deg), 0.0, math.radians(eq.beta_deg), 0.0]

    def turned(t, y):
        return abs(y[2] - psi0) - math.radians(max_heading_deg)
    turned.terminal = True  # type: ignore[attr-defined]

    def swung(t, y):  # a caster swung far round: beyond the tire data, stop
        return max(abs(y[6] - y0[6]), abs(y[8] - y0[8])) - math.radians(30.0)
    swung.terminal = True  # type: ignore[attr-defined]

    t_eval = np.linspace(0.0, duration, n_out)
    sol = solve_ivp(f, (0.0, duration), y0, method="LSODA", t_eval=t_eval, events=(turned, swung),
                    rtol=1e-8, atol=1e-10)
    t, y = sol.t, sol.y
    side = math.copysign(1.0, eq.cross_slope_deg) if eq.cross_slope_deg != 0 else 1.0
    dpsi = (y[2] - psi0) * side
    turn = "downhill" if dpsi[-1] > 0 else ("uphill" if dpsi[-1] < 0 else "none")

    t_rep = min(1.0, float(t[-1]))

    def at1(a: np.ndarray) -> float:
        return float(np.interp(t_rep, t, a))

    big = np.flatnonzero(np.abs(dpsi) >= math.radians(10.0))
    t10 = float(np.interp(math.radians(10.0), np.abs(dpsi[:big[0] + 1]), t[:big[0] + 1])) if big.size else None

    g2 = plane.gravity(model.p.g)[1]
    return UncorrectedPath(
        t=t, x=y[0], y=y[1], heading=y[2], yaw_rate=y[5], speed=y[3], turn=turn,
        report_time=t_rep, heading_change_deg=math.degrees(at1(dpsi)),
        yaw_rate_deg_s=math.degrees(at1(y[5] * side)), lateral_offset=at1(y[1] * side), time_to_10deg=t10,
        quasi_steady_rate_deg_s=math.degrees(g2 / eq.speed))
