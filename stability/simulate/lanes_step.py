"""The lanes kernel's step, phase by phase: each phase one loop over a block's runs on its work array ``W``.

The vectorised phases (:func:`slip_statics`, :func:`tire_forces`, :func:`dynam`, :func:`update`, the masks of
:func:`checks` and :func:`stops`; the final row's copy is the block's, :mod:`.lanes_kernel`) are arithmetic on ``W``'s
rows (:mod:`.lanes_physics`); the lanes a mask picks go lane by lane through the scalar kernel's functions.  All are
inlined into the lanes kernel's block, where ``W`` has a constant shape: the rows' distances are constants, and LLVM
vectorises without aliasing checks."""

from __future__ import annotations

import math

from numba import njit

from stability.simulate.kernel import (
    FCIMP,
    MAF,
    MBF,
    NSTATE,
    SETTLE_WINDOW,
    STOPPED_LEVEL,
    STOPPED_NONFINITE,
    STOPPED_SETTLED,
    STOPPED_WARNINGS,
    G,
    controlled,
    held_pins,
    range_check,
    stick_slip,
    tire_yaw_moment,
)
from stability.simulate.kernel_equations import _LINK, _NOWRAP
from stability.simulate.lanemath import sin_cos
from stability.simulate.lanes_physics import (
    _p,
    _s,
    l_accelerations,
    l_contact_loads,
    l_kinematics,
    l_kinetic,
    l_mechan,
    l_plane,
    l_rest_rate,
    l_slip_angles,
    l_table,
    l_tire_resultant,
)

__all__ = ["LANES", "MAX_LEVELS", "NROWS", "slip_statics", "tire_forces", "checks", "dynam", "held", "stops",
           "update"]

#: runs per block (measured: docs/simulator.md, "Runs as lanes"); the numbers do not depend on it
LANES = 64
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
#: a lane whose held caster breaks away this step (its stick-slip solve is the scalar kernel's, lane by lane)
_HELD = 166
_ATTN, _EVT = 167, 168        # the masks of checks and stops: a lane they take lane by lane this step
_TAB = 169     # the tire tables (casters, main wheels, camber), 48 rows each (l_table)
# record="final": the recorded step's caster trig (its tire yaw moment is computed once, when the call ends)
_RECTR = _TAB + 3 * 48
NROWS = _RECTR + 4


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
def _summaries(W, j, nlev, levels, k, t, a, prev_abs, t_prev):
    """:func:`stability.simulate.kernel.summaries` on the lane's rows of ``W`` (no per-run array view)."""
    if a > W[_STT, j] or k == 0:
        W[_STT, j], W[_STT + 1, j] = a, t
    for m in range(nlev):
        r = _STT + 2 + m
        if W[r, j] != W[r, j] and a >= levels[m]:
            W[r, j] = t if k == 0 else t_prev + (levels[m] - prev_abs) / (a - prev_abs) * (t - t_prev)


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
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


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def slip_statics(W, L, model, slope, cfg):
    """SLIP and STATICS, vectorised: caster trig, contact velocities, slip angles, normal loads."""
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


