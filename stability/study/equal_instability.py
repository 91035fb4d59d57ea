"""Equal-instability speed: the speed at which a chair is as unstable as the reference case (Figures 9-2, 9-3)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, cast

import numpy as np

from stability.chair import Chair, preset
from stability.chair.model import takes_chair, takes_chairs
from stability.layout.model import Layout
from stability.runtime.progress import ProgressBar
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion, check_impulse
from stability.study.memo import memoised
from stability.study.summaries import Summaries, run_steps, run_summaries

__all__ = ["EqualInstability", "reference_time", "interp_speed", "equal_instability_speeds", "bisect_speeds",
           "equal_instability_speed"]


@dataclass(frozen=True, eq=False)
class EqualInstability:
    """The speed at which a chair is as unstable as the reference case.

    Attributes
    ----------
    chair : Chair or Layout
        The chair, or the layout (:mod:`stability.study.layout_equal_instability`).
    speed : float or None
        Equal-instability speed (m/s); None when outside the bracket.
    status : {"found", "above", "below"}
        "above": even at the top of the bracket the chair is more stable than
        the reference (``speed`` > ``bracket[1]``); "below": at the bottom of
        the bracket it is already less stable (``speed`` < ``bracket[0]``).
    low, high : float
        Final bracket (m/s): at ``low`` the chair is more stable than the
        reference, at ``high`` at least as unstable.
    reference_time : float
        The reference case's time to the yaw-rate level (s).
    evaluations : tuple of (speed, time)
        Every simulation run (m/s, s), sorted by speed.
    bracket : (float, float)
        The search range, m/s.
    criterion : Criterion
    model, scheme : str
    impulse : (float, float)
        Push force (N) and duration (s).
    reference : str
        The reference case in words.
    """

    chair: Chair | Layout
    speed: float | None
    status: str
    low: float
    high: float
    reference_time: float
    evaluations: tuple
    bracket: tuple
    criterion: Criterion
    model: str
    scheme: str
    impulse: tuple
    reference: str = ""

    def describe(self, digits: int = 3, unit: bool = True) -> str:
        """The speed to ``digits`` figures, or the bracket end it lies beyond (``"> 3 m/s"``)."""
        u = " m/s" if unit else ""
        if self.status == "found":
            return f"{self.speed:.{digits}g}{u}"
        if self.status == "above":
            return f"> {self.bracket[1]:g}{u}"
        return f"< {self.bracket[0]:g}{u}"

    @property
    def value_or_bound(self) -> float:
        """The speed, or the bracket end it lies beyond (for tables and plots), m/s."""
        if self.speed is not None:
            return self.speed
        return self.bracket[1] if self.status == "above" else self.bracket[0]

    def signed(self, reverse: bool) -> EqualInstability:
        """This result on the signed speed axis (negative: reverse), as every command reports a speed.

        The reverse searches run on ``|U|`` (:mod:`stability.study.layout_equal_instability`); in reverse every speed
        is negated, the brackets' ends swap (so ``low <= high`` still holds on the signed axis) and "above"/"below"
        (beyond the bracket's fast/slow end) become "below"/"above".

        Parameters
        ----------
        reverse : bool
            True: the search ran backwards (the speeds are ``|U|``); False returns ``self``.

        Returns
        -------
        EqualInstability
        """
        if not reverse:
            return self
        status = {"above": "below", "below": "above"}.get(self.status, self.status)
        return dataclasses.replace(self, speed=None if self.speed is None else -self.speed, status=status,
                                   low=-self.high, high=-self.low, bracket=(-self.bracket[1], -self.bracket[0]),
                                   evaluations=tuple((-u, t) for u, t in reversed(self.evaluations)))


def reference_time(reference_chair: Chair | None = None, reference_speed: float = REFERENCE_SPEED,
                   run: RunSpec | None = None, *, criterion: Criterion = DEFAULT_CRITERION) -> float:
    """Time the reference case takes to reach the criterion's yaw rate (thesis: slightly over 3 s).

    Parameters
    ----------
    reference_chair : Chair, optional
        Default the E&J Premier.
    reference_speed : float
        m/s.
    run : RunSpec, optional
        The run's settings (its push, model, scheme, step, pin-friction law); its horizon is the
        criterion's duration.
    criterion : Criterion

    Returns
    -------
    float
        Seconds.  Raises ValueError when the level is never reached.
    """
    ref = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    spec = runs.study_run(run).replace(horizon=criterion.duration)
    res = runs.simulate_runs([ref], [reference_speed], spec)[0]
    t = criterion.time(res)
    if not math.isfinite(t):
        raise ValueError(f"the reference case ({ref.name} at {reference_speed:g} m/s) never reaches "
                         f"{criterion.yaw_rate:g} rad/s within {criterion.duration:g} s; choose another reference")
    return t


def interp_speed(s0: float, t0: float, s1: float, t1: float, target: float) -> float:
    """Speed between ``s0`` (time ``t0`` > target, maybe inf) and ``s1`` (time ``t1`` <= target).

    Interpolates ``log(time)`` linearly in speed (times fall roughly like
    ``exp(-a U)``); the midpoint when ``t0`` is infinite or equals ``t1``.

    Parameters
    ----------
    s0 : float
        Lower bracketing speed, m/s.
    t0 : float
        Time at ``s0`` for the instability criterion to be met (Figures 9-2, 9-3), s;
        > ``target``, may be ``inf``.
    s1 : float
        Upper bracketing speed, m/s.
    t1 : float
        Time at ``s1``, s; <= ``target``.
    target : float
        Time to reach, s (> 0).

    Returns
    -------
    float
        Interpolated speed, m/s, between ``s0`` and ``s1``.
    """
    if not math.isfinite(t0) or t0 == t1:
        return 0.5 * (s0 + s1)
    l0, l1, lt = math.log(t0), math.log(max(t1, 1e-9)), math.log(target)
    f = (l0 - lt) / (l0 - l1)
    return s0 + min(max(f, 0.0), 1.0) * (s1 - s0)


#: The first round's slowest grid points run together after its fastest one (:func:`_first_round`)
FIRST_SCAN = 4


def _first_round(candidates: int) -> list[list[int]]:
    """The first round's grid indices, in the order of its launches (:func:`_bisect`).

    The grid is ``numpy.linspace(lo, hi, candidates + 2)``.  Its decision (:func:`_narrow`) needs the fastest point
    (not at least as unstable there: "above") and then the points from the slowest up to the first at least as
    unstable.  So the fastest runs alone, then the slowest :data:`FIRST_SCAN` (most chairs' first point at least as
    unstable is among them), then the rest only when none of those was: the whole grid's bracket and status.

    Parameters
    ----------
    candidates : int
        Grid points inside the bracket.

    Returns
    -------
    list of list of int
        Indices into the grid, one list per launch.
    """
    top = candidates + 1
    return [[top], list(range(min(FIRST_SCAN, top))), list(range(min(FIRST_SCAN, top), top))]


def _decided(pts: list[tuple[float, float]], target: float, scanned: int, grid: np.ndarray) -> bool:
    """Whether the first round's points run so far (the fastest and the slowest ``scanned``) decide it."""
    done = dict(pts)
    if done[float(grid[-1])] > target:                    # "above": the fastest point alone decides
        return True
    return any(done[float(s)] <= target for s in grid[:scanned])


def _run_steps(chairs: Sequence[Chair | Layout], speeds: Mapping[int, Sequence[float] | np.ndarray],
               run: RunSpec) -> dict[int, list[float]] | None:
    """Each job's step at each of its ``speeds``, s, for :func:`stability.study.summaries.run_summaries` (None: not
    the fixed-step kernel, which picks no step).

    One call for a round's runs: a chair's linear model is built once for all its speeds (not once per launch of
    :func:`_first_round` or of a pair), and every step is the one a single launch of the round gave.
    """
    if run.scheme != "wchair":
        return None
    jobs = list(speeds)
    flat = run_steps([cast(Chair, chairs[i]) for i in jobs for _ in speeds[i]],   # the thesis engine's: chairs
                     [float(x) for i in jobs for x in speeds[i]],
                     run.fixed_step, run.model, run.casters).tolist()
    out, k = {}, 0
    for i in jobs:
        out[i], k = flat[k:k + len(speeds[i])], k + len(speeds[i])
    return out


def _pair(pts: list[tuple[float, float]], lo: float, hi: float, target: float, tol: float, end: float,
          kept: int) -> list[float]:
    """A later round's speeds for one chair: a pair ``tol`` apart around the regula-falsi root (Illinois).

    The root of ``log t(U) - log target`` is predicted by :func:`interp_speed`
    between the bracket's ends (a time beyond the run's horizon counts as the
    horizon ``end``: the prediction then errs towards ``lo``, and the pair
    moves ``lo`` up to a finite time); when the same end has been kept for
    ``kept >= 2`` rounds, that kept end's log-time margin is halved for each
    further round (Illinois), so a one-sided approach cannot stall.  The two
    speeds ``0.9 tol`` apart close the bracket in that round when they straddle the root.
    """
    t_lo = next(t for s, t in pts if s == lo)
    t_hi = next(t for s, t in pts if s == hi)
    f_lo = math.log(min(t_lo, end) / target)
    f_hi = math.log(max(t_hi, 1e-9) / target)
    if kept >= 2:
        f_hi *= 0.5 ** (kept - 1)
    elif kept <= -2:
        f_lo *= 0.5 ** (-kept - 1)
    x = lo + (hi - lo) * (f_lo / (f_lo - f_hi) if f_lo > f_hi else 0.5)
    a, b = x - 0.45 * tol, x + 0.45 * tol
    room = 0.05 * tol
    if b - a < hi - lo - 2.0 * room:
        shift = max(lo + room - a, 0.0) - max(b - (hi - room), 0.0)
        return [a + shift, b + shift]
    return [0.5 * (lo + hi)]


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


@takes_chairs
def equal_instability_speeds(chairs: Sequence[Chair], run: RunSpec | None = None, *,
                             reference_chair: Chair | None = None, reference_speed: float = REFERENCE_SPEED,
                             criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = (0.2, 3.0),
                             tol: float = 0.005, candidates: int = 7, max_rounds: int = 8,
                             reference: float | None = None, progress: bool = True) -> list[EqualInstability]:
    """:func:`equal_instability_speed` for many chairs at once.

    The first round decides from ``candidates`` equally spaced speeds and the
    bracket's ends for every chair, run in up to three launches that leave out
    the speeds deciding nothing (:func:`_first_round`); each later round two speeds ``0.9 tol``
    apart (the faster one run only where the slower one is not as unstable as the reference: where it is,
    the bracket ends there) around the regula-falsi root of ``log t(U) - log t_ref`` between
    the bracket's ends (Illinois-modified, so a one-sided approach cannot
    stall), all chairs' runs in one kernel call per round, every run stopped
    at the level.  When the bracket is narrower than ``tol`` the speed is
    interpolated inside it (in log time).

    Parameters
    ----------
    chairs : sequence of Chair
    run, reference_chair, reference_speed, criterion
        As in :func:`equal_instability_speed`.
    bracket : (float, float)
        Speed range searched, m/s.
    tol : float
        Final bracket width, m/s.
    candidates : int
        Speeds per chair in the first round (inside the bracket).
    max_rounds : int
    reference : float, optional
        The reference case's time, s (computed when None).
    progress : bool

    Returns
    -------
    list of EqualInstability
        One per chair, in order.
    """
    chairs = list(chairs)
    run = runs.study_run(run)
    # identical chairs (a sweep's nominal value is the base chair) are simulated once
    unique: dict = {}
    for c in chairs:
        unique.setdefault(c, len(unique))
    if len(unique) < len(chairs):
        res = equal_instability_speeds(list(unique), run, reference_chair=reference_chair,
                                       reference_speed=reference_speed, criterion=criterion, bracket=bracket, tol=tol,
                                       candidates=candidates, max_rounds=max_rounds, reference=reference,
                                       progress=progress)
        return [res[unique[c]] for c in chairs]
    check_impulse((run.push_force, run.push_duration))
    lo0, hi0 = (float(x) for x in bracket)
    if not (0 < lo0 < hi0 and math.isfinite(hi0)):
        raise ValueError(f"bracket={bracket!r} is invalid; expected 0 < low < high (m/s)")
    if not tol > 0:
        raise ValueError(f"tol={tol!r} is invalid; valid range: > 0 m/s")
    candidates = max(1, int(candidates))
    ref_chair = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    if reference is None:
        reference = reference_time(ref_chair, reference_speed, run, criterion=criterion)
    return bisect_speeds(chairs, [float(reference)] * len(chairs), [run.push_force] * len(chairs), run,
                         criterion=criterion, bracket=(lo0, hi0), tol=tol, candidates=candidates,
                         max_rounds=max_rounds, progress=progress,
                         reference_text=f"{ref_chair.name} at {reference_speed:g} m/s")


def bisect_speeds(chairs: Sequence[Chair | Layout], targets: Sequence[float], forces: Sequence[float], run: RunSpec, *,
                  criterion: Criterion, bracket: tuple[float, float], tol: float, candidates: int, max_rounds: int,
                  progress: bool, reference_text: str,
                  summarise: Callable[..., Summaries] | None = None) -> list[EqualInstability]:
    """The vectorised bisection behind :func:`equal_instability_speeds`, with a target time and a push per chair.

    Parameters
    ----------
    chairs : sequence of Chair
    targets : sequence of float
        Each chair's reference time, s.
    forces : sequence of float
        Each chair's push force, N.
    run : RunSpec
        The runs' settings (the push's duration, model, scheme, step, pin-friction law; the horizon follows
        the targets and the criterion).
    criterion, bracket, tol, candidates, max_rounds, progress
        As in :func:`equal_instability_speeds`.
    reference_text : str
        The reference case in words.
    summarise : callable, optional
        ``summarise(chairs, speeds, forces, run, level=...) -> Summaries`` of one round's runs; default
        :func:`stability.study.summaries.run_summaries` (the thesis engine).  The layout study passes the layout
        simulator's (:mod:`stability.study.layout_equal_instability`), so both share this search.

    Returns
    -------
    list of EqualInstability
    """
    def batch(idx: list[int]) -> list[EqualInstability]:
        return _bisect([chairs[i] for i in idx], [targets[i] for i in idx], [forces[i] for i in idx], run,
                       criterion=criterion, bracket=bracket, tol=tol, candidates=candidates, max_rounds=max_rounds,
                       progress=progress, reference_text=reference_text, summarise=summarise)

    # a chair's bisection does not depend on its batch (each run counts only up to its own horizon) nor on the
    # reference case's name (only its time): inside an open memo (the advisor's) a job asked again takes the result
    # already found (stability.study.memo), with this call's words for the reference
    keys = [None if summarise is not None else
            (c, float(t), float(f), run, criterion, tuple(bracket), float(tol), int(candidates), int(max_rounds))
            for c, t, f in zip(chairs, targets, forces, strict=True)]
    return [r if r.reference == reference_text else dataclasses.replace(r, reference=reference_text)
            for r in memoised("equal_instability", keys, batch)]


def _bisect(chairs: Sequence[Chair | Layout], targets: Sequence[float], forces: Sequence[float], run: RunSpec, *,
            criterion: Criterion, bracket: tuple[float, float], tol: float, candidates: int, max_rounds: int,
            progress: bool, reference_text: str,
            summarise: Callable[..., Summaries] | None = None) -> list[EqualInstability]:
    """:func:`bisect_speeds` for one batch (every job computed)."""
    summ_fn: Callable[..., Summaries] = run_summaries if summarise is None else summarise
    lo0, hi0 = bracket
    n = len(chairs)
    target = np.asarray(targets, dtype=float)
    force = np.asarray(forces, dtype=float)
    # a run still below the level at 1.5 x the reference time (+ 0.5 s) is certainly more stable than
    # the reference: no need to simulate it to the end of the criterion's duration
    horizons = np.minimum(criterion.duration, 1.5 * target + 0.5)
    horizon = float(horizons.max())
    run = run.replace(horizon=horizon)
    dt = 0.0 if run.scheme != "wchair" else run.fixed_step
    end = horizons + dt + 1e-12         # a run of a longer batch counts only up to its own horizon
    evals: list[list[tuple[float, float]]] = [[] for _ in range(n)]
    lo = np.full(n, lo0)
    hi = np.full(n, hi0)
    status = ["open"] * n
    kept = np.zeros(n, dtype=int)              # rounds the same end was kept (+: hi, -: lo), for Illinois
    rounds = 1 + max(0, int(math.ceil(math.log((hi0 - lo0) / tol) / math.log(candidates + 1))))

    def launch(speeds: dict[int, list[float]], steps: dict[int, list[float]] | None = None) -> None:
        """Run every job's ``speeds`` in one kernel call (stopped at the level), with their ``steps`` (s) if known."""
        owner = [i for i, sp in speeds.items() for _ in sp]
        run_speeds = [x for sp in speeds.values() for x in sp]
        if not run_speeds:
            return
        known = {} if steps is None else {"steps": [h for i in speeds for h in steps[i]]}
        summ = summ_fn([chairs[i] for i in owner], run_speeds, force[owner], run, level=criterion.yaw_rate, **known)
        for i, x, t in zip(owner, run_speeds, summ.t_level.tolist(), strict=True):
            evals[i].append((x, t if t <= end[i] else math.inf))

    with ProgressBar(min(rounds, max_rounds), "equal-instability bisection", enabled=progress, unit="round") as bar:
        for rnd in range(max_rounds):
            active = [i for i in range(n) if status[i] == "open" and (rnd == 0 or hi[i] - lo[i] > tol)]
            if not active:
                break
            if rnd == 0:                    # the grid, in launches that skip the points deciding nothing
                grids = {i: np.linspace(lo[i], hi[i], candidates + 2) for i in active}
                steps = _run_steps(chairs, grids, run) if summarise is None else None
                scanned = 0                 # the slowest grid points run so far
                for k, part in enumerate(_first_round(candidates)):
                    todo = [i for i in active if k == 0 or not _decided(evals[i], float(target[i]), scanned, grids[i])]
                    launch({i: [float(grids[i][j]) for j in part] for i in todo},
                           None if steps is None else {i: [steps[i][j] for j in part] for i in todo})
                    scanned = part[-1] + 1 if k and part else scanned
                for i in active:
                    status[i], lo[i], hi[i] = _narrow(evals[i], lo[i], hi[i], float(target[i]), True)
                bar.update()
                continue
            old_lo, old_hi = lo.copy(), hi.copy()
            # the pair's faster run only where the slower one is not as unstable: where it is, the new bracket ends
            # there whatever the faster one does (the first point as unstable decides, _narrow)
            pairs = {i: _pair(evals[i], float(lo[i]), float(hi[i]), float(target[i]), tol, float(end[i]),
                              int(kept[i])) for i in active}
            steps = _run_steps(chairs, pairs, run) if summarise is None else None
            for k in (0, 1):
                todo = [i for i in active if len(pairs[i]) > k and (k == 0 or dict(evals[i])[pairs[i][0]] > target[i])]
                launch({i: pairs[i][k:k + 1] for i in todo},
                       None if steps is None else {i: steps[i][k:k + 1] for i in todo})
            for i in active:
                status[i], lo[i], hi[i] = _narrow(evals[i], lo[i], hi[i], float(target[i]), False)
                if hi[i] == old_hi[i]:
                    kept[i] = max(kept[i], 0) + 1
                elif lo[i] == old_lo[i]:
                    kept[i] = min(kept[i], 0) - 1
                else:
                    kept[i] = 0
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
                                    criterion, run.model, run.scheme, (float(force[i]), run.push_duration),
                                    reference_text))
    return out


