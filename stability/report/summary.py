"""Page 1 of the report: the chair, a verdict, key numbers with their ranges, what helps most, caveats.

Every number comes from :class:`~stability.report.compute.ReportData`; the
rules (which pages are dropped, how changes are ranked) are in docs/report.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import preset
from stability.chair.design import get_parameter
from stability.chair.power import drive_kind
from stability.report.compute import ReportData
from stability.report.quick import mark
from stability.report.sections import section_drops
from stability.settings.reference import CROSS_SLOPE_STUDY, REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.study import FRICTION_OVER_TRAIL, TRAIL_AT_FIXED_GROUP

__all__ = ["Change", "best_changes", "elasticity_floor", "interval_text", "dropped_pages", "dropped_text",
           "model_gap", "push_text", "steady_turns", "summary_text"]


@dataclass(frozen=True)
class Change:
    """One parameter change ranked by its elasticity (:func:`stability.study.elasticities`).

    Attributes
    ----------
    label : str
        The parameter (M_f/l is one group).
    value : str
        The chair's own value, with its unit.
    direction : str
        ``"raise"`` or ``"lower"``: the way that raises the critical impulse.
    elasticity : float
        ``d ln J / d ln p`` of the critical impulse J.
    growth : float or None
        ``d ln sigma / d ln p`` of the linear growth rate (None when the rate is not positive).
    percent : float
        Change of the critical impulse for a 10 % change of the parameter in ``direction``, %.
    """

    label: str
    value: str
    direction: str
    elasticity: float
    growth: float | None
    percent: float


def push_text(d: ReportData) -> str:
    """The push convention in words, e.g. ``"40 N for 0.1 s (101 steps of 1 ms, 4.04 N s)"``.

    Parameters
    ----------
    d : ReportData
        The report's data.

    Returns
    -------
    str
    """
    return f"{THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s"


def model_gap(d: ReportData) -> str:
    """The thesis-versus-exact gap at the reference speed for this chair, with its cause, in one sentence.

    Parameters
    ----------
    d : ReportData
        The report's data.

    Returns
    -------
    str
    """
    rates = {}
    for s in (d.summary, d.summary_other):
        row = next((r for r in s.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
        if row is not None:
            rates[s.model] = row.rate
    gap = ""
    if len(rates) == 2 and rates["thesis"] != 0:
        gap = (f" For this chair at {REFERENCE_SPEED:g} m/s the largest real part is {rates['exact']:.3g} 1/s "
               f"(exact) against {rates['thesis']:.3g} 1/s (thesis), "
               f"{100 * (rates['exact'] / rates['thesis'] - 1):+.1f} %.")
    return ("Thesis numbers come from its own equations (our 'thesis' variant) integrated by WCHAIR; the 'exact' "
            "variant keeps five small terms those equations drop (the caster slip's -l r, caster inertia on the "
            "absolute acceleration, the pin acceleration from kinematics, caster inertia in the lateral and yaw "
            "equations), and readings from the thesis's figures carry a few per cent." + gap)


def elasticity_floor(d: ReportData) -> float:
    """Smallest elasticity the critical-impulse bisection resolves: ``2 rel_tol / ln((1+step)/(1-step))``.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    float
    """
    step = d.sensitivity.step if d.sensitivity is not None else 0.1
    return 2.0 * d.settings.impulse_tol / (math.log1p(step) - math.log1p(-step))


def best_changes(d: ReportData, n: int = 3) -> list[Change]:
    """The ``n`` parameters whose change raises the critical impulse most (largest |elasticity| first).

    Parameters
    ----------
    d : ReportData
    n : int

    Returns
    -------
    list of Change
        Only elasticities above :func:`elasticity_floor` (the bisection's resolution); empty when the
        chair's critical impulse at the reference speed was not found.
    """
    sens = d.sensitivity
    if sens is None or sens.nominal.impulse_Ns is None:
        return []
    floor = elasticity_floor(d)
    out = []
    for e in sens.ranked("critical_impulse"):
        if e.critical_impulse is None or abs(e.critical_impulse) <= floor:
            continue
        up = e.critical_impulse > 0
        factor = 1.1 if up else 0.9
        unit = "N" if e.parameter == FRICTION_OVER_TRAIL else get_parameter(
            "trail" if e.parameter == TRAIL_AT_FIXED_GROUP else e.parameter).unit
        value = f"{e.value:.4g}" + ("" if unit == "-" else f" {unit}")
        out.append(Change(e.label, value, "raise" if up else "lower", e.critical_impulse, e.growth_rate,
                          100.0 * (factor ** e.critical_impulse - 1.0)))
    return out[:n]


def dropped_pages(d: ReportData) -> dict[str, str]:
    """Pages that carry no information for this chair: page title -> the sentence saying why.

    Parameters
    ----------
    d : ReportData
        The report's data.

    Returns
    -------
    dict
        Page title -> the sentence saying why it is left out.
    """
    out = {}
    sweeps = d.chair_sweeps
    if d.chair_speed.status != "found" and all(r.status != "found" for sw in sweeps.sweeps for r in sw.results):
        why = (f"every variant of the parametric study (and the chair itself) stays outside the speed bracket "
               f"{d.chair_speed.bracket[0]:g}-{d.chair_speed.bracket[1]:g} m/s ({d.chair_speed.describe()}), "
               "so no parameter can be ranked")
        out["parametric study"] = why
        out["parametric study table"] = why
    if all(not np.isfinite(m.times).any() for m in (d.friction_map, d.disturbance_map)):
        out["stability maps"] = (f"no run of either map reaches |yaw rate| = {d.friction_map.criterion.yaw_rate:g} "
                                 f"rad/s within {d.friction_map.criterion.duration:g} s, so both maps are blank")
    out.update(section_drops(d))
    if drive_kind(d.chair) == "handrim":
        out["yaw-rate feedback root locus"] = ("it is a manual chair, pushed on its hand rims: no controller can "
                                               "close a yaw-rate feedback loop (the page is for power chairs)")
    elif d.gain_loci and all(g.stabilising_gain == 0 for g in d.gain_loci):
        out["yaw-rate feedback root locus"] = ("the linear model is stable without yaw-rate feedback at "
                                               + " and ".join(f"{g.speed:g}" for g in d.gain_loci)
                                               + " m/s, so there is no feedback gain to find")
    if d.baseline is None:
        out["comparison"] = "no baseline chair was given"
    if d.trail_window is None:
        out["trail design chart"] = ("no trail sweep or no shimmy model for this chair" if d.shimmy_note is None
                                     else d.shimmy_note)
    return out


def dropped_text(d: ReportData) -> list[str]:
    """The pages left out of this report and why, one line per reason.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    drop = dropped_pages(d)
    out, seen = [], set()
    for why in drop.values():
        if why not in seen:
            seen.add(why)
            same = [t for t, w in drop.items() if w == why]
            out.append(f"- {', '.join(same)}: {why}.")
    return out


def steady_turns(d: ReportData) -> list[tuple[float, float, float]]:
    """Runs that never reach the level but keep turning: (speed m/s, final |yaw rate| rad/s, heading change deg).

    The final yaw rate is the mean of the last second; only runs valid to the end are used.

    Parameters
    ----------
    d : ReportData
        The report's data.

    Returns
    -------
    list of (float, float, float)
    """
    out = []
    valid = d.validity.get("responses", ())
    for i, r in enumerate(d.responses.responses):
        if math.isfinite(r.time_to_level) or (i < len(valid) and valid[i].until is not None):
            continue
        t = np.asarray(r.t)
        last = t >= t[-1] - 1.0
        rate = float(np.mean(np.abs(np.asarray(r.yaw_rate)[last])))
        turn = float(np.degrees(abs(r.heading[-1] - r.heading[0])))
        if rate > 0.01:
            out.append((r.speed, rate, turn))
    return out


def _describe(v, m: str = "") -> str:
    return v.result.describe() + m if v.result is not None else "undefined (the reference case never reaches the level)"


def interval_text(iv) -> str:
    """One sentence: the equal-instability speed, its range and what moves it most.

    Parameters
    ----------
    iv : stability.study.EqualInstabilityInterval

    Returns
    -------
    str
    """
    rng = (f"{iv.range_text()}; moves it most: {iv.dominant}" if iv.low is not None and iv.high is not None
           and _ranked(iv) else iv.range_text())
    return f"{iv.chair_name} {iv.point.describe()}, {rng}"


def _interval_lines(d: ReportData) -> list[str]:
    iv = d.intervals
    if iv is None:
        return []
    f0 = THESIS_PUSH.force
    q = mark(d.settings)
    who = iv.chair_name + (" (the thesis's revised design)" if d.chair == preset(REFERENCE_CHAIR) else "")
    by = {f: [v for v in iv.variants if v.factor == f] for f in ("disturbance", "pin friction", "model", "step")}
    return [
        f"- Equal-instability speed of {who}: {iv.point.describe()}{q} ({d.model} model, thesis push)"
        + (f", {iv.range_text()}{q}" if iv.low is not None and iv.high is not None else "")
        + " over: push " + ", ".join(f"{v.force:g} N -> {_describe(v, q)}" for v in by["disturbance"])
        + f" (thesis {f0:g} N); pin friction of both chairs "
        + ", ".join(f"x{v.friction_factor:g} -> {_describe(v, q)}" for v in by["pin friction"]) + "; "
        + ", ".join(f"{v.model} model -> {_describe(v, q)}" for v in by["model"])
        + "".join(f"; {v.label} -> {_describe(v, q)}" for v in by["step"])
        + (f". Moves it most: {iv.dominant}{q}." if _ranked(iv) else
           ". Nothing can be ranked: every variant is a bound or undefined."),
    ]


def _ranked(iv) -> bool:
    """Whether the interval's variants can rank its factors (at least one found speed besides the nominal)."""
    return any(v.result is not None and v.result.status == "found" for v in iv.variants)


def _section_lines(d: ReportData) -> list[str]:
    out = []
    sl = d.slope
    if sl is not None and sl.per_degree is not None:
        out.append(f"- Cross slope at {sl.speed:g} m/s: holding moment {sl.per_degree:.3g} N m/deg (treadmill study of "
                   f"manual chairs: {CROSS_SLOPE_STUDY[0]:g}, {CROSS_SLOPE_STUDY[1]:g}-{CROSS_SLOPE_STUDY[2]:.2f} "
                   f"N m/deg; set by m x_m = {sl.m_x:.3g} kg m)"
                   + (f"; uncorrected it turns {sl.path.turn}" if sl.path is not None else "")
                   + (f"; refused at {', '.join(f'{p:g}' for p, _ in sl.refused)} deg (tire data)" if sl.refused
                      else "") + ".")
    sh = d.shimmy
    if sh is not None:
        crit = [x[2] for x in sh.corners]
        hi = max(crit)
        out.append(f"- Caster shimmy: linear boundary at trail {100 * sh.critical:.2f} cm with the estimated caster "
                   f"compliance (estimates: {100 * min(crit):.2f} cm to "
                   + (f"{100 * hi:.2f} cm" if math.isfinite(hi) else "> 25 cm") + " over their range); this chair's "
                   f"trail {100 * sh.chart.chair_trail:g} cm.")
    return out


def _rate_interval(d: ReportData) -> str:
    u = d.uncertainty
    if u is None:
        return ""
    lo, hi = u.rate_at(REFERENCE_SPEED)
    dom = u.dominant
    return (f" [{100 * u.intervals.level:g} %: {lo:.3g}-{hi:.3g} 1/s over {u.spec.source}"
            + (f", dominated by {dom[0]}" if dom is not None else ", zero spread") + "]")


def _impulse_interval(d: ReportData) -> str:
    u = d.uncertainty
    if u is None or u.nonlinear is None:
        return ""
    k = u.nonlinear.critical_impulse
    dom = k.dominant
    return (f" [{100 * u.nonlinear.level:g} %: {k.describe()}{mark(d.settings)} over {u.spec.source}"
            + (f", dominated by {dom[0]}" if dom is not None else ", zero spread") + "]")


def _nonlinear_lines(d: ReportData) -> list[str]:
    u = d.uncertainty
    e = None if u is None or u.nonlinear is None else u.nonlinear.equal_instability
    if u is None or u.nonlinear is None or e is None:
        return []
    dom = e.dominant
    return [f"- Equal-instability speed of {d.chair.name} over {u.spec.source} ({u.nonlinear.samples} draws, "
            f"reference case fixed): [{100 * u.nonlinear.level:g} %: {e.describe()}{mark(d.settings)}"
            + (f", dominated by {dom[0]}" if dom is not None else ", zero spread") + "]."]


def _verdict(d: ReportData) -> str:
    c, s, cs = d.chair, d.summary, d.chair_speed
    ref = d.thesis.speeds[REFERENCE_CHAIR]
    if s.free_unstable_at_all_speeds:
        lin = "with free, frictionless casters it is directionally unstable at every speed (linear model)"
    elif s.free_stable_at_all_speeds:
        lin = "with free, frictionless casters it is directionally stable at every speed searched (linear model)"
    else:
        lin = "its linear stability changes with speed (see the eigenvalue pages)"
    if cs.status == "found" and c == preset(REFERENCE_CHAIR):
        non = (f"this is the thesis's reference chair: with its pin friction, after the thesis's push at "
               f"{REFERENCE_SPEED:g} m/s ({3.6 * REFERENCE_SPEED:.2g} km/h, a slow walk) the user has "
               f"{d.thesis.reference_time:.2g} s before it turns at {d.thesis.criterion.yaw_rate:g} rad/s; faster "
               "than that it gets worse")
    elif cs.status == "found":
        rel = (f", {100 * (cs.speed / ref.speed - 1):+.0f} % against the {REFERENCE_CHAIR}"
               if ref.status == "found" else "")
        non = (f"in simulation with its pin friction it is as unstable as the thesis's reference case (the "
               f"{REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s) at {cs.describe()}{mark(d.settings)} "
               f"({3.6 * cs.speed:.2g} km/h){rel}")
    elif cs.status == "above":
        non = (f"in simulation it stays more stable than the thesis's reference case up to {cs.bracket[1]:g} m/s "
               "(the top of the range searched)")
    else:
        non = f"in simulation it is already less stable than the reference case at {cs.bracket[0]:g} m/s"
    return f"Verdict: {c.name} - {lin}; {non}."


def summary_text(d: ReportData) -> str:
    """The text of the summary page (paragraphs separated by blank lines).

    Parameters
    ----------
    d : ReportData
        The report's data.

    Returns
    -------
    str
    """
    c, s = d.chair, d.summary
    out = [f"Chair: {c.name}, {c.caster_position} casters; s1 = {c.s1:g} m, s2 = {c.s2:g} m, trail {c.trail:g} m, "
           f"mass {c.m:g} kg, yaw inertia {c.i_z:g} kg m^2, pin friction {c.pin_friction_left:g}/"
           f"{c.pin_friction_right:g} N m, tires {c.main_tire} (main) and {c.caster_tire} (casters).",
           _verdict(d), "Key numbers"]
    row = next((r for r in s.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    if row is not None:
        out.append(f"- Linear growth rate (largest real part; negative: decay) at {REFERENCE_SPEED:g} m/s, free "
                   f"casters: {row.rate:.3g} 1/s ({d.model} model)" + _rate_interval(d) + _other_rate(d) + ".")
    imp = [x for x in d.impulses if x is not None]
    if imp:
        parts = [f"{x.chair_name} {x.describe()}{mark(d.settings)}" + (f" ({x.kick_m_s:.3g} m/s: impulse per unit mass)"
                                                      if x.kick_m_s is not None else "")
                 + (_impulse_interval(d) if i == 0 else "") for i, x in enumerate(imp)]
        out.append(f"- Critical impulse at {REFERENCE_SPEED:g} m/s (smallest push at the c.g., force held "
                   f"{THESIS_PUSH.duration:g} s, that brings |yaw rate| to {d.thesis.criterion.yaw_rate:g} rad/s "
                   f"within {d.thesis.criterion.duration:g} s): " + "; ".join(parts)
                   + f". The thesis's push is {push_text(d)}.")
    out.extend(_nonlinear_lines(d))
    out.extend(_interval_lines(d))
    out.extend(_section_lines(d))
    t = d.tipping
    if t is not None:         # the appendix's chair-parameters page prints the same angles
        out.append(f"- Static stability angles (ISO 7176-1; brakes locked, casters in their least stable orientation): "
                   f"toward the main wheels {t.toward_main_wheels_deg:.1f} deg, toward the casters "
                   f"{t.toward_casters_deg:.1f} deg, sideways {t.lateral_left_deg:.1f} / {t.lateral_right_deg:.1f} deg "
                   "(left / right).")
    out.append(f"- Reference case ({REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s, {push_text(d)}): |yaw rate| reaches "
               f"{d.thesis.criterion.yaw_rate:g} rad/s after {d.thesis.reference_time:.2f} s "
               "(thesis: slightly over 3 s).")
    changes = best_changes(d)
    out.append(f"What helps most (elasticities of the critical impulse at {REFERENCE_SPEED:g} m/s: every parameter "
               "x0.9 and x1.1, the others at this chair's values)")
    if changes:
        q = mark(d.settings)
        out.extend(f"- {ch.label} (now {ch.value}): {ch.direction} it -> critical impulse {ch.percent:+.1f} %{q} per "
                   f"10 % (elasticity {ch.elasticity:+.2f}{q}"
                   + (f"; growth rate {ch.growth:+.2f})" if ch.growth is not None else ")") for ch in changes)
        out.append("  Pin friction and trail act through one quantity, the friction-limited caster side force M_f/l: "
                   "it is ranked as one group, and trail separately at fixed M_f/l.")
        opposite = [ch.label for ch in changes if ch.growth is not None and ch.elasticity * ch.growth > 0]
        if opposite:
            # both elasticities positive (or both negative): raising the parameter raises the critical impulse
            # (better) and the growth rate (worse) - the two measures disagree on direction
            out.append("  For " + ", ".join(opposite) + " the two measures point opposite ways: the linear growth "
                       "rate leaves out pin friction, the critical impulse (nonlinear, with stick-slip friction) "
                       "includes it, so the critical impulse decides (see the findings).")
    else:
        sens = d.sensitivity
        why = ("its critical impulse at this speed was not found (no push up to the largest tried brings |yaw rate| "
               "to the level)" if sens is None or sens.nominal.impulse_Ns is None
               else "no elasticity exceeds the bisection's resolution")
        out.append(f"- Nothing to rank: {why}.")
    out.append("Caveats")
    out.append(f"- Disturbance: the thesis's measure depends on the push chosen ({push_text(d)}); the ranges above "
               "show how much. The critical impulse does not depend on it.")
    out.append(f"- Pin friction: Coulomb pin friction ({c.pin_friction_left:g} N m here) has no linearisation; "
               "the nonlinear results rest on it (see the friction ranges above and the stability map).")
    out.append("- Model variant: the thesis's equations and the exact ones are compared in the method appendix.")
    if d.uncertainty is None:
        out.append("- Parameters: point values at the chair's parameters (an uncertainty file gives intervals).")
    if d.shimmy is not None:
        out.append("- Shimmy: the caster tire relaxation length and the pin's lateral stiffness are estimates.")
    cut = [v for v in d.validity.get("responses", ()) if v.until is not None]
    if cut:
        out.append(f"- Validity: {len(cut)} of {len(d.validity['responses'])} response runs leave the tire data "
                   f"(first at {min(v.until for v in cut):.2f} s: {min(cut, key=lambda v: v.until).reason}); "
                   "curves stop there.")
    return "\n".join(out)


def _other_rate(d: ReportData) -> str:
    row = next((r for r in d.summary_other.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    return "" if row is None else f", {row.rate:.3g} 1/s ({d.summary_other.model} model)"
