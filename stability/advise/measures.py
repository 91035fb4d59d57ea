"""Every measure the advisor weighs, for many chairs at once: the one place it calls the studies.

A chair's measures are exactly what the commands print for it:

- ``critical_impulse_Ns``: ``python -m stability.study critical-impulse --speeds 0.75 --interval``
  (:func:`stability.study.critical_impulse_intervals`; interval over pin friction x0.5/x1.5, model and
  half the simulator step);
- ``equal_instability_speed_m_s``: ``python -m stability.study equal-instability``
  (:func:`stability.study.equal_instability_intervals`; interval over push, pin friction, model and step);
- ``static_stability_deg``: the smallest of ``python -m stability.tipping``'s four angles;
- ``shimmy_margin_m``: ``python -m stability.shimmy --speeds S --json``'s ``shimmy_band.shimmy_margin_m``
  (interval over the estimate ranges);
- ``turning_effort_N_m``: the larger pin friction (the moment to swivel a caster at its pin);
- ``cross_slope_effort``: ``python -m stability.slope --cross-slope D --speed 0.75``'s drive difference
  (right minus left) with the drive the slope command picks: the hand-rim force difference (N) of a manual
  chair, the motor torque difference (N m) of a power chair (:func:`stability.chair.power.drive_kind`).

All chairs go through each study in one batch (:func:`measure_chairs`), so a faster study
(batched, started from the linear prediction) speeds the advisor up with no change here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import partial
from typing import Any, cast

import numpy as np

from stability.advise.lazy import Lazy, reused
from stability.bench import run_bench
from stability.chair import Chair, preset
from stability.chair.model import takes_chairs
from stability.chair.power import drive_kind
from stability.driver.linear import rule_speed
from stability.layout.model import Layout
from stability.linear import eigenvalues_vs_speed
from stability.runtime.progress import ProgressBar
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.shimmy.band import band_core, shimmy_band
from stability.slope import drive_report, solve
from stability.study import critical_impulse_intervals, equal_instability_intervals
from stability.study.impulse_intervals import CriticalImpulseInterval
from stability.study.intervals import scale_friction
from stability.tipping import tip_angles

__all__ = ["Interval", "Measures", "Linear", "LazyLinear", "measure_chairs", "linear_measures", "chair_linear",
           "nonlinear_measures", "screening_measures", "SCREEN_FRICTION_FACTOR", "cross_slope_effort", "IMPULSE_SPEED",
           "EFFORT_KEYS", "EFFORT_WORDS"]

#: Speed of the critical impulse the advisor weighs (the thesis's reference speed), m/s.
IMPULSE_SPEED = REFERENCE_SPEED


@dataclass(frozen=True)
class Interval:
    """A value with its interval.

    Attributes
    ----------
    value : float or None
        Nominal value (None: undefined; an infinity: unbounded, as a shimmy margin with no boundary on the trails
        searched, ``+inf``, or no stable trail, ``-inf``).
    low, high : float or None
        Interval ends (None: unbounded or undefined on that side; the shimmy margin's are infinities there).
    """

    value: float | None
    low: float | None
    high: float | None

    @property
    def robust(self) -> float | None:
        """The low end of the interval (what the advisor judges on), else the value."""
        return self.low if self.low is not None else self.value

    def to_mapping(self) -> dict:
        """``{"value": v, "interval": [low, high]}`` (non-finite numbers as null)."""
        def f(x: float | None) -> float | None:
            return None if x is None or not math.isfinite(x) else float(x)

        return {"value": f(self.value), "interval": [f(self.low), f(self.high)]}


@dataclass(frozen=True)
class Measures:
    """What the advisor knows about one chair.

    Attributes
    ----------
    chair : str
        Chair name.
    critical_impulse_Ns : Interval
        Critical impulse at :data:`IMPULSE_SPEED` (N s), interval over pin friction, model and step.
    equal_instability_speed_m_s : Interval
        Equal-instability speed (m/s; a bracket end when beyond it), interval over push, friction, model, step.
    static_stability_deg : Interval
        Smallest static stability angle (deg); geometric, so the interval is the value.
    shimmy_margin_m : Interval
        Signed distance of the trail from the nearest shimmy boundary at the use speeds (m), nominal
        estimates; interval over the estimate ranges (None: unbounded).
    shimmy_straddles : bool
        The estimate range straddles a boundary (measure pin stiffness and relaxation length first).
    turning_effort_N_m : float
        Larger of the two pins' Coulomb friction (N m): the moment to swivel a caster at its pin.
    cross_slope_effort : float or None
        Drive difference right minus left on the cross slope at :data:`IMPULSE_SPEED`: the hand-rim force
        difference (N) or, for a power chair, the motor torque difference (N m) (``drive``); None where the
        slope statics refuse the chair (tire data).
    growth_rate_1_s : float
        Linear growth rate, free frictionless casters, at :data:`IMPULSE_SPEED` (1/s).
    tip_angles_deg : dict
        The four ISO 7176-1 angles (deg) by direction.
    equal_instability_status : str
        ``"found"``, ``"above"`` (beyond 3 m/s) or ``"below"`` (below 0.2 m/s).
    critical_impulse_status : str
        ``"found"``, ``"never"`` (not even the largest push tried, 40 N s, spins it: the value is that
        bound) or ``"below"``.
    critical_impulse_half_step_Ns : float or None
        The nominal critical impulse again at half the simulator's 1 ms step (N s; None: not computed):
        where it differs much from the value, the 1 ms step resolves the caster modes too coarsely.
    drive : {"handrim", "motor"}
        What holds the chair on the cross slope (:func:`stability.chair.power.drive_kind`).
    human_speed_m_s : float or None
        With a driver: the speed up to which a driver of that reaction time holds the chair (the divergence
        rule, :func:`stability.driver.linear.rule_speed`), m/s; None without a driver.
    human_side : str
        ``"="``, or ``">"`` when beyond the speeds searched.
    bench_score : int or None
        A powered chair's worst ISO 7176-2 wheel-lift score on the virtual bench at the default drive settings
        (0-3, :func:`stability.bench.run_bench`); None for a chair pushed on its hand rims.
    shimmy_row : str
        A wheel layout's caster row whose margin this is (``"front"``, ``"rear"``; :mod:`.layout_measures`);
        empty for the short form (its one caster pair).
    shimmy_trail_m : float or None
        That row's trail, m (None: the short form's ``trail``).
    """

    chair: str
    critical_impulse_Ns: Interval
    equal_instability_speed_m_s: Interval
    static_stability_deg: Interval
    shimmy_margin_m: Interval
    shimmy_straddles: bool
    turning_effort_N_m: float
    cross_slope_effort: float | None
    growth_rate_1_s: float
    tip_angles_deg: dict
    equal_instability_status: str
    critical_impulse_status: str = "found"
    critical_impulse_half_step_Ns: float | None = None
    drive: str = "handrim"
    human_speed_m_s: float | None = None
    human_side: str = "="
    bench_score: int | None = None
    shimmy_row: str = ""
    shimmy_trail_m: float | None = None

    @property
    def effort_key(self) -> str:
        """The cross-slope effort's name with its unit: ``handrim_force_difference_N`` or
        ``motor_torque_difference_N_m``."""
        return EFFORT_KEYS[self.drive]

    def to_mapping(self) -> dict:
        """JSON-ready dict: the issue's ``predicted`` keys plus the costs."""
        return {
            "critical_impulse_Ns": self.critical_impulse_Ns.to_mapping(),
            "critical_impulse_speed_m_s": IMPULSE_SPEED,
            "critical_impulse_status": self.critical_impulse_status,
            "critical_impulse_half_step_Ns": self.critical_impulse_half_step_Ns,
            "equal_instability_speed_m_s": self.equal_instability_speed_m_s.to_mapping(),
            "equal_instability_status": self.equal_instability_status,
            "static_stability_deg": self.static_stability_deg.to_mapping(),
            "shimmy_margin_m": self.shimmy_margin_m.to_mapping(),
            "shimmy_estimate_range_straddles_boundary": self.shimmy_straddles,
            "turning_effort_N_m": self.turning_effort_N_m,
            self.effort_key: self.cross_slope_effort,
            "growth_rate_1_s": self.growth_rate_1_s,
            "tip_angles_deg": dict(self.tip_angles_deg),
            "human_limited_speed_m_s": self.human_speed_m_s,
            "human_limited_side": self.human_side if self.human_speed_m_s is not None else None,
            "bench_worst_score": self.bench_score,
            **({"shimmy_caster_row": self.shimmy_row, "shimmy_trail_m": self.shimmy_trail_m}
               if self.shimmy_row else {}),
        }


