"""The explorer's state for one browser session: the chair being edited, its history, pins and files.

Pure Python (no Panel): the page (:mod:`stability.app.page`) only shows what
this object holds and forwards the user's edits to it, so everything the page
does with a chair can be tested without a browser.

* An edit is checked exactly as ``--set NAME=VALUE`` is on the command line
  (:func:`stability.cli.apply_assignments`); a bad value gives the same one
  line ``error: ...`` and the chair stays the last valid one.
* The chair is a base (a preset, or an uploaded TOML file) plus the fields
  changed from it, in the order they were first changed
  (:class:`~stability.app.edits.Edit`); the URL query carries exactly that
  (:mod:`stability.app.links`).
* Every accepted change can be undone; the chair can be reset to its base.
* Downloads: :mod:`stability.app.downloads`.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from stability import chair as chair_mod
from stability.app import downloads, links
from stability.app.edits import (
    DEFAULT_PRESET,
    Edit,
    assignments,
    build_edit,
    error_line,
    field_text,
    preset_chair,
)
from stability.chair import Chair
from stability.settings import defaults as D

__all__ = ["AppState", "Edit", "MAX_PINNED", "DEFAULT_PRESET", "error_line", "assignments"]

#: Largest number of chairs pinned for comparison.
MAX_PINNED = 3


def _file_message(exc: BaseException, path: str, filename: str) -> str:
    """The one-line message for an uploaded file, naming the file as the user named it (not the server's copy)."""
    return error_line(exc).replace(repr(path), repr(filename)).replace(path, filename)


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
    user : dict or None
        The chair's user (``[user]`` table: :meth:`stability.driver.protocol.TrackingResult.user_table`), written
        into the chair's TOML download.
    """

    preset: str = DEFAULT_PRESET
    model: str = D.MODEL
    current: Edit = field(init=False)
    errors: dict[str, str] = field(default_factory=dict)
    pinned: list[Chair] = field(default_factory=list)
    uncertainty: Any = None
    uncertainty_name: str = ""
    user: dict | None = None
    _history: list[tuple[Edit, str]] = field(default_factory=list, repr=False)

    def __post_init__(self) -> None:
        if self.model not in links.MODELS:
            raise ValueError(f"model={self.model!r} is invalid; valid: 'exact' or 'thesis'")
        self.current = build_edit(self.preset, preset_chair(self.preset), {})

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
        return field_text(getattr(self.chair, name))

    # -- changing ---------------------------------------------------------
    def accept(self, new: Edit, keys: Sequence[str]) -> None:
        """Make ``new`` the current chair (undoable when it differs) and clear the messages of ``keys``.

        Parameters
        ----------
        new : Edit
        keys : sequence of str
            Fields (or ``"chair"``, ``"file"``, ``"url"``) whose messages the change answers.
        """
        if new.chair != self.current.chair or new.base != self.current.base:
            self._history.append((self.current, self.model))
        self.current = new
        for k in keys:
            self.errors.pop(k, None)

    def set_model(self, model: str) -> None:
        """Switch the equation variant (undoable: undo goes back to the chair and model before).

        Parameters
        ----------
        model : {"exact", "thesis"}
        """
        if model not in links.MODELS:
            raise ValueError(f"model={model!r} is invalid; valid: 'exact' or 'thesis'")
        if model != self.model:
            self._history.append((self.current, self.model))
            self.model = model

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
            new = build_edit(self.current.base, self.current.base_chair, changes)
        except ValueError as exc:
            self.errors[key] = error_line(exc)
            return self.errors[key]
        self.accept(new, list(texts))
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
            new = build_edit(name, preset_chair(name), {})
        except ValueError as exc:
            self.errors["chair"] = error_line(exc)
            return self.errors["chair"]
        self.accept(new, ["chair", *chair_mod.field_names()])
        self.errors.clear()
        return None

    def reset(self) -> bool:
        """Drop every change from the base chair (the preset or the uploaded file); undo takes it back.

        Returns
        -------
        bool
            False when nothing was changed.
        """
        if not self.current.changes:
            return False
        self.accept(build_edit(self.current.base, self.current.base_chair, {}), chair_mod.field_names())
        return True

    def load_toml(self, data: bytes | str, filename: str = "chair.toml") -> str | None:
        """Load an uploaded chair file (as ``--chair FILE`` reads it).

        Parameters
        ----------
        data : bytes or str
            The file's contents.
        filename : str
            Its name, shown as the base (``file:<name>``) and in messages.

        Returns
        -------
        str or None
            None, or the one-line message (``errors["file"]``; it names the file as uploaded, never the
            server's temporary copy); the chair is then unchanged.
        """
        name = os.path.basename(filename) or "chair.toml"
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, name)
            try:
                raw = data.encode() if isinstance(data, str) else bytes(data)
                with open(path, "wb") as fh:
                    fh.write(raw)
                base_chair = chair_mod.load(path)
                user = chair_mod.user_table(path)
                if user is not None:
                    from stability.driver import Driver

                    Driver.from_mapping(user)                   # checked as the commands check it
                new = build_edit(f"file:{name}", base_chair, {})
            except (ValueError, UnicodeDecodeError) as exc:
                self.errors["file"] = _file_message(exc, path, name)
                return self.errors["file"]
        self.accept(new, ["file", *chair_mod.field_names()])
        self.user = user
        return None

    def load_uncertainty(self, data: bytes | str, filename: str = "uncertainty.toml") -> str | None:
        """Load an uploaded uncertainty file (as ``--uncertainty FILE`` reads it, with its messages).

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
        from stability.uncertainty import load_uncertainty

        name = os.path.basename(filename) or "uncertainty.toml"
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, name)
            try:
                with open(path, "wb") as fh:
                    fh.write(data.encode() if isinstance(data, str) else bytes(data))
                unc = load_uncertainty(path)
            except (ValueError, UnicodeDecodeError) as exc:
                self.errors["uncertainty"] = _file_message(exc, path, name)
                return self.errors["uncertainty"]
        self.uncertainty, self.uncertainty_name = unc, name
        self.errors.pop("uncertainty", None)
        return None

    def clear_uncertainty(self) -> None:
        """Forget the uncertainty file."""
        self.uncertainty, self.uncertainty_name = None, ""

    def undo(self) -> bool:
        """Go back to the chair (and model) before the last accepted change.

        Returns
        -------
        bool
            False when there is nothing to undo.
        """
        if not self._history:
            return False
        self.current, self.model = self._history.pop()
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

    # -- the URL (stability.app.links) -------------------------------------
    def query(self) -> dict[str, str]:
        """The URL query that rebuilds this chair (:func:`stability.app.links.query`).

        Returns
        -------
        dict
        """
        return links.query(self)

    def url_query(self) -> str:
        """:meth:`query` encoded, e.g. ``"chair=revised&trail=0.06&s1=0.25"``.

        Returns
        -------
        str
        """
        return links.url_query(self)

    def apply_query(self, query: str | Mapping[str, Any]) -> str | None:
        """Restore the chair a URL query describes, its bad parts dropped (:func:`stability.app.links.apply_query`).

        Parameters
        ----------
        query : str or mapping

        Returns
        -------
        str or None
            None, or the messages of the dropped parts (``errors["url"]``).
        """
        return links.apply_query(self, query)

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

    # -- downloads (stability.app.downloads) --------------------------------
    def chair_toml(self) -> str:
        """The chair as a TOML file (loading it gives the same chair), with the session's ``[user]`` table.

        Returns
        -------
        str
        """
        return downloads.chair_toml(self.chair, self.user)

    def results_json(self) -> str:
        """The results JSON: what ``python -m stability.critical_speed --chair <the TOML download> --json`` prints
        (with the session's user, when there is one).

        Returns
        -------
        str
        """
        return downloads.results_json(self.chair, self.model, self.user)
