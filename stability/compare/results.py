"""The comparison's results: per-measure values (:class:`Quantity`), differences from the reference chair
(:class:`Difference`), single-parameter effects (:class:`SingleEffect`, :class:`EffectSet`) and the whole
(:class:`Comparison`), computed by :mod:`stability.compare.compute` and :mod:`stability.compare.layouts`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from stability.chair import Chair
from stability.layout.model import Layout
from stability.linear.intervals import LinearIntervals

__all__ = ["Quantity", "Difference", "SingleEffect", "EffectSet", "Comparison"]


@dataclass(frozen=True)
class Quantity:
    """One measure for every chair.

    Attributes
    ----------
    key : str
        JSON key with its unit, e.g. ``"growth_rate_1_s@0.75"``.
    label : str
        In words, e.g. ``"growth rate at 0.75 m/s"``.
    unit : str
    higher_is_more_stable : bool
        Ranking direction (a growth rate: lower is more stable; a critical speed: higher).
    values : tuple of float
        One per chair; ``inf`` for a critical speed that does not exist (stable up to the
        searched speed), ``nan`` where undefined.
    intervals : tuple
        One per chair: ``(low, high)`` central interval, or None without an uncertainty file.
    none_means : str
        What an infinite value means, in words (e.g. ``"no crossing below 30 m/s"``).
    """

    key: str
    label: str
    unit: str
    higher_is_more_stable: bool
    values: tuple[float, ...]
    intervals: tuple[tuple[float, float] | None, ...]
    none_means: str = ""


@dataclass(frozen=True)
class Difference:
    """How one chair differs from the reference (first) chair on one measure.

    Attributes
    ----------
    key : str
        The :class:`Quantity` key.
    chair : str
        Label of the compared chair.
    absolute : float or None
        ``value(chair) - value(reference)`` in the quantity's unit; None when either is infinite/undefined.
    percent : float or None
        ``100 absolute / |value(reference)|``; None when the reference value is 0 or not finite, or when the two
        values have opposite signs (a stable and an unstable growth rate, an understeering and an oversteering
        chair: a percentage of a quantity that crosses zero says nothing).
    more_stable : str
        Label of the more stable chair, ``"equal"``, ``"undetermined"`` or ``"not separable"`` (both values are
        bounds of the quantity's search, :attr:`Quantity.none_means`).
    interval : (float, float) or None
        Central interval of the difference from paired draws (see :func:`compare`), or None.
    distinguishable : bool or None
        With uncertainty: whether the interval of the difference excludes 0 (None without uncertainty).
    interval_sides : (str, str)
        Each end of ``interval`` a value (``"="``) or a bound (``">"``: the end lies above its value, ``"<"``:
        below; :mod:`stability.study.censored`), as a difference of measures found only as bounds of their search
        can be.
    """

    key: str
    chair: str
    absolute: float | None
    percent: float | None
    more_stable: str
    interval: tuple[float, float] | None
    distinguishable: bool | None
    interval_sides: tuple[str, str] = ("=", "=")


@dataclass(frozen=True)
class SingleEffect:
    """The effect of one parameter difference applied alone to the reference chair.

    Attributes
    ----------
    field : str
        Chair field.
    reference_value, value : Any
        The field's value in the reference and in the compared chair.
    growth_rate : float or None
        Change of the growth rate at :data:`stability.settings.reference.REFERENCE_SPEED`, 1/s (None: not computable).
    locked_critical_speed : float or None
        Change of the locked-caster critical speed, m/s (None: not computable or no finite critical speed).
    error : str or None
        Why the change alone gives no valid chair (e.g. it moves the c.g. outside the wheels).
    """

    field: str
    reference_value: Any
    value: Any
    growth_rate: float | None
    locked_critical_speed: float | None
    error: str | None = None


@dataclass(frozen=True)
class EffectSet:
    """Single-parameter effects of one chair against the reference, with the total and the interaction remainder.

    Attributes
    ----------
    chair : str
        Label of the compared chair.
    effects : tuple of SingleEffect
    total_growth_rate, total_locked_critical_speed : float or None
        The whole difference (chair minus reference), 1/s and m/s.
    remainder_growth_rate, remainder_locked_critical_speed : float or None
        Total minus the sum of the single effects (interactions); None when a term is missing.
    """

    chair: str
    effects: tuple[SingleEffect, ...]
    total_growth_rate: float | None
    total_locked_critical_speed: float | None
    remainder_growth_rate: float | None
    remainder_locked_critical_speed: float | None


@dataclass(frozen=True)
class Comparison:
    """Everything ``python -m stability.compare`` reports.

    Attributes
    ----------
    chairs : tuple of Chair
    labels : tuple of str
        Unique labels, in order; the first chair is the reference.
    model : str
    speeds : tuple of float
        m/s.
    max_speed : float
        Upper end of the critical-speed search, m/s.
    quantities : tuple of Quantity
    differences : tuple of Difference
        Every non-reference chair against the reference, per quantity.
    effects : tuple of EffectSet
    curve_speeds : tuple of float
        Speeds of the growth-rate curves, m/s.
    curves : tuple of tuple of float
        Growth rate of each chair at ``curve_speeds``, 1/s.
    uncertainty : dict or None
        ``{"samples", "seed", "level", "pairing", "files"}`` when intervals were computed.
    intervals : tuple of (LinearIntervals or None)
        Per chair.
    push : str or None
        The push convention of the nonlinear measures (None without them).
    """

    chairs: tuple[Chair | Layout, ...]
    labels: tuple[str, ...]
    model: str
    speeds: tuple[float, ...]
    max_speed: float
    quantities: tuple[Quantity, ...]
    differences: tuple[Difference, ...]
    effects: tuple[EffectSet, ...]
    curve_speeds: tuple[float, ...]
    curves: tuple[tuple[float, ...], ...]
    uncertainty: dict[str, Any] | None
    intervals: tuple[LinearIntervals | None, ...]
    push: str | None

    def quantity(self, key: str) -> Quantity:
        """The quantity with JSON key ``key``."""
        for q in self.quantities:
            if q.key == key:
                return q
        raise KeyError(key)
