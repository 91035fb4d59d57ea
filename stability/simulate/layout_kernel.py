"""The compiled layout kernel (numba): program WCHAIR's fixed-step scheme for a chair with any wheel layout.

The equations are the generated nonlinear functions of :mod:`stability.models.layout` (Kane's method for any
number of fixed wheels and casters, ``derivations/layout.py``), compiled as they are; the tire force law
(:mod:`stability.tires.law`), the slip angle and the pin-friction laws (:mod:`stability.models.forces`) are the
thesis engine's compiled functions (:mod:`stability.simulate.kernel_equations`), not copies.  What is new here
is the bookkeeping of ``K`` casters: a linear solve of the mass matrix instead of the thesis model's closed form,
the holding moments of any set of held (locked or stuck) casters, and the normal loads of any layout
(:func:`stability.layout.statics.load_rule`).

The step is :func:`stability.simulate.kernel.run_one`'s for the exact model, level or on a plane: the contact
velocities and slips, in-plane gravity in body axes at the step's heading (the generated ``gravity_body``), the
normal loads from the previous step's tire-force sums (the push included, as WCHAIR's UPDATE keeps it) under the
normal weight, the tire forces (MECHAN's: lateral, rolling resistance along each wheel, camber thrust on the fixed
wheels from their unscaled tire at the truncated camber angle), the accelerations with each body's in-plane weight
(the generated equations' ``g1, g2``), then the update ``x += v dt + a dt^2 / 2``, ``v += a dt`` with the
stick-slip rest rule.
"""

from __future__ import annotations

import math
import sys
from typing import Any

import numpy as np
from numba import njit, typeof
from numba.core import types as _nbtypes

from stability.models.layout import nonlinear as _gn
from stability.simulate import layout_forces as _lf
from stability.simulate import layout_solve as _ls
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.first_use import first_use
from stability.simulate.kernel_controller import controller_output
from stability.simulate.kernel_equations import (
    _NOREF,
    _inl,
    _int,
    camber_force,
    compiled,
    gravity_body,
    lateral_force,
    rest_rate,
    rolling_force,
    slip_angle,
)
from stability.simulate.layout_solve import _layout_loads, _pins, layout_loads
from stability.simulate.native_call import address, call_at, call_none_at

__all__ = ["step_layouts", "initial_state", "arguments", "work_length", "NSTATE", "S_CMD", "S_NREC",
           "layout_loads", "STOPPED_SLIP", "STOPPED_LOAD", "STOPPED_NONFINITE", "NCFG", "NREC"]

#: each shape's generated equations and contact velocities, compiled on their own (no wrappers, no reference
#: counts): :func:`step_layouts` calls its runs' shape's at their addresses (:func:`arguments`), so it is compiled
#: once for every shape, and a process compiles (or loads) only the shapes it runs, not all of them inlined
#: behind a branch on the shape
_shapes = compiled(_gn, tuple(f"{kind}_{nw}w{nc}c" for nw, nc in _gn.SHAPES
                              for kind in ("equations", "contact_velocities")), _int)
#: MECHAN for any layout (:mod:`.layout_forces`, plain Python that the statics call too), compiled with the
#: thesis engine's compiled tire law
_lfc = compiled(_lf, ("tire_forces", "wheel_frames"), _inl, {"lateral_force": lateral_force,
                                                                 "rolling_force": rolling_force,
                                                                 "camber_force": camber_force})
_tire_forces, _wheel_frames = _lfc.tire_forces, _lfc.wheel_frames

#: ``status[0]``: 0 ran to the horizon, 1 the eleventh slip warning, 2 the eleventh load warning, 3 non-finite
STOPPED_SLIP, STOPPED_LOAD, STOPPED_NONFINITE = 1.0, 2.0, 3.0
#: cfg slots: dt, steps, stride, push duration, push force, tire push force, pin mode (0 kinetic, 1 locked,
#: 2 stick-slip), stop on warnings, tire policy, slip limit deg, load limit N, warning limit, shape index, weight N,
#: c.g. height m, load mode (statics.LEVER / THREE / COMPLIANT), then the plane: on a slope (1.0) or level (0.0),
#: cos and sin of the cross slope, cos and sin of the grade, and g (m/s^2), then the motor lag of the controller's
#: yaw moment (s, 0: none)
NCFG = 23
#: recorded columns: x, y, heading, yaw rate, u, v, then each caster's angle and rate
NREC = 6


