"""Text and JSON of a :class:`~stability.compare.compute.Comparison` (formatting only, no computation)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from stability.chair import to_mapping
from stability.compare.compute import NOT_SEPARABLE, Comparison, Difference, Quantity
from stability.compare.layouts import LAYOUT_NOTE
from stability.layout.model import Layout
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["format_comparison", "comparison_dict"]


def _num(x: float | None, unit: str = "", digits: int = 4) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    if math.isinf(x):
        return "none" if x > 0 else "-inf"
    return f"{x:.{digits}g}" + (f" {unit}" if unit else "")


def _end(x: float, max_speed: float) -> str:
    """An interval's end: a bound beyond the searched range (``inf``) as ``"> max_speed"``."""
    return f"> {max_speed:g}" if math.isinf(x) and x > 0 else _num(x)


def _value(q: Quantity, v: float, max_speed: float) -> str:
    if math.isinf(v) and v > 0:
        if q.none_means:
            return f"none ({q.none_means})"
        if q.key.startswith("zero_width"):
            return "none (understeer)"
        return f"none < {max_speed:g} m/s"
    return _num(v, q.unit)


def _time_to_double(rate: float) -> str:
    return f"{math.log(2) / rate:.3g} s" if rate > 0 else "never"


def _signed_end(x: float, side: str) -> str:
    """A difference interval's end; a bound (``side`` ``">"`` or ``"<"``) as ``">= x"`` or ``"<= x"``."""
    return {">": ">= ", "<": "<= "}.get(side, "") + f"{x:+.3g}"


def _verdict(d: Difference, q: Quantity) -> str:
    if d.more_stable == "equal":
        text = "equal"
    elif d.more_stable == "undetermined":
        text = "undetermined"
    elif d.more_stable == NOT_SEPARABLE:
        text = f"not separable (both bounds: {q.none_means})"
    else:
        text = f"{d.more_stable} more stable"
    if d.absolute is not None:
        text += f" (difference {d.absolute:+.3g} {q.unit}" + (f", {d.percent:+.3g} %" if d.percent is not None
                                                               else "") + ")"
    if d.interval is not None:
        lo, hi = d.interval
        sl, sh = d.interval_sides
        text += f"; difference interval [{_signed_end(lo, sl)}, {_signed_end(hi, sh)}] {q.unit}: "
        text += "distinguishable" if d.distinguishable else "NOT distinguishable with these uncertainties"
    return text


def _describe(ch) -> str:
    """A chair's or a layout's geometry in one line."""
    if isinstance(ch, Layout):
        nf, nc = ch.shape
        return (f"layout of {nf} fixed wheels ({sum(w.driven for w in ch.wheels)} driven, x = "
                f"{', '.join(f'{w.x:+.3g}' for w in ch.wheels)} m) and {nc} casters (pins x = "
                f"{', '.join(f'{k.x:+.3g}' for k in ch.casters)} m), m = {ch.m:g} kg, I_z = {ch.i_z:g} kg m^2")
    return (f"casters {ch.caster_position}, s1 = {ch.s1:g} m, s2 = {ch.s2:g} m, trail = {ch.trail:g} m, "
            f"m = {ch.m:g} kg, I_z = {ch.i_z:g} kg m^2")


def _layout_tail(c: Comparison) -> list[str]:
    """The end of a comparison of layouts: what does not apply, the push, the linear model's limit."""
    out = ["", LAYOUT_NOTE]
    if c.uncertainty:
        out += ["", "Intervals: the growth rates, the speeds up to which a layout is stable and the static stability "
                "over the uncertainty files' draws (the layouts' axes; a draw stable up to the searched "
                f"{c.max_speed:g} m/s counts as that bound, and an end that is one prints as \"> {c.max_speed:g}\"); "
                "the critical impulse is its own value, not propagated (a push search per draw)."]
    if c.push:
        out += ["", f"Critical impulse: push convention {c.push}."]
    return out + ["", "The linear growth rates have no pin friction (Coulomb friction has no linearisation); the "
                  "critical impulse (--nonlinear) includes it: see docs/compare.md."]


