"""Critical impulse: the smallest lateral push at the c.g. after which |yaw rate| reaches a level.

A disturbance-robust measure of directional stability: instead of timing the
response to one push (Collins 1987, Figure 8-3a), ask how large a push must
be for the chair to reach the level at all within the horizon.  Rationale:
docs/studies.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair, takes_chairs
from stability.runtime.checks import check_positive, check_speeds
from stability.settings.defaults import MAX_IMPULSE
from stability.settings.reference import HORIZON, LEVEL, THESIS_PUSH, Push
from stability.settings.run import STEP_SECONDS, WORK_BUDGET_S, RunSpec
from stability.simulate.stepcheck import step_limits_and_growth
from stability.study.memo import memoised
from stability.study.runs import study_run
from stability.study.search import bracket_search
from stability.study.summaries import SummaryRunner, run_steps

__all__ = ["runs_per_speed", "check_study_work", "STEP_SECONDS", "WORK_BUDGET_S", "CriticalImpulse",
           "CriticalImpulseCurve", "critical_impulses", "critical_impulse",
           "critical_impulse_curve", "linear_critical_impulse", "push_impulse"]


def push_impulse(force: float, duration: float, scheme: str = "wchair", dt: float = 0.001) -> float:
    """Impulse a push delivers in the simulator, N s.

    Parameters
    ----------
    force : float
        N.
    duration : float
        s.
    scheme : {"wchair", "adaptive"}
        The WCHAIR scheme applies the force while ``t <= duration``:
        ``floor(duration/dt) + 1`` steps of ``dt`` (0.1 s is 101 steps of
        1 ms, 1.01 x force x duration); the adaptive scheme for exactly ``duration``.
    dt : float
        Fixed step of the WCHAIR scheme, s.

    Returns
    -------
    float
        N s.
    """
    return Push(force, duration).impulse(dt if scheme == "wchair" else None)


@dataclass(frozen=True)
class CriticalImpulse:
    """The smallest push after which ``|yaw rate|`` reaches ``level`` within ``horizon``.

    Attributes
    ----------
    chair_name : str
    mass : float
        Chair mass, kg.
    speed : float
        m/s.
    impulse_Ns : float or None
        Critical impulse, N s (geometric middle of the final bracket); None
        when even the largest push tried does not reach the level
        (``status == "never"``), or when even the smallest does (``"below"``).
    status : {"found", "never", "below"}
    low_Ns, high_Ns : float
        Final bracket, N s: the push ``low_Ns`` does not reach the level,
        ``high_Ns`` does (for "never": the largest tried twice; for "below": 0 and the smallest).
    largest_tried_Ns, smallest_tried_Ns : float
        N s.
    push : str
        The push convention, e.g. ``"force for 0.1 s (101 steps of 1 ms), impulse = force x 0.101 s"``.
    model, scheme : str
    level : float
        rad/s.
    horizon : float
        s.
    runs : int
        Simulations used for this speed.
    """

    chair_name: str
    mass: float
    speed: float
    impulse_Ns: float | None
    status: str
    low_Ns: float
    high_Ns: float
    largest_tried_Ns: float
    smallest_tried_Ns: float
    push: str
    model: str
    scheme: str
    level: float
    horizon: float
    runs: int

    @property
    def kick_m_s(self) -> float | None:
        """The critical impulse per unit mass: the lateral velocity kick it gives the chair, m/s."""
        return None if self.impulse_Ns is None else self.impulse_Ns / self.mass

    @property
    def bound_Ns(self) -> float:
        """The impulse, or the end of the range it lies beyond (for tables and plots), N s."""
        if self.impulse_Ns is not None:
            return self.impulse_Ns
        return self.largest_tried_Ns if self.status == "never" else self.smallest_tried_Ns

    def describe(self, digits: int = 3) -> str:
        """``"0.29 N s"``, ``"> 40 N s"`` or ``"< 1e-06 N s"``."""
        if self.status == "found":
            return f"{self.impulse_Ns:.{digits}g} N s"
        if self.status == "never":
            return f"> {self.largest_tried_Ns:.{digits}g} N s"
        return f"< {self.smallest_tried_Ns:.{digits}g} N s"

    def to_dict(self) -> dict:
        """JSON-ready dict (units in the keys), with ``kick_m_s``."""
        return {"chair": self.chair_name, "mass_kg": self.mass, "speed_m_s": self.speed,
                "impulse_Ns": self.impulse_Ns, "kick_m_s": self.kick_m_s, "status": self.status,
                "low_Ns": self.low_Ns, "high_Ns": self.high_Ns, "largest_tried_Ns": self.largest_tried_Ns,
                "smallest_tried_Ns": self.smallest_tried_Ns, "push": self.push, "model": self.model,
                "scheme": self.scheme, "level_rad_s": self.level, "horizon_s": self.horizon, "runs": self.runs}


@dataclass(frozen=True)
class CriticalImpulseCurve:
    """Critical impulse over speed (the boundary between pushes a chair survives and those it does not).

    Attributes
    ----------
    points : tuple of CriticalImpulse
        One per speed, in order.
    """

    points: tuple

    @property
    def speeds(self) -> np.ndarray:
        """m/s."""
        return np.array([p.speed for p in self.points])

    @property
    def impulses(self) -> np.ndarray:
        """Critical impulse per speed, N s (nan where not found)."""
        return np.array([np.nan if p.impulse_Ns is None else p.impulse_Ns for p in self.points])

    @property
    def kicks(self) -> np.ndarray:
        """Critical lateral velocity kick per speed, m/s (nan where not found)."""
        return np.array([np.nan if p.kick_m_s is None else p.kick_m_s for p in self.points])

    def to_dict(self) -> dict:
        """JSON-ready dict: ``{"points": [...]}``."""
        return {"points": [p.to_dict() for p in self.points]}


def linear_critical_impulse(chair: Chair, speed: float, *, model: str = "exact", duration: float = THESIS_PUSH.duration,
                            level: float = LEVEL, horizon: float = HORIZON, step: float = 0.001) -> float:
    """The linear model's critical impulse: ``level / max |r(t)|`` per N s of push over the horizon, N s.

    The linear model's yaw rate is linear in the push, so this is exact for
    it; the nonlinear critical impulse is close to it only for a chair
    without pin friction (Coulomb friction has no linearisation: with it the
    casters hold until the push overcomes it, and this is far too small).

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    model : {"exact", "thesis"}
    duration : float
        How long the force acts, s.
    level : float
        rad/s.
    horizon : float
        s.
    step : float
        Sample interval of ``|r(t)|``, s.

    Returns
    -------
    float
        N s (inf when the linear response never moves the yaw rate).
    """
    from stability.study.responses import linear_peak_yaw_rate

    peak = linear_peak_yaw_rate(chair, speed, horizon, impulse=(1.0 / duration, duration), model=model, step=step)
    return level / peak if peak > 0 else math.inf


def _start(chair: Chair, speed: float, model: str, duration: float, level: float, horizon: float,
           lo: float, hi: float) -> float:
    """First push of the search (log N s): the linear prediction for a frictionless chair, else the largest push.

    The prediction samples ``|r|`` every 10 ms (1000 samples over 10 s, a fraction of a millisecond): it is only
    where the search starts, and the peak it misses between samples is a fraction of a per cent of a response
    that grows or decays at a few per second.
    """
    if chair.pin_friction_left == 0 and chair.pin_friction_right == 0:
        j = linear_critical_impulse(chair, speed, model=model, duration=duration, level=level, horizon=horizon,
                                    step=min(0.01, duration))
        if math.isfinite(j):
            return math.log(min(max(j, lo), hi))
    return math.log(hi)




def runs_per_speed(min_impulse: float = 1e-6, max_impulse: float = MAX_IMPULSE, max_rounds: int = 40) -> int:
    """Most runs :func:`critical_impulses` makes at one speed: at most two a round of the batched search.

    Parameters
    ----------
    min_impulse, max_impulse : float
        N s (the search's range; the bound does not depend on it).
    max_rounds : int

    Returns
    -------
    int
    """
    return 2 * max_rounds


def check_study_work(chairs: Sequence[Chair], speeds: np.ndarray, model: str, horizon: float, dt: float,
                     runs_per_speed: int, name: str = "horizon", limits: np.ndarray | None = None) -> None:
    """Refuse a study whose simulation (count x cost) exceeds :data:`WORK_BUDGET_S`.

    Each of ``runs_per_speed`` runs at a speed takes ``horizon / step`` steps, the step being ``dt`` or the
    smaller stable step the studies pick at slow speeds (:func:`stability.simulate.stepcheck.stable_steps`).

    Parameters
    ----------
    chairs : sequence of Chair
        One per speed (broadcast).
    speeds : ndarray
        m/s.
    model : str
    horizon, dt : float
        s.
    runs_per_speed : int
    name : str
        The argument or option to name (``"horizon"``, ``"--horizon"``).
    limits : ndarray, optional
        The pairs' stable steps, s (:func:`stability.simulate.stepcheck.stable_steps`; computed when None).

    Raises
    ------
    ValueError
        Naming ``name``, the estimate and the largest allowed value.
    """
    from stability.simulate.stepcheck import auto_step, stable_steps

    if limits is None:
        limits = stable_steps(list(chairs), np.asarray(speeds, dtype=float), model, "free")
    limits = np.ravel(limits)
    steps = [min(dt, auto_step(float(x))) for x in limits]
    seconds = runs_per_speed * sum(horizon / h for h in steps) * STEP_SECONDS
    if seconds > WORK_BUDGET_S:
        raise ValueError(f"{name}={horizon:g} s is invalid here: {len(steps)} speed(s) x {runs_per_speed} runs of up "
                         f"to {horizon:g} s at steps down to {min(steps):.2g} s would take about {seconds / 60:.0f} "
                         f"min; the largest allowed {name} is {horizon * WORK_BUDGET_S / seconds:.3g} s "
                         "(or fewer or faster speeds)")



def check_search(run: RunSpec | None, level: float, max_impulse: float, min_impulse: float,
                 rel_tol: float) -> RunSpec:
    """The study's run settings (:func:`study_run`) with the search's arguments checked.

    Parameters
    ----------
    run : RunSpec or None
    level, max_impulse, min_impulse, rel_tol : float
        As :func:`critical_impulses` (1/s, N s, N s, relative).

    Returns
    -------
    RunSpec

    Raises
    ------
    ValueError
        A non-positive argument, or ``min_impulse >= max_impulse``, named with its value and the valid range.
    """
    run = study_run(run)
    for name, arg in (("level", level), ("max_impulse", max_impulse), ("min_impulse", min_impulse),
                      ("rel_tol", rel_tol)):
        check_positive(name, arg)
    check_positive("push_duration", run.push_duration)
    if not min_impulse < max_impulse:
        raise ValueError(f"min_impulse={min_impulse!r} is invalid; valid range: < max_impulse={max_impulse!r} N s")
    return run

@takes_chairs
def critical_impulses(chairs: Chair | Sequence[Chair], speeds: Any, run: RunSpec | None = None, *,
                      level: float = LEVEL, max_impulse: float = MAX_IMPULSE, min_impulse: float = 1e-6,
                      rel_tol: float = 0.005, max_rounds: int = 40) -> list[CriticalImpulse]:
    """:func:`critical_impulse` for many runs: chair i at speed i (broadcast), one kernel call per round.

    A bracketing search on the log push (:func:`stability.study.search.bracket_search`)
    for all (chair, speed) pairs together: it starts from the linear
    prediction (:func:`linear_critical_impulse`) for a chair without pin
    friction and from ``max_impulse`` otherwise, steps towards the push the
    margin (:meth:`~stability.study.summaries.Summaries.margin`) predicts,
    then closes the bracket by secant on the reaching side or Illinois
    regula falsi, until ``high/low - 1 <= rel_tol``.  Every run stops when
    ``|yaw rate|`` reaches the level.  The bracket is the lowest push that
    reaches the level and the largest tried below it (assumes that reaching
    the level is monotone in the push, as it is for the linear model).

    Parameters
    ----------
    chairs : Chair or sequence of Chair
    speeds : float or array_like
        m/s; broadcast against ``chairs``.
    run : RunSpec, optional
        The runs' settings (:func:`stability.study.runs.study_run`): the push's
        duration, the horizon within which the level must be reached, the
        step, scheme, pin-friction law, model and casters; its push force and
        speed are what the search varies.
    level : float
        |yaw rate| level, rad/s.
    max_impulse, min_impulse : float
        Range of pushes tried, N s.
    rel_tol : float
        Relative width of the final bracket (0.005 = 0.5 %).
    max_rounds : int
        Search rounds at most (each one simulation batch).

    Returns
    -------
    list of CriticalImpulse
        ``runs`` counts the simulations of each pair.
    """
    run = check_search(run, level, max_impulse, min_impulse, rel_tol)
    chair_arr = np.atleast_1d(np.asarray(chairs, dtype=object))        # a Chair is one object: shape (1,)
    chair_b, speed_b = np.broadcast_arrays(chair_arr, check_speeds(speeds))
    run_list = [(c, float(s)) for c, s in zip(chair_b.ravel(), speed_b.ravel(), strict=True)]

    def batch(idx: list[int]) -> list[CriticalImpulse]:
        return _searches([run_list[i] for i in idx], run, level, max_impulse, min_impulse, rel_tol, max_rounds)

    # a job asked again inside an open memo (the advisor's) takes the result already found (stability.study.memo)
    return memoised("critical_impulse", [(c, s, run, level, max_impulse, min_impulse, rel_tol, max_rounds)
                                         for c, s in run_list], batch)


def _searches(run_list: list[tuple[Chair, float]], run: RunSpec, level: float, max_impulse: float,
              min_impulse: float, rel_tol: float, max_rounds: int) -> list[CriticalImpulse]:
    """The searches of :func:`critical_impulses` for ``(chair, speed)`` pairs, one batch."""
    model, scheme, duration, horizon = run.model, run.scheme, run.push_duration, run.horizon
    dt = run.fixed_step
    pair_steps = None
    chairs_l, speeds_a = [c for c, _ in run_list], np.array([s for _, s in run_list], dtype=float)
    limits, rates = step_limits_and_growth(chairs_l, speeds_a, model, run.casters)
    if scheme == "wchair":
        free = limits if run.casters == "free" else None       # the work check is stated for free casters
        check_study_work(chairs_l, speeds_a, model, horizon, dt,
                         runs_per_speed(min_impulse, max_impulse, max_rounds), limits=free)
        pair_steps = run_steps([c for c, _ in run_list], [s for _, s in run_list], dt, model, run.casters,
                               limits=limits)
    # N s per N of force, per pair: a pair whose step is cut below dt (a stiff caster mode) holds the force over
    # its own steps, so the force that gives an impulse J is J over that pair's unit: the impulse the chair
    # receives is the one reported
    pair_dt = [dt] * len(run_list) if pair_steps is None else [float(h) for h in pair_steps]
    units = np.array([push_impulse(1.0, duration, scheme, h) for h in pair_dt])

    runner = SummaryRunner([c for c, _ in run_list], [s for _, s in run_list], run, level=level, steps=pair_steps)

    def evaluate(jobs: list[tuple[int, float]]) -> tuple[np.ndarray, ...]:
        idx = [i for i, _ in jobs]
        s = runner(idx, np.exp([x for _, x in jobs]) / units[idx])
        return s.t_level <= horizon, s.margin(level, horizon), s.sim_time, s.t_level

    starts = [_start(c, s, model, duration, level, horizon, min_impulse, max_impulse) for c, s in run_list]
    probs = bracket_search(len(run_list), starts, evaluate, x_min=math.log(min_impulse), x_max=math.log(max_impulse),
                           width=math.log1p(rel_tol), max_step=math.log(2.0), max_rounds=max_rounds,
                           horizon=horizon, rates=rates)
    return outcomes([(c.name, float(c.m), s) for c, s in run_list], probs, pair_dt, units, run, level)


def outcomes(pairs: Sequence[tuple[str, float, float]], probs: Sequence[Any], pair_dt: Sequence[float],
             units: np.ndarray, run: RunSpec, level: float, toward: str = "") -> list[CriticalImpulse]:
    """The searches' results: each problem's final bracket as a :class:`CriticalImpulse`.

    Parameters
    ----------
    pairs : sequence of (str, float, float)
        Per search: the chair's (or layout's) name, its mass (kg) and the speed (m/s).
    probs : sequence of stability.study.search.Problem
        The finished searches.
    pair_dt : sequence of float
        Each search's step, s.
    units : ndarray
        Each search's impulse per newton of push force, s.
    run : RunSpec
        The runs' settings (model, scheme, push duration, horizon).
    level : float
        rad/s.
    toward : str
        Words on the push's direction for its description (``""``: none, ``" to the left"``).

    Returns
    -------
    list of CriticalImpulse
    """
    model, scheme, duration, horizon = run.model, run.scheme, run.push_duration, run.horizon

    def convention(h: float, unit: float) -> str:
        return (f"constant force at the c.g.{toward} for {duration:g} s ({Push(1.0, duration).steps(h)} steps of "
                f"{h * 1e3:g} ms: impulse = force x {unit:.4g} s)" if scheme == "wchair" else
                f"constant force at the c.g.{toward} for {duration:g} s (impulse = force x {duration:g} s)")

    out = []
    value: float | None
    for k, ((name, mass, s), p) in enumerate(zip(pairs, probs, strict=True)):
        tried = [math.exp(x) for x in p.x]
        lo_x, hi_x = p.bracket()
        if hi_x is None:
            status, value, low, high = "never", None, max(tried), max(tried)
        elif lo_x is None:
            status, value, low, high = "below", None, 0.0, math.exp(hi_x)
        else:
            low, high = math.exp(lo_x), math.exp(hi_x)
            status, value = "found", math.sqrt(low * high)
        out.append(CriticalImpulse(name, mass, s, value, status, low, high, max(tried), min(tried),
                                   convention(pair_dt[k], float(units[k])), model, scheme, float(level),
                                   float(horizon), len(tried)))
    return out


@takes_chair
def critical_impulse(chair: Chair, speed: float, run: RunSpec | None = None, **search: Any) -> CriticalImpulse:
    """Smallest lateral impulse at the c.g. after which ``|yaw rate|`` reaches ``level`` within the horizon.

    The push is a constant force for ``run.push_duration`` s; its impulse is
    stated in the result's ``push`` (the WCHAIR scheme applies the force for
    ``floor(duration/dt) + 1`` steps).  Refined on the force to ``rel_tol``
    (0.5 %) by the batched bracketing search of :func:`critical_impulses`.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    run : RunSpec, optional
        The runs' settings (see :func:`critical_impulses`).
    **search
        ``level`` (rad/s), ``max_impulse``, ``min_impulse`` (N s), ``rel_tol``, ``max_rounds``: see
        :func:`critical_impulses`.

    Returns
    -------
    CriticalImpulse
        ``impulse_Ns`` (None when even ``max_impulse`` does not do it) and
        ``kick_m_s`` (impulse / mass, m/s).
    """
    return critical_impulses(chair, speed, run, **search)[0]


@takes_chair
def critical_impulse_curve(chair: Chair, speeds: Any, run: RunSpec | None = None,
                           **search: Any) -> CriticalImpulseCurve:
    """:func:`critical_impulse` over speeds, every search round one batch for all speeds.

    Parameters
    ----------
    chair : Chair
    speeds : array_like
        m/s.
    run : RunSpec, optional
        The runs' settings.
    **search
        As in :func:`critical_impulse`.

    Returns
    -------
    CriticalImpulseCurve
    """
    return CriticalImpulseCurve(tuple(critical_impulses(chair, speeds, run, **search)))
