"""Tire data of Collins (1987): Tables 3-2 and 4-1, the Appendix B raw tests and coefficients.

The numbers live in ``stability/data/tires/*.csv``; ``provenance.md`` beside
them lists every OCR correction with its evidence (see ``docs/tires.md``).
Units: forces in N (the raw tables also in lbf), angles in deg.
"""

from __future__ import annotations

import csv
import functools
import math
from importlib import resources
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "CASTER_TIRES",
    "FZ_MAX_N",
    "FZ_TESTED_MAX_1DEG_N",
    "LBF_TO_N",
    "MAIN_TIRES",
    "SLIP_MAX_DEG",
    "TABLE_4_1_FZ_N",
    "raw_camber",
    "raw_cornering",
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

_ALL = MAIN_TIRES + CASTER_TIRES

Coef3 = tuple[float, float, float]


def _canonical(name: str) -> str:
    if not isinstance(name, str):
        raise ValueError(f"name={name!r} is not valid; choose one of {_ALL}")
    key = name.strip().upper()
    if key not in _ALL:
        raise ValueError(f"name={name!r} is not valid; choose one of {_ALL}")
    return key


@functools.cache
def _read_csv(filename: str) -> tuple[dict[str, str], ...]:
    """Rows of ``stability/data/tires/<filename>`` as a tuple of dicts."""
    path = resources.files("stability").joinpath("data", "tires", filename)
    text = path.read_text(encoding="utf-8")
    return tuple(dict(row) for row in csv.DictReader(text.splitlines()))


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
