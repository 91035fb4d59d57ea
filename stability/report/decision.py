"""Page 1 of the report: the decision, from the advisor (:func:`stability.advise.advise`).

The words and the table take every number from the advisor's :class:`~stability.advise.Advice` (the chair as
it is, the recommended change with its predicted values and what it costs) and from the thesis's reference
chair measured the same way, so page 1 says what ``python -m stability.advise`` says.
"""

from __future__ import annotations

import math

from stability.advise.measures import Measures
from stability.advise.text import kmh
from stability.report.compute import ReportData
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH

__all__ = ["decision_paragraphs", "decision_rows", "decision_bars", "decision_beyond"]

_WORDS = {"static_stability_deg": "tips over on a slope of", "shimmy_margin_m": "shimmy margin",
          "turning_effort_N_m": "pin friction to overcome when turning", "handrim_force_difference_N":
          "hand-rim force difference on a cross slope"}


def _range(x, unit: str, digits: int = 3) -> str:
    if x.low is None or x.high is None:
        return ""
    return f" (range {x.low:.{digits}g}-{x.high:.{digits}g} {unit})"


def _cost(name: str, value: float | None) -> str:
    if value is None:
        return f"{_WORDS.get(name, name)}: not computed"
    if name == "static_stability_deg":
        return f"tips over on a {value:.1f} deg slope"
    if name == "shimmy_margin_m":
        return f"trail {100 * value:+.1f} cm from the nearest shimmy boundary"
    if name == "turning_effort_N_m":
        return f"{value:.2g} N m of pin friction to overcome when turning"
    return f"{abs(value):.0f} N hand-rim force difference on a 2 deg cross slope"


def decision_paragraphs(d: ReportData) -> list[str]:
    """The decision in plain words: verdict, recommendation, what it costs.

    Parameters
    ----------
    d : ReportData
        With ``advice`` computed.

    Returns
    -------
    list of str
    """
    a = d.advice
    m = a.verdict
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    out = []
    if m.critical_impulse_status == "never":
        push = (f"At {kmh(REFERENCE_SPEED)}, a slow walk, not even the largest sideways shove tried "
                f"({ci.value:.2g} N s) spins the chair: it keeps its heading by itself.")
    else:
        push = (f"At {kmh(REFERENCE_SPEED)}, a slow walk, a sideways shove of {ci.value:.2g} N s "
                f"({ci.value / THESIS_PUSH.duration:.0f} N for a tenth of a second){_range(ci, 'N s', 2)} is enough "
                "to spin the chair "
                "unless the user steers.")
    where = {"found": f"at {kmh(ei.value or 0.0)}", "above": "only above 3 m/s (11 km/h)",
             "below": "already below 0.2 m/s"}[m.equal_instability_status]
    times = [f"{t:.2g} s at {3.6 * u:.2g} km/h" for u, t in zip(a.speeds_m_s, a.time_to_correct_s, strict=False)
             if t is not None]
    same = (f"It is the thesis's reference chair: the other chairs' equal-instability speeds are measured against "
            f"it at {kmh(REFERENCE_SPEED)}." if a.chair.name == REFERENCE_CHAIR else
            f"It is as unstable as the thesis's reference chair at walking pace {where}{_range(ei, 'm/s')}.")
    out.append(f"VERDICT. {push} {same} After the thesis's push ({THESIS_PUSH.force:g} N for "
               f"{THESIS_PUSH.duration:g} s) "
               "the user has " + (", ".join(times) if times else "more than 10 s at every use speed")
               + " before it turns at 1 rad/s.")
    if not a.recommendations:
        out.append(f"RECOMMENDATION. None: {a.reason}.")
        return out
    r = a.recommendations[0]
    c = r.candidate
    rm = c.measures
    if not c.changes:
        out.append("RECOMMENDATION. No change: none of the levers tried raises the low ends of both the critical "
                   "impulse and the equal-instability speed while meeting every constraint"
                   + (" (the chair already resists the largest push tried)." if m.critical_impulse_status == "never"
                      else "."))
        return out
    out.append(f"RECOMMENDATION. {c.label[0].upper() + c.label[1:]}. Judged on the low ends of the ranges it "
               f"raises the critical impulse by {100 * c.gains['critical_impulse']:+.0f} % and the "
               f"equal-instability speed by {100 * c.gains['equal_instability_speed']:+.0f} %: predicted "
               + (">" if rm.critical_impulse_status == "never" else "")
               + f"{rm.critical_impulse_Ns.value:.3g} N s{_range(rm.critical_impulse_Ns, 'N s')} and "
               + {"above": "> ", "below": "< "}.get(rm.equal_instability_status, "")
               + f"{kmh(rm.equal_instability_speed_m_s.value or 0.0)}.")
    costs = "; ".join(_cost(k.name, k.value) + ("" if k.met else " (limit NOT met)") for k in c.constraints)
    out.append("WHAT IT COSTS. " + costs[:1].upper() + costs[1:] + "."
               + (" The trail is shimmy-free only with the estimated pin stiffness and tire relaxation length: "
                  "measure both before building it." if rm.shimmy_straddles else ""))
    if len(a.recommendations) > 1:
        out.append(f"RUNNER-UP. {a.recommendations[1].candidate.label}, "
                   f"{100 * a.recommendations[1].candidate.gain:+.0f} % on the low ends.")
    return out


