"""Nonlinear simulation of a freely rolling wheelchair (thesis chapter 7, program WCHAIR).

The planar full-width model of chapter 6 (:mod:`stability.models`, variant
``"thesis"`` = Table 6-1 as printed, or ``"exact"`` = a first-principles
derivation) is driven by the tire fits of chapter 4 (:mod:`stability.tires`:
lateral force interpolated linearly in slip angle between the integer-degree
cubic fits in normal load, exactly as MECHAN/POLYFT), with normal loads from
quasi-static lateral load transfer (:mod:`stability.loads`, eq 6-25, roll
coefficient k), Coulomb friction at the caster pins, optional rolling
resistance (off by default: TXMOD = CXMOD = 0), main-wheel camber and toe
(as SLIP and MECHAN apply them) and the thesis's range rules (slip angle
above 8 deg, normal load above 450 N) counted per step and reported.

Two integration schemes share that physics:

``scheme="wchair"``
    Program WCHAIR's fixed-step scheme reproduced step for step (Appendix C,
    main loop lines 0314-0328).  Per step, at ``t = k dt``:

    * SLIP: contact-point velocities from the current state, slip angle
      ``|atan(vy/vx)|`` in degrees (toe applied to the main wheels);
    * STATICS: normal loads from the PREVIOUS step's total forces FC1, FC2
      (which include the c.g. impulse FCIMP, as WCHAIR's do); zero at t = 0;
      a load above 450 N is a warning;
    * MECHAN: a slip angle above 8 deg is a warning; tire forces oppose the
      contact velocity; while ``t <= DUIMP`` the main-wheel lateral forces
      are REPLACED by FTIMP (if nonzero); camber force added, toe rotation;
    * DYNAM: pin friction ``SIGN(MAF, -ED)``, exactly zero when ``ED == 0``;
      FC2 includes FCIMP while ``t <= DUIMP``; accelerations from the model,
      the thesis variant's caster equations using the previous step's yaw
      acceleration (DYNAM forms ``Z10 = M*THEDD`` before updating THEDD);
    * UPDATE/ITRATE: constant acceleration over the step,
      ``x += v dt + a dt^2/2`` then ``v += a dt``; the global position is
      advanced with the heading at the start of the step.

    The loop runs ``t = 0, dt, ..., duration + dt`` (WCHAIR's
    ``DO 99 T = 0, TTOTAL+TSTEP, TSTEP``) and, with ``stop_on_warnings``
    (default for this scheme), a run stops at the eleventh warning of a kind
    (``NWARN > 10``: "TEST CASE TERMINATED").  The step that stops a run is
    not recorded.

``scheme="adaptive"``
    An error-controlled integration (:func:`scipy.integrate.solve_ivp`, see
    :data:`ADAPTIVE_METHOD`) of the same model with physically consistent
    details: normal loads consistent with the instantaneous tire forces (the
    algebraic loop solved by fixed-point iteration at every evaluation), the
    c.g. force left out of the load transfer (a force at the c.g. has no
    roll moment about it), no one-step lag in the caster equations, and a
    stick-slip model of Coulomb pin friction: a slipping caster whose rate
    reaches zero sticks if the pin moment needed to hold it is within the
    friction limit, else it reverses; a stuck caster (a locked caster for
    that side, the holding moment solved from its row of the equations)
    breaks away when that moment reaches the limit.  Both transitions are
    located with solve_ivp events and the integration restarts in the new
    mode.  Results are sampled every ``sample`` s (default 0.01 s) from the
    dense output; forces and loads are recomputed at the samples.

Locked casters (``casters="locked"``) hold eta and beta at their initial
angles: the caster rows of the equations are replaced by ``eta_dd = beta_dd
= 0`` and the pin moments become the reactions that enforce it (reported in
``pin_moment``); friction plays no part.  This equals the thesis's
"extremely high I_zp" trick of section "Method Two" without its stiffness.

Sign conventions (SAE): x forward, y to the right, yaw positive clockwise seen
from above; eta (A, left caster) and beta (B, right caster) are measured from
the trailing position.  Front-caster chairs move forward at positive speed
like rear-caster ones (the models use signed coordinates); a positive c.g.
force turns a rear-caster chair to the left (toward the side the push came
from) and a front-caster chair to the right.

Performance: a single run uses Python floats throughout (``math``, the tire
fits' scalar path; about 0.2 s for the 10 s reference run at 1 ms);
:func:`simulate_batch` steps all runs of the WCHAIR scheme together on numpy
arrays and, for large batches, splits them over forked worker processes.
Angles are converted exactly (WCHAIR multiplies by 0.0174532).

Command line::

    python -m stability.simulate --chair ej-premier --speed 0.75 --impulse 40 0.1 --json

Examples
--------
>>> from stability.chair import preset
>>> from stability.simulate import simulate
>>> res = simulate(preset("ej-premier"), 0.75, duration=4.0)   # doctest: +SKIP
>>> round(res.first_time_abs_yaw_rate(1.0), 2)                   # doctest: +SKIP
3.2
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import os
import sys
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np

from . import models as _models
from . import statics as _loads
from . import tires as _tires
from .chair import Chair
from .params import parameters as _parameters
from .progress import ProgressBar

__all__ = [
    "SCHEMES",
    "MODELS",
    "CASTERS",
    "OUT_OF_RANGE_POLICIES",
    "WHEELS",
    "SLIP_LIMIT_DEG",
    "LOAD_LIMIT_N",
    "WARNING_LIMIT",
    "ADAPTIVE_METHOD",
    "ChairState",
    "SimulationResult",
    "simulate",
    "simulate_batch",
    "linearise",
    "main",
]

SCHEMES = ("wchair", "adaptive")
MODELS = ("thesis", "exact")
CASTERS = ("free", "locked")
OUT_OF_RANGE_POLICIES = ("clamp", "extrapolate", "raise")
#: Wheel order of the per-wheel arrays: left caster, right caster, left main, right main.
WHEELS = ("A", "B", "D", "E")
WHEEL_LABELS = {"A": "left caster", "B": "right caster", "D": "left main wheel", "E": "right main wheel"}
#: Largest slip angle of the treadmill data (MECHAN's check).
SLIP_LIMIT_DEG = 8.0
#: Largest normal load of the treadmill data (STATICS's check).
LOAD_LIMIT_N = 450.0
#: WCHAIR stops at the eleventh warning of a kind (``IF (NWARN.GT.10) STOP``).
WARNING_LIMIT = 10
#: solve_ivp method of the adaptive scheme.  LSODA switches automatically
#: between non-stiff Adams and stiff BDF formulas: the caster modes are fast
#: (|lambda| ~ C l^2 / (u I_zp), several hundred 1/s at walking speed) while
#: the yaw divergence takes seconds, so a stiff-aware method takes long steps
#: once the casters settle, and its low order suits a right-hand side that is
#: only piecewise smooth (the tire fits are interpolated linearly between
#: integer slip angles).  See tests/test_simulate.py for the convergence check.
ADAPTIVE_METHOD = "LSODA"
_ADAPTIVE_SAMPLE = 0.01
_BATCH_SAMPLE = 0.01
_MAX_SWITCHES = 20000
_DEADBAND = 1e-10  # rad/s: a slipping caster "reverses" once its rate passes zero by this much

# record columns (internal)
_COLS = ("t", "x", "y", "heading", "yaw_rate", "u", "v", "eta", "eta_dot", "beta", "beta_dot",
         "fx_A", "fy_A", "fx_B", "fy_B", "fx_D", "fy_D", "fx_E", "fy_E",
         "fz_A", "fz_B", "fz_D", "fz_E", "slip_A", "slip_B", "slip_D", "slip_E",
         "tire_yaw_moment", "yaw_moment_input", "yaw_acceleration", "pin_moment_A", "pin_moment_B")
_NC = len(_COLS)


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
def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=float)
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
    stopped_by_warnings : whether the run was stopped by the warning rule.
    stop_time : time of the step that stopped it (s) or None.
    chair, speed, settings : the inputs.
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

    # -- construction ----------------------------------------------------
    @classmethod
    def _from_records(cls, rec: np.ndarray, *, warnings, stopped, stop_time, chair, speed, settings):
        cols = np.ascontiguousarray(rec.T, dtype=float)  # one copy; every column below is a view of it
        c = {name: cols[i] for i, name in enumerate(_COLS)}

        def wheels(prefix):
            return _frozen(np.stack([c[f"{prefix}_{w}"] for w in WHEELS], axis=1).reshape(-1, 4))

        return cls(
            t=_frozen(c["t"]), x=_frozen(c["x"]), y=_frozen(c["y"]), heading=_frozen(c["heading"]),
            yaw_rate=_frozen(c["yaw_rate"]), u=_frozen(c["u"]), v=_frozen(c["v"]),
            eta=_frozen(c["eta"]), eta_dot=_frozen(c["eta_dot"]), beta=_frozen(c["beta"]),
            beta_dot=_frozen(c["beta_dot"]), fx=wheels("fx"), fy=wheels("fy"),
            normal_load=wheels("fz"), slip_deg=wheels("slip"),
            tire_yaw_moment=_frozen(c["tire_yaw_moment"]),
            yaw_moment_input=_frozen(c["yaw_moment_input"]),
            yaw_acceleration=_frozen(c["yaw_acceleration"]),
            pin_moment=_frozen(np.stack([c["pin_moment_A"], c["pin_moment_B"]], axis=1).reshape(-1, 2)),
            warnings=_freeze_warnings(warnings), stopped_by_warnings=bool(stopped),
            stop_time=None if stop_time is None else float(stop_time), chair=chair,
            speed=float(speed), settings=dict(settings),
        )

    def _records(self) -> np.ndarray:
        """All columns of :data:`_COLS` as one ``(n, 32)`` array."""
        per_wheel = {"fx": self.fx, "fy": self.fy, "fz": self.normal_load, "slip": self.slip_deg}
        cols = []
        for name in _COLS:
            prefix, _, last = name.rpartition("_")
            if prefix in per_wheel and last in WHEELS:
                cols.append(per_wheel[prefix][:, WHEELS.index(last)])
            elif prefix == "pin_moment":
                cols.append(self.pin_moment[:, "AB".index(last)])
            else:
                cols.append(getattr(self, name))
        return np.column_stack(cols) if len(self.t) else np.zeros((0, _NC))

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
        a = np.abs(self.yaw_rate)
        hit = np.flatnonzero(a >= value)
        if hit.size == 0:
            return None
        i = int(hit[0])
        if i == 0:
            return float(self.t[0])
        a0, a1 = a[i - 1], a[i]
        t0, t1 = self.t[i - 1], self.t[i]
        return float(t0 + (value - a0) / (a1 - a0) * (t1 - t0))

    def at(self, time: float) -> dict[str, float]:
        """All scalar quantities linearly interpolated at ``time`` (s)."""
        rec = self._records()
        if not len(self.t) or not self.t[0] <= time <= self.t[-1]:
            raise ValueError(f"time={time!r} is outside the simulated span [{self.t[0] if len(self.t) else 0}, "
                             f"{self.t[-1] if len(self.t) else 0}] s")
        return {name: float(np.interp(time, self.t, rec[:, i])) for i, name in enumerate(_COLS)}

    def resample(self, dt: float) -> SimulationResult:
        """The result linearly interpolated on ``t0, t0 + dt, ...`` (s)."""
        dt = _positive("dt", dt)
        if len(self.t) < 2:
            return self
        n = int(math.floor((self.t[-1] - self.t[0]) / dt * (1 + 1e-12) + 1e-9)) + 1
        tt = self.t[0] + dt * np.arange(n)
        tt[-1] = min(tt[-1], self.t[-1])
        rec = self._records()
        out = np.empty((n, _NC))
        out[:, 0] = tt
        for i in range(1, _NC):
            out[:, i] = np.interp(tt, self.t, rec[:, i])
        settings = dict(self.settings, resampled=dt)
        return SimulationResult._from_records(out, warnings=self.warnings, stopped=self.stopped_by_warnings,
                                              stop_time=self.stop_time, chair=self.chair, speed=self.speed,
                                              settings=settings)

    def summary(self) -> str:
        """A short readable summary."""
        s = self.settings
        lines = [
            f"chair {self.chair.name} ({self.chair.caster_position} casters), speed {self.speed:g} m/s, "
            f"model {s.get('model')}, scheme {s.get('scheme')}, casters {s.get('casters')}",
            f"simulated {self.t[0]:.3f} .. {self.t[-1]:.3f} s ({len(self.t)} samples)"
            + (f"; STOPPED by warnings at t = {self.stop_time:.3f} s" if self.stopped_by_warnings else ""),
        ]
        for v in (0.5, 1.0):
            tv = self.first_time_abs_yaw_rate(v)
            lines.append(f"|yaw rate| never reaches {v:g} rad/s" if tv is None
                         else f"|yaw rate| reaches {v:g} rad/s at {tv:.3f} s")
        if len(self.t):
            lines.append(f"final: yaw rate {self.yaw_rate[-1]:+.4f} rad/s, heading "
                         f"{math.degrees(self.heading[-1]):+.2f} deg, position ({self.x[-1]:.3f}, {self.y[-1]:.3f}) m, "
                         f"max |yaw rate| {np.max(np.abs(self.yaw_rate)):.4f} rad/s")
        w = ", ".join(f"{k}: {v['count']}" + (f" (first at {v['first_time']:.3f} s)" if v["first_time"] is not None else "")
                      for k, v in self.warnings.items())
        lines.append(f"warnings: {w}")
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict (non-finite numbers become ``None``)."""
        rec = self._records()
        out: dict[str, Any] = {name: _json_list(rec[:, i]) for i, name in enumerate(_COLS)}
        out.update(
            stopped_by_warnings=self.stopped_by_warnings, stop_time=self.stop_time,
            warnings=_json_warnings(self.warnings), speed=self.speed, chair=self.chair.name,
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
        from .output import atomic_write_text

        rec = self._records()
        meta = [f"# stability.simulate: chair={self.chair.name} speed={self.speed!r} m/s",
                "# settings: " + json.dumps({k: _json_scalar(v) for k, v in self.settings.items()}, sort_keys=True),
                "# warnings: " + json.dumps(_json_warnings(self.warnings), sort_keys=True)
                + f" stopped_by_warnings={self.stopped_by_warnings}",
                "# units: s, m, rad, m/s, rad/s, N, deg, N m, rad/s^2; wheels A/B = left/right caster, "
                "D/E = left/right main wheel"]
        lines = meta + [",".join(_COLS)]
        lines += [",".join(repr(float(x)) for x in row) for row in rec]
        return atomic_write_text(path, "\n".join(lines) + "\n")

    def plot(self, path_or_ax=None, *, title: str | None = None):
        """Plot the yaw rate against time.

        ``path_or_ax`` is a matplotlib Axes (drawn on, returned) or a file
        path (a figure with yaw rate and trajectory is written atomically;
        PDFs through :func:`stability.output.write_pdf`); ``None`` returns a
        new figure.
        """
        label = f"{self.chair.name}, {self.speed:g} m/s"
        if title is None:
            title = (f"{self.chair.name} ({self.chair.caster_position} casters): "
                     f"{self.settings.get('model')} model, {self.settings.get('scheme')} scheme")
        if path_or_ax is not None and hasattr(path_or_ax, "plot") and hasattr(path_or_ax, "set_xlabel"):
            ax = path_or_ax
            ax.plot(self.t, self.yaw_rate, label=label)
            ax.set_xlabel("time (s)")
            ax.set_ylabel("yaw rate (rad/s)")
            ax.set_title(title)
            ax.legend()
            ax.grid(True, alpha=0.3)
            return ax
        from matplotlib.figure import Figure

        fig = Figure(figsize=(8.0, 6.5))
        ax1, ax2 = fig.subplots(2, 1)
        ax1.plot(self.t, self.yaw_rate, label=label)
        if self.stopped_by_warnings and self.stop_time is not None:
            ax1.axvline(self.stop_time, color="k", ls=":", lw=0.8, label="stopped by warnings")
        ax1.set_xlabel("time (s)")
        ax1.set_ylabel("yaw rate (rad/s)")
        ax1.set_title(title)
        ax1.legend()
        ax1.grid(True, alpha=0.3)
        ax2.plot(self.x, self.y, label="c.g. path")
        ax2.set_xlabel("X (m)")
        ax2.set_ylabel("Y (m, to the right)")
        ax2.invert_yaxis()
        ax2.set_aspect("equal", adjustable="datalim")
        ax2.legend()
        ax2.grid(True, alpha=0.3)
        fig.tight_layout()
        if path_or_ax is None:
            return fig
        return _save_figure(fig, path_or_ax, title)


def _save_figure(fig, path, title):
    from .output import save_figure

    return save_figure(fig, path, title=title)


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


def _json_warnings(w):
    return {k: {kk: _json_scalar(vv) for kk, vv in v.items()} for k, v in w.items()}


def _freeze_warnings(w):
    return {k: dict(v) for k, v in w.items()}


# ---------------------------------------------------------------------------
# options
# ---------------------------------------------------------------------------
def _positive(name, value, *, allow_inf=False):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is invalid; valid range: a number > 0") from None
    if math.isnan(x) or x <= 0 or (math.isinf(x) and not allow_inf):
        raise ValueError(f"{name}={value!r} is invalid; valid range: {'> 0' if allow_inf else 'finite > 0'}")
    return x


def _finite(name, value, unit=""):
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r} is invalid; valid range: a finite number{unit}") from None
    if not math.isfinite(x):
        raise ValueError(f"{name}={value!r} is invalid; valid range: a finite number{unit}")
    return x


