"""The adaptive scheme: error-controlled integration with consistent loads and stick-slip pin friction.

See ``docs/simulator.md`` for what differs from the WCHAIR scheme.
"""

from __future__ import annotations

import math

import numpy as np

from stability.chair import Chair
from stability.models.forces import pin_holds
from stability.simulate.engine import _raise_refused
from stability.simulate.first_use import first_use, load_kernel
from stability.simulate.options import (
    ADAPTIVE_METHOD,
    LOAD_LIMIT_N,
    SLIP_LIMIT_DEG,
    WARNING_LIMIT,
    WHEEL_LABELS,
    WHEELS,
    Options,
    impulse_on,
    initial_velocities,
)
from stability.simulate.packing import Packed, policy_code, slope_slots
from stability.simulate.results import NCOLS, ChairState, SimulationResult, warning_table

__all__ = ["AdaptiveModel", "adaptive_single", "NoLoadSolution", "FREE_POS", "FREE_NEG", "STUCK", "LOCKED"]

MAX_SWITCHES = 20000
#: Right-hand-side evaluations allowed per simulated second (at least one second's worth): a run that needs more
#: has stalled (LSODA's step collapsing at a kink of the right-hand side) and ends with an error instead of
#: filling the memory with dense output.  Ordinary runs take about 250 per second, stiff slow ones a few thousand.
MAX_NFEV_PER_S = 100_000
#: Re-integrations of the segment in which the loads lost their solution, each ending before the last failure.
STOP_TRIES = 8
#: The first re-integration ends this fraction of the segment's span before the failure (x4 each further try).
STOP_GAP = 1e-3
DEADBAND = 1e-10  # rad/s: a slipping caster "reverses" once its rate passes zero by this much
FREE_POS, FREE_NEG, STUCK, LOCKED = 1, -1, 0, 2


class NoLoadSolution(RuntimeError):
    """The fixed-point iteration of the normal loads and tire forces did not converge at ``t``.

    Seen late in a spin-out: a wheel lifts off and the load transfer swings
    it between lifted (negative load, no tire force) and loaded (period 2),
    so no consistent loads are found.  :func:`adaptive_single` ends the run
    at the last time it could integrate instead of raising.

    Attributes
    ----------
    t : float
        The (first) time of the failing evaluation, s.
    """

    def __init__(self, t):
        self.t = float(np.min(t))
        super().__init__(f"normal loads and tire forces did not converge (t = {t!r} s)")


