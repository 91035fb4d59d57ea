"""Treadmill tire data and the empirical tire-force model of Collins (1987).

This module turns the tire tests of chapter 3 and Appendix B of the thesis into
force functions for the planar wheelchair models:

* **cornering (lateral) force** -- equation (4-1),
  ``F_y = a F_z + b F_z**2 + c F_z**3`` with one set of constants per integer
  slip angle 1..8 deg, linearly interpolated between integer slip angles
  exactly as subroutine MECHAN / function POLYFT of program WCHAIR do
  (Appendix C, chapter 7);
* **cornering stiffness** -- Table 4-1 and Figure 4-2, the slope of the
  interpolated curve between 0 and 1 deg;
* **camber force** -- equation (4-2), ``f_c * F_y(alpha = gamma, F_z)`` with
  the camber coefficient ``f_c = 1/m`` of Figure 4-3;
* **rolling resistance** -- the Appendix B cubic in ``F_z`` and the linear
  coefficient ``f_r`` of Table 3-2 (equation 3-2).

Units: forces in newtons, angles in degrees (``*_per_rad`` helpers convert),
normal force ``fz`` in newtons.

The numbers live in ``stability/data/tires/*.csv``; ``provenance.md`` beside
them lists every OCR correction with its evidence. The published coefficients
are reproduced to about 1e-6 (relative) by :func:`refit` with
``method="pwrstar"`` (ordinary least squares of the four-term cubic with the
point ``(0, 0)`` appended to the six measurements, constant term then
discarded), which is how every disputed digit was settled.

Sign convention: :meth:`Tire.lateral_force` returns ``-sign(slip) * F``; a
positive slip angle gives a negative (restoring) force, as WCHAIR's
``SIGN(F, -V)`` makes the force oppose the lateral velocity of the wheel.

Examples
--------
>>> from stability import tires
>>> ag = tires.get("ag")
>>> round(ag.cornering_stiffness(150.0), 1)        # Table 4-1: 39.7 N/deg
39.7
>>> ag.lateral_force(2.5, 200.0) < 0
True
>>> tires.get("linear:30").lateral_force(-1.0, 200.0)
30.0
"""

from __future__ import annotations

import csv
import functools
import math
import warnings
from dataclasses import dataclass, field
from importlib import resources
from typing import Any, Literal, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "CASTER_TIRES",
    "FZ_MAX_N",
    "FZ_TESTED_MAX_1DEG_N",
    "LBF_TO_N",
    "LinearTire",
    "MAIN_TIRES",
    "POLICIES",
    "RefitResult",
    "SLIP_MAX_DEG",
    "TABLE_4_1_FZ_N",
    "Tire",
    "TireRangeWarning",
    "TireStack",
    "camber_coefficient_fit",
    "get",
    "names",
    "out_of_range",
    "raw_camber",
    "raw_cornering",
    "refit",
    "table_3_2",
    "table_4_1",
]

#: Pounds-force to newtons, the factor used throughout Appendix B.
LBF_TO_N = 4.44822
#: The five 24 inch main-wheel tires of Table 3-1.
MAIN_TIRES: tuple[str, ...] = ("AG", "EJP", "SS", "IM", "EJA")
#: The two caster tires of Table 3-1 (ER = Essem rubber, PU = polyurethane).
CASTER_TIRES: tuple[str, ...] = ("ER", "PU")
#: Largest tested slip angle (deg); WCHAIR warns above it (chapter 7).
SLIP_MAX_DEG = 8.0
#: Normal-force limit of WCHAIR (N, chapter 7 "the program checks that no
#: F_z value is greater than 450N").  Appendix B states 500 N; the raw data
#: reach about 475 N at 1 deg according to the thesis (the transcribed AG and
#: EJP 1 deg data actually reach 512 N).
FZ_MAX_N = 450.0
#: Largest normal force at 1 deg slip quoted in chapter 7 (N).
FZ_TESTED_MAX_1DEG_N = 475.0
#: Normal forces of Table 4-1 and Figures 4-1, 4-3 (N).
TABLE_4_1_FZ_N: tuple[float, ...] = (75.0, 150.0, 225.0, 300.0, 375.0, 450.0)
#: Out-of-range policies of :meth:`Tire.lateral_force`.
POLICIES: tuple[str, ...] = ("clamp", "extrapolate", "raise")

