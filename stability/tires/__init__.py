"""Treadmill tire data and the empirical tire-force model of Collins (1987), chapters 3-4 and Appendices A-B.

Cornering force eq (4-1) per whole degree of slip, interpolated as WCHAIR's
MECHAN (Appendix C); cornering stiffness (Table 4-1); camber force eq (4-2);
rolling resistance (Appendix B, eq 3-2); a user's own tire data fitted the same
way; one policy for loads and slips outside the fitted data. Forces in N,
angles in deg. Modules: ``data`` (tables, raw tests), ``fit`` (the cubic fits),
``ranges`` (fitted range, policies, notes), ``base``/``model`` (:class:`Tire`),
``law`` (the force law, once: floats, arrays, compiled), ``linear_tire``, ``cart`` (Appendix A statics),
``user`` (your own data), ``registry`` (:func:`get`, :func:`register`),
``checks`` (chair checks). See ``docs/tires.md``.

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

from stability.tires.base import TireCapabilities
from stability.tires.cart import CartForces, CartGeometry, cart_forces
from stability.tires.checks import WHEELS, check_chair_tires, range_check
from stability.tires.data import (
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
from stability.tires.fit import RefitResult, camber_coefficient_fit, fit_per_angle, refit
from stability.tires.linear_tire import AnyTire, LinearTire
from stability.tires.model import THESIS_SOURCE, Tire
from stability.tires.ranges import (
    POLICIES,
    RANGE_POLICIES,
    Policy,
    RangeNote,
    RangePolicy,
    TireRangeWarning,
    collect_notes,
    get_policy,
    out_of_range,
    range_policy,
    set_policy,
    summarise_notes,
    summarised_warnings,
)
from stability.tires.registry import get, names, register, registered, resolve_spec, unregister
from stability.tires.user import FitQuality, TireData, load_tire_data, read_tire_csv, tire_from_data

__all__ = [
    "AnyTire",
    "CASTER_TIRES",
    "CartForces",
    "CartGeometry",
    "FZ_MAX_N",
    "FZ_TESTED_MAX_1DEG_N",
    "FitQuality",
    "LBF_TO_N",
    "LinearTire",
    "MAIN_TIRES",
    "POLICIES",
    "Policy",
    "RANGE_POLICIES",
    "RangeNote",
    "RangePolicy",
    "RefitResult",
    "SLIP_MAX_DEG",
    "TABLE_4_1_FZ_N",
    "THESIS_SOURCE",
    "Tire",
    "TireCapabilities",
    "TireData",
    "TireRangeWarning",
    "WHEELS",
    "camber_coefficient_fit",
    "cart_forces",
    "check_chair_tires",
    "collect_notes",
    "summarise_notes",
    "summarised_warnings",
    "fit_per_angle",
    "get",
    "get_policy",
    "load_tire_data",
    "names",
    "out_of_range",
    "range_check",
    "range_policy",
    "raw_camber",
    "raw_cornering",
    "read_tire_csv",
    "refit",
    "register",
    "registered",
    "resolve_spec",
    "set_policy",
    "table_3_2",
    "table_4_1",
    "tire_from_data",
    "unregister",
]
