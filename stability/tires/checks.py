"""Checks of a chair's tires before any analysis: data it needs, static loads inside the fits.

Called by chair validation and the command lines; see ``docs/tires.md``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from stability.runtime.checks import first_argument, value_text
from stability.tires.ranges import RangeNote, record, resolve

if TYPE_CHECKING:
    from stability.chair import Chair

__all__ = ["WHEELS", "check_chair_tires", "range_check"]


def _chair_like(chair: object, name: str) -> None:
    """A chair, read by what this module uses of it (the chair package imports this one, so not by its class)."""
    if not callable(getattr(chair, "main_tire_model", None)):
        raise TypeError(f"{name}={value_text(chair)} is invalid; valid values: a stability.Chair")

#: Wheels of a chair: keys of :func:`stability.models.statics.static_loads` and which tire each carries.
WHEELS: tuple[tuple[str, str], ...] = (
    ("caster_left", "caster"), ("caster_right", "caster"), ("main_left", "main"), ("main_right", "main"),
)


@first_argument(_chair_like)
def check_chair_tires(chair: Chair) -> None:
    """Refuse, in one line, a chair whose tires lack data the chair's settings need.

    Camber force needs a camber coefficient when ``camber_deg != 0`` and the
    chair gives none (``camber_coefficient`` None): the thesis casters and
    ``linear:`` tires have none. Rolling resistance needs data when a rolling
    scale is non-zero: PU has none (chapter 3).

    Parameters
    ----------
    chair : Chair

    Raises
    ------
    ValueError
        Naming the chair field, the tire and the missing data, and how to fix it.
    TypeError
        If ``chair`` is not a chair (no tire models to read).
    """
    main = chair.main_tire_model().capabilities
    caster = chair.caster_tire_model().capabilities
    if chair.camber_deg != 0 and chair.camber_coefficient is None and not main.camber:
        raise ValueError(
            f"main_tire={chair.main_tire!r} has no camber coefficient, needed for camber_deg={chair.camber_deg!r}; "
            "set camber_coefficient (0 to 1) or camber_deg=0")
    for role, caps in (("main", main), ("caster", caster)):
        scale = getattr(chair, f"{role}_rolling_scale")
        if scale != 0 and not caps.rolling:
            spec = getattr(chair, f"{role}_tire")
            raise ValueError(
                f"{role}_tire={spec!r} has no rolling-resistance data, needed for {role}_rolling_scale={scale!r}; "
                f"set {role}_rolling_scale=0 or choose a tire with rolling data (e.g. ER)")


@first_argument(_chair_like)
def range_check(chair: Chair, loads: Mapping[str, float], *, policy: str | None = None) -> list[RangeNote]:
    """Which static loads of ``chair`` lie outside its tires' fitted load range.

    Parameters
    ----------
    chair : Chair
    loads : mapping
        Static normal loads (N) by wheel, as :func:`stability.models.statics.static_loads`
        returns (keys ``caster_left``, ``caster_right``, ``main_left``, ``main_right``).
    policy : {"warn", "raise", "clamp"}, optional
        Default the policy in force (:func:`stability.tires.get_policy`).

    Returns
    -------
    list of RangeNote
        One per wheel outside the range (empty when all are inside); also
        recorded in an active :func:`stability.tires.collect_notes` block
        (without a warning: this is a check, not a computation).

    Raises
    ------
    ValueError
        Under ``"raise"``, naming the first wheel, its load and the range.
    """
    pol = resolve(policy)
    tires = {"main": chair.main_tire_model(), "caster": chair.caster_tire_model()}
    notes = []
    for wheel, role in WHEELS:
        tire, load = tires[role], float(loads[wheel])
        if load > tire.fz_max_N:
            notes.append(RangeNote(tire=tire.name, quantity="load", value=load, low=0.0,
                                   high=float(tire.fz_max_N), policy=pol.name, wheel=wheel))
    # eq 4-2 evaluates the main tire's cornering fit at a slip angle equal to the camber angle
    main = tires["main"]
    camber = abs(float(chair.camber_deg))
    if camber > float(main.slip_max_deg):
        notes.append(RangeNote(tire=main.name, quantity="slip", value=camber, low=0.0,
                               high=float(main.slip_max_deg), policy=pol.name, wheel="main (camber force, eq 4-2)"))
    if notes and pol.name == "raise":
        raise ValueError(str(notes[0]) + "; use the 'warn' or 'clamp' tire-range policy to compute anyway")
    for note in notes:
        record(note, warn=False)
    return notes
