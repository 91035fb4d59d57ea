"""The critical impulse of any wheel layout with its interval, forward and in reverse: the short form's range.

The short form's interval (:mod:`stability.study.impulse_intervals`) is over the Coulomb pin friction (x0.5 and
x1.5, :data:`stability.study.intervals.FRICTION_FACTORS`), the model (exact or thesis) and the simulator's step (the
nominal case again at half the step, :data:`stability.study.intervals.STEP_FACTORS`).  A layout has the first and the
last (its equations are the exact model's only): every caster's pin friction scaled
(:func:`stability.study.layout_equal_instability.scale_layout_friction`), and the layout study
(:func:`stability.study.layout_impulse.layout_critical_impulses`) run again at the scaled step.  ``python -m
stability.study critical-impulse --chair LAYOUT --interval`` prints it; the advisor's layout measure is its range
(:mod:`stability.advise.layout_measures`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from stability.layout.model import Layout
from stability.settings.run import RunSpec
from stability.study.impulse_intervals import CriticalImpulseInterval
from stability.study.intervals import FRICTION_FACTORS, STEP_FACTORS
from stability.study.layout_equal_instability import scale_layout_friction
from stability.study.layout_impulse import layout_critical_impulses
from stability.study.runs import study_run

__all__ = ["layout_critical_impulse_intervals", "layout_interval_specs"]


def layout_interval_specs(run: RunSpec | None = None, friction_factors: Sequence[float] = FRICTION_FACTORS,
                          step_factors: Sequence[float] = STEP_FACTORS) -> list[tuple[str, float, float]]:
    """The interval's cases: ``(label, pin-friction factor, step s)``, the nominal case first.

    Parameters
    ----------
    run : RunSpec, optional
        The nominal runs' settings (its step; ``"auto"`` is program WCHAIR's 1 ms).
    friction_factors, step_factors : sequence of float

    Returns
    -------
    list of tuple
        Labels as the short form's (``"x0.5 pin friction"``, ``"0.5 ms step"``).
    """
    run = study_run(run)
    dt = run.fixed_step
    specs = [("nominal", 1.0, dt)] + [(f"x{f:g} pin friction", float(f), dt) for f in friction_factors]
    return specs + [(f"{dt * f * 1e3:g} ms step", 1.0, dt * float(f)) for f in step_factors]


def layout_critical_impulse_intervals(layout: Layout, speeds: Any, run: RunSpec | None = None, *,
                                      friction_factors: Sequence[float] = FRICTION_FACTORS,
                                      step_factors: Sequence[float] = STEP_FACTORS,
                                      **search: Any) -> list[CriticalImpulseInterval]:
    """Critical impulse of ``layout`` at each speed with its range over pin friction and the step.

    Parameters
    ----------
    layout : Layout
    speeds : float or array_like
        m/s, negative: reverse (:func:`stability.study.layout_impulse.layout_critical_impulses`'s range).
    run : RunSpec, optional
        The nominal runs' settings.
    friction_factors, step_factors : sequence of float
        Multipliers of every caster's Coulomb pin friction and of the fixed step.
    **search
        As :func:`stability.study.layout_impulse.layout_critical_impulses` (level, max_impulse, side, ...).

    Returns
    -------
    list of CriticalImpulseInterval
        One per speed (``speed`` signed), variants labelled as the short form's.
    """
    run = study_run(run)
    specs = layout_interval_specs(run, friction_factors, step_factors)
    res = [layout_critical_impulses(scale_layout_friction(layout, f), speeds, run.replace(dt=h), **search)
           for _, f, h in specs]
    out = []
    for k, point in enumerate(res[0]):
        variants = tuple((label, r[k]) for (label, _, _), r in zip(specs[1:], res[1:], strict=True))
        bounds = [point.bound_Ns] + [r.bound_Ns for _, r in variants]
        out.append(CriticalImpulseInterval(layout.name, float(point.speed), point, variants, float(min(bounds)),
                                           float(max(bounds))))
    return out
