"""The advisor's decision, stated once: the sentences the advise command, its JSON and the report's page 1 print.

:func:`decide` turns an :class:`~stability.advise.advisor.Advice` into a :class:`Decision`: the verdict, what to do,
what it costs (before -> after for every tip direction, the shimmy margin, the turning effort and the cross-slope
drive difference, each against its limit), why (the advisor's notes), what a limit blocks and the runner-up.
Every renderer (``advise.text``, ``report.decision``, the app) prints these strings; none rephrases them, so the
command, the JSON and the report cannot disagree.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from stability.advise.advisor import Advice, Blocked, Candidate
from stability.advise.limits import allow_words, constraint_text, limit_words, shimmy_sentence
from stability.advise.measures import EFFORT_WORDS, Measures
from stability.bench.loads import SCORE_WORDS
from stability.layout.model import Layout
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.shimmy.band import margin_cell
from stability.study.censored import describe, range_words, side_of

__all__ = ["Cost", "Decision", "decide", "kmh", "DIRECTION_WORDS"]

#: The four ISO 7176-1 tip directions in words: the short form's, then a wheel layout's
#: (:func:`stability.layout.statics.tip_angles`).
DIRECTION_WORDS = {"toward_main_wheels": "toward its main wheels", "toward_casters": "toward its casters",
                   "lateral_left": "over its left side", "lateral_right": "over its right side",
                   "forward": "toward its front", "backward": "toward its back", "left": "over its left side",
                   "right": "over its right side"}


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


@dataclass(frozen=True)
class Cost:
    """One quantity before and after the change, with its limit where it has one.

    Attributes
    ----------
    name : str
        Key with unit suffix (``tip_toward_casters_deg``, ``shimmy_margin_m``, ...).
    words : str
        What it is, in words.
    unit : str
        Display unit (``deg``, ``cm``, ``N m``, ``N``).
    before, after : float or None
        In the display unit (None: not computed, e.g. the slope statics refuse the chair).
    limit : str
        The limit in words (``">= 13.8 deg"``), empty when the quantity has none.
    met : bool or None
        Whether ``after`` meets the limit (None: no limit).
    higher_is_better : bool
        Direction of the quantity (a tip angle, a shimmy margin: higher; an effort: lower).
    """

    name: str
    words: str
    unit: str
    before: float | None
    after: float | None
    limit: str = ""
    met: bool | None = None
    higher_is_better: bool = True

    @property
    def worse(self) -> bool:
        """The change makes it worse (or it cannot be computed after the change)."""
        if self.after is None:
            return self.before is not None
        if self.before is None:
            return False
        return self.after < self.before if self.higher_is_better else self.after > self.before

    def text(self) -> str:
        """``"tips toward its casters on 21.9 -> 17.7 deg (limit >= 13.8 deg, met)"``."""
        def f(x: float | None) -> str:          # an infinity: a shimmy margin (cm) with no boundary, or every trail
            if x is None:
                return "not computed"
            return f"{x:.3g}" if math.isfinite(x) else margin_cell(x)

        change = f(self.before) if self.before == self.after else f"{f(self.before)} -> {f(self.after)}"
        lim = "" if not self.limit else f" (limit {self.limit}, {'met' if self.met else 'NOT met'})"
        return f"{self.words} {change}{' ' + self.unit if self.unit else ''}{lim}"

    def to_mapping(self) -> dict:
        """JSON-ready dict: ``before`` and ``after`` in the unit of the name's suffix (a shimmy margin in m, not cm)."""
        scale = 0.01 if self.unit == "cm" else 1.0

        def si(x: float | None) -> float | None:
            return None if x is None or not math.isfinite(x) else scale * x     # JSON: an infinity as null

        return {"name": self.name, "before": si(self.before), "after": si(self.after), "limit": self.limit or None,
                "met": self.met}


