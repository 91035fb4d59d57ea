"""The advice in plain language (designer and clinician) and as JSON."""

from __future__ import annotations

import math

import numpy as np

from stability.advise.advisor import Advice, Candidate
from stability.advise.levers import LEVERS
from stability.advise.limits import shimmy_sentence
from stability.advise.measures import Measures
from stability.settings.reference import REFERENCE_SPEED, THESIS_PUSH
from stability.study.censored import describe, side_of

__all__ = ["advice_text", "advice_mapping", "kmh"]

_DIRECTION_WORDS = {"toward_main_wheels": "toward its main wheels", "toward_casters": "toward its casters",
                    "lateral_left": "over its left side", "lateral_right": "over its right side"}


def kmh(speed: float) -> str:
    """A speed in m/s and km/h.

    Parameters
    ----------
    speed : float
        m/s.

    Returns
    -------
    str
        ``"0.75 m/s (2.7 km/h)"``.
    """
    return f"{speed:.3g} m/s ({speed * 3.6:.2g} km/h)"


def _iv(x, unit: str, digits: int = 3, status: str = "found") -> str:
    lo = "?" if x.low is None else f"{x.low:.{digits}g}"
    hi = "?" if x.high is None else f"{x.high:.{digits}g}"
    value = {"above": "> ", "never": "> ", "below": "< "}.get(status, "") + f"{x.value:.{digits}g}"
    return f"{value} {unit} (range {lo}-{hi})"


def _verdict(a: Advice) -> list[str]:
    m = a.verdict
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    force = (ci.value or 0.0) / 0.1
    lines = [f"{a.chair.name}: advice for use at {kmh(a.speeds_m_s[0])} to {kmh(a.speeds_m_s[-1])}", "",
             "VERDICT"]
    if m.critical_impulse_status == "never":
        lines.append(f"  At {kmh(REFERENCE_SPEED)} not even a sideways push of {ci.value:.2g} N s at the seat (the "
                     "largest tried) turns the chair to 1 rad/s within 10 s: it keeps its heading by itself.")
    else:
        lines.append(f"  At {kmh(REFERENCE_SPEED)} a sideways nudge of {ci.value:.2g} N s at the seat "
                     f"(about {force:.0f} N for a tenth of a second; range {ci.low:.2g}-{ci.high:.2g} N s over pin "
                     "friction, model and simulator step) turns the chair until it spins at 1 rad/s (57 deg/s) "
                     "within 10 s unless the user steers.")
    times = [f"{t:.2g} s at {u:g} m/s" if t is not None else f"more than 10 s at {u:g} m/s"
             for u, t in zip(a.speeds_m_s, a.time_to_correct_s, strict=False)]
    if times:
        lines.append(f"  After the thesis's reference push ({THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s) "
                     f"the user has {', '.join(times)} to correct before it turns at 1 rad/s.")
    where = {"found": f"at {kmh(ei.value or 0.0)}", "above": "only above 3 m/s", "below": "already below 0.2 m/s"}[
        m.equal_instability_status]
    lo = "?" if ei.low is None else f"{ei.low:.3g}"
    hi = "?" if ei.high is None else f"{ei.high:.3g}"
    lines.append(f"  It is as unstable as the thesis's reference case (E&J Premier at 0.75 m/s) {where} "
                 f"(range {lo}-{hi} m/s over push size, pin friction, model and simulator step); faster than that it "
                 "gives the user less time than the reference case.")
    lines.append(f"  Caster shimmy: {shimmy_sentence(m, a.chair.trail, a.shimmy_hold)}.")
    worst = min(m.tip_angles_deg, key=lambda k: m.tip_angles_deg[k])
    lines.append(f"  Static stability: it tips {_DIRECTION_WORDS[worst]} on a {m.static_stability_deg.value:.1f} deg "
                 "slope (rigid chair, brakes locked, casters in their worst swivel position); "
                 + ", ".join(f"{_DIRECTION_WORDS[k].split(' ', 1)[1]} {v:.1f}" for k, v in m.tip_angles_deg.items())
                 + " deg.")
    lines.append(f"  Linear model (free, frictionless casters): the heading error grows at {m.growth_rate_1_s:.3g} 1/s "
                 f"at "
                 f"{REFERENCE_SPEED:g} m/s. It has no pin friction, so where it disagrees with the push and speed "
                 "measures above (which include the pins' Coulomb friction) those decide; the advice says where.")
    if m.cross_slope_effort is not None and a.cross_slope_deg:
        what = ("one hand rim must push {:.0f} N harder than the other" if m.drive == "handrim" else
                "one drive motor must give {:.2g} N m more torque than the other")
        lines.append(f"  On a {a.cross_slope_deg:g} deg cross slope at {REFERENCE_SPEED:g} m/s "
                     + what.format(abs(m.cross_slope_effort)) + " to hold the line.")
    return lines


