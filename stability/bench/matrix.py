"""The virtual test bench: the manoeuvre and slope matrix of ISO 7176-2 (dynamic stability) and the stops of
ISO 7176-3 (braking), quasi-static, for any layout.

The drive's controller turns the joystick into wheel speeds with acceleration and deceleration limits
(:class:`Drive`); each manoeuvre is the quasi-static state at its largest acceleration (:mod:`.loads`) on level
ground and on the declared maximum safe slope:

- starting forward (uphill) and rearward (down the slope, facing uphill) at the drive's acceleration, limited by
  the drive wheels' traction;
- stopping from the top speed forward (downhill) and rearward by releasing the control, by commanding reverse and
  by cutting the power (the brakes engage after a delay);
- turning at the top speed at the controller's largest yaw rate, on level ground and across the slope, both ways.

Braking distance (ISO 7176-3): ``U t_delay + U^2 / (2 a)`` with ``a`` the deceleration less the slope's
``g sin(gamma)`` downhill, the deceleration limited by the drive wheels' traction (``mu`` times their share of the
load in that state over the mass).  The standard's own procedure (run-up, measurement, repeats) is not
simulated: the bench predicts before a prototype exists.  Issue 39; docs/bench.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from stability.bench.loads import SCORE_WORDS, LoadCase, case_loads
from stability.layout.model import Layout, takes_layout
from stability.layout.statics import contacts
from stability.models import slope as slope_model
from stability.settings.drive import DRIVE_SETTINGS

__all__ = ["Drive", "DRIVE_SETTINGS", "Case", "BenchResult", "run_bench", "braking_distance"]


@dataclass(frozen=True)
class Drive:
    """A power chair's drive controller and brakes (:data:`DRIVE_SETTINGS`: units, ranges, meaning).

    Parameters
    ----------
    max_speed_m_s, reverse_speed_m_s : float
        m/s.
    accel_m_s2, decel_m_s2, reverse_decel_m_s2, brake_decel_m_s2 : float
        m/s^2.
    brake_delay_s : float
        s.
    turn_rate_rad_s : float
        rad/s.
    traction : float
    max_slope_deg : float
        deg.
    """

    max_speed_m_s: float = DRIVE_SETTINGS["max_speed_m_s"][0]
    reverse_speed_m_s: float = DRIVE_SETTINGS["reverse_speed_m_s"][0]
    accel_m_s2: float = DRIVE_SETTINGS["accel_m_s2"][0]
    decel_m_s2: float = DRIVE_SETTINGS["decel_m_s2"][0]
    reverse_decel_m_s2: float = DRIVE_SETTINGS["reverse_decel_m_s2"][0]
    brake_decel_m_s2: float = DRIVE_SETTINGS["brake_decel_m_s2"][0]
    brake_delay_s: float = DRIVE_SETTINGS["brake_delay_s"][0]
    turn_rate_rad_s: float = DRIVE_SETTINGS["turn_rate_rad_s"][0]
    traction: float = DRIVE_SETTINGS["traction"][0]
    max_slope_deg: float = DRIVE_SETTINGS["max_slope_deg"][0]

    def __post_init__(self) -> None:
        for f, (_, unit, (lo, hi), _) in DRIVE_SETTINGS.items():
            v = getattr(self, f)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and lo <= v <= hi):
                raise ValueError(f"{f}={v!r} is invalid; valid range: {lo:g} to {hi:g} {unit}".rstrip())
            object.__setattr__(self, f, float(v))


@dataclass(frozen=True)
class Case:
    """One case of the matrix.

    Attributes
    ----------
    family : str
        ``"start"``, ``"stop"``, ``"turn"``.
    name : str
        E.g. ``"forward stop, reverse command"``.
    slope : str
        ``"level"``, ``"uphill"``, ``"downhill"``, ``"across"``.
    ax_m_s2, ay_m_s2 : float
        The quasi-static acceleration, body axes.
    grade_deg, cross_deg : float
    loads : LoadCase
    braking_distance_m : float or None
        Stops only.
    limited_by : str
        What sets the outcome: the contact that lifts or the edge the chair tips over, or the traction limit.
    """

    family: str
    name: str
    slope: str
    ax_m_s2: float
    ay_m_s2: float
    grade_deg: float
    cross_deg: float
    loads: LoadCase
    braking_distance_m: float | None = None
    limited_by: str = ""

    @property
    def score(self) -> int:
        """0-3 (:data:`stability.bench.loads.SCORE_WORDS`)."""
        return self.loads.score

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"family": self.family, "name": self.name, "slope": self.slope, "ax_m_s2": self.ax_m_s2,
                "ay_m_s2": self.ay_m_s2, "grade_deg": self.grade_deg, "cross_deg": self.cross_deg,
                "score": self.score, "score_words": SCORE_WORDS[self.score], "lifted": list(self.loads.lifted),
                "support_margin_m": self.loads.margin_m if math.isfinite(self.loads.margin_m) else None,
                "loads_N": [float(x) for x in self.loads.loads_N],
                "braking_distance_m": (self.braking_distance_m if self.braking_distance_m is None
                                       or math.isfinite(self.braking_distance_m) else None),
                "stops": None if self.braking_distance_m is None else math.isfinite(self.braking_distance_m),
                "limited_by": self.limited_by}


@dataclass(frozen=True)
class BenchResult:
    """The whole matrix for one chair.

    Attributes
    ----------
    layout : str
    drive : Drive
    cases : tuple of Case
    """

    layout: str
    drive: Drive
    cases: tuple = field(default_factory=tuple)

    @property
    def worst_score(self) -> int:
        """The largest score of the matrix."""
        return max(c.score for c in self.cases)

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"layout": self.layout, "drive": dict(vars(self.drive)), "worst_score": self.worst_score,
                "cases": [c.to_mapping() for c in self.cases]}


def _pull(g: float, grade_deg: float) -> float:
    """The slope's pull back down a grade rising ahead, ``g sin(grade)`` (m/s^2): minus the forward component of
    gravity in body axes of the generated slope model (:func:`stability.models.slope.gravity`)."""
    return -slope_model.gravity(g, 0.0, math.radians(grade_deg))[0]


def braking_distance(speed: float, decel: float, delay: float = 0.0, downhill_deg: float = 0.0, g: float = 9.81
                     ) -> float:
    """Stopping distance from ``speed``: ``speed delay + speed^2 / (2 (decel - g sin(downhill)))``, m.

    Parameters
    ----------
    speed : float
        m/s.
    decel : float
        m/s^2.
    delay : float
        s at full speed before the deceleration.
    downhill_deg : float
        deg (the slope pulls the chair on).
    g : float

    Returns
    -------
    float
        m; ``inf`` when the slope's pull is not less than the deceleration.
    """
    a = decel - _pull(g, downhill_deg)
    return math.inf if a <= 0 else speed * delay + speed * speed / (2.0 * a)


def _driven_share(layout: Layout, case: LoadCase) -> float:
    pts = contacts(layout)
    driven = {f"wheel {j}" for j, w in enumerate(layout.wheels) if w.driven}
    total = case.loads_N.sum()
    return float(sum(n for (lab, *_), n in zip(pts, case.loads_N, strict=True) if lab in driven) / total) \
        if total > 0 else 0.0


def _state(layout: Layout, ax: float, grade: float, drive: Drive, reverse: bool) -> tuple[LoadCase, float, str]:
    """The longitudinal state: the drive wheels' force ``m (ax + g sin(grade))`` limited by their traction
    ``mu N_driven`` (the acceleration then the traction's), its loads and what limits it.

    The traction limit is taken in the state it limits: the loads shift with the acceleration (a stop pitches a
    mid-wheel-drive base onto its front casters and unloads the drive wheels), so the achieved acceleration
    ``a`` solves ``m |a + g sin(grade)| = mu N_driven(a)`` between the free roll (``a = -g sin(grade)``, no drive
    force) and the controller's request, not the grip of the requested state.
    """
    c = case_loads(layout, ax, 0.0, grade, 0.0, reverse)
    m, pull = layout.m, _pull(layout.g, grade)

    def excess(a: float) -> float:
        ca = case_loads(layout, a, 0.0, grade, 0.0, reverse)
        return abs(m * (a + pull)) - drive.traction * _driven_share(layout, ca) * float(ca.loads_N.sum())

    top = ax
    if c.score >= 2:
        # the chair tips at the request: can the drive wheels' grip take it there?  The last state before the
        # tip (bisection on the support margin from the free roll, to 2^-60 of the interval) decides: a chair
        # braking on wheels off its tipping edge unloads them as it pitches and cannot brake itself over it.
        lo, hi = -pull, ax
        if case_loads(layout, lo, 0.0, grade, 0.0, reverse).score >= 2:
            return c, ax, _why(layout, c)                      # it tips standing on the slope
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if case_loads(layout, mid, 0.0, grade, 0.0, reverse).score >= 2 else (mid, hi)
        if excess(lo) <= 0.0:
            return c, ax, _why(layout, c)
        top = lo
    elif excess(ax) <= 0.0:
        return c, ax, _why(layout, c)
    # excess(-pull) = -grip <= 0 and excess(top) > 0: a root between (to 1e-12 m/s^2)
    ax2 = float(brentq(excess, -pull, top, xtol=1e-12, rtol=4 * np.finfo(float).eps))
    return case_loads(layout, ax2, 0.0, grade, 0.0, reverse), ax2, "traction of the drive wheels"


def _why(layout: Layout, c: LoadCase) -> str:
    if c.score == 0:
        return ""
    if c.score == 1:
        return "lifts: " + ", ".join(c.lifted)
    return "tips over the edge of its support" + (" onto its anti-tip devices" if c.score == 2 else "")


@takes_layout
def run_bench(layout: Layout, drive: Drive | None = None) -> BenchResult:
    """Every case of the matrix for one chair.

    Parameters
    ----------
    layout : Layout
    drive : Drive, optional
        Default :class:`Drive`.

    Returns
    -------
    BenchResult
    """
    d = drive or Drive()
    s = d.max_slope_deg
    g = layout.g
    out = []
    for slope, grade in (("level", 0.0), ("uphill", s)):
        c, ax, why = _state(layout, d.accel_m_s2, grade, d, False)
        out.append(Case("start", "forward start", slope, ax, 0.0, grade, 0.0, c, None, why))
    for slope, grade in (("level", 0.0), ("backwards down the slope", s)):
        c, ax, why = _state(layout, -d.accel_m_s2, grade, d, True)
        out.append(Case("start", "rearward start", slope, ax, 0.0, grade, 0.0, c, None, why))
    stops = (("control released", d.decel_m_s2, 0.0, False), ("reverse command", d.reverse_decel_m_s2, 0.0, False),
             ("power cut", d.brake_decel_m_s2, d.brake_delay_s, True))
    for name, decel, delay, brakes in stops:
        # forward at the top speed, facing downhill on the slope (grade -s); rearward at the reverse top speed,
        # facing uphill and backing down it (grade +s).  The controller holds its deceleration; the brakes give
        # a force, so the slope's pull takes from theirs.
        for direction, speed, sign, cases in (("forward", d.max_speed_m_s, -1.0, (("level", 0.0), ("downhill", -s))),
                                              ("rearward", d.reverse_speed_m_s, 1.0,
                                               (("level", 0.0), ("backwards down the slope", s)))):
            for slope, grade in cases:
                ax = sign * decel - (_pull(g, grade) if brakes else 0.0)
                c, ax, why = _state(layout, ax, grade, d, direction == "rearward")
                dist = speed * delay + speed * speed / (2.0 * abs(ax)) if sign * ax > 0 else math.inf
                if not math.isfinite(dist):
                    why = (why + "; " if why else "") + "does not stop: the slope pulls harder than it can brake"
                out.append(Case("stop", f"{direction} stop, {name}", slope, ax, 0.0, grade, 0.0, c, dist, why))
    ay = d.max_speed_m_s * d.turn_rate_rad_s
    for side, sign in (("right", 1.0), ("left", -1.0)):
        for slope, cross in (("level", 0.0), ("across, turning downhill", sign * s), ("across, turning uphill",
                                                                                       -sign * s)):
            c = case_loads(layout, 0.0, sign * ay, 0.0, cross)
            out.append(Case("turn", f"turn {side} at top speed", slope, 0.0, sign * ay, 0.0, cross, c, None,
                            _why(layout, c)))
    return BenchResult(layout.name, d, tuple(out))