_DEG_PER_RAD = 180.0 / math.pi
_ALL = MAIN_TIRES + CASTER_TIRES
_REFIT_METHODS = ("with_intercept", "through_origin", "pwrstar")

Policy = Literal["clamp", "extrapolate", "raise"]
Coef3 = tuple[float, float, float]


class TireRangeWarning(UserWarning):
    """Warning: a tire force was asked for outside the tested range.

    Emitted at most once per call of :meth:`Tire.lateral_force` (and the
    methods built on it) when ``|slip| > 8 deg`` or ``F_z > 450 N`` and the
    policy is ``"clamp"`` or ``"extrapolate"``.
    """


# ---------------------------------------------------------------------------
# data loading (cached; the returned objects are immutable tuples)
# ---------------------------------------------------------------------------


@functools.cache
def _read_csv(filename: str) -> tuple[dict[str, str], ...]:
    """Rows of ``stability/data/tires/<filename>`` as a tuple of dicts."""
    path = resources.files("stability").joinpath("data", "tires", filename)
    with path.open("r", encoding="utf-8", newline="") as fh:
        return tuple(dict(row) for row in csv.DictReader(fh))


def _float(text: str) -> float:
    return float(text) if text.strip() else math.nan


@functools.cache
def _cornering_coefficients() -> dict[str, tuple[tuple[Coef3, ...], tuple[float, ...], tuple[float, ...]]]:
    """``{tire: (rows 0..8 of (a, b, c), d 0..8, R 1..8)}``; row 0 is zero."""
    out: dict[str, Any] = {}
    for name in _ALL:
        rows = sorted(
            (r for r in _read_csv("cornering_coefficients.csv") if r["tire"] == name),
            key=lambda r: int(r["slip_deg"]),
        )
        if [int(r["slip_deg"]) for r in rows] != list(range(1, 9)):
            raise RuntimeError(f"cornering_coefficients.csv: tire {name} lacks slip 1..8")
        abc = ((0.0, 0.0, 0.0),) + tuple(
            (float(r["a"]), float(r["b"]), float(r["c"])) for r in rows
        )
        d = (0.0,) + tuple(float(r["d"]) for r in rows)
        big_r = tuple(float(r["R"]) for r in rows)
        out[name] = (abc, d, big_r)
    return out


@functools.cache
def _rolling_coefficients() -> dict[str, Coef3]:
    return {
        r["tire"]: (float(r["a"]), float(r["b"]), float(r["c"]))
        for r in _read_csv("rolling_coefficients.csv")
    }


@functools.cache
def _table_3_2() -> dict[str, float]:
    return {r["tire"]: float(r["f_r"]) for r in _read_csv("table_3_2.csv")}


def table_3_2() -> dict[str, float]:
    """Coefficients of rolling resistance ``f_r`` of Table 3-2 (eq 3-2).

    Returns
    -------
    dict
        ``{tire: f_r}`` for the six tires with rolling data (no PU).
    """
    return dict(_table_3_2())


def table_4_1() -> dict[str, tuple[float, ...]]:
    """Published cornering stiffnesses of Table 4-1 (N/deg).

    Returns
    -------
    dict
        ``{tire: (C at 75, 150, 225, 300, 375, 450 N)}`` for the seven tires.
    """
    out: dict[str, list[float]] = {n: [] for n in _ALL}
    for r in sorted(_read_csv("table_4_1.csv"), key=lambda r: float(r["Fz_N"])):
        out[r["tire"]].append(float(r["C_N_per_deg"]))
    return {k: tuple(v) for k, v in out.items()}


