"""The Tracking tab in Chromium: a scripted operator of known delay runs the critical tracking task, and the page
recovers that delay; the result reaches the chair's TOML download and the commands' ``--chair``.

The operator is the delayed-loop model's (:func:`stability.driver.tracking.operator_gain`: the most stable
proportional gain at the instability shown), played through the browser's Gamepad API (``navigator.getGamepads``
replaced before the page loads): at each step the page reads the pad, and the pad answers with
``-k(lambda) x_seen``, where ``x_seen`` is the marker as the page drew it ``tau`` earlier (the latest animation
frame at or before ``now - tau``, to the nearest frame: +/- 8 ms).  So the whole loop runs in real time: the
animation frames, the 60 Hz steps, the input path, the trials' round trip to the server and the server's
judgement.

Error model: the escape factor's trial-to-trial spread is about 10 % (its disturbance phases, one trial), so the
mean of five scored trials scatters by about 4.5 %; the escape factor's mean over the calibration population
differs from this operator's (gain 1) by about 3 %; frame timing adds a frame's worth of delay at worst (17 ms:
6 % of 0.3 s, when frames drop).  The test asks for 10 %, the brief's requirement (issue 37): that is the measure
the task must meet, not a margin of 100 over what is observed.
"""

from __future__ import annotations

import contextlib
import io
import json
import re

import pytest

from stability.chair import user_table
from stability.critical_speed import main as critical_speed_main
from stability.driver import Driver
from stability.driver.tracking import operator_gain_table

pytestmark = pytest.mark.ui

_OPERATOR = r"""
(() => {
  const op = __OPERATOR__;
  const interp = (th) => {
    const xs = op.theta, ys = op.ktau;
    if (th <= xs[0]) return ys[0];
    if (th >= xs[xs.length - 1]) return ys[ys.length - 1];
    let i = 1; while (xs[i] < th) i++;
    return ys[i - 1] + (ys[i] - ys[i - 1]) * (th - xs[i - 1]) / (xs[i] - xs[i - 1]);
  };
  navigator.getGamepads = function () {
    const T = window.stabilityTracking;
    let a = 0;
    if (T) {
      const s = T.snapshot();
      const now = performance.now(), want = now - 1000 * op.tau + 8;
      let seen = 0;
      for (let i = s.drawn.length - 1; i >= 0; i--) { if (s.drawn[i][0] <= want) { seen = s.drawn[i][1]; break; } }
      const k = interp(s.lambda * op.tau) / op.tau;
      a = Math.max(-1, Math.min(1, -k * seen / s.input_limit));
    }
    return [{connected: true, axes: [a, 0], buttons: [], id: 'scripted operator', index: 0,
             mapping: 'standard', timestamp: performance.now()}];
  };
})();
"""


def _operator_script(tau: float) -> str:
    theta, ktau = operator_gain_table()
    return _OPERATOR.replace("__OPERATOR__", json.dumps({"tau": tau, "theta": theta.tolist(),
                                                          "ktau": ktau.tolist()}))


@pytest.mark.parametrize("tau", [0.3, 0.5])
def test_a_scripted_operator_of_known_delay_is_measured(page, explorer, artifacts, tmp_path, tau):
    page.add_init_script(_operator_script(tau))
    explorer("chair=revised")
    page.get_by_text("Tracking", exact=True).click()
    start = page.locator(".ctt-start")
    start.wait_for()
    result = page.locator(".tracking-result")
    for _ in range(12):                                   # 1 practice + at most 10 scored trials
        page.wait_for_function("() => { const s = window.stabilityTracking && window.stabilityTracking.snapshot();"
                               " return s && (s.ready || !s.planned); }", timeout=120_000)
        if not page.evaluate("() => window.stabilityTracking.snapshot().planned"):
            break                                         # the protocol is complete
        start.click()
        page.wait_for_function("() => window.stabilityTracking.snapshot().running")
        page.wait_for_function("() => !window.stabilityTracking.snapshot().running", timeout=120_000)
    page.screenshot(path=artifacts / f"tracking-{tau}.png", full_page=True)
    assert result.count(), page.locator(".tracking-text").inner_text() + page.locator(".ctt-status").inner_text()
    text = result.inner_text()
    m = re.search(r"tau_e = ([0-9.]+) \+/- ([0-9.]+) s", text)
    assert m, text
    measured, spread = float(m.group(1)), float(m.group(2))
    print(f"\ntau {tau}: measured {measured} +/- {spread} s")
    # error model (the module docstring's): the five scored trials' mean has a standard error of about 4.5 %, the
    # calibration population's offset 3 %, frame timing up to 6 % of 0.3 s; 10 % is the brief's requirement
    assert measured == pytest.approx(tau, rel=0.10), text
    assert 0 < spread < 0.5 * measured
    rows = page.locator(".tracking-trials tr").all_inner_texts()
    assert sum("valid" in r and "invalid" not in r for r in rows) >= 3

    page.get_by_text("Downloads", exact=True).click()   # the chair file carries the user, read back by --chair
    with page.expect_download() as dl:
        page.locator(".download-toml button").click()
    path = tmp_path / "chair.toml"
    dl.value.save_as(path)
    table = user_table(str(path))
    saved = re.search(r"reaction_time_s = ([0-9.]+)", text)
    assert saved and table is not None and table["reaction_time_s"] == float(saved.group(1))
    assert Driver.from_mapping(table).reaction_time_s == table["reaction_time_s"]
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        assert critical_speed_main(["--chair", str(path)]) == 0
    assert (f"Driver (reaction time {table['reaction_time_s']:g} s, from critical tracking task: "
            in out.getvalue()), out.getvalue()



@pytest.mark.parametrize("width, height", [(1280, 720), (1024, 768)])
def test_the_tracking_tab_fits_a_laptop_and_a_tablet(page, explorer, artifacts, width, height):
    """As tests/ui/test_app_layout.py checks the other tabs: no sideways scroll, the track inside the window."""
    page.set_viewport_size({"width": width, "height": height})
    explorer()
    page.get_by_text("Tracking", exact=True).click()
    canvas = page.locator(".ctt-canvas")
    canvas.wait_for()
    page.wait_for_timeout(500)
    page.screenshot(path=artifacts / f"layout-{width}x{height}-tracking.png")
    box = canvas.bounding_box()
    assert box is not None and box["x"] >= 0 and box["x"] + box["width"] <= width + 0.5 and box["width"] >= 300
    assert page.evaluate("() => document.documentElement.scrollWidth <= document.documentElement.clientWidth")
    assert page.locator(".ctt-status").inner_text().startswith("next: practice trial 1")
