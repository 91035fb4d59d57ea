"""The chapter 8-9 study of Collins (1987): the E&J Premier, the revised design, +/-50 % pin friction, the sweeps."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair, preset
from stability.chair.design import get_parameter, main_tires
from stability.linear import analyse
from stability.linear.summary import ZeroWidthResult, zero_width
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion, check_impulse
from stability.study.equal_instability import EqualInstability, equal_instability_speeds, reference_time
from stability.study.sweeps import DEFAULT_PLAN, SweepTable, collect_sweeps, sweep_chairs

__all__ = ["LinearFacts", "ThesisStudy", "friction_variants", "thesis_study"]

#: Speed of the thesis's tire comparison (Figure 8-15; at 0.75 m/s it found "virtually no effect"), m/s.
TIRE_SPEED = 0.62
#: The chair of the thesis's locked-caster check (eq 8-1): the E&J Premier at 75 kg.
LOCKED_CHECK_MASS = 75.0

#: Options of the bisection that the single runs of :func:`thesis_study` do not take.
#: The thesis's study's runs: its equations (``model="thesis"``), the thesis's push, the measures' stick-slip
#: pin friction (``friction_law="kinetic"`` reproduces program WCHAIR's law).
THESIS_RUN = RunSpec(model="thesis")


@dataclass(frozen=True)
class LinearFacts:
    """Linear critical speeds of the reference chair (conclusion 1).

    Attributes
    ----------
    free : float or None
        First destabilising crossing with free frictionless casters, m/s.
    free_unstable_all : bool
        Unstable at every speed searched with free casters.
    locked : float or None
        First destabilising crossing with locked casters, m/s.
    doubling_0_75 : float or None
        Time to double of the fastest-growing mode at the reference speed, s.
    """

    free: float | None
    free_unstable_all: bool
    locked: float | None
    doubling_0_75: float | None


@dataclass(frozen=True, eq=False)
class ThesisStudy:
    """Everything the conclusions are tested on (the E&J Premier and the revised design).

    Attributes
    ----------
    sweeps : SweepTable
        Chapter-8 sweeps of the E&J Premier.
    speeds : dict of str to EqualInstability
        Keyed ``"ej-premier"``, ``"revised"``, ``"ej-premier-front-caster"``,
        and ``"<name> x0.5 friction"`` / ``"<name> x1.5 friction"`` for the
        E&J Premier and the revised design.
    reference_time : float
        The reference case's time to the yaw-rate level, s.
    time_at_2 : float
        The E&J Premier's time to the level at 2 m/s, s (conclusion 7).
    linear : LinearFacts
        Linear critical speeds of the E&J Premier.
    model, scheme : str
    criterion : Criterion
    impulse : (float, float)
        Force (N), duration (s).
    tire_speed : float
        Speed of the thesis's tire comparison (Figure 8-15), m/s.
    tire_times : dict of str to float
        Time to the yaw-rate level of the E&J Premier with each main tire at ``tire_speed``, s
        (+inf: never; conclusion 9, under the thesis's own conditions).
    tire_peaks : dict of str to float
        Largest |yaw rate| of the same runs within the criterion's duration, rad/s (the slow divergence
        the thesis compares when the level is not reached).
    locked_check : ZeroWidthResult or None
        The zero-width locked-caster critical speed of the thesis's eq 8-1 chair (m = 75 kg), which
        the thesis puts at about 12 m/s (eq 8-5).
    """

    sweeps: SweepTable
    speeds: dict
    reference_time: float
    time_at_2: float
    linear: LinearFacts
    model: str
    scheme: str
    criterion: Criterion
    impulse: tuple
    tire_speed: float = float("nan")
    tire_times: dict | None = None
    tire_peaks: dict | None = None
    locked_check: ZeroWidthResult | None = None


def friction_variants(c: Chair, factors: Sequence[float] = (0.5, 1.5)) -> list[Chair]:
    """``c`` with both pin frictions times each factor, named ``"<name> x<f> friction"``.

    Parameters
    ----------
    c : Chair
    factors : sequence of float

    Returns
    -------
    list of Chair
    """
    return [c.replace(name=f"{c.name} x{f:g} friction", pin_friction_left=c.pin_friction_left * f,
                      pin_friction_right=c.pin_friction_right * f) for f in factors]


def linear_facts(chair: Chair, model: str) -> LinearFacts:
    """:class:`LinearFacts` of ``chair`` from :func:`stability.linear.analyse`."""
    lin = analyse(chair, model=model, speeds=(REFERENCE_SPEED,))
    free = next((c.speed for c in lin.free_crossings if c.direction == "destabilising"), None)
    locked = next((c.speed for c in lin.locked_crossings if c.direction == "destabilising"), None)
    return LinearFacts(free, bool(lin.free_unstable_at_all_speeds), locked, lin.divergence[0].time_to_double)


def thesis_study(run: RunSpec = THESIS_RUN, *, plan: dict | None = None,
                 criterion: Criterion = DEFAULT_CRITERION, extra_chairs: Sequence[Chair] = (),
                 extra_plan_chair: Chair | None = None, extra_plan: dict | None = None, progress: bool = True,
                 **options: Any) -> tuple[ThesisStudy, list[EqualInstability], SweepTable | None]:
    """The chapter 8-9 study on the E&J Premier, the revised design and +/-50 % pin friction.

    All chairs are rated in one vectorised bisection.

    Parameters
    ----------
    run : RunSpec
        The runs' settings (default :data:`THESIS_RUN`).
    criterion
        As in :func:`stability.study.equal_instability_speed`.
    plan : dict, optional
        Sweep plan for the E&J Premier (default :data:`DEFAULT_PLAN`).
    extra_chairs : sequence of Chair
        Rated alongside (returned second).
    extra_plan_chair : Chair, optional
        Gets its own sweep table with ``extra_plan`` (returned third) in the same batches.
    extra_plan : dict, optional
    progress : bool
    **options
        Passed to :func:`equal_instability_speeds` (``bracket``, ``tol``, ``candidates``, ``max_rounds``).

    Returns
    -------
    (ThesisStudy, list of EqualInstability, SweepTable or None)
    """
    run = runs.study_run(run)
    model, scheme, impulse = run.model, run.scheme, run.push.as_tuple
    ej, rev = preset(REFERENCE_CHAIR), preset("revised")
    front = preset(f"{REFERENCE_CHAIR}-front-caster")
    named = [ej, rev, front] + friction_variants(ej) + friction_variants(rev)
    plan = DEFAULT_PLAN if plan is None else plan
    groups = sweep_chairs(ej, plan)
    other_groups, other_chairs = [], []
    if extra_plan_chair is not None:
        other_groups = sweep_chairs(extra_plan_chair, extra_plan or plan)
        other_chairs = [extra_plan_chair] + [c for g in other_groups for c in g[3]]
    ref = reference_time(ej, REFERENCE_SPEED, run, criterion=criterion)
    all_chairs = named + [c for g in groups for c in g[3]] + list(extra_chairs) + other_chairs
    res = equal_instability_speeds(all_chairs, run, criterion=criterion, reference=ref, progress=progress, **options)
    speeds = {c.name: r for c, r in zip(named, res[: len(named)], strict=True)}
    table, k = collect_sweeps(ej, groups, res, len(named), speeds[REFERENCE_CHAIR])
    extra = list(res[k:k + len(extra_chairs)])
    k += len(extra_chairs)
    other_table = None
    if extra_plan_chair is not None:
        other_table, k = collect_sweeps(extra_plan_chair, other_groups, res, k + 1, res[k])
    # conclusion 7: time to the level at 2 m/s
    # conclusion 9 under the thesis's conditions: every main tire at 0.62 m/s (Figure 8-15)
    tire = get_parameter("main_tire")
    tire_chairs = [tire.apply(ej, float(i)) for i in range(len(main_tires()))]
    extra_runs = runs.simulate_runs([ej] + tire_chairs, [2.0] + [TIRE_SPEED] * len(tire_chairs),
                                    run.replace(horizon=criterion.duration))
    tire_times = {c.main_tire: criterion.time(r) for c, r in zip(tire_chairs, extra_runs[1:], strict=True)}
    tire_peaks = {c.main_tire: float(np.max(np.abs(np.asarray(r.yaw_rate)[np.asarray(r.t) <= criterion.duration])))
                  for c, r in zip(tire_chairs, extra_runs[1:], strict=True)}
    # the thesis's own check of WCHAIR (eqs 8-1..8-5): the zero-width locked-caster critical speed at 75 kg
    locked = zero_width(ej.replace(m=LOCKED_CHECK_MASS))
    study = ThesisStudy(table, speeds, ref, criterion.time(extra_runs[0]), linear_facts(ej, model), model, scheme,
                        criterion, check_impulse(impulse), TIRE_SPEED, tire_times, tire_peaks, locked)
    return study, extra, other_table