def _raw(filename: str, angle_key: str, name: str | None) -> dict[str, NDArray[Any]]:
    rows = _read_csv(filename)
    if name is not None:
        name = _canonical(name)
        rows = tuple(r for r in rows if r["tire"] == name)
    return {
        "tire": np.array([r["tire"] for r in rows]),
        angle_key: np.array([int(r[angle_key]) for r in rows]),
        "W_lbf": np.array([_float(r["W_lbf"]) for r in rows]),
        "W_N": np.array([_float(r["W_N"]) for r in rows]),
        "Fz_lbf": np.array([_float(r["Fz_lbf"]) for r in rows]),
        "Fy_lbf": np.array([_float(r["Fy_lbf"]) for r in rows]),
        "Fz_N": np.array([_float(r["Fz_N"]) for r in rows]),
        "Fy_N": np.array([_float(r["Fy_N"]) for r in rows]),
        "flag": np.array([r["flag"] for r in rows]),
    }


def raw_cornering(name: str | None = None) -> dict[str, NDArray[Any]]:
    """Raw cornering-force data of Appendix B (Figures 3-4a..g).

    Parameters
    ----------
    name : str, optional
        Tire name; all seven tires when omitted.

    Returns
    -------
    dict of ndarray
        Columns ``tire, slip_deg, W_lbf, W_N, Fz_lbf, Fy_lbf, Fz_N, Fy_N,
        flag`` (fresh arrays). Missing values are NaN; ``flag`` is ``""``,
        ``"corrected"``, ``"partial"`` or ``"missing"`` (see provenance.md).
    """
    return _raw("cornering_raw.csv", "slip_deg", name)


def raw_camber(name: str | None = None) -> dict[str, NDArray[Any]]:
    """Raw camber-force data of Appendix B (Figures 3-7a..e).

    Parameters
    ----------
    name : str, optional
        Main-tire name; all five tires when omitted.

    Returns
    -------
    dict of ndarray
        As :func:`raw_cornering` with ``camber_deg`` instead of
        ``slip_deg``. ``flag == "outlier"`` marks the SS 2 deg, W = 227 lbf
        row (see :func:`camber_coefficient_fit`).
    """
    return _raw("camber_raw.csv", "camber_deg", name)


# ---------------------------------------------------------------------------
# refitting (chapter 4, "Empirical predictions of cornering force")
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class RefitResult:
    """Result of :func:`refit`.

    Attributes
    ----------
    angles_deg : ndarray of int
        Slip (or camber) angles, one per row of ``coefficients``.
    coefficients : ndarray
        ``(n, 3)`` ``(a, b, c)`` for ``"through_origin"``, ``(n, 4)``
        ``(a, b, c, d)`` otherwise (``d`` is the discarded constant term).
    n_points : ndarray of int
        Measurements used per angle (rows with NaN are skipped).
    rms_residual_N, max_abs_residual_N : ndarray
        Residuals of the measurements about the fitted polynomial *as used*
        (i.e. with ``d`` dropped), in N.
    r : ndarray
        Correlation coefficient ``sqrt(1 - SS_res/SS_tot)`` of the full fit
        over the points fitted (with ``"pwrstar"`` the origin is one of
        them, which reproduces the "R" column of Appendix B to 0.001).
    """

    angles_deg: NDArray[np.int_]
    coefficients: NDArray[np.float64]
    n_points: NDArray[np.int_]
    rms_residual_N: NDArray[np.float64]
    max_abs_residual_N: NDArray[np.float64]
    r: NDArray[np.float64]


def _fit_cubic(x: NDArray[np.float64], y: NDArray[np.float64], method: str) -> NDArray[np.float64]:
    if method == "through_origin":
        design = np.column_stack([x, x**2, x**3])
        return np.linalg.lstsq(design, y, rcond=None)[0]
    if method == "pwrstar":
        x = np.concatenate([[0.0], x])
        y = np.concatenate([[0.0], y])
    design = np.column_stack([x, x**2, x**3, np.ones_like(x)])
    return np.linalg.lstsq(design, y, rcond=None)[0]