#: The cross-slope effort's key (name and unit) by drive.
EFFORT_KEYS = {"handrim": "handrim_force_difference_N", "motor": "motor_torque_difference_N_m"}
#: What each drive's effort is, in words, with its unit.
EFFORT_WORDS = {"handrim": ("hand-rim force difference", "N"), "motor": ("motor torque difference", "N m")}


def cross_slope_effort(chair: Chair, cross_slope_deg: float) -> float | None:
    """The drive difference (right minus left) that holds ``chair`` on the cross slope at :data:`IMPULSE_SPEED`.

    Parameters
    ----------
    chair : Chair
    cross_slope_deg : float
        deg (0: level, no effort).

    Returns
    -------
    float or None
        Hand-rim force difference (N) of a manual chair, motor torque difference (N m) of a power chair
        (:func:`stability.chair.power.drive_kind`); None where the slope statics refuse the chair.
    """
    if cross_slope_deg == 0:
        return 0.0
    try:
        eq = solve(chair, cross_slope_deg, IMPULSE_SPEED, friction_range=False)   # the drive only: 4 solves fewer
    except ValueError:
        return None
    kind = drive_kind(chair)
    rep = drive_report(chair, eq, kind)
    if kind == "handrim":
        return float(rep["handrim_force_difference_N"])
    return float(rep["motor_torque_right_N_m"] - rep["motor_torque_left_N_m"])


