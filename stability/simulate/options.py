"""A run's resolved options: a :class:`~stability.settings.run.RunSpec` made ready for the engines.

Every run setting, its default and its valid range live in
:class:`stability.settings.run.RunSpec` (checked when it is built).
:func:`make_options` resolves what depends on the call (the step ``"auto"``,
the default output interval of a batch, the stop rule of each scheme, angles
in rad) into :class:`Options`, which the engines read; see ``docs/simulator.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from stability.settings.run import (
    CASTERS,
    FRICTION_LAWS,
    MODELS,
    OUT_OF_RANGE_POLICIES,
    SCHEMES,
    WCHAIR_DT,
    RunSpec,
)
from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = ["SCHEMES", "MODELS", "CASTERS", "FRICTION_LAWS", "OUT_OF_RANGE_POLICIES", "WHEELS", "WHEEL_LABELS",
           "SLIP_LIMIT_DEG", "LOAD_LIMIT_N", "WARNING_LIMIT", "ADAPTIVE_METHOD", "WCHAIR_DT", "Options",
           "make_options", "n_steps", "impulse_on", "initial_velocities", "MAX_SLOPE_DEG"]

#: Wheel order of the per-wheel arrays: left caster, right caster, left main, right main.
WHEELS = ("A", "B", "D", "E")
WHEEL_LABELS = {"A": "left caster", "B": "right caster", "D": "left main wheel", "E": "right main wheel"}
#: Largest slip angle of the treadmill data (MECHAN's check), deg.
SLIP_LIMIT_DEG = SLIP_MAX_DEG
#: Largest normal load of the treadmill data (STATICS's check), N.
LOAD_LIMIT_N = FZ_MAX_N
#: WCHAIR stops at the eleventh warning of a kind (``IF (NWARN.GT.10) STOP``).
WARNING_LIMIT = 10
#: solve_ivp method of the adaptive scheme (stiff-aware, low order; see docs/simulator.md).
ADAPTIVE_METHOD = "LSODA"
#: the adaptive scheme's load-transfer loop stops when the total tire force changes by less than this
#: fraction of its size (1 + |sum F_x| + |sum F_y|, N) between iterations
LOAD_TOLERANCE = 1e-9
#: Largest |cross slope| and |grade| of a simulation, deg (RunSpec's bound; tire data: slips stay within 8 deg
#: up to about 15 deg).
MAX_SLOPE_DEG = 15.0
ADAPTIVE_SAMPLE = 0.01
BATCH_SAMPLE = 0.01


@dataclass(frozen=True)
class Options:
    """Checked options of one simulation (angles in rad; see :func:`make_options`).

    Built only by :func:`make_options`; the fields mean what the keywords of
    :func:`stability.simulate.simulate` of the same name mean, except where
    noted.

    Attributes
    ----------
    duration : float
        Simulated time, s (TTOTAL).  > 0.
    scheme : {"wchair", "adaptive"}
        Integration scheme.
    model : {"thesis", "exact"}
        Variant of the equations of motion.
    dt : float
        Fixed step of the wchair scheme, s (TSTEP), already resolved from
        ``"auto"``.  0 < dt <= duration for the wchair scheme.
    impulse_force : float
        Lateral push at the c.g., N (FCIMP).
    impulse_duration : float
        How long the pushes act, s (DUIMP).  >= 0, may be ``inf``.
    tire_impulse : float
        Lateral force on each main tire while the push acts, N (FTIMP).
    lateral_velocity : float
        Initial lateral velocity, m/s (VD).
    eta0, beta0 : float
        Initial left and right caster angles, rad (E, B).
    casters : {"free", "locked"}
        Caster condition.
    yaw_moment : callable or None
        ``yaw_moment(t, state) -> N m`` input, or None.
    stop_on_warnings : bool
        Stop at the eleventh warning of a kind (resolved from None).
    out_of_range : {"clamp", "extrapolate", "raise"}
        Policy of the tire fits outside their data.
    sample : float or None
        Output interval, s (0 < sample <= duration); None: every step.
    stride : int
        Steps between recorded rows of the wchair scheme (``sample / dt``;
        >= 1).
    rtol, atol : float
        Tolerances of the adaptive scheme.
    reverse : bool
        Drive backwards (initial forward velocity ``-speed``).
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)``, deg.
    friction_law : {"kinetic", "stick-slip"}
        Pin friction law (resolved from None).
    """

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
    slope: tuple[float, float] = (0.0, 0.0)
    friction_law: str = "stick-slip"

    @property
    def pin_mode(self) -> float:
        """The compiled kernel's pin mode: 0 free (kinetic friction), 1 locked, 2 free (stick-slip)."""
        if self.casters == "locked":
            return 1.0
        return 2.0 if self.friction_law == "stick-slip" else 0.0

    @property
    def on_slope(self) -> bool:
        """True when the plane is inclined (``slope != (0, 0)``)."""
        return self.slope != (0.0, 0.0)

    def slope_trig(self) -> tuple[float, float, float, float]:
        """``(cos(phi), sin(phi), cos(theta), sin(theta))`` of the cross slope phi and the grade theta."""
        phi, theta = math.radians(self.slope[0]), math.radians(self.slope[1])
        return math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta)

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
        d["friction_law"] = self.friction_law
        if self.on_slope:   # level runs keep today's settings (and JSON) unchanged
            d.update(cross_slope_deg=self.slope[0], grade_deg=self.slope[1])
        if self.scheme == "wchair":
            d["dt"] = self.dt
        else:
            d.update(rtol=self.rtol, atol=self.atol, method=ADAPTIVE_METHOD)
        return d


