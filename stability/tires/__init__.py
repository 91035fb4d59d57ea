"""Treadmill tire data and the empirical tire-force model of Collins (1987), chapters 3-4 and Appendix B.

Cornering force eq (4-1) per whole degree of slip, interpolated as WCHAIR's
MECHAN (Appendix C); cornering stiffness (Table 4-1); camber force eq (4-2);
rolling resistance (Appendix B, eq 3-2). Forces in N, angles in deg. Modules:
``data`` (tables and raw tests), ``fit`` (the cubic fits), ``ranges`` (the
tested range and policies), ``model`` (:class:`Tire`), ``linear_tire``,
``stack`` (:class:`TireStack`), ``registry`` (:func:`get`). See ``docs/tires.md``.

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

from .data import (
    CASTER_TIRES,
    FZ_MAX_N,
    FZ_TESTED_MAX_1DEG_N,
    LBF_TO_N,
    MAIN_TIRES,
    SLIP_MAX_DEG,
    TABLE_4_1_FZ_N,
    raw_camber,
    raw_cornering,
    table_3_2,
    table_4_1,
)
from .fit import RefitResult, camber_coefficient_fit, fit_per_angle, refit
from .linear_tire import AnyTire, LinearTire
from .model import Tire
from .ranges import POLICIES, Policy, TireRangeWarning, out_of_range
from .registry import get, names
from .stack import TireStack

__all__ = [
    "AnyTire",
    "CASTER_TIRES",
    "FZ_MAX_N",
    "FZ_TESTED_MAX_1DEG_N",
    "LBF_TO_N",
    "LinearTire",
    "MAIN_TIRES",
    "POLICIES",
    "Policy",
    "RefitResult",
    "SLIP_MAX_DEG",
    "TABLE_4_1_FZ_N",
    "Tire",
    "TireRangeWarning",
    "TireStack",
    "camber_coefficient_fit",
    "fit_per_angle",
    "get",
    "names",
    "out_of_range",
    "raw_camber",
    "raw_cornering",
    "refit",
    "table_3_2",
    "table_4_1",
]