def _row(c: Candidate, base: Measures, broken: set) -> str:
    m = c.measures
    sm = m.shimmy_margin_m.value
    hr = m.cross_slope_effort
    ei = describe(m.equal_instability_speed_m_s.value or math.nan, side_of(m.equal_instability_status), digits=3)
    unmet = [k.name for k in c.constraints if not k.met]
    breaks = [n for n in unmet if n not in broken]
    still = [n for n in unmet if n in broken]
    flags = ("  breaks " + ", ".join(breaks) if breaks else "") + \
        ("  does not fix " + ", ".join(still) if still else "")
    return (f"  {c.changes[0].label:<72} {m.critical_impulse_Ns.low:6.2f}-{m.critical_impulse_Ns.high:<6.2f} "
            f"{ei:>6} {m.static_stability_deg.value:6.1f} "
            f"{'none' if sm is None else format(sm * 100, '+.2f'):>7} {m.turning_effort_N_m:6.3f} "
            f"{'-' if hr is None else format(abs(hr), '.3g'):>5} {m.growth_rate_1_s:5.2f} {c.gain * 100:+6.1f} %"
            + flags
            + ("  (impulse and speed disagree)" if min(c.gains.values()) < 0 < max(c.gains.values()) else "")
            + ("  (linear rate worse, nonlinear better: see the note on linear vs nonlinear)"
               if c.gain > 0 and m.growth_rate_1_s > base.growth_rate_1_s + 1e-9 else ""))


def _blocked(a: Advice) -> list[str]:
    if not a.blocked:
        return []
    out = ["", "BLOCKED BY A LIMIT (better than the recommendation, or fixing what the chair breaks)"]
    for b in a.blocked:
        c = b.candidate
        what = ("fixes " + ", ".join(b.fixes) + " and " if b.fixes else "") + \
            (f"gains {c.gain * 100:.0f} %" if c.gain >= 0 else f"costs {-c.gain * 100:.0f} %")
        limits = "; ".join(f"{k.name} {k.value:.4g} against the limit {k.kind} {k.limit:.4g}" if k.value is not None
                           else f"{k.name} refused by the slope statics" for k in b.limits)
        out += [f"  {c.label}: {what} on the robust measures, but {limits}",
                f"    (--set {' --set '.join(x for ch in c.changes for x in ch.assignments)}); allowed by: {b.allow}"]
    return out


def _own_constraints(a: Advice) -> tuple:
    keep = [r.candidate for r in a.recommendations if not r.candidate.changes]
    if keep:
        return keep[0].constraints
    from stability.advise.limits import constraints as _constraints

    return _constraints(a.verdict, a.verdict, a.min_tip_deg, a.min_tip_source, a.cross_slope_deg)