def _choice(name, value, choices):
    if value not in choices:
        raise ValueError(f"{name}={value!r} is invalid; valid choices: {list(choices)}")
    return value


@dataclass(frozen=True)
class _Options:
    duration: float
    scheme: str
    model: str
    dt: float
    impulse_force: float
    impulse_duration: float
    tire_impulse: float
    lateral_velocity: float
    eta0: float
    beta0: float
    casters: str
    yaw_moment: Callable | None
    stop_on_warnings: bool
    out_of_range: str
    sample: float | None
    stride: int
    rtol: float
    atol: float
    reverse: bool

    def step_constants(self) -> tuple:
        """What the WCHAIR loops read every step, as locals:
        ``(dt, dt^2/2, locked, thesis, yaw_moment, stop_on_warnings, stride, impulse_force)``."""
        return (self.dt, 0.5 * self.dt * self.dt, self.casters == "locked", self.model == "thesis",
                self.yaw_moment, self.stop_on_warnings, self.stride, self.impulse_force)

    def settings(self) -> dict[str, Any]:
        d = {
            "scheme": self.scheme, "model": self.model, "duration": self.duration, "casters": self.casters,
            "impulse_force": self.impulse_force, "impulse_duration": self.impulse_duration,
            "tire_impulse": self.tire_impulse, "lateral_velocity": self.lateral_velocity,
            "eta0_deg": math.degrees(self.eta0), "beta0_deg": math.degrees(self.beta0),
            "stop_on_warnings": self.stop_on_warnings, "out_of_range": self.out_of_range,
            "sample": self.sample, "yaw_moment": None if self.yaw_moment is None else getattr(
                self.yaw_moment, "__name__", type(self.yaw_moment).__name__),
            "reverse": self.reverse,
        }
        if self.scheme == "wchair":
            d["dt"] = self.dt
        else:
            d.update(rtol=self.rtol, atol=self.atol, method=ADAPTIVE_METHOD)
        return d


