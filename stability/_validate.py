"""Argument checks shared by the analysis modules.

Every check raises :class:`ValueError` with a one-line message that names the
parameter, its value and the valid range or choices, e.g.
``speed=-1.0 is invalid; valid range: speed > 0 m/s (forward motion)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = ["VARIANTS", "CASTERS", "check_choice", "check_model", "check_casters", "check_speed",
           "check_speeds", "check_positive", "check_nonnegative", "check_finite"]

VARIANTS = ("exact", "thesis")
CASTERS = ("free", "locked")

_SPEED_RANGE = "speed > 0 m/s (forward motion)"


def check_choice(name: str, value: Any, choices: Sequence) -> Any:
    """``value`` if it is one of ``choices``."""
    if value not in choices:
        raise ValueError(f"{name}={value!r} is invalid; valid choices: {list(choices)}")
    return value


def check_model(model: str) -> str:
    """Model variant, one of :data:`VARIANTS`."""
    return check_choice("model", model, VARIANTS)


def check_casters(casters: str) -> str:
    """Caster state, one of :data:`CASTERS`."""
    return check_choice("casters", casters, CASTERS)


def check_speed(speed: Any, name: str = "speed") -> float:
    """One forward speed (m/s) as a float: finite and > 0."""
    try:
        s = float(speed)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={speed!r} is invalid; valid range: {_SPEED_RANGE}") from None
    if not (math.isfinite(s) and s > 0):
        raise ValueError(f"{name}={speed!r} is invalid; valid range: {_SPEED_RANGE}")
    return s


def check_speeds(speeds: Any, name: str = "speed") -> np.ndarray:
    """Forward speeds (m/s) as a float array of at least one dimension: every one finite and > 0."""
    U = np.atleast_1d(np.asarray(speeds, dtype=float))
    ok = np.isfinite(U) & (U > 0)
    if not np.all(ok):
        raise ValueError(f"{name}={float(U[~ok][0])!r} is invalid; valid range: {_SPEED_RANGE}")
    return U


def _number(name: str, value: Any, valid: str, prefix: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ValueError(f"{prefix}{name}={value!r} is invalid; valid range: {valid}")
    return float(value)


def check_positive(name: str, value: Any, *, prefix: str = "") -> float:
    """A finite real number > 0 (booleans and strings are refused); ``prefix`` starts the message."""
    v = _number(name, value, "> 0 (finite)", prefix)
    if v <= 0:
        raise ValueError(f"{prefix}{name}={value!r} is invalid; valid range: > 0 (finite)")
    return v


def check_nonnegative(name: str, value: Any, *, prefix: str = "") -> float:
    """A finite real number >= 0 (booleans and strings are refused)."""
    v = _number(name, value, ">= 0 (finite)", prefix)
    if v < 0:
        raise ValueError(f"{prefix}{name}={value!r} is invalid; valid range: >= 0 (finite)")
    return v


def check_finite(name: str, value: Any, *, unit: str = "", prefix: str = "") -> float:
    """A finite real number of any sign (booleans and strings are refused); ``unit`` names its unit."""
    return _number(name, value, "a finite number" + (f" ({unit})" if unit else ""), prefix)
