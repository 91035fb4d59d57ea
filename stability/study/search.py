"""Batched bracketing root search on a margin: every open problem proposes a push (or speed) per round.

The critical-impulse and equal-instability searches share this machinery.
Each problem ``i`` looks for the root of a margin ``g_i(x)`` that is negative
where the run does not reach the level and non-negative where it does
(:meth:`stability.study.summaries.Summaries.margin`).  A problem keeps every
point it has evaluated; its bracket is the largest ``x`` that does not reach
below the smallest that does.  Each round it proposes at most two points:

* no bracket yet: a step from the nearest end towards the root the margin
  predicts (a response linear in the push has ``g = ln(J / J*)`` exactly;
  going up, the secant through the two largest points, since a peak near
  the level grows more slowly than the push), at least ``2 eps`` and at most ``max_step``;
* a bracket: the root predicted by the secant through the two points
  nearest the root on the reaching side (smooth there: the time to the level
  grows continuously as the push falls to the critical one), else by the
  Illinois-modified regula falsi through the bracket's ends; a prediction
  outside the middle 90 % of a wide bracket, or a bracket that the last round
  did not halve, falls back to the bracket's midpoint;
* once the prediction is trusted, the pair ``x* + eps`` and
  ``x* + eps - width`` around it: if they straddle the root the bracket is
  closed in that round; where ``x* + eps`` is within a width of the smallest
  reaching point, that one point alone (the lower one could only confirm a
  miss, at the cost of a full-horizon run).

The final bracket is at most ``width`` wide and is verified by two runs, as
the earlier plain bisection's was; so both report a point of the same
bracket around the same crossing, when reaching the level is monotone in ``x``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Problem", "bracket_search"]


@dataclass
class Problem:
    """One root search: its evaluated points and outcome.

    Attributes
    ----------
    x : list of float
        Evaluated points (log push or speed).
    g : list of float
        Margin at each point.
    reached : list of bool
        Whether each run reached the level.
    t : list of float
        When each run reached the level, s (inf: never).
    status : str
        "open", "found", "never" (nothing up to ``x_max`` reaches) or "below"
        (already ``x_min`` reaches).
    cost : float
        Simulated time spent, s.
    misses : int
        Fitted predictions that still reached the level (each widens the next step by 1.5).
    """

    x: list = field(default_factory=list)
    g: list = field(default_factory=list)
    reached: list = field(default_factory=list)
    t: list = field(default_factory=list)
    status: str = "open"
    cost: float = 0.0
    misses: int = 0

    def bracket(self) -> tuple[float | None, float | None]:
        """``(lo, hi)``: the largest non-reaching point below the smallest reaching one (None: none)."""
        hi = min((x for x, r in zip(self.x, self.reached, strict=True) if r), default=None)
        lo = max((x for x, r in zip(self.x, self.reached, strict=True) if not r and (hi is None or x < hi)),
                 default=None)
        return lo, hi

    def _g(self, x: float) -> float:
        return self.g[self.x.index(x)]

    def _t(self, x: float) -> float:
        return self.t[self.x.index(x)]


def _log_fit(p: Problem, horizon: float) -> float | None:
    """The root predicted by ``t_level = a - b ln(exp(x) - J0)`` through the three smallest reaching points.

    Near a threshold push ``J0`` the response leaves the slow creep after a
    time that grows like ``-ln(J - J0) / sigma``; the critical push is where
    that time equals the horizon: ``J0 + exp((a - horizon) / b)``.  None
    without three reaching points or when they do not fit the form.
    """
    pts = sorted((x, t) for x, t, r in zip(p.x, p.t, p.reached, strict=True) if r and math.isfinite(t))
    if len(pts) < 3:
        return None
    (x1, t1), (x2, t2), (x3, t3) = pts[:3]
    j1, j2, j3 = math.exp(x1), math.exp(x2), math.exp(x3)
    if not (t1 > t2 > t3 and j1 < j2 < j3):
        return None

    def f(j0: float) -> float:
        return (t1 - t2) / math.log((j2 - j0) / (j1 - j0)) - (t2 - t3) / math.log((j3 - j0) / (j2 - j0))

    a_, b_ = j1 - 1e3 * (j3 - j1), j1 * (1.0 - 1e-12)
    fa, fb = f(a_), f(b_)
    if not fa * fb < 0:
        return None
    for _ in range(100):
        m = 0.5 * (a_ + b_)
        fm = f(m)
        if fa * fm <= 0:
            b_ = m
        else:
            a_, fa = m, fm
    j0 = 0.5 * (a_ + b_)
    b = (t1 - t2) / math.log((j2 - j0) / (j1 - j0))
    a = t1 + b * math.log(j1 - j0)
    root = j0 + math.exp((a - horizon) / b)
    return math.log(root) if root > 0 else None


def _far_below(p: Problem, x_min: float, horizon: float) -> bool:
    """Whether the run reaches the level whatever the push: then try ``x_min`` next.

    Where the two smallest reaching pushes, at least ``ln 1.5`` apart, reach
    the level early (before half the horizon) and nearly together (the
    smaller less than 10 % later per halving of the push), the push no
    longer sets the disturbance (the fixed-step scheme's pin friction,
    switching with the sign of a tiny caster rate, does), and the line
    through them reaches the horizon below ``x_min``.  Halving the push from
    there would take a round per halving (25 from 40 to 1e-6 N s); one run at
    ``x_min`` settles it ("below" if it reaches, else a bracket).  Far from
    that floor a run pushed half as hard reaches 20-100 % later (E&J Premier
    and designs, 0.5-1.2 m/s), so the rule does not fire there.
    """
    pts = sorted((x, t) for x, t, r in zip(p.x, p.t, p.reached, strict=True) if r and math.isfinite(t))
    if len(pts) < 2:
        return False
    (x1, t1), (x2, t2) = pts[:2]
    if x2 - x1 < math.log(1.5) or t1 >= 0.5 * horizon:
        return False
    rise = (t1 - t2) / (x2 - x1)                     # s of delay per unit of log push less
    if rise * math.log(2.0) > 0.1 * t1:
        return False
    return rise <= 0.0 or (horizon - t1) / rise > x1 - x_min


def _linear_root(x1: float, g1: float, x2: float, g2: float) -> float | None:
    """Regula falsi through two points, if their margins grow like a response linear in the push.

    A response linear in the push has ``g = x - x*`` (slope 1 in the log
    push); far from that (slope outside 0.5-2) the margin is not a guide to
    the root (the creep below a friction threshold is flat in the push) and
    None is returned.
    """
    if x1 == x2:
        return None
    slope = (g2 - g1) / (x2 - x1)
    if not 0.5 <= slope <= 2.0:
        return None
    return x1 - g1 / slope


def _propose(p: Problem, x_start: float, x_min: float, x_max: float, width: float, max_step: float,
             horizon: float) -> list[float]:
    """The next points of one problem (empty when it is closed; sets ``p.status``)."""
    eps = 0.45 * width
    if not p.x:
        return [x_start]
    lo, hi = p.bracket()
    if hi is None:                                   # nothing reaches yet: go up
        top = max(p.x)
        if top >= x_max - 1e-12:
            p.status = "never"
            return []
        step = -p._g(top)                            # exact for a response linear in the push (slope 1)
        below = sorted(x for x in p.x if x < top)
        if below:               # secant through the two largest: the peak saturates near the level (slope < 1)
            x1 = below[-1]
            slope = (p._g(top) - p._g(x1)) / (top - x1)
            if slope > 0.1:
                step = -p._g(top) / slope
        step = min(max(step, 2.0 * eps), max_step)
        return [min(x_max, top + step + eps)]
    near = p._t(hi) >= 0.8 * horizon                 # the smallest reaching push reaches late: the root is close
    if lo is None:                                   # everything reaches: go down
        if hi <= x_min + 1e-12:
            p.status = "below"
            return []
        if _far_below(p, x_min, horizon):
            return [x_min]
        pred = _log_fit(p, horizon)
        if pred is None:
            pred = hi - p._g(hi)                     # exact for a response linear in the push
        else:
            p.misses += 1                            # a fit whose prediction still reached: step further
        step = min(max(hi - pred, 2.0 * eps) * 1.5 ** max(p.misses - 1, 0), max_step)
        target = max(x_min, hi - step + eps)
        return [target, target - 0.98 * width] if near and target - width > x_min else [target]
    w = hi - lo
    if w <= width * (1.0 + 1e-9):
        p.status = "found"
        return []
    pred = _log_fit(p, horizon)
    if pred is None or not lo < pred < hi:
        pred = _linear_root(lo, p._g(lo), hi, p._g(hi))
    if pred is None or not lo < pred < hi:
        return [hi - 0.35 * w]                       # no guide: a step from the cheap (reaching) side
    cap = hi - 0.98 * width
    a = min(pred + eps, cap)                         # at least one bracket width below the smallest reaching push
    if a >= cap:        # the root is predicted above a: a alone closes the bracket unless it reaches (then b,
        return [a]      # below a, would have been a wasted full-horizon run)
    b = a - 0.98 * width
    return [a, b] if b > lo and (near or w <= 4.0 * width) else [a]


def bracket_search(n: int, x_start: Sequence[float],
                   evaluate: Callable[[list[tuple[int, float]]], tuple[np.ndarray, ...]], *, x_min: float,
                   x_max: float, width: float, max_step: float, max_rounds: int, horizon: float) -> list[Problem]:
    """Run ``n`` root searches together, one ``evaluate`` call per round for every open one.

    Parameters
    ----------
    n : int
        Number of problems.
    x_start : sequence of float
        First point of each problem.
    evaluate : callable
        ``evaluate([(problem, x), ...]) -> (reached, margin, cost, t_level)`` arrays over the jobs.
    x_min, x_max : float
        Search range.
    width : float
        Final bracket width (same units as ``x``).
    max_step : float
        Largest step before a bracket exists.
    max_rounds : int
        Rounds at most (a problem still open then keeps its bracket).
    horizon : float
        Simulated time, s (the reaching time the critical case has).

    Returns
    -------
    list of Problem
    """
    probs = [Problem() for _ in range(n)]
    for _ in range(max_rounds):
        jobs = []
        for i, p in enumerate(probs):
            if p.status == "open":
                jobs += [(i, float(x)) for x in _propose(p, float(x_start[i]), x_min, x_max, width, max_step, horizon)]
        if not jobs:
            break
        reached, margin, cost, t_level = evaluate(jobs)
        for (i, x), r, g, c, tl in zip(jobs, reached, margin, cost, t_level, strict=True):
            p = probs[i]
            p.x.append(x)
            p.g.append(float(g))
            p.reached.append(bool(r))
            p.t.append(float(tl))
            p.cost += float(c)
    for p in probs:
        if p.status == "open":
            _propose(p, 0.0, x_min, x_max, width, max_step, horizon)
    return probs
