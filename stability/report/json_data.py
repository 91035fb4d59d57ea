"""The report's numbers as JSON (``python -m stability.report --json``): page 1 and the summary page.

:func:`report_mapping` takes every number from :class:`~stability.report.compute.ReportData`, the same objects
the pages print (page 1: :mod:`.decision` and :mod:`.clinician`; the summary page: :mod:`.summary`), so the
JSON and the text cannot disagree (``tests/test_report.py`` checks the printed numbers against the JSON).
Keys follow :mod:`stability.schemas`; the schema is ``stability/schemas/report.json``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.advise.text import advice_mapping
from stability.report.clinician import CLINIC_SLOPE_DEG, clinician_text
from stability.report.compute import ReportData
from stability.report.decision import decision_paragraphs
from stability.report.quick import coarsened, coarsened_text
from stability.report.summary import best_changes, elasticity_floor, summary_text
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH

__all__ = ["report_mapping"]


def _num(x: Any) -> float | None:
    """A JSON number: finite floats as float, None / NaN / infinity as None."""
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _safe(x: Any) -> Any:
    """``x`` with numpy scalars made plain and non-finite floats made None (recursively)."""
    if isinstance(x, dict):
        return {k: _safe(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_safe(v) for v in x]
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (float, np.floating)):
        return _num(x)
    if isinstance(x, np.integer):
        return int(x)
    return x


def _decision(d: ReportData) -> dict[str, Any]:
    a = d.advice
    adv = advice_mapping(a)
    verdict = adv["verdict"]
    ci = a.verdict.critical_impulse_Ns.value
    rs = sorted(d.responses.responses, key=lambda r: r.speed)
    reference = None
    if d.reference_measures is not None and a.chair.name != REFERENCE_CHAIR:
        reference = {"chair": REFERENCE_CHAIR, "measures": d.reference_measures.to_mapping(),
                     "trail_m": d.reference_trail}
    recs = adv["recommendations"]
    for r, rec in zip(a.recommendations, recs, strict=True):      # the trail column of page 1's table
        rec["trail_m"] = r.candidate.fields.get("trail", a.chair.trail)
    handrim = None
    s = d.slope
    if s is not None and s.drive == "handrim":
        slopes = np.asarray(s.curve.cross_slopes_deg, float)
        k = int(np.argmin(np.abs(slopes - CLINIC_SLOPE_DEG)))
        if abs(slopes[k] - CLINIC_SLOPE_DEG) < 1e-9:
            handrim = {"cross_slope_deg": CLINIC_SLOPE_DEG, "speed_m_s": s.speed,
                       "force_difference_N": abs(float(s.drive_difference[k]))}
    return {
        "reference_speed_m_s": REFERENCE_SPEED,
        "push_force_N": THESIS_PUSH.force, "push_duration_s": THESIS_PUSH.duration,
        "verdict": verdict,
        "critical_push_force_N": None if ci is None else ci / THESIS_PUSH.duration,
        "trail_m": a.chair.trail,
        "recommendation": recs[0] if recs else None,
        "runner_up": recs[1] if len(recs) > 1 else None,
        "no_recommendation_reason": adv["no_recommendation_reason"],
        "reference_chair": reference,
        "use_speeds_m_s": list(a.speeds_m_s),
        "cross_slope_deg": a.cross_slope_deg,
        "limits": adv["limits"],
        "clinician": {
            "level_rad_s": d.responses.criterion.yaw_rate,
            "horizon_s": d.responses.criterion.duration,
            "speeds_m_s": [r.speed for r in rs],
            "time_to_level_s": [_num(r.time_to_level) for r in rs],
            "handrim": handrim,
        },
        "advisor_decision": adv["decision"],
        "paragraphs": decision_paragraphs(d) + [clinician_text(d)],
    }


def _rate(summary: Any) -> float | None:
    row = next((r for r in summary.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    return None if row is None else _num(row.rate)


def _uncertainty(d: ReportData) -> dict[str, Any] | None:
    u = d.uncertainty
    if u is None:
        return None
    lo, hi = u.rate_at(REFERENCE_SPEED)
    dom = u.dominant
    out: dict[str, Any] = {"source": u.spec.source, "samples": int(u.spec.samples), "seed": int(u.spec.seed),
                           "level": u.intervals.level, "growth_rate_1_s": [lo, hi],
                           "growth_rate_dominant": None if dom is None else dom[0],
                           "growth_rate_dominant_share": None if dom is None else dom[1], "nonlinear": None}
    nl = u.nonlinear
    if nl is not None:
        def interval(k: Any) -> dict[str, Any] | None:
            if k is None:
                return None
            top = k.dominant
            return {"nominal": k.nominal, "interval": [k.low, k.high], "finite_fraction": k.finite_fraction,
                    "dominant": None if top is None else top[0], "text": k.describe()}

        out["nonlinear"] = {"samples": nl.samples, "level": nl.level,
                            "critical_impulse_Ns": interval(nl.critical_impulse),
                            "equal_instability_speed_m_s": interval(nl.equal_instability)}
    return out


def _slope(d: ReportData) -> dict[str, Any] | None:
    sl = d.slope
    if sl is None:
        return None
    return {"speed_m_s": sl.speed, "holding_moment_N_m_per_deg": sl.per_degree,
            "closed_form_N_m_per_deg": sl.closed_form_per_degree, "mass_times_cg_offset_kg_m": sl.m_x,
            "uncorrected_turn": None if sl.path is None else sl.path.turn,
            "refused_cross_slopes_deg": [p for p, _ in sl.refused]}


def _shimmy(d: ReportData) -> dict[str, Any] | None:
    sh = d.shimmy
    if sh is None:
        return None
    crit = [x[2] for x in sh.corners]
    return {"speed_m_s": sh.speed, "critical_trail_m": sh.critical,
            "critical_trail_range_m": [min(crit), max(crit)], "chair_trail_m": sh.chart.chair_trail,
            "chair_model_critical_trail_m": sh.chair_model_critical}


def _critical_speeds(d: ReportData) -> dict[str, Any]:
    """The linear critical speeds of the report's model (the "linear stability: critical speeds" page)."""
    s = d.summary

    def rows(cs: list) -> list[dict[str, Any]]:
        return [{"speed_m_s": c.speed, "kind": c.kind, "direction": c.direction} for c in cs]

    return {"model": s.model, "search_range_m_s": list(s.search_range),
            "zero_width_locked_m_s": s.zero_width.critical_speed,
            "zero_width_understeer_coefficient_rad": s.zero_width.understeer_coefficient,
            "locked_casters": rows(s.locked_crossings), "free_casters": rows(s.free_crossings)}


