"""The text panes of one tab: written while the tab is shown, kept (the latest) until it is shown otherwise.

The page's tabs are rendered when shown (``pn.Tabs(dynamic=True)``), so a hidden
tab costs the browser nothing per edit.  A tab that was shown and then hidden
keeps its Panel Markdown and HTML panes bound to Bokeh models that are no
longer in the document; Panel 1.9 rebuilds such a pane's properties with no
document when its text changes and then points the session's shared
stylesheets at the CDN (``cdn.holoviz.org``), which the page's
Content-Security-Policy refuses and which an offline machine cannot load.
So a tab's text panes are written only while the tab is shown; a text for a
hidden tab waits here and is written when the tab is shown again.  Figures and
other widgets are updated directly (their updates carry no stylesheets).
"""

from __future__ import annotations

from typing import Any

__all__ = ["TabText"]


class TabText:
    """The text panes of one tab.

    Attributes
    ----------
    shown : bool
        Whether the tab is the one shown (the page sets it when the active tab changes).
    """

    def __init__(self, shown: bool = False) -> None:
        self.shown = shown
        self._pending: dict[int, tuple[Any, str]] = {}

    def set(self, pane: Any, text: str) -> None:
        """Show ``text`` in ``pane`` now if the tab is shown, else when it next is (the latest text wins).

        Parameters
        ----------
        pane : panel.pane.Markdown or panel.pane.HTML
        text : str
            The pane's new object (already inert: user text through :mod:`stability.app.markup`).
        """
        if self.shown:
            self._pending.pop(id(pane), None)
            if pane.object != text:
                pane.object = text
        else:
            self._pending[id(pane)] = (pane, text)

    def get(self, pane: Any) -> str:
        """The text ``pane`` shows, or will show when the tab is next shown.

        Parameters
        ----------
        pane : panel.pane.Markdown or panel.pane.HTML

        Returns
        -------
        str
        """
        return self._pending.get(id(pane), (pane, pane.object))[1]

    def flush(self) -> None:
        """Write every waiting text (the tab has just been shown)."""
        pending, self._pending = self._pending, {}
        for pane, text in pending.values():
            if pane.object != text:
                pane.object = text