@dataclass(frozen=True)
class Decision:
    """What the advisor decided, in the words every output prints.

    Attributes
    ----------
    chair : str
    action : {"change", "keep", "measure first", "none"}
        Change the chair; keep it (nothing helps); keep it and measure the estimated inputs first (it breaks a
        limit that rests on estimates and nothing fixes it cheaply); no change meets every limit.
    verdict : tuple of str
        The chair as it is: push, time to correct, equal instability, shimmy.
    details : tuple of str
        The rest of the verdict: static stability in every direction, the linear model, the cross slope (page 1
        of the report shows them in its table).
    recommendation : str
        What to do, in one sentence.
    costs : tuple of Cost
        Before -> after of every tip direction, the shimmy margin, the turning effort and the cross-slope drive
        difference (for ``keep`` and ``measure first``: the chair against its limits).
    why : tuple of str
        The advisor's notes on the recommendation.
    blocked : tuple of str
        One sentence per change a limit blocks: what it buys, the limit, its value, the option that allows it.
    runner_up : str or None
        The runner-up in one sentence (None: there is none).
    """

    chair: str
    action: str
    verdict: tuple
    details: tuple
    recommendation: str
    costs: tuple
    why: tuple
    blocked: tuple
    runner_up: str | None

    def paragraphs(self) -> list[str]:
        """The decision as headed paragraphs (``VERDICT.``, ``RECOMMENDATION.``, ``WHAT IT COSTS.`` or
        ``LIMITS.``, ``WHY.``, ``BLOCKED BY A LIMIT.``, ``RUNNER-UP.``): page 1 of the report."""
        out = ["VERDICT. " + " ".join(self.verdict), "RECOMMENDATION. " + self.recommendation]
        out.append(self.cost_sentence())
        if self.why:
            out.append("WHY. " + " ".join(self.why))
        if self.blocked:
            out.append("BLOCKED BY A LIMIT. " + " ".join(self.blocked))
        if self.runner_up:
            out.append("RUNNER-UP. " + self.runner_up)
        return out

    def cost_sentence(self) -> str:
        """``WHAT IT COSTS.`` (what the change makes worse, against its limit) or ``LIMITS.`` (what the chair as it
        is breaks)."""
        if self.action == "change":
            worse = [c.text() for c in self.costs if c.worse]
            return "WHAT IT COSTS. " + ("; ".join(worse) if worse else "nothing: every quantity with a limit "
                                        "stays or gets better") + "."
        unmet = [c.text() for c in self.costs if c.met is False]
        return "LIMITS. " + ("The chair breaks: " + "; ".join(unmet) if unmet else "The chair meets every limit") + "."

    def to_mapping(self) -> dict:
        """JSON-ready dict (``paragraphs`` is what page 1 prints)."""
        return {"chair": self.chair, "action": self.action, "verdict": list(self.verdict),
                "details": list(self.details),
                "recommendation": self.recommendation, "costs": [c.to_mapping() for c in self.costs],
                "why": list(self.why), "blocked": list(self.blocked), "runner_up": self.runner_up,
                "paragraphs": self.paragraphs()}


def _direction(a: Advice) -> tuple[str, str, bool]:
    """``(" backwards" or "", what the ranges are over, whether it is the reference case)`` of the advice."""
    layout = isinstance(a.chair, Layout)
    reverse = any(u < 0 for u in a.speeds_m_s)
    over = "pin friction and simulator step" if layout else "pin friction, model and simulator step"
    return (" backwards" if reverse else ""), over, a.chair.name == REFERENCE_CHAIR and not reverse


def _verdict(a: Advice) -> tuple:
    m = a.verdict
    ci, ei = m.critical_impulse_Ns, m.equal_instability_speed_m_s
    back, over, reference = _direction(a)
    out = []
    if m.critical_impulse_status == "never":
        out.append(f"At {kmh(REFERENCE_SPEED)}{back} not even a sideways push of {ci.value:.2g} N s at the seat (the "
                   "largest tried) turns the chair to 1 rad/s within 10 s: it does not spin up (a slow steady turn is "
                   "not excluded by this measure).")
    else:
        rng = range_words(ci.low, ci.high, "N s", over, digits=2)
        out.append(f"At {kmh(REFERENCE_SPEED)}{back} a sideways push of {ci.value:.2g} N s{rng} at the seat (about "
                   f"{(ci.value or 0.0) / THESIS_PUSH.duration:.0f} N for a tenth of a second) turns "
                   "the chair until it spins at 1 rad/s (57 deg/s) within 10 s unless "
                   "the user steers.")
    times = [f"{t:.2g} s at {u:g} m/s" if t is not None else f"more than 10 s at {u:g} m/s"
             for u, t in zip(a.speeds_m_s, a.time_to_correct_s, strict=False)]
    if times:
        out.append(f"After the thesis's reference push ({THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s) the "
                   f"user has {', '.join(times)} to correct before it turns at 1 rad/s.")
    if reference:
        out.append(f"It is the thesis's reference chair: other chairs' equal-instability speeds are measured against "
                   f"it at {kmh(REFERENCE_SPEED)}.")
    else:
        where = {"found": f"at {kmh(ei.value or 0.0)}", "above": f"only above {kmh(ei.value or 0.0)}",
                 "below": f"already below {kmh(ei.value or 0.0)}"}[m.equal_instability_status] + back
        rng = range_words(ei.low, ei.high, "m/s", f"push size, {over}")
        out.append(f"It is as unstable as the thesis's reference case ({REFERENCE_CHAIR} at {REFERENCE_SPEED:g} m/s) "
                   f"{where}{rng}; faster than that it gives the user less time than the reference case.")
    if isinstance(a.chair, Layout):
        row = f" ({m.shimmy_row} casters, the row nearest a shimmy boundary)" if m.shimmy_row else ""
        out.append(f"Caster shimmy{row}: {shimmy_sentence(m, m.shimmy_trail_m or 0.0, a.shimmy_hold)}."
                   if m.shimmy_row else "Caster shimmy: the layout has no casters.")
    else:
        out.append(f"Caster shimmy: {shimmy_sentence(m, a.chair.trail, a.shimmy_hold)}.")
    if a.driver is not None and m.human_speed_m_s is not None and a.intended_speed_m_s is not None:
        u = m.human_speed_m_s
        where = (f"beyond {u:g} m/s, the fastest speed checked" if m.human_side == ">" else
                 f"up to {u:.3g} m/s ({3.6 * u:.1f} km/h)")
        verdict = "enough" if u >= a.intended_speed_m_s else "NOT enough"
        out.append(f"Driver: a driver who corrects the heading {a.driver.reaction_time_s:g} s late can hold this chair "
                   f"straight {where} (divergence rule, linear); {verdict} for the intended "
                   f"{a.intended_speed_m_s:g} m/s.")
    return tuple(out)


