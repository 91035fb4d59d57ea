"""``report --clinician``: one page for a clinician, computed on its own (no full report needed).

What the chair does after a bump at the user's speeds (spins up, keeps turning, or returns to its line) and
how long the user has to correct it; the steady drift that pin friction sustains; the hand-rim (or motor)
effort on a cross slope against a typical push; how to check the pin friction with a spring scale; and the
static tip angles by direction.  Every number comes from the toolkit's analyses or a cited source
(:data:`stability.report.clinician.TYPICAL_PUSH_N`); the words come from :mod:`stability.report.behaviour`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from matplotlib.figure import Figure

from stability import plotting as P
from stability import study
from stability.chair import Chair
from stability.linear import divergence
from stability.report.behaviour import Motion, motion, sig3
from stability.report.clinician import CLINIC_SLOPE_DEG, TABLE_8_2, TYPICAL_PUSH_N, user_sentence
from stability.report.compute import report_run
from stability.report.settings import Settings
from stability.report.slope_data import SlopeSection, slope_section
from stability.report.validity import responses_validity
from stability.settings.reference import THESIS_PUSH
from stability.tipping import TipAngles, tip_angles

__all__ = ["ClinicianSheet", "SlopeEffort", "clinician_sheet", "sheet_lines", "sheet_figure", "SPRING_LEVER_M",
           "TOLERABLE_PIN_FRICTION_N_M", "G"]

#: Lever arm at which the spring scale is hooked, m (10 cm from the pin axis: a hand's width).
SPRING_LEVER_M = 0.10
#: The thesis's tolerable maximum pin friction (conclusion 6), N m.
TOLERABLE_PIN_FRICTION_N_M = 0.3
#: Standard gravity, m/s^2 (spring scales read grams-force).
G = 9.80665
#: Simulated time after the push, s (the report's criterion: 1 rad/s within 10 s).
DURATION_S = 10.0


@dataclass(frozen=True)
class SlopeEffort:
    """The cross-slope paragraph's numbers at :data:`~stability.report.clinician.CLINIC_SLOPE_DEG`.

    Attributes
    ----------
    drive : {"handrim", "motor"}
    difference : float
        ``|right - left|`` hand-rim force (N) or ``|left - right|`` motor torque (N m) that holds the line.
    harder_side : str
        ``"uphill"`` or ``"downhill"``: the drive wheel that works harder.
    speed_m_s : float
        m/s.
    turn : str or None
        Which way the uncorrected chair turns (None: not simulated).
    """

    drive: str
    difference: float
    harder_side: str
    speed_m_s: float
    turn: str | None


@dataclass(frozen=True, eq=False)
class ClinicianSheet:
    """Everything the clinician sheet prints.

    Attributes
    ----------
    chair : Chair or stability.layout.Layout
        A short-form chair, or a wheel layout (:func:`stability.report.layout_clinician.layout_clinician_sheet`).
    speeds : tuple of float
        The user's speeds, m/s.
    motions : tuple of Motion
        The run after the thesis's push at each speed (stick-slip pin friction), valid part only.
    doubling : tuple of float or None
        Linear doubling time of a heading error at each speed (free casters, no pin friction), s (None:
        the error dies out).
    slope : SlopeSection or None
    tipping : TipAngles or dict
        The short form's angles, or a layout's by direction (:func:`stability.layout.statics.tip_angles`).
    responses : stability.study.ResponseSet
        The runs behind ``motions``.
    validity : tuple of Validity
    driver : stability.driver.Driver or None
        The user's reaction time, when given.
    human : stability.driver.HumanLimit or None
        Up to which speed that user holds the chair (None without a driver); a wheel layout's forwards.
    effort : SlopeEffort or None
        A wheel layout's cross-slope numbers (:mod:`stability.report.layout_clinician`); a chair's come from
        ``slope``.
    human_reverse : stability.driver.HumanLimit or None
        A wheel layout's limit backwards (:func:`stability.driver.layout.layout_human_limit`; None for a short-form
        chair, which the short form models forwards only).
    """

    chair: Any
    speeds: tuple
    motions: tuple
    doubling: tuple
    slope: SlopeSection | None
    tipping: Any
    responses: Any = None
    validity: tuple = ()
    driver: Any = None
    human: Any = None
    effort: SlopeEffort | None = None
    human_reverse: Any = None


def clinician_sheet(c: Chair, speeds: tuple, model: str = "exact", driver: Any = None) -> ClinicianSheet:
    """Compute the clinician sheet of chair ``c`` at the user's ``speeds`` (m/s).

    Parameters
    ----------
    c : Chair
    speeds : tuple of float
        m/s.
    model : {"exact", "thesis"}
    driver : stability.driver.Driver, optional
        The user's reaction time (``--reaction-time`` or the chair file's ``[user]``): the sheet then says up to
        which speed this user can hold the chair straight (:func:`stability.driver.human_limit`).

    Returns
    -------
    ClinicianSheet
    """
    human = None
    if driver is not None:
        from stability.driver import human_limit

        human = human_limit(c, driver, model)
    run = report_run(model, Settings.for_mode(False), "wchair").replace(horizon=DURATION_S)
    crit = study.Criterion(duration=DURATION_S)
    rs = study.yaw_rate_responses(c, list(speeds), run, criterion=crit, progress=False)
    val = responses_validity([c] * len(speeds), list(speeds), run)
    motions = tuple(motion(r, v) for r, v in zip(rs.responses, val, strict=True))
    dbl = tuple(x.time_to_double for x in divergence(c, list(speeds), model, "free"))
    return ClinicianSheet(c, tuple(speeds), motions, dbl, slope_section(c), tip_angles(c), rs, tuple(val), driver,
                          human)


def _kmh(u: float) -> str:
    return f"{3.6 * u:.1f} km/h"


def _speed_words(u: float) -> str:
    """A user's speed in km/h, ``"2.7 km/h backwards"`` for a negative one."""
    return _kmh(abs(u)) + (" backwards" if u < 0 else "")


