"""The sweep spec: a TOML file naming a base chair, grid axes, random draws, speeds and measures.

::

    chair = "ej-premier"          # a preset or a chair TOML file (relative to the spec)
    model = "exact"
    friction_law = "stick-slip"   # the nonlinear measures' pin friction (or "kinetic", program WCHAIR's)
    speeds = [0.5, 0.75, 1.0]     # m/s
    measures = ["growth_rate", "critical_speeds", "critical_impulse"]
    chunk_rows = 300              # rows per chunk file (a chunk holds whole designs x draws)

    [grid]                        # any chair field, or a design parameter (pin_friction sets both pins)
    trail = [0.04, 0.05, 0.06]
    pin_friction = [0.05, 0.1, 0.15]

    [draws]                       # optional: random draws of the uncertain fields around each design
    n = 100
    seed = 0
    uncertainty = "chair.uncertainty.toml"

One row of the results per (design, draw, speed).  :data:`SCHEMA` is the
JSON Schema of the file; every check here names the key, its value and the
valid range in one line.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from stability import chair as chair_mod
from stability.chair import Chair, design
from stability.driver.model import REACTION_TIME_RANGE_S, REACTION_TIME_S, Driver
from stability.layout.io import is_layout_spec, resolve_layout
from stability.layout.model import Layout
from stability.settings.bounds import SIGNED_SPEED
from stability.settings.run import FRICTION_LAWS, MODELS, RunSpec
from stability.sweep.layouts import LAYOUT_MEASURES, check_layout_axis, check_layout_uncertainty, layout_axes
from stability.uncertainty import Uncertainty, load_uncertainty

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["INVALID", "MEASURES", "SCHEMA", "SweepSpec", "load_spec", "loads_spec", "MAX_ROWS"]

#: Measures a sweep can compute: name -> (columns it writes, cost class).  Per-speed measures fill
#: every row; per-chair ones (critical speeds, equal-instability speed) repeat on a design-draw's rows.
MEASURES: dict[str, tuple[tuple[str, ...], str]] = {
    "growth_rate": (("growth_rate_1_s",), "linear"),
    "critical_speeds": (("critical_speed_m_s", "critical_speed_status", "locked_critical_speed_m_s",
                         "locked_critical_speed_status"), "linear"),
    "critical_impulse": (("critical_impulse_Ns", "critical_impulse_status"), "nonlinear"),
    "equal_instability_speed": (("equal_instability_speed_m_s", "equal_instability_status"), "nonlinear"),
    "shimmy_margin": (("shimmy_margin_m", "shimmy_margin_status"), "linear"),
    "tip_angles": (("static_stability_deg", "tip_toward_casters_deg", "tip_toward_main_wheels_deg",
                    "tip_lateral_deg"), "statics"),
    "holding_moment": (("holding_moment_N_m_per_deg",), "statics"),
    "human_limited_speed": (("human_limited_speed_m_s", "human_limited_status"), "linear"),
    "bench": (("bench_worst_score", "level_braking_distance_m"), "statics"),
}
#: The status of a row whose chair could not be built (its measures are NaN, its ``error`` says why).
INVALID = "invalid"
#: Units of the grid's axes (chair fields), as printed and drawn.
GRID_UNITS = {"pin_friction": "N m", "trail": "m", "s1": "m", "s2": "m", "l1": "m", "h": "m", "m": "kg",
              "i_z": "kg m^2", "d1": "m", "d2": "m", "t1": "m", "t2": "m", "pin_friction_left": "N m",
              "pin_friction_right": "N m", "toe_deg": "deg", "camber_deg": "deg", "m_c": "kg", "i_zp": "kg m^2"}
#: Work bound: rows of one sweep.
MAX_ROWS = 10_000_000
_TOP = {"chair", "model", "friction_law", "speeds", "measures", "grid", "draws", "chunk_rows", "reaction_time_s"}
_NUMERIC = [f for f in chair_mod.field_names()
            if f not in ("name", "caster_position", "main_tire", "caster_tire", "camber_coefficient")]
_GROUPS = {name: p for name, p in design.DESIGN_PARAMETERS.items() if not p.categorical and name not in _NUMERIC}

SCHEMA: dict[str, Any] = {
    "$schema": "https://json-schema.org/draft/2020-12/schema",
    "title": "stability sweep spec",
    "type": "object",
    "additionalProperties": False,
    "required": ["speeds", "measures"],
    "properties": {
        "chair": {"type": "string", "description": "preset name or chair TOML file (relative to the spec)"},
        "model": {"enum": ["exact", "thesis"], "default": "exact"},
        "friction_law": {"enum": list(FRICTION_LAWS), "default": RunSpec().friction_law,
                         "description": "pin friction of the nonlinear measures' fixed-step runs"},
        "speeds": {"type": "array", "items": {"type": "number", "exclusiveMinimum": 0, "maximum": 10},
                   "minItems": 1, "description": "forward speeds, m/s"},
        "measures": {"type": "array", "minItems": 1, "uniqueItems": True,
                     "items": {"enum": sorted(MEASURES)}},
        "chunk_rows": {"type": "integer", "minimum": 1, "default": 300},
        "reaction_time_s": {"type": "number", "minimum": REACTION_TIME_RANGE_S[0],
                            "maximum": REACTION_TIME_RANGE_S[1], "default": REACTION_TIME_S,
                            "description": "the driver's effective delay of the human_limited_speed measure, s"},
        "grid": {"type": "object", "description": "axis -> values: a numeric chair field or a design parameter",
                 "propertyNames": {"enum": sorted(_NUMERIC) + sorted(_GROUPS)},
                 "additionalProperties": {"type": "array", "items": {"type": "number"}, "minItems": 1}},
        "draws": {"type": "object", "additionalProperties": False, "required": ["n", "uncertainty"],
                  "properties": {"n": {"type": "integer", "minimum": 1}, "seed": {"type": "integer", "minimum": 0},
                                 "uncertainty": {"type": "string", "description": "uncertainty TOML file"}}},
    },
}


@dataclass(frozen=True, eq=False)
class SweepSpec:
    """A checked sweep spec.

    Attributes
    ----------
    chair : Chair or Layout
        The base chair, or the base layout of a layout sweep (a layout, or reverse speeds: :mod:`.layouts`).
    chair_source : str
        Preset name or file as given.
    model : str
    speeds : tuple of float
        m/s (negative: reverse, a layout sweep).
    measures : tuple of str
    grid : tuple of (str, tuple of float)
        Axes in file order (the first two are the plot axes).
    draws : int
        Draws per design (1: the design itself, no uncertainty).
    seed : int
    uncertainty : Uncertainty or None
    chunk_rows : int
    friction_law : {"kinetic", "stick-slip"}
        Pin friction of the critical impulse's and equal-instability speed's runs.
    reaction_time_s : float
        The driver's effective delay of the ``human_limited_speed`` measure, s (:mod:`stability.driver`): the
        spec's ``reaction_time_s``, else the chair file's ``[user]``, else :data:`stability.driver.REACTION_TIME_S`.
    """

    chair: Chair | Layout
    chair_source: str
    model: str
    speeds: tuple
    measures: tuple
    grid: tuple
    draws: int
    seed: int
    uncertainty: Uncertainty | None
    chunk_rows: int
    friction_law: str = RunSpec().friction_law
    reaction_time_s: float = REACTION_TIME_S

    @property
    def designs(self) -> int:
        """Number of grid points."""
        return math.prod(len(v) for _, v in self.grid) if self.grid else 1

    @property
    def rows(self) -> int:
        """Rows of the results: designs x draws x speeds."""
        return self.designs * self.draws * len(self.speeds)

    @property
    def run(self) -> RunSpec:
        """The nonlinear measures' run settings: the spec's model and pin-friction law, the rest the defaults."""
        return RunSpec(model=self.model, friction_law=self.friction_law)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary of the spec (what a results file was made from)."""
        return {"chair": self.chair_source, "model": self.model, "friction_law": self.friction_law,
                "speeds_m_s": list(self.speeds),
                "measures": list(self.measures), "grid": {k: list(v) for k, v in self.grid},
                "draws": self.draws, "seed": self.seed, "uncertainty": None if self.uncertainty is None
                else self.uncertainty.dumps(), "chunk_rows": self.chunk_rows,
                "reaction_time_s": self.reaction_time_s}


