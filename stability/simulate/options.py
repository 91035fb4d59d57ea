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

from stability.settings.run import WCHAIR_DT, RunSpec
from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = ["WHEELS", "WHEEL_LABELS", "SLIP_LIMIT_DEG", "LOAD_LIMIT_N", "WARNING_LIMIT", "ADAPTIVE_METHOD", "WCHAIR_DT",
           "Options", "make_options", "n_steps", "impulse_on", "initial_velocities"]

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
#: Default output interval of the adaptive scheme and of a batch, s.
ADAPTIVE_SAMPLE = BATCH_SAMPLE = 0.01


@dataclass(frozen=True)
class Options:
    """Checked options of one simulation, built only by :func:`make_options`.

    Attributes
    ----------
    duration, impulse_force, impulse_duration, tire_impulse : float
        The :class:`~stability.settings.run.RunSpec` fields under program
        WCHAIR's names: ``horizon`` (TTOTAL, s), ``push_force`` (FCIMP, N),
        ``push_duration`` (DUIMP, s), ``tire_push_force`` (FTIMP, N).
    eta0, beta0 : float
        Initial left and right caster angles, rad.
    dt, stride, stop_on_warnings, sample, yaw_moment
        Resolved by the call: the fixed step (TSTEP, s, never ``"auto"``),
        the steps between recorded rows of the wchair scheme (>= 1), the stop
        rule (never None), the output interval (s; None: every step), the
        ``yaw_moment(t, state) -> N m`` input or None.
    scheme, model, lateral_velocity, casters, out_of_range, rtol, atol, reverse, slope, friction_law
        The RunSpec fields of these names (``slope``: cross slope and grade, deg).
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
        return 1.0 if self.casters == "locked" else (2.0 if self.friction_law == "stick-slip" else 0.0)

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
            "reverse": self.reverse, "friction_law": self.friction_law,
        }
        if self.slope != (0.0, 0.0):   # level runs keep today's settings (and JSON) unchanged
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
    step = float(dt if dt is not None else run.fixed_step)
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
    """Steps of a wchair run: the F77 trip count of ``DO 99 T = 0, TTOTAL+TSTEP, TSTEP`` (program WCHAIR).

    Parameters
    ----------
    opts : Options
        Uses ``duration`` (TTOTAL, s) and ``dt`` (TSTEP, s).

    Returns
    -------
    int
        ``floor((duration + 2 dt) / dt)`` (a tolerance of 1e-9 absorbs the
        quotient's rounding): the run covers ``t = 0, dt, ..., duration + dt``.
    """
    return int(math.floor((opts.duration + 2.0 * opts.dt) / opts.dt + 1e-9))


def impulse_on(opts: Options, t: float) -> bool:
    """Whether the push acts at ``t``: WCHAIR's ``T .LE. DUIMP``.

    Parameters
    ----------
    opts : Options
        Uses ``impulse_duration`` (DUIMP, s).
    t : float
        Time, s (>= 0).

    Returns
    -------
    bool
        ``t <= impulse_duration`` within a relative 1e-12 (WCHAIR accumulates
        T in REAL; here ``t = k dt``, and the tolerance keeps ``t = DUIMP`` in).
    """
    return t <= opts.impulse_duration * (1.0 + 1e-12) + 1e-15


def initial_velocities(opts: Options, speed: float) -> tuple[float, float]:
    """The initial body-axis velocities.

    Parameters
    ----------
    opts : Options
        Uses ``reverse`` and ``lateral_velocity`` (VD, m/s).
    speed : float
        Initial forward speed, m/s (> 0; WCHAIR's UD).

    Returns
    -------
    tuple of float
        ``(u0, v0)``, m/s: ``-speed`` when reversing, else ``speed``, and VD.
    """
    u0 = -speed if opts.reverse else speed
    return u0, opts.lateral_velocity
