"""The interactive explorer: ``python -m stability.app`` serves a local web page to design a chair by hand.

Modules: ``state`` (one session's chair, edits, undo, URL, pins, downloads;
pure Python), ``views`` (the linear views' data from the toolkit's compute
functions), ``text`` and ``plots`` (what is shown), ``jobs`` (nonlinear work
in the background), ``page`` (the Panel page; needs the ``app`` extra) and
``server`` (serving it).  The app computes nothing itself.  See docs/app.md.
"""

from __future__ import annotations

from stability.app.state import MAX_PINNED, AppState, error_line

__all__ = ["AppState", "MAX_PINNED", "error_line"]
