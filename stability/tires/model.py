"""The tested-tire force model: cubic fits (4-1) per whole degree of slip, interpolated as WCHAIR's MECHAN.

:func:`_segment_force` is the force law (also used by :class:`~stability.tires.stack.TireStack`
and the compiled simulator); :class:`Tire` wraps it with range policies, stiffness,
camber (eq 4-2) and rolling resistance (Appendix B, eq 3-2).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .data import CASTER_TIRES, FZ_MAX_N, MAIN_TIRES, SLIP_MAX_DEG, Coef3
from .fit import camber_coefficient_fit
from .ranges import POLICIES, Policy, TireRangeWarning, _check_policy, _range_message

__all__ = ["Tire"]

_DEG_PER_RAD = 180.0 / math.pi


def _segment_force(segments: tuple, s: NDArray[np.float64], fz: NDArray[np.float64],
                   offset: Any = None) -> NDArray[np.float64]:
    """Magnitude of the interpolated cornering force (N): the force law of WCHAIR's MECHAN.

    ``segments`` are the columns ``a0, b0, c0, da, db, dc`` of one-degree
    segments (8 per tire, tires end to end, ``offset`` selecting the tire);
    ``s`` the slip magnitude (deg, already limited as the policy says) and
    ``fz`` the normal force (N).  Interpolating the coefficients linearly
    in slip and evaluating one cubic equals interpolating the forces, since
    the force is linear in the coefficients.  ``fz <= 0`` gives 0 (a wheel
    off the ground); NaN in gives NaN out.
    """
    fzp = np.maximum(fz, 0.0)
    i = np.floor(s)
    np.fmin(i, 7.0, out=i)                   # NaN slip -> segment 7 (t stays NaN: NaN force)
    t = s - i
    ii = i.astype(np.intp)
    if offset is not None:
        ii += offset
    a0, b0, c0, da, db, dc = segments
    c = c0.take(ii)
    c += t * dc.take(ii)
    b = b0.take(ii)
    b += t * db.take(ii)
    a = a0.take(ii)
    a += t * da.take(ii)
    c *= fzp
    c += b
    c *= fzp
    c += a
    c *= fzp
    return c


class _CamberForce:
    """Eq (4-2), shared by :class:`Tire` and :class:`LinearTire` (which supply
    ``lateral_force`` and ``camber_coefficient``)."""

    if TYPE_CHECKING:
        @property
        def camber_coefficient(self) -> float: ...

        def lateral_force(self, slip_deg: ArrayLike, fz: ArrayLike, *, policy: Policy = "clamp",
                          warn: bool = True) -> Any: ...

    def camber_force(
        self,
        camber_deg: ArrayLike,
        fz: ArrayLike,
        camber_coefficient: float | None = None,
        *,
        policy: Policy = "clamp",
        warn: bool = True,
    ) -> Any:
        """Camber force (N), eq (4-2): ``f_c * F_y(alpha = gamma, fz)``.

        ``F_y`` is the cornering force of :meth:`lateral_force` at a slip
        angle equal to the camber angle (``f_c * C * gamma`` for a
        :class:`LinearTire`). The force has the sign of
        ``camber_deg`` (it acts toward the side to which the wheel leans);
        the caller maps it onto the vehicle axes. Differences from WCHAIR,
        which uses ``POLYFT(TIRY, INT(CAMANG), FZ)`` unscaled: here the
        camber angle is interpolated and ``lateral_scale`` applies.

        Parameters
        ----------
        camber_deg : float or array_like
            Camber angle(s), deg.
        fz : float or array_like
            Normal force(s), N.
        camber_coefficient : float, optional
            ``f_c``; defaults to :attr:`camber_coefficient`.
        policy, warn
            As for :meth:`lateral_force`.

        Returns
        -------
        float or ndarray
            N.
        """
        fc = self.camber_coefficient if camber_coefficient is None else float(camber_coefficient)
        return -fc * self.lateral_force(camber_deg, fz, policy=policy, warn=warn)


@dataclass(frozen=True)
class Tire(_CamberForce):
    """A tested tire: cubic fits (4-1) per integer slip angle.

    Use :func:`get` to build one. Instances are immutable; :meth:`scaled`
    returns a new tire.

    Attributes
    ----------
    name : str
        Abbreviation of Table 3-1.
    rows : tuple of (a, b, c)
        Published (OCR-corrected) coefficients for slip 0..8 deg, row 0 zero.
    intercepts : tuple of float
        Discarded constant terms ``d`` for slip 0..8 deg (row 0 zero).
    rolling : (a, b, c) or None
        Rolling-resistance cubic of Appendix B (None for PU).
    f_r : float or None
        Linear coefficient of rolling resistance, Table 3-2 (None for PU).
    lateral_scale, rolling_scale : float
        Multipliers of the lateral and rolling forces (WCHAIR's TYMOD/CYMOD
        and TXMOD/CXMOD, chapter 7).
    """

    name: str
    rows: tuple[Coef3, ...]
    intercepts: tuple[float, ...]
    rolling: Coef3 | None
    f_r: float | None
    lateral_scale: float = 1.0
    rolling_scale: float = 1.0
    _array: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _segments: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if len(self.rows) != 9:
            raise ValueError(f"rows must have 9 entries (slip 0..8 deg), got {len(self.rows)}")
        arr = np.array(self.rows, dtype=float)
        arr.flags.writeable = False
        object.__setattr__(self, "_array", arr)
        # per 1-deg segment k: coefficients at k and their increment to k+1, as 1-D columns
        # (interpolating the coefficients then evaluating one cubic equals interpolating the
        # forces, since the force is linear in the coefficients)
        base, step = arr[:8], arr[1:] - arr[:8]
        segs = tuple(np.ascontiguousarray(col) for col in (*base.T, *step.T))
        for col in segs:
            col.flags.writeable = False
        object.__setattr__(self, "_segments", segs)

    # -- identity ---------------------------------------------------------
    @property
    def is_caster(self) -> bool:
        """True for the caster tires ER and PU."""
        return self.name in CASTER_TIRES

    @property
    def coefficients(self) -> NDArray[np.float64]:
        """``(9, 3)`` array of ``(a, b, c)`` for slip 0..8 deg (row 0 zero).

        Units: a [-], b [1/N], c [1/N^2]; force in N for F_z in N (eq 4-1).
        A fresh copy; modifying it does not change the tire.
        """
        return np.array(self._array)

    # -- lateral force ------------------------------------------------------
    def lateral_force(
        self,
        slip_deg: ArrayLike,
        fz: ArrayLike,
        *,
        policy: Policy = "clamp",
        warn: bool = True,
    ) -> Any:
        """Cornering force (N) at slip angle ``slip_deg`` and normal force ``fz``.

        ``F(s) = (s - I) (F_{I+1} - F_I) + F_I`` with ``I = int(s)``,
        ``s = |slip|``, ``F_0 = 0`` and ``F_k`` the cubic (4-1) of slip ``k``
        at ``fz`` -- subroutine MECHAN / function POLYFT of WCHAIR (Appendix
        C). The result is ``-sign(slip) * F * lateral_scale``.

        Parameters
        ----------
        slip_deg : float or array_like
            Slip angle(s), deg (any sign).
        fz : float or array_like
            Normal force(s), N; broadcast against ``slip_deg``. ``fz <= 0``
            (wheel off the ground) gives zero force.
        policy : {"clamp", "extrapolate", "raise"}
            Outside the fitted range (``|slip| > 8 deg`` or ``fz > 450 N``):
            ``"clamp"`` evaluates at 8 deg / 450 N; ``"extrapolate"`` extends
            the 7-8 deg segment linearly in slip and uses the cubic as is in
            ``fz`` (what WCHAIR computes); ``"raise"`` raises ValueError.
        warn : bool
            With ``"clamp"``/``"extrapolate"``, emit one
            :class:`TireRangeWarning` per call that had out-of-range points.

        Returns
        -------
        float or ndarray
            Python float for scalar inputs, else an ndarray of the broadcast
            shape.

        Raises
        ------
        ValueError
            Unknown ``policy``, or ``policy="raise"`` with an out-of-range
            input (the message names the quantity, value and range).
        """
        if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
            return self._lateral_scalar(float(slip_deg), float(fz), policy, warn)
        return self._lateral_array(slip_deg, fz, policy, warn)

    def _lateral_scalar(self, slip: float, fz: float, policy: str, warn: bool) -> float:
        if policy not in POLICIES:
            _check_policy(policy)
        if slip != slip or fz != fz:
            return math.nan
        s = slip if slip >= 0.0 else -slip
        if fz <= 0.0 or s == 0.0:
            return 0.0
        bad_s = s > SLIP_MAX_DEG
        bad_f = fz > FZ_MAX_N
        if bad_s or bad_f:
            if policy == "raise":
                if bad_s:
                    raise ValueError(
                        f"slip angle {slip!r} deg is outside the fitted range "
                        f"[-{SLIP_MAX_DEG:g}, {SLIP_MAX_DEG:g}] deg (tire {self.name})"
                    )
                raise ValueError(
                    f"normal force {fz!r} N is outside the fitted range "
                    f"[0, {FZ_MAX_N:g}] N (tire {self.name})"
                )
            if policy == "clamp":
                if bad_s:
                    s = SLIP_MAX_DEG
                if bad_f:
                    fz = FZ_MAX_N
            if warn:
                warnings.warn(
                    f"Tire {self.name} lateral_force: "
                    + _range_message(int(bad_s), int(bad_f), 1, policy),
                    TireRangeWarning,
                    stacklevel=3,
                )
        i = int(s)
        if i > 7:
            i = 7
        a0, b0, c0 = self.rows[i]
        a1, b1, c1 = self.rows[i + 1]
        f0 = fz * (a0 + fz * (b0 + fz * c0))
        f1 = fz * (a1 + fz * (b1 + fz * c1))
        force = ((s - i) * (f1 - f0) + f0) * self.lateral_scale
        return -force if slip > 0.0 else force

    def _lateral_array(self, slip_deg: ArrayLike, fz: ArrayLike, policy: str, warn: bool) -> NDArray[np.float64]:
        _check_policy(policy)
        slip, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
        s = np.abs(slip)
        bad_s = s > SLIP_MAX_DEG
        bad_f = f > FZ_MAX_N
        n_s, n_f = int(bad_s.sum()), int(bad_f.sum())
        if n_s or n_f:
            if policy == "raise":
                if n_s:
                    v = float(slip[bad_s].flat[0])
                    raise ValueError(
                        f"slip angle {v!r} deg is outside the fitted range "
                        f"[-{SLIP_MAX_DEG:g}, {SLIP_MAX_DEG:g}] deg (tire {self.name}; "
                        f"{n_s} such point(s))"
                    )
                v = float(f[bad_f].flat[0])
                raise ValueError(
                    f"normal force {v!r} N is outside the fitted range [0, {FZ_MAX_N:g}] N "
                    f"(tire {self.name}; {n_f} such point(s))"
                )
            if policy == "clamp":
                s = np.minimum(s, SLIP_MAX_DEG)
                f = np.minimum(f, FZ_MAX_N)
            if warn:
                warnings.warn(
                    f"Tire {self.name} lateral_force: "
                    + _range_message(n_s, n_f, int(s.size), policy),
                    TireRangeWarning,
                    stacklevel=3,
                )
        force = _segment_force(self._segments, s, f)
        if self.lateral_scale != 1.0:
            force = force * self.lateral_scale
        return np.where(slip > 0.0, -force, force) + 0.0

    # -- stiffness ------------------------------------------------------------
    def cornering_stiffness(self, fz: ArrayLike, *, include_intercept: bool = False) -> Any:
        """Cornering stiffness ``C_alpha`` (N/deg) at normal force ``fz``.

        The slope of the interpolated force curve between 0 and 1 deg, i.e.
        ``F(1 deg, fz) / 1 deg`` -- the method of Table 4-1 (eq 3-1).

        Parameters
        ----------
        fz : float or array_like
            Normal force, N (not range-limited; ``fz <= 0`` gives 0).
        include_intercept : bool
            Add the discarded constant ``d`` of the 1 deg fit. Table 4-1 was
            evidently computed with it: with ``True`` all 42 published values
            are reproduced to their printed rounding; without it (the force
            model actually used by WCHAIR and :meth:`lateral_force`) EJA
            differs by +2.0 % at 75 N and PU by -1.1 % at 75 N.

        Returns
        -------
        float or ndarray
            N/deg, times ``lateral_scale``.
        """
        a, b, c = self.rows[1]
        d = self.intercepts[1] if include_intercept else 0.0
        if isinstance(fz, (int, float)):
            fz = float(fz)
            if fz <= 0.0:
                return 0.0
            return (fz * (a + fz * (b + fz * c)) + d) * self.lateral_scale
        f = np.asarray(fz, dtype=float)
        out = (f * (a + f * (b + f * c)) + d) * self.lateral_scale
        return np.where(f > 0.0, out, 0.0)

    def cornering_stiffness_per_rad(self, fz: ArrayLike, *, include_intercept: bool = False) -> Any:
        """Cornering stiffness in N/rad (:meth:`cornering_stiffness` * 180/pi)."""
        c = self.cornering_stiffness(fz, include_intercept=include_intercept)
        return c * _DEG_PER_RAD

    # -- camber -----------------------------------------------------------------
    @property
    def has_camber_data(self) -> bool:
        """True for the five main tires (camber tested, Figures 3-7a..e)."""
        return self.name in MAIN_TIRES

    @property
    def camber_coefficient(self) -> float:
        """Camber coefficient ``f_c`` of eq (4-2), from Figure 4-3's method.

        See :func:`camber_coefficient_fit`. Raises ValueError for the casters,
        which were not tested for camber.
        """
        if not self.has_camber_data:
            raise ValueError(
                f"tire {self.name!r} is a caster and has no camber data (Appendix B tests "
                f"camber only for {MAIN_TIRES}); pass camber_coefficient= explicitly"
            )
        return camber_coefficient_fit(self.name)

    # -- rolling resistance -----------------------------------------------------
    def rolling_resistance(self, fz: ArrayLike) -> Any:
        """Magnitude of the rolling-resistance force (N), Appendix B cubic.

        ``|a F_z + b F_z**2 + c F_z**3| * rolling_scale`` (WCHAIR takes the
        magnitude with ``SIGN(..., -V)``); zero for ``fz <= 0``. The cubic is
        used as is above 450 N.

        Raises
        ------
        ValueError
            For PU, which has no rolling data (WCHAIR uses the ER
            coefficients for every caster).
        """
        if self.rolling is None:
            raise ValueError(
                f"tire {self.name!r} has no rolling-resistance data (chapter 3: only one PU "
                "caster was available); WCHAIR uses the ER caster coefficients"
            )
        a, b, c = self.rolling
        if isinstance(fz, (int, float)):
            fz = float(fz)
            if fz <= 0.0:
                return 0.0
            return abs(fz * (a + fz * (b + fz * c))) * self.rolling_scale
        f = np.asarray(fz, dtype=float)
        out = np.abs(f * (a + f * (b + f * c))) * self.rolling_scale
        return np.where(f > 0.0, out, 0.0)

    @property
    def rolling_coefficient_linear(self) -> float:
        """Coefficient of rolling resistance ``f_r`` of Table 3-2 (eq 3-2).

        Not scaled by ``rolling_scale``. Raises ValueError for PU.
        """
        if self.f_r is None:
            raise ValueError(f"tire {self.name!r} has no rolling-resistance data (Table 3-2)")
        return self.f_r

    # -- scaling ----------------------------------------------------------------
    def scaled(self, lateral: float = 1.0, rolling: float = 1.0) -> Tire:
        """A copy with lateral and rolling forces multiplied by the factors.

        Chapter 7's TYMOD/CYMOD (lateral) and TXMOD/CXMOD (rolling); factors
        compound with any existing scaling.
        """
        return Tire(
            name=self.name,
            rows=self.rows,
            intercepts=self.intercepts,
            rolling=self.rolling,
            f_r=self.f_r,
            lateral_scale=self.lateral_scale * float(lateral),
            rolling_scale=self.rolling_scale * float(rolling),
        )
