"""``report --uncertainty FILE`` on a wheel layout: the linear results' intervals over the file's layout fields.

An uncertainty file for a layout has the short form's tables (:mod:`stability.uncertainty`: normal or uniform,
absolute or relative, one draw shared by several ``fields``), naming the layout's numbers: the body's ``m``,
``i_z``, ``h`` and any wheel's field by the advisor's names (``caster_K_FIELD``, ``wheel_J_FIELD``, K and J from 1:
``caster_1_trail``, ``wheel_2_x``; :func:`stability.advise.layout_levers.apply_layout`).  The draws are the short
form's (:meth:`stability.uncertainty.Uncertainty.sample`: a draw that makes an invalid layout is redrawn) and the
intervals its Monte Carlo propagation (:func:`stability.uncertainty.propagate`) of the layout's linear growth rates
at :data:`stability.report.layout_report.COMPARE_SPEEDS` (forward, and at the reference speed in reverse) and its
static stability (the smallest ISO 7176-1 tip angle).  The nonlinear measures are not propagated (a thousand
simulator searches per measure).
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.layout.linear import growth_rates
from stability.layout.model import Layout
from stability.layout.statics import tip_angles
from stability.uncertainty import Uncertainty, load_uncertainty, propagate

__all__ = ["layout_fields", "LayoutDraw", "LayoutUncertainty", "load_layout_uncertainty", "layout_uncertainty",
           "MEASURES"]

#: The propagated measures: key (unit last), words.
MEASURES = (("growth_rate_1_s", "growth rate"), ("static_stability_deg", "static stability (smallest tip angle)"))

_NUMERIC_TOP = ("m", "i_z", "h")


def _numeric(obj: Any) -> list[str]:
    return [f.name for f in dataclasses.fields(obj) if isinstance(getattr(obj, f.name), (int, float))
            and not isinstance(getattr(obj, f.name), bool)]


def layout_fields(layout: Layout) -> frozenset:
    """The field names an uncertainty file may name for ``layout``.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    frozenset of str
        ``m``, ``i_z``, ``h`` and ``caster_K_FIELD`` / ``wheel_J_FIELD`` for every numeric wheel field.
    """
    out = set(_NUMERIC_TOP)
    for group, seq in (("caster", layout.casters), ("wheel", layout.wheels)):
        for k, w in enumerate(seq, start=1):
            out |= {f"{group}_{k}_{name}" for name in _numeric(w)}
    return frozenset(out)


@dataclass(frozen=True)
class LayoutDraw:
    """A layout seen as the uncertainty module sees a chair: its fields by name, and ``replace``.

    Attributes
    ----------
    layout : Layout
    """

    layout: Layout

    def __getattr__(self, name: str) -> float:
        if name in _NUMERIC_TOP:
            return float(getattr(self.layout, name))
        group, _, rest = name.partition("_")
        k, _, field = rest.partition("_")
        seq = {"caster": self.layout.casters, "wheel": self.layout.wheels}.get(group)
        if seq is None or not k.isdigit() or not 1 <= int(k) <= len(seq):
            raise AttributeError(name)
        return float(getattr(seq[int(k) - 1], field))

    def replace(self, **fields: float) -> LayoutDraw:
        """The layout with the given fields (validated as the advisor's changes are; ValueError if invalid)."""
        from stability.advise.layout_levers import apply_layout

        top: dict[str, Any] = {k: v for k, v in fields.items() if k in _NUMERIC_TOP}
        wheels = [(k, v) for k, v in fields.items() if k not in _NUMERIC_TOP]
        lay = dataclasses.replace(self.layout, **top) if top else self.layout
        return LayoutDraw(apply_layout(lay, wheels) if wheels else lay)


def load_layout_uncertainty(path: str | os.PathLike[str], layout: Layout) -> Uncertainty:
    """Read an uncertainty file whose tables name ``layout``'s fields (:func:`layout_fields`).

    Parameters
    ----------
    path : str or os.PathLike
    layout : Layout

    Returns
    -------
    Uncertainty
    """
    return load_uncertainty(path, layout_fields(layout))


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
    """

    speeds: tuple
    result: Any
    parameters: tuple

    def rows(self) -> list[tuple[str, str, float, float, float, float]]:
        """``(key, words, nominal, low, high, finite fraction)`` per output."""
        r = self.result
        keys = [(f"growth_rate_1_s@{u:g}", f"growth rate at {u:g} m/s" + (" (reverse)" if u < 0 else ""))
                for u in self.speeds] + [("static_stability_deg", MEASURES[1][1])]
        return [(k, w, float(r.nominal[i]), float(r.low[i]), float(r.high[i]), float(r.finite_fraction[i]))
                for i, (k, w) in enumerate(keys)]

    def lines(self) -> list[str]:
        """The page's text."""
        r = self.result
        unit = {"growth": "1/s", "static": "deg"}
        out = [f"{r.samples} seeded draws (seed {r.seed}) of {', '.join(self.parameters)} (the file's tables; a draw "
               f"that makes an invalid layout is redrawn: {r.rejected} redrawn); the linear model, free frictionless "
               f"casters; {100 * r.level:g} % central intervals:"]
        for key, words, nom, lo, hi, fin in self.rows():
            u = unit[key.split("_")[0]]
            out.append(f"  {words}: {nom:.4g} {u} ({100 * r.level:g} % interval {lo:.4g} to {hi:.4g} {u}"
                       + (f"; defined in {100 * fin:.0f} % of the draws" if fin < 1 else "") + ")")
        dom = [(n, s) for n, s in r.dominant_parameters if s > 0]
        if dom:
            out.append("Largest shares of the variance (first order, averaged over the outputs; regression R^2 "
                       + ", ".join(f"{x:.2f}" for x in np.atleast_1d(r.r_squared)) + "): "
                       + ", ".join(f"{n} {100 * s:.0f} %" for n, s in dom[:4]) + ".")
        out.append("The critical impulse and the equal-instability speed are not propagated (each is a simulator "
                   "search per draw); the report's pages before give their nominal values.")
        return out

    def to_mapping(self) -> dict:
        """JSON-ready dict (unit last)."""
        r = self.result
        return {"samples": r.samples, "seed": r.seed, "level": r.level, "parameters": list(self.parameters),
                "rejected": r.rejected,
                "measures": [{"measure": k.split("@")[0], "speed_m_s": float(k.split("@")[1]) if "@" in k else None,
                              "nominal": nom, "low": lo if math.isfinite(lo) else None,
                              "high": hi if math.isfinite(hi) else None, "finite_fraction": fin}
                             for k, _, nom, lo, hi, fin in self.rows()],
                "dominant_parameters": [{"parameter": n, "share": s} for n, s in r.dominant_parameters]}


def layout_uncertainty(layout: Layout, uncertainty: Uncertainty, speeds: Sequence[float], *, samples: int,
                       seed: int) -> LayoutUncertainty:
    """Propagate the file's distributions through the layout's linear measures.

    Parameters
    ----------
    layout : Layout
    uncertainty : Uncertainty
        Tables naming :func:`layout_fields`.
    speeds : sequence of float
        Signed speeds of the growth rates, m/s.
    samples, seed : int

    Returns
    -------
    LayoutUncertainty
    """
    u = [float(x) for x in speeds]

    def fn(draws: list) -> np.ndarray:
        out = np.empty((len(draws), len(u) + 1))
        for i, d in enumerate(draws):
            lay = d.layout
            out[i, :len(u)] = growth_rates(lay, u)
            out[i, -1] = min(tip_angles(lay).values())
        return out

    res = propagate(LayoutDraw(layout), uncertainty, fn, samples=samples, seed=seed)  # type: ignore[arg-type]
    return LayoutUncertainty(tuple(u), res, uncertainty.names)