def _summary(d: ReportData) -> dict[str, Any]:
    cs = d.chair_speed
    floor = elasticity_floor(d)
    return {
        "growth_rate": [{"model": d.summary.model, "speed_m_s": REFERENCE_SPEED, "growth_rate_1_s": _rate(d.summary)},
                        {"model": d.summary_other.model, "speed_m_s": REFERENCE_SPEED,
                         "growth_rate_1_s": _rate(d.summary_other)}],
        "free_casters_unstable_at_all_speeds": bool(d.summary.free_unstable_at_all_speeds),
        "critical_speeds": _critical_speeds(d),
        "free_casters_stable_at_all_speeds": bool(d.summary.free_stable_at_all_speeds),
        "equal_instability": {"chair": d.chair.name, "speed_m_s": cs.speed, "status": cs.status,
                              "bracket_m_s": list(cs.bracket), "text": cs.describe()},
        "equal_instability_range": None if d.intervals is None else d.intervals.to_dict(),
        "critical_impulses": [x.to_dict() for x in d.impulses if x is not None],
        "reference_time_s": d.thesis.reference_time,
        "reference_level_rad_s": d.thesis.criterion.yaw_rate,
        "best_changes": [{"parameter": ch.label, "value": ch.value, "direction": ch.direction,
                          "elasticity": ch.elasticity, "growth_rate_elasticity": ch.growth,
                          "impulse_change_pct": ch.percent} for ch in best_changes(d)],
        "elasticity_floor": floor,
        "slope": _slope(d),
        "shimmy": _shimmy(d),
        "uncertainty": _uncertainty(d),
        "text": summary_text(d),
    }


def report_mapping(d: ReportData) -> dict[str, Any]:
    """Page 1 (the decision) and the summary page's numbers, JSON-ready (non-finite numbers as null).

    Parameters
    ----------
    d : ReportData
        The report's data (:func:`stability.report.compute`).

    Returns
    -------
    dict
        ``quick`` and ``coarsened`` (what ``--quick`` coarsens: the values marked on the pages),
        ``decision`` (page 1: the advisor's verdict and recommendation with ranges, costs and
        constraints, the reference chair, the clinician's times), ``summary`` (growth rates, the
        equal-instability speed and its range, critical impulses, the reference time, what helps most,
        slope, shimmy, uncertainty intervals) and each page's ``text``; ``human_limit``: the user's limits
        (``--reaction-time`` or the chair file's ``[user]``; null without a driver), as
        ``python -m stability.critical_speed --json`` gives them.
    """
    return _safe({"quick": bool(d.settings.quick), "coarsened": coarsened(d.settings),
                  "coarsened_text": coarsened_text(d.settings) or None,
                  "decision": _decision(d), "summary": _summary(d),
                  "human_limit": None if d.human is None or d.driver is None else {
                      **d.human.to_mapping(), "driver": d.driver.to_mapping()}})
