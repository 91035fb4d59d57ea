"""The design levers of a wheel layout: caster trail per caster row, drive-wheel position, suspension.

A layout (:class:`stability.layout.Layout`) has no ``--set`` fields; a change names the wheels it moves
(``caster_1_trail``, ``wheel_2_x``, 1-based as the shimmy command names the casters) and their new values, which is
what to write into the layout's ``[[wheel]]`` file.  The levers:

``trail_<row>``
    The trail of one caster row (the casters whose pins share one x, a left-right pair: the front or the rear
    pair of a mid-wheel-drive base), both casters together, by -3, -2, -1 and +1 cm as the short form's trail lever.
``drive_position``
    The drive axle (the driven fixed wheels; every fixed wheel if none is driven) moved 10 and 5 cm forward and
    backward relative to the body, the c.g. and the casters staying: the c.g. ratio and the wheelbase change, as
    the short form's ``s1_fixed_s2``.
``suspension_<row>``
    On a base of more than two support lines (whose loads follow the wheels' vertical stiffnesses), the vertical
    stiffness of one caster row x0.5 and x2: it moves the static load between that row, the drive wheels and the
    other rows, which is what a suspension preload is set for.  The layout model has springs, not preloads: a
    preload shifts the load share and keeps the springs' rates, a stiffness change shifts the share and changes the
    rates as well (the load transfer of the nonlinear runs); the lever is the stiffness, named so.

A change the layout refuses (a value out of its range, a static load that is not positive) is left out with its
reason, as for the short form (:mod:`stability.advise.levers`).
"""

from __future__ import annotations

import dataclasses
import functools
import re
from collections.abc import Callable

from stability.advise.levers import Change
from stability.layout.model import Layout
from stability.layout.statics import contacts, static_loads
from stability.models.layout import supported_shapes

__all__ = ["caster_rows", "row_name", "layout_levers", "layout_lever_changes", "apply_layout", "TRAIL_STEPS_M",
           "DRIVE_STEPS_M", "STIFFNESS_FACTORS"]

#: Trail changes of a caster row, m (the short form's trail lever).
TRAIL_STEPS_M = (-0.03, -0.02, -0.01, 0.01)
#: Drive-axle moves, m (positive: forward).
DRIVE_STEPS_M = (-0.10, -0.05, 0.05, 0.10)
#: Vertical-stiffness factors of a caster row's suspension.
STIFFNESS_FACTORS = (0.5, 2.0)


def _r(x: float) -> float:
    return round(float(x), 6)


def caster_rows(layout: Layout) -> list[list[int]]:
    """The caster rows: indices of the casters whose pins share one x (a left-right pair), front first.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    list of list of int
        0-based caster indices per row.
    """
    rows: dict[float, list[int]] = {}
    for k, c in enumerate(layout.casters):
        rows.setdefault(round(c.x, 9), []).append(k)
    return [rows[x] for x in sorted(rows, reverse=True)]


def row_name(layout: Layout, row: list[int]) -> str:
    """``"front"``, ``"rear"``, or ``"x=+0.32"`` when two rows are on one side of the c.g.

    Parameters
    ----------
    layout : Layout
    row : list of int

    Returns
    -------
    str
    """
    x = layout.casters[row[0]].x
    same_side = [r for r in caster_rows(layout) if (layout.casters[r[0]].x > 0) == (x > 0)]
    if len(same_side) > 1:
        return f"x={x:+.2f}"
    return "front" if x > 0 else "rear"


def _lines(layout: Layout) -> int:
    return len({round(x, 9) for _, x, _, k in contacts(layout) if k != 0.0})


def _trail(layout: Layout, row: list[int]) -> list[Change]:
    name = row_name(layout, row)
    t0 = layout.casters[row[0]].trail
    out = []
    for d in TRAIL_STEPS_M:
        t = _r(t0 + d)
        if t > 0:
            out.append(Change(f"trail_{name}", f"{name} caster trail {t0 * 100:g} -> {t * 100:g} cm",
                              tuple((f"caster_{k + 1}_trail", t) for k in row)))
    return out


def _drive(layout: Layout) -> list[Change]:
    idx = [j for j, w in enumerate(layout.wheels) if w.driven] or list(range(len(layout.wheels)))
    what = "drive axle" if any(w.driven for w in layout.wheels) else "axle"
    x0 = layout.wheels[idx[0]].x
    return [Change("drive_position", f"{what} {abs(d) * 100:g} cm {'forward' if d > 0 else 'back'} (x "
                   f"{x0 * 100:+.1f} -> {(x0 + d) * 100:+.1f} cm from the c.g.)",
                   tuple((f"wheel_{j + 1}_x", _r(layout.wheels[j].x + d)) for j in idx)) for d in DRIVE_STEPS_M]


