"""One concluding caption per report page: what the reader should take from it, every number from the data.

A caption is one or two sentences in plain words, drawn at the foot of its page
(:func:`stability.report.document.pages`).  The functions here only read
:class:`~stability.report.compute.ReportData`; they compute nothing new.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from stability.advise.limits import shimmy_sentence
from stability.advise.text import kmh
from stability.report.behaviour import friction_role, motion, sig3
from stability.report.comparison import RESTATED, comparison_rows, report_key_numbers
from stability.report.compute import ReportData
from stability.report.ranges import interval_words
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED

__all__ = ["CAPTIONS", "caption"]


def _first(crossings, direction: str = "destabilising") -> float | None:
    return next((x.speed for x in crossings if x.direction == direction), None)


def _at_reference(d: ReportData):
    return next((r for r in d.summary.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)


def _chair(d: ReportData) -> str:
    c = d.chair
    x = c.s1 / (c.s1 + c.s2)
    t = d.tipping
    tip = ("" if t is None else
           f" Braked, it tips toward its casters on a {t.toward_casters_deg:.0f} deg slope and toward its main wheels "
           f"on {t.toward_main_wheels_deg:.0f} deg: moving the c.g. toward the main axle lowers the latter.")
    return (f"The c.g. lies {100 * c.s1:.3g} cm from the main axle, {100 * x:.0f} % of the way from the main axle "
            f"to the caster pins; the casters trail {100 * c.trail:.3g} cm behind their pins. The closer the c.g. to "
            "the main axle and the longer the axle-to-pin distance, the more directionally stable (thesis "
            "conclusions 2 and 3)." + tip)


def _tires(d: ReportData) -> str:
    zw = d.summary.zero_width
    row = _at_reference(d)
    grows = row is not None and row.rate > 0
    return (f"At this chair's static loads ({zw.load_main:.0f} N per main wheel, {zw.load_caster:.0f} N per caster) "
            f"the main tires give {math.radians(zw.stiffness_main):.3g} N/deg and the casters "
            f"{math.radians(zw.stiffness_caster):.3g} N/deg of cornering stiffness; "
            + ("a softer main tire slows the divergence a little (conclusion 9)." if grows else
               f"this chair does not diverge at {REFERENCE_SPEED:g} m/s (growth rate {row.rate:.3g} 1/s), so the "
               "tire has no divergence to slow." if row is not None else "no linear growth rate at the reference "
               "speed."))


def _linear(d: ReportData) -> str:
    s = d.summary
    locked = _first(s.locked_crossings)
    row = _at_reference(d)
    if s.free_unstable_at_all_speeds:
        txt = "With free casters and no pin friction the chair is unstable at every speed: the user must steer."
    elif s.free_stable_at_all_speeds:
        txt = "With free casters and no pin friction the chair is stable at every speed searched."
    else:
        txt = "With free casters the chair's linear stability changes with speed (see the crossings)."
    if row is not None and row.time_to_double is not None:
        txt += f" At {kmh(REFERENCE_SPEED)} a heading error doubles every {row.time_to_double:.2g} s."
    txt += (f" Locked casters would keep it stable up to {kmh(locked)}." if locked is not None
            else " Locked casters would keep it stable at every speed searched.")
    return txt


def _growth(d: ReportData) -> str:
    spans = []
    for loc in d.parameter_loci:
        rate = np.max(np.real(np.asarray(loc.eigenvalues)), axis=1)
        spans.append((float(rate.max() - rate.min()), loc.label, float(rate.min()), float(rate.max())))
    spans.sort(reverse=True)
    top = "; ".join(f"{lab} ({lo:.3g} to {hi:.3g} 1/s)" for _, lab, lo, hi in spans[:2])
    return (f"Over the ranges tried the frictionless linear growth rate moves most with {top}. It leaves out pin "
            "friction, so where it disagrees with the nonlinear pages those decide (see the findings).")


def _gain(d: ReportData) -> str:
    g = d.gain_loci[0]
    if g.stabilising_gain is None:
        return (f"For a power chair: yaw-rate feedback up to {g.gains[-1]:g} N m s/rad does not stabilise the linear "
                f"model at {kmh(g.speed)}.")
    if g.stabilising_gain == 0:
        return f"For a power chair: the linear model is stable at {kmh(g.speed)} without feedback."
    return (f"For a power chair: a yaw moment of more than {g.stabilising_gain:.3g} N m per rad/s of yaw rate "
            f"(feedback gain K) makes the chair directionally stable at {kmh(g.speed)}; the assist design builds on "
            "this.")


def _motions(d: ReportData, key: str) -> list:
    rs = getattr(d, {"responses": "responses", "frictionless": "responses_frictionless", "paths": "paths"}[key])
    val = d.validity.get(key) or (None,) * len(rs.responses)
    return [motion(r, v) for r, v in zip(rs.responses, val, strict=True)]


def _responses(d: ReportData) -> str:
    ms = _motions(d, "responses")
    ref = d.thesis.reference_time
    law = "stick-slip pin friction"
    spun = [m for m in ms if m.kind == "spins up"]
    if spun:
        fast = min(spun, key=lambda m: m.time_to_level)
        txt = (f"After the thesis's push ({law}) the chair spins up to {d.thesis.criterion.yaw_rate:g} rad/s within "
               f"{sig3(fast.time_to_level)} s at {kmh(fast.speed)} (reference case {sig3(ref)} s): the faster it "
               "goes, the less time the user has to correct it")
    else:
        txt = (f"No speed shown reaches {d.thesis.criterion.yaw_rate:g} rad/s within "
               f"{d.thesis.criterion.duration:g} s after the push ({law})")
    turning = [m for m in ms if m.kind == "keeps turning"]
    if turning:
        txt += ("; at " + ", ".join(kmh(m.speed) for m in turning) + " it "
                + turning[0].words().split(",")[0] + (" and similar" if len(turning) > 1 else ""))
    free = _motions(d, "frictionless")
    if free and ms:
        u = free[-1].speed
        own = min(ms, key=lambda m: abs(m.speed - u))
        if abs(own.speed - u) < 1e-6:
            txt += (f". At {kmh(u)} the pin friction {friction_role(own, free[-1])}: without it the chair "
                    f"{free[-1].words()}")
    return txt + "."


def _paths(d: ReportData) -> str:
    ms = _motions(d, "paths")
    m = ms[0]
    txt = f"After the push at {kmh(m.speed)} (stick-slip pin friction) the chair {m.words()}: {m.where()}"
    if len(ms) > 1:
        o = ms[1]
        txt += f"; with its casters at the other end the same chair {o.words()}: {o.where()}"
    front = [x for x, r in zip(ms, d.paths.responses, strict=False) if r.chair.caster_position == "front"]
    if front and front[0].kind == "keeps turning":
        txt += (". The thesis's Figure 8-4b shows its front-caster chair returning to straight-line motion; here "
                "the turn persists")
    return txt + "."


def _equal(d: ReportData) -> str:
    cs = d.chair_speed
    if cs.status != "found":
        return (f"This chair never matches the reference instability within {cs.bracket[0]:g}-{cs.bracket[1]:g} m/s "
                f"({cs.describe()}).")
    iv = d.intervals
    rng = interval_words(iv)
    if d.chair.name == REFERENCE_CHAIR:
        txt = (f"This is the thesis's reference chair: at {kmh(REFERENCE_SPEED)} it defines the reference case, so "
               "its own bar is the reference speed by construction; the other bars show what a change would buy.")
        if iv is not None and rng:
            txt += (f" The {iv.chair_name} design reaches the reference instability at {sig3(iv.point.speed)} m/s "
                    f"({rng}).")
        return txt
    txt = (f"This chair is as unstable at {kmh(cs.speed)} as the {REFERENCE_CHAIR} is at {kmh(REFERENCE_SPEED)}: "
           "the higher this speed, the more stable the chair")
    return txt + (f" ({rng})." if rng else ".")


def _sweeps(d: ReportData) -> str:
    ranked = [s for s in d.chair_sweeps.ranked() if s.effect_percent > 1.0][:3]
    if not ranked:
        return "No parameter tried moves the equal-instability speed by more than 1 %."
    return ("The parameters that move the equal-instability speed most: "
            + "; ".join(f"{s.label} ({s.effect_percent:.0f} % over {s.value_text(0)}-{s.value_text(len(s.values) - 1)}"
                        + ("" if s.unit == "-" else f" {s.unit}") + ")" for s in ranked)
            + ". The rest matter less.")


def _maps(d: ReportData) -> str:
    fm = d.friction_map
    j = int(np.argmax(fm.y_values))
    ok = fm.speeds[~(fm.times[j] < fm.reference_time)]
    edge = float(ok.max()) >= float(np.max(fm.speeds)) - 1e-9 if len(ok) else False
    top = (f"with {fm.y_values[j]:g} N m of pin friction the chair stays below the reference instability "
           + (f"at every speed of the map (up to its edge, {kmh(float(ok.max()))}; the equal-instability search "
              "gives the speed itself)" if edge else f"up to {kmh(float(ok.max()))}") if len(ok) else
           f"even {fm.y_values[j]:g} N m of pin friction does not keep it below the reference instability")
    return f"More pin friction or a smaller push moves the line to higher speeds: {top}."


def _slope(d: ReportData) -> str:
    s = d.slope
    if s is None or s.per_degree is None:
        return "No cross-slope result for this chair."
    return (f"On a cross slope the user must hold {s.per_degree:.3g} N m per degree of slope to go straight at "
            f"{kmh(s.speed)}; uncorrected, the chair turns " + (s.path.turn if s.path is not None else "off its line")
            + ".")


def _shimmy(d: ReportData) -> str:
    s = d.shimmy
    if s is None:
        return "No shimmy result for this chair."
    crit = [x[2] for x in s.corners]
    a = d.advice
    return (f"Caster shimmy: {shimmy_sentence(a.verdict, d.chair.trail, a.shimmy_hold)}. The boundary lies at "
            f"{100 * s.critical:.3g} cm with the estimated caster compliance (the same at every speed without viscous "
            f"pin damping; computed at {s.speed:g} m/s), and anywhere from {100 * min(crit):.3g} cm "
            + ("to beyond 25 cm (shimmy at every trail checked)" if not math.isfinite(max(crit))
               else f"to {100 * max(crit):.3g} cm")
            + " over the estimates' range: measure the caster's compliance before changing the trail.")


def _uncertainty(d: ReportData) -> str:
    u = d.uncertainty
    if u is None:
        return "Point values only: no uncertainty file was given."
    lo, hi = u.rate_at(REFERENCE_SPEED)
    dom = u.dominant
    return (f"With the stated parameter uncertainty the growth rate at {REFERENCE_SPEED:g} m/s lies in {lo:.3g}-"
            f"{hi:.3g} 1/s" + (f", most of the spread from {dom[0]}" if dom is not None else "") + ".")


def _comparison(d: ReportData) -> str:
    b = d.baseline
    if b is None:
        return ""
    rows = [r for r in comparison_rows(*report_key_numbers(d)) if not r[0].startswith(RESTATED)]
    wins = [r for r in rows if r[4] == "this chair"]
    losses = [r for r in rows if r[4] == "baseline"]
    txt = f"{d.chair.name} is better than {b.chair.name} on {len(wins)} of {len(rows)} measures"
    if losses:
        txt += "; worse on " + ", ".join(f"{r[0].split(' (')[0]} ({r[3]})" for r in losses)
    return txt + " (the doubling time restates the growth rate and is not counted again)."


def _trail_window(d: ReportData) -> str:
    w = d.trail_window
    if w is None:
        return ""
    where = {"robust": "inside the shimmy-free window for every estimate of the caster's compliance",
             "nominal": "shimmy-free with the nominal estimates only: measure the caster's compliance first",
             "outside": "inside a shimmy zone"}[w.chair_in_window]
    txt = f"This chair's {100 * w.chair_trail_m:.3g} cm trail is {where}."
    near = w.nearest_safe_m
    if near is None:
        return txt + " No trail is shimmy-free at every use speed with the nominal estimates."
    if w.chair_in_window == "outside":
        txt += f" The nearest shimmy-free trail is {100 * near:.3g} cm (nominal estimates)."
    best = w.best_in_window()
    if best is not None and not any(bool(f) for f in w.found):
        txt += (f" Every trail of the study is a bound (> {best[1]:.3g} m/s): the chart cannot rank trails for "
                "directional stability, only place them against the shimmy zones.")
    elif best is not None:
        t, u, found = best
        txt += (f" Of the study's trails in the window, {100 * t:.3g} cm gives the highest equal-instability speed, "
                f"{'' if found else '> '}{u:.3g} m/s.")
    if not w.robust_m:
        txt += " No trail is shimmy-free over the whole estimate range."
    return txt


def _conclusions(d: ReportData) -> str:
    v = [c.verdict for c in d.conclusions]
    txt = (f"On the thesis's own chairs our numbers agree with {v.count('agree')} of its nine conclusions, partly "
           f"with {v.count('partly')} and disagree with {v.count('disagree')}")
    own = [c.chair_verdict for c in d.conclusions if c.chair_verdict]
    if own:
        counts = {k: own.count(k) for k in dict.fromkeys(own)}
        txt += (f"; on {d.chair.name} the design conclusions come out "
                + ", ".join(f"{k} {n}" for k, n in counts.items()))
    return txt + "; the evidence column says why."


#: Page title -> caption function (pages without one are text pages).
CAPTIONS: dict[str, Callable[[ReportData], str]] = {
    "comparison": _comparison,
    "chair parameters and geometry": _chair,
    "tires": _tires,
    "linear stability: critical speeds": _linear,
    "eigenvalues as speed varies": _linear,
    "eigenvalues against speed": _linear,
    "growth rate against design parameters": _growth,
    "yaw-rate feedback root locus": _gain,
    "nonlinear yaw-rate responses": _responses,
    "paths": _paths,
    "equal-instability speeds": _equal,
    "parametric study": _sweeps,
    "parametric study table": _sweeps,
    "stability maps": _maps,
    "cross slope": _slope,
    "trail design chart": _trail_window,
    "caster shimmy": _shimmy,
    "parameter uncertainty": _uncertainty,
    "thesis conclusions": _conclusions,
}


def caption(d: ReportData, title: str) -> str | None:
    """The concluding caption of the page ``title`` (None for text-only pages).

    Parameters
    ----------
    d : ReportData
    title : str
        A page title of :func:`stability.report.builders.page_builders`.

    Returns
    -------
    str or None
    """
    f = CAPTIONS.get(title)
    return None if f is None else "What to conclude: " + f(d)
