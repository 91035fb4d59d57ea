"""The report on a wheel layout: what every layout command answers, forward and in reverse, in one PDF.

The short form's report (:mod:`stability.report.document`) is built on a :class:`stability.chair.Chair`'s fields;
a layout (a layout preset or a ``[[wheel]]`` file) gets this report instead, from the same computations the layout
commands print: the advisor's decision (:mod:`stability.advise`, forward driving, as page 1 of the short form's),
the wheels and their static loads, the linear model's growth rates and critical speeds both ways
(:mod:`stability.layout.text`), the ISO 7176-1 tip angles, the critical impulse at the reference speed forwards
and backwards, the equal-instability speed both ways, each caster row's shimmy margin, and the virtual bench.  The
short form's sections that cannot apply to a layout say so in one line each (:data:`NOT_APPLICABLE`).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from typing import Any

from matplotlib.figure import Figure

from stability import plotting as P
from stability.advise.advisor import advise
from stability.advise.decision import decide
from stability.advise.layout_measures import layout_shimmy_rows
from stability.bench import run_bench
from stability.bench.loads import SCORE_WORDS
from stability.compare.compute import Comparison
from stability.layout.linear import analyse_layout
from stability.layout.model import Layout
from stability.layout.text import layout_text
from stability.report.clinician_sheet import ClinicianSheet
from stability.runtime.files import write_pdf
from stability.settings import defaults as D
from stability.settings.reference import REFERENCE_SPEED
from stability.study.layout_equal_instability import layout_equal_instability_interval
from stability.study.layout_impulse import layout_critical_impulses, slow_divergences

__all__ = ["LayoutReport", "NOT_APPLICABLE", "NO_BENCH", "WHEELS_TITLE", "COMPARE_SPEEDS", "compute_layout_report",
           "layout_report_pages", "write_layout_report", "comparison_caption"]

#: Signed speeds of a comparison's growth-rate rows, m/s: the use range forwards and the reference speed backwards.
COMPARE_SPEEDS = (0.5, REFERENCE_SPEED, 1.0, 1.5, -REFERENCE_SPEED)
#: The page titles of the optional pages.
SHEET_TITLE, COMPARE_TITLE, CURVES_TITLE, NA_TITLE = ("For the clinician", "Compared with the baseline",
                                                      "Growth rates against speed, both chairs",
                                                      "Appendix: not applicable to a wheel layout")
UNCERTAINTY_TITLE = "Parameter uncertainty: the linear results' intervals"
#: The appendix's pages (after every result): the layout's wheels and linear model, then what does not apply.
WHEELS_TITLE = "Appendix: wheels, static loads, tip angles and the linear model"
#: The bench's line when the layout has no driven wheel (the bench drives the wheels: nothing to test).
NO_BENCH = ("The virtual ISO 7176-2/-3 bench", "the layout has no driven wheel, so there is no drive to test "
            "(the bench accelerates, brakes and turns on its driven wheels).")

#: The short form's report sections that do not apply to a layout, each with why, in one line.
NOT_APPLICABLE = (
    ("Cross slopes and grades", "not in this report yet: python -m stability.slope --chair NAME answers a layout "
     "(the held line, the holding moment and the uncorrected turn; docs/layouts.md)."),
    ("Design parameters and root loci (thesis chapter 8)", "the chapter's parameters (s1, s2, trail, ...) are the "
     "short form's fields; a layout's levers are the advisor's (caster trail per row, drive-axle position, "
     "suspension), whose effects the decision lists."),
    ("Thesis model against the exact model", "a layout's equations are the exact model's only."),
    ("Parameter uncertainty (nonlinear measures)", "--uncertainty FILE (tables naming the layout's axes: m, i_z, "
     "h, caster_K_FIELD, wheel_J_FIELD, trail_ROW, drive_x) propagates the linear growth rates and the static "
     "stability; the critical impulse and the equal-instability speed are a simulator search per draw and are not "
     "propagated."),
    ("Tire data", "each wheel's tire is named in the layout; the treadmill tables are the short form's report's "
     "(python -m stability.critical_speed --chair NAME prints every contact's static load)."),
    ("The driver", "--reaction-time S (or the file's [user]) adds the speed up to which that driver holds the "
     "layout, forwards and backwards (the divergence rule and the delayed loop on the layout's linear model); the "
     "nonlinear lane limit is the short form's only (docs/driver.md)."),
)


@dataclass(frozen=True)
class LayoutReport:
    """The report on one layout.

    Attributes
    ----------
    layout : Layout
    sections : tuple of (str, tuple of str)
        Title and paragraphs of each section, in page order.
    not_applicable : tuple of (str, str)
        :data:`NOT_APPLICABLE` (empty in a quick report).
    data : dict
        The numbers (JSON-ready): growth rates, critical speeds, tip angles, critical impulses, equal-instability
        speeds, shimmy margins, bench score, decision, and with the options the clinician sheet and the
        comparison.
    sheet : ClinicianSheet or None
        The clinician sheet (``--quick``).
    comparison : Comparison or None
        The comparison with the baseline (``--compare``).
    uncertainty : stability.report.layout_uncertainty.LayoutUncertainty or None
        The propagated intervals (``--uncertainty``).
    appendix : tuple of (str, tuple of str)
        Title and paragraphs of each appendix page (after every result, before :data:`NOT_APPLICABLE`'s page).
    intended_speed_m_s : float or None
        The advisor's intended speed with a driver (the option's, else the fastest use speed), m/s.
    """

    layout: Layout
    sections: tuple
    not_applicable: tuple
    data: dict
    sheet: ClinicianSheet | None = None
    comparison: Comparison | None = None
    uncertainty: Any = None
    appendix: tuple = ()
    intended_speed_m_s: float | None = None

    def page_texts(self) -> list[tuple[str, list[str]]]:
        """Each page's title and text lines, in page order (what :func:`layout_report_pages` draws)."""
        out = [(t, list(lines)) for t, lines in self.sections]
        if self.sheet is not None:
            from stability.report.clinician_sheet import sheet_lines

            d = sheet_lines(self.sheet)
            out.append((SHEET_TITLE, [" | ".join(d["bump_header"])] + [" | ".join(r) for r in d["bump_rows"]]
                        + d["paragraphs"]))
        if self.comparison is not None:
            from stability.compare.text import format_comparison

            out.append((COMPARE_TITLE, format_comparison(self.comparison).split("\n")))
            out.append((CURVES_TITLE, [comparison_caption(self.comparison)]))
        if self.uncertainty is not None:
            out.append((UNCERTAINTY_TITLE, self.uncertainty.lines()))
        out += [(t, list(lines)) for t, lines in self.appendix]
        if self.not_applicable:
            out.append((NA_TITLE, [f"{t}: {w}" for t, w in self.not_applicable]))
        return out

    def text(self) -> str:
        """Every page's text, page by page."""
        out = []
        for i, (title, lines) in enumerate(self.page_texts()):
            out += [f"=== page {i + 1}: {title}", *lines]
        return "\n".join(out)


