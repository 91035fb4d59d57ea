"""The explorer in a real browser: load, edit, bad values, downloads and reload, shared URLs, independent tabs."""

from __future__ import annotations

import contextlib
import io
import re

import pytest

from stability import chair as chair_mod
from stability.app.state import AppState
from stability.critical_speed import main as critical_speed_main

pytestmark = pytest.mark.ui


def printed_rate(chair: str = "ej-premier", *sets: str, speed: str = "0.75") -> str:
    """The growth rate ``python -m stability.critical_speed`` prints at ``speed`` (its text, 4 decimals)."""
    out = io.StringIO()
    argv = ["--chair", chair] + [a for s in sets for a in ("--set", s)]
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert critical_speed_main(argv) == 0
    for line in out.getvalue().splitlines():
        parts = line.split()
        if len(parts) == 4 and parts[0] == speed:
            return parts[1]
    raise AssertionError(out.getvalue())


def cli_message(*sets: str) -> str:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        assert critical_speed_main([a for s in sets for a in ("--set", s)]) == 2
    return err.getvalue().strip()


def row(page, speed: str = "0.75"):
    """The summary table's row whose first cell is ``speed`` (m/s) exactly (a doubling time may contain it)."""
    return page.locator(".summary tr").filter(
        has=page.locator("td:first-child", has_text=re.compile("^" + re.escape(speed) + "$"))).first


def set_field(page, name: str, value: str) -> None:
    box = page.locator(f".field-{name} input")
    box.fill(value)
    box.press("Enter")


def test_edit_shows_the_growth_rate_critical_speed_prints(page, explorer, artifacts):
    explorer()
    assert row(page).locator("td").nth(1).inner_text() == printed_rate()
    page.screenshot(path=artifacts / "explorer.png")
    set_field(page, "trail", "0.05")
    want = printed_rate("ej-premier", "trail=0.05")
    row(page).locator("td", has_text=want).wait_for()
    # the URL follows the chair (waited for: the address may arrive in a browser update of its own)
    page.wait_for_function("() => location.search.includes('chair=ej-premier&trail=0.05')")
    page.screenshot(path=artifacts / "edited.png")


def test_bad_value_shows_the_message_and_keeps_the_chair(page, explorer, artifacts):
    explorer()
    before = row(page).inner_text()
    for text in ("0.9", "abc"):
        set_field(page, "trail", text)
        msg = page.locator(".error-trail div").filter(has_text=f"trail={text}" if text == "0.9" else "trail needs")
        msg.wait_for()
        assert msg.first.inner_text().replace("\n", " ") == cli_message(f"trail={text}")
        assert row(page).inner_text() == before                # the views keep the last valid chair
    page.locator(".error-trail").evaluate("e => e.scrollIntoView({block: 'center'})")
    page.screenshot(path=artifacts / "bad-value.png")
    set_field(page, "trail", "0.07")                            # a good value clears it
    row(page).locator("td", has_text=printed_rate("ej-premier", "trail=0.07")).wait_for()
    assert page.locator(".error-trail div").filter(has_text="error").count() == 0


def test_download_the_chair_and_load_it_again(page, explorer, tmp_path, artifacts):
    explorer("chair=revised&trail=0.055")
    page.get_by_text("Downloads", exact=True).click()
    with page.expect_download() as dl:
        page.locator(".download-toml button").click()
    path = tmp_path / "mine.toml"
    dl.value.save_as(path)
    want = AppState.from_query("chair=revised&trail=0.055").chair
    assert chair_mod.load(path) == want
    explorer()                                                  # a fresh page with the default chair
    page.locator(".upload-chair input[type=file]").set_input_files(str(path))
    page.locator(".chair-title", has_text="base file:mine.toml").wait_for()
    row(page).locator("td", has_text=printed_rate(str(path))).wait_for()
    assert page.locator(".field-trail input").input_value() == "0.055"


def test_shared_url_opens_that_chair(page, explorer, artifacts):
    explorer("chair=revised&trail=0.055&s1=0.25")
    assert page.locator(".field-trail input").input_value() == "0.055"
    assert page.locator(".field-s1 input").input_value() == "0.25"
    row(page).locator("td", has_text=printed_rate("revised", "trail=0.055", "s1=0.25")).wait_for()
    page.screenshot(path=artifacts / "shared-url.png")


def test_two_tabs_are_independent(page, explorer, browser, browser_context_args):
    explorer()
    second = browser.new_context(**browser_context_args)      # another window: a session of its own
    second.set_default_timeout(180_000)
    try:
        other = explorer(target=second.new_page())
        set_field(page, "trail", "0.05")
        row(page).locator("td", has_text=printed_rate("ej-premier", "trail=0.05")).wait_for()
        set_field(other, "m", "80")
        row(other).locator("td", has_text=printed_rate("ej-premier", "m=80")).wait_for()
        assert other.locator(".field-trail input").input_value() == "0.08"
        assert page.locator(".field-m input").input_value() == "95.0"
        assert row(page).locator("td").nth(1).inner_text() == printed_rate("ej-premier", "trail=0.05")
    finally:
        second.close()


def test_tabs_geometry_nonlinear_compare(page, explorer, artifacts):
    explorer()
    page.get_by_text("Geometry", exact=True).click()
    page.wait_for_timeout(500)
    page.screenshot(path=artifacts / "geometry.png")
    page.get_by_text("Nonlinear", exact=True).click()
    page.locator(".nonlinear-text", has_text="Critical impulse").wait_for(timeout=240_000)
    page.screenshot(path=artifacts / "nonlinear.png")
    page.get_by_text("Trail window", exact=True).click()
    page.locator(".trail-text", has_text="Shimmy-free trail").wait_for(timeout=240_000)
    page.screenshot(path=artifacts / "trail.png")
    page.locator(".pin button").click()
    set_field(page, "trail", "0.05")
    page.wait_for_function("() => location.search.includes('trail=0.05')")   # the stability tab is not shown
    page.get_by_text("Compare", exact=True).click()
    page.locator(".compare-text", has_text="trail").wait_for(timeout=120_000)
    page.screenshot(path=artifacts / "compare.png")


def test_power_chair_assist_tab(page, explorer, artifacts):
    explorer("chair=power-fwd")
    page.get_by_text("Power assist", exact=True).click()
    page.locator(".run-assist button").click()
    page.locator(".assist-text", has_text="Motor assist (gyro LQR) for power-fwd").wait_for(timeout=300_000)
    page.screenshot(path=artifacts / "assist.png")


def test_apply_the_advisors_recommendation(page, explorer, artifacts):
    explorer()
    page.get_by_text("Advice", exact=True).click()
    page.locator(".run-advice button").click()
    page.locator(".advice-text", has_text="VERDICT").wait_for(timeout=600_000)
    button = page.locator(".apply-1 button")
    label = button.inner_text()
    page.screenshot(path=artifacts / "advice.png")
    button.click()
    page.locator(".chair-title", has_text="modified").wait_for()
    from stability.advise import advise

    rec = advise(chair_mod.preset("ej-premier")).recommendations[0].candidate
    assert rec.label[:60] in label
    for name, value in rec.fields.items():
        assert page.locator(f".field-{name} input").input_value() == repr(value)