def _make_options(*, duration, scheme, model, dt, impulse_force, impulse_duration, tire_impulse,
                  lateral_velocity, eta0_deg, beta0_deg, casters, yaw_moment, stop_on_warnings, out_of_range,
                  sample, rtol, atol, reverse, batch=False) -> _Options:
    scheme = _choice("scheme", scheme, SCHEMES)
    model = _choice("model", model, MODELS)
    casters = _choice("casters", casters, CASTERS)
    out_of_range = _choice("out_of_range", out_of_range, OUT_OF_RANGE_POLICIES)
    duration = _positive("duration", duration)
    dt = _positive("dt", dt)
    if scheme == "wchair" and dt > duration:
        raise ValueError(f"dt={dt!r} is invalid; valid range: 0 < dt <= duration = {duration!r} s")
    impulse_force = _finite("impulse_force", impulse_force, " (N)")
    try:
        impulse_duration = float(impulse_duration)
    except (TypeError, ValueError):
        impulse_duration = math.nan
    if math.isnan(impulse_duration) or impulse_duration < 0:
        raise ValueError(f"impulse_duration={impulse_duration!r} is invalid; valid range: >= 0 s (inf: constant force)")
    tire_impulse = _finite("tire_impulse", tire_impulse, " (N)")
    lateral_velocity = _finite("lateral_velocity", lateral_velocity, " (m/s)")
    eta0 = math.radians(_finite("eta0_deg", eta0_deg, " (deg)"))
    beta0 = math.radians(_finite("beta0_deg", beta0_deg, " (deg)"))
    if yaw_moment is not None and not callable(yaw_moment):
        raise ValueError(f"yaw_moment={yaw_moment!r} is invalid; expected a callable yaw_moment(t, state) -> N m")
    if stop_on_warnings is None:
        stop_on_warnings = scheme == "wchair"
    stop_on_warnings = bool(stop_on_warnings)
    if sample is None and (scheme == "adaptive" or batch):
        if scheme == "adaptive":
            sample = min(_ADAPTIVE_SAMPLE, duration)
        else:  # the multiple of dt nearest to 0.01 s
            sample = dt * max(1, int(round(_BATCH_SAMPLE / dt)))
            sample = min(sample, dt * max(1, int(duration / dt)))
    stride = 1
    if sample is not None:
        sample = _positive("sample", sample)
        if sample > duration:
            raise ValueError(f"sample={sample!r} is invalid; valid range: 0 < sample <= duration = {duration!r} s")
        if scheme == "wchair":
            ratio = sample / dt
            stride = int(round(ratio))
            if stride < 1 or abs(ratio - stride) > 1e-6 * ratio:
                raise ValueError(f"sample={sample!r} is invalid for scheme 'wchair'; valid values: a whole "
                                 f"multiple of dt = {dt!r} s")
    rtol = _positive("rtol", rtol)
    atol = _positive("atol", atol)
    if rtol < 1e-13:
        raise ValueError(f"rtol={rtol!r} is invalid; valid range: rtol >= 1e-13")
    return _Options(duration, scheme, model, dt, impulse_force, impulse_duration, tire_impulse,
                    lateral_velocity, eta0, beta0, casters, yaw_moment, stop_on_warnings, out_of_range,
                    sample, stride, rtol, atol, bool(reverse))


# ---------------------------------------------------------------------------
# shared physics glue (floats or arrays)
# ---------------------------------------------------------------------------
class _MathOps:
    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)
    atan2 = staticmethod(math.atan2)
    copysign = staticmethod(math.copysign)
    degrees = staticmethod(math.degrees)


class _NumpyOps:
    cos = staticmethod(np.cos)
    sin = staticmethod(np.sin)
    atan2 = staticmethod(np.arctan2)
    copysign = staticmethod(np.copysign)
    degrees = staticmethod(np.degrees)


_NO_FORCE = 0.0  # the longitudinal forces when rolling resistance is off (identity-tested)


def _shared_scalars(p):
    """Params with every field that is equal across the batch as a Python float."""
    return type(p)(*(float(f[0]) if np.ndim(f) and np.all(f == f[0]) else f for f in p))


def _ops(x):
    """math for Python floats, numpy for arrays."""
    return _NumpyOps if isinstance(x, np.ndarray) else _MathOps


class _TireGroup:
    """The tires of one group of runs (same tire models, scales, camber)."""

    def __init__(self, chair: Chair, opts: _Options):
        from . import tires

        self.main = chair.main_tire_model()
        self.caster = chair.caster_tire_model()
        self.main_rolling = chair.main_rolling_scale != 0
        self.caster_rolling = chair.caster_rolling_scale != 0
        self.camber_coefficient = chair.camber_coefficient
        if opts.scheme == "wchair":
            # MECHAN 0729-0733: CAMCOF * POLYFT(TIRY, INT(CAMANG), FZ): whole
            # degrees, the unscaled tire (TYMOD does not apply).
            self.camber_tire = tires.get(chair.main_tire)
            self.camber_deg = float(math.trunc(chair.camber_deg))
        else:
            self.camber_tire = self.main
            self.camber_deg = float(chair.camber_deg)
        # the treadmill range (8 deg, 450 N) applies to tested tires only
        self.check_main = isinstance(self.main, tires.Tire)
        self.check_caster = isinstance(self.caster, tires.Tire)

    @staticmethod
    def key(chair: Chair):
        return (chair.main_tire, chair.main_lateral_scale, chair.main_rolling_scale, chair.caster_tire,
                chair.caster_lateral_scale, chair.caster_rolling_scale, chair.camber_deg, chair.camber_coefficient)


class _Kernel:
    """Everything the physics glue needs: parameters, tires, options.

    The equations are the generated functions behind :mod:`stability.models`
    (:mod:`stability._generated.full_width`), looked up once here so that a
    step does not pay the facade's per-call dispatch.  In a batch, parameters
    shared by all runs are passed as Python floats (fewer array operations).
    """

    def __init__(self, chairs: Sequence[Chair], opts: _Options, vector: bool):
        fw = _models.full_width.generated
        self.vector = vector
        self.variant = opts.model
        self.policy = opts.out_of_range
        self.opts = opts
        self.cv_fn = getattr(fw, f"contact_velocities_{opts.model}")
        self.acc_fn = getattr(fw, f"accelerations_{opts.model}")
        self.thesis = opts.model == "thesis"
        if vector:
            self.p = _shared_scalars(_parameters(list(chairs)))
            keys = [_TireGroup.key(c) for c in chairs]
            uniq: dict = {}
            for i, k in enumerate(keys):
                uniq.setdefault(k, []).append(i)
            self.groups = [(_TireGroup(chairs[idx[0]], opts), np.array(idx)) for idx in uniq.values()]
            toe = np.array([math.radians(c.toe_deg) for c in chairs])
            self.toe = bool(np.any(toe != 0))
            self.ct, self.st = np.cos(toe), np.sin(toe)
        else:
            c = chairs[0]
            self.p = _parameters(c)
            self.groups = [(_TireGroup(c, opts), None)]
            toe = math.radians(c.toe_deg)
            self.toe = toe != 0
            self.ct, self.st = math.cos(toe), math.sin(toe)
        self.maf = self.p.pin_friction_left
        self.mbf = self.p.pin_friction_right
        self.geom = self.p.geometry
        self.inertia = self.p.inertia
        self.single_group = len(self.groups) == 1
        self.any_camber = any(g.camber_deg != 0 for g, _ in self.groups)
        self.any_rolling = any(g.main_rolling or g.caster_rolling for g, _ in self.groups)
        self._range_masks()
        self.ftimp = opts.tire_impulse
        self.duimp = opts.impulse_duration
        self.stack = None
        if self.single_group:  # bind the tire calls once (hot path)
            g0 = self.groups[0][0]
            pol = self.policy
            if vector and isinstance(g0.caster, _tires.Tire) and isinstance(g0.main, _tires.Tire):
                # all four wheels of every run in one call (rows A, B, D, E)
                self.stack = _tires.TireStack((g0.caster, g0.caster, g0.main, g0.main))
            cl, ml = g0.caster.lateral_force, g0.main.lateral_force
            self.caster_lateral = lambda slip, fz: cl(slip, fz, policy=pol, warn=False)
            self.main_lateral = lambda slip, fz: ml(slip, fz, policy=pol, warn=False)

    def _range_masks(self) -> None:
        """Which wheels the thesis's range rules apply to (tested tires only)."""
        g0 = self.groups[0][0]
        if self.single_group:
            self.chk = (g0.check_caster, g0.check_caster, g0.check_main, g0.check_main)
            self.check_all = all(self.chk)
            self.chk_mask = None
            return
        n = sum(int(i.size) for _, i in self.groups)
        m = np.zeros((4, n), dtype=bool)
        for g, idx in self.groups:
            m[0:2, idx] = g.check_caster
            m[2:4, idx] = g.check_main
        self.chk = None
        self.check_all = bool(m.all())
        self.chk_mask = None if self.check_all else m

    def compact(self, keep: np.ndarray) -> None:
        """Keep only the runs at positions ``keep`` (batch path)."""
        self.p = type(self.p)(*(f[keep] if np.ndim(f) else f for f in self.p))
        self.maf = self.p.pin_friction_left
        self.mbf = self.p.pin_friction_right
        self.geom = self.p.geometry
        self.inertia = self.p.inertia
        if self.toe:
            self.ct, self.st = self.ct[keep], self.st[keep]
        if not self.single_group:
            pos = np.full(int(max(np.max(i) for _, i in self.groups)) + 1, -1)
            pos[keep] = np.arange(len(keep))
            self.groups = [(g, pos[i][pos[i] >= 0]) for g, i in self.groups]
            if self.chk_mask is not None:
                self.chk_mask = self.chk_mask[:, keep]

    # -- tire calls (dispatch over groups for batches) ----------------------
    def _per_group(self, fn, *arrays):
        if self.single_group:
            return fn(self.groups[0][0], *arrays)
        out = np.zeros(np.shape(arrays[0]))
        for g, idx in self.groups:
            if idx.size:
                out[idx] = fn(g, *(a[idx] for a in arrays))
        return out

    def caster_lateral(self, slip, fz):
        pol = self.policy
        return self._per_group(lambda g, s, f: g.caster.lateral_force(s, f, policy=pol, warn=False), slip, fz)

    def main_lateral(self, slip, fz):
        pol = self.policy
        return self._per_group(lambda g, s, f: g.main.lateral_force(s, f, policy=pol, warn=False), slip, fz)

    def caster_rolling(self, fz, vx):
        xp = _ops(vx)
        return self._per_group(
            lambda g, f, w: xp.copysign(g.caster.rolling_resistance(f), -w) if g.caster_rolling else 0.0 * f, fz, vx)

    def main_rolling(self, fz, vx):
        xp = _ops(vx)
        return self._per_group(
            lambda g, f, w: xp.copysign(g.main.rolling_resistance(f), -w) if g.main_rolling else 0.0 * f, fz, vx)

    def camber(self, fz):
        return self._per_group(
            lambda g, f: (g.camber_tire.camber_force(g.camber_deg, f, g.camber_coefficient, policy=self.policy,
                                                     warn=False) if g.camber_deg != 0 else 0.0 * f), fz)


def _kinematics(K: _Kernel, u, v, r, ce, se, cb, sb, ed, bd):
    """Contact velocities (SLIP), main wheels in their toed wheel frames."""
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = K.cv_fn(u, v, r, ce, se, cb, sb, ed, bd, *K.geom)
    if K.toe:  # SLIP lines 0564-0573: right wheel turned by +toe, left by -toe
        ct, st = K.ct, K.st
        vEx, vEy = vEx * ct + vEy * st, -vEx * st + vEy * ct
        vDx, vDy = vDx * ct - vDy * st, vDx * st + vDy * ct
    return vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy


