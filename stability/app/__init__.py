"""The interactive explorer: ``python -m stability.app`` serves a local web page to design a chair by hand.

:mod:`.state` (one session's chair, edits, undo, URL, pins, downloads; pure
Python), :mod:`.views` (the linear views' data from the toolkit's compute
functions), :mod:`.jobs` (nonlinear work in the background), :mod:`.page`
(the Panel page; needs the ``app`` extra) and :mod:`.server` (serving it).
The app computes nothing itself.  See docs/app.md.
"""

from __future__ import annotations

from .state import MAX_PINNED, AppState, error_line

__all__ = ["AppState", "MAX_PINNED", "error_line"]
