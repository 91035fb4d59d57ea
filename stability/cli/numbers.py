"""Numbers at the command lines: every numeric option parsed by name within a plausibility bound, and no
non-finite result printed.

:func:`number` is the argparse ``type`` that :class:`stability.cli.OneLineErrorParser`
installs for every ``type=float`` and ``type=int`` option, so that a refusal always
names the option, the value and the valid range (:data:`OPTION_BOUNDS`).
:func:`check_finite_text` and :func:`first_non_finite` find a NaN or an infinity in
what a command is about to print or write (:class:`NonFiniteResult`, reported as
``error: could not compute ...``).
"""

from __future__ import annotations

import argparse
import math
import re
from collections.abc import Callable
from typing import Any

import numpy as np

from stability.settings.bounds import (
    ADVISE_CROSS_SLOPE,
    CONFIDENCE_LEVEL,
    DRIVE_WHEEL_RADIUS,
    HUMAN_SPEED,
    MIN_TIP_ANGLE,
    NONLINEAR_SAMPLES,
    SAMPLES,
    SEARCH_MAX_SPEED,
    SEED,
    SIGNED_SPEED,
    SPEED,
    Bound,
)
from stability.settings.drive import DRIVE_SETTINGS, drive_flag
from stability.settings.run import RUN_SETTINGS

__all__ = ["Bound", "OPTION_BOUNDS", "bound_for", "number", "with_unit", "slope_angle", "SLOPE_OPTIONS",
           "NonFiniteResult", "first_non_finite", "check_finite_text"]


#: Plausibility bound of every numeric option of every command, by option name; ``"command:--option"``
#: overrides where one name means another quantity in one command.  Each is wide enough for any real
#: wheelchair, user, sensor and road, and narrow enough that a typo or an attack (1e308, 1e-300) is refused
#: by name before any work.  The work an option costs (time steps, samples, speeds) is bounded separately by
#: each command's estimate of time and memory (count x cost).
OPTION_BOUNDS: dict[str, Bound] = {
    # speeds: a wheelchair, powered or pushed, does not exceed 20 m/s (72 km/h)
    "--speed": SPEED,
    "--max-speed": SEARCH_MAX_SPEED,          # the API's stability.analyse(max_speed=)
    # the slope command answers reverse (negative speeds) with the layout model, as RunSpec's speed
    "slope:--speed": SIGNED_SPEED,
    # counts and seeds
    "--samples": SAMPLES,
    "--nonlinear-samples": NONLINEAR_SAMPLES,
    "--seed": SEED,
    "--level": CONFIDENCE_LEVEL,                                # a probability (confidence level)
    "study:--level": Bound(0.0, 50.0, "rad/s", open_lo=True),   # a yaw-rate level
    # pushes: a person pushes with a few hundred N; 10 kN is a collision
    "--max-impulse": Bound(0.0, 1_000.0, "N s", open_lo=True),
    "--force": Bound(0.0, 10_000.0, "N", open_lo=True),
    # roads: no wheelchair ramp or road is steeper than 45 deg (commands bound it further)
    "--cross-slope": Bound(-45.0, 45.0, "deg"),
    "advise:--cross-slope": ADVISE_CROSS_SLOPE,                 # the advisor's drive constraint: everyday slopes
    "--grade": Bound(-45.0, 45.0, "deg"),
    # times: an hour of simulated motion; a push of at most 10 s; sample intervals from 1 us
    "--sim-time": Bound(0.0, 3600.0, "s", open_lo=True),
    "slope:--sim-time": Bound(0.0, 10.0, "s", open_lo=True),      # the slope command's uncorrected turn
    # the driver's effective delay: stability.driver.model.REACTION_TIME_RANGE_S (a reflex to a slow correction)
    "--reaction-time": Bound(0.05, 2.0, "s"),
    "--intended-speed": HUMAN_SPEED,                            # the human-limited speed's search range
    # integrator tolerances: below 1e-12 (relative) or 1e-14 (absolute, states of order 1) double precision
    # (eps 2.2e-16) cannot meet them and the step size collapses
    # assist: drive train, gyro and controller
    "--max-heading-error": Bound(0.0, 90.0, "deg", open_lo=True),
    "--max-yaw-rate": Bound(0.0, 1000.0, "deg/s"),
    "--torque-limit": Bound(1.0, 1000.0, "N m"),
    "--torque-budget": Bound(0.1, 1000.0, "N m"),
    "--wheel-radius": Bound(0.05, 1.0, "m"),                # a caster's radius to a 2 m (78 in) wheel
    "assist:--wheel-radius": DRIVE_WHEEL_RADIUS,            # a drive wheel (stability.chair.power.DriveTrain)
    "--handrim-radius": Bound(0.05, 1.0, "m"),
    "--gyro-noise": Bound(0.0, 100.0, "deg/s/sqrt(Hz)"),
    "--gyro-bias": Bound(0.0, 100.0, "deg/s"),     # its size (GyroSensor): the chair is mirror symmetric
    "--sample-rate": Bound(10.0, 2_000.0, "Hz"),            # controller rates in use: 50 Hz to 1 kHz
    "--bias-time-constant": Bound(0.0, 1000.0, "s"),
    "--motor-lag": Bound(0.0, 0.5, "s"),
    # advise: a static stability (tip) angle; a chair tips over at 0 deg and none is stable beyond 60 deg
    "--min-tip-deg": MIN_TIP_ANGLE,
    # shimmy: caster tire and frame
    "--relaxation-length": Bound(0.0, 1.0, "m", open_lo=True),
    "--lateral-stiffness": Bound(0.0, 1e8, "N/m", open_lo=True),
    "--amplitude-deg": Bound(0.0, 45.0, "deg", open_lo=True, open_hi=True),
}


