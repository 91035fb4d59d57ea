"""``python -m stability.report``: a multi-page PDF report on one chair.

Pages: the chair's parameters and a top view; its tires (Figures 4-1, 4-2
analogues); the linear critical-speed table; eigenvalues against speed (root
loci for free and locked casters and both model variants; real and imaginary
parts with unstable regions shaded); root loci against the chapter-8 design
parameters and against a yaw-rate feedback gain; nonlinear yaw-rate
responses and paths with the linear model's prediction overlaid; the
equal-instability speeds of chapter 9; the chapter-8 parametric study; two
stability maps; the thesis's conclusions 1-9 tested against our numbers;
and a page of findings in plain words (every number computed).

The same input gives a byte-identical file; the file appears only when it is
complete.  ``--quick`` builds a coarse version in seconds.

Examples
--------
::

    python -m stability.report --chair ej-premier -o reports/ej-premier.pdf
    python -m stability.report --chair revised --model thesis --quick -o /tmp/revised.pdf
    python -m stability.report --chair my_chair.toml --set trail=0.05 -o chair.pdf
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ._validate import check_model
from .chair import Chair, preset

__all__ = ["Settings", "ReportData", "Page", "ReportResult", "compute", "pages", "build", "findings",
           "figure_texts", "main"]


# ---------------------------------------------------------------------------
# settings
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Settings:
    """Resolution of every computation in the report (``full`` or ``quick``)."""

    quick: bool = False
    speed_points: int = 700
    locus_points: int = 121
    gain_points: int = 300
    duration: float = 10.0
    dt: float = 0.001
    tol: float = 0.005
    candidates: int = 7
    bracket: tuple = (0.2, 3.0)
    plan: dict | None = None           # None: study.DEFAULT_PLAN
    map_speeds: tuple = tuple(np.round(np.linspace(0.3, 2.0, 18), 3))
    map_frictions: tuple = tuple(np.round(np.linspace(0.0, 0.3, 13), 3))
    map_impulses: tuple = tuple(np.round(np.linspace(1.0, 10.0, 10), 3))

    @classmethod
    def for_mode(cls, quick: bool) -> Settings:
        if not quick:
            return cls()
        from .study import QUICK_PLAN

        return cls(quick=True, speed_points=150, locus_points=41, gain_points=80, duration=6.0, dt=0.001,
                   tol=0.05, candidates=9, bracket=(0.3, 2.5), plan=QUICK_PLAN,
                   map_speeds=(0.4, 0.8, 1.2, 1.6, 2.0), map_frictions=(0.0, 0.1, 0.2, 0.3),
                   map_impulses=(2.0, 4.0, 8.0))


# ---------------------------------------------------------------------------
# computation
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class ReportData:
    """Everything the report shows, computed once (see :func:`compute`)."""

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


def counterpart(c: Chair) -> Chair:
    """The same chair with its casters at the other end (s1 and s2 exchanged, as chapter 8's 'Method One')."""
    pos = "front" if c.caster_position == "rear" else "rear"
    return c.replace(name=f"{c.name}, casters swapped", caster_position=pos, s1=c.s2, s2=c.s1)


def _response_speeds(u_star: float) -> list[float]:
    """Five speeds around the equal-instability speed (the thesis: .55 ... .95 around .75)."""
    base = [0.55, 0.65, 0.75, 0.85, 0.95]
    f = u_star / 0.75
    return [round(s * f / 0.05) * 0.05 if f != 1 else s for s in base]


def compute(c: Chair, model: str = "exact", *, quick: bool = False, progress: bool = True,
            scheme: str = "wchair", settings: Settings | None = None,
            log: Callable[[str], None] | None = None) -> ReportData:
    """Run every analysis of the report for chair ``c``."""
    from . import rootlocus, study
    from .linear import analyse
    from .progress import ProgressBar
    from .validation import linearisation_check, with_rolling_resistance

    s = settings or Settings.for_mode(quick)
    other = "thesis" if model == "exact" else "exact"
    sim = dict(dt=s.dt, scheme=scheme)
    crit = study.Criterion(duration=s.duration)
    stages = 9
    with ProgressBar(stages, f"report {c.name}", enabled=progress, unit="stage") as bar:
        def stage(msg):
            if log:
                log(msg)
            bar.update()

        summary = analyse(c, model=model, speeds=(0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0))
        summary_other = analyse(c, model=other, speeds=(0.75,))
        rolling = linearisation_check(with_rolling_resistance(c), 0.75, model=model)
        stage("linear summary")
        loci = {}
        for m in (model, other):
            for cs in ("free", "locked"):
                loci[(m, cs)] = rootlocus.speed_locus(c, model=m, casters=cs, n=s.speed_points)
        stage("speed loci")
        plocs = rootlocus.parameter_loci(c, speed=0.75, model=model, n=s.locus_points)
        glocs = [rootlocus.gain_locus(c, u, model=model, n=s.gain_points) for u in (0.75, 1.5)]
        stage("parameter and gain loci")
        ej = preset("ej-premier")
        is_ej = c == ej
        extra = [c] + study.friction_variants(c) if not is_ej else []
        thesis, extra_res, other_table = study.thesis_study(
            model=model, criterion=crit, plan=s.plan, extra_chairs=extra,
            extra_plan_chair=None if is_ej else c, extra_plan=study.plan_for(c, s.plan), progress=progress,
            bracket=s.bracket, tol=s.tol, candidates=s.candidates, **sim)
        if is_ej:
            chair_sweeps = thesis.sweeps
            chair_speed = thesis.speeds["ej-premier"]
            chair_friction = [thesis.speeds["ej-premier x0.5 friction"], thesis.speeds["ej-premier x1.5 friction"]]
        else:
            chair_sweeps = other_table
            chair_speed = extra_res[0]
            chair_friction = extra_res[1:3]
        stage("equal-instability speeds and parametric study")
        u_star = chair_speed.speed if chair_speed.status == "found" else 0.75
        responses = study.yaw_rate_responses(c, _response_speeds(u_star), model=model, criterion=crit,
                                             progress=False, **sim)
        free = c.replace(pin_friction_left=0.0, pin_friction_right=0.0, name=f"{c.name}, no pin friction")
        frictionless = study.yaw_rate_responses(free, [round(0.5 * u_star, 2), u_star], model=model,
                                                criterion=crit, progress=False, **sim)
        stage("yaw-rate responses")
        paths = study.trajectories([c, counterpart(c)], 0.75, model=model,
                                   criterion=study.Criterion(duration=min(6.0, s.duration)), progress=False, **sim)
        stage("trajectories")
        fmap = study.stability_map(c, s.map_speeds, s.map_frictions, model=model, criterion=crit,
                                   reference=thesis.reference_time, progress=progress, **sim)
        stage("stability map: speed x friction")
        dmap = study.disturbance_map(c, s.map_speeds, s.map_impulses, model=model, criterion=crit,
                                     reference=thesis.reference_time, progress=progress, **sim)
        stage("stability map: speed x disturbance")
        conclusions = study.check_conclusions(thesis)
        stage("conclusions")
    return ReportData(c, model, s, summary, summary_other, loci, plocs, glocs, thesis, chair_sweeps, chair_speed,
                      list(chair_friction), responses, frictionless, paths, fmap, dmap, conclusions, scheme,
                      rolling=rolling)


# ---------------------------------------------------------------------------
# findings (plain words, computed numbers)
# ---------------------------------------------------------------------------
def _first(crossings, direction="destabilising"):
    return next((x.speed for x in crossings if x.direction == direction), None)


def findings(d: ReportData) -> list[str]:
    """The findings page: paragraphs in plain words; every number comes from ``d``."""
    c, m = d.chair, d.model
    s = d.summary
    out = []
    locked = _first(s.locked_crossings)
    r075 = next((r for r in s.divergence if abs(r["speed_m_s"] - 0.75) < 1e-9), None)
    if s.free_unstable_at_all_speeds:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} is directionally unstable at "
               f"every speed searched ({s.search_range[0]:g}-{s.search_range[1]:g} m/s).")
    elif s.free_stable_at_all_speeds:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} is directionally stable at "
               f"every speed searched ({s.search_range[0]:g}-{s.search_range[1]:g} m/s).")
    else:
        txt = (f"Linear model ({m}): with free, frictionless casters {c.name} changes stability at "
               + ", ".join(f"{x.speed:.3g} m/s ({x.direction})" for x in s.free_crossings) + ".")
    if r075 is not None and r075["time_to_double_s"] is not None:
        txt += (f" At 0.75 m/s its least stable mode grows at {r075['rate_1_s']:.3g} 1/s: a heading error "
                f"doubles every {r075['time_to_double_s']:.3g} s.")
    txt += (f" With the casters locked it is stable up to {locked:.3g} m/s." if locked is not None
            else " With the casters locked it is stable in the whole range searched.")
    zw = s.zero_width
    txt += (f" The zero-width model (eq 5-15) puts the locked-caster critical speed at {zw.critical_speed:.3g} m/s."
            if zw.critical_speed is not None else " The zero-width model (eq 5-16) says: understeer, stable with locked casters.")
    out.append(txt)
    so = d.summary_other
    fo = _first(so.free_crossings)
    out.append(f"The other model variant ({so.model}) gives: free casters "
               + ("unstable at every speed searched" if so.free_unstable_at_all_speeds else
                  "stable at every speed searched" if so.free_stable_at_all_speeds else
                  f"first critical speed {fo:.3g} m/s")
               + (f"; locked casters critical speed {_first(so.locked_crossings):.3g} m/s."
                  if _first(so.locked_crossings) is not None else "; locked casters stable in the range."))
    rl = d.rolling
    if rl is not None:
        from .validation import has_rolling_resistance

        own = has_rolling_resistance(c)
        out.append(("This chair's rolling resistance is" if own else
                    "Rolling resistance (off for this chair, as in WCHAIR's defaults) is")
                   + " left out of the linear model. "
                   + ("With it" if own else "With the tire fits' rolling resistance on all four wheels")
                   + f", the simulator's own linearisation puts the least stable mode at {rl.speed:g} m/s at "
                   f"{rl.eigenvalue_simulator.real:.3g} 1/s instead of {rl.eigenvalue_linear.real:.3g} 1/s "
                   f"({100 * rl.rate_difference:+.0f} %): a caster's drag follows its contact velocity, so the "
                   "casters act as an axle of small cornering stiffness (twice the drag, N/rad).")
    th = d.thesis
    out.append(f"Nonlinear simulation ({m} model, {d.scheme} scheme, Coulomb pin friction "
               f"{c.pin_friction_left:g}/{c.pin_friction_right:g} N m): the reference case (E&J Premier at 0.75 m/s, "
               f"{th.impulse[0]:g} N for {th.impulse[1]:g} s at the c.g.) reaches |yaw rate| = "
               f"{th.criterion.yaw_rate:g} rad/s after {th.reference_time:.2f} s (thesis: slightly over 3 s).")
    cs = d.chair_speed
    ref = th.speeds["ej-premier"]
    if c == preset("ej-premier"):
        rev = th.speeds["revised"]
        out.append(f"{c.name} is the reference chair: bisection on speed finds its own equal-instability speed at "
                   f"{cs.describe()} (the reference speed is 0.75 m/s). The chapter-9 revised design reaches the "
                   f"same instability at {rev.describe()} (thesis: 1.10-1.15 m/s), "
                   + (f"{100 * (rev.speed / cs.speed - 1):+.0f} %." if rev.status == cs.status == "found" else "."))
    elif cs.status == "found":
        rel = 100 * (cs.speed / ref.value_or_bound - 1) if ref.status == "found" else float("nan")
        out.append(f"{c.name} shows the same instability at {cs.speed:.3g} m/s"
                   + (f", {rel:+.0f} % against the E&J Premier's {ref.speed:.3g} m/s." if math.isfinite(rel) else ".")
                   + " Above that speed a user has less time to correct a disturbance than in the thesis's "
                     "reference case.")
    elif cs.status == "above":
        out.append(f"{c.name} never reaches the reference instability below {cs.bracket[1]:g} m/s: "
                   "it is more stable than the reference case at every speed tested.")
    else:
        out.append(f"{c.name} is already less stable than the reference case at {cs.bracket[0]:g} m/s.")
    fm = d.friction_map
    j = int(np.argmin(np.abs(fm.y_values - c.pin_friction_left)))
    finite = np.flatnonzero(np.isfinite(fm.times[j]))
    if len(finite) and finite[0] > 0:
        out.append(f"Pin friction holds the casters at low speed: with {fm.y_values[j]:g} N m the simulated chair "
                   f"does not reach {th.criterion.yaw_rate:g} rad/s within {fm.criterion.duration:g} s at "
                   f"{fm.speeds[finite[0] - 1]:g} m/s and below, but does at {fm.speeds[finite[0]]:g} m/s "
                   f"(after {fm.times[j, finite[0]]:.2f} s), although the frictionless linear model is "
                   + ("unstable at every speed." if s.free_unstable_at_all_speeds else "as described above."))
    f_lo, f_hi = d.chair_friction
    out.append(f"Pin friction: at half the friction the equal-instability speed is {f_lo.describe()}, at 1.5 times "
               f"it is {f_hi.describe()} (own friction: {cs.describe()}).")
    ranked = d.chair_sweeps.ranked()
    top = ", ".join(f"{sw.label} ({sw.effect_percent:.0f} %)" for sw in ranked[:4])
    low = ", ".join(f"{sw.label} ({sw.effect_percent:.1f} %)" for sw in ranked[-3:])
    if all(r.status != "found" for sw in ranked for r in sw.results) and cs.status != "found":
        out.append(f"The parametric study cannot rank the parameters for {c.name}: every variant tried stays "
                   f"outside the speed bracket ({cs.bracket[0]:g}-{cs.bracket[1]:g} m/s) of the reference instability.")
    else:
        out.append(f"What matters most (spread of the equal-instability speed over the values tried, in % of the "
                   f"chair's own{'; some values are bounds' if any(sw.censored for sw in ranked) else ''}): {top}. "
                   f"What matters least: {low}.")
    g = d.gain_loci[0]
    if g.stabilising_gain is None:
        out.append(f"Yaw-rate feedback Mz = -K r does not stabilise the linear model at {g.speed:g} m/s "
                   f"for K up to {g.gains[-1]:g} N m s/rad.")
    elif g.stabilising_gain == 0:
        out.append(f"The linear model is stable at {g.speed:g} m/s without feedback.")
    else:
        out.append(f"Yaw-rate feedback Mz = -K r stabilises the linear model at {g.speed:g} m/s for "
                   f"K > {g.stabilising_gain:.3g} N m s/rad; at {d.gain_loci[1].speed:g} m/s for K > "
                   + (f"{d.gain_loci[1].stabilising_gain:.3g} N m s/rad." if d.gain_loci[1].stabilising_gain is not None
                      else "(none in range)."))
    n_agree = sum(1 for x in d.conclusions if x.verdict == "agree")
    n_part = sum(1 for x in d.conclusions if x.verdict == "partly")
    n_dis = sum(1 for x in d.conclusions if x.verdict == "disagree")
    out.append(f"Thesis conclusions 1-9 against our numbers: {n_agree} agree, {n_part} partly, {n_dis} disagree "
               "(details on the previous page).")
    return out