def _bump_row(u: float, m: Motion, dbl: float | None) -> list[str]:
    k = m.kind
    if k == "spins up":
        what, t = "spins up", f"{sig3(m.time_to_level)} s to 1 rad/s"
    elif k == "keeps turning":
        what = f"keeps turning: {sig3(math.degrees(abs(m.final_rate)) * 10)} deg in 10 s"
        t = "no spin; steer against the drift"
    elif k == "straight":
        what, t = "returns to its line", "none needed"
    else:
        what, t = f"settles {abs(m.heading_deg):.0f} deg off its line", "re-aim once"
    return [f"{u:g} m/s ({_kmh(u)})", what, t, "-" if dbl is None else f"{sig3(dbl)} s",
            f"{sig3(m.sideways)} m after {sig3(m.travel)} m"]


def sheet_lines(s: ClinicianSheet) -> dict[str, Any]:
    """The sheet's words and table rows (what :func:`sheet_figure` draws and ``--text`` writes).

    Parameters
    ----------
    s : ClinicianSheet

    Returns
    -------
    dict
        ``"bump_header"``, ``"bump_rows"``, ``"paragraphs"`` (list of str).
    """
    c = s.chair
    header = ["speed", "after the bump", "time to correct", "doubles (no friction)", "off its line"]
    rows = [_bump_row(u, m, d) for u, m, d in zip(s.speeds, s.motions, s.doubling, strict=True)]
    paras = []
    spun = [m for m in s.motions if m.kind == "spins up"]
    turning = [m for m in s.motions if m.kind == "keeps turning"]
    bump = (f"AFTER A BUMP. A firm sideways shove ({THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s at the "
            "seat, the thesis's disturbance) at each of the user's speeds: ")
    bump += ("it spins up (1 rad/s = 57 deg/s) at " + ", ".join(_kmh(m.speed) for m in spun) + "; " if spun else
             "it never spins up within 10 s; ")
    if turning:
        worst = max(turning, key=lambda m: abs(m.final_rate))
        bump += (f"pin friction holds the casters off-centre so it keeps drifting at {_kmh(worst.speed)} by "
                 f"{sig3(math.degrees(abs(worst.final_rate)) * 10)} deg every 10 s until the user steers; ")
    bump += ("the table gives the time the user has. The thesis judged about 2 s enough at 2.7 km/h for its chair "
             "(Table 8-2: " + ", ".join(f"{_kmh(u)} " + ("> 6 s" if math.isinf(t) else f"{t:g} s")
                                          for u, t in TABLE_8_2.items()) + ").")
    paras.append(bump)
    if s.human is not None and s.driver is not None:
        from stability.driver.text import held_where, human_sentence

        def over(h: Any, u: float) -> bool:
            return h is not None and h.side != ">" and abs(u) > h.speed_m_s

        back = s.human_reverse
        out = [u for u in s.speeds if over(s.human if u > 0 else back, u)]
        if back is None:                  # a short-form chair: the sentence page 1 states
            who = user_sentence(s.human, s.driver)
        else:
            who = (f"{human_sentence(s.human, s.driver)} forwards and {held_where(back.speed_m_s, back.side)} "
                   "backwards (the layout's linear model, casters trailing the direction of travel) (reaction time "
                   f"from {s.driver.source}; linear model without pin friction: docs/driver.md)")
        paras.append(f"THE USER. {who}"
                     + (f"; at {', '.join(_speed_words(u) for u in out)} this user cannot hold it." if out else "."))
    if getattr(c, "caster_position", None) == "rear":
        paras.append("USE. The thesis advises rear-caster chairs primarily indoors, inclines only with another "
                     "person's help, and not above about 2 m/s (7 km/h).")
    eff = s.effort if s.effort is not None else _chair_effort(s.slope)
    if eff is not None:
        if eff.drive == "handrim":
            mean, sd = TYPICAL_PUSH_N
            f = eff.difference
            paras.append(
                f"CROSS SLOPE. On a {CLINIC_SLOPE_DEG:g} deg camber at {_kmh(eff.speed_m_s)} the {eff.harder_side} "
                f"hand rim must push {f:.0f} N harder than the other, all the way across, to go straight. That is a "
                f"sustained force: {100 * f / mean:.0f} % of a typical PEAK stroke force on the level ({mean:g} +/- "
                f"{sd:g} N, hand-rim study 2022), and a stroke's force is at its peak only briefly. "
                f"Uncorrected, the chair turns " + (eff.turn if eff.turn is not None else "off its line") + ".")
        else:
            paras.append(f"CROSS SLOPE. On a {CLINIC_SLOPE_DEG:g} deg camber at {_kmh(eff.speed_m_s)} the "
                         f"{eff.harder_side} motor must give {eff.difference:.3g} N m more than the other to go "
                         "straight.")
    mf, who = _pins(c)
    reads = " / ".join(f"{1000 * m / SPRING_LEVER_M / G:.0f} g ({m / SPRING_LEVER_M:.2g} N)" for m in mf)
    paras.append(
        f"CHECK THE PIN FRICTION. With the chair's weight on the caster, hook a spring scale {100 * SPRING_LEVER_M:g} "
        "cm from the swivel pin's axis, pull at right angles to that line and read the scale as the caster starts "
        f"to swivel: friction = reading x {SPRING_LEVER_M:g} m. This chair's pins ("
        + " / ".join(f"{m:.2g}" for m in mf) + f" N m, {who}) should read {reads}; the thesis's tolerable maximum "
        f"{TOLERABLE_PIN_FRICTION_N_M:g} N m reads {1000 * TOLERABLE_PIN_FRICTION_N_M / SPRING_LEVER_M / G:.0f} g "
        f"({TOLERABLE_PIN_FRICTION_N_M / SPRING_LEVER_M:.2g} N). More friction holds the line after a bump but "
        "makes turning harder and sustains a slow drift.")
    fore_aft, (left, right) = _tips(c, s.tipping)
    paras.append(
        "TIPPING (ISO 7176-1, brakes locked, static). The braked chair tips on a slope steeper than: "
        + ", ".join(f"{what} {deg:.1f} deg" for what, deg in fore_aft)
        + f", sideways {left:.1f} / {right:.1f} deg (left / right). For scale: Loane and Kirby (1985) measured "
        "28.6 deg mean rear stability of an occupied conventional chair with brakes unlocked. Dynamic effects (a "
        "push, a kerb) tip it earlier.")
    return {"bump_header": header, "bump_rows": rows, "paragraphs": paras}


