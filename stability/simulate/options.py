"""Options of a simulation: the one table of defaults, the checks, the step constants.

:data:`DEFAULTS` is the single source of every default of
:func:`~stability.simulate.simulate`, :func:`~stability.simulate.simulate_batch`
and :func:`~stability.simulate.linearise`; see ``docs/simulator.md``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .._validate import check_choice, check_finite, check_positive
from ..reference import HORIZON, THESIS_PUSH

__all__ = ["SCHEMES", "MODELS", "CASTERS", "OUT_OF_RANGE_POLICIES", "WHEELS", "WHEEL_LABELS", "SLIP_LIMIT_DEG",
           "LOAD_LIMIT_N", "WARNING_LIMIT", "ADAPTIVE_METHOD", "WCHAIR_DT", "SimulationDefaults", "DEFAULTS",
           "Options", "make_options", "n_steps", "impulse_on", "initial_velocities"]

SCHEMES = ("wchair", "adaptive")
MODELS = ("thesis", "exact")
CASTERS = ("free", "locked")
OUT_OF_RANGE_POLICIES = ("clamp", "extrapolate", "raise")
#: Wheel order of the per-wheel arrays: left caster, right caster, left main, right main.
WHEELS = ("A", "B", "D", "E")
WHEEL_LABELS = {"A": "left caster", "B": "right caster", "D": "left main wheel", "E": "right main wheel"}
#: Largest slip angle of the treadmill data (MECHAN's check), deg.
SLIP_LIMIT_DEG = 8.0
#: Largest normal load of the treadmill data (STATICS's check), N.
LOAD_LIMIT_N = 450.0
#: WCHAIR stops at the eleventh warning of a kind (``IF (NWARN.GT.10) STOP``).
WARNING_LIMIT = 10
#: solve_ivp method of the adaptive scheme (stiff-aware, low order; see docs/simulator.md).
ADAPTIVE_METHOD = "LSODA"
#: WCHAIR's time step TSTEP, s (the thesis's runs).
WCHAIR_DT = 0.001
ADAPTIVE_SAMPLE = 0.01
BATCH_SAMPLE = 0.01


@dataclass(frozen=True)
class SimulationDefaults:
    """The defaults of a simulation (units as in :func:`stability.simulate.simulate`).

    The thesis's reference push (:data:`stability.reference.THESIS_PUSH`) and
    horizon (:data:`stability.reference.HORIZON`), WCHAIR's step and scheme.
    """

    duration: float = HORIZON
    scheme: str = "wchair"
    model: str = "thesis"
    dt: float | str = WCHAIR_DT
    impulse_force: float = THESIS_PUSH.force
    impulse_duration: float = THESIS_PUSH.duration
    tire_impulse: float = 0.0
    lateral_velocity: float = 0.0
    eta0_deg: float = 0.0
    beta0_deg: float = 0.0
    casters: str = "free"
    yaw_moment: Callable | None = None
    stop_on_warnings: bool | None = None
    out_of_range: str = "clamp"
    sample: float | None = None
    rtol: float = 1e-6
    atol: float = 1e-9
    reverse: bool = False
    controller: Any = None
    record: str = "all"

    def as_dict(self) -> dict[str, Any]:
        """The defaults as a dict (keyword -> value)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


#: The one table of simulation defaults.
DEFAULTS = SimulationDefaults()


@dataclass(frozen=True)
class Options:
    """Checked options of one simulation (angles in rad; see :func:`make_options`)."""

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
        """The options as recorded in a result's ``settings``."""
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


def _float(value: Any) -> Any:
    """numpy scalars as Python numbers (the checks refuse other types)."""
    return value.item() if hasattr(value, "item") and not isinstance(value, (int, float)) else value


