"""The explorer's chair editor: the preset, the model, undo and reset, files, and every chair field in groups.

The editor holds widgets only; :class:`stability.app.page.Explorer` wires
their events to the session's :class:`~stability.app.state.AppState` and
calls :meth:`Editor.sync` and :meth:`Editor.show_errors` after each change.
Each field is labelled with its meaning, its name (as links and ``--set``
spell it) and its unit; hovering it gives the valid range.  The fields are
grouped (:data:`stability.app.text.FIELD_GROUPS`) in cards that open and
close; a sketch of the chair from above sits at the top of the column.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import panel as pn

from stability import chair as chair_mod
from stability import tires
from stability.app.text import FIELD_GROUPS, field_label, field_rows
from stability.app.widgets import widget
from stability.plotting.style import UNSTABLE

__all__ = ["Editor", "EDITOR_WIDTH", "ERROR_STYLE", "BUTTON_WRAP"]

#: Width of the editor column, px (the tabs take the rest of the window).
EDITOR_WIDTH = 330
#: Style of a one-line error message.
ERROR_STYLE = {"color": UNSTABLE, "font-size": "12px"}
#: A button's label wraps onto more lines instead of being cut.
BUTTON_WRAP = [":host .bk-btn { white-space: normal; text-align: left; line-height: 1.25; height: auto; }"]


class Editor:
    """The chair editor of one session.

    Parameters
    ----------
    state : AppState
        The session's state (its starting preset and model).

    Attributes
    ----------
    preset, model : panel.widgets.Select
        The preset (or the uploaded file) and the equation variant.
    undo_button, reset_button, pin_button : panel.widgets.Button
    upload, upload_unc : panel.widgets.FileInput
        A chair file and an uncertainty file (TOML).
    inputs : dict
        Chair field -> its widget (css class ``field-<name>``).
    field_errors : dict
        Chair field -> the HTML pane under it that shows its message (css class ``error-<name>``).
    syncing : bool
        True while :meth:`sync` sets the widgets (their events are then the page's own, not the user's).
    """

    def __init__(self, state: Any) -> None:
        presets = list(chair_mod.preset_names())
        self.preset = widget(pn.widgets.Select, "preset", options=presets,
                                        value=state.current.base if state.current.base in presets else presets[0],
                                        css_classes=["preset"], sizing_mode="stretch_width")
        self.model = widget(pn.widgets.Select, "equations", options=["exact", "thesis"], value=state.model, width=100,
                                       css_classes=["model"])
        self.undo_button = widget(pn.widgets.Button, "undo the last change", kind="default",
                                             css_classes=["undo"], sizing_mode="stretch_width", stylesheets=BUTTON_WRAP)
        self.reset_button = widget(pn.widgets.Button, "reset every field to the preset", kind="default",
                                              css_classes=["reset"], sizing_mode="stretch_width",
                                              stylesheets=BUTTON_WRAP)
        self.pin_button = widget(pn.widgets.Button, "pin this chair for the Compare tab", css_classes=["pin"],
                                            sizing_mode="stretch_width", stylesheets=BUTTON_WRAP)
        self.upload = pn.widgets.FileInput(accept=".toml", css_classes=["upload-chair"], sizing_mode="stretch_width")
        self.upload_unc = pn.widgets.FileInput(accept=".toml", css_classes=["upload-uncertainty"],
                                               sizing_mode="stretch_width")
        self.syncing = False
        self.inputs: dict[str, Any] = {}
        self.field_errors: dict[str, Any] = {}
        tire_names = list(tires.names())
        for row in field_rows():
            name = row["name"]
            label = field_label(row)
            tip = row["doc"] + (f"; valid range {row['range']}" if row["range"] else "")
            w: Any
            kw: dict[str, Any] = {"description": tip, "css_classes": [f"field-{name}"], "sizing_mode": "stretch_width"}
            if name == "caster_position":
                w = widget(pn.widgets.Select, label, options=["rear", "front"], **kw)
            elif name in ("main_tire", "caster_tire"):
                w = widget(pn.widgets.Select, label, options=tire_names, **kw)
            else:
                w = widget(pn.widgets.TextInput, label, placeholder=row["range"], **kw)
            self.inputs[name] = w
            self.field_errors[name] = pn.pane.HTML("", visible=False, styles=ERROR_STYLE, sizing_mode="stretch_width",
                                                   css_classes=[f"error-{name}"], margin=(0, 10))

    def watch(self, on_field: Callable[[str, Any], None]) -> None:
        """Call ``on_field(name, event)`` when a field's value changes.

        Parameters
        ----------
        on_field : callable
        """
        for name, w in self.inputs.items():
            w.param.watch(lambda e, name=name: on_field(name, e), "value")

    def panel(self, sketch: Any) -> Any:
        """The editor column.

        Parameters
        ----------
        sketch : panel pane
            The chair drawn from above, shown at the top.

        Returns
        -------
        panel.Column
        """
        cards = []
        for title, names, open_ in FIELD_GROUPS:
            rows = [pn.Column(self.inputs[n], self.field_errors[n], margin=0, sizing_mode="stretch_width")
                    for n in names]
            cards.append(pn.Card(*rows, title=title, collapsed=not open_, sizing_mode="stretch_width",
                                 css_classes=["field-group"], margin=(4, 0)))
        files = pn.Card(pn.pane.Markdown("A chair file (TOML, as `--chair FILE` reads it):", margin=(0, 10)),
                        self.upload,
                        pn.pane.Markdown("An uncertainty file (TOML, as `--uncertainty FILE`): the 95 % interval of "
                                         "the growth rate is drawn.", margin=(0, 10)),
                        self.upload_unc, title="Files", collapsed=True, sizing_mode="stretch_width", margin=(4, 0))
        from stability.layout.presets import layout_preset_names

        layouts = pn.Card(pn.pane.HTML(
            "<p>Power bases as lists of wheels (docs/layouts.md), each on a page of its own: "
            + ", ".join(f'<a href="?chair={n}">{n}</a>' for n in layout_preset_names()) + ".</p>",
            margin=(0, 10), sizing_mode="stretch_width", css_classes=["layout-links"]),
            title="Wheel layouts", collapsed=True, sizing_mode="stretch_width", margin=(4, 0))
        return pn.Column(
            sketch,
            pn.pane.Markdown("Values in SI units; hover a field's **?** for its valid range. Press Enter (or leave "
                             "the field) to apply.", margin=(0, 10)),
            pn.Row(self.preset, self.model, sizing_mode="stretch_width"),
            pn.Row(self.undo_button, self.reset_button, sizing_mode="stretch_width"),
            self.pin_button, files, layouts, *cards, width=EDITOR_WIDTH, css_classes=["editor"])

    def sync(self, state: Any) -> None:
        """Set every widget to the session's chair, preset and model (their events are ignored meanwhile).

        Parameters
        ----------
        state : AppState
        """
        self.syncing = True
        try:
            for name, w in self.inputs.items():
                text = state.value_text(name)
                if isinstance(w, pn.widgets.Select) and text not in w.options:
                    w.options = [*w.options, text]
                if w.value != text:
                    w.value = text
            base = state.current.base
            if base not in self.preset.options:                  # an uploaded file: shown as its own entry
                self.preset.options = [*chair_mod.preset_names(), base]
            if self.preset.value != base:
                self.preset.value = base
            if self.model.value != state.model:
                self.model.value = state.model
            if self.undo_button.disabled == state.can_undo:
                self.undo_button.disabled = not state.can_undo
            if self.reset_button.disabled == bool(state.current.changes):
                self.reset_button.disabled = not state.current.changes
        finally:
            self.syncing = False

    def show_errors(self, errors: dict[str, str], render: Callable[[str], str]) -> None:
        """Show each field's message under it (and hide the empty ones).

        Parameters
        ----------
        errors : dict
            Field -> message (:attr:`stability.app.state.AppState.errors`).
        render : callable
            User text -> inert markup (:func:`stability.app.markup.literal`).
        """
        for name, pane in self.field_errors.items():
            msg = render(errors.get(name, ""))
            if pane.object != msg:
                pane.param.update(object=msg, visible=bool(msg))
