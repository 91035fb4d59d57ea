"""The run specification: every setting of a simulated run in one frozen, checked object.

A :class:`RunSpec` says how a run starts, what disturbs it, how it is
integrated and with which equations: the speed, the push, the initial
conditions, the horizon and step, the scheme, the pin-friction law, the model,
the casters, the tire fits' range policy, the stop rule, the sampling, the
tolerances and the slope.  Its field metadata (unit, valid range or choices,
help text, JSON key, command-line flag) is the one table these settings have:

* the API checks a RunSpec on construction (:class:`ValueError` naming the
  field, its value and the valid range);
* the command lines build their options from it
  (:func:`stability.cli.options.add_run_options`) and refuse the same values
  with the same ranges;
* :data:`stability.settings.defaults.TABLE` lists its defaults;
* :meth:`RunSpec.to_dict` writes the JSON convention's keys (snake_case, unit
  last), and :meth:`RunSpec.from_dict` reads them back.

The defaults are the thesis's reference case (:mod:`stability.settings.reference`:
the E&J Premier's 0.75 m/s, the 40 N / 0.1 s push, 10 s), program WCHAIR's
1 ms step, the exact equations, and the **stick-slip** pin-friction law: it is
converged in the step where program WCHAIR's kinetic law is not
(docs/simulator.md); ``friction_law="kinetic"`` reproduces WCHAIR and the
thesis's figures and is named in every output that uses it.

Examples
--------
>>> from stability.settings.run import RunSpec
>>> run = RunSpec(speed=1.0, push_force=80.0)
>>> run.friction_law, run.horizon
('stick-slip', 10.0)
>>> run.replace(scheme="adaptive").scheme
'adaptive'
>>> RunSpec(speed=25.0)
Traceback (most recent call last):
...
ValueError: speed=25.0 is invalid; valid range: 0.01 <= |speed| <= 20 m/s (negative: reverse)
>>> RunSpec(speed=-0.5).speed, RunSpec(speed=-0.5).reverse
(0.5, True)
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
from dataclasses import dataclass, field
from typing import Any

from stability.runtime.checks import real_value, value_text
from stability.settings.bounds import SIGNED_SPEED, Bound
from stability.settings.reference import HORIZON, REFERENCE_SPEED, THESIS_PUSH, Push

__all__ = ["RunSpec", "Setting", "RUN_SETTINGS", "SCHEMES", "MODELS", "CASTERS", "FRICTION_LAWS",
           "OUT_OF_RANGE_POLICIES", "MAX_STEPS", "MAX_ROWS", "ROW_BYTES", "WCHAIR_DT", "json_key", "STEP_SECONDS",
           "WORK_BUDGET_S", "RUN_BYTES", "MAX_BATCH_BYTES"]

SCHEMES = ("wchair", "adaptive")
MODELS = ("exact", "thesis")
CASTERS = ("free", "locked")
FRICTION_LAWS = ("stick-slip", "kinetic")
OUT_OF_RANGE_POLICIES = ("clamp", "extrapolate", "raise")
#: Program WCHAIR's time step TSTEP, s (the thesis's runs).
WCHAIR_DT = 0.001

# Work bounds of one run (bounded time and memory): 2e7 fixed steps (about 0.2 us each compiled: seconds); a
# stored history of 2e6 rows of 32 x 8 bytes (512 MB).
MAX_STEPS, MAX_ROWS, ROW_BYTES = 20_000_000, 2_000_000, 256

#: Cost of one compiled WCHAIR step in a batch, s: 0.2 us measured on a quiet machine (a 10 s run in 2 ms),
#: taken five times over for a loaded one (both cores shared).
STEP_SECONDS = 1e-6
#: Simulation one call may ask for, s (ten minutes at :data:`STEP_SECONDS`): a batch's steps and a study's.
WORK_BUDGET_S = 600.0
#: Memory of one run's result besides its stored rows, bytes: 5.0 kB measured (20,000 runs of
#: ``record="final"``), taken at 8 kB.
RUN_BYTES = 8192
#: Memory one batch may keep, bytes: four times the largest history of one run (MAX_ROWS x ROW_BYTES).
MAX_BATCH_BYTES = 4 * MAX_ROWS * ROW_BYTES

_UNIT_SUFFIX = {"m/s": "m_s", "s": "s", "N": "N", "deg": "deg", "rad/s": "rad_s", "m": "m"}


@dataclass(frozen=True)
class Setting:
    """What one setting is: its unit, valid values, meaning and names (a RunSpec field's metadata).

    Attributes
    ----------
    unit : str
        Unit of the value (``""``: dimensionless or a choice).
    help : str
        What it is, in a few words (the command lines' help, the docs' table).
    bound : Bound or None
        Valid range of a number.
    choices : tuple or None
        Valid values of a choice.
    special : tuple
        Values valid beyond the bound (``"auto"`` for ``dt``, ``None`` for ``sample``).
    special_help : str
        What the special values mean.
    flag : str
        The command lines' option (``--speed``).
    """

    unit: str
    help: str
    bound: Bound | None = None
    choices: tuple | None = None
    special: tuple = ()
    special_help: str = ""
    flag: str = ""

    def range_text(self, name: str) -> str:
        """The valid values in words, e.g. ``"0.01 <= speed <= 20 m/s"`` or ``"'exact' or 'thesis'"``.

        Parameters
        ----------
        name : str
            The setting's name.

        Returns
        -------
        str
        """
        if self.choices is not None:
            return ", ".join(repr(c) for c in self.choices)
        text = self.bound.text(name) if self.bound is not None else "any"
        return text + (f" ({self.special_help})" if self.special_help else "")


def _s(default: Any, unit: str, help: str, bound: Bound | None = None, choices: tuple | None = None,
       special: tuple = (), special_help: str = "", flag: str = "") -> Any:
    return field(default=default, metadata={"setting": Setting(unit, help, bound, choices, special, special_help,
                                                                 flag)})


def json_key(name: str, unit: str) -> str:
    """The JSON key of a setting: its name with the unit last (``speed`` -> ``speed_m_s``).

    Parameters
    ----------
    name : str
        Field name (a name that already ends with its unit, ``eta0_deg``, is kept).
    unit : str
        Its unit.

    Returns
    -------
    str
    """
    suffix = _UNIT_SUFFIX.get(unit, "")
    return name if not suffix or name.endswith("_" + suffix) else f"{name}_{suffix}"


def _as_float(name: str, value: Any) -> float:
    """``value`` as a float (an integer beyond the float range as +-inf, refused by its bound)."""
    if isinstance(value, bool):
        raise TypeError(f"{name}={value!r} is invalid; expected a number")
    try:
        return real_value(value.item() if hasattr(value, "item") else value)
    except (TypeError, ValueError):
        raise TypeError(f"{name}={value_text(value)} is invalid; expected a number") from None


@dataclass(frozen=True)
class RunSpec:
    """Every setting of one simulated run (frozen; checked on construction).

    Parameters
    ----------
    speed : float
        Initial forward speed, m/s (WCHAIR's UD); 0.01-20 in magnitude.  A
        negative speed drives backwards: it is stored as ``speed=|speed|,
        reverse=True``.  A study that sweeps speeds sets it per run.
    push_force : float
        Lateral push at the c.g., N, positive to the right (FCIMP).
    push_duration : float
        How long the push (and ``tire_push_force``) acts, s (DUIMP): while
        ``t <= push_duration``, so on a fixed step ``dt`` it acts for
        ``floor(push_duration/dt) + 1`` steps; ``inf``: a constant force.
    tire_push_force : float
        Lateral force on each main tire while the push acts, N (FTIMP; it
        replaces the tire forces there, as MECHAN does).
    lateral_velocity : float
        Initial lateral velocity, m/s (VD).
    eta0_deg, beta0_deg : float
        Initial left and right caster angles, deg (E, B).
    horizon : float
        Simulated time, s (WCHAIR's TTOTAL; the fixed-step scheme runs to
        ``horizon + dt`` as WCHAIR's DO loop does).
    dt : float or "auto"
        Step of the wchair scheme, s (TSTEP).  ``"auto"``: 1 ms, or 1 ms / k
        when the step's stability limit at this speed needs a smaller one.
    scheme : {"wchair", "adaptive"}
        Program WCHAIR's fixed-step scheme, or error-controlled integration
        with event-located stick and slip (docs/simulator.md).
    friction_law : {"stick-slip", "kinetic"}
        Pin friction of free casters.  "stick-slip": a caster whose swivel
        rate would change sign within a step comes to rest and stays at rest
        while the friction limit can hold it (converged in the step).
        "kinetic": program WCHAIR's law (the moment opposes the rate and
        switches with its sign every step); the wchair scheme only.
    model : {"exact", "thesis"}
        Equations of motion (:mod:`stability.models`).
    casters : {"free", "locked"}
        Free casters with Coulomb pin friction, or casters held at their
        initial angles.
    out_of_range : {"clamp", "extrapolate", "raise"}
        What the tire fits do beyond their data (slip > 8 deg, load > 450 N):
        clamp at the data's edge (program WCHAIR's), extrapolate the cubic, or
        stop the run.
    stop_on_warnings : bool or None
        Stop at the eleventh slip or load warning of a kind (WCHAIR's rule);
        None: yes for the wchair scheme, no for the adaptive one.
    sample : float or None
        Output interval, s; None: every step of one wchair run, 0.01 s for the
        adaptive scheme, the multiple of ``dt`` nearest 0.01 s for a batch.
        For the wchair scheme a whole multiple of ``dt``.
    rtol, atol : float
        Relative and absolute tolerances of the adaptive scheme.
    reverse : bool
        Drive backwards (initial forward velocity ``-speed``).
    cross_slope_deg, grade_deg : float
        The plane falls to the right of the initial heading by the cross slope
        and rises ahead by the grade, deg (the exact model only).

    Raises
    ------
    ValueError
        A value outside its valid range, or settings that do not go together
        (the message names the field, its value and the valid range).
    TypeError
        A value of the wrong type (a string for a number).
    """

    speed: float = _s(REFERENCE_SPEED, "m/s", "initial forward speed (negative: reverse)",
                      SIGNED_SPEED, special_help="negative: reverse")
    push_force: float = _s(THESIS_PUSH.force, "N", "lateral push at the c.g., positive to the right",
                           Bound(-10_000.0, 10_000.0, "N"))
    push_duration: float = _s(THESIS_PUSH.duration, "s", "how long the push acts (while t <= push_duration)",
                              Bound(0.0, 3600.0, "s"), special=(math.inf,), special_help="or inf: a constant force")
    tire_push_force: float = _s(0.0, "N", "lateral force on each main tire while the push acts",
                                Bound(-10_000.0, 10_000.0, "N"))
    lateral_velocity: float = _s(0.0, "m/s", "initial lateral velocity", Bound(-5.0, 5.0, "m/s"))
    eta0_deg: float = _s(0.0, "deg", "initial left caster angle", Bound(-180.0, 180.0, "deg"), flag="--eta0")
    beta0_deg: float = _s(0.0, "deg", "initial right caster angle", Bound(-180.0, 180.0, "deg"), flag="--beta0")
    horizon: float = _s(HORIZON, "s", "simulated time", Bound(0.0, 3600.0, "s", open_lo=True))
    dt: float | str = _s(WCHAIR_DT, "s", "fixed step of the wchair scheme", Bound(1e-6, 0.1, "s"),
                         special=("auto",), special_help="or 'auto': 1 ms, smaller where the step is unstable")
    scheme: str = _s("wchair", "", "integration scheme", choices=SCHEMES)
    friction_law: str = _s("stick-slip", "", "pin friction law of free casters", choices=FRICTION_LAWS)
    model: str = _s("exact", "", "equations of motion", choices=MODELS)
    casters: str = _s("free", "", "free or locked casters", choices=CASTERS)
    out_of_range: str = _s("clamp", "", "the tire fits beyond their data", choices=OUT_OF_RANGE_POLICIES)
    stop_on_warnings: bool | None = _s(None, "", "stop at the eleventh slip or load warning of a kind",
                                       choices=(True, False, None))
    sample: float | None = _s(None, "s", "output interval", Bound(1e-6, 3600.0, "s"), special=(None,),
                              special_help="or none: every step, 0.01 s for the adaptive scheme or a batch")
    rtol: float = _s(1e-6, "", "relative tolerance of the adaptive scheme", Bound(1e-12, 0.1, ""))
    atol: float = _s(1e-9, "", "absolute tolerance of the adaptive scheme", Bound(1e-14, 1.0, ""))
    reverse: bool = _s(False, "", "drive backwards", choices=(False, True))
    cross_slope_deg: float = _s(0.0, "deg", "cross slope: the plane falls to the right of the heading (+)",
                                Bound(-15.0, 15.0, "deg"), flag="--cross-slope")
    grade_deg: float = _s(0.0, "deg", "grade: the plane rises ahead (+)", Bound(-15.0, 15.0, "deg"), flag="--grade")

    def __post_init__(self) -> None:
        self._check(dataclasses.fields(self))

    def _check(self, fields: Any) -> None:
        """Check ``fields`` (each alone: floats stored as floats), the reverse shorthand, the settings together."""
        for f in fields:
            s: Setting = f.metadata["setting"]
            value = getattr(self, f.name)
            if any(value is sp or (isinstance(sp, (str, float)) and isinstance(value, type(sp)) and value == sp)
                   for sp in s.special):
                continue
            if s.choices is not None:
                if isinstance(value, (bool, str)) or value is None:
                    if value in s.choices and type(value) is type(s.choices[s.choices.index(value)]):
                        continue
                raise ValueError(f"{f.name}={value_text(value)} is invalid; valid values: {s.range_text(f.name)}")
            x = _as_float(f.name, value)
            if math.isnan(x) or (s.bound is not None and not s.bound.holds(x)):
                raise ValueError(f"{f.name}={value_text(value)} is invalid; valid range: {s.range_text(f.name)}")
            object.__setattr__(self, f.name, x + 0.0)          # numpy scalars, ints and -0.0 as floats
        if self.speed < 0:                                      # a negative speed is the reverse flag's shorthand
            if self.reverse:
                raise ValueError(f"speed={self.speed!r} is invalid with reverse=True; valid values: a positive "
                                 "speed with reverse=True, or a negative speed alone (negative: reverse)")
            object.__setattr__(self, "speed", -self.speed)
            object.__setattr__(self, "reverse", True)
        self._check_together()

    def _check_together(self) -> None:
        if self.scheme == "adaptive" and self.friction_law != "stick-slip":
            raise ValueError(f"friction_law={self.friction_law!r} is invalid for scheme 'adaptive'; valid values: "
                             "'stick-slip' (its events resolve every stick and slip)")
        if self.on_slope and self.model != "exact":
            raise ValueError(f"model={self.model!r} is invalid on a slope (cross_slope_deg={self.cross_slope_deg:g}, "
                             f"grade_deg={self.grade_deg:g}); valid values: 'exact' (the slope equations are derived "
                             "for the exact model only)")
        if self.scheme != "wchair":
            return
        dt = self.fixed_step
        if dt > self.horizon:
            raise ValueError(f"dt={self.dt!r} is invalid; valid range: dt <= horizon = {self.horizon!r} s")
        if self.horizon / dt > MAX_STEPS:
            raise ValueError(f"horizon={self.horizon!r} s with dt={dt!r} s asks for {self.horizon / dt:.3g} steps; "
                             f"at most {MAX_STEPS:.3g} are allowed: the largest allowed horizon is "
                             f"{MAX_STEPS * dt:.4g} s, the smallest dt {self.horizon / MAX_STEPS:.3g} s")
        if self.sample is not None:
            if self.sample > self.horizon:
                raise ValueError(f"sample={self.sample!r} is invalid; valid range: sample <= horizon = "
                                 f"{self.horizon!r} s")
            ratio = self.sample / dt
            if self.dt != "auto" and (round(ratio) < 1 or abs(ratio - round(ratio)) > 1e-6 * ratio):
                raise ValueError(f"sample={self.sample!r} is invalid for scheme 'wchair'; valid values: a whole "
                                 f"multiple of dt = {dt!r} s")
        interval = self.sample if self.sample is not None else dt
        if self.horizon / interval > MAX_ROWS:
            raise ValueError(f"horizon={self.horizon:g} s stored every {interval:.3g} s is "
                             f"{self.horizon / interval:.3g} rows ({self.horizon / interval * ROW_BYTES / 2**20:.0f} "
                             f"MB); at most {MAX_ROWS:.3g} rows are allowed: the largest allowed horizon is "
                             f"{MAX_ROWS * interval:.4g} s, or give sample >= {self.horizon / MAX_ROWS:.3g} s")

    # -- reading ----------------------------------------------------------
    @property
    def push(self) -> Push:
        """The push as a :class:`~stability.settings.reference.Push` (force N, duration s)."""
        return Push(self.push_force, self.push_duration)

    @property
    def slope(self) -> tuple[float, float]:
        """``(cross_slope_deg, grade_deg)``."""
        return (self.cross_slope_deg, self.grade_deg)

    @property
    def fixed_step(self) -> float:
        """The WCHAIR scheme's step, s: ``dt``, or :data:`WCHAIR_DT` for ``"auto"`` (which a chair's own step limit
        may shorten further, :mod:`stability.simulate.stepcheck`)."""
        return WCHAIR_DT if self.dt == "auto" else float(self.dt)

    @property
    def on_slope(self) -> bool:
        """True when the plane is inclined."""
        return self.cross_slope_deg != 0.0 or self.grade_deg != 0.0

    def describe(self) -> str:
        """The run in one line, e.g. ``"wchair scheme, dt 1 ms, stick-slip pin friction, exact model"``.

        Returns
        -------
        str
        """
        step = ("dt auto" if self.dt == "auto" else f"dt {float(self.dt) * 1e3:g} ms") if self.scheme == "wchair" \
            else f"rtol {self.rtol:g}"
        friction = "locked casters" if self.casters == "locked" else f"{self.friction_law} pin friction"
        slope = f", cross slope {self.cross_slope_deg:g} deg, grade {self.grade_deg:g} deg" if self.on_slope else ""
        return f"{self.scheme} scheme, {step}, {friction}, {self.model} model{slope}"

    def replace(self, **changes: Any) -> RunSpec:
        """A copy with ``changes`` applied (checked again).

        Parameters
        ----------
        **changes
            Field name -> new value.

        Returns
        -------
        RunSpec

        Raises
        ------
        ValueError
            An unknown field (named, with the valid ones) or an invalid value.
        """
        unknown = sorted(set(changes) - set(_names()))
        if unknown:
            raise ValueError(f"unknown run setting(s) {unknown}; valid: {names()}")
        if all(type(v) is float and v == getattr(self, k) and type(getattr(self, k)) is float
               for k, v in changes.items()):
            return self           # the same floats (a checked spec is immutable): not checked again
        new = copy.copy(self)     # the other settings were checked: only the changed ones are, and all together
        for k, v in changes.items():
            object.__setattr__(new, k, v)
        new._check([_fields()[k] for k in changes])
        return new

    def to_dict(self) -> dict[str, Any]:
        """The settings under their JSON keys (snake_case, unit last: ``speed_m_s``, ``horizon_s``).

        JSON has no infinity: a setting whose special value is ``inf`` (``push_duration``: a constant
        force) is written as null, and :meth:`from_dict` reads null back as ``inf``.

        Returns
        -------
        dict
        """
        return {json_key(f.name, f.metadata["setting"].unit): _json_value(f, getattr(self, f.name))
                for f in dataclasses.fields(self)}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> RunSpec:
        """A RunSpec from :meth:`to_dict`'s keys (or the field names); unknown keys are refused.

        Parameters
        ----------
        data : dict

        Returns
        -------
        RunSpec
        """
        by_key = {json_key(f.name, f.metadata["setting"].unit): f.name for f in dataclasses.fields(cls)}
        by_key.update({n: n for n in names()})
        unknown = sorted(set(data) - set(by_key))
        if unknown:
            raise ValueError(f"unknown run setting(s) {unknown}; valid: {sorted(by_key)}")
        fields = {f.name: f for f in dataclasses.fields(cls)}
        values: dict[str, Any] = {by_key[k]: math.inf if v is None and math.inf in
                                  fields[by_key[k]].metadata["setting"].special else v for k, v in data.items()}
        return cls(**values)


def _json_value(f: dataclasses.Field, value: Any) -> Any:
    """``value`` for JSON: None for an infinite value the setting allows (:meth:`RunSpec.to_dict`)."""
    return None if isinstance(value, float) and math.isinf(value) and math.inf in f.metadata["setting"].special \
        else value


def names() -> list[str]:
    """The RunSpec's field names, in order.

    Returns
    -------
    list of str
    """
    return list(_names())


@functools.cache
def _names() -> tuple[str, ...]:
    return tuple(f.name for f in dataclasses.fields(RunSpec))


@functools.cache
def _fields() -> dict[str, dataclasses.Field]:
    return {f.name: f for f in dataclasses.fields(RunSpec)}


def setting(name: str) -> Setting:
    """The :class:`Setting` (metadata) of RunSpec field ``name``.

    Parameters
    ----------
    name : str

    Returns
    -------
    Setting
    """
    return {f.name: f.metadata["setting"] for f in dataclasses.fields(RunSpec)}[name]


#: Name -> :class:`Setting` of every RunSpec field, in order (the one table of the run settings).
RUN_SETTINGS: dict[str, Setting] = {f.name: f.metadata["setting"] for f in dataclasses.fields(RunSpec)}