def _details(a: Advice) -> tuple:
    m = a.verdict
    out = []
    worst = min(m.tip_angles_deg, key=lambda k: m.tip_angles_deg[k])
    out.append(f"Static stability: it tips {DIRECTION_WORDS[worst]} on a {m.static_stability_deg.value:.1f} deg slope "
               "(rigid chair, brakes locked, casters in their worst swivel position); "
               + ", ".join(f"{DIRECTION_WORDS[k].split(' ', 1)[1]} {v:.1f}" for k, v in m.tip_angles_deg.items())
               + " deg.")
    out.append(f"Linear model (free, frictionless casters): the heading error grows at {m.growth_rate_1_s:.3g} 1/s at "
               f"{REFERENCE_SPEED:g} m/s; it has no pin friction, so where it disagrees with the push and speed "
               "measures (which include the pins' Coulomb friction) those decide.")
    if m.bench_score is not None:
        out.append(f"Virtual ISO 7176-2 bench (default drive settings, quasi-static): worst wheel-lift score "
                   f"{m.bench_score}, {SCORE_WORDS[m.bench_score]} (python -m stability.bench; docs/bench.md).")
    if m.cross_slope_effort is not None and a.cross_slope_deg:
        what = ("one hand rim must push {:.0f} N harder than the other" if m.drive == "handrim" else
                "one drive motor must give {:.2g} N m more torque than the other")
        out.append(f"On a {a.cross_slope_deg:g} deg cross slope at {REFERENCE_SPEED:g} m/s "
                   + what.format(abs(m.cross_slope_effort)) + " to hold the line.")
    return tuple(out)


def _costs(a: Advice, c: Candidate) -> tuple:
    """Before -> after of every quantity a change can cost, each with its limit (from the candidate's constraints)."""
    base, m = a.verdict, c.measures
    lim = {k.name: k for k in c.constraints}
    out = []
    smallest = lim.get("static_stability_deg")
    for key, words in DIRECTION_WORDS.items():
        if key not in base.tip_angles_deg and key not in m.tip_angles_deg:
            continue                                     # the other form's directions
        before, after = base.tip_angles_deg.get(key), m.tip_angles_deg.get(key)
        limit = f">= {smallest.limit:.1f} deg" if smallest is not None else ""
        met = None if after is None or smallest is None else after >= smallest.limit - 1e-9
        out.append(Cost(f"tip_{key}_deg", f"tips {words} on", "deg", before, after, limit, met))
    sm = lim.get("shimmy_margin_m")

    def cm(x: float | None) -> float | None:
        return None if x is None else 100 * x

    if sm is not None:
        out.append(Cost("shimmy_margin_m", "shimmy margin", "cm", cm(base.shimmy_margin_m.value),
                        cm(m.shimmy_margin_m.value), f">= {100 * sm.limit:g} cm", sm.met))
    te = lim.get("turning_effort_N_m")
    if te is not None:
        out.append(Cost("turning_effort_N_m", "pin friction to overcome when turning", "N m",
                        base.turning_effort_N_m, m.turning_effort_N_m, f"<= {te.limit:.3g} N m", te.met, False))
    hs = lim.get("human_limited_speed_m_s")
    if hs is not None:
        out.append(Cost("human_limited_speed_m_s", "speed the driver can hold (driver limit)", "m/s",
                        base.human_speed_m_s, m.human_speed_m_s, f">= {hs.limit:.3g} m/s (the intended speed)",
                        hs.met))
    bs = lim.get("bench_worst_score")
    if bs is not None:
        out.append(Cost("bench_worst_score", "worst wheel-lift score on the ISO 7176-2 bench (0-3)", "",
                        base.bench_score, m.bench_score, f"<= {bs.limit:g}", bs.met, False))
    eff = lim.get(m.effort_key)
    if eff is not None:
        words, unit = EFFORT_WORDS[m.drive]

        def mag(x: float | None) -> float | None:
            return None if x is None else abs(x)

        out.append(Cost(m.effort_key, f"{words} on a {a.cross_slope_deg:g} deg cross slope", unit,
                        mag(base.cross_slope_effort), mag(m.cross_slope_effort),
                        "" if not math.isfinite(eff.limit) else f"<= {eff.limit:.3g} {unit}", eff.met, False))
    return tuple(out)