def _effects_tail(c: Comparison) -> list[str]:
    """The end of a comparison of short-form chairs: each differing parameter alone, the push, the linear limit."""
    ref = c.labels[0]
    lines: list[str] = []
    lines += ["", f"Why: each differing parameter applied alone to {ref}, largest effect first (change of the "
              f"growth rate at {REFERENCE_SPEED:g} m/s, 1/s; of the locked-caster critical speed, m/s; 0: below "
              "the eigenvalue solver's resolution):"]
    for e in c.effects:
        lines.append(f"  {e.chair}:")
        if not e.effects:
            lines.append("    no parameter differs")
            continue
        for s in sorted(e.effects, key=lambda s: (s.error is not None, -abs(s.growth_rate or 0.0),
                                                  -abs(s.locked_critical_speed or 0.0))):
            if s.error:
                lines.append(f"    {s.field:<22} {_field(s.reference_value)} -> {_field(s.value)}: "
                             f"not a valid chair alone ({s.error})")
                continue
            lines.append(f"    {s.field:<22} {_field(s.reference_value)} -> {_field(s.value)}: growth rate "
                         f"{_signed(s.growth_rate)}, locked critical speed {_signed(s.locked_critical_speed)}")
        lines.append(f"    {'total':<22} growth rate {_signed(e.total_growth_rate)}, locked critical speed "
                     f"{_signed(e.total_locked_critical_speed)}")
        lines.append(f"    {'interaction remainder':<22} growth rate {_signed(e.remainder_growth_rate)}, "
                     f"locked critical speed {_signed(e.remainder_locked_critical_speed)}")
    if c.push:
        lines += ["", f"Critical impulse: push convention {c.push}."]
    lines += ["", "The linear growth rates have no pin friction (Coulomb friction has no linearisation); the "
              "thesis's ranking by time to 1 rad/s after a push (--nonlinear) can differ: see docs/compare.md."]
    return lines


def format_comparison(c: Comparison) -> str:
    """The comparison as plain text: per-measure table, verdicts against the reference, single-parameter effects.

    Parameters
    ----------
    c : Comparison

    Returns
    -------
    str
    """
    ref = c.labels[0]
    lines = [f"Comparison of {', '.join(c.labels)} ({c.model} linear model; reference: {ref})", ""]
    for i, (label, ch) in enumerate(zip(c.labels, c.chairs, strict=True)):
        lines.append(f"  [{i + 1}] {label}: {_describe(ch)}")
    width = max(len(q.label) for q in c.quantities) + 2
    lines += ["", "Measures" + (f" (intervals: central {c.uncertainty['level']:.0%} over the uncertain parameters)"
                              if c.uncertainty else "") + ":"]
    for q in c.quantities:
        cells = []
        for v, iv in zip(q.values, q.intervals, strict=True):
            cell = _value(q, v, c.max_speed)
            if q.key.startswith("growth_rate"):
                cell += f" (doubles {_time_to_double(v)})"
            if iv is not None and iv[0] == iv[1]:       # a degenerate range says nothing but that it is one value
                cell += " [the same over the interval]"
            elif iv is not None:
                cell += f" [{_end(iv[0], c.max_speed)}, {_end(iv[1], c.max_speed)}]"
            cells.append(cell)
        lines.append(f"  {q.label:<{width}}" + " | ".join(cells))
    user = any(q.key == "human_limited_speed_m_s" for q in c.quantities)
    lines += ["", f"Against the reference {ref} (lower growth rate, higher critical speed, "
              "understeer coefficient" + (", critical impulse and speed the user holds" if user else
                                          " and critical impulse") + " = more stable):"]
    qmap = {q.key: q for q in c.quantities}
    for label in c.labels[1:]:
        lines.append(f"  {label}:")
        for d in c.differences:
            if d.chair == label:
                lines.append(f"    {qmap[d.key].label:<{width}}{_verdict(d, qmap[d.key])}")
    if c.uncertainty:
        lines.append(f"  (differences drawn with {c.uncertainty['pairing']} draws, {c.uncertainty['samples']} "
                     f"samples, seed {c.uncertainty['seed']}; overlapping chair intervals alone do not decide)")
    lines += _layout_tail(c) if any(isinstance(ch, Layout) for ch in c.chairs) else _effects_tail(c)
    return "\n".join(lines)


def _field(v: object) -> str:
    return f"{v:.4g}" if isinstance(v, float) else repr(v)