def _slips(K: _Kernel, vel):
    """Signed slip angles (deg): atan2(vy, |vx|); WCHAIR's SLIPx = abs of these."""
    xp = _ops(vel[1])
    a2, dg = xp.atan2, xp.degrees
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    return (dg(a2(vAy, abs(vAx))), dg(a2(vBy, abs(vBx))), dg(a2(vDy, abs(vDx))), dg(a2(vEy, abs(vEx))))


def _tire_forces(K: _Kernel, impulse_on: bool, vel, slips, NA, NB, ND, NE, S4=None, N4=None):
    """MECHAN: tire forces (casters in their frames, main wheels in body axes).

    ``S4``, ``N4`` (batch path): the slips and loads stacked as ``(4, n)``
    arrays, so that both wheels of a pair go through one tire call.
    """
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    sA, sB, sD, sE = slips
    ftimp_on = K.ftimp != 0.0 and impulse_on
    if S4 is not None and K.stack is not None:
        FAy, FBy, FDy, FEy = K.stack.lateral_force(S4, N4, policy=K.policy)
    elif S4 is not None and K.single_group:
        m = S4.shape[1]
        lat = K.caster_lateral(S4[0:2].reshape(-1), N4[0:2].reshape(-1))
        FAy, FBy = lat[:m], lat[m:]
        if not ftimp_on:
            lat = K.main_lateral(S4[2:4].reshape(-1), N4[2:4].reshape(-1))
            FDy, FEy = lat[:m], lat[m:]
    else:
        FAy = K.caster_lateral(sA, NA)
        FBy = K.caster_lateral(sB, NB)
        if not ftimp_on:
            FDy = K.main_lateral(sD, ND)
            FEy = K.main_lateral(sE, NE)
    if ftimp_on:  # MECHAN 0704-0706: FTIMP replaces FDY, FEY
        FDy = K.ftimp + 0.0 * ND
        FEy = K.ftimp + 0.0 * NE
    if K.any_rolling:
        FAx = K.caster_rolling(NA, vAx)
        FBx = K.caster_rolling(NB, vBx)
        FDx = K.main_rolling(ND, vDx)
        FEx = K.main_rolling(NE, vEx)
    else:
        FAx = FBx = FDx = FEx = _NO_FORCE
    if K.any_camber:  # MECHAN 0729-0733: tops inward push the left wheel right, the right wheel left
        FDy = FDy + K.camber(ND)
        FEy = FEy - K.camber(NE)
    if K.toe:  # MECHAN 0734-0743: back to body axes
        ct, st = K.ct, K.st
        FEx, FEy = FEx * ct - FEy * st, FEx * st + FEy * ct
        FDx, FDy = FDx * ct + FDy * st, -FDx * st + FDy * ct
    return FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy


def _resultant(F, ce, se, cb, sb):
    """Total tire force in body axes (DYNAM's FC1, FC2 without FCIMP)."""
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    if FAx is _NO_FORCE and FBx is _NO_FORCE and FDx is _NO_FORCE and FEx is _NO_FORCE:  # no rolling, no toe
        return -(FAy * se + FBy * sb), FDy + FEy + FAy * ce + FBy * cb
    fc1 = FDx + FEx + FAx * ce - FAy * se + FBx * cb - FBy * sb
    fc2 = FDy + FEy + FAx * se + FAy * ce + FBx * sb + FBy * cb
    return fc1, fc2


def _tire_yaw_moment(p, F, ce, se, cb, sb):
    """Yaw moment of the tire forces about the c.g. (N m, clockwise from above)."""
    FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
    l = p.trail
    xa, ya = p.x_p - l * ce, -p.t1 - l * se
    xb, yb = p.x_p - l * cb, p.t2 - l * sb
    fax, fay = FAx * ce - FAy * se, FAx * se + FAy * ce
    fbx, fby = FBx * cb - FBy * sb, FBx * sb + FBy * cb
    return (xa * fay - ya * fax + xb * fby - yb * fbx + p.x_m * (FDy + FEy) + p.d1 * FDx - p.d2 * FEx)


def _accelerations(K: _Kernel, state, F, M_A, M_B, fy_ext, mz, rdc=None):
    """(u_dot, v_dot, r_dot, eta_dd, beta_dd) from the model (DYNAM)."""
    u, v, r, ce, se, cb, sb, ed, bd = state
    if K.thesis:
        return K.acc_fn(u, v, r, ce, se, cb, sb, ed, bd, *F, M_A, M_B, fy_ext, mz, *K.inertia, r_dot_casters=rdc)
    return K.acc_fn(u, v, r, ce, se, cb, sb, ed, bd, *F, M_A, M_B, fy_ext, mz, *K.inertia)


def _held_accelerations(K: _Kernel, state, F, M_A, M_B, fy_ext, mz, hold_a, hold_b, rdc=None):
    """Accelerations with caster A and/or B held (eta_dd = 0 and/or beta_dd = 0).

    The equations are affine in the pin moments, so the holding moments are
    solved from two or three evaluations.  Returns ``(acc, M_A, M_B)`` with
    the held sides' moments replaced by the reactions.
    """
    if not (hold_a or hold_b):
        return _accelerations(K, state, F, M_A, M_B, fy_ext, mz, rdc), M_A, M_B
    base_a = 0.0 * M_A if hold_a else M_A
    base_b = 0.0 * M_B if hold_b else M_B
    a0 = _accelerations(K, state, F, base_a, base_b, fy_ext, mz, rdc)
    if hold_a and hold_b:
        a1 = _accelerations(K, state, F, base_a + 1.0, base_b, fy_ext, mz, rdc)
        a2 = _accelerations(K, state, F, base_a, base_b + 1.0, fy_ext, mz, rdc)
        k11, k21 = a1[3] - a0[3], a1[4] - a0[4]
        k12, k22 = a2[3] - a0[3], a2[4] - a0[4]
        det = k11 * k22 - k12 * k21
        ma = (-a0[3] * k22 + a0[4] * k12) / det
        mb = (-a0[4] * k11 + a0[3] * k21) / det
        acc = tuple(a0[i] + ma * (a1[i] - a0[i]) + mb * (a2[i] - a0[i]) for i in range(3)) + (0.0 * ma, 0.0 * mb)
        return acc, ma, mb
    if hold_a:
        a1 = _accelerations(K, state, F, base_a + 1.0, base_b, fy_ext, mz, rdc)
        ma = -a0[3] / (a1[3] - a0[3])
        acc = tuple(a0[i] + ma * (a1[i] - a0[i]) for i in range(5))
        return acc[:3] + (0.0 * ma, acc[4]), ma, M_B
    a2 = _accelerations(K, state, F, base_a, base_b + 1.0, fy_ext, mz, rdc)
    mb = -a0[4] / (a2[4] - a0[4])
    acc = tuple(a0[i] + mb * (a2[i] - a0[i]) for i in range(5))
    return acc[:4] + (0.0 * mb,), M_A, mb


def _n_steps(opts: _Options) -> int:
    """Iterations of ``DO 99 T = 0, TTOTAL+TSTEP, TSTEP`` (F77 trip count)."""
    return int(math.floor((opts.duration + 2.0 * opts.dt) / opts.dt + 1e-9))


def _impulse_on(opts: _Options, t: float) -> bool:
    # WCHAIR tests T .LE. DUIMP with T accumulated in REAL; here t = k*dt and
    # a relative tolerance keeps the inclusive test exact at t = DUIMP.
    return t <= opts.impulse_duration * (1.0 + 1e-12) + 1e-15


def _new_warnings():
    return {k: {"count": 0, "first_time": None, "max": None} for k in ("slip", "load", "lift_off")}


def _note(w, kind, t, value):
    d = w[kind]
    d["count"] += 1
    if d["first_time"] is None:
        d["first_time"] = float(t)
    d["max"] = float(value) if d["max"] is None else max(d["max"], float(value), key=abs)


def _initial(opts: _Options, speed: float):
    u0 = -speed if opts.reverse else speed
    return u0, opts.lateral_velocity


# ---------------------------------------------------------------------------
# scheme "wchair": one run, Python floats
# ---------------------------------------------------------------------------
def _wchair_single(chair: Chair, speed: float, opts: _Options) -> SimulationResult:
    K = _Kernel([chair], opts, vector=False)
    p = K.p
    dt, half_dt2, locked, thesis, yaw_fn, stop, stride, fcimp = opts.step_constants()
    cos, sin = math.cos, math.sin
    loads_fn = _loads.normal_loads
    maf, mbf = K.maf, K.mbf
    check_all, chk = K.check_all, K.chk

    UD, VD = _initial(opts, speed)
    X = Y = THE = THED = THEDD = 0.0
    E, B = opts.eta0, opts.beta0
    ED = BD = 0.0
    FC1 = FC2 = 0.0
    warn = _new_warnings()
    nwarn_load = nwarn_slip = 0
    stopped = False
    stop_time = None
    rec = []
    n = _n_steps(opts)
    for k in range(n):
        t = k * dt
        ce, se, cb, sb = cos(E), sin(E), cos(B), sin(B)
        # SLIP
        vel = _kinematics(K, UD, VD, THED, ce, se, cb, sb, ED, BD)
        slips = _slips(K, vel)
        # STATICS (previous step's FC1, FC2)
        NA, NB, ND, NE = loads_fn(p, FC1, FC2, ce, se, cb, sb)
        nmax = max(NA, NB, ND, NE) if check_all else max(
            (n_ for n_, c_ in zip((NA, NB, ND, NE), chk) if c_), default=0.0)
        if nmax > LOAD_LIMIT_N:
            nwarn_load += 1
            _note(warn, "load", t, nmax)
            if stop and nwarn_load > WARNING_LIMIT:
                stopped, stop_time = True, t
                break
        nmin = min(NA, NB, ND, NE)
        if nmin < 0.0:
            _note(warn, "lift_off", t, nmin)
        # MECHAN
        smax = max(abs(slips[0]), abs(slips[1]), abs(slips[2]), abs(slips[3])) if check_all else max(
            (abs(s_) for s_, c_ in zip(slips, chk) if c_), default=0.0)
        if smax > SLIP_LIMIT_DEG:
            nwarn_slip += 1
            _note(warn, "slip", t, smax)
            if stop and nwarn_slip > WARNING_LIMIT:
                stopped, stop_time = True, t
                break
        imp = _impulse_on(opts, t)
        F = _tire_forces(K, imp, vel, slips, NA, NB, ND, NE)
        # DYNAM
        fc1, fc2 = _resultant(F, ce, se, cb, sb)
        fy_ext = fcimp if (fcimp != 0.0 and imp) else 0.0
        mz = 0.0 if yaw_fn is None else float(yaw_fn(t, ChairState(X, Y, THE, UD, VD, THED, E, ED, B, BD, 0)))
        state = (UD, VD, THED, ce, se, cb, sb, ED, BD)
        rdc = THEDD if thesis else None
        if locked:
            acc, MA, MB = _held_accelerations(K, state, F, 0.0, 0.0, fy_ext, mz, True, True, rdc)
        else:
            MA = math.copysign(maf, -ED) if ED != 0.0 else 0.0
            MB = math.copysign(mbf, -BD) if BD != 0.0 else 0.0
            acc = _accelerations(K, state, F, MA, MB, fy_ext, mz, rdc)
        UDD, VDD, THEDD, EDD, BDD = acc
        if locked:
            EDD = BDD = 0.0
        if k % stride == 0:
            rec.append((t, X, Y, THE, THED, UD, VD, E, ED, B, BD, *F, NA, NB, ND, NE, *slips,
                        _tire_yaw_moment(p, F, ce, se, cb, sb), mz, THEDD, MA, MB))
        # UPDATE / ITRATE
        FC1, FC2 = fc1, fc2 + fy_ext
        du = UD * dt + UDD * half_dt2
        dv = VD * dt + VDD * half_dt2
        cost, sint = cos(THE), sin(THE)
        X += du * cost - dv * sint
        Y += du * sint + dv * cost
        UD += UDD * dt
        VD += VDD * dt
        B += BD * dt + BDD * half_dt2
        BD += BDD * dt
        E += ED * dt + EDD * half_dt2
        ED += EDD * dt
        THE += THED * dt + THEDD * half_dt2
        THED += THEDD * dt
    arr = np.array(rec, dtype=float).reshape(-1, _NC)
    return SimulationResult._from_records(arr, warnings=warn, stopped=stopped, stop_time=stop_time, chair=chair,
                                          speed=speed, settings=opts.settings())


