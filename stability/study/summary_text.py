"""The linear stability summary of one chair as JSON-ready data and as readable text.

What ``python -m stability.critical_speed`` prints and the report quotes: loads,
stiffnesses, critical speeds, the divergence table, and (when the chair has
effects the linear model leaves out) the simulator's own linearisation.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from stability.linear import StabilitySummary
from stability.study.validation import linearisation_check, omitted_effects

if TYPE_CHECKING:
    from stability.linear.intervals import LinearIntervals
    from stability.study.uncertain import NonlinearIntervals

__all__ = ["simulator_checks", "summary_dict", "interpretation", "format_summary", "intervals_dict",
           "nonlinear_intervals_dict"]


def _first(crossings, direction: str | None = None):
    for c in crossings:
        if direction is None or c.direction == direction:
            return c.speed
    return None


def simulator_checks(s: StabilitySummary) -> list:
    """The simulator's own linearisation at the divergence-table speeds, when it matters.

    Empty unless the chair has effects the linear model leaves out
    (:func:`stability.study.validation.omitted_effects`: rolling resistance, camber,
    toe); then one row per speed with the dominant rate of both models.

    Parameters
    ----------
    s : StabilitySummary
        The linear summary (:func:`stability.linear.analyse`).

    Returns
    -------
    list of dict
        Per speed: ``speed_m_s``, ``rate_linear_1_s``, ``rate_simulator_1_s``
        and their ``relative_difference``; empty when nothing is left out.
    """
    if not omitted_effects(s.chair):
        return []
    rows = []
    for r in s.divergence:
        chk = linearisation_check(s.chair, r.speed, model=s.model)
        rows.append({"speed_m_s": r.speed, "rate_linear_1_s": chk.eigenvalue_linear.real,
                     "rate_simulator_1_s": chk.eigenvalue_simulator.real,
                     "relative_difference": chk.rate_difference})
    return rows


def _pair(lo: float, hi: float) -> list[float | None]:
    return [None if math.isnan(lo) else lo, None if math.isnan(hi) else hi]


def intervals_dict(iv: LinearIntervals) -> dict:
    """The ``uncertainty`` block of the JSON summary.

    Parameters
    ----------
    iv : LinearIntervals

    Returns
    -------
    dict
        ``samples``, ``seed``, ``level``, ``method``, ``dominant_parameters``
        (name, variance share) and the delta-method rate intervals as a check.
    """
    return {"samples": iv.samples, "seed": iv.seed, "level": iv.level,
            "method": "Monte Carlo (seeded); central percentile intervals",
            "dominant_parameters": [[n, s] for n, s in iv.dominant_parameters],
            "delta_method_rate_1_s_intervals": [list(p) for p in iv.rate_delta],
            "note": "Coulomb pin friction has no linearisation: it does not move the linear results"}


def nonlinear_intervals_dict(nl: NonlinearIntervals) -> dict:
    """The nonlinear keys of the ``uncertainty`` block of the JSON summary.

    Parameters
    ----------
    nl : NonlinearIntervals

    Returns
    -------
    dict
        ``critical_impulse_Ns_interval`` and ``equal_instability_speed_m_s_interval``
        (``[low, high]``, None where no draw has a value) and ``nonlinear`` (the full result).
    """
    eq = nl.equal_instability
    k = nl.critical_impulse
    return {"critical_impulse_Ns_interval": _pair(k.low, k.high),
            "equal_instability_speed_m_s_interval": None if eq is None else _pair(eq.low, eq.high),
            "nonlinear": nl.to_dict()}


def summary_dict(s: StabilitySummary, checks: list | None = None, intervals: LinearIntervals | None = None,
                 nonlinear: NonlinearIntervals | None = None) -> dict:
    """The JSON structure printed by ``--json``.

    Parameters
    ----------
    s : StabilitySummary
    checks : list, optional
        Rows of :func:`simulator_checks`.
    intervals : LinearIntervals, optional
        With it, each divergence row gains ``rate_1_s_interval``, each critical
        speed a ``critical_speed_m_s_interval``, and the top level ``uncertainty``.
    nonlinear : NonlinearIntervals, optional
        With ``intervals``: ``uncertainty`` gains :func:`nonlinear_intervals_dict`.

    Returns
    -------
    dict
    """
    zw = s.zero_width

    def cross(lst):
        return [{"speed_m_s": c.speed, "kind": c.kind, "direction": c.direction,
                 "eigenvalue": [c.eigenvalue.real, c.eigenvalue.imag]} for c in lst]

    d: dict[str, Any] = {
        "chair": s.chair.name,
        "model": s.model,
        "caster_position": s.chair.caster_position,
        "static_load_N": {"main": s.static_loads["main"], "caster": s.static_loads["caster"]},
        "cornering_stiffness_N_per_deg": dict(s.stiffness_n_per_deg),
        "zero_width": {
            "understeer_coefficient_rad": zw.understeer_coefficient,
            "critical_speed_m_s": zw.critical_speed,
            "load_N": {"main": zw.load_main, "caster": zw.load_caster},
        },
        "locked_casters": {"critical_speed_m_s": _first(s.locked_crossings), "crossings": cross(s.locked_crossings)},
        "free_casters": {
            "critical_speed_m_s": _first(s.free_crossings),
            "stable_at_all_speeds": s.free_stable_at_all_speeds,
            "unstable_at_all_speeds": s.free_unstable_at_all_speeds,
            "crossings": cross(s.free_crossings),
            "divergence": [{k: r.to_dict()[k] for k in ("speed_m_s", "rate_1_s", "time_to_double_s")}
                           for r in s.divergence],
        },
        "search_range_m_s": list(s.search_range),
        "omitted_effects": list(omitted_effects(s.chair)),
        "simulator_linearisation": list(checks or []),
    }
    if intervals is not None:
        out = d
        for row, (lo, hi) in zip(out["free_casters"]["divergence"], intervals.rate, strict=True):
            row["rate_1_s_interval"] = [lo, hi]
        for key, trip in (("zero_width", intervals.zero_width_critical), ("locked_casters", intervals.locked_critical),
                          ("free_casters", intervals.free_critical)):
            out[key]["critical_speed_m_s_interval"] = _pair(trip[0], trip[1])
            out[key]["critical_speed_exists_fraction"] = trip[2]
        for key, (above, below) in (("locked_casters", intervals.locked_beyond),
                                    ("free_casters", intervals.free_beyond)):
            out[key]["stable_at_all_speeds_fraction"] = above
            out[key]["unstable_at_the_slowest_speed_fraction"] = below
        out["uncertainty"] = intervals_dict(intervals)
        if nonlinear is not None:
            out["uncertainty"].update(nonlinear_intervals_dict(nonlinear))
    return d


def _fmt(x, unit: str = "", digits: int = 3) -> str:
    if x is None:
        return "none in range"
    return f"{x:.{digits}g}{(' ' + unit) if unit else ''}"


def interpretation(s: StabilitySummary) -> str:
    """One sentence a wheelchair engineer can act on.

    States the speed range over which free casters are stable or unstable
    (with the time for a heading error to double when unstable) and what
    locking the casters would give, within the searched speed range.

    Parameters
    ----------
    s : StabilitySummary
        The linear summary (:func:`stability.linear.analyse`).

    Returns
    -------
    str
        The sentence, ending with a full stop.
    """
    lo, hi = s.search_range
    c = s.chair.name
    slow = next((r for r in s.divergence if r.rate > 0), None)
    if s.free_unstable_at_all_speeds:
        first = slow or s.divergence[0]
        msg = (f"With free casters {c} is directionally unstable at every speed from {lo:g} to {hi:g} m/s "
               f"(at {first.speed:g} m/s a heading error doubles every "
               f"{_fmt(first.time_to_double, 's')}), so the user must steer continually")
    elif s.free_stable_at_all_speeds:
        msg = f"With free casters {c} is directionally stable at every speed from {lo:g} to {hi:g} m/s"
    else:
        v = _first(s.free_crossings, "destabilising")
        where = [round(x.speed, 3) for x in s.free_crossings]
        msg = (f"With free casters {c} is stable below {_fmt(v, 'm/s')} and unstable above it"
               if v is not None else f"With free casters {c} changes stability at {where} m/s")
    locked = _first(s.locked_crossings, "destabilising")
    msg += (f"; with the casters locked it would be stable up to {_fmt(locked, 'm/s')}"
            if locked is not None else "; with the casters locked it would be stable in the whole range")
    return msg + "."


def format_summary(s: StabilitySummary, checks: list | None = None, intervals: LinearIntervals | None = None,
                   nonlinear: NonlinearIntervals | None = None) -> str:
    """The summary as readable text.

    Parameters
    ----------
    s : StabilitySummary
    checks : list, optional
        Rows of :func:`simulator_checks`.
    intervals : LinearIntervals, optional
        Intervals over the parameter uncertainty, printed after the point values.
    nonlinear : NonlinearIntervals, optional
        Intervals of the critical impulse and the equal-instability speed, printed after them.

    Returns
    -------
    str
    """
    d = summary_dict(s, checks)
    lines = [
        f"Chair: {s.chair.name} ({s.chair.caster_position} casters; main tire {s.chair.main_tire}, "
        f"caster tire {s.chair.caster_tire})   model: {s.model}",
        "",
        f"{'':28s}{'main wheel':>14s}{'caster':>14s}",
        f"{'static load (N)':28s}{d['static_load_N']['main']:14.1f}{d['static_load_N']['caster']:14.1f}",
        f"{'cornering stiffness (N/deg)':28s}{d['cornering_stiffness_N_per_deg']['main']:14.2f}"
        f"{d['cornering_stiffness_N_per_deg']['caster']:14.2f}",
        "",
        "Critical speeds (m/s)",
        f"  zero-width model, locked casters (eq 5-15): {_fmt(s.zero_width.critical_speed, digits=4)}"
        f"   [understeer coefficient k_us = {s.zero_width.understeer_coefficient:+.4f} rad, eq 5-16]",
        f"  full-width model, locked casters:           {_fmt(_first(s.locked_crossings), digits=4)}",
        f"  full-width model, free casters:             {_fmt(_first(s.free_crossings), digits=4)}"
        + ("   (unstable at all speeds searched)" if s.free_unstable_at_all_speeds else "")
        + ("   (stable at all speeds searched)" if s.free_stable_at_all_speeds else ""),
        f"  searched {s.search_range[0]:g} to {s.search_range[1]:g} m/s",
        "",
        "Least stable mode, free casters",
        f"  {'speed (m/s)':>12s}{'rate (1/s)':>12s}{'doubling (s)':>14s}{'freq (rad/s)':>14s}",
    ]
    for r in s.divergence:
        t2 = "-" if r.time_to_double is None else f"{r.time_to_double:.3g}"
        lines.append(f"  {r.speed:12.3g}{r.rate:12.4f}{t2:>14s}{r.frequency:14.3g}")
    if checks:
        lines += ["", f"The linear model leaves out {', '.join(d['omitted_effects'])}. With them, the simulator's "
                  "own linearisation (stability.simulate.linearise) gives:",
                  f"  {'speed (m/s)':>12s}{'linear (1/s)':>14s}{'simulator (1/s)':>17s}{'difference':>12s}"]
        for r in checks:
            lines.append(f"  {r['speed_m_s']:12.3g}{r['rate_linear_1_s']:14.4f}{r['rate_simulator_1_s']:17.4f}"
                         f"{100 * r['relative_difference']:+11.1f}%")
    if intervals is not None:
        lines += _interval_lines(intervals)
    if nonlinear is not None:
        lines += _nonlinear_lines(nonlinear)
    lines += ["", interpretation(s)]
    return "\n".join(lines)


def _interval_lines(iv: LinearIntervals) -> list[str]:
    pct = f"{100 * iv.level:g} %"

    def crit(name: str, trip: tuple[float, float, float], beyond: tuple[float, float] = (0.0, 0.0)) -> str:
        lo, hi, frac = trip
        # the draws without a crossing in the searched range, by which end they lie beyond
        parts = [(w, f) for w, f in zip(("stable at every speed searched", "unstable at the slowest speed searched"),
                                        beyond, strict=True) if f > 0]
        rest = "; ".join(f"{w} in {100 * f:.0f} %" for w, f in parts)
        if frac == 0:
            if len(parts) == 1:
                return f"  {name:42s} none in range: {parts[0][0]} in every draw"
            return f"  {name:42s} none in range in every draw" + (f" ({rest})" if rest else "")
        rng = f"{lo:.4g} to {hi:.4g} m/s"
        return f"  {name:42s} {rng}" + ("" if frac == 1 else f"   (exists in {100 * frac:.0f} % of draws"
                                         + (f"; {rest})" if rest else ")"))

    out = ["", f"With the parameter uncertainty ({pct} intervals, {iv.samples} Monte Carlo draws, seed {iv.seed}):",
           crit("zero-width critical speed, locked casters", iv.zero_width_critical),
           crit("full-width critical speed, locked casters", iv.locked_critical, iv.locked_beyond),
           crit("full-width critical speed, free casters", iv.free_critical, iv.free_beyond),
           f"  {'speed (m/s)':>12s}{'rate interval (1/s)':>24s}{'delta method (1/s)':>24s}"]
    for u, (lo, hi), (dlo, dhi) in zip(iv.speeds, iv.rate, iv.rate_delta, strict=True):
        out.append(f"  {u:12.3g}{f'{lo:.4f} to {hi:.4f}':>24s}{f'{dlo:.4f} to {dhi:.4f}':>24s}")
    top = [f"{n} ({100 * sh:.0f} %)" for n, sh in iv.dominant_parameters[:3] if sh > 0.005]
    out.append("  the variance comes mostly from: " + (", ".join(top) if top else "no parameter (no spread)")
               + "; Coulomb pin friction has no linearisation and moves none of these")
    return out


def _nonlinear_lines(nl: NonlinearIntervals) -> list[str]:
    def one(name: str, m: Any) -> str:
        nominal = _fmt(m.nominal if math.isfinite(m.nominal) else None, m.unit)
        top = [f"{n} ({100 * sh:.0f} %)" for n, sh in m.shares[:3] if sh > 0.005]
        out = "none in any draw" if not m.finite_fraction > 0 else f"{m.low:.4g} to {m.high:.4g} {m.unit}"
        beyond = ", ".join(f"{k} {100 * f:.0f} %" for k, f in m.outside if f > 0)
        return (f"  {name:42s} {out}   (nominal {nominal}; from {', '.join(top) if top else 'no parameter'}"
                + (f"; no value: {beyond}" if beyond else "") + ")")

    k, e = nl.critical_impulse, nl.equal_instability
    out = ["", f"Nonlinear, with the same uncertainty ({100 * nl.level:g} %, {nl.samples} draws, seed {nl.seed}, "
               f"{nl.model} model; pin friction acts here):",
           one(f"critical impulse at {nl.speed:g} m/s", k)]
    if e is not None:
        out.append(one("equal-instability speed", e))
        out.append(f"  reference case {nl.reference}, push {nl.push}")
    return out