def _bad(key: str, value: Any, valid: str) -> ValueError:
    return ValueError(f"spec {key}={value!r} is invalid; valid: {valid}")


def _numbers(key: str, value: Any, positive: bool = False) -> tuple[float, ...]:
    if not isinstance(value, list) or not value or any(isinstance(v, bool) or not isinstance(v, (int, float))
                                                       or not math.isfinite(v) for v in value):
        raise _bad(key, value, "a non-empty list of finite numbers")
    if positive and any(v <= 0 for v in value):
        raise _bad(key, value, "numbers > 0")
    return tuple(float(v) for v in value)


def _measures(value: Any) -> tuple[str, ...]:
    if not isinstance(value, list) or not value or any(not isinstance(m, str) for m in value):
        raise _bad("measures", value, f"a non-empty list of {sorted(MEASURES)}")
    for m in value:
        if m not in MEASURES:
            raise _bad("measures", m, f"one of {sorted(MEASURES)}")
    if len(set(value)) != len(value):
        raise _bad("measures", value, "each measure once")
    return tuple(value)


def _draws(draws_t: Any, base: Path, chair: Chair | Layout) -> tuple[int, int, Uncertainty | None]:
    if draws_t is None:
        return 1, 0, None
    if not isinstance(draws_t, Mapping) or set(draws_t) - {"n", "seed", "uncertainty"}:
        raise _bad("draws", draws_t, "a table [draws] with n, seed, uncertainty")
    n, seed = draws_t.get("n"), draws_t.get("seed", 0)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise _bad("draws.n", n, "an integer >= 1")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _bad("draws.seed", seed, "an integer >= 0")
    if not isinstance(draws_t.get("uncertainty"), str):
        raise _bad("draws.uncertainty", draws_t.get("uncertainty"), "an uncertainty TOML file")
    if not isinstance(chair, Layout):
        return n, seed, load_uncertainty(base / draws_t["uncertainty"])
    # a layout sweep: the tables name the layout's axes (stability.sweep.layouts)
    unc = load_uncertainty(base / draws_t["uncertainty"], valid_fields=layout_axes(chair))
    check_layout_uncertainty(chair, unc)
    return n, seed, unc


