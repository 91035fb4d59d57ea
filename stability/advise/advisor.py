"""The advisor: verdict, levers, and the recommended change judged on the low end of its intervals.

Method (docs/advise.md): measure the chair and every single change of every lever
(:mod:`.levers`) in one batch (:func:`.measures.measure_chairs`); a change's robust gain is the
smaller of its relative gains in the *low ends* of the critical-impulse and equal-instability
intervals, so a change one measure contradicts gains nothing.  The pairs of single changes of two
levers are ranked by the gain their two changes predict together (the product of their relative
changes) and checked in that order on the constraints alone (statics, shimmy band, cross slope: no
simulation, :func:`.measures.linear_measures`) as far as the choice reaches; the best that meet every
limit, with the triple of the three best levers, are measured.  The recommendation is the best measured change that
meets every limit, with the runner-up; a change that would be better but is blocked by a limit is
named with that limit, its value and the option that would allow it.

Screening (:mod:`.pruning`, the default for a chair): the chair is measured with its intervals, every change at
x0.5 pin friction only (one run per measure); a change's intervals are computed only when these runs (an upper
bound of its robust gain: an interval's low end is never above any of its variants) let it reach one of the
advisor's choices, so the decision is the one ``prune=False`` (every interval computed) gives.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from stability.advise.combinations import BLOCKED_BUDGET as BLOCKED_BUDGET  # re-exported: the combination filter
from stability.advise.combinations import (
    MAX_FIX_COST,
    PAIR_BUDGET,
    _screen,
    _settle_choice,
)
from stability.advise.combinations import _pairs as _pairs
from stability.advise.combinations import _predicted as _predicted
from stability.advise.levers import LEVERS
from stability.advise.limits import (
    HANDRIM_FACTOR,
    MAX_PIN_FRICTION_N_M,
    MIN_SHIMMY_MARGIN_M,
    SHIMMY_AMPLITUDE_DEG,
    Constraint,
    ShimmyHold,
    allow,
    limit_words,
    shimmy_sentence,
)
from stability.advise.limits import constraints as constraints_of
from stability.advise.limits import meets as meets_of
from stability.advise.measures import LazyLinear, Linear, Measures, nonlinear_measures, screening_measures
from stability.advise.pruning import Pool, screening_of
from stability.advise.subject import lever_changes, measure_chairs, shimmy_hold, use_speeds
from stability.advise.subject import time_to_correct as correct_time
from stability.chair import Chair
from stability.chair.model import check_chair
from stability.driver.model import Driver
from stability.layout.model import Layout
from stability.runtime.checks import first_argument
from stability.settings import defaults as D
from stability.settings.bounds import ADVISE_CROSS_SLOPE, HUMAN_SPEED, MIN_TIP_ANGLE
from stability.settings.reference import REFERENCE_SPEED
from stability.shimmy.band import margin_words
from stability.study.memo import memo_searches
from stability.tires import summarised_warnings

__all__ = ["Constraint", "Candidate", "Recommendation", "Blocked", "ShimmyHold", "Advice", "advise",
           "MAX_PIN_FRICTION_N_M", "MAX_FIX_COST", "MIN_SHIMMY_MARGIN_M", "HANDRIM_FACTOR", "DEFAULT_SPEEDS",
           "DEFAULT_CROSS_SLOPE_DEG", "PAIR_BUDGET", "SHIMMY_AMPLITUDE_DEG"]

#: Default use speeds (m/s): :data:`stability.settings.defaults.ADVISE_SPEEDS` (0.5:1:0.25).
DEFAULT_SPEEDS = (0.5, 0.75, 1.0)
#: Default cross slope for the hand-rim force (deg): :data:`stability.settings.defaults.ADVISE_CROSS_SLOPE_DEG`.
DEFAULT_CROSS_SLOPE_DEG = D.ADVISE_CROSS_SLOPE_DEG


@dataclass(frozen=True)
class Candidate:
    """A measured change (single or combined).

    Attributes
    ----------
    changes : tuple of Change
        The single changes it is made of.
    measures : Measures
        The changed chair's measures.
    gain : float
        Robust gain: min of the relative gains of the low ends of critical impulse and equal-instability speed.
    gains : dict
        The two relative gains (``critical_impulse``, ``equal_instability_speed``).
    constraints : tuple of Constraint
    bounded : bool
        The intervals were not computed (:mod:`.pruning`): ``measures`` holds, as the low ends, the screening
        run's upper bounds of them (:func:`.measures.screening_measures`; no nominal value, high ends None), and
        ``gain``/``gains`` are upper bounds of the robust gains, below what the advisor chose.
    """

    changes: tuple
    measures: Measures
    gain: float
    gains: dict
    constraints: tuple
    bounded: bool = False

    @property
    def feasible(self) -> bool:
        """Every constraint met."""
        return all(c.met for c in self.constraints)

    @property
    def fields(self) -> dict:
        """Chair field -> new value, all single changes merged."""
        out: dict = {}
        for ch in self.changes:
            out.update(ch.fields)
        return out

    @property
    def label(self) -> str:
        """The change in words (``"no change"`` for the chair as it is)."""
        return " + ".join(ch.label for ch in self.changes) or "no change"


@dataclass(frozen=True)
class Recommendation:
    """A recommended change.

    Attributes
    ----------
    rank : int
        1 (recommended) or 2 (runner-up).
    candidate : Candidate
    built_from : tuple of Candidate
        The single changes it combines, each measured alone (empty for a single change).
    notes : tuple of str
        Where the measures disagree and why (linear vs nonlinear), and flags.
    """

    rank: int
    candidate: Candidate
    built_from: tuple
    notes: tuple

    def to_mapping(self) -> dict:
        """JSON-ready dict: ``change``, ``set``, ``predicted``, ``constraints`` ..."""
        c = self.candidate
        return {"rank": self.rank, "label": c.label, "change": c.fields,
                "set": [a for ch in c.changes for a in ch.assignments], "robust_gain": c.gain,
                "gains": c.gains, "predicted": c.measures.to_mapping(),
                "constraints": [k.to_mapping() for k in c.constraints],
                "built_from": [{"label": b.label, "change": b.fields, "robust_gain": b.gain,
                                "predicted": b.measures.to_mapping()} for b in self.built_from],
                "notes": list(self.notes)}


@dataclass(frozen=True)
class Advice:
    """The advisor's answer for one chair.

    Attributes
    ----------
    chair : Chair or Layout
        The chair, or the wheel layout (:mod:`.subject`).
    speeds_m_s : tuple of float
        Use speeds (m/s; negative: a layout in reverse).
    cross_slope_deg : float
    min_tip_deg : float
        The static stability limit applied (deg).
    min_tip_source : str
        Where it comes from.
    verdict : Measures
        The chair as it is.
    time_to_correct_s : tuple of float or None
        Per use speed: time after the thesis's 40 N, 0.1 s push until |yaw rate| reaches 1 rad/s (s; None: never).
    candidates : tuple of Candidate
        Every measured single change, lever by lever.
    combinations : tuple of Candidate
    refused : tuple of (Change, str)
        Changes the chair refuses, with the reason.
    recommendations : tuple of Recommendation
        Recommended and runner-up (fewer, or none, when too few changes help and meet every constraint).
    reason : str
        Why there is no recommendation (empty when there is one).
    blocked : tuple of Blocked
        Measured changes better than the recommendation (or fixing what the chair breaks) that a limit
        blocks, best first.
    shimmy_hold : ShimmyHold or None
        What the chair's own pin friction buys against shimmy (None: no pin friction).
    pairs_screened, pairs_measured : int
        Pairs of changes checked on the constraints (in the order of their predicted gain, as far as the choice
        reaches), and measured by simulation.
    own_constraints : tuple of Constraint
        The chair as it is against every limit (what it already breaks).
    driver : Driver or None
        The user whose reaction time the human-limited speed constraint uses.
    intended_speed_m_s : float or None
        The speed that driver must be able to hold, m/s.
    intervals_computed : int
        Changes (single or combined) whose intervals were computed; the others are bounded (:mod:`.pruning`).
    """

    chair: Chair | Layout
    speeds_m_s: tuple
    cross_slope_deg: float
    min_tip_deg: float
    min_tip_source: str
    verdict: Measures
    time_to_correct_s: tuple
    candidates: tuple
    combinations: tuple
    refused: tuple
    recommendations: tuple
    reason: str
    blocked: tuple = ()
    shimmy_hold: ShimmyHold | None = None
    pairs_screened: int = 0
    pairs_measured: int = 0
    own_constraints: tuple = ()
    driver: Driver | None = None
    intended_speed_m_s: float | None = None
    intervals_computed: int = 0


@dataclass(frozen=True)
class Blocked:
    """A change a limit blocks: better than the recommendation, or fixing what the chair breaks.

    Attributes
    ----------
    candidate : Candidate
    limits : tuple of Constraint
        The constraints it does not meet (value, limit, source).
    fixes : tuple of str
        Constraints the chair breaks that it meets.
    allow : str
        What would allow it (an option, or why no option can).
    """

    candidate: Candidate
    limits: tuple
    fixes: tuple
    allow: str

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"label": self.candidate.label, "change": self.candidate.fields, "robust_gain": self.candidate.gain,
                "blocked_by": [k.to_mapping() for k in self.limits], "fixes": list(self.fixes),
                "allow": self.allow}


def _gain(m: Measures, base: Measures) -> tuple[float, dict]:
    def rel(new: float | None, old: float | None) -> float:
        if new is None or old is None or old <= 0:
            return -math.inf
        return new / old - 1.0

    g = {"critical_impulse": rel(m.critical_impulse_Ns.robust, base.critical_impulse_Ns.robust),
         "equal_instability_speed": rel(m.equal_instability_speed_m_s.robust, base.equal_instability_speed_m_s.robust)}
    return min(g.values()), g


#: Relative rise of the linear growth rate above which a change that helps gets the linear-vs-nonlinear note.
RATE_NOTE_RISE = 0.005
#: Relative difference between the critical impulse at 1 ms and at half the step above which the step is noted.
STEP_NOTE_DIFFERENCE = 0.1


def _step_note(m: Measures) -> str | None:
    """A note when the critical impulse moves by more than :data:`STEP_NOTE_DIFFERENCE` at half the step."""
    j, half = m.critical_impulse_Ns.value, m.critical_impulse_half_step_Ns
    if j is None or half is None or m.critical_impulse_status != "found":
        return None
    if abs(half - j) <= STEP_NOTE_DIFFERENCE * max(abs(half), abs(j)):
        return None
    return (f"Simulator step: at half of program WCHAIR's 1 ms step the critical impulse is {half:.3g} N s, against "
            f"{j:.3g} N s at 1 ms. The fixed step resolves this chair's stiff caster modes coarsely, so the 1 ms value "
            "is uncertain; the range includes both, and the adaptive scheme (--scheme adaptive) has no fixed step.")


def _notes(c: Candidate, base: Measures, chair: Chair | Layout) -> tuple:
    m = c.measures
    notes = []
    if m.growth_rate_1_s > base.growth_rate_1_s * (1 + RATE_NOTE_RISE) and c.gain > 0 and isinstance(chair, Chair):
        s_peak = math.sqrt(chair.i_z / chair.m)
        notes.append(
            f"The frictionless linear growth rate gets worse ({base.growth_rate_1_s:.3g} -> {m.growth_rate_1_s:.3g} "
            f"1/s at {REFERENCE_SPEED:g} m/s) while the push and speed measures improve: the linear model's casters "
            "are free and frictionless, and its divergent rate, about U m s1/(I_z + m s1^2), peaks at s1 = "
            f"sqrt(I_z/m) = {s_peak:.3g} m; the pins' Coulomb friction, which the nonlinear measures include, holds "
            "the casters straight after a small push.")
    step = _step_note(m)
    if step:
        notes.append(step)
    if m.shimmy_straddles and c.changes:
        own = m.shimmy_trail_m if m.shimmy_trail_m is not None or not isinstance(chair, Chair) else chair.trail
        trail = float(dict(c.fields).get("trail", own) or 0.0)
        now = base.shimmy_margin_m.value             # the chair as it is (the verdict's margin), so the two differ
        was = ("" if now is None else f" As it is, the margin is {100 * now:+.2f} cm." if math.isfinite(now) else
               f" As it is: {margin_words(now)}.")
        notes.append(f"Shimmy with the change: {shimmy_sentence(m, trail)}.{was}")
    return tuple(notes)


def _blocked(cands: list[Candidate], broken: set, best_gain: float) -> list[Blocked]:
    """Measured changes a limit blocks that beat the recommendation or fix what the chair breaks, best first."""
    out = []
    for c in cands:
        if c.feasible or not c.changes:
            continue
        unmet = tuple(k for k in c.constraints if not k.met)
        fixes = tuple(sorted(k.name for k in c.constraints if k.met and k.name in broken))
        if c.gain > best_gain or fixes:
            out.append(Blocked(c, unmet, fixes, "; ".join(allow(k) for k in unmet)))
    return sorted(out, key=lambda b: (-len(b.fixes), len(b.limits), -b.candidate.gain))[:3]


def _chair_or_layout(value: object, name: str) -> None:
    """A Layout, or what :func:`check_chair` accepts (its TypeError names ``name`` otherwise)."""
    if not isinstance(value, Layout):
        check_chair(value, name)


@summarised_warnings
@memo_searches
@first_argument(_chair_or_layout)
def advise(chair: Chair | Layout, *, speeds=DEFAULT_SPEEDS, min_tip_deg: float | None = None,
           cross_slope_deg: float = DEFAULT_CROSS_SLOPE_DEG, progress: bool = False,
           nonlinear: Callable | None = None, time_to_correct: bool = True, driver: Driver | None = None,
           intended_speed: float | None = None, prune: bool = True) -> Advice:
    """Verdict, levers and recommendation for ``chair``.

    Parameters
    ----------
    chair : Chair or Layout
        A wheel layout gets its own levers and measures (:mod:`.subject`: the cross-slope limit from the layout
        slope statics, the driver's limit from the layout's linear model, in the direction of travel); a chair at
        negative speeds is advised as its layout.
    speeds : sequence of float
        Use speeds (m/s; all negative: in reverse); the shimmy margin (the smallest over them) and the time to
        correct are taken at each.
    min_tip_deg : float, optional
        Smallest acceptable static stability angle (deg); default the chair's own (no change may
        make it tip on a gentler slope; no citable standard minimum was found, docs/tipping.md).
    cross_slope_deg : float
        Cross slope of the drive-difference constraint (deg).
    progress : bool
        Progress bars on stderr.
    nonlinear : callable, optional
        Replaces :func:`.measures.nonlinear_measures` (tests of everything else).
    time_to_correct : bool
        Simulate the reference push at the use speeds for the verdict (default True).
    driver : Driver, optional
        The user: adds the constraint that the speed this driver can hold (the divergence rule,
        :func:`stability.driver.linear.rule_speed`) reaches ``intended_speed``.
    intended_speed : float, optional
        m/s, a size (also in reverse); default the fastest use speed's size (with a driver only).
    prune : bool
        Measure the changes at x0.5 pin friction first and compute the intervals only of those that can reach
        a choice (:mod:`.pruning`; the same decision); False: every change with its intervals.  A wheel layout
        is always measured with every interval.

    Returns
    -------
    Advice
    """
    use = use_speeds(speeds)
    if isinstance(chair, Chair) and any(u < 0 for u in use):
        chair = Layout.from_chair(chair)
    tau = None if driver is None else driver.reaction_time_s
    if intended_speed is not None and driver is None:
        raise ValueError("intended_speed needs a driver (driver=Driver(reaction_time_s))")
    # the speed's size (in reverse too: the human-limited speed of a layout backwards is a size)
    intended = None if driver is None else float(max(abs(u) for u in use) if intended_speed is None
                                                 else intended_speed)
    if intended_speed is not None:
        HUMAN_SPEED.check("intended_speed", intended_speed)
    if min_tip_deg is not None:
        MIN_TIP_ANGLE.check("min_tip_deg", min_tip_deg)
    ADVISE_CROSS_SLOPE.check("cross_slope_deg", cross_slope_deg)
    singles, refused = lever_changes(chair)
    cores: dict = {}
    prune = prune and isinstance(chair, Chair)
    if prune:
        nominal = screening_measures if nonlinear is None else screening_of(nonlinear)
        measured = measure_chairs([chair], speeds=use, cross_slope_deg=cross_slope_deg, progress=progress,
                                  nonlinear=nonlinear, cores=cores, reaction_time=tau)
        measured += measure_chairs([c for _, c in singles], speeds=use, cross_slope_deg=cross_slope_deg,
                                   progress=progress, nonlinear=nominal, cores=cores,
                                   reaction_time=tau) if singles else []
    else:
        measured = measure_chairs([chair] + [c for _, c in singles], speeds=use, cross_slope_deg=cross_slope_deg,
                                  progress=progress, nonlinear=nonlinear, cores=cores, reaction_time=tau)
    base = measured[0]
    if min_tip_deg is None:
        min_tip = float(base.static_stability_deg.value or 0.0)
        source = "the chair's own smallest angle (no citable standard minimum found; docs/tipping.md)"
    else:
        min_tip, source = float(min_tip_deg), "--min-tip-deg"

    def constraints(m: Measures | Linear) -> tuple:
        return constraints_of(m, base, min_tip, source, cross_slope_deg,
                              None if tau is None or intended is None else (tau, intended))

    def meets(m: LazyLinear) -> bool:
        return meets_of(m, base, min_tip, source, cross_slope_deg,
                        None if tau is None or intended is None else (tau, intended))

    def candidate(changes: tuple, m: Measures, bounded: bool = False) -> Candidate:
        g, gs = _gain(m, base)
        return Candidate(changes, m, g, gs, constraints(m), bounded)

    pool = Pool(candidate, nonlinear or nonlinear_measures)
    pool.add([candidate((ch,), m, prune) for (ch, _), m in zip(singles, measured[1:], strict=True)],
             [c for _, c in singles])
    pool.refine(pool.unbounded())
    cands = pool.cands[:]
    own = constraints(base)
    broken = {k.name for k in own if not k.met}            # what the chair as it is already breaks
    chosen, n_screened = _screen(chair, cands, broken, meets, use, cross_slope_deg, cores, tau,
                                 pool=pool if prune else None)
    cm = measure_chairs([c for _, c in chosen], speeds=use, cross_slope_deg=cross_slope_deg, progress=progress,
                        nonlinear=nominal if prune else nonlinear, cores=cores, reaction_time=tau) if chosen else []
    pool.add([candidate(tuple(x.changes[0] for x in combo), m, prune) for (combo, _), m in zip(chosen, cm,
                                                                                              strict=True)],
             [c for _, c in chosen])
    pool.refine(pool.unbounded())
    if prune:
        _settle_choice(pool, broken)
    cands, combined = pool.cands[:len(singles)], pool.cands[len(singles):]

    feasible = sorted((c for c in cands + combined if c.feasible), key=lambda c: -c.gain)
    keep = Candidate((), base, 0.0, {"critical_impulse": 0.0, "equal_instability_speed": 0.0}, own)
    if broken:
        ranked = feasible if feasible and feasible[0].gain >= -MAX_FIX_COST else [keep] + feasible[:1]
    else:
        better = [c for c in feasible if c.gain > 0]
        ranked = better if better else [keep] + feasible[:1]
    recs = []
    for rank, c in enumerate(ranked[:2], start=1):
        parts = tuple(next(s for s in cands if s.changes == (ch,)) for ch in c.changes) if len(c.changes) > 1 else ()
        recs.append(Recommendation(rank, c, parts, _notes(c, base, chair)))
    best_gain = recs[0].candidate.gain if recs else -math.inf
    blocked = _blocked(cands + combined, broken, best_gain)
    recs = _explain(recs, broken, blocked, base)
    times: list[float | None] = []
    for u in use if time_to_correct else ():
        try:
            times.append(correct_time(chair, u))
        except ValueError:
            times.append(None)
    return Advice(chair, use, float(cross_slope_deg), min_tip, source, base, tuple(times), tuple(cands),
                  tuple(combined), tuple(refused), tuple(recs), "", tuple(blocked), shimmy_hold(chair, use),
                  n_screened, len(chosen), own, driver, intended,
                  sum(not c.bounded for c in cands + combined))


def _explain(recs: list[Recommendation], broken: set, blocked: list[Blocked], base: Measures) -> list:
    """The recommendations with the notes that say why (one statement per fact; the runner-up named only when
    there is one)."""
    out = []
    runner = recs[1].candidate if len(recs) > 1 else None
    breaks = ", ".join(limit_words(n) for n in sorted(broken))
    for r in recs:
        c, notes = r.candidate, r.notes
        if broken and c.changes:
            notes += (f"The chair as it is breaks the limit on {breaks}; this change meets every limit "
                      f"({'and gains' if c.gain > 0 else 'at a cost of'} {abs(c.gain) * 100:.0f} % on the robust "
                      "measures).",)
        elif broken:
            fix = (f"the runner-up ({runner.label}) fixes it at a cost of {abs(runner.gain) * 100:.0f} %"
                   if runner is not None and runner.changes else
                   "no change meets every limit"
                   + (": a limit blocks the fixes found (see BLOCKED BY A LIMIT)" if blocked else ""))
            notes += (f"The chair as it is breaks the limit on {breaks}, and no change fixes it for less than "
                      f"{MAX_FIX_COST * 100:.0f} % of the robust measures; {fix}"
                      + (". The shimmy margin rests on estimated pin stiffness and relaxation length: measure them "
                         "first" if "shimmy_margin_m" in broken else "") + ".",)
        if not c.changes and not broken:
            notes += ("No change of any lever, nor any pair of two levers, raises both the critical impulse and the "
                      "equal-instability speed at the low ends of their intervals while meeting every limit: keep "
                      "the chair as it is"
                      + (" (it is directionally stable beyond what the studies measure: critical impulse above "
                         f"{base.critical_impulse_Ns.value:g} N s, equal-instability speed above "
                         f"{base.equal_instability_speed_m_s.value:g} m/s)"
                         if base.equal_instability_status == "above" else "") + ".",)
        out.append(Recommendation(r.rank, c, r.built_from, notes))
    return out


def lever_names() -> list[str]:
    """The levers' names, in order."""
    return list(LEVERS)
