"""The explorer's Tracking tab: the critical tracking task that measures the user (:mod:`stability.driver.tracking`).

The plant runs in the browser (:class:`TrackingTask`, JavaScript in a Panel ``ReactiveHTML``): one step of
``x' = lambda x + u + d`` every :data:`stability.driver.tracking.FRAME_S` (60 Hz) from the animation frames, the
input read at every step from the keyboard (left/right arrows or A/D), the mouse over the track (a position
stick: the pointer's offset from the centre is the deflection) or the first gamepad's first axis (the browser's
Gamepad API), whichever moved last.  When the marker leaves the track the browser sends the trial (its starting
and final ``lambda``, duration, how far the input moved, the device) to the server, which judges it
(:func:`stability.driver.protocol.judge`), plans the next trial (:func:`~stability.driver.protocol.next_trial`)
and, after enough valid scored trials, gives ``tau_e`` with its spread; the chair's TOML download then carries it
as a ``[user]`` table (``reaction_time_s``), which every command's ``--chair`` reads.

Everything the browser sends is checked (:meth:`stability.driver.protocol.TrialRecord.from_mapping`); the user's
note is shown through :func:`stability.app.markup.literal` and written to TOML as an escaped string.  The
component's template holds no user text.  ``window.stabilityTracking`` exposes the task's state (offset, lambda,
the drawn offsets with their times) for scripted operators (the browser tests).
"""

from __future__ import annotations

from typing import Any

import panel as pn
import param
from panel.reactive import ReactiveHTML

from stability.app.markup import literal
from stability.app.widgets import widget
from stability.driver.protocol import TrackingResult, TrialRecord, next_trial, tracking_result
from stability.driver.tracking import MIN_VALID, PRACTICE_TRIALS, SCORED_TRIALS, browser_config

__all__ = ["TrackingTask", "TrackingTab", "MAX_TRIALS"]

#: Most trials one session keeps (the protocol needs at most ``PRACTICE_TRIALS + 2 SCORED_TRIALS``).
MAX_TRIALS = 100

_RENDER = r"""
state.cfg = data.config;
state.ctx = canvas.getContext('2d');
state.x = 0; state.lam = 0; state.k = 0; state.running = false; state.v = 0; state.key = 0;
state.mouse = null; state.pad = null; state.device = 'keyboard'; state.drawn = [];
state.onkey = (e, down) => {
  const dir = (e.key === 'ArrowLeft' || e.key === 'a' || e.key === 'A') ? -1 :
              (e.key === 'ArrowRight' || e.key === 'd' || e.key === 'D') ? 1 : 0;
  if (dir !== 0) { state.keys[dir] = down; state.device = 'keyboard'; e.preventDefault(); }
  else if (down && e.key === ' ' && !state.running && data.plan && data.plan.kind) {
    e.preventDefault(); self.start();
  }
};
state.keys = {'-1': false, '1': false};
state.kd = (e) => state.onkey(e, true);
state.ku = (e) => state.onkey(e, false);
window.addEventListener('keydown', state.kd);
window.addEventListener('keyup', state.ku);
canvas.addEventListener('mousemove', (e) => {
  const r = canvas.getBoundingClientRect();
  state.mouse = Math.max(-1, Math.min(1, (e.clientX - r.left - r.width / 2) / (r.width / 2)));
  state.device = 'mouse';
});
canvas.addEventListener('mouseleave', () => { state.mouse = null; });
window.stabilityTracking = {
  snapshot: () => ({running: state.running, x: state.x, lambda: state.lam, steps: state.k,
                    drawn: state.drawn.slice(), input_limit: state.cfg.input_limit,
                    planned: !!(data.plan && data.plan.kind), ready: !state.running && !start.disabled}),
  start: () => self.start(),
};
self.draw();
self.plan();
"""

