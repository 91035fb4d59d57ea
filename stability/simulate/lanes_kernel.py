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
from numba import carray, get_num_threads, njit, parallel_chunksize, prange, set_num_threads, types
from numba.extending import intrinsic

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.simulate import kernel as _k
from stability.simulate import kernel_equations as _ke
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.kernel import (
    D1,
    D2,
    EXTERNAL_MZ,
    FCIMP,
    MAF,
    MBF,
    NSTATE,
    SETTLE,
    SETTLE_WINDOW,
    SLOPE,
    SLOPE_MODEL,
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
    T1,
    T2,
    TRAIL,
    X_M,
    X_P,
    G,
    controlled,
    held_pins,
    range_check,
    stick_slip,
    tire_yaw_moment,
)
from stability.simulate.kernel_equations import _NOWRAP, compiled
from stability.simulate.lanemath import LANE_MATH, sin_cos
from stability.tires import law as _tire_law

__all__ = ["LANES", "MAX_LEVELS", "run_lanes", "lane_physics", "get_num_threads", "set_num_threads", "parallel_chunksize"]

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
l_tire_moment = _lfo.tire_yaw_moment
#: the tire law and MECHAN (the tables of a block side by side: a run's first column is ``8 j``)
_law = compiled(_tire_law, ("cubic", "segment_force", "lateral_force", "camber_force", "rolling_resistance",
                            "rolling_force"), _lane, {"math": LANE_MATH})
l_mechan = compiled(_k, ("mechan",), _lane, {"math": LANE_MATH, "lateral_force": _law.lateral_force,
                                              "rolling_force": _law.rolling_force,
                                              "camber_force": _law.camber_force}).mechan


@intrinsic
def _data(typingctx, arr):
    """The data pointer of a C-contiguous float64 array (for :func:`_borrowed`)."""
    if not (isinstance(arr, types.Array) and arr.dtype == types.float64 and arr.layout == "C"):
        return None

    def codegen(context, builder, sig, args):
        return context.make_array(sig.args[0])(context, builder, value=args[0]).data

    return types.CPointer(types.float64)(arr), codegen


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP)
def _borrowed(a):
    """A 2-D view of ``a`` without a reference count: the tire tables passed into MECHAN once per lane and step.

    numba counts references to an array passed into a function with branches (the tire law) with atomic operations
    that LLVM cannot remove, one pair per call, which cost more than the tire law itself and keep the loop from
    being vectorised; a view made by ``carray`` has no count to keep (``a`` must outlive it: the block's tables).
    """
    return carray(_data(a), a.shape)


@_lane
def _t3(W, r, j):
    return (W[r, j], W[r + 1, j], W[r + 2, j])


@_lane
def _t2(W, r, j):
    return (W[r, j], W[r + 1, j])


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP)
def _summaries(W, j, nlev, levels, k, t, a, prev_abs, t_prev):
    """:func:`stability.simulate.kernel.summaries` on the lane's rows of ``W`` (no per-run array view)."""
    if a > W[_STT, j] or k == 0:
        W[_STT, j], W[_STT + 1, j] = a, t
    for m in range(nlev):
        r = _STT + 2 + m
        if W[r, j] != W[r, j] and a >= levels[m]:
            W[r, j] = t if k == 0 else t_prev + (levels[m] - prev_abs) / (a - prev_abs) * (t - t_prev)


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP)
def _settled(W, j, t, held, a, ma, mb):
    """:func:`stability.simulate.kernel.settled` on the lane's tracker rows of ``W``."""
    r = _TRK
    if not held:
        W[r, j] = -1.0
        return False
    if W[r, j] < 0.0:
        W[r, j], W[r + 1, j] = t, 0.0
    elif W[r + 1, j] == 0.0 and t >= W[r, j] + 0.5 * SETTLE_WINDOW:
        W[r + 1, j], W[r + 2, j], W[r + 3, j], W[r + 4, j] = 1.0, a, ma, mb
    elif W[r + 1, j] != 0.0 and t >= W[r, j] + SETTLE_WINDOW:
        return a <= W[r + 2, j] and ma <= W[r + 3, j] and mb <= W[r + 4, j]
    return False


