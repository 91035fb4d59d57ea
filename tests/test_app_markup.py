"""User text is never markup in the explorer: :mod:`stability.app.markup` and :mod:`stability.app.security`.

The independent judge is a real parser: Python's ``html.parser`` reads what a
browser would build from the text (which elements and attributes), and
``markdown-it`` (the renderer Panel's Markdown pane uses) is applied when the
``app`` extra is installed.
"""

from __future__ import annotations

import html
from html.parser import HTMLParser

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from stability.app.markup import MAX_SHOWN, literal, pre
from stability.app.security import MAX_QUERY_FIELDS, MAX_QUERY_VALUE, add_nonce, content_security_policy, query_problem

HOSTILE = [
    "<script>alert(1)</script>",
    "<img src=x onerror=alert(2)>",
    "<svg onload=alert(3)>",
    '"><script>alert(4)</script>',
    "[click](javascript:alert(5))",
    "<a href='javascript:alert(6)'>x</a>",
    "```\n<script>alert(7)</script>\n```",
    "</pre><script>alert(8)</script><pre>",
    "&lt;script&gt;alert(9)&lt;/script&gt;",
    "| a | b |\n|---|---|\n| <b>x</b> | y |",
    "**bold** _em_ # heading",
    "<style>body{display:none}</style>",
    "<iframe srcdoc='<script>alert(10)</script>'>",
]


class _Tree(HTMLParser):
    """The elements, attributes and text a browser would build from an HTML fragment."""

    def __init__(self) -> None:
        super().__init__(convert_charrefs=True)
        self.tags: list[str] = []
        self.attrs: list[tuple[str, str | None]] = []
        self.text: list[str] = []

    def handle_starttag(self, tag, attrs):
        self.tags.append(tag)
        self.attrs.extend(attrs)

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)

    def handle_data(self, data):
        self.text.append(data)


def _tree(fragment: str) -> _Tree:
    t = _Tree()
    t.feed(fragment)
    t.close()
    return t


def _shown(text: str) -> str:
    """What :func:`literal` promises to show: the text on one line (white space runs as one space), without
    control characters (unicode category Cc)."""
    return "".join(c for c in " ".join(text.split()) if not (ord(c) < 32 or 127 <= ord(c) < 160))


@pytest.mark.parametrize("text", HOSTILE)
def test_literal_is_text_in_html(text):
    t = _tree(literal(text))
    assert t.tags == [] and t.attrs == []
    assert "".join(t.text) == _shown(text)


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.text(max_size=200))
def test_literal_of_any_text_is_that_text_in_html(text):
    t = _tree(literal(text))
    assert t.tags == [] and t.attrs == []
    assert "".join(t.text) == _shown(text)


@pytest.mark.parametrize("text", HOSTILE)
def test_literal_is_text_in_markdown(text):
    """Through markdown-it (Panel's renderer, gfm-like with tables and linkify): one paragraph of that text."""
    markdown_it = pytest.importorskip("markdown_it")
    md = markdown_it.MarkdownIt("gfm-like").enable("table")
    t = _tree(md.render(literal(text)))
    assert t.tags == ["p"] and t.attrs == []
    assert "".join(t.text).strip() == _shown(text)


def test_literal_bounds_what_it_shows():
    long = "9" * 20_000
    out = _tree(literal(long))
    assert "".join(out.text) == "9" * MAX_SHOWN + "... (20000 characters)"


@pytest.mark.parametrize("text", HOSTILE)
def test_pre_is_one_block_of_that_text(text):
    t = _tree(pre(text))
    assert t.tags == ["pre"] and t.attrs == [("class", "cli-text")]
    assert "".join(t.text) == text


@pytest.mark.parametrize("query, fragment", [
    ("chair=revised&s1=" + "9" * 5000, "URL field 's1' has 5000 characters; valid: at most 1000"),
    ("name=" + "x" * (MAX_QUERY_VALUE + 1), f"has {MAX_QUERY_VALUE + 1} characters"),
    ("&".join(f"k{i}=1" for i in range(MAX_QUERY_FIELDS + 1)), f"{MAX_QUERY_FIELDS + 1} query fields"),
])
def test_query_problem_names_the_field_and_the_bound(query, fragment):
    msg = query_problem(query)
    assert msg is not None and msg.startswith("error: ") and fragment in msg and "\n" not in msg


@pytest.mark.parametrize("query", ["", "chair=revised&trail=0.06&s1=0.25",
                                   "name=" + "x" * MAX_QUERY_VALUE,
                                   "&".join(f"k{i}=1" for i in range(MAX_QUERY_FIELDS))])
def test_query_problem_accepts_queries_within_the_bounds(query):
    assert query_problem(query) is None


def test_the_policy_admits_no_inline_script_but_the_nonce():
    policy = dict(d.strip().split(" ", 1) for d in content_security_policy("abc123").split(";"))
    script = policy["script-src"].split()
    assert "'unsafe-inline'" not in script and "'nonce-abc123'" in script and "'strict-dynamic'" not in script
    assert policy["object-src"] == "'none'" and policy["base-uri"] == "'none'"
    assert policy["frame-ancestors"] == "'none'"


def test_add_nonce_marks_every_script_tag_and_nothing_else():
    page = (b'<html><script type="application/json">{}</script><script src="a.js"></script>'
            b"<script>x()</script><scripts-not-a-tag><p>script</p></html>")
    out = add_nonce(page, "n0")
    assert out.count(b'<script nonce="n0"') == 3 and out.count(b"<script") == 4
    assert html.unescape(out.decode()).count("scripts-not-a-tag") == 1