def refit(
    name: str,
    *,
    method: str = "with_intercept",
    data: Literal["cornering", "camber"] = "cornering",
    include_outliers: bool = False,
) -> RefitResult:
    """Least-squares refit of the cubic (4-1) to the raw Appendix B data.

    One fit per slip angle (or camber angle), ``F_y`` against ``F_z`` in
    newtons, as chapter 4 describes for program PWRSTAR.

    Parameters
    ----------
    name : str
        Tire name (case-insensitive).
    method : {"with_intercept", "through_origin", "pwrstar"}
        ``"with_intercept"``: fit ``a, b, c, d`` to the six points, which is
        what the text of chapter 4 says PWRSTAR did (``d`` then dropped).
        ``"through_origin"``: fit ``a, b, c`` only. ``"pwrstar"``: fit
        ``a, b, c, d`` to the six points *plus the origin (0, 0)*.
        Only ``"pwrstar"`` reproduces the published Appendix B coefficients,
        including the printed ``d`` and ``R``, to printing precision (a, b, c
        within 4e-6 relative, median 1.3e-6, over the 54 complete blocks;
        forces at Fz = 75..450 N within 0.0012 %). ``"through_origin"`` is
        close (force differences median 0.09 %, max 1.3 %); the literal
        ``"with_intercept"`` fit is far off (median 48 %, max 381 %) and gives
        constant terms up to 190 N, contradicting the "about 1 N" of
        chapter 4. The two blocks with a missing measurement (IM 6 deg, ER
        1 deg) differ by 2.4 % and 2.75 % (pwrstar; 2.4 % and 2.9 % through
        the origin).
        The numbers are tabulated in ``provenance.md``.
    data : {"cornering", "camber"}
        Which raw table to fit (camber data exist for the main tires only).
    include_outliers : bool
        Include rows flagged ``"outlier"`` (the SS camber row).

    Returns
    -------
    RefitResult
        Coefficients per angle and residual statistics.

    Raises
    ------
    ValueError
        For an unknown ``method``/``data`` or a caster with ``data="camber"``.
    """
    name = _canonical(name)
    if method not in _REFIT_METHODS:
        raise ValueError(f"method={method!r} is not valid; choose one of {_REFIT_METHODS}")
    if data == "cornering":
        raw = raw_cornering(name)
        key = "slip_deg"
    elif data == "camber":
        if name in CASTER_TIRES:
            raise ValueError(f"name={name!r}: camber data exist only for the main tires {MAIN_TIRES}")
        raw = raw_camber(name)
        key = "camber_deg"
    else:
        raise ValueError(f"data={data!r} is not valid; choose one of ('cornering', 'camber')")
    angles = np.unique(raw[key])
    coefs, npts, rms, mx, rr = [], [], [], [], []
    for ang in angles:
        sel = (raw[key] == ang) & np.isfinite(raw["Fz_N"]) & np.isfinite(raw["Fy_N"])
        if not include_outliers:
            sel &= raw["flag"] != "outlier"
        x, y = raw["Fz_N"][sel], raw["Fy_N"][sel]
        c = _fit_cubic(x, y, method)
        res = y - (c[0] * x + c[1] * x**2 + c[2] * x**3)
        # R as PWRSTAR prints it: residuals of the full fit over the points
        # it was fitted to (the origin included for "pwrstar").
        xf, yf = (np.concatenate([[0.0], x]), np.concatenate([[0.0], y])) if method == "pwrstar" else (x, y)
        full = yf - (c[0] * xf + c[1] * xf**2 + c[2] * xf**3) - (c[3] if c.size == 4 else 0.0)
        ss_tot = float(np.sum((yf - yf.mean()) ** 2))
        coefs.append(c)
        npts.append(x.size)
        rms.append(float(np.sqrt(np.mean(res**2))))
        mx.append(float(np.max(np.abs(res))))
        rr.append(math.sqrt(max(0.0, 1.0 - float(np.sum(full**2)) / ss_tot)))
    return RefitResult(
        angles_deg=angles.astype(int),
        coefficients=np.array(coefs),
        n_points=np.array(npts),
        rms_residual_N=np.array(rms),
        max_abs_residual_N=np.array(mx),
        r=np.array(rr),
    )


