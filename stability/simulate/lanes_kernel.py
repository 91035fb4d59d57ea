"""The WCHAIR-scheme kernel with runs as SIMD lanes (numba): a block of runs stepped together, state as [state, run].

The same step as :func:`stability.simulate.kernel.run_one`, for a block of
runs at once: every per-step quantity is an array over the block's runs, and
the loops over runs that are plain arithmetic (the caster angles' sine and
cosine, the contact velocities, the slip angles, the normal loads, the
resultant, the accelerations under the kinetic pin law, the update) are
vectorised by LLVM.  What they compute is not written here: they are the
scalar kernel's own helpers (:mod:`stability.simulate.kernel`) and the
generated physics (:mod:`stability.models`), compiled again in a namespace
whose :mod:`math` is :data:`stability.simulate.lanemath.LANE_MATH`
(polynomial ``sin``, ``cos``, ``atan2`` that LLVM can vectorise; pip's numba
has no vector libm) and with numpy's error model (a division by zero gives
inf instead of raising, so the loops have no exits).  The decisions that
differ from run to run (the range rules and MECHAN's tire tables, the
stick-slip holding solve, the controller, the summaries and the stop rules)
run lane by lane through the scalar kernel's functions, unchanged.

So a run's numbers differ from the scalar kernel's only through the
polynomials' rounding (:mod:`stability.simulate.lanemath`: within 2 ulp for
sine and cosine, 3 ulp for the slip angle's arctangent); docs/simulator.md
states the tolerance that follows and ``tests/test_lanes_kernel.py`` checks
it.  A run's numbers do not depend on the block size, on its place in the
block or on the other runs (every lane executes the same instructions; LLVM
does not contract multiplies and adds into FMAs without fast-math, so the
vector and scalar forms of a loop round alike).
"""

from __future__ import annotations

import math

import numpy as np
from numba import get_num_threads, njit, parallel_chunksize, prange, set_num_threads

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.simulate import kernel as _k
from stability.simulate import kernel_equations as _ke
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.kernel import (
    C_PHI,
    C_THETA,
    CT,
    EXTERNAL_MZ,
    FCIMP,
    G,
    MAF,
    MBF,
    NSTATE,
    S_PHI,
    S_THETA,
    SETTLE,
    SLOPE,
    SLOPE_MODEL,
    ST,
    ST_FC1,
    ST_FC2,
    ST_MZ,
    ST_NEXTK,
    ST_NREC,
    ST_PREV,
    ST_THEDD,
    ST_TPREV,
    ST_TRACK,
    STOP_LEVEL,
    STOPPED_LEVEL,
    STOPPED_NONFINITE,
    STOPPED_SETTLED,
    STOPPED_WARNINGS,
    TOE,
    controlled,
    held_pins,
    mechan,
    range_check,
    record_row,
    settled,
    stick_slip,
    summaries,
)
from stability.simulate.kernel_equations import _NOWRAP, compiled
from stability.simulate.lanemath import LANE_MATH, sin_cos

__all__ = ["LANES", "run_lanes", "lane_physics", "get_num_threads", "set_num_threads", "parallel_chunksize"]

#: runs per block (measured: docs/simulator.md, "Runs as lanes"); the numbers do not depend on it
LANES = 64

_lane = njit(cache=False, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP)

# The generated physics, compiled again with the lane math (the same source; nothing re-typed)
_lfo = compiled(_fo, tuple(_fo.__all__), _lane, {"math": LANE_MATH})
_lfw = compiled(_fw, ("contact_velocities_exact", "contact_velocities_thesis", "accelerations_exact",
                      "accelerations_thesis"), _lane, {"math": LANE_MATH})
_lsl = compiled(_sl, ("accelerations_slope_exact", "gravity_body"), _lane, {"math": LANE_MATH})
#: the scalar kernel's helpers of the step's arithmetic, calling the lane physics
_lke = compiled(_ke, ("accelerations",), _lane, {
    "math": LANE_MATH, "acc_exact": _lfw.accelerations_exact, "acc_thesis": _lfw.accelerations_thesis,
    "acc_slope": _lsl.accelerations_slope_exact})
