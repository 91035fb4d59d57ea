"""The advice in plain language (designer and clinician) and as JSON."""

from __future__ import annotations

import math

import numpy as np

from stability.advise.advisor import Advice, Candidate
from stability.advise.decision import Decision, decide, kmh
from stability.advise.limits import limit_words
from stability.advise.measures import Interval, Measures
from stability.advise.subject import is_layout, levers_of
from stability.settings.defaults import MAX_IMPULSE
from stability.settings.reference import REFERENCE_SPEED
from stability.shimmy.band import margin_cell
from stability.study.censored import describe, range_words, side_of

__all__ = ["advice_text", "advice_mapping", "kmh"]

def _iv(x, unit: str, digits: int = 3, status: str = "found") -> str:
    value = {"above": "> ", "never": "> ", "below": "< "}.get(status, "") + f"{x.value:.{digits}g}"
    return f"{value} {unit}" + range_words(x.low, x.high, unit, digits=digits)


def _impulse_cell(j: Interval, bounded: bool) -> str:
    """The levers table's critical-impulse cell: its interval, an end at the search's largest push (never reached:
    a bound) as ``>40``, a range both of whose ends are that bound as one ``> 40``."""
    def end(x: float) -> str:
        return f">{MAX_IMPULSE:g}" if x >= MAX_IMPULSE else f"{x:.2f}"

    lo, hi = float(j.low if j.low is not None else math.nan), float(j.high if j.high is not None else math.nan)
    if bounded:
        return f"{end(lo):>6} (x0.5)"
    if lo >= MAX_IMPULSE:
        return f"{'> ' + format(MAX_IMPULSE, 'g'):>13}"
    return f"{lo:6.2f}-{hi:<6.2f}" if hi < MAX_IMPULSE else f"{lo:6.2f} to {end(hi):<3}"


def _row(c: Candidate, base: Measures, broken: set) -> str:
    m = c.measures
    sm = m.shimmy_margin_m.value
    hr = m.cross_slope_effort
    v = m.equal_instability_speed_m_s
    ei = describe((v.low if c.bounded else v.value) or math.nan, side_of(m.equal_instability_status), digits=3)
    unmet = [k.name for k in c.constraints if not k.met]
    breaks = [n for n in unmet if n not in broken]
    still = [n for n in unmet if n in broken]
    flags = ("  breaks " + ", ".join(breaks) if breaks else "") + \
        ("  does not fix " + ", ".join(still) if still else "")
    impulse = _impulse_cell(m.critical_impulse_Ns, c.bounded)
    gain = f"<={c.gain * 100:+4.0f} %" if c.bounded else f"{c.gain * 100:+6.1f} %"
    return (f"  {c.changes[0].label:<72} {impulse} "
            f"{ei:>6} {m.static_stability_deg.value:6.1f} "
            f"{'none' if sm is None else margin_cell(sm):>7} {m.turning_effort_N_m:6.3f} "
            f"{'-' if hr is None else format(abs(hr), '.3g'):>5} {m.growth_rate_1_s:5.2f} {gain}"
            + flags
            + ("  (impulse and speed disagree)" if not c.bounded and min(c.gains.values()) < 0 < max(c.gains.values())
               else "")
            + ("  (linear rate worse, nonlinear better: see the note on linear vs nonlinear)"
               if c.gain > 0 and m.growth_rate_1_s > base.growth_rate_1_s + 1e-9 else ""))


def _sets(a: Advice, changes: tuple) -> str:
    """The changes as ``--set`` options, or for a layout as the fields to write into its ``[[wheel]]`` file."""
    if is_layout(a.chair):
        return "in the [[wheel]] file: " + ", ".join(x for ch in changes for x in ch.assignments)
    return " ".join(f"--set {x}" for ch in changes for x in ch.assignments)


def _blocked(a: Advice, d: Decision) -> list[str]:
    if not d.blocked:
        return []
    out = ["", "BLOCKED BY A LIMIT (better than the recommendation, or fixing what the chair breaks)"]
    for b, sentence in zip(a.blocked, d.blocked, strict=True):
        out += [f"  {sentence}", f"    ({_sets(a, b.candidate.changes)}); allowed by: {b.allow}"]
    return out


def _recommendation(a: Advice, d: Decision) -> list[str]:
    out = ["", "RECOMMENDATION", f"  {d.recommendation}"]
    first = a.recommendations[0].candidate if a.recommendations else None
    if first is not None and first.changes:
        out.append(f"  ({_sets(a, first.changes)})")
    if not a.recommendations:
        return out + ["  limits:"] + [f"    {c.text()}" for c in d.costs]
    base = a.verdict
    for r in a.recommendations:
        c = r.candidate
        m = c.measures
        if r.rank > 1:
            out += ["", "RUNNER-UP", f"  {d.runner_up}"]
            if c.changes:
                out.append(f"  ({_sets(a, c.changes)})")
        if c.changes:
            out += [f"  critical impulse at {REFERENCE_SPEED:g} m/s: "
                    f"{_iv(base.critical_impulse_Ns, 'N s', status=base.critical_impulse_status)} -> "
                    f"{_iv(m.critical_impulse_Ns, 'N s', status=m.critical_impulse_status)}",
                    f"  equal-instability speed: "
                    f"{_iv(base.equal_instability_speed_m_s, 'm/s', status=base.equal_instability_status)} -> "
                    f"{_iv(m.equal_instability_speed_m_s, 'm/s', status=m.equal_instability_status)}"]
        for b in r.built_from:
            out.append(f"    alone, {b.label}: {b.gain * 100:+.0f} % (robust)")
        if r.rank == 1:
            out.append("  what it costs:" if c.changes else "  limits:")
            out += [f"    {x.text()}" for x in d.costs]
            out += [f"  why: {n}" for n in d.why]
        else:
            out.append("  limits: " + "; ".join(f"{limit_words(k.name)} {'met' if k.met else 'NOT met'}"
                                                for k in c.constraints))
    return out