def make_options(run: RunSpec, *, yaw_moment: Callable | None = None, batch: bool = False,
                 dt: float | None = None) -> Options:
    """Resolve a checked :class:`~stability.settings.run.RunSpec` into the engines' :class:`Options`.

    Parameters
    ----------
    run : RunSpec
        The run's settings (already checked).
    yaw_moment : callable, optional
        ``yaw_moment(t, state) -> N m`` input, or None.
    batch : bool
        Options of a :func:`~stability.simulate.simulate_batch` call: the wchair
        scheme then samples at the multiple of ``dt`` nearest 0.01 s by default.
    dt : float, optional
        The step chosen for ``run.dt == "auto"`` (s); default 1 ms.

    Returns
    -------
    Options
        Angles in rad, the step, the stop rule and the output stride resolved.

    Raises
    ------
    ValueError
        ``yaw_moment`` not callable.
    """
    if yaw_moment is not None and not callable(yaw_moment):
        raise ValueError(f"yaw_moment={yaw_moment!r} is invalid; expected a callable yaw_moment(t, state) -> N m")
    step = float(dt if dt is not None else (WCHAIR_DT if run.dt == "auto" else run.dt))
    stop = run.scheme == "wchair" if run.stop_on_warnings is None else bool(run.stop_on_warnings)
    sample = run.sample
    if sample is None and run.scheme == "adaptive":
        sample = min(ADAPTIVE_SAMPLE, run.horizon)
    elif sample is None and batch:                       # the multiple of dt nearest to 0.01 s
        sample = step * max(1, int(round(BATCH_SAMPLE / step)))
        sample = min(sample, step * max(1, int(run.horizon / step)))
    stride = 1
    if sample is not None and run.scheme == "wchair":
        stride = max(1, int(round(sample / step)))
        sample = stride * step if run.sample is None or run.dt == "auto" else sample
    return Options(run.horizon, run.scheme, run.model, step, run.push_force, run.push_duration, run.tire_push_force,
                   run.lateral_velocity, math.radians(run.eta0_deg), math.radians(run.beta0_deg), run.casters,
                   yaw_moment, stop, run.out_of_range, sample, stride, run.rtol, run.atol, run.reverse, run.slope,
                   run.friction_law)


def n_steps(opts: Options) -> int:
    """Iterations of ``DO 99 T = 0, TTOTAL+TSTEP, TSTEP`` (F77 trip count; program WCHAIR, Appendix C).

    Parameters
    ----------
    opts : Options
        Checked options; uses ``duration`` (TTOTAL, s) and ``dt`` (TSTEP, s).

    Returns
    -------
    int
        Number of steps, ``floor((duration + 2 dt) / dt)`` (a tolerance of
        1e-9 absorbs rounding of the quotient): the run covers
        ``t = 0, dt, ..., duration + dt``.
    """
    return int(math.floor((opts.duration + 2.0 * opts.dt) / opts.dt + 1e-9))


def impulse_on(opts: Options, t: float) -> bool:
    """Whether the push acts at ``t`` (s): WCHAIR's ``T .LE. DUIMP``.

    WCHAIR accumulates T in REAL; here ``t = k dt`` and a relative tolerance
    keeps the inclusive test exact at ``t = DUIMP``.

    Parameters
    ----------
    opts : Options
        Checked options; uses ``impulse_duration`` (DUIMP, s).
    t : float
        Time, s (>= 0).

    Returns
    -------
    bool
        True while ``t <= impulse_duration`` (within a relative 1e-12).
    """
    return t <= opts.impulse_duration * (1.0 + 1e-12) + 1e-15


def initial_velocities(opts: Options, speed: float) -> tuple[float, float]:
    """``(u0, v0)``, m/s: forward (negative when reversing) and lateral.

    Parameters
    ----------
    opts : Options
        Checked options; uses ``reverse`` and ``lateral_velocity`` (VD, m/s).
    speed : float
        Initial forward speed, m/s (> 0; WCHAIR's UD).

    Returns
    -------
    tuple of float
        ``(u0, v0)``: body-axis forward velocity (``-speed`` when
        ``opts.reverse``) and lateral velocity, m/s.
    """
    u0 = -speed if opts.reverse else speed
    return u0, opts.lateral_velocity
