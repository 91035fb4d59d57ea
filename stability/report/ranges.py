"""How the report prints a value with its range: the range says what it spans, bounds print as bounds, a
degenerate range is not printed, prose uses 3 significant figures."""

from __future__ import annotations

from typing import Any

from stability.report.behaviour import sig3

__all__ = ["value_range", "interval_words", "undefined_variants"]


def value_range(value: float | None, low: float | None, high: float | None, unit: str = "", *, spans: str = "",
                bound: str = "") -> str:
    """``"1.02 m/s (0.779-1.12 m/s over <spans>)"``; ``"> 3 m/s"`` for a bound; no range when it is degenerate.

    Parameters
    ----------
    value : float or None
        The nominal value (None: undefined).
    low, high : float or None
        Range ends (None: no range).
    unit : str
    spans : str
        What the range spans ("push, pin friction, model and step, one at a time").
    bound : {"", "above", "below", "never"}
        The value is a bound: above ("> v"), below ("< v").

    Returns
    -------
    str
    """
    u = f" {unit}" if unit else ""
    if value is None:
        return "undefined"
    sign = {"above": "> ", "never": "> ", "below": "< "}.get(bound, "")
    txt = f"{sign}{sig3(value)}{u}"
    if bound or low is None or high is None or sig3(low) == sig3(high):
        return txt
    return txt + f" ({sig3(low)}-{sig3(high)}{u}" + (f" over {spans}" if spans else "") + ")"


def undefined_variants(iv: Any) -> list[str]:
    """Labels of the variants of an :class:`stability.study.EqualInstabilityInterval` left out of its range.

    Parameters
    ----------
    iv : stability.study.EqualInstabilityInterval

    Returns
    -------
    list of str
        ``"<factor> <label>"`` of every undefined variant.
    """
    return [f"{v.factor} {v.label}" for v in iv.variants if v.result is None]


def interval_words(iv: Any) -> str:
    """The interval's range with what it spans and the variants it leaves out (empty when degenerate).

    Parameters
    ----------
    iv : stability.study.EqualInstabilityInterval

    Returns
    -------
    str
        E.g. ``"range 0.78-1.12 m/s over the push, pin friction, model and step variants; 3 of 8 undefined and
        left out: disturbance 20 N (0.5x), ..."`` (the variants are defined on the equal-instability page).
    """
    if iv is None or iv.low is None or iv.high is None:
        return ""
    out = []
    rng = iv.range_text()
    if sig3(iv.low) != sig3(iv.high):
        out.append(rng + " over the push, pin friction, model and step variants")
    und = undefined_variants(iv)
    if und:
        out.append(f"{len(und)} of {len(iv.variants)} undefined and left out: " + ", ".join(und))
    return "; ".join(out)
