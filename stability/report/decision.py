"""Page 1 of the report: the decision, from the advisor (:func:`stability.advise.advise`).

The words are the advisor's :class:`~stability.advise.decision.Decision` verbatim (the sentences ``python -m
stability.advise`` prints and its JSON carries under ``decision.paragraphs``); the table takes every number from
the advisor's :class:`~stability.advise.Advice` (the chair as it is, the recommended change's predicted values,
every tip direction and cost) and from the thesis's reference chair measured the same way.
"""

from __future__ import annotations

import math
from pathlib import Path

from stability.advise.decision import DIRECTION_WORDS, decide
from stability.advise.measures import EFFORT_WORDS, Measures
from stability.report.behaviour import better_word
from stability.report.compute import ReportData
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.shimmy.band import margin_cell
from stability.study import censored

__all__ = ["decision_paragraphs", "decision_rows", "decision_bars", "decision_beyond", "uncertainty_sentence"]

def uncertainty_sentence(d: ReportData) -> str | None:
    """The measured uncertainty's intervals, for page 1 when ``--uncertainty FILE`` is given (None otherwise).

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    str or None
    """
    u = d.uncertainty
    if u is None or u.nonlinear is None:
        return None
    nl = u.nonlinear
    parts = [f"critical impulse at {nl.speed:g} m/s {nl.critical_impulse.describe()}"]
    if nl.equal_instability is not None:
        eq = nl.equal_instability
        cross = ("" if not (eq.low < REFERENCE_SPEED < eq.high) else
                 f": it includes the reference {REFERENCE_SPEED:g} m/s, so within the measurement uncertainty the "
                 f"chair may be less stable than the {REFERENCE_CHAIR}")
        parts.append(f"equal-instability speed {eq.describe()}{cross}")
    dom = nl.critical_impulse.dominant
    drive = ("" if dom is None else
             f"; the parameter that drives it most is {dom[0]} ({100 * dom[1]:.0f} % of the variance)")
    return (f"MEASURED UNCERTAINTY (these intervals, not the table's, carry the measurement error). Over the "
            f"distributions of {Path(u.spec.source).name} ({nl.samples} draws, "
            f"{100 * nl.level:.0f} % intervals): " + ", ".join(parts) + drive + ".")


def decision_paragraphs(d: ReportData) -> list[str]:
    """Page 1's words: the advisor's decision (:meth:`stability.advise.decision.Decision.paragraphs`), verbatim,
    and the measured uncertainty's intervals when an uncertainty file is given.

    Parameters
    ----------
    d : ReportData
        With ``advice`` computed.

    Returns
    -------
    list of str
    """
    out = decide(d.advice).paragraphs()
    extra = uncertainty_sentence(d)
    return out + ([extra] if extra else [])


def _cells(m: Measures, trail: float) -> list[str]:
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    sm = m.shimmy_margin_m

    def rng(x, digits=3, bound=False) -> str:     # no range for a bound or a range that rounds to one value
        if bound or x.low is None or x.high is None or f"{x.low:.{digits}g}" == f"{x.high:.{digits}g}":
            return ""
        return f" ({x.low:.{digits}g}-{x.high:.{digits}g})"

    effort = m.cross_slope_effort
    ci_bound = m.critical_impulse_status == "never"
    ei_bound = m.equal_instability_status in ("above", "below")
    return ([("> " if ci_bound else "") + f"{ci.value:.3g}{rng(ci, bound=ci_bound)}",
             {"above": "> ", "below": "< "}.get(m.equal_instability_status, "")
             + f"{ei.value:.3g}{rng(ei, bound=ei_bound)}"]
            + [f"{m.tip_angles_deg[k]:.1f}" if k in m.tip_angles_deg else "-" for k in DIRECTION_WORDS]
            + ["none found" if sm.value is None else margin_cell(sm.value, "+.1f"),
               f"{m.turning_effort_N_m:.3g}",
               "-" if effort is None else f"{abs(effort):.3g}",
               f"{m.growth_rate_1_s:.3g}",
               f"{100 * trail:.3g}"])


