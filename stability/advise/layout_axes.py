"""The uncertain (and swept) numbers of a wheel layout: its axes, one set for every command.

An axis is one number of a layout by name, the names an uncertainty file's tables (``report``, ``advise``,
``compare``, ``sweep``'s ``[draws]``) and a sweep's grid use:

``caster_K_FIELD``, ``wheel_J_FIELD``
    One field of caster K or fixed wheel J (1-based, in the file's order): ``caster_1_trail``, ``wheel_2_x``,
    ``caster_3_vertical_stiffness`` ...;
``trail_ROW``
    The trail of every caster of one row (``trail_front``, ``trail_rear``; the advisor's row names,
    :func:`stability.advise.layout_levers.row_name`);
``drive_x``
    The x of every driven wheel (every fixed wheel if none is driven), m ahead of the c.g.;
``m``, ``i_z``, ``h``
    The body's mass (kg), yaw inertia (kg m^2) and c.g. height (m).

A draw ``relative = true`` is a fraction of the layout's own value (:func:`layout_axis_value`); a drawn value is
set with the advisor's validation (:func:`apply_layout_axis`: ranges, a base that still stands).
:class:`LayoutDraw` lets :mod:`stability.uncertainty`'s sampling and propagation see a layout through these axes.
"""

from __future__ import annotations

import dataclasses
import re
from typing import Any

import numpy as np

from stability.advise.layout_levers import apply_layout, caster_rows, row_name
from stability.layout.model import Layout
from stability.layout.statics import static_loads
from stability.uncertainty import Uncertainty

__all__ = ["check_layout_axis", "layout_axes", "apply_layout_axis", "layout_axis_value", "check_layout_uncertainty",
           "load_layout_uncertainty", "LayoutDraw", "draw_layout", "BODY_AXES"]

#: The body's axes.
BODY_AXES = ("m", "i_z", "h")
_BODY = BODY_AXES
_WHEEL = re.compile(r"(caster|wheel)_(\d+)_(\w+)")


def check_layout_axis(layout: Layout, axis: str) -> None:
    """Refuse a grid axis the layout does not have (one line naming it and the valid forms).

    Parameters
    ----------
    layout : Layout
    axis : str

    Raises
    ------
    ValueError
    """
    rows = [f"trail_{row_name(layout, r)}" for r in caster_rows(layout)]
    valid = (f"caster_K_FIELD (K 1-{len(layout.casters)}), wheel_J_FIELD (J 1-{len(layout.wheels)}), "
             f"{', '.join(rows + ['drive_x', *_BODY])}")
    if axis in rows or axis == "drive_x" or axis in _BODY:
        return
    hit = _WHEEL.fullmatch(axis)
    if hit:
        try:
            k = int(hit.group(2)) - 1
            seq = layout.casters if hit.group(1) == "caster" else layout.wheels
            if 0 <= k < len(seq) and hasattr(seq[k], hit.group(3)) and hit.group(3) not in ("tire", "driven"):
                return
        except ValueError:
            pass
    raise ValueError(f"spec grid={axis!r} is invalid for the layout {layout.name!r}; valid: {valid}")


def layout_axes(layout: Layout) -> frozenset:
    """Every axis :func:`check_layout_axis` accepts for ``layout`` (the names an uncertainty file's tables may use).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    frozenset of str
    """
    out = {f"trail_{row_name(layout, r)}" for r in caster_rows(layout)} | {"drive_x", *_BODY}
    for group, seq in (("caster", layout.casters), ("wheel", layout.wheels)):
        for k, w in enumerate(seq, start=1):
            out |= {f"{group}_{k}_{f.name}" for f in dataclasses.fields(w) if f.name not in ("tire", "driven")}
    return frozenset(out)


def apply_layout_axis(layout: Layout, axis: str, value: float) -> Layout:
    """The layout with one grid axis set (validated: ranges, positive static loads).

    Parameters
    ----------
    layout : Layout
    axis : str
        See the module's axes.
    value : float

    Returns
    -------
    Layout
    """

    if axis in _BODY:
        changes: dict[str, Any] = {axis: value}
        out = dataclasses.replace(layout, **changes)
        static_loads(out)
        return out
    if axis == "drive_x":
        idx = [j for j, w in enumerate(layout.wheels) if w.driven] or list(range(len(layout.wheels)))
        return apply_layout(layout, [(f"wheel_{j + 1}_x", value) for j in idx])
    for r in caster_rows(layout):
        if axis == f"trail_{row_name(layout, r)}":
            return apply_layout(layout, [(f"caster_{k + 1}_trail", value) for k in r])
    return apply_layout(layout, [(axis, value)])