def advice_text(a: Advice) -> str:
    """The advice as text: verdict, levers table, recommendation and what it costs.

    Parameters
    ----------
    a : Advice

    Returns
    -------
    str
    """
    d = decide(a)
    lines = [f"{a.chair.name}: advice for use at {kmh(a.speeds_m_s[0])} to {kmh(a.speeds_m_s[-1])}", "", "VERDICT"]
    lines += [f"  {x}" for x in d.verdict + d.details]
    lines += ["", "LEVERS (what each change buys and costs; robust gain = the smaller gain of the low ends of the "
              "critical-impulse and equal-instability intervals)",
              f"  {'change':<72} {'impulse N s':>13} {'EI m/s':>6} {'tip':>6} {'shimmy':>7} {'pin':>6} {'rim':>5} "
              f"{'lin':>5} {'gain':>8}",
              f"  {'':<72} {'(low-high)':>13} {'':>6} {'deg':>6} {'cm':>7} {'N m':>6} {'N':>5} {'1/s':>5}"]
    own = {k.name for k in a.own_constraints if not k.met}
    for name in levers_of(a.chair):
        lines += [_row(c, a.verdict, own) for c in a.candidates if c.changes[0].lever == name]
    for ch, why in a.refused:
        lines.append(f"  {ch.label:<72} refused: {why}")
    bounded = sum(c.bounded for c in a.candidates + a.combinations)
    if bounded:
        lines.append(f"  (x0.5): {bounded} change(s) measured at x0.5 pin friction only (impulse and EI columns); "
                     "these values already put them below the changes chosen (an interval's low end is never above "
                     "any of its variants), so their intervals were not computed and their gain is an upper bound "
                     "(<=)")
    if a.pairs_screened:
        lines.append(f"  pairs of two levers: {a.pairs_screened} checked on the limits in the order of their predicted "
                     f"gain, {a.pairs_measured} measured "
                     "(the best predicted that meet every limit)")
    lines += _blocked(a, d)
    lines += _recommendation(a, d)
    lines += ["", f"Limits: static stability >= {a.min_tip_deg:.1f} deg ({a.min_tip_source}); the others as listed. "
              "Speeds are also in km/h; a push in N s is force x time."]
    if is_layout(a.chair):
        lines.append("Wheel layout: caster wheels are numbered front to back as in the [[wheel]] file; the "
                     "cross-slope drive difference from the layout's slope statics and the driver's limit from its "
                     "linear model, in the direction of travel.")
    return "\n".join(lines)


def advice_mapping(a: Advice) -> dict:
    """JSON-ready advice: ``verdict``, ``levers``, ``recommendations`` (docs/advise.md).

    Parameters
    ----------
    a : Advice

    Returns
    -------
    dict
    """
    def finite(x):
        return None if x is None or (isinstance(x, float) and not math.isfinite(x)) else x

    levers = []
    for name, (desc, _) in levers_of(a.chair).items():
        cs = [c for c in a.candidates if c.changes[0].lever == name]
        levers.append({
            "name": name, "description": desc,
            "values": [{"label": c.label, "change": c.fields} for c in cs],
            "critical_impulse_Ns": [c.measures.critical_impulse_Ns.to_mapping() for c in cs],
            "equal_instability_speed_m_s": [c.measures.equal_instability_speed_m_s.to_mapping() for c in cs],
            "shimmy_margin_m": [c.measures.shimmy_margin_m.to_mapping() for c in cs],
            "static_stability_deg": [c.measures.static_stability_deg.to_mapping() for c in cs],
            "turning_effort_N_m": [c.measures.turning_effort_N_m for c in cs],
            a.verdict.effort_key: [c.measures.cross_slope_effort for c in cs],
            "robust_gain": [finite(c.gain) for c in cs],
            "intervals_computed": [not c.bounded for c in cs],
            "constraints_met": [c.feasible for c in cs],
            "refused": [{"label": ch.label, "change": ch.to_mapping(), "reason": why}
                        for ch, why in a.refused if ch.lever == name],
        })
    verdict = a.verdict.to_mapping()
    verdict["time_to_correct_s"] = [finite(t) for t in a.time_to_correct_s]
    verdict["time_to_correct_speeds_m_s"] = list(a.speeds_m_s)
    d = decide(a)
    verdict["text"] = "\n".join(d.verdict + d.details)
    return _json_safe({"verdict": verdict, "decision": d.to_mapping(), "levers": levers,
                       "recommendations": [r.to_mapping() for r in a.recommendations],
                       "blocked": [b.to_mapping() for b in a.blocked],
                       "shimmy_hold": None if a.shimmy_hold is None else a.shimmy_hold.to_mapping(),
                       "pairs_screened": a.pairs_screened, "pairs_measured": a.pairs_measured,
                       "intervals_computed": a.intervals_computed,
                       "no_recommendation_reason": a.reason or None,
                       "limits": {"min_tip_deg": a.min_tip_deg, "min_tip_source": a.min_tip_source},
                       "non_finite_as": "null (an unbounded interval end, an undefined gain or an absent limit)",
                       "text": advice_text(a)})


def _json_safe(x):
    """``x`` with every non-finite float (and numpy scalar) made JSON-safe: inf and NaN become None."""
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_json_safe(v) for v in x]
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, np.bool_):
        return bool(x)
    return x
