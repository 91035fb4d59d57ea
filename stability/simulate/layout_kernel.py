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

import numpy as np
from numba import njit

from stability.models.layout import nonlinear as _gn
from stability.simulate import layout_forces as _lf
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.kernel_controller import controller_output
from stability.simulate.kernel_equations import (
    _inl_py,
    _inl_rc,
    break_away_moment,
    camber_force,
    compiled,
    gravity_body,
    kinetic_pin_moment,
    lateral_force,
    pin_holds,
    rest_rate,
    rolling_force,
    slip_angle,
)

__all__ = ["step_layouts", "initial_state", "NSTATE", "S_CMD", "S_NREC", "layout_loads",
           "STOPPED_SLIP", "STOPPED_LOAD", "STOPPED_NONFINITE", "NCFG", "NREC"]

_eq = compiled(_gn, tuple(_gn.__all__), _inl_rc)
equations = _eq.equations
contact_velocities = _eq.contact_velocities
#: MECHAN for any layout (:mod:`.layout_forces`, plain Python that the statics call too), compiled with the
#: thesis engine's compiled tire law
_lfc = compiled(_lf, ("tire_forces", "wheel_frames"), _inl_rc, {"lateral_force": lateral_force,
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
_LEVER, _THREE = 0, 1


@_inl_rc
def _solve(A, b, n, x):
    """Solve the leading ``n x n`` system ``A x = b`` by Gaussian elimination with partial pivoting (``A``, ``b``
    overwritten)."""
    for c in range(n):
        p = c
        big = abs(A[c, c])
        for r in range(c + 1, n):
            if abs(A[r, c]) > big:
                big, p = abs(A[r, c]), r
        if p != c:
            for cc in range(n):
                A[c, cc], A[p, cc] = A[p, cc], A[c, cc]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, n):
            f = A[r, c] / A[c, c]
            if f != 0.0:
                for cc in range(c, n):
                    A[r, cc] -= f * A[c, cc]
                b[r] -= f * b[c]
    for c in range(n - 1, -1, -1):
        s = b[c]
        for cc in range(c + 1, n):
            s -= A[c, cc] * x[cc]
        x[c] = s / A[c, c]


@_inl_py
def layout_loads(mode, xs, ys, k, line, share, weight, h, sum_fx, sum_fy, out):
    """Normal loads of the contacts at ``(xs, ys)`` (m, about the c.g.) under the weight (N) and the tire forces'
    resultant ``(sum_fx, sum_fy)`` (N) at the ground ``h`` (m) below the c.g.: ``sum N = weight``,
    ``sum N x = -h sum_fx``, ``sum N y = -h sum_fy`` (:func:`stability.layout.statics.load_rule`).

    ``mode`` LEVER: two lines of two contacts (``line`` 0 or 1), each carrying ``share[line]`` of the roll moment;
    THREE: three contacts; COMPLIANT: ``N_i = k_i (z + theta x_i + phi y_i)``.  Contacts with ``k == 0`` carry
    nothing.  Written into ``out`` (N)."""
    n = xs.shape[0]
    pitch, roll = -h * sum_fx, -h * sum_fy
    for i in range(n):
        out[i] = 0.0
    # each rule's system in the leading m x m block, solved by one call (one inlined copy of the elimination)
    A, b, x, sel = np.zeros((4, 4)), np.zeros(4), np.zeros(4), np.zeros(4, dtype=np.int64)
    b[0], b[1] = weight, pitch
    m = 0
    if mode == _LEVER:
        b[2], b[3] = share[0] * roll, share[1] * roll
        for i in range(n):
            if line[i] >= 0:
                sel[m] = i
                A[0, m] = 1.0
                A[1, m] = xs[i]
                A[2 + line[i], m] = ys[i]
                m += 1
        m = 4
    elif mode == _THREE:
        b[2] = roll
        for i in range(n):
            if k[i] != 0.0:
                sel[m] = i
                A[0, m], A[1, m], A[2, m] = 1.0, xs[i], ys[i]
                m += 1
        m = 3
    else:
        b[2] = roll
        for i in range(n):                               # sum_i k_i b_i b_i^T q = (weight, pitch, roll)
            bi = (1.0, xs[i], ys[i])
            for r in range(3):
                for c in range(3):
                    A[r, c] += k[i] * bi[r] * bi[c]
        m = 3
    _solve(A, b, np.int64(m), x)
    if mode == _LEVER or mode == _THREE:
        for j in range(m):
            out[sel[j]] = x[j]
        return
    for i in range(n):
        out[i] = k[i] * (x[0] + x[1] * xs[i] + x[2] * ys[i])


@_inl_rc
def _accelerations(Mm, F0, nc, mom, held, W, w, acc):
    """Accelerations with the pin moments ``mom`` on the free casters and the ``held`` casters' swivel
    accelerations zero: the free rows of ``M acc = F0 + sum_k M_k e_(3+k)``; each held caster's moment (written
    into ``mom``) is then its own row's balance."""
    n = 3 + nc
    free = np.zeros(n, dtype=np.int64)
    m = 0
    for i in range(n):
        if i < 3 or not held[i - 3]:
            free[m] = i
            m += 1
    for a in range(m):
        w[a] = F0[free[a]] + (mom[free[a] - 3] if free[a] >= 3 else 0.0)
        for c in range(m):
            W[a, c] = Mm[free[a], free[c]]
    x = np.zeros(n)
    _solve(W, w, np.int64(m), x)
    for i in range(n):
        acc[i] = 0.0
    for a in range(m):
        acc[free[a]] = x[a]
    for kk in range(nc):
        if held[kk]:
            s = -F0[3 + kk]
            for c in range(n):
                s += Mm[3 + kk, c] * acc[c]
            mom[kk] = s


@_inl_rc
def _stick_slip(Mm, F0, nc, dd, mf, cpin, mom, held, W, w, acc):
    """Stick-slip Coulomb pins (the thesis engine's ``stick_slip`` for any number of casters): a swivelling caster
    gets the kinetic moment (plus its viscous part), a caster at rest is held while its holding moment is within
    its friction limit, else it breaks away with the limit moment in the holding moment's direction; decided again
    after each release (a held caster's moment changes the others')."""
    for kk in range(nc):
        mom[kk] = kinetic_pin_moment(dd[kk], mf[kk]) - cpin[kk] * dd[kk]
        held[kk] = dd[kk] == 0.0
    for it in range(nc + 2):      # one call of _accelerations (one inlined copy of the solve)
        anyheld = False
        for kk in range(nc):
            if it > nc:           # decided nc + 1 times: every caster free
                held[kk] = False
            anyheld = anyheld or held[kk]
        _accelerations(Mm, F0, nc, mom, held, W, w, acc)
        if not anyheld:
            return
        released = False
        for kk in range(nc):
            if held[kk] and not pin_holds(mom[kk], mf[kk]):
                mom[kk] = break_away_moment(mom[kk], mf[kk])
                held[kk] = False
                released = True
        if not released:
            return


@_inl_rc
def _range_rules(warn, t, loads, slips, CHK, kv, maxload, maxslip, stop, nwarn_limit):
    """Program WCHAIR's STATICS / MECHAN range rules on the tested tires on the ground: count the warnings;
    the stop code when a kind reaches its limit (``stop``), else 0."""
    nmax, smax, nmin = -math.inf, 0.0, math.inf
    for i in range(loads.shape[0]):
        if kv[i] != 0.0:
            nmin = min(nmin, loads[i])
            if CHK[i]:
                nmax = max(nmax, loads[i])
                smax = max(smax, abs(slips[i]))
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


@_inl_rc
def _pins(pin_mode, Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc):
    """Accelerations under the pin law: 1 every caster held (locked), 2 stick-slip, 0 WCHAIR's kinetic law (each
    with the viscous part ``-c_pin rate``)."""
    if pin_mode == 2:
        _stick_slip(Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc)
        return
    for kk in range(nc):          # one call of _accelerations for both laws: one inlined copy of the solve
        if pin_mode == 1:
            held[kk] = True
        else:
            mom[kk] = kinetic_pin_moment(DD[kk], mf[kk]) - cpin[kk] * DD[kk]
            held[kk] = False
    _accelerations(Mm, F0, nc, mom, held, W, w, acc)


@_inl_rc
def _kinematics(shape, p, nw, nc, UD, VD, THED, D, DD, cs, sn, vel, slips, xs, ys, CAM):
    """The caster angles' cosines and sines, the contact velocities (the fixed wheels' in their turned frames) and
    slip angles (deg), the caster contacts."""
    for kk in range(nc):
        cs[kk], sn[kk] = math.cos(D[kk]), math.sin(D[kk])
    contact_velocities(shape, UD, VD, THED, cs, sn, DD, p, vel)
    _wheel_frames(nw, CAM, vel)
    for i in range(nw + nc):
        slips[i] = slip_angle(vel[2 * i], vel[2 * i + 1])
    for kk in range(nc):
        base = 2 + 2 * nw + 6 * kk                 # x_p, y_p, trail of caster kk in p
        xs[nw + kk] = p[base] - p[base + 2] * cs[kk]
        ys[nw + kk] = p[base + 1] - p[base + 2] * sn[kk]


@_inl_rc
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


@njit(cache=True, nogil=True)
def initial_state(u0, v0, delta0, nz):
    """A run's :data:`NSTATE` + 2 nc + nz state at ``t = 0``: at rest in the plane, speeds ``u0``, ``v0`` (m/s), the
    casters at ``delta0`` (rad), not swivelling, no command."""
    nc = delta0.shape[0]
    state = np.zeros(NSTATE + 2 * nc + nz)
    state[4], state[5] = u0, v0
    for kk in range(nc):
        state[NSTATE + kk] = delta0[kk]
    return state


@njit(cache=True, nogil=True)
def step_layouts(k0, k1, cfg, p, nw, nc, TK, TS, TL, LIM, CHK, RK, RC, RS, CAM, kv, line, share, mf, cpin, states,
                 recs, status, warn, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise, mzrec):
    """Steps ``k0 .. k1 - 1`` of a batch of runs of one layout (one run: a batch of one, stepped to its end).

    ``cfg`` (:data:`NCFG` slots), parameters ``p`` (the generated order), ``nw`` fixed wheels and ``nc`` casters,
    per contact (fixed wheels, then casters) the tire slots (then each fixed wheel's camber tire) and range check,
    the rolling-resistance slots (kind, coefficients, scale), per fixed wheel the camber ``(deg, signed
    coefficient)`` and its angle's ``(cos, sin)``, the vertical stiffness and support line, the lines' roll shares,
    per caster the Coulomb limit (N m) and viscous coefficient (N m s/rad); one row per run of ``states``
    (:func:`initial_state`; its slot :data:`S_NREC` counts the rows written), ``recs`` (:data:`NREC` + 2 nc,
    rows), ``status`` (code, time), ``warn`` (3, 3: slip, load, lift-off counts, first time, largest) and
    ``mzrec``.  Each run still going (``status[r, 0] == 0``) advances.  With ``ctl_f[0] > 0`` the sampled
    controller of :mod:`stability.simulate.controller` (its arrays; the state it measures is ``[x, y, heading, u,
    v, yaw rate, delta_1, delta_d_1, ...]``) commands a yaw moment on the body at each sample, held until the next;
    without one, the yaw moment each run's command slot holds (set by the caller between calls, N m) acts.  Either
    goes through a first-order motor lag (``cfg[22]``, exact over each step); the commanded (saturated) moment is
    recorded in ``mzrec`` (N m).

    A run's steps are written in this loop, not in a jitted function of their own that it calls: numba compiles a
    called function to machine code on its own and then, linked into its caller, optimises and emits it again, so
    the whole step was compiled twice (about a fifth of the kernel's first use, measured)."""
    for r in range(states.shape[0]):
        if status[r, 0] != 0.0:
            continue
        # the run's rows (views); the step's scalars and scratch arrays are the run's own
        state, rec, run_status, run_warn, run_mz = states[r], recs[r], status[r], warn[r], mzrec[r]
        dt, stride, duimp, fcimp, ftimp = cfg[0], int(cfg[2]), cfg[3], cfg[4], cfg[5]
        pin_mode, stop, policy = int(cfg[6]), cfg[7] != 0.0, int(cfg[8])
        maxslip, maxload, nwarn_limit, shape, weight, h, mode = (cfg[9], cfg[10], cfg[11], int(cfg[12]), cfg[13],
                                                                 cfg[14], int(cfg[15]))
        slope, c_phi, s_phi, c_theta, s_theta, grav = cfg[16] != 0.0, cfg[17], cfg[18], cfg[19], cfg[20], cfg[21]
        g1 = g2 = 0.0
        wn = weight
        nt, n = nw + nc, 3 + nc
        half_dt2 = 0.5 * dt * dt
        X, Y, THE, THED, UD, VD = state[0], state[1], state[2], state[3], state[4], state[5]
        FC1, FC2 = state[6], state[7]
        next_k, cmd, mz, nrec = int(state[8]), state[S_CMD], state[10], int(state[S_NREC])
        D, DD = state[NSTATE:NSTATE + nc].copy(), state[NSTATE + nc:NSTATE + 2 * nc].copy()
        nz, ny = Az.shape[0], Cy.shape[0]
        z = state[NSTATE + 2 * nc:NSTATE + 2 * nc + nz]          # a view: advanced in place
        cs, sn, mom = np.zeros(nc), np.zeros(nc), np.zeros(nc)
        held = np.zeros(nc, dtype=np.bool_)
        rest = mf.copy() if pin_mode == 2 else np.zeros(nc)      # stick-slip: a reversing rate comes to rest
        vel, slips, loads, xs, ys = np.zeros(2 * nt), np.zeros(nt), np.zeros(nt), np.zeros(nt), np.zeros(nt)
        fw, fc = np.zeros(2 * nw), np.zeros(2 * nc)
        Mm, F0, W, w, acc = np.zeros((n, n)), np.zeros(n), np.zeros((n, n)), np.zeros(n), np.zeros(n)
        for j in range(nw):
            xs[j], ys[j] = p[2 + 2 * j], p[3 + 2 * j]
        use_ctl = ctl_f[0] > 0.0
        lag = cfg[22]
        keep = math.exp(-dt / lag) if lag > 0.0 else 0.0
        znew, y, sv = np.zeros(nz), np.zeros(ny), np.zeros(6 + 2 * nc)
        for k in range(k0, k1):
            t = k * dt
            if use_ctl:
                next_k, cmd = _samples(t, next_k, cmd, X, Y, THE, UD, VD, THED, D, DD, z, znew, y, sv, ctl_f, Cy, Dy,
                                       Az, Bu, By, Cz, noise)
            if lag <= 0.0:
                mz = cmd
            _kinematics(shape, p, nw, nc, UD, VD, THED, D, DD, cs, sn, vel, slips, xs, ys, CAM)
            if slope:   # gravity in body axes at the step's heading; the loads under the normal weight
                g1, g2, gn = gravity_body(grav, c_phi, s_phi, c_theta, s_theta, math.cos(THE), math.sin(THE))
                wn = weight * gn / grav
            layout_loads(mode, xs, ys, kv, line, share, wn, h, FC1, FC2, loads)
            code = _range_rules(run_warn, t, loads, slips, CHK, kv, maxload, maxslip, stop, nwarn_limit)
            if code != 0.0:
                run_status[0], run_status[1] = code, t
                break
            imp = t <= duimp * (1.0 + 1e-12) + 1e-15
            sum_fx, sum_fy = _tire_forces(nw, nc, TK, TS, TL, LIM, RK, RC, RS, CAM, vel, slips, loads, policy,
                                          ftimp != 0.0 and imp, ftimp, cs, sn, fw, fc)
            fy_ext = fcimp if (fcimp != 0.0 and imp) else 0.0
            equations(shape, UD, VD, THED, cs, sn, DD, p, fw, fc, fy_ext, mz, g1, g2, Mm, F0)
            _pins(pin_mode, Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc)
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




@_inl_rc
def _samples(t, next_k, cmd, X, Y, THE, UD, VD, THED, D, DD, z, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    """The sampled controller's samples due by ``t``: the next sample's index and the held command."""
    ks = int(math.floor(t / ctl_f[0] + 1e-9))
    while next_k <= ks:
        sv[0], sv[1], sv[2], sv[3], sv[4], sv[5] = X, Y, THE, UD, VD, THED
        for kk in range(D.shape[0]):
            sv[6 + 2 * kk], sv[7 + 2 * kk] = D[kk], DD[kk]
        cmd = controller_output(next_k, z, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
        next_k += 1
    return next_k, cmd


@_inl_rc
def _note(warn, kind, t, value):
    if warn[kind, 0] == 0.0 or abs(value) > abs(warn[kind, 2]):
        warn[kind, 2] = value
    if warn[kind, 0] == 0.0:
        warn[kind, 1] = t
    warn[kind, 0] += 1.0


invalidate_stale_cache(globals(), "layout_kernel.equations.sha256", (_gn, _lf, sys.modules[__name__]))