def _up_to(x: float) -> str:
    """A :func:`stability.compare.layouts.stable_up_to` speed in words."""
    if math.isinf(x):
        return "20 m/s and beyond"
    return "none: unstable from low speed" if x == 0 else f"{x:.3g} m/s"


def comparison_caption(c: Comparison) -> str:
    """The growth-rate figure's caption, from the comparison's own numbers: which chair's heading error grows
    more slowly at the reference speed forwards and backwards, and up to which speed each is stable.

    Parameters
    ----------
    c : Comparison
        Of two layouts (:func:`stability.compare.layouts.compare_layouts`).

    Returns
    -------
    str
    """
    q = {x.key: x for x in c.quantities}
    parts = []
    for v in (REFERENCE_SPEED, -REFERENCE_SPEED):
        g = q.get(f"growth_rate_1_s@{v:g}")
        if g is None:
            continue
        way = "backwards" if v < 0 else "forwards"
        lo = min(range(len(c.labels)), key=lambda i: g.values[i])
        words = ", ".join(f"{lab} {x:+.3g} 1/s" for lab, x in zip(c.labels, g.values, strict=True))
        parts.append(f"at {abs(v):g} m/s {way} {c.labels[lo]}'s heading error grows more slowly ({words}; below 0: "
                     "it dies out)")
    for way in ("forward", "reverse"):
        s = q[f"stable_up_to_{way}_m_s"]
        parts.append(f"stable {way} up to " + ", ".join(
            f"{lab} " + _up_to(x) for lab, x in zip(c.labels, s.values, strict=True)))
    return ("Linear model, free frictionless casters: " + "; ".join(parts)
            + (". The figure draws both directions (negative speeds: in reverse)." if min(c.curve_speeds) < 0
               else ". The figure draws the forward speeds; the table on the page before has the reverse ones."))


