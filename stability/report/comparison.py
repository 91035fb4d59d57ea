"""A report's comparison with a baseline chair (``report --compare BASELINE``): the key numbers side by side.

Every number is computed by the same functions, settings and model as the report's own chair
(:func:`stability.report.compute.compute` passes them in), so the two columns differ only by the chair.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from stability.chair import Chair
from stability.linear import analyse
from stability.report.shimmy_data import ShimmySection
from stability.report.slope_data import SlopeSection
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["Baseline", "KeyNumbers", "key_numbers", "comparison_rows"]


@dataclass(frozen=True, eq=False)
class Baseline:
    """What the report computes for the baseline chair.

    Attributes
    ----------
    chair : Chair
    summary : stability.linear.StabilitySummary
    speed : EqualInstability
        Its equal-instability speed (same reference case and bisection as the report's chair).
    impulse : CriticalImpulse
        Its critical impulse at the reference speed.
    slope : SlopeSection or None
    shimmy : ShimmySection or None
    """

    chair: Chair
    summary: Any
    speed: Any
    impulse: Any
    slope: SlopeSection | None
    shimmy: ShimmySection | None


@dataclass(frozen=True)
class KeyNumbers:
    """The numbers a comparison table shows for one chair (None: not defined for it).

    Attributes
    ----------
    growth_rate_1_s : float or None
        Largest real part at the reference speed, free frictionless casters, 1/s.
    doubling_time_s : float or None
    locked_critical_speed_m_s : float or None
    equal_instability_speed_m_s : float or None
    critical_impulse_Ns : float or None
    holding_moment_N_m_per_deg : float or None
    shimmy_boundary_m : float or None
        Linear shimmy boundary (trail) at the nominal estimates, m.
    """

    growth_rate_1_s: float | None
    doubling_time_s: float | None
    locked_critical_speed_m_s: float | None
    equal_instability_speed_m_s: float | None
    critical_impulse_Ns: float | None
    holding_moment_N_m_per_deg: float | None
    shimmy_boundary_m: float | None


def key_numbers(summary: Any, speed: Any, impulse: Any, slope: SlopeSection | None,
                shimmy: ShimmySection | None) -> KeyNumbers:
    """Collect :class:`KeyNumbers` from a chair's computed results.

    Parameters
    ----------
    summary : StabilitySummary
    speed : EqualInstability
    impulse : CriticalImpulse or None
    slope : SlopeSection or None
    shimmy : ShimmySection or None

    Returns
    -------
    KeyNumbers
    """
    row = next((r for r in summary.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    locked = next((x.speed for x in summary.locked_crossings if x.direction == "destabilising"), None)
    return KeyNumbers(
        None if row is None else float(row.rate),
        None if row is None else row.time_to_double,
        locked,
        speed.speed if speed.status == "found" else None,
        None if impulse is None else impulse.impulse_Ns,
        None if slope is None else slope.per_degree,
        None if shimmy is None or not math.isfinite(shimmy.critical) else shimmy.critical)


def baseline_summary(chair: Chair, model: str) -> Any:
    """The baseline's linear summary, on the same speeds as the report's chair.

    Parameters
    ----------
    chair : Chair
    model : str

    Returns
    -------
    StabilitySummary
    """
    return analyse(chair, model=model, speeds=(0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0))


#: (label, attribute, unit, digits, higher is better)
_ROWS = (
    (f"linear growth rate at {REFERENCE_SPEED:g} m/s (frictionless)", "growth_rate_1_s", "1/s", 3, False),
    ("time for a heading error to double", "doubling_time_s", "s", 2, True),
    ("critical speed with locked casters", "locked_critical_speed_m_s", "m/s", 3, True),
    ("equal-instability speed", "equal_instability_speed_m_s", "m/s", 3, True),
    (f"critical impulse at {REFERENCE_SPEED:g} m/s", "critical_impulse_Ns", "N s", 3, True),
    ("holding moment on a cross slope", "holding_moment_N_m_per_deg", "N m/deg", 3, False),
    ("shimmy boundary (trail, nominal estimates)", "shimmy_boundary_m", "m", 3, False),
)


def _fmt(v: float | None, digits: int) -> str:
    return "-" if v is None else f"{v:.{digits}g}"


def comparison_rows(this: KeyNumbers, base: KeyNumbers) -> list[list[str]]:
    """Rows of the side-by-side table: measure, this chair, baseline, change, which is better.

    Parameters
    ----------
    this, base : KeyNumbers

    Returns
    -------
    list of list of str
    """
    rows = []
    for label, attr, unit, digits, higher in _ROWS:
        a, b = getattr(this, attr), getattr(base, attr)
        if a is None or b is None:
            change, better = "-", "-"
        else:
            change = f"{100 * (a / b - 1):+.0f} %" if b != 0 and a * b > 0 else f"{a - b:+.3g} {unit}"
            better = "equal" if abs(a - b) <= 1e-3 * max(abs(a), abs(b)) else (
                "this chair" if (a > b) == higher else "baseline")
        rows.append([f"{label} ({unit})", _fmt(a, digits), _fmt(b, digits), change, better])
    return rows
