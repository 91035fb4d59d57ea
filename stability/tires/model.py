"""The tested-tire force model: cubic fits (4-1) per whole degree of slip, interpolated as WCHAIR's MECHAN.

:class:`Tire` holds a tested tire's table and evaluates the one force law of
:mod:`stability.tires.law` (which the compiled simulator runs too) with range
policies and warnings; stiffness, camber (eq 4-2) and rolling resistance
(Appendix B, eq 3-2) use the same law.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stability.tires import law
from stability.tires.base import TireCapabilities, _CamberForce
from stability.tires.data import CASTER_TIRES, FZ_MAX_N, MAIN_TIRES, SLIP_MAX_DEG, Coef3
from stability.tires.fit import camber_coefficient_fit
from stability.tires.ranges import POLICIES, Policy, TireRangeWarning, _check_policy, _range_message, limit_load

__all__ = ["THESIS_SOURCE", "Tire"]

#: :attr:`Tire.source` of the seven tires tested in the thesis.
THESIS_SOURCE = "Collins (1987), Appendix B"

_DEG_PER_RAD = 180.0 / math.pi


def law_on_arrays(fn: Any, *arrays: NDArray[np.float64], scalar: bool) -> Any:
    """A scalar function of :mod:`stability.tires.law` over broadcast arrays, element by element.

    Parameters
    ----------
    fn : callable
        ``fn(*floats) -> float``.
    *arrays : ndarray
        Its arguments (broadcast together).
    scalar : bool
        Return a Python float (the inputs were numbers).

    Returns
    -------
    float or ndarray
        ``fn`` at every element, of the broadcast shape.
    """
    out = np.asarray(np.frompyfunc(lambda *x: float(fn(*x)), len(arrays), 1)(*arrays), dtype=float)
    return float(out) if scalar else out


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
    slip_max_deg, fz_max_N : float
        The fitted range: largest slip angle (deg) and normal load (N) with
        data (8 deg and WCHAIR's 450 N for the thesis tires; a user tire's own,
        :func:`stability.tires.load_tire_data`). Outside it the policies apply.
    source : str
        Where the data come from (the thesis, or a user's file).
    camber_coef : float or None
        A given camber coefficient ``f_c`` (user tires); the thesis main tires
        use :func:`camber_coefficient_fit`.
    fit_quality : FitQuality or None
        Fit statistics per slip angle of a user tire (None for the thesis tires).
    """

    name: str
    rows: tuple[Coef3, ...]
    intercepts: tuple[float, ...]
    rolling: Coef3 | None
    f_r: float | None
    lateral_scale: float = 1.0
    rolling_scale: float = 1.0
    slip_max_deg: float = SLIP_MAX_DEG
    fz_max_N: float = FZ_MAX_N
    source: str = THESIS_SOURCE
    camber_coef: float | None = None
    fit_quality: Any = field(default=None, repr=False, compare=False)
    _array: NDArray[np.float64] = field(init=False, repr=False, compare=False)
    _segments: tuple = field(init=False, repr=False, compare=False)
    _table: NDArray[np.float64] = field(init=False, repr=False, compare=False)

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
        table = np.array(segs)              # (6, 8): the law's segment table (stability.tires.law)
        table.flags.writeable = False
        object.__setattr__(self, "_table", table)

    # -- identity ---------------------------------------------------------
    @property
    def is_thesis_tire(self) -> bool:
        """True for the seven tires tested in the thesis (Table 3-1)."""
        return self.source == THESIS_SOURCE

    @property
    def is_caster(self) -> bool:
        """True for the caster tires ER and PU."""
        return self.is_thesis_tire and self.name in CASTER_TIRES

    @property
    def capabilities(self) -> TireCapabilities:
        """Which data this tire has (cornering always; camber and rolling resistance maybe)."""
        return TireCapabilities(name=self.name, camber=self.has_camber_data, rolling=self.rolling is not None)

    def segment_arrays(self) -> tuple[NDArray[np.float64], ...]:
        """The force law as plain arrays, for compiled kernels.

        Returns
        -------
        tuple of 6 ndarray
            ``a0, b0, c0, da, db, dc``, each of length 8 (read-only): segment
            ``k`` (slip ``k..k+1`` deg) has coefficients ``a0[k] + t da[k]`` etc.
            with ``t = s - k``, and the force magnitude (before ``lateral_scale``)
            is ``F = ((c fz + b) fz + a) fz`` with ``fz = max(F_z, 0)``, ``k =
            min(floor(s), 7)`` -- exactly :func:`stability.tires.law.segment_force`.
        """
        return self._segments

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
        _check_policy(policy)
        table, scale, code = self._table, self.lateral_scale, POLICIES.index(policy)
        lim = (self.slip_max_deg, self.fz_max_N)
        if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
            force, refused = law.lateral_force(law.TESTED, table, scale, lim, float(slip_deg), float(fz), code)
            bad_s, bad_f = abs(slip_deg) > lim[0], fz > lim[1]
            if bad_s or bad_f:
                self._out_of_range(policy, warn, float(slip_deg if bad_s else fz), bad_s, int(bad_s), int(bad_f), 1)
            return float(force)
        slip, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
        bad = np.abs(slip) > lim[0]
        badf = f > lim[1]
        n_s, n_f = int(bad.sum()), int(badf.sum())
        if n_s or n_f:
            self._out_of_range(policy, warn, float((slip[bad] if n_s else f[badf]).flat[0]), bool(n_s), n_s, n_f,
                               int(slip.size))
        return law_on_arrays(lambda x, y: law.lateral_force(law.TESTED, table, scale, lim, x, y, code)[0],
                             slip, f, scalar=False)

    def _out_of_range(self, policy: str, warn: bool, value: float, is_slip: bool, n_s: int, n_f: int,
                      n: int) -> None:
        """``policy="raise"``: raise for the first value outside the fitted range; else warn (``warn``)."""
        if policy == "raise":
            self._refuse(value, is_slip, n_s or n_f)
        if warn:
            self._warn(n_s, n_f, n, policy)

    def _refuse(self, value: float, is_slip: bool, n: int) -> None:
        """Raise the one-line ValueError of ``policy="raise"`` (slip or load ``value``)."""
        more = f"; {n} such point(s)" if n > 1 else ""
        if is_slip:
            smax = self.slip_max_deg
            raise ValueError(f"slip angle {value!r} deg is outside the fitted range "
                             f"[-{smax:g}, {smax:g}] deg (tire {self.name}{more})")
        raise ValueError(f"normal force {value!r} N is outside the fitted range "
                         f"[0, {self.fz_max_N:g}] N (tire {self.name}{more})")

    def _warn(self, n_s: int, n_f: int, n: int, policy: str) -> None:
        msg = _range_message(n_s, n_f, n, policy, self.slip_max_deg, self.fz_max_N)
        warnings.warn(f"Tire {self.name} lateral_force: {msg}", TireRangeWarning, stacklevel=4)

    # -- stiffness ------------------------------------------------------------
    def cornering_stiffness(self, fz: ArrayLike, *, include_intercept: bool = False,
                            policy: str | None = None, wheel: str | None = None) -> Any:
        """Cornering stiffness ``C_alpha`` (N/deg) at normal force ``fz``.

        The slope of the interpolated force curve between 0 and 1 deg, i.e.
        ``F(1 deg, fz) / 1 deg`` -- the method of Table 4-1 (eq 3-1).

        Parameters
        ----------
        fz : float or array_like
            Normal force, N (``fz <= 0`` gives 0). Above :attr:`fz_max_N` the
            tire-range policy applies (:mod:`stability.tires.ranges`).
        policy : {"warn", "raise", "clamp"}, optional
            Tire-range policy; default the one in force
            (:func:`stability.tires.get_policy`, ``"warn"``: the cubic as is,
            with a warning and a :class:`RangeNote`).
        wheel : str, optional
            Named in the range note (e.g. ``"caster_left"``).
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
        fz = limit_load(self, fz, policy, wheel)
        if isinstance(fz, (int, float)):
            fz = float(fz)
            if fz <= 0.0:
                return 0.0
            return (law.cubic(a, b, c, fz) + d) * self.lateral_scale
        f = np.asarray(fz, dtype=float)
        return np.where(f > 0.0, (law.cubic(a, b, c, f) + d) * self.lateral_scale, 0.0)

    def cornering_stiffness_per_rad(self, fz: ArrayLike, *, include_intercept: bool = False,
                                    policy: str | None = None, wheel: str | None = None) -> Any:
        """Cornering stiffness in N/rad (:meth:`cornering_stiffness` * 180/pi; same arguments)."""
        c = self.cornering_stiffness(fz, include_intercept=include_intercept, policy=policy, wheel=wheel)
        return c * _DEG_PER_RAD

    # -- camber -----------------------------------------------------------------
    @property
    def has_camber_data(self) -> bool:
        """True for the five thesis main tires (Figures 3-7a..e) or when ``camber_coef`` is given."""
        return self.camber_coef is not None or (self.is_thesis_tire and self.name in MAIN_TIRES)

    @property
    def camber_coefficient(self) -> float:
        """Camber coefficient ``f_c`` of eq (4-2), from Figure 4-3's method.

        See :func:`camber_coefficient_fit`; ``camber_coef`` when given. Raises
        ValueError for the casters, which were not tested for camber, and for
        user tires loaded without one.
        """
        if self.camber_coef is not None:
            return self.camber_coef
        if not self.has_camber_data:
            what = ("is a caster and has no camber data (Appendix B tests camber only for "
                    f"{MAIN_TIRES})" if self.is_thesis_tire else f"({self.source}) has no camber coefficient")
            raise ValueError(f"tire {self.name!r} {what}; pass camber_coefficient= explicitly")
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
            raise ValueError(self._no_rolling())
        coef, scale = self.rolling, self.rolling_scale
        return law_on_arrays(lambda f: law.rolling_resistance(law.ROLLING_CUBIC, coef, scale, f),
                             np.asarray(fz, dtype=float), scalar=isinstance(fz, (int, float)))

    def rolling_force(self, fz: float, vx: float) -> float:
        """Rolling-resistance force along the wheel's heading (N), opposing its rolling velocity ``vx`` (m/s).

        :meth:`rolling_resistance` at ``fz`` (N) with the sign of ``-vx``
        (WCHAIR's ``SIGN(..., -V)``; :func:`stability.tires.law.rolling_force`).
        """
        if self.rolling is None:
            raise ValueError(self._no_rolling())
        return float(law.rolling_force(law.ROLLING_CUBIC, self.rolling, self.rolling_scale, float(fz), float(vx)))

    @property
    def rolling_coefficient_linear(self) -> float:
        """Coefficient of rolling resistance ``f_r`` of Table 3-2 (eq 3-2).

        Not scaled by ``rolling_scale``. Raises ValueError for PU.
        """
        if self.f_r is None:
            raise ValueError(self._no_rolling())
        return self.f_r

    def _no_rolling(self) -> str:
        if self.is_thesis_tire:
            return (f"tire {self.name!r} has no rolling-resistance data (chapter 3, Table 3-2: only one PU "
                    "caster was available); WCHAIR uses the ER caster coefficients")
        return f"tire {self.name!r} ({self.source}) has no rolling-resistance data; pass rolling_coefficient="

    # -- scaling ----------------------------------------------------------------
    def scaled(self, lateral: float = 1.0, rolling: float = 1.0) -> Tire:
        """A copy with lateral and rolling forces multiplied by the factors.

        Chapter 7's TYMOD/CYMOD (lateral) and TXMOD/CXMOD (rolling); factors
        compound with any existing scaling.

        The copy shares this tire's fields, among them the read-only arrays ``__post_init__`` derives from
        ``rows`` alone, instead of rebuilding them (:func:`dataclasses.replace` would: about 28 us a call, and the
        shimmy and statics searches ask for a chair's scaled tires tens of thousands of times); only the two
        scales differ, computed as before.
        """
        out = object.__new__(type(self))
        out.__dict__.update(self.__dict__)
        object.__setattr__(out, "lateral_scale", self.lateral_scale * float(lateral))
        object.__setattr__(out, "rolling_scale", self.rolling_scale * float(rolling))
        return out
