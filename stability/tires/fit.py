"""Least-squares fits of the cubic (4-1) per slip angle, as program PWRSTAR did (chapter 4).

:func:`fit_per_angle` is the one fit: the thesis tires (:func:`refit`) and a
user's own data (:func:`stability.tires.user.load_tire_data`) both go through it.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stability.tires.data import (
    CASTER_TIRES,
    MAIN_TIRES,
    TABLE_4_1_FZ_N,
    _canonical,
    _cornering_coefficients,
    raw_camber,
    raw_cornering,
)

__all__ = ["REFIT_METHODS", "RefitResult", "camber_coefficient_fit", "fit_per_angle", "refit"]

#: Fitting methods of :func:`refit` and :func:`fit_per_angle`.
REFIT_METHODS: tuple[str, ...] = ("with_intercept", "through_origin", "pwrstar")


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
        return np.asarray(np.linalg.lstsq(design, y, rcond=None)[0], dtype=np.float64)
    if method == "pwrstar":
        x = np.concatenate([[0.0], x])
        y = np.concatenate([[0.0], y])
    design = np.column_stack([x, x**2, x**3, np.ones_like(x)])
    return np.asarray(np.linalg.lstsq(design, y, rcond=None)[0], dtype=np.float64)


def fit_per_angle(
    angles_deg: ArrayLike, fz: ArrayLike, fy: ArrayLike, *, method: str = "pwrstar"
) -> RefitResult:
    """Fit the cubic (4-1) ``F_y = a F_z + b F_z**2 + c F_z**3 (+ d)`` separately at each angle.

    Parameters
    ----------
    angles_deg : array_like
        Slip (or camber) angle of each measurement, deg; one fit per distinct value.
    fz, fy : array_like
        Normal and lateral force of each measurement, N. Rows with NaN are skipped.
    method : {"with_intercept", "through_origin", "pwrstar"}
        See :func:`refit`; ``"pwrstar"`` (the published fits) by default.

    Returns
    -------
    RefitResult
        Coefficients per angle (ascending) and residual statistics.

    Raises
    ------
    ValueError
        For an unknown ``method``.
    """
    if method not in REFIT_METHODS:
        raise ValueError(f"method={method!r} is not valid; choose one of {REFIT_METHODS}")
    ang_all = np.asarray(angles_deg, dtype=float)
    fz_all = np.asarray(fz, dtype=float)
    fy_all = np.asarray(fy, dtype=float)
    ok = np.isfinite(ang_all) & np.isfinite(fz_all) & np.isfinite(fy_all)
    angles = np.unique(ang_all[ok])
    coefs, npts, rms, mx, rr = [], [], [], [], []
    for ang in angles:
        sel = ok & (ang_all == ang)
        x, y = fz_all[sel], fy_all[sel]
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
    if method not in REFIT_METHODS:
        raise ValueError(f"method={method!r} is not valid; choose one of {REFIT_METHODS}")
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
    keep = np.ones(raw[key].shape, dtype=bool) if include_outliers else raw["flag"] != "outlier"
    return fit_per_angle(raw[key][keep], raw["Fz_N"][keep], raw["Fy_N"][keep], method=method)


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
    for gamma, c in zip(fit.angles_deg, fit.coefficients, strict=True):
        cam.append(c[0] * fz + c[1] * fz**2 + c[2] * fz**3)
        a, b, cc = rows[int(gamma)]
        cor.append(a * fz + b * fz**2 + cc * fz**3)
    x = np.concatenate(cam)
    y = np.concatenate(cor)
    m = float(np.sum(x * y) / np.sum(x * x))
    return 1.0 / m
