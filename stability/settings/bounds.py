"""Valid ranges of settings: one :class:`Bound` type for the API's checks and the command lines' parsing.

A bound is a closed or open interval with a unit.  The run settings
(:class:`stability.settings.run.RunSpec`) carry theirs in their field metadata;
the command lines' other numeric options are in
:data:`stability.cli.numbers.OPTION_BOUNDS`.  A refusal always names the
parameter, its value and :meth:`Bound.text`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

__all__ = ["Bound", "number_text"]


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

    def holds(self, value: float) -> bool:
        """True when ``value`` lies in the range (NaN never does).

        Parameters
        ----------
        value : float

        Returns
        -------
        bool
        """
        if self.signed:
            value = abs(value)
        return ((self.lo < value if self.open_lo else self.lo <= value)
                and (value < self.hi if self.open_hi else value <= self.hi))
