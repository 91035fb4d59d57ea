"""The explorer's widgets use the keywords the installed Panel reads (stability.app.widgets): no deprecated
keyword on this release, the old keywords on a release that declares only those."""

from __future__ import annotations

import warnings

import pytest

pn = pytest.importorskip("panel")
param = pytest.importorskip("param")

from stability.app.widgets import widget  # noqa: E402


def test_a_button_shows_its_text_and_kind_under_the_names_its_class_declares():
    b = widget(pn.widgets.Button, "advise this chair", kind="primary")
    declared = pn.widgets.Button.param
    assert getattr(b, "label" if "label" in declared else "name") == "advise this chair"
    assert getattr(b, "color" if "color" in declared else "button_type") == "primary"
    s = widget(pn.widgets.Select, "preset", options=["a", "b"])
    assert s.name == "preset" and s.options == ["a", "b"]          # the name the app's code reads, either way


def test_a_release_without_label_or_color_gets_name_and_button_type():
    """Panel before the rename declares ``name`` (every Parameterized has it) and ``button_type`` only."""

    class OldButton(param.Parameterized):
        button_type = param.String(default="default")

    b = widget(OldButton, "start over", kind="primary")
    assert (b.name, b.button_type) == ("start over", "primary")
    assert widget(OldButton, "undo").button_type == "default"      # no kind: the class's default


def test_the_explorer_builds_without_a_deprecation_warning():
    """Every widget of the explorer's page, built on the installed Panel: a deprecated keyword (PendingDeprecation
    or Deprecation warning) is an error here."""
    from stability.app.page import Explorer

    with warnings.catch_warnings():
        warnings.simplefilter("error", PendingDeprecationWarning)
        warnings.simplefilter("error", DeprecationWarning)
        ex = Explorer(auto_nonlinear=False)
    assert ex.editor.preset.name == "preset"