def _chair_effort(sl: SlopeSection | None) -> SlopeEffort | None:
    """A short-form chair's cross-slope numbers at :data:`CLINIC_SLOPE_DEG` from its slope section (None: not
    solved there)."""
    if sl is None or sl.per_degree is None:
        return None
    import numpy as np

    slopes = np.asarray(sl.curve.cross_slopes_deg, float)
    k = int(np.argmin(np.abs(slopes - CLINIC_SLOPE_DEG)))
    if abs(slopes[k] - CLINIC_SLOPE_DEG) >= 1e-9:
        return None
    side = sl.harder_side[k] if k < len(sl.harder_side) else ""
    return SlopeEffort(sl.drive, float(abs(sl.drive_difference[k])), side, float(sl.speed),
                       sl.path.turn if sl.path is not None else None)


def _pins(c: Any) -> tuple[tuple[float, ...], str]:
    """Each caster's pin friction (N m) and which caster is which, in words."""
    if isinstance(c, Chair):
        return (c.pin_friction_left, c.pin_friction_right), "left / right"
    from stability.advise.layout_levers import caster_rows, row_name

    rows = caster_rows(c)
    order = [k for row in rows for k in row]
    words = []
    for row in rows:
        name = row_name(c, row)
        words += [f"{name} " + ("left" if c.casters[k].y < 0 else "right" if c.casters[k].y > 0 else "centre")
                  for k in row]
    return tuple(float(c.casters[k].pin_friction) for k in order), " / ".join(words)


