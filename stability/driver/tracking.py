"""The critical tracking task: measure a user's effective delay ``tau_e`` (Jex, McDonnell & Phatak 1966).

The user keeps a marker centred on an unstable first-order plant whose instability rises until control is lost::

    x' = lambda(t) x + u + d(t),        lose control when |x| > LIMIT

``x`` is the marker's offset in display half-widths (the edge of the track is :data:`LIMIT`), ``u`` the user's
input (half-widths per second; full deflection of the stick, the mouse or a key is :data:`INPUT_LIMIT_1_S`) and
``d`` a small stated disturbance (a sum of sines, random phases per trial, scaled to the trial's start) that
keeps the task alive while the user holds the marker still.  The instability's time constant ``1 / lambda``
falls linearly in time, ``1/lambda(t) = 1/lambda_0 - rate t``, so the task looks the same to a fast and a slow
user scaled to their own delay: ``d(lambda tau)/d(t/tau) = rate (lambda tau)^2``.

The ``lambda`` at loss of control, ``lambda_c``, is about ``1 / tau_e`` (a delayed proportional operator holds
``x' = lambda x - k x(t - tau)`` exactly while ``lambda tau < 1``: Stepan & Kollar 2000,
:mod:`stability.driver.linear`).  It is a little above: control is lost only once the error, already growing,
reaches the edge, while ``lambda`` keeps rising.  The **escape factor** ``E = lambda_c tau`` of that operator is
computed here, not typed: the operator of the delayed-loop model (the most stable gain at each ``lambda``, found
by :func:`stability.driver.linear.best_gains` on the one-state plant through the Pade delay) is run through the
same task, frame by frame, over a population of delays, gain errors and disturbance phases
(:func:`escape_factor`).  A user's delay is then ``tau_e = E / mean(lambda_c)``.

The protocol (:mod:`.protocol`; after ISO/TS 14198:2019, which standardises the task; docs/driver.md):
:data:`PRACTICE_TRIALS` practice trials (the first with a faster rise; not scored) then :data:`SCORED_TRIALS`
scored trials.
A trial is invalid with no input (the input never left its dead band) or an early loss (``lambda_c`` less
than :data:`EARLY_RISE` times the trial's starting ``lambda``: a lapse, not the limit); the result needs
:data:`MIN_VALID` valid scored trials.  Each trial starts at :data:`START_FRACTION` of the limit ``1/tau_e``
estimated from the last valid trial (the first at ``1 / FIRST_TIME_CONSTANT_S``).

The explorer's Tracking tab runs the same plant in the browser (:mod:`stability.app.tracking_tab`), one step
per :data:`FRAME_S`, with the constants of :func:`browser_config`.

References
----------
- Jex HR, McDonnell JD, Phatak AV (1966) A "critical" tracking task for manual control research. IEEE
  Transactions on Human Factors in Electronics HFE-7(4):138-145.
- Stepan G, Kollar L (2000) Balancing with reflex delay. Mathematical and Computer Modelling 31(4-5):199-205.
- ISO/TS 14198:2019 Road vehicles - Ergonomic aspects of transport information and control systems -
  Calibration tasks for methods which assess driver demand due to the use of in-vehicle systems.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from stability.driver.linear import best_gains

__all__ = ["FRAME_S", "LIMIT", "INPUT_LIMIT_1_S", "RAMP_S_PER_S", "PRACTICE_RAMP_S_PER_S", "FIRST_TIME_CONSTANT_S",
           "START_FRACTION", "LAMBDA_MAX_1_S", "DISTURBANCE_FREQUENCY_RATIOS", "DISTURBANCE_AMPLITUDE_RATIO",
           "PRACTICE_TRIALS", "SCORED_TRIALS", "MIN_VALID", "INPUT_DEADBAND", "EARLY_RISE", "CALIBRATION_TAU_S",
           "CALIBRATION_GAIN",
           "CALIBRATION_SEEDS", "ramp_lambda", "disturbance", "plant_step", "operator_gain_table", "operator_gain",
           "simulate_operator", "EscapeFactor", "escape_factor", "browser_config"]

#: One step of the task, s: the browser steps the plant at a fixed 60 Hz whatever the display's rate.
FRAME_S = 1.0 / 60.0
#: Loss of control: the marker's offset beyond this, display half-widths (the track's edge).
LIMIT = 1.0
#: The input at full deflection, half-widths per second: enough that a delayed proportional operator with
#: ``tau >= 0.15 s`` never saturates before it loses control (its gain ``k* <= e^0.6 / tau``, ``|x| <= 1``).
INPUT_LIMIT_1_S = 12.0
#: How fast the instability's time constant ``1 / lambda`` falls in a scored trial, s per s.
RAMP_S_PER_S = 0.02
#: The same in a practice trial (shorter trials; not scored), s per s.
PRACTICE_RAMP_S_PER_S = 0.1
#: ``1 / lambda`` at the start of the first trial, s.
FIRST_TIME_CONSTANT_S = 1.5
#: A trial starts at this fraction of the user's limit ``1/tau_e`` estimated from the last valid trial
#: (``lambda_c`` over the escape factor of that trial's ramp): well below the limit whatever the last ramp.
START_FRACTION = 0.7
#: The instability stops rising here, 1/s (nobody holds it: ``tau`` would be 30 ms).
LAMBDA_MAX_1_S = 50.0
#: Angular frequencies of the disturbance's sines relative to the trial's starting instability ``lambda_0``
#: (rad/s per 1/s): the disturbance is scaled to the trial as the ramp is, so the task is the same for every
#: user in time measured in their own delay (at ``lambda_0 = 1.67 1/s``, a user of 0.3 s: 0.13-0.98 Hz).
DISTURBANCE_FREQUENCY_RATIOS = (0.5, 0.87, 1.4, 2.3, 3.65)
#: Amplitude of each sine relative to ``lambda_0`` (half-widths per second per 1/s): 0.05 half-widths/s at
#: ``lambda_0 = 1.67 1/s``.
DISTURBANCE_AMPLITUDE_RATIO = 0.03
#: Longest simulated trial, s.
MAX_TRIAL_S = 600.0
#: Practice trials (not scored: the first at the fast ramp to find the range, the others as a scored trial
#: runs), then scored trials.
PRACTICE_TRIALS = 2
SCORED_TRIALS = 5
#: Valid scored trials needed for a result.
MIN_VALID = 3
#: The input counts as used once it has moved more than this fraction of its range during the trial.
INPUT_DEADBAND = 0.02
#: A loss before ``lambda`` has risen by this factor from the trial's start is an early loss (invalid).
EARLY_RISE = 1.25
#: The operators the escape factor is computed over: delays (s), gains relative to the most stable one (the
#: model's operator: the best gain; docs/driver.md gives the effect of a mistuned gain), and disturbance phases
#: per (delay, gain).
CALIBRATION_TAU_S = (0.2, 0.3, 0.4, 0.5, 0.6)
CALIBRATION_GAIN = (1.0,)
CALIBRATION_SEEDS = 10


def ramp_lambda(t: np.ndarray | float, lambda0: float, rate: float) -> np.ndarray:
    """The instability at time ``t`` of a trial: ``1/lambda = 1/lambda0 - rate t``, capped at LAMBDA_MAX_1_S.

    Parameters
    ----------
    t : float or ndarray
        Time since the trial's start, s.
    lambda0 : float
        Starting instability, 1/s (> 0).
    rate : float
        Fall of ``1 / lambda``, s per s (>= 0).

    Returns
    -------
    ndarray
        1/s.
    """
    tc = 1.0 / lambda0 - rate * np.asarray(t, dtype=float)
    return np.where(tc > 1.0 / LAMBDA_MAX_1_S, 1.0 / np.maximum(tc, 1.0 / LAMBDA_MAX_1_S), LAMBDA_MAX_1_S)


def disturbance(t: float, phases: np.ndarray, lambda0: float) -> np.ndarray:
    """The disturbance ``d(t) = A lambda_0 sum_i sin(r_i lambda_0 t + phi_i)``, half-widths per second.

    Parameters
    ----------
    t : float
        Time since the trial's start, s.
    phases : ndarray (..., len(DISTURBANCE_FREQUENCY_RATIOS))
        Phase of each sine, rad.
    lambda0 : float
        The trial's starting instability, 1/s.

    Returns
    -------
    ndarray (...)
    """
    w = np.asarray(DISTURBANCE_FREQUENCY_RATIOS) * lambda0
    return DISTURBANCE_AMPLITUDE_RATIO * lambda0 * np.sum(np.sin(w * t + phases), axis=-1)


def plant_step(x: np.ndarray, lam: float, w: np.ndarray, dt: float = FRAME_S) -> np.ndarray:
    """One step of ``x' = lambda x + w`` with ``w`` held over the step (exact zero-order hold).

    Parameters
    ----------
    x : ndarray
        Offset, half-widths.
    lam : float
        Instability, 1/s (> 0).
    w : ndarray
        Input plus disturbance, half-widths/s.
    dt : float
        Step, s.

    Returns
    -------
    ndarray
        The offset one step later, half-widths.
    """
    e = math.exp(lam * dt)
    return e * x + (e - 1.0) / lam * w


@lru_cache(maxsize=4)
def operator_gain_table(points: int = 41) -> tuple[np.ndarray, np.ndarray]:
    """The delayed-loop model's most stable proportional gain for ``x' = lambda x - k x(t - tau)``.

    Computed by :func:`stability.driver.linear.best_gains` (Pade delay) on the one-state plant at ``tau = 1 s``;
    the loop depends on ``lambda tau`` and ``k tau`` only, so one table serves every delay.

    Parameters
    ----------
    points : int
        Table points over ``lambda tau`` in [0.05, 2.5].

    Returns
    -------
    (ndarray, ndarray)
        ``lambda tau`` and the best ``k tau`` (dimensionless).
    """
    theta = np.linspace(0.05, 2.5, points)
    one = np.array([[1.0]])
    ktau = np.array([best_gains(np.array([[th]]), one, one, 1.0, log_bounds=((-3.0, 3.0),))[0][0]
                     for th in theta])
    return theta, ktau


def operator_gain(lam: np.ndarray | float, tau: float) -> np.ndarray:
    """The model operator's gain at instability ``lam``: the most stable gain of the delayed loop, 1/s.

    Parameters
    ----------
    lam : float or ndarray
        Instability, 1/s.
    tau : float
        The operator's delay, s.

    Returns
    -------
    ndarray
        Gain ``k`` (input per offset), 1/s.
    """
    theta, ktau = operator_gain_table()
    return np.interp(np.asarray(lam, dtype=float) * tau, theta, ktau) / tau


def simulate_operator(tau: float, lambda0: float, phases: np.ndarray, gain: float = 1.0,
                      rate: float = RAMP_S_PER_S, dt: float = FRAME_S) -> tuple[np.ndarray, np.ndarray]:
    """Trials of the task run by a delayed proportional operator, as the browser runs them.

    The operator sees the marker as drawn (one value per step) ``tau`` late and applies
    ``u = -gain k*(lambda) x_seen`` limited to :data:`INPUT_LIMIT_1_S`.  The steps are the browser's: at each
    animation frame the input is read and the plant stepped to the offset drawn in that same frame, so the
    offset drawn ``lag = ceil(tau / dt)`` frames before the one being computed is what the input answers
    (``x_{k+1}`` from ``u(x_{k+1-lag})``).

    Parameters
    ----------
    tau : float
        The operator's delay, s.
    lambda0 : float
        Starting instability, 1/s.
    phases : ndarray (n, len(DISTURBANCE_FREQUENCY_RATIOS))
        Disturbance phases of ``n`` trials, rad.
    gain : float
        The operator's gain relative to the most stable one.
    rate : float
        Fall of ``1/lambda``, s per s.
    dt : float
        Step, s.

    Returns
    -------
    (ndarray, ndarray)
        ``lambda_c`` (1/s) and the trial's duration (s), per trial.
    """
    phases = np.atleast_2d(np.asarray(phases, dtype=float))
    n = phases.shape[0]
    lag = int(math.ceil(tau / dt - 1e-9))
    hist = np.zeros((lag + 1, n))              # ring of the drawn offsets; row k % (lag+1) holds step k
    x = np.zeros(n)
    lam_c = np.full(n, np.nan)
    dur = np.full(n, np.nan)
    alive = np.ones(n, dtype=bool)
    k = 0
    while alive.any():
        t = k * dt
        lam = float(ramp_lambda(t, lambda0, rate))
        seen = hist[(k + 1 - lag) % (lag + 1)] if k + 1 >= lag else np.zeros(n)
        u = np.clip(-gain * float(operator_gain(lam, tau)) * seen, -INPUT_LIMIT_1_S, INPUT_LIMIT_1_S)
        x = plant_step(x, lam, u + disturbance(t, phases, lambda0), dt)
        k += 1
        hist[k % (lag + 1)] = x
        lost = alive & (np.abs(x) > LIMIT)
        lam_c[lost], dur[lost] = lam, k * dt
        alive &= ~lost
        if t > MAX_TRIAL_S:                    # a bound on the loop; LAMBDA_MAX_1_S loses every operator first
            break
    return lam_c, dur


@dataclass(frozen=True)
class EscapeFactor:
    """``E = lambda_c tau`` of the model operator in the task: how far past ``1/tau`` control is lost.

    Attributes
    ----------
    mean, sd : float
        Over the calibration population (dimensionless).
    low, high : float
        Its smallest and largest value.
    samples : int
        Trials simulated.
    rate_s_per_s : float
        The ramp it holds for.
    by_tau : tuple of (float, float)
        ``(tau, mean E)`` per calibration delay (s, dimensionless).
    """

    mean: float
    sd: float
    low: float
    high: float
    samples: int
    rate_s_per_s: float
    by_tau: tuple[tuple[float, float], ...]


@lru_cache(maxsize=4)
def escape_factor(rate: float = RAMP_S_PER_S, taus: tuple[float, ...] = CALIBRATION_TAU_S,
                  gains: tuple[float, ...] = CALIBRATION_GAIN, seeds: int = CALIBRATION_SEEDS,
                  lambda0_1_s: float | None = None) -> EscapeFactor:
    """The escape factor of the delayed proportional operator, computed from the delayed-loop model.

    Every calibration delay and gain runs ``seeds`` trials with random disturbance phases (seeded: the same
    every call), each started as a scored trial is, at ``START_FRACTION`` of the operator's own limit
    ``1/tau`` (so the task is scaled to the operator, as the protocol scales it to the user).

    Parameters
    ----------
    rate : float
        Fall of ``1/lambda``, s per s.
    taus : tuple of float
        Operator delays, s.
    gains : tuple of float
        Gains relative to the most stable one.
    seeds : int
        Trials per (delay, gain).
    lambda0_1_s : float, optional
        Start every trial here (1/s) instead of at ``START_FRACTION / tau`` (the first practice trial's fixed
        start).

    Returns
    -------
    EscapeFactor
    """
    rng = np.random.default_rng(20261204)
    values: list[float] = []
    by_tau = []
    for tau in taus:
        here: list[float] = []
        for g in gains:
            phases = rng.uniform(0.0, 2.0 * np.pi, (seeds, len(DISTURBANCE_FREQUENCY_RATIOS)))
            lam0 = START_FRACTION / tau if lambda0_1_s is None else lambda0_1_s
            lam_c, _ = simulate_operator(tau, lam0, phases, gain=g, rate=rate)
            here.extend((lam_c * tau).tolist())
        values.extend(here)
        by_tau.append((float(tau), float(np.mean(here))))
    v = np.asarray(values)
    return EscapeFactor(float(v.mean()), float(v.std(ddof=1)), float(v.min()), float(v.max()), int(v.size),
                        float(rate), tuple(by_tau))


def browser_config() -> dict:
    """The task's constants as the browser needs them (JSON-ready).

    Returns
    -------
    dict
    """
    return {"frame_s": FRAME_S, "limit": LIMIT, "input_limit": INPUT_LIMIT_1_S,
            "lambda_max": LAMBDA_MAX_1_S, "disturbance_ratios": list(DISTURBANCE_FREQUENCY_RATIOS),
            "disturbance_amplitude_ratio": DISTURBANCE_AMPLITUDE_RATIO, "input_deadband": INPUT_DEADBAND}

