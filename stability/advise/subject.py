"""What the advisor advises on: a short-form chair or a wheel layout, one door for both.

The advisor's method (:mod:`.advisor`: measure every single change, screen the pairs on the limits, measure the best,
the decision and the blocked-fix logic) does not depend on what it changes.  These functions give it the levers,
the changed designs and their measures of either kind: a :class:`stability.chair.Chair` goes to :mod:`.levers` and
:mod:`.measures` (the thesis engine's studies), a :class:`stability.layout.Layout` to :mod:`.layout_levers` and
:mod:`.layout_measures` (the layout studies, forward or in reverse).  Every function has the signature of the one
it stands for, so the advisor calls them unchanged.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from stability.advise.layout_levers import apply_layout, caster_rows, layout_lever_changes, layout_levers
from stability.advise.layout_measures import (
    layout_linear_measures,
    layout_shimmy_rows,
    layout_time_to_correct,
    measure_layouts,
)
from stability.advise.levers import LEVERS
from stability.advise.levers import apply as apply_chair
from stability.advise.levers import lever_changes as chair_lever_changes
from stability.advise.limits import SHIMMY_AMPLITUDE_DEG, ShimmyHold
from stability.advise.limits import shimmy_hold as chair_shimmy_hold
from stability.advise.measures import linear_measures as chair_linear_measures
from stability.advise.measures import measure_chairs as chair_measures
from stability.chair import Chair
from stability.layout.model import Layout
from stability.runtime.checks import is_real, real_value, value_text
from stability.settings.bounds import ADVISE_SPEED, ADVISE_SPEED_COUNT
from stability.settings.run import RunSpec
from stability.study import reference_time

__all__ = ["use_speeds", "lever_changes", "apply", "levers_of", "measure_chairs", "linear_measures", "shimmy_hold",
           "time_to_correct", "is_layout"]


def use_speeds(speeds: Any, name: str = "speeds") -> tuple[float, ...]:
    """The advisor's use speeds, checked before any work: the API's form of the commands' ``--speeds`` check.

    Parameters
    ----------
    speeds : sequence of float
        Use speeds, m/s: 1 to :data:`~stability.settings.bounds.ADVISE_SPEED_COUNT` real numbers whose sizes lie in
        :data:`~stability.settings.bounds.ADVISE_SPEED` (0.1 to 3 m/s), all positive (forward) or all negative (in
        reverse).
    name : str, optional
        The argument's name in a refusal (default ``"speeds"``).

    Returns
    -------
    tuple of float
        The speeds, m/s, in the order given.

    Raises
    ------
    ValueError
        Naming ``name`` (or the offending element ``name[i]``), its value and the valid range: not a sequence of
        numbers, empty, too many, a size outside the range, or mixed signs.
    """
    count = f"1 to {ADVISE_SPEED_COUNT} speeds, {ADVISE_SPEED.text('speed')} in size, all negative: in reverse"
    if isinstance(speeds, (str, bytes)) or not isinstance(speeds, Iterable):
        raise ValueError(f"{name}={value_text(speeds)} is invalid; valid values: a sequence of {count}")
    given = list(itertools.islice(speeds, ADVISE_SPEED_COUNT + 1))      # bounded: a huge iterable is not copied
    if not 1 <= len(given) <= ADVISE_SPEED_COUNT:
        raise ValueError(f"{name} has {'no' if not given else 'more than ' + str(ADVISE_SPEED_COUNT)} values; "
                         f"valid values: {count}")
    use = []
    for i, u in enumerate(given):
        if not (is_real(u) and bool(ADVISE_SPEED.holds(abs(real_value(u))))):
            raise ValueError(f"{name}[{i}]={value_text(u)} is invalid; valid range: {ADVISE_SPEED.text('speed')} "
                             "in size (all negative: in reverse)")
        use.append(real_value(u))
    if len({u < 0 for u in use}) > 1:
        raise ValueError(f"{name}={tuple(use)!r} is invalid; valid: all forward (> 0) or all in reverse (< 0)")
    return tuple(use)


def is_layout(subject: object) -> bool:
    """Whether the subject is a wheel layout.

    Parameters
    ----------
    subject : Chair or Layout

    Returns
    -------
    bool
    """
    return isinstance(subject, Layout)


def _all_layouts(subjects: Sequence) -> bool:
    kinds = {is_layout(s) for s in subjects}
    if len(kinds) > 1:
        raise ValueError("subjects: expected chairs or layouts, not both")
    return kinds == {True}


def lever_changes(subject: Chair | Layout) -> tuple[list, list]:
    """:func:`.levers.lever_changes` or :func:`.layout_levers.layout_lever_changes`.

    Parameters
    ----------
    subject : Chair or Layout

    Returns
    -------
    tuple
        ``([(change, changed subject), ...], [(change, reason), ...])``.
    """
    if isinstance(subject, Layout):
        return layout_lever_changes(subject)
    return chair_lever_changes(subject)


def apply(subject: Chair | Layout, fields) -> Chair | Layout:
    """:func:`.levers.apply` or :func:`.layout_levers.apply_layout`.

    Parameters
    ----------
    subject : Chair or Layout
    fields : iterable of (str, value)

    Returns
    -------
    Chair or Layout
    """
    if isinstance(subject, Layout):
        return apply_layout(subject, fields)
    return apply_chair(subject, fields)


def levers_of(subject: Chair | Layout) -> dict:
    """The subject's levers, name -> (description, generator), in the order the advice lists them.

    Parameters
    ----------
    subject : Chair or Layout

    Returns
    -------
    dict
    """
    if isinstance(subject, Layout):
        return layout_levers(subject)
    return LEVERS


def measure_chairs(subjects: Sequence, *, speeds: Sequence[float], cross_slope_deg: float, progress: bool = False,
                   nonlinear: Callable | None = None, cores: dict | None = None,
                   reaction_time: float | None = None) -> list:
    """:func:`.measures.measure_chairs`, or :func:`.layout_measures.measure_layouts` for layouts.

    Parameters
    ----------
    subjects : sequence of Chair, or of Layout
    speeds, cross_slope_deg, progress, nonlinear, cores, reaction_time
        As :func:`.measures.measure_chairs` (negative speeds: a layout in reverse).

    Returns
    -------
    list of Measures
    """
    subjects = list(subjects)
    if _all_layouts(subjects):
        return measure_layouts(subjects, speeds=speeds, progress=progress, nonlinear=nonlinear, cores=cores,
                               cross_slope_deg=cross_slope_deg, reaction_time=reaction_time)
    return chair_measures(subjects, speeds=speeds, cross_slope_deg=cross_slope_deg, progress=progress,
                          nonlinear=nonlinear, cores=cores, reaction_time=reaction_time)


def linear_measures(subjects: Sequence, *, speeds: Sequence[float], cross_slope_deg: float,
                    cores: dict | None = None, reaction_time: float | None = None, lazy: bool = False) -> list:
    """:func:`.measures.linear_measures`, or :func:`.layout_measures.layout_linear_measures` for layouts.

    Parameters
    ----------
    subjects : sequence of Chair, or of Layout
    speeds, cross_slope_deg, cores, reaction_time, lazy
        As :func:`.measures.linear_measures`.

    Returns
    -------
    list of Linear (or of LazyLinear)
    """
    subjects = list(subjects)
    if subjects and _all_layouts(subjects):
        return layout_linear_measures(subjects, speeds=speeds, cores=cores, cross_slope_deg=cross_slope_deg,
                                      reaction_time=reaction_time, lazy=lazy)
    return chair_linear_measures(subjects, speeds=speeds, cross_slope_deg=cross_slope_deg, cores=cores,
                                 reaction_time=reaction_time, lazy=lazy)


def shimmy_hold(subject: Chair | Layout, speeds: tuple,
                amplitude_deg: float = SHIMMY_AMPLITUDE_DEG) -> ShimmyHold | None:
    """:func:`.limits.shimmy_hold`; for a layout, of the caster row nearest a shimmy boundary.

    Parameters
    ----------
    subject : Chair or Layout
    speeds : tuple of float
        m/s (magnitudes taken).
    amplitude_deg : float

    Returns
    -------
    ShimmyHold or None
    """
    if not isinstance(subject, Layout):
        return chair_shimmy_hold(subject, speeds, amplitude_deg)
    import math

    from stability.shimmy.chair import friction_trail
    from stability.shimmy.layout_caster import LayoutCaster

    rows = caster_rows(subject)
    if not rows:
        return None
    bands = layout_shimmy_rows(subject, speeds)
    k = min(range(len(rows)), key=lambda i: bands[i][2].shimmy_margin_m)
    caster = LayoutCaster(subject, rows[k][0], all(float(u) < 0 for u in speeds))
    if caster.pin_friction_left <= 0:
        return None
    try:
        trail = max(friction_trail(caster, abs(float(u)), math.radians(amplitude_deg)) for u in speeds)
    except ValueError:
        return None
    return ShimmyHold(float(amplitude_deg), float(caster.pin_friction_left), float(trail),
                             float(caster.trail))


def time_to_correct(subject: Chair | Layout, speed: float) -> float:
    """Time after the thesis's push until ``|yaw rate|`` reaches 1 rad/s at ``speed`` (the advisor's verdict).

    Parameters
    ----------
    subject : Chair or Layout
    speed : float
        m/s (negative: a layout in reverse).

    Returns
    -------
    float
        s.  Raises ValueError when never reached.
    """
    if isinstance(subject, Layout):
        return layout_time_to_correct(subject, speed)
    return reference_time(subject, speed, RunSpec(model="exact"))
