"""Which panels can apply to a chair: the report's rules for leaving a panel out and saying so in one line
(issue 35: empty panels and zero-effect panels become one line)."""

from __future__ import annotations

import numpy as np

from stability.report.compute import ReportData

__all__ = ["NON_OSCILLATORY", "FLAT_GROWTH", "columns", "flat_growth", "no_effect", "no_effect_line",
           "stable_everywhere"]

#: Below this |imaginary part| (rad/s) at every speed a mode set is non-oscillatory: its frequency panel is
#: one line (numpy returns exactly 0 for a real eigenvalue of a real matrix; the margin covers rounding).
NON_OSCILLATORY = 1e-9


#: A growth-rate panel whose largest real part moves by less than this fraction of its size over the parameter's
#: whole span is one line instead of a panel (the doubling time, ln 2 / rate, then moves by less than 1 % too).
FLAT_GROWTH = 0.01


def stable_everywhere(locus) -> bool:
    """True when every eigenvalue of a speed locus has a negative real part at every speed: no critical speed.

    Parameters
    ----------
    locus : stability.rootlocus.SpeedLocus

    Returns
    -------
    bool
    """
    return bool(np.all(np.asarray(locus.eigenvalues).real < 0.0))


def flat_growth(loc) -> bool:
    """True when a growth-rate locus moves by less than :data:`FLAT_GROWTH` of its size over its span.

    Parameters
    ----------
    loc : stability.rootlocus.ParameterLocus

    Returns
    -------
    bool
    """
    a = loc.max_real
    return float(np.ptp(a)) < FLAT_GROWTH * float(np.max(np.abs(a)))


def columns(n: int) -> int:
    """Panels per row for ``n`` small multiples: one row up to 4, else two or more rows of 3 or 4.

    Parameters
    ----------
    n : int
        Panels.

    Returns
    -------
    int
    """
    return n if n <= 4 else (3 if n <= 6 else 4)


def no_effect(d: ReportData) -> tuple[list, list]:
    """The parametric study's sweeps split into those with an effect and those without: a sweep whose speeds
    (or bounds) all lie within the bisection's tolerance of each other moves nothing the search can resolve.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    (list, list)
        Sweeps with an effect (ranked), sweeps without one (ranked).
    """
    tol = d.settings.tol
    ranked = d.chair_sweeps.ranked()
    flat = [s for s in ranked if float(np.ptp(s.speeds)) <= tol]
    return [s for s in ranked if s not in flat], flat


def no_effect_line(d: ReportData, flat: list) -> str:
    """One line for the sweeps without an effect: what each tried and the speed it gives (m/s).

    Parameters
    ----------
    d : ReportData
    flat : list of stability.study.Sweep
        The sweeps without an effect (:func:`no_effect`).

    Returns
    -------
    str
        Empty when ``flat`` is.
    """
    if not flat:
        return ""
    parts = []
    for s in flat:
        lo, hi = f"{float(s.speeds.min()):.3g}", f"{float(s.speeds.max()):.3g}"
        status = {r.status for r in s.results}
        speed = (f"{lo} m/s" if lo == hi else f"{lo}-{hi} m/s") if status == {"found"} else (
            f"above {hi} m/s" if status == {"above"} else f"below {lo} m/s" if status == {"below"} else
            f"{lo}-{hi} m/s (bounds included)")
        tried = (", ".join(s.labels) if s.labels is not None else
                 f"{s.value_text(0)} to {s.value_text(len(s.values) - 1)}" + ("" if s.unit == "-" else f" {s.unit}"))
        parts.append(f"{s.label} ({tried}): {speed}")
    return (f"No effect within the search's {d.settings.tol:g} m/s (not drawn): " + "; ".join(parts) + ".")