class AdaptiveModel:
    """One run's right-hand side compiled (:mod:`.adaptive_kernel`), its stick-slip bookkeeping and its samples.

    A Python ``yaw_moment`` input is called at every evaluation with the
    state there (floats) and its value passed to the compiled right-hand side.
    """

    def __init__(self, chair: Chair, speed: float, opts: Options):
        with first_use("adaptive_load"):
            from stability.simulate import adaptive_kernel  # numba and the compiled code load only when the scheme runs

        self.k = adaptive_kernel
        self.chair, self.opts = chair, opts
        pk = Packed([chair], np.array([speed]), opts, None)
        self.head = (0 if opts.model == "thesis" else 1, float(opts.tire_impulse), policy_code(opts))
        self.arrays = (pk.P[0], pk.S[0], pk.TK[0], pk.TS[0], pk.TL[0], pk.LIM[0], pk.RK[0], pk.RC[0], pk.RS[0],
                       pk.CAM[0], np.array(slope_slots(opts)))
        self.guess = np.zeros(2)
        self._cache: tuple = (None, None)
        self.nfev = 0
        self.max_nfev = int(MAX_NFEV_PER_S * max(opts.duration, 1.0))

    def hold_drive(self, left: float, right: float) -> None:
        """Constant drive forces on the left and right main wheels, N (the linearisation about a slope's
        equilibrium; simulations have none)."""
        self.arrays[1][self.k.DRIVE_D], self.arrays[1][self.k.DRIVE_E] = left, right

    def yaw_moment(self, t: float, y: np.ndarray) -> float:
        """The yaw-moment input at ``(t, y)``, N m (0 without one)."""
        if self.opts.yaw_moment is None:
            return 0.0
        return float(self.opts.yaw_moment(float(t), ChairState._make([*(float(x) for x in y), 0])))

    def _check(self, code: int, aux: np.ndarray, t) -> None:
        if code == 3:
            raise NoLoadSolution(t)
        if code:
            _raise_refused([self.chair], self.opts, np.array([[0.0, 0.0, *aux[20:24]]]))

    def point(self, t: float, y: np.ndarray, modes, imp: bool, mz: float) -> tuple[np.ndarray, tuple[float, float]]:
        """``(dy, (M_A, M_B))`` at ``(t, y)``: the derivatives and the pin moments, N m (the yaw moment ``mz``)."""
        dy, aux = np.empty(10), np.zeros(self.k.NAUX)
        args = (float(t), y, int(modes[0]), int(modes[1]), bool(imp), float(mz), *self.head, *self.arrays, self.guess,
                dy, aux)
        load_kernel(self.k.evaluate, args, "adaptive")
        code = self.k.evaluate(*args)
        self._check(code, aux, t)
        return dy, (float(aux[16]), float(aux[17]))

    def _point(self, t, y, modes, imp):
        """:meth:`point` with the input's yaw moment, counted and cached for the event functions."""
        y = np.ascontiguousarray(y, dtype=float)
        key = (t, y.tobytes())
        if key == self._cache[0]:
            return self._cache[1]
        self.nfev += 1
        if self.nfev > self.max_nfev:
            raise RuntimeError(f"adaptive integration stalled at t = {t:.9g} s: more than {self.max_nfev} "
                               "right-hand-side evaluations (the step collapsed; try a looser rtol or the wchair "
                               "scheme)")
        val = self.point(t, y, modes, imp, self.yaw_moment(t, y))
        self._cache = (key, val)
        return val

    def rhs(self, modes, imp):
        def f(t, y):
            return self._point(t, y, modes, imp)[0]
        return f

    def pin_moment(self, t, y, modes, side, imp) -> float:
        """Pin moment of caster ``side`` (0 = A, 1 = B) at ``(t, y)``, N m."""
        return self._point(t, y, modes, imp)[1][side]

    def holding(self, t, y, modes, side, imp) -> float:
        """Pin moment needed to hold caster ``side`` (0 = A, 1 = B) at rest, N m."""
        m = list(modes)
        m[side] = STUCK
        y = np.array(y, dtype=float)
        y[7 if side == 0 else 9] = 0.0
        return self.pin_moment(t, y, tuple(m), side, imp)

    def limit(self, side):
        """The friction limit of caster ``side``'s pin, N m."""
        return self.chair.pin_friction_left if side == 0 else self.chair.pin_friction_right

    def samples(self, tt: np.ndarray, yy: np.ndarray, modes, imp: bool, mzs: np.ndarray) -> np.ndarray:
        """Columns ``COLUMNS[1:]`` at the samples, shape (31, m); ``mzs`` the yaw-moment input at each, N m."""
        out, dy, aux = np.empty((NCOLS - 1, tt.size)), np.empty(10), np.zeros(self.k.NAUX)
        args = (np.ascontiguousarray(tt, dtype=float), np.ascontiguousarray(yy, dtype=float),
                np.ascontiguousarray(mzs, dtype=float), int(modes[0]), int(modes[1]), bool(imp), *self.head,
                *self.arrays, out, np.zeros(2), dy, aux)
        load_kernel(self.k.samples, args, "adaptive_samples")
        code = self.k.samples(*args)
        self._check(code, aux, tt)
        return out


