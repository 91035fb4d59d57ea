"""Text from users, URLs and files shown in the explorer's Markdown and HTML panes as text, never as markup.

Panel's Markdown and HTML panes render their ``object`` as HTML in the browser,
and Panel runs the ``<script>`` elements it finds there.  Every string the
page shows that did not come from this package's own source (a chair's name, a
field's value echoed in a message, a file name, an exception's text, a command
line's output that quotes any of these) goes through :func:`literal` or
:func:`pre` on its way into a pane; the page's own markup (bold labels, the
tables it builds from numbers) is written around it.

:func:`literal` writes every ASCII character other than a letter, a digit or a
space as an HTML numeric character reference (``<`` is ``&#60;``).  Markdown
treats a character reference as the literal character (CommonMark 6.2), so the
result is inert in both languages: no tag, attribute, link, emphasis, table
cell or code fence can start inside it.  The browser shows the original text.
"""

from __future__ import annotations

import html
import unicodedata

__all__ = ["literal", "pre", "MAX_SHOWN", "PRE_STYLESHEET"]

#: The style of :func:`pre` blocks: a line longer than the pane scrolls sideways within the block (a command
#: line's table keeps its columns) instead of being cut or wrapped mid-row.
PRE_STYLESHEET = ("pre.cli-text { overflow-x: auto; white-space: pre; font-size: 12px; line-height: 1.35; "
                  "max-width: 100%; }")
#: Longest user text shown in full (characters); longer text is cut with its length stated.
MAX_SHOWN = 1000


def _cut(text: str) -> str:
    text = " ".join(str(text).split())            # one line: newlines and tabs would end a Markdown paragraph
    text = "".join(c for c in text if unicodedata.category(c) != "Cc")    # control characters show nothing
    if len(text) > MAX_SHOWN:
        text = f"{text[:MAX_SHOWN]}... ({len(text)} characters)"
    return text


def literal(text: object) -> str:
    """``text`` as inert Markdown/HTML that shows the same characters (at most :data:`MAX_SHOWN` of them).

    Parameters
    ----------
    text : object
        Any text (``str(text)`` is shown); newlines and runs of white space become one space, other
        control characters are dropped.

    Returns
    -------
    str
        Letters, digits and spaces as they are; every other ASCII character as ``&#N;``.
        Non-ASCII characters are kept (none of them is markup in Markdown or HTML).

    Examples
    --------
    >>> literal("<img src=x onerror=alert(1)>")
    '&#60;img src&#61;x onerror&#61;alert&#40;1&#41;&#62;'
    """
    return "".join(c if c.isalnum() or c == " " or ord(c) > 127 else f"&#{ord(c)};" for c in _cut(str(text)))


def pre(text: str) -> str:
    """A command line's text output for an HTML pane: a ``<pre>`` block with its text escaped.

    Parameters
    ----------
    text : str
        Any text, newlines kept (it may quote a chair's name or a file's contents).

    Returns
    -------
    str
        ``<pre class="cli-text">...</pre>``; ``&``, ``<``, ``>`` and quotes escaped.
    """
    return f'<pre class="cli-text">{html.escape(str(text), quote=True)}</pre>'
