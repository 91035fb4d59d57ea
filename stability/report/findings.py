"""The report's findings in plain words: every number taken from :class:`~stability.report.compute.ReportData`."""

from __future__ import annotations

import math

import numpy as np

from stability.chair import preset
from stability.report.compute import ReportData
from stability.report.summary import elasticity_floor, push_text, steady_turns
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.study.validation import has_rolling_resistance

__all__ = ["findings", "conclusion_rows"]


def _first(crossings, direction: str = "destabilising") -> float | None:
    return next((x.speed for x in crossings if x.direction == direction), None)


def findings(d: ReportData) -> list[str]:
    """The findings page: paragraphs in plain words; every number comes from ``d``.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
        One paragraph per finding.
    """
    c, m = d.chair, d.model
    s = d.summary
    out = []
    locked = _first(s.locked_crossings)
    r075 = next((r for r in s.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    if s.free_unstable_at_all_speeds:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} is directionally unstable at "
               f"every speed searched ({s.search_range[0]:g}-{s.search_range[1]:g} m/s).")
    elif s.free_stable_at_all_speeds:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} is directionally stable at "
               f"every speed searched ({s.search_range[0]:g}-{s.search_range[1]:g} m/s).")
    else:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} changes stability at "
               + ", ".join(f"{x.speed:.3g} m/s ({x.direction})" for x in s.free_crossings) + ".")
    if r075 is not None and r075.time_to_double is not None:
        txt += (f" At {REFERENCE_SPEED:g} m/s its least stable mode grows at {r075.rate:.3g} 1/s: "
                f"a heading error doubles every {r075.time_to_double:.3g} s.")
    txt += (f" With the casters locked it is stable up to {locked:.3g} m/s." if locked is not None
            else " With the casters locked it is stable in the whole range searched.")
    zw = s.zero_width
    txt += (f" The zero-width model (eq 5-15) puts the locked-caster critical speed at {zw.critical_speed:.3g} m/s."
            if zw.critical_speed is not None
            else " The zero-width model (eq 5-16) says: understeer, stable with locked casters.")
    out.append(txt)
    so = d.summary_other
    fo = _first(so.free_crossings)
    out.append(f"The other model variant ({so.model}) gives: free casters "
               + ("unstable at every speed searched" if so.free_unstable_at_all_speeds else
                  "stable at every speed searched" if so.free_stable_at_all_speeds else
                  f"first critical speed {fo:.3g} m/s")
               + (f"; locked casters critical speed {_first(so.locked_crossings):.3g} m/s."
                  if _first(so.locked_crossings) is not None else "; locked casters stable in the range."))
    rl = d.rolling
    if rl is not None:
        own = has_rolling_resistance(c)
        out.append(("This chair's rolling resistance is" if own else
                    "Rolling resistance (off for this chair, as in WCHAIR's defaults) is")
                   + " left out of the linear model. "
                   + ("With it" if own else "With the tire fits' rolling resistance on all four wheels")
                   + f", the simulator's own linearisation puts the least stable mode at {rl.speed:g} m/s at "
                   f"{rl.eigenvalue_simulator.real:.3g} 1/s instead of {rl.eigenvalue_linear.real:.3g} 1/s "
                   f"({100 * rl.rate_difference:+.0f} %): a caster's drag follows its contact velocity, so the "
                   "casters act as an axle of small cornering stiffness (twice the drag, N/rad).")
    th = d.thesis
    out.append(f"Nonlinear simulation ({m} model, {d.scheme} scheme, Coulomb pin friction "
               f"{c.pin_friction_left:g}/{c.pin_friction_right:g} N m): the reference case "
               f"(E&J Premier at {REFERENCE_SPEED:g} m/s, {push_text(d)} at the c.g.) reaches |yaw rate| = "
               f"{th.criterion.yaw_rate:g} rad/s after {th.reference_time:.2f} s (thesis: slightly over 3 s). "
               + "The two model variants are compared in the method appendix.")
    cs = d.chair_speed
    ref = th.speeds[REFERENCE_CHAIR]
    if c == preset(REFERENCE_CHAIR):
        rev = th.speeds["revised"]
        out.append(f"{c.name} is the reference chair: bisection on speed finds its own equal-instability speed at "
                   f"{cs.describe()} (the reference speed is {REFERENCE_SPEED:g} m/s). "
                   "The chapter-9 revised design reaches the "
                   f"same instability at {rev.describe()} (thesis: 1.10-1.15 m/s), "
                   + (f"{100 * (rev.speed / cs.speed - 1):+.0f} %." if rev.status == cs.status == "found" else "."))
    elif cs.status == "found":
        rel = 100 * (cs.speed / ref.value_or_bound - 1) if ref.status == "found" else float("nan")
        out.append(f"{c.name} shows the same instability at {cs.speed:.3g} m/s"
                   + (f", {rel:+.0f} % against the E&J Premier's {ref.speed:.3g} m/s." if math.isfinite(rel) else ".")
                   + " Above that speed a user has less time to correct a disturbance than in the thesis's "
                     "reference case.")
    elif cs.status == "above":
        out.append(f"{c.name} never reaches the reference instability below {cs.bracket[1]:g} m/s: "
                   "it is more stable than the reference case at every speed tested.")
    else:
        out.append(f"{c.name} is already less stable than the reference case at {cs.bracket[0]:g} m/s.")
    fm = d.friction_map
    j = int(np.argmin(np.abs(fm.y_values - c.pin_friction_left)))
    finite = np.flatnonzero(np.isfinite(fm.times[j]))
    if len(finite) and finite[0] > 0:
        out.append(f"Slow speeds: with {fm.y_values[j]:g} N m of pin friction the simulated chair does not reach "
                   f"{th.criterion.yaw_rate:g} rad/s within {fm.criterion.duration:g} s at "
                   f"{fm.speeds[finite[0] - 1]:g} m/s and below, but does at {fm.speeds[finite[0]]:g} m/s "
                   f"(after {fm.times[j, finite[0]]:.2f} s), although the frictionless linear model is "
                   + ("unstable at every speed." if s.free_unstable_at_all_speeds else "as described above.")
                   + _steady_turn_text(d))
    f_lo, f_hi = d.chair_friction
    out.append(f"Pin friction: at half the friction the equal-instability speed is {f_lo.describe()}, at 1.5 times "
               f"it is {f_hi.describe()} (own friction: {cs.describe()})." + _friction_gain_text(d))
    out.append(_figure_8_14_text(d))
    out.append(_elasticity_text(d))
    g = d.gain_loci[0]
    if g.stabilising_gain is None:
        out.append(f"Yaw-rate feedback Mz = -K r does not stabilise the linear model at {g.speed:g} m/s "
                   f"for K up to {g.gains[-1]:g} N m s/rad.")
    elif g.stabilising_gain == 0:
        out.append(f"The linear model is stable at {g.speed:g} m/s without feedback.")
    else:
        out.append(f"Yaw-rate feedback Mz = -K r stabilises the linear model at {g.speed:g} m/s for "
                   f"K > {g.stabilising_gain:.3g} N m s/rad; at {d.gain_loci[1].speed:g} m/s for K > "
                   + (f"{d.gain_loci[1].stabilising_gain:.3g} N m s/rad." if d.gain_loci[1].stabilising_gain is not None
                      else "(none in range)."))
    verdicts = [row[2].lower() for row in conclusion_rows(d)]
    n_agree, n_part, n_dis = (verdicts.count(v) for v in ("agree", "partly", "disagree"))
    out.append(f"Thesis conclusions 1-9 against our numbers: {n_agree} agree, {n_part} partly, {n_dis} disagree "
               "(details on the previous page).")
    return out