# ---------------------------------------------------------------------------
# pages
# ---------------------------------------------------------------------------
@dataclass
class Page:
    """One page: its title, the figure (until written) and all its text (for tests and the text dump)."""

    title: str
    texts: list = field(default_factory=list)


@dataclass
class ReportResult:
    path: Path | None
    pages: list
    data: ReportData
    seconds: float = 0.0

    def text(self) -> str:
        """All page texts, page by page."""
        out = []
        for i, p in enumerate(self.pages, start=1):
            out.append(f"=== page {i}: {p.title}")
            out.extend(t for t in p.texts)
        return "\n".join(out)


def figure_texts(fig) -> list[str]:
    """Every non-empty text string drawn on a figure (titles, labels, tick labels, legends, annotations)."""
    from matplotlib.text import Text

    fig.canvas.draw() if hasattr(fig.canvas, "draw") and fig.canvas is not None else None
    out = []
    for t in fig.findobj(Text):
        s = t.get_text()
        if s and t.get_visible():
            out.append(s)
    return out


def _subtitle(d: ReportData) -> str:
    c = d.chair
    return (f"{c.caster_position} casters; s1 = {c.s1:g} m, s2 = {c.s2:g} m, trail = {c.trail:g} m, m = {c.m:g} kg, "
            f"pin friction {c.pin_friction_left:g}/{c.pin_friction_right:g} N m, main tire {c.main_tire}, "
            f"caster tire {c.caster_tire}" + ("   [QUICK: coarse resolution]" if d.settings.quick else ""))


