"""One state of the explorer's chair editor: a base chair and the fields changed from it, checked as ``--set`` is.

The building block of :mod:`stability.app.state` (undo keeps a list of these)
and of :mod:`stability.app.links` (a URL query is a base and its changes).
Pure Python (no Panel).
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from stability import chair as chair_mod
from stability import tires
from stability.chair import Chair
from stability.cli import apply_assignments
from stability.settings import defaults as D

__all__ = ["Edit", "build_edit", "field_text", "error_line", "preset_chair", "assignments", "DEFAULT_PRESET"]

#: The chair a new session starts with (the command lines' default ``--chair``).
DEFAULT_PRESET = D.CHAIR


def error_line(exc: BaseException) -> str:
    """The one line the command lines print for ``exc`` (:func:`stability.cli.error`'s text).

    Parameters
    ----------
    exc : BaseException

    Returns
    -------
    str
        ``"error: "`` and the first line of the message.
    """
    msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
    return f"error: {msg}"


def field_text(value: Any) -> str:
    """A field value as the text an edit or a URL carries (floats with ``repr``: exact round trip).

    Parameters
    ----------
    value : Any
        A chair field's value (None: the tire's own camber coefficient).

    Returns
    -------
    str
    """
    if value is None:
        return "none"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def preset_chair(name: str) -> Chair:
    """The preset ``name`` (ValueError with the command line's message when unknown).

    Parameters
    ----------
    name : str

    Returns
    -------
    Chair
    """
    return chair_mod.preset(name)


@dataclass(frozen=True)
class Edit:
    """One state of the editor: the base chair and the fields changed from it.

    Attributes
    ----------
    base : str
        Preset name, or ``"file:<name>"`` for an uploaded chair file.
    base_chair : Chair
        The chair the changes start from.
    changes : tuple of (str, Any)
        Field name and value, in the order first changed.
    chair : Chair
        ``base_chair`` with ``changes`` applied (checked).
    """

    base: str
    base_chair: Chair
    changes: tuple[tuple[str, Any], ...]
    chair: Chair


def build_edit(base: str, base_chair: Chair, changes: Mapping[str, Any]) -> Edit:
    """The checked edit: ``base_chair`` with ``changes`` applied as ``--set NAME=VALUE`` applies them.

    Parameters
    ----------
    base : str
        Preset name or ``"file:<name>"``.
    base_chair : Chair
    changes : mapping
        Field -> value, in order.

    Returns
    -------
    Edit

    Raises
    ------
    ValueError
        With the command line's one-line message for a bad value.
    """
    texts = [f"{k}={field_text(v)}" for k, v in changes.items()]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        c = apply_assignments(base_chair, texts)
    return Edit(base, base_chair, tuple(changes.items()), c)


def assignments(fields: dict) -> dict[str, str]:
    """A recommendation's chair fields as editor texts (floats with ``repr``: the exact values).

    Parameters
    ----------
    fields : dict
        Chair field -> new value (:attr:`stability.advise.Candidate.fields`).

    Returns
    -------
    dict
        Field -> text for :meth:`stability.app.state.AppState.set_fields`.
    """
    return {k: repr(v) if isinstance(v, float) else str(v) for k, v in fields.items()}
