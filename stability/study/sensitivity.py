"""Elasticities d ln v / d ln p of the critical impulse and the linear growth rate at a design point."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.rootlocus import get_parameter
from stability.settings.reference import REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study.facts import growth_rate
from stability.study.impulse import CriticalImpulse, critical_impulses
from stability.study.runs import study_run

__all__ = ["FRICTION_OVER_TRAIL", "TRAIL_AT_FIXED_GROUP", "ELASTICITY_PARAMETERS", "Elasticity", "Sensitivity",
           "elasticities"]

#: The friction-limited caster side force M_f/l as one parameter (pin friction scaled, trail fixed).
FRICTION_OVER_TRAIL = "friction_over_trail"
#: Trail with M_f/l held (trail and pin friction scaled together): what trail does beyond the group.
TRAIL_AT_FIXED_GROUP = "trail_at_fixed_Mf_over_l"
#: Default parameters (all > 0 at the presets).
ELASTICITY_PARAMETERS = (FRICTION_OVER_TRAIL, TRAIL_AT_FIXED_GROUP, "s1", "s1_plus_s2", "mass_factor",
                         "caster_mass_factor", "main_lateral_scale", "width_factor", "h", "roll_k")

_LABELS = {FRICTION_OVER_TRAIL: "pin friction / trail M_f/l (trail fixed)",
           TRAIL_AT_FIXED_GROUP: "trail l at fixed M_f/l"}


def _scaler(name: str) -> tuple[Callable[[Chair, float], Chair], str, Callable[[Chair], float]]:
    """``(apply(chair, factor), label, current(chair))`` for a parameter name."""
    if name == FRICTION_OVER_TRAIL:
        return (lambda c, f: c.replace(pin_friction_left=c.pin_friction_left * f,
                                       pin_friction_right=c.pin_friction_right * f),
                _LABELS[name], lambda c: c.pin_friction_left / c.trail)
    if name == TRAIL_AT_FIXED_GROUP:
        return (lambda c, f: c.replace(trail=c.trail * f, pin_friction_left=c.pin_friction_left * f,
                                       pin_friction_right=c.pin_friction_right * f),
                _LABELS[name], lambda c: c.trail)
    p = get_parameter(name)
    if p.categorical:
        raise ValueError(f"parameter={name!r} is invalid; an elasticity needs a continuous parameter")
    return (lambda c, f: p.apply(c, float(p.current(c)) * f), p.label, lambda c: float(p.current(c)))


@dataclass(frozen=True)
class Elasticity:
    """``d ln v / d ln p`` for one parameter (central difference, relative step ``step``).

    Attributes
    ----------
    parameter, label : str
    value : float
        The parameter at the design point (unit of the parameter).
    critical_impulse : float or None
        Elasticity of the critical impulse (None when a perturbed impulse was not found).
    growth_rate : float or None
        Elasticity of the linear growth rate (None when the rate is not positive).
    """

    parameter: str
    label: str
    value: float
    critical_impulse: float | None
    growth_rate: float | None


@dataclass(frozen=True)
class Sensitivity:
    """Elasticities at a design point, and a ranking by the critical impulse.

    Attributes
    ----------
    chair_name : str
    speed : float
        m/s.
    model : str
    step : float
        Relative step (0.1: p x 0.9 and p x 1.1).
    nominal : CriticalImpulse
    nominal_growth_rate : float
        1/s.
    elasticities : tuple of Elasticity
    """

    chair_name: str
    speed: float
    model: str
    step: float
    nominal: CriticalImpulse
    nominal_growth_rate: float
    elasticities: tuple

    def ranked(self, measure: str = "critical_impulse") -> list[Elasticity]:
        """Elasticities by decreasing magnitude of ``measure`` ("critical_impulse" or "growth_rate")."""
        return sorted(self.elasticities, key=lambda e: -abs(getattr(e, measure) or 0.0))

    def to_dict(self) -> dict:
        """JSON-ready dict."""
        return {"chair": self.chair_name, "speed_m_s": self.speed, "model": self.model, "step": self.step,
                "critical_impulse_Ns": self.nominal.impulse_Ns, "growth_rate_1_s": self.nominal_growth_rate,
                "elasticities": [{"parameter": e.parameter, "label": e.label, "value": e.value,
                                  "critical_impulse": e.critical_impulse, "growth_rate": e.growth_rate}
                                 for e in self.ranked()]}


def _elasticity(lo: float | None, hi: float | None, step: float) -> float | None:
    if lo is None or hi is None or lo <= 0 or hi <= 0:
        return None
    return (math.log(hi) - math.log(lo)) / (math.log1p(step) - math.log1p(-step))


@takes_chair
def elasticities(chair: Chair, speed: float = REFERENCE_SPEED, run: RunSpec | None = None, *,
                 parameters: Sequence[str] = ELASTICITY_PARAMETERS, step: float = 0.1,
                 rel_tol: float = 0.001, **impulse_options: Any) -> Sensitivity:
    """Elasticities ``d ln v / d ln p`` of the critical impulse and of the linear growth rate.

    Every parameter is scaled by ``1 - step`` and ``1 + step`` (the same
    relative step for all), and ``(ln v+ - ln v-) / (ln(1+step) - ln(1-step))``
    is taken.  Pin friction and trail enter as the group ``M_f/l`` (pin
    friction scaled at fixed trail) and as trail at fixed ``M_f/l``.  The
    perturbed critical impulses are one vectorised bisection, searched within
    a factor 4 of the nominal one and refined to ``rel_tol``.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s.
    parameters : sequence of str
        Names of :data:`stability.rootlocus.DESIGN_PARAMETERS` (continuous) or
        :data:`FRICTION_OVER_TRAIL` / :data:`TRAIL_AT_FIXED_GROUP`.
    step : float
        Relative step, 0 < step < 1.
    run : RunSpec, optional
        The runs' settings (model, push duration, horizon, step, pin-friction law).
    rel_tol : float
        Relative width of the critical-impulse brackets.
    **impulse_options
        Passed to :func:`stability.study.critical_impulses` (``level``, ``max_impulse``, ...).

    Returns
    -------
    Sensitivity
    """
    if not 0 < step < 1:
        raise ValueError(f"step={step!r} is invalid; valid range: 0 < step < 1")
    run = study_run(run)
    model = run.model
    nominal = critical_impulses(chair, speed, run, rel_tol=rel_tol, **impulse_options)[0]
    scalers = [_scaler(n) for n in parameters]
    chairs = [apply(chair, f) for apply, _, _ in scalers for f in (1.0 - step, 1.0 + step)]
    imp: list[float | None] = [None] * len(chairs)
    if nominal.impulse_Ns is not None:
        j0 = nominal.impulse_Ns
        opts = dict(impulse_options, min_impulse=j0 / 4.0, max_impulse=j0 * 4.0)
        imp = [r.impulse_Ns for r in critical_impulses(chairs, speed, run, rel_tol=rel_tol, **opts)]
    g = [growth_rate(c, speed, model) for c in chairs]
    out = []
    for k, (name, (_, label, current)) in enumerate(zip(parameters, scalers, strict=True)):
        g_lo, g_hi = g[2 * k], g[2 * k + 1]
        out.append(Elasticity(name, label, float(current(chair)), _elasticity(imp[2 * k], imp[2 * k + 1], step),
                              _elasticity(g_lo if g_lo > 0 else None, g_hi if g_hi > 0 else None, step)))
    return Sensitivity(chair.name, float(speed), model, float(step), nominal, growth_rate(chair, speed, model),
                       tuple(out))