def _title(d: ReportData, what: str) -> str:
    return f"{d.chair.name} | {d.model} model | {what}"


def page_builders(d: ReportData) -> list[tuple[str, Callable[[], Any]]]:
    """``(title, build)`` for every page, in order; ``build()`` returns a Figure."""
    from . import plotting as P
    from .critical_speed import format_summary
    from .statics import static_loads
    from .study import THESIS

    sub = _subtitle(d)
    c = d.chair
    st = d.settings

    def p_chair():
        fig, axes = P.page(_title(d, "chair parameters and geometry"), sub, nrows=1, ncols=2,
                           gridspec_kw={"width_ratios": [1.35, 1]})
        P.parameter_table(c, axes[0, 0])
        P.chair_geometry(c, axes[0, 1])
        return P.finish(fig)

    def p_tires():
        loads = static_loads(c)
        fig, axes = P.page(_title(d, "tires (Figures 4-1 and 4-2 analogues)"), sub, nrows=1, ncols=3)
        P.tire_curves(c.main_tire, axes[0, 0], mark_load=loads["main"], role="main wheels")
        P.tire_curves(c.caster_tire, axes[0, 1], mark_load=loads["caster"], role="casters")
        P.cornering_stiffness_curves(axes[0, 2], highlight={"main": (c.main_tire, loads["main"]),
                                                            "caster": (c.caster_tire, loads["caster"])})
        return P.finish(fig)

    def p_summary():
        txt = format_summary(d.summary)
        so = d.summary_other
        txt += ("\n\nOther model variant (" + so.model + "): free casters "
                + ("unstable at all speeds searched" if so.free_unstable_at_all_speeds else
                   "stable at all speeds searched" if so.free_stable_at_all_speeds else
                   "critical speeds " + ", ".join(f"{x.speed:.4g} m/s ({x.direction})" for x in so.free_crossings))
                + "; locked casters critical speed "
                + (f"{_first(so.locked_crossings):.4g} m/s" if _first(so.locked_crossings) is not None else "none in range")
                + ".\n\nLinear models: straight-line motion, tire forces linear in slip with the cornering stiffness "
                  "at the static load (Table 4-1 method), viscous pin damping "
                  f"{c.pin_damping:g} N m s/rad; Coulomb pin friction has no linearisation (it appears only in the "
                  "nonlinear simulations of the later pages).")
        return P.text_page(_title(d, "linear stability: critical speeds"), txt, sub, monospace=True, width=125,
                           fontsize=9)

    def p_speed_loci():
        order = [(d.model, "free"), (d.model, "locked"),
                 ("thesis" if d.model == "exact" else "exact", "free"),
                 ("thesis" if d.model == "exact" else "exact", "locked")]
        return P.speed_loci_figure([d.speed_loci[k] for k in order],
                                   _title(d, "eigenvalues as speed varies (parametric root locus)"), sub)

    def p_re_im():
        fig, axes = P.page(_title(d, "eigenvalues against speed (shaded: unstable)"), sub, nrows=2, ncols=2)
        for j, cs in enumerate(("free", "locked")):
            P.eigenvalues_vs_speed(d.speed_loci[(d.model, cs)], [axes[0, j], axes[1, j]])
        return P.finish(fig)

    def p_ploci(part):
        loci = d.parameter_loci[:4] if part == 1 else d.parameter_loci[4:]
        return P.parameter_loci_figure(loci, _title(d, f"root loci against design parameters at 0.75 m/s ({part}/2)"),
                                       sub + "  |  free casters; black squares: this chair; x: first value")

    def p_growth():
        return P.growth_rate_vs_parameter(d.parameter_loci, _title(d, "growth rate of the least stable mode "
                                          "against design parameters, 0.75 m/s"), sub)

    def p_gain():
        fig, axes = P.page(_title(d, "root locus against a yaw-rate feedback gain (control.root_locus_map)"), sub,
                           nrows=1, ncols=2)
        for ax, g in zip(axes[0], d.gain_loci):
            P.gain_locus(g, ax, title=f"{c.name}: Mz = -K r, {g.model} model, {g.casters} casters, U = {g.speed:g} m/s")
        return P.finish(fig)

    def p_responses():
        fig, axes = P.page(_title(d, "nonlinear yaw-rate responses (Figure 8-3a analogue), linear overlay"), sub,
                           nrows=1, ncols=2)
        P.yaw_rate_responses(d.responses, axes[0, 0], reference_time=d.thesis.reference_time,
                             title=f"{c.name}: pin friction {c.pin_friction_left:g} N m ({d.model} model, "
                                   f"{d.scheme} scheme); dashed: linear, frictionless")
        P.yaw_rate_responses(d.responses_frictionless, axes[0, 1], reference_time=d.thesis.reference_time,
                             title=f"{c.name} without pin friction: where the linear model applies")
        fig.text(0.5, 0.015, d.responses.linear_note, ha="center", fontsize=7.5, color="0.3")
        return P.finish(fig)

    def p_paths():
        fig, axes = P.page(_title(d, "paths after the disturbance (Figure 8-4 analogue)"), sub, nrows=1, ncols=2)
        P.trajectories(d.paths, axes[0, 0])
        P.yaw_rate_responses(d.paths, axes[0, 1], label_chair=True, ylim=(-1.0, 1.5),
                             title=f"yaw rates of the same runs, 0.75 m/s ({d.model} model); dashed: linear")
        return P.finish(fig)

    def p_equal():
        th = d.thesis
        res = [th.speeds["ej-premier"], th.speeds["ej-premier x0.5 friction"], th.speeds["ej-premier x1.5 friction"],
               th.speeds["revised"], th.speeds["revised x0.5 friction"], th.speeds["revised x1.5 friction"],
               th.speeds["ej-premier-front-caster"]]
        if c != preset("ej-premier"):
            res = [d.chair_speed] + list(d.chair_friction) + res
        seen, uniq = set(), []
        for r in res:                      # a preset chair appears once
            if r.chair.name not in seen:
                seen.add(r.chair.name)
                uniq.append(r)
        res = uniq
        thesis_ranges = {"ej-premier": (0.75, 0.75), "revised": (1.10, 1.15), "revised x0.5 friction": (0.63, 0.67),
                         "revised x1.5 friction": (1.63, 1.67)}
        fig, axes = P.page(_title(d, "equal-instability speeds (chapter 9, Figures 9-2 and 9-3)"), sub, nrows=1,
                           ncols=2, gridspec_kw={"width_ratios": [1.5, 1]})
        P.equal_instability_chart(res, axes[0, 0], thesis=thesis_ranges)
        ax = axes[0, 1]
        ax.axis("off")
        crit = th.criterion
        txt = [
            "Criterion: " + crit.describe() + ".",
            f"Reference: E&J Premier at 0.75 m/s, {th.impulse[0]:g} N for {th.impulse[1]:g} s at the c.g.: "
            f"{th.reference_time:.3f} s (thesis: {THESIS['reference_time_to_1_rad_s']}).",
            "Equal-instability speed: the speed at which the chair takes exactly as long; found by bisection on "
            f"speed ({st.candidates} candidate speeds per round, one batch of simulations per round, to "
            f"{st.tol:g} m/s, bracket {st.bracket[0]:g}-{st.bracket[1]:g} m/s).",
            "Why: the thesis itself quotes this number for its reference case; for exponentially growing "
            "responses matching the time to a level matches the curve's position, which is how the thesis "
            "compares curves by eye (Figures 9-2, 9-3); it is monotone in speed.",
            "Thesis: revised " + THESIS["revised"] + "; half friction " + THESIS["revised_half_friction"]
            + "; 1.5x friction " + THESIS["revised_1.5x_friction"] + ".",
            "Grey hatched bars: outside the bracket (value is a bound).",
        ]
        y = 0.98
        for para in txt:
            for line in P._wrap(para, 56):
                ax.text(0.0, y, line, fontsize=8, va="top", transform=ax.transAxes)
                y -= 0.033
            y -= 0.02
        return P.finish(fig, left=0.22)

    def p_sweeps():
        table = d.chair_sweeps
        n = len(table.sweeps)
        ncols = 4
        nrows = int(math.ceil(n / ncols))
        fig, axes = P.page(_title(d, "parametric study: equal-instability speed per chapter-8 parameter"),
                           sub, nrows=nrows, ncols=ncols)
        P.sweep_chart(table, axes)
        fig.text(0.5, 0.012, "Dashed line: this chair's equal-instability speed; dotted line: its value of the "
                 "parameter; other parameters at the chair's values. Same speed scale in every panel.",
                 ha="center", fontsize=8, color="0.3")
        return P.finish(fig, bottom=0.09)

    def p_sweep_table():
        table = d.chair_sweeps
        rows = []
        for i, s in enumerate(table.ranked(), start=1):
            rows.append([str(i), s.label + ("" if s.unit == "-" else f" ({s.unit})"),
                         ", ".join(s.value_text(k) for k in range(len(s.values))),
                         ", ".join(r.describe(unit=False) for r in s.results),
                         f"{s.effect_percent:.1f}" + (" (bound)" if s.censored else ""), s.how])
        return P.table_page(_title(d, "which parameters matter, by how much"),
                            ["rank", "parameter", "values tried", "equal-instability speed (m/s)", "spread (%)",
                             "how varied"], rows, sub,
                            col_widths=[0.04, 0.17, 0.17, 0.27, 0.08, 0.27], wrap=[4, 26, 26, 44, 12, 42],
                            notes=(f"This chair: {table.nominal.describe()} (reference {d.thesis.reference_time:.2f} s "
                                   f"to {d.thesis.criterion.yaw_rate:g} rad/s). Spread: (max - min) / this chair's "
                                   "speed over the values tried. '(bound)': some speed lies outside the bracket, so "
                                   "the spread is a lower bound."))

    def p_maps():
        fig, axes = P.page(_title(d, "stability maps: time to |yaw rate| = 1 rad/s"), sub, nrows=1, ncols=2)
        P.stability_map(d.friction_map, axes[0, 0], nominal=c.pin_friction_left)
        P.stability_map(d.disturbance_map, axes[0, 1], nominal=d.thesis.impulse[0] * d.thesis.impulse[1])
        fig.text(0.5, 0.012, "Heavy line: the reference case's time. Slower than the line (left): more time to react than "
                 "in the reference case; faster (right): less.\nEach map is one simulate_batch call (the right one with "
                 "an impulse force per run). Dots: simulated grid points.",
                 ha="center", fontsize=8, color="0.3")
        return P.finish(fig, bottom=0.12)

    def p_conclusions():
        rows = [[str(x.number), x.statement, x.verdict.upper(), x.evidence] for x in d.conclusions]
        return P.table_page(_title(d, "the thesis's conclusions 1-9 against our numbers (E&J Premier, revised)"),
                            ["#", "conclusion (chapter 9)", "verdict", "our evidence"], rows, sub,
                            col_widths=[0.03, 0.25, 0.08, 0.64], wrap=[3, 40, 10, 100], fontsize=8,
                            notes=f"Nonlinear runs: {d.thesis.model} model, {d.scheme} scheme; "
                                  f"{d.thesis.criterion.describe()}.")

    def p_findings():
        return P.text_page(_title(d, "findings"), "\n\n".join(findings(d)), sub, fontsize=10.5, width=140)

    return [
        ("chair parameters and geometry", p_chair),
        ("tires", p_tires),
        ("linear stability: critical speeds", p_summary),
        ("eigenvalues as speed varies", p_speed_loci),
        ("eigenvalues against speed", p_re_im),
        ("root loci against design parameters 1", lambda: p_ploci(1)),
        ("root loci against design parameters 2", lambda: p_ploci(2)),
        ("growth rate against design parameters", p_growth),
        ("yaw-rate feedback root locus", p_gain),
        ("nonlinear yaw-rate responses", p_responses),
        ("paths", p_paths),
        ("equal-instability speeds", p_equal),
        ("parametric study", p_sweeps),
        ("parametric study table", p_sweep_table),
        ("stability maps", p_maps),
        ("thesis conclusions", p_conclusions),
        ("findings", p_findings),
    ]


