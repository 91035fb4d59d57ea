"""The report's pages: ``(title, build)`` pairs that draw :class:`~stability.report.compute.ReportData`."""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial

import numpy as np
from matplotlib.figure import Figure

from stability import plotting as P
from stability.chair import preset
from stability.report.appendix import glossary_text, method_text
from stability.report.clinician import clinician_text
from stability.report.comparison import comparison_rows, report_key_numbers
from stability.report.compute import ReportData
from stability.report.contents import CONTENTS_TITLE, contents_line, contents_text
from stability.report.decision import decision_bars, decision_beyond, decision_paragraphs, decision_rows
from stability.report.findings import conclusion_rows, findings
from stability.report.linear_page import linear_page
from stability.report.panels import (
    FLAT_GROWTH,
    NON_OSCILLATORY,
    columns,
    flat_growth,
    no_effect,
    no_effect_line,
)
from stability.report.quick import MARK
from stability.report.sections import footer as _footer
from stability.report.sections import shimmy_page, slope_page, uncertainty_page
from stability.report.summary import dropped_pages, interval_text, push_text, summary_text
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED
from stability.study import FRICTION_FACTORS, PUSH_FACTORS, RANGE_DEFINITION, THESIS

__all__ = ["page_builders", "VALIDITY_NOTE"]

#: What the end of a curve on a time-history plot means.
VALIDITY_NOTE = ("Curves end where the run leaves the model's range: first slip > 8 deg, load outside the tire data, "
                 "heading past 90 deg, or speed reversal (tire forces beyond are clamped, not results).")


#: Page 1's note in a quick report (what it coarsens is listed in the method appendix).
QUICK_NOTE = (f"QUICK REPORT. Values marked {MARK} come from coarse grids and may move in the full report; the "
              "decision above is the advisor's, the same in both. The method appendix lists what is coarsened.")


#: Page 1's note in the quick (brief) report.
BRIEF_NOTE = ("QUICK REPORT. This page, the clinician sheet and the references only, at full resolution: the "
              "decision is the full report's. The evidence (responses, paths, parametric study, maps, shimmy, "
              "slope, the thesis's conclusions) is in the full report (the same command without --quick).")


def _p_sheet(d: ReportData) -> Figure:
    from stability.report.clinician_sheet import sheet_figure

    return sheet_figure(d.sheet, d.model)


def _subtitle(d: ReportData) -> str:
    c = d.chair
    return (f"{c.caster_position} casters; s1 = {c.s1:.3g} m, s2 = {c.s2:.3g} m, trail = {c.trail:.3g} m, "
            f"m = {c.m:.3g} kg, pin friction {_pins(c)} N m, main tire {c.main_tire}, "
            f"caster tire {c.caster_tire}"
            + (f"   [QUICK: values marked {MARK} may move]" if d.settings.quick else ""))


def _title(d: ReportData, what: str) -> str:
    name = d.chair.name if len(d.chair.name) <= 40 else d.chair.name[:39] + "\u2026"   # the subtitle has the rest
    return f"{name} | {d.model} model | {what}"


