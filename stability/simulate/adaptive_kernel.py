"""The adaptive scheme's right-hand side compiled (numba): loads consistent with the forces, stick-slip pin modes.

The WCHAIR kernel's physics (:mod:`stability.simulate.kernel`: the generated
equations and contact forces, the tire law) with the normal loads solved
consistently with the tire forces and no one-step lag; scipy's ``solve_ivp``
drives the integration and the event location from
:mod:`stability.simulate.adaptive`; see ``docs/simulator.md``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from stability.simulate import kernel as _k  # the WCHAIR kernel's helpers and layouts (numba reads module attributes)
from stability.simulate.cache_stamp import invalidate_stale_cache
from stability.simulate.options import LOAD_TOLERANCE

__all__ = ["NAUX", "evaluate", "samples"]

_jit = njit(cache=True, nogil=True)   # the entries called from Python; helpers as the WCHAIR kernel's (_int, _inl)

#: aux layout: loads (4), forces (8), slips (4), pin moments A, B, yaw-moment input, (19 unused), refused tire
#: input (kind, wheel, slip or camber deg, load)
NAUX = 24
#: the slots of the held drive that :meth:`stability.simulate.adaptive.AdaptiveModel.hold_drive` sets
DRIVE_D, DRIVE_E = _k.DRIVE_D, _k.DRIVE_E
#: pin modes (as :mod:`stability.simulate.adaptive`)
FREE_POS, FREE_NEG, STUCK, LOCKED = 1, -1, 0, 2


@_k._inl
def _consistent(vel, slips, trig, tire_imp, ftimp, policy, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, guess, gn):
    """Loads consistent with the tire forces (a fixed-point iteration).

    ``gn``: gravity normal to the plane (m/s^2; ``P[G]`` when level).
    Returns ``(loads, F, refused, wheel, converged)``; ``guess`` (sum fx, sum fy) is updated in place.
    """
    ce, se, cb, sb = trig
    sfx, sfy = guess[0], guess[1]
    it = 0
    while True:
        loads = _k.contact_loads(P, sfx, sfy, gn, ce, se, cb, sb)
        F, refused, wheel = _k.mechan(vel, slips, loads, tire_imp, ftimp, policy, TK, TS[0], TS[1], TS[2], TL, LIM[0],
                                   LIM[1], LIM[2], RK, RC[0], RC[1], RS, CAM, S)
        if refused != 0:
            return loads, F, refused, wheel, True
        nfx, nfy = _k.tire_resultant(*F, ce, se, cb, sb)
        err = abs(nfx - sfx) + abs(nfy - sfy)
        scale = 1.0 + abs(nfx) + abs(nfy)
        sfx, sfy = nfx, nfy
        it += 1
        if err <= LOAD_TOLERANCE * scale:
            guess[0], guess[1] = sfx, sfy
            return loads, F, 0, 0, True
        if it == 100:
            return loads, F, 0, 0, False


@_jit
def evaluate(t, y, ma_mode, mb_mode, imp, mz, model, ftimp, policy, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, SL,
             guess, dy, aux):
    """Derivatives ``dy`` (10) and ``aux`` (:data:`NAUX`) at ``(t, y)``; returns 0, or 1/2 refused, 3 no convergence.

    ``y`` = (X, Y, psi, u, v, r, eta, eta_dot, beta, beta_dot); pin modes as
    :mod:`stability.simulate.adaptive`; ``imp``: the push acts; ``mz`` the
    yaw-moment input, N m; ``SL`` the plane slots
    (:func:`stability.simulate.packing.slope_slots`).
    """
    g1 = g2 = 0.0
    gn = P[_k.G]
    if SL[0] != 0.0:   # on a slope: gravity in body axes at the heading psi, the exact model with gravity
        model = _k.SLOPE_MODEL
        g1, g2, gn = _k.gravity_body(P[_k.G], SL[1], SL[2], SL[3], SL[4], math.cos(y[2]), math.sin(y[2]))
    psi, u, v, r, eta, ed, beta, bd = y[2], y[3], y[4], y[5], y[6], y[7], y[8], y[9]
    if ma_mode == STUCK or ma_mode == LOCKED:
        ed = 0.0 * ed
    if mb_mode == STUCK or mb_mode == LOCKED:
        bd = 0.0 * bd
    ce, se, cb, sb = math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta)
    vel = _k.kinematics(model, P, S, u, v, r, ce, se, cb, sb, ed, bd)
    slips = _k.slip_angles(vel)
    loads, F, refused, wheel, ok = _consistent(vel, slips, (ce, se, cb, sb), ftimp != 0.0 and imp, ftimp, policy,
                                               P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, guess, gn)
    if refused != 0:
        aux[20], aux[21] = refused, wheel
        aux[22], aux[23] = (slips[wheel], loads[wheel]) if refused == 1 else (CAM[0], loads[wheel])
        return refused
    if not ok:
        return 3
    fy_ext = S[_k.FCIMP] if (S[_k.FCIMP] != 0.0 and imp) else 0.0
    # a slipping caster's kinetic moment against the sign of its rate (the mode)
    ma = _k.kinetic_pin_moment(float(ma_mode), P[_k.MAF]) if (ma_mode == FREE_POS or ma_mode == FREE_NEG) else 0.0
    mb = _k.kinetic_pin_moment(float(mb_mode), P[_k.MBF]) if (mb_mode == FREE_POS or mb_mode == FREE_NEG) else 0.0
    hold_a = ma_mode == STUCK or ma_mode == LOCKED
    hold_b = mb_mode == STUCK or mb_mode == LOCKED
    acc, ma, mb = _k.held_pins(model, (u, v, r, ce, se, cb, sb, ed, bd), F, ma, mb, hold_a, hold_b, fy_ext, mz, None,
                            P, g1, g2)
    cpsi, spsi = math.cos(psi), math.sin(psi)
    dy[0], dy[1], dy[2] = u * cpsi - v * spsi, u * spsi + v * cpsi, r
    dy[3], dy[4], dy[5], dy[6], dy[7], dy[8], dy[9] = acc[0], acc[1], acc[2], ed, acc[3], bd, acc[4]
    for i in range(4):
        aux[i] = loads[i]
        aux[12 + i] = slips[i]
    for i in range(8):
        aux[4 + i] = F[i]
    aux[16], aux[17], aux[18] = ma, mb, mz
    return 0


@_jit
def samples(ts, yy, mzs, ma_mode, mb_mode, imp, model, ftimp, policy, P, S, TK, TS, TL, LIM, RK, RC, RS, CAM, SL,
            out, guess, dy, aux):
    """Recorded columns (``COLUMNS[1:]``, ``out`` of shape (31, m)) at the dense-output samples ``yy`` (10, m).

    ``mzs``: the yaw-moment input at each sample, N m.  Each sample's load
    iteration starts from zero forces.  Returns the first nonzero status of
    :func:`evaluate`, else 0.
    """
    y = np.empty(10)   # a contiguous copy of each sample: evaluate compiles for the solver's contiguous y only
    for j in range(ts.shape[0]):
        for c in range(10):
            y[c] = yy[c, j]
        guess[0], guess[1] = 0.0, 0.0
        code = evaluate(ts[j], y, ma_mode, mb_mode, imp, mzs[j], model, ftimp, policy, P, S, TK, TS, TL, LIM, RK,
                        RC, RS, CAM, SL, guess, dy, aux)
        if code != 0:
            return code
        F = (aux[4], aux[5], aux[6], aux[7], aux[8], aux[9], aux[10], aux[11])
        _k.record_row(out, j, (y[0], y[1], y[2], y[5], y[3], y[4], y[6], dy[6], y[8], dy[8]), F, aux[0:4],
                      aux[12:16], P, (math.cos(y[6]), math.sin(y[6]), math.cos(y[8]), math.sin(y[8])),
                      (aux[18], dy[5], aux[16], aux[17]))
    return 0


invalidate_stale_cache(globals(), "adaptive_kernel.equations.sha256")
