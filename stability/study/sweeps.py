"""Parametric study: equal-instability speed for each value of each chapter-8 parameter (Figures 8-9 to 8-15)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from stability.chair import Chair, preset
from stability.chair.design import DESIGN_PARAMETERS, get_parameter, main_tires
from stability.chair.model import takes_chair
from stability.settings.reference import REFERENCE_CHAIR
from stability.study.equal_instability import EqualInstability, equal_instability_speeds

__all__ = ["DEFAULT_PLAN", "QUICK_PLAN", "Sweep", "SweepRow", "SweepTable", "plan_for", "sweep_chairs",
           "collect_sweeps", "parameter_sweeps"]

#: Chapter-8 parameters and the values the thesis tried (plus a few more).
DEFAULT_PLAN: dict[str, tuple | None] = {
    "cg_ratio": (0.55, 0.60, 0.66, 0.70, 0.75),               # Figure 8-9
    "s1_plus_s2": (0.40, 0.46, 0.52, 0.57, 0.62),             # Figure 8-10
    "s1": (0.245, 0.295, 0.345),                              # chapter 9, conclusion 2
    "trail": (0.05, 0.06, 0.07, 0.08, 0.10),                  # Figure 8-11
    "caster_mass_factor": (1.0, 2.0, 3.0),                    # Figure 8-12
    "pin_friction": (0.05, 0.075, 0.10, 0.115, 0.12, 0.15, 0.30),  # Figure 8-13, 9-3; 0.3: conclusion 6
    "mass_factor": (0.8, 1.0, 1.2),                           # Figure 8-14
    "main_tire": None,                                        # Figure 8-15: all main tires
    "camber_deg": (0.0, 2.0, 5.0, 8.0),                       # chapter 8
    "width_factor": (0.8, 1.0, 1.2),                          # d1, d2, t1, t2
    "h": (0.50, 0.61, 0.70),                                  # c.g. height
    "roll_k": (0.5, 1.0, 2.0),                                # roll coefficient
}

#: A coarse plan for ``--quick`` reports and tests.  The main tires and camber
#: are left out: runs with another tire (or camber) form separate groups in
#: the batch simulator, each costing about as much per step as the whole
#: batch of one group.
QUICK_PLAN: dict[str, tuple | None] = {
    "cg_ratio": (0.60, 0.66),
    "s1_plus_s2": (0.52, 0.62),
    "s1": (0.245, 0.345),
    "trail": (0.06, 0.08),
    "pin_friction": (0.05, 0.10, 0.15, 0.30),
    "width_factor": (1.0, 1.2),
}


@dataclass(frozen=True, eq=False)
class Sweep:
    """Equal-instability speeds for the values of one parameter (relative changes are against ``nominal``).

    Attributes
    ----------
    parameter, label, unit : str
    values : tuple of float
        The values tried (indices for a categorical parameter).
    results : tuple of EqualInstability
        One per value.
    nominal_value : float
        The chair's own value.
    nominal : EqualInstability
        The chair's own result.
    labels : tuple of str or None
        Names of a categorical parameter's values.
    how : str
        How the parameter is varied.
    """

    parameter: str
    label: str
    unit: str
    values: tuple
    results: tuple
    nominal_value: float
    nominal: EqualInstability
    labels: tuple | None = None
    how: str = ""

    @property
    def speeds(self) -> np.ndarray:
        """Speed (or bracket bound) per value, m/s."""
        return np.array([r.value_or_bound for r in self.results])

    def value_text(self, i: int) -> str:
        """The ``i``-th value as text."""
        if self.labels is not None:
            return self.labels[i]
        return f"{self.values[i]:.3g}"

    @property
    def change_percent(self) -> np.ndarray:
        """Change of the equal-instability speed against the chair's own (%), per value."""
        return 100.0 * (self.speeds / self.nominal.value_or_bound - 1.0)

    @property
    def effect_percent(self) -> float:
        """Largest minus smallest speed over the values tried, in % of the chair's own speed."""
        s = self.speeds
        return float(100.0 * (s.max() - s.min()) / self.nominal.value_or_bound)

    @property
    def censored(self) -> bool:
        """True if some speed lies outside the bracket (then the effect is a lower bound)."""
        return any(r.status != "found" for r in self.results) or self.nominal.status != "found"

    def speed_at(self, value: Any) -> EqualInstability:
        """The result at one of the values tried (KeyError if not tried)."""
        for v, r in zip(self.values, self.results, strict=True):
            if (self.labels is not None and v == value) or (self.labels is None and abs(v - value) < 1e-12):
                return r
        raise KeyError(value)


