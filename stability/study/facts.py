"""Facts the report states about a design: equal pin friction, the friction exponent, the steady slow turn."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair, preset
from stability.chair.model import check_chair, takes_chair
from stability.linear import state_matrices
from stability.runtime.checks import first_argument
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion
from stability.study.equal_instability import EqualInstability, bisect_speeds, equal_instability_speeds
from stability.study.intervals import reference_times, scale_friction

__all__ = ["EqualFrictionRow", "EqualFrictionComparison", "equal_friction_comparison", "FrictionExponent",
           "friction_exponent", "fit_exponent", "PROPORTIONAL_RANGE", "SteadyTurn", "steady_turn",
           "growth_rate"]

#: Verdict rule for the thesis's "speed roughly proportional to friction" (conclusion 6): exponent k in
#: speed ~ M_f^k inside this range.
PROPORTIONAL_RANGE = (0.8, 1.2)


@takes_chair
def growth_rate(chair: Chair, speed: float, model: str = "exact") -> float:
    """Largest real part of the linear model's eigenvalues (free frictionless casters), 1/s.

    Parameters
    ----------
    chair : Chair
        The chair.
    speed : float
        Forward speed, m/s (> 0).
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).

    Returns
    -------
    float
        ``max Re(lambda)``, 1/s (> 0: directionally unstable).
    """
    return float(np.linalg.eigvals(state_matrices(chair, speed, model)[0]).real.max())


@dataclass(frozen=True)
class EqualFrictionRow:
    """Both chairs with the same pin friction.

    Attributes
    ----------
    friction : float
        Both pins of both chairs, N m.
    reference_time : float
        The reference chair's time to the level at the reference speed, s (+inf: never).
    result : EqualInstability or None
        ``chair``'s equal-instability speed (None when the reference never reaches the level).
    """

    friction: float
    reference_time: float
    result: EqualInstability | None


@dataclass(frozen=True)
class EqualFrictionComparison:
    """A design against the reference chair at equal pin friction (is the gain geometry or friction?).

    Attributes
    ----------
    chair_name, reference_name : str
    rows : tuple of EqualFrictionRow
    growth_chair, growth_reference : float
        Linear growth rates at the reference speed (frictionless casters), 1/s.
    s1 : float
        The chair's main-axle-to-c.g. distance, m.
    radius_of_gyration : float
        ``sqrt(I_z / m)``, m (the free-caster mode grows fastest near ``s1`` equal to it).
    model : str
    push : str
    """

    chair_name: str
    reference_name: str
    rows: tuple
    growth_chair: float
    growth_reference: float
    s1: float
    radius_of_gyration: float
    model: str
    push: str


@first_argument(check_chair, optional=True)
def equal_friction_comparison(chair: Chair | None = None, run: RunSpec | None = None, *,
                              reference_chair: Chair | None = None,
                              frictions: Sequence[float] = (0.0, 0.02, 0.05, 0.1),
                              criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = (0.2, 3.0),
                              tol: float = 0.01, candidates: int = 7) -> EqualFrictionComparison:
    """Equal-instability speed of ``chair`` (default the revised design) with both chairs at the same friction.

    Parameters
    ----------
    chair, reference_chair : Chair, optional
        Default the revised design and the E&J Premier.
    frictions : sequence of float
        Pin friction of both pins of both chairs, N m.
    run, criterion, bracket, tol, candidates
        As in :func:`stability.study.equal_instability_speeds`.

    Returns
    -------
    EqualFrictionComparison
    """
    c = chair if chair is not None else preset("revised")
    ref = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)

    def at(x: Chair, f: float) -> Chair:
        return x.replace(pin_friction_left=float(f), pin_friction_right=float(f))

    run = runs.study_run(run)
    model, push = run.model, run.push
    dt = run.fixed_step if run.scheme == "wchair" else None
    t_ref = reference_times([at(ref, f) for f in frictions], REFERENCE_SPEED, [push.force] * len(frictions), run,
                            criterion=criterion)
    ok = [k for k, t in enumerate(t_ref) if math.isfinite(t)]
    res = bisect_speeds([at(c, frictions[k]) for k in ok], [float(t_ref[k]) for k in ok], [push.force] * len(ok),
                        run, criterion=criterion, bracket=(float(bracket[0]), float(bracket[1])), tol=tol,
                        candidates=candidates, max_rounds=8, progress=False,
                        reference_text=f"{ref.name} at {REFERENCE_SPEED:g} m/s, equal friction")
    found = dict(zip(ok, res, strict=True))
    rows = tuple(EqualFrictionRow(float(f), float(t), found.get(k)) for k, (f, t) in enumerate(zip(frictions, t_ref,
                                                                                                  strict=True)))
    return EqualFrictionComparison(c.name, ref.name, rows, growth_rate(c, REFERENCE_SPEED, model),
                                   growth_rate(ref, REFERENCE_SPEED, model), float(c.s1), math.sqrt(c.i_z / c.m),
                                   model, push.describe(dt))


def fit_exponent(frictions: Sequence[float], speeds: Sequence[float]) -> float:
    """Least-squares slope ``k`` of ``ln speed = k ln friction + c`` (needs two or more positive points).

    Parameters
    ----------
    frictions : sequence of float
        Pin friction moments, N m (> 0).
    speeds : sequence of float
        The matching speeds, m/s (> 0), e.g. the speed at which a heading
        error reaches a set size.

    Returns
    -------
    float
        Exponent k of the power law ``speed ~ friction**k`` (dimensionless).
    """
    x, y = np.log(np.asarray(frictions, dtype=float)), np.log(np.asarray(speeds, dtype=float))
    return float(np.polyfit(x, y, 1)[0])


@dataclass(frozen=True)
class FrictionExponent:
    """Exponent ``k`` of ``speed ~ M_f^k`` (the thesis: "roughly proportional", conclusion 6).

    Attributes
    ----------
    chair_name : str
    frictions : tuple of float
        Pin friction (both pins), N m.
    results : tuple of EqualInstability
    exponent : float or None
        Fitted on the points found (None with fewer than two).
    proportional : bool
        ``exponent`` within :data:`PROPORTIONAL_RANGE`.
    model : str
    """

    chair_name: str
    frictions: tuple
    results: tuple
    exponent: float | None
    proportional: bool
    model: str

    def verdict(self) -> str:
        """``"roughly proportional (k = 0.97)"`` or ``"not proportional (k = 0.47; rule 0.8-1.2)"``."""
        if self.exponent is None:
            return "exponent not determined"
        lo, hi = PROPORTIONAL_RANGE
        return (f"roughly proportional (k = {self.exponent:.2f})" if self.proportional else
                f"not proportional (k = {self.exponent:.2f}; rule {lo:g}-{hi:g})")


@takes_chair
def friction_exponent(chair: Chair, factors: Sequence[float] = (0.5, 0.75, 1.0, 1.25, 1.5),
                      run: RunSpec | None = None, *, reference: float | None = None,
                      **options: Any) -> FrictionExponent:
    """Fit ``speed ~ M_f^k`` over the chair's pin friction times ``factors`` (reference case fixed).

    Parameters
    ----------
    chair : Chair
    factors : sequence of float
    run : RunSpec, optional
        The runs' settings.
    reference : float, optional
        The reference case's time, s.
    **options
        Passed to :func:`stability.study.equal_instability_speeds`.

    Returns
    -------
    FrictionExponent
    """
    chairs = [scale_friction(chair, f) for f in factors]
    run = runs.study_run(run)
    model = run.model
    res = equal_instability_speeds(chairs, run, reference=reference, progress=False, **options)
    pts = [(c.pin_friction_left, r.speed) for c, r in zip(chairs, res, strict=True) if r.speed is not None]
    k = fit_exponent(*zip(*pts, strict=True)) if len(pts) >= 2 else None
    prop = k is not None and PROPORTIONAL_RANGE[0] <= k <= PROPORTIONAL_RANGE[1]
    return FrictionExponent(chair.name, tuple(c.pin_friction_left for c in chairs), tuple(res), k, prop, model)


@dataclass(frozen=True)
class SteadyTurn:
    """What a chair does after a push when it does not diverge: the slow steady turn under pin friction.

    Attributes
    ----------
    chair_name : str
    speed : float
        m/s.
    final_yaw_rate : float
        Mean yaw rate over the last second, rad/s.
    heading_change_deg : float
        Heading at the end of the run, deg.
    duration : float
        s.
    time_to_level : float
        s (+inf: the level is never reached, the chair turns steadily instead).
    model : str
    push : str
    """

    chair_name: str
    speed: float
    final_yaw_rate: float
    heading_change_deg: float
    duration: float
    time_to_level: float
    model: str
    push: str


@takes_chair
def steady_turn(chair: Chair, speeds: Sequence[float] = (0.3, 0.5), run: RunSpec | None = None) -> list[SteadyTurn]:
    """Final yaw rate and heading change after a push, at speeds where the chair does not diverge (one batch).

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float
        m/s.
    run : RunSpec, optional
        The runs' settings (push, horizon, model, step, pin-friction law).

    Returns
    -------
    list of SteadyTurn
    """
    run = runs.study_run(run)
    model, push, duration = run.model, run.push, run.horizon
    dt = run.fixed_step if run.scheme == "wchair" else None
    res = runs.simulate_runs([chair] * len(speeds), list(speeds), run)
    crit = Criterion(DEFAULT_CRITERION.yaw_rate, duration)
    out = []
    for s, r in zip(speeds, res, strict=True):
        t, yr = np.asarray(r.t), np.asarray(r.yaw_rate)
        last = t >= t[-1] - 1.0
        out.append(SteadyTurn(chair.name, float(s), float(np.mean(yr[last])), math.degrees(float(r.heading[-1])),
                              float(duration), crit.time(r), model, push.describe(dt)))
    return out
