"""Nonlinear measures with intervals: Monte Carlo of the critical impulse and the equal-instability speed.

The linear analogue is :func:`stability.linear.intervals.linear_intervals`;
the propagation is :func:`stability.uncertainty.propagate`.  Why the
reference case stays fixed and why there is no delta-method check:
docs/studies.md ("Nonlinear intervals").
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair, preset
from stability.chair.model import takes_chair
from stability.runtime.checks import check_speed
from stability.settings.bounds import CONFIDENCE_LEVEL, NONLINEAR_SAMPLES
from stability.settings.reference import LEVEL, REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.study.criteria import Criterion
from stability.study.equal_instability import equal_instability_speeds, reference_time
from stability.study.impulse import critical_impulses
from stability.study.runs import study_run
from stability.uncertainty import Uncertainty, propagate

__all__ = ["MeasureInterval", "NonlinearIntervals", "nonlinear_intervals", "MAX_NONLINEAR_SAMPLES"]

#: Largest Monte Carlo sample (:data:`stability.settings.bounds.NONLINEAR_SAMPLES`'s upper end; bounded work: 200
#: draws of both measures take 11-17 s on two cores).
MAX_NONLINEAR_SAMPLES = int(NONLINEAR_SAMPLES.hi)


@dataclass(frozen=True)
class MeasureInterval:
    """One nonlinear measure over the parameter uncertainty.

    Attributes
    ----------
    nominal : float
        At the chair's own values (nan when it has no value there).
    low, high, median : float
        Central interval and median over the draws with a value (nan if none).
    finite_fraction : float
        Fraction of draws with a value.
    outside : tuple of (str, float)
        Fractions of draws without a value, by status (``"never"``: no push up
        to the largest tried spins the chair; ``"above"`` / ``"below"``: the
        equal-instability speed lies beyond the bracket's top / bottom).
    shares : tuple of (str, float)
        First-order variance share of each uncertain parameter, largest first.
    r_squared : float
        Variance explained by the linear regression behind the shares.
    unit : str
    """

    nominal: float
    low: float
    high: float
    median: float
    finite_fraction: float
    outside: tuple[tuple[str, float], ...]
    shares: tuple[tuple[str, float], ...]
    r_squared: float
    unit: str

    @property
    def dominant(self) -> tuple[str, float] | None:
        """The parameter with the largest share and its share (None when nothing varies)."""
        return self.shares[0] if self.shares and self.shares[0][1] > 0 else None

    def describe(self, digits: int = 3) -> str:
        """``"2.4-3.9 N s (97 % of draws)"``, or why there is no interval."""
        if not self.finite_fraction > 0:
            return "no value in any draw (" + ", ".join(f"{k} {100 * f:.0f} %" for k, f in self.outside) + ")"
        return (f"{self.low:.{digits}g}-{self.high:.{digits}g} {self.unit} "
                f"({100 * self.finite_fraction:.0f} % of draws)")

    def to_dict(self) -> dict:
        """JSON-ready dict (nan as None)."""
        def num(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {"nominal": num(self.nominal), "interval": [num(self.low), num(self.high)],
                "median": num(self.median), "finite_fraction": self.finite_fraction, "outside": dict(self.outside),
                "shares": dict(self.shares), "r_squared": num(self.r_squared), "unit": self.unit}


@dataclass(frozen=True)
class NonlinearIntervals:
    """Intervals of the critical impulse and the equal-instability speed over the uncertain parameters.

    Attributes
    ----------
    chair_name : str
    speed : float
        Speed of the critical impulse, m/s.
    model, scheme : str
    level : float
        Interval coverage (0.95: 2.5th to 97.5th percentile).
    samples, seed : int
        Monte Carlo draws and their seed (same seed, same intervals).
    push : str
        The push convention (:meth:`stability.settings.reference.Push.describe`).
    reference : str
        The equal-instability reference case in words (fixed: not drawn).
    reference_time : float
        Its time to the yaw-rate level, s (nan without the equal-instability speed).
    critical_impulse : MeasureInterval
        N s; a draw that spins even at the smallest push tried counts as 0 N s.
    equal_instability : MeasureInterval or None
        m/s; None when not computed.
    rejected : int
        Draws redrawn because they made an invalid chair.
    """

    chair_name: str
    speed: float
    model: str
    scheme: str
    level: float
    samples: int
    seed: int
    push: str
    reference: str
    reference_time: float
    critical_impulse: MeasureInterval
    equal_instability: MeasureInterval | None
    rejected: int = 0

    def to_dict(self) -> dict:
        """JSON-ready dict, units in the keys."""
        eq = self.equal_instability
        return {"chair": self.chair_name, "speed_m_s": self.speed, "model": self.model, "scheme": self.scheme,
                "level": self.level, "samples": self.samples, "seed": self.seed, "push": self.push,
                "reference": self.reference,
                "reference_time_s": self.reference_time if math.isfinite(self.reference_time) else None,
                "critical_impulse_Ns": self.critical_impulse.to_dict(),
                "equal_instability_speed_m_s": None if eq is None else eq.to_dict(), "rejected": self.rejected}


def _unique(chairs: Sequence[Chair]) -> tuple[list[Chair], list[int]]:
    """Distinct chairs and each chair's index among them (zero spread: one simulation, not ``samples``)."""
    index: dict[Chair, int] = {}
    owner = [index.setdefault(c, len(index)) for c in chairs]
    return list(index), owner


def _measure(mc: Any, j: int, statuses: list[str], outside: Sequence[str], unit: str) -> MeasureInterval:
    def at(x: Any) -> float:
        return float(np.atleast_1d(x)[j])

    n = max(len(statuses), 1)
    ranked = sorted(((name, at(s)) for name, s in mc.shares.items()), key=lambda kv: -kv[1])
    return MeasureInterval(nominal=at(mc.nominal), low=at(mc.low), high=at(mc.high), median=at(mc.median),
                           finite_fraction=at(mc.finite_fraction),
                           outside=tuple((k, statuses.count(k) / n) for k in outside),
                           shares=tuple(ranked), r_squared=at(mc.r_squared), unit=unit)


@takes_chair
def nonlinear_intervals(chair: Chair, uncertainty: Uncertainty, run: RunSpec | None = None, *,
                        speed: float = REFERENCE_SPEED, samples: int = 200, seed: int = 0, level: float = 0.95,
                        reference_chair: Chair | None = None, equal_instability: bool = True,
                        rel_tol: float = 0.005, bracket: tuple[float, float] = (0.2, 3.0), tol: float = 0.005,
                        candidates: int = 7) -> NonlinearIntervals:
    """Monte Carlo intervals of the critical impulse and the equal-instability speed.

    Every draw's critical impulse comes from one :func:`~stability.study.impulse.critical_impulses`
    call (one simulation batch per bisection round) and every draw's
    equal-instability speed from one batched bisection
    (:func:`~stability.study.equal_instability.equal_instability_speeds`).
    The reference case of the equal-instability speed, ``reference_chair``
    at :data:`~stability.settings.reference.REFERENCE_SPEED` under
    :data:`~stability.settings.reference.THESIS_PUSH`, is *fixed* at its nominal
    values: it is the benchmark being compared against, not a measurement,
    and drawing it together with the chair (when they are the same chair)
    would give ``REFERENCE_SPEED`` in every draw.

    Parameters
    ----------
    chair : Chair
        The nominal chair.
    uncertainty : Uncertainty
        Distributions of its uncertain fields (:func:`stability.uncertainty.load_uncertainty`).
    run : RunSpec, optional
        The runs' settings of both measures and of the reference time (model, scheme, step, pin-friction
        law; the horizon is the criterion's duration; the push is the thesis's).
    speed : float
        Speed of the critical impulse, m/s.
    samples : int
        Monte Carlo draws, 1 to :data:`MAX_NONLINEAR_SAMPLES`.
    seed : int
        Seed of the draws.
    level : float
        Interval coverage, 0 < level < 1.
    reference_chair : Chair, optional
        Reference of the equal-instability speed (default the E&J Premier), fixed.
    equal_instability : bool
        Also the equal-instability speed (the larger share of the work).
    rel_tol : float
        Relative bracket of each critical impulse.
    bracket : (float, float)
        Speed range of the equal-instability search, m/s.
    tol : float
        Final bracket width of each equal-instability speed, m/s.
    candidates : int
        Candidate speeds per chair and bisection round.

    Returns
    -------
    NonlinearIntervals

    Raises
    ------
    ValueError
        For an argument out of range, or a reference case that never reaches the level.
    """
    run = study_run(run).replace(push_force=THESIS_PUSH.force, push_duration=THESIS_PUSH.duration)
    model, scheme, horizon = run.model, run.scheme, run.horizon
    dt = run.fixed_step
    check_speed(speed)
    samples = int(NONLINEAR_SAMPLES.check("samples", samples, integer=True))
    level = CONFIDENCE_LEVEL.check("level", level)
    crit = Criterion(LEVEL, horizon)
    ref_chair = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    t_ref = math.nan
    if equal_instability:
        t_ref = reference_time(ref_chair, REFERENCE_SPEED, run, criterion=crit)
    calls: list[tuple[list[str], list[str]]] = []      # statuses of each fn call (the last: the draws)

    def fn(chairs: list[Chair]) -> np.ndarray:
        distinct, owner = _unique(chairs)
        ci = critical_impulses(distinct, speed, run, level=LEVEL, rel_tol=rel_tol)
        imp = [0.0 if r.status == "below" else (math.nan if r.impulse_Ns is None else r.impulse_Ns) for r in ci]
        cols = [np.array([imp[k] for k in owner])]
        eq_status: list[str] = []
        if equal_instability:
            eq = equal_instability_speeds(distinct, run, reference_chair=ref_chair, reference_speed=REFERENCE_SPEED,
                                          criterion=crit, bracket=bracket, tol=tol, candidates=candidates,
                                          reference=t_ref, progress=False)
            cols.append(np.array([math.nan if eq[k].speed is None else eq[k].speed for k in owner]))
            eq_status = [eq[k].status for k in owner]
        calls.append(([ci[k].status for k in owner], eq_status))
        return np.column_stack(cols)

    mc = propagate(chair, uncertainty, fn, samples=int(samples), seed=int(seed), level=level)
    imp_status, eq_status = calls[-1]
    eq_iv = _measure(mc, 1, eq_status, ("above", "below"), "m/s") if equal_instability else None
    return NonlinearIntervals(
        chair_name=chair.name, speed=float(speed), model=model, scheme=scheme, level=float(level),
        samples=int(samples), seed=int(seed), push=THESIS_PUSH.describe(dt),
        reference=f"{ref_chair.name} at {REFERENCE_SPEED:g} m/s, nominal values (fixed, not drawn)",
        reference_time=float(t_ref), critical_impulse=_measure(mc, 0, imp_status, ("never",), "N s"),
        equal_instability=eq_iv, rejected=mc.rejected)
