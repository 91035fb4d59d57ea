"""The limits a change must meet: static stability, shimmy margin, turning effort, cross-slope drive.

Each limit is a :class:`Constraint` (value, bound, source), so a change a limit blocks can be named
with the limit and the option that would allow it.  The shimmy margin is the frictionless linear
caster's; :func:`shimmy_hold` says what the chair's Coulomb pin friction buys against shimmy, and
:func:`shimmy_sentence` is the one sentence the verdict and the notes share.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from stability.advise.measures import LazyLinear, Linear, Measures
from stability.chair import Chair
from stability.settings import defaults as D
from stability.settings.reference import REFERENCE_SPEED
from stability.shimmy.band import margin_words

__all__ = ["Constraint", "ShimmyHold", "constraints", "meets", "allow", "allow_words", "constraint_text", "limit_words",
           "LIMIT_WORDS", "shimmy_hold", "shimmy_sentence",
           "MAX_PIN_FRICTION_N_M", "MAX_BENCH_SCORE", "MIN_SHIMMY_MARGIN_M", "HANDRIM_FACTOR", "SHIMMY_AMPLITUDE_DEG"]

#: Tolerable pin friction (N m): Collins (1987) conclusion 6 (L1853), "a reasonable estimate is 0.3 N-m".
MAX_PIN_FRICTION_N_M = 0.3
#: Smallest distance (m) of the trail from the nearest shimmy boundary at the nominal estimates (a
#: design choice: 5 mm, ten times the 0.5 mm at which the user journey's chair sat; docs/advise.md).
MIN_SHIMMY_MARGIN_M = 0.005
#: A change may raise the drive difference (hand-rim force or motor torque) on the cross slope by at most this factor.
HANDRIM_FACTOR = 1.1
#: Largest acceptable worst wheel-lift score on the virtual ISO 7176-2 bench (issue 39: no case above score 1).
MAX_BENCH_SCORE = 1
#: Shimmy amplitude of the friction estimate, deg (what pin friction buys against shimmy; the shimmy command's).
SHIMMY_AMPLITUDE_DEG = D.SHIMMY_AMPLITUDE_DEG


@dataclass(frozen=True)
class Constraint:
    """One constraint on a changed chair.

    Attributes
    ----------
    name : str
        ``static_stability_deg``, ``shimmy_margin_m``, ``turning_effort_N_m``, or the cross-slope effort:
        ``handrim_force_difference_N`` (manual chair) or ``motor_torque_difference_N_m`` (power chair).
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
class ShimmyHold:
    """What the chair's Coulomb pin friction buys against caster shimmy (describing function).

    The frictionless linear caster shimmies inside a shimmy zone whatever the amplitude; Coulomb friction
    holds a shimmy of amplitude ``A`` wherever the trail is at least ``hold_trail_m``
    (:func:`stability.shimmy.chair.friction_trail`, the largest over the use speeds).

    Attributes
    ----------
    amplitude_deg : float
        Shimmy amplitude, deg.
    pin_friction_N_m : float
        The pin friction used (the left pin's), N m.
    hold_trail_m : float
        Trail below which the friction no longer holds that amplitude, m (0: every trail; inf: none).
    trail_m : float
        The chair's trail, m.
    """

    amplitude_deg: float
    pin_friction_N_m: float
    hold_trail_m: float
    trail_m: float

    @property
    def held(self) -> bool:
        """Whether the chair's pin friction holds shimmy of that amplitude at its trail."""
        return self.trail_m >= self.hold_trail_m

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"amplitude_deg": self.amplitude_deg, "pin_friction_N_m": self.pin_friction_N_m,
                "hold_trail_m": self.hold_trail_m if math.isfinite(self.hold_trail_m) else None,
                "trail_m": self.trail_m, "held": self.held}


