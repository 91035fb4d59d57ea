"""Linear versus nonlinear: the simulated growth rate against the dominant eigenvalue, and the
simulator's own linearisation against the symbolic model (what the linear model leaves out).

See ``docs/validation.md`` for the method (fitting windows, Prony's method for complex pairs).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.simulate.signals import growth_rate

__all__ = ["RateComparison", "measured_rate", "linear_vs_nonlinear", "LinearisationCheck", "omitted_effects",
           "has_rolling_resistance", "with_rolling_resistance", "linearisation_check"]


@dataclass(frozen=True)
class RateComparison:
    """Result of :func:`linear_vs_nonlinear`.

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    model, casters, scheme : str
        Variant, caster condition and integration scheme.
    eigenvalue : complex
        Dominant eigenvalue of the linear model (1/s).
    rate_linear : float
        Its real part (1/s): growth (> 0) or decay (< 0) rate.
    rate_nonlinear : float
        Rate measured from the simulated yaw rate (1/s).
    relative_error : float
        ``|rate_nonlinear - rate_linear| / |rate_linear|``.
    window : tuple of float
        Fitting window (s).
    max_slip_deg : float
        Largest slip angle in the window (deg); the comparison is only
        meaningful below 1 deg.
    """

    speed: float
    model: str
    casters: str
    scheme: str
    eigenvalue: complex
    rate_linear: float
    rate_nonlinear: float
    relative_error: float
    window: tuple
    max_slip_deg: float


def measured_rate(t: np.ndarray, y: np.ndarray, oscillatory: bool, window: tuple[float, float]) -> float:
    """Exponential rate of ``y(t)`` inside ``window`` (1/s); see :func:`stability.simulate.signals.growth_rate`.

    Parameters
    ----------
    t : ndarray
        Uniformly sampled time, s.
    y : ndarray
        The signal at ``t`` (here the yaw rate, rad/s); non-finite samples
        are ignored.
    oscillatory : bool
        True: fit a complex pair by Prony's method of order 2
        (``sigma = ln|z| / dt``); False: least-squares slope of ``log|y|``
        (a single real mode; ``y`` must keep one sign in the window).
    window : tuple of float
        ``(start, end)`` of the fit, s; must hold at least 8 samples.

    Returns
    -------
    float
        Growth (> 0) or decay (< 0) rate, 1/s: the real part of the
        dominant mode's eigenvalue.

    Raises
    ------
    ValueError
        Fewer than 8 samples in the window, or a sign change of ``y`` in it
        for a real mode.
    """
    return growth_rate(t, y, oscillatory, window)


def linear_vs_nonlinear(chair: Chair, speed: float, *, model: str = "thesis", casters: str = "free",
                        scheme: str = "wchair", impulse_force: float = 0.4, impulse_duration: float = 0.1,
                        dt: float = 0.001, duration: float | None = None) -> RateComparison:
    """Compare the simulated yaw-rate growth/decay rate with the linear model's eigenvalue.

    The chair's pins are made frictionless (``pin_friction_* = 0``,
    ``pin_damping = 0``): Coulomb friction has no linearisation.  The
    default disturbance, 0.4 N for 0.1 s at the c.g., is 1 % of the
    thesis's reference impulse, which keeps every slip angle far below 1 deg.

    Parameters
    ----------
    chair : Chair
        The chair; its pin friction and damping are set to zero here.
    speed : float
        Forward speed (m/s, > 0).
    model : {"thesis", "exact"}
        Variant, the same for both the linear model and the simulator.
    casters : {"free", "locked"}
        Caster condition, the same for both.
    scheme : {"wchair", "adaptive"}
        Integration scheme of the simulator.
    impulse_force, impulse_duration : float
        Lateral force at the c.g. (N) and its duration (s).  Keep the push
        small enough that the slip angles stay below 1 deg (check
        ``max_slip_deg`` of the result).
    dt : float
        Time step of the wchair scheme (s); also the sampling interval.
    duration : float, optional
        Simulated time (s); by default long enough for the dominant mode to
        separate from the others and change by a factor e^3.

    Returns
    -------
    RateComparison
        The dominant eigenvalue, both rates, their relative difference, the
        fitting window and the largest slip angle in it.
    """
    from stability import linear
    from stability.settings.run import RunSpec
    from stability.simulate import simulate

    c = chair.replace(pin_friction_left=0.0, pin_friction_right=0.0, pin_damping=0.0)
    eigs = np.linalg.eigvals(linear.state_matrices(c, speed, model, casters)[0])
    order = np.argsort(-eigs.real)
    lam = complex(eigs[order[0]])
    oscillatory = abs(lam.imag) > 1e-6 * max(1.0, abs(lam))
    # the next distinct mode (skip the conjugate of an oscillatory dominant pair)
    others = [e for e in eigs[order[1:]] if not (oscillatory and abs(e - lam.conjugate()) < 1e-9 * abs(lam))]
    gap = lam.real - max(e.real for e in others) if others else 1.0
    t_start = impulse_duration + 8.0 / max(gap, 1e-3)
    span = 3.0 / max(abs(lam.real), 1e-3)
    if oscillatory:
        span = max(span, 4 * 2 * math.pi / abs(lam.imag))
    if duration is None:
        duration = t_start + span
    res = simulate(c, speed, RunSpec(horizon=duration, scheme=scheme, model=model, dt=dt, push_force=impulse_force,
                                     push_duration=impulse_duration, casters=casters, stop_on_warnings=False,
                                     sample=dt if scheme == "adaptive" else None))
    window = (t_start, min(duration, t_start + span))
    rate = measured_rate(res.t, res.yaw_rate, oscillatory, window)
    sel = (res.t >= window[0]) & (res.t <= window[1])
    slips = np.asarray(res.slip_deg)
    max_slip = float(np.nanmax(np.abs(slips[sel]))) if slips.size else float("nan")
    return RateComparison(
        speed=float(speed), model=model, casters=casters, scheme=scheme, eigenvalue=lam,
        rate_linear=float(lam.real), rate_nonlinear=rate,
        relative_error=abs(rate - lam.real) / max(abs(lam.real), 1e-12),
        window=window, max_slip_deg=max_slip,
    )


# ---------------------------------------------------------------------------
# symbolic linear model vs the simulator's own linearisation
# ---------------------------------------------------------------------------
def has_rolling_resistance(chair: Chair) -> bool:
    """Whether the simulator applies rolling resistance to any of the chair's tires.

    Parameters
    ----------
    chair : Chair
        The chair.

    Returns
    -------
    bool
        True if ``main_rolling_scale`` (TXMOD) or ``caster_rolling_scale``
        (CXMOD) is non-zero.  The thesis's studies have both zero.
    """
    return chair.main_rolling_scale != 0.0 or chair.caster_rolling_scale != 0.0


def with_rolling_resistance(chair: Chair) -> Chair:
    """``chair`` itself if it has rolling resistance, else with the tire fits' rolling resistance on.

    Parameters
    ----------
    chair : Chair
        The chair.

    Returns
    -------
    Chair
        ``chair`` unchanged if :func:`has_rolling_resistance`; otherwise a
        copy with ``main_rolling_scale = caster_rolling_scale = 1`` (the
        rolling resistance of the tire fits as measured) for each tire that
        has rolling-resistance data (a tire without, e.g. PU or a user's CSV
        of lateral forces, keeps scale 0: no rolling resistance is invented).
    """
    if has_rolling_resistance(chair):
        return chair
    changes = {f"{role}_rolling_scale": 1.0 for role, model in (("main", chair.main_tire_model()),
                                                                  ("caster", chair.caster_tire_model()))
               if model.capabilities.rolling}
    return chair.replace(**changes) if changes else chair


def omitted_effects(chair: Chair) -> tuple[str, ...]:
    """What the simulator has and the linear model leaves out, for this chair.

    The linear model (lateral tire forces linear in slip
    at the static loads) has no rolling resistance, camber or toe; a chair
    with none of them is linearised exactly (see :func:`linearisation_check`).

    Parameters
    ----------
    chair : Chair
        The chair.

    Returns
    -------
    tuple of str
        Labels such as ``"rolling resistance"``, ``"camber 2 deg"``,
        ``"toe 1 deg"``, in that order; empty when the chair has none.
    """
    out = []
    if has_rolling_resistance(chair):
        out.append("rolling resistance")
    if chair.camber_deg != 0.0:
        out.append(f"camber {chair.camber_deg:g} deg")
    if chair.toe_deg != 0.0:
        out.append(f"toe {chair.toe_deg:g} deg")
    return tuple(out)


@dataclass(frozen=True)
class LinearisationCheck:
    """Result of :func:`linearisation_check`.

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    model, casters : str
    omitted : tuple of str
        :func:`omitted_effects` of the chair.
    eigenvalue_linear, eigenvalue_simulator : complex
        Dominant eigenvalue (largest real part, 1/s) of the symbolic linear
        model and of the simulator's linearisation.
    rate_difference : float
        ``(Re eigenvalue_simulator - Re eigenvalue_linear) / |Re eigenvalue_linear|``.
    matrix_difference : float
        ``max |A_simulator - A_linear| / max |A_linear|``.
    """

    speed: float
    model: str
    casters: str
    omitted: tuple
    eigenvalue_linear: complex
    eigenvalue_simulator: complex
    rate_difference: float
    matrix_difference: float


def linearisation_check(chair: Chair, speed: float = 0.75, *, model: str = "exact",
                        casters: str = "free") -> LinearisationCheck:
    """Compare :func:`stability.linear.state_space` with :func:`stability.simulate.linearise`.

    Both are taken without pin damping (the simulator has none; Coulomb pin
    friction has no linearisation).  With no :func:`omitted_effects` the two
    must agree to rounding (tested); otherwise the difference measures what
    the linear model leaves out, e.g. rolling resistance, whose drag pitches
    load from the casters to the main wheels of a rear-caster chair.

    Parameters
    ----------
    chair : Chair
        The chair (its ``pin_damping`` is set to zero for both).
    speed : float
        Forward speed, m/s (> 0); default 0.75 m/s, the thesis's reference
        speed.
    model : {"thesis", "exact"}
        Variant, the same for both.
    casters : {"free", "locked"}
        Caster condition, the same for both.

    Returns
    -------
    LinearisationCheck
        Both dominant eigenvalues, their relative rate difference and the
        relative largest difference of the state matrices.
    """
    from stability import linear
    from stability.simulate import linearise

    c = chair.replace(pin_damping=0.0)
    A_lin = linear.state_matrices(c, speed, model, casters)[0]
    A_sim = np.asarray(linearise(c, speed, model=model, casters=casters).A)

    def dominant(A):
        e = np.linalg.eigvals(A)
        return complex(e[np.argmax(e.real)])

    lam_l, lam_s = dominant(A_lin), dominant(A_sim)
    return LinearisationCheck(
        speed=float(speed), model=model, casters=casters, omitted=omitted_effects(chair),
        eigenvalue_linear=lam_l, eigenvalue_simulator=lam_s,
        rate_difference=(lam_s.real - lam_l.real) / max(abs(lam_l.real), 1e-12),
        matrix_difference=float(np.max(np.abs(A_sim - A_lin)) / np.max(np.abs(A_lin))),
    )