def _elasticity_text(d: ReportData) -> str:
    sens = d.sensitivity
    if sens is None:
        return ""
    floor = elasticity_floor(d)

    def listing(measure: str) -> str:
        items = [(e.label, getattr(e, measure)) for e in sens.ranked(measure)]
        shown = [f"{lab} {v:+.2f}" for lab, v in items if v is not None and abs(v) > floor]
        return ", ".join(shown) if shown else "none above the resolution"

    imp = (f"critical impulse ({sens.nominal.describe()}): " + listing("critical_impulse")
           if sens.nominal.impulse_Ns is not None else "critical impulse: not found at this speed")
    grow = (f"linear growth rate ({sens.nominal_growth_rate:.3g} 1/s): " + listing("growth_rate")
            if sens.nominal_growth_rate > 0 else "linear growth rate: negative (stable), no elasticity")
    return (f"What matters most, as elasticities d ln v / d ln p at {sens.speed:g} m/s ({sens.model} model; every "
            f"parameter x{1 - sens.step:g} and x{1 + sens.step:g}; shown when above the resolution {floor:.2g}): "
            f"{imp}; {grow}. Pin friction and trail enter as the group M_f/l (the friction-limited caster side "
            "force) and trail at fixed M_f/l. The parametric-study pages show spreads over unequal ranges, which "
            "are not sensitivities.")