_START = r"""
if (state.running || !data.plan || !data.plan.kind) return;
state.x = 0; state.k = 0; state.acc = 0; state.last = null; state.v = 0;
state.vmin = Infinity; state.vmax = -Infinity; state.drawn = [];
state.phases = state.cfg.disturbance_ratios.map(() => 2 * Math.PI * Math.random());
state.trial = data.plan;
state.lam = data.plan.lambda_start_1_s;
state.running = true;
box.focus();
status.textContent = 'running: keep the marker centred';
const frame = (now) => {
  if (!state.running) return;
  const cfg = state.cfg, dt = cfg.frame_s, plan = state.trial;
  if (state.last === null) state.last = now - 1000 * dt;
  state.acc += Math.min(now - state.last, 250) / 1000;
  state.last = now;
  while (state.acc >= dt - 1e-9 && state.running) {
    state.acc -= dt;
    const t = state.k * dt;
    const tc = 1 / plan.lambda_start_1_s - plan.rate_s_per_s * t;
    const lam = tc > 1 / cfg.lambda_max ? 1 / tc : cfg.lambda_max;
    const v = self.input();
    state.vmin = Math.min(state.vmin, v); state.vmax = Math.max(state.vmax, v);
    let d = 0;
    const l0 = plan.lambda_start_1_s;
    for (let i = 0; i < cfg.disturbance_ratios.length; i++) {
      d += cfg.disturbance_amplitude_ratio * l0 * Math.sin(cfg.disturbance_ratios[i] * l0 * t + state.phases[i]);
    }
    const e = Math.exp(lam * dt);
    state.x = e * state.x + (e - 1) / lam * (cfg.input_limit * v + d);
    state.k += 1;
    state.lam = lam;
    if (Math.abs(state.x) > cfg.limit) {
      state.running = false;
      start.disabled = true;
      data.record = {kind: plan.kind, lambda_start_1_s: plan.lambda_start_1_s, lambda_c_1_s: lam,
                     duration_s: state.k * dt, input_range: Math.max(0, state.vmax - state.vmin),
                     device: state.device};
      status.textContent = 'control lost at lambda = ' + lam.toFixed(3) + ' 1/s after ' +
                           (state.k * dt).toFixed(1) + ' s';
    }
  }
  state.drawn.push([now, state.x]);
  if (state.drawn.length > 600) state.drawn.splice(0, state.drawn.length - 600);
  self.draw();
  if (state.running) state.raf = requestAnimationFrame(frame);
};
state.raf = requestAnimationFrame(frame);
"""

_INPUT = r"""
let pad = null;
if (navigator.getGamepads) {
  for (const g of navigator.getGamepads()) { if (g && g.connected && g.axes && g.axes.length) { pad = g; break; } }
}
if (pad !== null) {
  const a = Math.max(-1, Math.min(1, Number(pad.axes[0]) || 0));
  if (state.pad === null || Math.abs(a - state.pad) > 1e-6) state.device = 'gamepad';
  state.pad = a;
}
const dir = (state.keys['1'] ? 1 : 0) - (state.keys['-1'] ? 1 : 0);
const dt = state.cfg.frame_s;
if (dir !== 0) state.key = Math.max(-1, Math.min(1, state.key + 3 * dt * dir));
else state.key = Math.abs(state.key) <= 6 * dt ? 0 : state.key - 6 * dt * Math.sign(state.key);
if (state.device === 'gamepad' && state.pad !== null) state.v = state.pad;
else if (state.device === 'mouse' && state.mouse !== null) state.v = state.mouse;
else if (state.device === 'keyboard') state.v = state.key;
else state.v = 0;
return state.v;
"""

