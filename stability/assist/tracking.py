"""Yaw-rate command tracking and gyro-bias handling in the linear closed loop.

The joystick's yaw-rate command ``r_cmd`` enters as feedforward (the steady
turn of the design model) plus LQR with integral action: the heading state
of the regulator becomes the integral of the yaw-rate error,
``e = integral of (r_measured - r_cmd)``, so a constant command is followed
with zero steady-state error whatever the model error.  The gyro bias is
estimated from the difference between the gyro and the yaw rate of the
drive-wheel speeds, ``b_dot = (r_gyro - r_wheels - b)/T_b``, and
subtracted.  Argument and numbers in ``docs/assist.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import control
import numpy as np

from stability.assist.design import Design
from stability.assist.plant import Plant, system_name
from stability.settings.defaults import BIAS_TIME_CONSTANT, COMMAND_FILTER

__all__ = ["Feedforward", "feedforward", "closed_loop", "final_heading", "heading_drift", "TrackingMetrics",
           "step_metrics", "DriftCurves", "drift_curves"]


@dataclass(frozen=True, eq=False)
class Feedforward:
    """Steady turn of the design model per unit yaw rate.

    Attributes
    ----------
    Nx : ndarray (n_int,)
        Internal states (plant without the heading) per rad/s of yaw rate.
    Nu : float
        Yaw-moment command per rad/s (N m s).
    """

    Nx: np.ndarray
    Nu: float


def feedforward(p: Plant) -> Feedforward:
    """The steady turn ``A_int x + B_int u = 0`` with ``r = 1 rad/s`` of the plant ``p``.

    At standstill (:func:`~stability.assist.plant.standstill_plant`) the
    casters' angles and the slaved lateral velocity are left free by the
    equations; the minimum-norm solution sets them to zero (their gains are
    zero anyway).

    Parameters
    ----------
    p : Plant

    Returns
    -------
    Feedforward
    """
    idx = p.internal
    Am, Bm = p.A[np.ix_(idx, idx)], p.B[idx]
    m = len(idx)
    M = np.zeros((m + 1, m + 1))
    M[:m, :m], M[:m, m:] = Am, Bm
    M[m, 1] = 1.0
    rhs = np.zeros(m + 1)
    rhs[m] = 1.0
    try:
        sol = np.linalg.solve(M, rhs)
    except np.linalg.LinAlgError:      # the standstill plant: states it leaves free are set to 0
        sol = np.linalg.lstsq(M, rhs, rcond=None)[0]
    return Feedforward(sol[:m], float(sol[m]))


def closed_loop(d: Design, true_plant: Plant | None = None, *, use_feedforward: bool = True,
                bias_time_constant: float = BIAS_TIME_CONSTANT, heading: bool = False,
                command_filter: float = COMMAND_FILTER) -> control.StateSpace:
    """The linear closed loop with a yaw-rate command, a gyro bias and a lateral force as inputs.

    The defaults are the command line's (:mod:`stability.settings.defaults`): the
    gyro-bias estimate with a 1 s time constant and the 200 ms reference
    model on the command, so a step of ``r_cmd`` does not overshoot, as
    ``python -m stability.assist`` reports.  Inputs, outputs and states are
    named; without the heading (the default) the state matrix is regular, so
    :func:`control.dcgain` is finite (1 from ``r_cmd`` to ``r``) and the
    system goes straight into :func:`control.bode_plot`,
    :func:`control.step_response` and :func:`control.margin`.

    Plant ``x_dot = A x + B Mz + Bf Fy``; gyro ``r_m = r + b``; bias
    estimate ``b_hat`` (first order, time constant ``bias_time_constant``
    from the gyro-minus-wheel-speed yaw rate; 0: no bias handling);
    measured heading error ``e_dot = r_m - b_hat - r_cmd``.  Full-state
    design: ``Mz = -K_int (y_int - Nx r_cmd) - K_psi e + Nu r_cmd`` with the
    gyro's ``r`` in ``y_int``; gyro design: the Kalman estimate ``x_hat``
    (driven by the applied command) replaces ``y_int``.

    Parameters
    ----------
    d : Design
    true_plant : Plant, optional
        The plant the controller acts on (default: its design plant).
    use_feedforward : bool
        Include ``Nx``, ``Nu`` (integral action alone otherwise).
    bias_time_constant : float
        ``T_b`` of the bias estimate (s); 0 turns the handling off (default
        :data:`stability.settings.defaults.BIAS_TIME_CONSTANT`, 1 s).
    heading : bool
        Keep the true heading (a pure integrator of ``r`` that nothing
        depends on: the state matrix is then singular and DC gains are NaN).
        Default False.
    command_filter : float
        Time constant of the first-order reference model on ``r_cmd`` (s);
        0: the raw command (default :data:`stability.settings.defaults.COMMAND_FILTER`, 0.2 s).

    Returns
    -------
    control.StateSpace
        Inputs ``r_cmd`` (rad/s), ``bias`` (rad/s), ``Fy`` (N); outputs
        ``r`` (rad/s), ``psi`` (true heading, rad; only with ``heading``),
        ``Mz`` (yaw moment of the drive, N m), ``e`` (measured heading
        error, rad); states named after the plant's, the heading-error
        integrator ``e``, the estimate ``*_hat``, the bias estimate ``b_hat``
        and the reference model ``r_ref``.  Named ``<design>_closed_loop_U<speed>``
        (python-control allows no dots in names: ``gyro_closed_loop_U1p5``).
    """
    p = true_plant or d.plant
    n = p.n
    idx = p.internal
    ni = len(idx)
    ff = feedforward(d.plant) if use_feedforward else Feedforward(np.zeros(ni), 0.0)
    gyro = d.kind == "gyro"
    handle = bias_time_constant > 0
    N = n + 1 + (ni if gyro else 0) + (1 if handle else 0)
    E, XH, BH = n, n + 1, N - 1
    # r' = r + b - b_hat as (row over z, row over inputs [r_cmd, b, Fy])
    rz, ru = np.zeros(N), np.array([0.0, 1.0, 0.0])
    rz[1] = 1.0
    if handle:
        rz[BH] = -1.0
    Kint, Kpsi = d.K[0, idx], float(d.K[0, p.psi])
    mz_z, mz_u = np.zeros(N), np.zeros(3)
    mz_z[E] = -Kpsi
    mz_u[0] = ff.Nu + float(Kint @ ff.Nx)
    if gyro:
        mz_z[XH:XH + ni] = -Kint
    else:
        for j, i in enumerate(idx):
            mz_z[i] -= Kint[j]
        mz_z -= Kint[1] * (rz - np.eye(N)[1])      # the gyro's r, not the true r
        mz_u -= Kint[1] * ru
    A = np.zeros((N, N))
    Bu = np.zeros((N, 3))
    A[:n, :n] = p.A
    A[:n] += p.B @ mz_z[None, :]
    Bu[:n] += p.B @ mz_u[None, :]
    Bu[:n, 2] += p.Bf[:, 0]
    A[E] = rz
    Bu[E] = ru - np.array([1.0, 0.0, 0.0])
    if gyro:
        assert d.model_A is not None and d.model_B is not None and d.L is not None
        Le = np.vstack([d.L, np.zeros((ni - p.psi, 1))])
        A[XH:XH + ni, XH:XH + ni] = d.model_A - Le @ np.eye(ni)[1:2]
        A[XH:XH + ni] += d.model_B @ mz_z[None, :] + Le @ rz[None, :]
        Bu[XH:XH + ni] += d.model_B @ mz_u[None, :] + Le @ ru[None, :]
    if handle:
        A[BH, BH] = -1.0 / bias_time_constant
        Bu[BH, 1] = 1.0 / bias_time_constant
    C = np.zeros((4, N))
    D = np.zeros((4, 3))
    C[0, 1] = C[1, p.psi] = C[3, E] = 1.0
    C[2], D[2] = mz_z, mz_u
    names = list(p.states) + ["e"] + ([f"{p.states[i]}_hat" for i in idx] if gyro else []) \
        + (["b_hat"] if handle else [])
    outputs = ["r", "psi", "Mz", "e"]
    if not heading:      # nothing depends on the true heading: drop its integrator (for DC gains)
        keep = [i for i in range(N) if i != p.psi]
        A, Bu, C, D = A[np.ix_(keep, keep)], Bu[keep], C[np.ix_([0, 2, 3], keep)], D[[0, 2, 3]]
        names = [names[i] for i in keep]
        outputs = ["r", "Mz", "e"]
    if command_filter > 0:   # r_ref' = (r_cmd - r_ref)/T: the loop sees r_ref where it saw r_cmd
        A = np.block([[A, Bu[:, :1]], [np.zeros((1, A.shape[0])), np.array([[-1.0 / command_filter]])]])
        C = np.hstack([C, D[:, :1]])
        Bu = np.vstack([np.hstack([np.zeros((Bu.shape[0], 1)), Bu[:, 1:]]),
                        np.array([[1.0 / command_filter, 0.0, 0.0]])])
        D = np.hstack([np.zeros((D.shape[0], 1)), D[:, 1:]])
        names.append("r_ref")
    return control.ss(A, Bu, C, D, inputs=["r_cmd", "bias", "Fy"], outputs=outputs, states=names,
                      name=system_name(f"{d.kind.replace('-', '_')}_closed_loop", d.speed))


def final_heading(sys: control.StateSpace, inp: int) -> float:
    """Final true heading (rad) after a unit step on input ``inp`` of ``closed_loop(..., heading=False)``.

    The heading is the integral of the yaw rate; when the yaw rate returns
    to zero its final value is ``int_0^inf r dt = -C_r A^-2 B`` (the
    final-value theorem applied to ``R(s)/s``).  Raises ValueError if the
    yaw rate does not return to zero (the heading then drifts).

    Parameters
    ----------
    sys : control.StateSpace
        A closed loop without the heading state (asymptotically stable).
    inp : int
        Input index.

    Returns
    -------
    float
        rad per unit of the input.
    """
    A, B, C = np.asarray(sys.A), np.asarray(sys.B)[:, inp], np.asarray(sys.C)[0]
    xss = -np.linalg.solve(A, B)
    if abs(C @ xss) > 1e-9 * max(1.0, float(np.abs(C).max() * np.abs(xss).max())):
        raise ValueError("the yaw rate does not return to zero: the heading drifts")
    return float(C @ np.linalg.solve(A, xss))   # int_0^inf (x - x_ss) dt = A^-1 x_ss, here x_ss has r = 0


@dataclass(frozen=True)
class TrackingMetrics:
    """Response of the yaw rate to a step command.

    Attributes
    ----------
    command_rad_s : float
        Step size (rad/s).
    steady_state_error_pct : float
        ``100 (r_cmd - r_end)/r_cmd`` at the end of the record.
    overshoot_pct : float
        ``100 (max r - r_cmd)/r_cmd`` (0 if none).
    settling_time_s : float or None
        Last time ``|r - r_cmd|`` leaves 2 % of the command (None: never settles).
    peak_torque_N_m : float
        Largest differential torque per wheel (N m).
    """

    command_rad_s: float
    steady_state_error_pct: float
    overshoot_pct: float
    settling_time_s: float | None
    peak_torque_N_m: float

    def to_dict(self) -> dict[str, float | None]:
        """JSON-ready dict."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def step_metrics(t: np.ndarray, r: np.ndarray, torque: np.ndarray, command: float,
                 band: float = 0.02) -> TrackingMetrics:
    """Tracking metrics of a yaw-rate record after a step command at ``t = 0``.

    Parameters
    ----------
    t, r : ndarray
        Time (s) and yaw rate (rad/s).
    torque : ndarray
        Differential torque per wheel (N m).
    command : float
        rad/s (nonzero).
    band : float
        Settling band as a fraction of the command.

    Returns
    -------
    TrackingMetrics
    """
    t, r = np.asarray(t, dtype=float), np.asarray(r, dtype=float)
    err = np.abs(r - command) > band * abs(command)
    out = np.flatnonzero(err)
    settle = None if err[-1] else (float(t[out[-1] + 1]) if out.size else 0.0)
    return TrackingMetrics(float(command), float(100 * (command - r[-1]) / command),
                           float(max(0.0, 100 * (np.max(r / command) - 1.0))), settle,
                           float(np.max(np.abs(torque))) if np.size(torque) else 0.0)


