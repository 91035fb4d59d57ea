"""Linear results with intervals: Monte Carlo propagation of parameter uncertainty (and a delta-method check)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.linear.batch import ChairBatch, check_eigen_work
from stability.linear.summary import zero_width
from stability.settings.bounds import CONFIDENCE_LEVEL, SAMPLES
from stability.settings.defaults import MAX_SPEED
from stability.uncertainty import Uncertainty, delta_method, propagate

__all__ = ["LinearIntervals", "linear_intervals", "MAX_SAMPLES", "solves_per_draw", "GRID_POINTS",
           "BISECTION_STEPS"]

#: Largest Monte Carlo sample (:data:`stability.settings.bounds.SAMPLES`'s upper end; bounded work: ~1 ms per chair).
MAX_SAMPLES = int(SAMPLES.hi)


#: Speeds of the critical-speed search grid (geometric from :data:`GRID_LOW` to ``max_speed``).
GRID_POINTS = 600
#: First speed of the critical-speed search grid, m/s.
GRID_LOW = 0.01
#: Bisection steps of a critical speed (grid spacing 1.3 % of at most 100 m/s down to 1e-6 m/s: 2^21 > 1.3e6).
BISECTION_STEPS = 21


def solves_per_draw(n_speeds: int, n_grid: int) -> int:
    """Eigenvalue problems of one Monte Carlo draw: the table's speeds, then both caster states on the grid.

    Parameters
    ----------
    n_speeds, n_grid : int
        Speeds of the divergence table and of the critical-speed search grid.

    Returns
    -------
    int
    """
    return n_speeds + 2 * (n_grid + BISECTION_STEPS)


@dataclass(frozen=True)
class LinearIntervals:
    """Central intervals of the linear results over the uncertain chair parameters.

    Attributes
    ----------
    speeds : tuple of float
        Speeds of the divergence table, m/s.
    level : float
        Coverage of each interval (0.95: 2.5th to 97.5th percentile).
    samples, seed : int
        Monte Carlo draws and the seed (identical seed, identical intervals).
    rate : tuple of (float, float)
        Growth rate of the least stable free-caster mode at each speed, 1/s.
    rate_delta : tuple of (float, float)
        The same by the first-order delta method (a fast check; exact for a linear response).
    zero_width_critical, locked_critical, free_critical : tuple
        ``(low, high, fraction)`` of the zero-width, full-width locked-caster and
        free-caster critical speeds, m/s; ``fraction`` is the share of draws in
        which that critical speed exists in the searched range.
    locked_beyond, free_beyond : tuple of (float, float)
        Of the draws without a full-width critical speed in the searched range, the shares (of all draws) that are
        stable at every speed searched (above its end: the critical speed is a bound, "> max_speed") and that are
        unstable from its first speed ("< 0.01 m/s"): with the ``fraction`` above they add up to 1.
    search_m_s : (float, float)
        The first and last speeds of the critical-speed search, m/s.
    dominant_parameters : tuple of (str, float)
        Uncertain parameters ranked by their first-order share of the variance.
    """

    speeds: tuple[float, ...]
    level: float
    samples: int
    seed: int
    rate: tuple[tuple[float, float], ...]
    rate_delta: tuple[tuple[float, float], ...]
    zero_width_critical: tuple[float, float, float]
    locked_critical: tuple[float, float, float]
    free_critical: tuple[float, float, float]
    dominant_parameters: tuple[tuple[str, float], ...]
    locked_beyond: tuple[float, float] = (0.0, 0.0)
    free_beyond: tuple[float, float] = (0.0, 0.0)
    search_m_s: tuple[float, float] = (GRID_LOW, MAX_SPEED)


def _outputs(chairs: list[Chair], model: str, speeds: np.ndarray, grid: np.ndarray,
             statuses: list | None = None) -> np.ndarray:
    b = ChairBatch(chairs, model)
    zw = np.array([zero_width(c).critical_speed or np.nan for c in chairs])
    (lv, ls), (fv, fs) = (b.first_critical_speed_bounded(grid, casters) for casters in ("locked", "free"))
    if statuses is not None:                  # the statuses of this call's chairs (the bounds' sides)
        statuses.append((ls, fs))
    return np.column_stack([b.growth_rates(speeds), zw, np.where(ls == "found", lv, np.nan),
                            np.where(fs == "found", fv, np.nan)])


def _beyond(status: np.ndarray) -> tuple[float, float]:
    """Shares of the draws stable at every speed searched ("above") and unstable from its first ("below")."""
    return float(np.mean(status == "above")), float(np.mean(status == "below"))


def linear_intervals(chair: Chair, uncertainty: Uncertainty, *, model: str = "exact",
                     speeds: Sequence[float] | np.ndarray = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0),
                     max_speed: float = MAX_SPEED,
                     samples: int = 1000, seed: int = 0, level: float = 0.95) -> LinearIntervals:
    """Intervals of the growth rates and critical speeds over the parameter uncertainty.

    Parameters
    ----------
    chair : Chair
        The nominal chair.
    uncertainty : Uncertainty
        Distributions of its uncertain fields (:func:`stability.uncertainty.load_uncertainty`).
    model : {"exact", "thesis"}
        Equation variant.
    speeds : sequence of float
        Speeds of the divergence table, m/s.
    max_speed : float
        Upper end of the critical-speed search, m/s (grid of 600 speeds from 0.01).
    samples : int
        Monte Carlo draws, 1 to :data:`MAX_SAMPLES`.
    seed : int
        Seed of the draws.
    level : float
        Interval coverage, 0 < level < 1.

    Returns
    -------
    LinearIntervals
    """
    samples = int(SAMPLES.check("samples", samples, integer=True))
    level = CONFIDENCE_LEVEL.check("level", level)
    U = np.asarray(speeds, dtype=float)
    grid = np.geomspace(GRID_LOW, max_speed, GRID_POINTS)
    k = len(U)
    check_eigen_work("samples", int(samples), solves_per_draw(k, len(grid)))

    statuses: list = []

    def fn(chairs: list[Chair]) -> np.ndarray:
        return _outputs(chairs, model, U, grid, statuses)

    mc = propagate(chair, uncertainty, fn, samples=int(samples), seed=int(seed), level=level)
    locked_status, free_status = statuses[-1]   # propagate calls fn with the nominal chair, then with the draws
    dm = delta_method(chair, uncertainty, lambda cs: fn(cs)[:, :k], level=level)

    def triple(j: int) -> tuple[float, float, float]:
        return (float(mc.low[j]), float(mc.high[j]), float(mc.finite_fraction[j]))

    return LinearIntervals(
        speeds=tuple(float(x) for x in U), level=float(level), samples=int(samples), seed=int(seed),
        rate=tuple((float(mc.low[j]), float(mc.high[j])) for j in range(k)),
        rate_delta=tuple((float(np.atleast_1d(dm.low)[j]), float(np.atleast_1d(dm.high)[j])) for j in range(k)),
        zero_width_critical=triple(k), locked_critical=triple(k + 1), free_critical=triple(k + 2),
        dominant_parameters=tuple((n, float(s)) for n, s in mc.dominant_parameters),
        locked_beyond=_beyond(locked_status), free_beyond=_beyond(free_status),
        search_m_s=(float(grid[0]), float(grid[-1])),
    )