def _p_decision(d: ReportData, contents: str = "") -> Figure:
    fig, _ = P.page(_title(d, "the decision"), _subtitle(d), nrows=0, ncols=0)
    gs = fig.add_gridspec(2, 2, width_ratios=[1.15, 1], height_ratios=[1, 1], left=0.03, right=0.98, top=0.89,
                          bottom=0.08, wspace=0.12, hspace=0.3)
    ax_text, ax_table, ax_bar = fig.add_subplot(gs[:, 0]), fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, 1])
    ax_text.axis("off")
    y = 1.0
    paras = (decision_paragraphs(d) + [clinician_text(d)] + ([QUICK_NOTE] if d.settings.quick else [])
             + ([BRIEF_NOTE] if d.brief else []) + ([contents] if contents else []))
    pos = ax_text.get_position()
    w_pt, h_pt = pos.width * fig.get_figwidth() * 72.0, pos.height * fig.get_figheight() * 72.0
    for fs in np.arange(9.3, 6.99, -0.1):        # shrink the text until it fits its column, never below 7 pt
        # DejaVu Sans: about 0.55 em per character on average; the chart's bar labels reach 8 % into the column
        width = int(0.92 * w_pt / (0.58 * fs))
        line_h, gap = 1.22 * fs / h_pt, 0.5 * 1.22 * fs / h_pt
        if sum(len(P.wrap_text(p, width)) * line_h + gap for p in paras) <= 1.0:
            break
    for para in paras:
        head = para.split(" ", 1)[0].rstrip(".").isupper()       # VERDICT., RECOMMENDATION., ...
        for i, line in enumerate(P.wrap_text(para, width)):
            ax_text.text(0.0, y, line, fontsize=fs, va="top", transform=ax_text.transAxes,
                         fontweight="bold" if i == 0 and head else "normal")
            y -= line_h
        y -= gap
    header, rows = decision_rows(d)
    ax_table.axis("off")
    n = len(header)
    P.table_axes(ax_table, header, rows, col_widths=[0.42] + [0.58 / (n - 1)] * (n - 1), fontsize=8,
                 wrap=[32] + [12] * (n - 1), top=1.0, bottom=0.0)
    ax_table.set_title("key numbers (ranges over push, pin friction, model and simulator step)", fontsize=9)
    names, vals, lows, highs = decision_bars(d)
    P.decision_chart(names, vals, lows, highs, ax_bar, reference_speed=REFERENCE_SPEED,
                     title=f"{d.chair.name}: how fast before it is as unstable\nas the thesis's reference case",
                     beyond=decision_beyond(d))
    return fig


def _p_chair(d: ReportData) -> Figure:
    sub, c = _subtitle(d), d.chair
    fig, axes = P.page(_title(d, "appendix: chair parameters and geometry"), sub, nrows=1, ncols=2,
                       gridspec_kw={"width_ratios": [1.35, 1]})
    P.parameter_table(c, axes[0, 0])
    P.chair_geometry(c, axes[0, 1])
    t = d.tipping
    if t is not None:
        fig.text(0.60, 0.13, "Static stability angles (ISO 7176-1; brakes locked, casters in their\nleast stable "
                 f"orientation):\ntoward the main wheels {t.toward_main_wheels_deg:.1f} deg, toward the casters "
                 f"{t.toward_casters_deg:.1f} deg,\nsideways {t.lateral_left_deg:.1f} / {t.lateral_right_deg:.1f} "
                 "deg (left / right)", fontsize=8.5, va="top", ha="left")
    return P.finish(fig)


def _pins(c) -> str:
    """Both pins' friction, N m (one value when they are equal)."""
    a, b = c.pin_friction_left, c.pin_friction_right
    return f"{a:.3g}" if f"{a:.3g}" == f"{b:.3g}" else f"{a:.3g} / {b:.3g}"


def _p_comparison(d: ReportData) -> Figure:
    b = d.baseline
    assert b is not None
    sub = _subtitle(d)
    fig, axes = P.page(_title(d, f"compared with {b.chair.name}"), sub, nrows=1, ncols=2,
                       gridspec_kw={"width_ratios": [1, 1.6]})
    P.chair_geometry(d.chair, axes[0, 0], overlay=b.chair,
                     title=f"{d.chair.name} (solid) on {b.chair.name} (dashed), c.g. on c.g.")
    this, base = report_key_numbers(d)
    geometry = [["c.g. to main axle s1 (m)", f"{d.chair.s1:.3g}", f"{b.chair.s1:.3g}", "", ""],
                ["c.g. to caster pins s2 (m)", f"{d.chair.s2:.3g}", f"{b.chair.s2:.3g}", "", ""],
                ["caster trail (m)", f"{d.chair.trail:.3g}", f"{b.chair.trail:.3g}", "", ""],
                ["pin friction, left / right (N m)", _pins(d.chair), _pins(b.chair), "", ""],
                ["mass (kg)", f"{d.chair.m:.3g}", f"{b.chair.m:.3g}", "", ""]]
    axes[0, 1].axis("off")
    P.table_axes(axes[0, 1], ["", d.chair.name, b.chair.name, "change", "better"],
                 geometry + comparison_rows(this, base), col_widths=[0.5, 0.13, 0.13, 0.12, 0.12], fontsize=8.5,
                 wrap=[44, 12, 12, 10, 10], top=0.97, bottom=0.05)
    axes[0, 1].set_title(f"key numbers, {d.model} model, same settings for both chairs", fontsize=10)
    return P.finish(fig)