@_inl
def _range_rules(warn, t, loads, slips, CHK, kv, maxload, maxslip, stop, nwarn_limit):
    """Program WCHAIR's STATICS / MECHAN range rules on the tested tires on the ground: count the warnings;
    the stop code when a kind reaches its limit (``stop``), else 0."""
    nmax, smax, nmin = -math.inf, 0.0, math.inf
    # min/max as numba's (Python's) selects, NaN included, without compiling numba's functions for them
    for i in range(loads.shape[0]):
        if kv[i] != 0.0:
            nmin = loads[i] if loads[i] < nmin else nmin
            if CHK[i]:
                nmax = loads[i] if loads[i] > nmax else nmax
                si = abs(slips[i])
                smax = si if si > smax else smax
    if nmax > maxload:
        _note(warn, np.int64(1), t, nmax)
        if stop and warn[1, 0] > nwarn_limit:
            return STOPPED_LOAD
    if nmin < 0.0:
        _note(warn, np.int64(2), t, nmin)
    if smax > maxslip:
        _note(warn, np.int64(0), t, smax)
        if stop and warn[0, 0] > nwarn_limit:
            return STOPPED_SLIP
    return 0.0


@_inl
def _kinematics(cvf, p, nw, nc, UD, VD, THED, D, DD, cs, sn, vel, slips, xs, ys, CAM):
    """The caster angles' cosines and sines, the contact velocities (the fixed wheels' in their turned frames; the
    shape's generated ``contact_velocities`` at the address ``cvf``) and slip angles (deg), the caster contacts."""
    for kk in range(nc):
        cs[kk], sn[kk] = math.cos(D[kk]), math.sin(D[kk])
    call_none_at(cvf, UD, VD, THED, cs, sn, DD, p, vel)
    _wheel_frames(nw, CAM, vel)
    for i in range(nw + nc):
        slips[i] = slip_angle(vel[2 * i], vel[2 * i + 1])
    for kk in range(nc):
        base = 2 + 2 * nw + 6 * kk                 # x_p, y_p, trail of caster kk in p
        xs[nw + kk] = p[base] - p[base + 2] * cs[kk]
        ys[nw + kk] = p[base + 1] - p[base + 2] * sn[kk]


@_inl
def _record(rec, row, X, Y, THE, THED, UD, VD, D, DD):
    rec[0, row], rec[1, row], rec[2, row], rec[3, row], rec[4, row], rec[5, row] = X, Y, THE, THED, UD, VD
    for kk in range(D.shape[0]):
        rec[NREC + 2 * kk, row], rec[NREC + 2 * kk + 1, row] = D[kk], DD[kk]


#: the length of the head of a run's ``state`` between :func:`step_layouts` calls, and its command and rows slots:
#: the slots between :func:`step_layouts` calls: x, y, heading, yaw rate, u, v, the last step's tire-force
#: sums (x, y), the controller's next sample, its held command (or the caller's, :func:`step_layouts`), the applied
#: moment after the motor lag, the rows recorded; then each caster's angle, each caster's rate, the controller state
NSTATE = 12
S_CMD, S_NREC = 9, 11


def initial_state(u0: float, v0: float, delta0: np.ndarray, nz: int) -> np.ndarray:
    """A run's :data:`NSTATE` + 2 nc + nz state at ``t = 0``: at rest in the plane, speeds ``u0``, ``v0`` (m/s), the
    casters at ``delta0`` (rad), not swivelling, no command.

    Parameters
    ----------
    u0, v0 : float
        Forward and lateral speed, m/s.
    delta0 : ndarray
        Each caster's swivel angle, rad.
    nz : int
        The controller's state length (0: none).

    Returns
    -------
    ndarray
        The state row :func:`step_layouts` advances.
    """
    nc = delta0.shape[0]
    state = np.zeros(NSTATE + 2 * nc + nz)
    state[4], state[5] = u0, v0
    state[NSTATE:NSTATE + nc] = delta0
    return state