def layout_axis_value(layout: Layout, axis: str) -> float:
    """The layout's own value of one axis (the centre of a draw around it).

    Parameters
    ----------
    layout : Layout
    axis : str
        See the module's axes (checked with :func:`check_layout_axis`).

    Returns
    -------
    float
        ``drive_x``: the first driven wheel's x (the first fixed wheel's if none is driven); ``trail_ROW``: the
        row's first caster's trail; otherwise the field itself (SI units).
    """
    check_layout_axis(layout, axis)
    if axis in _BODY:
        return float(getattr(layout, axis))
    if axis == "drive_x":
        idx = [j for j, w in enumerate(layout.wheels) if w.driven] or [0]
        return float(layout.wheels[idx[0]].x)
    for r in caster_rows(layout):
        if axis == f"trail_{row_name(layout, r)}":
            return float(layout.casters[r[0]].trail)
    hit = _WHEEL.fullmatch(axis)
    assert hit is not None                       # checked above
    seq = layout.casters if hit.group(1) == "caster" else layout.wheels
    value = getattr(seq[int(hit.group(2)) - 1], hit.group(3))
    if value is None:                            # camber_coefficient None: the tire's own, no number to draw around
        raise ValueError(f"axis {axis!r} is invalid for the layout {layout.name!r}; valid: a field with a value of "
                         "its own (this one is the tire's: set it first, --set or the file)")
    return float(value)


def check_layout_uncertainty(layout: Layout, unc: Uncertainty) -> None:
    """Refuse an uncertainty table whose field is not one of the layout's axes (one line naming it).

    Parameters
    ----------
    layout : Layout
    unc : Uncertainty
        Read with ``valid_fields=layout_axes(layout)``.

    Raises
    ------
    ValueError
    """
    for d in unc.distributions:
        for f in d.fields:
            try:
                layout_axis_value(layout, f)
            except ValueError as exc:
                raise ValueError(f"uncertainty [{d.name}] field {f!r} is invalid for the layout {layout.name!r}; "
                                 + str(exc).split("; ", 1)[-1]) from None


def load_layout_uncertainty(path: Any, layout: Layout) -> Uncertainty:
    """Read an uncertainty file whose tables name ``layout``'s axes (:func:`layout_axes`), checked against it.

    Parameters
    ----------
    path : str or os.PathLike
    layout : Layout

    Returns
    -------
    Uncertainty

    Raises
    ------
    ValueError
        A table naming a field the layout does not have, or one with no value of its own; one line naming it.
    """
    from stability.uncertainty import load_uncertainty

    unc = load_uncertainty(path, valid_fields=layout_axes(layout))
    check_layout_uncertainty(layout, unc)
    return unc


@dataclasses.dataclass(frozen=True)
class LayoutDraw:
    """A layout seen as :mod:`stability.uncertainty` sees a chair: its axes as attributes, and ``replace``.

    The uncertainty module's sampling and propagation (:meth:`Uncertainty.sample`,
    :func:`stability.uncertainty.propagate`) read a field's own value with ``getattr`` and build a draw with
    ``replace``; here both go through the sweep's axes (:func:`layout_axis_value`, :func:`apply_layout_axis`), so
    an uncertainty file means the same for ``sweep``'s draws, ``report``, ``advise`` and ``compare``.

    Attributes
    ----------
    layout : Layout
    """

    layout: Layout

    def __getattr__(self, name: str) -> float:
        if name.startswith("__") or name == "layout":
            raise AttributeError(name)
        try:
            return layout_axis_value(self.layout, name)
        except ValueError:
            raise AttributeError(name) from None

    @property
    def name(self) -> str:
        """The layout's name."""
        return self.layout.name

    def replace(self, **fields: float) -> LayoutDraw:
        """The layout with the given axes set in order (validated; ValueError if invalid)."""
        lay = self.layout
        for axis, value in fields.items():
            lay = apply_layout_axis(lay, axis, float(value))
        return LayoutDraw(lay)


def draw_layout(layout: Layout, unc: Uncertainty, unit: dict[str, np.ndarray], draw: int) -> Layout:
    """The layout with draw ``draw`` of every uncertain axis set (each around the layout's own value).

    Parameters
    ----------
    layout : Layout
        The design (its grid values set).
    unc : Uncertainty
        The layout's uncertainty (:func:`check_layout_uncertainty`).
    unit : dict
        Standardised draws per table (:meth:`Uncertainty.unit_draws`: common random numbers across designs).
    draw : int
        Which draw.

    Returns
    -------
    Layout

    Raises
    ------
    ValueError
        A drawn value outside its field's range, or a base that no longer stands.
    """
    values = [(f, float(d.values(layout_axis_value(layout, f), unit[d.name][draw:draw + 1])[0]))
              for d in unc.distributions for f in d.fields]
    for f, v in values:
        layout = apply_layout_axis(layout, f, v)
    return layout
