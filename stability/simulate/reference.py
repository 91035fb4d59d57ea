"""The pure-numpy WCHAIR scheme over a batch of runs: the test reference of the compiled kernel.

Also the path of a batch with a Python ``yaw_moment(t, state)`` input, which
receives arrays over the active runs.  Step for step the scheme of
:mod:`.wchair` (see ``docs/simulator.md``).
"""

from __future__ import annotations

import math

import numpy as np

from ..chair import Chair
from ..models.full_width import tire_resultant, tire_yaw_moment
from ..progress import ProgressBar
from ..statics import normal_loads
from .options import LOAD_LIMIT_N, SLIP_LIMIT_DEG, WARNING_LIMIT, Options, impulse_on, initial_velocities, n_steps
from .physics import Physics, accelerations, held_accelerations, kinematics, tire_forces
from .results import NCOLS, ChairState, SimulationResult

__all__ = ["wchair_batch"]


def wchair_batch(chairs: list[Chair], speeds: np.ndarray, opts: Options, progress: bool,
                  bar: ProgressBar | None = None, forces: np.ndarray | None = None) -> list[SimulationResult]:
    """All runs stepped together; ``forces``: per-run impulse force (N) instead of ``opts.impulse_force``."""
    nrun = len(chairs)
    K = Physics(chairs, opts, vector=True)
    dt, half_dt2, locked, thesis, yaw_fn, stop, stride, fcimp = opts.step_constants()
    if forces is not None:
        fcimp = np.array(forces, dtype=float)
    n = n_steps(opts)
    nrec = (n - 1) // stride + 1
    buf = np.empty((nrun, nrec, NCOLS))   # rows beyond a run's length are never read
    nrec_run = np.zeros(nrun, dtype=int)
    stop_time = np.full(nrun, np.nan)
    stopped = np.zeros(nrun, dtype=bool)
    cnt = {k: np.zeros(nrun, dtype=int) for k in ("slip", "load", "lift_off")}
    first = {k: np.full(nrun, np.nan) for k in cnt}
    vmax = {k: np.full(nrun, np.nan) for k in cnt}

    run = np.arange(nrun)
    u0, v0 = initial_velocities(opts, 1.0)
    # velocities Sv = (UD, VD, THED, ED, BD) and angles Sp = (THE, E, B) stacked:
    # ITRATE is then a few operations on (5, n) and (3, n) arrays
    Sv = np.zeros((5, nrun))
    Sv[0] = np.asarray(speeds, dtype=float) * u0
    Sv[1] = v0
    Sp = np.zeros((3, nrun))
    Sp[1], Sp[2] = opts.eta0, opts.beta0
    UD, VD, THED, ED, BD = Sv
    THE, E, B = Sp
    z = np.zeros(nrun)
    X, Y, THEDD = z.copy(), z.copy(), z.copy()
    FC1, FC2 = z.copy(), z.copy()
    p_loads = normal_loads
    rad2deg = 180.0 / math.pi

    def flag(kind, mask, t, values):
        if not mask.any():
            return
        idx = run[mask]
        cnt[kind][idx] += 1
        new = idx[np.isnan(first[kind][idx])]
        first[kind][new] = t
        cur = vmax[kind][idx]
        val = values[mask]
        vmax[kind][idx] = np.where(np.isnan(cur) | (np.abs(val) > np.abs(cur)), val, cur)

    own_bar = bar is None
    if own_bar:
        bar = ProgressBar(n, "simulate (wchair batch)", enabled=progress, unit="step")
    done = 0
    try:
        for k in range(n):
            if run.size == 0:
                break
            t = k * dt
            Cp, Sn = np.cos(Sp), np.sin(Sp)            # heading, eta, beta at once
            ce, se, cb, sb = Cp[1], Sn[1], Cp[2], Sn[2]
            V = np.array(kinematics(K, UD, VD, THED, ce, se, cb, sb, ED, BD))   # (8, m): vx, vy per wheel
            S4 = np.arctan2(V[1::2], np.abs(V[0::2]))                            # as the kernel and SLIP
            S4 *= rad2deg
            N4 = np.array(p_loads(K.p, FC1, FC2, ce, se, cb, sb))               # (4, m)
            if K.check_all:
                nmax = N4.max(axis=0)
                smax = np.abs(S4).max(axis=0)
            else:
                nmax = np.where(K.chk_mask, N4, -np.inf).max(axis=0)
                smax = np.where(K.chk_mask, np.abs(S4), 0.0).max(axis=0)
            over_load = nmax > LOAD_LIMIT_N
            nmin = N4.min(axis=0)
            under = nmin < 0.0
            over_slip = smax > SLIP_LIMIT_DEG
            halt = None
            if over_load.any() or under.any() or over_slip.any():
                halt = np.zeros(run.size, dtype=bool)
                flag("load", over_load, t, nmax)
                if stop:
                    halt |= cnt["load"][run] > WARNING_LIMIT
                flag("lift_off", under & ~halt, t, nmin)
                flag("slip", over_slip & ~halt, t, smax)
                if stop:
                    halt |= cnt["slip"][run] > WARNING_LIMIT
            if halt is not None and halt.any():
                gone = run[halt]
                stopped[gone] = True
                stop_time[gone] = t
                keep = np.flatnonzero(~halt)
                K.compact(keep)
                run = run[keep]
                (X, Y, THEDD, FC1, FC2) = (a[keep] for a in (X, Y, THEDD, FC1, FC2))
                if forces is not None:
                    fcimp = fcimp[keep]
                Sv, Sp, V, S4, N4 = Sv[:, keep], Sp[:, keep], V[:, keep], S4[:, keep], N4[:, keep]
                Cp, Sn = Cp[:, keep], Sn[:, keep]
                ce, se, cb, sb = Cp[1], Sn[1], Cp[2], Sn[2]
                UD, VD, THED, ED, BD = Sv
                THE, E, B = Sp
                if run.size == 0:
                    break
            vel = tuple(V)
            slips = tuple(S4)
            NA, NB, ND, NE = N4
            imp = impulse_on(opts, t)
            F = tire_forces(K, imp, vel, slips, NA, NB, ND, NE, S4=S4, N4=N4)
            fc1, fc2 = tire_resultant(F, ce, se, cb, sb)
            fy_ext = fcimp if (imp and (forces is not None or fcimp != 0.0)) else 0.0
            if yaw_fn is None:
                mz = 0.0
            else:
                st_ = ChairState(*(a.copy() for a in (X, Y, THE, UD, VD, THED, E, ED, B, BD, run)))
                mz = np.broadcast_to(np.asarray(yaw_fn(t, st_), dtype=float), run.shape)
            state = (UD, VD, THED, ce, se, cb, sb, ED, BD)
            rdc = THEDD if thesis else None
            if locked:
                zero = np.zeros(run.size)
                acc, MA, MB = held_accelerations(K, state, F, zero, zero, fy_ext, mz, True, True, rdc)
            else:
                MA = np.where(ED != 0.0, np.copysign(K.maf, -ED), 0.0)
                MB = np.where(BD != 0.0, np.copysign(K.mbf, -BD), 0.0)
                acc = accelerations(K, state, F, MA, MB, fy_ext, mz, rdc)
            UDD, VDD, THEDD_new, EDD, BDD = acc
            if locked:
                EDD = BDD = np.zeros(run.size)
            if k % stride == 0:
                j = k // stride
                cols = (t, X, Y, THE, THED, UD, VD, E, ED, B, BD, *F, NA, NB, ND, NE, *slips,
                        tire_yaw_moment(K.p, F, ce, se, cb, sb), mz, THEDD_new, MA, MB)
                block = np.empty((run.size, NCOLS))
                for i, c in enumerate(cols):
                    block[:, i] = c
                buf[run, j, :] = block
                nrec_run[run] = j + 1
            # UPDATE / ITRATE: x += v dt + a dt^2/2 (global X, Y with the heading
            # at the start of the step), then v += a dt
            Acc = np.array((UDD, VDD, THEDD_new, EDD, BDD))
            THEDD = THEDD_new          # (Acc is scaled in place below)
            FC1, FC2 = fc1, fc2 + fy_ext
            D = Sv * dt
            D += Acc * half_dt2
            cost, sint = Cp[0], Sn[0]           # heading at the start of the step
            X = X + (D[0] * cost - D[1] * sint)
            Y = Y + (D[0] * sint + D[1] * cost)
            Sp += D[2:5]
            Acc *= dt
            Sv += Acc
            if k % 64 == 63:
                bar.update(64)
                done += 64
    finally:
        bar.update(n - done)
        if own_bar:
            bar.close()

    out = []
    settings = opts.settings()
    for i in range(nrun):
        if forces is not None:
            settings = dict(settings, impulse_force=float(forces[i]))
        w = {}
        for kind in cnt:
            c = int(cnt[kind][i])
            w[kind] = {"count": c, "first_time": None if c == 0 else float(first[kind][i]),
                       "max": None if c == 0 else float(vmax[kind][i])}
        out.append(SimulationResult._from_records(
            buf[i, :nrec_run[i]], warnings=w, stopped=bool(stopped[i]),
            stop_time=None if not stopped[i] else float(stop_time[i]), chair=chairs[i],
            speed=float(speeds[i]), settings=settings))
    return out