@functools.cache
def camber_coefficient_fit(name: str, *, include_outliers: bool = False) -> float:
    """Camber coefficient ``f_c = 1/m`` by the method of Figure 4-3.

    The camber data of each angle ``gamma = 2, 5, 8 deg`` are fitted with the
    same cubic as the cornering data (:func:`refit`, ``method="pwrstar"``);
    camber force and cornering force (published coefficients at slip
    ``alpha = gamma``) are evaluated at ``F_z = 75, 150, ..., 450 N``; ``m`` is
    the least-squares slope through the origin of cornering force (vertical
    axis) against camber force (horizontal axis); ``f_c = 1/m`` (eq 4-2).

    Parameters
    ----------
    name : str
        Main-tire name.
    include_outliers : bool
        By default the SS 2 deg, W = 227 lbf row (F_y = 44.68 lbf = 198.74 N,
        ten times its neighbours, pound and newton columns consistent) is
        left out; with it SS gives ``f_c = 0.220``, outside the 1/8..1/5
        range stated in chapter 4, without it ``f_c = 0.197``.

    Returns
    -------
    float
        ``f_c`` (dimensionless).
    """
    name = _canonical(name)
    fit = refit(name, method="pwrstar", data="camber", include_outliers=include_outliers)
    rows = _cornering_coefficients()[name][0]
    fz = np.array(TABLE_4_1_FZ_N)
    cam, cor = [], []
    for gamma, c in zip(fit.angles_deg, fit.coefficients):
        cam.append(c[0] * fz + c[1] * fz**2 + c[2] * fz**3)
        a, b, cc = rows[int(gamma)]
        cor.append(a * fz + b * fz**2 + cc * fz**3)
    x = np.concatenate(cam)
    y = np.concatenate(cor)
    m = float(np.sum(x * y) / np.sum(x * x))
    return 1.0 / m


# ---------------------------------------------------------------------------
# range handling
# ---------------------------------------------------------------------------


def out_of_range(slip_deg: ArrayLike, fz: ArrayLike) -> tuple[Any, Any]:
    """Masks of inputs outside the tested range, without warnings.

    Parameters
    ----------
    slip_deg : array_like
        Slip angle(s), deg.
    fz : array_like
        Normal force(s), N.

    Returns
    -------
    slip_mask, fz_mask : bool or ndarray of bool
        ``|slip| > 8 deg`` and ``fz > 450 N`` (broadcast together). Python
        bools for scalar inputs.
    """
    if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
        return abs(slip_deg) > SLIP_MAX_DEG, fz > FZ_MAX_N
    s, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
    return np.abs(s) > SLIP_MAX_DEG, f > FZ_MAX_N


def _check_policy(policy: str) -> None:
    if policy not in POLICIES:
        raise ValueError(f"policy={policy!r} is not valid; choose one of {POLICIES}")


def _range_message(n_slip: int, n_fz: int, n_total: int, policy: str) -> str:
    return (
        f"{n_slip + n_fz} out-of-range input(s) among {n_total} point(s) "
        f"(|slip| > {SLIP_MAX_DEG:g} deg: {n_slip}, Fz > {FZ_MAX_N:g} N: {n_fz}); "
        f"policy {policy!r} applied"
    )


# ---------------------------------------------------------------------------
# tire classes
# ---------------------------------------------------------------------------


def _canonical(name: str) -> str:
    if not isinstance(name, str):
        raise ValueError(f"name={name!r} is not valid; choose one of {_ALL}")
    key = name.strip().upper()
    if key not in _ALL:
        raise ValueError(f"name={name!r} is not valid; choose one of {_ALL}")
    return key


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


