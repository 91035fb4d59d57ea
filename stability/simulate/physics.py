"""Physics glue of the simulator: tires, contact kinematics, tire forces (MECHAN), accelerations (DYNAM).

Floats (one run) or numpy arrays over runs (the reference batch path).  The
equations come through :mod:`stability.models.full_width`; loads and contact
points from :mod:`stability.models.statics`.  See ``docs/simulator.md``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from stability import tires as _tires
from stability.chair import Chair
from stability.models import full_width
from stability.models import slope as slope_model
from stability.models.params import parameters as _parameters
from stability.models.statics import normal_loads as _level_loads
from stability.simulate.options import Options

__all__ = ["Physics", "TireGroup", "NO_FORCE", "kinematics", "slip_angles", "tire_forces", "accelerations",
           "held_accelerations", "plane", "loads"]

class _MathOps:
    cos = staticmethod(math.cos)
    sin = staticmethod(math.sin)
    atan2 = staticmethod(math.atan2)
    copysign = staticmethod(math.copysign)
    degrees = staticmethod(math.degrees)


class _NumpyOps:
    cos = staticmethod(np.cos)
    sin = staticmethod(np.sin)
    atan2 = staticmethod(np.arctan2)
    copysign = staticmethod(np.copysign)
    degrees = staticmethod(np.degrees)


NO_FORCE = 0.0  # the longitudinal forces when rolling resistance is off (identity-tested)


def shared_scalars(p):
    """Params with every field that is equal across the batch as a Python float."""
    return type(p)(*(float(f[0]) if np.ndim(f) and np.all(f == f[0]) else f for f in p))


def ops(x):
    """math for Python floats, numpy for arrays."""
    return _NumpyOps if isinstance(x, np.ndarray) else _MathOps


class TireGroup:
    """The tires of one group of runs (same tire models, scales, camber)."""

    def __init__(self, chair: Chair, opts: Options):
        self.main = chair.main_tire_model()
        self.caster = chair.caster_tire_model()
        self.main_rolling = chair.main_rolling_scale != 0
        self.caster_rolling = chair.caster_rolling_scale != 0
        self.camber_coefficient = chair.camber_coefficient
        if opts.scheme == "wchair":
            # MECHAN 0729-0733: CAMCOF * POLYFT(TIRY, INT(CAMANG), FZ): whole
            # degrees, the unscaled tire (TYMOD does not apply).
            self.camber_tire = _tires.get(chair.main_tire)
            self.camber_deg = float(math.trunc(chair.camber_deg))
        else:
            self.camber_tire = self.main
            self.camber_deg = float(chair.camber_deg)
        # the treadmill range (8 deg, 450 N) applies to tested tires only
        self.check_main = isinstance(self.main, _tires.Tire)
        self.check_caster = isinstance(self.caster, _tires.Tire)

    @staticmethod
    def key(chair: Chair):
        return (chair.main_tire, chair.main_lateral_scale, chair.main_rolling_scale, chair.caster_tire,
                chair.caster_lateral_scale, chair.caster_rolling_scale, chair.camber_deg, chair.camber_coefficient)


class Physics:
    """Everything the physics glue needs: parameters, tires, options.

    The equations are the generated functions behind :mod:`stability.models`
    (:mod:`stability._generated.full_width`), looked up once here so that a
    step does not pay the facade's per-call dispatch.  In a batch, parameters
    shared by all runs are passed as Python floats (fewer array operations).
    """

    def __init__(self, chairs: Sequence[Chair], opts: Options, vector: bool):
        fw = full_width.generated
        self.vector = vector
        self.variant = opts.model
        self.policy: Any = opts.out_of_range          # one of OUT_OF_RANGE_POLICIES (checked)
        self.opts = opts
        self.cv_fn = getattr(fw, f"contact_velocities_{opts.model}")
        self.acc_fn = getattr(fw, f"accelerations_{opts.model}")
        self.thesis = opts.model == "thesis"
        #: on a slope: (cos, sin) of the cross slope and of the grade; None when level
        self.slope_trig: tuple[float, float, float, float] | None = opts.slope_trig() if opts.on_slope else None
        if vector:
            self.p = shared_scalars(_parameters(list(chairs)))
            keys = [TireGroup.key(c) for c in chairs]
            uniq: dict = {}
            for i, k in enumerate(keys):
                uniq.setdefault(k, []).append(i)
            self.groups: list[tuple[TireGroup, Any]] = [(TireGroup(chairs[idx[0]], opts), np.array(idx))
                                                        for idx in uniq.values()]
            toe: Any = np.array([math.radians(c.toe_deg) for c in chairs])
            self.toe = bool(np.any(toe != 0))
            self.ct: Any = np.cos(toe)
            self.st: Any = np.sin(toe)
        else:
            c = chairs[0]
            self.p = _parameters(c)
            self.groups = [(TireGroup(c, opts), None)]
            toe = math.radians(c.toe_deg)
            self.toe = bool(toe != 0)
            self.ct, self.st = math.cos(toe), math.sin(toe)
        self.maf = self.p.pin_friction_left
        self.mbf = self.p.pin_friction_right
        self.geom = self.p.geometry
        self.inertia = self.p.inertia
        self.single_group = len(self.groups) == 1
        self.any_camber = any(g.camber_deg != 0 for g, _ in self.groups)
        self.any_rolling = any(g.main_rolling or g.caster_rolling for g, _ in self.groups)
        self._range_masks()
        self.ftimp = opts.tire_impulse
        self.duimp = opts.impulse_duration
        self.stack: _tires.TireStack | None = None
        self.caster_lateral: Callable = self._caster_lateral_groups
        self.main_lateral: Callable = self._main_lateral_groups
        if self.single_group:  # bind the tire calls once (hot path)
            g0 = self.groups[0][0]
            pol = self.policy
            if vector and isinstance(g0.caster, _tires.Tire) and isinstance(g0.main, _tires.Tire):
                # all four wheels of every run in one call (rows A, B, D, E)
                self.stack = _tires.TireStack((g0.caster, g0.caster, g0.main, g0.main))
            cl, ml = g0.caster.lateral_force, g0.main.lateral_force
            self.caster_lateral = lambda slip, fz: cl(slip, fz, policy=pol, warn=False)
            self.main_lateral = lambda slip, fz: ml(slip, fz, policy=pol, warn=False)

    def _range_masks(self) -> None:
        """Which wheels the thesis's range rules apply to (tested tires only)."""
        g0 = self.groups[0][0]
        if self.single_group:
            self.chk: tuple[bool, ...] | None = (g0.check_caster, g0.check_caster, g0.check_main, g0.check_main)
            self.check_all = all(self.chk)
            self.chk_mask: np.ndarray | None = None
            return
        n = sum(int(i.size) for _, i in self.groups)
        m = np.zeros((4, n), dtype=bool)
        for g, idx in self.groups:
            m[0:2, idx] = g.check_caster
            m[2:4, idx] = g.check_main
        self.chk = None
        self.check_all = bool(m.all())
        self.chk_mask = None if self.check_all else m

    def compact(self, keep: np.ndarray) -> None:
        """Keep only the runs at positions ``keep`` (batch path)."""
        self.p = type(self.p)(*(f[keep] if np.ndim(f) else f for f in self.p))
        self.maf = self.p.pin_friction_left
        self.mbf = self.p.pin_friction_right
        self.geom = self.p.geometry
        self.inertia = self.p.inertia
        if self.toe:
            self.ct, self.st = self.ct[keep], self.st[keep]
        if not self.single_group:
            # a group whose runs have all stopped is empty (it stays in the list, with no runs)
            pos = np.full(max((int(np.max(i)) for _, i in self.groups if i.size), default=-1) + 1, -1)
            pos[keep] = np.arange(len(keep))
            self.groups = [(g, pos[i][pos[i] >= 0]) for g, i in self.groups]
            if self.chk_mask is not None:
                self.chk_mask = self.chk_mask[:, keep]

    # -- tire calls (dispatch over groups for batches) ----------------------
    def _per_group(self, fn, *arrays):
        if self.single_group:
            return fn(self.groups[0][0], *arrays)
        out = np.zeros(np.shape(arrays[0]))
        for g, idx in self.groups:
            if idx.size:
                out[idx] = fn(g, *(a[idx] for a in arrays))
        return out

    def _caster_lateral_groups(self, slip, fz):
        pol = self.policy
        return self._per_group(lambda g, s, f: g.caster.lateral_force(s, f, policy=pol, warn=False), slip, fz)

    def _main_lateral_groups(self, slip, fz):
        pol = self.policy
        return self._per_group(lambda g, s, f: g.main.lateral_force(s, f, policy=pol, warn=False), slip, fz)

    def caster_rolling(self, fz, vx):
        xp = ops(vx)
        return self._per_group(
            lambda g, f, w: xp.copysign(g.caster.rolling_resistance(f), -w) if g.caster_rolling else 0.0 * f, fz, vx)

    def main_rolling(self, fz, vx):
        xp = ops(vx)
        return self._per_group(
            lambda g, f, w: xp.copysign(g.main.rolling_resistance(f), -w) if g.main_rolling else 0.0 * f, fz, vx)

    def camber(self, fz):
        return self._per_group(
            lambda g, f: (g.camber_tire.camber_force(g.camber_deg, f, g.camber_coefficient, policy=self.policy,
                                                     warn=False) if g.camber_deg != 0 else 0.0 * f), fz)