def constraints(m: Measures | Linear | LazyLinear, base: Measures, min_tip: float, tip_source: str, cross_slope: float,
                driver: tuple[float, float] | None = None) -> tuple:
    """The constraints on a changed chair against the chair as it is (docs/advise.md).

    Parameters
    ----------
    m : Measures, Linear or LazyLinear
        The changed chair's measures.
    base : Measures
        The chair as it is (the turning-effort and cross-slope limits are relative to it).
    min_tip : float
        Smallest acceptable static stability angle, deg.
    tip_source : str
        Where ``min_tip`` comes from (the note of its constraint).
    cross_slope : float
        Cross slope of the drive-difference constraint, deg (0: no such constraint).
    driver : (float, float), optional
        ``(reaction_time s, intended speed m/s)``: the human-limited speed must reach the intended speed.

    Returns
    -------
    tuple of Constraint
    """
    return tuple(k for limit in _LIMITS if (k := limit(m, base, min_tip, tip_source, cross_slope, driver)) is not None)


def meets(m: Measures | Linear | LazyLinear, base: Measures, min_tip: float, tip_source: str, cross_slope: float,
          driver: tuple[float, float] | None = None) -> bool:
    """Whether a changed chair meets every one of :func:`constraints`, checked the cheapest first and no further
    than the first it breaks.

    The same constraints, so the same answer as ``all(k.met for k in constraints(...))``; a
    :class:`~stability.advise.measures.LazyLinear` is measured only as far as they are read (the tip angles, the
    pin friction and the cross-slope statics before the shimmy band and the bench).

    Parameters
    ----------
    m, base, min_tip, tip_source, cross_slope, driver
        As :func:`constraints`.

    Returns
    -------
    bool
    """
    for limit in _CHEAP_FIRST:
        k = limit(m, base, min_tip, tip_source, cross_slope, driver)
        if k is not None and not k.met:
            return False
    return True


