"""The motor assist of any wheel layout, forward and in reverse: plant, LQR, Kalman filter, margins, safe top speed.

The short form's assist (:mod:`.plant`, :mod:`.design`, :mod:`.digital`, :mod:`.top_speed`) for a chair given as
a list of wheels (:class:`stability.layout.Layout`): the plant is the layout's linear model
(:mod:`stability.layout.linear`: ``v, r`` and each caster's angle and rate; a negative speed drives backwards with
the casters trailing at 180 deg) augmented with the heading and the motor lag; the differential torque ``tau``
per drive wheel gives the yaw moment ``Mz = tau w / r`` with ``w`` the lateral distance between the two drive
wheels (:func:`stability.study.layout_slope.drive_wheels`) and ``r`` their radius.  The LQR weights are Bryson's
(:class:`.weights.Weights`), the gyro design's estimator the same Kalman filter on the chair's states, the margins
those of the continuous and the sampled loop (:func:`.digital.margin_pair`), and the safe top speed the highest
design speed at which the sampled loop's margins hold there and below (:func:`.top_speed.top_speed` with the
margins, with ``check`` the torque (the short form's: the peak torque per drive wheel for the reference push, the
reference turn and a full joystick turn at every design speed, :func:`.driving.torque_requirement` and
:func:`.top_speed.full_turn_peaks` run in the layout simulator, within the motor and traction limits) and, with
``faults``, every single sensor fault safe:
:func:`.faults.fault_runs` on the direction's :func:`layout_schedule`, the firmware with its sensor monitor
stepped at every step of the layout simulator).
Forward and reverse each have their own grid and top speed.  With ``check`` the closed loop is simulated with the
layout simulator in each direction (:mod:`.layout_checks`: recovery after a push, the torque it takes, the decay
against the linear prediction).  See ``docs/assist.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import control
import numpy as np

from stability.assist.design import Design, _kalman, closed_loop_poles, realise
from stability.assist.digital import MarginPair, margin_pair
from stability.assist.plant import MOTOR_STATE, Plant
from stability.assist.schedule import Schedule
from stability.assist.top_speed import TopSpeed, top_speed
from stability.assist.weights import (
    DEFAULT_ESTIMATOR,
    DEFAULT_GYRO,
    DEFAULT_WEIGHTS,
    DESIGNS,
    EstimatorWeights,
    GyroSensor,
    Weights,
)
from stability.chair.power import DriveAxle, DriveTrain
from stability.layout.linear import input_matrices, state_matrices, states
from stability.layout.model import Layout
from stability.runtime.checks import check_choice, check_nonnegative
from stability.study.layout_slope import drive_wheels

__all__ = ["drive_lever", "drive_axle", "layout_plant", "layout_design", "LayoutSchedule", "layout_schedule",
           "LayoutAssistRow", "LayoutAssist", "layout_assist", "format_layout_assist", "LAYOUT_TORQUE_WORDS"]

#: What a layout's torque constraint counts (the words of its text and its top-speed page's caption).
LAYOUT_TORQUE_WORDS = ("the torque counts the peak per wheel of the reference push, the reference turn and a full "
                       "joystick turn at every design speed, as the short form's (layout simulator, noise-free, "
                       "torque limit; in reverse the same yaw-rate commands)")


def drive_lever(layout: Layout) -> float:
    """Lateral distance between the two drive wheels, m: the arm of the couple of their forces.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    float
    """
    left, right = drive_wheels(layout)
    return float(layout.wheels[right].y - layout.wheels[left].y)


def drive_axle(layout: Layout) -> DriveAxle:
    """The layout's drive wheels as the drive train reads them: ``d1``, ``d2`` the left and right wheels'
    distances from the centre line (``d1 + d2``: :func:`drive_lever`).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    DriveAxle
    """
    left, right = drive_wheels(layout)
    return DriveAxle(layout.name, -float(layout.wheels[left].y), float(layout.wheels[right].y))


def layout_plant(layout: Layout, speed: float, motor_time_constant: float = 0.0) -> Plant:
    """The layout's linear plant at a signed speed, augmented with the heading and, optionally, the motor lag.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s; negative: reverse (0.01 <= |speed| <= 20).
    motor_time_constant : float
        s, >= 0 (as :func:`stability.assist.plant.plant`).

    Returns
    -------
    Plant
        States: the layout's (:func:`stability.layout.linear.states`), ``psi``, and ``mz`` with a motor lag.
    """
    tau = check_nonnegative("motor_time_constant", motor_time_constant)
    A_c = state_matrices(layout, [speed])[0]
    Bm, Bf_c = (x[0] for x in input_matrices(layout, [speed]))
    nc = A_c.shape[0]
    n = nc + (2 if tau > 0 else 1)
    A, B, Bf = np.zeros((n, n)), np.zeros((n, 1)), np.zeros((n, 1))
    A[:nc, :nc] = A_c
    A[nc, 1] = 1.0                                      # psi_dot = r
    if tau > 0:
        A[:nc, nc + 1:nc + 2] = Bm
        A[nc + 1, nc + 1], B[nc + 1, 0] = -1.0 / tau, 1.0 / tau
    else:
        B[:nc] = Bm
    Bf[:nc] = Bf_c
    return Plant(float(speed), A, B, Bf, tau, chair_states=states(layout))


def layout_design(layout: Layout, speed: float, kind: str = "gyro", *, weights: Weights = DEFAULT_WEIGHTS,
                  drive: DriveTrain | None = None, gyro: GyroSensor = DEFAULT_GYRO,
                  estimator: EstimatorWeights = DEFAULT_ESTIMATOR) -> Design:
    """LQR design (and, for ``kind="gyro"``, its Kalman estimator) of a layout at one signed speed.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s (negative: reverse).
    kind : {"full-state", "gyro"}
    weights, drive, gyro, estimator
        As :func:`stability.assist.design.design`; the torque budget's yaw moment uses :func:`drive_lever`.

    Returns
    -------
    Design
    """
    check_choice("design", kind, DESIGNS)
    drive = drive or DriveTrain()
    lever = drive_lever(layout)
    p = layout_plant(layout, speed, drive.motor_time_constant)
    Q, R = weights.weight_matrices(p.states, p.n, weights.budget(drive) * lever / drive.wheel_radius)
    K = np.asarray(control.lqr(p.A, p.B, Q, R)[0], dtype=float).reshape(1, p.n)
    d = realise(kind, p, K, None if kind == "full-state" else _kalman(p, gyro, estimator))
    return replace(d, sample_time=1.0 / gyro.sample_rate_hz, wheel_radius=float(drive.wheel_radius),
                   track_width=lever)


@dataclass(frozen=True, eq=False)
class LayoutSchedule(Schedule):
    """A layout's gain schedule over one direction's grid: the short form's :class:`Schedule` (interpolation,
    firmware tables, margins of the tables) on the layout's linear model.

    ``speeds`` are signed and increasing (a reverse grid is negative, e.g. ``-3, -2, -1``); there is no
    standstill design (a layout's casters have no linear model at 0 m/s, where they swing round), so the end
    designs hold beyond the grid.  ``chair`` is the layout's :class:`~stability.chair.power.DriveAxle` (the
    name and the drive wheels' lever the drive train reads), ``model`` ``"exact"``.

    Attributes
    ----------
    chair : DriveAxle
        The layout's drive wheels and its name (``"... in reverse"`` for a reverse grid).
    kind : {"full-state", "gyro"}
    speeds : ndarray (N,)
        Signed, increasing design speeds, m/s.
    designs : tuple of Design
        :func:`layout_design` at each speed.
    drive, weights, gyro, estimator
        The design options.
    model : str
        ``"exact"`` (a layout's equations are derived from first principles only).
    standstill : None
        No standstill design.
    layout : Layout
    """

    layout: Layout | None = None

    def _check_speed(self, speed: float) -> float:
        u = float(speed)
        sign = math.copysign(1.0, float(self.speeds[0]))
        if not (math.isfinite(u) and u * sign > 0):
            raise ValueError(f"speed={speed!r} is invalid for this schedule; valid range: "
                             f"{'> 0' if sign > 0 else '< 0'} m/s (the direction of its grid)")
        return u

    def true_plant(self, speed: float) -> Plant:
        """The layout's linear plant at the signed ``speed`` (m/s) (:func:`layout_plant`).

        Parameters
        ----------
        speed : float

        Returns
        -------
        Plant
        """
        assert self.layout is not None
        return layout_plant(self.layout, speed, self.drive.motor_time_constant)


def layout_schedule(layout: Layout, speeds: Sequence[float], kind: str = "gyro", *,
                    weights: Weights = DEFAULT_WEIGHTS, drive: DriveTrain | None = None,
                    gyro: GyroSensor = DEFAULT_GYRO, estimator: EstimatorWeights = DEFAULT_ESTIMATOR
                    ) -> LayoutSchedule:
    """:func:`layout_design` at every speed of one direction's grid.

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        m/s, all of one sign (negative: reverse), 0.01 <= |U| <= 20; sorted here.
    kind, weights, drive, gyro, estimator
        As :func:`layout_design`.

    Returns
    -------
    LayoutSchedule
    """
    U = np.sort(np.asarray(speeds, dtype=float).reshape(-1))
    if U.size == 0 or not np.all(np.isfinite(U)) or np.any(np.abs(U) < 0.01) or np.any(np.abs(U) > 20.0) \
            or (U[0] < 0 < U[-1]) or np.any(np.diff(U) <= 0):
        raise ValueError(f"speeds={list(map(float, U))!r} is invalid for a schedule; valid range: distinct speeds "
                         "of one sign (one direction: a table over speed cannot pass 0 m/s, where the casters swing "
                         "round), each 0.01 <= |U| <= 20 m/s")
    drive = drive or DriveTrain()
    ds = tuple(layout_design(layout, float(u), kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator)
               for u in U)
    # the drive axle stands in for the short form's chair: the name (the titles': "... in reverse" for a reverse
    # grid) and the lever d1 + d2 the drive train reads
    axle = drive_axle(layout)
    if U[0] < 0:
        axle = replace(axle, name=f"{layout.name} in reverse")
    return LayoutSchedule(axle, kind, U, ds, drive, weights, gyro, estimator,  # type: ignore[arg-type]
                          "exact", None, layout)


@dataclass(frozen=True)
class LayoutAssistRow:
    """One design speed.

    Attributes
    ----------
    speed_m_s : float
        Signed design speed, m/s.
    open_loop_growth_1_s : float
        Largest real part of the chair's own eigenvalues (no assist), 1/s.
    closed_loop_growth_1_s : float
        Largest real part of the closed loop's eigenvalues (continuous), 1/s.
    wheel_torque_gains : dict
        The gain per drive wheel by state, N m per SI unit (``tau = -k x``).
    margin_pair : MarginPair
        Continuous and sampled margins.
    """

    speed_m_s: float
    open_loop_growth_1_s: float
    closed_loop_growth_1_s: float
    wheel_torque_gains: dict
    margin_pair: MarginPair

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        return {"speed_m_s": self.speed_m_s, "open_loop_growth_rate_1_s": self.open_loop_growth_1_s,
                "closed_loop_growth_rate_1_s": self.closed_loop_growth_1_s,
                "wheel_torque_gains": self.wheel_torque_gains, "margins": self.margin_pair.to_dict()}


@dataclass(frozen=True)
class _Grid:
    """What :func:`stability.assist.top_speed.top_speed` reads of a schedule: the gyro's rate and the drive."""

    gyro: GyroSensor
    drive: DriveTrain


@dataclass(frozen=True)
class _MarginRow:
    speed_m_s: float
    margin_pair: MarginPair


@dataclass(frozen=True)
class LayoutAssist:
    """The assist of a layout over a forward grid and, optionally, a reverse one.

    Attributes
    ----------
    layout : str
    kind : str
    forward, reverse : tuple of LayoutAssistRow
        Increasing ``|speed|`` (reverse rows have negative speeds; empty: not asked).
    forward_top, reverse_top : TopSpeed or None
        Safe top speed of each direction (speeds as magnitudes, m/s).
    lever_m, wheel_radius_m : float
        Drive-wheel lever and radius, m.
    forward_checks, reverse_checks : stability.assist.layout_checks.LayoutChecks or None
        The nonlinear checks of each direction (None: not asked or no rows).
    forward_faults, reverse_faults : tuple of stability.assist.faults.FaultRow or None
        The single sensor faults of each direction at every design speed (signed), counted in its safe top speed
        (None: not asked or no rows).
    schedules : tuple of LayoutSchedule or None
        The forward and reverse :func:`layout_schedule` the rows were read from (None: no rows); not compared, not
        in the mapping.
    """

    layout: str
    kind: str
    forward: tuple
    reverse: tuple
    forward_top: TopSpeed | None
    reverse_top: TopSpeed | None
    lever_m: float
    wheel_radius_m: float
    forward_checks: Any = None
    reverse_checks: Any = None
    forward_faults: Any = None
    reverse_faults: Any = None
    schedules: tuple = field(default=(None, None), repr=False, compare=False)

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        def top(t: TopSpeed | None) -> Any:
            return None if t is None else t.to_dict()

        return {"layout": self.layout, "design": self.kind, "drive_lever_m": self.lever_m,
                "wheel_radius_m": self.wheel_radius_m, "forward": [r.to_mapping() for r in self.forward],
                "reverse": [r.to_mapping() for r in self.reverse], "forward_top_speed": top(self.forward_top),
                "reverse_top_speed": top(self.reverse_top),
                "forward_checks": None if self.forward_checks is None else self.forward_checks.to_mapping(),
                "reverse_checks": None if self.reverse_checks is None else self.reverse_checks.to_mapping(),
                "forward_faults": None if self.forward_faults is None else [f.to_dict() for f in self.forward_faults],
                "reverse_faults": None if self.reverse_faults is None else [f.to_dict() for f in self.reverse_faults]}


def _rows(sched: LayoutSchedule | None, speeds: Sequence[float], faults: Sequence[Any] | None = None,
          torque: bool = False) -> tuple[tuple[LayoutAssistRow, ...], TopSpeed | None]:
    if sched is None or not speeds:
        return (), None
    by_speed = dict(zip((float(u) for u in sched.speeds), sched.designs, strict=True))
    rows = []
    for s in speeds:
        d = by_speed[float(s)]
        open_g = float(np.linalg.eigvals(d.plant.A6).real.max())
        closed = float(closed_loop_poles(d).real.max())
        gains = {k: v for k, v in d.gains_dict(per_wheel=True).items() if k != MOTOR_STATE}
        rows.append(LayoutAssistRow(float(s), open_g, closed, gains, margin_pair(d, d.sample_time)))
    torques, full = None, None
    if torque:      # the short form's torque rows and full joystick turns, in the layout simulator
        from stability.assist.commands import MAX_YAW_RATE, reference_command
        from stability.assist.driving import torque_requirement
        from stability.assist.top_speed import full_turn_peaks

        rows_t = torque_requirement(sched, tuple(speeds))
        # up to LATERAL_ACCELERATION / MAX_YAW_RATE the reference turn is the full joystick turn (the same
        # command_run: step, duration, filter): its peak is read, not simulated again
        same = {t.speed_m_s: t.turn_peak_N_m for t in rows_t if reference_command(abs(t.speed_m_s)) == MAX_YAW_RATE}
        rest = full_turn_peaks(sched, [u for u in speeds if u not in same])
        full = {abs(u): same[u] if u in same else rest[u] for u in speeds}
        torques = [replace(t, speed_m_s=abs(t.speed_m_s)) for t in rows_t]
    ts = top_speed(_Grid(sched.gyro, sched.drive), [_MarginRow(abs(r.speed_m_s), r.margin_pair) for r in rows],  # type: ignore[arg-type]
                   torques, None if faults is None else [replace(f, speed_m_s=abs(f.speed_m_s)) for f in faults], full)
    return tuple(rows), ts


def layout_assist(layout: Layout, speeds: Sequence[float], kind: str = "gyro", *, reverse: bool = False,
                  weights: Weights = DEFAULT_WEIGHTS, drive: DriveTrain | None = None, gyro: GyroSensor = DEFAULT_GYRO,
                  estimator: EstimatorWeights = DEFAULT_ESTIMATOR, check: bool = False, faults: bool = False,
                  seed: int = 0) -> LayoutAssist:
    """Designs, margins and the safe top speed of a layout's assist, forward and (optionally) in reverse.

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        Design speeds, m/s: positive ones make the forward grid, negative ones the reverse grid (each sorted by
        magnitude); 0.01 <= |speed| <= 20.
    kind : {"full-state", "gyro"}
    reverse : bool
        Also design in reverse at the negatives of the positive speeds.
    weights, drive, gyro, estimator
        As :func:`layout_design`.
    check : bool
        Also the nonlinear checks of each direction with the layout simulator
        (:func:`stability.assist.layout_checks.layout_checks` at :func:`~stability.assist.layout_checks.check_speeds`),
        and the torque constraint of each direction's safe top speed: the peak torque per drive wheel of the
        reference push, the reference turn and a full joystick turn at every design speed
        (:func:`stability.assist.driving.torque_requirement` and :func:`stability.assist.top_speed.full_turn_peaks`
        on the direction's :func:`layout_schedule`, in the layout simulator) within the motor and traction limits
        (the short form's rule, :func:`stability.assist.top_speed.top_speed`).
    faults : bool
        Also the single sensor faults at every design speed of each direction on level ground and the cross slope
        (:func:`stability.assist.faults.fault_runs` on the direction's :func:`layout_schedule`, in the layout
        simulator), counted in the direction's safe top speed; the gyro design only.
    seed : int
        Of the fault runs' gyro noise.

    Returns
    -------
    LayoutAssist
    """
    U = np.asarray(speeds, dtype=float).reshape(-1)
    if U.size == 0 or not np.all(np.isfinite(U)) or np.any(np.abs(U) < 0.01) or np.any(np.abs(U) > 20.0):
        raise ValueError(f"speeds={list(map(float, U))!r} is invalid; valid range: at least one speed, each "
                         "0.01 <= |U| <= 20 m/s (negative: reverse)")
    if faults and kind != "gyro":
        raise ValueError(f"faults=True with design={kind!r} is invalid; valid: design 'gyro' (the faults are those of "
                         "the gyro and wheel-speed sensors the gyro design's firmware reads)")
    drive = drive or DriveTrain()
    fwd = sorted(set(float(u) for u in U if u > 0))
    rev = sorted(set(float(u) for u in U if u < 0) | ({-u for u in fwd} if reverse else set()), key=abs)
    # one schedule per direction, read by the fault runs, the rows and top speed, and the checks
    scheds = [layout_schedule(layout, grid, kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator)
              if grid else None for grid in (fwd, rev)]
    bad: list[Any] = [None, None]
    if faults:
        from stability.assist.faults import fault_runs

        bad = [None if sc is None else tuple(fault_runs(sc, seed=seed)) for sc in scheds]
    f_rows, f_top = _rows(scheds[0], fwd, bad[0], check)
    r_rows, r_top = _rows(scheds[1], rev, bad[1], check)
    checks: list[Any] = [None, None]
    if check:
        from stability.assist.layout_checks import check_speeds, layout_checks

        for i, grid in enumerate((fwd, rev)):
            sc = scheds[i]
            if sc is not None:
                # a check speed on the grid has the schedule's design (the same layout_design call)
                on_grid = dict(zip((float(u) for u in sc.speeds), sc.designs, strict=True))
                designs = [on_grid[u] if u in on_grid else
                           layout_design(layout, u, kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator)
                           for u in check_speeds(grid)]
                checks[i] = layout_checks(layout, designs, drive)
    return LayoutAssist(layout.name, kind, f_rows, r_rows, f_top, r_top, drive_lever(layout),
                        float(drive.wheel_radius), checks[0], checks[1], bad[0], bad[1], tuple(scheds))


def format_layout_assist(a: LayoutAssist) -> str:
    """The command line's text: per speed the open and closed loop's growth rates, the heading and yaw-rate gains
    per wheel and the sampled margins, then each direction's safe top speed.

    Parameters
    ----------
    a : LayoutAssist

    Returns
    -------
    str
    """
    lines = [f"{a.layout}: motor assist ({a.kind} design), differential torque per drive wheel, drive wheels "
             f"{a.lever_m:g} m apart, radius {a.wheel_radius_m:g} m (layout model; reverse: casters trailing at "
             "180 deg)",
             f"{'U m/s':>7s} {'open 1/s':>9s} {'closed 1/s':>10s} {'k_psi N m/rad':>14s} {'k_r N m s/rad':>14s} "
             f"{'gain dB':>8s} {'phase deg':>9s} {'delay ms':>9s}"]

    def fmt(x: Any) -> str:
        return "inf" if x == "inf" or (isinstance(x, float) and math.isinf(x)) else f"{float(x):.3g}"

    from stability.assist.faults import format_faults

    for rows, top, what, chk, bad in ((a.forward, a.forward_top, "forward", a.forward_checks, a.forward_faults),
                                      (a.reverse, a.reverse_top, "reverse", a.reverse_checks, a.reverse_faults)):
        for r in rows:
            d = r.margin_pair.to_dict()["discrete"]
            lines.append(f"{r.speed_m_s:7.2f} {r.open_loop_growth_1_s:9.3f} {r.closed_loop_growth_1_s:10.3f} "
                         f"{r.wheel_torque_gains['psi']:14.4g} {r.wheel_torque_gains['r']:14.4g} "
                         f"{fmt(d['gain_db']):>8s} {fmt(d['phase_deg']):>9s} {fmt(d['delay_ms']):>9s}")
        if bad is not None:
            lines.append(f"{what}, " + format_faults(bad))
        if top is not None:
            words = top.sentence().split(" (not checked:")[0]
            done = ["the margins"] + [k for k, on in (("the torque (push and turns)", "torque" in top.checked),
                                                      ("the single sensor faults", bad is not None)) if on]
            off = [k for k, on in (("the torque: run without --no-check", "torque" not in top.checked),
                                   ("the single sensor faults: add --faults", bad is None)) if on]
            scope = " and ".join(done) + ("; not checked: " + "; ".join(off) if off else "")
            lines.append(f"{what}: {words} (from {scope})")
            if "torque" in top.checked:
                lines.append(f"{what}: {LAYOUT_TORQUE_WORDS}")
        if chk is not None:
            lines.append(f"{what}, nonlinear checks (layout simulator, the sampled controller compiled in, torque "
                         "limit, motor lag, noise-free; no --no-check):")
            lines += chk.lines()
    return "\n".join(lines)