def _p_trail_window(d: ReportData) -> Figure:
    w = d.trail_window
    assert w is not None
    fig, axes = P.page(_title(d, "trail design chart: directional stability against caster shimmy"), _subtitle(d),
                       nrows=1, ncols=1)
    P.trail_window_chart(w, axes[0, 0], model=d.model)
    speeds = ", ".join(f"{u:g}" for u in w.use_speeds_m_s)
    bottom = _footer(fig, f"Shimmy zones: linear towed-wheel model of the caster at {speeds} m/s with the estimated "
                     "caster compliance (tire relaxation length, frame stiffness at the pin), nominal and over the "
                     "estimates' range. Equal-instability speeds: the parametric study (trail varied at constant "
                     "pin-to-c.g. distance of the caster, with pin friction).")
    return P.finish(fig, bottom=bottom)


def _p_tires(d: ReportData) -> Figure:
    sub = _subtitle(d)
    fig, axes = P.page(_title(d, "appendix: tires (Figures 4-1 and 4-2 analogues)"), sub, nrows=1, ncols=3)
    P.tire_curves(d.tire_force[0], axes[0, 0])
    P.tire_curves(d.tire_force[1], axes[0, 1])
    P.cornering_stiffness_curves(d.tire_stiffness, axes[0, 2])
    return P.finish(fig)


def _p_linear(d: ReportData) -> Figure:
    return linear_page(d, _title(d, "appendix: linear stability: critical speeds and eigenvalues as speed varies"),
                       _subtitle(d))


def _p_re_im(d: ReportData) -> Figure:
    sub = _subtitle(d)
    fig, axes = P.page(_title(d, "eigenvalues against speed (shaded: unstable)"), sub, nrows=2, ncols=2)
    for j, cs in enumerate(("free", "locked")):
        locus = d.speed_loci[(d.model, cs)]
        real_only = float(np.abs(locus.eigenvalues.imag).max()) < NON_OSCILLATORY
        P.eigenvalues_vs_speed(locus, [axes[0, j], None if real_only else axes[1, j]],
                               mode_names=d.mode_names.get((d.model, cs)))
        if real_only:
            axes[1, j].axis("off")
            axes[1, j].text(0.5, 0.6, f"{cs.capitalize()} casters: every mode is non-oscillatory at every speed "
                            "(imaginary parts 0),\nso there is no frequency to plot.", ha="center", va="center",
                            fontsize=8.5, transform=axes[1, j].transAxes)
    bottom = _footer(fig, f"Modes named from their eigenvectors at {REFERENCE_SPEED:g} m/s (largest share of "
                     "sideslip v/U, yaw r s/U, casters in phase, casters opposed; a second share named when above "
                     "20 %). Linear axis; fast modes off scale are listed in the legend.")
    return P.finish(fig, bottom=bottom)


