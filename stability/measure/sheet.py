"""Measurement sheet (TOML of raw readings with uncertainties) -> Chair, Uncertainty and provenance.

Every reading is ``{value = ..., unit = "...", std = ...}`` (``std`` in the
same unit, optional) or a bare number in SI units.  docs/measure.md shows
a complete sheet; :data:`READINGS` lists every reading, its dimension and
valid range.  Derived values carry first-order standard uncertainties from
finite differences over the readings (treated as independent).
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from stability import chair as chair_mod
from stability.chair import Chair
from stability.chair.units import STANDARD_GRAVITY, dimension_name, parse_unit
from stability.measure.anthropometry import user_yaw_inertia
from stability.measure.bodies import Body, combine
from stability.measure.pendulum import compound_pendulum_inertia, solid_cylinder_inertia
from stability.measure.scales import WheelLoads, cg_from_scales, cg_height_from_tilt, tilt_reading
from stability.runtime import readfiles
from stability.uncertainty import Distribution, Uncertainty

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["READINGS", "Reading", "ProvenanceRow", "SheetResult", "read_sheet", "load_sheet"]

_SCALE = ("mass", "force")  # wheel scales and spring scales: a mass reading means mass x standard gravity
_WHEELS = ("left_main", "right_main", "left_caster", "right_caster")

#: reading -> (allowed dimensions, SI lower bound (exclusive), upper bound, required, description)
READINGS: dict[str, tuple[tuple[str, ...], float, float, bool, str]] = {
    "geometry.wheelbase": (("length",), 0.1, 2.0, True, "main-wheel contacts to caster contacts, casters trailing"),
    "geometry.main_track": (("length",), 0.1, 1.5, True, "between the main-wheel contacts"),
    "geometry.caster_track": (("length",), 0.05, 1.5, True, "between the caster contacts"),
    "geometry.trail": (("length",), -1e-12, 0.5, True, "caster pin axis to contact, horizontal"),
    "geometry.main_wheel_radius": (("length",), 0.02, 0.5, True, "main wheel radius"),
    "geometry.caster_wheel_radius": (("length",), 0.01, 0.5, True, "caster wheel radius"),
    **{f"scales.loaded.{w}": (_SCALE, -1e-12, 1e4, True, f"{w} wheel with user") for w in _WHEELS},
    "scales.loaded.weight": (_SCALE, 0.0, 1e4, False, "independent total weight, chair with user"),
    **{f"scales.empty.{w}": (_SCALE, -1e-12, 1e4, False, f"{w} wheel, chair alone") for w in _WHEELS},
    "tilt.lift": (("length",), 0.0, 1.0, False, "height the raised end's contacts are lifted"),
    "tilt.raised_left": (_SCALE, -1e-12, 1e4, False, "left reading under the raised end"),
    "tilt.raised_right": (_SCALE, -1e-12, 1e4, False, "right reading under the raised end"),
    "caster.mass": (("mass",), 0.0, 20.0, True, "one caster assembly (wheel, fork, bearing)"),
    "caster.l1": (("length",), -1e-12, 0.5, True, "pin axis to caster c.g."),
    "caster.period": (("time",), 0.0, 60.0, True, "compound-pendulum period about the pin"),
    "caster.amplitude": (("angle",), -1e-12, 1.5, False, "release amplitude of the caster's swing"),
    "pin_friction.lever_arm": (("length",), 0.0, 1.0, True, "pin to the spring-scale hook"),
    "pin_friction.left_force": (_SCALE, -1e-12, 100.0, True, "pull that just turns the left caster"),
    "pin_friction.right_force": (_SCALE, -1e-12, 100.0, True, "pull that just turns the right caster"),
    "inertia.rigidity": (("torsional rigidity",), 0.0, 1e4, False, "rod torsional rigidity K_t (if known)"),
    "inertia.calibration_mass": (("mass",), 0.0, 1e3, False, "solid calibration cylinder mass"),
    "inertia.calibration_radius": (("length",), 0.0, 2.0, False, "the calibration cylinder's radius"),
    "inertia.calibration_period": (("time",), 0.0, 600.0, False, "the calibration cylinder's period on the rod"),
    "inertia.fixture_period": (("time",), 0.0, 600.0, False, "period of the clamps and bar alone"),
    "inertia.chair_period": (("time",), 0.0, 600.0, True, "period of the chair hung at its c.g."),
    "user.stature": (("length",), 0.5, 2.5, False, "standing height (for the de Leva estimate)"),
    "user.inertia": (("inertia",), 0.0, 50.0, False, "measured seated yaw inertia about the user's c.g."),
}

#: derived chair field -> how it is computed (for the provenance table)
FORMULAS = {
    "m": "sum of the loaded wheel-scale readings",
    "s1": "wheelbase x (caster loads) / total: moments about the main axle",
    "s2": "wheelbase - s1 - trail (rear casters; + trail for front casters)",
    "d1": "main_track/2 + y_cg, y_cg from lateral moments of the four loads",
    "d2": "main_track/2 - y_cg",
    "t1": "caster_track/2 + y_cg",
    "t2": "caster_track/2 - y_cg",
    "h": "axle lift: moments about the pivot axle, level vs raised (scales.cg_height_from_tilt)",
    "trail": "measured directly",
    "m_c": "weighed directly",
    "l1": "measured directly",
    "i_zp": "compound pendulum about the pin: m_c g l1 T^2 / (4 pi^2)",
    "pin_friction_left": "spring-scale pull x lever arm",
    "pin_friction_right": "spring-scale pull x lever arm",
    "i_z": "eq D-1 torsional pendulum (chair) + user inertia, combined by the parallel-axis theorem",
}


@dataclass(frozen=True)
class Reading:
    """One sheet reading converted to SI units, with its sheet text.

    Attributes
    ----------
    key : str
        Dotted reading name, a key of :data:`READINGS` (e.g. ``"caster.period"``).
    value : float
        Value in SI units (m, kg, s, rad, N, N m/rad, kg m^2; scale readings given
        as a mass are converted to a weight in N with standard gravity).
    std : float
        Standard uncertainty in the same SI unit (0 when not given).
    shown : str
        The reading as written on the sheet (value, unit, ``+- std``), for reports.
    """

    key: str
    value: float
    std: float
    shown: str


@dataclass(frozen=True)
class ProvenanceRow:
    """A chair field from the sheet: value, standard uncertainty, readings it depends on, formula.

    Attributes
    ----------
    field : str
        Chair field name (e.g. ``"s1"``, ``"i_z"``).
    value : float
        Its value, in the chair field's SI unit.
    std : float
        First-order standard uncertainty (finite differences over the readings,
        treated as independent), same unit; 0 when exact or not given.
    readings : tuple of str
        Readings the value depends on (empty for fields given in ``[chair]``).
    formula : str
        How the value is computed (:data:`FORMULAS`), or ``"given in [chair]"``.
    """

    field: str
    value: float
    std: float
    readings: tuple[str, ...]
    formula: str


@dataclass(frozen=True)
class SheetResult:
    """Chair, uncertainty and provenance of a measurement sheet.

    Attributes
    ----------
    chair : Chair
        The chair built from the derived fields and the ``[chair]`` table.
    uncertainty : Uncertainty
        Normal distributions of every field with a non-zero standard uncertainty.
    provenance : tuple of ProvenanceRow
        One row per field given in ``[chair]`` or derived from the readings.
    readings : dict of str to Reading
        Every reading in SI units (with the de Leva estimate of ``user.inertia``
        when only ``user.stature`` was given).
    notes : tuple of str
        Plain-text remarks (e.g. how the user's inertia was estimated).
    """

    chair: Chair
    uncertainty: Uncertainty
    provenance: tuple[ProvenanceRow, ...]
    readings: dict[str, Reading]
    notes: tuple[str, ...]


def _bad(key: str, value: Any, valid: str) -> ValueError:
    """The one-line refusal of a sheet entry; a reading of :data:`READINGS` is followed by what it measures.

    Parameters
    ----------
    key : str
        The reading (or entry) at fault, e.g. ``"caster.mass"``.
    value : Any
        Its value as written on the sheet (with its unit, if any).
    valid : str
        What is valid instead (a range in SI units, a unit's dimension, ...).

    Returns
    -------
    ValueError
        ``sheet reading KEY=VALUE is invalid; valid range: VALID``, then ``; KEY: WORDS`` with the
        reading's words from :data:`READINGS` (the "what" column of docs/measure.md's table) when ``key`` is
        a reading.
    """
    what = f"; {key}: {READINGS[key][4]}" if key in READINGS else ""
    return ValueError(f"sheet reading {key}={value} is invalid; valid range: {valid}{what}")


def _parse_reading(key: str, raw: Any) -> Reading:
    dims, lo, hi, _, _ = READINGS[key]
    if isinstance(raw, Mapping):
        unknown = set(raw) - {"value", "unit", "std", "note"}
        if unknown:
            raise _bad(key, dict(raw), f"a table with keys value, unit, std, note (unknown {sorted(unknown)})")
        value, unit, std = raw.get("value"), raw.get("unit"), raw.get("std", 0.0)
    else:
        value, unit, std = raw, None, 0.0
    for name, v in (("value", value), ("std", std)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise _bad(key, repr(raw), f"{name} must be a finite number")
    if std < 0:
        raise _bad(key, repr(raw), "std >= 0")
    factor, dim, shown = 1.0, dims[0], f"{value:g}"
    if unit is not None:
        try:
            factor, d = parse_unit(str(unit))
        except ValueError as exc:
            raise _bad(key, repr(raw), str(exc)) from None
        dim = dimension_name(d)
        if dim not in dims:
            raise _bad(key, f"{value:g} {unit}", f"a {' or '.join(dims)} unit, not a {dim} unit")
        shown = f"{value:g} {unit}"
    if dim == "mass" and "force" in dims:  # scale readings in kg or lb: the weight of that mass
        factor *= STANDARD_GRAVITY
    si, si_std = float(value) * factor, float(std) * factor  # type: ignore[arg-type]
    if not lo < si <= hi:
        lo_txt = ">= 0" if lo < 0 else f"> {lo:g}"
        hi_txt = f"{hi / STANDARD_GRAVITY:.4g} kg ({hi:g} N)" if "force" in dims else f"{hi:g} (SI: {dims[0]})"
        raise _bad(key, shown, f"{lo_txt} and <= {hi_txt}")
    return Reading(key, si, si_std, shown + (f" +- {std:g}" if std else ""))


def _flatten(data: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in data.items():
        key = f"{prefix}{k}"
        if key in READINGS:
            out[key] = v
        elif isinstance(v, Mapping):
            out.update(_flatten(v, key + "."))
        else:
            out[key] = v
    return out


_OPTIONS = {"scales.loaded.tolerance", "tilt.end"}


def _derive(r: Mapping[str, float], opts: Mapping[str, Any]) -> dict[str, float]:
    """Chair fields from SI readings ``r`` (pure; used for values and finite differences)."""
    g0 = STANDARD_GRAVITY
    geo = {k: r[f"geometry.{k}"] for k in ("wheelbase", "main_track", "caster_track", "trail")}
    loaded = _scale_masses(r)
    try:
        cg = cg_from_scales(loaded, geo["wheelbase"], geo["main_track"], geo["caster_track"])
    except ValueError as exc:
        raise ValueError(f"sheet readings scales.loaded.*: {exc}") from None
    out: dict[str, float] = {"m": cg.total, "s1": cg.x, "trail": geo["trail"]}
    rear = opts.get("caster_position", "rear") == "rear"
    out["s2"] = geo["wheelbase"] - cg.x + (-geo["trail"] if rear else geo["trail"])
    if out["s2"] <= 0:
        raise _bad("geometry.trail", f"{geo['trail']:g} m",
                   f"< wheelbase - s1 = {geo['wheelbase'] - cg.x:.4g} m (c.g. behind the caster pins)")
    out.update(d1=geo["main_track"] / 2 + cg.y, d2=geo["main_track"] / 2 - cg.y,
               t1=geo["caster_track"] / 2 + cg.y, t2=geo["caster_track"] / 2 - cg.y)
    if "tilt.lift" in r:
        end = opts.get("tilt.end", "caster")
        rm, rc = r["geometry.main_wheel_radius"], r["geometry.caster_wheel_radius"]
        level = loaded.caster if end == "caster" else cg.total - loaded.caster
        tilted = (r["tilt.raised_left"] + r["tilt.raised_right"]) / g0
        h = cg_height_from_tilt(cg.total, level, tilted, r["tilt.lift"], geo["wheelbase"],
                                rm if end == "caster" else rc, rc if end == "caster" else rm)
        if not max(rm, rc) < h < 2:
            pivot, raised = (rm, rc) if end == "caster" else (rc, rm)
            x_level = level * geo["wheelbase"] / cg.total
            fall = level - tilt_reading(cg.total, x_level, 0.6, r["tilt.lift"], geo["wheelbase"], pivot, raised)
            raise _bad("tilt.raised_left + tilt.raised_right", f"{tilted:.4g} kg",
                       f"readings giving a c.g. height above the wheel axles ({max(rm, rc):.3g} m) and below "
                       f"2 m (got h = {h:.3g} m; for h = 0.6 m the raised end's load would fall by {fall:.3g} kg)")
        out["h"] = h
    out.update(m_c=r["caster.mass"], l1=r["caster.l1"])
    try:
        out["i_zp"] = float(compound_pendulum_inertia(r["caster.mass"], r["caster.l1"], r["caster.period"],
                                                      r.get("caster.amplitude", 0.0)))
    except ValueError as exc:
        raise _bad("caster.period", f"{r['caster.period']:g} s", str(exc).split("valid range: ")[-1]) from None
    arm = r["pin_friction.lever_arm"]
    out["pin_friction_left"] = r["pin_friction.left_force"] * arm
    out["pin_friction_right"] = r["pin_friction.right_force"] * arm
    # yaw inertia: chair alone (torsional pendulum) + user, parallel-axis combination
    if "inertia.rigidity" in r:
        k_t = r["inertia.rigidity"]
    else:
        i_cal = solid_cylinder_inertia(r["inertia.calibration_mass"], r["inertia.calibration_radius"])
        k_t = 4 * math.pi**2 * i_cal / r["inertia.calibration_period"] ** 2
    i_fix = k_t * r["inertia.fixture_period"] ** 2 / (4 * math.pi**2) if "inertia.fixture_period" in r else 0.0
    i_chair = k_t * r["inertia.chair_period"] ** 2 / (4 * math.pi**2) - i_fix
    if i_chair <= 0:
        raise _bad("inertia.chair_period", f"{r['inertia.chair_period']:g} s", "longer than inertia.fixture_period")
    empty = _scale_masses(r, "empty")
    cg_e = cg_from_scales(empty, geo["wheelbase"], geo["main_track"], geo["caster_track"])
    m_user = cg.total - cg_e.total
    if m_user <= 0:
        raise _bad("scales.empty (sum)", f"{cg_e.total:.4g} kg", f"< the loaded sum {cg.total:.4g} kg")
    m_chair = cg_e.total
    x_user = (cg.total * cg.x - cg_e.total * cg_e.x) / (cg.total - cg_e.total)
    y_user = (cg.total * cg.y - cg_e.total * cg_e.y) / (cg.total - cg_e.total)
    both = combine([Body(m_chair, cg_e.x, cg_e.y, float(i_chair), "chair"),
                    Body(m_user, x_user, y_user, r["user.inertia"], "user")])
    out["i_z"] = both.i_z
    return out


def _scale_masses(r: Mapping[str, float], which: str = "loaded") -> WheelLoads:
    """The wheel scales' readings (N) of the ``"loaded"`` or ``"empty"`` chair as masses per wheel, kg."""
    return WheelLoads(*(r[f"scales.{which}.{w}"] / STANDARD_GRAVITY for w in _WHEELS))


def _check_weight(r: Mapping[str, float], opts: Mapping[str, Any]) -> None:
    """Refuse loaded readings whose sum is off ``scales.loaded.weight`` by more than the tolerance.

    Checked once, on the readings as given: not inside :func:`_derive`, whose finite differences step a reading
    by a fraction of its std and would refuse a sum lying on the tolerance's edge.

    Parameters
    ----------
    r : Mapping of str to float
        The readings in SI units (scale readings in N).
    opts : Mapping of str to Any
        The sheet's options; ``scales.loaded.tolerance`` (a fraction, default 0.02).

    Raises
    ------
    ValueError
        One line naming both sums (kg) and the valid range, weight x (1 -+ tolerance), edges included.
    """
    if "scales.loaded.weight" not in r:
        return
    total = _scale_masses(r).total  # kg
    weight = r["scales.loaded.weight"] / STANDARD_GRAVITY
    tol = float(opts.get("scales.loaded.tolerance", 0.02))
    if not weight * (1 - tol) <= total <= weight * (1 + tol):
        raise ValueError(f"sheet readings scales.loaded.* sum to {total:.4g} kg but scales.loaded.weight = "
                         f"{weight:.4g} kg; valid range: {weight * (1 - tol):.4g} to {weight * (1 + tol):.4g} kg "
                         f"(within scales.loaded.tolerance = {tol:.1%})")


def _check_present(flat: Mapping[str, Any]) -> None:
    for key, (_, _, _, required, doc) in READINGS.items():
        if required and key not in flat:
            raise ValueError(f"sheet reading {key} is missing; it is required ({doc})")
    for w in _WHEELS:
        if f"scales.empty.{w}" not in flat:
            raise ValueError(f"sheet reading scales.empty.{w} is missing; the chair alone must be weighed "
                             "to place the user's c.g. for the inertia combination")
    if "tilt.lift" in flat and not {"tilt.raised_left", "tilt.raised_right"} <= set(flat):
        raise ValueError("sheet reading tilt.raised_left/raised_right is missing; needed with tilt.lift")
    calibration = {f"inertia.calibration_{k}" for k in ("mass", "radius", "period")}
    if "inertia.rigidity" not in flat and not calibration <= set(flat):
        raise ValueError("sheet reading inertia.rigidity is missing; give it or inertia.calibration_mass, "
                         "_radius and _period")
    if "user.inertia" not in flat and "user.stature" not in flat:
        raise ValueError("sheet reading user.inertia is missing; give it or user.stature for an estimate")


def _estimate_user(readings: dict[str, Reading], values: dict[str, float]) -> str:
    """Add the de Leva estimate as the reading user.inertia (with its uncertainty); return a note."""
    m_user = sum(values[f"scales.loaded.{w}"] - values[f"scales.empty.{w}"] for w in _WHEELS) / STANDARD_GRAVITY
    if m_user <= 0:
        raise _bad("scales.empty (sum)", f"{m_user:.4g} kg less than loaded", "less than the loaded sum")
    est = user_yaw_inertia(m_user, values["user.stature"])
    readings["user.inertia"] = Reading("user.inertia", est.value, est.std,
                                       f"{est.value:.3f} +- {est.std:.3f} kg m^2 (estimate)")
    values["user.inertia"] = est.value
    return (f"user yaw inertia estimated from mass {m_user:.1f} kg and stature {values['user.stature']:.2f} m "
            f"(de Leva 1996 seated model): {est.value:.2f} +- {est.std:.2f} kg m^2, posture range "
            f"{est.low:.2f} to {est.high:.2f}")


def _first_order(readings: Mapping[str, Reading], values: dict[str, float], opts: Mapping[str, Any],
                 derived: Mapping[str, float]) -> dict[str, dict[str, float]]:
    """field -> {reading: d field / d reading x its std} for every reading the field depends on."""
    sens: dict[str, dict[str, float]] = {f: {} for f in derived}
    for key, rd in readings.items():
        h = rd.std * 1e-3 if rd.std > 0 else max(abs(rd.value), 1e-3) * 1e-7
        hi = _derive({**values, key: rd.value + h}, opts)
        lo = _derive({**values, key: rd.value - h}, opts)
        for f in derived:
            d = (hi[f] - lo[f]) / (2 * h)
            if abs(d) * h > 1e-12 * max(abs(derived[f]), 1e-9):
                sens[f][key] = d * rd.std
    return sens


def _direct(direct: Mapping[str, Any]) -> tuple[dict[str, Any], list[Distribution], list[ProvenanceRow]]:
    """Chair fields given in [chair]: values, distributions for those with a std, provenance rows."""
    fixed: dict[str, Any] = {}
    dists, rows = [], []
    for k, v in direct.items():
        if not isinstance(v, Mapping):
            fixed[k] = v
            continue
        if set(v) - {"value", "std"} or not isinstance(v.get("value"), (int, float)):
            raise _bad(f"chair.{k}", dict(v), "a value or {value = ..., std = ...} in chair-file units")
        fixed[k] = float(v["value"])
        std = float(v.get("std", 0.0))
        if std:
            dists.append(Distribution(k, (k,), "normal", std=std))
        rows.append(ProvenanceRow(k, fixed[k], std, (), "given in [chair]"))
    return fixed, dists, rows


def read_sheet(data: Mapping[str, Any]) -> SheetResult:
    """Turn a parsed measurement sheet into a :class:`SheetResult`.

    Parameters
    ----------
    data : Mapping of str to Any
        The parsed TOML: reading tables (``geometry``, ``scales``, ``tilt``,
        ``caster``, ``pin_friction``, ``inertia``, ``user``; every key in
        :data:`READINGS`), the options ``scales.loaded.tolerance`` and
        ``tilt.end`` (``"caster"`` or ``"main"``), and an optional ``[chair]``
        table of fields given directly (a value or ``{value, std}``).

    Returns
    -------
    SheetResult
        The chair (c.g. from the wheel scales, h by axle lift, I_zp by compound
        pendulum, pin friction from spring-scale pulls, I_z by eq D-1 and the
        parallel-axis theorem), its uncertainty and the provenance table.

    Raises
    ------
    ValueError
        One line naming the reading at fault: unknown, missing, out of range,
        in the wrong unit, or inconsistent with the others.
    """
    data = dict(data)
    direct = data.pop("chair", {})
    if not isinstance(direct, Mapping):
        raise _bad("chair", repr(direct), "a table [chair] of chair fields")
    flat = _flatten(data)
    opts = {k: flat.pop(k) for k in list(flat) if k in _OPTIONS}
    opts["caster_position"] = direct.get("caster_position", "rear")
    unknown = sorted(set(flat) - set(READINGS))
    if unknown:
        raise ValueError(f"sheet entry {unknown[0]} is unknown; valid readings: {sorted(READINGS)}")
    _check_present(flat)
    if opts.get("tilt.end", "caster") not in ("caster", "main"):
        raise _bad("tilt.end", repr(opts["tilt.end"]), "'caster' or 'main'")
    if "tilt.lift" not in flat and "h" not in direct:
        raise ValueError("sheet reading tilt.lift is missing; give the axle-lift readings or [chair] h")
    readings = {k: _parse_reading(k, v) for k, v in flat.items()}
    values = {k: rd.value for k, rd in readings.items()}
    _check_weight(values, opts)
    notes = [] if "user.inertia" in readings else [_estimate_user(readings, values)]
    derived = _derive(values, opts)
    clash = sorted(set(derived) & set(direct))
    if clash:
        raise ValueError(f"sheet [chair] {clash[0]} is invalid; it is derived from the readings (remove it)")
    sens = _first_order(readings, values, opts, derived)
    fixed, dists, rows = _direct(direct)
    for f, v in derived.items():
        std = math.sqrt(sum(c * c for c in sens[f].values()))
        rows.append(ProvenanceRow(f, v, std, tuple(sens[f]), FORMULAS[f]))
        if std > 0:
            dists.append(Distribution(f, (f,), "normal", std=float(f"{std:.3g}")))
    try:
        chair = chair_mod.from_mapping({**fixed, **derived})
    except ValueError as exc:
        raise ValueError(f"sheet [chair] or derived {exc}") from None
    return SheetResult(chair, Uncertainty(tuple(dists)), tuple(rows), readings, tuple(notes))


def load_sheet(path: str | os.PathLike[str]) -> SheetResult:
    """Read and evaluate a measurement-sheet TOML file.

    Parameters
    ----------
    path : str or os.PathLike
        The sheet file (docs/measure.md shows a complete one).

    Returns
    -------
    SheetResult
        As :func:`read_sheet`.

    Raises
    ------
    ValueError
        If the file does not exist, is not valid TOML, or :func:`read_sheet` refuses it.
    """
    if not os.path.exists(path):
        raise ValueError(f"sheet {str(path)!r} does not exist")
    try:
        data = readfiles.load_toml(path)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"sheet {str(path)!r} is not valid TOML: {exc}") from None
    return read_sheet(data)
