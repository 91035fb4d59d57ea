"""The report's cross-slope section: holding moment, drive difference, uncorrected path, treadmill study.

Every number comes from :mod:`stability.slope` (``solve``, ``drive_report``, ``uncorrected_path``); rules and
sources in docs/report.md and docs/slopes.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.settings.reference import CROSS_SLOPE_STUDY, REFERENCE_SPEED
from stability.slope import HandRim, Plane, drive_report, holding_moment_closed_form, solve
from stability.slope.plots import HoldingCurve, magnitude_band
from stability.study.veer import UncorrectedPath, uncorrected_path

__all__ = ["TREADMILL", "SLOPES", "PATH_SLOPE", "SlopeSection", "drive_kind", "slope_section", "difference_of",
           "LayoutSlopeSection", "layout_slope_section"]

#: Richter et al., Arch Phys Med Rehabil 2007, 88:76-80: growth of the downhill turning moment with
#: cross slope over 26 manual wheelchair users, N m/deg: (mean, lowest, highest).
TREADMILL = CROSS_SLOPE_STUDY
#: Cross slopes of the section, deg (0-6 deg: the treadmill study's level, 3 and 6 deg and between).
SLOPES = (0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
#: Cross slope of the uncorrected path, deg (a steep sidewalk drainage slope; typical is about 2 %).
PATH_SLOPE = 2.0


@dataclass(frozen=True, eq=False)
class SlopeSection:
    """Steady straight running across a slope, for one chair at one speed.

    Attributes
    ----------
    chair_name : str
    speed : float
        Speed along the path, m/s.
    curve : HoldingCurve
        Holding-moment magnitude (N m) with its Coulomb pin-friction range over the accepted slopes.
    drive : {"handrim", "motor"}
        Manual chair (hand-rim forces) or power chair (motor torques).
    drive_difference : ndarray
        Per accepted slope: |right - left| hand-rim force (N) or |left - right| motor torque (N m).
    within_torque_limit : tuple of bool
        Power chairs: whether the differential torque is within the motors' limit (empty for manual chairs).
    harder_side : tuple of str
        Per accepted slope: which drive wheel works harder, ``"uphill"`` or ``"downhill"``
        (:func:`stability.slope.equilibrium.harder_side`, from the statics).
    refused : tuple of (float, str)
        Slopes the analysis refuses (deg) and its one-line reason.
    per_degree : float or None
        Holding moment at 1 deg, N m/deg (None if 1 deg is refused).
    closed_form_per_degree : float
        ``g sin(1 deg) (m x_m - 2 m_c (l1/trail)(x_m - x_c))``, N m/deg (frictionless pins, casters straight).
    m_x : float
        ``m |x_m|``, kg m: mass times the c.g.-to-main-axle distance, the quantity that sets the moment.
    path : UncorrectedPath or None
        Released from the held equilibrium at ``path_slope`` (None if every slope > 0 is refused).
    path_slope : float
        deg.
    g : float
        Gravitational acceleration of the chair, m/s^2.
    """

    chair_name: str
    speed: float
    curve: HoldingCurve
    drive: str
    drive_difference: np.ndarray
    within_torque_limit: tuple
    harder_side: tuple
    refused: tuple
    per_degree: float | None
    closed_form_per_degree: float
    m_x: float
    path: UncorrectedPath | None
    path_slope: float
    g: float = 9.81

    @property
    def treadmill_m_x(self) -> tuple[float, float, float]:
        """The treadmill study's mean, low and high as ``m x_m`` (kg m): ``M / (g sin 1 deg)``."""
        k = self.g * math.sin(math.radians(1.0))
        return tuple(v / k for v in TREADMILL)  # type: ignore[return-value]

    @property
    def path_heading_deg(self) -> np.ndarray:
        """Heading change of the uncorrected path from its start, deg (downhill +); empty without a path."""
        if self.path is None:
            return np.empty(0)
        side = math.copysign(1.0, self.path_slope)
        return np.degrees((self.path.heading - self.path.heading[0]) * side)

    @property
    def drive_label(self) -> str:
        """Axis label of the drive difference, with its unit."""
        return _drive_label(self.drive)