@njit(cache=True, nogil=True, **_NOWRAP)
def _record(rec, i, row, W, j):
    """:func:`stability.simulate.kernel.record_row` for lane ``j`` (run ``i``), from its rows of ``W``."""
    nc = rec.shape[1]
    xs = (W[_X, j], W[_Y, j], W[_THE, j], W[_THED, j], W[_UD, j], W[_VD, j], W[_E, j], W[_ED, j], W[_B, j],
          W[_BD, j])
    for c in range(min(nc, 10)):
        rec[i, c, row] = xs[c]
    if nc > 10:
        for c in range(8):
            rec[i, 10 + c, row] = W[_F + c, j]
        for c in range(4):
            rec[i, 18 + c, row] = W[_LD + c, j]
            rec[i, 22 + c, row] = W[_SL + c, j]
        rec[i, 26, row] = tire_yaw_moment(_p(W, j), (W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j],
                                                       W[_F + 4, j], W[_F + 5, j], W[_F + 6, j], W[_F + 7, j]),
                                          W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j])
        rec[i, 27, row], rec[i, 28, row] = W[_EXT + 1, j], W[_AC + 2, j]
        rec[i, 29, row], rec[i, 30, row] = W[_AC + 5, j], W[_AC + 6, j]


def lane_physics() -> dict:
    """The lane versions by name (for the tests: each is the scalar kernel's function in the lane namespace)."""
    return {"accelerations": l_accelerations, "plane": l_plane, "contact_loads": l_contact_loads,
            "kinematics": l_kinematics, "slip_angles": l_slip_angles, "tire_resultant": l_tire_resultant}


@_lane
def _p(W, j):
    """Lane ``j``'s chair parameters as a tuple (the scalar helpers index it like a run's ``P``)."""
    return (W[0, j], W[1, j], W[2, j], W[3, j], W[4, j], W[5, j], W[6, j], W[7, j], W[8, j], W[9, j],
            W[10, j], W[11, j], W[12, j], W[13, j], W[14, j], W[15, j], W[16, j], W[17, j])


@_lane
def _s(W, j):
    """Lane ``j``'s per-run scalars as a tuple (a run's ``S``)."""
    return (W[18, j], W[19, j], W[20, j], W[21, j], W[22, j], W[23, j], W[24, j], W[25, j], W[26, j], W[27, j])


# Rows of a block's one work array W (NROWS, LANES): every per-lane quantity of the vectorised loops lives in it, at
# constant offsets from one base, so that LLVM sees no possible aliasing between them (distinct arrays would need a
# runtime check per pair, beyond its limit). The chair parameters (18), the per-run scalars (10), the ten states, the
# lagged yaw acceleration and the previous force sums, the summaries' previous sample and the held yaw moment, the
# rest limits, the caster trig, the contact velocities, slips, loads, tire forces, resultant, accelerations and pin
# moments, the push and yaw moment, the in-plane gravity and the normal gravity, and whether the lane is running.
_PR, _SR, _XR = 0, 18, 28
_X, _Y, _THE, _UD, _VD, _THED, _E, _ED, _B, _BD, _THEDD, _FC1, _FC2 = range(28, 41)
_PREV, _TPREV, _MZH, _RA, _RB = range(41, 46)
_TR, _VEL, _SL, _LD, _F, _FC, _AC, _EXT, _GRAV, _GN, _ACT = 46, 50, 58, 62, 66, 74, 76, 83, 85, 87, 88
# the tires (kinds, scales, fitted ranges, rolling kinds, coefficients and scales, camber, range-rule flags), MECHAN's
# refusal and wheel, the summaries (peak, its time, up to MAX_LEVELS first times, the last recorded time), the settle
# tracker
_TK, _TL, _LIM, _RK, _RC, _RS, _CAM, _CHK, _REF, _STT, _TRK = 89, 92, 95, 101, 103, 109, 111, 113, 117, 119, 128
#: most |yaw rate| levels the lanes kernel reports (the engine passes two)
MAX_LEVELS = 6
# the last recorded row of a run that records its final step only (record="final": written when the call ends), whether
# this step is recorded, whether any step of this call was
_REC, _RECF, _RECANY = 133, 164, 165
NROWS = 166


