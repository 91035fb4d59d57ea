"""Yaw-rate responses to a push: the nonlinear runs and the linear model's exact prediction (Figures 8-3a, 8-4)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.linalg import expm

from stability.chair import Chair, preset
from stability.chair.model import check_chairs, takes_chair
from stability.linear import lateral_force_input, state_matrices
from stability.runtime.checks import first_argument
from stability.settings.reference import REFERENCE_CHAIR, REFERENCE_SPEED, THESIS_PUSH
from stability.settings.run import RunSpec
from stability.study import runs
from stability.study.criteria import DEFAULT_CRITERION, PATHS_CRITERION, Criterion, check_impulse

__all__ = ["linear_peak_yaw_rate", "LinearResponse", "linear_impulse_response", "Response", "ResponseSet",
           "yaw_rate_responses", "trajectories"]


@dataclass(frozen=True, eq=False)
class LinearResponse:
    """The linear model's response to a push (arrays over time).

    Attributes
    ----------
    t : numpy.ndarray
        Time, s.
    v : numpy.ndarray
        Lateral velocity of the c.g., m/s.
    yaw_rate : numpy.ndarray
        rad/s.
    heading : numpy.ndarray
        rad.
    x, y : numpy.ndarray
        Global position, m (``x = U t``).

    """

    t: np.ndarray
    v: np.ndarray
    yaw_rate: np.ndarray
    heading: np.ndarray
    x: np.ndarray
    y: np.ndarray


@takes_chair
def linear_impulse_response(chair: Chair, speed: float, t_end: float = 10.0, *,
                            impulse: Any = THESIS_PUSH.as_tuple, model: str = "exact", casters: str = "free",
                            step: float = 0.01) -> LinearResponse:
    """Response of the linear model to a push, exact for its piecewise-constant force.

    The state is augmented with the heading ``psi`` (``psi' = r``) and the
    lateral displacement ``Y`` (``Y' = U psi + v``) and stepped with the
    matrix exponential of the augmented system (zero-order hold: exact at the
    samples for a force constant over each step).  The force acts for
    ``ceil(duration/step)`` steps of ``duration/that`` s, so the impulse is
    exactly ``force * duration``.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed, m/s.
    t_end : float
        Last time, s.
    impulse : (float, float) or Push
        Force at the c.g. (N) and duration (s); default the thesis's push.
    model : {"exact", "thesis"}
    casters : {"free", "locked"}
    step : float
        Sample interval, s.

    Returns
    -------
    LinearResponse
    """
    force, length = check_impulse(impulse)
    U = float(speed)
    A = state_matrices(chair, U, model, casters)[0]
    b = lateral_force_input(chair, U, model, casters)
    n = A.shape[0]
    Aa = np.zeros((n + 2, n + 2))
    Aa[:n, :n] = A
    Aa[n, 1] = 1.0          # psi' = r
    Aa[n + 1, 0] = 1.0      # Y' = v + U psi
    Aa[n + 1, n] = U
    Ba = np.zeros(n + 2)
    Ba[:n] = b
    n_imp = max(1, int(math.ceil(length / step - 1e-9))) if length > 0 else 0
    h = length / n_imp if n_imp else step
    n_steps = int(math.ceil(t_end / h - 1e-9))
    M = np.zeros((n + 3, n + 3))
    M[: n + 2, : n + 2] = Aa * h
    M[: n + 2, n + 2] = Ba * h
    E = expm(M)
    Phi, Gam = E[: n + 2, : n + 2], E[: n + 2, n + 2]
    z = np.zeros((n_steps + 1, n + 2))
    for k in range(n_steps):
        u = force if k < n_imp else 0.0
        z[k + 1] = Phi @ z[k] + Gam * u
    t = h * np.arange(n_steps + 1)
    return LinearResponse(t=t, v=z[:, 0], yaw_rate=z[:, 1], heading=z[:, n], x=U * t, y=z[:, n + 1])


def linear_peak_yaw_rate(chair: Chair, speed: float, t_end: float = 10.0, *,
                         impulse: Any = THESIS_PUSH.as_tuple, model: str = "exact", step: float = 0.01) -> float:
    """Largest ``|yaw rate|`` of :func:`linear_impulse_response` over its samples, without stepping them one by one.

    The same samples ``t_k = k h``; with the eigen-decomposition ``A = V
    diag(lambda) V^-1`` of the state matrix the response to a constant force
    ``F`` from rest is ``r(t) = sum_j c_j d_j (exp(lambda_j t) - 1) / lambda_j``
    during the push (``c = V[r, :]``, ``d = V^-1 b F``) and ``sum_j c_j d_j
    (exp(lambda_j T) - 1) / lambda_j exp(lambda_j (t - T))`` after it (the
    zero-order hold of :func:`linear_impulse_response` is exact for a force
    constant over each step, so both give the same samples up to rounding),
    evaluated for all samples at once: about 1 ms instead of a 10 000-step
    Python loop.  Where the eigenvectors are ill-conditioned (``cond(V) >
    1e8``: a nearly defective matrix) or an eigenvalue is zero, the samples are
    stepped by :func:`linear_impulse_response`.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed, m/s.
    t_end : float
        Last time, s.
    impulse : (float, float) or Push
        Force at the c.g. (N) and duration (s).
    model : {"exact", "thesis"}
    step : float
        Sample interval, s.

    Returns
    -------
    float
        rad/s.
    """
    force, length = check_impulse(impulse)
    A = state_matrices(chair, float(speed), model, "free")[0]
    lam, V = np.linalg.eig(A)
    if np.linalg.cond(V) > 1e8 or np.min(np.abs(lam)) < 1e-9 or length <= 0:
        r = linear_impulse_response(chair, speed, t_end, impulse=(force, length), model=model, step=step)
        return float(np.max(np.abs(r.yaw_rate)))
    b = lateral_force_input(chair, float(speed), model, "free")
    n_imp = max(1, int(math.ceil(length / step - 1e-9)))
    h = length / n_imp
    n_steps = int(math.ceil(t_end / h - 1e-9))
    w = V[1, :] * np.linalg.solve(V, b.astype(complex) * force) / lam    # mode j's share of r per (exp - 1)
    t = h * np.arange(n_steps + 1)
    during = t[: n_imp + 1]
    # sums over the modes, not matrix products: a product of this size wakes OpenBLAS's threads, which then
    # spin for milliseconds on the cores the simulation kernel needs next
    r_push = (np.expm1(np.outer(during, lam)) * w).sum(axis=1)
    after = t[n_imp + 1:] - during[-1]
    r_free = (np.exp(np.outer(after, lam)) * (w * np.expm1(lam * during[-1]))).sum(axis=1)
    return float(max(np.max(np.abs(r_push.real)), np.max(np.abs(r_free.real), initial=0.0)))


@dataclass(frozen=True, eq=False)
class Response:
    """One nonlinear run and, optionally, the linear prediction for it.

    Attributes
    ----------
    chair : Chair
    speed : float
        m/s.
    t, yaw_rate, heading, x, y : numpy.ndarray
        The simulator's arrays: s, rad/s, rad, m, m (global).
    time_to_level : float
        The criterion's time, s (+inf: never).
    stopped_by_warnings : bool
    linear : LinearResponse or None
    """

    chair: Chair
    speed: float
    t: np.ndarray
    yaw_rate: np.ndarray
    heading: np.ndarray
    x: np.ndarray
    y: np.ndarray
    time_to_level: float
    stopped_by_warnings: bool = False
    linear: LinearResponse | None = None


@dataclass(frozen=True, eq=False)
class ResponseSet:
    """Several runs under one disturbance (Figures 8-3a, 8-4 analogues).

    Attributes
    ----------
    responses : tuple of Response
    model, scheme : str
    impulse : (float, float)
        Force (N), duration (s).
    criterion : Criterion
    linear_model : str
        The linear overlay's model ("" when none).
    linear_note : str
        What the linear overlay assumes.
    """

    responses: tuple
    model: str
    scheme: str
    impulse: tuple
    criterion: Criterion
    linear_model: str = ""
    linear_note: str = ""

    @property
    def speeds(self) -> list[float]:
        """The runs' speeds, m/s."""
        return [r.speed for r in self.responses]


def _responses(chairs: Sequence[Chair], speeds: Sequence[float], run: RunSpec | None, *, criterion: Criterion,
               linear: bool, linear_casters: str, progress: bool) -> ResponseSet:
    spec = runs.study_run(run).replace(horizon=criterion.duration)
    impulse = check_impulse(spec.push.as_tuple)
    model, scheme = spec.model, spec.scheme
    results = runs.simulate_runs(chairs, speeds, spec, progress=progress)
    out = []
    for c, s, res in zip(chairs, speeds, results, strict=True):
        lin = None
        if linear:
            lin = linear_impulse_response(c, s, criterion.duration, impulse=impulse, model=model,
                                          casters=linear_casters)
        heading = getattr(res, "heading", None)
        out.append(Response(
            chair=c, speed=float(s), t=np.asarray(res.t), yaw_rate=np.asarray(res.yaw_rate),
            heading=np.asarray(heading) if heading is not None else np.zeros_like(np.asarray(res.yaw_rate)),
            x=np.asarray(getattr(res, "x", np.zeros_like(res.t))),
            y=np.asarray(getattr(res, "y", np.zeros_like(res.t))),
            time_to_level=criterion.time(res), stopped_by_warnings=bool(getattr(res, "stopped_by_warnings", False)),
            linear=lin))
    note = ("linear model: free frictionless casters (pin damping as set), small-angle kinematics; "
            "the nonlinear model has Coulomb pin friction, so the two agree only when the casters "
            "swing freely" if linear_casters == "free" else "linear model: casters locked")
    return ResponseSet(tuple(out), model, scheme, impulse, criterion, model if linear else "", note if linear else "")


@takes_chair
def yaw_rate_responses(chair: Chair, speeds: Sequence[float] = (0.55, 0.65, 0.75, 0.85, 0.95),
                       run: RunSpec | None = None, *, criterion: Criterion = DEFAULT_CRITERION, linear: bool = True,
                       linear_casters: str = "free", progress: bool = True) -> ResponseSet:
    """Yaw-rate responses to a push at several speeds (Figure 8-3a analogue).

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float
        m/s.
    run : RunSpec, optional
        The runs' settings (push, model, scheme, step, pin-friction law; the thesis's Figure 8-3a uses
        ``model="thesis"`` and ``friction_law="kinetic"``); the horizon is the criterion's.
    criterion : Criterion
        Level and simulated time.
    linear : bool
        Attach the linear model's response to each run.
    linear_casters : {"free", "locked"}
    progress : bool

    Returns
    -------
    ResponseSet
    """
    speeds = [float(s) for s in speeds]
    return _responses([chair] * len(speeds), speeds, run, criterion=criterion, linear=linear,
                      linear_casters=linear_casters, progress=progress)


@first_argument(check_chairs, optional=True)
def trajectories(chairs: Sequence[Chair] | None = None, speed: float = REFERENCE_SPEED, run: RunSpec | None = None,
                 *, criterion: Criterion = PATHS_CRITERION, linear: bool = True,
                 progress: bool = True) -> ResponseSet:
    """Paths of several chairs after a push (Figure 8-4 analogue: rear vs front casters).

    Parameters
    ----------
    chairs : sequence of Chair, optional
        Default the E&J Premier and its front-caster counterpart.
    speed : float
        m/s.
    run, criterion, linear, progress
        As in :func:`yaw_rate_responses` (``criterion.duration`` default 6 s).

    Returns
    -------
    ResponseSet
    """
    if chairs is None:
        chairs = [preset(REFERENCE_CHAIR), preset(f"{REFERENCE_CHAIR}-front-caster")]
    chairs = list(chairs)
    return _responses(chairs, [float(speed)] * len(chairs), run, criterion=criterion, linear=linear,
                      linear_casters="free", progress=progress)