def from_mapping(data: Mapping[str, Any], base: Path | None = None) -> SweepSpec:
    """Check a parsed spec and build the :class:`SweepSpec` (ValueError in one line on bad input).

    Parameters
    ----------
    data : Mapping
        The TOML tables.
    base : Path, optional
        Directory that relative file names are read from.

    Returns
    -------
    SweepSpec
    """
    base = base or Path.cwd()
    unknown = set(data) - _TOP
    if unknown:
        raise ValueError(f"spec has unknown key(s) {sorted(unknown)}; valid keys: {sorted(_TOP)}")
    source = data.get("chair", "ej-premier")
    if not isinstance(source, str):
        raise _bad("chair", source, "a preset name or a chair TOML file")
    path = base / source
    where = str(path) if source.endswith(".toml") else source
    layout_form = is_layout_spec(where)
    chair: Chair | Layout = resolve_layout(where) if layout_form else chair_mod.resolve(where)
    model = data.get("model", RunSpec().model)
    if model not in MODELS:
        raise _bad("model", model, " or ".join(repr(m) for m in MODELS))
    friction_law = data.get("friction_law", RunSpec().friction_law)
    if friction_law not in FRICTION_LAWS:
        raise _bad("friction_law", friction_law, " or ".join(repr(m) for m in FRICTION_LAWS))
    if "speeds" not in data:
        raise ValueError("spec has no speeds; valid: speeds = [m/s, ...], each > 0")
    chair, speeds = _speeds(data["speeds"], chair, layout_form)
    if "measures" not in data:
        raise ValueError(f"spec has no measures; valid: measures = a list of {sorted(MEASURES)}")
    measures = _measures(data["measures"])
    grid_t = data.get("grid", {})
    if not isinstance(grid_t, Mapping):
        raise _bad("grid", grid_t, "a table [grid] of axis = [values]")
    grid = _grid(grid_t, chair)
    n, seed, unc = _draws(data.get("draws"), base, chair)
    if isinstance(chair, Layout):
        _check_layout(measures, model)
    chunk_rows = data.get("chunk_rows", 300)
    if isinstance(chunk_rows, bool) or not isinstance(chunk_rows, int) or chunk_rows < 1:
        raise _bad("chunk_rows", chunk_rows, "an integer >= 1")
    # the chair file's [user] when the spec names no driver, as every command's --chair reads it
    user = chair_mod.user_table(where) if where.endswith(".toml") else None
    tau = data.get("reaction_time_s", REACTION_TIME_S if user is None else Driver.from_mapping(user).reaction_time_s)
    lo, hi = REACTION_TIME_RANGE_S
    if isinstance(tau, bool) or not isinstance(tau, (int, float)) or not (math.isfinite(tau) and lo <= tau <= hi):
        raise _bad("reaction_time_s", tau, f"a number of s from {lo:g} to {hi:g}")
    spec = SweepSpec(chair, source, model, speeds, measures, grid, int(n), int(seed), unc, chunk_rows,
                     friction_law, float(tau))
    if spec.rows > MAX_ROWS:
        raise ValueError(f"spec asks for {spec.rows} rows (designs x draws x speeds); valid: at most {MAX_ROWS}")
    return spec


