"""Valid ranges of settings: one :class:`Bound` type for the API's checks and the command lines' parsing.

A bound is a closed or open interval with a unit.  The run settings
(:class:`stability.settings.run.RunSpec`) carry theirs in their field metadata;
the command lines' other numeric options are in
:data:`stability.cli.numbers.OPTION_BOUNDS`.  A refusal always names the
parameter, its value and :meth:`Bound.text`.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from stability.runtime.checks import MAX_SPEED, MIN_SPEED, is_real, real_value, value_text

__all__ = ["Bound", "number_text", "SEARCH_MAX_SPEED", "SPEED", "SIGNED_SPEED", "SAMPLES", "NONLINEAR_SAMPLES",
           "SEED", "CONFIDENCE_LEVEL", "HUMAN_SPEED", "ADVISE_CROSS_SLOPE", "MIN_TIP_ANGLE", "DRIVE_WHEEL_RADIUS",
           "ADVISE_SPEED", "ADVISE_SPEED_COUNT", "LAYOUT_MAX_SPEED"]


def number_text(x: float) -> str:
    """A bound as written: integers in full (4294967295), others in ``%g``.

    Parameters
    ----------
    x : float

    Returns
    -------
    str
    """
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return str(int(x)) if float(x).is_integer() and abs(x) < 1e15 else f"{x:g}"


class Bound(NamedTuple):
    """Plausible range of a number, ``lo <= value <= hi`` in ``unit`` (``<`` at an open end).

    Attributes
    ----------
    lo, hi : float
        Ends of the range, in ``unit`` (``-inf``/``inf`` for an unbounded end).
    unit : str
        Unit of the value (``""``: dimensionless).
    open_lo, open_hi : bool
        Whether the end itself is excluded.
    signed : bool
        The range is of the magnitude: ``lo <= |value| <= hi``, either sign
        (a speed, negative in reverse).
    """

    lo: float
    hi: float
    unit: str
    open_lo: bool = False
    open_hi: bool = False
    signed: bool = False

    def text(self, name: str = "value") -> str:
        """The range in words, e.g. ``"0 < value <= 20 m/s"``.

        Parameters
        ----------
        name : str
            What the range is of (default ``"value"``).

        Returns
        -------
        str
        """
        unit = f" {self.unit}" if self.unit else ""
        if self.signed:
            name = f"|{name}|"
        if math.isinf(self.hi) and self.hi > 0:
            return f"{name} {'>' if self.open_lo else '>='} {number_text(self.lo)}{unit}"
        return (f"{number_text(self.lo)} {'<' if self.open_lo else '<='} {name} {'<' if self.open_hi else '<='} "
                f"{number_text(self.hi)}{unit}")

    def holds(self, value: Any) -> Any:
        """True when ``value`` lies in the range (NaN never does); element by element for an array.

        Parameters
        ----------
        value : float or ndarray

        Returns
        -------
        bool or ndarray of bool
        """
        if self.signed:
            value = abs(value)
        return ((self.lo < value if self.open_lo else self.lo <= value)
                & (value < self.hi if self.open_hi else value <= self.hi))

    def check(self, name: str, value: Any, *, integer: bool = False) -> float:
        """``value`` as a float (an int when ``integer``) if it lies in the range, else raise naming ``name``.

        Parameters
        ----------
        name : str
            The argument's name in the message.
        value : Any
            A real number (an integer when ``integer``; booleans and strings are refused).
        integer : bool, optional
            Only whole numbers (a count).

        Returns
        -------
        float or int
            In the bound's unit.

        Raises
        ------
        TypeError
            ``value`` is not a real number (an integer when ``integer``).
        ValueError
            ``value`` is NaN, infinite or outside the range; the message names ``name``, the value and
            :meth:`text`.
        """
        kind = "an integer" if integer else "a number"
        x = real_value(value) if is_real(value) else math.nan
        if not is_real(value) or (integer and math.isfinite(x) and not x.is_integer()):
            raise TypeError(f"{name}={value_text(value)} is invalid; valid values: {kind}, {self.text(name)}")
        if math.isnan(x) or not self.holds(x):
            raise ValueError(f"{name}={value_text(value)} is invalid; valid range: {self.text(name)}")
        return int(value) if integer else x


#: The critical-speed search's upper end, m/s (``stability.analyse(max_speed=)``, ``--max-speed``): above the
#: slowest speed whose rates are not lost in round-off, up to the fastest speed searched.
SEARCH_MAX_SPEED = Bound(MIN_SPEED, MAX_SPEED, "m/s", open_lo=True)

#: A wheelchair's speed, m/s (``--speed``, a run's speed): from the slowest whose growth rates are not lost in
#: round-off (:data:`stability.runtime.checks.MIN_SPEED`) to 20 m/s (72 km/h), faster than any wheelchair.
SPEED = Bound(MIN_SPEED, 20.0, "m/s")

#: :data:`SPEED` as a signed speed, negative in reverse (:class:`stability.settings.run.RunSpec`'s ``speed``, the
#: wheel layouts' speeds).
SIGNED_SPEED = SPEED._replace(signed=True)

#: Monte Carlo draws of a linear uncertainty interval (``samples=``, ``--samples``): about 1 ms of eigenvalues per
#: draw, so the largest is about 20 s of work.
SAMPLES = Bound(1, 20_000, "")

#: Simulated draws of the nonlinear uncertainty check (``nonlinear_intervals(samples=)``,
#: ``--nonlinear-samples``): each draw is a critical-impulse search of tens of runs, so a tenth of :data:`SAMPLES`.
NONLINEAR_SAMPLES = Bound(1, 2_000, "")

#: Seed of the Monte Carlo draws (``seed=``, ``--seed``): numpy's legacy seeds, 32 bits.
SEED = Bound(0, 2**32 - 1, "")

#: A confidence level (``level=``, ``--level``): a probability strictly between 0 and 1.
CONFIDENCE_LEVEL = Bound(0.0, 1.0, "", open_lo=True, open_hi=True)

#: The human-limited speed's search range, m/s (:mod:`stability.driver.linear`, the advisor's ``intended_speed``,
#: ``--intended-speed``): a slow walk to a fast power chair, as a size (in reverse too).
HUMAN_SPEED = Bound(0.1, 6.0, "m/s")

#: The advisor's cross slope for its drive constraint, deg (``advise(cross_slope_deg=)``, ``--cross-slope``):
#: level ground to 8 deg, steeper than an accessible route's running slope (1:12, 4.8 deg) and far above its
#: cross slope (1:48, 1.2 deg).
ADVISE_CROSS_SLOPE = Bound(0.0, 8.0, "deg")

#: A drive wheel's radius, m (:class:`stability.chair.power.DriveTrain`, the assist's ``--wheel-radius``): up to a
#: 1 m (39 in) wheel, larger than any wheelchair's.
DRIVE_WHEEL_RADIUS = Bound(0.0, 0.5, "m", open_lo=True)

#: The advisor's use speeds, their size in m/s (``--speeds`` of ``python -m stability.advise``; in reverse too):
#: the thesis's indoor range around 0.75 m/s, up to a brisk walk.
ADVISE_SPEED = Bound(0.1, 3.0, "m/s")

#: Most use speeds the advisor measures at (``advise(speeds=)``, ``--speeds`` of the advisor and the report): every
#: one costs each candidate its simulations, so twelve keep a call within the work budget.
ADVISE_SPEED_COUNT = 12

#: The top of a wheel layout's critical-speed search and root locus, m/s (``critical_speed --max-speed`` for a
#: layout): above the locus's first speed (0.05 m/s) up to :data:`SEARCH_MAX_SPEED`'s end.
LAYOUT_MAX_SPEED = Bound(0.05, MAX_SPEED, "m/s", open_lo=True)

#: The smallest acceptable static stability angle, deg (``advise(min_tip_deg=)``, ``--min-tip-deg``): 0 sets no
#: tip-angle limit (a chair tips over at 0 deg) and none is stable beyond 60 deg.
MIN_TIP_ANGLE = Bound(0.0, 60.0, "deg")
