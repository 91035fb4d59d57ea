"""The adaptive scheme: error-controlled integration with consistent loads and stick-slip pin friction.

See ``docs/simulator.md`` for what differs from the WCHAIR scheme.
"""

from __future__ import annotations

import math

import numpy as np

from ..chair import Chair
from ..models.full_width import tire_resultant, tire_yaw_moment
from ..statics import normal_loads
from .options import (
    ADAPTIVE_METHOD,
    LOAD_LIMIT_N,
    SLIP_LIMIT_DEG,
    WARNING_LIMIT,
    Options,
    impulse_on,
    initial_velocities,
)
from .physics import Physics, held_accelerations, kinematics, ops, slip_angles, tire_forces
from .results import NCOLS, ChairState, SimulationResult, new_warnings, note_warning

__all__ = ["AdaptiveModel", "adaptive_single", "FREE_POS", "FREE_NEG", "STUCK", "LOCKED"]

MAX_SWITCHES = 20000
DEADBAND = 1e-10  # rad/s: a slipping caster "reverses" once its rate passes zero by this much
FREE_POS, FREE_NEG, STUCK, LOCKED = 1, -1, 0, 2


class AdaptiveModel:
    """Right-hand side, stick-slip bookkeeping and sample evaluation of one run."""

    def __init__(self, chair: Chair, speed: float, opts: Options):
        self.K = Physics([chair], opts, vector=False)
        self.opts = opts
        self.chair = chair
        self.speed = speed
        self.guess = (0.0, 0.0)
        self._cache_key = None
        self._cache_val = None
        self.nfev = 0

    # loads consistent with forces: N = loads(sum F(N))
    def _consistent(self, t, imp, vel, slips, ce, se, cb, sb, guess):
        """Fixed-point iteration of the load-transfer loop (a strong contraction).

        Stops when the total tire force changes by less than 1e-9 of its size
        between iterations; starts from the previous evaluation's solution.
        """
        K = self.K
        p = K.p
        sfx, sfy = guess
        vector = not isinstance(ce, float)
        for _ in range(100):
            N = normal_loads(p, sfx, sfy, ce, se, cb, sb)
            F = tire_forces(K, imp, vel, slips, *N)
            nfx, nfy = tire_resultant(F, ce, se, cb, sb)
            if vector:
                err = float(np.max(np.abs(nfx - sfx) + np.abs(nfy - sfy), initial=0.0))
                scale = 1.0 + float(np.max(np.abs(nfx) + np.abs(nfy), initial=0.0))
            else:
                err = abs(nfx - sfx) + abs(nfy - sfy)
                scale = 1.0 + abs(nfx) + abs(nfy)
            sfx, sfy = nfx, nfy
            if err <= 1e-9 * scale:
                return N, F, (sfx, sfy)
        raise RuntimeError(f"normal loads and tire forces did not converge (t = {t!r} s)")  # pragma: no cover

    def evaluate(self, t, y, modes, imp):
        """Derivatives and auxiliary quantities at ``(t, y)`` (floats or arrays of samples)."""
        K = self.K
        xp = ops(eta := y[6])
        X, Y, psi, u, v, r, eta, ed, beta, bd = y
        ma_mode, mb_mode = modes
        if ma_mode in (STUCK, LOCKED):
            ed = 0.0 * ed
        if mb_mode in (STUCK, LOCKED):
            bd = 0.0 * bd
        ce, se, cb, sb = xp.cos(eta), xp.sin(eta), xp.cos(beta), xp.sin(beta)
        vel = kinematics(K, u, v, r, ce, se, cb, sb, ed, bd)
        slips = slip_angles(K, vel)
        vector = not isinstance(ce, float)
        guess = (0.0, 0.0) if vector else self.guess
        N, F, sums = self._consistent(t, imp, vel, slips, ce, se, cb, sb, guess)
        if not vector:
            self.guess = sums
        opts = self.opts
        fy_ext = opts.impulse_force if (opts.impulse_force != 0.0 and imp) else 0.0
        yaw_fn = opts.yaw_moment
        if yaw_fn is None:
            mz = 0.0
        elif not vector:
            mz = float(yaw_fn(t, ChairState(X, Y, psi, u, v, r, eta, ed, beta, bd, 0)))
        else:  # samples of a single run: the input sees floats, one call per sample
            cols = np.broadcast_arrays(t, X, Y, psi, u, v, r, eta, ed, beta, bd)
            mz = np.array([float(yaw_fn(float(row[0]), ChairState(*(float(x) for x in row[1:]), 0)))
                           for row in zip(*cols, strict=False)])
        MA = -K.maf * ma_mode if ma_mode in (FREE_POS, FREE_NEG) else 0.0
        MB = -K.mbf * mb_mode if mb_mode in (FREE_POS, FREE_NEG) else 0.0
        hold_a = ma_mode in (STUCK, LOCKED)
        hold_b = mb_mode in (STUCK, LOCKED)
        state = (u, v, r, ce, se, cb, sb, ed, bd)
        acc, MA, MB = held_accelerations(K, state, F, MA, MB, fy_ext, mz, hold_a, hold_b)
        ud, vd, rd, edd, bdd = acc
        cpsi, spsi = xp.cos(psi), xp.sin(psi)
        dy = (u * cpsi - v * spsi, u * spsi + v * cpsi, r, ud, vd, rd, ed, edd, bd, bdd)
        return dy, dict(N=N, F=F, slips=slips, MA=MA, MB=MB, mz=mz, ce=ce, se=se, cb=cb, sb=sb)

    def rhs(self, modes, imp):
        def f(t, y):
            key = (t, y.tobytes())
            if key == self._cache_key:
                return self._cache_val[0]
            self.nfev += 1
            dy, aux = self.evaluate(t, [float(a) for a in y], modes, imp)
            out = np.array(dy)
            self._cache_key, self._cache_val = key, (out, aux)
            return out
        return f

    def aux(self, t, y, modes, imp):
        key = (t, np.asarray(y).tobytes())
        if key == self._cache_key:
            return self._cache_val[1]
        self.nfev += 1
        dy, aux = self.evaluate(t, [float(a) for a in y], modes, imp)
        self._cache_key, self._cache_val = key, (np.array(dy), aux)
        return aux

    def holding(self, t, y, modes, side, imp):
        """Pin moment needed to hold caster ``side`` (0 = A, 1 = B) at rest."""
        m = list(modes)
        m[side] = STUCK
        y = np.array(y, dtype=float)
        y[7 if side == 0 else 9] = 0.0
        aux = self.aux(t, y, tuple(m), imp)
        return aux["MA"] if side == 0 else aux["MB"]

    def limit(self, side):
        return self.K.maf if side == 0 else self.K.mbf

