"""Distributions of uncertain chair fields and their seeded sampling.

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
import zlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from stability import chair as chair_mod
from stability.chair import Chair

__all__ = ["Distribution", "Uncertainty", "KEYS"]

_TEXT_FIELDS = {"name", "caster_position", "main_tire", "caster_tire"}
KEYS = {"distribution", "std", "mean", "low", "high", "relative", "fields"}


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
    valid_fields : frozenset of str, optional
        The fields a table may name (default: the short form's numeric chair fields; a wheel layout's are
        :func:`stability.advise.layout_axes.layout_axes`).
    """

    name: str
    fields: tuple[str, ...]
    kind: str
    std: float | None = None
    mean: float | None = None
    low: float | None = None
    high: float | None = None
    relative: bool = False
    valid_fields: frozenset | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        def bad(key: str, value: Any, valid: str) -> ValueError:
            return ValueError(f"uncertainty [{self.name}] {key}={value!r} is invalid; valid range: {valid}")

        valid = (set(chair_mod.field_names()) - _TEXT_FIELDS - {"camber_coefficient"} if self.valid_fields is None
                 else set(self.valid_fields))
        what = "a numeric chair field" if self.valid_fields is None else "a numeric layout field"
        for f in self.fields:
            if f not in valid:
                raise bad("field" if f != self.name else "table", f, f"{what} {sorted(valid)}")
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