def kinematics(K: Physics, u, v, r, ce, se, cb, sb, ed, bd):
    """Contact velocities (program WCHAIR's SLIP, Appendix C), main wheels in their toed wheel frames.

    Floats for one run, or arrays of shape ``(n,)`` over the runs of a batch.

    Parameters
    ----------
    K : Physics
        Parameters, variant and toe of the run(s).
    u, v : float or ndarray
        Forward and lateral velocity of the c.g. in body axes, m/s (UD, VD).
    r : float or ndarray
        Yaw rate, rad/s (THED, positive clockwise from above).
    ce, se, cb, sb : float or ndarray
        cos and sin of the left (eta, E) and right (beta, B) caster angles.
    ed, bd : float or ndarray
        Caster swivel rates relative to the chair, rad/s (ED, BD).

    Returns
    -------
    tuple of 8 (float or ndarray)
        ``(vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy)``, m/s: casters A, B in
        their own frames, main wheels D (left), E (right) in their wheel
        frames, turned by the toe angle when the chair has toe (SLIP lines
        0564-0573).
    """
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = K.cv_fn(u, v, r, ce, se, cb, sb, ed, bd, *K.geom)
    if K.toe:  # SLIP lines 0564-0573: right wheel turned by +toe, left by -toe
        ct, st = K.ct, K.st
        vEx, vEy = vEx * ct + vEy * st, -vEx * st + vEy * ct
        vDx, vDy = vDx * ct - vDy * st, vDx * st + vDy * ct
    return vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy


def slip_angles(K: Physics, vel):
    """Signed slip angles (deg): atan2(vy, |vx|); WCHAIR's SLIPx = abs of these.

    Parameters
    ----------
    K : Physics
        Unused; kept for the uniform call signature of the physics glue.
    vel : tuple of 8 (float or ndarray)
        Contact velocities from :func:`kinematics`, m/s.

    Returns
    -------
    tuple of 4 (float or ndarray)
        Slip angles of A, B, D, E, deg, in ``[-90, 90]``; the sign is that of
        the lateral contact velocity.
    """
    xp = ops(vel[1])
    a2, dg = xp.atan2, xp.degrees
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    return (dg(a2(vAy, abs(vAx))), dg(a2(vBy, abs(vBx))), dg(a2(vDy, abs(vDx))), dg(a2(vEy, abs(vEx))))


def tire_forces(K: Physics, impulse_on: bool, vel, slips, NA, NB, ND, NE, S4=None, N4=None):
    """MECHAN: tire forces (casters in their frames, main wheels in body axes).

    ``S4``, ``N4`` (batch path): the slips and loads stacked as ``(4, n)``
    arrays, so that both wheels of a pair go through one tire call.

    Lateral forces come from the tire fits (the policy ``K.policy`` outside
    8 deg and 450 N); ``tire_impulse`` (FTIMP) replaces the main wheels'
    lateral forces while the push acts (MECHAN lines 0704-0706); rolling
    resistance opposes each wheel's longitudinal contact velocity; camber
    adds a lateral force on each main wheel (tops inward push the left wheel
    right and the right wheel left; MECHAN lines 0729-0733).

    Parameters
    ----------
    K : Physics
        Tires, options and toe of the run(s).
    impulse_on : bool
        Whether the push acts now (:func:`~stability.simulate.options.impulse_on`).
    vel : tuple of 8 (float or ndarray)
        Contact velocities from :func:`kinematics`, m/s.
    slips : tuple of 4 (float or ndarray)
        Signed slip angles of A, B, D, E from :func:`slip_angles`, deg.
    NA, NB, ND, NE : float or ndarray
        Normal loads on A, B, D, E, N (>= 0 while every wheel touches).
    S4, N4 : ndarray, optional
        ``(4, n)`` stacks of ``slips`` (deg) and loads (N), rows A, B, D, E
        (batch path); None for a single run.

    Returns
    -------
    tuple of 8 (float or ndarray)
        ``(FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy)``, N: casters in their own
        frames, main wheels in body axes.
    """
    vAx, vAy, vBx, vBy, vDx, vDy, vEx, vEy = vel
    sA, sB, sD, sE = slips
    ftimp_on = K.ftimp != 0.0 and impulse_on
    if S4 is not None and K.stack is not None:
        FAy, FBy, FDy, FEy = K.stack.lateral_force(S4, N4, policy=K.policy)
    elif S4 is not None and K.single_group:
        m = S4.shape[1]
        lat = K.caster_lateral(S4[0:2].reshape(-1), N4[0:2].reshape(-1))
        FAy, FBy = lat[:m], lat[m:]
        if not ftimp_on:
            lat = K.main_lateral(S4[2:4].reshape(-1), N4[2:4].reshape(-1))
            FDy, FEy = lat[:m], lat[m:]
    else:
        FAy = K.caster_lateral(sA, NA)
        FBy = K.caster_lateral(sB, NB)
        if not ftimp_on:
            FDy = K.main_lateral(sD, ND)
            FEy = K.main_lateral(sE, NE)
    if ftimp_on:  # MECHAN 0704-0706: FTIMP replaces FDY, FEY
        FDy = K.ftimp + 0.0 * ND
        FEy = K.ftimp + 0.0 * NE
    if K.any_rolling:
        FAx = K.caster_rolling(NA, vAx)
        FBx = K.caster_rolling(NB, vBx)
        FDx = K.main_rolling(ND, vDx)
        FEx = K.main_rolling(NE, vEx)
    else:
        FAx = FBx = FDx = FEx = NO_FORCE
    if K.any_camber:  # MECHAN 0729-0733: tops inward push the left wheel right, the right wheel left
        FDy = FDy + K.camber(ND)
        FEy = FEy - K.camber(NE)
    if K.toe:  # MECHAN 0734-0743: back to body axes
        ct, st = K.ct, K.st
        FEx, FEy = FEx * ct - FEy * st, FEx * st + FEy * ct
        FDx, FDy = FDx * ct + FDy * st, -FDx * st + FDy * ct
    return FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy


def plane(K: Physics, psi):
    """Gravity in body axes at heading ``psi`` on the run's plane (generated ``gravity_body``).

    Parameters
    ----------
    K : Physics
        Parameters and the plane (``K.slope_trig``, not None) of the run(s).
    psi : float or ndarray
        Heading from the initial direction, rad (THE, clockwise from above).

    Returns
    -------
    tuple of 3 (float or ndarray)
        ``(g1, g2, gn)``, m/s^2: forward and to the right in the plane, normal to it.
    """
    xp = ops(psi)
    assert K.slope_trig is not None
    cph, sph, cth, sth = K.slope_trig
    return slope_model.generated.gravity_body(K.p.g, cph, sph, cth, sth, xp.cos(psi), xp.sin(psi))


def loads(K: Physics, sum_fx, sum_fy, ce, se, cb, sb, gn=None):
    """STATICS: normal loads (N) from the tire-force sums; eq 6-25, or on a plane with normal gravity ``gn``.

    Parameters
    ----------
    K : Physics
        Parameters of the run(s).
    sum_fx, sum_fy : float or ndarray
        Sums of the forces on the chair in body axes, N (FC1, FC2).
    ce, se, cb, sb : float or ndarray
        cos and sin of the caster angles.
    gn : float or ndarray, optional
        Gravity normal to the plane, m/s^2 (:func:`plane`); None: level
        (:func:`stability.models.statics.normal_loads`, today's arithmetic).

    Returns
    -------
    tuple of 4 (float or ndarray)
        ``(N_A, N_B, N_D, N_E)``, N.
    """
    if gn is None:
        return _level_loads(K.p, sum_fx, sum_fy, ce, se, cb, sb)
    return slope_model.normal_loads_plane(K.p, sum_fx, sum_fy, gn, ce, se, cb, sb)