@njit(cache=True, nogil=True, error_model="numpy", **_NOWRAP)
def _block(lo, hi, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz,
           noise, state, rec, stats, warn, status, nrec):
    """Steps ``k0 .. k1 - 1`` of runs ``lo .. hi - 1`` (at most :data:`LANES`) as lanes (see
    :func:`stability.simulate.kernel.run_one`, whose arithmetic this is)."""
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
    full = rec.shape[1] > 10
    W = np.zeros((NROWS, LANES))
    TSB = np.zeros((3, 6, 8 * LANES))
    next_k = np.zeros(LANES, dtype=np.int64)
    nrc = np.zeros(LANES, dtype=np.int64)
    for j in range(L):
        i = lo + j
        for c in range(18):
            W[_PR + c, j] = P[i, c]
        for c in range(10):
            W[_SR + c, j] = S[i, c]
            W[_XR + c, j] = state[i, c]
        W[_THEDD, j], W[_FC1, j], W[_FC2, j] = state[i, ST_THEDD], state[i, ST_FC1], state[i, ST_FC2]
        W[_PREV, j], W[_TPREV, j], W[_MZH, j] = state[i, ST_PREV], state[i, ST_TPREV], state[i, ST_MZ]
        next_k[j], nrc[j] = int(state[i, ST_NEXTK]), int(state[i, ST_NREC])
        W[_ACT, j] = 1.0 if status[i, 0] == 0.0 and status[i, 2] == 0.0 else 0.0
        if sticks:
            W[_RA, j], W[_RB, j] = P[i, MAF], P[i, MBF]
        for c in range(3):
            W[_TK + c, j], W[_TL + c, j] = TK[i, c], TL[i, c]
            W[_LIM + 2 * c, j], W[_LIM + 2 * c + 1, j] = LIM[i, c, 0], LIM[i, c, 1]
            for r in range(6):
                for q in range(8):
                    TSB[c, r, 8 * j + q] = TS[i, c, r, q]
        for c in range(2):
            W[_RK + c, j], W[_RS + c, j], W[_CAM + c, j] = RK[i, c], RS[i, c], CAM[i, c]
            W[_RC + 3 * c, j], W[_RC + 3 * c + 1, j], W[_RC + 3 * c + 2, j] = RC[i, c, 0], RC[i, c, 1], RC[i, c, 2]
        for c in range(4):
            W[_CHK + c, j] = 1.0 if CHK[i, c] else 0.0
        for c in range(3 + nlev):
            W[_STT + (c if c < 2 + nlev else MAX_LEVELS + 2), j] = stats[i, c]
        for c in range(5):
            W[_TRK + c, j] = state[i, ST_TRACK + c]
    seg_c, seg_m, seg_k = _borrowed(TSB[0]), _borrowed(TSB[1]), _borrowed(TSB[2])
    for k in range(k0, min(k1, n)):
        going = 0.0
        for j in range(L):
            going += W[_ACT, j]
        if going == 0.0:
            break
        t = k * dt
        imp = t <= duimp * (1.0 + 1e-12) + 1e-15
        # SLIP and STATICS, vectorised: caster angles' trig, contact velocities, slip angles, normal loads
        if slope:
            for j in range(L):
                g1, g2, g = l_plane(_p(W, j), cfg, W[_THE, j])
                W[_GRAV, j], W[_GRAV + 1, j], W[_GN, j] = g1, g2, g
        else:
            for j in range(L):
                W[_GN, j] = W[_PR + G, j]
        for j in range(L):
            se, ce = sin_cos(W[_E, j])
            sb, cb = sin_cos(W[_B, j])
            Pj = _p(W, j)
            v8 = l_kinematics(model, Pj, _s(W, j), W[_UD, j], W[_VD, j], W[_THED, j], ce, se, cb, sb, W[_ED, j],
                              W[_BD, j])
            s4 = l_slip_angles(v8)
            n4 = l_contact_loads(Pj, W[_FC1, j], W[_FC2, j], W[_GN, j], ce, se, cb, sb)
            W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j] = ce, se, cb, sb
            W[_VEL, j], W[_VEL + 1, j], W[_VEL + 2, j], W[_VEL + 3, j] = v8[0], v8[1], v8[2], v8[3]
            W[_VEL + 4, j], W[_VEL + 5, j], W[_VEL + 6, j], W[_VEL + 7, j] = v8[4], v8[5], v8[6], v8[7]
            W[_SL, j], W[_SL + 1, j], W[_SL + 2, j], W[_SL + 3, j] = s4
            W[_LD, j], W[_LD + 1, j], W[_LD + 2, j], W[_LD + 3, j] = n4
        # MECHAN, vectorised: tire forces (the block's tire tables side by side)
        tire_imp = ftimp != 0.0 and imp
        for j in range(L):
            f8, refused, w = l_mechan(
                (W[_VEL, j], W[_VEL + 1, j], W[_VEL + 2, j], W[_VEL + 3, j], W[_VEL + 4, j], W[_VEL + 5, j],
                 W[_VEL + 6, j], W[_VEL + 7, j]), (W[_SL, j], W[_SL + 1, j], W[_SL + 2, j], W[_SL + 3, j]),
                (W[_LD, j], W[_LD + 1, j], W[_LD + 2, j], W[_LD + 3, j]), tire_imp, ftimp, policy, _t3(W, _TK, j),
                seg_c, seg_m, seg_k, _t3(W, _TL, j), _t2(W, _LIM, j), _t2(W, _LIM + 2, j), _t2(W, _LIM + 4, j),
                _t2(W, _RK, j), _t3(W, _RC, j), _t3(W, _RC + 3, j), _t2(W, _RS, j), _t2(W, _CAM, j), _s(W, j), 8 * j)
            W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j], \
                W[_F + 7, j] = f8
            W[_REF, j], W[_REF + 1, j] = float(refused), float(w)
        # the range rules (counted where one is exceeded: the scalar kernel's function), refusals, the controller
        for j in range(L):
            if W[_ACT, j] == 0.0:
                continue
            i = lo + j
            loads = (W[_LD, j], W[_LD + 1, j], W[_LD + 2, j], W[_LD + 3, j])
            slips = (W[_SL, j], W[_SL + 1, j], W[_SL + 2, j], W[_SL + 3, j])
            nmax = -math.inf
            smax = 0.0
            for c in range(4):
                if W[_CHK + c, j] != 0.0:
                    nmax = max(nmax, loads[c])
                    smax = max(smax, abs(slips[c]))
            if nmax > maxload or smax > maxslip or min(min(loads[0], loads[1]), min(loads[2], loads[3])) < 0.0:
                chk = (W[_CHK, j] != 0.0, W[_CHK + 1, j] != 0.0, W[_CHK + 2, j] != 0.0, W[_CHK + 3, j] != 0.0)
                if range_check(warn[i], t, loads, slips, chk, maxload, maxslip, stop, nwarn_limit):
                    status[i, 0], status[i, 1] = STOPPED_WARNINGS, t
                    W[_ACT, j] = 0.0
                    continue
            refused = int(W[_REF, j])
            if refused != 0:
                w = int(W[_REF + 1, j])
                status[i, 2], status[i, 3] = refused, w
                status[i, 4], status[i, 5] = (slips[w], loads[w]) if refused == 1 else (CAM[i, 0], loads[w])
                W[_ACT, j] = 0.0
                continue
            mz = W[_MZH, j] if ext else 0.0
            if use_ctl:
                held, nk = controlled(t, next_k[j], W[_MZH, j], state[i, NSTATE:NSTATE + nz], znew, y, sv,
                                      (W[_XR, j], W[_XR + 1, j], W[_XR + 2, j], W[_XR + 3, j], W[_XR + 4, j],
                                       W[_XR + 5, j], W[_XR + 6, j], W[_XR + 7, j], W[_XR + 8, j], W[_XR + 9, j]),
                                      ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
                W[_MZH, j], next_k[j] = held, nk
                mz = held
            W[_EXT + 1, j] = mz
        # DYNAM, vectorised: the resultant and the accelerations with the kinetic pin moments
        for j in range(L):
            ce, se, cb, sb = W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j]
            f8 = (W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j],
                  W[_F + 7, j])
            f1, f2 = l_tire_resultant(*f8, ce, se, cb, sb)
            fimp = W[_SR + FCIMP, j]
            fy = fimp if (fimp != 0.0 and imp) else 0.0
            Pj = _p(W, j)
            ma = l_kinetic(W[_ED, j], Pj[MAF])
            mb = l_kinetic(W[_BD, j], Pj[MBF])
            a5 = l_accelerations(model, (W[_UD, j], W[_VD, j], W[_THED, j], ce, se, cb, sb, W[_ED, j], W[_BD, j]),
                                 f8, ma, mb, fy, W[_EXT + 1, j], W[_THEDD, j], Pj, W[_GRAV, j], W[_GRAV + 1, j])
            W[_FC, j], W[_FC + 1, j], W[_EXT, j] = f1, f2, fy
            W[_AC, j], W[_AC + 1, j], W[_AC + 2, j], W[_AC + 3, j], W[_AC + 4, j] = a5
            W[_AC + 5, j], W[_AC + 6, j] = ma, mb
        # held casters (locked, or stuck under stick-slip), lane by lane: the scalar kernel's solve
        if locked or sticks:
            for j in range(L):
                if W[_ACT, j] == 0.0 or not (locked or W[_ED, j] == 0.0 or W[_BD, j] == 0.0):
                    continue
                i = lo + j
                st_ = (W[_UD, j], W[_VD, j], W[_THED, j], W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j],
                       W[_ED, j], W[_BD, j])
                f8 = (W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j],
                      W[_F + 7, j])
                if locked:
                    a5, ma, mb = held_pins(model, st_, f8, 0.0, 0.0, True, True, W[_EXT, j], W[_EXT + 1, j],
                                           W[_THEDD, j], _p(W, j), W[_GRAV, j], W[_GRAV + 1, j])
                else:
                    a5, ma, mb = stick_slip(model, st_, f8, W[_EXT, j], W[_EXT + 1, j], W[_THEDD, j], _p(W, j),
                                            W[_GRAV, j], W[_GRAV + 1, j])
                W[_AC, j], W[_AC + 1, j], W[_AC + 2, j], W[_AC + 3, j], W[_AC + 4, j] = a5
                if locked:
                    W[_AC + 3, j] = W[_AC + 4, j] = 0.0
                W[_AC + 5, j], W[_AC + 6, j] = ma, mb
        # the summaries, the record and the stop rules, lane by lane
        for j in range(L):
            if W[_ACT, j] == 0.0:
                continue
            i = lo + j
            a = abs(W[_THED, j])
            if not a < math.inf:
                W[_STT, j] = math.nan
                status[i, 0], status[i, 1] = STOPPED_NONFINITE, t
                W[_ACT, j] = 0.0
                continue
            _summaries(W, j, nlev, levels, k, t, a, W[_PREV, j], W[_TPREV, j])
            W[_PREV, j], W[_TPREV, j] = a, t
            if mode == 2:                       # kept in W (a vectorised copy below), written when the call ends
                W[_RECF, j] = 1.0
                nrc[j] = 1
                W[_STT + MAX_LEVELS + 2, j] = t
            elif k % stride == 0:
                row = k // stride
                _record(rec, i, row, W, j)
                nrc[j] = row + 1
                W[_STT + MAX_LEVELS + 2, j] = t
            if stop_lvl >= 0 and W[_STT + 2 + stop_lvl, j] == W[_STT + 2 + stop_lvl, j]:
                status[i, 0], status[i, 1] = STOPPED_LEVEL, t
                W[_ACT, j] = 0.0
                continue
            if settle and _settled(W, j, t, t > duimp and W[_ED, j] == 0.0 and W[_BD, j] == 0.0
                                   and W[_AC + 3, j] == 0.0 and W[_AC + 4, j] == 0.0, a, abs(W[_AC + 5, j]),
                                   abs(W[_AC + 6, j])):
                status[i, 0], status[i, 1] = STOPPED_SETTLED, t
                W[_ACT, j] = 0.0
        if mode == 2:       # record="final": this step's row, vectorised, where it is recorded
            for j in range(L):
                on = W[_RECF, j] != 0.0
                W[_RECANY, j] = 1.0 if on else W[_RECANY, j]
                W[_RECF, j] = 0.0
                vals = (W[_X, j], W[_Y, j], W[_THE, j], W[_THED, j], W[_UD, j], W[_VD, j], W[_E, j], W[_ED, j],
                        W[_B, j], W[_BD, j])
                for c in range(10):
                    W[_REC + c, j] = vals[c] if on else W[_REC + c, j]
                if full:
                    for c in range(8):
                        W[_REC + 10 + c, j] = W[_F + c, j] if on else W[_REC + 10 + c, j]
                    for c in range(4):
                        W[_REC + 18 + c, j] = W[_LD + c, j] if on else W[_REC + 18 + c, j]
                        W[_REC + 22 + c, j] = W[_SL + c, j] if on else W[_REC + 22 + c, j]
                    mzt = l_tire_moment(W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j],
                                        W[_F + 5, j], W[_F + 6, j], W[_F + 7, j], W[_TR, j], W[_TR + 1, j],
                                        W[_TR + 2, j], W[_TR + 3, j], W[_PR + X_M, j], W[_PR + X_P, j],
                                        W[_PR + D1, j], W[_PR + D2, j], W[_PR + T1, j], W[_PR + T2, j],
                                        W[_PR + TRAIL, j])
                    W[_REC + 26, j] = mzt if on else W[_REC + 26, j]
                    W[_REC + 27, j] = W[_EXT + 1, j] if on else W[_REC + 27, j]
                    W[_REC + 28, j] = W[_AC + 2, j] if on else W[_REC + 28, j]
                    W[_REC + 29, j] = W[_AC + 5, j] if on else W[_REC + 29, j]
                    W[_REC + 30, j] = W[_AC + 6, j] if on else W[_REC + 30, j]
        # UPDATE / ITRATE, vectorised (a stopped lane keeps its state)
        for j in range(L):
            on = W[_ACT, j] != 0.0
            X, Y, THE, UD, VD, THED = W[_X, j], W[_Y, j], W[_THE, j], W[_UD, j], W[_VD, j], W[_THED, j]
            E, ED, B, BD = W[_E, j], W[_ED, j], W[_B, j], W[_BD, j]
            UDD, VDD, THEDD, EDD, BDD = W[_AC, j], W[_AC + 1, j], W[_AC + 2, j], W[_AC + 3, j], W[_AC + 4, j]
            du = UD * dt + UDD * half_dt2
            dv = VD * dt + VDD * half_dt2
            sint, cost = sin_cos(THE)
            W[_X, j] = X + (du * cost - dv * sint) if on else X
            W[_Y, j] = Y + (du * sint + dv * cost) if on else Y
            W[_UD, j] = UD + UDD * dt if on else UD
            W[_VD, j] = VD + VDD * dt if on else VD
            W[_B, j] = B + (BD * dt + BDD * half_dt2) if on else B
            W[_E, j] = E + (ED * dt + EDD * half_dt2) if on else E
            W[_BD, j] = l_rest_rate(BD, BD + BDD * dt, W[_RB, j]) if on else BD
            W[_ED, j] = l_rest_rate(ED, ED + EDD * dt, W[_RA, j]) if on else ED
            W[_THE, j] = THE + (THED * dt + THEDD * half_dt2) if on else THE
            W[_THED, j] = THED + THEDD * dt if on else THED
            W[_THEDD, j] = THEDD if on else W[_THEDD, j]
            W[_FC1, j] = W[_FC, j] if on else W[_FC1, j]
            W[_FC2, j] = W[_FC + 1, j] + W[_EXT, j] if on else W[_FC2, j]
    for j in range(L):
        i = lo + j
        for c in range(10):
            state[i, c] = W[_XR + c, j]
        state[i, ST_THEDD], state[i, ST_FC1], state[i, ST_FC2] = W[_THEDD, j], W[_FC1, j], W[_FC2, j]
        state[i, ST_PREV], state[i, ST_TPREV], state[i, ST_MZ] = W[_PREV, j], W[_TPREV, j], W[_MZH, j]
        state[i, ST_NEXTK], state[i, ST_NREC] = next_k[j], nrc[j]
        nrec[i] = nrc[j]
        for c in range(3 + nlev):
            stats[i, c] = W[_STT + (c if c < 2 + nlev else MAX_LEVELS + 2), j]
        for c in range(5):
            state[i, ST_TRACK + c] = W[_TRK + c, j]
        if mode == 2 and W[_RECANY, j] != 0.0:
            for c in range(rec.shape[1]):
                rec[i, c, 0] = W[_REC + c, j]


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