def drive_kind(chair: Chair) -> str:
    """``"motor"`` for power chairs (preset names ``power-*``), else ``"handrim"`` (as ``python -m stability.slope``).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    str
    """
    return "motor" if chair.name.startswith("power") else "handrim"


def difference_of(report: dict) -> tuple[float, bool | None]:
    """The drive difference that holds the line, from a :func:`stability.slope.equilibrium.drive_report`.

    Parameters
    ----------
    report : dict
        The drive report (its ``drive`` says which).

    Returns
    -------
    (float, bool or None)
        ``|right - left|`` hand-rim force (N) and None, or ``|left - right|`` motor torque (N m) and whether the
        differential torque is within the motors' limit.
    """
    if report["drive"] == "handrim":
        return abs(report["handrim_force_difference_N"]), None
    return (abs(report["motor_torque_left_N_m"] - report["motor_torque_right_N_m"]),
            bool(report["within_torque_limit"]))


def _difference(chair: Chair, eq, kind: str) -> tuple[float, bool | None]:
    return difference_of(drive_report(chair, eq, kind, HandRim() if kind == "handrim" else None))


@dataclass(frozen=True, eq=False)
class LayoutSlopeSection:
    """:class:`SlopeSection`'s curves for any wheel layout (the layout model's statics and simulator).

    Attributes
    ----------
    layout_name : str
    speed : float
        Speed along the path, m/s (negative: reverse).
    side : float
        +1: the slopes fall to the right; -1: to the left.
    curve : HoldingCurve
        Holding-moment magnitude (N m) with its Coulomb pin-friction range over the accepted slopes (their
        magnitudes, deg), and the hand-rim force difference (N).
    drive : {"handrim", "motor"}
    drive_difference : ndarray
        Per accepted slope, as :class:`SlopeSection`'s.
    harder_side : tuple of str
    refused : tuple of (float, str)
    path : LayoutPath or None
        Released from the held line at ``path_slope`` with Coulomb pin friction (the layout simulator).
    path_slope : float
        Magnitude, deg (NaN without a path).
    path_error : str or None
        Why there is no path, when one was tried.
    """

    layout_name: str
    speed: float
    side: float
    curve: HoldingCurve
    drive: str
    drive_difference: np.ndarray
    harder_side: tuple
    refused: tuple
    path: Any
    path_slope: float
    path_error: str | None = None

    @property
    def drive_label(self) -> str:
        """Axis label of the drive difference, with its unit."""
        return _drive_label(self.drive)


def _drive_label(kind: str) -> str:
    return ("hand-rim force difference |right - left| (N)" if kind == "handrim"
            else "motor torque difference |left - right| (N m)")


