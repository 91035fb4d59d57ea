"""Result of a simulated run: :class:`SimulationResult` (time histories, CSV, JSON) and :class:`ChairState`."""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from stability.chair import Chair
from stability.runtime.checks import check_positive
from stability.runtime.files import atomic_write_text
from stability.simulate.options import WHEELS
from stability.simulate.signals import time_to_level

__all__ = ["JSON_COLUMNS", "json_key", "COLUMNS", "NCOLS", "ChairState", "RunStats", "SimulationResult", "new_warnings",
           "warning_table", "WARNING_KINDS"]

COLUMNS = ("t", "x", "y", "heading", "yaw_rate", "u", "v", "eta", "eta_dot", "beta", "beta_dot",
         "fx_A", "fy_A", "fx_B", "fy_B", "fx_D", "fy_D", "fx_E", "fy_E",
         "fz_A", "fz_B", "fz_D", "fz_E", "slip_A", "slip_B", "slip_D", "slip_E",
         "tire_yaw_moment", "yaw_moment_input", "yaw_acceleration", "pin_moment_A", "pin_moment_B")
NCOLS = len(COLUMNS)
_WHEEL_KEYS = {"A": "caster_left", "B": "caster_right", "D": "main_left", "E": "main_right"}
_COLUMN_UNITS = {"t": "s", "x": "m", "y": "m", "heading": "rad", "yaw_rate": "rad_s", "u": "m_s", "v": "m_s",
                 "eta": "rad", "eta_dot": "rad_s", "beta": "rad", "beta_dot": "rad_s", "fx": "N", "fy": "N", "fz": "N",
                 "slip": "deg", "tire_yaw_moment": "N_m", "yaw_moment_input": "N_m", "yaw_acceleration": "rad_s2",
                 "pin_moment": "N_m"}


def json_key(column: str) -> str:
    """The JSON key of a CSV column: the wheel spelled out and the unit last (``fy_A`` -> ``fy_caster_left_N``).

    Parameters
    ----------
    column : str
        One of :data:`COLUMNS`.

    Returns
    -------
    str
    """
    base, _, wheel = column.rpartition("_")
    if wheel in _WHEEL_KEYS and base:
        return f"{base}_{_WHEEL_KEYS[wheel]}_{_COLUMN_UNITS[base]}"
    return f"{column}_{_COLUMN_UNITS[column]}"


#: JSON keys of the time histories, in :data:`COLUMNS` order.
JSON_COLUMNS = tuple(json_key(c) for c in COLUMNS)
_WARNING_UNITS = {"slip": "deg", "load": "N", "lift_off": "N"}
#: The range warnings a run counts (:func:`warning_table`).
WARNING_KINDS = tuple(_WARNING_UNITS)


# ---------------------------------------------------------------------------
# state passed to a yaw-moment input
# ---------------------------------------------------------------------------
class ChairState(NamedTuple):
    """State handed to a ``yaw_moment(t, state)`` input.

    Floats for a single run; arrays of shape ``(n_active,)`` in a batch, where
    ``run`` holds the index (into the batch) of each active run (runs that
    stopped by warnings drop out).
    """

    x: Any          #: global X of the c.g. (m)
    y: Any          #: global Y of the c.g. (m)
    heading: Any    #: yaw angle (rad, clockwise from above)
    u: Any          #: forward velocity (m/s, body axes)
    v: Any          #: lateral velocity (m/s, body axes, to the right)
    yaw_rate: Any   #: yaw rate (rad/s)
    eta: Any        #: left caster angle (rad)
    eta_dot: Any    #: left caster rate (rad/s)
    beta: Any       #: right caster angle (rad)
    beta_dot: Any   #: right caster rate (rad/s)
    run: Any = 0    #: run index (batch) or 0