def decision_rows(d: ReportData) -> tuple[list[str], list[list[str]]]:
    """Header and rows of page 1's table: this chair, the recommended chair, the thesis's reference chair.

    Every tip direction, the shimmy margin, the turning effort and the cross-slope drive difference are rows, so
    the table shows before -> after of everything the change costs; with a user (the advice's driver) the speed
    that user can hold is the last row.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    (list of str, list of list of str)
    """
    a = d.advice
    cols = [("this chair", a.verdict, a.chair.trail)]
    if a.recommendations and a.recommendations[0].candidate.changes:
        c = a.recommendations[0].candidate
        cols.append(("recommended", c.measures, c.fields.get("trail", a.chair.trail)))
    if d.reference_measures is not None and a.chair.name != REFERENCE_CHAIR:
        cols.append((REFERENCE_CHAIR, d.reference_measures, d.reference_trail))
    words, unit = EFFORT_WORDS[a.verdict.drive]
    labels = ([f"critical impulse, {REFERENCE_SPEED:g} m/s (N s)", "equal-instability speed (m/s)"]
              + [f"tip {w.replace('its ', '')} (deg)" for w in DIRECTION_WORDS.values()]
              + ["shimmy margin (cm)", "turning pin friction (N m)",
                 f"{words.split()[0]} diff., {a.cross_slope_deg:g} deg slope ({unit})",
                 "linear growth rate (1/s)", "caster trail (cm)"])
    cells = [_cells(m, t) for _, m, t in cols]
    if len(cols) > 1 and cols[1][0] == "recommended":       # the change's direction on every measure, in words
        before, after = _values(cols[0][1], cols[0][2]), _values(cols[1][1], cols[1][2])
        for i, (a, b, higher) in enumerate(zip(before, after, _HIGHER_IS_BETTER, strict=True)):
            if a is not None and b is not None and higher is not None:
                word = better_word(b - a, higher, tolerance=1e-3 * max(abs(a), abs(b), 1e-12))
                cells[1][i] += "" if word == "no change" else f" ({word})"
    rows = [[lab] + [c[i] for c in cells] for i, lab in enumerate(labels)]
    driver = d.advice.driver            # (``a`` is reused by the loop above)
    if driver is not None:              # the user's limit, the advisor's constraint on every change
        rows.append(user_row(driver.reaction_time_s, [m for _, m, _ in cols],
                             len(cols) > 1 and cols[1][0] == "recommended"))
    # a tip direction no column has (a chair's four, a wheel layout's four) is no row: it could only print dashes
    have = {k for _, m, _ in cols for k, v in m.tip_angles_deg.items() if v is not None}
    tips = {2 + j: k for j, k in enumerate(DIRECTION_WORDS)}
    rows = [r for i, r in enumerate(rows) if i not in tips or tips[i] in have]
    return ["measure (range)"] + [n for n, _, _ in cols], rows


def user_row(tau: float, measures: list, recommended: bool) -> list[str]:
    """Page 1's row of the speed a user with delay ``tau`` can hold (the divergence rule), one cell per column.

    Parameters
    ----------
    tau : float
        The user's delay, s.
    measures : list of Measures
        The table's columns: this chair, then the recommended chair (``recommended``) and/or the reference chair.
    recommended : bool
        The second column is the recommended chair: its cell says whether the change makes the speed better or
        worse (as every other row does).

    Returns
    -------
    list of str
        The label and the cells.
    """
    cells = [_user_cell(m) for m in measures]
    if recommended and measures[0].human_speed_m_s is not None and measures[1].human_speed_m_s is not None:
        # a bound ranks as the set of speeds it allows (stability.study.censored, as the comparison page ranks):
        # "> 6" beats every speed found, two like bounds are undecided, found speeds within the table's 1e-3 equal
        word = censored.compare(measures[1].human_speed_m_s, measures[1].human_side, measures[0].human_speed_m_s,
                                measures[0].human_side, True, rel_tol=1e-3)
        cells[1] += f" ({word})" if word in ("better", "worse") else ""
    return [f"speed a user {tau:g} s late holds (m/s, divergence rule)"] + cells


def _user_cell(m: Measures) -> str:
    """The divergence rule's speed as a value, a bound as a bound (``"> 6"``), ``"-"`` where not computed."""
    if m.human_speed_m_s is None:
        return "-"
    return censored.describe(m.human_speed_m_s, m.human_side, digits=3)


#: Per row of :func:`decision_rows`: whether a higher value is better (None: neither, e.g. the trail itself).
_HIGHER_IS_BETTER: tuple = ((True, True) + (True,) * len(DIRECTION_WORDS) + (True, False, False, False, None))


def _finite(x: float | None) -> float | None:
    return x if x is not None and math.isfinite(x) else None


def _values(m: Measures, trail: float) -> list:
    """The numbers behind :func:`_cells` (None where a row has none, or where the value is a bound)."""
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    effort = m.cross_slope_effort
    return ([None if m.critical_impulse_status == "never" else ci.value,
             ei.value if m.equal_instability_status == "found" else None]
            + [m.tip_angles_deg.get(k) for k in DIRECTION_WORDS]
            + [_finite(m.shimmy_margin_m.value), m.turning_effort_N_m, None if effort is None else abs(effort),
               m.growth_rate_1_s, trail])


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
    if a.recommendations and a.recommendations[0].candidate.changes:
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
    if a.recommendations and a.recommendations[0].candidate.changes:
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
