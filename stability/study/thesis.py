"""The chapter 8-9 study of Collins (1987): the E&J Premier, the revised design, +/-50 % pin friction, the sweeps."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..chair import Chair, preset
from ..linear import analyse
from ..reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from . import runs
from .criteria import DEFAULT_CRITERION, Criterion, check_impulse
from .equal_instability import EqualInstability, equal_instability_speeds, reference_time
from .sweeps import DEFAULT_PLAN, SweepTable, collect_sweeps, sweep_chairs

__all__ = ["LinearFacts", "ThesisStudy", "friction_variants", "thesis_study"]

#: Options of the bisection that the single runs of :func:`thesis_study` do not take.
_BISECTION_ONLY = ("dt", "bracket", "tol", "candidates", "max_rounds")


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


def thesis_study(*, model: str = "thesis", scheme: str = "wchair", plan: dict | None = None,
                 criterion: Criterion = DEFAULT_CRITERION, impulse: Any = THESIS_PUSH.as_tuple,
                 extra_chairs: Sequence[Chair] = (), extra_plan_chair: Chair | None = None,
                 extra_plan: dict | None = None, progress: bool = True,
                 **options: Any) -> tuple[ThesisStudy, list[EqualInstability], SweepTable | None]:
    """The chapter 8-9 study on the E&J Premier, the revised design and +/-50 % pin friction.

    All chairs are rated in one vectorised bisection.

    Parameters
    ----------
    model, scheme, criterion, impulse
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
        Passed to :func:`equal_instability_speeds`.

    Returns
    -------
    (ThesisStudy, list of EqualInstability, SweepTable or None)
    """
    ej, rev = preset(REFERENCE_CHAIR), preset("revised")
    front = preset(f"{REFERENCE_CHAIR}-front-caster")
    named = [ej, rev, front] + friction_variants(ej) + friction_variants(rev)
    plan = DEFAULT_PLAN if plan is None else plan
    groups = sweep_chairs(ej, plan)
    other_groups, other_chairs = [], []
    if extra_plan_chair is not None:
        other_groups = sweep_chairs(extra_plan_chair, extra_plan or plan)
        other_chairs = [extra_plan_chair] + [c for g in other_groups for c in g[3]]
    sim_extra = {k: v for k, v in options.items() if k not in _BISECTION_ONLY}
    ref = reference_time(ej, REFERENCE_SPEED, impulse=impulse, criterion=criterion, model=model, scheme=scheme,
                         dt=options.get("dt", 0.001), **sim_extra)
    all_chairs = named + [c for g in groups for c in g[3]] + list(extra_chairs) + other_chairs
    res = equal_instability_speeds(all_chairs, model=model, scheme=scheme, criterion=criterion, impulse=impulse,
                                   reference=ref, progress=progress, **options)
    speeds = {c.name: r for c, r in zip(named, res[: len(named)], strict=True)}
    table, k = collect_sweeps(ej, groups, res, len(named), speeds[REFERENCE_CHAIR])
    extra = list(res[k:k + len(extra_chairs)])
    k += len(extra_chairs)
    other_table = None
    if extra_plan_chair is not None:
        other_table, k = collect_sweeps(extra_plan_chair, other_groups, res, k + 1, res[k])
    # conclusion 7: time to the level at 2 m/s
    opts = runs.sim_options(model, scheme, check_impulse(impulse), options.get("dt", 0.001), criterion.duration,
                            sim_extra)
    r2 = runs.simulate_runs([ej], [2.0], progress=False, **opts)[0]
    study = ThesisStudy(table, speeds, ref, criterion.time(r2), linear_facts(ej, model), model, scheme, criterion,
                        check_impulse(impulse))
    return study, extra, other_table
