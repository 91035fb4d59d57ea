"""The explorer's shared links: the URL query that rebuilds a chair, and a query applied to a session.

A chair is a base (a preset) plus the fields changed from it, in the order
they were first changed; the query carries exactly that
(``?chair=revised&trail=0.06&s1=0.25``, ``&model=thesis`` when not exact), so
opening the link rebuilds the same chair, its name included (floats written
with ``repr``: exact round trip).  An uploaded chair is written as the default
preset plus every field that differs from it.

A link comes from a stranger: a bad part (an unknown preset or model, an
unknown field, a bad value) is dropped with the command line's one-line
message and the rest is applied, so ``?chair=revised&trail=abc`` opens the
revised chair, never another one.  The functions take the session's
:class:`~stability.app.state.AppState` (its ``current`` edit, ``model`` and
``errors``); the state's ``query``, ``url_query`` and ``apply_query`` methods
call them.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any
from urllib.parse import parse_qsl, urlencode

from stability import chair as chair_mod
from stability.app.edits import DEFAULT_PRESET, build_edit, error_line, field_text, preset_chair

__all__ = ["query", "url_query", "apply_query", "MODELS"]

#: The equation variants a link may name.
MODELS = ("exact", "thesis")


def query(state: Any) -> dict[str, str]:
    """The URL query that rebuilds the session's chair: ``chair`` (a preset) and the fields changed from it.

    Parameters
    ----------
    state : AppState

    Returns
    -------
    dict
        Parameter -> text, in order (``model`` only when not ``exact``).
    """
    base = state.current.base
    if base.startswith("file:"):
        ref = preset_chair(DEFAULT_PRESET)
        out = {"chair": DEFAULT_PRESET}
        out.update({k: field_text(getattr(state.chair, k)) for k in chair_mod.field_names()
                    if getattr(state.chair, k) != getattr(ref, k)})
    else:
        out = {"chair": base}
        out.update({k: field_text(v) for k, v in state.current.changes})
    if state.model != "exact":
        out["model"] = state.model
    return out


def url_query(state: Any) -> str:
    """:func:`query` encoded, e.g. ``"chair=revised&trail=0.06&s1=0.25"``.

    Parameters
    ----------
    state : AppState

    Returns
    -------
    str
    """
    return urlencode(query(state))


def _items(text: str | Mapping[str, Any]) -> dict[str, str]:
    if isinstance(text, str):
        items = parse_qsl(text.lstrip("?"), keep_blank_values=True)
    else:
        items = [(k, v[-1] if isinstance(v, (list, tuple)) else v) for k, v in text.items()]
    return {k: (v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)) for k, v in items}


def apply_query(state: Any, text: str | Mapping[str, Any]) -> str | None:
    """Restore on ``state`` the chair a URL query describes (see :func:`query`), keeping every valid part of it.

    A bad part is dropped with the command line's one-line message and the rest
    is applied; the page then rewrites the URL to the chair shown.

    Parameters
    ----------
    state : AppState
        Changed in place: its chair (one undoable change), model and ``errors["url"]``.
    text : str or mapping
        ``"chair=revised&trail=0.06"`` (a leading ``?`` is ignored) or a mapping of
        parameter -> text (a list value uses its last item, as a browser's repeated key).

    Returns
    -------
    str or None
        None, or the messages of the dropped parts joined by ``"; "`` (``errors["url"]``).
    """
    params = _items(text)
    problems: list[str] = []
    base = params.pop("chair", DEFAULT_PRESET)
    try:
        base_chair = preset_chair(base)
    except ValueError as exc:
        problems.append(error_line(exc).removeprefix("error: "))
        base, base_chair = DEFAULT_PRESET, preset_chair(DEFAULT_PRESET)
    model = params.pop("model", state.model)
    if model not in MODELS:
        problems.append(f"model {model!r} is invalid; valid: 'exact' or 'thesis'")
        model = state.model
    changes: dict[str, Any] = {}
    for k, v in params.items():
        try:
            name, value = chair_mod.parse_assignment(f"{k}={v}")
            build_edit(base, base_chair, {**changes, name: value})
        except ValueError as exc:
            problems.append(error_line(exc).removeprefix("error: "))
            continue
        changes[name] = value
    state.accept(build_edit(base, base_chair, changes), ["url", *chair_mod.field_names()])
    state.model = model
    if problems:
        state.errors["url"] = "error: the link's " + "; ".join(problems) + " (dropped; the rest applied)"
        return state.errors["url"]
    return None