def _events(model: AdaptiveModel, modes: tuple, imp: bool) -> tuple[list, list]:
    """solve_ivp events of the current pin modes: a slipping caster comes to rest, a stuck one breaks away."""
    events, kinds = [], []
    for side in (0, 1):
        mode = modes[side]
        ri = 7 if side == 0 else 9
        if mode in (FREE_POS, FREE_NEG):
            def ev_rest(tt, yy, ri=ri, s=float(mode)):
                return s * yy[ri] + DEADBAND
            ev_rest.terminal, ev_rest.direction = True, -1  # type: ignore[attr-defined]
            events.append(ev_rest)
            kinds.append(("rest", side))
        elif mode == STUCK:
            lim = model.limit(side)

            def ev_break(tt, yy, side=side, lim=lim, m=modes, i=imp):
                return abs(model.pin_moment(tt, yy, m, side, i)) - lim
            ev_break.terminal, ev_break.direction = True, 1  # type: ignore[attr-defined]
            events.append(ev_break)
            kinds.append(("break", side))
    return events, kinds


def _held_or_slipping(model: AdaptiveModel, t: float, y: np.ndarray, modes: list, side: int, imp: bool,
                      may_stick: bool = True) -> int:
    """Caster ``side`` at rest: stuck while its pin holds it (``may_stick``), else slipping against the holding
    moment."""
    h = model.holding(t, y, tuple(modes), side, imp)
    return STUCK if may_stick and pin_holds(h, model.limit(side)) else (FREE_NEG if h > 0 else FREE_POS)


def _switch(model: AdaptiveModel, t: float, y: np.ndarray, modes: tuple, kinds: list, t_events: list,
            imp: bool) -> tuple:
    """New pin modes after a stick-slip event (``y`` is updated in place for a caster that came to rest)."""
    new = list(modes)
    for (kind, side), te in zip(kinds, t_events, strict=False):
        if len(te) == 0:
            continue
        if kind == "rest":
            y[7 if side == 0 else 9] = 0.0
        new[side] = _held_or_slipping(model, t, y, new, side, imp, may_stick=kind == "rest")
    return tuple(new)


def _settle(model: AdaptiveModel, t: float, y: np.ndarray, modes: tuple, imp: bool) -> tuple:
    """Stuck/free decision for resting casters (t = 0, after a breakpoint)."""
    new = list(modes)
    for side in (0, 1):
        if new[side] == STUCK:
            new[side] = _held_or_slipping(model, t, y, new, side, imp)
    return tuple(new)


