"""The explorer's state for one browser session: the chair being edited, its history, pins and files.

Pure Python (no Panel): the page (:mod:`stability.app.page`) only shows what
this object holds and forwards the user's edits to it, so everything the page
does with a chair can be tested without a browser.

* An edit is checked exactly as ``--set NAME=VALUE`` is on the command line
  (:func:`stability.cli.apply_assignments`); a bad value gives the same one
  line ``error: ...`` and the chair stays the last valid one.
* The chair is a base (a preset, or an uploaded TOML file) plus the fields
  changed from it, in the order they were first changed; the URL query
  carries exactly that (``?chair=revised&trail=0.06&s1=0.25``), so opening
  the URL rebuilds the same chair, its name included.
* Every accepted change can be undone.
* Downloads: the chair as TOML (it reloads to the same chair), the results
  JSON (the document ``python -m stability.critical_speed --json`` prints),
  the eigenvalues against speed as CSV.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import parse_qsl, urlencode

from stability import chair as chair_mod
from stability import tires
from stability.chair import Chair
from stability.cli import apply_assignments
from stability.runtime.files import json_text, with_tire_range
from stability.settings import defaults as D

__all__ = ["AppState", "Edit", "MAX_PINNED", "DEFAULT_PRESET", "error_line", "assignments"]

#: Largest number of chairs pinned for comparison.
MAX_PINNED = 3
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


def _text(value: Any) -> str:
    """A field value as the text an edit or a URL carries (floats with ``repr``: exact round trip)."""
    if value is None:
        return "none"
    if isinstance(value, float):
        return repr(value)
    return str(value)


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


def _build(base: str, base_chair: Chair, changes: Mapping[str, Any]) -> Edit:
    """The checked edit; raises ValueError with the command line's message."""
    assignments = [f"{k}={_text(v)}" for k, v in changes.items()]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tires.TireRangeWarning)
        c = apply_assignments(base_chair, assignments)
    return Edit(base, base_chair, tuple(changes.items()), c)