#: Changes smaller than this are eigenvalue round-off, shown as 0 (1/s or m/s): the solver's error is about
#: eps * ||A|| * cond ~ 1e-12 here (t1 alone changes the growth rate by 4e-12); a margin of 1000 over that.
RESOLUTION = 1e-9


def _signed(x: float | None) -> str:
    if x is None:
        return "n/a"
    return "0" if abs(x) < RESOLUTION else f"{x:+.3g}"


def _finite(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def _measure(key: str) -> dict[str, Any]:
    """``"growth_rate_1_s@0.25"`` -> ``{"measure": "growth_rate_1_s", "speed_m_s": 0.25}`` (null speed without @)."""
    name, sep, speed = key.partition("@")
    return {"measure": name, "speed_m_s": float(speed) if sep else None}


def comparison_dict(c: Comparison, header: dict[str, Any]) -> dict[str, Any]:
    """JSON-ready dict of a comparison.

    Parameters
    ----------
    c : Comparison
    header : dict
        What :func:`stability.cli.json_header` gives for the reference chair (version, model, options);
        its ``chair``/``chair_parameters`` are replaced by the list ``chairs``.

    Returns
    -------
    dict
        Keys: ``stability_version``, ``model``, ``options``, ``chairs`` (label, name, parameters),
        ``reference``, ``measures`` (a list, one entry per quantity and speed: ``measure`` (e.g.
        ``growth_rate_1_s``), ``speed_m_s`` (null for a measure that is not per speed), unit, direction,
        and ``chairs``, a list in the order of ``chairs`` with each chair's value and interval;
        infinite values as null with ``"none_in_range": true``), ``verdicts`` (``measure``, ``speed_m_s``),
        ``single_effects``, ``uncertainty``, ``push``.  No value is ever part of a key.
    """
    out = {k: v for k, v in header.items() if k not in ("chair", "chair_parameters")}
    out["chairs"] = [{"label": lab, "name": ch.name,
                      "parameters": dataclasses.asdict(ch) if isinstance(ch, Layout) else to_mapping(ch)}
                     for lab, ch in zip(c.labels, c.chairs, strict=True)]
    out["reference"] = c.labels[0]
    out["speeds_m_s"] = list(c.speeds)
    measures = []
    for q in c.quantities:
        per = []
        for lab, v, iv in zip(c.labels, q.values, q.intervals, strict=True):
            row: dict[str, Any] = {"chair": lab, "value": _finite(v), "none_in_range": bool(math.isinf(v) and v > 0)}
            if row["none_in_range"] and q.none_means:
                row["none_means"] = q.none_means
            if q.key.startswith("growth_rate"):
                row["time_to_double_s"] = math.log(2) / v if v > 0 else None
            if iv is not None:
                row["interval"] = [_finite(iv[0]), _finite(iv[1])]
            per.append(row)
        measures.append({**_measure(q.key), "label": q.label, "unit": q.unit,
                         "higher_is_more_stable": q.higher_is_more_stable, "chairs": per})
    out["measures"] = measures
    units = {q.key: q.unit for q in c.quantities}
    out["verdicts"] = [{**_measure(d.key), "chair": d.chair, "reference": c.labels[0], "more_stable": d.more_stable,
                        "difference": d.absolute, "unit": units.get(d.key), "difference_percent": d.percent,
                        "difference_interval": list(d.interval) if d.interval else None,
                        "difference_interval_sides": list(d.interval_sides) if d.interval else None,
                        "distinguishable": d.distinguishable} for d in c.differences]
    out["single_effects"] = [
        {"chair": e.chair, "reference": c.labels[0], "speed_m_s": REFERENCE_SPEED,
         "effects": [{"field": s.field, "reference_value": s.reference_value, "value": s.value,
                      "growth_rate_change_1_s": s.growth_rate,
                      "locked_critical_speed_change_m_s": s.locked_critical_speed, "error": s.error}
                     for s in e.effects],
         "total_growth_rate_change_1_s": e.total_growth_rate,
         "total_locked_critical_speed_change_m_s": e.total_locked_critical_speed,
         "interaction_growth_rate_1_s": e.remainder_growth_rate,
         "interaction_locked_critical_speed_m_s": e.remainder_locked_critical_speed}
        for e in c.effects]
    out["uncertainty"] = c.uncertainty
    out["push"] = c.push
    return out
