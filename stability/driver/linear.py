"""The human-limited speed: how fast a driver who corrects after a delay ``tau`` can keep this chair straight.

Two linear answers, compared in docs/driver.md:

- **the divergence rule**: the speed at which the chair's divergence rate reaches ``1 / tau``
  (``lambda(U) tau = 1``): the exact limit of delayed proportional control of a one-state divergence
  ``x' = lambda x - k x(t - tau)`` (Stepan & Kollar 2000), the quantity the critical tracking task measures;
- **the delayed loop**: the full linear chair (free casters, heading added) closed by a delayed
  proportional-derivative operator on heading and heading rate, ``Mz(t) = -(k_p psi + k_d r)(t - tau)``, whose
  gains adapt to the chair (the crossover model's adaptation: McRuer & Krendel 1974).  The limit is the speed
  above which no gains make the loop stable.  The delay is a Pade approximant of order :data:`PADE_ORDER`; the
  limit computed at twice that order bounds its error (:attr:`HumanLimit.pade_error_m_s`).

Everything here is linear and frictionless (free casters): docs/driver.md says what that leaves out.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.driver.delay import PADE_ORDER, pade
from stability.driver.loop import abscissa, best_gains, closed_loop_matrix
from stability.driver.model import Driver
from stability.linear import input_matrices, state_matrices
from stability.runtime.checks import check_model, check_speed
from stability.settings.bounds import HUMAN_SPEED

__all__ = ["PADE_ORDER", "SPEED_RANGE_M_S", "pade", "closed_loop_matrix", "abscissa", "best_gains", "heading_plant",
           "OperatorFit", "operator_fit", "divergence_rate", "HumanLimit", "human_limit", "rule_speed", "plant_limit",
           "rule_crossing", "with_heading"]

#: Speeds searched for the limit, m/s: a limit outside is reported as a bound (``> 6 m/s``).
SPEED_RANGE_M_S = (HUMAN_SPEED.lo, HUMAN_SPEED.hi)
#: Speed grid of the search (the limit is then refined between two grid speeds).
_GRID = np.round(np.linspace(SPEED_RANGE_M_S[0], SPEED_RANGE_M_S[1], 25), 4)
#: Limit speeds are refined to this, m/s.
SPEED_TOL_M_S = 1e-3


def heading_plant(chair: Chair, speed: float, model: str = "exact") -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The linear chair (free casters) with its heading, driven by a yaw moment; the driver sees heading and rate.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s (> 0).
    model : {"exact", "thesis"}

    Returns
    -------
    (A, B, C)
        States ``[v, r, eta, eta_dot, beta, beta_dot, psi]``; input the yaw moment (N m); outputs ``psi`` (rad)
        and ``r`` (rad/s).
    """
    return with_heading(state_matrices(chair, speed, model)[0], input_matrices(chair, speed, model)[0])


