"""The explorer opens a wheel layout preset (``?chair=mid-wheel-drive``) and shows what the layout commands compute.

Checked in chromium at a laptop's 1280x720 and a tablet's 1024x768 (every tab of the mid-wheel-drive base), failing
on any console error (the ``console_errors`` fixture): the header names the layout; the Stability vs speed tab's text is what ``python -m stability.critical_speed --chair
NAME`` prints (run here as a command: an independent path from the page's in-process call); the Geometry tab's is
what ``python -m stability.tipping --chair NAME`` prints; the Nonlinear and Trail window tabs show the critical
impulse forward and in reverse and a shimmy table per caster row; Advice, Compare and Power assist show what
``advise``, ``compare`` (against the other drive layouts) and ``assist`` print, each read here from the command run
independently; the Downloads tab's layout file reads back as the preset and its JSON is what ``critical_speed
--json`` prints; Tracking says in one line that it does not apply; the top view draws every contact; no sideways
scroll.  A screenshot of each tab goes to
``STABILITY_UI_ARTIFACTS`` (``wheel-layout-<name>-<tab>.png``).
"""

from __future__ import annotations

import re
import subprocess
import sys

import pytest

pytestmark = pytest.mark.ui

_SCROLL = "() => ({scroll: document.documentElement.scrollWidth, client: document.documentElement.clientWidth})"


def _command(*args: str) -> str:
    done = subprocess.run([sys.executable, "-m", *args], capture_output=True, text=True, check=True, timeout=600)
    return done.stdout.rstrip()


def _open(page, app_url, query: str, size: tuple[int, int] = (1280, 720)):
    page.context.set_default_timeout(90_000)
    page.set_viewport_size({"width": size[0], "height": size[1]})
    page.goto(f"{app_url}?{query}")
    page.locator(".summary pre", has_text="growth rate").wait_for()


def _tab(page, tab: str) -> None:
    page.get_by_text(tab, exact=True).click()


def _shot(page, artifacts, name: str, tab: str) -> None:
    page.wait_for_timeout(500)                                      # the figures' first paint
    page.screenshot(path=artifacts / f"wheel-layout-{name}-{re.sub(r'[^a-z]+', '-', tab.lower())}.png")
    box = page.evaluate(_SCROLL)
    assert box["scroll"] <= box["client"], (tab, box)               # no sideways scroll at this width


@pytest.mark.parametrize("size", [(1280, 720), (1024, 768)], ids=["laptop", "tablet"])
def test_mid_wheel_drive_every_tab(page, app_url, console_errors, artifacts, size, tmp_path):
    from stability.app.layout_page import NOT_FOR_LAYOUTS
    from stability.app.page import TAB_NAMES
    from stability.layout.io import load_layout
    from stability.layout.presets import layout_preset

    name = "mid-wheel-drive"
    _open(page, app_url, f"chair={name}", size)
    page.locator(".chair-title", has_text=f"{name} (wheel layout: 2 fixed wheels, 4 casters").wait_for()
    # the summary equals the command line's output, character for character
    assert page.locator(".summary pre").inner_text().rstrip() == _command("stability.critical_speed", "--chair", name)
    # the top view is in the page (its points: test_top_view_draws_every_contact)
    assert page.evaluate("() => [...Bokeh.documents[0].all_models].some(m => typeof m.text === 'string' && "
                         "m.text.startsWith('mid-wheel-drive from above'))")
    for tab in TAB_NAMES:
        _tab(page, tab)
        if tab == "Geometry":
            text = page.locator(".layout-geometry pre", has_text="smallest").inner_text(timeout=240_000)
            assert text.split("\n\n", 1)[1].rstrip() == _command("stability.tipping", "--chair", name)
        elif tab == "Nonlinear":
            text = page.locator(".layout-nonlinear pre", has_text="kick:").inner_text(timeout=600_000)
            assert "-0.75 m/s reverse" in text and "+0.75 m/s forward" in text, text
        elif tab == "Trail window":
            text = page.locator(".layout-trail-window pre", has_text="caster shimmy").inner_text(timeout=600_000)
            assert "(front left)" in text and "(rear left)" in text, text       # one table per caster row
        elif tab in ("Advice", "Compare", "Power assist"):
            from stability.app.layout_page import command_line

            cls = f".layout-{tab.lower().replace(' ', '-')} pre"
            text = page.locator(cls, has_text="$ python -m").inner_text(timeout=600_000)
            head, body = text.split("\n\n", 1)
            assert head == "$ python -m " + " ".join(command_line(tab, name))
            if size == (1280, 720):                  # the command's own output, once (the advisor's minute)
                assert body.split("\n\n")[0] == _command(*command_line(tab, name)).split("\n\n")[0]
        elif tab == "Downloads":
            with page.expect_download() as dl:
                page.locator(".download-toml button").click()
            path = tmp_path / f"{name}.toml"
            dl.value.save_as(path)
            assert load_layout(path) == layout_preset(name)
            with page.expect_download() as dl:
                page.locator(".download-json button").click()
            dl.value.save_as(tmp_path / "results.json")
            assert (tmp_path / "results.json").read_text() == _command("stability.critical_speed", "--chair", name,
                                                                       "--json") + "\n"
        elif tab != "Stability vs speed":
            page.locator(".not-for-layouts", has_text=NOT_FOR_LAYOUTS[tab][:30]).wait_for()
        _shot(page, artifacts, f"{name}-{size[0]}x{size[1]}", tab)


