"""What the firmware's number format costs: a derived bound on the output change, and the margins it leaves.

Output bound (:func:`output_bound`).  The quantised controller (tables
``Phi_q = Phi + dPhi`` ...) and the ideal one read the same inputs, so the
gyro-bias estimate, the corrected gyro ``r`` and the reference model are
identical in both.  With ``x`` the estimate, ``e`` the heading integrator and
``s_k`` = 1 where the torque is not saturated (0 where it is), the differences
``dx = x_q - x``, ``de = e_q - e`` obey exactly::

    dx_k  = (I + dPhi_q) dx_(k-1) + g0_q s_(k-1) dMz_(k-1) + [dPhi x_(k-1) + dg0 u_(k-1) + dg1 r_(k-1)]
    de_k  = de_(k-1) + a_(k-1) (1 - s_(k-1)) dMz_(k-1) + [g_aw |excess| (1/K_psi,q - 1/K_psi)]
    dMz_k = -K_int,q dx_k - K_psi,q de_k + [dK_int x_k + dK_psi e_k - dF c~_(k-1)]
    dtau_k = c s_k dMz_k

(``a`` the back-calculation gain ``g_aw / K_psi,q`` while the joystick turns,
``c = r_w / (d1 + d2)``): a linear time-varying system driven by the
bracketed sources, each bounded by the tables' half steps ``h`` times the
ideal run's signals (``|dPhi x| <= h_Phi sum|x|`` ...).  Summing the absolute
impulse responses (the transition matrices along the run) times those
bounds gives ``|tau_q,k - tau_k| <= bound_k`` at every sample; it holds while
both runs saturate at the same samples (checked: the ideal torque stays
farther from the limit than the bound, or the quantised mirror saturates
alike).  The single-precision arithmetic of the C adds at most
:data:`FLOAT_RELATIVE` of full scale (the torque limit).

Margins (:func:`margin_rows`): the sampled loop's margins
(:func:`~stability.assist.digital.discrete_margins`) of the ideal scheduled
controller (``Schedule.at``), of the firmware's interpolated tables and of
their Q15 and Q31 roundings, at the grid speeds and half-way between.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import control
import numpy as np

from stability.assist.digital import _summary, discrete_margins
from stability.assist.firmware import FirmwareController, FirmwareTables, half_steps, quantise
from stability.assist.schedule import Schedule

__all__ = ["FLOAT_RELATIVE", "output_bound", "vector_tolerances", "table_controller", "MarginRow", "margin_rows"]

#: Tolerance of single-precision C against the float64 Python, relative to full scale (the torque limit; the
#: issue's 1e-5).  Single precision rounds the inputs, the tables and every operation by 2**-24 relative; measured
#: over the vectors, the float export stays within 2e-7 of full scale (module docstring).
FLOAT_RELATIVE = 1e-5


def _trajectory(t: FirmwareTables, inputs: np.ndarray) -> dict[str, np.ndarray]:
    """Run the mirror and keep what the bound needs, one row per sample."""
    fc = FirmwareController(t)
    keys = ("xhat", "e", "u", "mz", "r", "rc", "raw")
    rec: dict[str, list] = {k: [] for k in (*keys, "tau", "sat")}
    for row in inputs:
        tau = fc.step(*row)[0]
        for k in keys:
            rec[k].append(np.array(getattr(fc, k)[0], dtype=float))
        rec["tau"].append(tau)
        rec["sat"].append(abs(tau) >= t.torque_limit)
    return {k: np.array(v) for k, v in rec.items()}


def output_bound(ideal: FirmwareTables, quantised: FirmwareTables, inputs: np.ndarray) -> np.ndarray:
    """Bound on ``|tau_quantised - tau_ideal|`` at every sample of a replay of ``inputs`` (N m; module docstring).

    Parameters
    ----------
    ideal, quantised : FirmwareTables
        The same controller before and after :func:`~stability.assist.firmware.quantise`.
    inputs : ndarray (N, 4)
        Rows ``speed, command, gyro, wheel``.

    Returns
    -------
    ndarray (N,)
        N m (exact arithmetic; add :data:`FLOAT_RELATIVE` for single precision).
    """
    h = half_steps(quantised)
    tr = _trajectory(ideal, inputs)
    N, n = len(inputs), ideal.n
    dphi_q, gam_q, kint_q, kpsi_q, _ = _tables_along(quantised, inputs)
    _, _, _, kpsi, _ = _tables_along(ideal, inputs)
    c = quantised.torque_per_moment
    s = (~tr["sat"]).astype(float)
    s[0] = 0.0                                   # the first output is 0 in both
    turning = tr["raw"] != 0.0
    backcalc = quantised.anti_windup == "back-calculation"
    a = np.where(turning & backcalc, quantised.windup_gain / kpsi_q, 0.0) * (1.0 - s)
    a[0] = 0.0
    absx = np.abs(tr["xhat"])
    rc_prev = np.concatenate([[0.0], tr["rc"][:-1]])
    src_mz = absx @ h["k_int"] + h["k_psi"] * np.abs(tr["e"]) + h["feedforward"] * np.abs(rc_prev)
    src_mz[0] = 0.0
    src_x = absx @ h["phi_minus_i"].T + np.abs(tr["u"])[:, None] * h["gamma"][:, 0] \
        + np.abs(tr["r"])[:, None] * h["gamma"][:, 1]
    excess = np.where(turning, tr["mz"] - tr["u"], 0.0)
    hk = h["k_psi"]
    src_e = np.where(turning & backcalc, quantised.windup_gain * np.abs(excess) * hk
                     / (np.abs(kpsi) * np.maximum(np.abs(kpsi) - hk, 1e-300)), 0.0)
    # A_k, B_k map the differences of sample k-1 to sample k (index k = 1 .. N-1)
    M = np.concatenate([-kint_q, -kpsi_q[:, None]], axis=1)              # (N, n+1): dMz_k = M_k z_k + src
    A = np.zeros((N, n + 1, n + 1))
    B = np.zeros((N, n + 1))
    A[:, :n, :n] = np.eye(n) + dphi_q
    A[:, n, n] = 1.0
    B[1:, :n] = gam_q[:-1, :, 0] * s[:-1, None]
    B[1:, n] = a[:-1]
    A[1:] += B[1:, :, None] * M[:-1, None, :]
    src_xe = np.concatenate([src_x, src_e[:, None]], axis=1)           # (N, n+1) sources of sample j
    total = src_mz.copy()
    R = M.copy()                                                        # R_k = M_k A_k ... A_(k-m+1)
    for m in range(N - 1):
        k = np.arange(m + 1, N)
        j = k - 1 - m
        Rk = R[k]
        total[k] += np.abs(np.einsum("ki,ki->k", Rk, B[k - m])) * src_mz[j] + np.einsum("ki,ki->k", np.abs(Rk),
                                                                                          src_xe[j])
        R[k] = np.einsum("ki,kij->kj", Rk, A[k - m])
    return c * s * total


def _tables_along(t: FirmwareTables, inputs: np.ndarray) -> tuple[np.ndarray, ...]:
    """The interpolated tables at each sample's speed (leading axis the samples)."""
    fc = FirmwareController(t, runs=len(inputs))
    return fc.tables_at(inputs[:, 0])


