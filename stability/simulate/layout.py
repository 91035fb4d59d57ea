"""Nonlinear simulation of a chair with any wheel layout, forward and in reverse.

:func:`simulate_layout` runs a :class:`~stability.layout.model.Layout` (any generated shape: two fixed wheels and
one to four casters) through the compiled layout kernel (:mod:`stability.simulate.layout_kernel`): program
WCHAIR's fixed-step scheme, the exact equations of the layout (``derivations/layout.py``), each wheel's tire
through the thesis engine's tire law at its normal load, the loads from the layout's statics with the
quasi-static load transfer of the tire forces (:func:`stability.layout.statics.load_rule`), and each caster's pin
under the run's friction law (``run.friction_law``: WCHAIR's kinetic law or stick-slip; ``run.casters="locked"``
holds them) plus its viscous part (``Caster.pin_damping``).  The run's push, step, horizon, stop rule and tire
range policy are the :class:`~stability.settings.run.RunSpec`'s, applied as the thesis engine applies them.

A negative speed (or ``run.reverse``) drives backwards.  Each caster starts at its own angle
(``caster_angles_deg``; by default ``run.eta0_deg`` for the casters on the left, ``y < 0``, and ``run.beta0_deg``
on the right): 0 deg trails for driving forwards, 180 deg trails for reversing, 90 deg points the wheel to the
right (the cases of Guo et al. 2003).

Rolling resistance (each wheel's ``rolling_scale``, its tire's rolling data), the camber thrust of the fixed
wheels (``camber_deg``, tops toward the centre line) and a plane (``run.cross_slope_deg``, ``run.grade_deg``:
each body's in-plane weight from the generated equations, the loads under the normal weight) are the thesis
engine's, applied as it applies them to the short form, and so is each fixed wheel's angle (``angle_deg``, toe:
its velocity turned into its frame for the slip, its forces turned back).  Not modelled here: the thesis's
lagged-yaw variant,
the adaptive scheme; the normal loads take the weight at C (the c.g. with the casters trailing forward) as in the
thesis engine, not at the system's c.g. with the casters swivelled.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from stability import tires as _tires
from stability.layout.model import Layout, check_layout
from stability.layout.statics import load_rule
from stability.models.layout import nonlinear as _gn
from stability.models.layout import shape_index
from stability.runtime.files import atomic_write_text
from stability.settings.bounds import SIGNED_SPEED
from stability.settings.run import RunSpec
from stability.simulate.first_use import load_kernel
from stability.simulate.options import LOAD_LIMIT_N, SLIP_LIMIT_DEG, WARNING_LIMIT, make_options, n_steps
from stability.simulate.packing import _rolling_slot, _tire_slot, policy_code, slope_slots

__all__ = ["LayoutRun", "simulate_layout", "simulate_layout_runs", "layout_state_order", "ENDINGS", "parameter_vector",
           "tire_slots", "check_layout_run"]

#: Why a run ends, by the kernel's status code.
ENDINGS = {0.0: "horizon", 1.0: "slip warnings", 2.0: "load warnings", 3.0: "non-finite"}


@dataclass(frozen=True, eq=False)
class LayoutRun:
    """One simulated run of a layout (arrays read-only).

    Attributes
    ----------
    layout : str
    speed_m_s : float
        Initial forward speed, m/s (negative: reverse).
    t_s : ndarray
        Times of the rows, s.
    heading_rad, yaw_rate_rad_s : ndarray
        Heading (positive clockwise seen from above: to the right) and its rate.
    x_m, y_m : ndarray
        Path of the c.g. in the ground frame (x along the initial heading, y to its right), m.
    u_m_s, v_m_s : ndarray
        Body-axis velocities, m/s.
    caster_angle_rad, caster_rate_rad_s : ndarray
        Shape ``(casters, rows)``: swivel angles from the body's forward axis (0 trailing for forward driving) and
        their rates.
    ended : str
        Why the run ended: ``"horizon"``, ``"slip warnings"`` or ``"load warnings"`` (program WCHAIR's eleventh
        warning of a kind, with ``run.stop_on_warnings``), ``"non-finite"``.
    end_time_s : float
        When, s.
    warnings : dict
        ``slip``, ``load``, ``lift_off``: count, first time (s), largest value (deg or N).
    settings : dict
        The run's settings (:meth:`RunSpec.to_dict` keys) and ``caster_angles_deg``.
    yaw_moment_N_m : ndarray
        The controller's commanded yaw moment at the rows (saturated, before the motor lag), N m (empty without a
        controller).
    """

    layout: str
    speed_m_s: float
    t_s: np.ndarray
    heading_rad: np.ndarray
    yaw_rate_rad_s: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    u_m_s: np.ndarray
    v_m_s: np.ndarray
    caster_angle_rad: np.ndarray
    caster_rate_rad_s: np.ndarray
    ended: str
    end_time_s: float
    warnings: dict = field(default_factory=dict)
    settings: dict = field(default_factory=dict)
    yaw_moment_N_m: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def heading_deg(self) -> np.ndarray:
        """Heading, deg."""
        return np.degrees(self.heading_rad)

    @property
    def final_heading_deg(self) -> float:
        """Heading at the last row, deg."""
        return float(np.degrees(self.heading_rad[-1]))

    def heading_at(self, time_s: float) -> float:
        """Heading at ``time_s`` (linear between rows), deg."""
        return float(np.degrees(np.interp(time_s, self.t_s, self.heading_rad)))

    def summary(self) -> str:
        """The run in a few lines: speed and direction, how it ended, the heading and path at the end, the casters."""
        direction = "backwards" if self.speed_m_s < 0 else "forwards"
        start = ", ".join(f"{a:g}" for a in self.settings.get("caster_angles_deg", []))
        end = ", ".join(f"{np.degrees(a[-1]):.1f}" for a in self.caster_angle_rad)
        why = {"horizon": "ran to the horizon", "slip warnings": "stopped at the eleventh slip warning (a tire "
               "beyond its data: give --no-stop-on-warnings to run on with the fits clamped)",
               "load warnings": "stopped at the eleventh load warning (a tire beyond its data)"}.get(self.ended,
                                                                                                  self.ended)
        cross, grade = self.settings.get("cross_slope_deg", 0.0), self.settings.get("grade_deg", 0.0)
        plane = f" on a cross slope of {cross:g} deg and a grade of {grade:g} deg" if cross or grade else ""
        return "\n".join([
            f"{self.layout}: {abs(self.speed_m_s):g} m/s {direction}{plane}, casters starting at {start} deg "
            "(0: trailing for forward driving, 180: for reversing); layout model, wchair scheme",
            f"  {why} at t = {self.end_time_s:.3f} s",
            f"  heading {self.final_heading_deg:+.2f} deg (peak |heading| {np.abs(self.heading_deg).max():.2f} deg), "
            f"lateral offset {self.y_m[-1]:+.3f} m after {abs(self.x_m[-1]):.2f} m of travel",
            f"  caster angles at the end: {end} deg",
            "  slip warnings {slip}, load warnings {load}, lift-off {lift}".format(
                slip=self.warnings["slip"]["count"], load=self.warnings["load"]["count"],
                lift=self.warnings["lift_off"]["count"])])

    def csv_columns(self, caster_labels: Sequence[str]) -> tuple[str, ...]:
        """The CSV's column names: the short form's (:data:`stability.simulate.results.COLUMNS`) for the body, then
        ``delta_<label>``, ``delta_dot_<label>`` per caster, ``<label>`` the layout's caster label
        (:attr:`stability.layout.Layout.caster_labels`) in snake case, e.g. ``delta_caster_1_front_left``.

        Parameters
        ----------
        caster_labels : sequence of str
            One per caster, in order.

        Returns
        -------
        tuple of str
        """
        if len(caster_labels) != len(self.caster_angle_rad):
            raise ValueError(f"caster_labels={list(caster_labels)!r} is invalid; valid: {len(self.caster_angle_rad)} "
                             "labels (one per caster)")
        keys = ["_".join("".join(ch if ch.isalnum() else " " for ch in lab.lower()).split()) for lab in caster_labels]
        return ("t", "x", "y", "heading", "yaw_rate", "u", "v") + tuple(
            f"{kind}_{key}" for key in keys for kind in ("delta", "delta_dot"))

    def to_csv(self, path: str | os.PathLike[str], caster_labels: Sequence[str]) -> Path:
        """Write the time histories to a CSV file atomically, in the short form's convention.

        ``#`` comment lines (layout, speed, settings, warnings, units) precede the header row
        (:meth:`csv_columns`); every column is in SI units (s, m, rad, m/s, rad/s).

        Parameters
        ----------
        path : path-like
        caster_labels : sequence of str
            The layout's :attr:`~stability.layout.Layout.caster_labels`.

        Returns
        -------
        pathlib.Path
        """
        names = self.csv_columns(caster_labels)
        body = [self.t_s, self.x_m, self.y_m, self.heading_rad, self.yaw_rate_rad_s, self.u_m_s, self.v_m_s]
        for a, r in zip(self.caster_angle_rad, self.caster_rate_rad_s, strict=True):
            body += [a, r]
        meta = [f"# stability.simulate: layout={self.layout} speed={self.speed_m_s!r} m/s model=exact scheme=wchair",
                "# settings: " + json.dumps(self.settings, sort_keys=True),
                "# warnings: " + json.dumps(self.warnings, sort_keys=True) + f" ended={self.ended}"
                f" end_time_s={self.end_time_s!r}",
                "# units: s, m, rad, m/s, rad/s; delta_*: caster swivel angle from the body's forward axis (0: "
                "trailing for forward driving, pi: for reversing), casters " + "; ".join(caster_labels)]
        rows = [",".join(repr(float(x)) for x in row) for row in np.column_stack(body)]
        return atomic_write_text(path, "\n".join(meta + [",".join(names)] + rows) + "\n")

    def to_mapping(self) -> dict:
        """JSON-ready summary (unit last): the final heading, lateral offset and caster angles, the ending."""
        return {"layout": self.layout, "speed_m_s": self.speed_m_s, "ended": self.ended,
                "end_time_s": self.end_time_s, "final_heading_deg": self.final_heading_deg,
                "final_lateral_offset_m": float(self.y_m[-1]),
                "final_caster_angles_deg": [float(np.degrees(a[-1])) for a in self.caster_angle_rad],
                "warnings": self.warnings, "settings": self.settings}


def _check_run(layout: Any, speed: Any, run: RunSpec | None) -> tuple[Layout, float, RunSpec]:
    check_layout(layout)
    if run is None:
        run = RunSpec()
    elif not isinstance(run, RunSpec):
        raise TypeError(f"run={run!r} is invalid; expected a stability.settings.run.RunSpec")
    if speed is None:
        signed = -run.speed if run.reverse else run.speed
    else:
        if isinstance(speed, bool) or not isinstance(speed, (int, float, np.floating, np.integer)):
            raise TypeError(f"speed={speed!r} is invalid; expected a number (m/s, negative: reverse)")
        signed = float(speed)
        if not SIGNED_SPEED.holds(signed):
            raise ValueError(f"speed={speed!r} is invalid; valid range: {SIGNED_SPEED.text('speed')} (negative: "
                             "reverse)")
        run = run.replace(speed=abs(signed), reverse=signed < 0)
    check_layout_run(run)
    return layout, signed, run


def check_layout_run(run: RunSpec, level_only: bool = False) -> None:
    """Refuse run settings the layout simulator does not have (another scheme or model).

    Parameters
    ----------
    run : RunSpec
    level_only : bool
        Refuse a slope too (a study defined on level ground: the critical impulse, whose push must be what turns
        the chair).

    Raises
    ------
    ValueError
        Naming the setting, its value and the valid values.
    """
    for name, ok, valid in (("scheme", run.scheme == "wchair", "'wchair'"), ("model", run.model == "exact", "'exact'")):
        if not ok:
            raise ValueError(f"{name}={getattr(run, name)!r} is invalid for a layout; valid values: {valid} (the "
                             "layout's equations are the exact model's, stepped by the fixed-step scheme)")
    if level_only and run.on_slope:
        raise ValueError(f"cross_slope_deg={run.cross_slope_deg:g}, grade_deg={run.grade_deg:g} is invalid here; "
                         "valid: level ground (0, 0) (on a slope the chair turns without a push)")


def _caster_angles(layout: Layout, run: RunSpec, caster_angles_deg: Sequence[float] | None) -> np.ndarray:
    nc = len(layout.casters)
    if caster_angles_deg is None:
        return np.radians([run.eta0_deg if c.y < 0 else run.beta0_deg for c in layout.casters])
    a = np.asarray(caster_angles_deg, dtype=float).reshape(-1)
    if a.shape != (nc,) or not np.all(np.abs(a) <= 180.0):
        raise ValueError(f"caster_angles_deg={caster_angles_deg!r} is invalid; valid: {nc} angles (one per caster), "
                         "each -180 to 180 deg")
    return np.radians(a)


def parameter_vector(layout: Layout) -> np.ndarray:
    """The generated nonlinear equations' parameter vector ``p`` of a layout (their ``PARAMETERS`` order, SI).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    ndarray
    """
    values = {"m": layout.m, "i_z": layout.i_z}
    for j, w in enumerate(layout.wheels):
        values.update({f"x_w_{j}": w.x, f"y_w_{j}": w.y})
    for k, c in enumerate(layout.casters):
        values.update({f"x_p_{k}": c.x, f"y_p_{k}": c.y, f"trail_{k}": c.trail, f"l_{k}": c.l, f"m_c_{k}": c.m_c,
                       f"i_zp_{k}": c.i_zp})
    return np.array([values[n] for n in _gn.PARAMETERS[layout.shape]], dtype=float)


def tire_slots(layout: Layout) -> tuple[np.ndarray, ...]:
    """The kernel's tire arrays ``(TK, TS, TL, LIM, CHK, RK, RC, RS, CAM)``.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    tuple of ndarray
        The tire slots, one per contact (fixed wheels, then casters), then each fixed wheel's camber tire
        (MECHAN's: the unscaled tire at the camber angle truncated to whole degrees); the range check per
        contact; the rolling slots per contact; per fixed wheel ``(camber deg, side sign x f_c, cos a, sin a)``
        (the thrust points to the side the wheel's top leans; ``a`` the wheel's angle, its toe).
    """
    specs = [(w.tire, w.lateral_scale, w.rolling_scale) for w in layout.wheels]
    specs += [(c.tire, c.lateral_scale, c.rolling_scale) for c in layout.casters]
    n, nw = len(specs), len(layout.wheels)
    TK, TS, TL = np.zeros(n + nw, dtype=np.int64), np.zeros((n + nw, 6, 8)), np.ones(n + nw)
    LIM, CHK = np.full((n + nw, 2), math.inf), np.zeros(n, dtype=np.bool_)
    RK, RC, RS = np.zeros(n, dtype=np.int64), np.zeros((n, 3)), np.zeros(n)
    CAM = np.zeros((nw, 4))
    for j, w in enumerate(layout.wheels):
        CAM[j, 2:] = math.cos(math.radians(w.angle_deg)), math.sin(math.radians(w.angle_deg))
    for i, (spec, scale, rolling) in enumerate(specs):
        tire = _tires.get(spec).scaled(lateral=scale, rolling=rolling)
        TK[i], TS[i], TL[i], LIM[i] = _tire_slot(tire)
        CHK[i] = isinstance(tire, _tires.Tire)
        RK[i], RC[i], RS[i] = _rolling_slot(tire, rolling != 0)
    for j, w in enumerate(layout.wheels):
        cam_deg = float(math.trunc(w.camber_deg))
        if cam_deg == 0.0:
            continue
        cam_tire = _tires.get(w.tire)
        TK[n + j], TS[n + j], TL[n + j], LIM[n + j] = _tire_slot(cam_tire)
        fc = cam_tire.camber_coefficient if w.camber_coefficient is None else float(w.camber_coefficient)
        CAM[j, :2] = cam_deg, (1.0 if w.y < 0 else -1.0) * fc
    return TK, TS, TL, LIM, CHK, RK, RC, RS, CAM


def layout_state_order(layout: Layout) -> tuple[str, ...]:
    """The state a layout's sampled controller measures (:class:`stability.simulate.controller.SampledController`'s
    ``state_names``): ``x, y, heading, u, v, yaw_rate``, then each caster's ``delta_k, delta_d_k`` (k from 0; the
    swivel angle from the body's forward axis, rad, and its rate).

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    tuple of str
    """
    return ("x", "y", "heading", "u", "v", "yaw_rate") + tuple(
        n for k in range(len(layout.casters)) for n in (f"delta_{k}", f"delta_d_{k}"))


def simulate_layout(layout: Layout, speed: float | None = None, run: RunSpec | None = None, *,
                    caster_angles_deg: Sequence[float] | None = None, controller: Any = None,
                    motor_lag_s: float = 0.0) -> LayoutRun:
    """Simulate one run of a layout disturbed from straight motion by the run's push.

    Parameters
    ----------
    layout : Layout
        Any generated shape (:func:`stability.models.layout.supported_shapes`).
    speed : float, optional
        Initial forward speed, m/s; negative drives backwards.  Default ``run.speed`` (backwards with
        ``run.reverse``).
    run : RunSpec, optional
        Push, horizon, step (``"auto"``: 1 ms), pin-friction law, casters free or locked, tire range policy, stop
        rule, sampling, the plane (cross slope falling to the right +, grade uphill +; the chair starts headed
        along the path) (default ``RunSpec()``).  The scheme must be ``"wchair"``, the model ``"exact"``.
    caster_angles_deg : sequence of float, optional
        Initial swivel angle of each caster, deg (0: trailing for forward driving, 180: for reversing); default
        ``run.eta0_deg`` on the left (``y < 0``), ``run.beta0_deg`` on the right.
    controller : stability.simulate.controller.SampledController, optional
        A sampled yaw-moment controller on the body (its ``state_names`` :func:`layout_state_order`); its command
        (saturated, before the motor lag) is the run's ``yaw_moment_N_m``.
    motor_lag_s : float
        First-order lag between the controller's command and the applied moment, s (>= 0; exact over each step).

    Returns
    -------
    LayoutRun

    Raises
    ------
    ValueError
        A bad argument (named, with its value and the valid range), a shape that is not generated, or a layout
        with fewer than three contacts on the ground.
    """
    return _runs(layout, [speed], run, [caster_angles_deg], controller, motor_lag_s)[0]


def simulate_layout_runs(layout: Layout, speeds: Sequence[float], run: RunSpec | None = None, *,
                         caster_angles_deg: Sequence[Sequence[float] | None] | None = None) -> list[LayoutRun]:
    """Runs of one layout at several speeds under one run's settings, stepped to their ends in one kernel call.

    Each run is :func:`simulate_layout`'s at its speed, bit for bit: the kernel advances every run of a batch on its
    own (:func:`stability.simulate.layout_kernel.step_layouts`); only the per-call preparation is shared (the
    layout's parameter vector and tire slots, the run's configuration row, which do not depend on the speed).

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        Initial forward speed of each run, m/s (negative: reverse).
    run : RunSpec, optional
        As :func:`simulate_layout`'s (one for all runs).
    caster_angles_deg : sequence, optional
        Each run's initial swivel angles, deg (an entry None: :func:`simulate_layout`'s default).

    Returns
    -------
    list of LayoutRun
        In the order of ``speeds``.

    Raises
    ------
    ValueError, FloatingPointError
        As :func:`simulate_layout` (the first run in order that leaves the finite numbers is named).
    """
    angles = [None] * len(speeds) if caster_angles_deg is None else list(caster_angles_deg)
    if len(angles) != len(speeds) or not len(speeds):
        raise ValueError(f"speeds has {len(speeds)} entries and caster_angles_deg {len(angles)}, which is invalid; "
                         "valid: at least one speed, one row of angles per speed")
    return _runs(layout, list(speeds), run, angles, None, 0.0)


def _runs(layout: Layout, speeds: list, run: RunSpec | None, angles: list, controller: Any,
          motor_lag_s: float) -> list[LayoutRun]:
    """:func:`simulate_layout` at each of ``speeds`` (with each run's ``angles``), one kernel call for all."""
    checked = [_check_run(layout, u, run) for u in speeds]
    layout = checked[0][0]
    deltas = [_caster_angles(layout, r, a) for (_, _, r), a in zip(checked, angles, strict=True)]
    # the configuration row and the layout's arrays do not depend on the speed (make_options reads none)
    cfg, nrec, consts = _kernel_inputs(layout, checked[0][2], motor_lag_s)
    ctl = _controller_arrays(layout, controller)
    from stability.simulate import layout_kernel as k  # numba loads on first use

    nc, R = len(layout.casters), len(speeds)
    # one run is a batch of one, stepped to its end in one call: the batch's compiled step, not a second entry
    # point that numba would compile (and optimise the whole step in) again
    states = np.array([k.initial_state(s, r.lateral_velocity, d, ctl[3].shape[0])
                       for (_, s, r), d in zip(checked, deltas, strict=True)])
    recs = np.full((R, k.NREC + 2 * nc, nrec), np.nan)
    statuses, warns, mzrecs = np.zeros((R, 2)), np.zeros((R, 3, 3)), np.zeros((R, nrec))
    args = (0, int(cfg[1]), *k.arguments(cfg, consts, states, recs, statuses, warns, ctl, mzrecs))
    load_kernel(k.step_layouts, args, "layout")
    k.step_layouts(*args)
    out = []
    for i, ((_, signed, r), delta0) in enumerate(zip(checked, deltas, strict=True)):
        m, status = int(states[i, k.S_NREC]), statuses[i]
        if status[0] == k.STOPPED_NONFINITE:
            raise FloatingPointError(f"the simulation of layout {layout.name!r} at {signed:g} m/s left the finite "
                                     f"numbers at t = {status[1]:g} s")
        settings = dict(r.to_dict(), caster_angles_deg=[float(x) for x in np.degrees(delta0)], dt_s=float(cfg[0]))
        if controller is not None:
            settings.update(controller=controller.name, motor_lag_s=float(motor_lag_s))
        out.append(_layout_run(layout, signed, recs[i], m, status, warns[i], settings,
                               mzrecs[i] if controller is not None else None, int(cfg[2]), float(cfg[0])))
    return out


def _kernel_inputs(layout: Layout, run: RunSpec, motor_lag_s: float, batch: bool = False
                   ) -> tuple[np.ndarray, int, tuple]:
    """The kernel's configuration row, the rows it records (a batch's every 0.01 s unless ``run.sample``), and its
    layout arguments (``p`` to ``cpin``)."""
    opts = make_options(run, batch=batch)
    steps = n_steps(opts)
    rule = load_rule(layout)
    nw, nc = layout.shape
    cfg = np.array([opts.dt, steps, opts.stride, opts.impulse_duration, opts.impulse_force, opts.tire_impulse,
                    opts.pin_mode, float(opts.stop_on_warnings), policy_code(opts), SLIP_LIMIT_DEG, LOAD_LIMIT_N,
                    WARNING_LIMIT, shape_index(layout.shape), layout.m * layout.g, layout.h, rule.mode,
                    *slope_slots(opts), layout.g, _check_lag(motor_lag_s)], dtype=float)
    mf = np.array([c.pin_friction for c in layout.casters], dtype=float)
    cpin = np.array([c.pin_damping for c in layout.casters], dtype=float)
    consts = (parameter_vector(layout), nw, nc, *tire_slots(layout), rule.stiffness, rule.line, rule.roll_share, mf,
              cpin)
    return cfg, (steps - 1) // opts.stride + 1, consts


def _layout_run(layout: Layout, signed: float, rec: np.ndarray, m: int, status: np.ndarray, warn: np.ndarray,
                settings: dict, mzrec: np.ndarray | None, stride: int, dt: float) -> LayoutRun:
    """A :class:`LayoutRun` of the kernel's arrays (``m`` rows recorded, every ``stride`` steps of ``dt`` s)."""
    from stability.simulate import layout_kernel as k

    rec = rec[:, :m].copy()
    rec.flags.writeable = False
    t = np.arange(m) * stride * dt
    t.flags.writeable = False
    end = float(status[1]) if status[0] else float(t[-1])
    w = {kind: {"count": int(warn[j, 0]), "first_time_s": None if warn[j, 0] == 0 else float(warn[j, 1]),
                "max": None if warn[j, 0] == 0 else float(warn[j, 2])}
         for j, kind in enumerate(("slip", "load", "lift_off"))}
    mz = mzrec[:m].copy() if mzrec is not None else np.zeros(0)
    mz.flags.writeable = False
    return LayoutRun(layout.name, signed, t, rec[2], rec[3], rec[0], rec[1], rec[4], rec[5], rec[k.NREC::2],
                     rec[k.NREC + 1::2], ENDINGS[float(status[0])], end, w, settings, mz)


def _check_lag(motor_lag_s: float) -> float:
    lag = float(motor_lag_s)
    if not (math.isfinite(lag) and 0.0 <= lag <= 1.0):
        raise ValueError(f"motor_lag_s={motor_lag_s!r} is invalid; valid range: 0 to 1 s")
    return lag


def _controller_arrays(layout: Layout, controller: Any) -> tuple:
    """The kernel's controller arrays (the "no controller" ones for None)."""
    from stability.simulate.controller import SampledController

    if controller is None:
        return SampledController.none().arrays()
    order = layout_state_order(layout)
    if tuple(controller.state_names) != order:
        raise ValueError(f"controller state_names={tuple(controller.state_names)!r} is invalid for layout "
                         f"{layout.name!r}; valid: {order!r} (stability.simulate.layout.layout_state_order)")
    return controller.arrays()
