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

The gain and phase minimums are the usual single-loop design rules (6 dB,
30 deg; e.g. Skogestad & Postlethwaite 2005, sec. 2.4.3).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from stability.assist.commands import COMMAND_FILTER, MAX_YAW_RATE, command_run, step_command
from stability.assist.schedule import Schedule

__all__ = ["MIN_GAIN_MARGIN_DB", "MIN_PHASE_MARGIN_DEG", "CONSTRAINTS", "loop_delay", "full_turn_peaks", "SpeedCheck",
           "TopSpeed",
           "top_speed", "format_top_speed"]

#: Minimum sampled gain margin (dB) and phase margin (deg).
MIN_GAIN_MARGIN_DB = 6.0
MIN_PHASE_MARGIN_DEG = 30.0
#: Names of the constraints, in the order they are reported.
CONSTRAINTS = ("gain_margin", "phase_margin", "delay_margin", "torque", "faults")
#: JSON key of each constraint's check (the key convention: the unit last; the faults are a count).
JSON_KEYS = {"gain_margin": "gain_margin_db", "phase_margin": "phase_margin_deg", "delay_margin": "delay_margin_ms",
             "torque": "torque_N_m", "faults": "unsafe_fault_count"}


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
class TopSpeed:
    """The safe top speed and the constraint that sets it.

    Attributes
    ----------
    safe_top_speed_m_s : float or None
        Highest design speed with every constraint holding there and at every design speed below (None: fails at
        the first).
    limited_by : str
        The constraint(s) failing at the next design speed, or ``"design_grid"`` when all hold up to the last.
    checks : list of SpeedCheck
    """

    safe_top_speed_m_s: float | None
    limited_by: str
    checks: list[SpeedCheck]

    def to_dict(self) -> dict[str, Any]:
        """JSON: ``safe_top_speed_m_s``, ``limited_by`` and the per-speed checks."""
        from stability.assist._format import json_float

        return {"safe_top_speed_m_s": self.safe_top_speed_m_s, "limited_by": self.limited_by,
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


def top_speed(sched: Schedule, rows: Sequence[Any], torque_rows: Sequence[Any],
              fault_rows: Sequence[Any] | None, full_turn: dict[float, float] | None = None) -> TopSpeed:
    """Check every constraint at every design speed and find the safe top speed.

    Parameters
    ----------
    sched : Schedule
    rows : sequence of GainRow
        :func:`~stability.assist.tables.gain_table` (their ``margin_pair``).
    torque_rows : sequence of TorqueRow
        :func:`~stability.assist.driving.torque_requirement` at the design speeds.
    fault_rows : sequence of FaultRow, optional
        :func:`~stability.assist.faults.fault_runs` (None: the fault constraint is not checked).
    full_turn : dict, optional
        :func:`full_turn_peaks` (speed -> N m), counted in the torque constraint.

    Returns
    -------
    TopSpeed
    """
    delay_ms = 1e3 * loop_delay(sched)
    torques = {round(t.speed_m_s, 9): t for t in torque_rows}
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
    return TopSpeed(top, limited, checks)


def format_top_speed(ts: TopSpeed) -> str:
    """Text block: the per-speed checks and the result.

    Parameters
    ----------
    ts : TopSpeed

    Returns
    -------
    str
    """
    lines = ["Safe top speed: every constraint at the design speed and below (sampled gain >= "
             f"{MIN_GAIN_MARGIN_DB:g} dB, phase >= {MIN_PHASE_MARGIN_DEG:g} deg, delay margin > the loop's own "
             "delay, peak torque for the reference push, the reference turn and a full joystick turn within the motor "
             "and traction limits, every "
             "single fault safe)",
             f"{'m/s':>5s}  " + "  ".join(f"{k:>20s}" for k in CONSTRAINTS)]
    for c in ts.checks:
        cells = []
        for k in CONSTRAINTS:
            if k in c.values:
                v, lim, ok = c.values[k]
                cells.append(f"{v:8.3g} / {lim:<6.3g}{'ok' if ok else 'NO':>4s}")
            else:
                cells.append(f"{'-':>20s}")
        lines.append(f"{c.speed_m_s:5.2f}  " + "  ".join(f"{x:>20s}" for x in cells))
    top = "none" if ts.safe_top_speed_m_s is None else f"{ts.safe_top_speed_m_s:g} m/s"
    lines.append(f"safe top speed: {top}; limited by: {ts.limited_by}"
                 + (" (every constraint holds up to the last design speed; extend --speeds to find the limit)"
                    if ts.limited_by == "design_grid" else ""))
    return "\n".join(lines)