def work_length(nw: int, nc: int, nz: int, ny: int) -> int:
    """The length of :func:`step_layouts`' float scratch ``work`` (as it cuts it) for ``nw`` fixed wheels, ``nc``
    casters and a controller of ``nz`` states and ``ny`` measurements.

    Parameters
    ----------
    nw, nc, nz, ny : int

    Returns
    -------
    int
    """
    nt, n = nw + nc, 3 + nc
    return 6 * nc + 6 * nt + 2 * nw + 2 * nc + 4 * n + nz + ny + 6 + 2 * nc + 9


#: the numba types of the shape's functions' arguments other than ``p``: floats, and :func:`step_layouts`' views
#: of its scratch (contiguous rows and matrices)
_F, _V, _M = _nbtypes.float64, _nbtypes.float64[::1], _nbtypes.float64[:, ::1]
#: ``(shape, p's numba type)``: the addresses of the shape's equations and contact velocities; the controller's
#: arrays' numba types: the address of :func:`_samples` for them
_ADDRESSES: dict[tuple, Any] = {}


def arguments(cfg: np.ndarray, consts: tuple, states: np.ndarray, recs: np.ndarray, status: np.ndarray,
              warn: np.ndarray, ctl: tuple, mzrec: np.ndarray) -> tuple:
    """:func:`step_layouts`' arguments after ``k0, k1``: the addresses of the layout's shape's generated equations
    and contact velocities (compiled, or loaded from numba's cache, the first time a process runs the shape) and of
    the controller's sampling (with a controller, likewise; else 0), the caller's arrays, and the step's scratch
    arrays (allocated here, once per call of :func:`step_layouts`' caller: the compiled step allocates nothing).

    Parameters
    ----------
    cfg : ndarray
        The :data:`NCFG` configuration row (its shape index, ``cfg[12]``, picks the equations).
    consts : tuple
        ``p`` to ``cpin`` (:func:`step_layouts`).
    states, recs, status, warn : ndarray
        The runs' rows.
    ctl : tuple of ndarray
        The controller's arrays ``ctl_f`` to ``noise``.
    mzrec : ndarray
        The runs' recorded commands.

    Returns
    -------
    tuple
        ``(eqf, cvf, ctlf, cfg, *consts, states, recs, status, warn, *ctl, mzrec, work, mats, free, held)``.

    Raises
    ------
    ValueError
        With a controller, ``states`` not C-contiguous.
    """
    p, nw, nc = consts[0], consts[1], consts[2]
    shape = int(cfg[12])
    key = (shape, typeof(p))
    if key not in _ADDRESSES:
        tag = "{}w{}c".format(*_gn.SHAPES[shape])
        eq, cv = getattr(_shapes, f"equations_{tag}"), getattr(_shapes, f"contact_velocities_{tag}")
        with first_use("layout"):       # the shape's equations load, or compile once per machine
            _ADDRESSES[key] = (address(eq, (_F, _F, _F, _V, _V, _V, key[1], _V, _V, _F, _F, _F, _F, _M, _V),
                                       _nbtypes.none),
                               address(cv, (_F, _F, _F, _V, _V, _V, key[1], _V), _nbtypes.none))
    ctlf = 0
    if ctl[0][0] > 0.0:           # a sampled controller: its state views are rows of states and of the scratch
        if not states.flags.c_contiguous:      # the row types the address is taken for
            raise ValueError("states must be C-contiguous (initial_state rows stacked by np.array)")
        ckey = tuple(map(typeof, ctl))
        if ckey not in _ADDRESSES:
            with first_use("layout"):
                _ADDRESSES[ckey] = address(_samples, (_F, _nbtypes.int64, *(_F,) * 6, *(_V,) * 6, *ckey, _V))
        ctlf = _ADDRESSES[ckey]
    n = 3 + nc
    work = np.zeros(work_length(nw, nc, ctl[3].shape[0], ctl[1].shape[0]))
    return (*_ADDRESSES[key], ctlf, cfg, *consts, states, recs, status, warn, *ctl, mzrec, work, np.zeros((3, n, n)),
            np.zeros(n, dtype=np.int64), np.zeros(nc, dtype=np.bool_))


