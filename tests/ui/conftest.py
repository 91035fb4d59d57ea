"""Browser tests of the explorer (marked ``ui``): a served page driven by playwright in Debian's chromium.

The browser is the system's chromium (``STABILITY_CHROMIUM`` or ``chromium`` on
PATH), given to playwright as its executable: nothing is downloaded.
Screenshots go to ``STABILITY_UI_ARTIFACTS`` (default a folder under the
system's temporary directory; its path is printed).  Any console error or
uncaught page error fails the test that caused it.
"""

from __future__ import annotations

import os
import pathlib
import tempfile

import pytest
from explorer_server import chromium, serve

pytest.importorskip("panel")
pytest.importorskip("playwright")


@pytest.fixture(scope="session")
def browser_type_launch_args(browser_type_launch_args):
    """pytest-playwright's launch options with Debian's chromium (never a downloaded browser)."""
    path = chromium()
    if path is None:
        pytest.skip("no chromium on this machine (apt-get install chromium, or set STABILITY_CHROMIUM)")
    return {**browser_type_launch_args, "executable_path": path, "args": ["--no-sandbox"]}


@pytest.fixture(scope="session")
def browser_context_args(browser_context_args):
    """A viewport large enough for the editor and the plots side by side; downloads accepted."""
    return {**browser_context_args, "viewport": {"width": 1500, "height": 1150}, "accept_downloads": True}


@pytest.fixture(scope="session")
def artifacts() -> pathlib.Path:
    """Folder for the screenshots (``STABILITY_UI_ARTIFACTS``; printed)."""
    d = pathlib.Path(os.environ.get("STABILITY_UI_ARTIFACTS") or
                     pathlib.Path(tempfile.gettempdir()) / "stability-ui-artifacts")
    d.mkdir(parents=True, exist_ok=True)
    print(f"\nscreenshots: {d}")
    return d


@pytest.fixture(scope="session")
def app_url():
    """``python -m stability.app --port 0 --no-browser``, running for the session; its URL."""
    with serve() as url:
        yield url


@pytest.fixture
def console_errors(page):
    """Collect the page's console errors and uncaught errors; the test fails if any occurred."""
    errors: list[str] = []
    page.on("console", lambda m: errors.append(f"console {m.type}: {m.text}") if m.type == "error" else None)
    page.on("pageerror", lambda e: errors.append(f"page error: {e}"))
    yield errors
    assert not errors, errors


@pytest.fixture
def explorer(page, app_url, console_errors):
    """Open the explorer; returns ``open(query="")`` that loads it (waits for the linear views)."""
    page.context.set_default_timeout(90_000)

    def open_page(query: str = "", target=None):
        p = target or page
        p.goto(app_url + (f"?{query}" if query else ""))
        p.locator(".summary table").wait_for()
        return p

    return open_page
