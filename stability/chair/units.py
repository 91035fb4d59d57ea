"""Measurement units with exact conversion factors to SI.

``quantity(0.66, "ft lbf/rad")`` returns 0.8948... (N m/rad).  A unit string
is a product of tokens separated by spaces or ``*`` with optional ``^n``
exponents, optionally divided by a second such product after one ``/``.
``lb`` is the pound *mass* (0.45359237 kg exactly); ``lbf`` the pound
*force* (0.45359237 kg x 9.80665 m/s^2 = 4.4482216152605 N exactly).
"""

from __future__ import annotations

import math
import re

__all__ = ["STANDARD_GRAVITY", "quantity", "parse_unit", "dimension_name", "DIMENSIONS", "number_with_unit"]

#: standard acceleration of gravity (m/s^2, exact by definition; CGPM 1901)
STANDARD_GRAVITY = 9.80665
_LB = 0.45359237  # kg, exact (international pound, 1959)
_FT = 0.3048  # m, exact (international foot, 1959)
_IN = 0.0254  # m, exact
_LBF = _LB * STANDARD_GRAVITY  # 4.4482216152605 N, exact

# dimension exponents: (mass, length, time, angle)
_M, _L, _T, _A = (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 0, 1)
_F = (1, 1, -2, 0)
_NONE = (0, 0, 0, 0)

#: unit token -> (factor to SI, dimension exponents (mass, length, time, angle))
_TOKENS: dict[str, tuple[float, tuple[int, int, int, int]]] = {
    "m": (1.0, _L), "cm": (0.01, _L), "mm": (0.001, _L), "km": (1000.0, _L), "in": (_IN, _L), "ft": (_FT, _L),
    "mi": (1609.344, _L),
    "kg": (1.0, _M), "g": (0.001, _M), "lb": (_LB, _M), "lbm": (_LB, _M), "slug": (_LBF / _FT, _M),
    "s": (1.0, _T), "ms": (0.001, _T), "min": (60.0, _T), "h": (3600.0, _T), "Hz": (1.0, (0, 0, -1, 0)),
    "N": (1.0, _F), "kN": (1000.0, _F), "lbf": (_LBF, _F), "kgf": (STANDARD_GRAVITY, _F),
    "ozf": (_LBF / 16, _F),
    "rad": (1.0, _A), "deg": (math.pi / 180, _A), "rev": (2 * math.pi, _A),
    "1": (1.0, _NONE), "-": (1.0, _NONE),
}

#: names of the dimensions the measurement sheet uses
DIMENSIONS: dict[tuple[int, int, int, int], str] = {
    _L: "length", _M: "mass", _T: "time", _F: "force", _A: "angle", _NONE: "dimensionless",
    (1, 2, -2, 0): "moment", (1, 2, -2, -1): "torsional rigidity", (1, 2, 0, 0): "inertia",
    (0, 1, -2, 0): "acceleration", (0, 1, -1, 0): "speed", (0, 0, -1, 0): "frequency", (1, 1, -1, 0): "impulse",
}

_TOKEN_RE = re.compile(r"^([A-Za-z]+|1|-)(?:\^?(-?\d+))?$")


def _parse_product(text: str) -> tuple[float, list[int]]:
    factor, dims = 1.0, [0, 0, 0, 0]
    for tok in re.split(r"[\s*\u00b7]+", text.strip()):
        if not tok:
            continue
        m = _TOKEN_RE.match(tok)
        if not m or m.group(1) not in _TOKENS:
            raise ValueError(f"unknown unit {tok!r}; known units: {sorted(_TOKENS)}")
        f, d = _TOKENS[m.group(1)]
        p = int(m.group(2)) if m.group(2) else 1
        factor *= f**p
        for i in range(4):
            dims[i] += d[i] * p
    return factor, dims