def accelerations(K: Physics, state, F, M_A, M_B, fy_ext, mz, rdc=None, grav=None):
    """(u_dot, v_dot, r_dot, eta_dd, beta_dd) from the model (DYNAM; equations of motion of Table 6-1).

    Parameters
    ----------
    K : Physics
        Parameters and variant (``"thesis"`` or ``"exact"``) of the run(s).
    state : tuple of 9 (float or ndarray)
        ``(u, v, r, ce, se, cb, sb, eta_dot, beta_dot)``: velocities of the
        c.g., m/s; yaw rate, rad/s; cos/sin of the caster angles; caster
        swivel rates, rad/s.
    F : tuple of 8 (float or ndarray)
        Tire forces from :func:`tire_forces`, N.
    M_A, M_B : float or ndarray
        Pin moments on casters A and B, N m (Coulomb friction opposing the
        swivel rate, or the holding moments).
    fy_ext : float or ndarray
        External lateral force at the c.g., N (FCIMP while the push acts).
    mz : float or ndarray
        External yaw moment on the chair, N m.
    rdc : float or ndarray, optional
        Thesis variant only: the yaw acceleration the caster equations use,
        rad/s^2 (WCHAIR's DYNAM uses the previous step's THEDD); None: the
        current one.  Ignored by the exact variant.
    grav : tuple of 2 (float or ndarray), optional
        ``(g1, g2)``: in-plane gravity in body axes, m/s^2 (:func:`plane`);
        the exact model on a slope (gravity on the chair and on each caster
        at its own c.g., generated ``accelerations_slope_exact``).  None: level.

    Returns
    -------
    tuple of 5 (float or ndarray)
        ``(u_dot, v_dot, r_dot, eta_dd, beta_dd)``: m/s^2, m/s^2, rad/s^2,
        rad/s^2, rad/s^2.
    """
    u, v, r, ce, se, cb, sb, ed, bd = state
    if grav is not None:
        FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy = F
        x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp = K.inertia
        return slope_model.generated.accelerations_slope_exact(
            u, v, r, ce, se, cb, sb, ed, bd, FAx, FAy, FBx, FBy, FDx, FDy, FEx, FEy, M_A, M_B, fy_ext, mz,
            grav[0], grav[1], x_m, x_p, d1, d2, t1, t2, trail, l1, m, m_c, i_z, i_zp)
    if K.thesis:
        return K.acc_fn(u, v, r, ce, se, cb, sb, ed, bd, *F, M_A, M_B, fy_ext, mz, *K.inertia, r_dot_casters=rdc)
    return K.acc_fn(u, v, r, ce, se, cb, sb, ed, bd, *F, M_A, M_B, fy_ext, mz, *K.inertia)