def _impulses(layout: Layout) -> tuple[list[str], list[dict]]:
    pts = layout_critical_impulses(layout, [REFERENCE_SPEED, -REFERENCE_SPEED])
    lines = [f"The smallest sideways push at the c.g. (a constant force for 0.1 s, as its impulse) after which the "
             f"yaw rate reaches 1 rad/s within 10 s, every caster starting trailing the direction of travel; push "
             f"{pts[0].push}:"]
    for p in pts:
        way = "backwards" if p.speed < 0 else "forwards"
        kick = f"{p.kick_m_s:.3g} m/s" if p.kick_m_s is not None else "-"
        lines.append(f"  {abs(p.speed):g} m/s {way}: {p.describe()} (sideways kick {kick})")
    slow = {d.speed: d for d in slow_divergences(layout, pts)}
    lines += [f"  Note, {d.text()}" for d in slow.values()]
    return lines, [{**p.to_dict(), "slow_divergence": slow[p.speed].to_dict() if p.speed in slow else None}
                   for p in pts]


def _equal(layout: Layout) -> tuple[list[str], list[dict]]:
    lines = ["The speed at which this layout, after the thesis's push, reaches 1 rad/s as soon as the reference "
             "chair (E&J Premier) does at 0.75 m/s forwards; in reverse, driving backwards against the same "
             "reference:"]
    data = []
    for reverse in (False, True):
        r = layout_equal_instability_interval(layout, reverse=reverse).signed(reverse)
        lines.append(f"  {'backwards' if reverse else 'forwards'}: {r.describe()}")
        data.append({"direction": "reverse" if reverse else "forward", **r.to_dict()})
    return lines, data


def _shimmy(layout: Layout, speeds: tuple) -> tuple[list[str], list[dict]]:
    """Each caster row's shimmy margin forwards and in reverse: the reverse rows are their own computation
    (:func:`stability.advise.layout_measures.layout_shimmy_rows` at the negated speeds: every caster swung round,
    trailing the other way, at the reversed statics' load), which differs from forwards wherever the rows carry
    different loads backwards."""
    sizes = tuple(abs(float(u)) for u in speeds)
    both = [(way, layout_shimmy_rows(layout, tuple(sign * u for u in sizes)))
            for way, sign in (("forward", 1.0), ("reverse", -1.0))]
    if not both[0][1]:
        return ["The layout has no casters."], []
    at = ", ".join(f"{u:g}" for u in sizes)
    lines = [f"Each caster row as a towed wheel on its pin at its own static load, at {at} m/s; in reverse each "
             "caster has swung round and trails the other way, its load from the statics of the casters trailing "
             "backwards (python -m stability.shimmy --chair NAME --speeds -U):"]
    data = []
    for way, rows in both:
        lines.append(f"  {'Forwards' if way == 'forward' else 'Backwards'}:")
        for name, trail, band in rows:
            lo, hi = band.shimmy_margin_interval_m
            lines.append(f"    {name} casters, trail {trail * 100:g} cm: margin {band.shimmy_margin_m * 100:+.2f} cm "
                         f"to the nearest shimmy boundary (over the estimate ranges {lo * 100:+.2f} to "
                         f"{hi * 100:+.2f} cm"
                         + ("; it straddles a boundary: measure pin stiffness and relaxation length" if band.straddles
                            else "") + ")")
            data.append({"row": name, "direction": way, "trail_m": trail, "shimmy_margin_m": band.shimmy_margin_m,
                         "interval_m": [lo if math.isfinite(lo) else None, hi if math.isfinite(hi) else None],
                         "straddles": band.straddles})
    return lines, data