@njit(cache=True, nogil=True, **_NOREF)
def step_layouts(k0, k1, eqf, cvf, ctlf, cfg, p, nw, nc, TK, TS, TL, LIM, CHK, RK, RC, RS, CAM, kv, line, share, mf,
                 cpin, states, recs, status, warn, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, mzrec, work, mats, free,
                 held):
    """Steps ``k0 .. k1 - 1`` of a batch of runs of one layout (one run: a batch of one, stepped to its end).

    ``eqf``, ``cvf`` the addresses of the layout's shape's generated equations and contact velocities, ``ctlf`` the
    controller's sampling (:func:`_samples`; 0: none) (:func:`arguments`), ``cfg`` (:data:`NCFG` slots), parameters
    ``p`` (the generated order), ``nw`` fixed wheels and ``nc`` casters, per contact (fixed wheels, then casters)
    the tire slots (then each fixed wheel's camber tire) and range check, the rolling-resistance slots (kind,
    coefficients, scale), per fixed wheel the camber ``(deg, signed coefficient)`` and its angle's ``(cos, sin)``,
    the vertical stiffness and support line, the lines' roll shares, per caster the Coulomb limit (N m) and viscous
    coefficient (N m s/rad); one row per run of ``states`` (:func:`initial_state`; its slot :data:`S_NREC` counts
    the rows written), ``recs`` (:data:`NREC` + 2 nc, rows), ``status`` (code, time), ``warn`` (3, 3: slip, load,
    lift-off counts, first time, largest) and ``mzrec``. Each run still going (``status[r, 0] == 0``) advances. With
    ``ctl_f[0] > 0`` the sampled controller of :mod:`stability.simulate.controller` (its arrays; the state it
    measures is ``[x, y, heading, u, v, yaw rate, delta_1, delta_d_1, ...]``) commands a yaw moment on the body at
    each sample, held until the next; without one, the yaw moment each run's command slot holds (set by the caller
    between calls, N m) acts. Either goes through a first-order motor lag (``cfg[22]``, exact over each step); the
    commanded (saturated) moment is recorded in ``mzrec`` (N m). ``work`` (:func:`work_length`), ``mats`` (3, 3 +
    nc, 3 + nc), ``free`` (int, 3 + nc) and ``held`` (bool, nc) are scratch, zeroed for each run as fresh arrays
    were.

    A run's steps are written in this loop, not in a jitted function of their own that it calls: numba compiles a
    called function to machine code on its own and then, linked into its caller, optimises and emits it again, so
    the whole step was compiled twice (about a fifth of the kernel's first use, measured).  Nothing here allocates
    (no numpy allocation to type, no reference counts: compiled without numba's NRT), and the shape's equations are
    called, not inlined: one compile serves every shape."""
    nt, n = nw + nc, 3 + nc
    nz, ny = Az.shape[0], Cy.shape[0]
    # the scratch's views, cut in work_length's order
    D, DD, cs, sn, mom, rest = (work[0:nc], work[nc:2 * nc], work[2 * nc:3 * nc], work[3 * nc:4 * nc],
                                work[4 * nc:5 * nc], work[5 * nc:6 * nc])
    o = 6 * nc
    vel, slips, loads, xs, ys = (work[o:o + 2 * nt], work[o + 2 * nt:o + 3 * nt], work[o + 3 * nt:o + 4 * nt],
                                 work[o + 4 * nt:o + 5 * nt], work[o + 5 * nt:o + 6 * nt])
    o += 6 * nt
    fw, fc = work[o:o + 2 * nw], work[o + 2 * nw:o + 2 * nw + 2 * nc]
    o += 2 * nw + 2 * nc
    F0, w, acc, x = work[o:o + n], work[o + n:o + 2 * n], work[o + 2 * n:o + 3 * n], work[o + 3 * n:o + 4 * n]
    o += 4 * n
    znew, y, sv = work[o:o + nz], work[o + nz:o + nz + ny], work[o + nz + ny:o + nz + ny + 6 + 2 * nc]
    o += nz + ny + 6 + 2 * nc
    lb, lx, io = work[o:o + 4], work[o + 4:o + 8], work[o + 8:o + 9]
    Mm, W, A = mats[0], mats[1], mats[2]
    for r in range(states.shape[0]):
        if status[r, 0] != 0.0:
            continue
        # the run's rows (views); the step's scalars and scratch are the run's own
        state, rec, run_status, run_warn, run_mz = states[r], recs[r], status[r], warn[r], mzrec[r]
        _fresh(work, mats, free, held)
        dt, stride, duimp, fcimp, ftimp = cfg[0], np.int64(cfg[2]), cfg[3], cfg[4], cfg[5]
        pin_mode, stop, policy = np.int64(cfg[6]), cfg[7] != 0.0, np.int64(cfg[8])
        maxslip, maxload, nwarn_limit, weight, h, mode = (cfg[9], cfg[10], cfg[11], cfg[13], cfg[14],
                                                          np.int64(cfg[15]))
        slope, c_phi, s_phi, c_theta, s_theta, grav = cfg[16] != 0.0, cfg[17], cfg[18], cfg[19], cfg[20], cfg[21]
        g1 = g2 = 0.0
        wn = weight
        half_dt2 = 0.5 * dt * dt
        X, Y, THE, THED, UD, VD = state[0], state[1], state[2], state[3], state[4], state[5]
        FC1, FC2 = state[6], state[7]
        next_k, cmd, mz, nrec = np.int64(state[8]), state[S_CMD], state[10], np.int64(state[S_NREC])
        z = state[NSTATE + 2 * nc:NSTATE + 2 * nc + nz]          # a view: advanced in place
        _start(state, nw, nc, p, mf, pin_mode == 2, D, DD, rest, xs, ys)
        use_ctl = ctl_f[0] > 0.0
        lag = cfg[22]
        keep = math.exp(-dt / lag) if lag > 0.0 else 0.0
        for k in range(k0, k1):
            t = k * dt
            if use_ctl:
                io[0] = cmd
                next_k = call_at(ctlf, t, next_k, X, Y, THE, UD, VD, THED, D, DD, z, znew, y, sv, ctl_f, Cy, Dy, Az,
                                 Bu, By, Cz, noise, io)
                cmd = io[0]
            if lag <= 0.0:
                mz = cmd
            _kinematics(cvf, p, nw, nc, UD, VD, THED, D, DD, cs, sn, vel, slips, xs, ys, CAM)
            if slope:   # gravity in body axes at the step's heading; the loads under the normal weight
                g1, g2, gn = gravity_body(grav, c_phi, s_phi, c_theta, s_theta, math.cos(THE), math.sin(THE))
                wn = weight * gn / grav
            _layout_loads(mode, xs, ys, kv, line, share, wn, h, FC1, FC2, loads, A, lb, lx, free)
            code = _range_rules(run_warn, t, loads, slips, CHK, kv, maxload, maxslip, stop, nwarn_limit)
            if code != 0.0:
                run_status[0], run_status[1] = code, t
                break
            imp = t <= duimp * (1.0 + 1e-12) + 1e-15
            sum_fx, sum_fy = _tire_forces(nw, nc, TK, TS, TL, LIM, RK, RC, RS, CAM, vel, slips, loads, policy,
                                          ftimp != 0.0 and imp, ftimp, cs, sn, fw, fc)
            fy_ext = fcimp if (fcimp != 0.0 and imp) else 0.0
            call_none_at(eqf, UD, VD, THED, cs, sn, DD, p, fw, fc, fy_ext, mz, g1, g2, Mm, F0)
            _pins(pin_mode, Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc, free, x)
            if not abs(THED) < math.inf:
                run_status[0], run_status[1] = STOPPED_NONFINITE, t
                break
            if k % stride == 0:
                _record(rec, k // stride, X, Y, THE, THED, UD, VD, D, DD)
                run_mz[k // stride] = cmd
                nrec = k // stride + 1
            # UPDATE (the thesis engine's): positions with the half-step term, velocities forward, the rest rule
            FC1, FC2 = sum_fx, sum_fy + fy_ext
            du = UD * dt + acc[0] * half_dt2
            dv = VD * dt + acc[1] * half_dt2
            cost, sint = math.cos(THE), math.sin(THE)
            X += du * cost - dv * sint
            Y += du * sint + dv * cost
            UD += acc[0] * dt
            VD += acc[1] * dt
            if pin_mode != 1:
                for kk in range(nc):
                    D[kk] += DD[kk] * dt + acc[3 + kk] * half_dt2
                    DD[kk] = rest_rate(DD[kk], DD[kk] + acc[3 + kk] * dt, rest[kk])
            THE += THED * dt + acc[2] * half_dt2
            THED += acc[2] * dt
            if lag > 0.0:     # the motor lag, exact over the step for the held command
                mz = cmd + (mz - cmd) * keep
        state[0], state[1], state[2], state[3], state[4], state[5] = X, Y, THE, THED, UD, VD
        state[6], state[7], state[8], state[S_CMD], state[10], state[S_NREC] = FC1, FC2, next_k, cmd, mz, nrec
        for kk in range(nc):
            state[NSTATE + kk], state[NSTATE + nc + kk] = D[kk], DD[kk]




@_int
def _samples(t, next_k, X, Y, THE, UD, VD, THED, D, DD, z, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, io):
    """The sampled controller's samples due by ``t``: returns the next sample's index; the held command in
    ``io[0]``.  Compiled on its own, when a process first runs a layout with a controller, and called at its
    address (:func:`arguments`): a run without one compiles no controller code."""
    cmd = io[0]
    ks = math.floor(t / ctl_f[0] + 1e-9)         # an integer (numba's floor of a float)
    while next_k <= ks:
        sv[0], sv[1], sv[2], sv[3], sv[4], sv[5] = X, Y, THE, UD, VD, THED
        for kk in range(D.shape[0]):
            sv[6 + 2 * kk], sv[7 + 2 * kk] = D[kk], DD[kk]
        cmd = controller_output(next_k, z, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
        next_k += 1
    io[0] = cmd
    return next_k


@_inl
def _fresh(work, mats, free, held):
    """Zero a run's scratch, as the fresh arrays of each run were."""
    for i in range(work.shape[0]):
        work[i] = 0.0
    for m in range(mats.shape[0]):
        for i in range(mats.shape[1]):
            for j in range(mats.shape[2]):
                mats[m, i, j] = 0.0
    for i in range(free.shape[0]):
        free[i] = 0
    for i in range(held.shape[0]):
        held[i] = False


@_inl
def _start(state, nw, nc, p, mf, stick, D, DD, rest, xs, ys):
    """A run's caster angles and rates from its ``state``, the rates that come to rest (``stick``: stick-slip, a
    reversing rate), the fixed wheels' contacts."""
    for kk in range(nc):
        D[kk], DD[kk] = state[NSTATE + kk], state[NSTATE + nc + kk]
        rest[kk] = mf[kk] if stick else 0.0
    for j in range(nw):
        xs[j], ys[j] = p[2 + 2 * j], p[3 + 2 * j]


@_inl
def _note(warn, kind, t, value):
    if warn[kind, 0] == 0.0 or abs(value) > abs(warn[kind, 2]):
        warn[kind, 2] = value
    if warn[kind, 0] == 0.0:
        warn[kind, 1] = t
    warn[kind, 0] += 1.0


# the helpers of layout_solve and the shapes' functions are flushed with the kernel (a cached helper carries the
# functions it calls)
invalidate_stale_cache({**globals(), **vars(_ls), **vars(_shapes)}, "layout_kernel.equations.sha256",
                       (_gn, _lf, _ls, sys.modules[__name__]))
