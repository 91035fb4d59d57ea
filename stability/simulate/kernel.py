"""The compiled WCHAIR-scheme kernel (numba): one run per thread, the same code for one run and for a batch.

Imported only when a simulation runs (numba costs about 0.5 s to import; the compiled code is cached on disk, see
``docs/simulator.md``).  Every array layout is written by :mod:`stability.simulate.engine`.  The equations are the
generated functions behind :mod:`stability.models.full_width` and :mod:`stability.models.slope`, compiled as they
are, and so are the contact forces (:mod:`stability.models.forces`: normal loads, the tire resultant and yaw moment,
slip angles, pin friction) and the tire force law (:mod:`stability.tires.law`): nothing is transcribed.
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any

import numpy as np
from numba import get_num_threads, njit, parallel_chunksize, prange, set_num_threads, typeof
from numba._dispatcher import compute_fingerprint
from numba.core import config as _config
from numba.core import types as _nbtypes
from numba.extending import overload

from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.first_use import first_use
from stability.simulate.kernel_controller import controlled, controller_step, scratch_columns  # noqa: F401

# the layouts and the compiled physics as this module's globals, where numba resolves them (the engine, the adaptive
# and lanes kernels and the tests read them here too)
from stability.simulate.kernel_equations import *  # noqa: F403
from stability.simulate.kernel_equations import _NOREF, _NOWRAP, _OVERLOAD, _inl, _inl_py, _int  # noqa: F401
from stability.simulate.native_call import address, call_at, row_types

#: numba's largest thread count (set when numba is imported)
NUMBA_NUM_THREADS: int = vars(_config)["NUMBA_NUM_THREADS"]

#: the thread controls re-exported for :mod:`.engine` (which imports this module lazily)
__all__ = ["NUMBA_NUM_THREADS", "get_num_threads", "parallel_chunksize", "set_num_threads", "variant", "call_model",
           "run_single", "PER_RUN_ARGS", "run_batch",
           "run_serial", "run_one", "mechan", "kinematics", "contact_loads", "lateral_force", "accelerations",
           "held_pins", "stick_slip", "tire_yaw_moment", "plane"]

def variant(cfg: np.ndarray, ctl_f: np.ndarray) -> tuple[int, int]:
    """The kernel variant a configuration row runs: the first two arguments of :func:`run_one`, :func:`run_batch`
    and :func:`run_serial`, compiled as constants (numba literals, :func:`call_model`).

    Parameters
    ----------
    cfg : ndarray
        The kernel's configuration row (``engine._config``).
    ctl_f : ndarray
        The sampled controller's scalars (:meth:`SampledController.arrays`; sample time first, 0 for none).

    Returns
    -------
    model : int
        0 thesis, 1 exact, :data:`SLOPE_MODEL` the exact model on a plane (``cfg[SLOPE]`` set).
    ctl : int
        1 when a sampled controller gives the yaw moment, else 0 (its code is not compiled).
    """
    model = SLOPE_MODEL if cfg[SLOPE] != 0.0 else int(cfg[5])
    return model, int(ctl_f[0] > 0.0 and cfg[EXTERNAL_MZ] == 0.0)


#: the compiled specialisations :func:`call_model` found, by entry point, variant and the arguments' type fingerprints
_ENTRIES: dict[tuple, Any] = {}


def call_model(entry: Any, var: tuple[int, int], *args: Any) -> Any:
    """``entry(*var, *args)`` (:func:`run_batch`, :func:`run_serial`, :func:`run_one`) for the variant ``var``.

    :func:`run_one` takes the variant as numba literals, which Python ints do not match by type: numba's dispatch
    would type the call again every time (about 8 ms).  The first call for a variant and argument types compiles
    (or loads from the cache, under the first-use notice) :func:`run_one`'s literal specialisation directly; later
    ones call it directly, found by the arguments' type fingerprints (numba's own dispatch key, about 2 us).
    :func:`run_batch` and :func:`run_serial` are compiled once for every variant and call that specialisation for
    each run's rows at its address (:func:`~stability.simulate.native_call.call_at`).

    Parameters
    ----------
    entry : numba dispatcher
        :func:`run_batch`, :func:`run_serial`, :func:`run_one` or a copy of it.
    var : tuple of int
        :func:`variant` of the runs.
    *args
        The entry point's other arguments.

    Returns
    -------
    object
        What the entry point returns.
    """
    key = (entry, var, tuple(map(compute_fingerprint, args)))
    fn = _ENTRIES.get(key)
    if fn is None:
        with first_use("wchair"):
            types_, lit = tuple(typeof(a) for a in args), tuple(map(_nbtypes.literal, var))
            if entry is run_batch or entry is run_serial:     # the step for one run's rows (numba's types of a[i])
                step = address(run_one, (*lit, *types_[:2], *row_types(types_[2:-1], PER_RUN_ARGS)))
                fn = partial(entry.compile((typeof(step), *map(typeof, var), *types_)), step, *var)
            else:
                fn = partial(entry.compile((*lit, *types_)), *var)
        _ENTRIES[key] = fn
    return fn(*args)


@_inl
def plane(P, cfg, psi):
    """Gravity ``(g1, g2, gn)`` (m/s^2) in body axes at heading ``psi`` (generated ``gravity_body``)."""
    return gravity_body(P[G], cfg[C_PHI], cfg[S_PHI], cfg[C_THETA], cfg[S_THETA], math.cos(psi), math.sin(psi))


@_inl
def contact_loads(P, sum_fx, sum_fy, gn, ce, se, cb, sb):
    """Normal loads from the tire-force sums and the normal gravity ``gn`` (``P[G]`` when level; generated)."""
    return normal_loads(sum_fx, sum_fy, gn, ce, se, cb, sb, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2],
                               P[TRAIL], P[H], P[M], P[ROLL_K])


@_inl
def tire_yaw_moment(P, F, ce, se, cb, sb):
    """Yaw moment of the tire forces about the c.g., N m (generated)."""
    return tire_moment(*F, ce, se, cb, sb, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL])


@_inl
def velocities(model, P, u, v, r, ce, se, cb, sb, ed, bd):
    """Contact velocities of the model chosen at run time (0 thesis, else exact; generated): SLIP's, wheel frames
    untoed.  Compiled code calls :func:`model_velocities`."""
    if model == 0:
        return _cv_thesis(model, P, u, v, r, ce, se, cb, sb, ed, bd)
    return _cv_exact(model, P, u, v, r, ce, se, cb, sb, ed, bd)


@_inl
def _cv_thesis(model, P, u, v, r, ce, se, cb, sb, ed, bd):
    return cv_thesis(u, v, r, ce, se, cb, sb, ed, bd, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL])


@_inl
def _cv_exact(model, P, u, v, r, ce, se, cb, sb, ed, bd):
    return cv_exact(u, v, r, ce, se, cb, sb, ed, bd, P[X_M], P[X_P], P[D1], P[D2], P[T1], P[T2], P[TRAIL])


def step_gravity(model, P, cfg, psi, g1, g2, gn):
    """Gravity ``(g1, g2, gn)`` of the step: on a plane (``model`` :data:`SLOPE_MODEL`) in body axes at the heading
    ``psi`` with the normal weight (:func:`plane`), else ``(g1, g2, gn)`` as given (level: 0, 0, ``P[G]``); a literal
    model compiles its case only.  Compiled code only."""
    raise NotImplementedError("compiled code only (numba overload)")


@overload(step_gravity, **_OVERLOAD)
def _step_gravity(model, P, cfg, psi, g1, g2, gn):
    if isinstance(model, _nbtypes.IntegerLiteral) and model.literal_value != SLOPE_MODEL:
        def level(model, P, cfg, psi, g1, g2, gn):
            return g1, g2, gn
        return level

    def impl(model, P, cfg, psi, g1, g2, gn):
        if model == SLOPE_MODEL:
            return plane(P, cfg, psi)
        return g1, g2, gn
    return impl


def model_velocities(model, P, u, v, r, ce, se, cb, sb, ed, bd):
    """:func:`velocities` for compiled code only: a numba literal ``model`` compiles its model's alone
    (:func:`~stability.simulate.kernel_equations.model_accelerations`)."""
    raise NotImplementedError("compiled code only (numba overload)")


@overload(model_velocities, **_OVERLOAD)
def _model_velocities(model, P, u, v, r, ce, se, cb, sb, ed, bd):
    return by_model(model, (_cv_thesis, _cv_exact, _cv_exact), velocities)


@_inl
def kinematics(model, P, S, u, v, r, ce, se, cb, sb, ed, bd):
    """Contact velocities (SLIP), main wheels in their toed frames."""
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = model_velocities(model, P, u, v, r, ce, se, cb, sb, ed, bd)
    if S[TOE] != 0.0:
        ct, st = S[CT], S[ST]
        vEx, vEy = vEx * ct + vEy * st, -vEx * st + vEy * ct
        vDx, vDy = vDx * ct - vDy * st, vDx * st + vDy * ct
    return vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy


@_inl
def mechan(vel, slips, loads, tire_imp, ftimp, policy, TK, seg_c, seg_m, seg_k, TL, lim_c, lim_m, lim_k, RK, rc_c,
           rc_m, RS, CAM, S, col=0):
    """MECHAN: tire forces ``F`` (casters in their frames, main wheels in body axes) and ``(refused, wheel)``.

    ``refused``: 0 none, 1 a lateral force refused (policy "raise") at ``wheel``, 2 a camber force refused.
    ``tire_imp``: FTIMP acts (it then replaces the main wheels' lateral forces).  ``col``: the run's first column
    in the segment tables (0; the lanes kernel's block tables, :func:`stability.tires.law.segment_force`).
    """
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    sA, sB, sD, sE = slips
    NA, NB, ND, NE = loads
    FAy, bad0 = lateral_force(TK[0], seg_c, TL[0], lim_c, sA, NA, policy, col)
    FBy, bad1 = lateral_force(TK[0], seg_c, TL[0], lim_c, sB, NB, policy, col)
    if tire_imp:
        FDy, bad2 = ftimp + 0.0 * ND, False
        FEy, bad3 = ftimp + 0.0 * NE, False
    else:
        FDy, bad2 = lateral_force(TK[1], seg_m, TL[1], lim_m, sD, ND, policy, col)
        FEy, bad3 = lateral_force(TK[1], seg_m, TL[1], lim_m, sE, NE, policy, col)
    refused, wheel = 0, 0
    if bad0 or bad1 or bad2 or bad3:
        refused, wheel = 1, (0 if bad0 else (1 if bad1 else (2 if bad2 else 3)))
    FAx = rolling_force(RK[0], rc_c, RS[0], NA, vAx)
    FBx = rolling_force(RK[0], rc_c, RS[0], NB, vBx)
    FDx = rolling_force(RK[1], rc_m, RS[1], ND, vDx)
    FEx = rolling_force(RK[1], rc_m, RS[1], NE, vEx)
    if S[DRIVE_D] != 0.0 or S[DRIVE_E] != 0.0:       # a held drive (the slope linearisation), in the wheel frames
        FDx, FEx = FDx + S[DRIVE_D], FEx + S[DRIVE_E]
    if CAM[0] != 0.0 and refused == 0:
        cD, badc = lateral_force(TK[2], seg_k, TL[2], lim_k, CAM[0], ND, policy, col)
        cE, badd = lateral_force(TK[2], seg_k, TL[2], lim_k, CAM[0], NE, policy, col)
        if badc or badd:
            refused, wheel = 2, (2 if badc else 3)
        FDy = FDy + camber_force(CAM[1], cD)
        FEy = FEy - camber_force(CAM[1], cE)
    if S[TOE] != 0.0:
        ct, st = S[CT], S[ST]
        FEx, FEy = FEx * ct - FEy * st, FEx * st + FEy * ct
        FDx, FDy = FDx * ct + FDy * st, -FDx * st + FDy * ct
    return (FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy), refused, wheel


@_inl
def slip_angles(vel):
    """Signed slip angles ``atan2(vy, |vx|)`` in degrees (SLIP; generated)."""
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    return (slip_angle(vAx, vAy), slip_angle(vBx, vBy), slip_angle(vDx, vDy),
            slip_angle(vEx, vEy))


@_inl
def range_check(warn, t, loads, slips, CHK, maxload, maxslip, stop, nwarn_limit):
    """STATICS / MECHAN range rules (tested tires only): count warnings; True when the run stops here."""
    nmax = -math.inf
    smax = 0.0
    # min/max as numba's (Python's) selects, NaN included, without compiling numba's functions for them
    n01 = loads[1] if loads[1] < loads[0] else loads[0]
    n23 = loads[3] if loads[3] < loads[2] else loads[2]
    nmin = n23 if n23 < n01 else n01
    for w in range(4):
        if CHK[w]:
            nmax = loads[w] if loads[w] > nmax else nmax
            sw = abs(slips[w])
            smax = sw if sw > smax else smax
    if nmax > maxload:
        _note(warn[1], t, nmax)
        if stop and warn[1, 0] > nwarn_limit:
            return True
    if nmin < 0.0:
        _note(warn[2], t, nmin)
    if smax > maxslip:
        _note(warn[0], t, smax)
        if stop and warn[0, 0] > nwarn_limit:
            return True
    return False


@_inl
def summaries(stats, levels, k, t, a, prev_abs, t_prev):
    """Peak |yaw rate| and first times |yaw rate| >= each level (interpolated between steps)."""
    if a > stats[0] or k == 0:
        stats[0], stats[1] = a, t
    for j in range(levels.shape[0]):
        if stats[2 + j] != stats[2 + j] and a >= levels[j]:
            stats[2 + j] = t if k == 0 else t_prev + (levels[j] - prev_abs) / (a - prev_abs) * (t - t_prev)


@_inl
def record_row(rec, row, states, F, loads, slips, P, trig, extra):
    """One recorded step: the ten states, then (``record="all"``) forces, loads, slips, moments."""
    for c in range(10 if rec.shape[0] > 10 else rec.shape[0]):
        rec[c, row] = states[c]
    if rec.shape[0] > 10:
        for c in range(8):
            rec[10 + c, row] = F[c]
        for c in range(4):
            rec[18 + c, row] = loads[c]
            rec[22 + c, row] = slips[c]
        ce, se, cb, sb = trig
        rec[26, row] = tire_yaw_moment(P, F, ce, se, cb, sb)
        rec[27, row], rec[28, row], rec[29, row], rec[30, row] = extra


@_inl
def settled(track, t, held, a, ma, mb):
    """Whether a run has settled: both casters held (stuck) since ``track[0]`` for :data:`SETTLE_WINDOW` s, the
    push over, and neither ``|yaw rate|`` ``a`` nor either holding moment ``ma``, ``mb`` larger than at the middle
    of that window (``track[2:5]``, recorded when ``track[1]`` is set).  A held caster's moment is within its
    friction limit; a chair with both casters held is the locked-caster chair, stable below its locked critical
    speed, whose response settles into a steady coast or turn while its speed falls: it then stays held and never
    reaches the level.  ``held`` is this step's state; ``track`` is updated in place."""
    if not held:
        track[0] = -1.0
        return False
    if track[0] < 0.0:
        track[0], track[1] = t, 0.0
    elif track[1] == 0.0 and t >= track[0] + 0.5 * SETTLE_WINDOW:
        track[1], track[2], track[3], track[4] = 1.0, a, ma, mb
    elif track[1] != 0.0 and t >= track[0] + SETTLE_WINDOW:
        return a <= track[2] and ma <= track[3] and mb <= track[4]
    return False


@njit(cache=True, nogil=True, **dict(_NOWRAP, no_cpython_wrapper=False), **_NOREF)   # Python wrapper: run_single
def run_one(model, ctl, k0, k1, prow, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu,
            By, Cz, noise, state, rec, stats, warn, status):
    """Steps ``k0 .. k1 - 1`` of one run of the WCHAIR scheme, from and back to ``state`` (:data:`NSTATE` + the
    controller's states), with the chair's parameters ``prow``; writes ``rec`` (ncol, nrec), ``stats``, ``warn``
    (3, 3), ``status``; returns the rows recorded so far.  A stopped run (``status``) does nothing.

    ``model, ctl``: the run's :func:`variant`, compile-time constants (numba literals, compiled by
    :func:`call_model`, which the entry points call at its address), so that a run compiles its model's equations
    only, and the controller's step only with a controller (a ``literally`` here compiled numba's overload of it
    twice).  ``cfg[EXTERNAL_MZ]``: the yaw moment is ``state[ST_MZ]``, set by the caller between calls (a Python
    input sampled at the step), else the controller's."""
    if status[0] != 0.0 or status[2] != 0.0:
        return np.int64(state[ST_NREC])
    # the arrays of the step without reference counts (kept atomically per call of a helper; borrowed), P as a tuple
    P = leading(prow, NPARAM)
    S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK = (borrowed(S), borrowed(TK), borrowed(TS), borrowed(TL), borrowed(LIM),
                                                borrowed(RK), borrowed(RC), borrowed(RS), borrowed(CAM), borrowed(CHK))
    cfg, levels, state, rec, stats, warn, status = (borrowed(cfg), borrowed(levels), borrowed(state), borrowed(rec),
                                                    borrowed(stats), borrowed(warn), borrowed(status))
    ctl_f, Cy, Dy, Az, Bu, By, Cz, noise = (borrowed(ctl_f), borrowed(Cy), borrowed(Dy), borrowed(Az), borrowed(Bu),
                                            borrowed(By), borrowed(Cz), borrowed(noise))
    c = leading(cfg, NCFG)    # the configuration row as a tuple; integers cast (numba compiles int() on its own)
    dt, duimp, ftimp, n, stride, locked, stop, policy, mode = (
        c[0], c[1], c[2], np.int64(c[3]), np.int64(c[4]), c[6] == 1.0, c[7] != 0.0, np.int64(c[8]), np.int64(c[9]))
    sticks = c[6] == 2.0            # free casters with stick-slip pin friction (else WCHAIR's kinetic law)
    settle = sticks and np.int64(c[STOP_LEVEL]) >= 0 and c[SETTLE] != 0.0
    track = state[ST_TRACK:ST_TRACK + 5]           # settled(): since when both held, mid-window values
    rest_a, rest_b = (P[MAF], P[MBF]) if sticks else (0.0, 0.0)   # stick-slip: a reversing rate comes to rest
    use_ctl = ctl_f[0] > 0.0 and c[EXTERNAL_MZ] == 0.0
    half_dt2 = 0.5 * dt * dt
    maxslip, maxload, nwarn_limit, stop_lvl = c[10], c[11], c[12], np.int64(c[STOP_LEVEL])
    g1 = g2 = 0.0
    gn = P[G]
    # the controller's states, then its scratch (scratch_columns), views of the state: the step allocates nothing
    nz, ny = Az.shape[0], Cy.shape[0]
    z, znew = state[NSTATE:NSTATE + nz], state[NSTATE + nz:NSTATE + 2 * nz]
    y, sv = state[NSTATE + 2 * nz:NSTATE + 2 * nz + ny], state[NSTATE + 2 * nz + ny:NSTATE + 2 * nz + ny + 10]
    s0 = leading(state, ST_TRACK)     # the run's state before the settle tracker, as a tuple
    X, Y, THE, UD, VD, THED, E, ED, B, BD = s0[:10]
    THEDD, FC1, FC2 = s0[ST_THEDD], s0[ST_FC1], s0[ST_FC2]
    prev_abs, t_prev, next_k, mz_held = s0[ST_PREV], s0[ST_TPREV], np.int64(s0[ST_NEXTK]), s0[ST_MZ]
    nrec = np.int64(s0[ST_NREC])
    fcimp = S[FCIMP]
    seg_c, seg_m, seg_k = TS[0], TS[1], TS[2]      # per-run views made once (no per-step array views)
    lim_c, lim_m, lim_k = LIM[0], LIM[1], LIM[2]
    rc_c, rc_m = RC[0], RC[1]
    for k in range(k0, n if n < k1 else k1):     # min(k1, n)
        t = k * dt
        ce, se, cb, sb = math.cos(E), math.sin(E), math.cos(B), math.sin(B)
        vel = kinematics(model, P, S, UD, VD, THED, ce, se, cb, sb, ED, BD)
        slips = slip_angles(vel)
        g1, g2, gn = step_gravity(model, P, cfg, THE, g1, g2, gn)
        loads = contact_loads(P, FC1, FC2, gn, ce, se, cb, sb)
        if range_check(warn, t, loads, slips, CHK, maxload, maxslip, stop, nwarn_limit):
            status[0], status[1] = STOPPED_WARNINGS, t
            break
        imp = t <= duimp * (1.0 + 1e-12) + 1e-15
        F, refused, w = mechan(vel, slips, loads, ftimp != 0.0 and imp, ftimp, policy, TK, seg_c, seg_m, seg_k, TL,
                               lim_c, lim_m, lim_k, RK, rc_c, rc_m, RS, CAM, S)
        if refused != 0:
            status[2], status[3] = refused, w
            status[4], status[5] = (slips[w], loads[w]) if refused == 1 else (CAM[0], loads[w])
            break
        # DYNAM
        fc1, fc2 = tire_resultant(*F, ce, se, cb, sb)
        fy_ext = fcimp if (fcimp != 0.0 and imp) else 0.0
        mz = mz_held if c[EXTERNAL_MZ] != 0.0 else 0.0
        if use_ctl:
            mz_held, next_k = controller_step(ctl, t, next_k, mz_held, z, znew, y, sv,
                                              (X, Y, THE, UD, VD, THED, E, ED, B, BD),
                                         ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
            mz = mz_held
        st_ = (UD, VD, THED, ce, se, cb, sb, ED, BD)
        if locked:
            # the flags as variables (True here): literal True would compile held_pins for a second signature
            acc, MA, MB = held_pins(model, st_, F, 0.0, 0.0, locked, locked, fy_ext, mz, THEDD, P, g1, g2)
        elif sticks and (ED == 0.0 or BD == 0.0):
            acc, MA, MB = stick_slip(model, st_, F, fy_ext, mz, THEDD, P, g1, g2)
        else:   # the kinetic law, or stick-slip with both casters swivelling (stick_slip's own first case, here
            # without the call: its arguments and result passed through memory cost about a tenth of a run)
            MA = kinetic_pin_moment(ED, P[MAF])
            MB = kinetic_pin_moment(BD, P[MBF])
            acc = model_accelerations(model, st_, F, MA, MB, fy_ext, mz, THEDD, P, g1, g2)
        UDD, VDD, THEDD, EDD, BDD = acc
        if locked:
            EDD = BDD = 0.0
        a = abs(THED)
        if not a < math.inf:        # NaN or infinite: stop, and leave no finite summary behind
            stats[0] = math.nan
            status[0], status[1] = STOPPED_NONFINITE, t
            break
        summaries(stats, levels, k, t, a, prev_abs, t_prev)
        prev_abs, t_prev = a, t
        if mode == 2 or k % stride == 0:
            row = 0 if mode == 2 else k // stride
            record_row(rec, row, (X, Y, THE, THED, UD, VD, E, ED, B, BD), F, loads, slips, P, (ce, se, cb, sb),
                       (mz, THEDD, MA, MB))
            nrec = row + 1
            stats[2 + levels.shape[0]] = t
        if stop_lvl >= 0 and stats[2 + stop_lvl] == stats[2 + stop_lvl]:   # the level is reached: stop here
            status[0], status[1] = STOPPED_LEVEL, t
            break
        if settle and settled(track, t, t > duimp and ED == 0.0 and BD == 0.0 and EDD == 0.0 and BDD == 0.0, a,
                              abs(MA), abs(MB)):
            status[0], status[1] = STOPPED_SETTLED, t
            break
        # UPDATE / ITRATE
        FC1, FC2 = fc1, fc2 + fy_ext
        du = UD * dt + UDD * half_dt2
        dv = VD * dt + VDD * half_dt2
        cost, sint = math.cos(THE), math.sin(THE)
        X += du * cost - dv * sint
        Y += du * sint + dv * cost
        UD += UDD * dt
        VD += VDD * dt
        B += BD * dt + BDD * half_dt2
        E += ED * dt + EDD * half_dt2
        BD = rest_rate(BD, BD + BDD * dt, rest_b)    # the kinetic law passes limit 0: no rest
        ED = rest_rate(ED, ED + EDD * dt, rest_a)
        THE += THED * dt + THEDD * half_dt2
        THED += THEDD * dt
    state[0], state[1], state[2], state[3], state[4] = X, Y, THE, UD, VD
    state[5], state[6], state[7], state[8], state[9] = THED, E, ED, B, BD
    state[ST_THEDD], state[ST_FC1], state[ST_FC2] = THEDD, FC1, FC2
    state[ST_PREV], state[ST_TPREV], state[ST_NEXTK], state[ST_MZ] = prev_abs, t_prev, next_k, mz_held
    state[ST_NREC] = nrec
    return nrec


@_inl
def _note(w, t, value):
    """One warning of a kind, ``w`` its row of ``warn``: count, first time, largest value (a row rather than the
    kind's index, which numba would compile once per literal kind)."""
    if w[0] == 0.0 or abs(value) > abs(w[2]):
        w[2] = value
    if w[0] == 0.0:
        w[1] = t
    w[0] += 1.0


#: the arguments of :func:`run_batch` (after the step, the variant and the steps) that hold one row per run
PER_RUN_ARGS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 21, 22, 23, 24, 25)


def run_single(var: tuple[int, int], args: tuple, step: Any = None) -> None:
    """One run of the variant ``var``: :func:`run_one` called from Python (no parallel entry to compile for it,
    nor to re-optimise the step in).

    Parameters
    ----------
    var : tuple of int
        :func:`variant` of the run.
    args : tuple
        :func:`run_batch`'s arguments after the variant, each per-run array with one row; ``args[-1][0]`` is
        set to the rows recorded.
    step : numba dispatcher, optional
        :func:`run_one` (the default) or a copy of it compiled with other functions
        (:func:`stability.simulate.baseline.polynomial_trig_step`, a measurement).
    """
    k0, k1, rest = args[0], args[1], args[2:]
    row = [a[0] if i in PER_RUN_ARGS else a for i, a in enumerate(rest[:-1])]
    rest[-1][0] = call_model(run_one if step is None else step, var, k0, k1, *row)


@njit(cache=True, parallel=True)
def run_batch(step, model, ctl, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az,
              Bu, By, Cz, noise, state, rec, stats, warn, status, nrec):
    """Steps ``k0 .. k1 - 1`` of all runs, one per thread (``prange``); every array has the run as its first axis.
    ``step``: the address of :func:`run_one`'s specialisation for the runs' :func:`variant` ``model, ctl`` and
    rows (:func:`call_model`), called, not compiled in: one compile of this entry serves every variant."""
    for i in prange(P.shape[0]):
        nrec[i] = call_at(step, model, ctl, k0, k1, P[i], S[i], TK[i], TS[i], TL[i], LIM[i], RK[i], RC[i], RS[i],
                          CAM[i], CHK[i], cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, state[i], rec[i],
                          stats[i], warn[i], status[i])


@njit(cache=True, nogil=True)
def run_serial(step, model, ctl, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az,
               Bu, By, Cz, noise, state, rec, stats, warn, status, nrec):
    """:func:`run_batch` on the calling thread: the step-by-step calls of a Python yaw-moment input."""
    for i in range(P.shape[0]):
        nrec[i] = call_at(step, model, ctl, k0, k1, P[i], S[i], TK[i], TS[i], TL[i], LIM[i], RK[i], RC[i], RS[i],
                          CAM[i], CHK[i], cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, state[i], rec[i],
                          stats[i], warn[i], status[i])


invalidate_stale_cache(globals(), "kernel.equations.sha256")
