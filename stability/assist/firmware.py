"""The gyro assist as firmware runs it: tables over speed, linear interpolation, one step per sample.

:func:`firmware_tables` reads, at every speed of the schedule's grid (the
standstill design included), the matrices the sampled controller
:class:`~stability.assist.controller.DigitalController` runs: the estimator's
exact discretisation ``Phi``, ``Gamma`` (inputs: applied yaw moment, corrected
gyro), the gains ``K_int``, ``K_psi`` and the feedforward ``F``, and the
speed-independent gains of the bias estimate, the reference model and the
anti-windup.  :class:`FirmwareController` runs them the way the exported C
(:mod:`.export_c`) does, on numpy arrays over independent runs: at a grid
speed it is the :class:`DigitalController` of that design (same arithmetic in
the same order); between grid speeds every table entry is interpolated
linearly in speed (a controller that stores tables; ``Schedule.at``
interpolates the continuous matrices and discretises instead, the margins of
both are in :mod:`.quantisation`).  Outside the grid the end tables hold.

Per sample ``k`` (inputs ``U_k``, raw command ``c_k``, gyro ``g_k``, wheel-speed
yaw rate ``w_k``; the torque applied from ``t_k`` was computed from the samples
before ``k``: one sample of computation delay)::

    e_k    = e_(k-1) + T (r_(k-1) - c~_(k-1)) + anti-windup      (k > 0)
    xh_k   = Phi xh_(k-1) + Gamma [Mz_(k-1), r_(k-1)]              (k > 0)
    b_k    = b_(k-1) + g_b ((g_k - w_k) - b_(k-1));   r_k = g_k - b_k
    Mz_k   = -K_int xh_k - K_psi e_k + F c~_(k-1);   tau_k = sat(Mz_k r_w / (d1 + d2))
    c~_k   = c~_(k-1) + g_c (c_k - c~_(k-1))

with ``tau_k`` the differential torque per drive wheel (left ``+tau``, right
``-tau``, N m).  Before that, the sensor monitor low-passes ``g_k - w_k``
(:data:`MONITOR_TIME`); when it departs from ``b_(k-1)`` by more than
:data:`MONITOR_THRESHOLD_DEG_S` the controller latches a degraded mode
(:data:`MODES`): if ``w_k`` is implausible (:data:`WHEEL_PLAUSIBLE`) the gyro
is used alone with the bias estimate frozen, else ``w_k`` replaces the gyro;
it then asks for :data:`DEGRADED_SPEED`.  See docs/assist.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from stability.assist.controller import ANTI_WINDUP, TRACKING_TIME, DigitalController
from stability.assist.schedule import Schedule
from stability.runtime.checks import check_choice

__all__ = ["Q_FORMATS", "MONITOR_TIME", "MONITOR_THRESHOLD_DEG_S", "WHEEL_PLAUSIBLE", "PLAUSIBLE_MIN_SPEED",
           "DEGRADED_SPEED", "MODES", "FirmwareTables", "firmware_tables", "quantise", "q_bits", "half_steps",
           "FirmwareController", "mirror_outputs"]

#: Number formats of the exported tables: 16- and 32-bit fixed point, or float.
Q_FORMATS = ("float", "Q15", "Q31")
#: Sensor monitor: low-pass time constant of gyro minus wheel-speed yaw rate (s) and the threshold of that
#: residual less the bias estimate (deg/s; a healthy gyro keeps it at the noise level, ~0.1 deg/s).
MONITOR_TIME = 0.05
MONITOR_THRESHOLD_DEG_S = 3.0
#: A wheel-speed yaw rate is implausible when it implies a wheel-speed difference of at least WHEEL_PLAUSIBLE
#: times the forward speed (one wheel at most half the other's speed), the speed taken as at least
#: PLAUSIBLE_MIN_SPEED (m/s).
WHEEL_PLAUSIBLE = 0.5
PLAUSIBLE_MIN_SPEED = 0.3
#: The speed limit the degraded mode commands (m/s).
DEGRADED_SPEED = 1.0
#: Monitor modes: 0 normal, 1 gyro at fault (the wheel-speed yaw rate steers), 2 wheel-speed sensor at fault (the
#: gyro alone, bias estimate frozen).
MODES = ("normal", "wheel_speed_yaw_rate", "gyro_only")


@dataclass(frozen=True, eq=False)
class FirmwareTables:
    """The controller's tables over speed and its constants.

    Attributes
    ----------
    speeds : ndarray (S,)
        Increasing table speeds, m/s (0: the standstill design).
    phi_minus_i : ndarray (S, n, n)
        ``Phi - I`` of the estimator (stored as the difference: its entries are small at a high sample rate).
    gamma : ndarray (S, n, 2)
        Estimator input matrix, columns applied yaw moment (per N m) and corrected gyro (per rad/s).
    k_int : ndarray (S, n)
        Gains on the estimate, N m per state unit.
    k_psi : ndarray (S,)
        Gain on the heading error, N m/rad.
    feedforward : ndarray (S,)
        ``F``, N m per rad/s of filtered command.
    sample_time : float
        s.
    torque_per_moment : float
        Differential wheel torque per yaw moment ``r_w / (d1 + d2)`` (N m per N m).
    torque_limit : float
        N m per wheel (inf: no saturation).
    bias_gain, command_gain, windup_gain : float
        ``g_b = 1 - exp(-T / T_b)``, ``g_c = 1 - exp(-T / T_ref)`` and ``T / T_t``.
    anti_windup : str
        One of :data:`~stability.assist.controller.ANTI_WINDUP`.
    track : float
        ``d1 + d2``, the drive wheels' track (m), for the wheel-speed plausibility check.
    q_format : str
        One of :data:`Q_FORMATS`.
    exponents : dict
        Table name -> binary exponents ``E`` of its entries' fixed-point scales (value = integer * 2**(E - bits));
        empty for float.
    """

    speeds: np.ndarray
    phi_minus_i: np.ndarray
    gamma: np.ndarray
    k_int: np.ndarray
    k_psi: np.ndarray
    feedforward: np.ndarray
    sample_time: float
    torque_per_moment: float
    torque_limit: float
    bias_gain: float
    command_gain: float
    windup_gain: float
    anti_windup: str
    track: float
    q_format: str = "float"
    exponents: Any = None

    #: names of the tables over speed (quantised by :func:`quantise`)
    TABLES = ("phi_minus_i", "gamma", "k_int", "k_psi", "feedforward")

    @property
    def monitor_gain(self) -> float:
        """Per-sample gain of the monitor's low-pass, ``1 - exp(-T / MONITOR_TIME)``."""
        return 1.0 - math.exp(-self.sample_time / MONITOR_TIME)

    @property
    def n(self) -> int:
        """Estimator order."""
        return int(self.k_int.shape[1])