# ---------------------------------------------------------------------------
# results
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class RunStats:
    """Summaries of a run taken at every step (not only the recorded ones).

    Attributes
    ----------
    levels : tuple of float
        |yaw rate| levels, rad/s.
    time_to_level : tuple of (float or None)
        First time |yaw rate| reaches each level, s (linear interpolation
        between the two steps that bracket it); None if never.
    peak_abs_yaw_rate : float
        Largest |yaw rate|, rad/s.
    peak_time : float
        When it occurred, s.
    """

    levels: tuple[float, ...]
    time_to_level: tuple[float | None, ...]
    peak_abs_yaw_rate: float
    peak_time: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (keys with their units)."""
        return {"levels_rad_s": list(self.levels), "time_to_level_s": list(self.time_to_level),
                "peak_abs_yaw_rate_rad_s": _json_scalar(self.peak_abs_yaw_rate),
                "peak_time_s": _json_scalar(self.peak_time)}


def _readonly(a: np.ndarray) -> np.ndarray:
    """A read-only view (no copy)."""
    a = a.view()
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """Time histories of one simulated run.

    Per-sample arrays have shape ``(n,)``; per-wheel arrays ``(n, 4)`` with
    columns in :data:`WHEELS` order (A left caster, B right caster, D left
    main wheel, E right main wheel); pin moments ``(n, 2)`` (A, B).

    Attributes
    ----------
    t : s.  x, y : global position of the c.g., m.  heading : rad.
    yaw_rate : rad/s (positive clockwise from above).  u, v : body
    velocities, m/s.  eta, beta : caster angles, rad; eta_dot, beta_dot :
    rad/s.
    fx, fy : tire forces, N; casters in their own wheel frames, main wheels in
        body axes (the wheel frame when toe is zero).
    normal_load : N (positive pressing on the ground).
    slip_deg : signed slip angle ``atan2(vy, |vx|)`` of each contact, deg
        (WCHAIR's SLIPA..SLIPE are the absolute values).
    tire_yaw_moment : yaw moment of all tire forces about the c.g., N m (the
        "total destabilizing torque" of Figure 9-4 when no input acts).
    yaw_moment_input : the ``yaw_moment`` input, N m.
    yaw_acceleration : rad/s^2.
    pin_moment : moment of each pin on its caster, N m: Coulomb friction when
        the caster turns, the holding reaction when it is stuck or locked.
    warnings : ``{"slip": {...}, "load": {...}, "lift_off": {...}}``, each
        ``{"count": int, "first_time": float | None, "max": float | None}``:
        steps (wchair) or samples (adaptive) with a slip angle above
        :data:`SLIP_LIMIT_DEG`, a normal load above :data:`LOAD_LIMIT_N`, or
        a negative normal load (a wheel lifting; information only).
    stopped_by_warnings : whether the run was stopped early: by the warning
        rule, or (adaptive scheme) because the normal loads lost their
        solution (a wheel lifts off; ``stop_reason`` says so).
    stop_time : time of the step that stopped it (s) or None.
    stop_reason : one line saying why the run stopped when not by the warning
        rule, else None.
    chair, speed, settings : the inputs.
    stats : RunStats or None
        Summaries over every step of a compiled run (also when only some
        steps are recorded): peak |yaw rate|, first times of given levels.
    step_unstable : bool
        The fixed step lies outside the scheme's stability limit at this
        speed (``settings["stable_dt"]`` holds the largest safe step): the
        traces may be numerical artefacts.
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heading: np.ndarray
    yaw_rate: np.ndarray
    u: np.ndarray
    v: np.ndarray
    eta: np.ndarray
    eta_dot: np.ndarray
    beta: np.ndarray
    beta_dot: np.ndarray
    fx: np.ndarray
    fy: np.ndarray
    normal_load: np.ndarray
    slip_deg: np.ndarray
    tire_yaw_moment: np.ndarray
    yaw_moment_input: np.ndarray
    yaw_acceleration: np.ndarray
    pin_moment: np.ndarray
    warnings: Mapping[str, Mapping[str, Any]]
    stopped_by_warnings: bool
    stop_time: float | None
    chair: Chair
    speed: float
    settings: Mapping[str, Any] = field(default_factory=dict)
    stats: RunStats | None = None
    step_unstable: bool = False
    stop_reason: str | None = None

    # -- construction ----------------------------------------------------
    @classmethod
    def from_columns(cls, t: np.ndarray, cols: np.ndarray, *, warnings, stopped, stop_time, chair, speed, settings,
                     stats: RunStats | None = None, step_unstable: bool = False,
                     stop_reason: str | None = None) -> SimulationResult:
        """A result from ``t`` (n,) and ``cols`` (k, n): the columns after ``t`` of :data:`COLUMNS`.

        ``k = 31`` (all) or ``10`` (the states; the other quantities read as NaN,
        broadcast views that take no memory).  Rows of ``cols`` are used as views
        (no copy) when contiguous.
        """
        n = len(t)
        full = cols.shape[0] == NCOLS - 1
        c = {name: cols[i] for i, name in enumerate(COLUMNS[1:cols.shape[0] + 1])}

        def col(name):
            return _readonly(c[name]) if name in c else np.broadcast_to(np.nan, (n,))

        def wheels(rows):   # (n, 4) views of rows of cols (no copy)
            return _readonly(cols[rows].T) if full else np.broadcast_to(np.nan, (n, 4))

        pins = _readonly(cols[29:31].T) if full else np.broadcast_to(np.nan, (n, 2))
        return cls(
            t=_readonly(t), x=col("x"), y=col("y"), heading=col("heading"), yaw_rate=col("yaw_rate"), u=col("u"),
            v=col("v"), eta=col("eta"), eta_dot=col("eta_dot"), beta=col("beta"), beta_dot=col("beta_dot"),
            fx=wheels(slice(10, 18, 2)), fy=wheels(slice(11, 18, 2)), normal_load=wheels(slice(18, 22)),
            slip_deg=wheels(slice(22, 26)), tire_yaw_moment=col("tire_yaw_moment"),
            yaw_moment_input=col("yaw_moment_input"),
            yaw_acceleration=col("yaw_acceleration"), pin_moment=pins,
            warnings={k: dict(v) for k, v in warnings.items()}, stopped_by_warnings=bool(stopped),
            stop_time=None if stop_time is None else float(stop_time), chair=chair, speed=float(speed),
            settings=dict(settings), stats=stats, step_unstable=bool(step_unstable), stop_reason=stop_reason)

    @classmethod
    def _from_records(cls, rec: np.ndarray, **kw: Any) -> SimulationResult:
        """A result from ``rec`` (n, 32): every column of :data:`COLUMNS` (one copy; the arrays are views of it)."""
        cols = np.ascontiguousarray(rec.T, dtype=float)
        return cls.from_columns(cols[0], cols[1:], **kw)

    def _records(self) -> np.ndarray:
        """All columns of :data:`COLUMNS` as one ``(n, 32)`` array."""
        per_wheel = {"fx": self.fx, "fy": self.fy, "fz": self.normal_load, "slip": self.slip_deg}
        cols = []
        for name in COLUMNS:
            prefix, _, last = name.rpartition("_")
            if prefix in per_wheel and last in WHEELS:
                cols.append(per_wheel[prefix][:, WHEELS.index(last)])
            elif prefix == "pin_moment":
                cols.append(self.pin_moment[:, "AB".index(last)])
            else:
                cols.append(getattr(self, name))
        return np.column_stack(cols) if len(self.t) else np.zeros((0, NCOLS))

    # -- queries -----------------------------------------------------------
    def __len__(self) -> int:
        return len(self.t)

    @property
    def duration(self) -> float:
        """Time span covered by the samples (s)."""
        return float(self.t[-1] - self.t[0]) if len(self.t) else 0.0

    @property
    def warning_counts(self) -> dict[str, int]:
        """``{kind: count}``."""
        return {k: int(v["count"]) for k, v in self.warnings.items()}

    def first_time_abs_yaw_rate(self, value: float) -> float | None:
        """First time at which ``|yaw_rate|`` reaches ``value`` (rad/s).

        Linear interpolation between the two samples that bracket the
        crossing; ``0.0`` if it already holds at the first sample; ``None``
        if it never does.
        """
        value = float(value)
        if not math.isfinite(value) or value < 0:
            raise ValueError(f"value={value!r} is invalid; valid range: a finite yaw rate >= 0 rad/s")
        t = time_to_level(self.t, self.yaw_rate, value)
        return None if math.isinf(t) else t

    def at(self, time: float) -> dict[str, float]:
        """All scalar quantities linearly interpolated at ``time`` (s)."""
        rec = self._records()
        if not len(self.t) or not self.t[0] <= time <= self.t[-1]:
            raise ValueError(f"time={time!r} is outside the simulated span [{self.t[0] if len(self.t) else 0}, "
                             f"{self.t[-1] if len(self.t) else 0}] s")
        return {name: float(np.interp(time, self.t, rec[:, i])) for i, name in enumerate(COLUMNS)}

    def resample(self, dt: float) -> SimulationResult:
        """The result linearly interpolated on ``t0, t0 + dt, ...`` (s)."""
        dt = check_positive("dt", dt)
        if len(self.t) < 2:
            return self
        n = int(math.floor((self.t[-1] - self.t[0]) / dt * (1 + 1e-12) + 1e-9)) + 1
        tt = self.t[0] + dt * np.arange(n)
        tt[-1] = min(tt[-1], self.t[-1])
        rec = self._records()
        out = np.empty((n, NCOLS))
        out[:, 0] = tt
        for i in range(1, NCOLS):
            out[:, i] = np.interp(tt, self.t, rec[:, i])
        settings = dict(self.settings, resampled=dt)
        return SimulationResult._from_records(out, warnings=self.warnings, stopped=self.stopped_by_warnings,
                                              stop_time=self.stop_time, chair=self.chair, speed=self.speed,
                                              settings=settings, stop_reason=self.stop_reason)

    def summary(self) -> str:
        """A short readable summary."""
        s = self.settings
        lines = [
            f"chair {self.chair.name} ({self.chair.caster_position} casters), speed {self.speed:g} m/s, "
            f"model {s.get('model')}, scheme {s.get('scheme')}, casters {s.get('casters')}"
            + (f" ({s['friction_law']} pin friction)" if "friction_law" in s else ""),
            f"simulated {self.t[0]:.3f} .. {self.t[-1]:.3f} s ({len(self.t)} samples)"
            + (f"; STOPPED by warnings at t = {self.stop_time:.3f} s"
               if self.stopped_by_warnings and self.stop_reason is None else ""),
        ]
        if self.stop_reason is not None:
            lines.append(f"STOPPED at t = {self.stop_time:.3f} s: {self.stop_reason}")
        for v in (0.5, 1.0):
            tv = self.first_time_abs_yaw_rate(v)
            lines.append(f"|yaw rate| never reaches {v:g} rad/s" if tv is None
                         else f"|yaw rate| reaches {v:g} rad/s at {tv:.3f} s")
        if len(self.t):
            lines.append(f"final: yaw rate {self.yaw_rate[-1]:+.4f} rad/s, heading "
                         f"{math.degrees(self.heading[-1]):+.2f} deg, position ({self.x[-1]:.3f}, {self.y[-1]:.3f}) m, "
                         f"max |yaw rate| {np.max(np.abs(self.yaw_rate)):.4f} rad/s")
        w = ", ".join(f"{k}: {v['count']}"
                      + (f" (first at {v['first_time']:.3f} s)" if v["first_time"] is not None else "")
                      for k, v in self.warnings.items())
        lines.append(f"warnings: {w}")
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite numbers become ``None``).

        The time histories are keyed with their units and the wheels spelled
        out (:data:`JSON_COLUMNS`, e.g. ``yaw_rate_rad_s``, ``fy_caster_left_N``,
        ``slip_main_right_deg``); the CSV keeps the short names of :data:`COLUMNS`.
        """
        rec = self._records()
        out: dict[str, Any] = {name: _json_list(rec[:, i]) for i, name in enumerate(JSON_COLUMNS)}
        out.update(
            stopped_by_warnings=self.stopped_by_warnings, stop_time_s=self.stop_time, stop_reason=self.stop_reason,
            step_unstable=self.step_unstable, stats=None if self.stats is None else self.stats.to_dict(),
            warnings={k: {"count": v["count"], "first_time_s": _json_scalar(v["first_time"]),
                          f"max_{_WARNING_UNITS.get(k, 'value')}": _json_scalar(v["max"])}
                      for k, v in self.warnings.items()},
            speed_m_s=self.speed, chair=self.chair.name,
            settings={k: _json_scalar(v) for k, v in self.settings.items()},
        )
        return out

    # -- output ------------------------------------------------------------
    def to_csv(self, path: str | os.PathLike[str]) -> Path:
        """Write all time histories to a CSV file atomically.

        A few ``#`` comment lines (chair, speed, settings, warnings) precede
        the header row; columns are in SI units and named like ``fy_A``
        (lateral force on the left caster, N).
        """
        rec = self._records()
        meta = [f"# stability.simulate: chair={self.chair.name} speed={self.speed!r} m/s",
                "# settings: " + json.dumps({k: _json_scalar(v) for k, v in self.settings.items()}, sort_keys=True),
                "# warnings: " + json.dumps({k: {kk: _json_scalar(vv) for kk, vv in v.items()}
                                             for k, v in self.warnings.items()}, sort_keys=True)
                + f" stopped_by_warnings={self.stopped_by_warnings}"
                + (f" stop_reason: {self.stop_reason}" if self.stop_reason is not None else ""),
                "# units: s, m, rad, m/s, rad/s, N, deg, N m, rad/s^2; wheels A/B = left/right caster, "
                "D/E = left/right main wheel"]
        lines = meta + [",".join(COLUMNS)]
        lines += [",".join(repr(float(x)) for x in row) for row in rec]
        return atomic_write_text(path, "\n".join(lines) + "\n")

    def plot(self, path_or_ax=None, *, title: str | None = None):
        """Plot the yaw rate against time (and the path): :func:`stability.plotting.responses.plot_result`."""
        from stability.plotting.responses import plot_result  # matplotlib is a heavy optional import

        return plot_result(self, path_or_ax, title=title)


def _json_scalar(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, (np.floating, np.integer)):
        return _json_scalar(v.item())
    if isinstance(v, (str, int, float, bool)) or v is None:
        return v
    return str(v)


def _json_list(a):
    a = np.asarray(a, dtype=float)
    return [float(x) if math.isfinite(x) else None for x in a.tolist()]


def warning_table(warn: np.ndarray) -> dict[str, dict[str, Any]]:
    """A run's range warnings from its counters.

    Parameters
    ----------
    warn : ndarray, shape (3, 3)
        Per kind of :data:`WARNING_KINDS` (program WCHAIR's slip angle > 8 deg
        and normal force > 450 N, and a wheel lifting off, which never stops a
        run): the count, the first time (s), the value of largest magnitude.

    Returns
    -------
    dict
        ``{kind: {"count": int, "first_time": float | None, "max": float | None}}``.
    """
    return {kind: {"count": int(w[0]), "first_time": None if w[0] == 0 else float(w[1]),
                   "max": None if w[0] == 0 else float(w[2])} for kind, w in zip(WARNING_KINDS, warn, strict=True)}


def new_warnings() -> dict[str, dict[str, Any]]:
    """Empty warning counters.

    Returns
    -------
    dict
        :func:`warning_table` of no warning.
    """
    return warning_table(np.zeros((3, 3)))