def _p_growth(d: ReportData) -> Figure:
    sub = _subtitle(d)
    drawn = [loc for loc in d.parameter_loci if not flat_growth(loc)]
    flat = [loc for loc in d.parameter_loci if flat_growth(loc)]
    fig = P.growth_rate_vs_parameter(drawn, _title(d, "appendix: growth rate of the least stable mode against design "
                                                      "parameters, 0.75 m/s"), sub, ncols=columns(len(drawn)))
    bottom = 0.08
    if flat:
        bottom = _footer(fig, f"Within {100 * FLAT_GROWTH:g} % over the whole span (not drawn): " + "; ".join(
            f"{loc.label}: {float(np.median(loc.max_real)):.3g} 1/s" for loc in flat) + ".")
    return P.finish(fig, top=0.88, bottom=bottom)


def _p_gain(d: ReportData) -> Figure:
    sub, c = _subtitle(d), d.chair
    fig, axes = P.page(_title(d, "appendix: root locus against a yaw-rate feedback gain (for power chairs)"), sub,
                       nrows=1, ncols=2)
    for ax, g, poles in zip(axes[0], d.gain_loci, d.gain_poles, strict=True):
        P.gain_locus(g, ax, stabilising_poles=poles,
                     title=f"{c.name}: Mz = -K r, {g.model} model, {g.casters} casters, U = {g.speed:g} m/s")
    return P.finish(fig)


def _p_responses(d: ReportData) -> Figure:
    sub, c = _subtitle(d), d.chair
    fig, axes = P.page(_title(d, "nonlinear yaw-rate responses (Figure 8-3a analogue), linear overlay"), sub,
                       nrows=1, ncols=2)
    P.yaw_rate_responses(d.responses, axes[0, 0], reference_time=d.thesis.reference_time,
                         validity=d.validity.get("responses"), flip=True,
                         title=f"pin friction {_pins(c)} N m, stick-slip ({d.model} model, {d.scheme} scheme); "
                               "dashed: linear")
    P.yaw_rate_responses(d.responses_frictionless, axes[0, 1], reference_time=d.thesis.reference_time,
                         validity=d.validity.get("frictionless"), flip=True,
                         title="without pin friction (where the linear model applies)")
    bottom = _footer(fig, f"Push: {push_text(d)} at the c.g. (WCHAIR applies the force while t <= 0.1 s). "
                     + VALIDITY_NOTE + "\n" + d.responses.linear_note + ".")
    return P.finish(fig, bottom=bottom)


def _p_paths(d: ReportData) -> Figure:
    sub = _subtitle(d)
    fig, axes = P.page(_title(d, "paths after the disturbance (Figure 8-4 analogue)"), sub, nrows=1, ncols=2)
    P.trajectories(d.paths, axes[0, 0], validity=d.validity.get("paths"),
                   title=f"paths after {push_text(d)} at the c.g., {REFERENCE_SPEED:g} m/s: {d.model} model, "
                         f"{d.scheme} scheme")
    P.yaw_rate_responses(d.paths, axes[0, 1], label_chair=True, ylim=(-1.0, 1.5), validity=d.validity.get("paths"),
                         flip=True,
                         title=f"yaw rates of the same runs, {REFERENCE_SPEED:g} m/s ({d.model} model); "
                               "dashed: linear")
    bottom = _footer(fig, VALIDITY_NOTE)
    return P.finish(fig, bottom=bottom)


