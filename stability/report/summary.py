"""Page 1 of the report: the chair, a verdict, key numbers with their ranges, what helps most, caveats.

Every number comes from :class:`~stability.report.compute.ReportData`; the
rules (which pages are dropped, how changes are ranked) are in docs/report.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..chair import preset
from ..reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from .compute import ReportData

__all__ = ["Change", "best_changes", "dropped_pages", "model_gap", "push_text", "steady_turns", "summary_text"]


@dataclass(frozen=True)
class Change:
    """One parameter change from the parametric study and its effect on the equal-instability speed.

    Attributes
    ----------
    label : str
        The parameter.
    value, current : str
        The value tried and the chair's own, with units.
    speed : str
        The equal-instability speed with that value.
    percent : float
        Change against the chair's own speed, %.
    """

    label: str
    value: str
    current: str
    speed: str
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
    return THESIS_PUSH.describe(d.settings.dt if d.scheme == "wchair" else None)


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
        row = next((r for r in s.divergence if abs(r["speed_m_s"] - REFERENCE_SPEED) < 1e-9), None)
        if row is not None:
            rates[s.model] = row["rate_1_s"]
    gap = ""
    if len(rates) == 2 and rates["thesis"] != 0:
        gap = (f" For this chair at {REFERENCE_SPEED:g} m/s the largest real part is {rates['exact']:.3g} 1/s "
               f"(exact) against {rates['thesis']:.3g} 1/s (thesis), "
               f"{100 * (rates['exact'] / rates['thesis'] - 1):+.1f} %.")
    return ("Thesis numbers come from its own equations (our 'thesis' variant) integrated by WCHAIR; the 'exact' "
            "variant keeps five small terms those equations drop (the caster slip's -l r, caster inertia on the "
            "absolute acceleration, the pin acceleration from kinematics, caster inertia in the lateral and yaw "
            "equations), and readings from the thesis's figures carry a few per cent." + gap)


def best_changes(d: ReportData, n: int = 3) -> list[Change]:
    """The ``n`` single-parameter changes of the parametric study that raise the equal-instability speed most.

    Parameters
    ----------
    d : ReportData
    n : int

    Returns
    -------
    list of Change
        Largest gain first; only changes whose speed was found (not a bound) and is higher than the chair's.
    """
    u0 = d.chair_speed
    if u0.status != "found":
        return []
    out = []
    for sw in d.chair_sweeps.sweeps:
        best, k_best = 0.0, -1
        for k, r in enumerate(sw.results):
            if r.status == "found" and r.speed / u0.speed - 1 > best:
                best, k_best = r.speed / u0.speed - 1, k
        if k_best >= 0:
            cur = (d.chair.main_tire if sw.labels is not None else
                   (f"{sw.nominal_value:g}" + ("" if sw.unit == "-" else f" {sw.unit}")))
            out.append(Change(sw.label, sw.value_text(k_best) + ("" if sw.unit in ("-", "") or sw.labels is not None
                                                                  else f" {sw.unit}"),
                              cur, sw.results[k_best].describe(), 100 * best))
    return sorted(out, key=lambda ch: -ch.percent)[:n]


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


def _interval_lines(d: ReportData) -> list[str]:
    iv = d.intervals
    if iv is None:
        return []
    lo, hi = iv.span()
    f0 = THESIS_PUSH.force
    p_lo, p_hi = iv.push
    f_lo, f_hi = iv.friction
    who = iv.chair.name + (" (the thesis's revised design)" if d.chair == preset(REFERENCE_CHAIR) else "")
    return [
        f"- Equal-instability speed of {who}: {iv.nominal.describe()} ({d.model} model, thesis push), range "
        f"{lo:.3g}-{hi:.3g} m/s over: push {p_lo.impulse[0]:g} N -> {p_lo.describe()}, {p_hi.impulse[0]:g} N -> "
        f"{p_hi.describe()} (thesis {f0:g} N); pin friction x0.5 -> {f_lo.describe()}, x1.5 -> {f_hi.describe()}; "
        f"{iv.other_model.model} model -> {iv.other_model.describe()}. Moves it most: {iv.widest()}.",
    ]


def _verdict(d: ReportData) -> str:
    c, s, cs = d.chair, d.summary, d.chair_speed
    ref = d.thesis.speeds[REFERENCE_CHAIR]
    if s.free_unstable_at_all_speeds:
        lin = "with free, frictionless casters it is directionally unstable at every speed (linear model)"
    elif s.free_stable_at_all_speeds:
        lin = "with free, frictionless casters it is directionally stable at every speed searched (linear model)"
    else:
        lin = "its linear stability changes with speed (see the eigenvalue pages)"
    if cs.status == "found":
        rel = (f", {100 * (cs.speed / ref.speed - 1):+.0f} % against the {REFERENCE_CHAIR}"
               if ref.status == "found" and c != preset(REFERENCE_CHAIR) else "")
        non = (f"in simulation with its pin friction it is as unstable as the thesis's reference case at "
               f"{cs.describe()}{rel}")
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
    row = next((r for r in s.divergence if abs(r["speed_m_s"] - REFERENCE_SPEED) < 1e-9), None)
    if row is not None:
        out.append(f"- Linear growth rate (largest real part; negative: decay) at {REFERENCE_SPEED:g} m/s, free "
                   f"casters: {row['rate_1_s']:.3g} 1/s ({d.model} model)" + _other_rate(d) + ".")
    imp = [x for x in d.impulses if x is not None]
    if imp:
        parts = [f"{x.chair_name} {x.describe()}" + (f" ({x.kick_m_s:.3g} m/s per unit mass)"
                                                      if x.kick_m_s is not None else "") for x in imp]
        out.append(f"- Critical impulse at {REFERENCE_SPEED:g} m/s (smallest push at the c.g., force held "
                   f"{THESIS_PUSH.duration:g} s, that brings |yaw rate| to {d.thesis.criterion.yaw_rate:g} rad/s "
                   f"within {d.thesis.criterion.duration:g} s): " + "; ".join(parts)
                   + f". The thesis's push is {push_text(d)}.")
    out.extend(_interval_lines(d))
    out.append(f"- Reference case ({REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s, {push_text(d)}): |yaw rate| reaches "
               f"{d.thesis.criterion.yaw_rate:g} rad/s after {d.thesis.reference_time:.2f} s "
               "(thesis: slightly over 3 s).")
    changes = best_changes(d)
    out.append("What helps most (single changes of the parametric study, other parameters at this chair's values)")
    if changes:
        out.extend(f"- {ch.label}: {ch.value} instead of {ch.current} -> equal-instability speed {ch.speed} "
                   f"({ch.percent:+.0f} %)" for ch in changes)
        out.append("  Pin friction and trail act together through the friction-limited caster side force M_f/l: "
                   "their effects are not independent.")
    else:
        out.append("- No single change of the study raises a found equal-instability speed "
                   f"({d.chair_speed.describe()}).")
    out.append("Caveats")
    out.append(f"- Disturbance: the thesis's measure depends on the push chosen ({push_text(d)}); the ranges above "
               "show how much. The critical impulse does not depend on it.")
    out.append(f"- Pin friction: Coulomb pin friction ({c.pin_friction_left:g} N m here) has no linearisation; "
               "the nonlinear results rest on it (see the friction ranges above and the stability map).")
    out.append("- Model variant: " + model_gap(d))
    cut = [v for v in d.validity.get("responses", ()) if v.until is not None]
    if cut:
        out.append(f"- Validity: {len(cut)} of {len(d.validity['responses'])} response runs leave the tire data "
                   f"(first at {min(v.until for v in cut):.2f} s: {min(cut, key=lambda v: v.until).reason}); "
                   "curves stop there.")
    drop = dropped_pages(d)
    if drop:
        out.append("Pages left out")
        seen = set()
        for why in drop.values():
            if why not in seen:
                seen.add(why)
                same = [t for t, w in drop.items() if w == why]
                out.append(f"- {', '.join(same)}: {why}.")
    return "\n".join(out)


def _other_rate(d: ReportData) -> str:
    row = next((r for r in d.summary_other.divergence if abs(r["speed_m_s"] - REFERENCE_SPEED) < 1e-9), None)
    return "" if row is None else f", {row['rate_1_s']:.3g} 1/s ({d.summary_other.model} model)"
