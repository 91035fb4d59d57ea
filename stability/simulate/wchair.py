"""Program WCHAIR's fixed-step scheme in Python floats: the path for a Python ``yaw_moment(t, state)`` input.

The compiled kernel (:mod:`.kernel`) runs every other WCHAIR-scheme run; this
path is taken only when a Python callable must see the state every step.

The step (SLIP, STATICS, MECHAN, DYNAM, UPDATE/ITRATE) is described in ``docs/simulator.md``.
"""

from __future__ import annotations

import math

import numpy as np

from stability.chair import Chair
from stability.models.full_width import tire_resultant, tire_yaw_moment
from stability.models.statics import normal_loads
from stability.simulate.options import (
    LOAD_LIMIT_N,
    SLIP_LIMIT_DEG,
    WARNING_LIMIT,
    Options,
    impulse_on,
    initial_velocities,
    n_steps,
)
from stability.simulate.physics import (
    Physics,
    accelerations,
    held_accelerations,
    kinematics,
    loads,
    plane,
    slip_angles,
    tire_forces,
)
from stability.simulate.pin_friction import rest_rate, stick_slip
from stability.simulate.results import NCOLS, ChairState, SimulationResult, new_warnings, note_warning

__all__ = ["wchair_single"]

# ---------------------------------------------------------------------------
# scheme "wchair": one run, Python floats
# ---------------------------------------------------------------------------
def wchair_single(chair: Chair, speed: float, opts: Options) -> SimulationResult:
    """One run of program WCHAIR's fixed-step scheme (Appendix C) in Python floats.

    Each step: SLIP (contact velocities, slip angles), STATICS (normal loads
    from the previous step's resultant forces; warning above 450 N), MECHAN
    (tire forces; warning above 8 deg of slip), DYNAM (accelerations), then
    UPDATE/ITRATE (constant acceleration over the step).  Used for a Python
    ``yaw_moment`` input and inside :func:`~stability.simulate.reference_engine`;
    the compiled kernel is tested against it.

    Pin friction follows ``opts.friction_law``: "kinetic" is WCHAIR's moment
    ``-M_f sign(swivel rate)``; "stick-slip" holds a caster at rest while
    its holding moment is within the friction limit and brings a rate that
    would change sign within a step to rest
    (:func:`~stability.simulate.pin_friction.stick_slip`,
    :func:`~stability.simulate.pin_friction.rest_rate`), the compiled
    kernel's law in the same operations.

    Parameters
    ----------
    chair : Chair
        The chair.
    speed : float
        Initial forward speed, m/s (> 0; checked by the caller).
    opts : Options
        Checked options (:func:`~stability.simulate.options.make_options`)
        with ``scheme="wchair"``.

    Returns
    -------
    SimulationResult
        Rows every ``opts.stride`` steps from ``t = 0`` to ``duration + dt``,
        or, when ``opts.stop_on_warnings``, up to the step before the one
        whose eleventh warning of a kind stopped the run.
    """
    K = Physics([chair], opts, vector=False)
    p = K.p
    dt, half_dt2, locked, thesis, yaw_fn, stop, stride, fcimp = opts.step_constants()
    cos, sin = math.cos, math.sin
    loads_fn = normal_loads
    maf, mbf = K.maf, K.mbf
    sticks = opts.pin_mode == 2.0       # free casters with stick-slip pin friction (else WCHAIR's kinetic law)
    slope = K.slope_trig is not None
    grav = None
    check_all, chk = K.check_all, K.chk or (True, True, True, True)   # single run: one tire group, chk set

    UD, VD = initial_velocities(opts, speed)
    X = Y = THE = THED = THEDD = 0.0
    E, B = opts.eta0, opts.beta0
    ED = BD = 0.0
    FC1 = FC2 = 0.0
    warn = new_warnings()
    nwarn_load = nwarn_slip = 0
    stopped = False
    stop_time = None
    rec = []
    n = n_steps(opts)
    for k in range(n):
        t = k * dt
        ce, se, cb, sb = cos(E), sin(E), cos(B), sin(B)
        # SLIP
        vel = kinematics(K, UD, VD, THED, ce, se, cb, sb, ED, BD)
        slips = slip_angles(K, vel)
        # STATICS (previous step's FC1, FC2); on a slope gravity at this step's heading
        if slope:
            g1, g2, gn = plane(K, THE)
            grav = (g1, g2)
            NA, NB, ND, NE = loads(K, FC1, FC2, ce, se, cb, sb, gn)
        else:
            NA, NB, ND, NE = loads_fn(p, FC1, FC2, ce, se, cb, sb)
        nmax = max(NA, NB, ND, NE) if check_all else max(
            (n_ for n_, c_ in zip((NA, NB, ND, NE), chk, strict=False) if c_), default=0.0)
        if nmax > LOAD_LIMIT_N:
            nwarn_load += 1
            note_warning(warn, "load", t, nmax)
            if stop and nwarn_load > WARNING_LIMIT:
                stopped, stop_time = True, t
                break
        nmin = min(NA, NB, ND, NE)
        if nmin < 0.0:
            note_warning(warn, "lift_off", t, nmin)
        # MECHAN
        smax = max(abs(slips[0]), abs(slips[1]), abs(slips[2]), abs(slips[3])) if check_all else max(
            (abs(s_) for s_, c_ in zip(slips, chk, strict=False) if c_), default=0.0)
        if smax > SLIP_LIMIT_DEG:
            nwarn_slip += 1
            note_warning(warn, "slip", t, smax)
            if stop and nwarn_slip > WARNING_LIMIT:
                stopped, stop_time = True, t
                break
        imp = impulse_on(opts, t)
        F = tire_forces(K, imp, vel, slips, NA, NB, ND, NE)
        # DYNAM
        fc1, fc2 = tire_resultant(F, ce, se, cb, sb)
        fy_ext = fcimp if (fcimp != 0.0 and imp) else 0.0
        mz = 0.0 if yaw_fn is None else float(yaw_fn(t, ChairState(X, Y, THE, UD, VD, THED, E, ED, B, BD, 0)))
        state = (UD, VD, THED, ce, se, cb, sb, ED, BD)
        rdc = THEDD if thesis else None
        if locked:
            acc, MA, MB = held_accelerations(K, state, F, 0.0, 0.0, fy_ext, mz, True, True, rdc, grav)
        elif sticks:
            acc, MA, MB = stick_slip(K, state, F, fy_ext, mz, rdc, grav)
        else:
            MA = math.copysign(maf, -ED) if ED != 0.0 else 0.0
            MB = math.copysign(mbf, -BD) if BD != 0.0 else 0.0
            acc = accelerations(K, state, F, MA, MB, fy_ext, mz, rdc, grav)
        UDD, VDD, THEDD, EDD, BDD = acc
        if locked:
            EDD = BDD = 0.0
        if k % stride == 0:
            rec.append((t, X, Y, THE, THED, UD, VD, E, ED, B, BD, *F, NA, NB, ND, NE, *slips,
                        tire_yaw_moment(p, F, ce, se, cb, sb), mz, THEDD, MA, MB))
        # UPDATE / ITRATE
        FC1, FC2 = fc1, fc2 + fy_ext
        du = UD * dt + UDD * half_dt2
        dv = VD * dt + VDD * half_dt2
        cost, sint = cos(THE), sin(THE)
        X += du * cost - dv * sint
        Y += du * sint + dv * cost
        UD += UDD * dt
        VD += VDD * dt
        B += BD * dt + BDD * half_dt2
        E += ED * dt + EDD * half_dt2
        if sticks:      # a rate that would change sign within the step comes to rest (pin_friction.rest_rate)
            BD = rest_rate(BD, BDD, dt, mbf)
            ED = rest_rate(ED, EDD, dt, maf)
        else:
            BD += BDD * dt
            ED += EDD * dt
        THE += THED * dt + THEDD * half_dt2
        THED += THEDD * dt
    arr = np.array(rec, dtype=float).reshape(-1, NCOLS)
    return SimulationResult._from_records(arr, warnings=warn, stopped=stopped, stop_time=stop_time, chair=chair,
                                          speed=speed, settings=opts.settings())