def _p_equal(d: ReportData) -> Figure:
    sub, c, st = _subtitle(d), d.chair, d.settings
    th = d.thesis
    res = [th.speeds["ej-premier"], th.speeds["ej-premier x0.5 friction"], th.speeds["ej-premier x1.5 friction"],
           th.speeds["revised"], th.speeds["revised x0.5 friction"], th.speeds["revised x1.5 friction"],
           th.speeds["ej-premier-front-caster"]]
    if c != preset(REFERENCE_CHAIR):
        res = [d.chair_speed] + list(d.chair_friction) + res
    seen, uniq = set(), []
    for r in res:                      # a preset chair appears once
        if r.chair.name not in seen:
            seen.add(r.chair.name)
            uniq.append(r)
    if d.figure_8_14 is not None:
        uniq.append(d.figure_8_14.speed)
    res = uniq
    thesis_ranges = {"ej-premier": (0.75, 0.75), "revised": (1.10, 1.15), "revised x0.5 friction": (0.63, 0.67),
                     "revised x1.5 friction": (1.63, 1.67)}
    if d.figure_8_14 is not None:
        thesis_ranges[d.figure_8_14.chair.name] = (0.85, 0.85)
    fig, axes = P.page(_title(d, "equal-instability speeds (chapter 9, Figures 9-2 and 9-3)"), sub, nrows=1,
                       ncols=2, gridspec_kw={"width_ratios": [1.5, 1]})
    iv = d.intervals
    errors = ({iv.point.chair.name: (iv.low, iv.high)} if iv is not None and iv.low is not None
              and iv.high is not None else None)
    P.equal_instability_chart(res, axes[0, 0], thesis=thesis_ranges, errors=errors,
                              error_label=f"range: push x{PUSH_FACTORS[0]:g}-x{PUSH_FACTORS[-1]:g}, pin friction "
                                          f"x{FRICTION_FACTORS[0]:g}-x{FRICTION_FACTORS[-1]:g}, model variant")
    ax = axes[0, 1]
    ax.axis("off")
    crit = th.criterion
    txt = [
        "Criterion: " + crit.describe() + ".",
        f"Reference: E&J Premier at {REFERENCE_SPEED:g} m/s, {push_text(d)} at the c.g.: "
        f"{th.reference_time:.3f} s (thesis: {THESIS['reference_time_to_1_rad_s']}).",
        "Equal-instability speed: the speed at which the chair takes exactly as long; found by a bracketing "
        f"search on speed ({st.candidates} candidate speeds in the first round, then a regula-falsi pair per "
        "round, one batch of simulations per round, to "
        f"{st.tol:g} m/s, bracket {st.bracket[0]:g}-{st.bracket[1]:g} m/s).",
        "Why: the thesis itself quotes this number for its reference case; for exponentially growing "
        "responses matching the time to a level matches the curve's position, which is how the thesis "
        "compares curves by eye (Figures 9-2, 9-3); it is monotone in speed.",
        "Thesis: revised " + THESIS["revised"] + "; half friction " + THESIS["revised_half_friction"]
        + "; 1.5x friction " + THESIS["revised_1.5x_friction"] + ".",
        "Figure 8-14 (lighter chair): thesis about 0.85 m/s; not reproduced, see the findings page.",
        "Grey hatched bars: outside the bracket (value is a bound).",
        "'x0.5 / x1.5 friction' bars: that chair's friction scaled, the reference unchanged (the range scales "
        "both chairs').",
        "Thesis vs ours: the two model variants are compared in the method appendix.",
    ]
    if d.intervals is not None:
        txt.insert(3, "How firm: " + interval_text(d.intervals) + "; " + RANGE_DEFINITION + ".")
    y = 0.99
    for para in txt:
        for line in P.wrap_text(para, 60):
            ax.text(0.0, y, line, fontsize=7.5, va="top", transform=ax.transAxes)
            y -= 0.029
        y -= 0.015
    return P.finish(fig, left=0.22)


def _p_sweeps(d: ReportData) -> Figure:
    sub = _subtitle(d)
    table = d.chair_sweeps
    drawn, flat = no_effect(d)
    n = max(len(drawn), 1)
    ncols = columns(n)
    nrows = int(math.ceil(n / ncols))
    fig, axes = P.page(_title(d, "parametric study: equal-instability speed per chapter-8 parameter"),
                       sub, nrows=nrows, ncols=ncols)
    limits = {p: (v, f"tips at {d.tip_limits_deg:g} deg") for p, v in d.tip_limits.items()}
    P.sweep_chart(table, axes, limits=limits, sweeps=drawn)
    note = (f" Dash-dot line: where the braked chair's static stability angle toward its main wheels falls to "
            f"{d.tip_limits_deg:g} deg (Loane and Kirby's measured mean for a conventional chair, brakes "
            "unlocked: a scale, not a like-for-like "
            "limit): moving the axle "
            "past it trades tipping for directional stability." if limits else "")
    flat_line = no_effect_line(d, flat)
    bottom = _footer(fig, "Dashed line: this chair's equal-instability speed; dotted line: its value of the "
             "parameter; other parameters at the chair's values. Same speed scale in every panel." + note
             + ("\n" + flat_line if flat_line else ""))
    return P.finish(fig, bottom=bottom)


