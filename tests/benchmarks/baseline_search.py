"""The critical-impulse and equal-instability searches as they were before issue 25: the benchmarks' baseline.

Kept verbatim (renamed) from ``stability/study/impulse.py`` and
``stability/study/equal_instability.py`` at commit 1dd3716: a factor-4 grid of
pushes from ``min_impulse`` to ``max_impulse`` and then ``candidates``
geometric pushes per bracket and round, every run a full ``horizon`` with
full records; and the linear-spaced speed bisection.  The benchmark times the
new searches against these in the same run, and
``tests/test_search.py`` checks that both give the same answers.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.runtime.checks import check_choice, check_model, check_positive, check_speeds
from stability.runtime.progress import ProgressBar
from stability.settings.reference import HORIZON, LEVEL, THESIS_PUSH, Push
from stability.settings.run import SCHEMES, RunSpec
from stability.study import runs
from stability.study.criteria import Criterion
from stability.study.equal_instability import EqualInstability, interp_speed
from stability.study.impulse import CriticalImpulse, push_impulse


def _run(model: str, scheme: str, push_duration: float, dt: float | None, horizon: float, extra: dict) -> RunSpec:
    """The baseline's run settings (its keyword arguments as one RunSpec; the studies' stop rule)."""
    fields = dict(model=model, scheme=scheme, push_duration=push_duration, horizon=horizon, **extra)
    if dt is not None:
        fields["dt"] = dt
    return runs.study_run(RunSpec(**fields))


def _initial_grid(lo: float, hi: float, factor: float) -> np.ndarray:
    n = int(math.ceil(math.log(hi / lo) / math.log(factor) - 1e-9))
    return hi / factor ** np.arange(n, -1, -1.0)


def critical_impulses_bisection(chairs: Chair | Sequence[Chair], speeds: Any, *, model: str = "exact",
                      scheme: str = "wchair", duration: float = THESIS_PUSH.duration, level: float = LEVEL,
                      horizon: float = HORIZON, dt: float = 0.001, max_impulse: float = 40.0,
                      min_impulse: float = 1e-6, rel_tol: float = 0.005, candidates: int = 7,
                      max_rounds: int = 8, **sim_options: Any) -> list[CriticalImpulse]:
    """:func:`critical_impulse` for many runs: chair i at speed i (broadcast), one batch per round.

    Round 0 simulates a geometric grid of pushes (factor 4) from
    ``min_impulse`` to ``max_impulse`` for every (chair, speed); each later
    round ``candidates`` pushes geometrically spaced inside every unresolved
    bracket, all in one :func:`stability.simulate.simulate_batch` call, until
    ``high/low - 1 <= rel_tol``.  The bracket is the lowest push that reaches
    the level and the largest tried below it (assumes that reaching the level
    is monotone in the push, as it is for the linear model).

    Parameters
    ----------
    chairs : Chair or sequence of Chair
    speeds : float or array_like
        m/s; broadcast against ``chairs``.
    model : {"exact", "thesis"}
    scheme : {"wchair", "adaptive"}
    duration : float
        How long the constant force acts, s.
    level : float
        |yaw rate| level, rad/s.
    horizon : float
        Simulated time, s.
    dt : float
        Fixed step of the WCHAIR scheme, s.
    max_impulse, min_impulse : float
        Range of pushes tried, N s.
    rel_tol : float
        Relative width of the final bracket (0.005 = 0.5 %).
    candidates : int
        Pushes per bracket and round.
    max_rounds : int
    **sim_options
        More :func:`stability.simulate.simulate` options (``stop_on_warnings`` is False unless given).

    Returns
    -------
    list of CriticalImpulse
    """
    check_model(model)
    check_choice("scheme", scheme, SCHEMES)
    for name, arg in (("duration", duration), ("level", level), ("horizon", horizon), ("dt", dt),
                        ("max_impulse", max_impulse), ("min_impulse", min_impulse), ("rel_tol", rel_tol)):
        check_positive(name, arg)
    if not min_impulse < max_impulse:
        raise ValueError(f"min_impulse={min_impulse!r} is invalid; valid range: < max_impulse={max_impulse!r} N s")
    chair_arr = np.atleast_1d(np.asarray(chairs, dtype=object)) if not isinstance(chairs, Chair) else np.array([chairs],
                                                                                                              dtype=object)
    chair_b, speed_b = np.broadcast_arrays(chair_arr, check_speeds(speeds))
    run_list = [(c, float(s)) for c, s in zip(chair_b.ravel(), speed_b.ravel(), strict=True)]
    unit = push_impulse(1.0, duration, scheme, dt)         # N s per N of force
    crit = Criterion(level, horizon)
    spec = _run(model, scheme, duration, dt if scheme == "wchair" else None, horizon, sim_options)
    n = len(run_list)
    tried: list[dict[float, bool]] = [{} for _ in range(n)]
    lo = np.zeros(n)
    hi = np.zeros(n)
    open_ = np.ones(n, dtype=bool)
    grid0 = _initial_grid(min_impulse, max_impulse, 4.0)
    for rnd in range(max_rounds):
        active = [i for i in range(n) if open_[i]]
        if not active:
            break
        jobs = []
        for i in active:
            pushes = grid0 if rnd == 0 else np.geomspace(lo[i], hi[i], candidates + 2)[1:-1]
            jobs += [(i, float(j)) for j in pushes]
        results = runs.simulate_runs([run_list[i][0] for i, _ in jobs], [run_list[i][1] for i, _ in jobs], spec,
                                     push_forces=np.array([j / unit for _, j in jobs]))
        for (i, j), r in zip(jobs, results, strict=True):
            tried[i][j] = crit.time(r) <= horizon
        for i in active:
            reach = sorted(j for j, ok in tried[i].items() if ok)
            if not reach:
                open_[i] = False
                continue
            first = reach[0]
            below = [j for j, ok in tried[i].items() if not ok and j < first]
            if not below:
                open_[i] = False
                lo[i], hi[i] = 0.0, first
                continue
            lo[i], hi[i] = max(below), first
            open_[i] = hi[i] / lo[i] - 1.0 > rel_tol
    steps = Push(1.0, duration).steps(dt)
    convention = (f"constant force at the c.g. for {duration:g} s ({steps} steps of {dt * 1e3:g} ms: "
                  f"impulse = force x {unit:.4g} s)" if scheme == "wchair" else
                  f"constant force at the c.g. for {duration:g} s (impulse = force x {duration:g} s)")
    out = []
    value: float | None
    for i, (c, s) in enumerate(run_list):
        tr = tried[i]
        if not any(tr.values()):
            status, value, low, high = "never", None, max(tr), max(tr)
        elif lo[i] == 0.0:
            status, value, low, high = "below", None, 0.0, float(hi[i])
        else:
            status, value, low, high = "found", float(math.sqrt(lo[i] * hi[i])), float(lo[i]), float(hi[i])
        out.append(CriticalImpulse(c.name, float(c.m), s, value, status, low, high, max(tr), min(tr), convention,
                                   model, scheme, float(level), float(horizon), len(tr)))
    return out


def _round_runs(chairs: list[Chair], active: list[int], lo: np.ndarray, hi: np.ndarray, candidates: int,
                first: bool) -> tuple[list[Chair], list[float], list[int]]:
    run_chairs, run_speeds, owner = [], [], []
    for i in active:
        grid = np.linspace(lo[i], hi[i], candidates + 2)
        for s in (grid if first else grid[1:-1]):
            run_chairs.append(chairs[i])
            run_speeds.append(float(s))
            owner.append(i)
    return run_chairs, run_speeds, owner


def _narrow(pts: list[tuple[float, float]], lo: float, hi: float, target: float,
            first: bool) -> tuple[str, float, float]:
    """New status and bracket from the evaluations inside ``[lo, hi]``."""
    inside = [(s, t) for s, t in sorted(pts) if lo - 1e-12 <= s <= hi + 1e-12]
    if first:
        if inside[-1][1] > target:
            return "above", lo, hi
        if inside[0][1] <= target:
            return "below", lo, hi
    k = next(j for j, (_, t) in enumerate(inside) if t <= target)   # first speed at least as unstable
    return "open", inside[k - 1][0], inside[k][0]


def bisect_speeds_baseline(chairs: Sequence[Chair], targets: Sequence[float], forces: Sequence[float], length: float, *,
                  model: str, scheme: str, criterion: Criterion, bracket: tuple[float, float], tol: float,
                  candidates: int, max_rounds: int, dt: float | None, progress: bool, reference_text: str,
                  sim_options: dict) -> list[EqualInstability]:
    """The vectorised bisection behind :func:`equal_instability_speeds`, with a target time and a push per chair.

    Parameters
    ----------
    chairs : sequence of Chair
    targets : sequence of float
        Each chair's reference time, s.
    forces : sequence of float
        Each chair's push force, N.
    length : float
        Push duration, s (common).
    model, scheme, criterion, bracket, tol, candidates, max_rounds, dt, progress
        As in :func:`equal_instability_speeds`.
    reference_text : str
        The reference case in words.
    sim_options : dict
        More simulator options.

    Returns
    -------
    list of EqualInstability
    """
    lo0, hi0 = bracket
    n = len(chairs)
    target = np.asarray(targets, dtype=float)
    force = np.asarray(forces, dtype=float)
    # a run still below the level at 1.5 x the reference time (+ 0.5 s) is certainly more stable than
    # the reference: no need to simulate it to the end of the criterion's duration
    horizons = np.minimum(criterion.duration, 1.5 * target + 0.5)
    horizon = float(horizons.max())
    spec = _run(model, scheme, length, dt, horizon, sim_options).replace(push_force=float(force[0]))
    end = horizons + (dt or 0.0) + 1e-12         # a run of a longer batch counts only up to its own horizon
    crit = [Criterion(criterion.yaw_rate, float(h)) for h in horizons]
    evals: list[list[tuple[float, float]]] = [[] for _ in range(n)]
    lo = np.full(n, lo0)
    hi = np.full(n, hi0)
    status = ["open"] * n
    rounds = 1 + max(0, int(math.ceil(math.log((hi0 - lo0) / tol) / math.log(candidates + 1))))
    with ProgressBar(min(rounds, max_rounds), "equal-instability bisection", enabled=progress, unit="round") as bar:
        for rnd in range(max_rounds):
            active = [i for i in range(n) if status[i] == "open" and (rnd == 0 or hi[i] - lo[i] > tol)]
            if not active:
                break
            run_chairs, run_speeds, owner = _round_runs(list(chairs), active, lo, hi, candidates, rnd == 0)
            results = runs.simulate_runs(run_chairs, run_speeds, spec,
                                         push_forces=force[owner] if np.any(force != force[0]) else None)
            for i, s, r in zip(owner, run_speeds, results, strict=True):
                t = crit[i].time(r)
                evals[i].append((s, t if t <= end[i] else math.inf))
            for i in active:
                status[i], lo[i], hi[i] = _narrow(evals[i], lo[i], hi[i], float(target[i]), rnd == 0)
            bar.update()
    out = []
    for i, c in enumerate(chairs):
        pts = tuple(sorted(evals[i]))
        speed = None
        st = status[i]
        if st == "open":
            st = "found"
            t_lo = next(t for s, t in pts if s == lo[i])
            t_hi = next(t for s, t in pts if s == hi[i])
            speed = interp_speed(lo[i], t_lo, hi[i], t_hi, float(target[i]))
        out.append(EqualInstability(c, speed, st, float(lo[i]), float(hi[i]), float(target[i]), pts, (lo0, hi0),
                                    criterion, model, scheme, (float(force[i]), float(length)), reference_text))
    return out
