"""Argument checks shared by the analysis modules.

Every check raises :class:`ValueError` with a one-line message that names the
parameter, its value and the valid range or choices, e.g.
``speed=-1.0 is invalid; valid range: speed > 0 m/s (forward motion)``.
"""

from __future__ import annotations

import functools
import inspect
import math
from collections.abc import Callable, Sequence
from typing import Any, TypeVar, cast

import numpy as np

__all__ = ["VARIANTS", "CASTERS", "check_choice", "check_model", "check_casters", "check_speed",
           "check_speeds", "check_positive", "check_nonnegative", "check_finite", "is_real", "real_value",
           "real_array", "value_text", "first_argument", "MIN_SPEED", "MAX_SPEED"]

F = TypeVar("F", bound=Callable[..., Any])

VARIANTS = ("exact", "thesis")
CASTERS = ("free", "locked")

#: Slowest speed, m/s.  The linear model's tire terms grow as 1/speed and its kinematic terms shrink with it,
#: so the rates of the slow modes (proportional to speed there) are found next to modes of order 1/speed: the
#: eigenvalue solver's relative error grows as 1/speed^2 (measured for ej-premier: 4e-3 at 1e-4 m/s, 1e7 times
#: the true rate below 1e-6 m/s).  At 0.01 m/s it is 4e-7, 250 times below the 1e-4 the tables print; and the
#: simulator's stable step shrinks with speed alike.  1 cm/s is no question of directional stability.
MIN_SPEED = 0.01
#: Fastest speed, m/s: the critical-speed search's upper end (no wheelchair reaches it).
MAX_SPEED = 100.0
_SPEED_RANGE = (f"{MIN_SPEED:g} <= speed <= {MAX_SPEED:g} m/s (forward motion; below {MIN_SPEED:g} m/s the rates, "
                "proportional to speed there, are lost in round-off)")


#: Longest value quoted in a refusal, characters: an argument's value is named, never dumped (a 400-digit integer,
#: a million-element array).
MAX_VALUE_TEXT = 60


def value_text(value: Any) -> str:
    """``repr(value)`` as a refusal quotes it: at most :data:`MAX_VALUE_TEXT` characters.

    An integer too long to show is written in scientific notation (``10**400`` as ``1.000e+400``); any other
    long repr (an array, a long string) is cut, with its length said.

    Parameters
    ----------
    value : Any

    Returns
    -------
    str
    """
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**21:
        digits = str(abs(value))
        sign = "-" if value < 0 else ""
        return f"{sign}{digits[0]}.{digits[1:4]}e+{len(digits) - 1}"
    try:
        text = repr(value)
    except Exception:  # noqa: BLE001  (a repr that fails still names the type)
        text = f"<{type(value).__name__}>"
    text = " ".join(text.split())                  # one line: an array's repr spans several
    if len(text) > MAX_VALUE_TEXT:
        text = f"{text[:MAX_VALUE_TEXT - 20]}... ({len(text)} characters)"
    return text


def real_value(value: Any) -> float:
    """A real number as a float: an integer too large for a float is +-inf (outside every bound), not an error.

    Parameters
    ----------
    value : Any
        A real number (:func:`is_real`).

    Returns
    -------
    float
        ``float(value)``; ``+-inf`` for an integer beyond the float range.
    """
    try:
        return float(value)
    except OverflowError:
        return math.inf if value > 0 else -math.inf


def real_array(values: Any) -> np.ndarray:
    """``values`` as a float array; an integer beyond the float range becomes +-inf (:func:`real_value`), outside
    every bound, rather than an OverflowError.

    Parameters
    ----------
    values : Any
        A number or a (nested) sequence or array of numbers.

    Returns
    -------
    ndarray of float
        The shape of ``np.asarray(values)``.

    Raises
    ------
    TypeError, ValueError
        ``values`` is not numeric (numpy's own refusal, for the caller to name the argument).
    """
    try:
        return np.asarray(values, dtype=float)
    except OverflowError:
        obj = np.asarray(values, dtype=object)
        return np.array([real_value(v) for v in obj.ravel()], dtype=float).reshape(obj.shape)


def check_choice(name: str, value: Any, choices: Sequence) -> Any:
    """Return ``value`` unchanged if it is one of ``choices``, else raise.

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : Any
        Value to check.
    choices : Sequence
        Allowed values.

    Returns
    -------
    Any
        ``value`` itself.

    Raises
    ------
    ValueError
        If ``value`` is not in ``choices``; the message lists the valid choices.
    """
    try:
        ok = value in choices
    except Exception:  # noqa: BLE001  (an array or an object whose == is not a truth value)
        ok = False
    if not ok:
        raise ValueError(f"{name}={value_text(value)} is invalid; valid choices: {list(choices)}")
    return value


