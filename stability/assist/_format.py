"""Number formatting shared by the assist's tables and JSON rows."""

from __future__ import annotations

import math

__all__ = ["json_float", "fmt"]


def json_float(x: float | None) -> float | str | None:
    """A float for JSON: finite as is, ``inf`` as ``"inf"``/``"-inf"``, NaN and None as None.

    Parameters
    ----------
    x : float or None

    Returns
    -------
    float, str or None
    """
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else (None if math.isnan(x) else ("inf" if x > 0 else "-inf"))


def fmt(x: float | str | None, spec: str = ".3g", none: str = "-") -> str:
    """``format(x, spec)``, with ``none`` for None, an infinite margin as ``unlim`` and ``nan`` spelt out.

    A margin without a crossover is unlimited (``unlim``, ``-unlim``), a result and
    not a failure; ``nan`` is a failure, which the command line refuses to print
    (:func:`stability.cli.check_finite_text`).

    Parameters
    ----------
    x : float, str or None
        The value (a str is returned as is).
    spec : str
        Format specification.
    none : str
        Text for None.

    Returns
    -------
    str
    """
    if x is None:
        return none
    if isinstance(x, str):
        return x
    if not math.isfinite(x):
        return "unlim" if x > 0 else ("-unlim" if x < 0 else "nan")
    return format(x, spec)
