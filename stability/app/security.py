"""What the explorer's server adds to Panel's page handler: a bounded URL and a Content-Security-Policy.

* **A bounded URL.**  Panel parses every query value before the page's own
  checks run (``int()`` on a value of digits, ``ast.literal_eval`` on one that
  starts with a bracket); a value of more than 4,300 digits raised inside Panel
  and gave HTTP 500.  :class:`CheckedDocHandler` refuses a query with a value
  longer than :data:`MAX_QUERY_VALUE` characters, or more than
  :data:`MAX_QUERY_FIELDS` fields, before Panel sees it: HTTP 400 and the
  command lines' one-line message as plain text.
* **No inline script but the page's own.**  Every response of the page handler
  carries a Content-Security-Policy whose ``script-src`` admits the page's
  static files and, by a nonce drawn per response, the inline scripts Panel's
  template writes; nothing else.  A script or an event attribute (``onerror=``)
  that reached the document some other way (as user text shown as markup)
  would not run, and Chromium reports the refusal.  This is the second line:
  the first is that user text is never markup (:mod:`stability.app.markup`).
  ``'unsafe-eval'`` stays allowed: BokehJS compiles some of its models'
  code with ``new Function``.
"""

from __future__ import annotations

import re
import secrets
from typing import Any
from urllib.parse import parse_qsl

__all__ = ["MAX_QUERY_VALUE", "MAX_QUERY_FIELDS", "query_problem", "content_security_policy", "add_nonce",
           "checked_doc_handler", "install"]

#: Longest value of one URL query field (characters); a chair's longest number needs about 25.
MAX_QUERY_VALUE = 1000
#: Most fields in one URL query (a chair has 38 fields, plus ``chair`` and ``model``).
MAX_QUERY_FIELDS = 100

_SCRIPT_TAG = re.compile(rb"<script(?=[\s>])")


def query_problem(query: str) -> str | None:
    """Why a URL query is refused before the page is built, or None.

    Parameters
    ----------
    query : str
        The raw query (without ``?``), as the browser sent it.

    Returns
    -------
    str or None
        The one-line message (``error: ...``), or None when every field is within bounds.
    """
    items = parse_qsl(query, keep_blank_values=True)
    if len(items) > MAX_QUERY_FIELDS:
        return (f"error: the URL has {len(items)} query fields; valid: at most {MAX_QUERY_FIELDS} "
                "(a chair's fields, chair= and model=)")
    for key, value in items:
        if len(key) > MAX_QUERY_VALUE or len(value) > MAX_QUERY_VALUE:
            shown = key if len(key) <= 40 else key[:40] + "..."
            return (f"error: URL field {shown!r} has {max(len(key), len(value))} characters; valid: at most "
                    f"{MAX_QUERY_VALUE}")
    return None


def content_security_policy(nonce: str) -> str:
    """The page's Content-Security-Policy header value.

    Parameters
    ----------
    nonce : str
        This response's nonce (base64 characters).

    Returns
    -------
    str
    """
    return "; ".join((
        "default-src 'self'",
        f"script-src 'self' 'nonce-{nonce}' 'unsafe-eval'",
        "style-src 'self' 'unsafe-inline'",
        "img-src 'self' data: blob:",
        "font-src 'self' data:",
        "connect-src 'self' ws: wss:",
        "object-src 'none'",
        "base-uri 'none'",
        "frame-ancestors 'none'",
        "form-action 'self'",
    ))


def add_nonce(page: bytes, nonce: str) -> bytes:
    """``page`` with ``nonce="..."`` on every ``<script`` tag (the template's own; user text never reaches it).

    Parameters
    ----------
    page : bytes
        The HTML page Panel rendered.
    nonce : str

    Returns
    -------
    bytes
    """
    return _SCRIPT_TAG.sub(b'<script nonce="' + nonce.encode("ascii") + b'"', page)


def checked_doc_handler(base: type) -> type:
    """A subclass of Panel's page handler ``base`` that bounds the query and sends the CSP.

    Parameters
    ----------
    base : type
        ``panel.io.server.DocHandler``.

    Returns
    -------
    type
    """

    class CheckedDocHandler(base):
        _nonce = ""

        async def prepare(self) -> Any:
            self._nonce = secrets.token_urlsafe(18)
            self.set_header("Content-Security-Policy", content_security_policy(self._nonce))
            self.set_header("X-Content-Type-Options", "nosniff")
            self.set_header("Referrer-Policy", "no-referrer")
            problem = query_problem(self.request.query)
            if problem is not None:
                self.set_status(400)
                self.set_header("Content-Type", "text/plain; charset=utf-8")
                self.finish(problem + "\n")
                return
            await super().prepare()

        def write(self, chunk: Any) -> None:
            if isinstance(chunk, str):
                chunk = chunk.encode("utf-8")
            if isinstance(chunk, bytes) and self._nonce:
                chunk = add_nonce(chunk, self._nonce)
            super().write(chunk)

    return CheckedDocHandler


def install(server: Any) -> int:
    """Replace Panel's page handler in a not yet started Bokeh ``server`` by :func:`checked_doc_handler`'s.

    Parameters
    ----------
    server : bokeh.server.server.Server

    Returns
    -------
    int
        How many routes were replaced (one per page; 0 would leave the page unprotected, so it raises).
    """
    from panel.io.server import DocHandler

    replaced = 0
    for rule in server._tornado.wildcard_router.rules:
        if isinstance(rule.target, type) and issubclass(rule.target, DocHandler):
            rule.target = checked_doc_handler(rule.target)
            replaced += 1
    if not replaced:
        raise RuntimeError("the explorer's page handler was not found: Panel's server layout changed")
    return replaced
