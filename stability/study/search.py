"""Batched bracketing root search on a margin: every open problem proposes a push (or speed) per round.

The critical-impulse search (:func:`stability.study.impulse.critical_impulses`) runs on it.
Each problem ``i`` looks for the root of a margin ``g_i(x)`` that is negative
where the run does not reach the level and non-negative where it does
(:meth:`stability.study.summaries.Summaries.margin`).  A problem keeps every
point it has evaluated; its bracket is the largest ``x`` that does not reach
below the smallest that does.  Each round it proposes at most two points:

* the first round, without a prediction to start from: the largest push and
  half of it (both usually reach the level early, cheaply, and together
  give the next prediction);
* no bracket yet, going down: the root predicted from the times the two
  smallest reaching pushes took to reach the level and the linear model's
  growth rate at the speed (:func:`_rate_fit`), at most a factor 4 down;
  else from three of those times (:func:`_log_fit`), else the step the
  margin predicts (a response linear in the push has ``g = ln(J / J*)``
  exactly), at least ``2 eps`` and at most ``max_step``;
* going up: the secant through the two largest points (a peak near the
  level grows more slowly than the push), at most ``max_step``;
* a bracket: the root predicted by :func:`_rate_fit`, else
  :func:`_log_fit` through the points nearest the root on the reaching side
  (smooth there: the time to the level grows continuously as the push falls
  to the critical one), else regula falsi through the bracket's ends where
  the margins grow like a linear response; otherwise a step from the
  reaching end;
* once the prediction is trusted (a :func:`_rate_fit` within 10 % of the
  smallest reaching push, or any prediction inside a bracket), the pair
  ``x* + eps`` and ``x* + eps - width`` around it: if they straddle the
  root the bracket is closed in that round; where ``x* + eps`` is within a
  width of the smallest reaching point, that one point alone (the lower one
  could only confirm a miss).  A trusted pair that both reach means the
  responses do not leave a threshold the way :func:`_rate_fit` assumes (the
  kinetic pin-friction law's creep, docs/studies.md): that problem
  continues without it.

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
        Fitted predictions that still reached the level (each widens the next step by 1.5; after the first,
        :func:`_rate_fit` is no longer used).
    rounds : int
        Rounds in which the problem had runs.
    fit_pair : bool
        Whether the last proposal was a pair around a trusted :func:`_rate_fit` prediction.
    """

    x: list = field(default_factory=list)
    g: list = field(default_factory=list)
    reached: list = field(default_factory=list)
    t: list = field(default_factory=list)
    status: str = "open"
    cost: float = 0.0
    misses: int = 0
    rounds: int = 0
    fit_pair: bool = False

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


def _reaching(p: Problem) -> list[tuple[float, float]]:
    """``(x, t_level)`` of the reaching runs with a finite time, smallest push first."""
    return sorted((x, t) for x, t, r in zip(p.x, p.t, p.reached, strict=True) if r and math.isfinite(t))


def _log_fit(p: Problem, horizon: float) -> float | None:
    """The root predicted by ``t_level = a - b ln(exp(x) - J0)`` through the three smallest reaching points.

    Near a threshold push ``J0`` the response leaves the slow creep after a
    time that grows like ``-ln(J - J0) / sigma``; the critical push is where
    that time equals the horizon: ``J0 + exp((a - horizon) / b)``.  None
    without three reaching points or when they do not fit the form.
    """
    pts = _reaching(p)
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


def _rate_fit(p: Problem, rate: float, horizon: float) -> float | None:
    """The root predicted by ``t_level = a - ln(J - J0) / rate`` through the two smallest reaching points.

    Past the threshold push ``J0`` the response leaves along the linear
    model's unstable mode, ``|r| ~ c (J - J0) exp(rate t)``, so the time
    to the level is ``a - ln(J - J0) / rate``: with ``rate`` known (the
    frictionless linear model's largest growth rate at the speed, 1/s), two
    reaching runs ``J1 < J2`` give ``J0 = (q J1 - J2) / (q - 1)``,
    ``q = exp(rate (t1 - t2))``.  The critical push is where that time
    equals the horizon, ``J0 + (J1 - J0) exp(-rate (horizon - t1))``.
    E&J Premier at 0.75 m/s (rate 1.451/s): runs at 5.03, 4.27, 3.88 and
    3.26 N s reach the level at 2.35, 2.74, 3.07 and 6.55 s, a slope of
    0.69-0.74 s per unit of ``ln(J - J0)`` against ``1/rate`` = 0.69 s,
    and the pair at 5.03 and 4.27 N s predicts 3.263 N s against the
    threshold's 3.253-3.257 N s.
    Just above the threshold the escape is slower than ``rate`` (the
    friction still acts), so the prediction approaches from above (the
    next pair brackets it).  None without two such points, without a
    growing mode, or when they do not fit the form.
    """
    if not rate > 0.0:
        return None
    pts = _reaching(p)
    if not pts:
        return None
    x1, t1 = pts[0]
    far = [(x, t) for x, t in pts[1:] if x - x1 >= FIT_SPREAD]
    if not far:
        return None
    x2, t2 = far[0]
    if not t1 > t2:
        return None
    j1, j2 = math.exp(x1), math.exp(x2)
    q = math.exp(min(rate * (t1 - t2), 700.0))
    j0 = (q * j1 - j2) / (q - 1.0)
    if not 0.0 < j0 < j1:
        return None
    return math.log(j0 + (j1 - j0) * math.exp(-rate * max(horizon - t1, 0.0)))


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
    pts = _reaching(p)
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


