"""The advisor: verdict, levers, and the recommended change judged on the low end of its intervals.

Method (docs/advise.md): measure the chair and every single change of every lever
(:mod:`.levers`) in one batch (:func:`.measures.measure_chairs`); a change's robust gain is the
smaller of its relative gains in the *low ends* of the critical-impulse and equal-instability
intervals, so a change one measure contradicts gains nothing; keep the changes that meet every
constraint; combine the best single change of the three best levers (pairs and the triple, when
they touch different fields) and measure those too; recommend the best, with the runner-up.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from stability.advise.levers import LEVERS, apply, lever_changes
from stability.advise.measures import Measures, measure_chairs
from stability.chair import Chair
from stability.settings import defaults as D
from stability.settings.reference import REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study import reference_time

__all__ = ["Constraint", "Candidate", "Recommendation", "Advice", "advise", "MAX_PIN_FRICTION_N_M", "MAX_FIX_COST",
           "MIN_SHIMMY_MARGIN_M", "HANDRIM_FACTOR", "DEFAULT_SPEEDS", "DEFAULT_CROSS_SLOPE_DEG"]

#: Tolerable pin friction (N m): Collins (1987) conclusion 6 (L1853), "a reasonable estimate is 0.3 N-m".
MAX_PIN_FRICTION_N_M = 0.3
#: Smallest distance (m) of the trail from the nearest shimmy boundary at the nominal estimates (a
#: design choice: 5 mm, ten times the 0.5 mm at which the user journey's chair sat; docs/advise.md).
MIN_SHIMMY_MARGIN_M = 0.005
#: A change that only fixes a constraint the chair breaks is recommended if it costs at most this fraction of
#: the robust measures; a dearer fix is the runner-up behind "no change, measure first".
MAX_FIX_COST = 0.25
#: A change may raise the hand-rim force difference on the cross slope by at most this factor.
HANDRIM_FACTOR = 1.1
#: Default use speeds (m/s): :data:`stability.settings.defaults.ADVISE_SPEEDS` (0.5:1:0.25).
DEFAULT_SPEEDS = (0.5, 0.75, 1.0)
#: Default cross slope for the hand-rim force (deg): :data:`stability.settings.defaults.ADVISE_CROSS_SLOPE_DEG`.
DEFAULT_CROSS_SLOPE_DEG = D.ADVISE_CROSS_SLOPE_DEG


@dataclass(frozen=True)
class Constraint:
    """One constraint on a changed chair.

    Attributes
    ----------
    name : str
        ``static_stability_deg``, ``shimmy_margin_m``, ``turning_effort_N_m`` or
        ``handrim_force_difference_N``.
    value : float or None
        The changed chair's value (unit in the name).
    limit : float
        The bound (``>=`` for the first two, ``<=`` for the others; see :attr:`kind`).
    kind : str
        ``">="`` or ``"<="``.
    met : bool
    note : str
        Source of the limit, or a flag (e.g. measure pin stiffness and relaxation length first).
    """

    name: str
    value: float | None
    limit: float
    kind: str
    met: bool
    note: str = ""

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        v = self.value if self.value is None or math.isfinite(self.value) else None
        return {"name": self.name, "value": v, "limit": self.limit, "kind": self.kind, "met": self.met,
                "note": self.note}


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
    """

    changes: tuple
    measures: Measures
    gain: float
    gains: dict
    constraints: tuple

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
    chair : Chair
    speeds_m_s : tuple of float
        Use speeds (m/s).
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
    """

    chair: Chair
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


def _gain(m: Measures, base: Measures) -> tuple[float, dict]:
    def rel(new: float | None, old: float | None) -> float:
        if new is None or old is None or old <= 0:
            return -math.inf
        return new / old - 1.0

    g = {"critical_impulse": rel(m.critical_impulse_Ns.robust, base.critical_impulse_Ns.robust),
         "equal_instability_speed": rel(m.equal_instability_speed_m_s.robust, base.equal_instability_speed_m_s.robust)}
    return min(g.values()), g


def _constraints(m: Measures, base: Measures, min_tip: float, tip_source: str, cross_slope: float) -> tuple:
    out = [Constraint("static_stability_deg", m.static_stability_deg.value, min_tip, ">=",
                      (m.static_stability_deg.value or -math.inf) >= min_tip - 1e-9, tip_source)]
    sm = m.shimmy_margin_m.value
    ok = sm is not None and sm >= MIN_SHIMMY_MARGIN_M
    out.append(Constraint("shimmy_margin_m", sm, MIN_SHIMMY_MARGIN_M, ">=", ok,
                          "nominal estimates; over their range it straddles a boundary: measure pin lateral "
                          "stiffness and caster relaxation length first" if m.shimmy_straddles else
                          "nominal estimates, and met over their range"))
    limit = max(MAX_PIN_FRICTION_N_M, base.turning_effort_N_m)
    effort = m.turning_effort_N_m
    out.append(Constraint("turning_effort_N_m", effort, limit, "<=", effort <= limit + 1e-12,
                          "tolerable pin friction ~0.3 N m (Collins 1987, conclusion 6)"))
    if cross_slope:
        b, v = base.handrim_force_difference_N, m.handrim_force_difference_N
        lim = HANDRIM_FACTOR * abs(b) if b is not None else math.inf
        out.append(Constraint("handrim_force_difference_N", None if v is None else abs(v), lim, "<=",
                              v is not None and abs(v) <= lim + 1e-9,
                              f"on a {cross_slope:g} deg cross slope at {REFERENCE_SPEED:g} m/s; at most "
                              f"{HANDRIM_FACTOR:g} x the chair's own"))
    return tuple(out)


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


def _notes(c: Candidate, base: Measures, chair: Chair) -> tuple:
    m = c.measures
    notes = []
    if m.growth_rate_1_s > base.growth_rate_1_s * (1 + RATE_NOTE_RISE) and c.gain > 0:
        s_peak = math.sqrt(chair.i_z / chair.m)
        notes.append(
            f"The frictionless linear growth rate gets worse ({base.growth_rate_1_s:.3g} -> {m.growth_rate_1_s:.3g} "
            f"1/s at {REFERENCE_SPEED:g} m/s) while the critical impulse and the equal-instability speed improve. "
            "The linear model has free, frictionless casters: its divergent mode grows at about U m s1/(I_z + m s1^2), "
            f"which peaks at s1 = sqrt(I_z/m) = {s_peak:.3g} m, so moving the axle toward that point raises it. "
            "The nonlinear measures include the pins' Coulomb friction, whose moment against the caster's side force "
            "(pin friction over trail) holds the casters straight after a small push; that is what they reward.")
    step = _step_note(m)
    if step:
        notes.append(step)
    if m.shimmy_straddles:
        notes.append("Shimmy: the trail is shimmy-free at the estimated pin stiffness and relaxation length, but not "
                     "over their whole range; measure both before building it.")
    return tuple(notes)


def _combos(best: list[Candidate]) -> list[tuple]:
    out: list[tuple] = []
    n = len(best)
    for i in range(n):
        for j in range(i + 1, n):
            out.append((best[i], best[j]))
    if n >= 3:
        out.append((best[0], best[1], best[2]))
    return [c for c in out if len({k for x in c for k in x.fields}) == sum(len(x.fields) for x in c)]


def advise(chair: Chair, *, speeds=DEFAULT_SPEEDS, min_tip_deg: float | None = None,
           cross_slope_deg: float = DEFAULT_CROSS_SLOPE_DEG, progress: bool = False,
           nonlinear: Callable | None = None, time_to_correct: bool = True) -> Advice:
    """Verdict, levers and recommendation for ``chair``.

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float
        Use speeds (m/s); the shimmy margin (the smallest over them) and the time to correct are taken
        at each.
    min_tip_deg : float, optional
        Smallest acceptable static stability angle (deg); default the chair's own (no change may
        make it tip on a gentler slope; no citable standard minimum was found, docs/tipping.md).
    cross_slope_deg : float
        Cross slope of the hand-rim force constraint (deg).
    progress : bool
        Progress bars on stderr.
    nonlinear : callable, optional
        Replaces :func:`.measures.nonlinear_measures` (tests of everything else).
    time_to_correct : bool
        Simulate the reference push at the use speeds for the verdict (default True).

    Returns
    -------
    Advice
    """
    use = tuple(float(u) for u in speeds)
    singles, refused = lever_changes(chair)
    measured = measure_chairs([chair] + [c for _, c in singles], speeds=use, cross_slope_deg=cross_slope_deg,
                              progress=progress, nonlinear=nonlinear)
    base = measured[0]
    if min_tip_deg is None:
        min_tip = float(base.static_stability_deg.value or 0.0)
        source = "the chair's own smallest angle (no citable standard minimum found; docs/tipping.md)"
    else:
        min_tip, source = float(min_tip_deg), "--min-tip-deg"

    def candidate(changes: tuple, m: Measures) -> Candidate:
        g, gs = _gain(m, base)
        return Candidate(changes, m, g, gs, _constraints(m, base, min_tip, source, cross_slope_deg))

    cands = [candidate((ch,), m) for (ch, _), m in zip(singles, measured[1:], strict=True)]
    own = _constraints(base, base, min_tip, source, cross_slope_deg)
    broken = {k.name for k in own if not k.met}            # what the chair as it is already breaks

    def acceptable(c: Candidate) -> bool:                  # breaks nothing the chair itself meets
        return all(k.met or k.name in broken for k in c.constraints)

    best_per_lever: dict[str, Candidate] = {}
    for c in cands:
        lever = c.changes[0].lever
        if acceptable(c) and c.gain > 0 and (lever not in best_per_lever or c.gain > best_per_lever[lever].gain):
            best_per_lever[lever] = c
    pool = sorted(best_per_lever.values(), key=lambda c: -c.gain)[:3]
    fixes = sorted((c for c in cands if c.feasible), key=lambda c: -c.gain) if broken else []
    pool += [c for c in fixes[:2] if c.changes[0].lever not in {p.changes[0].lever for p in pool}]
    combos = _combos(pool)
    combo_chairs = [apply(chair, [f for x in combo for f in x.changes[0].fields]) for combo in combos]
    cm = measure_chairs(combo_chairs, speeds=use, cross_slope_deg=cross_slope_deg, progress=progress,
                        nonlinear=nonlinear) if combo_chairs else []
    combined = [candidate(tuple(x.changes[0] for x in combo), m) for combo, m in zip(combos, cm, strict=True)]
    feasible = [c for c in cands + combined if c.feasible]
    ranked = sorted((c for c in feasible if c.gain > 0 or broken), key=lambda c: -c.gain)
    keep = Candidate((), base, 0.0, {"critical_impulse": 0.0, "equal_instability_speed": 0.0}, own)
    if not broken and not ranked:
        # nothing helps and nothing needs fixing: keep the chair as it is; the runner-up is the best other change
        ranked = [keep] + sorted(feasible, key=lambda c: -c.gain)[:1]
    elif broken and not (ranked and ranked[0].gain >= -MAX_FIX_COST):
        # the fixes (if any) cost too much: measure first, the cheapest fix as the runner-up
        ranked = [keep] + ranked[:1]
    recs = []
    for rank, c in enumerate(ranked[:2], start=1):
        parts = tuple(next(s for s in cands if s.changes == (ch,)) for ch in c.changes) if len(c.changes) > 1 else ()
        notes = _notes(c, base, chair)
        if broken and c.changes:
            notes += (f"The chair as it is breaks {', '.join(sorted(broken))}; this change meets every constraint "
                      f"({'and gains' if c.gain > 0 else 'at a cost of'} {abs(c.gain) * 100:.0f} % on the robust "
                      "measures).",)
        elif broken:
            notes += (f"The chair as it is breaks {', '.join(sorted(broken))}, and no change fixes it for less than "
                      f"{MAX_FIX_COST * 100:.0f} % of the robust measures"
                      + (": measure the pin's lateral stiffness and the caster tire's relaxation length first; "
                         "if the estimates are confirmed, the runner-up fixes it" if "shimmy_margin_m" in broken
                         else "") + ".",)
        if not c.changes and not broken:
            notes += ("No change of any lever raises both the critical impulse and the equal-instability speed at the "
                      "low ends of their intervals while meeting every constraint: keep the chair as it is"
                      + (" (it is directionally stable beyond what the studies measure: critical impulse above "
                         f"{base.critical_impulse_Ns.value:g} N s, equal-instability speed above "
                         f"{base.equal_instability_speed_m_s.value:g} m/s)"
                         if base.equal_instability_status == "above" else "") + ".",)
        recs.append(Recommendation(rank, c, parts, notes))
    reason = ""
    if not recs:
        helping = [c for c in cands if c.gain > 0]
        reason = ("the chair breaks " + ", ".join(sorted(broken)) + " and no change of any lever meets every "
                  "constraint: " + "; ".join(f"{c.label} ({', '.join(k.name for k in c.constraints if not k.met)})"
                                             for c in (helping or cands)[:3]))
    times: list[float | None] = []
    for u in use if time_to_correct else ():
        try:
            times.append(reference_time(chair, u, RunSpec(model="exact")))
        except ValueError:
            times.append(None)
    return Advice(chair, use, float(cross_slope_deg), min_tip, source, base, tuple(times), tuple(cands),
                  tuple(combined), tuple(refused), tuple(recs), reason)


def lever_names() -> list[str]:
    """The levers' names, in order."""
    return list(LEVERS)