@dataclass(frozen=True)
class LinearTire(_CamberForce):
    """A hypothetical linear tire: ``F_y = -C * slip`` independent of load.

    For chairs whose tires were never tested (``get("linear:<C>")``). Same
    methods as :class:`Tire`; nothing is out of range for a linear tire
    (``policy`` only validates its argument), and ``fz <= 0`` still gives
    zero force.

    Attributes
    ----------
    stiffness_N_per_deg : float
        Cornering stiffness ``C`` (N/deg).
    f_r : float
        Linear coefficient of rolling resistance (eq 3-2), default 0.
    camber_coef : float or None
        Camber coefficient ``f_c``; None means none given.
    lateral_scale, rolling_scale : float
        Force multipliers as for :class:`Tire`.
    """

    stiffness_N_per_deg: float
    f_r: float = 0.0
    camber_coef: float | None = None
    lateral_scale: float = 1.0
    rolling_scale: float = 1.0

    @property
    def name(self) -> str:
        """``"linear:<C>"``."""
        return f"linear:{self.stiffness_N_per_deg:g}"

    @property
    def is_caster(self) -> bool:
        """Always False (a linear tire is not one of the tested casters)."""
        return False

    @property
    def coefficients(self) -> NDArray[np.float64]:
        """``(9, 3)`` equivalent table: ``F_k = C k``, not a cubic in ``F_z``.

        A linear tire has no load dependence, so no ``(a, b, c)`` exist;
        this returns NaN except the zero row.
        """
        arr = np.full((9, 3), np.nan)
        arr[0] = 0.0
        return arr

    def lateral_force(
        self,
        slip_deg: ArrayLike,
        fz: ArrayLike,
        *,
        policy: Policy = "clamp",
        warn: bool = True,
    ) -> Any:
        """Lateral force ``-C * slip * lateral_scale`` (N); 0 where ``fz <= 0``."""
        if policy not in POLICIES:
            _check_policy(policy)
        k = self.stiffness_N_per_deg * self.lateral_scale
        if isinstance(slip_deg, (int, float)) and isinstance(fz, (int, float)):
            if fz <= 0.0:
                return 0.0
            return -k * float(slip_deg) + 0.0
        s, f = np.broadcast_arrays(np.asarray(slip_deg, dtype=float), np.asarray(fz, dtype=float))
        return np.where(f > 0.0, -k * s, 0.0) + 0.0

    def cornering_stiffness(self, fz: ArrayLike, *, include_intercept: bool = False) -> Any:
        """``C * lateral_scale`` (N/deg) wherever ``fz > 0``."""
        k = self.stiffness_N_per_deg * self.lateral_scale
        if isinstance(fz, (int, float)):
            return k if fz > 0.0 else 0.0
        return np.where(np.asarray(fz, dtype=float) > 0.0, k, 0.0)

    def cornering_stiffness_per_rad(self, fz: ArrayLike, *, include_intercept: bool = False) -> Any:
        """Cornering stiffness in N/rad."""
        return self.cornering_stiffness(fz) * _DEG_PER_RAD

    @property
    def has_camber_data(self) -> bool:
        """True when a camber coefficient was given."""
        return self.camber_coef is not None

    @property
    def camber_coefficient(self) -> float:
        """The given camber coefficient; ValueError when none was given."""
        if self.camber_coef is None:
            raise ValueError(f"{self.name} has no camber coefficient; pass camber_coefficient= explicitly")
        return self.camber_coef

    def rolling_resistance(self, fz: ArrayLike) -> Any:
        """``f_r * fz * rolling_scale`` (N), eq (3-2); 0 where ``fz <= 0``."""
        k = self.f_r * self.rolling_scale
        if isinstance(fz, (int, float)):
            return k * float(fz) if fz > 0.0 else 0.0
        f = np.asarray(fz, dtype=float)
        return np.where(f > 0.0, k * f, 0.0)

    @property
    def rolling_coefficient_linear(self) -> float:
        """``f_r``."""
        return self.f_r

    def scaled(self, lateral: float = 1.0, rolling: float = 1.0) -> LinearTire:
        """A copy with the force multipliers compounded (TYMOD/TXMOD)."""
        return LinearTire(
            stiffness_N_per_deg=self.stiffness_N_per_deg,
            f_r=self.f_r,
            camber_coef=self.camber_coef,
            lateral_scale=self.lateral_scale * float(lateral),
            rolling_scale=self.rolling_scale * float(rolling),
        )


AnyTire = Union[Tire, LinearTire]