def firmware_tables(sched: Schedule, *, command_filter_s: float, anti_windup: str = ANTI_WINDUP[0],
                    tracking_time_s: float = TRACKING_TIME, saturate: bool = True) -> FirmwareTables:
    """The tables of a gyro schedule, read from :class:`DigitalController` at each grid speed.

    Parameters
    ----------
    sched : Schedule
        A ``"gyro"`` schedule.
    command_filter_s : float
        Reference-model time constant, s (0: none).
    anti_windup : str
        :data:`~stability.assist.controller.ANTI_WINDUP`.
    tracking_time_s : float
        Back-calculation time constant, s.
    saturate : bool
        Saturate at the drive's torque limit.

    Returns
    -------
    FirmwareTables
    """
    if sched.kind != "gyro":
        raise ValueError(f"design={sched.kind!r} is invalid for firmware; valid: 'gyro' (the full-state design "
                         "needs the lateral velocity and caster angles, which a chair does not measure)")
    check_choice("anti_windup", anti_windup, ANTI_WINDUP)
    speeds, designs = sched.grid
    ctls = [DigitalController(d, sched.chair, sched.drive, gyro=sched.gyro, noise=False, saturate=saturate,
                              command_filter_s=command_filter_s, anti_windup=anti_windup,
                              tracking_time_s=tracking_time_s) for d in designs]
    c0 = ctls[0]
    n = len(c0._idx)
    return FirmwareTables(
        np.asarray(speeds, dtype=float), np.array([c._Phi - np.eye(n) for c in ctls]),
        np.array([c._Gam for c in ctls]), np.array([c._Kint for c in ctls]),
        np.array([c._Kpsi for c in ctls]), np.array([c._F for c in ctls]), c0.Ts,
        float(sched.drive.wheel_torque(sched.chair, 1.0)),
        float(sched.drive.torque_limit) if saturate else math.inf, c0._bias_gain, c0._cmd_gain, c0._aw_gain,
        anti_windup, float(sched.chair.d1 + sched.chair.d2))


def _exponents(values: np.ndarray, bits: int) -> np.ndarray:
    """Per entry (over the speed axis 0): smallest ``E`` with ``max|v| * 2**(bits - E) <= 2**bits - 1``."""
    m = np.max(np.abs(values), axis=0)
    e = np.where(m > 0, np.ceil(np.log2(np.where(m > 0, m, 1.0))), 0.0)
    e = np.where(m * 2.0 ** (bits - e) > 2.0 ** bits - 1, e + 1, e)
    return e.astype(int)