@dataclass
class AppState:
    """Everything one browser session holds (each session has its own).

    Parameters
    ----------
    preset : str, optional
        The starting preset (default :data:`DEFAULT_PRESET`).
    model : {"exact", "thesis"}, optional
        Equation variant of the linear views.

    Attributes
    ----------
    preset : str
        The preset the session started from.
    model : str
        Equation variant of the views.
    current : Edit
        The last valid chair and how it was made.
    errors : dict
        Field name (or ``"chair"``, ``"file"``, ``"uncertainty"``, ``"url"``, ``"pin"``) -> the
        one-line message of the last rejected input there; cleared by the next accepted one.
    pinned : list of Chair
        Chairs pinned for comparison (at most :data:`MAX_PINNED`).
    uncertainty : Uncertainty or None
        The loaded uncertainty file.
    uncertainty_name : str
        Its file name.
    """

    preset: str = DEFAULT_PRESET
    model: str = D.MODEL
    current: Edit = field(init=False)
    errors: dict[str, str] = field(default_factory=dict)
    pinned: list[Chair] = field(default_factory=list)
    uncertainty: Any = None
    uncertainty_name: str = ""
    _history: list[Edit] = field(default_factory=list, repr=False)

    def __post_init__(self) -> None:
        if self.model not in ("exact", "thesis"):
            raise ValueError(f"model={self.model!r} is invalid; valid: 'exact' or 'thesis'")
        self.current = _build(self.preset, _preset(self.preset), {})

    # -- reading ----------------------------------------------------------
    @property
    def chair(self) -> Chair:
        """The last valid chair."""
        return self.current.chair

    @property
    def changes(self) -> dict[str, Any]:
        """Fields changed from the base chair, in the order first changed."""
        return dict(self.current.changes)

    @property
    def can_undo(self) -> bool:
        """Whether an accepted change can be undone."""
        return bool(self._history)

    def value_text(self, name: str) -> str:
        """The current chair's value of field ``name`` as editor text.

        Parameters
        ----------
        name : str

        Returns
        -------
        str
        """
        return _text(getattr(self.chair, name))

    # -- changing ---------------------------------------------------------
    def _accept(self, new: Edit, keys: Sequence[str]) -> None:
        if new.chair != self.current.chair or new.base != self.current.base:
            self._history.append(self.current)
        self.current = new
        for k in keys:
            self.errors.pop(k, None)

    def set_field(self, name: str, text: str) -> str | None:
        """Edit one field from its text, as ``--set NAME=TEXT`` would.

        Parameters
        ----------
        name : str
            A chair field.
        text : str
            The new value in the field's SI unit (``none`` for the tire's own camber coefficient).

        Returns
        -------
        str or None
            None when accepted; else the command line's one-line message (kept in
            ``errors[name]``), and the chair is unchanged.
        """
        return self.set_fields({name: text})

    def set_fields(self, texts: Mapping[str, str]) -> str | None:
        """Edit several fields at once (all or none), e.g. to apply a recommendation.

        Parameters
        ----------
        texts : mapping
            Field name -> value text.

        Returns
        -------
        str or None
            None when accepted, else the message (kept in ``errors`` under the first field).
        """
        key = next(iter(texts), "chair")
        try:
            parsed = dict(chair_mod.parse_assignment(f"{k}={v}") for k, v in texts.items())
            changes = self.changes
            for k, v in parsed.items():
                if k in changes and getattr(self.current.base_chair, k) == v:
                    del changes[k]
                elif getattr(self.current.base_chair, k) != v or k in changes:
                    changes[k] = v
            new = _build(self.current.base, self.current.base_chair, changes)
        except ValueError as exc:
            self.errors[key] = error_line(exc)
            return self.errors[key]
        self._accept(new, list(texts))
        return None

    def select_preset(self, name: str) -> str | None:
        """Start over from a preset (the edits so far can be undone).

        Parameters
        ----------
        name : str
            A preset name (:func:`stability.chair.all_preset_names`).

        Returns
        -------
        str or None
            None, or the message for an unknown preset (``errors["chair"]``).
        """
        try:
            new = _build(name, _preset(name), {})
        except ValueError as exc:
            self.errors["chair"] = error_line(exc)
            return self.errors["chair"]
        self._accept(new, ["chair", *chair_mod.field_names()])
        self.errors.clear()
        return None

    def load_toml(self, data: bytes | str, filename: str = "chair.toml") -> str | None:
        """Load an uploaded chair file (as ``--chair FILE`` reads it).

        Parameters
        ----------
        data : bytes or str
            The file's contents.
        filename : str
            Its name, shown as the base (``file:<name>``).

        Returns
        -------
        str or None
            None, or the one-line message (``errors["file"]``); the chair is then unchanged.
        """
        try:
            raw = data.encode() if isinstance(data, str) else bytes(data)
            with tempfile.TemporaryDirectory() as d:
                path = os.path.join(d, os.path.basename(filename) or "chair.toml")
                with open(path, "wb") as fh:
                    fh.write(raw)
                base_chair = chair_mod.load(path)
            new = _build(f"file:{os.path.basename(filename)}", base_chair, {})
        except (ValueError, UnicodeDecodeError) as exc:
            self.errors["file"] = error_line(exc)
            return self.errors["file"]
        self._accept(new, ["file", *chair_mod.field_names()])
        return None

    def load_uncertainty(self, data: bytes | str, filename: str = "uncertainty.toml") -> str | None:
        """Load an uploaded uncertainty file (as ``--uncertainty FILE`` reads it).

        Parameters
        ----------
        data : bytes or str
            The file's contents.
        filename : str
            Its name.

        Returns
        -------
        str or None
            None, or the one-line message (``errors["uncertainty"]``).
        """
        from stability.uncertainty import loads_uncertainty

        try:
            text = data if isinstance(data, str) else bytes(data).decode()
            unc = loads_uncertainty(text)
        except (ValueError, UnicodeDecodeError) as exc:
            self.errors["uncertainty"] = error_line(exc)
            return self.errors["uncertainty"]
        self.uncertainty, self.uncertainty_name = unc, os.path.basename(filename)
        self.errors.pop("uncertainty", None)
        return None

    def clear_uncertainty(self) -> None:
        """Forget the uncertainty file."""
        self.uncertainty, self.uncertainty_name = None, ""

    def undo(self) -> bool:
        """Go back to the chair before the last accepted change.

        Returns
        -------
        bool
            False when there is nothing to undo.
        """
        if not self._history:
            return False
        self.current = self._history.pop()
        self.errors.clear()
        return True

    # -- pins -------------------------------------------------------------
    def pin(self) -> str | None:
        """Pin the current chair for comparison.

        Returns
        -------
        str or None
            None, or why not (already pinned, or :data:`MAX_PINNED` pinned), kept in ``errors["pin"]``.
        """
        if any(p == self.chair for p in self.pinned):
            self.errors["pin"] = f"error: chair {self.chair.name!r} is already pinned"
        elif len(self.pinned) >= MAX_PINNED:
            self.errors["pin"] = (f"error: {len(self.pinned)} chairs are pinned; at most {MAX_PINNED} can be "
                                  "compared: unpin one first")
        else:
            self.pinned.append(self.chair)
            self.errors.pop("pin", None)
            return None
        return self.errors["pin"]

    def unpin(self, index: int) -> None:
        """Remove the pinned chair at ``index`` (0-based; out of range: nothing happens).

        Parameters
        ----------
        index : int
        """
        if 0 <= index < len(self.pinned):
            del self.pinned[index]

    # -- the URL ----------------------------------------------------------
    def query(self) -> dict[str, str]:
        """The URL query that rebuilds this chair: ``chair`` (a preset) and the fields changed from it.

        An uploaded chair is given as the default preset plus every field that
        differs from it, its name included.

        Returns
        -------
        dict
            Parameter -> text, in order (``model`` only when not ``exact``).
        """
        base = self.current.base
        if base.startswith("file:"):
            ref = _preset(DEFAULT_PRESET)
            out = {"chair": DEFAULT_PRESET}
            out.update({k: _text(getattr(self.chair, k)) for k in chair_mod.field_names()
                        if getattr(self.chair, k) != getattr(ref, k)})
        else:
            out = {"chair": base}
            out.update({k: _text(v) for k, v in self.current.changes})
        if self.model != "exact":
            out["model"] = self.model
        return out

    def url_query(self) -> str:
        """:meth:`query` encoded, e.g. ``"chair=revised&trail=0.06&s1=0.25"``.

        Returns
        -------
        str
        """
        return urlencode(self.query())

    def apply_query(self, query: str | Mapping[str, Any]) -> str | None:
        """Restore the chair a URL query describes (see :meth:`query`), keeping every valid part of it.

        A bad part (an unknown preset or model, an unknown field, a bad value) is
        dropped with the command line's one-line message, and the rest is applied:
        ``?chair=revised&trail=abc`` opens the revised chair with a message about
        ``trail``, never another chair.  The page then rewrites the URL to the chair shown.

        Parameters
        ----------
        query : str or mapping
            ``"chair=revised&trail=0.06"`` (a leading ``?`` is ignored) or a mapping of
            parameter -> text (a list value uses its last item, as a browser's repeated key).

        Returns
        -------
        str or None
            None, or the messages of the dropped parts joined by ``"; "`` (``errors["url"]``).
        """
        if isinstance(query, str):
            items = parse_qsl(query.lstrip("?"), keep_blank_values=True)
        else:
            items = [(k, v[-1] if isinstance(v, (list, tuple)) else v) for k, v in query.items()]
        params = {k: (v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)) for k, v in items}
        problems: list[str] = []
        base = params.pop("chair", DEFAULT_PRESET)
        try:
            base_chair = _preset(base)
        except ValueError as exc:
            problems.append(error_line(exc).removeprefix("error: "))
            base, base_chair = DEFAULT_PRESET, _preset(DEFAULT_PRESET)
        model = params.pop("model", self.model)
        if model not in ("exact", "thesis"):
            problems.append(f"model {model!r} is invalid; valid: 'exact' or 'thesis'")
            model = self.model
        changes: dict[str, Any] = {}
        for k, v in params.items():
            try:
                name, value = chair_mod.parse_assignment(f"{k}={v}")
                _build(base, base_chair, {**changes, name: value})
            except ValueError as exc:
                problems.append(error_line(exc).removeprefix("error: "))
                continue
            changes[name] = value
        self.model = model
        self._accept(_build(base, base_chair, changes), ["url", *chair_mod.field_names()])
        if problems:
            self.errors["url"] = "error: the link's " + "; ".join(problems) + " (dropped; the rest applied)"
            return self.errors["url"]
        return None

    @classmethod
    def from_query(cls, query: str | Mapping[str, Any]) -> AppState:
        """A new state restored from a URL query (its bad parts dropped with a message, the rest applied).

        Parameters
        ----------
        query : str or mapping

        Returns
        -------
        AppState
        """
        state = cls()
        state.apply_query(query)
        state._history.clear()
        return state

    # -- downloads --------------------------------------------------------
    def chair_toml(self) -> str:
        """The chair as a TOML file (:func:`stability.chair.dumps`; loading it gives the same chair).

        Returns
        -------
        str
        """
        return chair_mod.dumps(self.chair)

    def results_json(self) -> str:
        """The results JSON: what ``python -m stability.critical_speed --chair <this chair> --json`` prints.

        Computed with the command's own defaults (its parser's) and its own
        document builder, so the two cannot drift apart.

        Returns
        -------
        str
        """
        from stability.cli import parse_speeds
        from stability.critical_speed.command import build_parser, document
        from stability.linear import analyse
        from stability.study.summary_text import simulator_checks

        args = build_parser().parse_args(["--model", self.model])
        speeds = parse_speeds(args.speeds)
        with tires.range_policy(args.tire_range), tires.collect_notes() as notes, warnings.catch_warnings():
            warnings.simplefilter("ignore", tires.TireRangeWarning)
            tires.range_check(self.chair, _static_loads(self.chair))
            summary = analyse(self.chair, model=self.model, speeds=speeds, max_speed=args.max_speed)
            doc = document(summary, simulator_checks(summary), args, speeds)
        return json_text(with_tire_range(doc, notes, args.tire_range)) + "\n"


def _preset(name: str) -> Chair:
    return chair_mod.preset(name)


def _static_loads(c: Chair) -> Any:
    from stability.models.statics import static_loads

    return static_loads(c)


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
