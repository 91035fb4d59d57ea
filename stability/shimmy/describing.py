"""Coulomb pin friction against shimmy: describing function and stick-slip simulation.

A Coulomb torque ``M_f sign(psi_dot)`` acting on ``psi = A sin(w t)`` has the
first harmonic of viscous damping ``c_eq = 4 M_f / (pi A w)`` (Gelb and
Vander Velde 1968, ch. 2; Kantrowitz 1940 for castering wheels).  With
friction, a linearly unstable wheel has a (unstable) limit cycle of
amplitude ``A* = 4 M_f / (pi w (c_crit - c))``: smaller disturbances die out,
larger ones grow into shimmy.  :func:`simulate` integrates the linear wheel
with exact stick-slip friction (event-located switching) to confirm it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from stability.shimmy.towed_wheel import TowedWheel

__all__ = ["equivalent_damping", "critical_damping", "FrictionEstimate", "suppressing_friction",
           "Simulation", "simulate", "simulated_threshold"]


def equivalent_damping(friction: float, amplitude: float, frequency: float) -> float:
    """Viscous pin damping equivalent to Coulomb pin friction (describing function).

    At caster-angle amplitude A and frequency w, the first harmonic of
    ``M_f sign(psi_dot)`` dissipates as much energy per cycle as a viscous
    damper ``c_eq = 4 M_f / (pi A w)``.

    Parameters
    ----------
    friction : float
        Coulomb pin friction moment M_f, N m (>= 0).
    amplitude : float
        Caster-angle amplitude A, rad (> 0).
    frequency : float
        Shimmy angular frequency w, rad/s (> 0).

    Returns
    -------
    float
        Equivalent viscous damping c_eq, N m s/rad.
    """
    return 4.0 * friction / (math.pi * amplitude * frequency)


def critical_damping(wheel: TowedWheel, speed: float, c_max: float = 100.0, n_grid: int = 200
                     ) -> tuple[float, float]:
    """Pin damping above which the wheel is stable at ``speed``, and the shimmy frequency there.

    ``(0, nan)`` if the wheel is stable without pin damping; ``(inf, nan)``
    if no damping up to ``c_max`` stabilises it (e.g. a real divergence).
    Only ``pin_damping`` is swept; the wheel's own ``pin_damping`` is ignored.

    Parameters
    ----------
    wheel : TowedWheel
        The towed wheel (caster).
    speed : float
        Forward speed, m/s (> 0).
    c_max : float, optional
        Largest pin damping searched, N m s/rad (default 100).
    n_grid : int, optional
        Number of geometrically spaced damping values from 1e-6 to ``c_max``
        (default 200); Hopf crossings between them are refined.

    Returns
    -------
    tuple of (float, float)
        Critical pin damping (N m s/rad) and the frequency of the crossing pair
        there (rad/s).
    """
    w0 = wheel.replace(pin_damping=0.0)
    if w0.routh_hurwitz(speed).stable:
        return 0.0, math.nan
    grid = np.concatenate([[0.0], np.geomspace(1e-6, c_max, n_grid)])
    vals, freqs, dest = w0.hopf_crossings("pin_damping", grid, speed)
    for v, f, d in zip(vals[::-1], freqs[::-1], dest[::-1], strict=True):
        if not d and w0.replace(pin_damping=float(v) * (1 + 1e-6) + 1e-12).routh_hurwitz(speed).stable:
            return float(v), float(f)
    return math.inf, math.nan


@dataclass(frozen=True)
class FrictionEstimate:
    """Describing-function estimate at one speed.

    Attributes
    ----------
    speed : float
        m/s.
    amplitude : float
        Caster-angle amplitude (rad).
    critical_damping : float
        Pin damping that puts the shimmy pair on the imaginary axis (N m s/rad).
    frequency : float
        Shimmy frequency there (rad/s).
    friction : float
        Coulomb pin friction (N m) that suppresses shimmy of ``amplitude``
        and below, ``pi A w (c_crit - c) / 4``; 0 if the wheel is stable with
        its viscous damping alone, inf if no damping stabilises it.
    """

    speed: float
    amplitude: float
    critical_damping: float
    frequency: float
    friction: float


def suppressing_friction(wheel: TowedWheel, speed: float, amplitude: float) -> FrictionEstimate:
    """Coulomb pin friction that suppresses shimmy up to ``amplitude`` at ``speed`` (describing function).

    The friction whose equivalent damping (:func:`equivalent_damping`) makes
    up the gap between the critical damping and the wheel's own viscous pin
    damping: ``M_f = pi A w (c_crit - c) / 4``.

    Parameters
    ----------
    wheel : TowedWheel
        The towed wheel (caster), with its viscous ``pin_damping`` (N m s/rad).
    speed : float
        Forward speed, m/s (> 0).
    amplitude : float
        Caster-angle amplitude A, rad (finite, > 0).

    Returns
    -------
    FrictionEstimate
        Speed (m/s), amplitude (rad), critical damping (N m s/rad), shimmy
        frequency (rad/s) and the friction needed (N m; 0 if already stable,
        ``inf`` if no damping stabilises).

    Raises
    ------
    ValueError
        If ``amplitude`` is not finite and > 0.
    """
    if not (amplitude > 0 and math.isfinite(amplitude)):
        raise ValueError(f"amplitude={amplitude!r} is invalid; valid range: > 0 rad (finite)")
    c_crit, w = critical_damping(wheel, speed)
    extra = c_crit - wheel.pin_damping
    if extra <= 0:
        friction = 0.0
    elif math.isinf(extra):
        friction = math.inf
    else:
        friction = math.pi * amplitude * w * extra / 4.0
    return FrictionEstimate(float(speed), float(amplitude), c_crit, w, friction)


@dataclass(frozen=True)
class Simulation:
    """Time history of the towed wheel with Coulomb pin friction.

    Attributes
    ----------
    t : ndarray
        Times (s).
    x : ndarray, shape (len(t), n)
        States named by ``states`` (SI units, angles in rad).
    states : tuple of str
    stuck : ndarray of bool
        True where the pin is stuck (friction holds the fork).
    """

    t: np.ndarray
    x: np.ndarray
    states: tuple[str, ...]
    stuck: np.ndarray

    @property
    def psi(self) -> np.ndarray:
        return self.x[:, self.states.index("psi")]


def shimmy_mode_state(wheel: TowedWheel, speed: float, amplitude: float) -> np.ndarray:
    """Initial state on the least-damped oscillatory mode with caster angle ``amplitude`` (rad), psi_dot = 0."""
    A, _ = wheel.state_matrix(speed)
    ev, vec = np.linalg.eig(A)
    osc = np.abs(ev.imag) > 1e-9 * np.abs(ev).max()
    if not osc.any():
        raise ValueError(f"the {wheel.case} wheel has no oscillatory mode at speed={speed!r} m/s")
    j = int(np.argmax(np.where(osc, ev.real, -np.inf)))
    v = vec[:, j] / vec[wheel.states.index("psi"), j]
    return amplitude * v.real


def simulate(wheel: TowedWheel, speed: float, x0: np.ndarray, t_end: float, *,
             rtol: float = 1e-9, atol: float = 1e-12, max_events: int = 100_000) -> Simulation:
    """Integrate ``x_dot = A x + B T`` with ``T = -M_f sign(psi_dot)`` and exact stick-slip.

    Slipping: ``T = -M_f s`` with ``s = sign(psi_dot)``, until ``psi_dot``
    reaches zero (event).  There, if the torque that keeps ``psi_dot = 0``,
    ``T_s = -(A x)_i / B_i``, satisfies ``|T_s| <= M_f`` the pin sticks
    (``T = T_s``) until ``|T_s| = M_f`` (event); otherwise it slips on in
    the direction of ``(A x)_i``.  Each segment is linear; solve_ivp (DOP853)
    integrates it with located events.

    Parameters
    ----------
    wheel : TowedWheel
        The towed wheel; its ``pin_friction`` is M_f (N m). Needs a compliant
        pivot or a compliant tire (a ``psi_dot`` state).
    speed : float
        Forward speed, m/s (> 0).
    x0 : numpy.ndarray
        Initial state, ordered as ``wheel.states`` (SI units, angles in rad).
    t_end : float
        End time, s (> 0).
    rtol, atol : float, optional
        solve_ivp tolerances (default 1e-9, 1e-12).
    max_events : int, optional
        Largest number of stick/slip segments integrated (default 100000).

    Returns
    -------
    Simulation
        Times (s), states and where the pin is stuck.

    Raises
    ------
    ValueError
        If the wheel has no ``psi_dot`` state on which pin friction acts.
    """
    A, B = wheel.state_matrix(speed)
    i = wheel.states.index("psi_dot") if "psi_dot" in wheel.states else None
    if i is None or B[i] <= 0:
        raise ValueError(f"pin friction has no effect on a {wheel.case} towed wheel; valid: a compliant "
                         "pivot or a compliant tire")
    Mf = wheel.pin_friction
    x = np.array(x0, dtype=float)

    def hold(xx):  # torque that keeps psi_dot at zero
        return -(A[i] @ xx) / B[i]

    mode = int(np.sign(x[i])) or (int(np.sign(A[i] @ x)) if abs(hold(x)) > Mf else 0)
    ts, xs, stuck = [np.array([0.0])], [x[None, :]], [np.array([mode == 0])]
    t0 = 0.0
    for _ in range(max_events):
        if t0 >= t_end:
            break
        rhs, ev = _segment(A, B, i, Mf, mode)
        sol = solve_ivp(rhs, (t0, t_end), x, method="DOP853", events=ev, rtol=rtol, atol=atol,
                        dense_output=False, max_step=t_end / 50)
        ts.append(sol.t[1:])
        xs.append(sol.y.T[1:])
        stuck.append(np.full(sol.t.size - 1, mode == 0))
        x, t0 = sol.y[:, -1].copy(), float(sol.t[-1])
        if sol.status != 1:
            break
        x[i] = 0.0
        T = hold(x)
        mode = 0 if abs(T) <= Mf * (1 + 1e-12) and mode != 0 else int(np.sign(A[i] @ x)) or 1
    return Simulation(np.concatenate(ts), np.concatenate(xs), wheel.states, np.concatenate(stuck))


def _segment(A: np.ndarray, B: np.ndarray, i: int, Mf: float, mode: int):
    """Right-hand side and terminal event of one stick (mode 0) or slip (mode +-1) segment."""
    def hold(xx):
        return -(A[i] @ xx) / B[i]

    def rhs(_t, xx):
        if mode == 0:
            d = A @ xx + B * hold(xx)
            d[i] = 0.0
            return d
        return A @ xx - B * (Mf * mode)

    def ev(_t, xx):
        return abs(hold(xx)) - Mf if mode == 0 else mode * xx[i]

    ev.direction = 1 if mode == 0 else -1  # type: ignore[attr-defined]
    ev.terminal = True  # type: ignore[attr-defined]
    return rhs, ev


def _grows(wheel: TowedWheel, speed: float, amplitude: float, cycles: float) -> bool:
    _, w = critical_damping(wheel, speed)
    A, _ = wheel.state_matrix(speed)
    freq = w if math.isfinite(w) else float(np.abs(np.linalg.eigvals(A).imag).max())
    t_end = cycles * 2 * math.pi / freq
    sim = simulate(wheel, speed, shimmy_mode_state(wheel, speed, amplitude), t_end)
    last = sim.t > t_end - 2 * math.pi / freq
    return bool(np.abs(sim.psi[last]).max() > amplitude)


def simulated_threshold(wheel: TowedWheel, speed: float, low: float, high: float, *,
                        cycles: float = 12.0, iterations: int = 8) -> tuple[float, float]:
    """Bracket ``(lo, hi)`` of the initial shimmy amplitude above which simulated shimmy grows.

    Bisection (geometric) between ``low`` (must decay) and ``high`` (must
    grow) on the caster-angle peak of the last of ``cycles`` cycles, each run
    started in the shimmy mode with :func:`simulate`.  Checks the describing-
    function estimate of :func:`suppressing_friction`.

    Parameters
    ----------
    wheel : TowedWheel
        The towed wheel with its Coulomb ``pin_friction`` (N m).
    speed : float
        Forward speed, m/s (> 0).
    low, high : float
        Initial caster-angle amplitudes, rad, that bracket the threshold.
    cycles : float, optional
        Simulated shimmy cycles per run (default 12).
    iterations : int, optional
        Bisection steps (default 8).

    Returns
    -------
    tuple of (float, float)
        ``(lo, hi)``, rad: shimmy started at ``lo`` decays, at ``hi`` grows.

    Raises
    ------
    ValueError
        If ``low`` and ``high`` do not bracket the threshold.
    """
    if _grows(wheel, speed, low, cycles) or not _grows(wheel, speed, high, cycles):
        raise ValueError(f"amplitudes low={low!r}, high={high!r} rad do not bracket the threshold")
    for _ in range(iterations):
        mid = math.sqrt(low * high)
        if _grows(wheel, speed, mid, cycles):
            high = mid
        else:
            low = mid
    return low, high
