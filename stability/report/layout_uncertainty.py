"""``report --uncertainty FILE`` on a wheel layout: the linear results' intervals over the file's layout fields.

An uncertainty file for a layout has the short form's tables (:mod:`stability.uncertainty`: normal or uniform,
absolute or relative, one draw shared by several ``fields``), naming the layout's axes
(:func:`stability.advise.layout_axes.layout_axes`, the sweep's: the body's ``m``, ``i_z``, ``h``, any wheel's field
``caster_K_FIELD`` / ``wheel_J_FIELD`` with K and J from 1, a caster row's ``trail_ROW``, ``drive_x``; read with
:func:`stability.advise.layout_axes.load_layout_uncertainty`).  The draws are the short form's
(:meth:`stability.uncertainty.Uncertainty.sample`: a draw that makes an invalid layout is redrawn) and the intervals
its Monte Carlo propagation (:func:`stability.uncertainty.propagate`) of the layout's linear growth rates
at :data:`stability.report.layout_report.COMPARE_SPEEDS` (forward, and at the reference speed in reverse) and its
static stability (the smallest ISO 7176-1 tip angle; both :func:`stability.compare.layouts.linear_rows`, as
``compare``'s), and with ``critical=True`` (``critical_speed --uncertainty``) the first critical speed forward and in
reverse (:func:`stability.layout.linear.critical_speed`; a draw whose stability does not change up to 20 m/s has
none, NaN, as the short form's :func:`stability.linear.intervals.linear_intervals`).  The nonlinear measures are not
propagated (a thousand simulator searches per measure).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.advise.layout_axes import LayoutDraw
from stability.compare.layouts import linear_rows
from stability.layout.linear import critical_speed
from stability.layout.model import Layout
from stability.uncertainty import Uncertainty, propagate

__all__ = ["LayoutUncertainty", "layout_uncertainty", "MEASURES"]

#: The propagated measures: key (unit last), words.
MEASURES = (("growth_rate_1_s", "growth rate"), ("static_stability_deg", "static stability (smallest tip angle)"),
            ("critical_speed_forward_m_s", "critical speed forward"),
            ("critical_speed_reverse_m_s", "critical speed in reverse"))

@dataclass(frozen=True)
class LayoutUncertainty:
    """The propagated intervals.

    Attributes
    ----------
    speeds : tuple of float
        Signed speeds of the growth rates, m/s.
    result : stability.uncertainty.PropagationResult
        Outputs in order: the growth rate at each speed, then the static stability.
    parameters : tuple of str
        The file's tables.
    critical : bool
        The critical speeds forward and in reverse follow the static stability.
    """

    speeds: tuple
    result: Any
    parameters: tuple
    critical: bool = False

    def rows(self) -> list[tuple[str, str, float, float, float, float]]:
        """``(key, words, nominal, low, high, finite fraction)`` per output."""
        r = self.result
        keys = [(f"growth_rate_1_s@{u:g}", f"growth rate at {u:g} m/s" + (" (reverse)" if u < 0 else ""))
                for u in self.speeds] + [MEASURES[1]] + (list(MEASURES[2:]) if self.critical else [])
        return [(k, w, float(r.nominal[i]), float(r.low[i]), float(r.high[i]), float(r.finite_fraction[i]))
                for i, (k, w) in enumerate(keys)]

    def lines(self) -> list[str]:
        """The page's text."""
        r = self.result
        unit = {"growth": "1/s", "static": "deg", "critical": "m/s"}
        out = [f"{r.samples} seeded draws (seed {r.seed}) of {', '.join(self.parameters)} (the file's tables; a draw "
               f"that makes an invalid layout is redrawn: {r.rejected} redrawn); the linear model, free frictionless "
               f"casters; {100 * r.level:g} % central intervals:"]
        for key, words, nom, lo, hi, fin in self.rows():
            u = unit[key.split("_")[0]]
            if fin == 0:
                out.append(f"  {words}: none (the stability does not change up to 20 m/s in any draw)")
                continue
            out.append(f"  {words}: {nom:.4g} {u} ({100 * r.level:g} % interval {lo:.4g} to {hi:.4g} {u}"
                       + (f"; defined in {100 * fin:.0f} % of the draws" if fin < 1 else "") + ")")
        dom = [(n, s) for n, s in r.dominant_parameters if s > 0]
        if dom:
            out.append("Largest shares of the variance (first order, averaged over the outputs; regression R^2 "
                       + ", ".join(f"{x:.2f}" if math.isfinite(x) else "- (undefined)"
                                   for x in np.atleast_1d(r.r_squared)) + "): "
                       + ", ".join(f"{n} {100 * s:.0f} %" for n, s in dom[:4]) + ".")
        out.append("The critical impulse and the equal-instability speed are not propagated (each is a simulator "
                   "search per draw); their nominal values and their ranges over pin friction and the step: python "
                   "-m stability.study critical-impulse (or equal-instability) --chair NAME --interval.")
        return out

    def to_mapping(self) -> dict:
        """JSON-ready dict (unit last)."""
        r = self.result
        return {"samples": r.samples, "seed": r.seed, "level": r.level, "parameters": list(self.parameters),
                "rejected": r.rejected,
                "measures": [{"measure": k.split("@")[0], "speed_m_s": float(k.split("@")[1]) if "@" in k else None,
                              "nominal": nom if math.isfinite(nom) else None, "low": lo if math.isfinite(lo) else None,
                              "high": hi if math.isfinite(hi) else None, "finite_fraction": fin}
                             for k, _, nom, lo, hi, fin in self.rows()],
                "dominant_parameters": [{"parameter": n, "share": s} for n, s in r.dominant_parameters]}


def layout_uncertainty(layout: Layout, uncertainty: Uncertainty, speeds: Sequence[float], *, samples: int,
                       seed: int, critical: bool = False, level: float = 0.95) -> LayoutUncertainty:
    """Propagate the file's distributions through the layout's linear measures.

    Parameters
    ----------
    layout : Layout
    uncertainty : Uncertainty
        Tables naming the layout's axes (:func:`stability.advise.layout_axes.layout_axes`).
    speeds : sequence of float
        Signed speeds of the growth rates, m/s.
    samples, seed : int
    critical : bool
        Also the first critical speed forward and in reverse (m/s; NaN in a draw without one).
    level : float
        Coverage of the central intervals (0 < level < 1).

    Returns
    -------
    LayoutUncertainty
    """
    u = [float(x) for x in speeds]

    def fn(draws: list) -> np.ndarray:
        rows = linear_rows([d.layout for d in draws], u)
        if not critical:
            return rows
        crit = [[c[0] if not c[1].startswith("none") else math.nan for c in (critical_speed(d.layout),
                                                                              critical_speed(d.layout, True))]
                for d in draws]
        return np.column_stack([rows, np.asarray(crit, dtype=float)])

    res = propagate(LayoutDraw(layout), uncertainty, fn, samples=samples, seed=seed,  # type: ignore[arg-type]
                    level=level)
    return LayoutUncertainty(tuple(u), res, uncertainty.names, critical)