@pytest.mark.parametrize("name", ["power-fwd-base", "power-rwd-base"])
def test_the_other_layouts_open(page, app_url, console_errors, artifacts, name):
    _open(page, app_url, f"chair={name}&trail=0.05")
    page.locator(".chair-title", has_text=f"{name} (wheel layout: 2 fixed wheels, 2 casters").wait_for()
    # a short form's field in the link is named as ignored, as text
    page.locator(".app-message", has_text="ignored for a wheel layout (its wheels are set in a [[wheel]] chair "
                                          "file, not by fields): trail").wait_for()
    assert page.locator(".summary pre").inner_text().rstrip() == _command("stability.critical_speed", "--chair", name)
    _shot(page, artifacts, name, "Stability vs speed")
    # the links between layouts and back to the short form
    page.locator(".layout-about a", has_text="mid-wheel-drive").click()
    page.wait_for_function("() => location.search.includes('chair=mid-wheel-drive')")
    page.locator(".chair-title", has_text="mid-wheel-drive").wait_for()
    page.locator(".layout-about a", has_text="ej-premier").click()
    page.locator(".summary table").wait_for()                      # the field editor's page
    page.get_by_text("Wheel layouts", exact=True).click()          # its card of links to the layouts
    page.locator(".layout-links a", has_text=name).click()
    page.locator(".chair-title", has_text=f"{name} (wheel layout").wait_for()


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base", "power-rwd-base"])
def test_top_view_draws_every_contact(name):
    """Every wheel, pin and caster contact of the preset, and the c.g., at its body coordinates (left up)."""
    from bokeh.models import GlyphRenderer

    from stability.app.layout_page import top_view
    from stability.layout.presets import layout_preset
    from stability.layout.statics import contacts

    layout = layout_preset(name)
    fig = top_view(layout)
    drawn = {(r.glyph.marker, round(x, 9), round(y, 9)) for r in fig.select(GlyphRenderer)
             if hasattr(r.glyph, "marker") for x, y in zip(r.data_source.data["x"], r.data_source.data["y"],
                                                           strict=True)}
    want = {("square", round(w.x, 9), round(-w.y, 9)) for w in layout.wheels}
    want |= {("circle", round(c.x, 9), round(-c.y, 9)) for c in layout.casters}
    want |= {("triangle", round(x, 9), round(-y, 9)) for label, x, y, _ in contacts(layout) if label.startswith("c")}
    want.add(("circle_cross", 0.0, 0.0))
    assert drawn == want