def _suspension(layout: Layout, row: list[int]) -> list[Change]:
    if _lines(layout) <= 2:                      # statically determinate: the stiffnesses share no static load
        return []
    name = row_name(layout, row)
    nw = len(layout.wheels)
    loads = static_loads(layout)
    share0 = sum(loads[nw + k] for k in row) / layout.m / layout.g
    out = []
    for f in STIFFNESS_FACTORS:
        fields = tuple((f"caster_{k + 1}_vertical_stiffness", _r(layout.casters[k].vertical_stiffness * f))
                       for k in row)
        try:
            changed = apply_layout(layout, fields)
            share = sum(static_loads(changed)[nw + k] for k in row) / layout.m / layout.g
            words = f" (its share of the weight {share0 * 100:.0f} -> {share * 100:.0f} %)"
        except ValueError:
            words = ""
        out.append(Change(f"suspension_{name}", f"{name} caster suspension stiffness x{f:g}{words}", fields))
    return out


def layout_levers(layout: Layout) -> dict[str, tuple[str, Callable[[Layout], list[Change]]]]:
    """The levers of this layout: lever name -> (description, change generator), in the order the advice lists.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    dict
    """
    out: dict[str, tuple[str, Callable[[Layout], list[Change]]]] = {}
    rows = caster_rows(layout)
    for row in rows:
        name = row_name(layout, row)
        out[f"trail_{name}"] = (f"trail of the {name} caster row", functools.partial(_trail, row=row))
    out["drive_position"] = ("drive-axle position (the c.g. and the casters staying)", _drive)
    for row in rows:
        name = row_name(layout, row)
        if _lines(layout) > 2:
            out[f"suspension_{name}"] = (f"suspension stiffness of the {name} caster row (its share of the load)",
                                         functools.partial(_suspension, row=row))
    return out


def apply_layout(layout: Layout, fields) -> Layout:
    """``layout`` with the changed wheel fields (validated: ranges, positive static loads, a generated shape).

    Parameters
    ----------
    layout : Layout
    fields : iterable of (str, float)
        ``("caster_K_NAME", value)`` or ``("wheel_J_NAME", value)``, K and J from 1 (``caster_1_trail``).

    Returns
    -------
    Layout

    Raises
    ------
    ValueError
        A value out of range, an unknown wheel or field, or a layout that no longer stands on every wheel.
    """
    wheels, casters = list(layout.wheels), list(layout.casters)
    for key, value in fields:
        hit = re.fullmatch(r"(caster|wheel)_(\d+)_(\w+)", str(key))
        seq = {"caster": casters, "wheel": wheels}.get(hit.group(1)) if hit else None
        if hit is None or seq is None or not 1 <= int(hit.group(2)) <= len(seq):
            raise ValueError(f"{key}={value!r} is invalid; valid: caster_K_FIELD (K 1-{len(casters)}) or "
                             f"wheel_J_FIELD (J 1-{len(wheels)})")
        group, i, name = hit.group(1), int(hit.group(2)) - 1, hit.group(3)
        if name not in {f.name for f in dataclasses.fields(seq[i])}:
            raise ValueError(f"{key}={value!r} is invalid; {name!r} is not a field of a {group}")
        seq[i] = dataclasses.replace(seq[i], **{name: value})
    out = dataclasses.replace(layout, wheels=tuple(wheels), casters=tuple(casters))
    if out.shape not in supported_shapes():
        raise ValueError(f"layout {out.name!r} has shape {out.shape}; valid shapes: {supported_shapes()}")
    static_loads(out)
    return out


def layout_lever_changes(layout: Layout) -> tuple[list[tuple[Change, Layout]], list[tuple[Change, str]]]:
    """Every single change of every lever of ``layout``: the feasible ones with their layouts, the others with why
    not.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    tuple
        ``([(change, changed layout), ...], [(change, reason), ...])``.
    """
    ok, refused = [], []
    for _, gen in layout_levers(layout).values():
        for ch in gen(layout):
            try:
                ok.append((ch, apply_layout(layout, ch.fields)))
            except ValueError as exc:
                refused.append((ch, str(exc)))
    return ok, refused