def _driver(layout: Layout, driver: Any) -> tuple[tuple[str, ...], dict]:
    """The speed up to which the driver holds the layout, forwards and backwards: the short form's two limits on the
    layout's linear model (:func:`stability.driver.layout.layout_human_limit`: the divergence rule and the best
    delayed PD heading loop), the lower of them the driver's."""
    from stability.driver.layout import layout_human_limit

    tau = float(driver.reaction_time_s)
    lines = [f"A driver with an effective delay of {tau:g} s (from {driver.source}): the speed up to which they hold "
             "the layout, the lower of the divergence rule (its largest growth rate reaches 1/delay) and the delayed "
             "loop (the best delayed PD heading loop stops being stable), on the layout's linear model with free "
             "frictionless casters:"]
    rows = []

    def at(u: float, side: str) -> str:
        return ("" if side == "=" else f"{side} ") + f"{u:.3g} m/s"

    for reverse in (False, True):
        h = layout_human_limit(layout, driver, reverse)
        way = "backwards" if reverse else "forwards"
        lines.append(f"  {way}: {at(h.speed_m_s, h.side)}, limited by the {h.limited_by} (divergence rule "
                     f"{at(h.rule_speed_m_s, h.rule_side)}, delayed loop {at(h.loop_speed_m_s, h.loop_side)})")
        rows.append({"direction": "reverse" if reverse else "forward", "rule_speed_m_s": float(h.rule_speed_m_s),
                     "side": h.rule_side, "delayed_loop_speed_m_s": float(h.loop_speed_m_s),
                     "delayed_loop_side": h.loop_side, "speed_m_s": float(h.speed_m_s), "limited_by": h.limited_by,
                     "pade_error_m_s": float(h.pade_error_m_s)})
    lines.append("It leaves out pin friction (python -m stability.critical_speed --chair "
                 f"{layout.name} --reaction-time {tau:g} gives both limits with their Pade check; the lane limit is "
                 "the short form's).")
    return tuple(lines), {"reaction_time_s": tau, "source": driver.source, "limits": rows}