# ---------------------------------------------------------------------------
# scheme "wchair": a batch, numpy arrays over runs
# ---------------------------------------------------------------------------
def _wchair_batch(chairs: list[Chair], speeds: np.ndarray, opts: _Options, progress: bool,
                  bar: ProgressBar | None = None, forces: np.ndarray | None = None) -> list[SimulationResult]:
    """All runs stepped together; ``forces``: per-run impulse force (N) instead of ``opts.impulse_force``."""
    nrun = len(chairs)
    K = _Kernel(chairs, opts, vector=True)
    dt, half_dt2, locked, thesis, yaw_fn, stop, stride, fcimp = opts.step_constants()
    if forces is not None:
        fcimp = np.array(forces, dtype=float)
    n = _n_steps(opts)
    nrec = (n - 1) // stride + 1
    buf = np.empty((nrun, nrec, _NC))   # rows beyond a run's length are never read
    nrec_run = np.zeros(nrun, dtype=int)
    stop_time = np.full(nrun, np.nan)
    stopped = np.zeros(nrun, dtype=bool)
    cnt = {k: np.zeros(nrun, dtype=int) for k in ("slip", "load", "lift_off")}
    first = {k: np.full(nrun, np.nan) for k in cnt}
    vmax = {k: np.full(nrun, np.nan) for k in cnt}

    run = np.arange(nrun)
    u0, v0 = _initial(opts, 1.0)
    # velocities Sv = (UD, VD, THED, ED, BD) and angles Sp = (THE, E, B) stacked:
    # ITRATE is then a few operations on (5, n) and (3, n) arrays
    Sv = np.zeros((5, nrun))
    Sv[0] = np.asarray(speeds, dtype=float) * u0
    Sv[1] = v0
    Sp = np.zeros((3, nrun))
    Sp[1], Sp[2] = opts.eta0, opts.beta0
    UD, VD, THED, ED, BD = Sv
    THE, E, B = Sp
    z = np.zeros(nrun)
    X, Y, THEDD = z.copy(), z.copy(), z.copy()
    FC1, FC2 = z.copy(), z.copy()
    p_loads = _loads.normal_loads
    rad2deg = 180.0 / math.pi

    def flag(kind, mask, t, values):
        if not mask.any():
            return
        idx = run[mask]
        cnt[kind][idx] += 1
        new = idx[np.isnan(first[kind][idx])]
        first[kind][new] = t
        cur = vmax[kind][idx]
        val = values[mask]
        vmax[kind][idx] = np.where(np.isnan(cur) | (np.abs(val) > np.abs(cur)), val, cur)

    own_bar = bar is None
    if own_bar:
        bar = ProgressBar(n, "simulate (wchair batch)", enabled=progress, unit="step")
    done = 0
    try:
        for k in range(n):
            if run.size == 0:
                break
            t = k * dt
            Cp, Sn = np.cos(Sp), np.sin(Sp)            # heading, eta, beta at once
            ce, se, cb, sb = Cp[1], Sn[1], Cp[2], Sn[2]
            V = np.array(_kinematics(K, UD, VD, THED, ce, se, cb, sb, ED, BD))   # (8, m): vx, vy per wheel
            with np.errstate(divide="ignore", invalid="ignore"):
                S4 = np.arctan(V[1::2] / np.abs(V[0::2]))                        # = atan2(vy, |vx|)
            S4 *= rad2deg
            N4 = np.array(p_loads(K.p, FC1, FC2, ce, se, cb, sb))               # (4, m)
            if K.check_all:
                nmax = N4.max(axis=0)
                smax = np.abs(S4).max(axis=0)
            else:
                nmax = np.where(K.chk_mask, N4, -np.inf).max(axis=0)
                smax = np.where(K.chk_mask, np.abs(S4), 0.0).max(axis=0)
            over_load = nmax > LOAD_LIMIT_N
            nmin = N4.min(axis=0)
            under = nmin < 0.0
            over_slip = smax > SLIP_LIMIT_DEG
            halt = None
            if over_load.any() or under.any() or over_slip.any():
                halt = np.zeros(run.size, dtype=bool)
                flag("load", over_load, t, nmax)
                if stop:
                    halt |= cnt["load"][run] > WARNING_LIMIT
                flag("lift_off", under & ~halt, t, nmin)
                flag("slip", over_slip & ~halt, t, smax)
                if stop:
                    halt |= cnt["slip"][run] > WARNING_LIMIT
            if halt is not None and halt.any():
                gone = run[halt]
                stopped[gone] = True
                stop_time[gone] = t
                keep = np.flatnonzero(~halt)
                K.compact(keep)
                run = run[keep]
                (X, Y, THEDD, FC1, FC2) = (a[keep] for a in (X, Y, THEDD, FC1, FC2))
                if forces is not None:
                    fcimp = fcimp[keep]
                Sv, Sp, V, S4, N4 = Sv[:, keep], Sp[:, keep], V[:, keep], S4[:, keep], N4[:, keep]
                Cp, Sn = Cp[:, keep], Sn[:, keep]
                ce, se, cb, sb = Cp[1], Sn[1], Cp[2], Sn[2]
                UD, VD, THED, ED, BD = Sv
                THE, E, B = Sp
                if run.size == 0:
                    break
            vel = tuple(V)
            slips = tuple(S4)
            NA, NB, ND, NE = N4
            imp = _impulse_on(opts, t)
            F = _tire_forces(K, imp, vel, slips, NA, NB, ND, NE, S4=S4, N4=N4)
            fc1, fc2 = _resultant(F, ce, se, cb, sb)
            fy_ext = fcimp if (imp and (forces is not None or fcimp != 0.0)) else 0.0
            if yaw_fn is None:
                mz = 0.0
            else:
                st_ = ChairState(*(a.copy() for a in (X, Y, THE, UD, VD, THED, E, ED, B, BD, run)))
                mz = np.broadcast_to(np.asarray(yaw_fn(t, st_), dtype=float), run.shape)
            state = (UD, VD, THED, ce, se, cb, sb, ED, BD)
            rdc = THEDD if thesis else None
            if locked:
                zero = np.zeros(run.size)
                acc, MA, MB = _held_accelerations(K, state, F, zero, zero, fy_ext, mz, True, True, rdc)
            else:
                MA = np.where(ED != 0.0, np.copysign(K.maf, -ED), 0.0)
                MB = np.where(BD != 0.0, np.copysign(K.mbf, -BD), 0.0)
                acc = _accelerations(K, state, F, MA, MB, fy_ext, mz, rdc)
            UDD, VDD, THEDD_new, EDD, BDD = acc
            if locked:
                EDD = BDD = np.zeros(run.size)
            if k % stride == 0:
                j = k // stride
                cols = (t, X, Y, THE, THED, UD, VD, E, ED, B, BD, *F, NA, NB, ND, NE, *slips,
                        _tire_yaw_moment(K.p, F, ce, se, cb, sb), mz, THEDD_new, MA, MB)
                block = np.empty((run.size, _NC))
                for i, c in enumerate(cols):
                    block[:, i] = c
                buf[run, j, :] = block
                nrec_run[run] = j + 1
            # UPDATE / ITRATE: x += v dt + a dt^2/2 (global X, Y with the heading
            # at the start of the step), then v += a dt
            Acc = np.array((UDD, VDD, THEDD_new, EDD, BDD))
            THEDD = THEDD_new          # (Acc is scaled in place below)
            FC1, FC2 = fc1, fc2 + fy_ext
            D = Sv * dt
            D += Acc * half_dt2
            cost, sint = Cp[0], Sn[0]           # heading at the start of the step
            X = X + (D[0] * cost - D[1] * sint)
            Y = Y + (D[0] * sint + D[1] * cost)
            Sp += D[2:5]
            Acc *= dt
            Sv += Acc
            if k % 64 == 63:
                bar.update(64)
                done += 64
    finally:
        bar.update(n - done)
        if own_bar:
            bar.close()

    out = []
    settings = opts.settings()
    for i in range(nrun):
        if forces is not None:
            settings = dict(settings, impulse_force=float(forces[i]))
        w = {}
        for kind in cnt:
            c = int(cnt[kind][i])
            w[kind] = {"count": c, "first_time": None if c == 0 else float(first[kind][i]),
                       "max": None if c == 0 else float(vmax[kind][i])}
        out.append(SimulationResult._from_records(
            buf[i, :nrec_run[i]], warnings=w, stopped=bool(stopped[i]),
            stop_time=None if not stopped[i] else float(stop_time[i]), chair=chairs[i],
            speed=float(speeds[i]), settings=settings))
    return out


# ---------------------------------------------------------------------------
# batches over several processes
# ---------------------------------------------------------------------------
_RUNS_PER_WORKER = 250


