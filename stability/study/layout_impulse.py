"""Critical impulse of any wheel layout, forward and in reverse: the thesis chair's study on the layout simulator.

The smallest lateral push at the c.g. (N s) after which ``|yaw rate|`` reaches the level (1 rad/s) within the
horizon (10 s): the criterion, the push, the bracket search (:func:`stability.study.search.bracket_search`), its
margin (:meth:`stability.study.summaries.Summaries.margin`), its stop rule (``high/low - 1 <= rel_tol``) and its
step rule (WCHAIR's 1 ms, cut where the linear model's stiff caster modes need a smaller step) are those of
:func:`stability.study.impulse.critical_impulses`; only the runs differ: each is a
:func:`stability.simulate.layout.simulate_layout` run of the layout, and the growth rate and the step limit come
from the layout's linear model (:func:`stability.layout.linear.state_matrices`), forward or in reverse.

A negative speed drives backwards.  Every caster starts trailing the direction of travel (0 deg forward, 180 deg
in reverse): straight running, the state the linear models linearise about, so that the push is the only
disturbance (a caster starting the wrong way round is a disturbance of its own: docs/layouts.md, Guo et al.
2003).  The push is to the right (positive force) or, with ``side="left"``, to the left.

Rationale and the comparison of the drive layouts: docs/layouts.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.layout.linear import state_matrices
from stability.layout.model import Layout, check_layout, takes_layout
from stability.settings.defaults import MAX_IMPULSE
from stability.settings.reference import LEVEL
from stability.settings.run import RunSpec
from stability.simulate.layout import check_layout_run, simulate_layout
from stability.simulate.signals import time_to_level
from stability.study.impulse import (
    WORK_BUDGET_S,
    CriticalImpulse,
    CriticalImpulseCurve,
    check_search,
    outcomes,
    push_impulse,
    runs_per_speed,
)
from stability.study.runs import study_run
from stability.study.search import bracket_search
from stability.study.summaries import Summaries, run_steps

__all__ = ["layout_critical_impulses", "layout_critical_impulse_curve", "layout_step_limits_and_growth",
           "check_layout_work", "trailing_angles", "SlowDivergence", "slow_divergences",
           "LAYOUT_STEP_SECONDS", "SIDES", "MAX_PUSH_FORCE_N"]

#: Cost of one layout-kernel step, s: 2.1 us measured (a 10 s run of 10 001 steps in 21 ms, four casters, on the
#: shared 2-core machine), taken five times over for a loaded machine.
LAYOUT_STEP_SECONDS = 1e-5
#: Push directions: the sign of the push force.
SIDES = {"right": 1.0, "left": -1.0}
#: Largest push force a run takes, N (the RunSpec's bound on ``push_force``).
MAX_PUSH_FORCE_N = 10_000.0
#: Slowest and fastest |speed| of a layout run, m/s (:func:`stability.simulate.layout.simulate_layout`).
SPEED_RANGE_M_S = (0.01, 20.0)


def _signed_speeds(speeds: Any) -> np.ndarray:
    """Speeds as a float array (negative: reverse), each ``0.01 <= |U| <= 20`` m/s."""
    try:
        u = np.atleast_1d(np.asarray(speeds, dtype=float)).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"speeds={speeds!r} is invalid; expected numbers, m/s (negative: reverse)") from None
    lo, hi = SPEED_RANGE_M_S
    bad = ~(np.isfinite(u) & (np.abs(u) >= lo) & (np.abs(u) <= hi))
    if len(u) == 0 or bad.any():
        value = float(u[bad][0]) if bad.any() else speeds
        raise ValueError(f"speed={value!r} is invalid; valid range: {lo:g} <= |speed| <= {hi:g} m/s for a layout "
                         "(negative: reverse)")
    return u


def trailing_angles(layout: Layout, speed: float) -> list[float]:
    """Caster angles of straight running at ``speed``: every caster trailing the direction of travel, deg.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s (negative: reverse).

    Returns
    -------
    list of float
        0 deg per caster forward, 180 deg in reverse.
    """
    return [180.0 if speed < 0 else 0.0] * len(layout.casters)


def layout_step_limits_and_growth(layout: Layout, speeds: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The fixed step's stability limit and the largest growth rate at each speed, from the layout's linear model.

    As :func:`stability.simulate.stepcheck.step_limits_and_growth` for the short form: the limit
    ``min -2 Re(lambda) / |lambda|^2`` over the decaying modes (forward Euler in the velocities), the growth rate
    ``max Re(lambda)``; frictionless free casters.

    Parameters
    ----------
    layout : Layout
    speeds : ndarray
        m/s (negative: reverse, linearised with every caster trailing at 180 deg).

    Returns
    -------
    limits : ndarray
        s (``inf`` where no mode decays).
    growth : ndarray
        1/s.
    """
    lam = np.linalg.eigvals(state_matrices(layout, speeds))
    with np.errstate(divide="ignore", invalid="ignore"):
        lim = np.where(lam.real < 0, -2.0 * lam.real / np.abs(lam) ** 2, np.inf)
    return lim.min(axis=-1), lam.real.max(axis=-1)


