"""Your own tires: a treadmill or test-cart CSV fitted with the thesis's cubic (4-1) per slip angle.

The same fit as the thesis tires (:func:`stability.tires.fit.fit_per_angle`,
PWRSTAR's method); the fitted range is recorded on the tire so the range
policy applies outside it. File format and rationale: ``docs/tires.md``.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stability.runtime import readfiles
from stability.runtime.checks import value_text
from stability.tires.cart import CartGeometry, cart_forces
from stability.tires.data import _ALL, SLIP_MAX_DEG
from stability.tires.fit import fit_per_angle
from stability.tires.model import Tire

__all__ = ["MIN_POINTS_PER_ANGLE", "FitQuality", "TireData", "load_tire_data", "read_tire_csv", "tire_from_data"]

#: Fewest measurements per slip angle (the cubic plus constant has 4 unknowns; the origin is added).
MIN_POINTS_PER_ANGLE = 4
_FORCE_COLUMNS = ("slip_deg", "fz_n", "fy_n")
_CART_COLUMNS = ("slip_deg", "w_n", "fs_n")
_META_KEYS = ("name", "camber_coefficient", "rolling_coefficient")


@dataclass(frozen=True)
class FitQuality:
    """How well the cubic (4-1) fits a tire's data, per slip angle.

    Attributes
    ----------
    slip_deg : tuple of int
        Slip angles with data, deg.
    n_points : tuple of int
        Measurements per angle.
    r_squared : tuple of float
        ``1 - SS_res / SS_tot`` of the measurements about the cubic as used
        (constant term dropped), per angle, ``SS_tot`` about the mean of the
        measured forces. Near or below 0 where the force hardly varies with load
        (saturated casters): judge those by the RMS residual.
    r_pwrstar : tuple of float
        The correlation coefficient R as Appendix B prints it (the origin among
        the points; see :class:`stability.tires.RefitResult`).
    rms_residual_N, max_abs_residual_N : tuple of float
        Residuals of the measurements about the cubic as used, N.
    fz_min_N, fz_max_N : tuple of float
        Measured load range per angle, N.
    """

    slip_deg: tuple[int, ...]
    n_points: tuple[int, ...]
    r_squared: tuple[float, ...]
    r_pwrstar: tuple[float, ...]
    rms_residual_N: tuple[float, ...]
    max_abs_residual_N: tuple[float, ...]
    fz_min_N: tuple[float, ...]
    fz_max_N: tuple[float, ...]

    def to_dict(self) -> dict[str, list[Any]]:
        """JSON-ready dict of lists."""
        return {k: list(v) for k, v in asdict(self).items()}

    def __str__(self) -> str:
        lines = ["slip (deg)  points   R^2      R (B)   RMS (N)  max |res| (N)  Fz range (N)"]
        for row in zip(*asdict(self).values(), strict=True):
            s, n, r2, r, rms, mx, lo, hi = row
            lines.append(f"{s:10d}  {n:6d}  {r2:7.4f}  {r:6.3f}  {rms:8.3f}  {mx:13.3f}  {lo:5.0f} to {hi:.0f}")
        return "\n".join(lines)


def _rows_0_to_8(angles: NDArray[np.int_], values: NDArray[np.float64]) -> NDArray[np.float64]:
    """Values at whole degrees 0..8: zero at 0, the fits at measured angles, linear between, and the
    last measured segment extended linearly beyond the last angle (so "extrapolate" continues it)."""
    knots = np.concatenate([[0], angles]).astype(float)
    vals = np.vstack([np.zeros((1, values.shape[1])), values])
    out = np.empty((9, values.shape[1]))
    for k in range(9):
        j = min(int(np.searchsorted(knots, k, side="right")) - 1, len(knots) - 2)
        t = (k - knots[j]) / (knots[j + 1] - knots[j])
        out[k] = vals[j] + t * (vals[j + 1] - vals[j])
    return out


def tire_from_data(slip_deg: ArrayLike, fz: ArrayLike, fy: ArrayLike, *, name: str,
                   camber_coefficient: float | None = None, rolling_coefficient: float | None = None,
                   source: str = "user data") -> Tire:
    """Fit the cubic (4-1) per slip angle to measurements and build a :class:`Tire`.

    Parameters
    ----------
    slip_deg : array_like
        Slip angle of each measurement, whole degrees 1..8 (the model
        interpolates per whole degree, as WCHAIR's MECHAN).
    fz, fy : array_like
        Normal force and lateral force magnitude of each measurement, N
        (Appendix B convention: positive ``F_y`` for a positive slip angle).
    name : str
        Tire name (not one of the thesis names).
    camber_coefficient : float, optional
        ``f_c`` of eq (4-2), 0..1.
    rolling_coefficient : float, optional
        ``f_r`` of eq (3-2); rolling resistance is then ``f_r F_z``.
    source : str
        Recorded on the tire.

    Returns
    -------
    Tire
        With ``slip_max_deg`` the largest measured slip angle, ``fz_max_N`` the
        largest load measured at *every* slip angle, and ``fit_quality``.

    Raises
    ------
    ValueError
        Angles not whole degrees in 1..8, fewer than :data:`MIN_POINTS_PER_ANGLE`
        measurements at an angle, or a bad coefficient.
    """
    s = np.asarray(slip_deg, dtype=float)
    f = np.asarray(fz, dtype=float)
    y = np.asarray(fy, dtype=float)
    if s.size == 0 or not (s.shape == f.shape == y.shape):
        raise ValueError(f"tire {name!r}: slip_deg, fz, fy must be equal-length non-empty arrays")
    if np.any((s != np.round(s)) | (s < 1) | (s > SLIP_MAX_DEG)):
        raise ValueError(f"tire {name!r}: slip angles must be whole degrees 1..{SLIP_MAX_DEG:g} "
                         f"(got {sorted(set(s.tolist()))})")
    for ang in np.unique(s):
        n = int(np.count_nonzero(s == ang))
        if n < MIN_POINTS_PER_ANGLE:
            raise ValueError(f"tire {name!r}: slip angle {ang:g} deg has {n} measurement(s); "
                             f"at least {MIN_POINTS_PER_ANGLE} are needed for the cubic (4-1)")
        if not np.any(y[s == ang]):          # the fit's R has no spread to measure and the tire no cornering force
            raise ValueError(f"tire {name!r}: slip angle {ang:g} deg has a lateral force of 0 N at every load; "
                             "valid: measured forces, some nonzero at every slip angle (a tire at a slip angle "
                             "corners)")
    if not (np.all(np.isfinite(f)) and np.all(np.isfinite(y))):
        raise ValueError(f"tire {name!r}: fz and fy must be finite numbers, N")
    for label, value, hi in (("camber_coefficient", camber_coefficient, 1.0),
                             ("rolling_coefficient", rolling_coefficient, 1.0)):
        if value is not None and not (math.isfinite(value) and 0.0 <= value <= hi):
            raise ValueError(f"tire {name!r}: {label}={value!r} is invalid; valid range: 0 to {hi:g}")
    fit = fit_per_angle(s, f, y, method="pwrstar")
    angles = fit.angles_deg
    abc = _rows_0_to_8(angles, fit.coefficients[:, :3])
    d = _rows_0_to_8(angles, fit.coefficients[:, 3:4])[:, 0]
    r2, lo, hi_ = [], [], []
    for k, ang in enumerate(angles):
        sel = s == ang
        ss_tot = float(np.sum((y[sel] - y[sel].mean()) ** 2))
        ss_res = float(fit.n_points[k] * fit.rms_residual_N[k] ** 2)
        r2.append(1.0 - ss_res / ss_tot if ss_tot > 0 else math.nan)
        lo.append(float(f[sel].min()))
        hi_.append(float(f[sel].max()))
    quality = FitQuality(
        slip_deg=tuple(int(a) for a in angles), n_points=tuple(int(n) for n in fit.n_points),
        r_squared=tuple(r2), r_pwrstar=tuple(float(v) for v in fit.r),
        rms_residual_N=tuple(float(v) for v in fit.rms_residual_N),
        max_abs_residual_N=tuple(float(v) for v in fit.max_abs_residual_N),
        fz_min_N=tuple(lo), fz_max_N=tuple(hi_),
    )
    fr = rolling_coefficient
    return Tire(
        name=name,
        rows=tuple((float(a), float(b), float(c)) for a, b, c in abc),
        intercepts=tuple(float(v) for v in d),
        rolling=None if fr is None else (float(fr), 0.0, 0.0),
        f_r=fr,
        slip_max_deg=float(angles.max()),
        fz_max_N=min(hi_),
        source=source,
        camber_coef=camber_coefficient,
        fit_quality=quality,
    )


@dataclass(frozen=True)
class TireData:
    """Measurements read from a tire CSV (:func:`read_tire_csv`).

    Attributes
    ----------
    slip_deg, fz_N, fy_N : ndarray
        Slip angle (deg), normal and lateral force (N) per measurement
        (reduced from the cart readings when the file holds those).
    meta : dict
        ``# key = value`` header lines (name, camber_coefficient, rolling_coefficient, cart.*).
    cart : CartGeometry or None
        The cart used to reduce raw readings, if any.
    """

    slip_deg: NDArray[np.float64]
    fz_N: NDArray[np.float64]
    fy_N: NDArray[np.float64]
    meta: dict[str, str]
    cart: CartGeometry | None


def _bad(path: Path, line: int, column: str, problem: str) -> ValueError:
    return ValueError(f"tire data {str(path)!r}, line {line}, column {column!r}: {problem}")


def _path(path: Any) -> Path:
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError(f"path={value_text(path)} is invalid; valid values: the path of a tire CSV (str or "
                        "path-like)")
    return Path(path)


def _parse(path: Path, text: str) -> tuple[dict[str, str], list[tuple[int, dict[str, str]]], list[str]]:
    meta: dict[str, str] = {}
    body: list[tuple[int, str]] = []
    for number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("#"):
            key, sep, value = stripped.lstrip("#").partition("=")
            if sep:
                meta[key.strip().lower()] = value.strip()
        elif stripped:
            body.append((number, line))
    if not body:
        raise _bad(path, 1, "-", "no header row and no data (expected columns slip_deg, Fz_N, Fy_N)")
    header_line, header_text = body[0]
    header = [h.strip().lower() for h in next(csv.reader([header_text]))]
    twice = sorted({h for h in header if h and header.count(h) > 1})
    if twice:                                # which of the two would be read is a guess: refuse it
        raise _bad(path, header_line, twice[0], "named twice in the header; valid: each column once")
    rows = []
    for number, line in body[1:]:
        cells = next(csv.reader([line]))
        if len(cells) != len(header):
            raise _bad(path, number, "-", f"{len(cells)} cells, the header has {len(header)}")
        rows.append((number, dict(zip(header, (c.strip() for c in cells), strict=True))))
    if not rows:
        raise _bad(path, header_line, "-", "a header but no data rows")
    return meta, rows, header


def _column(path: Path, rows: list[tuple[int, dict[str, str]]], col: str, label: str) -> NDArray[np.float64]:
    out = np.empty(len(rows))
    for k, (number, row) in enumerate(rows):
        try:
            v = float(row[col])
        except ValueError:
            raise _bad(path, number, label, f"{row[col]!r} is not a number") from None
        if not math.isfinite(v):
            raise _bad(path, number, label, f"{row[col]!r} is not a finite number")
        if col == "slip_deg" and (v != round(v) or not 1 <= v <= SLIP_MAX_DEG):
            raise _bad(path, number, label, f"{v:g} is invalid; valid: whole degrees 1 to {SLIP_MAX_DEG:g}")
        if col in ("fz_n", "w_n") and v <= 0:
            raise _bad(path, number, label, f"{v:g} is invalid; valid range: > 0 N")
        out[k] = v
    return out


def read_tire_csv(path: str | os.PathLike[str], cart: CartGeometry | None = None) -> TireData:
    """Read a tire CSV: forces (``slip_deg, Fz_N, Fy_N``) or cart readings (``slip_deg, W_N, Fs_N``).

    Header names are case-insensitive; other columns are ignored. Lines
    starting with ``#`` may hold ``key = value`` metadata: ``name``,
    ``camber_coefficient``, ``rolling_coefficient`` and, for cart readings,
    ``cart.<field>`` of :class:`CartGeometry` (unless ``cart`` is given).

    Parameters
    ----------
    path : str or path-like
    cart : CartGeometry, optional
        Test-cart dimensions for a file of raw readings (Appendix A).

    Returns
    -------
    TireData

    Raises
    ------
    ValueError
        One line naming the file, the line and the column of the problem, or a file larger than
        :data:`stability.runtime.readfiles.MAX_INPUT_BYTES`.
    TypeError
        ``path`` is not a path.
    """
    p = _path(path)
    try:
        text = readfiles.read_text(p)
    except (OSError, UnicodeDecodeError) as exc:
        raise ValueError(f"tire data {str(p)!r} cannot be read: {exc.__class__.__name__}: {exc}") from None
    meta, rows, header = _parse(p, text)
    names = {"slip_deg": "slip_deg", "fz_n": "Fz_N", "fy_n": "Fy_N", "w_n": "W_N", "fs_n": "Fs_N"}
    if all(c in header for c in _FORCE_COLUMNS):
        s, fz, fy = (_column(p, rows, c, names[c]) for c in _FORCE_COLUMNS)
        return TireData(s, fz, fy, meta, None)
    if all(c in header for c in _CART_COLUMNS):
        if cart is None:
            dims = {k.split(".", 1)[1]: v for k, v in meta.items() if k.startswith("cart.")}
            if not dims:
                raise _bad(p, 1, "cart.*", "cart readings (W_N, Fs_N) need the cart's dimensions: "
                                           "'# cart.<field> = value' lines or cart=CartGeometry(...)")
            try:
                cart = CartGeometry.from_mapping(dims)
            except (TypeError, ValueError) as exc:
                raise _bad(p, 1, "cart.*", str(exc)) from None
        s, w, fs = (_column(p, rows, c, names[c]) for c in _CART_COLUMNS)
        forces = cart_forces(w, fs, s, cart)
        return TireData(s, np.asarray(forces.fz), np.asarray(forces.fy), meta, cart)
    missing = [names[c] for c in _FORCE_COLUMNS if c not in header]
    raise _bad(p, 1, missing[0], f"missing; the header needs {list(names[c] for c in _FORCE_COLUMNS)} "
                                 f"(forces) or {list(names[c] for c in _CART_COLUMNS)} (cart readings)")


def _meta_float(path: Path, meta: dict[str, str], key: str) -> float | None:
    if key not in meta:
        return None
    try:
        return float(meta[key])
    except ValueError:
        raise _bad(path, 1, f"# {key}", f"{meta[key]!r} is not a number") from None


def load_tire_data(path: str | os.PathLike[str], *, name: str | None = None, cart: CartGeometry | None = None,
                   camber_coefficient: float | None = None, rolling_coefficient: float | None = None) -> Tire:
    """Load a user's tire data from CSV and fit it as the thesis tires were (eq 4-1, PWRSTAR's method).

    Parameters
    ----------
    path : str or path-like
        CSV file (format in :func:`read_tire_csv` and ``docs/tires.md``).
    name : str, optional
        Tire name; default the ``# name`` header line, else the file's stem.
    cart : CartGeometry, optional
        For a file of raw cart readings.
    camber_coefficient, rolling_coefficient : float, optional
        ``f_c`` (eq 4-2) and ``f_r`` (eq 3-2); default the header lines, else none.

    Returns
    -------
    Tire
        ``tire.fit_quality`` holds R^2 and residuals per slip angle;
        ``slip_max_deg`` / ``fz_max_N`` the fitted range.

    Raises
    ------
    ValueError
        One line naming the file (and line and column where there is one), or a file larger than
        :data:`stability.runtime.readfiles.MAX_INPUT_BYTES`.
    TypeError
        ``path`` is not a path.
    """
    p = _path(path)
    data = read_tire_csv(p, cart)
    unknown = sorted(k for k in data.meta if k not in _META_KEYS and not k.startswith("cart."))
    if unknown:
        raise _bad(p, 1, f"# {unknown[0]}", f"unknown header key; valid: {list(_META_KEYS)} and cart.<field>")
    label = name or data.meta.get("name") or p.stem
    if label.strip().upper() in _ALL or label.strip().lower().startswith(("linear:", "file:")):
        label = f"{label} (user data)"
    fc = camber_coefficient if camber_coefficient is not None else _meta_float(p, data.meta, "camber_coefficient")
    fr = rolling_coefficient if rolling_coefficient is not None else _meta_float(p, data.meta, "rolling_coefficient")
    if np.median(data.fy_N) < 0:
        raise _bad(p, 1, "Fy_N", "lateral forces are mostly negative; give magnitudes (Appendix B convention)")
    try:
        return tire_from_data(data.slip_deg, data.fz_N, data.fy_N, name=label, camber_coefficient=fc,
                              rolling_coefficient=fr, source=f"user data {str(p)!r}")
    except ValueError as exc:
        raise ValueError(f"tire data {str(p)!r}: {exc}") from None