def _usable_cpus() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - non-Linux
        return os.cpu_count() or 1


def _auto_workers(n_runs: int, opts: _Options) -> int:
    if opts.yaw_moment is not None:
        return 1
    return max(1, min(_usable_cpus(), n_runs // _RUNS_PER_WORKER))


def _check_workers(workers) -> int:
    if isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1:
        raise ValueError(f"workers={workers!r} is invalid; valid range: an integer >= 1, or None (automatic)")
    return int(workers)


def _fork_context():
    import multiprocessing as mp

    if "fork" not in mp.get_all_start_methods():  # pragma: no cover - Windows
        return None
    return mp.get_context("fork")


class _CounterBar:
    """Progress sink of a worker process: a shared counter of steps done."""

    def __init__(self, counter):
        self.counter = counter

    def update(self, n: int = 1) -> None:
        self.counter.value += n


def _batch_worker(conn, chairs, speeds, opts, counter, forces) -> None:  # pragma: no cover - runs in a child
    try:
        res = _wchair_batch(chairs, speeds, opts, False, bar=_CounterBar(counter), forces=forces)
        conn.send(("ok", res))
    except BaseException as exc:
        try:
            conn.send(("error", exc))
        except Exception:
            conn.send(("error", RuntimeError(f"{type(exc).__name__}: {exc}")))
    finally:
        conn.close()


def _wchair_batch_processes(chairs, speeds, opts, progress, workers, forces=None) -> list[SimulationResult]:
    from multiprocessing.connection import wait

    ctx = _fork_context()
    n = len(chairs)
    chunks = [np.arange(w, n, workers) for w in range(workers)]  # interleaved: balances early stops
    steps = _n_steps(opts)
    procs, conns, counters = [], [], []
    for idx in chunks:
        parent, child = ctx.Pipe(duplex=False)
        counter = ctx.Value("q", 0, lock=False)
        pr = ctx.Process(target=_batch_worker, daemon=True,
                         args=(child, [chairs[i] for i in idx], speeds[idx], opts, counter,
                               None if forces is None else forces[idx]))
        pr.start()
        child.close()
        procs.append(pr)
        conns.append(parent)
        counters.append(counter)
    results: list = [None] * workers
    pending = dict(zip(conns, range(workers)))
    shown = 0
    try:
        with ProgressBar(steps * workers, "simulate (wchair batch)", enabled=progress, unit="step") as bar:
            while pending:
                for conn in wait(list(pending), timeout=0.1):
                    w = pending.pop(conn)
                    try:
                        status, payload = conn.recv()
                    except EOFError:
                        raise RuntimeError(f"batch worker {w} died (exit code {procs[w].exitcode})") from None
                    if status != "ok":
                        raise payload
                    results[w] = payload
                total = sum(c.value for c in counters)
                bar.update(total - shown)
                shown = total
    finally:
        for pr in procs:
            if pr.is_alive():
                pr.terminate()
            pr.join()
    out: list = [None] * n
    for idx, res in zip(chunks, results):
        for i, r in zip(idx, res):
            out[int(i)] = r
    return out


# ---------------------------------------------------------------------------
# scheme "adaptive"
# ---------------------------------------------------------------------------
_FREE_POS, _FREE_NEG, _STUCK, _LOCKED = 1, -1, 0, 2


class _AdaptiveModel:
    """Right-hand side, stick-slip bookkeeping and sample evaluation of one run."""

    def __init__(self, chair: Chair, speed: float, opts: _Options):
        self.K = _Kernel([chair], opts, vector=False)
        self.opts = opts
        self.chair = chair
        self.speed = speed
        self.guess = (0.0, 0.0)
        self._cache_key = None
        self._cache_val = None
        self.nfev = 0

    # loads consistent with forces: N = loads(sum F(N))
    def _consistent(self, t, imp, vel, slips, ce, se, cb, sb, guess):
        """Fixed-point iteration of the load-transfer loop (a strong contraction).

        Stops when the total tire force changes by less than 1e-9 of its size
        between iterations; starts from the previous evaluation's solution.
        """
        K = self.K
        p = K.p
        sfx, sfy = guess
        vector = not isinstance(ce, float)
        for _ in range(100):
            N = _loads.normal_loads(p, sfx, sfy, ce, se, cb, sb)
            F = _tire_forces(K, imp, vel, slips, *N)
            nfx, nfy = _resultant(F, ce, se, cb, sb)
            if vector:
                err = float(np.max(np.abs(nfx - sfx) + np.abs(nfy - sfy), initial=0.0))
                scale = 1.0 + float(np.max(np.abs(nfx) + np.abs(nfy), initial=0.0))
            else:
                err = abs(nfx - sfx) + abs(nfy - sfy)
                scale = 1.0 + abs(nfx) + abs(nfy)
            sfx, sfy = nfx, nfy
            if err <= 1e-9 * scale:
                return N, F, (sfx, sfy)
        raise RuntimeError(f"normal loads and tire forces did not converge (t = {t!r} s)")  # pragma: no cover

    def evaluate(self, t, y, modes, imp):
        """Derivatives and auxiliary quantities at ``(t, y)`` (floats or arrays of samples)."""
        K = self.K
        xp = _ops(eta := y[6])
        X, Y, psi, u, v, r, eta, ed, beta, bd = y
        ma_mode, mb_mode = modes
        if ma_mode in (_STUCK, _LOCKED):
            ed = 0.0 * ed
        if mb_mode in (_STUCK, _LOCKED):
            bd = 0.0 * bd
        ce, se, cb, sb = xp.cos(eta), xp.sin(eta), xp.cos(beta), xp.sin(beta)
        vel = _kinematics(K, u, v, r, ce, se, cb, sb, ed, bd)
        slips = _slips(K, vel)
        vector = not isinstance(ce, float)
        guess = (0.0, 0.0) if vector else self.guess
        N, F, sums = self._consistent(t, imp, vel, slips, ce, se, cb, sb, guess)
        if not vector:
            self.guess = sums
        opts = self.opts
        fy_ext = opts.impulse_force if (opts.impulse_force != 0.0 and imp) else 0.0
        yaw_fn = opts.yaw_moment
        if yaw_fn is None:
            mz = 0.0
        elif not vector:
            mz = float(yaw_fn(t, ChairState(X, Y, psi, u, v, r, eta, ed, beta, bd, 0)))
        else:  # samples of a single run: the input sees floats, one call per sample
            cols = np.broadcast_arrays(t, X, Y, psi, u, v, r, eta, ed, beta, bd)
            mz = np.array([float(yaw_fn(float(row[0]), ChairState(*(float(x) for x in row[1:]), 0)))
                           for row in zip(*cols)])
        MA = -K.maf * ma_mode if ma_mode in (_FREE_POS, _FREE_NEG) else 0.0
        MB = -K.mbf * mb_mode if mb_mode in (_FREE_POS, _FREE_NEG) else 0.0
        hold_a = ma_mode in (_STUCK, _LOCKED)
        hold_b = mb_mode in (_STUCK, _LOCKED)
        state = (u, v, r, ce, se, cb, sb, ed, bd)
        acc, MA, MB = _held_accelerations(K, state, F, MA, MB, fy_ext, mz, hold_a, hold_b)
        ud, vd, rd, edd, bdd = acc
        cpsi, spsi = xp.cos(psi), xp.sin(psi)
        dy = (u * cpsi - v * spsi, u * spsi + v * cpsi, r, ud, vd, rd, ed, edd, bd, bdd)
        return dy, dict(N=N, F=F, slips=slips, MA=MA, MB=MB, mz=mz, ce=ce, se=se, cb=cb, sb=sb)

    def rhs(self, modes, imp):
        def f(t, y):
            key = (t, y.tobytes())
            if key == self._cache_key:
                return self._cache_val[0]
            self.nfev += 1
            dy, aux = self.evaluate(t, [float(a) for a in y], modes, imp)
            out = np.array(dy)
            self._cache_key, self._cache_val = key, (out, aux)
            return out
        return f

    def aux(self, t, y, modes, imp):
        key = (t, np.asarray(y).tobytes())
        if key == self._cache_key:
            return self._cache_val[1]
        self.nfev += 1
        dy, aux = self.evaluate(t, [float(a) for a in y], modes, imp)
        self._cache_key, self._cache_val = key, (np.array(dy), aux)
        return aux

    def holding(self, t, y, modes, side, imp):
        """Pin moment needed to hold caster ``side`` (0 = A, 1 = B) at rest."""
        m = list(modes)
        m[side] = _STUCK
        y = np.array(y, dtype=float)
        y[7 if side == 0 else 9] = 0.0
        aux = self.aux(t, y, tuple(m), imp)
        return aux["MA"] if side == 0 else aux["MB"]

    def limit(self, side):
        return self.K.maf if side == 0 else self.K.mbf


def linearise(chair: Chair, speed: float, *, model: str = "thesis", casters: str = "free",
              step: float = 1e-6):
    """The simulator's own linearisation about straight running, by central differences.

    Differentiates the right-hand side the simulator integrates (the adaptive
    scheme's, whose normal loads are solved consistently with the tire
    forces) with respect to ``[v, r, eta, eta_dot, beta, beta_dot]`` (free
    casters) or ``[v, r]`` (locked) and the yaw-moment input, at forward
    speed ``speed`` held fixed, casters trailing, no disturbance.  Unlike
    :func:`stability.linear.state_space` it keeps everything the simulator
    has: rolling resistance (drag on the casters, pitch load transfer),
    camber and toe with the lateral load transfer they couple to, and each
    tire's force law at its actual (not static) load.  Pins are taken as
    frictionless (Coulomb friction has no linearisation) and without the
    linear models' viscous ``pin_damping``, which the simulator does not have.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed, m/s (> 0).
    model : {"thesis", "exact"}
        Equation variant.
    casters : {"free", "locked"}
    step : float
        Central-difference step in the state units (m/s, rad/s, rad); the
        slip angles stay far inside the first degree, where the tire model
        is linear in slip.

    Returns
    -------
    control.StateSpace
        Same states, input ``Mz`` (N m) and outputs ``v``, ``r`` as
        :func:`stability.linear.state_space`.
    """
    import control

    from . import _validate

    speed = _validate.check_speed(speed)
    step = _positive("step", step)
    chair = chair.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    opts = _make_options(duration=1.0, scheme="adaptive", model=model, dt=0.001, impulse_force=0.0,
                         impulse_duration=0.0, tire_impulse=0.0, lateral_velocity=0.0, eta0_deg=0.0,
                         beta0_deg=0.0, casters=casters, yaw_moment=None, stop_on_warnings=False,
                         out_of_range="raise", sample=None, rtol=1e-6, atol=1e-9, reverse=False)
    modes = (_LOCKED, _LOCKED) if opts.casters == "locked" else (_FREE_POS, _FREE_POS)
    u0, _ = _initial(opts, speed)
    mz_in = [0.0]                       # the yaw-moment input of the evaluation below (N m)
    model_ = _AdaptiveModel(chair, speed, dataclasses.replace(opts, yaw_moment=lambda t, st: mz_in[0]))

    def derivative(dx, mz=0.0):
        mz_in[0] = mz
        model_.guess = (0.0, 0.0)       # every evaluation solves the load-transfer loop from scratch
        y = [0.0, 0.0, 0.0, u0, *dx] + [0.0] * (6 - len(dx))
        dy, _ = model_.evaluate(0.0, y, modes, False)
        return np.array(dy[4:4 + len(dx)], dtype=float)

    n = 2 if opts.casters == "locked" else 6
    eye = np.eye(n) * step
    A = np.column_stack([(derivative(eye[j]) - derivative(-eye[j])) / (2.0 * step) for j in range(n)])
    B = ((derivative(np.zeros(n), 1.0) - derivative(np.zeros(n), -1.0)) / 2.0)[:, None]
    states = ["v", "r", "eta", "eta_dot", "beta", "beta_dot"][:n]
    C = np.zeros((2, n))
    C[0, 0] = C[1, 1] = 1.0
    name = f"{chair.name} (simulator {opts.model}, {opts.casters} casters, U={speed:g} m per s)".replace(".", "p")
    return control.ss(A, B, C, np.zeros((2, 1)), states=states, inputs=["Mz"], outputs=["v", "r"], name=name)


def _adaptive_single(chair: Chair, speed: float, opts: _Options) -> SimulationResult:
    from scipy.integrate import solve_ivp

    model = _AdaptiveModel(chair, speed, opts)
    u0, v0 = _initial(opts, speed)
    y = np.array([0.0, 0.0, 0.0, u0, v0, 0.0, opts.eta0, 0.0, opts.beta0, 0.0])
    T = opts.duration
    impulse = opts.impulse_force != 0.0 or opts.tire_impulse != 0.0
    breaks = [T]
    if impulse and 0.0 < opts.impulse_duration < T:
        breaks.insert(0, opts.impulse_duration)
    t = 0.0
    imp = impulse and opts.impulse_duration > 0.0   # a zero-length force has no effect on an ODE

    def settle(t, y, modes):
        """Stuck/free decision for resting casters (t = 0, after a breakpoint)."""
        modes = list(modes)
        for side in (0, 1):
            if modes[side] == _STUCK:
                h = model.holding(t, y, modes, side, imp)
                if abs(h) > model.limit(side):
                    modes[side] = _FREE_NEG if h > 0 else _FREE_POS
        return tuple(modes)

    if opts.casters == "locked":
        modes = (_LOCKED, _LOCKED)
    else:
        modes = settle(t, y, (_STUCK, _STUCK))
    segments = []
    switches = 0
    while t < T:
        t_end = next(b for b in breaks if b > t)
        events = []
        kinds = []
        for side in (0, 1):
            mode = modes[side]
            ri = 7 if side == 0 else 9
            if mode in (_FREE_POS, _FREE_NEG):
                s = float(mode)

                def ev(tt, yy, ri=ri, s=s):
                    return s * yy[ri] + _DEADBAND
                ev.terminal, ev.direction = True, -1
                events.append(ev)
                kinds.append(("rest", side))
            elif mode == _STUCK:
                lim = model.limit(side)

                def ev(tt, yy, side=side, lim=lim, m=modes, i=imp):
                    aux = model.aux(tt, yy, m, i)
                    return abs(aux["MA"] if side == 0 else aux["MB"]) - lim
                ev.terminal, ev.direction = True, 1
                events.append(ev)
                kinds.append(("break", side))
        sol = solve_ivp(model.rhs(modes, imp), (t, t_end), y, method=ADAPTIVE_METHOD, rtol=opts.rtol,
                        atol=opts.atol, events=events or None, dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"adaptive integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
        segments.append((float(sol.t[0]), float(sol.t[-1]), sol.sol, modes, imp))
        t = float(sol.t[-1])
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            switches += 1
            if switches > _MAX_SWITCHES:
                raise RuntimeError(f"more than {_MAX_SWITCHES} stick-slip switches by t = {t:.6g} s "
                                   "(chattering); loosen rtol/atol or use scheme='wchair'")
            new = list(modes)
            for (kind, side), te in zip(kinds, sol.t_events):
                if len(te) == 0:
                    continue
                ri = 7 if side == 0 else 9
                if kind == "rest":
                    y[ri] = 0.0
                    h = model.holding(t, y, tuple(new), side, imp)
                    if abs(h) <= model.limit(side):
                        new[side] = _STUCK
                    else:
                        new[side] = _FREE_NEG if h > 0 else _FREE_POS
                else:
                    h = model.holding(t, y, tuple(new), side, imp)
                    new[side] = _FREE_NEG if h > 0 else _FREE_POS
            modes = tuple(new)
        else:
            if t < T and impulse and not _impulse_on(opts, t + 1e-12):
                imp = False
            if t < T and opts.casters != "locked":
                modes = settle(t, y, modes)

    # samples
    step = opts.sample
    ns = int(math.floor(T / step * (1 + 1e-12) + 1e-9)) + 1
    ts = step * np.arange(ns)
    ts[-1] = min(ts[-1], T)
    rec = np.empty((ns, _NC))
    K = model.K
    for i, (a, b, dense, modes, imp_seg) in enumerate(segments):
        last = i == len(segments) - 1
        sel = (ts >= a) & ((ts < b) | (last & (ts <= b)))
        if not sel.any():
            continue
        tt = ts[sel]
        yy = dense(tt)
        if modes[0] in (_STUCK, _LOCKED):
            yy[7] = 0.0
        if modes[1] in (_STUCK, _LOCKED):
            yy[9] = 0.0
        dy, aux = model.evaluate(tt, list(yy), modes, imp_seg)
        F = aux["F"]
        block = (tt, yy[0], yy[1], yy[2], yy[5], yy[3], yy[4], yy[6], yy[7], yy[8], yy[9], *F, *aux["N"],
                 *aux["slips"], _tire_yaw_moment(K.p, F, aux["ce"], aux["se"], aux["cb"], aux["sb"]),
                 aux["mz"], dy[5], aux["MA"], aux["MB"])
        for j, c in enumerate(block):
            rec[sel, j] = c
    warn = _new_warnings()
    stopped, stop_time = False, None
    slip_abs = np.max(np.abs(rec[:, 23:27]), axis=1)
    nmax = np.max(rec[:, 19:23], axis=1)
    nmin = np.min(rec[:, 19:23], axis=1)
    end = ns
    counts = {"slip": 0, "load": 0}
    for i in range(ns):
        if nmax[i] > LOAD_LIMIT_N:
            _note(warn, "load", ts[i], nmax[i])
            counts["load"] += 1
        if nmin[i] < 0:
            _note(warn, "lift_off", ts[i], nmin[i])
        if slip_abs[i] > SLIP_LIMIT_DEG:
            _note(warn, "slip", ts[i], slip_abs[i])
            counts["slip"] += 1
        if opts.stop_on_warnings and max(counts.values()) > WARNING_LIMIT:
            stopped, stop_time, end = True, float(ts[i]), i
            break
    settings = opts.settings()
    settings.update(switches=switches, nfev=model.nfev)
    return SimulationResult._from_records(rec[:end], warnings=warn, stopped=stopped, stop_time=stop_time,
                                          chair=chair, speed=speed, settings=settings)


# ---------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------
def _check_speed(speed):
    try:
        s = float(speed)
    except (TypeError, ValueError):
        raise ValueError(f"speed={speed!r} is invalid; valid range: speed > 0 m/s (forward motion)") from None
    if not math.isfinite(s) or s <= 0:
        raise ValueError(f"speed={speed!r} is invalid; valid range: speed > 0 m/s (forward motion)")
    return s


def _check_chair(chair):
    if not isinstance(chair, Chair):
        raise ValueError(f"chair={chair!r} is invalid; expected a stability.chair.Chair "
                         "(see stability.chair.preset / resolve)")
    return chair


def simulate(chair: Chair, speed: float, *, duration: float = 10.0, scheme: str = "wchair",
             model: str = "thesis", dt: float = 0.001, impulse_force: float = 40.0,
             impulse_duration: float = 0.1, tire_impulse: float = 0.0, lateral_velocity: float = 0.0,
             eta0_deg: float = 0.0, beta0_deg: float = 0.0, casters: str = "free",
             yaw_moment: Callable[[float, ChairState], float] | None = None,
             stop_on_warnings: bool | None = None, out_of_range: str = "clamp", sample: float | None = None,
             rtol: float = 1e-6, atol: float = 1e-9, reverse: bool = False) -> SimulationResult:
    """Simulate one run of a freely rolling chair disturbed from straight motion.

    Parameters
    ----------
    chair : Chair
        The chair (rear or front casters).
    speed : float
        Initial forward speed, m/s (> 0).
    duration : float
        Simulated time, s (WCHAIR's TTOTAL; the wchair scheme runs to
        ``duration + dt`` as WCHAIR's DO loop does).
    scheme : {"wchair", "adaptive"}
        Program WCHAIR's fixed-step scheme, or error-controlled integration
        with stick-slip pin friction (see the module docstring).
    model : {"thesis", "exact"}
        Equations of motion (:mod:`stability.models`).
    dt : float
        Step of the wchair scheme, s (TSTEP).
    impulse_force, impulse_duration : float
        Lateral force at the c.g., N (FCIMP, positive to the right), and how
        long it acts, s (DUIMP; ``t <= DUIMP``).  Default 40 N for 0.1 s (the
        thesis's 4 N s reference disturbance); ``impulse_duration=math.inf``
        (or >= duration) gives a constant side force.
    tire_impulse : float
        Lateral force on EACH main tire while ``t <= impulse_duration``, N
        (FTIMP; replaces the tire forces there, as MECHAN does).
    lateral_velocity : float
        Initial lateral velocity, m/s (VD).
    eta0_deg, beta0_deg : float
        Initial caster angles, deg (E, B).
    casters : {"free", "locked"}
        Free casters with Coulomb pin friction, or casters locked at their
        initial angles.
    yaw_moment : callable, optional
        ``yaw_moment(t, state) -> N m``: a yaw moment on the chair (e.g. a
        motor-assist controller); ``state`` is a :class:`ChairState`.
    stop_on_warnings : bool, optional
        Stop at the eleventh warning of a kind (WCHAIR's rule).  Default:
        True for the wchair scheme, False for the adaptive one.
    out_of_range : {"clamp", "extrapolate", "raise"}
        What the tire fits do outside their data (slip > 8 deg, load >
        450 N): passed to :meth:`stability.tires.Tire.lateral_force`.
    sample : float, optional
        Output interval, s: every step of the wchair scheme by default (must
        be a multiple of ``dt``); 0.01 s for the adaptive scheme.
    rtol, atol : float
        Tolerances of the adaptive scheme.
    reverse : bool
        Drive the chair backwards (initial forward velocity ``-speed``).  Only
        for reproducing the thesis's front-caster trick of section "Method
        One" (a rear-caster model driven backwards with its casters at
        180 deg); a front-caster chair is normally simulated directly.

    Returns
    -------
    SimulationResult

    Raises
    ------
    ValueError
        A bad argument (the message names it, its value and the valid range).
    """
    chair = _check_chair(chair)
    speed = _check_speed(speed)
    opts = _make_options(duration=duration, scheme=scheme, model=model, dt=dt, impulse_force=impulse_force,
                         impulse_duration=impulse_duration, tire_impulse=tire_impulse,
                         lateral_velocity=lateral_velocity, eta0_deg=eta0_deg, beta0_deg=beta0_deg,
                         casters=casters, yaw_moment=yaw_moment, stop_on_warnings=stop_on_warnings,
                         out_of_range=out_of_range, sample=sample, rtol=rtol, atol=atol, reverse=reverse)
    if opts.scheme == "wchair":
        return _wchair_single(chair, speed, opts)
    return _adaptive_single(chair, speed, opts)


def simulate_batch(chairs: Chair | Sequence[Chair], speeds, *, progress: bool = True,
                   workers: int | None = None, **options) -> list[SimulationResult]:
    """Simulate many runs at once.

    ``chairs`` (one chair or a sequence) is broadcast against ``speeds`` (a
    number or a 1-D array) with numpy rules; every other keyword is as in
    :func:`simulate` and applies to all runs (``yaw_moment`` receives arrays
    over the active runs, with ``state.run`` their indices), except
    ``impulse_force``, which may also be a 1-D array broadcast with the
    chairs and speeds: one disturbance per run (a speed x disturbance-size
    map in one call; each result's ``settings`` holds its own force).

    The wchair scheme steps all runs together on numpy arrays (runs grouped
    by tire type where they differ); a run stopped by the warning rule is
    frozen and drops out.  The adaptive scheme integrates the runs one after
    another.  Batches record every 0.01 s by default (``sample``) to bound
    memory (about ``runs * samples * 32 * 8`` bytes).  ``progress`` shows a
    bar on a terminal.

    ``workers`` (wchair scheme): processes sharing the runs (forked, POSIX
    only).  ``None`` picks one per 250 runs up to the usable CPUs, and one
    when a ``yaw_moment`` input is given (a stateful controller must see all
    its calls in this process); ``1`` keeps everything in this process.  The
    results do not depend on it beyond floating-point rounding.

    Returns
    -------
    list of SimulationResult, one per run in broadcast order.
    """
    if isinstance(chairs, Chair):
        chair_list = [chairs]
    else:
        chair_list = list(chairs)
        if not chair_list:
            raise ValueError("chairs=[] is invalid; expected a Chair or a non-empty sequence of Chair")
    for c in chair_list:
        _check_chair(c)
    sp = np.asarray(speeds, dtype=float)
    if sp.ndim > 1:
        raise ValueError(f"speeds has shape {sp.shape}; expected a number or a 1-D array")
    if sp.size == 0:
        raise ValueError("speeds=[] is invalid; expected at least one speed > 0 m/s")
    for s in np.atleast_1d(sp).tolist():
        _check_speed(s)
    fa = None
    if np.ndim(options.get("impulse_force", 0.0)) > 0:   # one force per run
        try:
            fa = np.asarray(options["impulse_force"], dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"impulse_force={options['impulse_force']!r} is invalid; expected a number or a 1-D "
                             "array of finite forces (N)") from None
        if fa.ndim != 1 or fa.size == 0 or not np.all(np.isfinite(fa)):
            raise ValueError(f"impulse_force={options['impulse_force']!r} is invalid; expected a number or a "
                             "non-empty 1-D array of finite forces (N)")
        options = dict(options, impulse_force=float(fa[0]))
    try:
        shape = np.broadcast_shapes((len(chair_list),) if not isinstance(chairs, Chair) else (), sp.shape,
                                    () if fa is None else fa.shape)
    except ValueError:
        raise ValueError(f"cannot broadcast {len(chair_list)} chairs against {sp.size} speeds"
                         + ("" if fa is None else f" and {fa.size} impulse forces")
                         + "; give one of each or equally many") from None
    n = int(np.prod(shape)) if shape else 1
    chair_idx = np.broadcast_to(np.arange(len(chair_list)) if not isinstance(chairs, Chair) else 0, shape).reshape(-1)
    speed_arr = np.broadcast_to(sp, shape).reshape(-1).astype(float)
    run_chairs = [chair_list[int(i)] for i in chair_idx]
    defaults = dict(duration=10.0, scheme="wchair", model="thesis", dt=0.001, impulse_force=40.0,
                    impulse_duration=0.1, tire_impulse=0.0, lateral_velocity=0.0, eta0_deg=0.0, beta0_deg=0.0,
                    casters="free", yaw_moment=None, stop_on_warnings=None, out_of_range="clamp", sample=None,
                    rtol=1e-6, atol=1e-9, reverse=False)
    unknown = set(options) - set(defaults)
    if unknown:
        raise ValueError(f"unknown option(s) {sorted(unknown)}; valid options: {sorted(defaults)}")
    defaults.update(options)
    opts = _make_options(batch=True, **defaults)
    if n == 0:
        return []
    forces = None if fa is None else np.broadcast_to(fa, shape).reshape(-1).astype(float)
    if opts.scheme == "wchair":
        nw = _auto_workers(n, opts) if workers is None else _check_workers(workers)
        if nw > 1 and _fork_context() is not None:
            return _wchair_batch_processes(run_chairs, speed_arr, opts, progress, min(nw, n), forces)
        return _wchair_batch(run_chairs, speed_arr, opts, progress, forces=forces)
    out = []
    with ProgressBar(n, "simulate (adaptive)", enabled=progress, unit="run") as bar:
        for i, (c, s) in enumerate(zip(run_chairs, speed_arr)):
            o = opts if forces is None else dataclasses.replace(opts, impulse_force=float(forces[i]))
            out.append(_adaptive_single(c, float(s), o))
            bar.update()
    return out


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------
def _parser() -> argparse.ArgumentParser:
    from .cli import OneLineErrorParser, add_chair_options

    ap = OneLineErrorParser(prog="python -m stability.simulate",
                 description="Simulate a wheelchair disturbed from straight motion (thesis chapter 7).")
    add_chair_options(ap)
    ap.add_argument("--speed", type=float, default=0.75, help="initial forward speed, m/s (default 0.75)")
    ap.add_argument("--impulse", type=float, nargs=2, metavar=("FORCE", "DURATION"), default=(40.0, 0.1),
                    help="lateral force at the c.g. (N) and its duration (s); default 40 0.1")
    ap.add_argument("--tire-impulse", type=float, default=0.0, metavar="F",
                    help="lateral force on each main tire during the impulse duration, N")
    ap.add_argument("--lateral-velocity", type=float, default=0.0, metavar="V", help="initial lateral velocity, m/s")
    ap.add_argument("--eta0", type=float, default=0.0, metavar="DEG", help="initial left caster angle, deg")
    ap.add_argument("--beta0", type=float, default=0.0, metavar="DEG", help="initial right caster angle, deg")
    ap.add_argument("--scheme", default="wchair", help="wchair (default) or adaptive")
    ap.add_argument("--model", default="thesis", help="thesis (default) or exact")
    ap.add_argument("--casters", default="free", help="free (default) or locked")
    ap.add_argument("--duration", type=float, default=10.0, help="simulated time, s (default 10)")
    ap.add_argument("--dt", type=float, default=0.001, help="wchair time step, s (default 0.001)")
    ap.add_argument("--sample", type=float, default=None, help="output interval of --json/--csv, s")
    ap.add_argument("--no-stop", action="store_true", help="do not stop at the eleventh warning")
    ap.add_argument("--out-of-range", default="clamp", help="clamp (default), extrapolate or raise")
    ap.add_argument("--rtol", type=float, default=1e-6, help="adaptive scheme relative tolerance")
    ap.add_argument("--atol", type=float, default=1e-9, help="adaptive scheme absolute tolerance")
    ap.add_argument("--csv", metavar="FILE", help="write the time histories to a CSV file")
    ap.add_argument("--plot", metavar="FILE", help="write a plot (pdf, png, svg)")
    ap.add_argument("--json", action="store_true", help="print results as JSON")
    return ap


def _run_cli(args: argparse.Namespace) -> int:
    from .cli import check_directory, load_chair

    c = load_chair(args.chair, args.set)
    check_directory(args.csv, "--csv")
    check_directory(args.plot, "--plot")
    res = simulate(c, args.speed, duration=args.duration, scheme=args.scheme, model=args.model, dt=args.dt,
                   impulse_force=args.impulse[0], impulse_duration=args.impulse[1],
                   tire_impulse=args.tire_impulse, lateral_velocity=args.lateral_velocity,
                   eta0_deg=args.eta0, beta0_deg=args.beta0, casters=args.casters,
                   stop_on_warnings=False if args.no_stop else None, out_of_range=args.out_of_range,
                   rtol=args.rtol, atol=args.atol)
    times = {str(v): res.first_time_abs_yaw_rate(v) for v in (0.5, 1.0)}
    out = res.resample(args.sample) if args.sample is not None else res
    if args.csv:
        out.to_csv(args.csv)
    if args.plot:
        res.plot(args.plot)
    if args.json:
        d = out.to_dict()
        d["first_time_abs_yaw_rate_s"] = times
        print(json.dumps(d, allow_nan=False))
    else:
        print(res.summary())
        if args.csv:
            print(f"wrote {args.csv}")
        if args.plot:
            print(f"wrote {args.plot}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Command-line entry point; returns the exit status (2 on bad input)."""
    from .cli import run

    return run(_parser(), argv, _run_cli, errors=(ValueError, OSError))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