def _p_sweep_table(d: ReportData) -> Figure:
    sub = _subtitle(d)
    table = d.chair_sweeps
    rows = []
    for i, s in enumerate(table.ranked(), start=1):
        rows.append([str(i), s.label + ("" if s.unit == "-" else f" ({s.unit})"),
                     ", ".join(s.value_text(k) for k in range(len(s.values))),
                     ", ".join(r.describe(unit=False) for r in s.results),
                     f"{s.effect_percent:.1f}" + (" (bound)" if s.censored else ""), s.how])
    return P.table_page(_title(d, "appendix: which parameters matter, by how much"),
                        ["rank", "parameter", "values tried", "equal-instability speed (m/s)", "spread (%)",
                         "how varied"], rows, sub,
                        col_widths=[0.04, 0.17, 0.17, 0.27, 0.08, 0.27], wrap=[4, 24, 22, 40, 10, 40],
                        notes=(f"This chair: {table.nominal.describe()} (reference {d.thesis.reference_time:.2f} s "
                               f"to {d.thesis.criterion.yaw_rate:g} rad/s). Spread: (max - min) / this chair's "
                               "speed over the values tried. '(bound)': some speed lies outside the bracket, so "
                               "the spread is a lower bound."))


def _p_maps(d: ReportData) -> Figure:
    sub, c = _subtitle(d), d.chair
    fig, axes = P.page(_title(d, "stability maps: time to |yaw rate| = 1 rad/s"), sub, nrows=1, ncols=2)
    P.stability_map(d.friction_map, axes[0, 0], nominal=c.pin_friction_left)
    P.stability_map(d.disturbance_map, axes[0, 1], nominal=d.thesis.impulse[0] * d.thesis.impulse[1])
    bottom = _footer(fig, "Heavy line: the reference case's time. Slower than the line (left): more time to react than "
             "in the reference case; faster (right): less. Dots: simulated grid points. Left map: push "
             f"{push_text(d)}. Right map: impulse = force x 0.1 s (the push convention of the method appendix).")
    return P.finish(fig, bottom=bottom)


def _p_conclusions(d: ReportData) -> Figure:
    sub = _subtitle(d)
    rows = conclusion_rows(d)
    own = len(rows[0]) > 4
    header = ["#", "conclusion (chapter 9)", "verdict (thesis's chairs)", "our evidence (E&J Premier, revised)"]
    if own:
        header.append(f"{d.chair.name}'s own test")
    return P.table_page(_title(d, "the thesis's conclusions 1-9 against our numbers"),
                        header, rows, sub,
                        col_widths=[0.03, 0.2, 0.08, 0.44, 0.25] if own else [0.03, 0.25, 0.08, 0.64],
                        wrap=[3, 34, 12, 80, 44] if own else [3, 40, 12, 100], fontsize=7 if own else 8,
                        notes=f"Nonlinear runs: {d.thesis.model} model, {d.scheme} scheme; "
                              f"{d.thesis.criterion.describe()}; push {push_text(d)}. The verdicts test the thesis "
                              "on its own chairs under its own conditions and are the same in every report; the "
                              "last column (when present) applies the design conclusions to this chair. The 'agree "
                              "if' thresholds are justified in the method appendix.")


def _p_summary_page(d: ReportData) -> Figure:
    sub = _subtitle(d)
    return P.text_page(_title(d, "key numbers, their ranges and caveats"), summary_text(d), sub, fontsize=9.5,
                       width=150)