#: the camber table :func:`tire_forces` passes MECHAN in a block without camber (looked up only where the angle is 0)
_NO_CAMBER = (0.0,) * 48


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _mechan(W, j, ftimp, tire_imp, policy, seg_k):
    """MECHAN for lane ``j`` on its rows of ``W`` (camber table ``seg_k``), its forces and refusal stored in ``W``."""
    f8, refused, w = l_mechan(
        (W[_VEL, j], W[_VEL + 1, j], W[_VEL + 2, j], W[_VEL + 3, j], W[_VEL + 4, j], W[_VEL + 5, j],
         W[_VEL + 6, j], W[_VEL + 7, j]), (W[_SL, j], W[_SL + 1, j], W[_SL + 2, j], W[_SL + 3, j]),
        (W[_LD, j], W[_LD + 1, j], W[_LD + 2, j], W[_LD + 3, j]), tire_imp, ftimp, policy,
        (W[_TK, j], W[_TK + 1, j], W[_TK + 2, j]), l_table(W, _TAB + 0, j), l_table(W, _TAB + 48, j),
        seg_k, (W[_TL, j], W[_TL + 1, j], W[_TL + 2, j]),
        (W[_LIM, j], W[_LIM + 1, j]), (W[_LIM + 2, j], W[_LIM + 3, j]), (W[_LIM + 4, j], W[_LIM + 5, j]),
        (W[_RK, j], W[_RK + 1, j]), (W[_RC, j], W[_RC + 1, j], W[_RC + 2, j]),
        (W[_RC + 3, j], W[_RC + 4, j], W[_RC + 5, j]), (W[_RS, j], W[_RS + 1, j]), (W[_CAM, j], W[_CAM + 1, j]),
        _s(W, j), 0)   # rows as tuples: a helper taking the offset compiles once per offset (_TAB + 0: int64)
    W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j], W[_F + 7, j] = f8
    W[_REF, j], W[_REF + 1, j] = float(refused), float(w)


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def tire_forces(W, L, ftimp, imp, policy, camber):
    """MECHAN, vectorised: the tire forces (the lane's tables read as tuples, :func:`.lanes_physics.l_table`).

    A block no run of which has a camber angle (``camber`` False) passes a table of zeros for the camber table,
    which MECHAN then never looks up: its 48 rows are not read, the same forces bit for bit."""
    tire_imp = ftimp != 0.0 and imp
    if camber:
        for j in range(L):
            _mechan(W, j, ftimp, tire_imp, policy, l_table(W, _TAB + 96, j))
    else:
        for j in range(L):
            _mechan(W, j, ftimp, tire_imp, policy, _NO_CAMBER)


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _attention(W, L, maxload, maxslip, ext, use_ctl):
    """Which lanes :func:`checks` takes lane by lane (``W[_ATTN]``), vectorised: a tested tire's load or slip beyond
    its limit or a negative load (the range rule counts), a refusal, or the controller; every lane's yaw moment
    ``W[_EXT + 1]`` (the held external moment, or none: what :func:`checks` leaves for a lane it does not take)."""
    for j in range(L):
        nmax = -math.inf
        smax = 0.0
        l0, l1, l2, l3 = W[_LD, j], W[_LD + 1, j], W[_LD + 2, j], W[_LD + 3, j]
        c0, c1, c2, c3 = W[_CHK, j] != 0.0, W[_CHK + 1, j] != 0.0, W[_CHK + 2, j] != 0.0, W[_CHK + 3, j] != 0.0
        nmax = max(nmax, l0) if c0 else nmax
        smax = max(smax, abs(W[_SL, j])) if c0 else smax
        nmax = max(nmax, l1) if c1 else nmax
        smax = max(smax, abs(W[_SL + 1, j])) if c1 else smax
        nmax = max(nmax, l2) if c2 else nmax
        smax = max(smax, abs(W[_SL + 2, j])) if c2 else smax
        nmax = max(nmax, l3) if c3 else nmax
        smax = max(smax, abs(W[_SL + 3, j])) if c3 else smax
        bad = (nmax > maxload) | (smax > maxslip) | (min(min(l0, l1), min(l2, l3)) < 0.0) | (W[_REF, j] != 0.0)
        W[_ATTN, j] = 1.0 if (W[_ACT, j] != 0.0) & (bad | use_ctl) else 0.0
        W[_EXT + 1, j] = W[_MZH, j] if ext else 0.0


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def checks(W, L, runs, t, warn, status, CAM, maxload, maxslip, stop, nwarn_limit, ext, use_ctl, next_k, state, nz,
           znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    """The range rules (counted where a limit is exceeded, by the scalar kernel's function), refusals, the
    controller: lane by lane for the lanes that need one (:func:`_attention`, vectorised); lane ``j`` is run
    ``runs[j]``."""
    _attention(W, L, maxload, maxslip, ext, use_ctl)
    for j in range(L):
        if W[_ATTN, j] == 0.0:
            continue
        i = runs[j]
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


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _dynam_kinetic(W, L, model, imp):
    """DYNAM, vectorised: the resultant and the accelerations under the kinetic pin moments (no caster held)."""
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


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _dynam_held(W, L, model, imp, sticks, locked):
    """DYNAM, vectorised: the resultant and the accelerations; held casters (locked, or at rest under stick-slip)
    solved here too, by :func:`stability.simulate.kernel_equations.held_pins`'s arithmetic on its three evaluations
    (their points are known before the solve), except a lane whose held caster breaks away: ``W[_HELD]`` 1, left to
    :func:`held` (the scalar kernel's :func:`~stability.simulate.kernel_equations.stick_slip`)."""
    for j in range(L):
        ce, se, cb, sb = W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j]
        f8 = (W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j],
              W[_F + 7, j])
        f1, f2 = l_tire_resultant(*f8, ce, se, cb, sb)
        fimp = W[_SR + FCIMP, j]
        fy = fimp if (fimp != 0.0 and imp) else 0.0
        Pj = _p(W, j)
        ed, bd = W[_ED, j], W[_BD, j]
        ma = 0.0 if locked else l_kinetic(ed, Pj[MAF])
        mb = 0.0 if locked else l_kinetic(bd, Pj[MBF])
        ha = locked or (sticks and ed == 0.0)
        hb = locked or (sticks and bd == 0.0)
        st_ = (W[_UD, j], W[_VD, j], W[_THED, j], ce, se, cb, sb, ed, bd)
        mz, rdc, g1, g2 = W[_EXT + 1, j], W[_THEDD, j], W[_GRAV, j], W[_GRAV + 1, j]
        # held_pins' evaluation points: both held (0, 0), (1, 0), (0, 1); one held (0|1, other's moment)
        p0a, p0b = (0.0 if ha else ma), (0.0 if hb else mb)
        p1a, p1b = (1.0 if ha else ma), (0.0 if (ha and hb) else (1.0 if hb else mb))
        p2a, p2b = p0a, (1.0 if (ha and hb) else p0b)
        a0 = l_accelerations(model, st_, f8, p0a, p0b, fy, mz, rdc, Pj, g1, g2)
        a1 = l_accelerations(model, st_, f8, p1a, p1b, fy, mz, rdc, Pj, g1, g2)
        a2 = l_accelerations(model, st_, f8, p2a, p2b, fy, mz, rdc, Pj, g1, g2)
        # both held
        k11, k21 = a1[3] - a0[3], a1[4] - a0[4]
        k12, k22 = a2[3] - a0[3], a2[4] - a0[4]
        det = k11 * k22 - k12 * k21
        bma = (-a0[3] * k22 + a0[4] * k12) / det
        bmb = (-a0[4] * k11 + a0[3] * k21) / det
        # one held (A, or B)
        ra = -a0[3] / (a1[3] - a0[3])
        rb = -a0[4] / (a1[4] - a0[4])
        both, only_a, only_b = ha and hb, ha and not hb, hb and not ha
        r = ra if only_a else rb
        MA = bma if both else (ra if only_a else ma)
        MB = bmb if both else (rb if only_b else mb)
        u = a0[0] + bma * (a1[0] - a0[0]) + bmb * (a2[0] - a0[0]) if both else a0[0] + r * (a1[0] - a0[0])
        v = a0[1] + bma * (a1[1] - a0[1]) + bmb * (a2[1] - a0[1]) if both else a0[1] + r * (a1[1] - a0[1])
        w = a0[2] + bma * (a1[2] - a0[2]) + bmb * (a2[2] - a0[2]) if both else a0[2] + r * (a1[2] - a0[2])
        e = 0.0 if (both or only_a) else (a0[3] + r * (a1[3] - a0[3]) if only_b else a0[3])
        b = 0.0 if (both or only_b) else (a0[4] + r * (a1[4] - a0[4]) if only_a else a0[4])
        held_any = ha or hb
        W[_FC, j], W[_FC + 1, j], W[_EXT, j] = f1, f2, fy
        W[_AC, j] = u if held_any else a0[0]
        W[_AC + 1, j] = v if held_any else a0[1]
        W[_AC + 2, j] = w if held_any else a0[2]
        W[_AC + 3, j] = 0.0 if locked else e
        W[_AC + 4, j] = 0.0 if locked else b
        W[_AC + 5, j], W[_AC + 6, j] = MA, MB
        free = not locked and ((ha and not abs(MA) <= Pj[MAF]) or (hb and not abs(MB) <= Pj[MBF]))
        W[_HELD, j] = 1.0 if free else 0.0


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _held_lanes(W, L):
    """How many running lanes have a caster at rest (stick-slip: held this step), vectorised."""
    n = 0
    for j in range(L):
        n += int((W[_ACT, j] != 0.0) & ((W[_ED, j] == 0.0) | (W[_BD, j] == 0.0)))
    return n


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def dynam(W, L, model, imp, sticks, locked, vec_held):
    """DYNAM, vectorised: the kinetic law's one evaluation of the accelerations, or (``vec_held``) the holding
    solve's three; without ``vec_held`` (a block too small to vectorise) :func:`held` solves held casters.  A
    stick-slip block none of whose running lanes holds a caster this step evaluates once: for such a lane the
    holding solve's first evaluation is the kinetic law's, with the same arguments, and the only one it uses."""
    if vec_held and (locked or _held_lanes(W, L) > 0):
        _dynam_held(W, L, model, imp, sticks, locked)
    else:
        _dynam_kinetic(W, L, model, imp)
        if vec_held:
            for j in range(L):
                W[_HELD, j] = 0.0


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def held(W, L, model, locked, vec_held):
    """Held casters lane by lane, the scalar kernel's solve: with ``vec_held`` only a caster breaking away under
    stick-slip (``W[_HELD]``), else every locked or resting caster (the same arithmetic as the vectorised solve)."""
    for j in range(L):
        if W[_ACT, j] == 0.0:
            continue
        if (W[_HELD, j] == 0.0) if vec_held else not (locked or W[_ED, j] == 0.0 or W[_BD, j] == 0.0):
            continue
        st_ = (W[_UD, j], W[_VD, j], W[_THED, j], W[_TR, j], W[_TR + 1, j], W[_TR + 2, j], W[_TR + 3, j],
               W[_ED, j], W[_BD, j])
        f8 = (W[_F, j], W[_F + 1, j], W[_F + 2, j], W[_F + 3, j], W[_F + 4, j], W[_F + 5, j], W[_F + 6, j],
              W[_F + 7, j])
        if locked:
            a5, ma, mb = held_pins(model, st_, f8, 0.0, 0.0, locked, locked, W[_EXT, j], W[_EXT + 1, j],
                                   W[_THEDD, j], _p(W, j), W[_GRAV, j], W[_GRAV + 1, j])
        else:
            a5, ma, mb = stick_slip(model, st_, f8, W[_EXT, j], W[_EXT + 1, j], W[_THEDD, j], _p(W, j),
                                    W[_GRAV, j], W[_GRAV + 1, j])
        W[_AC, j], W[_AC + 1, j], W[_AC + 2, j], W[_AC + 3, j], W[_AC + 4, j] = a5
        if locked:
            W[_AC + 3, j] = W[_AC + 4, j] = 0.0
        W[_AC + 5, j], W[_AC + 6, j] = ma, mb


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _quiet_step(W, L, k, t, lv, mode, settle):
    """The summaries of the running lanes without an event this step, vectorised: the peak |yaw rate| and its
    time, the previous sample, the final row's flag and time (``record="final"``); ``W[_EVT]`` 1 for a lane with an
    event (a first crossing of a level, a non-finite yaw rate, a settle tracker to step), left to :func:`stops`.
    A lane without an event reaches no new level, so no stop rule fires for it."""
    l0, l1, l2, l3, l4, l5 = lv
    r = _STT + 2
    for j in range(L):
        on = W[_ACT, j] != 0.0
        a = abs(W[_THED, j])
        ev = settle | (not a < math.inf)
        ev = ev | ((W[r, j] != W[r, j]) & (a >= l0)) | ((W[r + 1, j] != W[r + 1, j]) & (a >= l1))
        ev = ev | ((W[r + 2, j] != W[r + 2, j]) & (a >= l2)) | ((W[r + 3, j] != W[r + 3, j]) & (a >= l3))
        ev = ev | ((W[r + 4, j] != W[r + 4, j]) & (a >= l4)) | ((W[r + 5, j] != W[r + 5, j]) & (a >= l5))
        W[_EVT, j] = 1.0 if on & ev else 0.0
        quiet = on & (not ev)
        peak = quiet & ((a > W[_STT, j]) | (k == 0))
        W[_STT, j] = a if peak else W[_STT, j]
        W[_STT + 1, j] = t if peak else W[_STT + 1, j]
        W[_PREV, j] = a if quiet else W[_PREV, j]
        W[_TPREV, j] = t if quiet else W[_TPREV, j]
        if mode == 2:
            W[_RECF, j] = 1.0 if quiet else W[_RECF, j]
            W[_STT + MAX_LEVELS + 2, j] = t if quiet else W[_STT + MAX_LEVELS + 2, j]


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def stops(W, L, runs, k, t, levels, lv, nlev, mode, stride, rec, nrc, status, stop_lvl, settle, duimp):
    """The summaries, the record (every ``stride`` steps) and the stop rules: vectorised for the lanes without an
    event (:func:`_quiet_step`), lane by lane for the others and for a recorded step (``record`` not "final");
    lane ``j`` is run ``runs[j]``."""
    _quiet_step(W, L, k, t, lv, mode, settle)
    record_now = mode != 2 and k % stride == 0
    for j in range(L):
        if W[_EVT, j] == 0.0:
            if record_now and W[_ACT, j] != 0.0:
                row = k // stride
                _record(rec, runs[j], row, W, j)
                nrc[j] = row + 1
                W[_STT + MAX_LEVELS + 2, j] = t
            continue
        i = runs[j]
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


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def update(W, L, dt, half_dt2):
    """UPDATE / ITRATE, vectorised (a stopped lane keeps its state)."""
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