def _cells(m: Measures, trail: float) -> list[str]:
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    sm = m.shimmy_margin_m

    def rng(x, digits=3) -> str:
        return "" if x.low is None or x.high is None else f" ({x.low:.{digits}g}-{x.high:.{digits}g})"

    return [(">" if m.critical_impulse_status == "never" else "") + f"{ci.value:.3g}{rng(ci)}",
            {"above": "> ", "below": "< "}.get(m.equal_instability_status, "") + f"{ei.value:.3g}{rng(ei)}",
            f"{m.static_stability_deg.value:.1f}",
            "none found" if sm.value is None else f"{100 * sm.value:+.1f}",
            f"{m.growth_rate_1_s:.3g}",
            f"{100 * trail:.3g}"]


def decision_rows(d: ReportData) -> tuple[list[str], list[list[str]]]:
    """Header and rows of page 1's table: this chair, the recommended chair, the thesis's reference chair.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    (list of str, list of list of str)
    """
    a = d.advice
    cols = [("this chair", a.verdict, a.chair.trail)]
    if a.recommendations:
        c = a.recommendations[0].candidate
        cols.append(("recommended", c.measures, c.fields.get("trail", a.chair.trail)))
    if d.reference_measures is not None and a.chair.name != REFERENCE_CHAIR:
        cols.append((REFERENCE_CHAIR, d.reference_measures, d.reference_trail))
    labels = [f"critical impulse at {REFERENCE_SPEED:g} m/s (N s)", "equal-instability speed (m/s)",
              "static stability, smallest angle (deg)", "shimmy margin (cm)",
              "linear growth rate, no friction (1/s)", "caster trail (cm)"]
    cells = [_cells(m, t) for _, m, t in cols]
    rows = [[lab] + [c[i] for c in cells] for i, lab in enumerate(labels)]
    return ["measure (range)"] + [n for n, _, _ in cols], rows


def decision_beyond(d: ReportData) -> list[bool]:
    """For each bar of :func:`decision_bars`: whether its value is the bracket's end, the speed lying above it.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of bool
        One per bar, in :func:`decision_bars`'s order.
    """
    a = d.advice
    st = [a.verdict.equal_instability_status]
    if a.recommendations:
        st.append(a.recommendations[0].candidate.measures.equal_instability_status)
    if d.reference_measures is not None and a.chair.name != REFERENCE_CHAIR:
        st.append(d.reference_measures.equal_instability_status)
    return [s == "above" for s in st]


def decision_bars(d: ReportData) -> tuple[list[str], list[float], list[float], list[float]]:
    """Names, equal-instability speeds and their range ends (m/s) for page 1's figure.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    (names, values, lows, highs)
    """
    a = d.advice
    items = [("this chair", a.verdict)]
    if a.recommendations:
        items.append(("recommended", a.recommendations[0].candidate.measures))
    if d.reference_measures is not None and a.chair.name != REFERENCE_CHAIR:
        items.append((f"{REFERENCE_CHAIR} (thesis)", d.reference_measures))
    names = [n for n, _ in items]
    vals = [float(m.equal_instability_speed_m_s.value or math.nan) for _, m in items]
    lows = [float(m.equal_instability_speed_m_s.low if m.equal_instability_speed_m_s.low is not None else v)
            for (_, m), v in zip(items, vals, strict=True)]
    highs = [float(m.equal_instability_speed_m_s.high if m.equal_instability_speed_m_s.high is not None else v)
             for (_, m), v in zip(items, vals, strict=True)]
    return names, vals, lows, highs
