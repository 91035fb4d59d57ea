"""The explorer's widgets built with the keywords the installed Panel reads (pyproject: ``panel>=1.5,<1.10``).

Panel 1.9 renamed a widget's text from ``name`` to ``label`` and a button's kind from ``button_type`` to
``color``; the old keywords still work there but warn (``PendingDeprecationWarning``: removed in Panel 2.0), and
releases before the rename know only the old ones.  :func:`widget` passes the text and the kind under whichever
name the widget class declares, so the explorer builds without a deprecation warning on every supported release.
"""

from __future__ import annotations

from typing import Any

__all__ = ["widget"]


def widget(cls: Any, text: str, *, kind: str | None = None, **params: Any) -> Any:
    """A Panel widget of class ``cls`` showing ``text``.

    Parameters
    ----------
    cls : type
        A ``panel.widgets`` class (Button, Select, FloatInput, ...).
    text : str
        What the widget shows: its label, or a button's caption.
    kind : str, optional
        A button's kind (``"primary"``, ``"default"``, ...): its colour; None leaves the class's default.
    **params
        Every other parameter, as the class takes it.

    Returns
    -------
    panel.widgets.Widget
        The widget, with ``text`` under ``label`` where the class declares it (else ``name``) and ``kind`` under
        ``color`` where the class declares it (else ``button_type``).
    """
    declared = cls.param
    params["label" if "label" in declared else "name"] = text
    if kind is not None:
        params["color" if "color" in declared else "button_type"] = kind
    return cls(**params)