def _p_contents(d: ReportData, titles: list[str]) -> Figure:
    return P.text_page(_title(d, "appendix: contents of this report (the results, then the appendix)"),
                       contents_text(d, titles), _subtitle(d), fontsize=9.5, width=150)


def _p_method(d: ReportData) -> Figure:
    return P.text_page(_title(d, "appendix: method"), "\n\n".join(method_text(d)), _subtitle(d), fontsize=10,
                       width=140)


def _p_glossary(d: ReportData) -> Figure:
    return P.text_page(_title(d, "appendix: glossary and references"), "\n".join(glossary_text()), _subtitle(d),
                       fontsize=10, width=140)


def _p_findings(d: ReportData) -> Figure:
    sub = _subtitle(d)
    return P.text_page(_title(d, "appendix: findings in detail"), "\n\n".join(findings(d)), sub, fontsize=10.5,
                       width=140)


def _p_slope(d: ReportData) -> Figure:
    return slope_page(d, _title(d, "cross slope: holding a straight line, the uncorrected turn"),
                      _subtitle(d))


def _p_shimmy(d: ReportData) -> Figure:
    return shimmy_page(d, _title(d, "caster trail trade-off: yaw divergence and caster shimmy"),
                       _subtitle(d))


def _p_uncertainty(d: ReportData) -> Figure:
    return uncertainty_page(d, _title(d, "parameter uncertainty: linear and nonlinear results with intervals"),
                            _subtitle(d))


def page_builders(d: ReportData) -> list[tuple[str, Callable[[], Figure]]]:
    """``(title, build)`` for every page, in order; ``build()`` returns a Figure.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of (str, callable)
    """
    if d.brief:
        return [("decision", partial(_p_decision, d)), ("for the clinician", partial(_p_sheet, d)),
                ("glossary and references", partial(_p_glossary, d))]
    drop = dropped_pages(d)
    pages: list[tuple[str, Callable[[], Figure]]] = [
        # main body: the decision and the evidence
        ("decision", partial(_p_decision, d)),
        ("summary", partial(_p_summary_page, d)),
        ("comparison", partial(_p_comparison, d)),
        ("eigenvalues against speed", partial(_p_re_im, d)),
        ("nonlinear yaw-rate responses", partial(_p_responses, d)),
        ("paths", partial(_p_paths, d)),
        ("equal-instability speeds", partial(_p_equal, d)),
        ("parametric study", partial(_p_sweeps, d)),
        ("stability maps", partial(_p_maps, d)),
        ("trail design chart", partial(_p_trail_window, d)),
        ("caster shimmy", partial(_p_shimmy, d)),
        ("cross slope", partial(_p_slope, d)),
        ("parameter uncertainty", partial(_p_uncertainty, d)),
        ("thesis conclusions", partial(_p_conclusions, d)),
        # appendix (contents.APPENDIX_PAGES): its contents, method, validation and the linear analysis in full
        (CONTENTS_TITLE, lambda: Figure()),
        ("method", partial(_p_method, d)),
        ("chair parameters and geometry", partial(_p_chair, d)),
        ("findings", partial(_p_findings, d)),
        ("linear stability: critical speeds", partial(_p_linear, d)),
        ("tires", partial(_p_tires, d)),
        ("growth rate against design parameters", partial(_p_growth, d)),
        ("yaw-rate feedback root locus", partial(_p_gain, d)),
        ("parametric study table", partial(_p_sweep_table, d)),
        ("glossary and references", partial(_p_glossary, d)),
    ]
    kept = [(t, b) for t, b in pages if t not in drop]
    titles = [t for t, _ in kept]
    bind = {"decision": partial(_p_decision, d, contents_line(titles)),
            CONTENTS_TITLE: partial(_p_contents, d, titles)}
    return [(t, bind.get(t, b)) for t, b in kept]