def with_heading(A0: np.ndarray, B0: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``x' = A0 x + B0 Mz`` with the heading ``psi`` appended (``psi' = r``).

    Parameters
    ----------
    A0, B0 : ndarray
        ``(n, n)`` states ``[v, r, ...]`` (SI) and ``(n, 1)`` yaw-moment column (per N m).

    Returns
    -------
    (A, B, C)
        Order n+1; outputs ``psi`` (rad) and ``r`` (rad/s).
    """
    n = A0.shape[0]
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = A0
    A[n, 1] = 1.0                                      # psi' = r
    B = np.zeros((n + 1, 1))
    B[:n] = np.reshape(B0, (n, 1))
    C = np.zeros((2, n + 1))
    C[0, n] = 1.0
    C[1, 1] = 1.0
    return A, B, C


def divergence_rate(chair: Chair, speed: float, model: str = "exact") -> float:
    """The chair's divergence rate: the largest real part of the free-caster linear model.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    model : {"exact", "thesis"}

    Returns
    -------
    float
        1/s.
    """
    return float(np.max(np.linalg.eigvals(state_matrices(chair, speed, model)[0]).real))


@dataclass(frozen=True)
class OperatorFit:
    """The delayed PD operator adapted to the chair at one speed.

    Attributes
    ----------
    speed_m_s : float
    reaction_time_s : float
    kp_N_m_per_rad, kd_N_m_s_per_rad : float
        Heading and heading-rate gains.
    abscissa_1_s : float
        The closed loop's largest real part, 1/s (negative: the driver holds the chair).
    crossover_rad_s : float or None
        Where the open loop's gain crosses 1 (exact delay), rad/s; None if it does not.
    """

    speed_m_s: float
    reaction_time_s: float
    kp_N_m_per_rad: float
    kd_N_m_s_per_rad: float
    abscissa_1_s: float
    crossover_rad_s: float | None

    @property
    def holds(self) -> bool:
        """Whether the delayed loop is stable."""
        return self.abscissa_1_s < 0


def _crossover(A: np.ndarray, B: np.ndarray, C: np.ndarray, gains: np.ndarray) -> float | None:
    w = np.logspace(-2, 3, 2000)
    n = A.shape[0]
    resp = np.array([(gains @ C @ np.linalg.solve(1j * x * np.eye(n) - A, B))[0] for x in w])
    mag = np.abs(resp)
    idx = np.nonzero((mag[:-1] >= 1) & (mag[1:] < 1))[0]
    if len(idx) == 0:
        return None
    k = int(idx[-1])
    f = (math.log(mag[k]) - 0.0) / (math.log(mag[k]) - math.log(mag[k + 1]))
    return float(math.exp(math.log(w[k]) + f * (math.log(w[k + 1]) - math.log(w[k]))))


@takes_chair
def operator_fit(chair: Chair, speed: float, driver: Driver | None = None, model: str = "exact",
                 order: int = PADE_ORDER) -> OperatorFit:
    """The driver's best gains at ``speed`` and how stable they make the chair.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    driver : Driver, optional
        Default :class:`Driver`.
    model : {"exact", "thesis"}
    order : int
        Pade order.

    Returns
    -------
    OperatorFit
    """
    d = driver or Driver()
    check_model(model)
    speed = float(check_speed(speed))
    A, B, C = heading_plant(chair, speed, model)
    g, a = best_gains(A, B, C, d.reaction_time_s, order)
    return OperatorFit(speed, d.reaction_time_s, float(g[0]), float(g[1]), float(a), _crossover(A, B, C, g))


@dataclass(frozen=True)
class HumanLimit:
    """The human-limited speed of a chair for one driver.

    Attributes
    ----------
    chair : str
    model : str
    reaction_time_s : float
    rule_speed_m_s : float
        Where ``lambda(U) tau = 1`` (the divergence rule), or the searched range's end (see ``rule_side``).
    rule_side : str
        ``"="`` found, ``">"`` above the range (the driver holds the chair at every speed searched), ``"<"`` below.
    loop_speed_m_s : float
        Where the best delayed PD loop stops being stable, or the range's end (``loop_side``).
    loop_side : str
    pade_order : int
    pade_error_m_s : float
        ``|loop_speed(order) - loop_speed(2 order)|``: the Pade approximant's effect on the loop limit.
    speed_range_m_s : tuple of float
    """

    chair: str
    model: str
    reaction_time_s: float
    rule_speed_m_s: float
    rule_side: str
    loop_speed_m_s: float
    loop_side: str
    pade_order: int
    pade_error_m_s: float
    speed_range_m_s: tuple = SPEED_RANGE_M_S

    @property
    def speed_m_s(self) -> float:
        """The human-limited speed: the lower of the two limits (a bound when both are bounds), m/s."""
        return min(self.rule_speed_m_s, self.loop_speed_m_s)

    @property
    def side(self) -> str:
        """``"="``, or ``">"`` when neither limit lies in the searched range (``"<"``: below it)."""
        sides = {self.rule_side, self.loop_side}
        return "<" if "<" in sides else "=" if "=" in sides else ">"

    @property
    def limited_by(self) -> str:
        """Which limit is the lower: ``"divergence rule"`` or ``"delayed loop"``."""
        return "divergence rule" if self.rule_speed_m_s <= self.loop_speed_m_s else "delayed loop"

    def to_mapping(self) -> dict:
        """JSON-ready dict (key convention: unit last)."""
        return {"speed_m_s": self.speed_m_s, "side": self.side, "limited_by": self.limited_by,
                "reaction_time_s": self.reaction_time_s, "model": self.model,
                "divergence_rule_speed_m_s": self.rule_speed_m_s, "divergence_rule_side": self.rule_side,
                "delayed_loop_speed_m_s": self.loop_speed_m_s, "delayed_loop_side": self.loop_side,
                "pade_order": self.pade_order, "pade_error_m_s": self.pade_error_m_s,
                "speed_range_m_s": list(self.speed_range_m_s)}


def _first_crossing(f, grid: np.ndarray, holds: Callable[[float], bool] | None = None) -> tuple[float, str]:
    """The first speed on ``grid`` where ``f`` turns >= 0, refined by bisection to :data:`SPEED_TOL_M_S`; or a
    bound (``"<"``: already at the grid's start, ``">"``: not on the grid).

    ``holds(u)``, if given, is a cheap test that proves ``f(u) < 0`` when it passes (it may fail where ``f(u) < 0``
    too): the grid scan calls ``f`` only where it fails; the first grid speed and the bisection always call ``f``."""
    if f(float(grid[0])) >= 0:
        return float(grid[0]), "<"
    for k in range(1, len(grid)):
        if holds is not None and holds(float(grid[k])):
            continue
        if f(float(grid[k])) >= 0:
            lo, hi = float(grid[k - 1]), float(grid[k])
            while hi - lo > SPEED_TOL_M_S:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if f(mid) >= 0 else (mid, hi)
            return 0.5 * (lo + hi), "="
    return float(grid[-1]), ">"


def rule_speed(chair: Chair, reaction_time: float, model: str = "exact") -> tuple[float, str]:
    """The divergence rule's speed alone: where the chair's divergence rate reaches ``1 / reaction_time``.

    Cheap (about 35 eigenvalue problems of order 6): the advisor's constraint on every candidate chair.

    Parameters
    ----------
    chair : Chair
    reaction_time : float
        s.
    model : {"exact", "thesis"}

    Returns
    -------
    (float, str)
        Speed (m/s) and side (``"="``; ``">"``: beyond :data:`SPEED_RANGE_M_S`; ``"<"``: below it).
    """
    check_model(model)
    return rule_crossing(lambda u: divergence_rate(chair, u, model), reaction_time)


class _LoopAbscissa:
    """``U -> best abscissa`` of the delayed loop on ``plant(U)``, warm-started from the last speed's gains."""

    def __init__(self, plant: Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]], tau: float,
                 order: int) -> None:
        self.plant, self.tau, self.order = plant, tau, order
        self.gains: np.ndarray | None = None

    def __call__(self, u: float) -> float:
        A, B, C = self.plant(u)
        warm = None
        if self.gains is not None:          # the optimum moves smoothly with speed: start from the last one's
            warm = best_gains(A, B, C, self.tau, self.order, start=self.gains)
            if warm[1] < 0:
                self.gains = warm[0]
                return warm[1]
        g, a = best_gains(A, B, C, self.tau, self.order)      # the grid: a crossing is never declared without it
        if warm is not None and warm[1] < a:                  # the warm start's search (the same, deterministic)
            g, a = warm
        self.gains = g
        return a

    def holds(self, u: float) -> bool:
        """Whether the last gains found (none before a search) still make the loop stable at ``u``: then the best
        gains do too (their abscissa is at most these gains'); one eigenvalue problem instead of a search."""
        return self.gains is not None and bool(
            abscissa(*self.plant(u), self.gains[None, :], self.tau, self.order)[0] < 0)


