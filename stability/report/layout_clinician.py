"""``report --clinician`` (and the quick report's sheet) on a wheel layout: the short form's one page, computed
with the layout's own model.

The sheet's words and drawing are the short form's (:func:`stability.report.clinician_sheet.sheet_lines`,
:func:`~stability.report.clinician_sheet.sheet_figure`); what differs is where the numbers come from:

- after a bump: the layout simulator (:func:`stability.simulate.layout.simulate_layout`) with the report's push,
  step and stick-slip pin friction over 10 s, every caster trailing the direction of travel at the start
  (:func:`stability.study.layout_impulse.trailing_angles`); the time to correct is the short form's criterion
  (:class:`stability.study.Criterion`) and the valid part the short form's rule
  (:func:`stability.report.validity.run_validity`);
- the doubling time: ``ln 2`` over the layout's linear growth rate (:func:`stability.layout.linear.growth_rates`,
  free frictionless casters), as :func:`stability.linear.divergence` gives the short form's;
- the cross slope: ``python -m stability.slope``'s answer for the layout
  (:func:`stability.study.layout_slope_report.layout_slope_report`) at the reference speed, the uncorrected turn with
  frictionless pins as the short form's;
- the pins: every caster's pin friction, row by row; the tip angles: the layout's ISO 7176-1 angles by direction
  (:func:`stability.layout.statics.tip_angles`);
- the user (``--reaction-time`` or the file's ``[user]``): the speed up to which that driver holds the layout,
  forwards and backwards (:func:`stability.driver.layout.layout_human_limit`: the short form's divergence rule and
  delayed loop on the layout's linear model).
"""

from __future__ import annotations

import math
from types import SimpleNamespace
from typing import Any, cast

import numpy as np

from stability.layout.linear import growth_rates
from stability.layout.model import Layout
from stability.layout.statics import tip_angles
from stability.report.clinician import CLINIC_SLOPE_DEG
from stability.report.clinician_sheet import DURATION_S, ClinicianSheet, SlopeEffort
from stability.report.compute import report_run
from stability.report.settings import Settings
from stability.report.validity import Validity, run_validity
from stability.settings.reference import REFERENCE_SPEED
from stability.simulate.layout import LayoutRun, simulate_layout
from stability.study.criteria import Criterion
from stability.study.layout_impulse import trailing_angles
from stability.study.responses import Response

__all__ = ["layout_clinician_sheet", "layout_response", "layout_slope_effort"]


def _as_result(r: LayoutRun) -> Any:
    """The run in the short form's result names (what :func:`run_validity` and :class:`Criterion` read); ``u``
    along the direction of travel, so that a reverse run's valid part ends where it stops backing, as a forward
    run's ends where it stops going forwards."""
    w = {k: {"first_time": v["first_time_s"]} for k, v in r.warnings.items()}
    u = np.asarray(r.u_m_s) * (-1.0 if r.speed_m_s < 0 else 1.0)
    return SimpleNamespace(t=r.t_s, yaw_rate=r.yaw_rate_rad_s, heading=r.heading_rad, u=u, warnings=w,
                           stopped_by_warnings=r.ended in ("slip warnings", "load warnings"))


def layout_response(layout: Layout, speed: float) -> tuple[Response, Validity]:
    """The report's bump run of a layout at one speed, as the short form's response, and its valid part.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s (negative: reverse, the casters trailing at 180 deg).

    Returns
    -------
    (stability.study.Response, Validity)
    """
    run = report_run("exact", Settings.for_mode(False), "wchair").replace(horizon=DURATION_S)
    r = simulate_layout(layout, speed, run, caster_angles_deg=trailing_angles(layout, speed))
    res = _as_result(r)
    ttl = Criterion(duration=DURATION_S).time(res)
    resp = Response(cast(Any, layout), float(speed), r.t_s, r.yaw_rate_rad_s, r.heading_rad, r.x_m, r.y_m, ttl,
                    bool(res.stopped_by_warnings))
    return resp, run_validity(res)


def layout_slope_effort(layout: Layout, speed: float = REFERENCE_SPEED) -> SlopeEffort | None:
    """The drive difference that holds the layout's line on :data:`CLINIC_SLOPE_DEG` at ``speed``.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s.

    Returns
    -------
    SlopeEffort or None
        None when the layout has no left and right drive wheel pair or the slope has no equilibrium.
    """
    from stability.study.layout_slope_report import layout_slope_report

    try:
        data, _ = layout_slope_report(layout, CLINIC_SLOPE_DEG, speed)
    except ValueError:
        return None
    d = data["drive_forces"]
    if d["drive"] == "handrim":
        diff = abs(float(d["handrim_force_difference_N"]))
    else:
        diff = abs(float(d["motor_torque_left_N_m"]) - float(d["motor_torque_right_N_m"]))
    path = (data.get("uncorrected_simulator") or {}).get("frictionless") or {}
    return SlopeEffort(d["drive"], diff, d["harder_side"], float(speed), path.get("uncorrected_turn"))


def layout_clinician_sheet(layout: Layout, speeds: tuple, driver: Any = None) -> ClinicianSheet:
    """The clinician sheet of a wheel layout at the user's ``speeds`` (m/s, negative: backwards).

    Parameters
    ----------
    layout : Layout
    speeds : tuple of float
        m/s.
    driver : stability.driver.Driver, optional
        The user's reaction time: the sheet then says up to which speed this user holds the layout straight,
        forwards and backwards.

    Returns
    -------
    ClinicianSheet
        ``chair`` is the layout, ``slope`` None and ``effort`` the cross-slope numbers; with a driver ``human`` the
        limit forwards and ``human_reverse`` backwards.
    """
    from stability.report.behaviour import motion

    human = back = None
    if driver is not None:
        from stability.driver.layout import layout_human_limit

        human, back = (layout_human_limit(layout, driver, reverse) for reverse in (False, True))

    pairs = [layout_response(layout, float(u)) for u in speeds]
    motions = tuple(motion(r, v) for r, v in pairs)
    dbl = tuple(math.log(2) / g if g > 0 else None for g in (float(x) for x in growth_rates(layout, list(speeds))))
    return ClinicianSheet(layout, tuple(float(u) for u in speeds), motions, dbl, None, tip_angles(layout),
                          tuple(r for r, _ in pairs), tuple(v for _, v in pairs), driver, human,
                          layout_slope_effort(layout), back)