def quantise(t: FirmwareTables, q_format: str) -> tuple[FirmwareTables, dict[str, np.ndarray]]:
    """The tables rounded to a fixed-point format, one binary scale per table entry (shared over speed).

    ``Qn`` stores each entry's values over the speed grid as signed ``n + 1``-bit
    integers ``q`` with ``value = q * 2**(E - n)``, ``E`` the smallest exponent
    whose range holds that entry's largest value over speed (so the
    interpolation between speeds is between integers of one scale); rounding
    to nearest changes a value by at most half a step, ``2**(E - n - 1)``.

    Parameters
    ----------
    t : FirmwareTables
    q_format : str
        :data:`Q_FORMATS` ("float": unchanged).

    Returns
    -------
    FirmwareTables
        With the rounded values and ``exponents`` (table name -> integer array of the entry shape).
    dict
        Table name -> integers (int64 arrays; empty for float).
    """
    check_choice("q_format", q_format, Q_FORMATS)
    if q_format == "float":
        return replace(t, q_format="float", exponents={}), {}
    bits = q_bits(q_format)
    ints: dict[str, np.ndarray] = {}
    exps: dict[str, np.ndarray] = {}
    vals: dict[str, np.ndarray] = {}
    for name in FirmwareTables.TABLES:
        v = np.asarray(getattr(t, name), dtype=float)
        e = _exponents(v, bits)
        q = np.rint(v * 2.0 ** (bits - e)).astype(np.int64)
        ints[name], exps[name], vals[name] = q, e, q * 2.0 ** (e - bits)
    return replace(t, q_format=q_format, exponents=exps, **vals), ints  # type: ignore[arg-type]


def q_bits(q_format: str) -> int:
    """Fraction bits of a Q format (15 or 31).

    Parameters
    ----------
    q_format : str

    Returns
    -------
    int
    """
    return 15 if q_format == "Q15" else 31


def half_steps(t: FirmwareTables) -> dict[str, np.ndarray]:
    """Largest rounding change of each table entry (half a step; 0 for float tables).

    Parameters
    ----------
    t : FirmwareTables

    Returns
    -------
    dict
        Table name -> array of the entry shape (the table's units).
    """
    if not t.exponents:
        return {name: np.zeros(np.shape(getattr(t, name))[1:]) for name in FirmwareTables.TABLES}
    bits = q_bits(t.q_format)
    return {name: 2.0 ** (np.asarray(e) - bits - 1) for name, e in t.exponents.items()}


