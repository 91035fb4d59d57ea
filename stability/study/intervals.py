"""Equal-instability speed with an honest interval: over the push size, the pin-friction uncertainty and both models."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from stability.chair import Chair, preset
from stability.chair.model import takes_chair, takes_chairs
from stability.layout.model import Layout
from stability.runtime.checks import VARIANTS, check_model
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, Push
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, Criterion
from stability.study.equal_instability import EqualInstability, bisect_speeds
from stability.study.memo import memoised

__all__ = ["Variant", "FactorRange", "EqualInstabilityInterval", "scale_friction", "reference_times",
           "equal_instability_interval", "equal_instability_intervals", "PUSH_FACTORS", "FRICTION_FACTORS",
           "RANGE_TOL", "RANGE_BRACKET", "RANGE_DEFINITION", "STEP_FACTORS"]


#: The equal-instability range's definition, one for the study command, the report and the advisor: the push
#: force times these factors (the thesis's 40 N for 0.1 s: 20, 30, 60, 80 N) ...
PUSH_FACTORS = (0.5, 0.75, 1.5, 2.0)
#: ... the pin friction times these factors on both the chair and the reference chair (the friction estimate is
#: uncertain for the reference's pins too) ...
FRICTION_FACTORS = (0.5, 1.5)
#: ... the other model variant, and the simulator's fixed step times these factors (WCHAIR's 1 ms resolves fast
#: caster modes coarsely and its Coulomb pin friction chatters there; docs/simulator.md, "Accuracy beyond
#: stability"; the critical impulse's interval uses the same factors) ...
STEP_FACTORS = (0.5,)
#: ... each found by bisection to this tolerance (m/s) in this bracket (m/s).
RANGE_TOL, RANGE_BRACKET = 0.01, (0.2, 3.0)
#: The definition in words (printed with the range by the study command and the report).
RANGE_DEFINITION = ("the range is over the push force x0.5, x0.75, x1.5 and x2, the pin friction x0.5 and x1.5 "
                    "(on both the chair and the reference chair), the other model variant and half the "
                    "simulator's step, one at a time: not a statistical interval")


@dataclass(frozen=True)
class Variant:
    """One assumption set: the model, the push force and a pin-friction factor (applied to both chairs).

    Attributes
    ----------
    factor : {"nominal", "disturbance", "pin friction", "model", "step"}
        Which input this variant moves.
    label : str
        E.g. ``"20 N (0.5x)"``.
    model : str
    force : float
        Push force, N (for the push's duration).
    friction_factor : float
        Multiplies both pins' friction of the chair and of the reference chair.
    reference_time : float
        The reference case's time to the level, s (+inf: never, the variant is undefined).
    result : EqualInstability or None
        None when undefined.
    step_s : float or None
        The simulator's fixed step of this variant, s (None: the adaptive scheme).
    """

    factor: str
    label: str
    model: str
    force: float
    friction_factor: float
    reference_time: float
    result: EqualInstability | None
    step_s: float | None = None

    @property
    def speed(self) -> float | None:
        """The equal-instability speed, m/s (None if undefined or outside the bracket)."""
        return None if self.result is None else self.result.speed


@dataclass(frozen=True)
class FactorRange:
    """How far one input moves the equal-instability speed.

    Attributes
    ----------
    factor : str
    low, high : float or None
        Smallest and largest speed over the nominal case and this factor's variants, m/s.
    undefined : tuple of str
        Variants where the measure is undefined (the reference never reaches the level) or
        the speed lies outside the bracket.
    """

    factor: str
    low: float | None
    high: float | None
    undefined: tuple

    @property
    def width(self) -> float:
        """``high - low``, m/s (0 when undefined)."""
        return 0.0 if self.low is None or self.high is None else self.high - self.low


@dataclass(frozen=True)
class EqualInstabilityInterval:
    """The equal-instability speed, its interval over the inputs it rests on, and what moves it most.

    Attributes
    ----------
    chair_name : str
    point : EqualInstability
        The nominal case (the thesis's push, nominal friction, ``model``).
    low, high : float or None
        Smallest and largest speed over every defined variant, m/s (a variant beyond the searched bracket counts
        as the bracket's end).
    factors : tuple of FactorRange
    dominant : str
        The factor with the widest range.
    variants : tuple of Variant
    push : str
        The nominal push convention.
    friction_scope : str
        To which chairs the friction factors apply.
    """

    chair_name: str
    point: EqualInstability
    low: float | None
    high: float | None
    factors: tuple
    dominant: str
    variants: tuple
    push: str
    friction_scope: str = "both the chair and the reference chair"

    def range_text(self) -> str:
        """``"range 0.779-1.11 m/s"`` (3 significant figures); ``"no spread: 0.75 m/s in every variant"`` when both
        ends print the same; ``"no range: ..."`` when no variant is defined: the words the study command, the
        report and the explorer print."""
        if self.low is None or self.high is None:
            return "no range: every variant is undefined"
        bound = {v.result.status for v in self.variants if v.result is not None and v.speed is None}
        above = "above" in bound and self.high == max(v.result.value_or_bound for v in self.variants
                                                         if v.result is not None)
        below = "below" in bound and self.low == min(v.result.value_or_bound for v in self.variants
                                                        if v.result is not None)
        if not (above or below):
            if f"{self.low:.3g}" == f"{self.high:.3g}":         # a degenerate range says nothing: say so
                return f"no spread: {self.low:.3g} m/s in every variant"
            return f"range {self.low:.3g}{' to ' if self.low < 0 else '-'}{self.high:.3g} m/s"
        lo = f"below {self.low:.3g}" if below else f"{self.low:.3g}"
        hi = f"above {self.high:.3g}" if above else f"{self.high:.3g}"
        return f"range {lo} to {hi} m/s" if self.low != self.high else f"range {hi} m/s"

    def describe(self) -> str:
        """One line: the point value, the interval and what drives it."""
        if self.low is None or self.high is None:
            return f"{self.point.describe()} (no interval: no variant defined)"
        text = self.range_text()
        moved = "" if text.startswith("no spread") else f"; moved most by {self.dominant}"
        return f"{self.point.describe()} ({text} over " + ", ".join(f.factor for f in self.factors) + moved + ")"

    def signed(self, reverse: bool) -> EqualInstabilityInterval:
        """This interval on the signed speed axis (negative: reverse), as every command reports a speed.

        Parameters
        ----------
        reverse : bool
            True: the searches ran backwards (speeds ``|U|``): every speed is negated and each interval's ends swap
            (:meth:`stability.study.equal_instability.EqualInstability.signed`); False returns ``self``.

        Returns
        -------
        EqualInstabilityInterval
        """
        if not reverse:
            return self

        def neg(x: float | None) -> float | None:
            return None if x is None else -x

        return replace(self, point=self.point.signed(True), low=neg(self.high), high=neg(self.low),
                       factors=tuple(replace(f, low=neg(f.high), high=neg(f.low)) for f in self.factors),
                       variants=tuple(v if v.result is None else replace(v, result=v.result.signed(True))
                                      for v in self.variants))

    def to_dict(self) -> dict:
        """JSON-ready dict."""
        return {"chair": self.chair_name, "speed_m_s": self.point.speed, "status": self.point.status,
                "low_m_s": self.low, "high_m_s": self.high, "dominant": self.dominant, "push": self.push,
                "friction_scope": self.friction_scope,
                "factors": [{"factor": f.factor, "low_m_s": f.low, "high_m_s": f.high, "undefined": list(f.undefined)}
                            for f in self.factors],
                "variants": [{"factor": v.factor, "label": v.label, "model": v.model, "force_N": v.force,
                              "friction_factor": v.friction_factor,
                              "reference_time_s": v.reference_time if math.isfinite(v.reference_time) else None,
                              "speed_m_s": v.speed, "status": None if v.result is None else v.result.status}
                             for v in self.variants]}


def scale_friction(c: Chair, factor: float) -> Chair:
    """``c`` with both pins' Coulomb friction times ``factor``.

    Parameters
    ----------
    c : Chair
        The chair.
    factor : float
        Multiplier of ``pin_friction_left`` and ``pin_friction_right`` (>= 0;
        1 returns ``c`` itself).

    Returns
    -------
    Chair
        The chair with scaled pin friction, N m.
    """
    if factor == 1.0:
        return c
    return c.replace(pin_friction_left=c.pin_friction_left * factor, pin_friction_right=c.pin_friction_right * factor)


def reference_times(reference: Chair | Sequence[Chair], speed: float, forces: Sequence[float], run: RunSpec, *,
                    criterion: Criterion) -> np.ndarray:
    """The reference case's time to the level for several pushes (and reference chairs), one batch.

    Parameters
    ----------
    reference : Chair or sequence of Chair
        One per force, or one for all.
    speed : float
        m/s.
    forces : sequence of float
        N.
    run : RunSpec
        The runs' settings (push duration, model, scheme, step, friction law); the horizon is the criterion's.
    criterion : Criterion

    Returns
    -------
    numpy.ndarray
        Seconds, +inf where the level is never reached.
    """
    forces = [float(f) for f in forces]
    chairs = [reference] * len(forces) if isinstance(reference, Chair) else list(reference)
    spec = runs.study_run(run).replace(horizon=criterion.duration)

    def batch(idx: list[int]) -> list[float]:
        res = runs.simulate_runs([chairs[i] for i in idx], [speed] * len(idx), spec,
                                 push_forces=[forces[i] for i in idx])
        return [criterion.time(r) for r in res]

    # each run is its own: inside an open memo (the advisor's) a reference case asked again is not run again
    return np.array(memoised("reference_time", [(c, float(speed), f, spec, criterion)
                                                for c, f in zip(chairs, forces, strict=True)], batch), dtype=float)


def _variants(model: str, force: float, force_factors: Sequence[float], friction_factors: Sequence[float],
              models: Sequence[str], dt: float | None,
              step_factors: Sequence[float]) -> list[tuple[str, str, str, float, float, float | None]]:
    out: list[tuple[str, str, str, float, float, float | None]] = [
        ("nominal", f"{force:g} N, x1 friction, {model}", model, force, 1.0, dt)]
    out += [("disturbance", f"{force * f:g} N ({f:g}x)", model, force * f, 1.0, dt) for f in force_factors]
    out += [("pin friction", f"x{g:g} pin friction", model, force, g, dt) for g in friction_factors]
    out += [("model", f"{m} model", m, force, 1.0, dt) for m in models if m != model]
    if dt is not None:
        out += [("step", f"{dt * f * 1e3:g} ms step", model, force, 1.0, dt * f) for f in step_factors]
    return out


@takes_chair
def equal_instability_interval(chair: Chair, run: RunSpec | None = None, *,
                               force_factors: Sequence[float] = PUSH_FACTORS,
                               friction_factors: Sequence[float] = FRICTION_FACTORS, models: Sequence[str] = VARIANTS,
                               reference_chair: Chair | None = None, reference_speed: float = REFERENCE_SPEED,
                               criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = RANGE_BRACKET,
                               tol: float = RANGE_TOL, candidates: int = 7, max_rounds: int = 8,
                               friction_on_reference: bool = True, progress: bool = False,
                               step_factors: Sequence[float] = STEP_FACTORS) -> EqualInstabilityInterval:
    """Equal-instability speed of ``chair`` over the inputs it depends on, one factor at a time.

    Its defaults are the toolkit's one definition of the equal-instability range (:data:`PUSH_FACTORS`,
    :data:`FRICTION_FACTORS` on both chairs, both models, :data:`RANGE_TOL`; :data:`RANGE_DEFINITION`),
    used by ``python -m stability.study equal-instability``, the report and the advisor.

    The nominal case is the thesis's: the reference chair at the reference
    speed under the run's push, nominal pin friction, the run's model.  Each
    variant moves one input: the push force (``force_factors`` x), the pin
    friction of both chairs (``friction_factors`` x: the uncertainty of the
    measured friction applies to the reference's pins too), the model, or the
    step.  A variant in which the reference never reaches the level is
    undefined (listed).  Per model and step, the reference runs are one batch
    and the bisection of every variant shares its rounds.

    Parameters
    ----------
    chair : Chair
    run : RunSpec, optional
        The nominal runs' settings (push, model, scheme, step, pin-friction law).
    force_factors, friction_factors : sequence of float
    models : sequence of str
        Models compared (the nominal one plus the others).
    reference_chair : Chair, optional
        Default the E&J Premier.
    reference_speed : float
        m/s.
    criterion, bracket, tol, candidates, max_rounds, progress
        As in :func:`stability.study.equal_instability_speeds`.
    friction_on_reference : bool
        Apply the friction factors to the reference chair too (default), or
        to ``chair`` only (the thesis's Figure 9-3 convention).
    step_factors : sequence of float
        Multipliers of the fixed step ``run.dt`` (scheme ``"wchair"``): the nominal case again at each step,
        reference runs included (:data:`STEP_FACTORS`).

    Returns
    -------
    EqualInstabilityInterval
    """
    return equal_instability_intervals(
        [chair], run, force_factors=force_factors, friction_factors=friction_factors, models=models,
        reference_chair=reference_chair, reference_speed=reference_speed, criterion=criterion, bracket=bracket,
        tol=tol, candidates=candidates, max_rounds=max_rounds, friction_on_reference=friction_on_reference,
        progress=progress, step_factors=step_factors)[0]


@takes_chairs
def equal_instability_intervals(chairs: Sequence[Chair], run: RunSpec | None = None, *,
                                force_factors: Sequence[float] = PUSH_FACTORS,
                                friction_factors: Sequence[float] = FRICTION_FACTORS, models: Sequence[str] = VARIANTS,
                                reference_chair: Chair | None = None, reference_speed: float = REFERENCE_SPEED,
                                criterion: Criterion = DEFAULT_CRITERION, bracket: tuple = RANGE_BRACKET,
                                tol: float = RANGE_TOL, candidates: int = 7, max_rounds: int = 8,
                                friction_on_reference: bool = True, progress: bool = False,
                                step_factors: Sequence[float] = STEP_FACTORS) -> list[EqualInstabilityInterval]:
    """:func:`equal_instability_interval` for many chairs: per model one reference batch and one bisection.

    Every chair's result equals what :func:`equal_instability_interval` gives for it alone (each run of
    the shared bisection counts only up to its own horizon).

    Parameters
    ----------
    chairs : sequence of Chair
    run, force_factors, friction_factors, models, reference_chair, reference_speed, criterion, bracket, tol,
    candidates, max_rounds, friction_on_reference, progress, step_factors
        As in :func:`equal_instability_interval`.

    Returns
    -------
    list of EqualInstabilityInterval
        One per chair, in order.
    """
    run = runs.study_run(run)
    for m in models:
        check_model(m)
    chairs = list(chairs)
    model, scheme, push = run.model, run.scheme, run.push
    dt = run.fixed_step if scheme == "wchair" else None
    ref0 = reference_chair if reference_chair is not None else preset(REFERENCE_CHAIR)
    specs = _variants(model, push.force, force_factors, friction_factors, models, dt, step_factors)
    variants: list[list[Variant | None]] = [[None] * len(specs) for _ in chairs]
    for m, h in dict.fromkeys((s[2], s[5]) for s in specs):     # one reference batch and bisection per model, step
        idx = [k for k, s in enumerate(specs) if (s[2], s[5]) == (m, h)]
        spec = run.replace(model=m) if h is None else run.replace(model=m, dt=h)
        refs = [scale_friction(ref0, specs[k][4] if friction_on_reference else 1.0) for k in idx]
        t_ref = reference_times(refs, reference_speed, [specs[k][3] for k in idx], spec, criterion=criterion)
        ok = [k for k, t in zip(idx, t_ref, strict=True) if math.isfinite(t)]
        jobs = [(n, k) for n in range(len(chairs)) for k in ok]
        res = bisect_speeds([scale_friction(chairs[n], specs[k][4]) for n, k in jobs],
                            [float(t_ref[idx.index(k)]) for _, k in jobs], [specs[k][3] for _, k in jobs],
                            spec, criterion=criterion, bracket=(float(bracket[0]), float(bracket[1])), tol=tol,
                            candidates=candidates, max_rounds=max_rounds, progress=progress,
                            reference_text=f"{ref0.name} at {reference_speed:g} m/s")
        found = dict(zip(jobs, res, strict=True))
        for n in range(len(chairs)):
            for k, t in zip(idx, t_ref, strict=True):
                variants[n][k] = Variant(*specs[k][:2], m, specs[k][3], specs[k][4], float(t), found.get((n, k)),
                                         h)
    scope = "both the chair and the reference chair" if friction_on_reference else "the chair only"
    return [_assemble(chair, tuple(v for v in vlist if v is not None), ref0, reference_speed, criterion, push, dt,
                      scheme, scope) for chair, vlist in zip(chairs, variants, strict=True)]


def _assemble(chair: Chair | Layout, vs: tuple, ref0: Chair, reference_speed: float, criterion: Criterion, push: Push,
              dt: float | None, scheme: str, scope: str) -> EqualInstabilityInterval:
    nominal = vs[0]
    if nominal.result is None:
        raise ValueError(f"the reference case ({ref0.name} at {reference_speed:g} m/s) never reaches "
                         f"{criterion.yaw_rate:g} rad/s within {criterion.duration:g} s under {push.describe(dt)}")
    factors = []
    for name in dict.fromkeys(v.factor for v in vs[1:]):
        group = [nominal] + [v for v in vs if v.factor == name]
        sp = [v.speed for v in group if v.speed is not None]
        factors.append(FactorRange(name, float(min(sp)) if sp else None, float(max(sp)) if sp else None,
                                   tuple(v.label for v in group if v.speed is None)))
    # the range's ends include a variant beyond the searched bracket at the bracket's end ("above 3 m/s" counts as
    # 3 m/s): a nominal case above the bracket is then inside its own range (the advisor's and page 1's intervals)
    all_sp = [v.result.value_or_bound for v in vs if v.result is not None]
    dominant = max(factors, key=lambda f: f.width).factor if factors else "nominal"
    return EqualInstabilityInterval(chair.name, nominal.result, float(min(all_sp)) if all_sp else None,
                                    float(max(all_sp)) if all_sp else None, tuple(factors), dominant, vs,
                                    push.describe(dt if scheme == "wchair" else None), scope)
