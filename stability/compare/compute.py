"""Side-by-side comparison of chairs: per-measure values, differences from the first chair, single-parameter effects.

Measures: the growth rate of the least stable free-caster mode (and its time
to double) at a list of speeds, the full-width locked-caster critical speed,
the zero-width understeer coefficient and critical speed (Collins 1987,
eqs 5-15, 5-16) and, optionally, the nonlinear critical impulse.
Rationale and conventions: docs/compare.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from stability.chair import Chair, to_mapping
from stability.chair.model import takes_chairs
from stability.compare.results import Comparison, Difference, EffectSet, Quantity, SingleEffect
from stability.linear import zero_width
from stability.linear.batch import ChairBatch, check_eigen_work
from stability.linear.intervals import (
    BISECTION_STEPS,
    GRID_POINTS,
    LinearIntervals,
    linear_intervals,
    solves_per_draw,
)
from stability.runtime.checks import check_model
from stability.settings.bounds import SAMPLES
from stability.settings.defaults import SUMMARY_SPEEDS
from stability.settings.reference import REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.uncertainty import Uncertainty

__all__ = ["NOT_SEPARABLE", "Quantity", "Difference", "SingleEffect", "EffectSet", "Comparison", "compare",
           "DEFAULT_SPEEDS", "single_effects", "growth_curves"]

DEFAULT_SPEEDS = SUMMARY_SPEEDS
#: ``Difference.more_stable`` when both values are bounds of the same search (both beyond what it reached).
NOT_SEPARABLE = "not separable"
#: Speeds of the growth-rate curves in the figure, m/s.
CURVE_SPEEDS = tuple(float(x) for x in np.linspace(0.05, 3.0, 60))


def _grid(max_speed: float) -> np.ndarray:
    return np.geomspace(0.01, max_speed, GRID_POINTS)


def solves_per_sample(n_uncertain: int, n_speeds: int) -> int:
    """Eigenvalue problems per Monte Carlo sample of a comparison with ``n_uncertain`` uncertain chairs.

    Each uncertain chair: its intervals (:func:`~stability.linear.intervals.solves_per_draw`) and its paired
    draws (the table's speeds and the locked-caster search).

    Parameters
    ----------
    n_uncertain, n_speeds : int

    Returns
    -------
    int
    """
    return n_uncertain * (solves_per_draw(n_speeds, GRID_POINTS) + n_speeds + GRID_POINTS + BISECTION_STEPS)


def _locked(batch: ChairBatch, grid: np.ndarray) -> np.ndarray:
    """Locked-caster critical speeds; inf: stable over the whole grid; nan: unstable from its start."""
    crit = batch.first_critical_speed(grid.tolist(), "locked")
    start = batch.max_real_part(np.full(batch.n, grid[0]), "locked")
    return np.where(np.isnan(crit) & (start < 0), np.inf, crit)


def _zero_width(chairs: Sequence[Chair]) -> tuple[np.ndarray, np.ndarray]:
    zs = [zero_width(c) for c in chairs]
    kus = np.array([z.understeer_coefficient for z in zs])
    crit = np.array([np.inf if z.critical_speed is None else z.critical_speed for z in zs])
    return kus, crit


def _measures(chairs: Sequence[Chair], model: str, speeds: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Columns: growth rates at ``speeds``, locked critical speed, k_us, zero-width critical speed (row per chair)."""
    b = ChairBatch(list(chairs), model)
    kus, zcrit = _zero_width(chairs)
    return np.column_stack([b.growth_rates(speeds.tolist()), _locked(b, grid), kus, zcrit])


def _more_stable(a: float, b: float, higher: bool, la: str, lb: str, bounds: bool = False) -> str:
    if math.isnan(a) or math.isnan(b):
        return "undetermined"
    if bounds and math.isinf(a) and math.isinf(b) and a > 0 and b > 0:
        return NOT_SEPARABLE        # each somewhere above the search's bound: a bound is a value, not a tie
    if a == b:
        return "equal"
    return la if (a > b) == higher else lb


def _difference(q: Quantity, i: int, label: str, ref_label: str, samples: np.ndarray | None,
                level: float) -> Difference:
    a, r = q.values[i], q.values[0]
    finite = math.isfinite(a) and math.isfinite(r)
    absolute = a - r if finite else None
    percent = 100.0 * (a - r) / abs(r) if finite and r != 0 and a * r > 0 else None
    interval, dist = None, None
    if samples is not None:
        d = samples[np.isfinite(samples)]
        if d.size and d.size >= 0.5 * samples.size:
            lo, hi = np.percentile(d, [50 * (1 - level), 50 * (1 + level)])
            interval, dist = (float(lo), float(hi)), bool(lo > 0 or hi < 0)
        else:  # the measure is undefined or infinite in most draws: no interval of the difference
            dist = None
    more = _more_stable(a, r, q.higher_is_more_stable, label, ref_label, bool(q.none_means))
    return Difference(q.key, label, absolute, percent, more, interval, dist)


def single_effects(reference: Chair, other: Chair, label: str, *, model: str = "exact",
                   max_speed: float = 30.0) -> EffectSet:
    """Apply each differing field of ``other`` alone to ``reference`` and measure the change.

    Parameters
    ----------
    reference, other : Chair
    label : str
        Label of ``other``.
    model : {"exact", "thesis"}
    max_speed : float
        Upper end of the critical-speed search, m/s.

    Returns
    -------
    EffectSet
        Changes of the growth rate at :data:`stability.settings.reference.REFERENCE_SPEED` (1/s) and of the
        locked-caster critical speed (m/s); ``name`` is never compared.
    """
    ra, rb = to_mapping(reference), to_mapping(other)
    names = [f for f in sorted(set(ra) | set(rb)) if f != "name" and ra.get(f) != rb.get(f)]
    singles: list[Chair] = []
    errors: dict[str, str] = {}
    for f in names:
        try:
            singles.append(reference.replace(**{f: rb.get(f)}))
        except ValueError as exc:
            errors[f] = str(exc).splitlines()[0]
    speeds = np.array([REFERENCE_SPEED])
    m = _measures([reference, other, *singles], model, speeds, _grid(max_speed))
    g, lc = m[:, 0], m[:, 1]

    def diff(x: float, x0: float) -> float | None:
        return float(x - x0) if math.isfinite(x) and math.isfinite(x0) else None

    effects, k = [], 2
    for f in names:
        if f in errors:
            effects.append(SingleEffect(f, ra.get(f), rb.get(f), None, None, errors[f]))
            continue
        effects.append(SingleEffect(f, ra.get(f), rb.get(f), diff(g[k], g[0]), diff(lc[k], lc[0])))
        k += 1
    total_g, total_l = diff(g[1], g[0]), diff(lc[1], lc[0])

    def remainder(total: float | None, parts: list[float | None]) -> float | None:
        if total is None or any(p is None for p in parts):
            return None
        return float(total - math.fsum(p for p in parts if p is not None))

    return EffectSet(label, tuple(effects), total_g, total_l,
                     remainder(total_g, [e.growth_rate for e in effects]),
                     remainder(total_l, [e.locked_critical_speed for e in effects]))


@takes_chairs
def growth_curves(chairs: Sequence[Chair], model: str = "exact",
                  speeds: Sequence[float] = CURVE_SPEEDS) -> np.ndarray:
    """Growth rate of the least stable free-caster mode of each chair at each speed.

    Parameters
    ----------
    chairs : sequence of Chair
    model : {"exact", "thesis"}
    speeds : sequence of float
        m/s.

    Returns
    -------
    ndarray
        Shape (chairs, speeds), 1/s.
    """
    return ChairBatch(list(chairs), model).growth_rates(speeds)


def _paired_draws(chairs: Sequence[Chair], uncertainties: Sequence[Uncertainty | None], model: str,
                  speeds: np.ndarray, grid: np.ndarray, samples: int, seed: int, pairing: str) -> list[np.ndarray]:
    """Measure rows of every chair's draws (shape (samples, k)); a chair without uncertainty repeats its own row."""
    out = []
    for i, (c, u) in enumerate(zip(chairs, uncertainties, strict=True)):
        if u is None:
            out.append(np.repeat(_measures([c], model, speeds, grid), samples, axis=0))
            continue
        draws = u.sample(c, samples, seed if pairing == "shared" else seed + 1009 * i)
        out.append(_measures(draws, model, speeds, grid))
    return out


def _quantities(vals: np.ndarray, speeds: np.ndarray, ivs: Sequence[LinearIntervals | None]) -> list[Quantity]:
    k = len(speeds)

    def iv(get) -> tuple[tuple[float, float] | None, ...]:
        return tuple(None if x is None else get(x) for x in ivs)

    qs = []
    for j, s in enumerate(speeds):
        qs.append(Quantity(f"growth_rate_1_s@{s:g}", f"growth rate at {s:g} m/s", "1/s", False,
                           tuple(float(v) for v in vals[:, j]), iv(lambda x, j=j: x.rate[j])))
    qs.append(Quantity("locked_critical_speed_m_s", "locked-caster critical speed", "m/s", True,
                       tuple(float(v) for v in vals[:, k]), iv(lambda x: x.locked_critical[:2])))
    qs.append(Quantity("understeer_coefficient_rad", "zero-width understeer coefficient k_us", "rad", True,
                       tuple(float(v) for v in vals[:, k + 1]), tuple(None for _ in ivs)))
    qs.append(Quantity("zero_width_critical_speed_m_s", "zero-width critical speed", "m/s", True,
                       tuple(float(v) for v in vals[:, k + 2]), iv(lambda x: x.zero_width_critical[:2])))
    return qs


def _nonlinear(chairs: Sequence[Chair], model: str, nonlinear_speeds: Sequence[float]) -> tuple[list[Quantity], str]:
    from stability.study import critical_impulses  # the simulator (numba) is imported only when asked for

    flat_chairs = [c for _ in nonlinear_speeds for c in chairs]
    flat_speeds = np.array([float(s) for s in nonlinear_speeds for _ in chairs])
    run = RunSpec(model=model)
    res = critical_impulses(flat_chairs, flat_speeds, run)
    qs = []
    n = len(chairs)
    for j, s in enumerate(nonlinear_speeds):
        row = res[j * n:(j + 1) * n]
        vals = tuple(np.inf if r.status == "never" else 0.0 if r.status == "below" else float(r.impulse_Ns or np.nan)
                     for r in row)
        largest = max(r.largest_tried_Ns for r in row)
        qs.append(Quantity(f"critical_impulse_Ns@{s:g}", f"critical impulse at {s:g} m/s", "N s", True, vals,
                           tuple(None for _ in chairs), f"level not reached with pushes up to {largest:.3g} N s"))
    push = (f"{res[0].push}; reference push {THESIS_PUSH.describe(0.001)}" if res else THESIS_PUSH.describe(0.001)) \
        + f"; {run.friction_law} pin friction (docs/simulator.md)"
    return qs, push


def _user_speeds(chairs: Sequence[Chair], model: str, reaction_time: float) -> Quantity:
    """The speed a user with delay ``reaction_time`` can hold on each chair: the divergence rule
    (:func:`stability.driver.linear.rule_speed`, the advisor's limit), ``inf`` beyond the speeds it checks (a bound:
    stable for this user everywhere checked), 0 below them (not even at the slowest); no interval (the rule is not
    drawn over the uncertainty files)."""
    from stability.driver.linear import SPEED_RANGE_M_S, rule_speed

    vals = []
    for c in chairs:
        u, side = rule_speed(c, reaction_time, model)
        vals.append(math.inf if side == ">" else 0.0 if side == "<" else float(u))
    return Quantity("human_limited_speed_m_s", f"speed a user {reaction_time:g} s late holds", "m/s", True,
                    tuple(vals), tuple(None for _ in chairs),
                    f"held at every speed checked, up to {SPEED_RANGE_M_S[1]:g} m/s")


@takes_chairs
def compare(chairs: Sequence[Chair], *, labels: Sequence[str] | None = None, model: str = "exact",
            speeds: Sequence[float] = DEFAULT_SPEEDS, max_speed: float = 30.0,
            uncertainties: Sequence[Uncertainty | None] | None = None, samples: int = 1000, seed: int = 0,
            level: float = 0.95, pairing: str = "shared", nonlinear: bool = False,
            nonlinear_speeds: Sequence[float] = (REFERENCE_SPEED,), reaction_time: float | None = None) -> Comparison:
    """Compare two or more chairs on every measure, against the first.

    Parameters
    ----------
    chairs : sequence of Chair
        Two or more; the first is the reference.
    labels : sequence of str, optional
        Unique labels (default: the chairs' names, numbered when repeated).
    model : {"exact", "thesis"}
        Equation variant.
    speeds : sequence of float
        Speeds of the growth-rate table, m/s.
    max_speed : float
        Upper end of the critical-speed search, m/s (600-point geometric grid from 0.01 m/s).
    uncertainties : sequence of (Uncertainty or None), optional
        One per chair (None: that chair is taken as exact).
    samples, seed : int
        Monte Carlo draws per chair and their seed.
    level : float
        Interval coverage.
    pairing : {"shared", "independent"}
        "shared": every chair is drawn with the same seed, so a table of the same name gets the
        same standardised draw in every chair (the same unknown, e.g. the same user's inertia,
        in both); the difference is computed draw by draw.  "independent": separate seeds.
    nonlinear : bool
        Also compute the critical impulse (simulation; seconds per chair).
    nonlinear_speeds : sequence of float
        Speeds of the critical impulse, m/s.
    reaction_time : float, optional
        A user's effective delay, s: adds the speed that user can hold on each chair (:func:`_user_speeds`).

    Returns
    -------
    Comparison
    """
    chairs = tuple(chairs)
    if len(chairs) < 2:
        raise ValueError(f"chairs: {len(chairs)} given; valid: at least two chairs to compare")
    model = check_model(model)
    if pairing not in ("shared", "independent"):
        raise ValueError(f"pairing={pairing!r} is invalid; valid: 'shared' or 'independent'")
    samples = int(SAMPLES.check("samples", samples, integer=True))
    labels = tuple(labels) if labels is not None else unique_labels([c.name for c in chairs])
    if len(labels) != len(chairs) or len(set(labels)) != len(labels):
        raise ValueError(f"labels={list(labels)!r} is invalid; valid: one unique label per chair")
    uncs = tuple(uncertainties) if uncertainties is not None else (None,) * len(chairs)
    if len(uncs) != len(chairs):
        raise ValueError(f"uncertainties: {len(uncs)} given for {len(chairs)} chairs; valid: one per chair")
    U = np.asarray(speeds, dtype=float)
    check_eigen_work("samples", int(samples), solves_per_sample(sum(u is not None for u in uncs), len(U)))
    grid = _grid(max_speed)
    vals = _measures(chairs, model, U, grid)
    ivs = tuple(None if u is None else linear_intervals(c, u, model=model, speeds=U.tolist(), max_speed=max_speed,
                                                        samples=samples, seed=seed, level=level)
                for c, u in zip(chairs, uncs, strict=True))
    qs = _quantities(vals, U, ivs)
    draws = None
    if any(u is not None for u in uncs):
        draws = _paired_draws(chairs, uncs, model, U, grid, int(samples), int(seed), pairing)
    push = None
    if nonlinear:
        nq, push = _nonlinear(chairs, model, nonlinear_speeds)
        qs += nq
    if reaction_time is not None:
        qs.append(_user_speeds(chairs, model, reaction_time))
    diffs = []
    for i in range(1, len(chairs)):
        for j, q in enumerate(qs):
            d = None
            if draws is not None and j < vals.shape[1]:
                d = draws[i][:, j] - draws[0][:, j]
            diffs.append(_difference(q, i, labels[i], labels[0], d, level))
    effects = tuple(single_effects(chairs[0], c, labels[i], model=model, max_speed=max_speed)
                    for i, c in enumerate(chairs) if i > 0)
    curves = growth_curves(chairs, model)
    unc_info = None if draws is None else {"samples": int(samples), "seed": int(seed), "level": float(level),
                                           "pairing": pairing}
    return Comparison(chairs, labels, model, tuple(float(x) for x in U), float(max_speed), tuple(qs), tuple(diffs),
                      effects, CURVE_SPEEDS, tuple(tuple(float(v) for v in row) for row in curves), unc_info, ivs,
                      push)


def unique_labels(names: Sequence[str]) -> tuple[str, ...]:
    """The names, with ``" #2"``, ``" #3"``, ... appended to repeats (``["a", "a"]`` -> ``("a", "a #2")``)."""
    seen: dict[str, int] = {}
    out = []
    for n in names:
        seen[n] = seen.get(n, 0) + 1
        out.append(n if seen[n] == 1 else f"{n} #{seen[n]}")
    return tuple(out)