_DRAW = r"""
const c = state.ctx, w = canvas.width, h = canvas.height, lim = state.cfg.limit;
c.clearRect(0, 0, w, h);
c.fillStyle = '#f4f4f4'; c.fillRect(0, 0, w, h);
c.strokeStyle = '#999'; c.lineWidth = 1;
c.beginPath(); c.moveTo(w / 2, 10); c.lineTo(w / 2, h - 30); c.stroke();
c.strokeStyle = '#c33'; c.lineWidth = 3;
c.beginPath(); c.moveTo(4, 10); c.lineTo(4, h - 30); c.moveTo(w - 4, 10); c.lineTo(w - 4, h - 30); c.stroke();
const px = w / 2 + (w / 2 - 8) * Math.max(-1.05, Math.min(1.05, state.x / lim));
c.fillStyle = state.running ? '#1f77b4' : '#777';
c.beginPath(); c.arc(px, (h - 20) / 2, 12, 0, 2 * Math.PI); c.fill();
c.fillStyle = '#555'; c.fillRect(w / 2, h - 18, (w / 2 - 8) * state.v, 8);
c.fillStyle = '#222'; c.font = '12px sans-serif';
c.fillText('lambda ' + state.lam.toFixed(2) + ' 1/s', 10, h - 4);
"""

_PLAN = r"""
const p = data.plan;
if (p && p.kind) {
  start.disabled = false;
  if (!state.running) status.textContent = 'next: ' + p.kind + ' trial ' + p.number +
      ' - press the button or the space bar';
} else {
  start.disabled = true;
  if (!state.running) status.textContent = 'no trial left: the result is below (start over to measure again)';
}
"""

_REMOVE = r"""
state.running = false;
if (state.raf) cancelAnimationFrame(state.raf);
window.removeEventListener('keydown', state.kd);
window.removeEventListener('keyup', state.ku);
"""


class TrackingTask(ReactiveHTML):
    """The task in the browser: a track, a marker, the rising instability; one trial per start.

    Parameters
    ----------
    config : dict
        :func:`stability.driver.tracking.browser_config`.
    plan : dict
        The next trial (:func:`stability.driver.protocol.next_trial`), ``{}`` when none is left.
    record : dict
        The last trial, set by the browser (untrusted).
    """

    config = param.Dict(default={})
    plan = param.Dict(default={})
    record = param.Dict(default={})

    _template = """
<div id="box" class="ctt-box" tabindex="0" style="outline: none;">
  <canvas id="canvas" class="ctt-canvas" width="640" height="150" style="width: 100%; max-width: 640px;"></canvas>
  <div><button id="start" class="ctt-start" onclick="${script('start')}">start the trial</button>
  <span id="status" class="ctt-status"></span></div>
</div>
"""
    _scripts = {"render": _RENDER, "start": _START, "input": _INPUT, "draw": _DRAW, "plan": _PLAN,
                "remove": _REMOVE}


