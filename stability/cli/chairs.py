"""Chairs at the command lines: ``--chair`` (a preset, a layout preset or a chair file) and ``--set`` read one way.

Every command reads its chair with :func:`load_chair` (the short form) or :func:`load_layout` (any wheel layout),
and applies ``--set NAME=VALUE`` with :func:`apply_assignments` / :func:`apply_layout_assignments`; a mistyped
preset is answered with the closest name and every valid one.
"""

from __future__ import annotations

import difflib
import os
from collections.abc import Sequence
from typing import Any

from stability import chair as chair_mod
from stability import tires
from stability.models.statics import check_static_loads, static_loads

__all__ = ["LAYOUT_COMMANDS", "LAYOUT_BODY_FIELDS", "load_chair", "load_layout", "apply_assignments",
           "apply_layout_assignments"]

#: The commands that answer any wheel layout (docs/layouts.md).
LAYOUT_COMMANDS = ("critical_speed", "tipping", "bench", "simulate", "shimmy", "study critical-impulse", "slope",
                   "assist", "study equal-instability", "advise", "compare")


def _check_known(spec: str) -> None:
    """Refuse a ``--chair`` that is neither a preset nor a file, with the closest preset name and every valid one
    (the chair presets and the wheel-layout presets, which the layout commands answer)."""
    from stability.layout.presets import layout_preset_names

    names, layouts = list(chair_mod.preset_names()), list(layout_preset_names())
    if spec in names or spec in layouts or spec.endswith(".toml") or os.path.exists(spec):
        return
    close = difflib.get_close_matches(spec, names + layouts, n=1)
    hint = f"did you mean {close[0]!r}? " if close else ""
    raise ValueError(f"unknown chair {spec!r}: not a preset nor a file; {hint}valid: a chair preset {names}, a "
                     f"wheel-layout preset {layouts} (python -m stability.{{{','.join(LAYOUT_COMMANDS)}}}) or a "
                     "chair file (.toml)")


def load_chair(spec: str, assignments: Sequence[str]) -> chair_mod.Chair:
    """Chair from ``--chair`` and ``--set`` options, with its static loads checked.

    Parameters
    ----------
    spec : str
        ``--chair`` value: a preset name (:func:`stability.chair.preset_names`) or a TOML file.
    assignments : sequence of str
        ``--set`` values, each ``NAME=VALUE`` (:func:`stability.chair.parse_assignments`: units allowed,
        ``pin_friction``, ``d`` and ``t`` set a left/right pair),
        applied in order over the chair read from ``spec``.

    Returns
    -------
    Chair
        The chair, its static wheel loads checked and its tire data checked
        against the fitted load range.

    Raises
    ------
    ValueError
        One line naming the file, field or value at fault.
    """
    if os.path.isdir(spec):
        raise ValueError(f"--chair {spec!r} is a directory; expected a preset name or a TOML file")
    from stability.layout.io import is_layout_spec

    if is_layout_spec(spec):
        raise ValueError(f"--chair {spec!r} is a wheel layout (the [[wheel]] form); this command answers the short "
                         "form (two main wheels and a caster pair) only; for a layout use python -m "
                         f"stability.{{{','.join(LAYOUT_COMMANDS)}}}")
    _check_known(spec)
    try:
        c = chair_mod.resolve(spec)
    except OSError as exc:
        raise ValueError(f"--chair {spec!r}: cannot read the file ({exc.strerror or exc})") from None
    return apply_assignments(c, assignments)


def load_layout(spec: str, assignments: Sequence[str]) -> Any:
    """``--chair`` and ``--set`` as a wheel layout, for the commands that answer any layout.

    Parameters
    ----------
    spec : str
        ``--chair`` value: a layout preset or ``[[wheel]]`` file, taken as it is, or a short-form chair
        (:func:`load_chair`) expanded into its layout (:meth:`stability.layout.Layout.from_chair`).
    assignments : sequence of str
        ``--set`` values: the short form's (:func:`load_chair`) for a short-form chair, the layout's fields by the
        advisor's names for a layout (:func:`apply_layout_assignments`).

    Returns
    -------
    Layout

    Raises
    ------
    ValueError
        As :func:`load_chair` or :func:`apply_layout_assignments`.
    """
    from stability.layout import Layout
    from stability.layout.io import is_layout_spec, resolve_layout

    if not is_layout_spec(spec):
        return Layout.from_chair(load_chair(spec, assignments))
    return apply_layout_assignments(resolve_layout(spec), assignments)


