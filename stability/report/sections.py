"""Pages of the slope, shimmy and uncertainty sections: their text (every number from the data) and figures."""

from __future__ import annotations

import math

from matplotlib.figure import Figure

from stability import plotting as P
from stability.advise.limits import shimmy_sentence
from stability.report.compute import ReportData
from stability.report.slope_data import TREADMILL
from stability.settings.reference import LEVEL, THESIS_PUSH
from stability.shimmy.plots import plot_trail_chart
from stability.slope.plots import plot_holding
from stability.study.censored import side_of, sort_key
from stability.study.uncertain import MeasureInterval

__all__ = ["footer", "slope_text", "shimmy_text", "uncertainty_text", "nonlinear_uncertainty_text", "slope_page",
           "shimmy_page", "uncertainty_page", "section_drops"]


def _cm(x: float) -> str:
    return "> 25 cm (shimmy at every trail checked)" if not math.isfinite(x) else f"{100 * x:.2f} cm"


def slope_text(d: ReportData) -> list[str]:
    """Paragraphs of the cross-slope page.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    s, c = d.slope, d.chair
    if s is None:
        return []
    cv = s.curve
    out = []
    k = len(cv.cross_slopes_deg) - 1
    top = float(cv.cross_slopes_deg[k])
    per = (f"{s.per_degree:.3g} N m per deg (at 1 deg)" if s.per_degree is not None else "not defined at 1 deg")
    out.append(f"Holding a straight line at {s.speed:g} m/s needs a yaw moment from the drive of {per}; "
               f"closed form (frictionless pins, casters straight) {s.closed_form_per_degree:.3g} N m/deg. At "
               f"{top:g} deg: {cv.holding_moment[k]:.3g} N m, and " + (
                   f"with Coulomb pin friction any moment in {cv.friction_low[k]:.3g}-{cv.friction_high[k]:.3g} "
                   "N m holds (the band)." if cv.friction_low[k] > 0 else
                   "with Coulomb pin friction the pins alone can hold the line (no drive moment needed); up to "
                   f"{cv.friction_high[k]:.3g} N m in the holding direction still holds (the band)."))
    sides = sorted(set(s.harder_side[1:] if len(s.harder_side) > 1 else s.harder_side) - {"neither"})
    side = (f"the {sides[0]} wheel works harder at every slope shown" if len(sides) == 1 else
            "the harder-working side changes with the slope: " + ", ".join(
                f"{x:g} deg {h}" for x, h in zip(cv.cross_slopes_deg, s.harder_side, strict=True)))
    if s.drive == "handrim":
        out.append(f"Manual chair (24-inch wheels 0.305 m, hand rims 0.265 m): hand-rim force difference "
                   f"{s.drive_difference[k]:.3g} N at {top:g} deg; {side}"
                   + (f" (against the chair's uncorrected turn {sides[0]})." if len(sides) == 1 else "."))
    else:
        ok = all(s.within_torque_limit)
        out.append(f"Power chair: motor torque difference {s.drive_difference[k]:.3g} N m at {top:g} deg; {side} "
                   + ("(within the motors' limit at every slope shown)." if ok else
                      "(beyond the motors' limit at some slopes shown)."))
    p = s.path
    if p is not None:
        ended = float(p.t[-1])
        stop = (f"; the run ends at {ended:.2f} s (heading past 45 deg or a caster swung 30 deg: beyond the tire "
                "data)" if ended < 2.0 - 1e-9 else "")
        ten = f", 10 deg after {p.time_to_10deg:.2f} s" if p.time_to_10deg is not None else ""
        out.append(f"Uncorrected at {s.path_slope:g} deg (both wheels at the mean drive force) the chair turns "
                   f"{p.turn}: heading {p.heading_change_deg:+.1f} deg and yaw rate {p.yaw_rate_deg_s:+.1f} deg/s "
                   f"after {p.report_time:.2f} s (downhill +){ten}{stop}. A rear-caster chair turns uphill, a "
                   "front-caster chair downhill: the end held by the fixed wheels stays, the castered end swings "
                   "downhill. Exact model, viscous pins only (no Coulomb pin friction in this run).")
    mean, lo, hi = TREADMILL
    mx = s.treadmill_m_x
    if s.per_degree is not None:
        out.append(f"Treadmill study (Richter et al., Arch Phys Med Rehabil 2007, 88:76-80; 26 manual wheelchair "
                   f"users in their own chairs): {mean:g} N m/deg on average, {lo:g}-{hi:g} between users. This "
                   f"chair: {s.per_degree:.3g} N m/deg, {s.per_degree / mean:.1f} times the mean. What drives it: "
                   f"to leading order the moment is m g sin(phi) x_m (the main wheels carry the slope's lateral "
                   f"weight), and this chair has m x_m = {s.m_x:.3g} kg m ({c.m:g} kg, main axle {c.s1:g} m from "
                   f"the c.g.); the published mean and range correspond to m x_m of {mx[0]:.2g} ({mx[1]:.2g}-"
                   f"{mx[2]:.2g}) kg m, i.e. chairs with the c.g. a few cm from the drive axle. Not modelled: "
                   "users shifting their trunk, and the study's one-arm measurement.")
    for phi, why in s.refused:
        out.append(f"Refused at {phi:g} deg (not extrapolated): {why}.")
    return out


def shimmy_text(d: ReportData) -> list[str]:
    """Paragraphs of the caster-shimmy page.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    s = d.shimmy
    if s is None:
        return []
    ch, comp = s.chart, s.compliance
    crit = [x[2] for x in s.corners]
    lo, hi = min(crit), max(crit)
    dlo, dhi = s.divergence_span
    out = [f"Estimates: {s.note}. Nominal: relaxation length {1000 * comp.relaxation_length:g} mm, lateral "
           f"stiffness at the pin {comp.lateral_stiffness / 1000:g} kN/m; ranges "
           f"{1000 * comp.relaxation_length_range[0]:g}-{1000 * comp.relaxation_length_range[1]:g} mm and "
           f"{comp.lateral_stiffness_range[0] / 1000:g}-{comp.lateral_stiffness_range[1] / 1000:g} kN/m.",
           f"Shimmy boundary at {s.speed:g} m/s (linear, no pin friction): trail {_cm(s.critical)} with the nominal "
           f"estimates (chair model with relaxed caster tires and compliant pins: {_cm(s.chair_model_critical)}). "
           f"At the use speeds ({', '.join(f'{u:g}' for u in d.advice.speeds_m_s)} m/s) "
           f"{shimmy_sentence(d.advice.verdict, d.chair.trail, d.advice.shimmy_hold)}."
           + f" Over the estimate range the boundary at {s.speed:g} m/s lies between {_cm(lo)} and {_cm(hi)}:",
           ]
    out += [f"  relaxation {1000 * sg:g} mm, pin stiffness {k / 1000:g} kN/m: {_cm(t)}" for sg, k, t in s.corners]
    ft = ch.friction_trail[-1]
    gain = ""
    if "trail" in d.chair_sweeps:
        sw = d.chair_sweeps.get("trail")
        i = int(sw.values.index(min(sw.values)))
        short, nominal = sw.results[i], sw.nominal
        better = sort_key(short.value_or_bound, side_of(short.status), True) < \
            sort_key(nominal.value_or_bound, side_of(nominal.status), True)
        gain = (f" With pin friction, at {100 * sw.values[i]:g} cm trail the equal-instability speed is "
                f"{short.describe()} against {nominal.describe()} at this chair's {100 * sw.nominal_value:g} cm "
                "(parametric study)"
                + (": the friction-limited caster side force M_f/l grows as the trail shrinks." if better else "."))
    out.append(f"Pin friction {ch.pin_friction:g} N m holds {math.degrees(ch.amplitude):g} deg shimmy down to a trail "
               f"of {_cm(ft)} at {ch.speeds[-1]:g} m/s (describing function). Without pin friction the linear yaw "
               f"divergence rate at {ch.speeds[-1]:g} m/s moves only {dlo:.3g}-{dhi:.3g} 1/s over trails "
               f"{100 * ch.trails[0]:g}-{100 * ch.trails[-1]:g} cm." + gain + " Whether a trail is shimmy-free "
               "depends on the two estimates, which must be measured.")
    return out


