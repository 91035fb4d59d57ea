"""Propagating parameter uncertainty through a function of the chair: seeded Monte Carlo and the delta method."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from statistics import NormalDist
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.uncertainty.distributions import Uncertainty

__all__ = ["PropagationResult", "propagate", "DeltaResult", "delta_method"]


def _evaluate(fn: Callable[[list[Chair]], Any], chairs: list[Chair]) -> tuple[np.ndarray, bool]:
    """fn's outputs as (chairs, outputs) and whether fn returns one number per chair."""
    out = np.asarray(fn(chairs), dtype=float)
    if out.ndim == 0 or out.shape[0] != len(chairs):
        raise ValueError(f"fn returned shape {out.shape}; valid: first axis of length {len(chairs)} "
                         "(one row per chair)")
    return out.reshape(len(chairs), -1), out.ndim == 1


def _shape(a: np.ndarray, scalar: bool):
    return float(a[0]) if scalar else a


@dataclass(frozen=True)
class PropagationResult:
    """Monte Carlo propagation of parameter uncertainty through a function of the chair.

    Attributes
    ----------
    samples, seed : int
        Number of chairs drawn and the seed.
    level : float
        Coverage of the central interval [low, high] (e.g. 0.95: 2.5th to 97.5th percentiles).
    low, high, median, mean, std : float or ndarray
        Over the finite outputs, per output (floats when ``fn`` returns one number per chair).
    nominal : float or ndarray
        ``fn`` at the chair's own values.
    finite_fraction : float or ndarray
        Fraction of draws with a finite output (e.g. a critical speed that exists).
    shares : dict
        Parameter -> share of the output variance (first order, per output),
        from a regression of the outputs on the standardised draws.
    r_squared : float or ndarray
        Variance explained by that linear regression (near 1: the shares are reliable).
    dominant_parameters : tuple of (str, float)
        Parameters ranked by share (averaged over outputs), largest first.
    rejected : int
        Draws redrawn because they made an invalid chair.
    """

    samples: int
    seed: int
    level: float
    low: Any
    high: Any
    median: Any
    mean: Any
    std: Any
    nominal: Any
    finite_fraction: Any
    shares: dict[str, Any] = field(default_factory=dict)
    r_squared: Any = float("nan")
    dominant_parameters: tuple[tuple[str, float], ...] = ()
    rejected: int = 0


def _regression_shares(x: dict[str, np.ndarray], y: np.ndarray) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """First-order variance shares from standardised regression coefficients (SRC^2, normalised)."""
    names = [k for k, v in x.items() if np.std(v) > 0]
    k = y.shape[1]
    shares = {name: np.zeros(k) for name in x}
    r2 = np.full(k, np.nan)
    for j in range(k):
        ok = np.isfinite(y[:, j])
        yj = y[ok, j]
        if not names or ok.sum() < len(names) + 2 or np.ptp(yj) == 0:
            continue
        cols = [(x[n][ok] - x[n][ok].mean()) / (x[n][ok].std() or 1.0) for n in names]
        a = np.column_stack(cols + [np.ones(ok.sum())])
        beta, *_ = np.linalg.lstsq(a, yj, rcond=None)
        fitted = a @ beta
        r2[j] = 1 - np.sum((yj - fitted) ** 2) / np.sum((yj - yj.mean()) ** 2)
        b2 = beta[:-1] ** 2
        total = b2.sum()
        for n, b in zip(names, b2, strict=True):
            shares[n][j] = b / total if total > 0 else 0.0
    return shares, r2


def _rank(shares: Mapping[str, np.ndarray]) -> tuple[tuple[str, float], ...]:
    avg = {n: float(np.mean(s)) for n, s in shares.items()}
    return tuple(sorted(avg.items(), key=lambda kv: -kv[1]))


def propagate(chair: Chair, uncertainty: Uncertainty, fn: Callable[[list[Chair]], Any], *, samples: int = 1000,
              seed: int = 0, level: float = 0.95) -> PropagationResult:
    """Monte Carlo propagation: intervals of ``fn`` over seeded draws of the uncertain parameters.

    Parameters
    ----------
    chair : Chair
        The nominal chair.
    uncertainty : Uncertainty
        Distributions of its uncertain fields.
    fn : callable
        Maps a list of chairs to an array with one row per chair (a number
        or a vector of numbers each; NaN where undefined).  It is called
        twice: once with ``[chair]``, once with all draws.
    samples : int
        Number of draws.
    seed : int
        Seed (identical seed, identical result).
    level : float
        Central interval coverage, 0 < level < 1.

    Returns
    -------
    PropagationResult
    """
    if not 0 < level < 1:
        raise ValueError(f"level={level!r} is invalid; valid range: 0 < level < 1")
    y0, scalar = _evaluate(fn, [chair])
    nominal = y0[0]
    chairs, rejected, unit = uncertainty._sample(chair, int(samples), seed, 0.5)
    y = _evaluate(fn, chairs)[0]
    q = 100 * np.array([(1 - level) / 2, 0.5, (1 + level) / 2])
    finite = np.isfinite(y)
    stats = np.full((5, y.shape[1]), np.nan)
    for j in range(y.shape[1]):
        yj = y[finite[:, j], j]
        if yj.size:
            stats[:3, j] = np.percentile(yj, q)
            if np.ptp(yj) == 0:  # identical outputs (e.g. zero uncertainty): exactly that value, zero spread
                stats[3, j], stats[4, j] = yj[0], 0.0
            else:
                stats[3, j], stats[4, j] = yj.mean(), yj.std(ddof=1)
    spread = {d.name: unit[d.name] for d in uncertainty.distributions
              if any(d.std_value(float(getattr(chair, f))) > 0 for f in d.fields)}
    shares, r2 = _regression_shares(spread, y)
    shares = {d.name: shares.get(d.name, np.zeros(y.shape[1])) for d in uncertainty.distributions}
    return PropagationResult(
        samples=int(samples), seed=int(seed), level=float(level),
        low=_shape(stats[0], scalar), high=_shape(stats[2], scalar), median=_shape(stats[1], scalar),
        mean=_shape(stats[3], scalar), std=_shape(stats[4], scalar), nominal=_shape(nominal, scalar),
        finite_fraction=_shape(finite.mean(axis=0), scalar),
        shares={n: _shape(s, scalar) for n, s in shares.items()}, r_squared=_shape(r2, scalar),
        dominant_parameters=_rank(shares), rejected=rejected)