def vector_tolerances(ideal: FirmwareTables, quantised: FirmwareTables, cases: Sequence[Any]) -> dict[str, float]:
    """Per case: the largest :func:`output_bound` plus :data:`FLOAT_RELATIVE` times the torque limit (N m).

    Parameters
    ----------
    ideal, quantised : FirmwareTables
    cases : sequence of VectorCase

    Returns
    -------
    dict
        Case name -> N m.
    """
    out = {}
    for cs in cases:
        b = 0.0 if quantised.q_format == "float" else float(np.max(output_bound(ideal, quantised, cs.inputs)))
        out[cs.name] = b + FLOAT_RELATIVE * quantised.torque_limit
    return out


def table_controller(t: FirmwareTables, speed: float) -> control.StateSpace:
    """The firmware's controller at ``speed`` as :func:`~stability.assist.digital.discrete_controller` writes it.

    Parameters
    ----------
    t : FirmwareTables
    speed : float
        m/s.

    Returns
    -------
    control.StateSpace
        States ``[x_hat, e]``, input the gyro, output ``-Mz``; ``dt`` the sample time.
    """
    fc = FirmwareController(t)
    dphi, gam, kint, kpsi, _ = (x[0] for x in fc.tables_at(speed))
    n, T = t.n, t.sample_time
    Gu, Gr = gam[:, :1], gam[:, 1:]
    A = np.block([[np.eye(n) + dphi - Gu @ kint[None, :], -Gu * kpsi], [np.zeros((1, n)), np.ones((1, 1))]])
    B = np.vstack([Gr, [[T]]])
    C = np.concatenate([kint, [kpsi]])[None, :]
    return control.ss(A, B, C, np.zeros((1, 1)), T)