_lk = compiled(_k, ("plane", "contact_loads", "kinematics", "slip_angles"), _lane, {
    "math": LANE_MATH, "gravity_body": _lsl.gravity_body, "normal_loads": _lfo.normal_loads,
    "cv_thesis": _lfw.contact_velocities_thesis, "cv_exact": _lfw.contact_velocities_exact,
    "slip_angle": _lfo.slip_angle})
l_accelerations = _lke.accelerations
l_plane, l_contact_loads, l_kinematics, l_slip_angles = _lk.plane, _lk.contact_loads, _lk.kinematics, _lk.slip_angles
l_tire_resultant, l_kinetic, l_rest_rate = _lfo.tire_resultant, _lfo.kinetic_pin_moment, _lfo.rest_rate


def lane_physics() -> dict:
    """The lane versions by name (for the tests: each is the scalar kernel's function in the lane namespace)."""
    return {"accelerations": l_accelerations, "plane": l_plane, "contact_loads": l_contact_loads,
            "kinematics": l_kinematics, "slip_angles": l_slip_angles, "tire_resultant": l_tire_resultant}


@_lane
def _p(Pt, j):
    """Lane ``j``'s chair parameters as a tuple (the scalar helpers index it like a run's ``P``)."""
    return (Pt[0, j], Pt[1, j], Pt[2, j], Pt[3, j], Pt[4, j], Pt[5, j], Pt[6, j], Pt[7, j], Pt[8, j], Pt[9, j],
            Pt[10, j], Pt[11, j], Pt[12, j], Pt[13, j], Pt[14, j], Pt[15, j], Pt[16, j], Pt[17, j])


@_lane
def _s(St, j):
    """Lane ``j``'s per-run scalars as a tuple (a run's ``S``)."""
    return (St[0, j], St[1, j], St[2, j], St[3, j], St[4, j], St[5, j], St[6, j], St[7, j], St[8, j], St[9, j])


# rows of the block's state x: the ten states, the lagged yaw acceleration, the previous force sums
_X, _Y, _THE, _UD, _VD, _THED, _E, _ED, _B, _BD, _THEDD, _FC1, _FC2 = range(13)