def check_model(model: str) -> str:
    """Check a model variant name, one of :data:`VARIANTS` (``"exact"`` or ``"thesis"``).

    Parameters
    ----------
    model : str
        Model variant: ``"exact"`` (first-principles Kane derivation) or ``"thesis"``
        (Collins 1987 Table 6-1, eqs 6-17/6-18, as program WCHAIR integrates).

    Returns
    -------
    str
        ``model`` itself.

    Raises
    ------
    ValueError
        If ``model`` is not one of :data:`VARIANTS`.
    """
    return check_choice("model", model, VARIANTS)


def check_casters(casters: str) -> str:
    """Check a caster state, one of :data:`CASTERS` (``"free"`` or ``"locked"``).

    Parameters
    ----------
    casters : str
        Caster state: ``"free"`` (casters swivel) or ``"locked"`` (caster swivel angle held at zero).

    Returns
    -------
    str
        ``casters`` itself.

    Raises
    ------
    ValueError
        If ``casters`` is not one of :data:`CASTERS`.
    """
    return check_choice("casters", casters, CASTERS)


def check_speed(speed: Any, name: str = "speed", floor: float = MIN_SPEED) -> float:
    """Check one forward speed and return it as a float: finite and > 0.

    Parameters
    ----------
    speed : Any
        Forward speed U, m/s; anything ``float()`` accepts. Valid range: finite, > 0.
    name : str, optional
        Parameter name used in the error message (default ``"speed"``).
    floor : float, optional
        Slowest speed allowed, m/s (default :data:`MIN_SPEED`); 0: any speed > 0
        (internal searches and finite differences near the floor).

    Returns
    -------
    float
        The speed, m/s.

    Raises
    ------
    ValueError
        If ``speed`` is not a number, not finite or not > 0.
    """
    try:
        s = real_value(speed)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value_text(speed)} is invalid; valid range: {_SPEED_RANGE}") from None
    if not (math.isfinite(s) and (floor <= s if floor > 0 else s > 0) and s <= MAX_SPEED):
        raise ValueError(f"{name}={value_text(speed)} is invalid; valid range: {_SPEED_RANGE}")
    return s


def check_speeds(speeds: Any, name: str = "speed", floor: float = MIN_SPEED,
                 max_count: int | None = None, one_dim: bool = False) -> np.ndarray:
    """Check forward speeds and return them as a float array of at least one dimension.

    Parameters
    ----------
    speeds : Any
        Forward speed(s) U, m/s: a scalar or array-like. Valid range: every one finite and > 0.
    name : str, optional
        Parameter name used in the error message (default ``"speed"``).
    floor : float, optional
        Slowest speed allowed, m/s (default :data:`MIN_SPEED`); 0: any speed > 0.
    max_count : int, optional
        Most speeds allowed (the caller's work bound); default any number.
    one_dim : bool, optional
        Refuse more than one dimension (a public function's list of speeds); default: any shape (internal
        batches broadcast speeds against chairs).

    Returns
    -------
    numpy.ndarray
        Speeds, m/s, as a float array with ``ndim >= 1``.

    Raises
    ------
    ValueError
        If any speed is not a number, not finite or not > 0 (the message names the first offending value), if
        ``speeds`` is empty (or has more than one dimension with ``one_dim``), or more than ``max_count`` speeds.
    """
    size = np.size(speeds) if isinstance(speeds, np.ndarray) else None
    if max_count is not None and size is not None and size > max_count:      # before any copy of a huge array
        raise ValueError(f"{name} has {size} values; at most {max_count} are allowed here")
    try:
        U = np.atleast_1d(real_array(speeds))
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value_text(speeds)} is invalid; valid range: every speed a number, "
                         f"{_SPEED_RANGE}") from None
    if (one_dim and U.ndim != 1) or U.size == 0:
        raise ValueError(f"{name}={value_text(speeds)} is invalid; valid values: a speed or a non-empty 1-D "
                         f"sequence of speeds, {_SPEED_RANGE}")
    if max_count is not None and U.size > max_count:
        raise ValueError(f"{name} has {U.size} values; at most {max_count} are allowed here")
    ok = np.isfinite(U) & ((U >= floor) if floor > 0 else (U > 0)) & (U <= MAX_SPEED)
    if not np.all(ok):
        i = int(np.flatnonzero(~ok.ravel())[0])
        raw = speeds if isinstance(speeds, np.ndarray) else np.asarray(speeds, dtype=object)
        given = raw.ravel()[i] if raw.size == U.size else None
        shown = (value_text(given) if isinstance(given, (int, np.integer)) and not isinstance(given, bool)
                 else repr(float(U.ravel()[i])))      # an integer as given (10**400, not the inf it maps to)
        raise ValueError(f"{name}={shown} is invalid; valid range: {_SPEED_RANGE}")
    return U