def _predicted(m: Measures) -> str:
    ci = describe(m.critical_impulse_Ns.value or math.nan, side_of(m.critical_impulse_status), digits=3)
    ei = describe(m.equal_instability_speed_m_s.value or math.nan, side_of(m.equal_instability_status), digits=3)
    rng = m.critical_impulse_Ns
    r = range_words(rng.low, rng.high, "N s")
    return f"critical impulse {ci} N s{r}, equal-instability speed {ei} m/s"


def _blocked_sentence(b: Blocked) -> str:
    c = b.candidate
    buys = ("fixes the " + ", ".join(limit_words(n) for n in b.fixes) + " and " if b.fixes else "") + \
        (f"gains {c.gain * 100:.0f} %" if c.gain >= 0 else f"costs {-c.gain * 100:.0f} %")
    limits = "; ".join(constraint_text(k) for k in b.limits)
    allowed = "; ".join(allow_words(k) for k in b.limits)
    return f"{c.label[0].upper() + c.label[1:]} {buys} on the robust measures, but {limits}; {allowed}."


def decide(a: Advice) -> Decision:
    """The decision in :class:`Decision`'s words, from the advice alone.

    Parameters
    ----------
    a : Advice

    Returns
    -------
    Decision
    """
    verdict, details = _verdict(a), _details(a)
    blocked = tuple(_blocked_sentence(b) for b in a.blocked)
    if not a.recommendations:
        own = Candidate((), a.verdict, 0.0, {}, a.own_constraints)
        return Decision(a.chair.name, "none", verdict, details,
                        "None: the chair breaks a limit and no change of any lever, nor any pair of two levers, meets "
                        "every limit" + (" (see BLOCKED BY A LIMIT)" if blocked else "") + ".",
                        _costs(a, own), (), blocked, None)
    r = a.recommendations[0]
    c = r.candidate
    broken_names = [k.name for k in c.constraints if not k.met] if not c.changes else []
    broken = [limit_words(n) for n in broken_names]
    if c.changes:
        action = "change"
        rec = (f"{c.label[0].upper() + c.label[1:]}. Judged on the low ends of "
               f"the ranges it changes the critical impulse by {100 * c.gains['critical_impulse']:+.0f} % and the "
               f"equal-instability speed by {100 * c.gains['equal_instability_speed']:+.0f} %: predicted "
               f"{_predicted(c.measures)}.")
        worst_before = min(a.verdict.tip_angles_deg, key=lambda k: a.verdict.tip_angles_deg[k])
        worst_after = min(c.measures.tip_angles_deg, key=lambda k: c.measures.tip_angles_deg[k])
        if worst_after != worst_before:
            t = c.measures.tip_angles_deg
            rec += (f" The weakest tip direction becomes {DIRECTION_WORDS[worst_after].split(' ', 1)[1]} "
                    f"({a.verdict.tip_angles_deg[worst_after]:.1f} -> {t[worst_after]:.1f} deg).")
    elif "shimmy_margin_m" in broken_names and a.verdict.shimmy_straddles:
        action = "measure first"
        rec = ("No change yet: measure the pin lateral stiffness and the caster relaxation length first; the chair "
               f"breaks the limit on {', '.join(broken)} on estimates, and no change fixes it cheaply.")
    else:
        action = "keep"
        rec = ("No change: " + (f"the chair breaks the limit on {', '.join(broken)} and nothing fixes it cheaply."
                                if broken else "no change meets every limit and improves the chair."))
    runner = None
    if len(a.recommendations) > 1:
        rc = a.recommendations[1].candidate
        runner = (f"{rc.label[0].upper() + rc.label[1:]}, {100 * rc.gain:+.0f} % on the low ends: predicted "
                  f"{_predicted(rc.measures)}.")
    return Decision(a.chair.name, action, verdict, details, rec, _costs(a, c), tuple(r.notes), blocked, runner)