def _steady_turn_text(d: ReportData) -> str:
    turns = steady_turns(d)
    if not turns:
        return ""
    lo = min(t[1] for t in turns)
    hi = max(t[1] for t in turns)
    deg = max(t[2] for t in turns)
    speeds = ", ".join(f"{t[0]:.3g}" for t in turns)
    rate = f"{lo:.2g} rad/s" if abs(hi - lo) < 0.005 else f"{lo:.2g}-{hi:.2g} rad/s"
    return (f" This is not straight running: at {speeds} m/s the friction-held casters leave the chair in a steady "
            f"slow turn of {rate} (heading changed by up to {deg:.0f} deg in {d.responses.criterion.duration:g} s), "
            "which the thesis would call unstable: the user must keep correcting it. The time-to-level measure "
            "does not see it.")


def _friction_gain_text(d: ReportData) -> str:
    """The revised design against the reference chair at EQUAL pin friction (x0.5, x1, x1.5 of both).

    Comparing one chair at half friction with the other at full friction mixes the friction effect with
    the geometry effect; only equal friction levels separate them.
    """
    sp = d.thesis.speeds
    ref, rev = preset(REFERENCE_CHAIR), preset("revised")
    if d.chair not in (ref, rev) or rev.pin_friction_left != ref.pin_friction_left:
        return ""
    pairs = [(f, sp[f"{REFERENCE_CHAIR} x{f:g} friction" if f != 1 else REFERENCE_CHAIR],
              sp[f"revised x{f:g} friction" if f != 1 else "revised"]) for f in (0.5, 1.0, 1.5)]
    if any(a.status != "found" or b.status != "found" for _, a, b in pairs):
        return ""
    better = all(b.speed > a.speed for _, a, b in pairs)
    txt = "; ".join(f"{f * ref.pin_friction_left:g} N m: {b.speed:.3g} vs {a.speed:.3g} m/s" for f, a, b in pairs)
    return (f" At equal pin friction (both chairs) the revised design against the {REFERENCE_CHAIR}: {txt}"
            + (" - better at every level, so its gain is geometry, and pin friction adds to it." if better
               else " - not better at every level."))


def _figure_8_14_text(d: ReportData) -> str:
    f = d.figure_8_14
    if f is None:
        return ""
    ref = d.thesis.speeds[REFERENCE_CHAIR]
    ours = ""
    if f.speed.status == "found" and ref.status == "found":
        ours = (" - more stable than the reference chair, as the thesis found" if f.speed.speed > ref.speed
                else " - less stable than the reference chair, the opposite of the thesis")
    return (f"Figure 8-14 (the {REFERENCE_CHAIR} with m = {f.chair.m:g} kg and I_z = {f.chair.i_z:g} kg m^2): the "
            "thesis finds that the lighter chair reaches the reference instability only at about 0.85 m/s, so "
            f"reducing mass and inertia improved stability; we find {f.speed.describe()} ({d.model} model){ours}. "
            f"Why they can differ: with free casters the unstable mode is the massless-caster mode, whose rate at "
            f"low speed is U m x_m / (I_z + m x_m^2) ({f.massless_reference:.3g} vs {f.massless_light:.3g} 1/s at "
            f"{REFERENCE_SPEED:g} m/s; full linear model {f.rate_reference:.3g} vs {f.rate_light:.3g} 1/s): nearly "
            "unchanged when m and I_z shrink together. The thesis's argument (less load, less cornering stiffness, "
            "eq 5-18) is about the locked-caster zero-width model, not this mode.")


def conclusion_rows(d: ReportData) -> list[list[str]]:
    """The conclusions table: number, statement, verdict, evidence (verdict rules: :mod:`stability.study.conclusions`)
    and, when the report's chair has its own tests, a separate column with that chair's verdict and evidence.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of list of str
        One row per conclusion.
    """
    own = any(x.chair_verdict for x in d.conclusions)
    return [[str(x.number), x.statement, x.verdict.upper(), x.evidence]
            + ([(x.chair_verdict.upper() + ": " + x.chair_evidence) if x.chair_verdict else "-"] if own else [])
            for x in d.conclusions]
