"""Bounds are values: a measure found only as "above" or "below" the searched range is ranked, compared and
printed by its bound.

A search that runs off its range still says something: an equal-instability
speed "above 3 m/s" is at least 3 m/s (better than any speed found inside the
range), a critical impulse "never reached up to 40 N s" is at least 40 N s.
Treating such a result as missing ranks the most stable designs last.  Here a
result is a pair ``(value, side)``: ``side`` is ``"="`` (found), ``">"`` (the
true value lies above ``value``) or ``"<"`` (below it).  For ranking, a bound
counts as its value, which is the conservative choice in both directions: a
lower bound on a better-when-higher measure can only be better, an upper bound
only worse.

:func:`side_of` maps the searches' statuses to sides, :func:`quantile` takes an
order statistic of censored draws (telling whether the quantile itself is a
bound), :func:`describe` prints one (``"> 3 m/s"``) and :func:`range_words` its range, unless the range is
degenerate (``"range 3-3 m/s"`` says nothing).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = ["SIDES", "side_of", "quantile", "describe", "range_words", "sort_key", "compare"]

#: The sides of a result: found, lower bound (the value is above), upper bound (below).
SIDES = ("=", ">", "<")
#: Status words of the searches and the side they mean.
_STATUS = {"found": "=", "above": ">", "never": ">", "below": "<", "": "=", "nan": "="}


def side_of(status: str) -> str:
    """The side of a search's status (``"found"`` -> ``"="``, ``"above"``/``"never"`` -> ``">"``,
    ``"below"`` -> ``"<"``).

    Parameters
    ----------
    status : str
        :attr:`stability.study.EqualInstability.status` or :attr:`stability.study.CriticalImpulse.status`.

    Returns
    -------
    str
        One of :data:`SIDES`.

    Raises
    ------
    ValueError
        An unknown status.
    """
    try:
        return _STATUS[str(status)]
    except KeyError:
        raise ValueError(f"status={status!r} is invalid; valid: found, above, never, below") from None


def quantile(values: Sequence[float], sides: Sequence[str], q: float) -> tuple[float, str]:
    """The ``q`` quantile of censored draws, and whether it is a bound.

    Each draw counts at its value (a bound at its bound, the conservative
    position).  Between two draws that are both values the quantile is
    interpolated linearly (numpy's default); where either neighbour is a bound
    it is the neighbour on the conservative side (the lower one for
    ``q <= 0.5``, the upper one above), and carries that draw's side.

    Parameters
    ----------
    values : sequence of float
        The draws' values or bounds (NaN draws are left out).
    sides : sequence of str
        Each draw's side (:data:`SIDES`).
    q : float
        0 <= q <= 1.

    Returns
    -------
    (float, str)
        The quantile and its side (``"="`` unless it is a bound); ``(nan, "=")`` without draws.
    """
    v = np.asarray(values, dtype=float)
    s = np.asarray(list(sides), dtype=object)
    ok = np.isfinite(v)
    v, s = v[ok], s[ok]
    if v.size == 0:
        return math.nan, "="
    order = np.lexsort((np.array([{"<": 0, "=": 1, ">": 2}[x] for x in s]), v))
    v, s = v[order], s[order]
    pos = q * (v.size - 1)
    lo, hi = int(math.floor(pos)), int(math.ceil(pos))
    if s[lo] == "=" and s[hi] == "=":
        return float(v[lo] + (pos - lo) * (v[hi] - v[lo])), "="
    k = lo if q <= 0.5 else hi
    return float(v[k]), str(s[k])


def sort_key(value: float, side: str, higher_is_better: bool) -> tuple[float, int]:
    """Sort key of a censored value, best first.

    Parameters
    ----------
    value : float
        The value or the bound (NaN sorts last).
    side : str
        One of :data:`SIDES`.
    higher_is_better : bool
        The measure's direction.

    Returns
    -------
    tuple
        Ascending order puts the best first: by value (in the good direction), then a bound beyond the value
        before the value itself ("> 3" before "3", "< 1" before "1" for a smaller-is-better measure).
    """
    if not math.isfinite(value):
        return (math.inf, 0)
    beyond = {"=": 0, ">": -1 if higher_is_better else 1, "<": 1 if higher_is_better else -1}[side]
    return (-value if higher_is_better else value, beyond)


def describe(value: float, side: str, unit: str = "", digits: int = 4) -> str:
    """A censored value in words: ``"1.16 m/s"``, ``"> 3 m/s"``, ``"< 1e-06 N s"``.

    Parameters
    ----------
    value : float
    side : str
        One of :data:`SIDES`.
    unit : str
    digits : int
        Significant figures.

    Returns
    -------
    str
    """
    if not math.isfinite(value):
        return "no value"
    text = f"{value:.{digits}g}" + (f" {unit}" if unit else "")
    return text if side == "=" else f"{side} {text}"


def range_words(low: float | None, high: float | None, unit: str, over: str = "", digits: int = 3) -> str:
    """``" (range 2.31-4.2 N s over ...)"``, or ``""`` when an end is missing or both print the same.

    Parameters
    ----------
    low, high : float or None
        The range's ends (None: no range).
    unit : str
    over : str
        What the range spans (``"push size, pin friction and simulator step"``), after "over".
    digits : int
        Significant figures.

    Returns
    -------
    str
        With a leading space, for appending to a value.
    """
    if low is None or high is None:
        return ""
    lo, hi = f"{low:.{digits}g}", f"{high:.{digits}g}"
    if lo == hi:
        return ""
    return f" (range {lo}-{hi}" + (f" {unit}" if unit else "") + (f" over {over}" if over else "") + ")"


def compare(a: float, side_a: str, b: float, side_b: str, higher_is_better: bool, rel_tol: float = 1e-3) -> str:
    """Which of two censored values is better.

    Each value stands for the set it allows: ``"="`` the value itself, ``">"`` everything above it, ``"<"``
    everything below.  ``a`` is better when every value it allows beats every value ``b`` allows.

    Parameters
    ----------
    a, b : float
        Values or bounds (NaN: no value).
    side_a, side_b : str
        One of :data:`SIDES`.
    higher_is_better : bool
    rel_tol : float
        Two found values closer than this (relative) are equal.

    Returns
    -------
    str
        ``"better"``, ``"worse"``, ``"equal"`` (both found, within ``rel_tol``) or ``"undecided"`` (the allowed
        sets overlap, e.g. ``> 3`` against ``3.5``, or a value is missing).
    """
    if not (math.isfinite(a) and math.isfinite(b)):
        return "undecided"
    if side_a == "=" and side_b == "=" and abs(a - b) <= rel_tol * max(abs(a), abs(b)):
        return "equal"

    def span(v: float, side: str) -> tuple[float, float]:
        return {"=": (v, v), ">": (v, math.inf), "<": (-math.inf, v)}[side]

    lo_a, hi_a = span(a, side_a)
    lo_b, hi_b = span(b, side_b)
    if lo_a >= hi_b and not (lo_a == hi_b and side_a == "=" and side_b == "="):
        return "better" if higher_is_better else "worse"
    if hi_a <= lo_b and not (hi_a == lo_b and side_a == "=" and side_b == "="):
        return "worse" if higher_is_better else "better"
    return "undecided"
