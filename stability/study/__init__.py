"""Parametric studies with the nonlinear simulator (Collins 1987, chapters 8 and 9).

The thesis rates a design by the time its |yaw rate| takes to reach 1 rad/s
after a 40 N, 0.1 s lateral push at the c.g., against the E&J Premier at
0.75 m/s (:mod:`stability.settings.reference`).  Modules: :mod:`.criteria` (the
criterion), :mod:`.runs` (simulator access), :mod:`.responses` (nonlinear
and linear responses), :mod:`.equal_instability`, :mod:`.maps`,
:mod:`.sweeps`, :mod:`.thesis`, :mod:`.conclusions`; the robust
measures :mod:`.impulse`, :mod:`.intervals`, :mod:`.sensitivity`, :mod:`.facts`;
:mod:`.uncertain` (nonlinear measures with Monte Carlo intervals); :mod:`.layout_impulse` (the critical impulse
of any wheel layout, forward and in reverse).  Rationale:
docs/studies.md.
"""

from __future__ import annotations

from stability.linear import lateral_force_input
from stability.settings.reference import THESIS_PUBLISHED
from stability.study.conclusions import CONCLUSIONS, ConclusionCheck, check_conclusions
from stability.study.criteria import Criterion, check_impulse, time_to_yaw_rate
from stability.study.equal_instability import (
    EqualInstability,
    equal_instability_speed,
    equal_instability_speeds,
    reference_time,
)
from stability.study.facts import (
    PROPORTIONAL_RANGE,
    EqualFrictionComparison,
    EqualFrictionRow,
    FrictionExponent,
    SteadyTurn,
    equal_friction_comparison,
    fit_exponent,
    friction_exponent,
    growth_rate,
    steady_turn,
)
from stability.study.impulse import (
    CriticalImpulse,
    CriticalImpulseCurve,
    critical_impulse,
    critical_impulse_curve,
    critical_impulses,
    push_impulse,
)
from stability.study.impulse_intervals import CriticalImpulseInterval, critical_impulse_intervals
from stability.study.intervals import (
    FRICTION_FACTORS,
    PUSH_FACTORS,
    RANGE_BRACKET,
    RANGE_DEFINITION,
    RANGE_TOL,
    EqualInstabilityInterval,
    FactorRange,
    Variant,
    equal_instability_interval,
    equal_instability_intervals,
)
from stability.study.layout_impulse import layout_critical_impulse_curve, layout_critical_impulses
from stability.study.maps import StabilityMap, disturbance_map, stability_map
from stability.study.responses import (
    LinearResponse,
    Response,
    ResponseSet,
    linear_impulse_response,
    trajectories,
    yaw_rate_responses,
)
from stability.study.runs import SCALAR_RUNS
from stability.study.sensitivity import (
    ELASTICITY_PARAMETERS,
    FRICTION_OVER_TRAIL,
    TRAIL_AT_FIXED_GROUP,
    Elasticity,
    Sensitivity,
    elasticities,
)
from stability.study.sweeps import DEFAULT_PLAN, QUICK_PLAN, Sweep, SweepRow, SweepTable, parameter_sweeps, plan_for
from stability.study.thesis import LinearFacts, ThesisStudy, friction_variants, thesis_study
from stability.study.uncertain import MAX_NONLINEAR_SAMPLES, MeasureInterval, NonlinearIntervals, nonlinear_intervals

#: Former name of :data:`stability.settings.reference.THESIS_PUBLISHED` (kept for callers not yet moved).
THESIS = THESIS_PUBLISHED

__all__ = [
    "Criterion",
    "time_to_yaw_rate",
    "check_impulse",
    "SCALAR_RUNS",
    "LinearResponse",
    "Response",
    "ResponseSet",
    "linear_impulse_response",
    "lateral_force_input",
    "yaw_rate_responses",
    "trajectories",
    "reference_time",
    "EqualInstability",
    "equal_instability_speed",
    "equal_instability_speeds",
    "StabilityMap",
    "stability_map",
    "disturbance_map",
    "Sweep",
    "SweepRow",
    "SweepTable",
    "DEFAULT_PLAN",
    "QUICK_PLAN",
    "parameter_sweeps",
    "plan_for",
    "LinearFacts",
    "ThesisStudy",
    "thesis_study",
    "friction_variants",
    "ConclusionCheck",
    "CONCLUSIONS",
    "check_conclusions",
    "THESIS",
    "CriticalImpulse",
    "CriticalImpulseCurve",
    "critical_impulse",
    "critical_impulses",
    "critical_impulse_curve",
    "push_impulse",
    "EqualInstabilityInterval",
    "FactorRange",
    "Variant",
    "equal_instability_interval",
    "equal_instability_intervals",
    "PUSH_FACTORS",
    "FRICTION_FACTORS",
    "RANGE_TOL",
    "RANGE_BRACKET",
    "RANGE_DEFINITION",
    "CriticalImpulseInterval",
    "critical_impulse_intervals",
    "EqualFrictionComparison",
    "EqualFrictionRow",
    "equal_friction_comparison",
    "FrictionExponent",
    "friction_exponent",
    "fit_exponent",
    "PROPORTIONAL_RANGE",
    "SteadyTurn",
    "steady_turn",
    "growth_rate",
    "Elasticity",
    "Sensitivity",
    "elasticities",
    "ELASTICITY_PARAMETERS",
    "FRICTION_OVER_TRAIL",
    "TRAIL_AT_FIXED_GROUP",
    "MeasureInterval",
    "NonlinearIntervals",
    "nonlinear_intervals",
    "MAX_NONLINEAR_SAMPLES",
    "layout_critical_impulses",
    "layout_critical_impulse_curve",
]
