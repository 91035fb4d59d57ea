"""Chairs as TOML files and plain mappings; ``--chair``/``--set`` parsing helpers."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import fields
from typing import Any

from stability import tires
from stability.chair.model import Chair, field_names
from stability.chair.presets import all_preset_names, preset
from stability.chair.units import number_with_unit
from stability.runtime import readfiles
from stability.runtime.checks import value_text
from stability.runtime.files import atomic_write_text

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["to_mapping", "from_mapping", "dumps", "toml_value", "save", "load", "resolve", "parse_assignment",
           "parse_assignments", "GROUPS", "user_table"]


def to_mapping(c: Chair) -> dict[str, Any]:
    """Chair as a plain dict of field values (``None`` values omitted).

    Parameters
    ----------
    c : Chair
        The chair.

    Returns
    -------
    dict of str to Any
        Field name -> value, in the chair's SI units; the inverse of :func:`from_mapping`.
    """
    return {f.name: getattr(c, f.name) for f in fields(c) if getattr(c, f.name) is not None}


def from_mapping(data: Mapping[str, Any], base: Chair | None = None) -> Chair:
    """Build a chair from a mapping of field values over ``base``.

    Parameters
    ----------
    data : Mapping of str to Any
        Field name -> value (SI units, as the :class:`Chair` fields); fields not
        given keep ``base``'s values.
    base : Chair or None, optional
        Chair whose values fill the fields missing from ``data``; default the
        default ``Chair()``.

    Returns
    -------
    Chair
        The new chair (its fields validated by :meth:`Chair.replace`).

    Raises
    ------
    ValueError
        If ``data`` names an unknown field or a value is out of range.
    """
    valid = set(field_names())
    unknown = set(data) - valid
    if unknown:
        raise ValueError(f"unknown chair parameter(s) {sorted(unknown)}; valid names: {sorted(valid)}")
    base = base or Chair()
    return base.replace(**dict(data))


def toml_value(value: Any) -> str:
    """A field's value as TOML (strings quoted and escaped; floats by ``repr``, which round-trips exactly).

    Parameters
    ----------
    value : str, bool, int or float

    Returns
    -------
    str
    """
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return repr(value)
    return repr(float(value))  # repr round-trips exactly


def dumps(c: Chair) -> str:
    """Chair as TOML text (a flat table; floats written with ``repr``: exact round trip).

    Parameters
    ----------
    c : Chair

    Returns
    -------
    str
        One ``name = value  # unit: meaning`` line per field.
    """
    lines = ["# stability chair parameters (units: m, kg, kg m^2, N m, deg)"]
    for f in fields(c):
        value = getattr(c, f.name)
        if value is None:
            continue
        lines.append(f"{f.name} = {toml_value(value)}  # {f.metadata['unit']}: {f.metadata['doc']}")
    return "\n".join(lines) + "\n"


def save(c: Chair, path: str | os.PathLike[str]) -> None:
    """Write ``c`` to a TOML file atomically (temporary file + rename).

    Parameters
    ----------
    c : Chair
        The chair to write (as :func:`dumps` formats it).
    path : str or os.PathLike
        Destination file; replaced if it exists.
    """
    atomic_write_text(path, dumps(c))


def load(path: str | os.PathLike[str]) -> Chair:
    """Read a chair from a TOML file (missing fields take the default chair's values).

    Parameters
    ----------
    path : str or os.PathLike
        TOML file with the chair's fields either at the top level or in one
        ``[chair]`` table (not both). Tire data files named by ``main_tire`` or
        ``caster_tire`` are resolved relative to this file's directory.  A ``[user]``
        table (the driver, :func:`user_table`) is not part of the chair.

    Returns
    -------
    Chair
        The chair read from the file.

    Raises
    ------
    ValueError
        If the file mixes top-level keys with a ``[chair]`` table, names an
        unknown field or holds a value out of range.
    OSError
        If the file cannot be read.
    """
    data = _read(path)
    data.pop("user", None)                  # the driver's table: user_table()
    if "chair" in data and isinstance(data["chair"], dict):
        others = sorted(k for k in data if k != "chair")
        if others:
            raise ValueError(f"chair file {str(path)!r} has keys at the top level ({others}) and a [chair] table; "
                             "put every field in one place")
        data = data["chair"]
    base = os.path.dirname(os.path.abspath(path))
    data = {k: (tires.resolve_spec(v, base) if k in ("main_tire", "caster_tire") else v) for k, v in data.items()}
    return from_mapping(data)


def _read(path: str | os.PathLike[str]) -> dict:
    try:
        return dict(readfiles.load_toml(path))
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"chair file {str(path)!r} is not valid TOML: {exc}") from None


def user_table(spec: str | os.PathLike[str]) -> dict | None:
    """The ``[user]`` table of a chair file: the driver who uses the chair (:class:`stability.driver.Driver`).

    Parameters
    ----------
    spec : str or os.PathLike
        A chair file (a preset name has no user: None).

    Returns
    -------
    dict or None
        E.g. ``{"reaction_time_s": 0.35, "source": "tracking task 2026-12-03"}``; None without a ``[user]`` table.

    Raises
    ------
    ValueError
        If ``[user]`` is not a table.
    """
    if str(spec) in all_preset_names() or not os.path.isfile(spec):
        return None
    user = _read(spec).get("user")
    if user is None:
        return None
    if not isinstance(user, dict):
        raise ValueError(f"chair file {str(spec)!r}: [user] must be a table (reaction_time_s = ..., "
                         "hand_force_N = ...)")
    return dict(user)


def resolve(spec: str) -> Chair:
    """The chair a ``--chair`` value names: a preset or a TOML file.

    Parameters
    ----------
    spec : str or path-like
        A name from :func:`~stability.chair.preset_names` or a path to a chair file.

    Returns
    -------
    Chair

    Raises
    ------
    ValueError
        Naming ``spec`` when it is neither (one line).
    TypeError
        Naming ``spec`` when it is not a string or a path.
    """
    if not isinstance(spec, (str, os.PathLike)):
        raise TypeError(f"spec={value_text(spec)} is invalid; valid values: a preset name {list(all_preset_names())} "
                        "or the path of a chair file (.toml)")
    spec = os.fspath(spec)
    if spec in all_preset_names():
        return preset(spec)
    if spec.endswith(".toml") or os.path.exists(spec):
        if not os.path.exists(spec):
            raise ValueError(f"chair file {spec!r} does not exist")
        return load(spec)
    raise ValueError(f"unknown chair {spec!r}: not a preset {list(all_preset_names())} nor a TOML file")


#: ``--set`` names that set a left/right pair at once (a symmetric chair): group -> fields.
GROUPS: dict[str, tuple[str, ...]] = {"pin_friction": ("pin_friction_left", "pin_friction_right"),
                                      "d": ("d1", "d2"), "t": ("t1", "t2")}


def parse_assignments(texts: Sequence[str]) -> dict[str, Any]:
    """Parse ``--set`` options, in order, into field -> value; a group name sets both of its fields.

    Parameters
    ----------
    texts : sequence of str
        Each ``NAME=VALUE`` (:func:`parse_assignment`) or ``GROUP=VALUE`` with
        GROUP a key of :data:`GROUPS` (``pin_friction=0.2`` sets
        ``pin_friction_left`` and ``pin_friction_right``; ``d=0.27`` sets
        ``d1`` and ``d2``; ``t=0.2`` sets ``t1`` and ``t2``).  Later ones win.

    Returns
    -------
    dict
        Field name -> typed value.

    Examples
    --------
    >>> parse_assignments(["pin_friction=0.2", "trail=5cm"])
    {'pin_friction_left': 0.2, 'pin_friction_right': 0.2, 'trail': 0.05}
    """
    out: dict[str, Any] = {}
    for text in texts:
        name = text.split("=", 1)[0].strip()
        if name in GROUPS:
            _, value = parse_assignment(text.replace(name, GROUPS[name][0], 1))
            out.update(dict.fromkeys(GROUPS[name], value))
        else:
            key, value = parse_assignment(text)
            out[key] = value
    return out


def parse_assignment(text: str) -> tuple[str, Any]:
    """Parse ``NAME=VALUE`` (a ``--set`` option) into a field name and typed value.

    Parameters
    ----------
    text : str
        ``NAME=VALUE``; NAME a :class:`Chair` field. VALUE is kept as text for
        ``name``, ``caster_position``, ``main_tire`` and ``caster_tire``;
        ``camber_coefficient`` also accepts ``none``, ``tire`` or empty (-> ``None``);
        every other field needs a number, in the field's SI unit or with a unit
        the measurement sheet knows (``trail=5cm``, ``m=95kg``, ``m=210 lb``,
        ``pin_friction_left=0.1 ft lbf``; :func:`stability.chair.units.quantity`),
        converted to the field's unit.

    Returns
    -------
    tuple of (str, Any)
        The field name and its value (``str``, ``float`` or ``None``).

    Raises
    ------
    ValueError
        If ``text`` has no ``=``, names an unknown field or a numeric field gets a non-number.
    """
    if "=" not in text:
        raise ValueError(f"--set expects NAME=VALUE, got {text!r}")
    name, raw = (s.strip() for s in text.split("=", 1))
    kinds = {f.name: f for f in fields(Chair)}
    if name not in kinds:
        raise ValueError(f"unknown chair parameter {name!r}; valid names: {field_names()} and the pairs "
                         + ", ".join(f"{g} ({' and '.join(f)})" for g, f in GROUPS.items()))
    if name in ("name", "caster_position", "main_tire", "caster_tire"):
        return name, raw
    if name == "camber_coefficient" and raw.lower() in ("none", "tire", ""):
        return name, None
    try:
        value = float(raw)
    except ValueError:
        value = number_with_unit(name, raw, kinds[name].metadata["unit"])
    return name, value
