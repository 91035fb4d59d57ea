"""What the explorer computes in the background for one chair: the simulator's measures and the trail window.

Both come from the toolkit's own functions and run on the session's background
worker (:mod:`stability.app.jobs`); the linear views never wait for them.

* :func:`nonlinear_view`: the yaw-rate response to a push (the compiled WCHAIR
  simulator and the linear model), the time to the thesis's criterion, the
  critical impulse and the equal-instability speed with the ranges
  ``python -m stability.study ... --interval`` prints, and every warning the
  simulator raised on the way (shown next to the result it qualifies).
* :func:`trail_window`: yaw growth and caster shimmy against trail from the
  chair model with relaxation-length caster tires on compliant pins (the model
  whose boundary is the shimmy-free band's), the band itself and a cross slope.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.settings import defaults as D

__all__ = ["NonlinearView", "nonlinear_view", "response", "warning_lines", "TrailWindow", "trail_window", "TRAILS",
           "TRAIL_SPEEDS", "TRAIL_PIN"]


def warning_lines(caught: list) -> tuple[str, ...]:
    """The distinct warnings caught while computing, as ``"Kind: message"`` lines (first line of each).

    Parameters
    ----------
    caught : list of warnings.WarningMessage
        What :func:`warnings.catch_warnings` recorded.

    Returns
    -------
    tuple of str
        In the order first raised, each once.
    """
    out: dict[str, None] = {}
    for w in caught:
        text = str(w.message).splitlines()[0] if str(w.message) else ""
        out[f"{w.category.__name__}: {text}"] = None
    return tuple(out)


@dataclass(frozen=True)
class NonlinearView:
    """The nonlinear measures the explorer computes in the background for one chair.

    Attributes
    ----------
    chair : Chair
    model : str
    speed : float
        m/s.
    push : tuple of float
        Force (N) and duration (s) of the push at the c.g.
    t, yaw_rate : ndarray
        The simulator's run (WCHAIR scheme), s and rad/s.
    linear_t, linear_yaw_rate : ndarray
        The linear model's response to the same push, s and rad/s.
    time_to_level : float
        Time for the run's ``|yaw rate|`` to reach :data:`stability.settings.defaults.YAW_RATE_LEVEL` (the
        thesis's criterion), s; +inf when it does not within the simulated time.
    critical_impulse : CriticalImpulseInterval
        Smallest push that spins the chair (``|yaw rate|`` 1 rad/s within 10 s) at ``speed`` with its range
        over pin friction, model and step (:func:`stability.study.critical_impulse_intervals`).
    equal_instability : EqualInstabilityInterval or None
        Speed at which the chair is as unstable as the thesis's reference case, with its range
        (:func:`stability.study.equal_instability_interval`; None: not computed).
    warnings : tuple of str
        Every distinct warning the simulator and the searches raised (``"Kind: message"``).
    """

    chair: Chair
    model: str
    speed: float
    push: tuple[float, float]
    t: np.ndarray
    yaw_rate: np.ndarray
    linear_t: np.ndarray
    linear_yaw_rate: np.ndarray
    time_to_level: float
    critical_impulse: Any
    equal_instability: Any
    warnings: tuple[str, ...] = ()


def response(chair: Chair, model: str, speed: float, push: tuple[float, float], duration: float = D.HORIZON_S):
    """The yaw-rate response to a push: the simulator's run and the linear model's, as ``(run, t_lin, r_lin)``.

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    speed : float
        m/s.
    push : (float, float)
        Force at the c.g. (N) and its duration (s).
    duration : float
        Simulated time, s (default the criterion's horizon).

    Returns
    -------
    tuple
        The simulator's :class:`~stability.simulate.SimulationResult`, then the linear response's times (s)
        and yaw rates (rad/s).
    """
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.study import linear_impulse_response

    run = simulate(chair, speed, RunSpec(horizon=duration, model=model, push_force=push[0], push_duration=push[1]))
    lin = linear_impulse_response(chair, speed, duration, impulse=push, model=model)
    return run, lin.t, lin.yaw_rate


def nonlinear_view(chair: Chair, model: str, speed: float, push: tuple[float, float],
                   equal_instability: bool = True) -> NonlinearView:
    """Run the simulator for the response, the critical impulse and the equal-instability speed (with ranges).

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    speed : float
        m/s.
    push : (float, float)
        Force (N), duration (s).
    equal_instability : bool
        Also the equal-instability speed (:func:`stability.study.equal_instability_interval`).

    Returns
    -------
    NonlinearView
    """
    from stability.settings.run import RunSpec
    from stability.study import critical_impulse_intervals, equal_instability_interval
    from stability.study.criteria import DEFAULT_CRITERION

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run, tl, rl = response(chair, model, speed, push)
        ci = critical_impulse_intervals([chair], speed, run=RunSpec(model=model, push_duration=push[1]))[0]
        eq = equal_instability_interval(chair, run=RunSpec(model=model)) if equal_instability else None
    return NonlinearView(chair, model, speed, push, np.asarray(run.t), np.asarray(run.yaw_rate), tl, rl,
                         DEFAULT_CRITERION.time(run), ci, eq, warning_lines(caught))


#: Trails of the trail window, m: the shimmy-free band's search range (:data:`stability.shimmy.band.TRAIL_SEARCH_M`,
#: 1 mm to 25 cm), so both of a band's boundaries are on the chart.
TRAILS = np.linspace(0.005, 0.25, 50)
#: Speeds of the trail window, m/s.
TRAIL_SPEEDS = (0.5, 1.0, 1.5)
#: The caster pins of the trail window's chair model: on the lateral spring of the band's towed wheel.
TRAIL_PIN = "compliant"


@dataclass(frozen=True)
class TrailWindow:
    """The trail trade-off for one chair: directional stability and caster shimmy against trail, and a cross slope.

    Attributes
    ----------
    chart : ChairTrailChart
        :func:`stability.shimmy.chair_trail_chart` over :data:`TRAILS` x :data:`TRAIL_SPEEDS` with the caster
        pins on their lateral spring (:data:`TRAIL_PIN`, the exact model: the only one with that pin): growth
        rate of the yaw mode and real part of the shimmy mode (1/s).  Its shimmy curves cross zero at the
        band's boundaries (a symmetric chair's least damped caster mode is the towed wheel's, docs/shimmy.md).
    band : ShimmyBand
        :func:`stability.shimmy.band.shimmy_band` at :data:`TRAIL_SPEEDS`: the shimmy-free trail band(s), every
        boundary, the chair's margin (m) and damping ratio, and whether the estimate range straddles a boundary.
    slope : Equilibrium
        :func:`stability.slope.solve` on the cross slope at the speed: the holding moment (N m).
    handrim : dict
        :func:`stability.slope.drive_report` (hand-rim forces and their difference, N).
    cross_slope_deg, speed : float
        The cross slope (deg) and speed (m/s) of ``slope``.
    warnings : tuple of str
        Every distinct warning raised while computing (``"Kind: message"``).
    """

    chart: Any
    band: Any
    slope: Any
    handrim: dict
    cross_slope_deg: float
    speed: float
    warnings: tuple[str, ...] = ()


def trail_window(chair: Chair, model: str = D.MODEL, cross_slope_deg: float = 2.0, speed: float = 1.0) -> TrailWindow:
    """Compute the trail window (see :class:`TrailWindow`).

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}
        The equations of the cross slope; the trail chart uses the exact model (compliant pins).
    cross_slope_deg : float
        deg, positive falling to the right.
    speed : float
        m/s.

    Returns
    -------
    TrailWindow
    """
    from stability.shimmy import chair_trail_chart
    from stability.shimmy.band import shimmy_band
    from stability.slope import drive_report, solve

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        chart = chair_trail_chart(chair, TRAILS, TRAIL_SPEEDS, model="exact", pin=TRAIL_PIN)
        band = shimmy_band(chair, TRAIL_SPEEDS)
        eq = solve(chair, cross_slope_deg, speed)
        handrim = drive_report(chair, eq)
    return TrailWindow(chart, band, eq, handrim, cross_slope_deg, speed, warning_lines(caught))
