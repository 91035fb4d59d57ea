"""The documentation's equations render in a browser with no network: MathJax is served with the site.

The explorer review: the site loaded MathJax from a CDN, so offline every equation showed as raw LaTeX
(``\\(x\\)``, ``\\[F_y = a F_z + ... \\tag{4-1}\\]``).  docs/_ext/stability_mathjax.py now copies MathJax into the
site.  This test (marked ``docs``: CI runs it right after the build) serves the built site on 127.0.0.1, opens
pages with equations in Debian's chromium with every request to another host refused, and checks that MathJax
typeset them (``mjx-container`` elements, no raw delimiters left, no request failed or went elsewhere).
"""

from __future__ import annotations

import functools
import http.server
import threading
from pathlib import Path

import pytest
from explorer_server import chromium

ROOT = Path(__file__).resolve().parents[1]
BUILT = ROOT / "docs" / "_build" / "html"

#: A page with inline and displayed equations (Sphinx loads MathJax only on pages with math).
PAGE = "physics.html"


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


@pytest.fixture(scope="module")
def site():
    if not (BUILT / "physics.html").exists():
        pytest.skip("no built site (python -m sphinx -b html docs docs/_build/html)")
    handler = functools.partial(_Quiet, directory=str(BUILT))
    httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=httpd.serve_forever, daemon=True).start()
    try:
        yield f"http://127.0.0.1:{httpd.server_address[1]}/"
    finally:
        httpd.shutdown()


@pytest.mark.docs
def test_the_site_ships_mathjax_and_names_no_cdn():
    if not (BUILT / "physics.html").exists():
        pytest.skip("no built site")
    assert (BUILT / "_static" / "mathjax" / "tex-chtml.js").exists()
    assert 'src="_static/mathjax/tex-chtml.js"' in (BUILT / PAGE).read_text()
    for page in BUILT.rglob("*.html"):
        assert "cdn.jsdelivr.net" not in page.read_text(), page


@pytest.mark.docs
def test_equations_render_without_the_network(site):
    pytest.importorskip("playwright")
    from playwright.sync_api import sync_playwright

    path = chromium()
    if path is None:
        pytest.skip("no chromium on this machine")
    outside, failed = [], []
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=path, args=["--no-sandbox"])
        try:
            tab = browser.new_page()

            def route(r):
                if r.request.url.startswith(site):
                    r.continue_()
                else:
                    outside.append(r.request.url)
                    r.abort()

            tab.route("**/*", route)
            tab.on("requestfailed", lambda r: failed.append(r.url))
            tab.goto(site + PAGE)
            tab.locator("mjx-container").first.wait_for(timeout=60_000)
            tab.wait_for_load_state("networkidle")
            text = tab.locator("article").inner_text()
            typeset = tab.locator("mjx-container").count()
        finally:
            browser.close()
    assert typeset > 0
    assert "\\(" not in text and "\\[" not in text and "\\tag" not in text, text[:500]
    assert not [u for u in failed if u.startswith(site)], failed
    assert not [u for u in outside if "mathjax" in u.lower() or "jsdelivr" in u], outside
