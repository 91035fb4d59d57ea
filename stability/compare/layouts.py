"""Side-by-side comparison of any chairs as wheel layouts, forward and in reverse.

When one of the chairs is a wheel layout (a layout preset or a ``[[wheel]]`` file), or a speed is negative, every
chair is compared as a layout (a short-form chair through :meth:`stability.layout.Layout.from_chair`): the
measures are those ``python -m stability.critical_speed``, ``tipping`` and ``study critical-impulse`` print for a
layout, each with the short form's comparison (the differences from the first chair, which is more stable):

- the growth rate of the least stable mode at each signed speed (the layout's linear model, free frictionless
  casters; negative speeds: in reverse, the casters trailing at 180 deg), lower is more stable;
- forward and in reverse, the speed up to which the chair is stable (:func:`stability.layout.linear.critical_speed`:
  the destabilising critical speed; infinite when stable up to 20 m/s, 0 when unstable from the slowest speed or
  only stable above a speed), higher is more stable;
- the static stability, the smallest of the four ISO 7176-1 angles over the outermost contacts, higher is more
  stable;
- with ``nonlinear``: the critical impulse at the reference speed (forward, and in reverse when a speed is
  negative), higher is more stable.

The short form's zero-width and locked-caster measures and its single-parameter effects (a chair's named fields)
have no layout counterpart here: the comparison says so in one line.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np

from stability.advise.layout_axes import LayoutDraw
from stability.compare.compute import CURVE_SPEEDS, Comparison, Difference, Quantity, _difference
from stability.layout.linear import SEARCH_SPEEDS_M_S, critical_speed, growth_rates
from stability.layout.model import Layout
from stability.layout.statics import tip_angles
from stability.linear.batch import check_eigen_work
from stability.linear.intervals import solves_per_draw
from stability.settings.bounds import CONFIDENCE_LEVEL, SAMPLES
from stability.settings.reference import REFERENCE_SPEED, THESIS_PUSH
from stability.study.censored import quantile
from stability.study.layout_impulse import layout_critical_impulses
from stability.uncertainty import Uncertainty, propagate

__all__ = ["compare_layouts", "stable_up_to", "stable_up_to_bounded", "stable_up_to_rows", "bounded_interval",
           "bounded_difference", "linear_rows", "LAYOUT_NOTE"]

#: What a layout comparison leaves out, in one line.
LAYOUT_NOTE = ("Compared as wheel layouts: the short form's zero-width and locked-caster measures and its "
               "single-parameter effects (a chair's named fields) do not apply to a layout.")


def stable_up_to_bounded(layout: Layout, reverse: bool = False) -> tuple[float, str]:
    """The speed up to which ``layout`` is stable (linear model, free frictionless casters), and its status: the
    searched range's ends as bounds (a bound is a value).

    Parameters
    ----------
    layout : Layout
    reverse : bool
        In reverse (the casters leading).

    Returns
    -------
    (float, str)
        ``(speed m/s, status)``: the destabilising critical speed and ``"found"``; the search's last speed
        (20 m/s) and ``"above"`` when stable at every speed searched; its first speed (0.02 m/s) and ``"below"``
        when unstable from the slowest speed or only stable above a speed.
    """
    speed, kind = critical_speed(layout, reverse)
    if kind == "destabilising":
        return float(speed), "found"
    if kind == "none-stable":
        return float(SEARCH_SPEEDS_M_S[-1]), "above"
    return float(SEARCH_SPEEDS_M_S[0]), "below"


def stable_up_to(layout: Layout, reverse: bool = False) -> float:
    """:func:`stable_up_to_bounded` as one number, m/s.

    Parameters
    ----------
    layout, reverse
        As :func:`stable_up_to_bounded`.

    Returns
    -------
    float
        The destabilising critical speed, m/s; ``inf`` for "above" (stable up to the searched 20 m/s), 0 for
        "below" (unstable at the slowest speed searched, 0.02 m/s, or only stable above a speed).
    """
    speed, status = stable_up_to_bounded(layout, reverse)
    return speed if status == "found" else (math.inf if status == "above" else 0.0)


def linear_rows(layouts: Sequence[Layout], speeds: Sequence[float] | np.ndarray) -> np.ndarray:
    """The propagated measures of each layout: its growth rates at ``speeds``, then its static stability.

    Parameters
    ----------
    layouts : sequence of Layout
    speeds : sequence of float
        Signed speeds, m/s.

    Returns
    -------
    ndarray
        Shape ``(layouts, len(speeds) + 1)``: growth rates (1/s, the layout's linear model, free frictionless
        casters), then the smallest ISO 7176-1 tip angle (deg).
    """
    u = [float(x) for x in speeds]
    out = np.empty((len(layouts), len(u) + 1))
    for i, lay in enumerate(layouts):
        out[i, :len(u)] = growth_rates(lay, u)
        out[i, -1] = min(tip_angles(lay).values())
    return out


def stable_up_to_rows(layouts: Sequence[Layout]) -> np.ndarray:
    """:func:`stable_up_to` of each layout, forward then in reverse.

    Parameters
    ----------
    layouts : sequence of Layout

    Returns
    -------
    ndarray
        Shape ``(layouts, 2)``, m/s (``inf``: stable up to the searched range's end).
    """
    return np.array([[stable_up_to(lay), stable_up_to(lay, reverse=True)] for lay in layouts]).reshape(-1, 2)


def bounded_interval(draws: np.ndarray, level: float, top: float) -> tuple[float, float]:
    """The central interval of draws of :func:`stable_up_to`, a draw stable up to the searched ``top`` being that
    bound (:func:`stability.study.censored.quantile`); an end that is such a bound is ``inf``.

    Parameters
    ----------
    draws : ndarray
        The draws' speeds, m/s (``inf``: stable up to ``top``).
    level : float
        Coverage, 0 < level < 1.
    top : float
        The searched range's end, m/s.

    Returns
    -------
    (float, float)
        The interval's ends, m/s.
    """
    bound = np.isinf(draws)
    values = np.where(bound, top, draws)
    sides = np.where(bound, ">", "=")
    ends = (quantile(values.tolist(), sides.tolist(), q) for q in ((1 - level) / 2, (1 + level) / 2))
    lo, hi = ((math.inf if side == ">" else v) for v, side in ends)
    return float(lo), float(hi)


def bounded_difference(a: np.ndarray, r: np.ndarray, level: float,
                       top: float) -> tuple[tuple[float, float], tuple[str, str]] | None:
    """The central interval of paired differences ``a - r`` of :func:`stable_up_to` draws, a draw stable up to the
    searched ``top`` counting as that bound (:func:`stability.study.censored.quantile`).

    A pair with ``a`` a bound and ``r`` a value differs by at least ``top - r`` (a lower bound), the reverse by at
    most ``a - top`` (an upper bound); a pair of two bounds says nothing and is left out.

    Parameters
    ----------
    a, r : ndarray
        Paired draws of the compared and the reference layout, m/s (``inf``: stable up to ``top``).
    level : float
        Coverage, 0 < level < 1.
    top : float
        The searched range's end, m/s.

    Returns
    -------
    ((float, float), (str, str)) or None
        The interval's ends, m/s, and each end's side (``"="`` a value, ``">"``/``"<"`` a bound); None when fewer
        than half the pairs say something (both bounds).
    """
    ba, br = np.isinf(a), np.isinf(r)
    keep = ~(ba & br)
    if keep.sum() < 0.5 * a.size:
        return None
    d = np.where(ba, top, a)[keep] - np.where(br, top, r)[keep]
    sides = np.where(ba[keep], ">", np.where(br[keep], "<", "="))
    (lo, s_lo), (hi, s_hi) = (quantile(d.tolist(), sides.tolist(), q) for q in ((1 - level) / 2, (1 + level) / 2))
    return (float(lo), float(hi)), (s_lo, s_hi)


def _propagated(layouts: Sequence[Layout], uncertainties: Sequence[Uncertainty | None], speeds: np.ndarray,
                samples: int, seed: int, level: float, pairing: str,
                nominal: np.ndarray) -> tuple[list, list[np.ndarray]]:
    """Each uncertain layout's propagation (:func:`stability.uncertainty.propagate` of :func:`linear_rows` and
    :func:`stable_up_to_rows`) and every layout's rows of draws, shape ``(samples, speeds + 3)`` (a layout without
    uncertainty repeats its own row of ``nominal``)."""
    results: list = []
    draws: list[np.ndarray] = []
    for i, (lay, unc) in enumerate(zip(layouts, uncertainties, strict=True)):
        if unc is None:
            results.append(None)
            draws.append(np.repeat(nominal[i:i + 1], samples, axis=0))
            continue
        seen: list[np.ndarray] = []

        def fn(ds: list, seen: list = seen) -> np.ndarray:
            lays = [d.layout for d in ds]
            seen.append(np.column_stack([linear_rows(lays, speeds), stable_up_to_rows(lays)]))
            return seen[-1]

        # "shared": the same seed for every layout, so a table of one name is the same unknown in each (the short
        # form's pairing, stability.compare.compute.compare); "independent": separate seeds
        res = propagate(LayoutDraw(lay), unc, fn, samples=samples,  # type: ignore[arg-type]
                        seed=seed if pairing == "shared" else seed + 1009 * i, level=level)
        results.append(res)
        draws.append(seen[-1])                       # propagate's second call: the draws
    return results, draws


def compare_layouts(layouts: Sequence[Layout], *, labels: Sequence[str] | None = None,
                    speeds: Sequence[float] = (0.5, 0.75, 1.0, 1.5), nonlinear: bool = False,
                    uncertainties: Sequence[Uncertainty | None] | None = None, samples: int = 1000, seed: int = 0,
                    level: float = 0.95, pairing: str = "shared") -> Comparison:
    """Compare layouts; the first is the reference.

    Parameters
    ----------
    layouts : sequence of Layout
        Two or more.
    labels : sequence of str, optional
        Unique labels (default the names).
    speeds : sequence of float
        Signed speeds of the growth rates, m/s (negative: reverse; ``0.01 <= |U| <= 20``).
    nonlinear : bool
        Also the critical impulse at :data:`~stability.settings.reference.REFERENCE_SPEED` (and at its negative
        when a speed is negative): the layout simulator's search.
    uncertainties : sequence of (Uncertainty or None), optional
        One per layout, tables naming its axes (:func:`stability.advise.layout_axes.load_layout_uncertainty`;
        None: taken as exact).  The growth rates and the static stability get central intervals
        (:func:`stability.uncertainty.propagate` of :func:`linear_rows`) and each difference from the reference
        an interval from the draws, as the short form's comparison; so do the speeds up to which a layout is
        stable, forward and in reverse (a critical-speed search per draw, as the short form's critical speeds; a
        draw stable up to the searched 20 m/s counts as that bound, :func:`stability.study.censored.quantile`, and
        an interval end that is such a bound is infinite).  The critical impulse is not propagated (a push search
        per draw; the short form's comparison does not either).
    samples, seed : int
        Draws per uncertain layout (:data:`stability.settings.bounds.SAMPLES`) and their seed.
    level : float
        Interval coverage, 0 < level < 1.
    pairing : {"shared", "independent"}
        As :func:`stability.compare.compute.compare`.

    Returns
    -------
    Comparison
        ``chairs`` are the layouts; ``effects`` empty; ``model`` ``"layout"``; ``max_speed`` the searched 20 m/s;
        ``curve_speeds`` the forward curve's speeds, and in reverse their negatives too when a speed is negative.
    """
    layouts = list(layouts)
    if len(layouts) < 2:
        raise ValueError(f"layouts: {len(layouts)} given; valid: at least two")
    labels = tuple(labels) if labels is not None else tuple(lay.name for lay in layouts)
    if len(labels) != len(layouts) or len(set(labels)) != len(labels):
        raise ValueError(f"labels={labels!r} is invalid; valid: one unique label per layout")
    if pairing not in ("shared", "independent"):
        raise ValueError(f"pairing={pairing!r} is invalid; valid: 'shared' or 'independent'")
    samples = int(SAMPLES.check("samples", samples, integer=True))
    level = CONFIDENCE_LEVEL.check("level", level)
    uncs = list(uncertainties) if uncertainties is not None else [None] * len(layouts)
    if len(uncs) != len(layouts):
        raise ValueError(f"uncertainties: {len(uncs)} given for {len(layouts)} layouts; valid: one per layout")
    u = np.asarray(speeds, dtype=float)
    # each uncertain draw: the rates at the speeds, then a critical-speed search forward and in reverse (the grid
    # and its bisection), the short form's count (stability.linear.intervals.solves_per_draw)
    check_eigen_work("samples", int(samples) * sum(x is not None for x in uncs),
                     solves_per_draw(len(u), len(SEARCH_SPEEDS_M_S)))
    # (layouts, speeds + 3): the growth rates, the static stability, stable up to forward and in reverse
    rows = np.column_stack([linear_rows(layouts, u), stable_up_to_rows(layouts)])
    results, draws = (_propagated(layouts, uncs, u, int(samples), int(seed), level, pairing, rows)
                      if any(x is not None for x in uncs) else ([None] * len(layouts), None))

    def ivs(col: int) -> tuple[tuple[float, float] | None, ...]:
        return tuple(None if r is None else (float(r.low[col]), float(r.high[col])) for r in results)

    qs = [Quantity(f"growth_rate_1_s@{s:g}", f"growth rate at {s:g} m/s" + (" (reverse)" if s < 0 else ""), "1/s",
                   False, tuple(float(x) for x in rows[:, k]), ivs(k))
          for k, s in enumerate(u)]
    top = float(SEARCH_SPEEDS_M_S[-1])
    for j, way in enumerate(("forward", "reverse")):
        col = len(u) + 1 + j                          # the draws' columns: rates, static stability, fwd, rev
        qs.append(Quantity(f"stable_up_to_{way}_m_s", f"stable up to ({way}, linear)", "m/s", True,
                           tuple(float(x) for x in rows[:, col]),
                           tuple(None if r is None or draws is None else bounded_interval(draws[i][:, col], level, top)
                                 for i, r in enumerate(results)),
                           f"stable up to {top:g} m/s"))
    qs.append(Quantity("static_stability_deg", "static stability (ISO 7176-1, smallest)", "deg", True,
                       tuple(float(x) for x in rows[:, len(u)]), ivs(len(u))))
    column = ({q.key: j for j, q in enumerate(qs[:len(u)])}
              | {"static_stability_deg": len(u), "stable_up_to_forward_m_s": len(u) + 1,
                 "stable_up_to_reverse_m_s": len(u) + 2})
    push = None
    if nonlinear:
        signs = [1.0] + ([-1.0] if bool(np.any(u < 0)) else [])
        for sign in signs:
            v = sign * REFERENCE_SPEED
            # as the short form's comparison: a push search that never reached the level is a bound (inf, "never
            # reached up to ..."), one already past it at the smallest push is 0 (stability.study.censored)
            row = [layout_critical_impulses(lay, v)[0] for lay in layouts]
            vals = tuple(np.inf if r.status == "never" else 0.0 if r.status == "below" else float(r.bound_Ns)
                         for r in row)
            largest = max(r.largest_tried_Ns for r in row)
            qs.append(Quantity(f"critical_impulse_Ns@{v:g}", f"critical impulse at {v:g} m/s", "N s", True, vals,
                               (None,) * len(layouts), f"level not reached with pushes up to {largest:.3g} N s"))
        push = (f"{THESIS_PUSH.force:g} N lateral at the c.g. for {THESIS_PUSH.duration:g} s, scaled; every caster "
                "trailing the direction of travel at the start (the layout simulator)")
    bounded = ("stable_up_to_forward_m_s", "stable_up_to_reverse_m_s")

    def difference(q: Quantity, i: int) -> Difference:
        if draws is None or q.key not in column:
            return _difference(q, i, labels[i], labels[0], None, level)
        a, r = draws[i][:, column[q.key]], draws[0][:, column[q.key]]
        if q.key not in bounded:
            return _difference(q, i, labels[i], labels[0], a - r, level)
        d = _difference(q, i, labels[i], labels[0], None, level)
        found = bounded_difference(a, r, level, top)
        if found is None:
            return d
        (lo, hi), sides = found
        # a bound end counts at its value, the conservative position (stability.study.censored)
        return dataclasses.replace(d, interval=(lo, hi), interval_sides=sides, distinguishable=bool(lo > 0 or hi < 0))

    diffs = tuple(difference(q, i) for i in range(1, len(layouts)) for q in qs)
    curve_speeds = (tuple(-x for x in reversed(CURVE_SPEEDS)) if bool(np.any(u < 0)) else ()) + tuple(CURVE_SPEEDS)
    curves = tuple(tuple(float(x) for x in growth_rates(lay, curve_speeds)) for lay in layouts)
    unc_info = None if draws is None else {"samples": int(samples), "seed": int(seed), "level": float(level),
                                           "pairing": pairing}
    return Comparison(tuple(layouts), labels, "layout", tuple(float(s) for s in u), top, tuple(qs), diffs, (),
                      curve_speeds, curves, unc_info, (None,) * len(layouts), push)