def _tip(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    tip = m.static_stability_deg.value            # None: no tip angle (not met); 0 deg is a value
    return Constraint("static_stability_deg", tip, min_tip, ">=", tip is not None and tip >= min_tip - 1e-9,
                      tip_source)


def _shimmy(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    sm = m.shimmy_margin_m.value
    ok = sm is not None and sm >= MIN_SHIMMY_MARGIN_M
    return Constraint("shimmy_margin_m", sm, MIN_SHIMMY_MARGIN_M, ">=", ok,
                      "nominal estimates; over their range it straddles a boundary: measure pin lateral "
                      "stiffness and caster relaxation length first" if m.shimmy_straddles else
                      "nominal estimates, and met over their range")


def _turning(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    limit = max(MAX_PIN_FRICTION_N_M, base.turning_effort_N_m)
    effort = m.turning_effort_N_m
    return Constraint("turning_effort_N_m", effort, limit, "<=", effort <= limit + 1e-12,
                      "tolerable pin friction ~0.3 N m (Collins 1987, conclusion 6)")


def _slope(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    if not cross_slope:
        return None
    b, v = base.cross_slope_effort, m.cross_slope_effort
    lim = HANDRIM_FACTOR * abs(b) if b is not None else math.inf
    return Constraint(m.effort_key, None if v is None else abs(v), lim, "<=", v is not None and abs(v) <= lim + 1e-9,
                      f"on a {cross_slope:g} deg cross slope at {REFERENCE_SPEED:g} m/s; at most "
                      f"{HANDRIM_FACTOR:g} x the chair's own")


def _bench(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    if m.bench_score is None:
        return None
    # ISO 7176-2's matrix on the virtual bench (issue 39: no case above score 1); a chair already above it may
    # not get worse
    own = base.bench_score if base.bench_score is not None else MAX_BENCH_SCORE
    lim = max(MAX_BENCH_SCORE, own)
    return Constraint("bench_worst_score", float(m.bench_score), float(lim), "<=", m.bench_score <= lim,
                      "the virtual ISO 7176-2 bench at the default drive settings (docs/bench.md): no case "
                      f"above score {MAX_BENCH_SCORE} (a wheel may lift, the chair may not tip)"
                      + (f"; the chair as it is scores {own}, so not worse than that" if own > MAX_BENCH_SCORE
                         else ""))


def _driver(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint | None:
    if driver is None:
        return None
    tau, intended = driver
    u = m.human_speed_m_s
    return Constraint("human_limited_speed_m_s", u, intended, ">=", u is not None and u >= intended - 1e-9,
                      f"a driver who corrects {tau:g} s late holds the chair up to this speed (the divergence "
                      "rule lambda(U) tau = 1; docs/driver.md)"
                      + ("; beyond the speeds checked" if m.human_side == ">" else ""))


#: The limits, each ``limit(m, base, min_tip, tip_source, cross_slope, driver) -> Constraint or None`` (None: it
#: does not apply), in the order :func:`constraints` lists them.
_LIMITS = (_tip, _shimmy, _turning, _slope, _bench, _driver)
#: The order :func:`meets` checks them: the measures cheapest to compute first (tip angles and pin friction are
#: geometry, the cross-slope statics one solve; a new shimmy band core and the bench cost 30-180 ms and 40 ms a
#: design, the driver's rule a sweep of the linear model).
_CHEAP_FIRST = (_tip, _turning, _slope, _shimmy, _bench, _driver)


def shimmy_sentence(m: Measures | Linear, trail: float, hold: ShimmyHold | None = None) -> str:
    """The one statement of a chair's shimmy margin that the verdict and the notes share.

    Parameters
    ----------
    m : Measures or Linear
        The chair's measures (its frictionless shimmy margin, its range over the compliance estimates).
    trail : float
        The chair's trail, m.
    hold : ShimmyHold, optional
        What its pin friction holds.

    Returns
    -------
    str
        E.g. ``"the 4.5 cm trail is inside a shimmy zone by 0.23 cm (frictionless caster at the estimated pin
        stiffness and relaxation length; ...); its 0.118 N m pin friction holds a shimmy of up to 5 deg at trails
        from 4.4 cm, so also at this one"``.
    """
    sm = m.shimmy_margin_m
    value = math.nan if sm.value is None else sm.value       # every band has a margin (advise.measures)
    if math.isinf(value):
        # unbounded at the nominal estimates (+inf: no boundary on the trails searched; -inf: none is stable)
        text = margin_words(value)
    else:
        where = "clear of the nearest shimmy zone by" if value > 0 else "inside a shimmy zone by"
        rng = ("" if sm.low is None or sm.high is None or math.isinf(sm.low) or math.isinf(sm.high) else
               f"; over the estimates' ranges {100 * sm.low:+.2g} to {100 * sm.high:+.2g} cm")
        flag = ": it could shimmy, measure them first" if m.shimmy_straddles else ""
        text = (f"the {trail * 100:g} cm trail is {where} {abs(value) * 100:.2f} cm (frictionless caster at the "
                f"estimated pin stiffness and relaxation length{rng}{flag})")
    if hold is not None and hold.pin_friction_N_m > 0:
        if math.isinf(hold.hold_trail_m):
            buys = f"does not hold a {hold.amplitude_deg:g} deg shimmy at any trail"
        else:
            buys = (f"holds a shimmy of up to {hold.amplitude_deg:g} deg at trails from "
                    f"{hold.hold_trail_m * 100:.2g} cm, so {'also' if hold.held else 'not'} at this one")
        text += f"; its {hold.pin_friction_N_m:.3g} N m pin friction {buys} (describing function)"
    return text


#: Each limit in words: its name, display unit and the factor from its value's unit to the display unit.
LIMIT_WORDS = {"static_stability_deg": ("static stability", "deg", 1.0),
               "shimmy_margin_m": ("shimmy margin", "cm", 100.0),
               "turning_effort_N_m": ("turning pin friction", "N m", 1.0),
               "handrim_force_difference_N": ("hand-rim force difference on the cross slope", "N", 1.0),
               "motor_torque_difference_N_m": ("motor torque difference on the cross slope", "N m", 1.0),
               "human_limited_speed_m_s": ("the speed the driver can hold", "m/s", 1.0),
               "bench_worst_score": ("worst wheel-lift score on the ISO 7176-2 bench", "", 1.0)}


def limit_words(name: str) -> str:
    """A limit's name in words.

    Parameters
    ----------
    name : str
        The constraint's name (``shimmy_margin_m``).

    Returns
    -------
    str
        ``"shimmy margin"``.
    """
    return LIMIT_WORDS.get(name, (name.replace("_", " "), "", 1.0))[0]


def constraint_text(k: Constraint) -> str:
    """A constraint in plain words and display units.

    Parameters
    ----------
    k : Constraint

    Returns
    -------
    str
        ``"static stability 12.9 deg against the limit >= 13.8 deg"``.
    """
    words, unit, f = LIMIT_WORDS.get(k.name, (k.name.replace("_", " "), "", 1.0))
    if k.value is None:
        return f"{words} refused by the slope statics (tire data)"
    if k.name == "shimmy_margin_m" and math.isinf(k.value):
        return f"{words}: {margin_words(k.value)}, against the limit {k.kind} {f * k.limit:.3g} {unit}"
    u = f" {unit}" if unit else ""
    return f"{words} {f * k.value:.3g}{u} against the limit {k.kind} {f * k.limit:.3g}{u}"


def allow(k: Constraint) -> str:
    """What would allow a change that a constraint blocks, for the advise command.

    Parameters
    ----------
    k : Constraint
        The constraint the change does not meet.

    Returns
    -------
    str
        The command-line option and value (``"--min-tip-deg 12.9 (...)"``), or why no option can.
    """
    if k.name == "static_stability_deg":
        return (f"--min-tip-deg {math.floor(k.value * 10) / 10:.1f} (the limit is {k.limit:.1f} deg, {k.note})"
                if k.value is not None else "no limit allows it")
    if k.name == "turning_effort_N_m":
        return (f"no option: pin friction above {k.limit:.3g} N m makes the chair hard to turn (Collins 1987, "
                "conclusion 6)")
    if k.name == "shimmy_margin_m":
        return f"no option: the shimmy margin limit is {MIN_SHIMMY_MARGIN_M * 1000:g} mm from the nearest boundary"
    if k.name == "bench_worst_score":
        return ("no option: the bench's drive settings are those of python -m stability.bench (docs/bench.md); a "
                "change that tips the chair in the ISO 7176-2 matrix is not allowed")
    if k.name == "human_limited_speed_m_s":
        return (f"--intended-speed {math.floor((k.value or 0.0) * 100) / 100:.2f} (a slower intended speed), or a "
                "driver who reacts faster (--reaction-time)")
    return "--cross-slope 0 (drops the cross-slope limit)"


def allow_words(k: Constraint) -> str:
    """:func:`allow` in plain words, for a reader who does not run the command (the report).

    Parameters
    ----------
    k : Constraint
        The constraint the change does not meet.

    Returns
    -------
    str
        ``"a lower static-stability limit (12.9 deg) would allow it"``, or why no setting does.
    """
    if k.name == "static_stability_deg":
        return (f"a lower static-stability limit ({math.floor(k.value * 10) / 10:.1f} deg) would allow it"
                if k.value is not None else "no limit would allow it")
    if k.name == "turning_effort_N_m":
        return (f"no setting allows it (pin friction above {k.limit:.3g} N m makes the chair hard to turn; Collins "
                "1987, conclusion 6)")
    if k.name == "shimmy_margin_m":
        return f"no setting allows it (the shimmy margin must be at least {MIN_SHIMMY_MARGIN_M * 1000:g} mm)"
    if k.name == "bench_worst_score":
        return "no setting allows it (the chair would tip in the ISO 7176-2 manoeuvres of the virtual bench)"
    if k.name == "human_limited_speed_m_s":
        return (f"driving no faster than {k.value or 0.0:.2f} m/s, or a driver who reacts faster, would allow it")
    return "dropping the cross-slope limit would allow it"


def shimmy_hold(chair: Chair, speeds: tuple, amplitude_deg: float = SHIMMY_AMPLITUDE_DEG) -> ShimmyHold | None:
    """What ``chair``'s pin friction buys against shimmy of ``amplitude_deg`` at the use speeds.

    Parameters
    ----------
    chair : Chair
    speeds : tuple of float
        m/s.
    amplitude_deg : float
        deg.

    Returns
    -------
    ShimmyHold or None
        None without pin friction, or where the statics refuse the chair.
    """
    from stability.shimmy.chair import friction_trail

    if chair.pin_friction_left <= 0:
        return None
    try:
        trail = max(friction_trail(chair, float(u), math.radians(amplitude_deg)) for u in speeds)
    except ValueError:          # the statics refuse the chair at its own or a scanned trail: nothing to state
        return None
    return ShimmyHold(float(amplitude_deg), float(chair.pin_friction_left), float(trail), float(chair.trail))
