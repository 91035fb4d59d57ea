"""Uncertainty files: TOML text <-> :class:`~stability.uncertainty.distributions.Uncertainty`."""

from __future__ import annotations

import os
import sys
from collections.abc import Mapping
from typing import Any

from stability.runtime import readfiles
from stability.uncertainty.distributions import KEYS, Distribution, Uncertainty

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["from_mapping", "loads_uncertainty", "load_uncertainty"]


def from_mapping(data: Mapping[str, Any], valid_fields: frozenset | None = None) -> Uncertainty:
    """Build an :class:`Uncertainty` from a parsed TOML mapping (table name -> table).

    Parameters
    ----------
    data : Mapping of str to Mapping
        Table name -> table with keys ``distribution`` (``"normal"`` or
        ``"uniform"``), ``std``, ``mean``, ``low``, ``high``, ``relative`` and
        ``fields`` (default ``[name]``); values in the chair file's units.
    valid_fields : frozenset of str, optional
        The fields a table may name (default the short form's numeric chair fields).

    Returns
    -------
    Uncertainty
        One :class:`Distribution` per table.

    Raises
    ------
    ValueError
        One line naming the table and key at fault.
    """
    dists = []
    for name, table in data.items():
        if not isinstance(table, Mapping):
            raise ValueError(f"uncertainty entry {name!r} = {table!r} is invalid; valid: a table [{name}]")
        unknown = set(table) - KEYS
        if unknown:
            raise ValueError(f"uncertainty [{name}] has unknown key(s) {sorted(unknown)}; valid keys: {sorted(KEYS)}")
        fields = table.get("fields", [name])
        if isinstance(fields, str) or not isinstance(fields, list) or not fields:
            raise ValueError(f"uncertainty [{name}] fields={fields!r} is invalid; valid: a list of chair fields")

        def num(key: str, table: Mapping[str, Any] = table, name: str = name) -> float | None:
            v = table.get(key)
            if v is None:
                return None
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise ValueError(f"uncertainty [{name}] {key}={v!r} is invalid; valid range: a number")
            return float(v)

        relative = table.get("relative", False)
        if not isinstance(relative, bool):
            raise ValueError(f"uncertainty [{name}] relative={relative!r} is invalid; valid: true or false")
        dists.append(Distribution(name, tuple(fields), str(table.get("distribution", "")), num("std"),
                                  num("mean"), num("low"), num("high"), relative, valid_fields))
    return Uncertainty(tuple(dists))


def loads_uncertainty(text: str) -> Uncertainty:
    """Parse uncertainty TOML text.

    Parameters
    ----------
    text : str
        TOML text as written by :meth:`Uncertainty.dumps` (one table per uncertain parameter).

    Returns
    -------
    Uncertainty
        As :func:`stability.uncertainty.from_mapping`.
    """
    return from_mapping(tomllib.loads(text))


def load_uncertainty(path: str | os.PathLike[str], valid_fields: frozenset | None = None) -> Uncertainty:
    """Read an uncertainty TOML file.

    Parameters
    ----------
    path : str or os.PathLike
        The file (one table per uncertain parameter, see :func:`stability.uncertainty.from_mapping`).
    valid_fields : frozenset of str, optional
        As :func:`stability.uncertainty.from_mapping`.

    Returns
    -------
    Uncertainty
        As :func:`stability.uncertainty.from_mapping`.

    Raises
    ------
    ValueError
        If the file does not exist, is not valid TOML, or a table is invalid.
    """
    if not os.path.exists(path):
        raise ValueError(f"uncertainty file {str(path)!r} does not exist")
    try:
        data = readfiles.load_toml(path)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"uncertainty file {str(path)!r} is not valid TOML: {exc}") from None
    return from_mapping(data, valid_fields)