def is_real(value: Any) -> bool:
    """True for a real number: ``int``, ``float`` and numpy's integer and floating scalars, not booleans.

    Parameters
    ----------
    value : Any

    Returns
    -------
    bool
    """
    return isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, (bool, np.bool_))


def _number(name: str, value: Any, valid: str, prefix: str) -> float:
    if not is_real(value) or not math.isfinite(real_value(value)):
        raise ValueError(f"{prefix}{name}={value_text(value)} is invalid; valid range: {valid}")
    return float(value)


def check_positive(name: str, value: Any, *, prefix: str = "") -> float:
    """Check a finite real number > 0 (booleans and strings are refused).

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : Any
        Value to check; must be an ``int`` or ``float`` (not ``bool``), finite and > 0.
    prefix : str, optional
        Text that starts the error message (e.g. a table name), default empty.

    Returns
    -------
    float
        ``value`` as a float, in the caller's unit.

    Raises
    ------
    ValueError
        If ``value`` is not a finite real number > 0.
    """
    v = _number(name, value, "> 0 (finite)", prefix)
    if v <= 0:
        raise ValueError(f"{prefix}{name}={value_text(value)} is invalid; valid range: > 0 (finite)")
    return v


def check_nonnegative(name: str, value: Any, *, prefix: str = "") -> float:
    """Check a finite real number >= 0 (booleans and strings are refused).

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : Any
        Value to check; must be an ``int`` or ``float`` (not ``bool``), finite and >= 0.
    prefix : str, optional
        Text that starts the error message, default empty.

    Returns
    -------
    float
        ``value`` as a float, in the caller's unit.

    Raises
    ------
    ValueError
        If ``value`` is not a finite real number >= 0.
    """
    v = _number(name, value, ">= 0 (finite)", prefix)
    if v < 0:
        raise ValueError(f"{prefix}{name}={value_text(value)} is invalid; valid range: >= 0 (finite)")
    return v


def check_finite(name: str, value: Any, *, unit: str = "", prefix: str = "") -> float:
    """Check a finite real number of any sign (booleans and strings are refused).

    Parameters
    ----------
    name : str
        Parameter name used in the error message.
    value : Any
        Value to check; must be an ``int`` or ``float`` (not ``bool``) and finite.
    unit : str, optional
        Unit shown in the error message's valid range (e.g. ``"deg"``), default none.
    prefix : str, optional
        Text that starts the error message, default empty.

    Returns
    -------
    float
        ``value`` as a float, in ``unit``.

    Raises
    ------
    ValueError
        If ``value`` is not a finite real number.
    """
    return _number(name, value, "a finite number" + (f" ({unit})" if unit else ""), prefix)


_ABSENT = object()


def first_argument(check: Callable[[Any, str], Any], optional: bool = False) -> Callable[[F], F]:
    """Decorator: ``check(value, name)`` on a public function's first argument before its body runs.

    The check raises the one-line TypeError or ValueError of the API's contract (``chair='ej-premier' is
    invalid; ...``) where the body would fail later with an AttributeError on the wrong object, or compute.

    Parameters
    ----------
    check : callable
        ``check(value, name)``, raising TypeError or ValueError naming ``name``, the first parameter's name (read
        from the function's signature); its return value is ignored.
    optional : bool, optional
        Skip the check for ``None`` (a parameter whose default is None).

    Returns
    -------
    callable
        The decorator; the decorated function keeps its name, signature and docstring (``functools.wraps``).
    """
    def decorate(func: F) -> F:
        name = next(iter(inspect.signature(func).parameters))

        @functools.wraps(func)
        def checked(*args: Any, **kwargs: Any) -> Any:
            value = args[0] if args else kwargs.get(name, _ABSENT)
            if value is not _ABSENT and not (optional and value is None):
                check(value, name)
            return func(*args, **kwargs)
        return cast(F, checked)
    return decorate