def _speeds(value: Any, chair: Chair | Layout, layout_form: bool) -> tuple[Chair | Layout, tuple[float, ...]]:
    """The speeds, and the base chair as a layout when it is one or a speed is negative (reverse)."""
    speeds = _numbers("speeds", value)
    if layout_form or any(u < 0 for u in speeds):       # a layout, or reverse: the layout sweep (sweep.layouts)
        if not all(SIGNED_SPEED.holds(u) for u in speeds):
            raise _bad("speeds", value, f"numbers with {SIGNED_SPEED.text('speed')} (negative: reverse)")
        return (chair if isinstance(chair, Layout) else Layout.from_chair(chair)), speeds
    if any(u <= 0 for u in speeds):
        raise _bad("speeds", value, "numbers > 0 (or a negative one: the layout sweep in reverse)")
    return chair, speeds


def _grid(grid_t: Mapping[str, Any], chair: Chair | Layout) -> tuple:
    """The grid's axes in file order, each checked against the chair's fields or the layout's axes."""
    grid = []
    for axis, values in grid_t.items():
        if isinstance(chair, Layout):
            check_layout_axis(chair, axis)
        elif axis not in _NUMERIC and axis not in _GROUPS:
            raise _bad("grid", axis, f"a numeric chair field {_NUMERIC} or a design parameter {sorted(_GROUPS)}")
        grid.append((axis, _numbers(f"grid.{axis}", values)))
    return tuple(grid)


def _check_layout(measures: tuple, model: str) -> None:
    """What a layout sweep (a layout, or reverse speeds) refuses, in one line each."""
    other = [m for m in measures if m not in LAYOUT_MEASURES]
    if other:
        raise _bad("measures", other, f"for a layout or reverse speeds one of {list(LAYOUT_MEASURES)}")
    if model != "exact":
        raise _bad("model", model, "'exact' for a layout or reverse speeds (the layout's equations)")


def loads_spec(text: str, base: Path | None = None) -> SweepSpec:
    """Parse spec TOML text.

    Parameters
    ----------
    text : str
        The spec (see :func:`from_mapping`).
    base : Path, optional
        Directory that relative file names are read from (default: the working directory).

    Returns
    -------
    SweepSpec
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"spec is not valid TOML: {exc}") from None
    return from_mapping(data, base)


def load_spec(path: str | os.PathLike[str]) -> SweepSpec:
    """Read a spec file (relative file names in it are read next to it).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    SweepSpec
    """
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"spec file {str(path)!r} does not exist")
    return loads_spec(p.read_text(), p.parent)


def apply_axis(chair: Chair, axis: str, value: float) -> Chair:
    """The chair with one grid axis set.

    Parameters
    ----------
    chair : Chair
    axis : str
        A numeric chair field, or a design parameter such as ``pin_friction`` (both pins).
    value : float

    Returns
    -------
    Chair
    """
    if axis in _GROUPS:
        return _GROUPS[axis].apply(chair, value)
    return chair.replace(**{axis: value})
