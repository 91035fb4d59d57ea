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
inf instead of raising, so the loops have no exits).  MECHAN is vectorised
too: a block's tire tables are rows of its work array, read per lane
unconditionally and looked up by selects
(:func:`stability.simulate.lanes_physics.l_segment_force`), since a gather
at an index read from the data, or a load under a condition, keeps LLVM from
vectorising the loop.  The holding solve is vectorised where a caster is
held (its three evaluations); a caster breaking away, the range rules'
counting, the controller and the summaries and stop rules of a lane with an
event run lane by lane through the scalar kernel's functions, unchanged.

So a run's numbers differ from the scalar kernel's only through the
polynomials' rounding (:mod:`stability.simulate.lanemath`: within 2 ulp for
sine and cosine, 3 ulp for the slip angle's arctangent); docs/simulator.md
states the tolerance that follows and ``tests/test_lanes_kernel.py`` checks
it.  A run's numbers do not depend on the block size, on its place in the
block or on the other runs (every lane executes the same instructions; LLVM
does not contract multiplies and adds into FMAs without fast-math, so the
vector and scalar forms of a loop round alike), nor on the columns it moves
to when other lanes of its block stop (:func:`_compact`: a block steps its
running lanes only).
"""

from __future__ import annotations

import math
from functools import partial
from typing import Any

import numpy as np
from numba import get_num_threads, literally, njit, parallel_chunksize, prange, set_num_threads, typeof
from numba import types as _nbtypes
from numba._dispatcher import compute_fingerprint

from stability.simulate import lanes_physics as _lp  # a module: its uncached dispatchers stay out of globals()
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.first_use import first_use
from stability.simulate.kernel import (
    D1,
    D2,
    EXTERNAL_MZ,
    MAF,
    MBF,
    SETTLE,
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
    T1,
    T2,
    TRAIL,
    X_M,
    X_P,
    variant,
)
from stability.simulate.kernel_equations import _LINK, _NOWRAP
from stability.simulate.lanes_physics import lane_physics
from stability.simulate.lanes_step import (
    _AC,
    _ACT,
    _CAM,
    _CHK,
    _E,
    _EXT,
    _F,
    _FC1,
    _FC2,
    _LD,
    _LIM,
    _MZH,
    _PR,
    _PREV,
    _RA,
    _RB,
    _RC,
    _REC,
    _RECANY,
    _RECF,
    _RECTR,
    _RK,
    _RS,
    _SL,
    _SR,
    _STT,
    _TAB,
    _THE,
    _THED,
    _THEDD,
    _TK,
    _TL,
    _TPREV,
    _TR,
    _TRK,
    _UD,
    _VD,
    _X,
    _XR,
    _Y,
    LANES,
    MAX_LEVELS,
    NROWS,
    checks,
    dynam,
    held,
    slip_statics,
    stops,
    tire_forces,
    update,
)
from stability.simulate.native_call import address, call_none_at

__all__ = ["LANES", "MAX_LEVELS", "run_lanes", "lane_physics", "get_num_threads", "set_num_threads",
           "parallel_chunksize"]


#: stopped lanes that make a block move its running lanes to its first columns and step those only (:func:`_compact`):
#: one vector of doubles on an AVX-512 machine, so that the vectorised loops run at least one iteration fewer (measured
#: against a half, a quarter and two vectors: docs/simulator.md, "Runs as lanes")
COMPACT_AFTER = 8

#: smallest block whose holding solve is vectorised (three evaluations for every lane); a smaller block (one run)
#: solves only its held lanes, lane by lane, with the same arithmetic (tested: blocks of 1, 8 and 64 agree bit for bit)
VEC_HELD_MIN = 4


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
def padded_levels(levels):
    """The |yaw rate| levels (rad/s) as :data:`MAX_LEVELS` scalars, infinite beyond ``levels`` (never reached)."""
    n, inf = levels.shape[0], math.inf          # no array operation: their error paths cost seconds to compile
    return (levels[0] if n > 0 else inf, levels[1] if n > 1 else inf, levels[2] if n > 2 else inf,
            levels[3] if n > 3 else inf, levels[4] if n > 4 else inf, levels[5] if n > 5 else inf)


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
def _load(W, next_k, nrc, lo, L, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, state, stats, status, nlev, sticks):
    """The block's runs into ``W``'s rows (the tire tables too: row ``_TAB + 48 c + 8 r + q``); whether a run of the
    block has a camber angle (MECHAN's test: :func:`.lanes_step.tire_forces`)."""
    camber = False
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
        W[_RA, j], W[_RB, j] = (P[i, MAF], P[i, MBF]) if sticks else (0.0, 0.0)
        for c in range(3):
            W[_TK + c, j], W[_TL + c, j] = TK[i, c], TL[i, c]
            W[_LIM + 2 * c, j], W[_LIM + 2 * c + 1, j] = LIM[i, c, 0], LIM[i, c, 1]
            for r in range(6):
                for q in range(8):
                    W[_TAB + 48 * c + 8 * r + q, j] = TS[i, c, r, q]
        for c in range(2):
            W[_RK + c, j], W[_RS + c, j], W[_CAM + c, j] = RK[i, c], RS[i, c], CAM[i, c]
            W[_RC + 3 * c, j], W[_RC + 3 * c + 1, j], W[_RC + 3 * c + 2, j] = RC[i, c, 0], RC[i, c, 1], RC[i, c, 2]
        for c in range(4):
            W[_CHK + c, j] = 1.0 if CHK[i, c] else 0.0
        for c in range(3 + nlev):
            W[_STT + (c if c < 2 + nlev else MAX_LEVELS + 2), j] = stats[i, c]
        for c in range(5):
            W[_TRK + c, j] = state[i, ST_TRACK + c]
        camber = camber or CAM[i, 0] != 0.0
    return camber


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def _keep(W, dst, src, j, on):
    """``W[dst, j] = W[src, j]`` where ``on``: a store under a condition (a masked store once vectorised; a select
    of the two loads LLVM turns into a load at a selected address, which keeps the loop scalar)."""
    if on:
        W[dst, j] = W[src, j]


@njit(cache=True, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)
def final_row(W, L, full):
    """record="final": this step's row where it is recorded, vectorised (written when the call ends).

    Every column is copied between constant rows by :func:`_keep`, a store under the lane's flag (a masked store
    once vectorised; a select of the two loads, as this copy once had, kept LLVM from vectorising it).  The tire yaw
    moment's column is not computed here every step: the caster angles' cosines and sines are kept (rows
    ``_RECTR``) and :func:`_store` computes the moment once, by the same function from the same numbers."""
    for j in range(L):
        on = W[_RECF, j] != 0.0
        W[_RECANY, j] = 1.0 if on else W[_RECANY, j]
        W[_RECF, j] = 0.0
        # the rows as int64 (a bare global is a numba literal, and _keep would compile once per row: "+ 0")
        _keep(W, _REC + 0, _X + 0, j, on)
        _keep(W, _REC + 1, _Y + 0, j, on)
        _keep(W, _REC + 2, _THE + 0, j, on)
        _keep(W, _REC + 3, _THED + 0, j, on)
        _keep(W, _REC + 4, _UD + 0, j, on)
        _keep(W, _REC + 5, _VD + 0, j, on)
        for c in range(4):                      # E, ED, B, BD: consecutive rows, as the record's columns
            _keep(W, _REC + 6 + c, _E + c, j, on)
        if full:
            for c in range(8):
                _keep(W, _REC + 10 + c, _F + c, j, on)
            for c in range(4):
                _keep(W, _REC + 18 + c, _LD + c, j, on)
                _keep(W, _REC + 22 + c, _SL + c, j, on)
                _keep(W, _RECTR + c, _TR + c, j, on)
            _keep(W, _REC + 27, _EXT + 1, j, on)
            _keep(W, _REC + 28, _AC + 2, j, on)
            _keep(W, _REC + 29, _AC + 5, j, on)
            _keep(W, _REC + 30, _AC + 6, j, on)


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
def _store_lane(W, j, i, next_k, nrc, state, stats, rec, nrec, nlev, mode):
    """Lane ``j`` of the block back from ``W`` into run ``i``: its state, summaries, the final row
    (``record="final"``)."""
    for c in range(10):
        state[i, c] = W[_XR + c, j]
    state[i, ST_THEDD], state[i, ST_FC1], state[i, ST_FC2] = W[_THEDD, j], W[_FC1, j], W[_FC2, j]
    state[i, ST_PREV], state[i, ST_TPREV], state[i, ST_MZ] = W[_PREV, j], W[_TPREV, j], W[_MZH, j]
    if mode == 2 and W[_RECANY, j] != 0.0:        # record="final": a step recorded in this call (final_row)
        nrc[j] = 1
    state[i, ST_NEXTK], state[i, ST_NREC] = next_k[j], nrc[j]
    nrec[i] = nrc[j]
    for c in range(3 + nlev):
        stats[i, c] = W[_STT + (c if c < 2 + nlev else MAX_LEVELS + 2), j]
    for c in range(5):
        state[i, ST_TRACK + c] = W[_TRK + c, j]
    if mode == 2 and W[_RECANY, j] != 0.0:
        if rec.shape[1] > 10:                       # the tire yaw moment of the recorded step (final_row)
            W[_REC + 26, j] = _lp.l_tire_moment(
                W[_REC + 10, j], W[_REC + 11, j], W[_REC + 12, j], W[_REC + 13, j], W[_REC + 14, j],
                W[_REC + 15, j], W[_REC + 16, j], W[_REC + 17, j], W[_RECTR, j], W[_RECTR + 1, j],
                W[_RECTR + 2, j], W[_RECTR + 3, j], W[_PR + X_M, j], W[_PR + X_P, j], W[_PR + D1, j],
                W[_PR + D2, j], W[_PR + T1, j], W[_PR + T2, j], W[_PR + TRAIL, j])
        for c in range(rec.shape[1]):
            rec[i, c, 0] = W[_REC + c, j]


@njit(cache=True, nogil=True, forceinline=True, **_NOWRAP, **_LINK)
def _compact(W, L, runs, next_k, nrc, state, stats, rec, nrec, nlev, mode):
    """The block's stopped lanes written back (:func:`_store_lane`) and its running lanes moved, in order, to the
    first columns (every row of ``W``, with ``runs``, ``next_k``, ``nrc``); returns how many run.  A lane's numbers do
    not depend on its column (every lane executes the same instructions), and a stopped lane's rows no longer change,
    so its numbers are those it would have at the end."""
    m = 0
    for j in range(L):
        if W[_ACT, j] == 0.0:
            _store_lane(W, j, runs[j], next_k, nrc, state, stats, rec, nrec, nlev, mode)
            continue
        if m != j:                  # the columns m .. j - 1 are stopped lanes, already written back
            for r in range(NROWS):
                W[r, m] = W[r, j]
            runs[m], next_k[m], nrc[m] = runs[j], next_k[j], nrc[j]
        m += 1
    return m


@njit(cache=True, nogil=True, error_model="numpy", **_NOWRAP)
def _block(model, lo, hi, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu,
           By, Cz, noise, state, rec, stats, warn, status, nrec):
    """Steps ``k0 .. k1 - 1`` of runs ``lo .. hi - 1`` (at most :data:`LANES`) as lanes (see
    :func:`stability.simulate.kernel.run_one`, whose arithmetic this is); ``model`` (:func:`.kernel.variant`) a
    numba literal: the vectorised loops compute that model's contact velocities and accelerations alone."""
    literally(model)
    L = hi - lo
    dt, duimp, ftimp, n, stride, locked, stop, policy, mode = (
        cfg[0], cfg[1], cfg[2], int(cfg[3]), int(cfg[4]), cfg[6] == 1.0, cfg[7] != 0.0, int(cfg[8]), int(cfg[9]))
    sticks = cfg[6] == 2.0
    settle = sticks and int(cfg[STOP_LEVEL]) >= 0 and cfg[SETTLE] != 0.0
    ext = cfg[EXTERNAL_MZ] != 0.0
    use_ctl = ctl_f[0] > 0.0 and not ext
    half_dt2 = 0.5 * dt * dt
    maxslip, maxload, nwarn_limit, stop_lvl = cfg[10], cfg[11], cfg[12], int(cfg[STOP_LEVEL])
    slope = model == SLOPE_MODEL
    nlev = levels.shape[0]
    nz = Az.shape[0]
    znew, y, sv = np.zeros(nz), np.zeros(Cy.shape[0]), np.zeros(10)
    W = np.zeros((NROWS, LANES))              # constant shape: LLVM sees the rows' distances (no aliasing checks)
    next_k = np.zeros(LANES, dtype=np.int64)
    nrc = np.zeros(LANES, dtype=np.int64)
    runs = np.empty(LANES, dtype=np.int64)      # the run of each lane (columns move when stopped lanes leave)
    for j in range(L):
        runs[j] = lo + j
    vec_held = (sticks or locked) and L >= VEC_HELD_MIN
    lv = padded_levels(levels)
    camber = _load(W, next_k, nrc, lo, L, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, state, stats, status, nlev,
                   sticks)
    for k in range(k0, min(k1, n)):
        running = W[_ACT, :L].sum()
        if running == 0.0:
            break
        if running <= L - COMPACT_AFTER:            # a vector's worth of stopped lanes: step the running ones only
            L = _compact(W, L, runs, next_k, nrc, state, stats, rec, nrec, nlev, mode)
            vec_held = (sticks or locked) and L >= VEC_HELD_MIN
        t = k * dt
        imp = t <= duimp * (1.0 + 1e-12) + 1e-15
        slip_statics(W, L, model, slope, cfg)
        tire_forces(W, L, ftimp, imp, policy, camber)
        checks(W, L, runs, t, warn, status, CAM, maxload, maxslip, stop, nwarn_limit, ext, use_ctl, next_k, state,
               nz, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
        dynam(W, L, model, imp, sticks, locked, vec_held)
        if sticks or (locked and not vec_held):
            held(W, L, model, locked, vec_held)
        stops(W, L, runs, k, t, levels, lv, nlev, mode, stride, rec, nrc, status, stop_lvl, settle, duimp)
        if mode == 2:
            final_row(W, L, rec.shape[1] > 10)
        update(W, L, dt, half_dt2)
    for j in range(L):
        _store_lane(W, j, runs[j], next_k, nrc, state, stats, rec, nrec, nlev, mode)


@njit(cache=True, parallel=True)
def _run_lanes(step, model, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By,
               Cz, noise, state, rec, stats, warn, status, nrec, lanes):
    """The blocks of ``lanes`` runs, one per thread (``prange``); ``step``: the address of :func:`_block`'s
    specialisation for the runs' model and arrays (:func:`run_lanes`), called, not compiled in (numba would link the
    block's code into this entry, its parfor body and their two wrappers, and LLVM would optimise it in each)."""
    nb = (P.shape[0] + lanes - 1) // lanes
    for b in prange(nb):
        lo = b * lanes
        call_none_at(step, model, lo, min(P.shape[0], lo + lanes), k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM,
                     CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, state, rec, stats, warn, status, nrec)


@njit(cache=True, nogil=True)
def _run_lanes_serial(step, model, k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, CHK, cfg, levels, ctl_f, Cy, Dy, Az,
                      Bu, By, Cz, noise, state, rec, stats, warn, status, nrec, lanes):
    """:func:`_run_lanes` on the calling thread: one block, or one thread (no parallel entry to compile or wake)."""
    nb = (P.shape[0] + lanes - 1) // lanes
    for b in range(nb):
        lo = b * lanes
        call_none_at(step, model, lo, min(P.shape[0], lo + lanes), k0, k1, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM,
                     CHK, cfg, levels, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, state, rec, stats, warn, status, nrec)


#: the address of :func:`_block`'s specialisation, by model and the arrays' fingerprints (numba's dispatch key)
_STEPS: dict[tuple, int] = {}
#: the compiled entries found by :func:`run_lanes` (serial or not), by model and the arrays' fingerprints
_ENTRIES: dict[tuple, Any] = {}


def _entry(serial: bool, model: int, arrays: tuple) -> Any:
    """The compiled entry (:func:`_run_lanes_serial` or :func:`_run_lanes`) with its step's address and ``model``
    bound: compiled, or loaded from numba's cache, under the first-use notice the first time, apart from the runs."""
    prints = tuple(map(compute_fingerprint, arrays))
    fn = _ENTRIES.get((serial, model, prints))
    if fn is None:
        with first_use("wchair"):
            types_ = tuple(map(typeof, arrays))
            step = _STEPS.get((model, prints))
            if step is None:
                sig = (_nbtypes.literal(model), *(_nbtypes.int64,) * 4, *types_)
                step = _STEPS[(model, prints)] = address(_block, sig, returns=_nbtypes.none)
            entry = _run_lanes_serial if serial else _run_lanes
            fn = partial(entry.compile((*(_nbtypes.int64,) * 4, *types_, _nbtypes.int64)), step, model)
        _ENTRIES[(serial, model, prints)] = fn
    return fn


def run_lanes(k0: int, k1: int, P: np.ndarray, *args: Any) -> None:
    """:func:`stability.simulate.kernel.run_batch` with the runs in blocks of ``lanes`` (at most :data:`LANES`)
    stepped as lanes, one block per thread (``prange``); the same arguments, and the block size last.

    The runs' model (:func:`stability.simulate.kernel.variant` of the configuration row) is compiled as a constant,
    as the scalar kernel's (:func:`stability.simulate.kernel.call_model`): the first call for a model compiles (or
    loads from the cache) :func:`_block`'s specialisation, under the first-use notice, and the entries call it at its
    address (:func:`~stability.simulate.native_call.call_none_at`), so that one compile of each entry serves every
    model.  One block, or one thread, runs on the calling thread without the parallel entry.

    Parameters
    ----------
    k0, k1 : int
        First step and the step after the last.
    P : ndarray
        The runs' chair parameters (``kernel.run_batch``'s).
    *args
        ``kernel.run_batch``'s other arrays, from ``S`` to ``nrec``, then the block size (int).
    """
    model = variant(args[10], args[12])[0]          # cfg, ctl_f; the controller is found at run time (ctl 0)
    arrays, lanes = (P, *args[:-1]), int(args[-1])
    serial = -(-P.shape[0] // lanes) == 1 or get_num_threads() == 1
    _entry(serial, model, arrays)(int(k0), int(k1), *arrays, lanes)


invalidate_stale_cache(globals(), "lanes_kernel.equations.sha256")
