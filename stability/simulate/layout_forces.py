"""MECHAN for any wheel layout: the tire forces of the fixed wheels and the casters (plain Python).

The layout kernel (:mod:`stability.simulate.layout_kernel`) compiles :func:`tire_forces` with the thesis engine's
compiled tire law; the layout's slope statics (:mod:`stability.study.layout_slope`) call it as it is, with the
tire law of :mod:`stability.tires.law`: one bookkeeping of rolling resistance, camber and the caster frames.
"""

from __future__ import annotations

from stability.tires.law import camber_force, lateral_force, rolling_force

__all__ = ["tire_forces", "wheel_frames"]


def wheel_frames(nw, CAM, vel):
    """Turn each fixed wheel's contact velocity from body axes into its own frame (the wheel turned by its angle
    ``a``, toe: ``CAM[j, 2:] = cos a, sin a``), in place, as the thesis engine's SLIP turns the toed main wheels'.

    Parameters
    ----------
    nw : int
        Number of fixed wheels.
    CAM : ndarray, shape (nw, 4)
        Per fixed wheel: camber deg, camber sign x f_c, cos and sin of the wheel's angle.
    vel : ndarray
        Contact velocities (forward, lateral per contact, fixed wheels first), m/s; the fixed wheels' rewritten.
    """
    for j in range(nw):
        if CAM[j, 3] != 0.0:
            c, s = CAM[j, 2], CAM[j, 3]
            vx, vy = vel[2 * j], vel[2 * j + 1]
            vel[2 * j], vel[2 * j + 1] = vx * c + vy * s, -vx * s + vy * c


def tire_forces(nw, nc, TK, TS, TL, LIM, RK, RC, RS, CAM, vel, slips, loads, policy, tire_push, ftimp, cs, sn, fw,
                 fc):
    """MECHAN for any layout: the tire forces of the fixed wheels in body axes (lateral, ``ftimp`` instead while
    ``tire_push``; rolling resistance against the contact's forward velocity; the camber thrust ``CAM[j, 1]``
    (the side's sign times ``f_c``) times the camber tire's force at ``CAM[j, 0]`` deg, the camber tires in the
    tire slots after the contacts'; all in the wheel's frame, turned into body axes by its angle ``CAM[j, 2:]``,
    as the thesis engine's MECHAN turns a toed main wheel's) and of the casters in their frames (lateral, rolling)
    written into ``fw``, ``fc``; returns their resultant in body axes ``(sum_fx, sum_fy)``, N.

    Parameters
    ----------
    nw, nc : int
        Numbers of fixed wheels and casters.
    TK, TS, TL, LIM : ndarray
        Per tire slot (contacts first, then the camber tires): the tire law's kind, coefficients, load
        scale and slip/load limits (:mod:`stability.tires.law`).
    RK, RC, RS : ndarray
        Per contact: rolling-resistance kind, coefficients and scale.
    CAM : ndarray, shape (nw, 4)
        Per fixed wheel: camber angle, deg, and the camber thrust's sign (0: no camber); cos and sin of the
        wheel's angle.
    vel : ndarray
        Contact velocities in the wheel's frame (:func:`wheel_frames`), m/s, forward then lateral per contact.
    slips : ndarray
        Slip angle per contact, deg.
    loads : ndarray
        Normal load per contact, N.
    policy : int
        The tire-range policy's code.
    tire_push : bool
        While the tire push acts (lateral force ``ftimp`` on each fixed wheel).
    ftimp : float
        The tire push's lateral force per fixed wheel, N.
    cs, sn : ndarray
        Cosine and sine of each caster's swivel angle.
    fw, fc : ndarray
        Written: the fixed wheels' (body axes) and casters' (caster frames) ``(fx, fy)``, N.

    Returns
    -------
    tuple of float
        ``(sum_fx, sum_fy)``: the resultant in body axes, N.
    """
    sum_fx = sum_fy = 0.0
    nt = nw + nc
    for j in range(nw):
        if tire_push:
            fy = ftimp
        else:
            fy, _bad = lateral_force(TK[j], TS[j], TL[j], LIM[j], slips[j], loads[j], policy, 0)
        fx = rolling_force(RK[j], RC[j], RS[j], loads[j], vel[2 * j])
        if CAM[j, 1] != 0.0:
            cf, _bad = lateral_force(TK[nt + j], TS[nt + j], TL[nt + j], LIM[nt + j], CAM[j, 0], loads[j], policy,
                                       0)
            fy += camber_force(CAM[j, 1], cf)
        if CAM[j, 3] != 0.0:
            c, s = CAM[j, 2], CAM[j, 3]
            fx, fy = fx * c - fy * s, fx * s + fy * c
        fw[2 * j], fw[2 * j + 1] = fx, fy
        sum_fx += fx
        sum_fy += fy
    for kk in range(nc):
        i = nw + kk
        fy, _bad = lateral_force(TK[i], TS[i], TL[i], LIM[i], slips[i], loads[i], policy, 0)
        fx = rolling_force(RK[i], RC[i], RS[i], loads[i], vel[2 * i])
        fc[2 * kk], fc[2 * kk + 1] = fx, fy
        sum_fx += fx * cs[kk] - fy * sn[kk]
        sum_fy += fx * sn[kk] + fy * cs[kk]
    return sum_fx, sum_fy