def compute_layout_report(layout: Layout, *, speeds: tuple = (0.5, 0.75, 1.0), progress: bool = False,
                          nonlinear: Callable | None = None, quick: bool = False,
                          baseline: Layout | None = None, uncertainty: Any = None, samples: int = D.SAMPLES,
                          seed: int = D.SEED, driver: Any = None, intended_speed: float | None = None) -> LayoutReport:
    """Every section of the layout's report.

    Parameters
    ----------
    layout : Layout
    speeds : tuple of float
        Use speeds of the advisor, the shimmy margins and the clinician sheet, m/s (forwards).
    progress : bool
    nonlinear : callable, optional
        Replaces the advisor's simulated measures (:func:`stability.advise.advise`'s ``nonlinear``; tests).
    quick : bool
        The quick report: the decision and the clinician sheet only.
    baseline : Layout, optional
        Compare with this layout (a short-form chair as :meth:`Layout.from_chair`).
    uncertainty : stability.uncertainty.Uncertainty, optional
        Distributions of the layout's axes (:func:`stability.advise.layout_axes.load_layout_uncertainty`).
    samples, seed : int
        Monte Carlo draws and their seed with ``uncertainty``.
    driver : stability.driver.Driver, optional
        The user (``--reaction-time`` or the file's ``[user]``): the advisor's decision weighs the speed this driver
        holds (:func:`stability.advise.advise`'s ``driver``) and a section gives that speed both ways.
    intended_speed : float, optional
        With ``driver``: the speed the user wants to drive at, m/s (the advisor's ``intended_speed``).

    Returns
    -------
    LayoutReport
    """
    if quick and (baseline is not None or uncertainty is not None):
        raise ValueError("baseline, uncertainty: the quick report is the decision and the clinician sheet; drop quick "
                         "to compare or to propagate an uncertainty")
    a = advise(layout, speeds=speeds, progress=progress, nonlinear=nonlinear, driver=driver,
               intended_speed=intended_speed)
    d = decide(a)
    decision = ("The decision (forward driving)", tuple(d.paragraphs()) + (
        f"For the advice on reversing: python -m stability.advise --chair {layout.name} --speeds -0.5:1.",))
    if quick:
        from stability.report.layout_clinician import layout_clinician_sheet

        sheet = layout_clinician_sheet(layout, tuple(a.speeds_m_s), driver)
        data = {"layout": layout.name, "quick": True, "decision": d.to_mapping(), "clinician": _sheet_data(sheet)}
        return LayoutReport(layout, (decision,), (), data, sheet=sheet, intended_speed_m_s=a.intended_speed_m_s)
    summary = analyse_layout(layout)
    text = layout_text(layout, summary).split("\n")
    imp_lines, imp = _impulses(layout)
    eq_lines, eq = _equal(layout)
    sh_lines, sh = _shimmy(layout, speeds)
    sections: list[tuple[str, tuple]] = [
        decision,
        ("After a push: the critical impulse, forwards and backwards", tuple(imp_lines)),
        ("The equal-instability speed, forwards and backwards", tuple(eq_lines)),
        ("Caster shimmy, row by row", tuple(sh_lines)),
    ]
    bench = None
    if any(w.driven for w in layout.wheels):
        b = run_bench(layout)
        bench = {"worst_score": b.worst_score}
        sections.append(("The virtual ISO 7176-2/-3 bench", (
            f"Worst wheel-lift score {b.worst_score}: {SCORE_WORDS[b.worst_score]} (default drive settings, "
            "quasi-static; python -m stability.bench gives every case).",)))
    not_applicable = NOT_APPLICABLE if bench is not None else (*NOT_APPLICABLE, NO_BENCH)
    drv = None
    if driver is not None:
        drv_lines, drv = _driver(layout, driver)
        sections.append(("The driver: the speed this user holds, forwards and backwards", drv_lines))
    data = {"layout": layout.name, "growth_rates": summary.to_mapping(), "critical_impulse": imp,
            "equal_instability": eq, "shimmy_rows": sh, "bench": bench, "decision": d.to_mapping(),
            "driver": drv, "not_applicable": [{"section": t, "why": w} for t, w in not_applicable]}
    comparison = None
    if baseline is not None:
        from stability.compare.compute import unique_labels
        from stability.compare.layouts import compare_layouts
        from stability.compare.text import comparison_dict

        comparison = compare_layouts([layout, baseline], labels=unique_labels([layout.name, baseline.name]),
                                     speeds=COMPARE_SPEEDS, nonlinear=True)
        cd = comparison_dict(comparison, {})
        data["comparison"] = {k: cd[k] for k in ("chairs", "reference", "speeds_m_s", "measures", "verdicts", "push")
                              if k in cd}
    unc = None
    if uncertainty is not None:
        from stability.report.layout_uncertainty import layout_uncertainty

        unc = layout_uncertainty(layout, uncertainty, COMPARE_SPEEDS, samples=samples, seed=seed)
        data["uncertainty"] = unc.to_mapping()
    return LayoutReport(layout, tuple(sections), not_applicable, data, comparison=comparison, uncertainty=unc,
                        appendix=((WHEELS_TITLE, tuple(text)),), intended_speed_m_s=a.intended_speed_m_s)