def nonlinear_measures(chairs: Sequence[Chair]) -> list[tuple[Interval, Interval, str, str, float | None]]:
    """Critical impulse and equal-instability speed (with intervals) of every chair, one batch per study.

    Parameters
    ----------
    chairs : sequence of Chair

    Returns
    -------
    list of tuple
        ``(critical_impulse_Ns, equal_instability_speed_m_s, equal_instability_status, critical_impulse_status,
        critical_impulse_half_step_Ns)`` per chair.
    """
    ci = critical_impulse_intervals(chairs, IMPULSE_SPEED)
    ei = equal_instability_intervals(chairs)
    return [(Interval(float(imp.point.bound_Ns), imp.low_Ns, imp.high_Ns),
             Interval(float(eq.point.value_or_bound), eq.low, eq.high), eq.point.status,
             imp.point.status, _half_step(imp))
            for imp, eq in zip(ci, ei, strict=True)]


#: Pin-friction factor of the screening runs (:func:`screening_measures`): the variant that sets the low end of the
#: presets' and their changes' critical-impulse intervals, and of most of their equal-instability intervals.
SCREEN_FRICTION_FACTOR = 0.5


def screening_measures(chairs: Sequence[Chair]) -> list[tuple[Interval, Interval, str, str, float | None]]:
    """Upper bounds of the low ends of every chair's critical-impulse and equal-instability intervals: the
    advisor's screening (:mod:`.pruning`), one run per measure and chair.

    Runs only the :data:`SCREEN_FRICTION_FACTOR` pin-friction variant of :func:`nonlinear_measures` (the chair's
    pins scaled, and for the equal-instability speed the reference chair's too, as the interval scales both), one
    batch per study.  A chair's result does not depend on its batch, so each value is that variant's value in
    :func:`nonlinear_measures`, and the low end it gives (the smallest over every variant) is at most this.

    Parameters
    ----------
    chairs : sequence of Chair

    Returns
    -------
    list of tuple
        As :func:`nonlinear_measures`, with ``Interval(None, bound of the low end, None)`` (no nominal value),
        the statuses of the screening runs and no half-step value.
    """
    f = SCREEN_FRICTION_FACTOR
    scaled = [scale_friction(c, f) for c in chairs]
    ci = critical_impulse_intervals(scaled, IMPULSE_SPEED, friction_factors=(), models=(), step_factors=())
    ei = equal_instability_intervals(scaled, force_factors=(), friction_factors=(), models=(), step_factors=(),
                                     reference_chair=scale_friction(preset(REFERENCE_CHAIR), f))
    return [(Interval(None, float(imp.point.bound_Ns), None), Interval(None, float(eq.point.value_or_bound), None),
             eq.point.status, imp.point.status, None) for imp, eq in zip(ci, ei, strict=True)]


def _half_step(imp: CriticalImpulseInterval) -> float | None:
    """The interval's half-step variant (:data:`stability.study.impulse_intervals.STEP_FACTORS`), N s."""
    half = [r for label, r in imp.variants if label.endswith(" ms step")]
    return float(half[0].bound_Ns) if half else None


