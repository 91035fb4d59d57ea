"""Every measure the advisor weighs, for wheel layouts, forward or in reverse: the layout studies' answers.

The measures of a layout are what the commands print for it, as for the short form (:mod:`.measures`):

- ``critical_impulse_Ns``: ``python -m stability.study critical-impulse --chair LAYOUT --speeds 0.75`` (or -0.75
  in reverse; :func:`stability.study.layout_impulse.layout_critical_impulses`), with the short form's interval
  over pin friction x0.5/x1.5 and half the simulator step (no model variant: a layout's equations are the exact
  model's);
- ``equal_instability_speed_m_s``: ``python -m stability.study equal-instability --chair LAYOUT [--reverse]``
  (:func:`stability.study.layout_equal_instability.layout_equal_instability_interval`);
- ``static_stability_deg``: the smallest of ``python -m stability.tipping``'s four ISO 7176-1 angles of the layout
  (tip lines between the outermost contacts: :func:`stability.layout.statics.tip_angles`; keys ``forward``,
  ``backward``, ``left``, ``right``);
- ``shimmy_margin_m``: the smallest over the caster rows of ``python -m stability.shimmy --chair LAYOUT``'s margins
  (each row's towed wheel at its own static load, :mod:`stability.shimmy.layout_caster`), with the row that sets
  it (``shimmy_row``, ``shimmy_trail_m``);
- ``turning_effort_N_m``: the largest pin friction of any caster;
- ``growth_rate_1_s``: the layout's linear model at 0.75 m/s (or -0.75);
- ``bench_score``: ``python -m stability.bench``'s worst score for a layout with driven wheels.

- ``cross_slope_effort``: ``python -m stability.slope --chair LAYOUT --cross-slope D --speed 0.75`` (or -0.75)'s
  drive difference, right minus left (:func:`layout_cross_slope_effort`: the layout slope statics of
  :mod:`stability.study.layout_slope` with the short form's drive report): the hand-rim force difference (N) of a
  layout without driven wheels, the motor torque difference (N m) of a powered one;
- ``human_speed_m_s``: the divergence rule of :func:`stability.driver.linear.rule_speed` on the layout's linear
  model in the direction of travel (:func:`layout_rule_speed`): the speed (its size) at which the layout's
  largest growth rate reaches ``1 / reaction_time``.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from functools import partial
from typing import Any, cast

from stability.advise.layout_levers import caster_rows, row_name
from stability.advise.lazy import reused
from stability.advise.measures import IMPULSE_SPEED, Interval, LazyLinear, Measures
from stability.bench import run_bench
from stability.driver.layout import layout_rule_speed
from stability.layout.linear import growth_rates
from stability.layout.model import Layout
from stability.layout.statics import tip_angles
from stability.runtime.progress import ProgressBar
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.shimmy.band import ShimmyBand, band_core, shimmy_band
from stability.shimmy.layout_caster import LayoutCaster
from stability.simulate.options import WCHAIR_DT
from stability.study.layout_equal_instability import (
    layout_equal_instability_interval,
    layout_summaries,
)
from stability.study.layout_impulse_intervals import layout_critical_impulse_intervals
from stability.study.runs import study_run

__all__ = ["direction_of", "layout_linear", "layout_linear_measures", "layout_nonlinear_measures", "measure_layouts",
           "layout_time_to_correct", "layout_shimmy_rows", "layout_cross_slope_effort", "layout_rule_speed"]


def direction_of(speeds: Sequence[float]) -> bool:
    """Whether the use speeds are backwards (all negative); mixed signs are refused.

    Parameters
    ----------
    speeds : sequence of float
        m/s.

    Returns
    -------
    bool
        True in reverse.
    """
    neg = [float(u) < 0 for u in speeds]
    if any(neg) and not all(neg):
        raise ValueError(f"speeds={tuple(speeds)!r} is invalid; valid: all forward (> 0) or all in reverse (< 0)")
    return bool(neg) and all(neg)


def _core_key(layout: Layout, row: list[int]) -> tuple:
    """What a row's band core depends on: the layout with that row's trail and pin friction set aside (the band
    search scans the row's trail, the loads following, and ignores the Coulomb pin friction)."""
    casters = tuple(dataclasses.replace(c, trail=0.05, pin_friction=0.0) if k in row else c
                    for k, c in enumerate(layout.casters))
    return dataclasses.replace(layout, name="-", casters=casters), row[0]


def layout_shimmy_rows(layout: Layout, speeds: Sequence[float],
                       cores: dict | None = None) -> list[tuple[str, float, ShimmyBand]]:
    """Each caster row's shimmy band at the use speeds: ``(row name, trail m, ShimmyBand)``, front first.

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        m/s (all negative: in reverse, where each caster has swung round and trails the other way, the towed wheel
        at the speeds' sizes with the load of the casters trailing backwards,
        :class:`stability.shimmy.layout_caster.LayoutCaster` ``reverse=True``, as ``python -m stability.shimmy``
        answers negative speeds).
    cores : dict, optional
        Band cores to share between calls (:func:`stability.shimmy.band.band_core`), keyed by what they depend on.

    Returns
    -------
    list of tuple
    """
    reverse = direction_of(speeds)
    u = [abs(float(s)) for s in speeds]
    cores = {} if cores is None else cores
    out = []
    for row in caster_rows(layout):
        key = (_core_key(layout, row), tuple(u), reverse)
        if key not in cores:
            cores[key] = band_core(LayoutCaster(key[0][0], row[0], reverse), u)
        out.append((row_name(layout, row), layout.casters[row[0]].trail,
                    shimmy_band(LayoutCaster(layout, row[0], reverse), u, core=cores[key])))
    return out


def layout_cross_slope_effort(layout: Layout, cross_slope_deg: float, reverse: bool = False) -> float | None:
    """The drive difference (right minus left) that holds ``layout`` on the cross slope at :data:`IMPULSE_SPEED`.

    Parameters
    ----------
    layout : Layout
    cross_slope_deg : float
        deg (0: level, no effort).
    reverse : bool
        Backwards (at ``-IMPULSE_SPEED``, the casters trailing the other way).

    Returns
    -------
    float or None
        Hand-rim force difference (N) of a layout without driven wheels, motor torque difference (N m) of a
        powered one (the short form's :func:`stability.slope.equilibrium.drive_report` on the layout's drive
        forces); None where the slope statics refuse the layout or find no equilibrium.
    """
    if cross_slope_deg == 0:
        return 0.0
    from types import SimpleNamespace
    from typing import Any, cast

    from stability.slope.equilibrium import drive_report
    from stability.study.layout_slope import layout_drive_forces

    try:    # the equilibrium's drive forces (layout_equilibrium's, without its pin-friction range)
        forces = layout_drive_forces(layout, cross_slope_deg, -IMPULSE_SPEED if reverse else IMPULSE_SPEED)
    except ValueError:
        return None
    kind = "motor" if any(w.driven for w in layout.wheels) else "handrim"
    shim = SimpleNamespace(drive_forces=forces, cross_slope_deg=float(cross_slope_deg))
    rep = drive_report(cast(Any, None), cast(Any, shim), kind)
    if kind == "handrim":
        return float(rep["handrim_force_difference_N"])
    return float(rep["motor_torque_right_N_m"] - rep["motor_torque_left_N_m"])


def layout_linear(lay: Layout, *, speeds: Sequence[float], cores: dict, cross_slope_deg: float = 0.0,
                  reaction_time: float | None = None) -> LazyLinear:
    """One layout's measures that need no simulation, each computed when first read (:func:`layout_linear_measures`).

    Parameters
    ----------
    lay : Layout
    speeds, cores, cross_slope_deg, reaction_time
        As :func:`layout_linear_measures` (``cores`` is filled as the shimmy rows are read).

    Returns
    -------
    LazyLinear
    """
    reverse = direction_of(speeds)
    sign = -1.0 if reverse else 1.0
    driven = any(w.driven for w in lay.wheels)

    def tips() -> dict[str, Any]:
        angles = {k.removesuffix("_deg"): float(v) for k, v in tip_angles(lay).items()}
        smallest = min(angles.values())
        return {"static_stability_deg": Interval(smallest, smallest, smallest), "tip_angles_deg": angles}

    def rows() -> dict[str, Any]:
        found = layout_shimmy_rows(lay, speeds, cores)
        if not found:
            return {"shimmy_margin_m": Interval(None, None, None), "shimmy_straddles": False, "shimmy_row": "",
                    "shimmy_trail_m": None}
        name, trail, band = min(found, key=lambda r: r[2].shimmy_margin_m)
        low, high = band.shimmy_margin_interval_m
        return {"shimmy_margin_m": Interval(float(band.shimmy_margin_m), float(low), float(high)),
                "shimmy_straddles": any(r[2].straddles for r in found), "shimmy_row": name, "shimmy_trail_m": trail}

    def human() -> dict[str, Any]:
        u, side = layout_rule_speed(lay, reaction_time, reverse) if reaction_time is not None else (None, "=")
        return {"human_speed_m_s": u, "human_side": side}

    return LazyLinear({               # the order of the eager measures before (tire-range warnings in that order)
        "tips": (("static_stability_deg", "tip_angles_deg"), tips),
        "rows": (("shimmy_margin_m", "shimmy_straddles", "shimmy_row", "shimmy_trail_m"), rows),
        "human": (("human_speed_m_s", "human_side"), human),
        "turning": (("turning_effort_N_m",),
                    lambda: {"turning_effort_N_m": max((c.pin_friction for c in lay.casters), default=0.0)}),
        "slope": (("cross_slope_effort",),
                  lambda: {"cross_slope_effort": layout_cross_slope_effort(lay, cross_slope_deg, reverse)}),
        "drive": (("drive",), lambda: {"drive": "motor" if driven else "handrim"}),
        "growth": (("growth_rate_1_s",),
                   lambda: {"growth_rate_1_s": float(growth_rates(lay, [sign * IMPULSE_SPEED])[0])}),
        "bench": (("bench_score",), lambda: {"bench_score": run_bench(lay).worst_score if driven else None})})


def layout_linear_measures(layouts: Sequence[Layout], *, speeds: Sequence[float], cores: dict | None = None,
                           cross_slope_deg: float = 0.0, reaction_time: float | None = None,
                           lazy: bool = False) -> list:
    """The measures that need no simulation, for every layout (the constraints of the advisor).

    Parameters
    ----------
    layouts : sequence of Layout
    speeds : sequence of float
        Use speeds, m/s (negative: reverse; the growth rate is taken at :data:`~.measures.IMPULSE_SPEED` in the
        direction of travel).
    cores : dict, optional
        Shimmy band cores shared between calls (:func:`layout_shimmy_rows`), and each layout's measures computed so
        far (:func:`.lazy.reused`).
    cross_slope_deg : float
        deg: the cross-slope drive difference (:func:`layout_cross_slope_effort`; 0: none).
    reaction_time : float, optional
        A driver's effective delay, s: adds the human-limited speed (:func:`layout_rule_speed`).
    lazy : bool
        Return each layout's :class:`~.measures.LazyLinear` (a measure computed when read) instead of its Linear.

    Returns
    -------
    list of Linear (or of LazyLinear)
    """
    cores = {} if cores is None else cores
    inputs = (tuple(speeds), cross_slope_deg, reaction_time)
    out = [cast(LazyLinear, reused(cores, lay, inputs, partial(layout_linear, lay, speeds=speeds, cores=cores,
                                                              cross_slope_deg=cross_slope_deg,
                                                              reaction_time=reaction_time))) for lay in layouts]
    return out if lazy else [x.linear() for x in out]


def _critical(layouts: list[Layout], speed: float) -> list[tuple[Interval, str, float | None]]:
    """Critical impulse with its range over pin friction and half the step (the short form's, less the model:
    :func:`stability.study.layout_impulse_intervals.layout_critical_impulse_intervals`)."""
    out = []
    for lay in layouts:
        iv = layout_critical_impulse_intervals(lay, speed, RunSpec(dt=WCHAIR_DT))[0]
        half = [r.bound_Ns for label, r in iv.variants if label.endswith(" ms step")]
        out.append((Interval(float(iv.point.bound_Ns), iv.low_Ns, iv.high_Ns), iv.point.status,
                    float(half[0]) if half else None))
    return out


def layout_nonlinear_measures(layouts: Sequence[Layout], reverse: bool = False
                              ) -> list[tuple[Interval, Interval, str, str, float | None]]:
    """Critical impulse and equal-instability speed (with intervals) of every layout, as
    :func:`.measures.nonlinear_measures` for the short form.

    Parameters
    ----------
    layouts : sequence of Layout
    reverse : bool
        Backwards: the critical impulse at ``-IMPULSE_SPEED``, the equal-instability speed backwards.

    Returns
    -------
    list of tuple
        ``(critical_impulse_Ns, equal_instability_speed_m_s, equal_instability_status, critical_impulse_status,
        critical_impulse_half_step_Ns)`` per layout.
    """
    layouts = list(layouts)
    ci = _critical(layouts, -IMPULSE_SPEED if reverse else IMPULSE_SPEED)
    out = []
    for lay, (imp, status, half) in zip(layouts, ci, strict=True):
        eq = layout_equal_instability_interval(lay, reverse=reverse)
        out.append((imp, Interval(float(eq.point.value_or_bound), eq.low, eq.high), eq.point.status, status, half))
    return out


def measure_layouts(layouts: Sequence[Layout], *, speeds: Sequence[float], progress: bool = False,
                    nonlinear: Callable | None = None, cores: dict | None = None, cross_slope_deg: float = 0.0,
                    reaction_time: float | None = None) -> list[Measures]:
    """The advisor's measures of every layout (:func:`.measures.measure_chairs` for layouts).

    Parameters
    ----------
    layouts : sequence of Layout
    speeds : sequence of float
        Use speeds, m/s (all negative: reverse).
    progress : bool
    nonlinear : callable, optional
        Replaces :func:`layout_nonlinear_measures` (``nonlinear(layouts)``); for tests of everything else.
    cores : dict, optional
        Shimmy band cores shared between calls (:func:`layout_shimmy_rows`).
    cross_slope_deg, reaction_time
        As :func:`layout_linear_measures`.

    Returns
    -------
    list of Measures
    """
    layouts = list(layouts)
    reverse = direction_of(speeds)
    with ProgressBar(2, f"measuring {len(layouts)} layout(s)", enabled=progress, unit="step") as bar:
        nl = nonlinear(layouts) if nonlinear is not None else layout_nonlinear_measures(layouts, reverse)
        bar.update()
        out = []
        lins = layout_linear_measures(layouts, speeds=speeds, cores=cores, cross_slope_deg=cross_slope_deg,
                                      reaction_time=reaction_time)
        for lay, lin, (imp, eq, status, *more) in zip(layouts, lins, nl, strict=True):
            out.append(Measures(
                chair=lay.name, critical_impulse_Ns=imp, equal_instability_speed_m_s=eq,
                static_stability_deg=lin.static_stability_deg, shimmy_margin_m=lin.shimmy_margin_m,
                shimmy_straddles=lin.shimmy_straddles, turning_effort_N_m=lin.turning_effort_N_m,
                cross_slope_effort=lin.cross_slope_effort, growth_rate_1_s=lin.growth_rate_1_s,
                tip_angles_deg=lin.tip_angles_deg,
                equal_instability_status=status, critical_impulse_status=more[0] if more else "found",
                critical_impulse_half_step_Ns=more[1] if len(more) > 1 else None, drive=lin.drive,
                bench_score=lin.bench_score, shimmy_row=lin.shimmy_row, shimmy_trail_m=lin.shimmy_trail_m,
                human_speed_m_s=lin.human_speed_m_s, human_side=lin.human_side))
        bar.update()
    return out


def layout_time_to_correct(layout: Layout, speed: float, level: float = 1.0) -> float:
    """Time after the thesis's push until ``|yaw rate|`` reaches ``level``, every caster trailing at the start.

    Parameters
    ----------
    layout : Layout
    speed : float
        m/s (negative: reverse).
    level : float
        rad/s.

    Returns
    -------
    float
        s.  Raises ValueError when the level is not reached within the run (10 s), as
        :func:`stability.study.reference_time` does.
    """
    s = layout_summaries([layout], [abs(float(speed))], [THESIS_PUSH.force], study_run(RunSpec()), level=level,
                         reverse=speed < 0)
    t = float(s.t_level[0])
    if not math.isfinite(t) or t > s.sim_time[0]:
        raise ValueError(f"{layout.name} at {speed:g} m/s never reaches {level:g} rad/s within {s.sim_time[0]:g} s")
    return t