class FirmwareController:
    """:class:`FirmwareTables` run sample by sample on arrays of independent runs (the exported C in numpy).

    Parameters
    ----------
    tables : FirmwareTables
    runs : int
        Number of independent runs stepped together.
    """

    def __init__(self, tables: FirmwareTables, runs: int = 1) -> None:
        self.t = tables
        self.runs = int(runs)
        self._at: tuple[np.ndarray, tuple[np.ndarray, ...]] | None = None    # the last speeds and their tables
        self.reset()

    def reset(self) -> None:
        """``assist_init``: every state zero, the next step is the first."""
        R, n = self.runs, self.t.n
        self.first = True
        self.xhat = np.zeros((R, n))
        self.e = np.zeros(R)
        self.bhat = np.zeros(R)
        self.r = np.zeros(R)        # corrected gyro of the last sample
        self.rc = np.zeros(R)       # reference-model output of the last sample
        self.u = np.zeros(R)        # applied yaw moment of the last sample
        self.mz = np.zeros(R)       # unsaturated yaw moment of the last sample (u when not saturated)
        self.raw = np.zeros(R)      # raw command of the last sample
        self.monitor = np.zeros(R)  # low-passed gyro minus wheel-speed yaw rate
        self.mode = np.zeros(R, dtype=int)
        self.frozen = np.zeros(R)   # bias estimate at the alarm

    def tables_at(self, speed: Any) -> tuple[np.ndarray, ...]:
        """Tables interpolated linearly at each run's speed (held outside the grid).

        Parameters
        ----------
        speed : array_like (runs,)
            m/s.

        Returns
        -------
        tuple of ndarray
            ``(phi_minus_i, gamma, k_int, k_psi, feedforward)``, leading axis the runs.
        """
        s = self.t.speeds
        u = np.clip(np.broadcast_to(np.asarray(speed, dtype=float), (self.runs,)), s[0], s[-1])
        if len(s) == 1:
            i, w = np.zeros(self.runs, dtype=int), np.zeros(self.runs)
        else:
            i = np.clip(np.searchsorted(s, u, side="right") - 1, 0, len(s) - 2)
            w = (u - s[i]) / (s[i + 1] - s[i])
        out = []
        for name in FirmwareTables.TABLES:
            tab = getattr(self.t, name)
            a = tab[i]
            b = tab[np.minimum(i + 1, len(s) - 1)]
            ww = w.reshape((-1,) + (1,) * (tab.ndim - 1))
            out.append(a + ww * (b - a))
        return tuple(out)

    def _monitor(self, speed: np.ndarray, g: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The sensor monitor and the degraded mode: the yaw-rate readings the controller then uses."""
        t = self.t
        self.monitor = self.monitor + t.monitor_gain * ((g - w) - self.monitor)
        alarm = (self.mode == 0) & (np.abs(self.monitor - self.bhat) > MONITOR_THRESHOLD_DEG_S * math.pi / 180)
        wheel_bad = np.abs(w) * t.track >= WHEEL_PLAUSIBLE * np.maximum(np.abs(speed), PLAUSIBLE_MIN_SPEED)
        self.mode = np.where(alarm, np.where(wheel_bad, 2, 1), self.mode)
        self.frozen = np.where(alarm, self.bhat, self.frozen)
        g_in = np.where(self.mode == 1, w, g)
        w_in = np.where(self.mode == 1, w, np.where(self.mode == 2, g - self.frozen, w))
        return g_in, w_in

    def step(self, speed: Any, command: Any, gyro: Any, wheel: Any) -> np.ndarray:
        """``assist_step`` for every run: the differential torque per wheel for this sample (N m).

        Parameters
        ----------
        speed : array_like
            Forward speed, m/s.
        command : array_like
            Raw yaw-rate command, rad/s.
        gyro : array_like
            Gyro reading, rad/s.
        wheel : array_like
            Yaw rate from the drive wheels' speeds, rad/s.

        Returns
        -------
        ndarray (runs,)
            ``tau`` (left wheel ``+tau``, right ``-tau``), N m.
        """
        t = self.t
        sp = np.asarray(speed, dtype=float)
        if self._at is None or not np.array_equal(sp, self._at[0]):     # the speeds changed: interpolate again
            self._at = (sp.copy(), self.tables_at(sp))
        dphi, gam, kint, kpsi, ff = self._at[1]
        g = np.broadcast_to(np.asarray(gyro, dtype=float), (self.runs,))
        w = np.broadcast_to(np.asarray(wheel, dtype=float), (self.runs,))
        c = np.broadcast_to(np.asarray(command, dtype=float), (self.runs,))
        g, w = self._monitor(np.broadcast_to(np.asarray(speed, dtype=float), (self.runs,)), g, w)
        if not self.first:
            err = self.r - self.rc
            excess = np.where(self.raw != 0.0, self.mz - self.u, 0.0)
            inc = t.sample_time * err
            if t.anti_windup == "conditional":
                inc = np.where((excess != 0.0) & (-kpsi * err * excess > 0), 0.0, inc)
            elif t.anti_windup == "back-calculation":
                inc = np.where(excess != 0.0, inc + t.windup_gain * excess / kpsi, inc)
            self.e = self.e + inc
            self.xhat = self.xhat + np.einsum("rij,rj->ri", dphi, self.xhat) + gam[:, :, 0] * self.u[:, None] \
                + gam[:, :, 1] * self.r[:, None]
        self.bhat = self.bhat + t.bias_gain * ((g - w) - self.bhat)
        self.r = g - self.bhat
        if self.first:
            mz = np.zeros(self.runs)
            tau = np.zeros(self.runs)
            u = np.zeros(self.runs)
        else:
            mz = -np.einsum("ri,ri->r", kint, self.xhat) - kpsi * self.e + ff * self.rc
            tau = np.clip(mz * t.torque_per_moment, -t.torque_limit, t.torque_limit)
            u = tau / t.torque_per_moment
            mz = np.where(np.abs(tau) >= t.torque_limit, mz, u)
        self.u, self.mz = u, mz
        self.rc = self.rc + t.command_gain * (c - self.rc)
        self.raw = c.copy()
        self.first = False
        return tau


def mirror_outputs(t: FirmwareTables, inputs: np.ndarray) -> np.ndarray:
    """Run rows ``speed, command, gyro, wheel`` through :class:`FirmwareController` (float64): ``tau`` (N m).

    Parameters
    ----------
    t : FirmwareTables
    inputs : ndarray (N, 4)

    Returns
    -------
    ndarray (N,)
    """
    fc = FirmwareController(t)
    return np.array([fc.step(*row)[0] for row in inputs])