@dataclass(frozen=True)
class SweepRow:
    """One row of the ranked sweep table.

    Attributes
    ----------
    parameter : str
    label : str
        With the unit.
    values : list of str
    speeds_m_s : list of str
        Each speed as text (``"0.75 m/s"``, ``"> 3 m/s"``).
    effect_percent : float
    censored : bool
    """

    parameter: str
    label: str
    values: list
    speeds_m_s: list
    effect_percent: float
    censored: bool

    def to_dict(self) -> dict:
        """A JSON-ready dict."""
        return asdict(self)


@dataclass(frozen=True, eq=False)
class SweepTable:
    """The chapter-8 sweeps of one chair, ranked by effect ("which parameters matter, by how much").

    Attributes
    ----------
    chair : Chair
    nominal : EqualInstability
    sweeps : tuple of Sweep
    """

    chair: Chair
    nominal: EqualInstability
    sweeps: tuple

    def ranked(self) -> list[Sweep]:
        """Sweeps by decreasing effect."""
        return sorted(self.sweeps, key=lambda s: -s.effect_percent)

    def get(self, parameter: str) -> Sweep:
        """The sweep of one parameter (KeyError if not swept)."""
        for s in self.sweeps:
            if s.parameter == parameter:
                return s
        raise KeyError(parameter)

    def __contains__(self, parameter: str) -> bool:
        return any(s.parameter == parameter for s in self.sweeps)

    def rows(self) -> list[SweepRow]:
        """One row per parameter, ranked: values, speeds, effect (%)."""
        return [SweepRow(s.parameter, s.label if s.unit == "-" else f"{s.label} ({s.unit})",
                         [s.value_text(i) for i in range(len(s.values))], [r.describe() for r in s.results],
                         s.effect_percent, s.censored) for s in self.ranked()]


#: Parameters whose plan values scale with the chair's own value in :func:`plan_for`
#: (the others shift with it).
_MULTIPLICATIVE = ("pin_friction", "roll_k", "caster_mass_factor", "mass_factor", "width_factor",
                   "main_lateral_scale", "pin_damping")


@takes_chair
def plan_for(chair: Chair, plan: dict | None = None, base: Chair | None = None) -> dict:
    """A plan (written for ``base``, default the E&J Premier) moved to ``chair``'s own values.

    Each parameter keeps the steps the thesis tried around its chair: values
    shift by ``chair's value - base's value`` (lengths, ratios, angles) or
    scale by ``chair's value / base's value`` (friction, factors).  Values
    the chair cannot take (e.g. ``s1 + s2 <= s1``) are dropped.  For the E&J
    Premier itself the plan is unchanged.

    Parameters
    ----------
    chair : Chair
    plan : dict, optional
        ``{parameter: values}`` (default :data:`DEFAULT_PLAN`).
    base : Chair, optional

    Returns
    -------
    dict
    """
    plan = DEFAULT_PLAN if plan is None else plan
    base = base if base is not None else preset(REFERENCE_CHAIR)
    out: dict = {}
    for name, values in plan.items():
        p = get_parameter(name)
        if p.categorical or values is None:
            out[name] = values
            continue
        v0, c0 = float(p.current(base)), float(p.current(chair))
        if name in _MULTIPLICATIVE:
            new = [v * c0 / v0 if v0 else v for v in values]
        else:
            new = [v + (c0 - v0) for v in values]
        ok = []
        for v in new:
            v = c0 if abs(v - c0) < 1e-9 else round(v, 4)
            try:
                p.apply(chair, v)
            except ValueError:
                continue
            ok.append(v)
        # a plan value that stands for the base chair's own (the thesis's rounded 0.66 for the E&J's c.g. ratio
        # 0.6635) becomes this chair's own value, so the sweep contains the chair itself
        near = [i for i, v in enumerate(ok) if abs(v - c0) <= _OWN_VALUE_TOLERANCE * max(abs(c0), 1e-12)]
        if near and c0 != v0 and c0 not in ok and abs(v0 - min(values, key=lambda v: abs(v - v0))) <= \
                _OWN_VALUE_TOLERANCE * max(abs(v0), 1e-12):
            ok[min(near, key=lambda i: abs(ok[i] - c0))] = c0
        if ok:
            out[name] = tuple(ok)
    return out


