"""Layouts in chair files: the ``[[wheel]]`` form, and the one place a ``--chair`` value becomes a layout.

A chair file in the long form::

    [body]
    name = "my base"
    m = 215.0          # kg, with the user
    i_z = 13.0         # kg m^2 about the c.g., casters trailing forward
    h = 0.49           # m, c.g. height

    [[wheel]]
    kind = "fixed"     # a drive or main wheel
    x = -0.03          # m ahead of the c.g.
    y = -0.275         # m right of the c.g.
    tire = "linear:110"
    driven = true

    [[wheel]]
    kind = "caster"
    x = 0.32           # the pin
    y = -0.22
    trail = 0.05
    ...

    [[anti_tip]]       # optional: where an anti-tip device touches the ground once the chair has tipped
    x = -0.45
    y = 0.0

Every field of :class:`~stability.layout.model.FixedWheel` and :class:`~stability.layout.model.Caster` may be
given (:func:`dumps` writes them all: ``python -m stability.chair export mid-wheel-drive`` gives a file to start
from); the short form (:class:`stability.chair.Chair`'s fields) expands with :meth:`Layout.from_chair`.
"""

from __future__ import annotations

import dataclasses
import os

from stability.layout.model import Caster, FixedWheel, Layout
from stability.layout.presets import layout_preset, layout_preset_names
from stability.runtime import readfiles

__all__ = ["load_layout", "resolve_layout", "is_layout_spec", "dumps"]


def _fields(cls) -> set[str]:
    return {f.name for f in dataclasses.fields(cls)}


def load_layout(path: str | os.PathLike[str]) -> Layout:
    """Read a layout from a chair file with ``[body]`` and ``[[wheel]]`` tables.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    Layout

    Raises
    ------
    ValueError
        A missing table, an unknown key or kind, or a value out of range (one line naming it).
    """
    data = readfiles.load_toml(path)
    unknown = sorted(set(data) - {"body", "wheel", "anti_tip", "user"})
    if unknown:
        raise ValueError(f"chair file {str(path)!r}: unknown table(s) {unknown} in the [[wheel]] form; valid: "
                         "[body], [[wheel]], [[anti_tip]], [user]")
    body = data.get("body")
    wheels = data.get("wheel")
    if not isinstance(body, dict) or not isinstance(wheels, list) or not wheels:
        raise ValueError(f"chair file {str(path)!r}: the [[wheel]] form needs a [body] table and [[wheel]] tables")
    bad = sorted(set(body) - {"name", "m", "i_z", "h", "g"})
    if bad:
        raise ValueError(f"chair file {str(path)!r}: [body] has unknown key(s) {bad}; valid: name, m, i_z, h, g")
    fixed: list[FixedWheel] = []
    casters: list[Caster] = []
    for i, w in enumerate(wheels):
        w = dict(w)
        kind = w.pop("kind", None)
        cls: type | None = {"fixed": FixedWheel, "caster": Caster}.get(str(kind))
        if cls is None:
            raise ValueError(f"chair file {str(path)!r}: wheel {i + 1} has kind={kind!r}; valid: 'fixed' or 'caster'")
        extra = sorted(set(w) - _fields(cls))
        if extra:
            raise ValueError(f"chair file {str(path)!r}: wheel {i + 1} ({kind}) has unknown key(s) {extra}; valid: "
                             f"{sorted(_fields(cls))}")
        try:
            if kind == "fixed":
                fixed.append(FixedWheel(**w))
            else:
                casters.append(Caster(**w))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"chair file {str(path)!r}: wheel {i + 1} ({kind}): {exc}") from None
    anti_tip = data.get("anti_tip", [])
    if not isinstance(anti_tip, list) or any(not isinstance(a, dict) or set(a) != {"x", "y"} for a in anti_tip):
        raise ValueError(f"chair file {str(path)!r}: each [[anti_tip]] table needs exactly x and y (m)")
    name = body.get("name", os.path.splitext(os.path.basename(str(path)))[0])
    return Layout(str(name), body.get("m", 0.0), body.get("i_z", 0.0), body.get("h", 0.0), tuple(fixed),
                  tuple(casters), body.get("g", 9.81), tuple((a["x"], a["y"]) for a in anti_tip))


def dumps(layout: Layout) -> str:
    """A layout as a chair file in the ``[[wheel]]`` form, every field written (:func:`load_layout` reads it back
    exactly: floats by ``repr``).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    str
        TOML text: ``[body]``, one ``[[wheel]]`` table per fixed wheel then per caster (the order the layout keeps
        them in, which the advisor's caster numbers follow), and ``[[anti_tip]]`` tables if any.
    """
    from stability.chair.io import toml_value

    def table(header: str, pairs: list[tuple[str, object]]) -> list[str]:
        return ["", header] + [f"{k} = {toml_value(v)}" for k, v in pairs if v is not None]

    lines = ["# stability wheel layout (the [[wheel]] form; units: m, kg, kg m^2, N/m, N m s/rad, N m, deg;",
             "# every field: docs/layouts.md).  x forward of the c.g., y to its right; a caster's x, y is its pin."]
    lines += table("[body]", [("name", layout.name), ("m", layout.m), ("i_z", layout.i_z), ("h", layout.h),
                              ("g", layout.g)])
    for kind, items in (("fixed", layout.wheels), ("caster", layout.casters)):
        for w in items:
            lines += table("[[wheel]]", [("kind", kind)] + [(f.name, getattr(w, f.name))
                                                              for f in dataclasses.fields(w)])
    for x, y in layout.anti_tip:
        lines += table("[[anti_tip]]", [("x", x), ("y", y)])
    return "\n".join(lines) + "\n"


def is_layout_spec(spec: str) -> bool:
    """Whether a ``--chair`` value names a layout preset or a file in the ``[[wheel]]`` form.

    Parameters
    ----------
    spec : str

    Returns
    -------
    bool
    """
    if spec in layout_preset_names():
        return True
    if os.path.isfile(spec) and spec.endswith(".toml"):
        try:
            return "wheel" in readfiles.load_toml(spec)
        except Exception:                                   # noqa: BLE001 - not a TOML file: the chair reader says
            return False
    return False


def resolve_layout(spec: str) -> Layout:
    """The layout a ``--chair`` value names: a layout preset, a ``[[wheel]]`` file, or a chair in the short form.

    Parameters
    ----------
    spec : str

    Returns
    -------
    Layout
    """
    if spec in layout_preset_names():
        return layout_preset(spec)
    if is_layout_spec(spec):
        return load_layout(spec)
    from stability.chair import resolve

    return Layout.from_chair(resolve(spec))