@dataclass(frozen=True)
class MarginRow:
    """Sampled margins at one speed: ideal schedule, float tables, Q15 and Q31 tables.

    Attributes
    ----------
    speed_m_s : float
    margins : dict
        ``"ideal" | "float" | "Q15" | "Q31"`` -> ``{gain_db, phase_deg, delay_ms}``.
    """

    speed_m_s: float
    margins: dict[str, dict[str, float]]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        from stability.assist._format import json_float

        return {"speed_m_s": self.speed_m_s,
                **{k: {kk: json_float(v[kk]) for kk in ("gain_db", "phase_deg", "delay_ms")}
                   for k, v in self.margins.items()}}


def margin_rows(sched: Schedule, tables: FirmwareTables, speeds: Sequence[float] | None = None) -> list[MarginRow]:
    """Sampled margins of the ideal schedule and of the firmware tables (float, Q15, Q31) at ``speeds``.

    Parameters
    ----------
    sched : Schedule
    tables : FirmwareTables
        Float tables of ``sched`` (:func:`~stability.assist.firmware.firmware_tables`).
    speeds : sequence of float, optional
        m/s (> 0); default: the grid speeds and the midpoints between them.

    Returns
    -------
    list of MarginRow
    """
    g = np.asarray(sched.speeds, dtype=float)
    at = np.sort(np.concatenate([g, 0.5 * (g[1:] + g[:-1])])) if speeds is None else np.asarray(speeds, dtype=float)
    variants = {"float": tables, "Q15": quantise(tables, "Q15")[0], "Q31": quantise(tables, "Q31")[0]}
    rows = []
    for s in at:
        d = sched.at(float(s))
        T = tables.sample_time
        m = {"ideal": _summary(discrete_margins(d, T))}
        for k, t in variants.items():
            m[k] = _summary(discrete_margins(d, T, table_controller(t, float(s))))
        rows.append(MarginRow(float(s), m))
    return rows


def worst_change(rows: Sequence[MarginRow], variant: str) -> dict[str, float]:
    """Largest loss of each margin of ``variant`` against the ideal schedule over the rows (dB, deg, ms).

    Parameters
    ----------
    rows : sequence of MarginRow
    variant : str

    Returns
    -------
    dict
        ``{gain_db, phase_deg, delay_ms}``: max over rows of ``ideal - variant`` (positive: a loss).
    """
    out = {}
    for key in ("gain_db", "phase_deg", "delay_ms"):
        d = [r.margins["ideal"][key] - r.margins[variant][key] for r in rows
             if math.isfinite(r.margins["ideal"][key]) and math.isfinite(r.margins[variant][key])]
        out[key] = max(d) if d else math.nan
    return out