def pages(d: ReportData, record: list | None = None) -> Iterator:
    """Build the figures one at a time; append a :class:`Page` (title, texts) to ``record`` for each."""
    for title, build_fig in page_builders(d):
        fig = build_fig()
        if record is not None:
            record.append(Page(title, figure_texts(fig)))
        yield fig


def build(c: Chair, path, *, model: str = "exact", quick: bool = False, progress: bool = True,
          settings: Settings | None = None, data: ReportData | None = None) -> ReportResult:
    """Compute and write the report for chair ``c`` to ``path`` (atomically, reproducibly)."""
    from .output import write_pdf
    from .progress import ProgressBar

    t0 = time.perf_counter()
    check_model(model)
    path = Path(path)
    directory = path.parent if str(path.parent) else Path(".")
    if not directory.is_dir():
        raise ValueError(f"output directory {str(directory)!r} does not exist")
    d = data or compute(c, model, quick=quick, progress=progress, settings=settings)
    record: list[Page] = []
    builders = page_builders(d)
    with ProgressBar(len(builders), "pages", enabled=progress, unit="page") as bar:
        write_pdf(pages(d, record), path, title=f"stability report: {c.name} ({model} model)",
                  on_page=lambda i: bar.update())
    return ReportResult(path, record, d, time.perf_counter() - t0)