#: The body's fields ``--set`` may change on a layout (the names of a layout uncertainty file's tables).
LAYOUT_BODY_FIELDS = ("m", "i_z", "h")


def apply_layout_assignments(layout: Any, assignments: Sequence[str]) -> Any:
    """``layout`` with ``--set`` assignments applied, in order, by the advisor's names.

    Parameters
    ----------
    layout : Layout
    assignments : sequence of str
        Each ``NAME=VALUE``: NAME one of :data:`LAYOUT_BODY_FIELDS` or ``caster_K_FIELD`` / ``wheel_J_FIELD`` (K and
        J from 1, in the order of the ``[[wheel]]`` file; FIELD a field of :class:`stability.layout.Caster` or
        :class:`stability.layout.FixedWheel`, e.g. ``caster_1_trail=0.06``); VALUE a number in the field's SI unit
        (:data:`stability.layout.model.FIELD_UNITS`) or with a unit of its kind (``caster_1_trail=6cm``,
        ``m=210 lb``), or the text of a text field (``caster_2_tire=ER``).

    Returns
    -------
    Layout
        Validated as the advisor's changes are (each field's range, a generated shape, every wheel loaded).

    Raises
    ------
    ValueError
        One line naming the assignment at fault and what is valid.
    """
    import dataclasses

    from stability.advise.layout_levers import apply_layout
    from stability.chair.units import number_with_unit
    from stability.layout.model import FIELD_UNITS

    if not assignments:
        return layout
    valid = (f"valid names: {', '.join(LAYOUT_BODY_FIELDS)}, caster_K_FIELD (K 1-{len(layout.casters)}), "
             f"wheel_J_FIELD (J 1-{len(layout.wheels)})")
    body: dict[str, float] = {}
    wheels: list[tuple[str, Any]] = []
    for text in assignments:
        name, eq, raw = (part.strip() for part in str(text).partition("="))
        if not eq:
            raise ValueError(f"--set expects NAME=VALUE, got {text!r}")
        group, _, rest = name.partition("_")
        k, _, field = rest.partition("_")
        seq = {"caster": layout.casters, "wheel": layout.wheels}.get(group)
        current: Any = None
        if name in LAYOUT_BODY_FIELDS:
            current = getattr(layout, name)
        elif seq is not None and k.isdigit() and 1 <= int(k) <= len(seq) and field in {
                f.name for f in dataclasses.fields(seq[int(k) - 1])}:
            current = getattr(seq[int(k) - 1], field)
        else:
            raise ValueError(f"--set {text!r}: {name!r} is not a field of layout {layout.name!r}; {valid}")
        value: Any = raw
        if isinstance(current, bool):
            if raw.lower() not in ("true", "false"):
                raise ValueError(f"--set {text!r}: {raw!r} is invalid; valid: true, false")
            value = raw.lower() == "true"
        elif not isinstance(current, str):
            owner = "Layout" if name in LAYOUT_BODY_FIELDS else type(seq[int(k) - 1]).__name__  # type: ignore[index]
            unit = FIELD_UNITS[owner][name if owner == "Layout" else field]
            try:
                value = float(raw)
            except ValueError:
                try:
                    value = number_with_unit(name, raw, unit, what="layout field")
                except ValueError as exc:
                    raise ValueError(f"--set {text!r}: {exc}") from None
        if name in LAYOUT_BODY_FIELDS:
            body[name] = value
        else:
            wheels.append((name, value))
    try:
        return apply_layout(dataclasses.replace(layout, **body) if body else layout, wheels)
    except TypeError as exc:
        raise ValueError(f"--set: {exc}") from None


def apply_assignments(c: chair_mod.Chair, assignments: Sequence[str]) -> chair_mod.Chair:
    """``c`` with ``--set`` assignments applied, its static loads and tire data checked (as :func:`load_chair`).

    The explorer (:mod:`stability.app`) checks its edits with it, so a bad value gives the same one line there.

    Parameters
    ----------
    c : Chair
        The chair the assignments start from.
    assignments : sequence of str
        ``NAME=VALUE`` texts (:func:`stability.chair.parse_assignment`), applied in order.

    Returns
    -------
    Chair
        Raises ValueError naming the field or value at fault.
    """
    changes = chair_mod.parse_assignments(assignments)
    c = c.replace(**changes) if changes else c
    check_static_loads(c)
    tires.range_check(c, static_loads(c))
    return c