@dataclass(frozen=True)
class Linear:
    """The measures of a chair that need no simulation (statics, shimmy band, linear model): the constraints.

    Attributes
    ----------
    static_stability_deg : Interval
        Geometric: the interval is the value.
    tip_angles_deg : dict
    shimmy_margin_m : Interval
    shimmy_straddles : bool
    turning_effort_N_m : float
    cross_slope_effort : float or None
    drive : str
    growth_rate_1_s : float
    human_speed_m_s : float or None
    human_side : str
    bench_score : int or None
        As :attr:`Measures.bench_score`.
    shimmy_row : str
    shimmy_trail_m : float or None
        As :attr:`Measures.shimmy_row` and :attr:`Measures.shimmy_trail_m`.
    """

    static_stability_deg: Interval
    tip_angles_deg: dict
    shimmy_margin_m: Interval
    shimmy_straddles: bool
    turning_effort_N_m: float
    cross_slope_effort: float | None
    drive: str
    growth_rate_1_s: float
    human_speed_m_s: float | None = None
    human_side: str = "="
    bench_score: int | None = None
    shimmy_row: str = ""
    shimmy_trail_m: float | None = None

    @property
    def effort_key(self) -> str:
        """As :attr:`Measures.effort_key`."""
        return EFFORT_KEYS[self.drive]


def bench_score(chair: Chair) -> int | None:
    """A powered chair's worst wheel-lift score on the virtual bench (ISO 7176-2 matrix, default drive settings).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    int or None
        0-3 (:data:`stability.bench.loads.SCORE_WORDS`); None for a chair pushed on its hand rims.
    """
    return run_bench(Layout.from_chair(chair)).worst_score if drive_kind(chair) == "motor" else None


class LazyLinear(Lazy):
    """A design's :class:`Linear` measures, each computed when first read (the same calls, so the same values).

    The advisor's pair screening reads the measures only as far as a limit fails
    (:func:`stability.advise.limits.meets`): a pair below the chair's tip angle needs neither its shimmy band nor
    its bench.  :meth:`linear` reads every measure, in the order of the groups (:class:`.lazy.Lazy`).
    """

    @property
    def effort_key(self) -> str:
        """As :attr:`Measures.effort_key`."""
        return EFFORT_KEYS[self.drive]

    def linear(self) -> Linear:
        """Every measure (the groups computed in their order).

        Returns
        -------
        Linear
        """
        return Linear(**self.values())


def chair_linear(c: Chair, *, speeds: Sequence[float], cross_slope_deg: float, cores: dict,
                 reaction_time: float | None = None) -> LazyLinear:
    """One chair's measures that need no simulation, each computed when first read (:func:`linear_measures`).

    Parameters
    ----------
    c : Chair
    speeds, cross_slope_deg, cores, reaction_time
        As :func:`linear_measures` (``cores`` is filled as the shimmy band is read).

    Returns
    -------
    LazyLinear
    """
    def band() -> dict[str, Any]:
        key = c.replace(trail=0.05, pin_friction_left=0.0, pin_friction_right=0.0, name="-")
        if key not in cores:
            cores[key] = band_core(c, speeds)
        b = shimmy_band(c, speeds, core=cores[key])
        low, high = b.shimmy_margin_interval_m
        # the infinities kept (an unbounded margin is a value the limit can be met by; JSON writes null)
        return {"shimmy_margin_m": Interval(float(b.shimmy_margin_m), float(low), float(high)),
                "shimmy_straddles": b.straddles}

    def tips() -> dict[str, Any]:
        t = tip_angles(c)
        return {"static_stability_deg": Interval(t.smallest_deg, t.smallest_deg, t.smallest_deg),
                "tip_angles_deg": {k: getattr(t, k + "_deg") for k in ("toward_main_wheels", "toward_casters",
                                                                      "lateral_left", "lateral_right")}}

    def human() -> dict[str, Any]:
        u, side = rule_speed(c, reaction_time) if reaction_time is not None else (None, "=")
        return {"human_speed_m_s": u, "human_side": side}

    return LazyLinear({               # the order of the eager measures before (tire-range warnings in that order)
        "band": (("shimmy_margin_m", "shimmy_straddles"), band),
        "tips": (("static_stability_deg", "tip_angles_deg"), tips),
        "human": (("human_speed_m_s", "human_side"), human),
        "turning": (("turning_effort_N_m",),
                    lambda: {"turning_effort_N_m": max(c.pin_friction_left, c.pin_friction_right)}),
        "slope": (("cross_slope_effort",), lambda: {"cross_slope_effort": cross_slope_effort(c, cross_slope_deg)}),
        "drive": (("drive",), lambda: {"drive": drive_kind(c)}),
        "growth": (("growth_rate_1_s",), lambda: {"growth_rate_1_s": float(np.max(eigenvalues_vs_speed(
            c, [IMPULSE_SPEED], track=False).real))}),
        "bench": (("bench_score",), lambda: {"bench_score": bench_score(c)})})