def held_accelerations(K: Physics, state, F, M_A, M_B, fy_ext, mz, hold_a, hold_b, rdc=None, grav=None):
    """Accelerations with caster A and/or B held (eta_dd = 0 and/or beta_dd = 0).

    The equations are affine in the pin moments, so the holding moments are
    solved from two or three evaluations.  Returns ``(acc, M_A, M_B)`` with
    the held sides' moments replaced by the reactions.

    Parameters
    ----------
    K, state, F, M_A, M_B, fy_ext, mz, rdc, grav
        As in :func:`accelerations` (``M_A``, ``M_B`` in N m are used only
        for a side that is not held).
    hold_a, hold_b : bool
        Hold caster A (left) and/or B (right) against swivelling: locked
        casters, or a pin stuck by its Coulomb friction (stick phase of the
        adaptive scheme).

    Returns
    -------
    acc : tuple of 5 (float or ndarray)
        ``(u_dot, v_dot, r_dot, eta_dd, beta_dd)`` as in
        :func:`accelerations`, with ``eta_dd`` and/or ``beta_dd`` zero on the
        held side(s).
    M_A, M_B : float or ndarray
        Pin moments, N m: the holding reaction on a held side, the input
        moment otherwise.
    """
    if not (hold_a or hold_b):
        return accelerations(K, state, F, M_A, M_B, fy_ext, mz, rdc, grav), M_A, M_B
    base_a = 0.0 * M_A if hold_a else M_A
    base_b = 0.0 * M_B if hold_b else M_B
    a0 = accelerations(K, state, F, base_a, base_b, fy_ext, mz, rdc, grav)
    if hold_a and hold_b:
        a1 = accelerations(K, state, F, base_a + 1.0, base_b, fy_ext, mz, rdc, grav)
        a2 = accelerations(K, state, F, base_a, base_b + 1.0, fy_ext, mz, rdc, grav)
        k11, k21 = a1[3] - a0[3], a1[4] - a0[4]
        k12, k22 = a2[3] - a0[3], a2[4] - a0[4]
        det = k11 * k22 - k12 * k21
        ma = (-a0[3] * k22 + a0[4] * k12) / det
        mb = (-a0[4] * k11 + a0[3] * k21) / det
        acc = tuple(a0[i] + ma * (a1[i] - a0[i]) + mb * (a2[i] - a0[i]) for i in range(3)) + (0.0 * ma, 0.0 * mb)
        return acc, ma, mb
    if hold_a:
        a1 = accelerations(K, state, F, base_a + 1.0, base_b, fy_ext, mz, rdc, grav)
        ma = -a0[3] / (a1[3] - a0[3])
        acc = tuple(a0[i] + ma * (a1[i] - a0[i]) for i in range(5))
        return acc[:3] + (0.0 * ma, acc[4]), ma, M_B
    a2 = accelerations(K, state, F, base_a, base_b + 1.0, fy_ext, mz, rdc, grav)
    mb = -a0[4] / (a2[4] - a0[4])
    acc = tuple(a0[i] + mb * (a2[i] - a0[i]) for i in range(5))
    return acc[:4] + (0.0 * mb,), M_A, mb