def adaptive_single(chair: Chair, speed: float, opts: Options) -> SimulationResult:
    """One run of the adaptive scheme (see ``docs/simulator.md``)."""
    from scipy.integrate import solve_ivp  # heavy (imports scipy.optimize): only when the adaptive scheme runs

    model = AdaptiveModel(chair, speed, opts)
    u0, v0 = initial_velocities(opts, speed)
    y = np.array([0.0, 0.0, 0.0, u0, v0, 0.0, opts.eta0, 0.0, opts.beta0, 0.0])
    T = opts.duration
    impulse = opts.impulse_force != 0.0 or opts.tire_impulse != 0.0
    breaks = [T]
    if impulse and 0.0 < opts.impulse_duration < T:
        breaks.insert(0, opts.impulse_duration)
    t = 0.0
    imp = impulse and opts.impulse_duration > 0.0   # a zero-length force has no effect on an ODE

    def settle(t, y, modes):
        """Stuck/free decision for resting casters (t = 0, after a breakpoint)."""
        modes = list(modes)
        for side in (0, 1):
            if modes[side] == STUCK:
                h = model.holding(t, y, modes, side, imp)
                if abs(h) > model.limit(side):
                    modes[side] = FREE_NEG if h > 0 else FREE_POS
        return tuple(modes)

    if opts.casters == "locked":
        modes = (LOCKED, LOCKED)
    else:
        modes = settle(t, y, (STUCK, STUCK))
    segments = []
    switches = 0
    while t < T:
        t_end = next(b for b in breaks if b > t)
        events = []
        kinds = []
        for side in (0, 1):
            mode = modes[side]
            ri = 7 if side == 0 else 9
            if mode in (FREE_POS, FREE_NEG):
                s = float(mode)

                def ev(tt, yy, ri=ri, s=s):
                    return s * yy[ri] + DEADBAND
                ev.terminal, ev.direction = True, -1
                events.append(ev)
                kinds.append(("rest", side))
            elif mode == STUCK:
                lim = model.limit(side)

                def ev(tt, yy, side=side, lim=lim, m=modes, i=imp):
                    aux = model.aux(tt, yy, m, i)
                    return abs(aux["MA"] if side == 0 else aux["MB"]) - lim
                ev.terminal, ev.direction = True, 1
                events.append(ev)
                kinds.append(("break", side))
        sol = solve_ivp(model.rhs(modes, imp), (t, t_end), y, method=ADAPTIVE_METHOD, rtol=opts.rtol,
                        atol=opts.atol, events=events or None, dense_output=True)
        if sol.status < 0:
            raise RuntimeError(f"adaptive integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
        segments.append((float(sol.t[0]), float(sol.t[-1]), sol.sol, modes, imp))
        t = float(sol.t[-1])
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            switches += 1
            if switches > MAX_SWITCHES:
                raise RuntimeError(f"more than {MAX_SWITCHES} stick-slip switches by t = {t:.6g} s "
                                   "(chattering); loosen rtol/atol or use scheme='wchair'")
            new = list(modes)
            for (kind, side), te in zip(kinds, sol.t_events, strict=False):
                if len(te) == 0:
                    continue
                ri = 7 if side == 0 else 9
                if kind == "rest":
                    y[ri] = 0.0
                    h = model.holding(t, y, tuple(new), side, imp)
                    if abs(h) <= model.limit(side):
                        new[side] = STUCK
                    else:
                        new[side] = FREE_NEG if h > 0 else FREE_POS
                else:
                    h = model.holding(t, y, tuple(new), side, imp)
                    new[side] = FREE_NEG if h > 0 else FREE_POS
            modes = tuple(new)
        else:
            if t < T and impulse and not impulse_on(opts, t + 1e-12):
                imp = False
            if t < T and opts.casters != "locked":
                modes = settle(t, y, modes)

    # samples
    step = opts.sample
    ns = int(math.floor(T / step * (1 + 1e-12) + 1e-9)) + 1
    ts = step * np.arange(ns)
    ts[-1] = min(ts[-1], T)
    rec = np.empty((ns, NCOLS))
    K = model.K
    for i, (a, b, dense, modes, imp_seg) in enumerate(segments):
        last = i == len(segments) - 1
        sel = (ts >= a) & ((ts < b) | (last & (ts <= b)))
        if not sel.any():
            continue
        tt = ts[sel]
        yy = dense(tt)
        if modes[0] in (STUCK, LOCKED):
            yy[7] = 0.0
        if modes[1] in (STUCK, LOCKED):
            yy[9] = 0.0
        dy, aux = model.evaluate(tt, list(yy), modes, imp_seg)
        F = aux["F"]
        block = (tt, yy[0], yy[1], yy[2], yy[5], yy[3], yy[4], yy[6], yy[7], yy[8], yy[9], *F, *aux["N"],
                 *aux["slips"], tire_yaw_moment(K.p, F, aux["ce"], aux["se"], aux["cb"], aux["sb"]),
                 aux["mz"], dy[5], aux["MA"], aux["MB"])
        for j, c in enumerate(block):
            rec[sel, j] = c
    warn = new_warnings()
    stopped, stop_time = False, None
    slip_abs = np.max(np.abs(rec[:, 23:27]), axis=1)
    nmax = np.max(rec[:, 19:23], axis=1)
    nmin = np.min(rec[:, 19:23], axis=1)
    end = ns
    counts = {"slip": 0, "load": 0}
    for i in range(ns):
        if nmax[i] > LOAD_LIMIT_N:
            note_warning(warn, "load", ts[i], nmax[i])
            counts["load"] += 1
        if nmin[i] < 0:
            note_warning(warn, "lift_off", ts[i], nmin[i])
        if slip_abs[i] > SLIP_LIMIT_DEG:
            note_warning(warn, "slip", ts[i], slip_abs[i])
            counts["slip"] += 1
        if opts.stop_on_warnings and max(counts.values()) > WARNING_LIMIT:
            stopped, stop_time, end = True, float(ts[i]), i
            break
    settings = opts.settings()
    settings.update(switches=switches, nfev=model.nfev)
    return SimulationResult._from_records(rec[:end], warnings=warn, stopped=stopped, stop_time=stop_time,
                                          chair=chair, speed=speed, settings=settings)
