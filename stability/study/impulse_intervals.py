"""The critical impulse with its interval over the inputs it rests on: pin friction, model and step.

The critical impulse *is* a push size, so unlike the equal-instability speed it has no push
variant; it depends on the pin's Coulomb friction (measured only roughly; x0.5 and x1.5, as the
equal-instability interval), on the model (exact or thesis) and on the simulator's fixed step:
program WCHAIR's 1 ms resolves the stiff caster modes (hundreds to thousands of 1/s at walking
speed) coarsely, and the answer moves with it (E&J Premier at 1.0 m/s: 2.16 N s at 1 ms, 2.36 at
0.5 ms, 2.52 at 0.125 ms and 2.53 from the adaptive scheme; power-fwd with a 6 cm trail at 0.75
m/s: 2.10 at 1 ms but 11.6-11.7 at 0.5-0.25 ms), so the nominal case is run again at half the step
(``STEP_FACTORS``) and that variant is part of the range.  One batch of
:func:`stability.study.critical_impulses` per model covers every chair and variant; a chair's
result does not depend on the batch it runs in.  ``python -m stability.study critical-impulse
--interval`` prints it.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from stability.chair import Chair
from stability.chair.model import takes_chairs
from stability.runtime.checks import VARIANTS
from stability.settings.run import RunSpec
from stability.study.impulse import CriticalImpulse, critical_impulses
from stability.study.intervals import FRICTION_FACTORS, STEP_FACTORS, scale_friction
from stability.study.runs import study_run

__all__ = ["CriticalImpulseInterval", "critical_impulse_intervals", "FRICTION_FACTORS", "STEP_FACTORS"]

# The pin-friction factors of the interval are stability.study.intervals.FRICTION_FACTORS, the equal-instability
# range's (imported above).



@dataclass(frozen=True)
class CriticalImpulseInterval:
    """Critical impulse at one speed with its range over pin friction and model.

    Attributes
    ----------
    chair_name : str
    speed : float
        m/s.
    point : CriticalImpulse
        Nominal: the chair's pin friction, the nominal model.
    variants : tuple of (str, CriticalImpulse)
        Label (``"x0.5 pin friction"``, ``"thesis model"``) and result.
    low_Ns, high_Ns : float
        Smallest and largest impulse (or bound, see :attr:`CriticalImpulse.bound_Ns`) over the nominal
        case and every variant, N s.
    """

    chair_name: str
    speed: float
    point: CriticalImpulse
    variants: tuple
    low_Ns: float
    high_Ns: float

    def describe(self) -> str:
        """``"3.22 N s (range 2.3-4.2 N s over pin friction x0.5-x1.5 and the thesis model)"``."""
        labels = ", ".join(label for label, _ in self.variants)
        return f"{self.point.describe()} (range {self.low_Ns:.3g}-{self.high_Ns:.3g} N s over {labels})"

    def to_dict(self) -> dict:
        """JSON-ready dict (N s, m/s)."""
        return {"chair": self.chair_name, "speed_m_s": self.speed, "impulse_Ns": self.point.impulse_Ns,
                "status": self.point.status, "low_Ns": self.low_Ns, "high_Ns": self.high_Ns,
                "variants": [{"label": label, "impulse_Ns": r.impulse_Ns, "status": r.status, "bound_Ns": r.bound_Ns}
                             for label, r in self.variants]}


@takes_chairs
def critical_impulse_intervals(chairs: Sequence[Chair], speed: float, run: RunSpec | None = None, *,
                               friction_factors: Sequence[float] = FRICTION_FACTORS,
                               models: Sequence[str] = VARIANTS, step_factors: Sequence[float] = STEP_FACTORS,
                               **search: Any) -> list[CriticalImpulseInterval]:
    """Critical impulse of each chair at ``speed``, with its range over pin friction and model.

    Parameters
    ----------
    chairs : sequence of Chair
    speed : float
        m/s.
    run : RunSpec, optional
        The nominal runs' settings (model, push duration, horizon, step, pin-friction law).
    friction_factors : sequence of float
        Multipliers of both pins' Coulomb friction (nominal model).
    models : sequence of str
        Models compared (the other ones at nominal friction).
    step_factors : sequence of float
        Multipliers of the fixed step ``dt`` (nominal model and friction; labelled by the step in ms).
    **search
        As :func:`stability.study.critical_impulses` (level, max_impulse, ...).

    Returns
    -------
    list of CriticalImpulseInterval
        One per chair, in order.
    """
    run = study_run(run)
    model = run.model
    chairs = list(chairs)
    dt = run.fixed_step
    # (label, model, friction factor, step): one batch per (model, step)
    specs: list[tuple[str, str, float, float]] = [("nominal", model, 1.0, dt)]
    specs += [(f"x{f:g} pin friction", model, float(f), dt) for f in friction_factors]
    specs += [(f"{m} model", m, 1.0, dt) for m in models if m != model]
    specs += [(f"{dt * f * 1e3:g} ms step", model, 1.0, dt * float(f)) for f in step_factors]
    results: dict[tuple[int, int], CriticalImpulse] = {}
    for m, h in dict.fromkeys((s[1], s[3]) for s in specs):
        idx = [k for k, s in enumerate(specs) if (s[1], s[3]) == (m, h)]
        jobs = [(n, k) for n in range(len(chairs)) for k in idx]
        res = critical_impulses([scale_friction(chairs[n], specs[k][2]) for n, k in jobs], speed,
                                run.replace(model=m, dt=h), **search)
        results.update(zip(jobs, res, strict=True))
    out = []
    for n, c in enumerate(chairs):
        point = results[(n, 0)]
        variants = tuple((specs[k][0], results[(n, k)]) for k in range(1, len(specs)))
        bounds = [point.bound_Ns] + [r.bound_Ns for _, r in variants]
        out.append(CriticalImpulseInterval(c.name, float(speed), point, variants, float(min(bounds)),
                                           float(max(bounds))))
    return out
