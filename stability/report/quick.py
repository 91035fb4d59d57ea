"""What ``--quick`` coarsens, in words and as data, and the mark it puts next to the values that may move.

The quick report (:meth:`Settings.for_mode(True) <stability.report.settings.Settings.for_mode>`) bisects more
loosely, simulates shorter, sweeps fewer values and draws fewer points.  Page 1 says what it coarsens
(:func:`coarsened_text`), every value computed on a coarsened grid carries :data:`MARK` (:func:`mark`), and the
JSON lists the same settings (:func:`coarsened`).  Page 1's decision itself comes from the advisor
(:func:`stability.advise.advise`), which the report runs at its own full resolution in both modes.
"""

from __future__ import annotations

from typing import Any

from stability.report.settings import Settings
from stability.report.uncertainty_data import BAND_SPEEDS, NONLINEAR_SAMPLES, QUICK_BAND_SPEEDS, QUICK_NONLINEAR_SAMPLES

__all__ = ["MARK", "mark", "coarsened", "coarsened_text"]

#: Placed right after a value computed on a coarsened grid in a quick report (nothing in a full report).
MARK = "\u2020"


def mark(s: Settings) -> str:
    """:data:`MARK` for a quick report, empty for a full one.

    Parameters
    ----------
    s : Settings

    Returns
    -------
    str
    """
    return MARK if s.quick else ""


def _plan_size(plan: dict | None) -> int:
    from stability import study

    p = study.DEFAULT_PLAN if plan is None else plan
    return sum(len(v) for v in p.values() if v is not None)


def coarsened(s: Settings) -> list[dict[str, Any]]:
    """The settings a quick report coarsens: what each governs, its quick and its full value.

    Parameters
    ----------
    s : Settings
        The report's settings (empty list for full settings).

    Returns
    -------
    list of dict
        ``{"setting", "what", "quick", "full"}`` (values as numbers or lists of numbers; units in ``what``).
    """
    if not s.quick:
        return []
    f = Settings.for_mode(False)
    return [
        {"setting": "tol", "what": "equal-instability speed bisection tolerance, m/s", "quick": s.tol, "full": f.tol},
        {"setting": "bracket", "what": "equal-instability speed search bracket, m/s", "quick": list(s.bracket),
         "full": list(f.bracket)},
        {"setting": "impulse_rel_tol", "what": "relative tolerance of the critical impulses",
         "quick": s.impulse_rel_tol, "full": f.impulse_rel_tol},
        {"setting": "impulse_tol", "what": "relative tolerance of the elasticities' critical impulses",
         "quick": s.impulse_tol, "full": f.impulse_tol},
        {"setting": "duration", "what": "simulated time of the nonlinear runs, s", "quick": s.duration,
         "full": f.duration},
        {"setting": "plan", "what": "parametric study: chair variants", "quick": _plan_size(s.plan),
         "full": _plan_size(f.plan)},
        {"setting": "map_grid", "what": "stability maps: speeds x (frictions, impulses)",
         "quick": [len(s.map_speeds), len(s.map_frictions), len(s.map_impulses)],
         "full": [len(f.map_speeds), len(f.map_frictions), len(f.map_impulses)]},
        {"setting": "locus_points", "what": "root-locus points: speed, parameter, gain",
         "quick": [s.speed_points, s.locus_points, s.gain_points],
         "full": [f.speed_points, f.locus_points, f.gain_points]},
        {"setting": "shimmy_grid", "what": "trail chart: trails x speeds",
         "quick": [len(s.shimmy_trails), len(s.shimmy_speeds)], "full": [len(f.shimmy_trails), len(f.shimmy_speeds)]},
        {"setting": "uncertainty", "what": "uncertainty page: band speeds, nonlinear draws (at most)",
         "quick": [len(QUICK_BAND_SPEEDS), QUICK_NONLINEAR_SAMPLES], "full": [len(BAND_SPEEDS), NONLINEAR_SAMPLES]},
    ]


def coarsened_text(s: Settings) -> str:
    """Page 1's paragraph on what a quick report coarsens (empty for a full report).

    Parameters
    ----------
    s : Settings

    Returns
    -------
    str
    """
    if not s.quick:
        return ""
    f = Settings.for_mode(False)
    return (f"QUICK REPORT. Coarse grids: equal-instability speeds bisected to {s.tol:g} m/s in "
            f"{s.bracket[0]:g}-{s.bracket[1]:g} m/s (full: {f.tol:g} m/s in {f.bracket[0]:g}-{f.bracket[1]:g}), "
            f"critical impulses to {100 * s.impulse_rel_tol:g} % (full {100 * f.impulse_rel_tol:g} %), elasticities "
            f"to {100 * s.impulse_tol:g} % (full {100 * f.impulse_tol:g} %), runs of {s.duration:g} s (full "
            f"{f.duration:g} s), {_plan_size(s.plan)} parametric-study variants (full {_plan_size(f.plan)}), "
            f"{len(s.map_speeds)} map speeds (full {len(f.map_speeds)}), {s.speed_points} speed-locus points (full "
            f"{f.speed_points}). Values marked {MARK} come from these grids and may move in the full report "
            "(the dominant parameter and what helps most among them); the decision above comes from the advisor, "
            "computed the same way in both.")