def uncertainty_text(d: ReportData) -> list[str]:
    """Paragraphs of the uncertainty page.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    u = d.uncertainty
    if u is None:
        return []
    iv = u.intervals
    lvl = f"{100 * iv.level:g} %"
    out = [f"Parameter distributions from {u.spec.source}: {iv.samples} Monte Carlo draws, seed {iv.seed} "
           f"(the same seed gives the same intervals); {lvl} central intervals; dotted: the first-order delta "
           "method as a check."]
    crit = []
    for name, (a, b, frac), (above, below) in (
            ("zero-width locked-caster", iv.zero_width_critical, (0.0, 0.0)),
            ("locked-caster", iv.locked_critical, iv.locked_beyond), ("free-caster", iv.free_critical, iv.free_beyond)):
        beyond = "".join(f"; {w} in {100 * f:.0f} %" for w, f in (("stable at every speed searched", above),
                                                                    ("unstable at the slowest speed", below)) if f > 0)
        crit.append(f"{name} {a:.3g}-{b:.3g} m/s (exists in {100 * frac:.0f} % of draws{beyond})" if frac > 0
                    else f"{name}: none in {iv.search_m_s[0]:g}-{iv.search_m_s[1]:g} m/s in any draw"
                    + (f" ({beyond[2:]})" if beyond else ""))
    out.append("Critical speeds (" + lvl + "): " + "; ".join(crit) + ".")
    dom = u.dominant
    if dom is None:
        out.append("No parameter varies (zero spread): the intervals are the point values.")
    else:
        out.append(f"Dominant parameter: {dom[0]} ({100 * dom[1]:.0f} % of the variance, first order); then "
                   + ", ".join(f"{n} {100 * x:.0f} %" for n, x in iv.dominant_parameters[1:]) + ".")
    out.extend(nonlinear_uncertainty_text(d))
    return out


def _shares(m: MeasureInterval) -> str:
    dom = m.dominant
    if dom is None:
        return "no parameter moves it (zero spread)"
    rest = ", ".join(f"{n} {100 * x:.0f} %" for n, x in m.shares[1:] if x >= 0.005)
    return f"dominated by {dom[0]} ({100 * dom[1]:.0f} %" + (f"; then {rest})" if rest else ")")


def nonlinear_uncertainty_text(d: ReportData) -> list[str]:
    """Paragraphs on the nonlinear measures' intervals (critical impulse, equal-instability speed).

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    list of str
    """
    u = d.uncertainty
    if u is None or u.nonlinear is None:
        return []
    nl = u.nonlinear
    lvl = f"{100 * nl.level:g} %"
    k = nl.critical_impulse
    out = [f"Nonlinear measures ({nl.samples} draws of the same file, seed {nl.seed}, {nl.model} model; pin "
           f"friction acts here, not in the linear results): critical impulse at {nl.speed:g} m/s (force held "
           f"{THESIS_PUSH.duration:g} s at the c.g.) {lvl}: {k.describe()}, nominal {k.nominal:.3g} N s, "
           f"{_shares(k)}." + (f" No push up to the largest tried spins the chair in {100 * k.outside[0][1]:.0f} % "
                               "of draws." if k.outside and k.outside[0][1] > 0 else "")]
    e = nl.equal_instability
    if e is not None:
        beyond = "; ".join(f"{100 * f:.0f} % of draws {k_} the searched speeds" for k_, f in e.outside if f > 0)
        out.append(f"Equal-instability speed ({lvl}, against {nl.reference}: {nl.reference_time:.2f} s to "
                   f"{LEVEL:g} rad/s under the thesis's push, {THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s): "
                   f"{e.describe()}, nominal "
                   + (f"{e.nominal:.3g} m/s" if math.isfinite(e.nominal) else "outside the searched speeds")
                   + f", {_shares(e)}" + (f"; {beyond}" if beyond else "") + ". No delta-method check: the "
                   "bisections' resolution is coarser than a finite-difference step.")
    return out


def section_drops(d: ReportData) -> dict[str, str]:
    """The section pages that carry no information for this chair: title -> why.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    dict
    """
    out = {}
    if d.slope is not None and not any(p > 0 for p in d.slope.curve.cross_slopes_deg):
        out["cross slope"] = "the slope analysis refuses every cross slope > 0: " + d.slope.refused[0][1]
    if d.shimmy is None and d.shimmy_note:
        out["caster shimmy"] = d.shimmy_note
    if d.uncertainty is None:
        out["parameter uncertainty"] = ("no uncertainty file was given, so the linear numbers "
                                        "are point values at the chair's parameters")
    return out


def footer(fig: Figure, text: str, width: int = 190) -> float:
    """Write a wrapped note at the bottom of a page; return the bottom margin that leaves room for it.

    Parameters
    ----------
    fig : Figure
    text : str
        Paragraphs separated by newlines.
    width : int
        Characters per line.

    Returns
    -------
    float
        Bottom margin (figure fraction) for :func:`stability.plotting.finish`.
    """
    lines = P.wrap_text(text, width)
    for i, line in enumerate(reversed(lines)):
        fig.text(0.5, 0.022 + 0.016 * i, line, ha="center", fontsize=7.5, color="0.3")
    return 0.08 + 0.016 * len(lines)


def _text_column(ax, paragraphs: list[str], width: int, fontsize: float = 7.5, step: float = 0.028) -> None:
    ax.axis("off")
    y = 0.99
    for para in paragraphs:
        for line in P.wrap_text(para, width):
            ax.text(0.0, y, line, fontsize=fontsize, va="top", transform=ax.transAxes)
            y -= step
        y -= 0.012


def slope_page(d: ReportData, title: str, sub: str) -> Figure:
    """The cross-slope page (holding moment, drive difference, uncorrected heading, text).

    Parameters
    ----------
    d : ReportData
    title, sub : str
        Page title and subtitle.

    Returns
    -------
    Figure
    """
    s = d.slope
    assert s is not None
    fig, axes = P.page(title, sub, nrows=1, ncols=3)
    plot_holding([s.curve], axes[0, 0], published=TREADMILL)
    axes[0, 0].set_title(f"holding moment at {s.speed:g} m/s\n(band: Coulomb pin friction; grey: treadmill study)",
                         fontsize=9)
    P.drive_difference(s.curve.cross_slopes_deg, s.drive_difference, s.drive_label, axes[0, 1], chair=s.chair_name)
    axes[0, 1].set_title("drive difference that holds a straight line", fontsize=9)
    if s.path is not None:
        P.uncorrected_heading(s.path.t, s.path_heading_deg, axes[0, 2],
                              title=f"uncorrected at {s.path_slope:g} deg cross slope, {s.speed:g} m/s:\nturns "
                                    f"{s.path.turn}", quasi_steady_deg_s=s.path.quasi_steady_rate_deg_s)
    else:
        axes[0, 2].axis("off")
    bottom = footer(fig, "\n".join(slope_text(d)))
    return P.finish(fig, top=0.85, bottom=bottom)


def shimmy_page(d: ReportData, title: str, sub: str) -> Figure:
    """The caster-shimmy trail trade-off page (chart and text).

    Parameters
    ----------
    d : ReportData
    title, sub : str

    Returns
    -------
    Figure
    """
    s = d.shimmy
    assert s is not None
    fig, axes = P.page(title, sub, nrows=1, ncols=2, gridspec_kw={"width_ratios": [1.5, 1]})
    plot_trail_chart(s.chart, axes[0, 0])
    _text_column(axes[0, 1], shimmy_text(d), 62)
    return P.finish(fig, top=0.85)


def uncertainty_page(d: ReportData, title: str, sub: str) -> Figure:
    """The uncertainty page: growth-rate band against speed, variance shares (linear and nonlinear), text.

    Parameters
    ----------
    d : ReportData
    title, sub : str

    Returns
    -------
    Figure
    """
    u = d.uncertainty
    assert u is not None
    iv = u.intervals
    nl = u.nonlinear
    ratios = [1.4, 1] + ([1] if nl is not None else [])
    fig, axes = P.page(title, sub, nrows=1, ncols=len(ratios), gridspec_kw={"width_ratios": ratios})
    P.growth_rate_band(iv.speeds, u.nominal_rates, [r[0] for r in iv.rate], [r[1] for r in iv.rate], axes[0, 0],
                       level=iv.level, delta=([r[0] for r in iv.rate_delta], [r[1] for r in iv.rate_delta]),
                       title=f"{d.chair.name}: growth rate of the least stable mode,\nfree casters ({d.model} model)")
    names = [n for n, _ in iv.dominant_parameters]
    P.variance_shares(names, [x for _, x in iv.dominant_parameters], axes[0, 1],
                      title="linear results: which parameter dominates\n(first-order share, mean over outputs)")
    if nl is not None:
        k = dict(nl.critical_impulse.shares)
        P.variance_shares(names, [k.get(n, 0.0) for n in names], axes[0, 2],
                          title=f"critical impulse at {nl.speed:g} m/s:\nwhich parameter dominates (first order)")
    bottom = footer(fig, "\n".join(uncertainty_text(d)))
    return P.finish(fig, top=0.86, bottom=bottom)