def _tips(c: Any, t: TipAngles | dict) -> tuple[list[tuple[str, float]], tuple[float, float]]:
    """The fore-and-aft tip angles with their words, and the sideways pair (left, right), deg."""
    if isinstance(t, dict):                    # a layout's (stability.layout.statics.tip_angles)
        return ([("forward", float(t["forward_deg"])), ("backward", float(t["backward_deg"]))],
                (float(t["left_deg"]), float(t["right_deg"])))
    main_dir, cast_dir = ("forward", "backward") if c.caster_position == "rear" else ("backward", "forward")
    return ([(f"{main_dir} (toward the main wheels)", t.toward_main_wheels_deg),
             (f"{cast_dir} (toward the casters)", t.toward_casters_deg)],
            (t.lateral_left_deg, t.lateral_right_deg))


def _subtitle(s: ClinicianSheet, model: str) -> str:
    c = s.chair
    if isinstance(c, Chair):
        return (f"{c.caster_position} casters; s1 = {c.s1:.3g} m, trail = {c.trail:.3g} m, m = {c.m:.3g} kg, pin "
                f"friction {c.pin_friction_left:.2g}/{c.pin_friction_right:.2g} N m; {model} model, stick-slip pin "
                "friction")
    trails = sorted({round(k.trail, 6) for k in c.casters})
    return (f"wheel layout: {c.shape[0]} fixed wheels, {c.shape[1]} casters; trail = "
            + "/".join(f"{x:.3g}" for x in trails) + f" m, m = {c.m:.3g} kg; layout model (exact), stick-slip pin "
            "friction, casters trailing at the start")


def sheet_figure(s: ClinicianSheet, model: str = "exact") -> Figure:
    """The one-page sheet as a figure (A4 landscape).

    Parameters
    ----------
    s : ClinicianSheet
    model : str

    Returns
    -------
    matplotlib.figure.Figure
    """
    c = s.chair
    lines = sheet_lines(s)
    fig, _ = P.page(f"{c.name} | for the clinician", _subtitle(s, model), nrows=0, ncols=0)
    ax_t = fig.add_axes((0.04, 0.70, 0.92, 0.17))
    ax_t.axis("off")
    P.table_axes(ax_t, lines["bump_header"], lines["bump_rows"], col_widths=[0.17, 0.27, 0.2, 0.16, 0.2],
                 fontsize=9, wrap=[22, 34, 26, 20, 24], top=1.0, bottom=0.0)
    ax = fig.add_axes((0.04, 0.03, 0.92, 0.63))
    ax.axis("off")
    y = 1.0
    for para in lines["paragraphs"]:
        wrapped = P.wrap_text(para, 150)
        for i, line in enumerate(wrapped):
            ax.text(0.0, y, line, fontsize=9, va="top", transform=ax.transAxes,
                    fontweight="bold" if i == 0 else "normal")
            y -= 0.046
        y -= 0.027
    return fig