@dataclass(frozen=True)
class DeltaResult:
    """First-order (delta-method) propagation: ``value +- z std`` with ``std^2 = sum (df/dp_i sigma_i)^2``.

    Output quantities are in ``fn``'s units; each is a float when ``fn``
    returns one number per chair, else an array over ``fn``'s outputs.

    Attributes
    ----------
    level : float
        Interval coverage, 0 < level < 1 (e.g. 0.95).
    value : float or ndarray
        ``fn`` at the parameters' means.
    std : float or ndarray
        First-order standard deviation of ``fn``.
    low, high : float or ndarray
        ``value -+ z std`` with z the normal quantile at ``(1 + level)/2``.
    contributions : dict of str to float or ndarray
        Table name -> ``df/dp_i sigma_i``, signed, in output units.
    dominant_parameters : tuple of (str, float)
        Table names with their share of the variance (mean over outputs,
        0 to 1), largest first.
    """

    level: float
    value: Any
    std: Any
    low: Any
    high: Any
    contributions: dict[str, Any]
    dominant_parameters: tuple[tuple[str, float], ...]


def delta_method(chair: Chair, uncertainty: Uncertainty, fn: Callable[[list[Chair]], Any], *,
                 level: float = 0.95, step: float = 0.01) -> DeltaResult:
    """First-order propagation with central finite differences of ``fn`` (a fast check on :func:`propagate`).

    Linearises about every parameter's mean; each derivative uses steps of
    ``step`` standard deviations (``2 p + 1`` chairs in one call of ``fn``).
    Exact for ``fn`` linear in the parameters; it misses curvature and
    truncation, which the Monte Carlo result shows.

    Parameters
    ----------
    chair : Chair
        Nominal chair; the uncertain fields are moved to their distributions' means.
    uncertainty : Uncertainty
        The uncertain parameters (p tables).
    fn : callable
        ``fn(chairs) -> array`` with one row (a number or a vector) per chair.
    level : float, optional
        Interval coverage, 0 < level < 1 (default 0.95).
    step : float, optional
        Finite-difference step in standard deviations (default 0.01).

    Returns
    -------
    DeltaResult
        Value, standard deviation, interval and per-parameter contributions.

    Raises
    ------
    ValueError
        If ``level`` is outside (0, 1) or ``fn`` does not return one row per chair.
    """
    if not 0 < level < 1:
        raise ValueError(f"level={level!r} is invalid; valid range: 0 < level < 1")
    means, sigmas = {}, {}
    centre: dict[str, float] = {}
    for d in uncertainty.distributions:
        for f in d.fields:
            centre[f] = d.mean_value(float(getattr(chair, f)))
        means[d.name] = {f: centre[f] for f in d.fields}
        sigmas[d.name] = {f: d.std_value(float(getattr(chair, f))) for f in d.fields}
    base = chair.replace(**centre) if centre else chair
    chairs = [base]
    for d in uncertainty.distributions:
        for sign in (1, -1):
            chairs.append(base.replace(**{f: means[d.name][f] + sign * step * sigmas[d.name][f] for f in d.fields}))
    y, scalar = _evaluate(fn, chairs)
    contrib = {}
    for i, d in enumerate(uncertainty.distributions):
        contrib[d.name] = (y[1 + 2 * i] - y[2 + 2 * i]) / (2 * step)  # df/dz for z in standard deviations
    var = sum((c**2 for c in contrib.values()), np.zeros(y.shape[1]))
    sd = np.sqrt(var)
    z = NormalDist().inv_cdf((1 + level) / 2)
    shares = {n: np.where(var > 0, c**2 / np.where(var > 0, var, 1), 0.0) for n, c in contrib.items()}
    return DeltaResult(level=float(level), value=_shape(y[0], scalar), std=_shape(sd, scalar),
                       low=_shape(y[0] - z * sd, scalar), high=_shape(y[0] + z * sd, scalar),
                       contributions={n: _shape(c, scalar) for n, c in contrib.items()},
                       dominant_parameters=_rank(shares))
