"""The report's parameter-uncertainty section: linear and nonlinear intervals over an uncertainty file.

:func:`stability.linear.intervals.linear_intervals` (Monte Carlo, seeded; delta method as a check) gives the
growth-rate band against speed, the critical-speed intervals and the dominant parameters;
:func:`stability.study.uncertain.nonlinear_intervals` the critical impulse and equal-instability speed intervals.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.linear.batch import ChairBatch
from stability.linear.intervals import LinearIntervals, linear_intervals
from stability.report.settings import Settings
from stability.settings.bounds import SAMPLES, SEED
from stability.settings.reference import REFERENCE_SPEED
from stability.settings.run import RunSpec
from stability.study.uncertain import NonlinearIntervals, nonlinear_intervals
from stability.uncertainty import Uncertainty

__all__ = ["UncertaintySpec", "UncertaintySection", "uncertainty_section", "BAND_SPEEDS", "QUICK_BAND_SPEEDS",
           "NONLINEAR_SAMPLES", "QUICK_NONLINEAR_SAMPLES"]

#: Speeds of the growth-rate band, m/s (the reference speed among them).
BAND_SPEEDS = tuple(float(x) for x in np.round(np.linspace(0.25, 3.0, 12), 4))
#: The same for ``--quick``.
QUICK_BAND_SPEEDS = (0.25, 0.75, 1.5, 2.25, 3.0)
#: Most Monte Carlo draws of the nonlinear measures (``--samples`` caps it; each draw is a few hundred simulations).
NONLINEAR_SAMPLES = 200
#: The same for ``--quick``.
QUICK_NONLINEAR_SAMPLES = 40


@dataclass(frozen=True)
class UncertaintySpec:
    """What ``--uncertainty FILE --samples N --seed S`` asks for.

    Attributes
    ----------
    source : str
        The file (for the page's text).
    uncertainty : Uncertainty
        Its distributions.
    samples : int
        Monte Carlo draws (:data:`stability.settings.bounds.SAMPLES`).
    seed : int
        Seed of the draws (:data:`stability.settings.bounds.SEED`).
    """

    source: str
    uncertainty: Uncertainty
    samples: int = 1000
    seed: int = 0

    def __post_init__(self) -> None:
        SAMPLES.check("--samples", self.samples, integer=True)
        SEED.check("--seed", self.seed, integer=True)


@dataclass(frozen=True, eq=False)
class UncertaintySection:
    """Intervals of the linear and nonlinear results over the uncertain parameters.

    Attributes
    ----------
    spec : UncertaintySpec
    intervals : LinearIntervals
        At the band speeds (``intervals.speeds``), with the critical speeds and dominant parameters.
    nominal_rates : ndarray
        Growth rate at the band speeds for the nominal chair, 1/s (free casters).
    nonlinear : NonlinearIntervals or None
        Critical impulse at the reference speed and equal-instability speed, with the
        report's simulation settings (at most :data:`NONLINEAR_SAMPLES` draws,
        :data:`QUICK_NONLINEAR_SAMPLES` with ``--quick``); None when not computed.
    """

    spec: UncertaintySpec
    intervals: LinearIntervals
    nominal_rates: np.ndarray
    nonlinear: NonlinearIntervals | None = None

    def rate_at(self, speed: float = REFERENCE_SPEED) -> tuple[float, float]:
        """The growth-rate interval at ``speed`` (one of the band speeds), 1/s."""
        k = int(np.argmin(np.abs(np.asarray(self.intervals.speeds) - speed)))
        return self.intervals.rate[k]

    @property
    def dominant(self) -> tuple[str, float] | None:
        """The parameter with the largest share of the variance and its share (None if nothing varies)."""
        top = self.intervals.dominant_parameters
        return top[0] if top and top[0][1] > 0 else None


def uncertainty_section(chair: Chair, spec: UncertaintySpec, *, model: str, quick: bool,
                        settings: Settings | None = None, scheme: str = "wchair",
                        nonlinear: bool = True) -> UncertaintySection:
    """Compute the section (see :class:`UncertaintySection`).

    Parameters
    ----------
    chair : Chair
    spec : UncertaintySpec
    model : {"exact", "thesis"}
    quick : bool
        Fewer band speeds and nonlinear draws.
    settings : Settings, optional
        The report's simulation settings (default ``Settings.for_mode(quick)``): the nonlinear
        nominal values then equal the report's own critical impulse and equal-instability speed.
    scheme : {"wchair", "adaptive"}
        Integration scheme of the simulations.
    nonlinear : bool
        Also the nonlinear intervals.

    Returns
    -------
    UncertaintySection
    """
    s = settings or Settings.for_mode(quick)
    speeds = QUICK_BAND_SPEEDS if quick else BAND_SPEEDS
    iv = linear_intervals(chair, spec.uncertainty, model=model, speeds=speeds, samples=spec.samples, seed=spec.seed)
    nominal = ChairBatch([chair], model).growth_rates(np.asarray(speeds))[0]
    nl = None
    if nonlinear:
        n = min(int(spec.samples), QUICK_NONLINEAR_SAMPLES if quick else NONLINEAR_SAMPLES)
        # the tolerances of the report's own critical impulses and equal-instability speeds (compute.compute)
        nl = nonlinear_intervals(chair, spec.uncertainty, RunSpec(model=model, scheme=scheme, dt=s.dt,
                                                                  horizon=s.duration),
                                 speed=REFERENCE_SPEED, samples=n, seed=spec.seed, rel_tol=s.impulse_rel_tol,
                                 bracket=s.bracket, tol=s.tol, candidates=s.candidates)
    return UncertaintySection(spec, iv, np.asarray(nominal, dtype=float), nl)
