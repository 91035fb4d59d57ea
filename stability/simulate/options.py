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

from stability.runtime.checks import check_choice, check_finite, check_positive
from stability.settings import defaults as D
from stability.settings.reference import HORIZON, THESIS_PUSH
from stability.simulate.bounds import check_pushes, check_rows, check_steps, check_tolerances
from stability.tires.data import FZ_MAX_N, SLIP_MAX_DEG

__all__ = ["SCHEMES", "MODELS", "CASTERS", "FRICTION_LAWS", "OUT_OF_RANGE_POLICIES", "WHEELS", "WHEEL_LABELS",
           "SLIP_LIMIT_DEG",
           "LOAD_LIMIT_N", "WARNING_LIMIT", "ADAPTIVE_METHOD", "WCHAIR_DT", "SimulationDefaults", "DEFAULTS",
           "Options", "make_options", "n_steps", "impulse_on", "initial_velocities", "MAX_SLOPE_DEG", "check_slope"]

SCHEMES = ("wchair", "adaptive")
MODELS = ("thesis", "exact")
CASTERS = ("free", "locked")
FRICTION_LAWS = ("kinetic", "stick-slip")
OUT_OF_RANGE_POLICIES = ("clamp", "extrapolate", "raise")
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
#: WCHAIR's time step TSTEP, s (the thesis's runs).
WCHAIR_DT = D.DT
#: Largest |cross slope| and |grade| of a simulation, deg (tire data: slips stay within 8 deg up to ~15 deg).
MAX_SLOPE_DEG = 15.0
ADAPTIVE_SAMPLE = 0.01
BATCH_SAMPLE = 0.01