class TrackingTab:
    """The Tracking tab of one session.

    Parameters
    ----------
    on_change : callable
        Wraps a widget callback as the page does.
    measured : callable
        ``measured(user_table or None) -> str``: the page keeps the ``[user]`` table for the chair download and returns
        what the result means for the chair being edited (plain text, shown under the result).
    meaning : callable, optional
        ``meaning(user_table) -> str``: what the result means for the chair being edited, the page's user left as
        it is (:meth:`chair_changed`: after an edit or a loaded file).  Default: ``measured``.
    """

    def __init__(self, on_change: Any, measured: Any, meaning: Any = None) -> None:
        self.measured = measured
        self.meaning = meaning if meaning is not None else measured
        self.records: list[TrialRecord] = []
        self.result: TrackingResult | None = None
        self.task = TrackingTask(config=browser_config(), plan=next_trial([]) or {}, sizing_mode="stretch_width",
                                 height=190, css_classes=["tracking-task"])
        self.task.param.watch(on_change(self._record), "record")
        self.note = widget(pn.widgets.TextInput, "note saved with the result (who, when; plain text)", width=340,
                                         css_classes=["tracking-note"], max_length=200)
        self.note.param.watch(on_change(lambda e: self._show()), "value")
        self.restart = widget(pn.widgets.Button, "start over", width=120, css_classes=["tracking-restart"])
        self.restart.on_click(on_change(lambda e: self.start_over()))
        self.text = pn.pane.HTML("", css_classes=["tracking-text"], sizing_mode="stretch_width")
        intro = pn.pane.Markdown(
            "**Critical tracking task** (Jex, McDonnell & Phatak 1966; after ISO/TS 14198): keep the marker on "
            "the centre line with the left/right arrow keys (or A/D), the mouse over the track, or a joystick. "
            "The marker drifts away by itself, faster and faster, until you lose it at the red edges. "
            f"{PRACTICE_TRIALS} practice trials, then scored trials until {SCORED_TRIALS} are valid (at most "
            f"{2 * SCORED_TRIALS}; a result needs {MIN_VALID}). Your effective delay `tau_e` is saved with the "
            "chair (Downloads: the chair TOML gets a `[user]` table that every command's `--chair` reads). "
            "See docs/driver.md.",
            sizing_mode="stretch_width")
        self.panel = pn.Column(intro, self.task, pn.Row(self.note, self.restart), self.text,
                               sizing_mode="stretch_width")
        self._show()

    def _record(self, event: Any) -> None:
        if not event.new:
            return
        if len(self.records) >= MAX_TRIALS:
            return
        try:
            rec = TrialRecord.from_mapping(event.new)
        except ValueError as exc:
            self.text.object = f"<p>trial refused: {literal(exc)}</p>"
            self.task.plan = {**(next_trial(self.records) or {}), "seq": -len(self.records) - 1}
            return
        self.records.append(rec)
        self._show()
        self.task.plan = next_trial(self.records) or {"seq": len(self.records)}

    def start_over(self) -> None:
        """Forget the trials (the last saved result stays with the chair until a new one)."""
        self.records = []
        self.result = None
        self.task.plan = next_trial([]) or {}
        self._show()

    def chair_changed(self) -> None:
        """Say again what the result means, for the chair now edited (the page calls it after every edit and file):
        the user the page keeps is not changed here (a loaded chair file's own ``[user]`` stays)."""
        if self.result is not None and self.result.reaction_time_s is not None:
            self._show(keep=False)

    def _show(self, keep: bool = True) -> None:
        res = tracking_result(self.records) if self.records else None
        self.result = res
        rows = []
        for i, t in enumerate(res.trials if res else (), 1):
            r = t.record
            rows.append(f"<tr><td>{i}</td><td>{r.kind}</td><td>{r.lambda_start_1_s:.3f}</td>"
                        f"<td>{r.lambda_c_1_s:.3f}</td><td>{r.duration_s:.1f}</td><td>{r.device}</td>"
                        f"<td>{'valid' if t.valid else 'invalid: ' + t.reason}</td></tr>")
        table = ("<table class='tracking-trials'><tr><th>trial</th><th>kind</th><th>lambda start (1/s)</th>"
                 "<th>lambda_c (1/s)</th><th>duration (s)</th><th>input</th><th></th></tr>"
                 + "".join(rows) + "</table>") if rows else ""
        if res is not None and res.reaction_time_s is not None:
            e = res.escape
            user = res.user_table(self.note.value or "")
            summary = (f"<p class='tracking-result'><b>tau_e = {res.reaction_time_s:.3f} +/- "
                       f"{res.reaction_time_sd_s:.3f} s</b> (lambda_c = {res.lambda_c_1_s:.3f} +/- "
                       f"{res.lambda_c_sd_1_s:.3f} 1/s over {res.valid_scored} valid scored trials; escape factor "
                       f"{e.mean:.3f} +/- {e.sd:.3f} of a delayed proportional operator). Saved with the chair: "
                       f"<code>[user] reaction_time_s = {user['reaction_time_s']:.4f}</code>"
                       + (f"; note: {literal(self.note.value)}" if (self.note.value or '').strip() else "")
                       + "</p>")
            meaning = self.measured(user) if keep else self.meaning(user)
            if meaning:
                summary += f"<p class='tracking-meaning'>{literal(meaning)}</p>"
        else:
            summary = "<p>No result yet.</p>"
        html = summary + table
        if self.text.object != html:
            self.text.object = html