def linear_measures(chairs: Sequence[Chair], *, speeds: Sequence[float], cross_slope_deg: float,
                    cores: dict | None = None, reaction_time: float | None = None,
                    lazy: bool = False) -> list:
    """The measures that need no simulation, for every chair (about 4 ms a chair, 25 ms with a new band core).

    Parameters
    ----------
    chairs : sequence of Chair
    speeds : sequence of float
        Use speeds (m/s) of the shimmy band.
    cross_slope_deg : float
        deg.
    cores : dict, optional
        Cache of shimmy band cores (the band search ignores the trail and the Coulomb pin friction), and of each
        chair's measures computed so far (:func:`.lazy.reused`: the advisor's screened pairs measured again);
        shared between calls.
    reaction_time : float, optional
        A driver's effective delay, s: adds the human-limited speed (the divergence rule).
    lazy : bool
        Return each chair's :class:`LazyLinear` (a measure computed when read) instead of its :class:`Linear`.

    Returns
    -------
    list of Linear (or of LazyLinear)
    """
    cores = {} if cores is None else cores
    inputs = (tuple(speeds), cross_slope_deg, reaction_time)
    out = [cast(LazyLinear, reused(cores, c, inputs, partial(chair_linear, c, speeds=speeds,
                                                            cross_slope_deg=cross_slope_deg, cores=cores,
                                                            reaction_time=reaction_time))) for c in chairs]
    return out if lazy else [x.linear() for x in out]


@takes_chairs
def measure_chairs(chairs: Sequence[Chair], *, speeds: Sequence[float], cross_slope_deg: float,
                   progress: bool = False, nonlinear: Callable | None = None,
                   cores: dict | None = None, reaction_time: float | None = None) -> list[Measures]:
    """The advisor's measures of every chair, each study in one batch for all of them.

    Parameters
    ----------
    chairs : sequence of Chair
    speeds : sequence of float
        Use speeds (m/s) at which the shimmy margin is taken (the smallest over them).
    cross_slope_deg : float
        Cross slope of the drive difference (deg).
    progress : bool
        Show a progress bar on stderr.
    nonlinear : callable, optional
        Replaces :func:`nonlinear_measures` (same signature); for tests of everything else.
    cores : dict, optional
        Shimmy band cores to share (:func:`linear_measures`).
    reaction_time : float, optional
        A driver's effective delay, s (:func:`linear_measures`).

    Returns
    -------
    list of Measures
        One per chair, in order.
    """
    chairs = list(chairs)
    with ProgressBar(2, f"measuring {len(chairs)} chair(s)", enabled=progress, unit="step") as bar:
        nl = (nonlinear or nonlinear_measures)(chairs)
        bar.update()
        out = []
        for c, lin, (imp, eq, status, *more) in zip(chairs, linear_measures(chairs, speeds=speeds,
                                                                             cross_slope_deg=cross_slope_deg,
                                                                             cores=cores,
                                                                             reaction_time=reaction_time),
                                                             nl, strict=True):
            out.append(Measures(
                chair=c.name, critical_impulse_Ns=imp, equal_instability_speed_m_s=eq,
                static_stability_deg=lin.static_stability_deg,
                shimmy_margin_m=lin.shimmy_margin_m, shimmy_straddles=lin.shimmy_straddles,
                turning_effort_N_m=lin.turning_effort_N_m, cross_slope_effort=lin.cross_slope_effort,
                growth_rate_1_s=lin.growth_rate_1_s, tip_angles_deg=lin.tip_angles_deg,
                equal_instability_status=status, critical_impulse_status=more[0] if more else "found",
                critical_impulse_half_step_Ns=more[1] if len(more) > 1 else None, drive=lin.drive,
                human_speed_m_s=lin.human_speed_m_s, human_side=lin.human_side, bench_score=lin.bench_score,
            ))
        bar.update()
    return out