def _solve(model: AdaptiveModel, t: float, t_end: float, y: np.ndarray, modes: tuple, imp: bool, opts: Options):
    """One solve_ivp call between stick-slip events: ``(sol, kinds)``; raises on an integrator failure."""
    from scipy.integrate import solve_ivp  # heavy (imports scipy.optimize): only when the adaptive scheme runs

    events, kinds = _events(model, modes, imp)
    sol = solve_ivp(model.rhs(modes, imp), (t, t_end), y, method=ADAPTIVE_METHOD, rtol=opts.rtol,
                    atol=opts.atol, events=events or None, dense_output=True)
    if sol.status < 0:
        raise RuntimeError(f"adaptive integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
    return sol, kinds


def _up_to(model: AdaptiveModel, t: float, t_fail: float, y: np.ndarray, modes: tuple, imp: bool, opts: Options):
    """The segment from ``t`` re-integrated to just before ``t_fail`` (no load solution there).

    Each try ends ``STOP_GAP`` of the span before the latest failure (the gap x4 per try,
    :data:`STOP_TRIES` tries).  Returns ``((sol, kinds) or None, t_fail)``: None when no
    try gets past ``t``; ``t_fail`` the latest failure, s.
    """
    gap = STOP_GAP * (t_fail - t)
    for _ in range(STOP_TRIES):
        end = t_fail - gap
        if not end > t:
            break
        try:
            return _solve(model, t, end, y, modes, imp, opts), t_fail
        except NoLoadSolution as e:
            t_fail = min(e.t, end)
            gap *= 4.0
    return None, t_fail


def _integrate(model: AdaptiveModel, speed: float, opts: Options) -> tuple[list, int, float | None]:
    """Integrate segment by segment between breakpoints and stick-slip events.

    Returns ``(segments, switches, t_fail)``: ``t_fail`` is the time at which the
    normal loads lost their solution (the run ends at the last segment's end), else None.
    """
    u0, v0 = initial_velocities(opts, speed)
    y = np.array([0.0, 0.0, 0.0, u0, v0, 0.0, opts.eta0, 0.0, opts.beta0, 0.0])
    T = opts.duration
    impulse = opts.impulse_force != 0.0 or opts.tire_impulse != 0.0
    breaks = [T]
    if impulse and 0.0 < opts.impulse_duration < T:
        breaks.insert(0, opts.impulse_duration)
    t = 0.0
    imp = impulse and opts.impulse_duration > 0.0   # a zero-length force has no effect on an ODE
    modes: tuple = (LOCKED, LOCKED) if opts.casters == "locked" else _settle(model, t, y, (STUCK, STUCK), imp)
    segments: list[tuple] = []
    switches = 0
    while t < T:
        t_end = next(b for b in breaks if b > t)
        t_fail = None
        try:
            sol, kinds = _solve(model, t, t_end, y, modes, imp, opts)
        except NoLoadSolution as e:   # a wheel lifts off: keep what can be integrated up to there, then stop
            part, t_fail = _up_to(model, t, e.t, y, modes, imp, opts)
            if part is None:
                return segments, switches, t_fail
            sol, kinds = part
        segments.append((float(sol.t[0]), float(sol.t[-1]), sol.sol, modes, imp))
        t = float(sol.t[-1])
        y = sol.y[:, -1].copy()
        if sol.status == 1:
            switches += 1
            if switches > MAX_SWITCHES:
                raise RuntimeError(f"more than {MAX_SWITCHES} stick-slip switches by t = {t:.6g} s "
                                   "(chattering); loosen rtol/atol or use scheme='wchair'")
            try:
                modes = _switch(model, t, y, modes, kinds, sol.t_events, imp)
            except NoLoadSolution as e:   # no holding moment: the run ends at the event
                return segments, switches, e.t
        elif t_fail is not None:      # the re-integration reached its end, just before the failure
            return segments, switches, t_fail
        else:
            if t < T and impulse and not impulse_on(opts, t + 1e-12):
                imp = False
            if t < T and opts.casters != "locked":
                try:
                    modes = _settle(model, t, y, modes, imp)
                except NoLoadSolution as e:
                    return segments, switches, e.t
    return segments, switches, None


def _block(model: AdaptiveModel, tt: np.ndarray, yy: np.ndarray, modes: tuple, imp: bool) -> np.ndarray:
    """Every column of :data:`COLUMNS` at the samples ``tt`` of one segment (states ``yy``), shape (NCOLS, m)."""
    out = np.empty((NCOLS, tt.size))
    out[0] = tt
    mzs = np.array([model.yaw_moment(t, yy[:, j]) for j, t in enumerate(tt)])
    out[1:] = model.samples(tt, yy, modes, imp, mzs)
    return out


def _sample(model: AdaptiveModel, segments: list, opts: Options,
            t_stop: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``(ts, rec)``: every column of :data:`COLUMNS` at the output samples, from the dense output.

    ``t_stop``: the run ended there (s; the last segment's end), a last sample is added at it;
    samples of the last segment whose loads have no solution (each sample's iteration starts
    from zero forces) end the record.
    """
    T, step = opts.duration, opts.sample
    assert step is not None          # make_options sets it for the adaptive scheme
    ns = int(math.floor(T / step * (1 + 1e-12) + 1e-9)) + 1
    ts = step * np.arange(ns)
    ts[-1] = min(ts[-1], T)
    if t_stop is not None:
        ts = ts[ts < t_stop * (1 - 1e-12)]
        ts = np.append(ts, t_stop)
    rec = np.empty((ts.size, NCOLS))
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
        if not (last and t_stop is not None):
            rec[sel] = _block(model, tt, yy, modes, imp_seg).T
            continue
        rows = np.flatnonzero(sel)
        for j, row in enumerate(rows):      # sample by sample: the first without a load solution ends the record
            try:
                rec[row] = _block(model, tt[j:j + 1], yy[:, j:j + 1], modes, imp_seg)[:, 0]
            except NoLoadSolution:
                if row == 0:
                    raise
                return ts[:row], rec[:row]
    return ts, rec


def _sample_warnings(ts: np.ndarray, rec: np.ndarray, opts: Options) -> tuple[dict, bool, float | None, int]:
    """Range warnings counted per sample: ``(warnings, stopped, stop_time, samples kept)``.

    A run that stops at the eleventh slip or load warning keeps the samples before it; its warnings count it.
    """
    values = (np.max(np.abs(rec[:, 23:27]), axis=1), np.max(rec[:, 19:23], axis=1), np.min(rec[:, 19:23], axis=1))
    hits = (values[0] > SLIP_LIMIT_DEG, values[1] > LOAD_LIMIT_N, values[2] < 0)
    over = np.flatnonzero(np.maximum(np.cumsum(hits[0]), np.cumsum(hits[1])) > WARNING_LIMIT)
    end = int(over[0]) if opts.stop_on_warnings and over.size else len(ts)
    warn = np.zeros((3, 3))
    for j, (hit, v) in enumerate(zip(hits, values, strict=True)):
        idx = np.flatnonzero(hit[:end + 1])
        if idx.size:
            warn[j] = idx.size, ts[idx[0]], v[idx[np.argmax(np.abs(v[idx]))]]
    return warning_table(warn), end < len(ts), float(ts[end]) if end < len(ts) else None, end


def adaptive_single(chair: Chair, speed: float, opts: Options) -> SimulationResult:
    """One run of the adaptive scheme (see ``docs/simulator.md``).

    The right-hand side runs compiled (:mod:`.adaptive_kernel`); a Python
    ``yaw_moment`` input is called at every evaluation.

    Parameters
    ----------
    chair : Chair
        The chair.
    speed : float
        Initial forward speed, m/s (> 0; checked by the caller).
    opts : Options
        Checked options with ``scheme="adaptive"`` (``rtol``, ``atol``,
        ``sample`` in s).

    Returns
    -------
    SimulationResult
        Rows every ``opts.sample`` s; ``settings`` also holds the number of
        stick-slip switches (``switches``) and right-hand-side evaluations
        (``nfev``).  When the normal loads lose their solution (a wheel
        lifts off) the run ends at the last time it could integrate (a last
        sample there): ``stopped_by_warnings``, ``stop_time`` and
        ``stop_reason`` (one line) say so.

    Raises
    ------
    RuntimeError
        The integrator failed or stalled (more than :data:`MAX_NFEV_PER_S`
        evaluations per simulated second), or more than ``MAX_SWITCHES`` stick-slip
        switches occurred (chattering).
    NoLoadSolution
        The loads have no solution in the first segment of the run.
    """
    model = AdaptiveModel(chair, speed, opts)
    segments, switches, t_fail = _integrate(model, speed, opts)
    if t_fail is not None and not segments:
        raise NoLoadSolution(t_fail)
    ts, rec = _sample(model, segments, opts, None if t_fail is None else segments[-1][1])
    warn, stopped, stop_time, end = _sample_warnings(ts, rec, opts)
    reason = None
    if t_fail is not None and not stopped:
        stopped, stop_time, reason = True, float(ts[-1]), _stop_reason(t_fail, rec[-1])
    settings = opts.settings()
    settings.update(switches=switches, nfev=model.nfev, engine="compiled")
    return SimulationResult._from_records(rec[:end], warnings=warn, stopped=stopped, stop_time=stop_time,
                                          chair=chair, speed=speed, settings=settings, stop_reason=reason)


def _stop_reason(t_fail: float, row: np.ndarray) -> str:
    """One line: why a run ended early (no load solution at ``t_fail``, s), with the state of its last sample."""
    loads = row[19:23]
    w = int(np.argmin(loads))
    side = WHEEL_LABELS[WHEELS[w]]
    what = "lifts off" if loads[w] < 0 else "is about to lift off"
    return (f"normal loads and tire forces have no converging solution at t = {t_fail:.4f} s (the {side} {what}: "
            f"load {loads[w]:.0f} N, yaw rate {row[4]:+.2f} rad/s at {row[0]:.4f} s, the last time integrated)")