@dataclass(frozen=True)
class SimulationDefaults:
    """The defaults of a simulation (units as in :func:`stability.simulate.simulate`).

    The thesis's reference push (:data:`stability.settings.reference.THESIS_PUSH`) and
    horizon (:data:`stability.settings.reference.HORIZON`), WCHAIR's step and scheme
    (program WCHAIR, Appendix C; the defaults of Table 8-1).  Each field is the
    default of the keyword of the same name of :func:`stability.simulate.simulate`,
    which documents it in full.

    Attributes
    ----------
    duration : float
        Simulated time, s (WCHAIR's TTOTAL; 10 s).  > 0.
    scheme : {"wchair", "adaptive"}
        Integration scheme: WCHAIR's fixed step or error-controlled.
    model : {"thesis", "exact"}
        Variant of the equations of motion (default "exact", as every
        command line: :data:`stability.settings.defaults.MODEL`).
    dt : float or "auto"
        Fixed step of the wchair scheme, s (WCHAIR's TSTEP; 0.001 s).  > 0 and
        <= ``duration``.
    impulse_force : float
        Lateral push at the c.g., N (FCIMP; 40 N, positive to the right).
    impulse_duration : float
        How long the push (and ``tire_impulse``) acts, s (DUIMP; 0.1 s).  >= 0;
        ``inf`` for a constant force.
    tire_impulse : float
        Lateral force on each main tire while the push acts, N (FTIMP; 0).
    lateral_velocity : float
        Initial lateral velocity, m/s (VD; 0).
    eta0_deg, beta0_deg : float
        Initial left and right caster angles, deg (E, B; 0).
    casters : {"free", "locked"}
        Free casters with Coulomb pin friction, or casters held at their
        initial angles.
    friction_law : {"kinetic", "stick-slip"} or None
        Pin friction of free casters: "kinetic" (program WCHAIR's: the
        moment opposes the swivel rate, switching with its sign every step)
        or "stick-slip" (a caster at rest stays at rest while the friction
        limit can hold it; step-converged).  None: "kinetic" for the wchair
        scheme, "stick-slip" (its only law) for the adaptive one.
    yaw_moment : callable or None
        ``yaw_moment(t, state) -> N m`` applied to the chair; None: none.
    stop_on_warnings : bool or None
        Stop at the eleventh slip or load warning of a kind; None: True for
        the wchair scheme, False for the adaptive one.
    out_of_range : {"clamp", "extrapolate", "raise"}
        Tire fits outside their data (slip > 8 deg, load > 450 N).
    sample : float or None
        Output interval, s; None: every step (wchair, single run) or 0.01 s.
    rtol, atol : float
        Relative and absolute tolerances of the adaptive scheme (> 0;
        ``rtol >= 1e-13``).
    reverse : bool
        Drive backwards (initial forward velocity ``-speed``).
    controller : SampledController or None
        Sampled linear yaw-moment controller run in the compiled kernel.
    record : {"all", "states", "final"}
        What the compiled wchair scheme keeps of the time histories.
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)``: the plane falls to the right of the
        initial heading by the cross slope and rises ahead by the grade, deg
        (``(0, 0)``: level; each within +-15 deg; exact model only).
    """

    duration: float = HORIZON
    scheme: str = D.SCHEME
    model: str = D.MODEL
    dt: float | str = WCHAIR_DT
    impulse_force: float = THESIS_PUSH.force
    impulse_duration: float = THESIS_PUSH.duration
    tire_impulse: float = 0.0
    lateral_velocity: float = 0.0
    eta0_deg: float = 0.0
    beta0_deg: float = 0.0
    casters: str = D.CASTERS
    friction_law: str | None = D.FRICTION_LAW
    yaw_moment: Callable | None = None
    stop_on_warnings: bool | None = None
    out_of_range: str = D.SIM_OUT_OF_RANGE
    sample: float | None = None
    rtol: float = 1e-6
    atol: float = 1e-9
    reverse: bool = False
    controller: Any = None
    record: str = "all"
    slope: tuple[float, float] = (0.0, 0.0)

    def as_dict(self) -> dict[str, Any]:
        """The defaults as a dict (keyword -> value)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


#: The one table of simulation defaults.
DEFAULTS = SimulationDefaults()


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
        ``(cross_slope_deg, grade_deg)``, deg (checked by :func:`check_slope`).
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
    friction_law: str = "kinetic"

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
        if self.friction_law != "kinetic" and self.scheme == "wchair":   # the adaptive scheme has only stick-slip
            d["friction_law"] = self.friction_law
        if self.on_slope:   # level runs keep today's settings (and JSON) unchanged
            d.update(cross_slope_deg=self.slope[0], grade_deg=self.slope[1])
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
                 sample, rtol, atol, reverse, slope=(0.0, 0.0), friction_law=None, batch: bool = False) -> Options:
    """Check every option (ValueError naming the parameter, its value and the valid range) -> :class:`Options`.

    Parameters
    ----------
    duration : float
        Simulated time, s (TTOTAL).  > 0.
    scheme : {"wchair", "adaptive"}
        Integration scheme.
    model : {"thesis", "exact"}
        Variant of the equations of motion.
    dt : float
        Fixed step, s (TSTEP); > 0 and, for the wchair scheme, <= ``duration``.
        (``"auto"`` is resolved by the caller before this check.)
    impulse_force : float
        Lateral push at the c.g., N (FCIMP); finite.
    impulse_duration : float
        How long the pushes act, s (DUIMP); >= 0 (``inf``: constant force).
    tire_impulse : float
        Lateral force on each main tire while the push acts, N (FTIMP); finite.
    lateral_velocity : float
        Initial lateral velocity, m/s (VD); finite.
    eta0_deg, beta0_deg : float
        Initial left and right caster angles, deg (E, B); finite.
    casters : {"free", "locked"}
        Caster condition.
    yaw_moment : callable or None
        ``yaw_moment(t, state) -> N m`` input, or None.
    stop_on_warnings : bool or None
        Stop at the eleventh warning of a kind; None: True for the wchair
        scheme, False for the adaptive one.
    out_of_range : {"clamp", "extrapolate", "raise"}
        Policy of the tire fits outside their data (8 deg, 450 N).
    sample : float or None
        Output interval, s; 0 < sample <= duration and, for the wchair
        scheme, a whole multiple of ``dt``.  None: every step for one wchair
        run; 0.01 s for the adaptive scheme; the multiple of ``dt`` nearest
        0.01 s for a wchair batch.
    rtol, atol : float
        Tolerances of the adaptive scheme; > 0, ``rtol >= 1e-13``.
    reverse : bool
        Drive backwards.
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)``, each within +-15 deg
        (:func:`check_slope`); nonzero needs ``model="exact"``.
    friction_law : {"kinetic", "stick-slip"} or None
        Pin friction law; None: "kinetic" (wchair), "stick-slip" (adaptive,
        its only law).
    batch : bool
        Options of a :func:`~stability.simulate.simulate_batch` call (sets
        the default ``sample`` of the wchair scheme).

    Returns
    -------
    Options
        The checked options, angles in rad.

    Raises
    ------
    ValueError
        An option outside its valid range (the message names it, its value
        and the range).
    """
    scheme = check_choice("scheme", scheme, SCHEMES)
    model = check_choice("model", model, MODELS)
    casters = check_choice("casters", casters, CASTERS)
    out_of_range = check_choice("out_of_range", out_of_range, OUT_OF_RANGE_POLICIES)
    if friction_law is None:
        friction_law = "kinetic" if scheme == "wchair" else "stick-slip"
    friction_law = check_choice("friction_law", friction_law, FRICTION_LAWS)
    if scheme == "adaptive" and friction_law != "stick-slip":
        raise ValueError(f"friction_law={friction_law!r} is invalid for scheme 'adaptive'; valid values: "
                         "'stick-slip' (its events resolve every stick and slip)")
    duration = check_positive("duration", _float(duration))
    dt = check_positive("dt", _float(dt))
    if scheme == "wchair" and dt > duration:
        raise ValueError(f"dt={dt!r} is invalid; valid range: 0 < dt <= duration = {duration!r} s")
    check_steps(scheme, duration, dt)
    impulse_force = check_finite("impulse_force", _float(impulse_force), unit="N")
    try:
        impulse_duration = float(impulse_duration)
    except (TypeError, ValueError):
        impulse_duration = math.nan
    if math.isnan(impulse_duration) or impulse_duration < 0:
        raise ValueError(f"impulse_duration={impulse_duration!r} is invalid; valid range: >= 0 s (inf: constant force)")
    tire_impulse = check_finite("tire_impulse", _float(tire_impulse), unit="N")
    lateral_velocity = check_finite("lateral_velocity", _float(lateral_velocity), unit="m/s")
    check_pushes(impulse_force, tire_impulse, lateral_velocity)
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
    check_rows(duration, dt * stride if scheme == "wchair" else (sample or ADAPTIVE_SAMPLE))
    rtol, atol = check_tolerances(rtol, atol)
    slope = check_slope(slope)
    if slope != (0.0, 0.0) and model != "exact":
        raise ValueError(f"model={model!r} is invalid on a slope (slope={slope!r} deg); valid values: 'exact' "
                         "(the slope equations are derived for the exact model only)")
    return Options(duration, scheme, model, dt, impulse_force, impulse_duration, tire_impulse,
                   lateral_velocity, eta0, beta0, casters, yaw_moment, stop_on_warnings, out_of_range,
                   sample, stride, rtol, atol, bool(reverse), slope, friction_law)


def check_slope(slope: Any) -> tuple[float, float]:
    """Check ``slope = (cross_slope_deg, grade_deg)``.

    Parameters
    ----------
    slope : pair of float
        Cross slope (plane falls to the right, +) and grade (uphill ahead, +), deg.

    Returns
    -------
    tuple of float
        The pair as floats (``-0.0`` becomes ``0.0``).

    Raises
    ------
    ValueError
        Not a pair of finite numbers, or a component beyond +-:data:`MAX_SLOPE_DEG`.
    """
    msg = (f"slope={slope!r} is invalid; valid range: (cross_slope_deg, grade_deg) with |cross_slope_deg| <= "
           f"{MAX_SLOPE_DEG:g} and |grade_deg| <= {MAX_SLOPE_DEG:g} deg")
    try:
        cross, grade = (float(_float(x)) for x in slope)
    except (TypeError, ValueError):
        raise ValueError(msg) from None
    if not (math.isfinite(cross) and math.isfinite(grade) and abs(cross) <= MAX_SLOPE_DEG
            and abs(grade) <= MAX_SLOPE_DEG):
        raise ValueError(msg)
    return cross + 0.0, grade + 0.0


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