#: Commands whose run options are generated from the RunSpec's table (stability.cli.options.add_run_options): their
#: bounds are the RunSpec's, one entry per option as ``"command:--option"``.
RUN_COMMANDS = ("simulate", "study")
OPTION_BOUNDS.update({f"bench:{drive_flag(name)}": Bound(lo, hi, unit)
                      for name, (_, unit, (lo, hi), _) in DRIVE_SETTINGS.items()})
OPTION_BOUNDS.update({f"{command}:{setting.flag or '--' + name.replace('_', '-')}": setting.bound
                      for command in RUN_COMMANDS for name, setting in RUN_SETTINGS.items()
                      if setting.bound is not None})


def bound_for(prog: str | None, option: str) -> Bound | None:
    """The bound of ``option`` in the command whose parser is called ``prog``.

    Parameters
    ----------
    prog : str or None
        The parser's ``prog``, e.g. ``"python -m stability.study critical-impulse"``.
    option : str
        The option, e.g. ``"--level"``; ``"command:--option"`` entries win.

    Returns
    -------
    Bound or None
        None when :data:`OPTION_BOUNDS` has no entry.
    """
    words = [w for w in (prog or "").split() if w.startswith("stability.")]
    command = words[0].rsplit(".", 1)[-1] if words else ""
    for key in (f"{command}:{option}", option):
        if key in OPTION_BOUNDS:
            return OPTION_BOUNDS[key]
    return None


_QUANTITY = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(\S.*?)\s*$")


def with_unit(option: str, text: str, unit: str, rng: str) -> float:
    """A number with a unit (``3.6 km/h``, ``100 ms``, ``2deg``) in the option's own ``unit``.

    Parameters
    ----------
    option : str
        The option, named in a refusal.
    text : str
        What was given.
    unit : str
        The option's unit (:func:`stability.chair.units.parse_unit`'s grammar, e.g. ``"m/s"``).
    rng : str
        The valid range's words appended to a refusal (``"; valid range: ..."``).

    Returns
    -------
    float
        The value in ``unit``.

    Raises
    ------
    argparse.ArgumentTypeError
        Not a number with a unit of the same dimension as ``unit``; one line naming the option and the value.
    """
    from stability.chair.units import dimension_name, parse_unit

    m = _QUANTITY.match(text or "")
    try:
        own, own_dims = parse_unit(unit) if unit else (1.0, None)
    except ValueError:                      # an option whose unit the parser does not write (deg/s/sqrt(Hz))
        own, own_dims = 1.0, None
    if not m or own_dims is None:
        raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid; expected a finite number"
                                         + (f" (or a number with a unit of {unit})" if own_dims else "") + rng)
    try:
        factor, dims = parse_unit(m.group(2))
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid; {exc}{rng}") from None
    if dims != own_dims:
        want = dimension_name(own_dims)
        raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid: {m.group(2)!r} is a {dimension_name(dims)}"
                                         f" unit; expected a{'n' if want[0] in 'aeiou' else ''} {want} ({unit}){rng}")
    return float(m.group(1)) * factor / own


#: Options that are the angle of a surface (deg), which also take a road's and a ramp's notation: a percentage
#: (``8%``: rise over run, 4.57 deg) or a ratio ``1:12`` (rise:run, 4.76 deg, an accessible ramp's limit).
SLOPE_OPTIONS = ("--grade", "--cross-slope")

_SLOPE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+))\s*(?:(%)|:\s*(\d+\.?\d*|\.\d+))\s*$")