def layout_slope_section(layout: Any, speed: float, slopes=SLOPES, path_slope: float = PATH_SLOPE, side: float = 1.0,
                         grade_deg: float = 0.0, drive: str = "auto", sim_time: float = 1.0) -> LayoutSlopeSection:
    """:func:`slope_section` for any wheel layout, forward or in reverse: the layout model's held line at each
    slope (:func:`stability.study.layout_slope.layout_equilibrium`) and its uncorrected release
    (:func:`stability.study.layout_slope.layout_uncorrected_path`).

    Parameters
    ----------
    layout : Layout
    speed : float
        Speed along the path, m/s (negative: reverse).
    slopes : sequence of float
        Cross slope magnitudes, deg (>= 0).
    path_slope : float
        Magnitude of the uncorrected path's slope, deg; the largest accepted slope below it if refused.
    side : float
        +1: the slopes fall to the right; -1: to the left.
    grade_deg : float
        Grade, deg (uphill +).
    drive : {"auto", "handrim", "motor"}
        As :func:`stability.study.layout_slope_report.layout_drive_kind`.
    sim_time : float
        Report time of the uncorrected run, s.

    Returns
    -------
    LayoutSlopeSection
    """
    from stability.study.layout_slope import layout_equilibrium, layout_uncorrected_path
    from stability.study.layout_slope_report import layout_drive_kind, layout_drive_report

    kind = layout_drive_kind(layout, drive)
    ok, eqs, refused = [], [], []
    for phi in slopes:
        try:
            eqs.append(layout_equilibrium(layout, side * float(phi), speed, grade_deg))
        except ValueError as exc:
            refused.append((float(phi), str(exc)))
            continue
        ok.append(float(phi))
    reports = [layout_drive_report(e, kind) for e in eqs]
    fr = np.array([magnitude_band(e.friction_range_N_m) for e in eqs]).reshape(-1, 2)
    curve = HoldingCurve(layout.name, np.array(ok), np.array([abs(e.holding_moment_N_m) for e in eqs]), fr[:, 0],
                         fr[:, 1], np.array([difference_of(layout_drive_report(e, "handrim"))[0] for e in eqs]))
    p_path = max((p for p in ok if 0 < p <= path_slope), default=None)
    path, why = None, None
    if p_path is not None:
        try:
            path = layout_uncorrected_path(layout, eqs[ok.index(p_path)], sim_time)
        except ValueError as exc:
            p_path, why = None, str(exc)
    return LayoutSlopeSection(layout.name, float(speed), float(side), curve, kind,
                              np.array([difference_of(r)[0] for r in reports]),
                              tuple(r["harder_side"] for r in reports), tuple(refused), path,
                              float(p_path) if p_path is not None else math.nan, why)


def slope_section(chair: Chair, speed: float = REFERENCE_SPEED, slopes=SLOPES,
                  path_slope: float = PATH_SLOPE) -> SlopeSection:
    """Solve the section's equilibria; slopes the analysis refuses are listed with the reason, not extrapolated.

    Parameters
    ----------
    chair : Chair
    speed : float
        Speed along the path, m/s (default the reference speed).
    slopes : sequence of float
        Cross slopes, deg (>= 0, falling to the right).
    path_slope : float
        Cross slope of the uncorrected path, deg; the largest accepted slope below it if refused.

    Returns
    -------
    SlopeSection
    """
    kind = drive_kind(chair)
    ok, eqs, refused = [], [], []
    for phi in slopes:
        try:
            e = solve(chair, float(phi), speed)
        except ValueError as exc:
            refused.append((float(phi), str(exc)))
            continue
        ok.append(float(phi))
        eqs.append(e)
    sides = tuple(drive_report(chair, e, kind)["harder_side"] for e in eqs)
    fr = np.array([magnitude_band(e.friction_range) for e in eqs]).reshape(-1, 2)
    curve = HoldingCurve(chair.name, np.array(ok), np.array([abs(e.holding_moment) for e in eqs]),
                         fr[:, 0], fr[:, 1], np.array([_difference(chair, e, "handrim")[0] for e in eqs]))
    diffs = [_difference(chair, e, kind) for e in eqs]
    one = next((e for p, e in zip(ok, eqs, strict=True) if p == 1.0), None)
    p_path = max((p for p in ok if 0 < p <= path_slope), default=None)
    path = None
    if p_path is not None:
        try:
            path = uncorrected_path(chair, eqs[ok.index(p_path)])
        except ValueError:        # viscous pin damping: the simulator has none, so no path
            p_path = None
    return SlopeSection(
        chair.name, float(speed), curve, kind, np.array([d[0] for d in diffs]),
        tuple(d[1] for d in diffs) if kind == "motor" else (), sides, tuple(refused),
        None if one is None else abs(one.holding_moment),
        abs(holding_moment_closed_form(chair, Plane(1.0, 0.0))),
        chair.m * abs(chair.x_main), path, float(p_path) if p_path is not None else math.nan, float(chair.g))
