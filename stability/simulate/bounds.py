"""Bounds of one simulation run: plausible input and bounded time and memory (the API's and the CLI's).

Each check raises :class:`ValueError` naming the argument, its value and the
largest (or smallest) allowed value.
"""

from __future__ import annotations

from typing import Any

from stability.runtime.checks import check_positive

__all__ = ["MAX_DURATION_S", "MAX_STEPS", "MIN_DT_S", "MAX_ROWS", "ROW_BYTES", "MAX_PUSH_N", "MIN_RTOL", "MIN_ATOL",
           "check_steps", "check_pushes", "check_rows", "check_tolerances"]

# Bounds of one run (bounded time and memory, plausible input), shared by the API and the command line:
# an hour of motion; 2e7 fixed steps (about 0.2 us each compiled: seconds); steps of 1 us at least (below,
# t + dt loses 1e-10 of the step at 1 h); a stored history of 2e6 rows of 32 x 8 bytes (512 MB); pushes of
# 10 kN at most (a person pushes with a few hundred N); a lateral skid of 5 m/s; tolerances no tighter than
# double precision can hold for states of order 1 (eps = 2.2e-16; tighter collapses the step to round-off).
MAX_DURATION_S, MAX_STEPS, MIN_DT_S, MAX_ROWS, ROW_BYTES = 3600.0, 20_000_000, 1e-6, 2_000_000, 256
MAX_PUSH_N, MIN_RTOL, MIN_ATOL = 10_000.0, 1e-12, 1e-14

def check_steps(scheme: str, duration: float, dt: float) -> None:
    """An hour at most, and at most :data:`MAX_STEPS` fixed steps of at least :data:`MIN_DT_S`.

    Parameters
    ----------
    scheme : str
        ``"wchair"`` (fixed steps) or ``"adaptive"``.
    duration, dt : float
        Simulated time and fixed step, s.

    Raises
    ------
    ValueError
        Naming the argument, its value and the largest (smallest) allowed value.
    """
    if duration > MAX_DURATION_S:
        raise ValueError(f"duration={duration!r} is invalid; valid range: 0 < duration <= {MAX_DURATION_S:g} s")
    if scheme == "wchair" and dt < MIN_DT_S:
        raise ValueError(f"dt={dt!r} is invalid; valid range: {MIN_DT_S:g} s <= dt <= duration")
    if scheme == "wchair" and duration / dt > MAX_STEPS:
        raise ValueError(f"duration={duration!r} s with dt={dt!r} s asks for {duration / dt:.3g} steps; at most "
                         f"{MAX_STEPS:.3g} are allowed: the largest allowed duration is {MAX_STEPS * dt:.4g} s, "
                         f"the smallest dt {duration / MAX_STEPS:.3g} s")


def check_pushes(impulse_force: float, tire_impulse: float, lateral_velocity: float) -> None:
    """Pushes within :data:`MAX_PUSH_N` and the initial lateral velocity within 5 m/s (a skid at a run).

    Parameters
    ----------
    impulse_force, tire_impulse : float
        N.
    lateral_velocity : float
        m/s.

    Raises
    ------
    ValueError
        Naming the argument, its value and the largest (smallest) allowed value.
    """
    for name, value, bound, unit in (("impulse_force", impulse_force, MAX_PUSH_N, "N"), ("tire_impulse", tire_impulse,
                                     MAX_PUSH_N, "N"), ("lateral_velocity", lateral_velocity, 5.0, "m/s")):
        if abs(value) > bound:
            raise ValueError(f"{name}={value!r} is invalid; valid range: |{name}| <= {bound:g} {unit}")


def check_rows(duration: float, interval: float) -> None:
    """The stored history (a row every ``interval`` s) within :data:`MAX_ROWS` rows.

    Parameters
    ----------
    duration, interval : float
        s.

    Raises
    ------
    ValueError
        Naming the argument, its value and the largest (smallest) allowed value.
    """
    rows = duration / interval
    if rows > MAX_ROWS:
        raise ValueError(f"duration={duration:g} s stored every {interval:.3g} s is {rows:.3g} rows "
                         f"({rows * ROW_BYTES / 2**20:.0f} MB); at most {MAX_ROWS:.3g} rows are allowed: the largest "
                         f"allowed duration is {MAX_ROWS * interval:.4g} s, or give sample >= "
                         f"{duration / MAX_ROWS:.3g} s")


def check_tolerances(rtol: Any, atol: Any) -> tuple[float, float]:
    """Tolerances of the adaptive scheme, no tighter than :data:`MIN_RTOL` and :data:`MIN_ATOL`.

    Parameters
    ----------
    rtol, atol : Any
        Relative and absolute tolerances.

    Returns
    -------
    tuple of float
        ``(rtol, atol)``.

    Raises
    ------
    ValueError
        Naming the argument, its value and the largest (smallest) allowed value.
    """
    rtol = check_positive("rtol", rtol)
    atol = check_positive("atol", atol)
    if rtol < MIN_RTOL:
        raise ValueError(f"rtol={rtol!r} is invalid; valid range: rtol >= {MIN_RTOL:g}")
    if atol < MIN_ATOL:
        raise ValueError(f"atol={atol!r} is invalid; valid range: atol >= {MIN_ATOL:g}")
    return rtol, atol
