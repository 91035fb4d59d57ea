"""The JSON outputs' conventions: key names, and one JSON Schema per command shipped with the package.

Key convention (every command's JSON, checked by :func:`bad_keys` in the tests):

* snake_case words, lower case, starting with a letter: ``growth_rate_1_s``;
* the unit, if any, last, from :data:`UNIT_SUFFIXES` (``_m``, ``_m_s``, ``_N``, ``_N_m``, ``_N_per_m``,
  ``_1_s``, ``_deg``, ``_Ns``, ``_s``, ``_hz``, ...): the only upper-case letters a key may carry are those
  units' (``N``, ``Ns``); lower-case ``_n_m`` or ``_per_s`` spellings are refused;
* never a value inside a key (``growth_rate_1_s@0.25`` or ``{"0.5": ...}``): a quantity over speeds is an
  array next to a ``speeds_m_s`` list.

:func:`schema` loads ``stability/schemas/<command>.json`` (JSON Schema, draft 2020-12) and
:func:`validate` checks an output against it (needs ``jsonschema``, in the ``test`` extra).

Examples
--------
>>> bad_keys({"growth_rate_1_s": 1.0, "peak_torque_Nm": 2.0, "rows": [{"x@0.25": 1}]})
['peak_torque_Nm', 'rows[0].x@0.25']
"""

from __future__ import annotations

import json
import re
from functools import cache
from importlib import resources
from typing import Any

__all__ = ["UNIT_SUFFIXES", "KEY_PATTERN", "bad_keys", "schema", "validate", "schema_names"]

#: Unit suffixes a key may end with (the upper-case ones are the only upper case allowed in a key).
UNIT_SUFFIXES = ("m", "m_s", "m_s2", "N", "N_m", "N_per_m", "N_m_s", "1_s", "deg", "deg_s", "rad", "rad_s", "Ns",
                 "s", "kg", "kg_m", "kg_m2", "hz", "db", "ms", "pct", "N_m_per_deg", "deg_per_m", "N_per_deg")
_UPPER = sorted({tok for u in UNIT_SUFFIXES for tok in u.split("_") if not tok.islower() and not tok.isdigit()},
                key=len, reverse=True)
#: A key: lower-case snake_case words; upper-case tokens only from the unit suffixes.
KEY_PATTERN = re.compile(r"^[a-z][a-z0-9]*(?:_(?:[a-z0-9]+|" + "|".join(_UPPER) + r"))*$")
_RAW_UNITS = re.compile(r"(?:^|_)(?:Nm|m_per_s|n_per_m|per_s)(?:_|$)|_(?:n|n_m|nm|ns)$")


def bad_keys(data: Any, path: str = "") -> list[str]:
    """Keys of ``data`` (walked recursively) that break the convention, as dotted paths.

    Parameters
    ----------
    data : Any
        A decoded JSON value.
    path : str, optional
        Prefix of the reported paths.

    Returns
    -------
    list of str
        Empty when every key follows it; ``chair_parameters`` (the chair's field names, units in the
        chair file's header) is checked for the syntax only.
    """
    out: list[str] = []
    if isinstance(data, dict):
        for k, v in data.items():
            where = f"{path}.{k}" if path else str(k)
            if not isinstance(k, str) or not KEY_PATTERN.match(k) or _RAW_UNITS.search(k):
                out.append(where)
            out.extend(bad_keys(v, where))
    elif isinstance(data, list):
        for i, v in enumerate(data):
            out.extend(bad_keys(v, f"{path}[{i}]"))
    return out


def schema_names() -> list[str]:
    """The commands that ship a JSON Schema (file stems in this package).

    Returns
    -------
    list of str
    """
    return sorted(p.name[:-5] for p in resources.files(__name__).iterdir() if p.name.endswith(".json"))


@cache
def _load(name: str) -> str:
    return resources.files(__name__).joinpath(f"{name}.json").read_text(encoding="utf-8")


def schema(command: str) -> dict[str, Any]:
    """The JSON Schema of a command's JSON output.

    Parameters
    ----------
    command : str
        Command name as ``python -m stability.<command>`` spells it (``study`` has one per subcommand:
        ``study_critical_impulse``, ``study_equal_instability``).

    Returns
    -------
    dict
    """
    if command not in schema_names():
        raise ValueError(f"command {command!r} has no JSON schema; valid: {', '.join(schema_names())}")
    return json.loads(_load(command))


@cache
def _validator(command: str) -> Any:
    """The validator of a command's schema, the schema checked against its metaschema once per process (what
    ``jsonschema.validate`` does on every call: tens of milliseconds per shipped schema, far more than a
    validation)."""
    from jsonschema.validators import validator_for

    doc = schema(command)
    cls = validator_for(doc)
    cls.check_schema(doc)
    return cls(doc, registry=_registry())


@cache
def _registry() -> Any:
    """The shipped schemas as one ``referencing`` registry, each under its ``$id``: a schema may refer to another's
    definitions (report.json to advise.json's measures, recommendation and decision)."""
    from referencing import Registry, Resource

    docs = [json.loads(_load(name)) for name in schema_names()]
    return Registry().with_resources((doc["$id"], Resource.from_contents(doc)) for doc in docs)


def validate(command: str, data: Any) -> None:
    """Check ``data`` against the command's schema and the key convention.

    Parameters
    ----------
    command : str
        See :func:`schema`.
    data : Any
        The decoded JSON output.

    Raises
    ------
    ValueError
        One line: the first schema violation, or the keys that break the convention.
    """
    from jsonschema.exceptions import best_match

    exc = best_match(_validator(command).iter_errors(data))     # what jsonschema.validate reports, first
    if exc is not None:
        where = "/".join(str(p) for p in exc.absolute_path)
        raise ValueError(f"{command} JSON at {where or 'top level'}: {exc.message}") from None
    keys = bad_keys(data)
    if keys:
        raise ValueError(f"{command} JSON keys break the convention: {', '.join(keys[:10])}")