@takes_chair
def equal_instability_speed(chair: Chair, run: RunSpec | None = None, **options: Any) -> EqualInstability:
    """Forward speed at which ``chair`` is as unstable as the reference case (Figures 9-2, 9-3).

    The reference case is ``reference_chair`` (default the E&J Premier) at
    ``reference_speed`` (0.75 m/s) under the run's push (default the thesis's
    40 N for 0.1 s at the c.g., :data:`stability.settings.reference.THESIS_PUSH`).
    ``criterion`` (default: time to reach ``|yaw rate| = 1 rad/s``; see
    docs/studies.md) is evaluated for the reference and for ``chair`` at
    candidate speeds; the speed at which the chair's time equals the
    reference's is found by a bracketing search on speed (:func:`equal_instability_speeds`).

    Parameters
    ----------
    chair : Chair
    run : RunSpec, optional
        The runs' settings: the push, the model (the thesis's figures use ``model="thesis"`` and
        ``friction_law="kinetic"``), the scheme, step and pin-friction law.
    **options
        See :func:`equal_instability_speeds` (``reference_chair``, ``reference_speed``, ``criterion``,
        ``bracket``, ``tol``, ``candidates``, ``reference``, ``progress``).

    Returns
    -------
    EqualInstability
        The thesis: the revised design reaches the reference instability at
        about 1.10-1.15 m/s (Figure 9-2), and with half or 1.5 times the pin
        friction at about 0.65 and 1.65 m/s (Figure 9-3).
    """
    return equal_instability_speeds([chair], run, **options)[0]
