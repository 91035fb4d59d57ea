"""The report's paragraph for a clinician: time to correct a heading error, the thesis's usage advice, and the
hand-rim effort on a cross slope against a typical push.  Every number from the report's data or a cited source.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.report.behaviour import motion, sig3
from stability.report.compute import ReportData
from stability.report.quick import mark
from stability.settings.reference import THESIS_PUSH

__all__ = ["TABLE_8_2", "TYPICAL_PUSH_N", "clinician_text", "user_sentence"]

#: Collins (1987) Table 8-2: the thesis's by-eye "maximum response time" (s) before the yaw-rate curve of
#: Figure 8-3a rises sharply, per speed (m/s); ``inf`` stands for "> 6 s".
TABLE_8_2 = {0.55: math.inf, 0.65: 3.5, 0.75: 2.0, 0.85: 1.5, 0.95: 1.0}

#: Peak hand-rim force of level hand-rim propulsion at low intensity on a treadmill, mean and SD (N):
#: 63 +/- 21 N (J NeuroEngineering Rehabil 2022, doi:10.1186/s12984-022-01007-5, hand-rim group).
TYPICAL_PUSH_N = (63.0, 21.0)

#: The cross slope the paragraph quotes (deg): a common pavement camber.
CLINIC_SLOPE_DEG = 2.0


def _kmh(u: float) -> str:
    return f"{3.6 * u:.1f} km/h"


def clinician_text(d: ReportData) -> str:
    """One paragraph for a clinician.

    Parameters
    ----------
    d : ReportData

    Returns
    -------
    str
    """
    c = d.chair
    val = d.validity.get("responses") or (None,) * len(d.responses.responses)
    pairs = sorted(zip(d.responses.responses, val, strict=True), key=lambda p: p[0].speed)
    q = mark(d.settings)           # the speeds sit around the (coarse, in a quick report) equal-instability speed

    def at(r, v) -> str:
        if math.isfinite(r.time_to_level):
            return f"at {_kmh(r.speed)} {r.time_to_level:.1f} s{q}"
        m = motion(r, v)
        if m.kind == "keeps turning":
            return (f"at {_kmh(r.speed)} it does not spin up within {d.responses.criterion.duration:g} s but keeps "
                    f"turning, {sig3(math.degrees(abs(m.final_rate)) * 10)} deg every 10 s")
        return f"at {_kmh(r.speed)} it does not within {d.responses.criterion.duration:g} s ({m.words()})"

    times = "; ".join(at(r, v) for r, v in pairs)
    thesis = ", ".join(f"{_kmh(u)}: " + ("> 6 s" if math.isinf(t) else f"{t:g} s") for u, t in TABLE_8_2.items())
    out = [f"FOR THE CLINICIAN. After a firm sideways shove ({THESIS_PUSH.force:g} N for {THESIS_PUSH.duration:g} s) "
           f"{c.name} spins up to {d.responses.criterion.yaw_rate:g} rad/s (about 60 deg/s): {times}. The user must "
           "correct well before that: for the thesis's chair the thesis estimated the time before the turn speeds "
           f"up sharply at {thesis} (Table 8-2)."]
    if c.caster_position == "rear":
        out.append("The thesis advises rear-caster chairs primarily for indoor use, inclines only with another "
                   "person's help, and not above about 2 m/s (7 km/h).")
    s = d.slope
    if s is not None and s.drive == "handrim":
        slopes = np.asarray(s.curve.cross_slopes_deg, float)
        k = int(np.argmin(np.abs(slopes - CLINIC_SLOPE_DEG)))
        if abs(slopes[k] - CLINIC_SLOPE_DEG) < 1e-9:
            f = float(abs(s.drive_difference[k]))
            mean, sd = TYPICAL_PUSH_N
            out.append(f"On a {CLINIC_SLOPE_DEG:g} deg cross slope at {_kmh(s.speed)} one hand rim must push "
                       f"{f:.0f} N harder than the other, all the way across, to go straight: a sustained force "
                       f"of {100 * f / mean:.0f} % of a typical PEAK stroke force of {mean:g} +/- {sd:g} N on the "
                       "level (hand-rim propulsion study, J NeuroEng Rehabil 2022), which a stroke holds only "
                       "briefly.")
    if d.human is not None and d.driver is not None:
        out.append(f"{user_sentence(d.human, d.driver, getattr(d.advice, 'intended_speed_m_s', None))}.")
    return " ".join(out)


def user_sentence(h: Any, driver: Any, intended: float | None = None) -> str:
    """The user's limit as page 1 and the clinician sheet state it (without a final full stop).

    Parameters
    ----------
    h : stability.driver.HumanLimit
        :func:`stability.driver.human_limit` of the chair for ``driver``.
    driver : stability.driver.Driver
    intended : float, optional
        The advisor's intended speed, m/s: when the divergence rule (the advisor's check of every change) reaches
        it but the delayed loop does not, the sentence says so.

    Returns
    -------
    str
        ``"A driver who corrects the heading 0.5 s late can hold this chair straight up to 1.02 m/s (3.7 km/h),
        limited by the delayed loop (divergence rule 1.04 m/s, delayed loop 1.02 m/s; reaction time from
        --reaction-time; the exact linear model without pin friction: docs/driver.md)"``; the model is named, as
        the advisor's "Driver:" line is the exact model's whatever the report's model.
    """
    from stability.driver.text import human_sentence, limit_values

    out = (f"{human_sentence(h, driver)}, limited by the {h.limited_by} ({limit_values(h)}; reaction time from "
           f"{driver.source}; the {h.model} linear model without pin friction: docs/driver.md)")
    # a bound at the searched range's end (side ">") is that end, beyond every intended speed; below its start ("<")
    # it is the start, below every one
    if intended is not None and h.loop_speed_m_s < intended <= h.rule_speed_m_s:
        out += (f": the advisor's check, the divergence rule, reaches the intended {intended:g} m/s but the delayed "
                "loop does not, so take that speed as beyond this user")
    return out