# ---------------------------------------------------------------------------
# command line
# ---------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    from .cli import OneLineErrorParser, add_chair_options

    p = OneLineErrorParser(prog="python -m stability.report", description=__doc__.split("\n\n")[0])
    add_chair_options(p)
    p.add_argument("--model", default="exact", choices=["exact", "thesis"],
                   help="equation variant for the linear analysis and the simulations (default exact)")
    p.add_argument("--quick", action="store_true", help="coarse version in seconds")
    p.add_argument("--no-progress", action="store_true", help="no progress bars")
    p.add_argument("--text", metavar="FILE", help="also write the text of every page to FILE")
    p.add_argument("-o", "--output", required=True, metavar="FILE.pdf", help="output PDF")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``python -m stability.report``; returns the exit status (2 on bad input)."""
    from .cli import run

    return run(build_parser(), argv, _run, errors=(ValueError, OSError))


def _run(args: argparse.Namespace) -> int:
    from .cli import load_chair
    from .output import atomic_write_text

    c = load_chair(args.chair, args.set)
    if not args.output.lower().endswith(".pdf"):
        raise ValueError(f"output {args.output!r} must end in .pdf")
    res = build(c, args.output, model=args.model, quick=args.quick, progress=not args.no_progress)
    if args.text:
        atomic_write_text(args.text, res.text() + "\n")
    print(f"wrote {res.path} ({len(res.pages)} pages, {res.seconds:.1f} s)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