def heading_drift(d: Design, bias_deg_s: float, duration: float, *, bias_time_constant: float = 0.0) -> float:
    """True heading (deg) after ``duration`` s of straight driving with a constant gyro bias (linear loop).

    Parameters
    ----------
    d : Design
    bias_deg_s : float
        deg/s.
    duration : float
        s.
    bias_time_constant : float
        s; 0: no bias handling.

    Returns
    -------
    float
        deg.
    """
    return float(_drift(d, bias_deg_s, duration, bias_time_constant)[1][-1])


def _drift(d: Design, bias_deg_s: float, duration: float, bias_time_constant: float) -> tuple[np.ndarray, np.ndarray]:
    """Time (s) and true heading (deg) of the linear loop, straight command, constant gyro bias."""
    sys = closed_loop(d, bias_time_constant=bias_time_constant, heading=True, command_filter=0.0)
    t = np.linspace(0.0, duration, int(duration * 200) + 1)
    u = np.zeros((3, t.size))
    u[1] = np.radians(bias_deg_s)
    resp = control.forced_response(sys, t, u)
    return t, np.degrees(np.asarray(resp.outputs)[1])


@dataclass(frozen=True, eq=False)
class DriftCurves:
    """Heading drift of the linear loop under a constant gyro bias, with and without the bias handling.

    Attributes
    ----------
    speed_m_s : float
        Design speed of the controller (m/s).
    t : ndarray
        s.
    bias_deg_s : tuple of float
        The biases (deg/s), one row of ``without`` and ``handled`` each.
    without, handled : ndarray (n_bias, n_t)
        True heading (deg): no bias handling / bias estimate from the wheel speeds.
    bias_time_constant_s : float
        ``T_b`` of the handling (s); the heading settles at ``-b T_b``.
    """

    speed_m_s: float
    t: np.ndarray
    bias_deg_s: tuple[float, ...]
    without: np.ndarray
    handled: np.ndarray
    bias_time_constant_s: float


def drift_curves(d: Design, bias_deg_s: tuple[float, ...] = (0.1, 1.0), duration: float = 20.0, *,
                 bias_time_constant: float = 1.0) -> DriftCurves:
    """Heading against time with each gyro bias, straight command, without and with the handling.

    Parameters
    ----------
    d : Design
    bias_deg_s : tuple of float
        deg/s.
    duration : float
        s.
    bias_time_constant : float
        ``T_b`` of the handled case (s, > 0).

    Returns
    -------
    DriftCurves
    """
    rows = [(_drift(d, b, duration, 0.0), _drift(d, b, duration, bias_time_constant)) for b in bias_deg_s]
    t = rows[0][0][0]
    return DriftCurves(float(d.speed), t, tuple(float(b) for b in bias_deg_s), np.array([w[1] for w, _ in rows]),
                       np.array([h[1] for _, h in rows]), float(bias_time_constant))
