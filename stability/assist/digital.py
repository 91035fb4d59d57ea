"""The sampled loop: zero-order hold, one sample of computation delay, motor lag; discrete margins.

The discrete controller is exactly the one :class:`~stability.assist.controller.DigitalController`
runs; the plant (with the drive's motor lag) is discretised with a
zero-order hold (:func:`control.c2d`).  Margins of the loop broken at the
plant input, continuous and discrete side by side.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any

import control
import numpy as np
from scipy.linalg import expm

from stability.assist._memo import memo
from stability.assist.design import LOOP_INPUT, LOOP_OUTPUT, Design, LoopMargins, _margins, loop_margins
from stability.assist.disk import frequency_response
from stability.assist.plant import system_name

__all__ = ["discrete_controller", "discrete_loop", "discrete_margins", "MarginPair", "margin_pair", "MarginCurves",
           "margin_curves"]


def discrete_controller(d: Design, sample_time: float) -> control.StateSpace:
    """The sampled controller from the measurements to ``-Mz`` (no feedthrough: one sample of delay).

    Gyro design: states ``[x_hat, e]``, ``x_hat`` propagated with the
    exact discretisation of the estimator for held inputs, ``e`` the running
    sum of the gyro; full-state design: states ``[x_(k-1), e]``.

    Parameters
    ----------
    d : Design
    sample_time : float
        s.

    Returns
    -------
    control.StateSpace
        Discrete, ``dt = sample_time``; inputs ``r`` (gyro) or the internal states (full-state).
    """
    T = float(sample_time)
    p = d.plant
    idx = p.internal
    ni = len(idx)
    Kint, Kpsi = d.K[:, idx], d.K[:, p.psi:p.psi + 1]
    if d.kind == "gyro":
        assert d.model_A is not None and d.model_B is not None and d.L is not None
        Le = np.vstack([d.L, np.zeros((ni - p.psi, 1))])
        M = np.zeros((ni + 2, ni + 2))
        M[:ni, :ni] = d.model_A - Le @ np.eye(ni)[1:2]
        M[:ni, ni:ni + 1] = d.model_B
        M[:ni, ni + 1:] = Le
        E = expm(M * T)
        Phi, Gu, Gr = E[:ni, :ni], E[:ni, ni:ni + 1], E[:ni, ni + 1:]
        A = np.block([[Phi - Gu @ Kint, -Gu @ Kpsi], [np.zeros((1, ni)), np.ones((1, 1))]])
        B = np.vstack([Gr, [[T]]])
    else:
        A = np.zeros((ni + 1, ni + 1))
        A[ni, ni] = 1.0
        B = np.zeros((ni + 1, ni))
        B[:ni] = np.eye(ni)
        B[ni, 1] = T
    C = np.hstack([Kint, Kpsi])
    return control.ss(A, B, C, np.zeros((1, B.shape[1])), T)


def discrete_loop(d: Design, sample_time: float | None = None,
                  controller: control.StateSpace | None = None) -> control.StateSpace:
    """Loop transfer ``L(z)`` broken at the plant input of the sampled controller.

    Parameters
    ----------
    d : Design
    sample_time : float, optional
        s; default the design's own (:attr:`Design.sample_time`, from its
        gyro's sample rate), so it is given once.
    controller : control.StateSpace, optional
        A discrete controller of the form :func:`discrete_controller` returns (e.g. from firmware tables);
        default: that of ``d``.

    Returns
    -------
    control.StateSpace
        Discrete (``dt`` = the sample time), SISO, negative feedback: input
        ``Mz_N_m`` (the yaw moment applied at the plant input, N m), output
        ``u_N_m`` (the controller's ``-Mz``, N m); named ``<design>_loop_U<speed>``.
    """
    sample_time = d.sample_time if sample_time is None else sample_time
    p = d.plant
    idx = p.internal
    A, B = p.A[np.ix_(idx, idx)], p.B[idx]
    C = np.eye(len(idx))[1:2] if d.kind == "gyro" else np.eye(len(idx))
    Pd = control.c2d(control.ss(A, B, C, np.zeros((C.shape[0], 1))), sample_time, method="zoh")
    L = control.series(Pd, discrete_controller(d, sample_time) if controller is None else controller)
    return control.ss(L.A, L.B, L.C, L.D, L.dt, inputs=[LOOP_INPUT], outputs=[LOOP_OUTPUT],
                      name=system_name(f"{d.kind.replace('-', '_')}_loop", d.speed))


def discrete_margins(d: Design, sample_time: float | None = None,
                     controller: control.StateSpace | None = None) -> LoopMargins:
    """Margins of :func:`discrete_loop` (:func:`control.stability_margins`; delay margin ``pm / w_gc``).

    Parameters
    ----------
    d : Design
    sample_time : float
        s.
    controller : control.StateSpace, optional
        As :func:`discrete_loop`.

    Returns
    -------
    LoopMargins
    """
    if controller is None:      # the design's own sampled controller: once per design and sample time
        return memo(d, ("discrete", None if sample_time is None else float(sample_time)),
                    lambda: _discrete_margins(d, sample_time, None))
    return _discrete_margins(d, sample_time, controller)


def _discrete_margins(d: Design, sample_time: float | None, controller: control.StateSpace | None) -> LoopMargins:
    L = discrete_loop(d, sample_time, controller)
    T = float(L.dt)
    A, B, C = np.asarray(L.A), np.asarray(L.B)[:, 0], np.asarray(L.C)[0]

    def resp(w: Any) -> np.ndarray:
        return frequency_response(L, w)

    w = np.geomspace(1e-3, math.pi / T * (1 - 1e-9), 2000)
    Lw = resp(w)
    wgc = _crossings(w, np.abs(Lw) - 1.0, lambda x: float(np.abs(resp(x))[0]) - 1.0)
    wpc = _crossings(w, Lw.imag, lambda x: float(resp(x)[0].imag))
    Lg = resp(np.array(wgc)) if wgc else np.zeros(0)
    pm = np.degrees(np.angle(-Lg)) if wgc else np.zeros(0)      # angle of L from -180 deg
    gm = [1.0 / abs(float(resp(x)[0].real)) for x in wpc if float(resp(x)[0].real) < 0]
    disk = float(np.min(np.abs(1.0 + Lw)))
    m = _margins(L, gm or [np.inf], pm if len(pm) else [np.inf], [disk], wgc or [np.nan], continuous=False,
                 dt=T, return_difference=disk)
    # L is strictly proper (one sample of computation delay): the closed loop u = -y has state matrix A - B C
    if np.max(np.abs(np.linalg.eigvals(A - np.outer(B, C)))) >= 1.0:
        # the sampled loop is unstable at this rate: no margin is left (phase margin reported negative, no
        # delay is tolerated); the text and the JSON say so instead of a margin read off an unstable loop
        return replace(m, phase_margin_deg=-abs(m.phase_margin_deg), delay_margin_s=0.0, min_return_difference=0.0,
                       disk_margin=0.0, disk_gain_margin_db=0.0, disk_phase_margin_deg=0.0, disk_frequency_rad_s=None)
    return m


def _crossings(w: np.ndarray, f: np.ndarray, fn: Any) -> list[float]:
    """Roots of ``fn`` bracketed by sign changes of ``f`` on the grid ``w`` (refined by Brent's method)."""
    from scipy.optimize import brentq  # scipy.optimize only here

    out = []
    for i in np.flatnonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0):
        out.append(float(brentq(fn, w[i], w[i + 1], xtol=1e-12 * w[i + 1])))
    return out


def _summary(m: LoopMargins) -> dict[str, Any]:
    lower = -20 * math.log10(m.gain_margin_lower) if m.gain_margin_lower > 0 else math.inf
    upper = 20 * math.log10(m.gain_margin_upper) if math.isfinite(m.gain_margin_upper) else math.inf
    return {"gain_db": min(lower, upper), "gain_up_db": upper, "gain_down_db": lower,
            "phase_deg": m.phase_margin_deg, "delay_ms": 1e3 * m.delay_margin_s, "disk_margin": m.disk_margin,
            "disk_gain_db": m.disk_gain_margin_db, "disk_phase_deg": m.disk_phase_margin_deg}


@dataclass(frozen=True)
class MarginPair:
    """Margins of the continuous loop and of the sampled loop (ZOH, one-sample delay, motor lag in both).

    Attributes
    ----------
    continuous, discrete : LoopMargins
    sample_time : float
        s.
    """

    continuous: LoopMargins
    discrete: LoopMargins
    sample_time: float

    def to_dict(self) -> dict[str, Any]:
        """``{continuous: {gain_db, phase_deg, delay_ms, ...}, discrete: {...}}``.

        ``gain_db`` is the smaller of the gain increase and decrease (dB) that
        destabilises (the open-loop chair is unstable, so a decrease can);
        ``disk_margin`` (-), ``disk_gain_db`` and ``disk_phase_deg`` are the
        balanced disk margin and the gain (up or down) and phase change it
        tolerates together (:mod:`stability.assist.disk`).
        """
        from stability.assist._format import json_float

        return {k: {kk: json_float(vv) for kk, vv in _summary(getattr(self, k)).items()}
                for k in ("continuous", "discrete")}


def margin_pair(d: Design, sample_time: float) -> MarginPair:
    """Continuous and discrete margins of one design.

    Parameters
    ----------
    d : Design
    sample_time : float
        s.

    Returns
    -------
    MarginPair
    """
    return MarginPair(loop_margins(d), discrete_margins(d, sample_time), float(sample_time))


@dataclass(frozen=True, eq=False)
class MarginCurves:
    """Continuous and sampled margins against speed (arrays, one entry per speed; ``nan`` where none).

    Attributes
    ----------
    speeds : ndarray
        m/s.
    gain_db : ndarray (2, n)
        Smaller of the gain increase and decrease that destabilises (dB); rows continuous, sampled.
    phase_deg : ndarray (2, n)
        deg.
    delay_ms : ndarray (2, n)
        ms.
    sample_time : float
        s.
    disk_gain_db, disk_phase_deg : ndarray (2, n)
        Gain (dB, up or down) and phase (deg) change the balanced disk margin tolerates together.
    """

    speeds: np.ndarray
    gain_db: np.ndarray
    phase_deg: np.ndarray
    delay_ms: np.ndarray
    sample_time: float
    disk_gain_db: np.ndarray | None = None
    disk_phase_deg: np.ndarray | None = None


def margin_curves(speeds: Sequence[float] | np.ndarray, pairs: Sequence[MarginPair]) -> MarginCurves:
    """Collect :class:`MarginPair` results (one per speed) as arrays for plotting.

    Parameters
    ----------
    speeds : sequence of float
        m/s.
    pairs : sequence of MarginPair

    Returns
    -------
    MarginCurves
    """
    def arr(key: str) -> np.ndarray:
        out = np.array([[_summary(getattr(p, k))[key] for p in pairs] for k in ("continuous", "discrete")],
                       dtype=float)
        out[~np.isfinite(out)] = np.nan
        return out

    return MarginCurves(np.asarray(speeds, dtype=float), arr("gain_db"), arr("phase_deg"), arr("delay_ms"),
                        float(pairs[0].sample_time) if pairs else math.nan, arr("disk_gain_db"),
                        arr("disk_phase_deg"))
