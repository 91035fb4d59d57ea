"""Every number the report shows, computed once: :func:`compute` -> :class:`ReportData`."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import brentq

from stability import rootlocus, study
from stability.advise import advise
from stability.advise.measures import measure_chairs
from stability.chair import Chair, preset
from stability.chair.design import get_parameter
from stability.driver import human_limit
from stability.linear import analyse, divergence, massless_caster_rate
from stability.linear.names import mode_names
from stability.report.comparison import Baseline, baseline_summary
from stability.report.settings import Settings
from stability.report.shimmy_data import ShimmySection, shimmy_section, shimmy_unavailable
from stability.report.slope_data import SlopeSection, slope_section
from stability.report.tire_data import ForceCurves, StiffnessCurves, force_curves, stiffness_curves
from stability.report.trail_window import TrailWindow, trail_window
from stability.report.uncertainty_data import UncertaintySection, UncertaintySpec, uncertainty_section
from stability.report.validity import responses_validity
from stability.runtime.progress import ProgressBar
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.shimmy.band import shimmy_band
from stability.study.impulse import critical_impulses
from stability.study.validation import linearisation_check, with_rolling_resistance
from stability.tipping import LOANE_KIRBY_REAR_DEG, TipAngles, tip_angles

__all__ = ["Settings", "ReportData", "Figure814", "compute", "parameter_loci", "counterpart",
           "response_speeds", "stabilising_poles", "FIGURE_8_14", "COMPARISON_CHAIR",
           "equal_instability_range"]

#: Figure 8-14 of the thesis: the E&J Premier with less mass and yaw inertia (kg, kg m^2).
FIGURE_8_14 = {"m": 75.0, "i_z": 4.7}
#: Speeds a manual chair is used at (m/s: a slow walk to a brisk one), for the shimmy-free trail window.
USE_SPEEDS = (0.5, 0.75, 1.0, 1.5, 2.0)
#: The chair whose intervals the reference chair's report shows (the thesis's revised design).
COMPARISON_CHAIR = "revised"


@dataclass(frozen=True, eq=False)
class Figure814:
    """The thesis's Figure 8-14 (a lighter E&J Premier) recomputed, and why it is not reproduced.

    Attributes
    ----------
    chair : Chair
        The reference chair with ``FIGURE_8_14`` mass and yaw inertia.
    speed : EqualInstability
        Its equal-instability speed (the thesis reads about 0.85 m/s).
    rate_reference, rate_light : float
        Linear growth rates at the reference speed (free casters), 1/s.
    massless_reference, massless_light : float
        The massless-caster closed form ``U m x_m / (I_z + m x_m^2)`` for both, 1/s.
    """

    chair: Chair
    speed: Any
    rate_reference: float
    rate_light: float
    massless_reference: float
    massless_light: float


@dataclass(frozen=True, eq=False)
class ReportData:
    """Everything the report shows, computed once (see :func:`compute`).

    Attributes
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    settings : Settings
    summary, summary_other : stability.linear.StabilitySummary
        Linear summaries in the report's model and the other variant.
    speed_loci : dict
        (model, casters) -> SpeedLocus.
    parameter_loci, gain_loci : list
        Root loci against the design parameters and a yaw-rate feedback gain (0.75 and 1.5 m/s).
    thesis : stability.study.ThesisStudy
    chair_sweeps : stability.study.SweepTable
        The parametric study around this chair.
    chair_speed : EqualInstability
        This chair's equal-instability speed.
    chair_friction : list of EqualInstability
        At 0.5 and 1.5 times its pin friction.
    responses, responses_frictionless, paths : stability.study.ResponseSet
        Yaw-rate responses around the equal-instability speed, without pin friction, and the paths of
        the chair and its caster-swapped counterpart.
    friction_map, disturbance_map : stability.study.StabilityMap
    conclusions : list of ConclusionCheck
    scheme : str
    rolling : LinearisationCheck or None
        The simulator's linearisation with rolling resistance on, at the reference speed.
    tire_force : tuple of ForceCurves
        Main and caster tire (Figure 4-1).
    tire_stiffness : StiffnessCurves or None
        Figure 4-2 with the chair's static points.
    gain_poles : tuple
        Closed-loop eigenvalues at each gain locus's stabilising gain (or None).
    mode_names : dict
        (model, casters) -> names of the speed locus's branches.
    validity : dict
        "responses", "frictionless", "paths" -> tuple of Validity, one per run.
    intervals : stability.study.EqualInstabilityInterval or None
        The equal-instability speed of the chair (the revised design in the reference chair's report) over
        the variations of :func:`stability.study.equal_instability_interval` (the one definition the study
        command and the advisor share: ``stability.study.RANGE_DEFINITION``), at its own resolution in a full
        report (so the study command prints the same range) and at the quick settings' with ``--quick``.
    sensitivity : stability.study.Sensitivity or None
        Elasticities of the critical impulse and growth rate at the reference speed (M_f/l as one group).
    slope : SlopeSection or None
        Cross-slope holding moment, drive difference and uncorrected path.
    shimmy : ShimmySection or None
        Trail trade-off (None when the casters cannot shimmy in the model; ``shimmy_note`` says why).
    shimmy_note : str or None
    uncertainty : UncertaintySection or None
        Linear intervals over ``--uncertainty FILE`` (None without it).
    impulses : tuple of CriticalImpulse
        The chair and the reference (or revised) chair at the reference speed.
    figure_8_14 : Figure814 or None
    baseline : Baseline or None
        The chair the report compares with (``report --compare``), computed the same way.
    tipping : TipAngles or None
        Static stability angles (ISO 7176-1) of the chair.
    trail_window : TrailWindow or None
        Directional stability against trail with the shimmy-free window (None without a trail sweep or
        a shimmy model).
    tip_limits : dict
        Axle-position parameter (``s1``, ``cg_ratio``) -> the value at which the static stability angle toward
        the main wheels falls to ``tip_limits_deg`` (the parametric study's constraint line).
    tip_limits_deg : float
        That angle, deg.
    advice : stability.advise.Advice or None
        The advisor's verdict and recommendation (page 1).
    reference_measures : stability.advise.Measures or None
        The thesis's reference chair measured as the advisor measures (None when the chair is that chair).
    reference_trail : float
        Its trail, m.
    brief : bool
        The quick report (:func:`stability.report.brief.compute_brief`): page 1, the clinician sheet and the
        references only.
    sheet : stability.report.clinician_sheet.ClinicianSheet or None
        The clinician sheet (brief report only).
    driver, human : stability.driver.Driver, stability.driver.HumanLimit or None
        The user (``--reaction-time`` or the file's ``[user]``; the advice weighs it) and its two limits.
    """

    chair: Chair
    model: str
    settings: Settings
    summary: Any                 # linear.StabilitySummary
    summary_other: Any           # the other model variant's summary
    speed_loci: dict             # (model, casters) -> SpeedLocus
    parameter_loci: list
    gain_loci: list
    thesis: Any                  # study.ThesisStudy
    chair_sweeps: Any            # study.SweepTable for this chair
    chair_speed: Any             # EqualInstability of this chair
    chair_friction: list         # EqualInstability at x0.5, x1.5 friction
    responses: Any               # ResponseSet (speeds)
    responses_frictionless: Any  # ResponseSet (no pin friction: where the linear model applies)
    paths: Any                   # ResponseSet (chair and caster-swapped counterpart)
    friction_map: Any
    disturbance_map: Any
    conclusions: list
    scheme: str = "wchair"
    rolling: Any = None          # validation.LinearisationCheck at 0.75 m/s with rolling resistance on
    tire_force: tuple[ForceCurves, ...] = ()     # main, caster (Figure 4-1)
    tire_stiffness: StiffnessCurves | None = None  # Figure 4-2 with the chair's static points
    gain_poles: tuple = ()       # closed-loop eigenvalues at each gain locus's stabilising gain (or None)
    mode_names: dict = field(default_factory=dict)   # (model, casters) -> names of the speed locus's branches
    validity: dict = field(default_factory=dict)     # "responses", "frictionless", "paths" -> tuple of Validity
    intervals: Any = None        # study.EqualInstabilityInterval
    sensitivity: Any = None      # study.Sensitivity
    slope: SlopeSection | None = None
    shimmy: ShimmySection | None = None
    shimmy_note: str | None = None
    uncertainty: UncertaintySection | None = None
    impulses: tuple = ()         # CriticalImpulse of the chair and the reference chair at the reference speed
    figure_8_14: Figure814 | None = None
    baseline: Baseline | None = None
    tipping: TipAngles | None = None
    trail_window: TrailWindow | None = None
    tip_limits: dict = field(default_factory=dict)
    advice: Any = None
    reference_measures: Any = None
    reference_trail: float = float("nan")
    tip_limits_deg: float = LOANE_KIRBY_REAR_DEG
    brief: bool = False
    sheet: Any = None
    driver: Any = None
    human: Any = None


def tip_limits(c: Chair, sweeps: Any, angle_deg: float = LOANE_KIRBY_REAR_DEG) -> dict:
    """Where moving the main axle toward the c.g. makes the braked chair tip toward its main wheels at
    ``angle_deg``: parameter -> value, for the axle-position sweeps present (``s1``, ``cg_ratio``).

    Parameters
    ----------
    c : Chair
    sweeps : SweepTable
    angle_deg : float

    Returns
    -------
    dict
        Parameter name -> value (absent when the angle is not crossed inside the parameter's span).
    """
    out = {}
    for name in ("s1", "cg_ratio"):
        if name not in sweeps:
            continue
        p = get_parameter(name)
        lo, hi = p.span(c)
        f = lambda v, p=p: tip_angles(p.apply(c, v)).toward_main_wheels_deg - angle_deg  # noqa: E731
        try:
            fa, fb = f(lo), f(hi)
        except ValueError:            # a value of the span the chair cannot take
            continue
        if fa * fb < 0:
            out[name] = float(brentq(f, lo, hi, xtol=1e-5))
    return out


def equal_instability_range(c: Chair, model: str, s: Settings, scheme: str = "wchair") -> Any:
    """The report's equal-instability range: :func:`stability.study.equal_instability_interval`'s definition
    (the one ``python -m stability.study equal-instability`` and the advisor use), at the study's resolution in
    a full report and at the coarse settings' with ``--quick``.

    Parameters
    ----------
    c : Chair
    model : {"exact", "thesis"}
    s : Settings
    scheme : str

    Returns
    -------
    stability.study.EqualInstabilityInterval
    """
    return study.equal_instability_interval(
        c, report_run(model, s, scheme), criterion=study.Criterion(duration=s.duration),
        bracket=s.bracket if s.quick else study.RANGE_BRACKET, tol=s.tol if s.quick else study.RANGE_TOL,
        candidates=s.candidates)


def report_run(model: str, s: Settings, scheme: str) -> RunSpec:
    """The report's runs: the thesis's push, the settings' step and horizon, ``model`` and ``scheme``, the
    default (stick-slip) pin friction.

    Parameters
    ----------
    model : {"exact", "thesis"}
    s : Settings
    scheme : str

    Returns
    -------
    RunSpec
    """
    return RunSpec(model=model, scheme=scheme, dt=s.dt, horizon=s.duration, push_force=THESIS_PUSH.force,
                   push_duration=THESIS_PUSH.duration)


def counterpart(c: Chair) -> Chair:
    """The same chair with its casters at the other end (s1 and s2 exchanged, as chapter 8's 'Method One').

    Parameters
    ----------
    c : Chair

    Returns
    -------
    Chair
    """
    pos = "front" if c.caster_position == "rear" else "rear"
    return c.replace(name=f"{c.name}, casters swapped", caster_position=pos, s1=c.s2, s2=c.s1)


def response_speeds(u_star: float) -> list[float]:
    """Five speeds around the equal-instability speed (the thesis: .55 ... .95 around .75).

    Parameters
    ----------
    u_star : float
        The chair's equal-instability speed (m/s).

    Returns
    -------
    list of float
        Speeds (m/s), rounded to 0.05 m/s when scaled.
    """
    base = [0.55, 0.65, 0.75, 0.85, 0.95]
    f = u_star / REFERENCE_SPEED
    return [round(s * f / 0.05) * 0.05 if f != 1 else s for s in base]


def stabilising_poles(locus: Any) -> np.ndarray | None:
    """Closed-loop eigenvalues (1/s) of a gain locus at its smallest stabilising gain.

    Parameters
    ----------
    locus : stability.rootlocus.GainLocus

    Returns
    -------
    ndarray of complex or None
        None when no positive gain stabilises the model.
    """
    k = locus.stabilising_gain
    if k is None or k <= 0:
        return None
    a = rootlocus.closed_loop_matrices(locus.chair, locus.speed, [k], model=locus.model, casters=locus.casters)[0]
    return np.linalg.eigvals(a)


def parameter_loci(c: Chair, model: str, n: int) -> list:
    """Root loci against the design parameters at the reference speed, over each parameter's default span.

    The spans stay within chairs that can stand (:meth:`stability.chair.design.Parameter.span`; e.g. the
    c.g.-ratio span of a front-caster chair ends before its main wheels unload).

    Parameters
    ----------
    c : Chair
    model : {"exact", "thesis"}
    n : int
        Points per locus.

    Returns
    -------
    list of stability.rootlocus.ParameterLocus
    """
    return [rootlocus.parameter_locus(c, name, speed=REFERENCE_SPEED, model=model, n=n)
            for name in rootlocus.LOCUS_PARAMETERS]


def compute(c: Chair, model: str = "exact", *, quick: bool = False, progress: bool = True,
            scheme: str = "wchair", settings: Settings | None = None,
            log: Callable[[str], None] | None = None, uncertainty: UncertaintySpec | None = None,
            baseline: Chair | None = None, driver: Any = None,
            intended_speed: float | None = None) -> ReportData:
    """Run every analysis of the report for chair ``c``.

    Parameters
    ----------
    c : Chair
    model : {"exact", "thesis"}
        Equation variant of the linear analysis and the simulations.
    quick : bool
        Coarse settings (ignored when ``settings`` is given).
    progress : bool
        Show progress bars (on a terminal).
    scheme : str
        Integration scheme of the simulations (``"wchair"``: the thesis's).
    settings : Settings, optional
    log : callable, optional
        Called with the name of each finished stage.
    uncertainty : UncertaintySpec, optional
        Parameter distributions for the linear and nonlinear intervals (``--uncertainty FILE``).
    baseline : Chair, optional
        A chair to compare with: its key numbers are computed with the same settings, model and reference.
    driver, intended_speed : stability.driver.Driver, float (m/s), optional
        The user and the speed they want: :func:`stability.advise.advise`'s; page 1 gives the user's limits.

    Returns
    -------
    ReportData
    """
    s = settings or Settings.for_mode(quick)
    other = "thesis" if model == "exact" else "exact"
    run = report_run(model, s, scheme)
    crit = study.Criterion(duration=s.duration)
    ref_chair = preset(REFERENCE_CHAIR)
    is_ej = c == ref_chair
    light = ref_chair.replace(name=f"{REFERENCE_CHAIR}, m {FIGURE_8_14['m']:g} kg, I_z {FIGURE_8_14['i_z']:g} kg m^2",
                              **FIGURE_8_14)
    stages = 12
    with ProgressBar(stages, f"report {c.name}", enabled=progress, unit="stage") as bar:
        def stage(msg: str) -> None:
            if log:
                log(msg)
            bar.update()

        summary = analyse(c, model=model, speeds=(0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0))
        summary_other = analyse(c, model=other, speeds=(REFERENCE_SPEED,))
        rolling = linearisation_check(with_rolling_resistance(c), REFERENCE_SPEED, model=model)
        tire_force = (force_curves(c, "main"), force_curves(c, "caster"))
        tire_stiffness = stiffness_curves(c)
        stage("linear summary")
        loci = {}
        for m in (model, other):
            for cs in ("free", "locked"):
                loci[(m, cs)] = rootlocus.speed_locus(c, model=m, casters=cs, n=s.speed_points)
        names = {k: mode_names(v) for k, v in loci.items()}
        stage("speed loci")
        plocs = parameter_loci(c, model, s.locus_points)
        glocs = [rootlocus.gain_locus(c, u, model=model, n=s.gain_points) for u in (REFERENCE_SPEED, 1.5)]
        gain_poles = tuple(stabilising_poles(g) for g in glocs)
        stage("parameter and gain loci")
        extra = ([c] + study.friction_variants(c) if not is_ej else []) + [light] + (
            [baseline] if baseline is not None else [])
        thesis, extra_res, other_table = study.thesis_study(
            run, criterion=crit, plan=s.plan, extra_chairs=extra,
            extra_plan_chair=None if is_ej else c, extra_plan=study.plan_for(c, s.plan), progress=progress,
            bracket=s.bracket, tol=s.tol, candidates=s.candidates)
        chair_sweeps: Any
        if is_ej:
            chair_sweeps = thesis.sweeps
            chair_speed = thesis.speeds[REFERENCE_CHAIR]
            chair_friction = [thesis.speeds[f"{REFERENCE_CHAIR} x0.5 friction"],
                              thesis.speeds[f"{REFERENCE_CHAIR} x1.5 friction"]]
        else:
            chair_sweeps = other_table
            chair_speed = extra_res[0]
            chair_friction = list(extra_res[1:3])
        rates = [divergence(x, [REFERENCE_SPEED], model, "free")[0].rate for x in (ref_chair, light)]
        base_speed = extra_res.pop() if baseline is not None else None
        fig814 = Figure814(light, extra_res[-1], *rates,
                           *(float(massless_caster_rate(x, REFERENCE_SPEED)) for x in (ref_chair, light)))
        stage("equal-instability speeds and parametric study")
        subject = preset(COMPARISON_CHAIR) if is_ej else c
        intervals = equal_instability_range(subject, model, s, scheme)
        rated = ([c, ref_chair] if not is_ej else [c, subject]) + ([baseline] if baseline is not None else [])
        impulses = tuple(critical_impulses(rated, REFERENCE_SPEED, run, rel_tol=s.impulse_rel_tol))
        base_impulse = None
        if baseline is not None:
            base_impulse, impulses = impulses[-1], impulses[:-1]
        sensitivity = study.elasticities(c, REFERENCE_SPEED, run, rel_tol=s.impulse_tol)
        stage("intervals, critical impulses and elasticities")
        u_star = chair_speed.speed if chair_speed.status == "found" else REFERENCE_SPEED
        r_speeds = response_speeds(u_star)
        responses = study.yaw_rate_responses(c, r_speeds, run, criterion=crit, progress=False)
        free = c.replace(pin_friction_left=0.0, pin_friction_right=0.0, name=f"{c.name}, no pin friction")
        f_speeds = [round(0.5 * u_star, 2), u_star]
        frictionless = study.yaw_rate_responses(free, f_speeds, run, criterion=crit, progress=False)
        stage("yaw-rate responses")
        path_crit = study.Criterion(duration=min(6.0, s.duration))
        pair = [c, counterpart(c)]
        paths = study.trajectories(pair, REFERENCE_SPEED, run, criterion=path_crit, progress=False)
        valid = dict(
            responses=responses_validity([c] * len(r_speeds), r_speeds, run.replace(horizon=crit.duration)),
            frictionless=responses_validity([free] * 2, f_speeds, run.replace(horizon=crit.duration)),
            paths=responses_validity(pair, [REFERENCE_SPEED] * 2, run.replace(horizon=path_crit.duration)))
        stage("trajectories and validity")
        fmap = study.stability_map(c, s.map_speeds, s.map_frictions, run, criterion=crit,
                                   reference=thesis.reference_time, progress=progress)
        stage("stability map: speed x friction")
        dmap = study.disturbance_map(c, s.map_speeds, s.map_impulses, run, criterion=crit,
                                     reference=thesis.reference_time, progress=progress)
        stage("stability map: speed x disturbance")
        conclusions = study.check_conclusions(thesis, own=None if is_ej else chair_sweeps,
                                              own_friction=() if is_ej else chair_friction)
        stage("conclusions")
        slope = slope_section(c)
        shimmy_note = shimmy_unavailable(c)
        shimmy = None if shimmy_note else shimmy_section(c, s.shimmy_trails, s.shimmy_speeds)
        unc = None if uncertainty is None else uncertainty_section(c, uncertainty, model=model, quick=s.quick,
                                                                   settings=s, scheme=scheme)
        tipping = tip_angles(c)
        limits = tip_limits(c, chair_sweeps)
        window = None
        if shimmy_note is None and "trail" in chair_sweeps:
            window = trail_window(c.name, c.trail, chair_sweeps.get("trail"), shimmy_band(c, USE_SPEEDS))
        stage("slope, shimmy and uncertainty")
        advice = advise(c, progress=progress, driver=driver, intended_speed=intended_speed)
        human = None if driver is None else human_limit(c, driver, model)
        tau = None if driver is None else driver.reaction_time_s    # the reference chair's user limit too
        base = None
        if baseline is not None:
            b_note = shimmy_unavailable(baseline)
            base = Baseline(baseline, baseline_summary(baseline, model), base_speed, base_impulse,
                            slope_section(baseline),
                            None if b_note else shimmy_section(baseline, s.shimmy_trails, s.shimmy_speeds),
                            None if b_note else shimmy_band(baseline, advice.speeds_m_s).shimmy_margin_m)
        ref_m = None if is_ej else measure_chairs([ref_chair], speeds=advice.speeds_m_s,
                                                  cross_slope_deg=advice.cross_slope_deg,
                                                  reaction_time=tau)[0]
        stage("advice")
    return ReportData(c, model, s, summary, summary_other, loci, plocs, glocs, thesis, chair_sweeps, chair_speed,
                      list(chair_friction), responses, frictionless, paths, fmap, dmap, conclusions, scheme,
                      rolling=rolling, tire_force=tire_force, tire_stiffness=tire_stiffness,
                      gain_poles=gain_poles, mode_names=names, validity=valid, intervals=intervals,
                      impulses=impulses, figure_8_14=fig814, sensitivity=sensitivity, slope=slope, shimmy=shimmy,
                      shimmy_note=shimmy_note, uncertainty=unc, baseline=base, tipping=tipping,
                      trail_window=window, tip_limits=limits, advice=advice, reference_measures=ref_m,
                      reference_trail=ref_chair.trail, driver=driver, human=human)