def _sheet_data(s: ClinicianSheet) -> dict:
    """The clinician sheet's numbers (JSON-ready, unit last)."""
    def fin(x: float) -> float | None:
        return x if math.isfinite(x) else None

    rows = [{"speed_m_s": m.speed, "after_the_bump": m.kind, "time_to_level_s": fin(m.time_to_level),
             "doubling_time_s": dbl, "final_yaw_rate_rad_s": m.final_rate, "sideways_m": m.sideways,
             "travel_m": m.travel, "valid_until_s": m.until}
            for m, dbl in zip(s.motions, s.doubling, strict=True)]
    e = s.effort
    effort = None if e is None else {"drive": e.drive, ("handrim_force_difference_N" if e.drive == "handrim" else
                                                        "motor_torque_difference_N_m"): e.difference,
                                     "harder_side": e.harder_side, "speed_m_s": e.speed_m_s, "uncorrected_turn": e.turn}
    from stability.report.clinician import CLINIC_SLOPE_DEG

    return {"bump": rows, "cross_slope_deg": CLINIC_SLOPE_DEG, "cross_slope": effort,
            "pin_friction_N_m": [float(c.pin_friction) for c in s.chair.casters],
            "tip_angles_deg": {k.removesuffix("_deg"): float(v) for k, v in dict(s.tipping).items()}}


def layout_report_pages(r: LayoutReport) -> Iterator[Figure]:
    """The report's pages: one text page per section, the clinician sheet, the comparison's table and curves, then
    the sections that do not apply.

    Parameters
    ----------
    r : LayoutReport

    Yields
    ------
    matplotlib.figure.Figure
    """
    sub = f"wheel layout {r.layout.name}: {r.layout.shape[0]} fixed wheels, {r.layout.shape[1]} casters"
    for title, lines in r.sections:
        yield P.text_page(title, list(lines), sub)
    if r.sheet is not None:
        from stability.report.clinician_sheet import sheet_figure

        yield sheet_figure(r.sheet)
    if r.comparison is not None:
        from stability.compare.text import format_comparison

        yield P.text_page(COMPARE_TITLE, format_comparison(r.comparison).split("\n"), sub, monospace=True,
                          fontsize=8.0, width=140)
        yield _curves_page(r.comparison, sub)
    if r.uncertainty is not None:
        yield P.text_page(UNCERTAINTY_TITLE, r.uncertainty.lines(), sub)
    for title, lines in r.appendix:       # reference material: after the results
        yield P.text_page(title, list(lines), sub, monospace=True)
    if r.not_applicable:
        yield P.text_page(NA_TITLE, [f"{t}: {w}" for t, w in r.not_applicable], sub)


def _curves_page(c: Comparison, sub: str) -> Figure:
    from stability.compare.plots import plot_growth_rates
    from stability.report.document import add_caption

    fig, axes = P.page(CURVES_TITLE, sub)
    plot_growth_rates(axes[0, 0], c)
    P.finish(fig, top=0.86)             # the axes title is two lines (chairs, then the model): below the subtitle
    add_caption(fig, comparison_caption(c))
    return fig


def write_layout_report(r: LayoutReport, path: str | os.PathLike[str]) -> int:
    """Write the report's PDF (atomically, reproducibly); returns the number of pages.

    Parameters
    ----------
    r : LayoutReport
    path : str or os.PathLike

    Returns
    -------
    int
    """
    titles = [t for t, _ in r.page_texts()]
    write_pdf(layout_report_pages(r), path, title=f"stability report: {r.layout.name} (wheel layout)",
              outline=[(f"{i + 1}. {t}", i) for i, t in enumerate(titles)])
    return len(titles)