def parse_unit(unit: str) -> tuple[float, tuple[int, int, int, int]]:
    """Factor to SI and dimension exponents (mass, length, time, angle) of a unit string.

    Parameters
    ----------
    unit : str
        For example ``"ft lbf/rad"``, ``"slug ft^2"``, ``"lb in^2"``, ``"N m"``, ``"kgf"``.

    Returns
    -------
    factor : float
        Multiply a value in ``unit`` by this to get SI (kg, m, s, N, rad).
    dims : tuple of int
        Exponents of mass, length, time and angle.
    """
    if not isinstance(unit, str) or not unit.strip():
        raise ValueError(f"unit {unit!r} is invalid; expected a unit string such as 'm' or 'ft lbf/rad'")
    parts = unit.split("/")
    if len(parts) > 2:
        raise ValueError(f"unit {unit!r} is invalid; use at most one '/'")
    factor, dims = _parse_product(parts[0])
    if len(parts) == 2:
        f2, d2 = _parse_product(parts[1])
        factor /= f2
        dims = [a - b for a, b in zip(dims, d2, strict=True)]
    return factor, (dims[0], dims[1], dims[2], dims[3])


def dimension_name(dims: tuple[int, int, int, int]) -> str:
    """Readable name of a dimension vector (e.g. ``"moment"``) or its exponents.

    Parameters
    ----------
    dims : tuple of int
        Exponents of (mass, length, time, angle), as :func:`parse_unit` returns them.

    Returns
    -------
    str
        The name from ``DIMENSIONS`` (``"length"``, ``"moment"``, ...), else
        ``"M^a L^b T^c angle^d"``.
    """
    return DIMENSIONS.get((dims[0], dims[1], dims[2], dims[3]), f"M^{dims[0]} L^{dims[1]} T^{dims[2]} angle^{dims[3]}")


def quantity(value: float, unit: str, expect: str | None = None) -> float:
    """Convert ``value`` in ``unit`` to SI, optionally checking its dimension.

    Parameters
    ----------
    value : float
        The reading.
    unit : str
        Its unit (see :func:`parse_unit`).
    expect : str, optional
        Required dimension name from ``DIMENSIONS`` (``"length"``, ``"moment"``, ...).

    Returns
    -------
    float
        The value in SI units (kg, m, s, rad and their products).

    Raises
    ------
    ValueError
        If the unit cannot be parsed or its dimension is not ``expect``.

    Examples
    --------
    >>> round(quantity(0.66, "ft lbf/rad"), 4)  # Collins (1987) Appendix D rod
    0.8948
    """
    factor, dims = parse_unit(unit)
    if expect is not None and dimension_name(dims) != expect:
        raise ValueError(f"unit {unit!r} is a {dimension_name(dims)}, not a {expect}")
    return float(value) * factor


_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.+?)\s*$")


def number_with_unit(name: str, raw: str, field_unit: str, what: str = "chair parameter") -> float:
    """A ``--set`` value written as a number and a unit (``5cm``, ``210 lb``), converted to its field's unit.

    Parameters
    ----------
    name : str
        The field's name (in a refusal).
    raw : str
        The value as typed: a number followed by a unit of :func:`parse_unit`.
    field_unit : str
        The field's own unit (``"m"``, ``"N m"``, ``"kg m^2"``); ``"-"`` or ``""``: dimensionless.
    what : str, optional
        What the field belongs to, in a refusal (default ``"chair parameter"``; ``"layout field"``).

    Returns
    -------
    float
        The value in ``field_unit``.

    Raises
    ------
    ValueError
        One line naming ``name`` and ``raw``: no number and unit, an unknown unit, or a unit of another kind.

    Examples
    --------
    >>> number_with_unit("trail", "5cm", "m")
    0.05
    """
    plain = field_unit in ("-", "")
    m = _NUMBER_UNIT.match(raw)
    bad = (f"{what} {name} needs a number (it has no unit), got {raw!r}" if plain else
           f"{what} {name} needs a number in {field_unit} or a number with a unit of the same kind "
           f"(e.g. {name}=5cm), got {raw!r}")
    if not m:
        raise ValueError(bad)
    try:
        factor, dims = parse_unit(m.group(2))
        field_factor, field_dims = parse_unit("1" if plain else field_unit)
    except ValueError as exc:
        raise ValueError(f"{bad}: {exc}") from None
    if dims != field_dims:
        if plain:
            raise ValueError(f"{what} {name} has no unit; give a plain number (got {raw!r})")
        raise ValueError(f"{what} {name} is in {field_unit}; {m.group(2)!r} is not a unit of that kind "
                         f"(got {raw!r})")
    return float(m.group(1)) * factor / field_factor