def _recommendation(a: Advice) -> list[str]:
    if not a.recommendations:
        return ["", "RECOMMENDATION", "  None: the chair breaks a limit and no change of any lever, nor any pair of "
                "two levers, meets every limit" + (" (see BLOCKED above)" if a.blocked else "") + "."]
    out = []
    base = a.verdict
    for r in a.recommendations:
        c = r.candidate
        m = c.measures
        out += ["", "RECOMMENDATION" if r.rank == 1 else "RUNNER-UP",
                f"  {c.label}",
                f"  (--set {' --set '.join(x for ch in c.changes for x in ch.assignments)})" if c.changes else
                "  (the chair as it is)",
                f"  critical impulse at {REFERENCE_SPEED:g} m/s: "
                f"{_iv(base.critical_impulse_Ns, 'N s', status=base.critical_impulse_status)} -> "
                f"{_iv(m.critical_impulse_Ns, 'N s', status=m.critical_impulse_status)}",
                f"  equal-instability speed: "
                f"{_iv(base.equal_instability_speed_m_s, 'm/s', status=base.equal_instability_status)} -> "
                f"{_iv(m.equal_instability_speed_m_s, 'm/s', status=m.equal_instability_status)} "
                f"({m.equal_instability_speed_m_s.value * 3.6:.2g} km/h)",
                f"  judged on the low ends: {c.gains['critical_impulse'] * 100:+.0f} % critical impulse, "
                f"{c.gains['equal_instability_speed'] * 100:+.0f} % equal-instability speed"]
        for b in r.built_from:
            out.append(f"    alone, {b.label}: {b.gain * 100:+.0f} % (robust)")
        out.append("  what it costs:")
        for k in c.constraints:
            v = "refused by the slope statics" if k.value is None else f"{k.value:.4g}"
            out.append(f"    {k.name} = {v} (limit {k.kind} {k.limit:.4g}; {'met' if k.met else 'NOT met'}; {k.note})")
        out += [f"  note: {n}" for n in r.notes]
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
    lines = _verdict(a)
    lines += ["", "LEVERS (what each change buys and costs; robust gain = the smaller gain of the low ends of the "
              "critical-impulse and equal-instability intervals)",
              f"  {'change':<72} {'impulse N s':>13} {'EI m/s':>6} {'tip':>6} {'shimmy':>7} {'pin':>6} {'rim':>5} "
              f"{'lin':>5} {'gain':>8}",
              f"  {'':<72} {'(low-high)':>13} {'':>6} {'deg':>6} {'cm':>7} {'N m':>6} {'N':>5} {'1/s':>5}"]
    own = {k.name for k in _own_constraints(a) if not k.met}
    for name in LEVERS:
        lines += [_row(c, a.verdict, own) for c in a.candidates if c.changes[0].lever == name]
    for ch, why in a.refused:
        lines.append(f"  {ch.label:<72} refused: {why}")
    if a.pairs_screened:
        lines.append(f"  pairs of two levers: {a.pairs_screened} screened on the limits, {a.pairs_measured} measured "
                     "(the best predicted that meet every limit)")
    lines += _blocked(a)
    lines += _recommendation(a)
    lines += ["", f"Limits: static stability >= {a.min_tip_deg:.1f} deg ({a.min_tip_source}); the others as listed. "
              "Speeds are also in km/h; a push in N s is force x time."]
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
    for name, (desc, _) in LEVERS.items():
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
            "constraints_met": [c.feasible for c in cs],
            "refused": [{"label": ch.label, "change": ch.to_mapping(), "reason": why}
                        for ch, why in a.refused if ch.lever == name],
        })
    verdict = a.verdict.to_mapping()
    verdict["time_to_correct_s"] = [finite(t) for t in a.time_to_correct_s]
    verdict["time_to_correct_speeds_m_s"] = list(a.speeds_m_s)
    verdict["text"] = "\n".join(_verdict(a)[3:])
    return _json_safe({"verdict": verdict, "levers": levers,
                       "recommendations": [r.to_mapping() for r in a.recommendations],
                       "blocked": [b.to_mapping() for b in a.blocked],
                       "shimmy_hold": None if a.shimmy_hold is None else a.shimmy_hold.to_mapping(),
                       "pairs_screened": a.pairs_screened, "pairs_measured": a.pairs_measured,
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
