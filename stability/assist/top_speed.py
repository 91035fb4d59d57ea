"""The safe top speed: the highest scheduled speed at which every constraint holds (and at every speed below).

Constraints at each design speed:

- ``gain_margin``: the sampled loop's gain margin (the smaller of increase and
  decrease) at least :data:`MIN_GAIN_MARGIN_DB`;
- ``phase_margin``: its phase margin at least :data:`MIN_PHASE_MARGIN_DEG`;
- ``delay_margin``: its delay margin above the loop's own delay
  (:func:`loop_delay`: one sample of computation, half a sample of zero-order
  hold and the motor lag), so the loop tolerates twice its delay;
- ``torque``: the peak differential torque for the reference push, the
  reference turn (:func:`~stability.assist.driving.torque_requirement`) and a
  full joystick turn (:func:`full_turn_peaks`: a
  :data:`~stability.assist.commands.MAX_YAW_RATE` step through the reference
  model) within the motor limit and the traction limit ``mu N r``;
- ``faults``: every single sensor fault (:mod:`.faults`) "safe" on level
  ground and on the cross slope.

The margins and the torque need no fault runs: :func:`check_top_speed` runs
them by default (the command line's default output, its JSON and PDF, and the
``--export-c`` README, which warns when the exported schedule goes beyond the
safe top speed); ``--faults`` adds the fault runs.  A constraint that was not
checked (the torque under ``--no-check``, the faults without ``--faults``) is
named as such, so the speed is the top speed *of the checked constraints*.

The gain and phase minimums are the usual single-loop design rules (6 dB,
30 deg; e.g. Skogestad & Postlethwaite 2005, sec. 2.4.3).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from stability.assist.commands import COMMAND_FILTER, MAX_YAW_RATE, command_run, step_command
from stability.assist.digital import margin_pair
from stability.assist.schedule import Schedule

__all__ = ["MIN_GAIN_MARGIN_DB", "MIN_PHASE_MARGIN_DEG", "CONSTRAINTS", "DESCRIPTIONS", "loop_delay",
           "full_turn_peaks", "SpeedCheck", "Limit", "TopSpeed", "top_speed", "check_top_speed", "margin_top_speed",
           "format_top_speed"]

#: Minimum sampled gain margin (dB) and phase margin (deg).
MIN_GAIN_MARGIN_DB = 6.0
MIN_PHASE_MARGIN_DEG = 30.0
#: Names of the constraints, in the order they are reported.
CONSTRAINTS = ("gain_margin", "phase_margin", "delay_margin", "torque", "faults")
#: JSON key of each constraint's check (the key convention: the unit last; the faults are a count).
JSON_KEYS = {"gain_margin": "gain_margin_db", "phase_margin": "phase_margin_deg", "delay_margin": "delay_margin_ms",
             "torque": "torque_N_m", "faults": "unsafe_fault_count"}
#: Each constraint in words: (what, unit of value and limit, the limit in words, how the value fails it).
DESCRIPTIONS = {
    "gain_margin": ("the sampled gain margin (the smaller of increase and decrease)", "dB", "the minimum of",
                    "below"),
    "phase_margin": ("the sampled phase margin", "deg", "the minimum of", "below"),
    "delay_margin": ("the sampled delay margin", "ms", "the loop's own delay of", "not above"),
    "torque": ("the peak differential torque per wheel", "N m", "the smaller of the motor and traction limits,",
               "above"),
    "faults": ("the number of unsafe single sensor faults", "", "the allowed", "above"),
}
#: How to add a constraint that was not checked.
ENABLE = {"torque": "the torque (run without --no-check)", "faults": "the single sensor faults (add --faults)"}


def loop_delay(sched: Schedule) -> float:
    """The loop's own delay: one sample of computation, half a sample of hold and the motor lag (s).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    float
    """
    T = 1.0 / sched.gyro.sample_rate_hz
    return 1.5 * T + sched.drive.motor_time_constant


@dataclass(frozen=True)
class SpeedCheck:
    """The constraints at one speed: value, limit and whether it holds.

    Attributes
    ----------
    speed_m_s : float
    values : dict
        Constraint -> ``(value, limit, ok)``: gain dB vs minimum, phase deg vs minimum, delay margin ms vs loop
        delay ms, peak torque N m vs the smaller limit N m, unsafe fault count vs 0.
    """

    speed_m_s: float
    values: dict[str, tuple[float, float, bool]]

    @property
    def ok(self) -> bool:
        """All constraints hold."""
        return all(v[2] for v in self.values.values())

    def failing(self) -> list[str]:
        """Names of the constraints that fail."""
        return [k for k in CONSTRAINTS if k in self.values and not self.values[k][2]]


@dataclass(frozen=True)
class Limit:
    """A constraint that fails at the first design speed above the safe top speed.

    Attributes
    ----------
    constraint : str
        One of :data:`CONSTRAINTS`.
    speed_m_s : float
        The design speed where it fails (m/s).
    value, limit : float
        Its value and its limit there, in :attr:`unit`.
    unit : str
    """

    constraint: str
    speed_m_s: float
    value: float
    limit: float
    unit: str

    def describe(self) -> str:
        """In words, e.g. ``"at 1.75 m/s the sampled delay margin is 34.8 ms, not above the loop's own delay
        35 ms"``."""
        what, unit, limit_words, fails = DESCRIPTIONS[self.constraint]
        u = f" {unit}" if unit else ""
        return (f"at {self.speed_m_s:g} m/s {what} is {self.value:.3g}{u}, {fails} {limit_words} "
                f"{self.limit:.3g}{u}")

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``constraint``, ``speed_m_s``, ``value``, ``limit``, ``unit``."""
        from stability.assist._format import json_float

        return {"constraint": self.constraint, "speed_m_s": self.speed_m_s, "value": json_float(self.value),
                "limit": json_float(self.limit), "unit": self.unit}


@dataclass(frozen=True)
class TopSpeed:
    """The safe top speed and the constraint that sets it.

    Attributes
    ----------
    safe_top_speed_m_s : float or None
        Highest design speed with every checked constraint holding there and at every design speed below (None:
        fails at the first).
    limited_by : str
        The constraint(s) failing at the next design speed (joined by ``+``), or ``"design_grid"`` when all hold
        up to the last.
    checks : list of SpeedCheck
    checked : tuple of str
        The constraints that were checked (:data:`CONSTRAINTS` order); the others were not run.
    """

    safe_top_speed_m_s: float | None
    limited_by: str
    checks: list[SpeedCheck]
    checked: tuple[str, ...] = field(default=CONSTRAINTS)

    @property
    def not_checked(self) -> tuple[str, ...]:
        """The constraints that were not run."""
        return tuple(k for k in CONSTRAINTS if k not in self.checked)

    @property
    def last_speed_m_s(self) -> float:
        """The highest design speed (m/s)."""
        return self.checks[-1].speed_m_s

    @property
    def exceeded(self) -> bool:
        """The schedule goes beyond the safe top speed."""
        return self.limited_by != "design_grid"

    def limits(self) -> list[Limit]:
        """The constraints failing at the first design speed above the safe top speed (empty: none fails).

        Returns
        -------
        list of Limit
        """
        for c in self.checks:
            if not c.ok:
                return [Limit(k, c.speed_m_s, *c.values[k][:2], DESCRIPTIONS[k][1]) for k in c.failing()]
        return []

    def sentence(self) -> str:
        """One line: the safe top speed, what limits it with its value against its limit, and what was checked."""
        lim = self.limits()
        why = ("; ".join(x.describe() for x in lim) if lim else
               f"every checked constraint holds up to the last design speed {self.last_speed_m_s:g} m/s; extend "
               "--speeds to find the limit")
        head = "no design speed is safe" if self.safe_top_speed_m_s is None else \
            f"safe top speed {self.safe_top_speed_m_s:g} m/s"
        return f"{head}: {why}" + self._scope()

    def warning(self) -> str | None:
        """The export's warning (one line) when the schedule goes beyond the safe top speed, else None."""
        if not self.exceeded:
            return None
        top = "no design speed" if self.safe_top_speed_m_s is None else f"{self.safe_top_speed_m_s:g} m/s"
        return (f"the exported schedule runs to {self.last_speed_m_s:g} m/s, beyond the safe top speed {top}: "
                + "; ".join(x.describe() for x in self.limits()) + self._scope())

    def _scope(self) -> str:
        if not self.not_checked:
            return ""
        return " (not checked: " + ", ".join(ENABLE[k] for k in self.not_checked) + ")"

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``safe_top_speed_m_s``, ``limited_by``, ``constraints_checked``, ``limits`` and ``checks``."""
        from stability.assist._format import json_float

        return {"safe_top_speed_m_s": self.safe_top_speed_m_s, "limited_by": self.limited_by,
                "constraints_checked": list(self.checked), "limits": [x.to_dict() for x in self.limits()],
                "checks": [{"speed_m_s": c.speed_m_s,
                            **{JSON_KEYS[k]: {"value": json_float(v[0]), "limit": json_float(v[1]), "ok": v[2]}
                               for k, v in c.values.items()}} for c in self.checks]}


def full_turn_peaks(sched: Schedule, speeds: Sequence[float]) -> dict[float, float]:
    """Peak differential torque per wheel (N m) of a full joystick turn at each speed.

    A :data:`~stability.assist.commands.MAX_YAW_RATE` step through the
    reference model (:data:`~stability.assist.commands.COMMAND_FILTER`), 3 s,
    noise-free, in the nonlinear loop (:func:`~stability.assist.commands.command_run`).

    Parameters
    ----------
    sched : Schedule
    speeds : sequence of float
        m/s.

    Returns
    -------
    dict
        Speed (m/s) -> N m.
    """
    return {float(s): command_run(sched, float(s), step_command(MAX_YAW_RATE), duration=3.0,
                                  command_filter_s=COMMAND_FILTER).peak_torque_N_m for s in speeds}


def top_speed(sched: Schedule, rows: Sequence[Any], torque_rows: Sequence[Any] | None,
              fault_rows: Sequence[Any] | None, full_turn: dict[float, float] | None = None) -> TopSpeed:
    """Check every constraint at every design speed and find the safe top speed.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow
        :func:`~stability.assist.tables.gain_table` (their ``margin_pair``).
    torque_rows : sequence of TorqueRow, optional
        :func:`~stability.assist.driving.torque_requirement` at the design speeds (None: the torque constraint is
        not checked).
    fault_rows : sequence of FaultRow, optional
        :func:`~stability.assist.faults.fault_runs` (None: the fault constraint is not checked).
    full_turn : dict, optional
        :func:`full_turn_peaks` (speed -> N m), counted in the torque constraint.

    Returns
    -------
    TopSpeed
    """
    delay_ms = 1e3 * loop_delay(sched)
    torques = {round(t.speed_m_s, 9): t for t in torque_rows or []}
    checks = []
    for r in rows:
        s = float(r.speed_m_s)
        d = r.margin_pair.to_dict()["discrete"]
        gm, pm, dm = (float(d[k]) if d[k] != "inf" else math.inf for k in ("gain_db", "phase_deg", "delay_ms"))
        vals: dict[str, tuple[float, float, bool]] = {
            "gain_margin": (gm, MIN_GAIN_MARGIN_DB, gm >= MIN_GAIN_MARGIN_DB),
            "phase_margin": (pm, MIN_PHASE_MARGIN_DEG, pm >= MIN_PHASE_MARGIN_DEG),
            "delay_margin": (dm, delay_ms, dm > delay_ms)}
        t = torques.get(round(s, 9))
        if t is not None:
            peak = max(t.push_peak_N_m, t.turn_peak_N_m, (full_turn or {}).get(s, 0.0))
            lim = min(t.motor_limit_N_m, t.traction_limit_N_m)
            vals["torque"] = (peak, lim, peak <= lim * (1 - 1e-9))
        if fault_rows is not None:
            bad = sum(1 for f in fault_rows if abs(f.speed_m_s - s) < 1e-9 and f.outcome != "safe")
            vals["faults"] = (float(bad), 0.0, bad == 0)
        checks.append(SpeedCheck(s, vals))
    top: float | None = None
    limited = "design_grid"
    for c in checks:
        if not c.ok:
            limited = "+".join(c.failing())
            break
        top = c.speed_m_s
    checked = tuple(k for k in CONSTRAINTS if any(k in c.values for c in checks))
    return TopSpeed(top, limited, checks, checked)


def check_top_speed(sched: Schedule, rows: Sequence[Any], *, torque_rows: Sequence[Any] | None = None,
                    fault_rows: Sequence[Any] | None = None) -> TopSpeed:
    """The top-speed check of the command line: the sampled margins always, the torque and the faults when given.

    With ``torque_rows`` (:func:`~stability.assist.driving.torque_requirement` at the design speeds) the full
    joystick turn is simulated at each design speed too (:func:`full_turn_peaks`, a few seconds in all).

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow
    torque_rows : sequence of TorqueRow, optional
    fault_rows : sequence of FaultRow, optional

    Returns
    -------
    TopSpeed
    """
    full = full_turn_peaks(sched, [float(s) for s in sched.speeds]) if torque_rows is not None else None
    return top_speed(sched, rows, torque_rows, fault_rows, full)


@dataclass(frozen=True)
class _MarginRow:
    """What :func:`top_speed` reads of a gain-table row."""

    speed_m_s: float
    margin_pair: Any


def margin_top_speed(sched: Schedule) -> TopSpeed:
    """The safe top speed of the sampled margins alone (no simulation): what a firmware export checks when it is
    given no :class:`TopSpeed`.

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    TopSpeed
    """
    rows = [_MarginRow(float(s), margin_pair(d, d.sample_time)) for s, d in zip(sched.speeds, sched.designs,
                                                                                 strict=True)]
    return top_speed(sched, rows, None, None)


def format_top_speed(ts: TopSpeed) -> str:
    """Text block: the per-speed checks (value / limit) and the result in words.

    Parameters
    ----------
    ts : TopSpeed

    Returns
    -------
    str
    """
    keys = ts.checked
    rules = {"gain_margin": f"sampled gain margin >= {MIN_GAIN_MARGIN_DB:g} dB",
             "phase_margin": f"phase margin >= {MIN_PHASE_MARGIN_DEG:g} deg",
             "delay_margin": "delay margin > the loop's own delay (1.5 samples + motor lag)",
             "torque": "peak torque (reference push, reference turn, full joystick turn) within the motor and "
                       "traction limits",
             "faults": "every single sensor fault safe"}
    lines = ["Safe top speed: every checked constraint holds at the design speed and below ("
             + "; ".join(rules[k] for k in keys) + ")",
             f"{'U':>5s}  " + "  ".join(f"{k.replace('_', ' '):>20s}" for k in keys),
             f"{'m/s':>5s}  " + "  ".join(f"{('value / limit ' + DESCRIPTIONS[k][1]).strip():>20s}" for k in keys)]
    for c in ts.checks:
        cells = []
        for k in keys:
            if k in c.values:
                v, lim, ok = c.values[k]
                cells.append(f"{v:8.3g} / {lim:<6.3g}{'ok' if ok else 'NO':>4s}")
            else:
                cells.append("-")
        lines.append(f"{c.speed_m_s:5.2f}  " + "  ".join(f"{x:>20s}" for x in cells))
    text = ts.sentence()
    lines.append(text[0].upper() + text[1:] + ".")
    return "\n".join(lines)
