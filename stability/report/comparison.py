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
from stability.study.censored import compare, side_of

__all__ = ["Baseline", "KeyNumbers", "key_numbers", "report_key_numbers", "comparison_rows"]


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
    shimmy_margin_m : float or None
        Signed distance of its trail from the nearest shimmy boundary at the advisor's use speeds, nominal
        estimates (m; :func:`stability.shimmy.band.shimmy_band`, as the advisor's for the report's chair).
    """

    chair: Chair
    summary: Any
    speed: Any
    impulse: Any
    slope: SlopeSection | None
    shimmy: ShimmySection | None
    shimmy_margin_m: float | None = None


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
        The speed, or the bracket's end it lies beyond (``equal_instability_side``), m/s.
    critical_impulse_Ns : float or None
        The impulse, or the largest push tried when none spins the chair (``critical_impulse_side``), N s.
    holding_moment_N_m_per_deg : float or None
    shimmy_margin_m : float or None
        Signed distance of the trail from the nearest shimmy boundary at the use speeds, nominal estimates, m
        (positive: clear of every shimmy zone; negative: inside one).
    equal_instability_side, critical_impulse_side : str
        ``"="`` (found), ``">"`` (a lower bound) or ``"<"`` (an upper bound): :mod:`stability.study.censored`.
    """

    growth_rate_1_s: float | None
    doubling_time_s: float | None
    locked_critical_speed_m_s: float | None
    equal_instability_speed_m_s: float | None
    critical_impulse_Ns: float | None
    holding_moment_N_m_per_deg: float | None
    shimmy_margin_m: float | None
    equal_instability_side: str = "="
    critical_impulse_side: str = "="

    def side(self, attr: str) -> str:
        """The side of a value (``"="`` for the measures that are never censored)."""
        return {"equal_instability_speed_m_s": self.equal_instability_side,
                "critical_impulse_Ns": self.critical_impulse_side}.get(attr, "=")


def key_numbers(summary: Any, speed: Any, impulse: Any, slope: SlopeSection | None,
                shimmy_margin_m: float | None) -> KeyNumbers:
    """Collect :class:`KeyNumbers` from a chair's computed results.

    Parameters
    ----------
    summary : StabilitySummary
    speed : EqualInstability
    impulse : CriticalImpulse or None
    slope : SlopeSection or None
    shimmy_margin_m : float or None
        m.

    Returns
    -------
    KeyNumbers
    """
    row = next((r for r in summary.divergence if abs(r.speed - REFERENCE_SPEED) < 1e-9), None)
    locked = next((x.speed for x in summary.locked_crossings if x.direction == "destabilising"), None)
    margin = None if shimmy_margin_m is None or not math.isfinite(shimmy_margin_m) else float(shimmy_margin_m)
    return KeyNumbers(
        None if row is None else float(row.rate),
        None if row is None else row.time_to_double,
        locked,
        float(speed.value_or_bound),
        None if impulse is None else float(impulse.bound_Ns),
        None if slope is None else slope.per_degree,
        margin,
        side_of(speed.status),
        "=" if impulse is None else side_of(impulse.status))


def report_key_numbers(d: Any) -> tuple[KeyNumbers, KeyNumbers]:
    """The report's chair and its baseline (``d.baseline`` must be set), computed the same way.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    (KeyNumbers, KeyNumbers)
    """
    b = d.baseline
    this = key_numbers(d.summary, d.chair_speed, d.impulses[0] if d.impulses else None, d.slope,
                       d.advice.verdict.shimmy_margin_m.value)
    return this, key_numbers(b.summary, b.speed, b.impulse, b.slope, b.shimmy_margin_m)


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
    ("shimmy margin (trail from the nearest boundary)", "shimmy_margin_m", "m", 3, True),
)

#: Measures that are None when the chair is stable there (a better value than any number), and their words.
_NONE_IS_STABLE = {"doubling_time_s": "none (stable)", "locked_critical_speed_m_s": "none (stable)"}
#: Rows that restate another row's measure (not counted again in the page's "better on N of M").
RESTATED = ("time for a heading error to double",)

_BETTER = {"better": "this chair", "worse": "baseline", "equal": "equal", "undecided": "undecided (bounds)"}


def _fmt(v: float | None, side: str, digits: int) -> str:
    return "-" if v is None else ("" if side == "=" else f"{side} ") + f"{v:.{digits}g}"


def comparison_rows(this: KeyNumbers, base: KeyNumbers) -> list[list[str]]:
    """Rows of the side-by-side table: measure, this chair, baseline, change, which is better.

    A bound ("> 3 m/s") is compared as the set of values it allows (:func:`stability.study.censored.compare`):
    above 3 m/s beats 1.2 m/s, and two bounds that overlap are undecided.  The shimmy margin is better when
    larger (a chair inside a shimmy zone has a negative margin).

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
        sa, sb = this.side(attr), base.side(attr)
        if attr in _NONE_IS_STABLE and (a is None or b is None):
            # no doubling / no locked-caster critical speed: the error dies out, the chair is stable there
            change = "-"
            better = "equal" if a is None and b is None else ("this chair" if a is None else "baseline")
            rows.append([f"{label} ({unit})", _NONE_IS_STABLE[attr] if a is None else _fmt(a, sa, digits),
                         _NONE_IS_STABLE[attr] if b is None else _fmt(b, sb, digits), change, better])
            continue
        if a is None or b is None:
            change, better = "-", "-"
        else:
            exact = sa == "=" and sb == "="
            change = ("-" if not exact else
                      f"{100 * (a / b - 1):+.0f} %" if b != 0 and a * b > 0 else f"{a - b:+.3g} {unit}")
            better = _BETTER[compare(a, sa, b, sb, higher)]
        rows.append([f"{label} ({unit})", _fmt(a, sa, digits), _fmt(b, sb, digits), change, better])
    return rows