def check_layout_work(steps: Sequence[float], horizon: float, runs: int, name: str = "horizon") -> None:
    """Refuse a layout study whose simulation (count x cost) exceeds :data:`stability.study.impulse.WORK_BUDGET_S`.

    Parameters
    ----------
    steps : sequence of float
        Each search's step, s (one search per speed, and per speed and variant with ``--interval``).
    horizon : float
        s.
    runs : int
        Runs per speed at most.
    name : str
        The argument or option to name.

    Raises
    ------
    ValueError
        Naming ``name``, the estimate and the largest allowed value.
    """
    seconds = runs * sum(horizon / h for h in steps) * LAYOUT_STEP_SECONDS
    if seconds > WORK_BUDGET_S:
        raise ValueError(f"{name}={horizon:g} s is invalid here: {len(steps)} search(es) x {runs} layout runs of up to "
                         f"{horizon:g} s at steps down to {min(steps):.2g} s would take about {seconds / 60:.0f} min; "
                         f"the largest allowed {name} is {horizon * WORK_BUDGET_S / seconds:.3g} s (or fewer speeds)")


def _summaries(layout: Layout, speed: float, angles: list[float], run: RunSpec, force: float,
               level: float) -> tuple[float, float, float, float]:
    """``(peak, t_half, t_level, sim_time)`` of one layout run under the push ``force`` (N), as the compiled
    engine's summaries: the first crossings linearly interpolated between steps, a run stopped by the warning
    rule reaching the level when it stopped."""
    r = simulate_layout(layout, speed, run.replace(push_force=force), caster_angles_deg=angles)
    t, y = r.t_s, r.yaw_rate_rad_s
    t_level = time_to_level(t, y, level)
    if r.ended in ("slip warnings", "load warnings"):
        t_level = min(t_level, r.end_time_s)
    return float(np.max(np.abs(y))), time_to_level(t, y, 0.5 * level), t_level, float(t[-1])


@takes_layout
def layout_critical_impulses(layout: Layout, speeds: Any, run: RunSpec | None = None, *, level: float = LEVEL,
                             max_impulse: float = MAX_IMPULSE, min_impulse: float = 1e-6, rel_tol: float = 0.005,
                             max_rounds: int = 40, side: str = "right") -> list[CriticalImpulse]:
    """Critical impulse of a layout at each speed (negative: reverse), the thesis chair's search on its runs.

    Parameters
    ----------
    layout : Layout
    speeds : float or array_like
        m/s, ``0.01 <= |U| <= 20``; negative drives backwards.
    run : RunSpec, optional
        The runs' settings (:func:`stability.study.runs.study_run`): push duration, horizon, step, pin-friction
        law, casters; the scheme must be ``"wchair"``, the model ``"exact"``, the ground level.  Its push force
        and speed are what the search varies.
    level : float
        |yaw rate| level, rad/s.
    max_impulse, min_impulse : float
        Range of pushes tried, N s.
    rel_tol : float
        Relative width of the final bracket.
    max_rounds : int
        Search rounds at most.
    side : {"right", "left"}
        Which way the push acts.

    Returns
    -------
    list of CriticalImpulse
        One per speed (``speed`` signed, ``chair_name`` the layout's).

    Raises
    ------
    ValueError
        A bad argument, named with its value and the valid range (before any run).
    """
    check_layout(layout)
    run = check_search(run, level, max_impulse, min_impulse, rel_tol)
    if side not in SIDES:
        raise ValueError(f"side={side!r} is invalid; valid values: {', '.join(map(repr, SIDES))}")
    check_layout_run(run, level_only=True)
    u = _signed_speeds(speeds)
    dt = run.fixed_step
    limits, rates = layout_step_limits_and_growth(layout, u)
    steps = [float(h) for h in run_steps([], u, dt, run.model, run.casters, limits=limits)]
    check_layout_work(steps, run.horizon, runs_per_speed(min_impulse, max_impulse, max_rounds))
    units = np.array([push_impulse(1.0, run.push_duration, "wchair", h) for h in steps])
    if max_impulse / units.min() > MAX_PUSH_FORCE_N:
        raise ValueError(f"max_impulse={max_impulse!r} is invalid; valid range: <= {MAX_PUSH_FORCE_N * units.min():.4g}"
                         f" N s (a push force up to {MAX_PUSH_FORCE_N:g} N for {run.push_duration:g} s)")
    sign = SIDES[side]
    runs = [run.replace(dt=h, sample=h) for h in steps]          # every step recorded: crossings as the engine's
    angles = [trailing_angles(layout, float(s)) for s in u]

    def evaluate(jobs: list[tuple[int, float]]) -> tuple[np.ndarray, ...]:
        rows = np.array([_summaries(layout, float(u[i]), angles[i], runs[i], sign * math.exp(x) / units[i], level)
                         for i, x in jobs]).reshape(-1, 4)
        s = Summaries(rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3])
        return s.t_level <= run.horizon, s.margin(level, run.horizon), s.sim_time, s.t_level

    # every search starts from the largest push (the thesis chair's start for a chair with pin friction; the
    # linear prediction it uses for a frictionless chair is the short form's)
    probs = bracket_search(len(u), [math.log(max_impulse)] * len(u), evaluate, x_min=math.log(min_impulse),
                           x_max=math.log(max_impulse), width=math.log1p(rel_tol), max_step=math.log(2.0),
                           max_rounds=max_rounds, horizon=run.horizon, rates=rates)
    toward = "" if side == "right" else " to the left"
    return outcomes([(layout.name, layout.m, float(s)) for s in u], probs, steps, units, run, level, toward)


