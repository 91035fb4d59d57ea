"""Parameter uncertainty: TOML distributions per chair field, seeded sampling, Monte Carlo and delta-method propagation.

An uncertainty file has one table per uncertain chair field::

    [s1]
    distribution = "normal"   # around the chair's own value; optional mean
    std = 0.01

    [pin_friction]            # a label: one draw shared by several fields
    fields = ["pin_friction_left", "pin_friction_right"]
    distribution = "uniform"
    low = -0.5
    high = 0.5
    relative = true           # low/high are fractions of each field's own value

Draws of each table come from their own stream seeded by (seed, table name),
so adding a table leaves the others' draws unchanged.
"""

from __future__ import annotations

import math
import os
import sys
import zlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from statistics import NormalDist
from typing import Any

import numpy as np

from .. import chair as chair_mod
from ..chair import Chair

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["Distribution", "Uncertainty", "load_uncertainty", "loads_uncertainty", "from_mapping",
           "PropagationResult", "DeltaResult", "propagate", "delta_method"]

_TEXT_FIELDS = {"name", "caster_position", "main_tire", "caster_tire"}
_KEYS = {"distribution", "std", "mean", "low", "high", "relative", "fields"}


@dataclass(frozen=True)
class Distribution:
    """One uncertain parameter (possibly shared by several chair fields).

    Attributes
    ----------
    name : str
        Table name (a chair field, or a label when ``fields`` is given).
    fields : tuple of str
        Chair fields that receive the draw.
    kind : {"normal", "uniform"}
    std : float or None
        Normal: standard deviation (field units, or a fraction of the centre if ``relative``).
    mean : float or None
        Normal: centre (absolute, field units); default the chair's own value.
    low, high : float or None
        Uniform: bounds (field units, or fractional deviations from the chair's value if ``relative``).
    relative : bool
    """

    name: str
    fields: tuple[str, ...]
    kind: str
    std: float | None = None
    mean: float | None = None
    low: float | None = None
    high: float | None = None
    relative: bool = False

    def __post_init__(self) -> None:
        def bad(key: str, value: Any, valid: str) -> ValueError:
            return ValueError(f"uncertainty [{self.name}] {key}={value!r} is invalid; valid range: {valid}")

        valid = set(chair_mod.field_names()) - _TEXT_FIELDS - {"camber_coefficient"}
        for f in self.fields:
            if f not in valid:
                raise bad("field" if f != self.name else "table", f, f"a numeric chair field {sorted(valid)}")
        if self.kind == "normal":
            if self.std is None or not math.isfinite(self.std) or self.std < 0:
                raise bad("std", self.std, ">= 0")
            if self.mean is not None and not math.isfinite(self.mean):
                raise bad("mean", self.mean, "a finite number")
        elif self.kind == "uniform":
            if self.low is None or self.high is None or not (math.isfinite(self.low) and math.isfinite(self.high)):
                raise bad("low/high", (self.low, self.high), "two finite numbers")
            if self.high < self.low:
                raise bad("high", self.high, f">= low = {self.low!r}")
        else:
            raise bad("distribution", self.kind, "'normal' or 'uniform'")

    def _unit(self, n: int, rng: np.random.Generator) -> np.ndarray:
        """Standardised draws: N(0, 1) for normal, U(0, 1) for uniform."""
        return rng.standard_normal(n) if self.kind == "normal" else rng.random(n)

    def values(self, nominal: float, unit: np.ndarray) -> np.ndarray:
        """Field values for standardised draws ``unit`` around the chair's value ``nominal``."""
        if self.kind == "normal":
            centre = nominal if self.mean is None else self.mean
            std = float(self.std or 0.0)
            sd = std * abs(centre) if self.relative else std
            return centre + sd * unit
        low, high = float(self.low or 0.0), float(self.high or 0.0)
        lo, hi = (nominal * (1 + low), nominal * (1 + high)) if self.relative else (low, high)
        return lo + (hi - lo) * unit

    def mean_value(self, nominal: float) -> float:
        """Expected value of the field (field units)."""
        return float(self.values(nominal, np.array([0.0 if self.kind == "normal" else 0.5]))[0])

    def std_value(self, nominal: float) -> float:
        """Standard deviation of the field (field units)."""
        if self.kind == "normal":
            centre = nominal if self.mean is None else self.mean
            std = float(self.std or 0.0)
            return std * abs(centre) if self.relative else std
        lo, hi = self.values(nominal, np.array([0.0, 1.0]))
        return float(abs(hi - lo)) / math.sqrt(12)

    def to_toml(self) -> str:
        """This table as TOML text."""
        lines = [f"[{self.name}]"]
        if self.fields != (self.name,):
            lines.append("fields = [" + ", ".join(f'"{f}"' for f in self.fields) + "]")
        lines.append(f'distribution = "{self.kind}"')
        for key in ("std", "mean", "low", "high"):
            v = getattr(self, key)
            if v is not None:
                lines.append(f"{key} = {float(v)!r}")
        if self.relative:
            lines.append("relative = true")
        return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Uncertainty:
    """A set of independent :class:`Distribution` s (each chair field in at most one).

    Attributes
    ----------
    distributions : tuple of Distribution
        The uncertain parameters, in file order; draws of different tables are
        independent (each table seeded from the seed and its name).
    """

    distributions: tuple[Distribution, ...] = ()

    def __post_init__(self) -> None:
        seen: dict[str, str] = {}
        for d in self.distributions:
            for f in d.fields:
                if f in seen:
                    raise ValueError(f"uncertainty: field {f!r} appears in both [{seen[f]}] and [{d.name}]; "
                                     "valid: each field in one table")
                seen[f] = d.name

    @property
    def names(self) -> tuple[str, ...]:
        """Table names, in file order."""
        return tuple(d.name for d in self.distributions)

    def __getitem__(self, name: str) -> Distribution:
        for d in self.distributions:
            if d.name == name:
                return d
        raise KeyError(name)

    def _rng(self, name: str, seed: int) -> np.random.Generator:
        return np.random.default_rng([int(seed), zlib.crc32(name.encode())])

    def unit_draws(self, n: int, seed: int) -> dict[str, np.ndarray]:
        """Standardised draws per table (N(0,1) or U(0,1)), ``n`` each."""
        if n < 1:
            raise ValueError(f"samples={n!r} is invalid; valid range: >= 1")
        return {d.name: d._unit(n, self._rng(d.name, seed)) for d in self.distributions}

    def field_values(self, chair: Chair, unit: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Chair-field arrays for standardised draws ``unit`` (from :meth:`unit_draws`)."""
        out = {}
        for d in self.distributions:
            for f in d.fields:
                out[f] = d.values(float(getattr(chair, f)), np.asarray(unit[d.name], dtype=float))
        return out

    def sample_arrays(self, chair: Chair, n: int, seed: int = 0) -> dict[str, np.ndarray]:
        """``n`` seeded draws of every uncertain field (field -> array), without validation."""
        return self.field_values(chair, self.unit_draws(n, seed))

    def sample(self, chair: Chair, n: int, seed: int = 0, *, max_rejected: float = 0.5) -> list[Chair]:
        """``n`` seeded chairs drawn around ``chair``.

        A draw that makes an invalid chair (say a negative pin friction) is
        redrawn: the distributions are truncated to valid chairs.  More than
        ``max_rejected`` of the draws rejected raises ValueError naming a
        parameter to fix.
        """
        return self._sample(chair, n, seed, max_rejected)[0]

    def _sample(self, chair: Chair, n: int, seed: int, max_rejected: float):
        unit = self.unit_draws(n, seed)
        rngs = {d.name: self._rng(d.name + "/redraw", seed) for d in self.distributions}
        chairs: list[Chair | None] = [None] * n
        todo = np.arange(n)
        rejected, last_error = 0, ""
        for _ in range(1000):
            vals = self.field_values(chair, {k: v[todo] for k, v in unit.items()})
            still = []
            for j, i in enumerate(todo):
                try:
                    chairs[i] = chair.replace(**{f: float(v[j]) for f, v in vals.items()})
                except ValueError as exc:
                    still.append(i)
                    last_error = str(exc)
            rejected += len(still)
            if rejected > max_rejected * n:
                raise ValueError(f"uncertainty: {rejected} of {n} draws give an invalid chair, e.g. {last_error}; "
                                 f"valid: at most {max_rejected:.0%} (narrow that distribution)")
            if not still:
                break
            todo = np.array(still)
            for d in self.distributions:
                unit[d.name][todo] = d._unit(len(todo), rngs[d.name])
        return chairs, rejected, unit

    def dumps(self) -> str:
        """TOML text that :func:`loads_uncertainty` reads back."""
        head = "# stability uncertainty file: one table per uncertain chair field (units as in the chair file)\n"
        return head + "\n".join(d.to_toml() for d in self.distributions)


def from_mapping(data: Mapping[str, Any]) -> Uncertainty:
    """Build an :class:`Uncertainty` from a parsed TOML mapping (table name -> table).

    Parameters
    ----------
    data : Mapping of str to Mapping
        Table name -> table with keys ``distribution`` (``"normal"`` or
        ``"uniform"``), ``std``, ``mean``, ``low``, ``high``, ``relative`` and
        ``fields`` (default ``[name]``); values in the chair file's units.

    Returns
    -------
    Uncertainty
        One :class:`Distribution` per table.

    Raises
    ------
    ValueError
        One line naming the table and key at fault.
    """
    dists = []
    for name, table in data.items():
        if not isinstance(table, Mapping):
            raise ValueError(f"uncertainty entry {name!r} = {table!r} is invalid; valid: a table [{name}]")
        unknown = set(table) - _KEYS
        if unknown:
            raise ValueError(f"uncertainty [{name}] has unknown key(s) {sorted(unknown)}; valid keys: {sorted(_KEYS)}")
        fields = table.get("fields", [name])
        if isinstance(fields, str) or not isinstance(fields, list) or not fields:
            raise ValueError(f"uncertainty [{name}] fields={fields!r} is invalid; valid: a list of chair fields")

        def num(key: str, table: Mapping[str, Any] = table, name: str = name) -> float | None:
            v = table.get(key)
            if v is None:
                return None
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise ValueError(f"uncertainty [{name}] {key}={v!r} is invalid; valid range: a number")
            return float(v)

        relative = table.get("relative", False)
        if not isinstance(relative, bool):
            raise ValueError(f"uncertainty [{name}] relative={relative!r} is invalid; valid: true or false")
        dists.append(Distribution(name, tuple(fields), str(table.get("distribution", "")), num("std"),
                                  num("mean"), num("low"), num("high"), relative))
    return Uncertainty(tuple(dists))


def loads_uncertainty(text: str) -> Uncertainty:
    """Parse uncertainty TOML text.

    Parameters
    ----------
    text : str
        TOML text as written by :meth:`Uncertainty.dumps` (one table per uncertain parameter).

    Returns
    -------
    Uncertainty
        As :func:`from_mapping`.
    """
    return from_mapping(tomllib.loads(text))


def load_uncertainty(path: str | os.PathLike[str]) -> Uncertainty:
    """Read an uncertainty TOML file.

    Parameters
    ----------
    path : str or os.PathLike
        The file (one table per uncertain parameter, see :func:`from_mapping`).

    Returns
    -------
    Uncertainty
        As :func:`from_mapping`.

    Raises
    ------
    ValueError
        If the file does not exist, is not valid TOML, or a table is invalid.
    """
    if not os.path.exists(path):
        raise ValueError(f"uncertainty file {str(path)!r} does not exist")
    with open(path, "rb") as fh:
        try:
            return from_mapping(tomllib.load(fh))
        except tomllib.TOMLDecodeError as exc:
            raise ValueError(f"uncertainty file {str(path)!r} is not valid TOML: {exc}") from None


# ---------------------------------------------------------------------------
# propagation
# ---------------------------------------------------------------------------
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