class TireStack:
    """Several tested tires evaluated in one call: row ``j`` of the input uses tire ``j``.

    The batch simulator's kernel (:mod:`stability.simulate`): the four wheels
    of every run of a batch, as ``(k, n)`` arrays of slip angles and normal
    loads, go through one sequence of array operations instead of one per
    tire.  The force law is exactly :meth:`Tire.lateral_force` (same
    interpolation, same policies, same rounding), but no
    :class:`TireRangeWarning` is emitted: the caller counts out-of-range
    points itself, as WCHAIR's range warnings do.

    Parameters
    ----------
    tires : sequence of Tire
        One tested tire per row (:class:`LinearTire` has no table to stack).
    """

    def __init__(self, tires: tuple[Tire, ...] | list[Tire]):
        tires = tuple(tires)
        if not tires or not all(isinstance(t, Tire) for t in tires):
            raise ValueError(f"tires={tires!r} is not valid; valid: a non-empty sequence of tested Tire objects")
        k = len(tires)
        # (6, 8 k): a0, b0, c0, da, db, dc of every tire's 8 one-degree segments, end to end
        self._table = tuple(np.ascontiguousarray(np.concatenate([t._segments[c] for t in tires]))
                            for c in range(6))
        self._offset = (8 * np.arange(k, dtype=np.intp))[:, None]
        scale = np.array([t.lateral_scale for t in tires], dtype=float)[:, None]
        self._scale = None if np.all(scale == 1.0) else scale
        self.tires = tires
        self.names = tuple(t.name for t in tires)

    def lateral_force(self, slip_deg: NDArray[np.float64], fz: NDArray[np.float64], *,
                      policy: Policy = "clamp") -> NDArray[np.float64]:
        """Cornering force (N) of each row's tire; ``slip_deg``, ``fz`` of shape ``(k, n)``.

        See :meth:`Tire.lateral_force` for the force law and ``policy``
        (``"raise"`` raises ValueError naming the first offending value).
        """
        s = np.abs(slip_deg)
        if policy == "clamp":
            np.minimum(s, SLIP_MAX_DEG, out=s)
            f = np.minimum(fz, FZ_MAX_N)
        elif policy == "extrapolate":
            f = fz
        else:
            _check_policy(policy)
            bad = (s > SLIP_MAX_DEG) | (fz > FZ_MAX_N)
            if bad.any():   # the offending row's tire raises its own error
                j = int(np.argwhere(bad)[0][0])
                self.tires[j].lateral_force(slip_deg[j], fz[j], policy="raise")
            f = fz
        c = _segment_force(self._table, s, f, self._offset)
        if self._scale is not None:
            c *= self._scale
        return np.where(slip_deg > 0.0, -c, c) + 0.0


def names() -> tuple[str, ...]:
    """Names of the tested tires, main wheels first (Table 3-1)."""
    return _ALL


@functools.cache
def _tested(name: str) -> Tire:
    rows, d, _ = _cornering_coefficients()[name]
    return Tire(
        name=name,
        rows=rows,
        intercepts=d,
        rolling=_rolling_coefficients().get(name),
        f_r=_table_3_2().get(name),
    )


def get(spec: str) -> AnyTire:
    """A tire by name or a linear tire by stiffness.

    Parameters
    ----------
    spec : str
        One of :func:`names` (case-insensitive), or ``"linear:<C>"`` with
        ``C`` the cornering stiffness in N/deg (load-independent).

    Returns
    -------
    Tire or LinearTire

    Raises
    ------
    ValueError
        Naming the parameter, the value and the valid choices.
    """
    if isinstance(spec, str):
        key = spec.strip()
        if key.lower().startswith("linear:"):
            text = key.split(":", 1)[1].strip()
            try:
                c = float(text)
            except ValueError:
                c = math.nan
            if not math.isfinite(c) or c < 0.0:
                raise ValueError(
                    f"spec={spec!r} is not valid: 'linear:<C>' needs a finite C >= 0 in N/deg"
                )
            return LinearTire(stiffness_N_per_deg=c)
        if key.upper() in _ALL:
            return _tested(key.upper())
    raise ValueError(
        f"spec={spec!r} is not valid; choose one of {_ALL} (any case) or 'linear:<C>' "
        "with C in N/deg"
    )