@takes_layout
def layout_critical_impulse_curve(layout: Layout, speeds: Any, run: RunSpec | None = None,
                                  **search: Any) -> CriticalImpulseCurve:
    """:func:`layout_critical_impulses` as a :class:`~stability.study.impulse.CriticalImpulseCurve`.

    Parameters
    ----------
    layout : Layout
    speeds : array_like
        m/s (negative: reverse).
    run : RunSpec, optional
    **search
        As in :func:`layout_critical_impulses`.

    Returns
    -------
    CriticalImpulseCurve
    """
    return CriticalImpulseCurve(tuple(layout_critical_impulses(layout, speeds, run, **search)))


@dataclass(frozen=True)
class SlowDivergence:
    """A speed at which the linear model diverges but no push up to the largest tried reaches the yaw-rate level.

    The critical-impulse criterion (``|yaw rate| >= level`` within the horizon) is the thesis's spin-out of the
    rear-caster chair; a chair whose unstable mode is slow turns away from its line without spinning up to the
    level, so "> 40 N s" there is not robustness.  This is the run at the largest push that shows it.

    Attributes
    ----------
    speed : float
        m/s (negative: reverse).
    growth_rate : float
        Largest real part of the linear model's eigenvalues at ``speed``, 1/s (> 0).
    push_Ns : float
        The largest push tried, N s.
    heading_deg : float
        Heading at the end of that run, deg (the direction the chair faces against its starting line).
    peak_yaw_rate : float
        Largest ``|yaw rate|`` of the run, rad/s (below the level).
    end_time_s : float
        When the run ended, s.
    """

    speed: float
    growth_rate: float
    push_Ns: float
    heading_deg: float
    peak_yaw_rate: float
    end_time_s: float

    def text(self) -> str:
        """One line for the command's output."""
        return (f"{self.speed:+.3g} m/s: the linear model diverges (growth rate {self.growth_rate:.3g} 1/s, "
                f"doubling in {math.log(2.0) / self.growth_rate:.3g} s) yet no push reaches the yaw-rate level: "
                f"after {self.push_Ns:.3g} N s the chair turns {abs(self.heading_deg):.3g} deg off its line in "
                f"{self.end_time_s:.3g} s at up to {self.peak_yaw_rate:.3g} rad/s (a slow divergence the driver "
                "must steer against, not robustness)")

    def to_dict(self) -> dict:
        """JSON-ready dict (units in the keys)."""
        return {"speed_m_s": self.speed, "growth_rate_1_s": self.growth_rate, "push_Ns": self.push_Ns,
                "heading_deg": self.heading_deg, "peak_yaw_rate_rad_s": self.peak_yaw_rate,
                "end_time_s": self.end_time_s}


def slow_divergences(layout: Layout, points: Sequence[CriticalImpulse], run: RunSpec | None = None,
                     side: str = "right") -> tuple[SlowDivergence, ...]:
    """The speeds of ``points`` whose search found no critical push although the linear model diverges there.

    Parameters
    ----------
    layout : Layout
    points : sequence of CriticalImpulse
        As returned by :func:`layout_critical_impulses` for ``layout`` (with the same ``run`` and ``side``).
    run : RunSpec, optional
        The searches' settings (push duration, horizon, step, pin-friction law).
    side : {"right", "left"}

    Returns
    -------
    tuple of SlowDivergence
        One per point with status ``"never"`` and a positive growth rate, the largest push re-run.
    """
    run = study_run(run)                      # the searches' settings; their push bounds are in the points
    if side not in SIDES:
        raise ValueError(f"side={side!r} is invalid; valid values: {', '.join(map(repr, SIDES))}")
    never = [p for p in points if p.status == "never"]
    if not never:
        return ()
    u = np.array([p.speed for p in never])
    limits, rates = layout_step_limits_and_growth(layout, u)
    out = []
    dt = run.fixed_step
    for p, h, rate in zip(never, run_steps([], u, dt, run.model, run.casters, limits=limits), rates, strict=True):
        if not rate > 0.0:
            continue
        force = SIDES[side] * p.largest_tried_Ns / push_impulse(1.0, run.push_duration, "wchair", float(h))
        r = simulate_layout(layout, p.speed, run.replace(push_force=force, dt=float(h)),
                            caster_angles_deg=trailing_angles(layout, p.speed))
        out.append(SlowDivergence(p.speed, float(rate), p.largest_tried_Ns, float(r.heading_deg[-1]),
                                  float(np.max(np.abs(r.yaw_rate_rad_s))), float(r.t_s[-1])))
    return tuple(out)
