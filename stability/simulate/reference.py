"""The pure-numpy WCHAIR scheme over a batch of runs: the test reference of the compiled kernel.

Also the path of a batch with a Python ``yaw_moment(t, state)`` input, which
receives arrays over the active runs.  Step for step the scheme of
:mod:`.wchair` (see ``docs/simulator.md``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.models.full_width import tire_resultant, tire_yaw_moment
from stability.models.statics import normal_loads
from stability.runtime.progress import ProgressBar
from stability.simulate.options import (
    LOAD_LIMIT_N,
    SLIP_LIMIT_DEG,
    WARNING_LIMIT,
    Options,
    impulse_on,
    initial_velocities,
    n_steps,
)
from stability.simulate.physics import Physics, accelerations, held_accelerations, kinematics, loads, plane, tire_forces
from stability.simulate.pin_friction import rest_rates, stick_slip_runs
from stability.simulate.results import NCOLS, ChairState, SimulationResult

__all__ = ["wchair_batch"]


class _Warnings:
    """Per-run warning counters of the batch (count, first time, largest value by kind)."""

    def __init__(self, nrun: int):
        self.cnt = {k: np.zeros(nrun, dtype=int) for k in ("slip", "load", "lift_off")}
        self.first = {k: np.full(nrun, np.nan) for k in self.cnt}
        self.vmax = {k: np.full(nrun, np.nan) for k in self.cnt}

    def flag(self, kind: str, run: np.ndarray, mask: np.ndarray, t: float, values: np.ndarray) -> None:
        if not mask.any():
            return
        idx = run[mask]
        self.cnt[kind][idx] += 1
        new = idx[np.isnan(self.first[kind][idx])]
        self.first[kind][new] = t
        cur = self.vmax[kind][idx]
        val = values[mask]
        self.vmax[kind][idx] = np.where(np.isnan(cur) | (np.abs(val) > np.abs(cur)), val, cur)

    def of_run(self, i: int) -> dict[str, dict]:
        out = {}
        for kind, cnt in self.cnt.items():
            c = int(cnt[i])
            out[kind] = {"count": c, "first_time": None if c == 0 else float(self.first[kind][i]),
                         "max": None if c == 0 else float(self.vmax[kind][i])}
        return out


def _range_rules(K: Physics, S4: np.ndarray, N4: np.ndarray, run: np.ndarray, warns: _Warnings, stop: bool,
                 t: float) -> np.ndarray | None:
    """STATICS / MECHAN range rules of the active runs; the runs that stop here (or None)."""
    if K.check_all:
        nmax = N4.max(axis=0)
        smax = np.abs(S4).max(axis=0)
    else:   # tested tires only (one tire group: its per-wheel flags, as the kernel's CHK)
        mask = K.chk_mask if K.chk_mask is not None else np.array(K.chk, dtype=bool)[:, None]
        nmax = np.where(mask, N4, -np.inf).max(axis=0)
        smax = np.where(mask, np.abs(S4), 0.0).max(axis=0)
    over_load = nmax > LOAD_LIMIT_N
    nmin = N4.min(axis=0)
    under = nmin < 0.0
    over_slip = smax > SLIP_LIMIT_DEG
    if not (over_load.any() or under.any() or over_slip.any()):
        return None
    halt = np.zeros(run.size, dtype=bool)
    warns.flag("load", run, over_load, t, nmax)
    if stop:
        halt |= warns.cnt["load"][run] > WARNING_LIMIT
    warns.flag("lift_off", run, under & ~halt, t, nmin)
    warns.flag("slip", run, over_slip & ~halt, t, smax)
    if stop:
        halt |= warns.cnt["slip"][run] > WARNING_LIMIT
    return halt


class _State:
    """The active runs' state: velocities ``Sv`` = (UD, VD, THED, ED, BD), angles ``Sp`` = (THE, E, B) stacked
    (ITRATE is then a few operations on (5, n) and (3, n) arrays), X, Y, the lagged THEDD and FC1, FC2."""

    def __init__(self, speeds: np.ndarray, opts: Options, fcimp: Any):
        nrun = len(speeds)
        u0, v0 = initial_velocities(opts, 1.0)
        self.run = np.arange(nrun)
        self.Sv = np.zeros((5, nrun))
        self.Sv[0] = np.asarray(speeds, dtype=float) * u0
        self.Sv[1] = v0
        self.Sp = np.zeros((3, nrun))
        self.Sp[1], self.Sp[2] = opts.eta0, opts.beta0
        z = np.zeros(nrun)
        self.X, self.Y, self.THEDD, self.FC1, self.FC2 = z.copy(), z.copy(), z.copy(), z.copy(), z.copy()
        self.fcimp = fcimp

    def compact(self, keep: np.ndarray, per_run_force: bool) -> None:
        self.run = self.run[keep]
        self.X, self.Y, self.THEDD, self.FC1, self.FC2 = (a[keep] for a in (self.X, self.Y, self.THEDD, self.FC1,
                                                                            self.FC2))
        if per_run_force:
            self.fcimp = self.fcimp[keep]
        self.Sv, self.Sp = self.Sv[:, keep], self.Sp[:, keep]


def _step(K: Physics, s: _State, opts: Options, k: int, warns: _Warnings, stopped: np.ndarray, stop_time: np.ndarray,
          per_run_force: bool) -> tuple | None:
    """SLIP, STATICS, MECHAN, DYNAM of step ``k``: the record columns and accelerations, or None (all stopped)."""
    dt, _, locked, thesis, yaw_fn, stop, _, _ = opts.step_constants()
    t = k * dt
    Cp, Sn = np.cos(s.Sp), np.sin(s.Sp)            # heading, eta, beta at once
    UD, VD, THED, ED, BD = s.Sv
    V = np.array(kinematics(K, UD, VD, THED, Cp[1], Sn[1], Cp[2], Sn[2], ED, BD))   # (8, m): vx, vy per wheel
    S4 = np.arctan2(V[1::2], np.abs(V[0::2]))                                         # as the kernel and SLIP
    S4 *= 180.0 / math.pi
    if K.slope_trig is None:
        N4 = np.array(normal_loads(K.p, s.FC1, s.FC2, Cp[1], Sn[1], Cp[2], Sn[2]))    # (4, m)
    else:   # on a slope: gravity at each run's heading, loads with the normal weight
        G3 = np.array(np.broadcast_arrays(*plane(K, s.Sp[0])))
        N4 = np.array(loads(K, s.FC1, s.FC2, Cp[1], Sn[1], Cp[2], Sn[2], G3[2]))
    halt = _range_rules(K, S4, N4, s.run, warns, stop, t)
    if halt is not None and halt.any():
        gone = s.run[halt]
        stopped[gone] = True
        stop_time[gone] = t
        keep = np.flatnonzero(~halt)
        K.compact(keep)
        s.compact(keep, per_run_force)
        V, S4, N4, Cp, Sn = V[:, keep], S4[:, keep], N4[:, keep], Cp[:, keep], Sn[:, keep]
        if K.slope_trig is not None:
            G3 = G3[:, keep]
        if s.run.size == 0:
            return None
    UD, VD, THED, ED, BD = s.Sv
    THE, E, B = s.Sp
    ce, se, cb, sb = Cp[1], Sn[1], Cp[2], Sn[2]
    NA, NB, ND, NE = N4
    imp = impulse_on(opts, t)
    F = tire_forces(K, imp, tuple(V), tuple(S4), NA, NB, ND, NE, S4=S4, N4=N4)
    fc1, fc2 = tire_resultant(F, ce, se, cb, sb)
    fy_ext = s.fcimp if (imp and (per_run_force or s.fcimp != 0.0)) else 0.0
    if yaw_fn is None:
        mz: Any = 0.0
    else:
        st_ = ChairState(*(a.copy() for a in (s.X, s.Y, THE, UD, VD, THED, E, ED, B, BD, s.run)))
        mz = np.broadcast_to(np.asarray(yaw_fn(t, st_), dtype=float), s.run.shape)
    state = (UD, VD, THED, ce, se, cb, sb, ED, BD)
    rdc = s.THEDD if thesis else None
    grav = None if K.slope_trig is None else (G3[0], G3[1])
    if locked:
        zero = np.zeros(s.run.size)
        acc, MA, MB = held_accelerations(K, state, F, zero, zero, fy_ext, mz, True, True, rdc, grav)
    elif opts.pin_mode == 2.0:      # stick-slip: each run holds or frees its own casters
        acc, MA, MB = stick_slip_runs(K, state, F, fy_ext, mz, rdc, grav)
    else:
        MA = np.where(ED != 0.0, np.copysign(K.maf, -ED), 0.0)
        MB = np.where(BD != 0.0, np.copysign(K.mbf, -BD), 0.0)
        acc = accelerations(K, state, F, MA, MB, fy_ext, mz, rdc, grav)
    UDD, VDD, THEDD_new, EDD, BDD = acc
    if locked:
        EDD = BDD = np.zeros(s.run.size)
    cols = (t, s.X, s.Y, THE, THED, UD, VD, E, ED, B, BD, *F, NA, NB, ND, NE, *S4,
            tire_yaw_moment(K.p, F, ce, se, cb, sb), mz, THEDD_new, MA, MB)
    return cols, (UDD, VDD, THEDD_new, EDD, BDD), (fc1, fc2 + fy_ext), (Cp[0], Sn[0])


def _update(s: _State, acc: tuple, fc: tuple, heading_trig: tuple, dt: float, half_dt2: float,
            limits: tuple | None = None) -> None:
    """UPDATE / ITRATE: x += v dt + a dt^2/2 (global X, Y with the heading at the start of the step), v += a dt.

    ``limits``: the casters' friction limits (M_A, M_B), N m, under the stick-slip law (a swivel rate that
    would change sign within the step comes to rest: :func:`~stability.simulate.pin_friction.rest_rates`).
    """
    old = None if limits is None else s.Sv[3:5].copy()
    Acc = np.array(acc)
    s.THEDD = acc[2]          # (Acc is scaled in place below)
    s.FC1, s.FC2 = fc
    D = s.Sv * dt
    D += Acc * half_dt2
    cost, sint = heading_trig
    s.X = s.X + (D[0] * cost - D[1] * sint)
    s.Y = s.Y + (D[0] * sint + D[1] * cost)
    s.Sp += D[2:5]
    Acc *= dt
    s.Sv += Acc
    if old is not None and limits is not None:
        rest_rates(old[0], s.Sv[3], limits[0])
        rest_rates(old[1], s.Sv[4], limits[1])


def wchair_batch(chairs: list[Chair], speeds: np.ndarray, opts: Options, progress: bool,
                 bar: ProgressBar | None = None, forces: np.ndarray | None = None) -> list[SimulationResult]:
    """All runs stepped together; ``forces``: per-run impulse force (N) instead of ``opts.impulse_force``.

    The pure-numpy reference of program WCHAIR's scheme (Appendix C) for a
    batch: every step operates on arrays over the runs still active (a run
    stopped by the warning rule drops out).  Used for a Python
    ``yaw_moment`` input in a batch and inside
    :func:`~stability.simulate.reference_engine`.

    Pin friction follows ``opts.friction_law``: "kinetic" is WCHAIR's moment
    ``-M_f sign(swivel rate)``; "stick-slip" is the compiled kernel's law
    (:func:`~stability.simulate.pin_friction.stick_slip_runs`: each run
    holds a caster at rest while its holding moment is within the friction
    limit, and a rate that would change sign within a step comes to rest).

    Parameters
    ----------
    chairs : list of Chair
        One chair per run.
    speeds : ndarray
        Initial forward speeds, m/s (> 0), shape ``(len(chairs),)``.
    opts : Options
        Checked options with ``scheme="wchair"``.
    progress : bool
        Show a progress bar over the steps (when ``bar`` is None).
    bar : ProgressBar, optional
        A bar owned by the caller, advanced once per step instead.
    forces : ndarray, optional
        Per-run lateral push at the c.g., N (FCIMP), shape ``(len(chairs),)``.

    Returns
    -------
    list of SimulationResult
        One per run, in input order.
    """
    nrun = len(chairs)
    K = Physics(chairs, opts, vector=True)
    dt, half_dt2, stride = opts.dt, 0.5 * opts.dt * opts.dt, opts.stride
    sticks = opts.pin_mode == 2.0
    s = _State(speeds, opts, opts.impulse_force if forces is None else np.array(forces, dtype=float))
    n = n_steps(opts)
    nrec = (n - 1) // stride + 1
    buf = np.empty((nrun, nrec, NCOLS))   # rows beyond a run's length are never read
    nrec_run = np.zeros(nrun, dtype=int)
    stop_time = np.full(nrun, np.nan)
    stopped = np.zeros(nrun, dtype=bool)
    warns = _Warnings(nrun)
    own_bar = bar is None
    pbar = ProgressBar(n, "simulate (wchair batch)", enabled=progress, unit="step") if bar is None else bar
    done = 0
    try:
        for k in range(n):
            out = _step(K, s, opts, k, warns, stopped, stop_time, forces is not None)
            if out is None:
                break
            cols, acc, fc, heading_trig = out
            if k % stride == 0:
                block = np.empty((s.run.size, NCOLS))
                for i, c in enumerate(cols):
                    block[:, i] = c
                buf[s.run, k // stride, :] = block
                nrec_run[s.run] = k // stride + 1
            _update(s, acc, fc, heading_trig, dt, half_dt2, (K.maf, K.mbf) if sticks else None)
            if k % 64 == 63:
                pbar.update(64)
                done += 64
    finally:
        pbar.update(n - done)
        if own_bar:
            pbar.close()
    settings = opts.settings()
    return [SimulationResult._from_records(
        buf[i, :nrec_run[i]], warnings=warns.of_run(i), stopped=bool(stopped[i]),
        stop_time=None if not stopped[i] else float(stop_time[i]), chair=chairs[i], speed=float(speeds[i]),
        settings=settings if forces is None else dict(settings, impulse_force=float(forces[i])))
        for i in range(nrun)]