def slope_angle(text: str) -> float | None:
    """The angle (deg) of a slope written as a percentage (``8%``) or a rise:run ratio (``1:12``), else None.

    Parameters
    ----------
    text : str
        E.g. ``"8%"``, ``"-2 %"``, ``"1:12"``.

    Returns
    -------
    float or None
        ``atan(rise / run)`` in degrees (negative for a negative rise); None when ``text`` is neither notation
        (or the run is 0).
    """
    m = _SLOPE.match(text or "")
    if not m:
        return None
    rise = float(m.group(1))
    run = 100.0 if m.group(2) else float(m.group(3))
    return math.degrees(math.atan2(rise, run)) if run > 0 else None


def number(option: str, kind: type = float, bound: Bound | None = None) -> Callable[[str], float]:
    """An argparse ``type`` that parses one number of option ``option``, finite and inside ``bound``.

    A float may carry a unit of the bound's dimension (``--speed 3.6km/h``, ``--sample-rate 100Hz``,
    ``stability.cli.numbers.with_unit``), converted to the bound's unit; a grade or cross slope
    (``stability.cli.numbers.SLOPE_OPTIONS``) may also be a percentage or a rise:run ratio (``8%``, ``1:12``,
    ``stability.cli.numbers.slope_angle``).

    Every numeric option of every command is parsed by one of these (the
    parser installs it for ``type=float`` and ``type=int``), so a refusal
    always names the option, the value and the valid range.

    Parameters
    ----------
    option : str
        The option's name, e.g. ``"--seed"``.
    kind : type
        ``float`` or ``int``.
    bound : Bound, optional
        The plausible range (default: any finite number).

    Returns
    -------
    callable
        ``parse(text) -> float or int``, raising :class:`argparse.ArgumentTypeError`.
    """
    expected = "an integer" if kind is int else "a finite number"

    def parse(text: str) -> Any:
        rng = f"; valid range: {bound.text()}" if bound else ""
        try:
            value = kind(text)
        except (TypeError, ValueError, OverflowError):
            if kind is not float:
                raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid; expected {expected}{rng}") from None
            angle = slope_angle(text) if option in SLOPE_OPTIONS else None
            if angle is None and option in SLOPE_OPTIONS and (":" in text or "%" in text):
                raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid; expected an angle (deg), a percentage "
                                                 f"(8%) or a rise:run ratio with run > 0 (1:12){rng}") from None
            value = angle if angle is not None else with_unit(option, text, bound.unit if bound else "", rng)
        if kind is float and not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{option} {text!r} is invalid; expected {expected}{rng}")
        if bound is not None and not bound.holds(value):
            raise argparse.ArgumentTypeError(f"{option} {text} is invalid; valid range: {bound.text()}")
        return value

    parse.__name__ = kind.__name__        # argparse names the type in its own messages
    return parse


class NonFiniteResult(ArithmeticError):
    """A result that is NaN or infinite: never printed, reported as ``error: could not compute ...``."""


def first_non_finite(data: Any, where: str = "") -> str:
    """The key path of the first NaN or infinity in JSON-like ``data``.

    Parameters
    ----------
    data : Any
        Dicts, lists, tuples, arrays and numbers.
    where : str
        Path of ``data`` itself.

    Returns
    -------
    str
        E.g. ``"rows[0]['growth_rate_1_s']"``; empty when every number is finite.
    """
    if isinstance(data, dict):
        items: Any = data.items()
    elif isinstance(data, (list, tuple, np.ndarray)):
        items = enumerate(data)
    else:
        try:
            return "" if math.isfinite(float(data)) else (where or "value")
        except (TypeError, ValueError):
            return ""
    for key, value in items:
        found = first_non_finite(value, f"{where}[{key!r}]" if where else str(key))
        if found:
            return found
    return ""


#: A NaN or an infinity printed as a number (a word such as "info" or "infinite" is not one).
_NON_FINITE_TEXT = re.compile(r"(?:^|(?<=[\s(\[=:,]))[-+]?(?:nan|inf|infinity)(?=$|[\s)\],;])",
                              re.IGNORECASE | re.MULTILINE)


def check_finite_text(text: str) -> None:
    """Refuse text output that prints a NaN or an infinity as a result.

    Parameters
    ----------
    text : str
        What a command is about to print.

    Raises
    ------
    NonFiniteResult
        Quoting the line that holds the non-finite number.
    """
    m = _NON_FINITE_TEXT.search(text)
    if m:
        start = text.rfind("\n", 0, m.start()) + 1
        end = text.find("\n", m.end())
        line = text[start:end if end >= 0 else len(text)].strip()
        raise NonFiniteResult(f"a result is not finite ({line[:120]!r})")
