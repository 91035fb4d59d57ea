"""Equal-instability speed of any wheel layout, forward and in reverse: the thesis chair's study on the layout runs.

The definition is the short form's (:mod:`stability.study.equal_instability`, thesis chapter 9): the speed at which
the chair, after the push, reaches ``|yaw rate|`` 1 rad/s as soon as the reference case does (the E&J Premier at
0.75 m/s on the thesis engine, its time from :func:`stability.study.equal_instability.reference_time`).  The search
is the same (:func:`stability.study.equal_instability.bisect_speeds`: candidates, regula falsi, the run's horizon
cut at 1.5 x the reference time + 0.5 s); only the runs differ: each is a
:func:`stability.simulate.layout.simulate_layout` run of the layout, at the step the critical-impulse study of a
layout takes (:func:`stability.study.layout_impulse.layout_step_limits_and_growth`).

In reverse the speeds searched are backwards (the search runs on ``|U|``) and every caster starts trailing the
direction of travel (180 deg), as in :mod:`stability.study.layout_impulse`: the reference case stays the thesis's
forward one, so the answer reads "backwards, this layout is as unstable as the reference chair at 0.75 m/s
forwards at ...".

The range (:func:`layout_equal_instability_interval`) is the short form's over the push force and the pin friction
(on the layout's casters and on the reference chair) and half the step; the model variant is left out (a layout's
equations are the exact model's only): :data:`LAYOUT_RANGE_DEFINITION`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np

from stability.chair import Chair, preset
from stability.layout.model import Layout, check_layout
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.simulate.layout import check_layout_run, simulate_layout_runs
from stability.simulate.signals import time_to_level
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion, check_impulse
from stability.study.equal_instability import EqualInstability, bisect_speeds, reference_time
from stability.study.intervals import (
    FRICTION_FACTORS,
    PUSH_FACTORS,
    RANGE_BRACKET,
    RANGE_TOL,
    STEP_FACTORS,
    EqualInstabilityInterval,
    Variant,
    _assemble,
    _variants,
    reference_times,
    scale_friction,
)
from stability.study.layout_impulse import layout_step_limits_and_growth, trailing_angles
from stability.study.summaries import Summaries, run_steps

__all__ = ["layout_summaries", "layout_equal_instability", "layout_equal_instability_interval",
           "scale_layout_friction", "LAYOUT_RANGE_DEFINITION", "direction_words"]

#: The layout range's definition in words (the short form's, :data:`stability.study.intervals.RANGE_DEFINITION`,
#: without the model variant).
LAYOUT_RANGE_DEFINITION = ("the range is over the push force x0.5, x0.75, x1.5 and x2, the pin friction x0.5 and "
                           "x1.5 (on both the layout's casters and the reference chair) and half the simulator's "
                           "step, one at a time: not a statistical interval (no model variant: a layout's equations "
                           "are the exact model's)")


def direction_words(reverse: bool) -> str:
    """``"forward"`` or ``"in reverse"``.

    Parameters
    ----------
    reverse : bool

    Returns
    -------
    str
    """
    return "in reverse" if reverse else "forward"


def scale_layout_friction(layout: Layout, factor: float) -> Layout:
    """``layout`` with every caster's Coulomb pin friction times ``factor`` (1: ``layout`` itself).

    Parameters
    ----------
    layout : Layout
    factor : float
        >= 0.

    Returns
    -------
    Layout
    """
    if factor == 1.0:
        return layout
    return dataclasses.replace(layout, casters=tuple(dataclasses.replace(c, pin_friction=c.pin_friction * factor)
                                                     for c in layout.casters))


def layout_summaries(layouts: Sequence[Layout], speeds: Sequence[float] | np.ndarray,
                     forces: Sequence[float] | np.ndarray, run: RunSpec, *, level: float,
                     reverse: bool = False) -> Summaries:
    """Run summaries of layout runs (layout i at speed i under a push of force i), as the thesis engine's.

    Each run's step is the critical-impulse study's for a layout (``run.dt``, cut where the layout's linear model
    needs a smaller one); every step is recorded, so that the crossings are interpolated as the compiled engine
    interpolates them; a run stopped by the warning rule reaches the level when it stopped.  The runs of one layout
    (the same object) under one push at one step are stepped in one kernel call
    (:func:`stability.simulate.layout.simulate_layout_runs`: each run's arithmetic is its own run's, bit for bit).

    Parameters
    ----------
    layouts : sequence of Layout
    speeds : sequence of float
        ``|U|``, m/s (> 0).
    forces : sequence of float
        Push force, N.
    run : RunSpec
        The runs' settings (wchair scheme, exact model, level ground).
    level : float
        |yaw rate| level, rad/s.
    reverse : bool
        Drive backwards, every caster starting at 180 deg (trailing).

    Returns
    -------
    Summaries
    """
    sign = -1.0 if reverse else 1.0
    dt = run.fixed_step
    n = len(layouts)
    signed = sign * np.asarray(speeds, dtype=float).reshape(-1)
    force = np.asarray(forces, dtype=float).reshape(-1)
    if not (signed.size == force.size == n):
        raise ValueError(f"layouts, speeds and forces have {n}, {signed.size} and {force.size} entries, which is "
                         "invalid; valid: one speed and one force per layout")
    # the runs of one layout (one linear model for all its speeds), then of one push and step (one kernel call)
    groups: dict[int, list[int]] = {}
    for i, lay in enumerate(layouts):
        groups.setdefault(id(lay), []).append(i)
    h = np.empty(n)
    for idx in groups.values():
        limits, _ = layout_step_limits_and_growth(layouts[idx[0]], signed[idx])
        h[idx] = run_steps([], signed[idx], dt, "exact", run.casters, limits=limits)
    batches: dict[tuple[int, float, float], list[int]] = {}
    for i in range(n):
        batches.setdefault((id(layouts[i]), float(force[i]), float(h[i])), []).append(i)
    peak, t_half, t_level, sim_time = (np.empty(n) for _ in range(4))
    for (_, f, step), idx in batches.items():
        lay = layouts[idx[0]]
        runs_ = simulate_layout_runs(lay, [float(signed[i]) for i in idx], run.replace(push_force=f, dt=step,
                                                                                        sample=step),
                                     caster_angles_deg=[trailing_angles(lay, float(signed[i])) for i in idx])
        for i, r in zip(idx, runs_, strict=True):
            t, y = r.t_s, r.yaw_rate_rad_s
            t_level[i] = time_to_level(t, y, level)
            if r.ended in ("slip warnings", "load warnings"):
                t_level[i] = min(t_level[i], r.end_time_s)
            peak[i] = float(np.max(np.abs(y)))
            t_half[i] = time_to_level(t, y, 0.5 * level)
            sim_time[i] = float(t[-1])
    return Summaries(peak, t_half, t_level, sim_time)


def _check(layout: Layout, run: RunSpec | None) -> RunSpec:
    check_layout(layout)
    run = runs.study_run(run)
    check_layout_run(run)
    check_impulse((run.push_force, run.push_duration))
    return run


def layout_equal_instability(layout: Layout, run: RunSpec | None = None, *, reverse: bool = False,
                             reference_chair: Chair | None = None, reference_speed: float = REFERENCE_SPEED,
                             criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = (0.2, 3.0),
                             tol: float = 0.005, candidates: int = 7, max_rounds: int = 8,
                             reference: float | None = None, progress: bool = False) -> EqualInstability:
    """Speed (forward, or backwards with ``reverse``) at which ``layout`` is as unstable as the reference case.

    Parameters
    ----------
    layout : Layout
    run : RunSpec, optional
        The runs' settings: the push (the thesis's 40 N for 0.1 s by default), the step and the pin-friction law;
        the scheme must be ``"wchair"``, the model ``"exact"``.  The reference case runs with the same settings on
        the thesis engine.
    reverse : bool
        Search backwards speeds (casters trailing at 180 deg); the reference case stays forwards.
    reference_chair, reference_speed, criterion, bracket, tol, candidates, max_rounds, reference, progress
        As in :func:`stability.study.equal_instability.equal_instability_speeds` (``bracket`` in ``|U|``).

    Returns
    -------
    EqualInstability
        Its speeds are ``|U|``; ``chair`` is the layout.  The E&J Premier as a layout gives the reference speed
        (it is the reference case).
    """
    run = _check(layout, run)
    lo0, hi0 = (float(x) for x in bracket)
    if not (0 < lo0 < hi0 and math.isfinite(hi0)):
        raise ValueError(f"bracket={bracket!r} is invalid; expected 0 < low < high (m/s)")
    if not tol > 0:
        raise ValueError(f"tol={tol!r} is invalid; valid range: > 0 m/s")
    ref_chair = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    if reference is None:
        reference = reference_time(ref_chair, reference_speed, run, criterion=criterion)
    return bisect_speeds([layout], [float(reference)], [run.push_force], run, criterion=criterion,
                         bracket=(lo0, hi0), tol=tol, candidates=max(1, int(candidates)), max_rounds=max_rounds,
                         progress=progress, reference_text=f"{ref_chair.name} at {reference_speed:g} m/s",
                         summarise=_summariser(reverse))[0]


def _summariser(reverse: bool):
    def summarise(layouts, speeds, forces, run, *, level):
        return layout_summaries(layouts, speeds, forces, run, level=level, reverse=reverse)

    return summarise


def layout_equal_instability_interval(layout: Layout, run: RunSpec | None = None, *, reverse: bool = False,
                                      force_factors: Sequence[float] = PUSH_FACTORS,
                                      friction_factors: Sequence[float] = FRICTION_FACTORS,
                                      step_factors: Sequence[float] = STEP_FACTORS,
                                      reference_chair: Chair | None = None,
                                      reference_speed: float = REFERENCE_SPEED,
                                      criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = RANGE_BRACKET,
                                      tol: float = RANGE_TOL, candidates: int = 7, max_rounds: int = 8,
                                      friction_on_reference: bool = True,
                                      progress: bool = False) -> EqualInstabilityInterval:
    """The equal-instability speed of a layout with the short form's range, less the model variant.

    Each variant moves one input: the push force (both the reference's and the layout's runs), the pin friction
    (every caster of the layout and, with ``friction_on_reference``, both pins of the reference chair), or the
    fixed step (both).  A variant in which the reference never reaches the level is undefined.

    Parameters
    ----------
    layout : Layout
    run : RunSpec, optional
        As in :func:`layout_equal_instability`.
    reverse : bool
    force_factors, friction_factors, step_factors : sequence of float
    reference_chair, reference_speed, criterion, bracket, tol, candidates, max_rounds, friction_on_reference,
    progress
        As in :func:`stability.study.intervals.equal_instability_interval`.

    Returns
    -------
    EqualInstabilityInterval
        Speeds ``|U|``.
    """
    run = _check(layout, run)
    push = run.push
    dt = run.fixed_step
    ref0 = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    specs = _variants("exact", push.force, force_factors, friction_factors, ("exact",), dt, step_factors)
    out: list[Variant] = []
    for h in dict.fromkeys(s[5] for s in specs):        # one reference batch per step
        idx = [k for k, s in enumerate(specs) if s[5] == h]
        spec = run.replace(dt=h)
        refs = [scale_friction(ref0, specs[k][4] if friction_on_reference else 1.0) for k in idx]
        t_ref = reference_times(refs, reference_speed, [specs[k][3] for k in idx], spec, criterion=criterion)
        for k, t in zip(idx, t_ref, strict=True):
            res = None
            if math.isfinite(t):
                res = bisect_speeds([scale_layout_friction(layout, specs[k][4])], [float(t)], [specs[k][3]], spec,
                                    criterion=criterion, bracket=(float(bracket[0]), float(bracket[1])), tol=tol,
                                    candidates=candidates, max_rounds=max_rounds, progress=progress,
                                    reference_text=f"{ref0.name} at {reference_speed:g} m/s",
                                    summarise=_summariser(reverse))[0]
            out.append(Variant(*specs[k][:2], "exact", specs[k][3], specs[k][4], float(t), res, h))
    out.sort(key=lambda v: [s[1] for s in specs].index(v.label))
    scope = "both the layout's casters and the reference chair" if friction_on_reference else "the layout only"
    return _assemble(layout, tuple(out), ref0, reference_speed, criterion, push, dt, "wchair", scope)