#: Largest step down to a :func:`_rate_fit` prediction (ln 4: a fit through pushes far above the threshold,
#: where the response saturates, overshoots less often than it stops short)
FIT_STEP = math.log(4.0)
#: A :func:`_rate_fit` predicting the root within 10 % below the smallest reaching push is trusted to about
#: 1 %: the round tries the pair around it
FIT_NEAR = math.log(1.1)
#: :func:`_rate_fit` takes its second run at least 2 % above the first: two runs closer together reach the level
#: at nearly the same time, and the difference of those times no longer resolves the threshold
FIT_SPREAD = math.log(1.02)


def _propose(p: Problem, x_start: float, x_min: float, x_max: float, width: float, max_step: float,
             horizon: float, rate: float = math.nan) -> list[float]:
    """The next points of one problem (empty when it is closed; sets ``p.status``)."""
    if not p.x:
        if x_start >= x_max - 1e-12:            # no prediction: the largest push and half of it, for _rate_fit
            return [x_start, x_start - max_step]
        return [x_start]
    lo, hi = p.bracket()
    if hi is None:
        return _go_up(p, x_max, width, max_step)
    if lo is None:
        return _go_down(p, hi, x_min, width, max_step, horizon, rate)
    return _close(p, lo, hi, width, horizon, rate)


def _go_up(p: Problem, x_max: float, width: float, max_step: float) -> list[float]:
    """Nothing reaches yet: the step up the margin predicts ("never" at ``x_max``)."""
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
    step = min(max(step, 0.9 * width), max_step)
    return [min(x_max, top + step + 0.45 * width)]


def _go_down(p: Problem, hi: float, x_min: float, width: float, max_step: float, horizon: float,
             rate: float) -> list[float]:
    """Everything reaches: a step down to the predicted root ("below" at ``x_min``)."""
    eps = 0.45 * width
    if hi <= x_min + 1e-12:
        p.status = "below"
        return []
    if _far_below(p, x_min, horizon):
        return [x_min]
    if p.fit_pair:                               # the pair around a trusted prediction both reached:
        p.misses, p.fit_pair = p.misses + 1, False  # no threshold of the form here (the kinetic law's creep)
    pred = _rate_fit(p, rate, horizon) if not p.misses else None
    if pred is not None:
        step = min(max(hi - pred, 2.0 * eps), FIT_STEP)
        target = max(x_min, hi - step + eps)
        p.fit_pair = hi - pred <= FIT_NEAR and target - width > x_min
        return [target, target - 0.98 * width] if p.fit_pair else [target]
    pred = _log_fit(p, horizon)
    if pred is None:
        pred = hi - p._g(hi)                     # exact for a response linear in the push
    else:
        p.misses += 1                            # a fit whose prediction still reached: step further
    step = min(max(hi - pred, 2.0 * eps) * 1.5 ** max(p.misses - 1, 0), max_step)
    target = max(x_min, hi - step + eps)
    near = p._t(hi) >= 0.8 * horizon             # the smallest reaching push reaches late: the root is close
    return [target, target - 0.98 * width] if near and target - width > x_min else [target]


def _close(p: Problem, lo: float, hi: float, width: float, horizon: float, rate: float) -> list[float]:
    """A bracket: the point or pair that narrows it most ("found" once it is ``width`` wide)."""
    w = hi - lo
    if w <= width * (1.0 + 1e-9):
        p.status = "found"
        return []
    pred = _rate_fit(p, rate, horizon) if not p.misses else None
    trusted = pred is not None and lo < pred < hi
    if not trusted:
        pred = _log_fit(p, horizon)
    if pred is None or not lo < pred < hi:
        pred = _linear_root(lo, p._g(lo), hi, p._g(hi))
    if pred is None or not lo < pred < hi:
        return [hi - 0.35 * w]                   # no guide: a step from the cheap (reaching) side
    cap = hi - 0.98 * width
    a = min(pred + 0.45 * width, cap)            # at least one bracket width below the smallest reaching push
    if a >= cap:        # the root is predicted above a: a alone closes the bracket unless it reaches (then b,
        return [a]      # below a, would have been a wasted full-horizon run)
    b = a - 0.98 * width
    near = p._t(hi) >= 0.8 * horizon
    return [a, b] if b > lo and (trusted or near or w <= 4.0 * width) else [a]


def bracket_search(n: int, x_start: Sequence[float],
                   evaluate: Callable[[list[tuple[int, float]]], tuple[np.ndarray, ...]], *, x_min: float,
                   x_max: float, width: float, max_step: float, max_rounds: int, horizon: float,
                   rates: Sequence[float] | np.ndarray | None = None) -> list[Problem]:
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
    rates : sequence of float, optional
        Each problem's growth rate for :func:`_rate_fit`, 1/s (the linear
        model's largest real eigenvalue part at the speed; None or not
        positive: not used).

    Returns
    -------
    list of Problem
    """
    probs = [Problem() for _ in range(n)]
    for _ in range(max_rounds):
        jobs = []
        for i, p in enumerate(probs):
            if p.status == "open":
                jobs += [(i, float(x)) for x in _propose(p, float(x_start[i]), x_min, x_max, width, max_step, horizon,
                                                          math.nan if rates is None else float(rates[i]))]
        if not jobs:
            break
        reached, margin, cost, t_level = evaluate(jobs)
        for i in {i for i, _ in jobs}:
            probs[i].rounds += 1
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