def plant_limit(name: str, model: str, plant: Callable[[float], tuple[np.ndarray, np.ndarray, np.ndarray]],
                rate: Callable[[float], float], tau: float, order: int = PADE_ORDER) -> HumanLimit:
    """Both limits of a driver with delay ``tau`` on any linear heading plant (the short form's or a layout's).

    Parameters
    ----------
    name, model : str
    plant : callable
        ``U -> (A, B, C)`` at a speed's size ``U`` (m/s), as :func:`heading_plant`'s.
    rate : callable
        ``U -> `` the divergence rate at ``U`` (1/s), as :func:`divergence_rate`'s.
    tau : float
        The driver's effective delay, s.
    order : int
        Pade order of the delay.

    Returns
    -------
    HumanLimit
        The loop limit's Pade error is estimated from the abscissa at the limit with twice the order, divided
        by the abscissa's slope in speed there.
    """
    rule, rule_side = rule_crossing(rate, tau)
    f = _LoopAbscissa(plant, tau, order)
    speed, side = _first_crossing(f, _GRID, f.holds)
    err = 0.0
    if side == "=":
        A, B, C = plant(speed)
        g, a = best_gains(A, B, C, tau, order)
        a2 = best_gains(A, B, C, tau, 2 * order, start=g)[1]
        h = 0.01
        slope = (f(speed + h) - f(speed - h)) / (2 * h)
        err = abs(a2 - a) / abs(slope) if slope else math.inf
    return HumanLimit(name, model, tau, rule, rule_side, speed, side, order, float(err))


def rule_crossing(rate: Callable[[float], float], reaction_time: float) -> tuple[float, str]:
    """The divergence rule's speed of any divergence rate: where ``rate(U) * reaction_time`` reaches 1.

    Parameters
    ----------
    rate : callable
        ``U -> `` divergence rate (1/s) at the speed's size ``U`` (m/s).
    reaction_time : float
        s (:class:`Driver`'s range).

    Returns
    -------
    (float, str)
        Speed (m/s) and side, as :func:`rule_speed`'s.
    """
    tau = Driver(reaction_time).reaction_time_s
    return _first_crossing(lambda u: rate(u) * tau - 1.0, _GRID)


@takes_chair
def human_limit(chair: Chair, driver: Driver | None = None, model: str = "exact",
                order: int = PADE_ORDER) -> HumanLimit:
    """The speeds above which this driver cannot hold this chair straight (linear, frictionless casters).

    Parameters
    ----------
    chair : Chair
    driver : Driver, optional
        Default :class:`Driver` (0.3 s).
    model : {"exact", "thesis"}
    order : int
        Pade order of the delay.

    Returns
    -------
    HumanLimit
        :func:`plant_limit` on the chair's :func:`heading_plant` and :func:`divergence_rate`.
    """
    d = driver or Driver()
    check_model(model)
    return plant_limit(chair.name, model, lambda u: heading_plant(chair, u, model),
                       lambda u: divergence_rate(chair, u, model), d.reaction_time_s, order)