#: Relative distance within which a plan value stands for the base chair's own value (the thesis rounds to
#: two digits: 0.66 for 0.6635 is 0.5 % away).
_OWN_VALUE_TOLERANCE = 0.01


def sweep_chairs(chair: Chair, plan: dict) -> list[tuple[str, tuple, tuple | None, list[Chair]]]:
    """The chairs of a plan: ``(parameter, values, labels, chairs)`` per parameter.

    Parameters
    ----------
    chair : Chair
    plan : dict
        ``{parameter: values}``; a categorical parameter (the main tire) takes every main tire.

    Returns
    -------
    list of tuple
    """
    out = []
    for name, values in plan.items():
        p = get_parameter(name)
        if p.categorical:
            labels: tuple | None = main_tires()
            vals = tuple(float(i) for i in range(len(labels or ())))
        else:
            vals, labels = tuple(float(v) for v in values), None
        out.append((name, vals, labels, [p.apply(chair, v) for v in vals]))
    return out


def collect_sweeps(chair: Chair, groups: list, results: Sequence[EqualInstability], start: int,
                   nominal: EqualInstability) -> tuple[SweepTable, int]:
    """Build a :class:`SweepTable` from ``results[start:]`` laid out as ``groups``; returns it and the next index.

    Parameters
    ----------
    chair : Chair
        The nominal chair (its own parameter values are recorded).
    groups : list of tuple
        One ``(name, values, labels, chairs)`` per swept parameter: a key of
        :data:`stability.chair.design.DESIGN_PARAMETERS`, the values (parameter
        unit), their labels (or None) and the chairs built from them.
    results : sequence of EqualInstability
        Results for all chairs of all groups, in order, from index ``start``.
    start : int
        Index in ``results`` of the first group's first chair.
    nominal : EqualInstability
        Result for the nominal chair.

    Returns
    -------
    tuple of (SweepTable, int)
        The table and the index in ``results`` after its last chair.
    """
    k = start
    sweeps = []
    for name, vals, labels, chairs in groups:
        p = DESIGN_PARAMETERS[name]
        sweeps.append(Sweep(name, p.label, p.unit, vals, tuple(results[k:k + len(chairs)]), float(p.current(chair)),
                            nominal, labels, p.how))
        k += len(chairs)
    return SweepTable(chair, nominal, tuple(sweeps)), k


@takes_chair
def parameter_sweeps(chair: Chair, plan: dict | None = None, *, extra_chairs: Sequence[Chair] = (),
                     progress: bool = True, **options: Any) -> tuple[SweepTable, list[EqualInstability]]:
    """Equal-instability speed for each value of each parameter in ``plan`` (one vectorised bisection).

    Parameters
    ----------
    chair : Chair
        The base chair; every other parameter keeps its value.
    plan : dict, optional
        ``{parameter: values}``; default :data:`DEFAULT_PLAN` (the thesis's
        chapter-8 values; ``None`` values for ``main_tire`` mean every main tire).
    extra_chairs : sequence of Chair
        More chairs to rate in the same bisection (returned second).
    progress : bool
    **options
        Passed to :func:`equal_instability_speeds` (``model``, ``scheme``,
        ``impulse``, ``criterion``, ``bracket``, ``tol``, ``dt``, ``reference``...).

    Returns
    -------
    (SweepTable, list of EqualInstability)
    """
    plan = DEFAULT_PLAN if plan is None else plan
    groups = sweep_chairs(chair, plan)
    all_chairs = [chair] + [c for g in groups for c in g[3]] + list(extra_chairs)
    res = equal_instability_speeds(all_chairs, progress=progress, **options)
    table, k = collect_sweeps(chair, groups, res, 1, res[0])
    return table, list(res[k:])