def make_options(*, duration, scheme, model, dt, impulse_force, impulse_duration, tire_impulse,
                 lateral_velocity, eta0_deg, beta0_deg, casters, yaw_moment, stop_on_warnings, out_of_range,
                 sample, rtol, atol, reverse, batch: bool = False) -> Options:
    """Check every option (ValueError naming the parameter, its value and the valid range) -> :class:`Options`."""
    scheme = check_choice("scheme", scheme, SCHEMES)
    model = check_choice("model", model, MODELS)
    casters = check_choice("casters", casters, CASTERS)
    out_of_range = check_choice("out_of_range", out_of_range, OUT_OF_RANGE_POLICIES)
    duration = check_positive("duration", _float(duration))
    dt = check_positive("dt", _float(dt))
    if scheme == "wchair" and dt > duration:
        raise ValueError(f"dt={dt!r} is invalid; valid range: 0 < dt <= duration = {duration!r} s")
    impulse_force = check_finite("impulse_force", _float(impulse_force), unit="N")
    try:
        impulse_duration = float(impulse_duration)
    except (TypeError, ValueError):
        impulse_duration = math.nan
    if math.isnan(impulse_duration) or impulse_duration < 0:
        raise ValueError(f"impulse_duration={impulse_duration!r} is invalid; valid range: >= 0 s (inf: constant force)")
    tire_impulse = check_finite("tire_impulse", _float(tire_impulse), unit="N")
    lateral_velocity = check_finite("lateral_velocity", _float(lateral_velocity), unit="m/s")
    eta0 = math.radians(check_finite("eta0_deg", _float(eta0_deg), unit="deg"))
    beta0 = math.radians(check_finite("beta0_deg", _float(beta0_deg), unit="deg"))
    if yaw_moment is not None and not callable(yaw_moment):
        raise ValueError(f"yaw_moment={yaw_moment!r} is invalid; expected a callable yaw_moment(t, state) -> N m")
    if stop_on_warnings is None:
        stop_on_warnings = scheme == "wchair"
    stop_on_warnings = bool(stop_on_warnings)
    if sample is None and (scheme == "adaptive" or batch):
        if scheme == "adaptive":
            sample = min(ADAPTIVE_SAMPLE, duration)
        else:  # the multiple of dt nearest to 0.01 s
            sample = dt * max(1, int(round(BATCH_SAMPLE / dt)))
            sample = min(sample, dt * max(1, int(duration / dt)))
    stride = 1
    if sample is not None:
        sample = check_positive("sample", _float(sample))
        if sample > duration:
            raise ValueError(f"sample={sample!r} is invalid; valid range: 0 < sample <= duration = {duration!r} s")
        if scheme == "wchair":
            ratio = sample / dt
            stride = int(round(ratio))
            if stride < 1 or abs(ratio - stride) > 1e-6 * ratio:
                raise ValueError(f"sample={sample!r} is invalid for scheme 'wchair'; valid values: a whole "
                                 f"multiple of dt = {dt!r} s")
    rtol = check_positive("rtol", _float(rtol))
    atol = check_positive("atol", _float(atol))
    if rtol < 1e-13:
        raise ValueError(f"rtol={rtol!r} is invalid; valid range: rtol >= 1e-13")
    return Options(duration, scheme, model, dt, impulse_force, impulse_duration, tire_impulse,
                   lateral_velocity, eta0, beta0, casters, yaw_moment, stop_on_warnings, out_of_range,
                   sample, stride, rtol, atol, bool(reverse))


def n_steps(opts: Options) -> int:
    """Iterations of ``DO 99 T = 0, TTOTAL+TSTEP, TSTEP`` (F77 trip count)."""
    return int(math.floor((opts.duration + 2.0 * opts.dt) / opts.dt + 1e-9))


def impulse_on(opts: Options, t: float) -> bool:
    """Whether the push acts at ``t`` (s): WCHAIR's ``T .LE. DUIMP``.

    WCHAIR accumulates T in REAL; here ``t = k dt`` and a relative tolerance
    keeps the inclusive test exact at ``t = DUIMP``.
    """
    return t <= opts.impulse_duration * (1.0 + 1e-12) + 1e-15


def initial_velocities(opts: Options, speed: float) -> tuple[float, float]:
    """``(u0, v0)``, m/s: forward (negative when reversing) and lateral."""
    u0 = -speed if opts.reverse else speed
    return u0, opts.lateral_velocity