@njit(cache=True, nogil=True, error_model="numpy", **_NOWRAP)
def _block(lo, hi, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz,
           noise, state, rec, stats, warn, status, nrec):
    """Steps ``k0 .. k1 - 1`` of runs ``lo .. hi - 1`` as lanes (see :func:`stability.simulate.kernel.run_one`)."""
    L = hi - lo
    dt, duimp, ftimp, n, stride, model, locked, stop, policy, mode = (
        cfg[0], cfg[1], cfg[2], int(cfg[3]), int(cfg[4]), int(cfg[5]), cfg[6] == 1.0, cfg[7] != 0.0,
        int(cfg[8]), int(cfg[9]))
    sticks = cfg[6] == 2.0
    settle = sticks and int(cfg[STOP_LEVEL]) >= 0 and cfg[SETTLE] != 0.0
    ext = cfg[EXTERNAL_MZ] != 0.0
    use_ctl = ctl_f[0] > 0.0 and not ext
    half_dt2 = 0.5 * dt * dt
    maxslip, maxload, nwarn_limit, stop_lvl = cfg[10], cfg[11], cfg[12], int(cfg[STOP_LEVEL])
    slope = cfg[SLOPE] != 0.0
    if slope:
        model = SLOPE_MODEL
    nlev = levels.shape[0]
    nz = Az.shape[0]
    znew = np.zeros(nz)
    y = np.zeros(Cy.shape[0])
    sv = np.zeros(10)
    Pt = np.empty((18, L))
    St = np.empty((10, L))
    x = np.empty((13, L))
    aux = np.empty((3, L))                      # |yaw rate| and time of the previous step, held yaw moment
    next_k = np.empty(L, dtype=np.int64)
    nrc = np.empty(L, dtype=np.int64)
    active = np.empty(L, dtype=np.bool_)
    rest = np.zeros((2, L))
    for j in range(L):
        i = lo + j
        for c in range(18):
            Pt[c, j] = P[i, c]
        for c in range(10):
            St[c, j] = S[i, c]
            x[c, j] = state[i, c]
        x[_THEDD, j], x[_FC1, j], x[_FC2, j] = state[i, ST_THEDD], state[i, ST_FC1], state[i, ST_FC2]
        aux[0, j], aux[1, j], aux[2, j] = state[i, ST_PREV], state[i, ST_TPREV], state[i, ST_MZ]
        next_k[j], nrc[j] = int(state[i, ST_NEXTK]), int(state[i, ST_NREC])
        active[j] = status[i, 0] == 0.0 and status[i, 2] == 0.0
        if sticks:
            rest[0, j], rest[1, j] = P[i, MAF], P[i, MBF]
    tr = np.empty((4, L))
    vel = np.empty((8, L))
    sl = np.empty((4, L))
    ld = np.empty((4, L))
    F = np.empty((8, L))
    fc = np.empty((2, L))
    ac = np.empty((7, L))                       # accelerations, then the pin moments
    ext_f = np.empty((2, L))                    # the push at the c.g., the yaw moment
    grav = np.zeros((2, L))
    gn = np.empty(L)
    for k in range(k0, min(k1, n)):
        going = 0
        for j in range(L):
            going += 1 if active[j] else 0
        if going == 0:
            break
        t = k * dt
        imp = t <= duimp * (1.0 + 1e-12) + 1e-15
        # SLIP and STATICS, vectorised: caster angles' trig, contact velocities, slip angles, normal loads
        for j in range(L):
            se, ce = sin_cos(x[_E, j])
            sb, cb = sin_cos(x[_B, j])
            Pj = _p(Pt, j)
            v8 = l_kinematics(model, Pj, _s(St, j), x[_UD, j], x[_VD, j], x[_THED, j], ce, se, cb, sb, x[_ED, j],
                              x[_BD, j])
            s4 = l_slip_angles(v8)
            g = Pj[G]
            if slope:
                g1, g2, g = l_plane(Pj, cfg, x[_THE, j])
                grav[0, j], grav[1, j] = g1, g2
            gn[j] = g
            n4 = l_contact_loads(Pj, x[_FC1, j], x[_FC2, j], g, ce, se, cb, sb)
            tr[0, j], tr[1, j], tr[2, j], tr[3, j] = ce, se, cb, sb
            vel[0, j], vel[1, j], vel[2, j], vel[3, j] = v8[0], v8[1], v8[2], v8[3]
            vel[4, j], vel[5, j], vel[6, j], vel[7, j] = v8[4], v8[5], v8[6], v8[7]
            sl[0, j], sl[1, j], sl[2, j], sl[3, j] = s4
            ld[0, j], ld[1, j], ld[2, j], ld[3, j] = n4
        # the range rules and MECHAN, lane by lane (the scalar kernel's functions: tire tables per run)
        for j in range(L):
            if not active[j]:
                continue
            i = lo + j
            loads = (ld[0, j], ld[1, j], ld[2, j], ld[3, j])
            slips = (sl[0, j], sl[1, j], sl[2, j], sl[3, j])
            if range_check(warn[i], t, loads, slips, CHK[i], maxload, maxslip, stop, nwarn_limit):
                status[i, 0], status[i, 1] = STOPPED_WARNINGS, t
                active[j] = False
                continue
            v8 = (vel[0, j], vel[1, j], vel[2, j], vel[3, j], vel[4, j], vel[5, j], vel[6, j], vel[7, j])
            f8, refused, w = mechan(v8, slips, loads, ftimp != 0.0 and imp, ftimp, policy, TK[i], TS[i, 0], TS[i, 1],
                                    TS[i, 2], TL[i], LIM[i, 0], LIM[i, 1], LIM[i, 2], RK[i], RC[i, 0], RC[i, 1], RS[i],
                                    CAM[i], S[i])
            if refused != 0:
                status[i, 2], status[i, 3] = refused, w
                status[i, 4], status[i, 5] = (slips[w], loads[w]) if refused == 1 else (CAM[i, 0], loads[w])
                active[j] = False
                continue
            for c in range(8):
                F[c, j] = f8[c]
            mz = aux[2, j] if ext else 0.0
            if use_ctl:
                held, nk = controlled(t, next_k[j], aux[2, j], state[i, NSTATE:NSTATE + nz], znew, y, sv,
                                      (x[0, j], x[1, j], x[2, j], x[3, j], x[4, j], x[5, j], x[6, j], x[7, j],
                                       x[8, j], x[9, j]), ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
                aux[2, j], next_k[j] = held, nk
                mz = held
            ext_f[1, j] = mz
        # DYNAM, vectorised: the resultant and the accelerations with the kinetic pin moments
        for j in range(L):
            ce, se, cb, sb = tr[0, j], tr[1, j], tr[2, j], tr[3, j]
            f1, f2 = l_tire_resultant(F[0, j], F[1, j], F[2, j], F[3, j], F[4, j], F[5, j], F[6, j], F[7, j],
                                      ce, se, cb, sb)
            fc[0, j], fc[1, j] = f1, f2
            fimp = St[FCIMP, j]
            fy = fimp if (fimp != 0.0 and imp) else 0.0
            ext_f[0, j] = fy
            Pj = _p(Pt, j)
            ma = l_kinetic(x[_ED, j], Pj[MAF])
            mb = l_kinetic(x[_BD, j], Pj[MBF])
            a5 = l_accelerations(model, (x[_UD, j], x[_VD, j], x[_THED, j], ce, se, cb, sb, x[_ED, j], x[_BD, j]),
                                 (F[0, j], F[1, j], F[2, j], F[3, j], F[4, j], F[5, j], F[6, j], F[7, j]), ma, mb,
                                 fy, ext_f[1, j], x[_THEDD, j], Pj, grav[0, j], grav[1, j])
            ac[0, j], ac[1, j], ac[2, j], ac[3, j], ac[4, j] = a5
            ac[5, j], ac[6, j] = ma, mb
        # held casters (locked, or stuck under stick-slip), lane by lane: the scalar kernel's solve
        if locked or sticks:
            for j in range(L):
                if not active[j] or not (locked or x[_ED, j] == 0.0 or x[_BD, j] == 0.0):
                    continue
                i = lo + j
                st_ = (x[_UD, j], x[_VD, j], x[_THED, j], tr[0, j], tr[1, j], tr[2, j], tr[3, j], x[_ED, j],
                       x[_BD, j])
                f8 = (F[0, j], F[1, j], F[2, j], F[3, j], F[4, j], F[5, j], F[6, j], F[7, j])
                if locked:
                    a5, ma, mb = held_pins(model, st_, f8, 0.0, 0.0, True, True, ext_f[0, j], ext_f[1, j],
                                           x[_THEDD, j], P[i], grav[0, j], grav[1, j])
                else:
                    a5, ma, mb = stick_slip(model, st_, f8, ext_f[0, j], ext_f[1, j], x[_THEDD, j], P[i],
                                            grav[0, j], grav[1, j])
                for c in range(5):
                    ac[c, j] = a5[c]
                if locked:
                    ac[3, j] = ac[4, j] = 0.0
                ac[5, j], ac[6, j] = ma, mb
        # the summaries, the record and the stop rules, lane by lane
        for j in range(L):
            if not active[j]:
                continue
            i = lo + j
            a = abs(x[_THED, j])
            if not a < math.inf:
                stats[i, 0] = math.nan
                status[i, 0], status[i, 1] = STOPPED_NONFINITE, t
                active[j] = False
                continue
            summaries(stats[i], levels, k, t, a, aux[0, j], aux[1, j])
            aux[0, j], aux[1, j] = a, t
            if mode == 2 or k % stride == 0:
                row = 0 if mode == 2 else k // stride
                record_row(rec[i], row, (x[0, j], x[1, j], x[2, j], x[5, j], x[3, j], x[4, j], x[6, j], x[7, j],
                                         x[8, j], x[9, j]),
                           (F[0, j], F[1, j], F[2, j], F[3, j], F[4, j], F[5, j], F[6, j], F[7, j]),
                           (ld[0, j], ld[1, j], ld[2, j], ld[3, j]), (sl[0, j], sl[1, j], sl[2, j], sl[3, j]), P[i],
                           (tr[0, j], tr[1, j], tr[2, j], tr[3, j]), (ext_f[1, j], ac[2, j], ac[5, j], ac[6, j]))
                nrc[j] = row + 1
                stats[i, 2 + nlev] = t
            if stop_lvl >= 0 and stats[i, 2 + stop_lvl] == stats[i, 2 + stop_lvl]:
                status[i, 0], status[i, 1] = STOPPED_LEVEL, t
                active[j] = False
                continue
            if settle and settled(state[i, ST_TRACK:ST_TRACK + 5], t,
                                  t > duimp and x[_ED, j] == 0.0 and x[_BD, j] == 0.0 and ac[3, j] == 0.0
                                  and ac[4, j] == 0.0, a, abs(ac[5, j]), abs(ac[6, j])):
                status[i, 0], status[i, 1] = STOPPED_SETTLED, t
                active[j] = False
        # UPDATE / ITRATE, vectorised (a stopped lane keeps its state)
        for j in range(L):
            on = active[j]
            X, Y, THE, UD, VD, THED = x[_X, j], x[_Y, j], x[_THE, j], x[_UD, j], x[_VD, j], x[_THED, j]
            E, ED, B, BD = x[_E, j], x[_ED, j], x[_B, j], x[_BD, j]
            UDD, VDD, THEDD, EDD, BDD = ac[0, j], ac[1, j], ac[2, j], ac[3, j], ac[4, j]
            du = UD * dt + UDD * half_dt2
            dv = VD * dt + VDD * half_dt2
            sint, cost = sin_cos(THE)
            x[_X, j] = X + (du * cost - dv * sint) if on else X
            x[_Y, j] = Y + (du * sint + dv * cost) if on else Y
            x[_UD, j] = UD + UDD * dt if on else UD
            x[_VD, j] = VD + VDD * dt if on else VD
            x[_B, j] = B + (BD * dt + BDD * half_dt2) if on else B
            x[_E, j] = E + (ED * dt + EDD * half_dt2) if on else E
            x[_BD, j] = l_rest_rate(BD, BD + BDD * dt, rest[1, j]) if on else BD
            x[_ED, j] = l_rest_rate(ED, ED + EDD * dt, rest[0, j]) if on else ED
            x[_THE, j] = THE + (THED * dt + THEDD * half_dt2) if on else THE
            x[_THED, j] = THED + THEDD * dt if on else THED
            x[_THEDD, j] = THEDD if on else x[_THEDD, j]
            x[_FC1, j] = fc[0, j] if on else x[_FC1, j]
            x[_FC2, j] = fc[1, j] + ext_f[0, j] if on else x[_FC2, j]
    for j in range(L):
        i = lo + j
        for c in range(10):
            state[i, c] = x[c, j]
        state[i, ST_THEDD], state[i, ST_FC1], state[i, ST_FC2] = x[_THEDD, j], x[_FC1, j], x[_FC2, j]
        state[i, ST_PREV], state[i, ST_TPREV], state[i, ST_MZ] = aux[0, j], aux[1, j], aux[2, j]
        state[i, ST_NEXTK], state[i, ST_NREC] = next_k[j], nrc[j]
        nrec[i] = nrc[j]


@njit(cache=True, parallel=True, error_model="numpy")
def run_lanes(k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz,
              noise, state, rec, stats, warn, status, nrec, lanes):
    """:func:`stability.simulate.kernel.run_batch` with the runs in blocks of ``lanes`` stepped as lanes, one block
    per thread (``prange``); the same arguments, and the block size."""
    nb = (P.shape[0] + lanes - 1) // lanes
    for b in prange(nb):
        lo = b * lanes
        _block(lo, min(P.shape[0], lo + lanes), k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels,
               ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, state, rec, stats, warn, status, nrec)


invalidate_stale_cache(globals(), "lanes_kernel.equations.sha256")
