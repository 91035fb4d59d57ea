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
from stability.report.clinician import CLINIC_SLOPE_DEG, TABLE_8_2, TYPICAL_PUSH_N
from stability.report.compute import report_run
from stability.report.settings import Settings
from stability.report.slope_data import SlopeSection, slope_section
from stability.report.validity import responses_validity
from stability.settings.reference import THESIS_PUSH
from stability.tipping import TipAngles, tip_angles

__all__ = ["ClinicianSheet", "clinician_sheet", "sheet_lines", "sheet_figure", "SPRING_LEVER_M",
           "TOLERABLE_PIN_FRICTION_N_M", "G"]

#: Lever arm at which the spring scale is hooked, m (10 cm from the pin axis: a hand's width).
SPRING_LEVER_M = 0.10
#: The thesis's tolerable maximum pin friction (conclusion 6), N m.
TOLERABLE_PIN_FRICTION_N_M = 0.3
#: Standard gravity, m/s^2 (spring scales read grams-force).
G = 9.80665
#: Simulated time after the push, s (the report's criterion: 1 rad/s within 10 s).
DURATION_S = 10.0


@dataclass(frozen=True, eq=False)
class ClinicianSheet:
    """Everything the clinician sheet prints.

    Attributes
    ----------
    chair : Chair
    speeds : tuple of float
        The user's speeds, m/s.
    motions : tuple of Motion
        The run after the thesis's push at each speed (stick-slip pin friction), valid part only.
    doubling : tuple of float or None
        Linear doubling time of a heading error at each speed (free casters, no pin friction), s (None:
        the error dies out).
    slope : SlopeSection or None
    tipping : TipAngles
    responses : stability.study.ResponseSet
        The runs behind ``motions``.
    validity : tuple of Validity
    driver : stability.driver.Driver or None
        The user's reaction time, when given.
    human : stability.driver.HumanLimit or None
        Up to which speed that user holds the chair (None without a driver).
    """

    chair: Chair
    speeds: tuple
    motions: tuple
    doubling: tuple
    slope: SlopeSection | None
    tipping: TipAngles
    responses: Any = None
    validity: tuple = ()
    driver: Any = None
    human: Any = None


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
        from stability.driver.text import human_sentence

        over = [u for u in s.speeds if s.human.side != ">" and u > s.human.speed_m_s]
        paras.append(f"THE USER. {human_sentence(s.human, s.driver)} (reaction time from {s.driver.source}; linear "
                     "model without pin friction: docs/driver.md)"
                     + (f"; at {', '.join(_kmh(u) for u in over)} this user cannot hold it." if over else "."))
    if c.caster_position == "rear":
        paras.append("USE. The thesis advises rear-caster chairs primarily indoors, inclines only with another "
                     "person's help, and not above about 2 m/s (7 km/h).")
    sl = s.slope
    if sl is not None and sl.per_degree is not None:
        import numpy as np

        slopes = np.asarray(sl.curve.cross_slopes_deg, float)
        k = int(np.argmin(np.abs(slopes - CLINIC_SLOPE_DEG)))
        if abs(slopes[k] - CLINIC_SLOPE_DEG) < 1e-9:
            f = float(abs(sl.drive_difference[k]))
            side = sl.harder_side[k] if k < len(sl.harder_side) else ""
            if sl.drive == "handrim":
                mean, sd = TYPICAL_PUSH_N
                paras.append(
                    f"CROSS SLOPE. On a {CLINIC_SLOPE_DEG:g} deg camber at {_kmh(sl.speed)} the {side} hand rim must "
                    f"push {f:.0f} N harder than the other, all the way across, to go straight. That is a sustained "
                    f"force: {100 * f / mean:.0f} % of a typical PEAK stroke force on the level ({mean:g} +/- "
                    f"{sd:g} N, hand-rim study 2022), and a stroke's force is at its peak only briefly. "
                    f"Uncorrected, the chair turns " + (sl.path.turn if sl.path is not None else "off its line")
                    + ".")
            else:
                paras.append(f"CROSS SLOPE. On a {CLINIC_SLOPE_DEG:g} deg camber at {_kmh(sl.speed)} the {side} "
                             f"motor must give {f:.3g} N m more than the other to go straight.")
    mf = (c.pin_friction_left, c.pin_friction_right)
    reads = " / ".join(f"{1000 * m / SPRING_LEVER_M / G:.0f} g ({m / SPRING_LEVER_M:.2g} N)" for m in mf)
    paras.append(
        f"CHECK THE PIN FRICTION. With the chair's weight on the caster, hook a spring scale {100 * SPRING_LEVER_M:g} "
        "cm from the swivel pin's axis, pull at right angles to that line and read the scale as the caster starts "
        f"to swivel: friction = reading x {SPRING_LEVER_M:g} m. This chair's pins ({mf[0]:.2g} / {mf[1]:.2g} N m, "
        f"left / right) should read {reads}; the thesis's tolerable maximum {TOLERABLE_PIN_FRICTION_N_M:g} N m "
        f"reads {1000 * TOLERABLE_PIN_FRICTION_N_M / SPRING_LEVER_M / G:.0f} g "
        f"({TOLERABLE_PIN_FRICTION_N_M / SPRING_LEVER_M:.2g} N). More friction holds the line after a bump but "
        "makes turning harder and sustains a slow drift.")
    t = s.tipping
    fwd_main = c.caster_position == "rear"
    main_dir, cast_dir = ("forward", "backward") if fwd_main else ("backward", "forward")
    paras.append(
        "TIPPING (ISO 7176-1, brakes locked, static). The braked chair tips on a slope steeper than: "
        f"{main_dir} (toward the main wheels) {t.toward_main_wheels_deg:.1f} deg, {cast_dir} (toward the casters) "
        f"{t.toward_casters_deg:.1f} deg, sideways {t.lateral_left_deg:.1f} / {t.lateral_right_deg:.1f} deg (left "
        "/ right). For scale: Loane and Kirby (1985) measured 28.6 deg mean rear stability of an occupied "
        "conventional chair with brakes unlocked. Dynamic effects (a push, a kerb) tip it earlier.")
    return {"bump_header": header, "bump_rows": rows, "paragraphs": paras}


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
    fig, _ = P.page(f"{c.name} | for the clinician", f"{c.caster_position} casters; s1 = {c.s1:.3g} m, trail = "
                    f"{c.trail:.3g} m, m = {c.m:.3g} kg, pin friction {c.pin_friction_left:.2g}/"
                    f"{c.pin_friction_right:.2g} N m; {model} model, stick-slip pin friction", nrows=0, ncols=0)
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
