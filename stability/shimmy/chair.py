"""The wheelchair's caster as a towed wheel, and the trail x speed design chart.

Each caster is modelled as a towed wheel whose pivot is its caster pin,
held laterally by an equivalent frame/fork stiffness and moving straight
ahead at the chair's speed; the chair's own yaw and sideslip are not coupled
in (docs/shimmy.md says what that leaves out).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from stability.settings.run import WORK_BUDGET_S  # ten minutes: the one budget of every command and API call
from stability.shimmy import describing
from stability.shimmy.compliance import ESTIMATE_NOTE, CasterCompliance
from stability.shimmy.layout_caster import CasterSource, LayoutCaster
from stability.shimmy.towed_wheel import TowedWheel

__all__ = ["SECONDS_PER_SPEED", "WORK_BUDGET_S", "check_speed_count", "CasterCompliance", "caster_wheel",
           "critical_trail", "friction_trail", "TrailChart", "trail_chart",
           "CasterSummary", "caster_summary",
           "ESTIMATE_NOTE"]

#: Cost of one speed, s, measured on the 2-core CI machine under load (both cores shared with other work, load
#: average 20; a quiet machine is several times faster): the summary (critical and friction trails by root
#: finding on the towed-wheel model) and the PDF's trail chart (26 trails).
SECONDS_PER_SPEED = {"summary": 1.7, "chart": 2.5}

def check_speed_count(name: str, n_speeds: int, seconds_per_speed: float) -> None:
    """Refuse ``n_speeds`` speeds costing ``seconds_per_speed`` each beyond :data:`WORK_BUDGET_S`.

    Parameters
    ----------
    name : str
        The argument or option of the speeds (``"speeds"``, ``"--speeds"``).
    n_speeds : int
    seconds_per_speed : float

    Raises
    ------
    ValueError
        Naming ``name``, the estimated time and the largest allowed number of speeds.
    """
    if n_speeds * seconds_per_speed > WORK_BUDGET_S:
        raise ValueError(f"{name}: {n_speeds} speeds would take about {n_speeds * seconds_per_speed / 60:.0f} min "
                         f"({seconds_per_speed:g} s each); the largest allowed number is "
                         f"{int(WORK_BUDGET_S // seconds_per_speed)}")


def _static_stiffness(chair: CasterSource) -> dict[str, float]:
    if isinstance(chair, LayoutCaster):         # one caster: both "sides" are it
        c = float(chair.caster_tire_model().cornering_stiffness_per_rad(chair.static_load()))
        return {"A": c, "B": c}
    try:
        from stability.models.statics import static_stiffness
    except ImportError:  # pragma: no cover - older layout
        from stability.models import static_stiffness  # type: ignore[attr-defined,no-redef]
    return static_stiffness(chair)


def caster_wheel(chair: CasterSource, compliance: CasterCompliance | None = None, side: str = "A") -> TowedWheel:
    """One caster of ``chair`` as a :class:`TowedWheel` (side ``"A"`` left, ``"B"`` right).

    mass ``m_c``; inertia about its own c.g. ``i_zp - m_c l1^2``; c.g. ``l1``
    behind the pin, contact ``trail - l1`` behind the c.g.; cornering
    stiffness of the caster tire at its static load; the chair's viscous
    ``pin_damping`` and the side's Coulomb pin friction.

    Parameters
    ----------
    chair : Chair
        The chair (trail > 0 m, m_c > 0 kg, i_zp > m_c l1^2 kg m^2).
    compliance : CasterCompliance or None, optional
        Relaxation length (m) and pin lateral stiffness (N/m); default the
        estimates of :class:`CasterCompliance`.
    side : {"A", "B"}, optional
        Left (``"A"``, default) or right (``"B"``) caster: selects the static
        cornering stiffness and the pin friction.

    Returns
    -------
    TowedWheel
        The caster as a towed wheel pivoting at its pin.

    Raises
    ------
    ValueError
        If ``side`` is invalid, trail <= 0 or i_zp <= m_c l1^2.
    """
    comp = compliance or CasterCompliance()
    if side not in ("A", "B"):
        raise ValueError(f"side={side!r} is invalid; valid choices: ['A', 'B']")
    if chair.trail <= 0:
        raise ValueError(f"chair parameter trail={chair.trail!r} is invalid for shimmy; valid range: > 0 m")
    inertia = chair.i_zp - chair.m_c * chair.l1**2
    if chair.m_c <= 0 or inertia <= 0:
        raise ValueError(f"chair parameter i_zp={chair.i_zp!r} is invalid for shimmy; valid range: "
                         f"> m_c*l1^2 = {chair.m_c * chair.l1**2:.6g} kg m^2 with m_c > 0")
    return TowedWheel(mass=chair.m_c, inertia=inertia, contact_behind_cm=chair.trail - chair.l1,
                      pivot_ahead_of_cm=chair.l1, lateral_stiffness=comp.lateral_stiffness,
                      cornering_stiffness=_static_stiffness(chair)[side], relaxation_length=comp.relaxation_length,
                      pin_damping=chair.pin_damping,
                      pin_friction=chair.pin_friction_left if side == "A" else chair.pin_friction_right)


def _trail_grid(chair: CasterSource) -> np.ndarray:
    return np.linspace(max(1e-3, chair.l1 * 0.05), 0.2, 60)


def critical_trail(chair: CasterSource, speed: float, compliance: CasterCompliance | None = None) -> float:
    """Lower boundary of the shimmy-free trail set (linear model, viscous damping only).

    The smallest trail at which the caster stops shimmying (the lower end of the
    first shimmy-free band of :func:`stability.shimmy.band.shimmy_band`); ``0``
    if the caster is stable from 1 mm, ``inf`` if it shimmies at every trail up
    to 25 cm (soft pivots: the shimmy mode of the pivot spring, docs/shimmy.md).
    The shimmy-free set can also end above (a band such as 5-17 cm) or be split
    in two: :func:`stability.shimmy.band.shimmy_band` gives every boundary.

    Parameters
    ----------
    chair : Chair
        The chair; its trail is varied, everything else kept.
    speed : float
        Forward speed, m/s (> 0).
    compliance : CasterCompliance or None, optional
        Caster compliance; default :class:`CasterCompliance` estimates.

    Returns
    -------
    float
        Critical trail, m (0 or ``inf`` as above).
    """
    from stability.shimmy.band import TRAIL_SEARCH_M, shimmy_intervals

    iv = shimmy_intervals(chair, [speed], compliance or CasterCompliance())[0]
    if not iv:
        return math.inf
    lo = iv[0][0]
    return 0.0 if lo <= TRAIL_SEARCH_M[0] else lo


def friction_trail(chair: CasterSource, speed: float, amplitude: float, compliance: CasterCompliance | None = None
                   ) -> float:
    """Largest trail below which the chair's pin friction cannot hold shimmy of ``amplitude``.

    The describing-function estimate: the trail where the friction needed
    (:func:`stability.shimmy.describing.suppressing_friction`) equals the
    pin's own Coulomb friction.  ``0`` if the friction suffices at every
    trail on 1 mm-0.2 m, ``inf`` if it suffices at none.

    Parameters
    ----------
    chair : Chair
        The chair; its trail is varied, the left pin friction (N m) used.
    speed : float
        Forward speed, m/s (> 0).
    amplitude : float
        Shimmy amplitude of the caster angle, rad (> 0).
    compliance : CasterCompliance or None, optional
        Caster compliance; default :class:`CasterCompliance` estimates.

    Returns
    -------
    float
        Friction trail, m (0 or ``inf`` as above; for a layout's caster the trails searched end where the layout
        would no longer stand, NaN if it stands on fewer than two of them).
    """
    def wheel(trail: float) -> TowedWheel:
        return caster_wheel(chair.replace(trail=trail), compliance)

    def excess(w: TowedWheel) -> float:
        need = describing.suppressing_friction(w, speed, amplitude).friction
        return min(need, 1e3) - w.pin_friction

    grid = _trail_grid(chair)
    if isinstance(chair, LayoutCaster):
        # a layout's caster: only the trails at which the layout still stands (in reverse a long trail moves the
        # contacts so far that a base can tip onto the casters)
        grid = grid[np.isfinite(chair.loads(grid))]
        if grid.size < 2:
            return math.nan
    upper = excess(wheel(float(grid[-1])))
    if upper > 0:
        return math.inf
    # The largest root: the one in the highest grid step where the excess changes sign (a root per sign change,
    # each refined by Brent's method in its own step, the highest the largest), so the search goes down from the
    # top and stops there; the describing function below that step is not needed.  Every grid trail's caster is
    # still built, bottom up (its tire's static load records the same tire-range notes, in the same order, and
    # raises at the same trail under the "raise" policy, as a scan of the whole grid).
    wheels = [wheel(t) for t in grid]
    for i in range(grid.size - 2, -1, -1):
        lower = excess(wheels[i])
        if np.sign(lower) * np.sign(upper) < 0:
            return float(brentq(lambda t: excess(wheel(t)), grid[i], grid[i + 1], xtol=1e-7))
        upper = lower
    return 0.0


@dataclass(frozen=True)
class TrailChart:
    """Trail x speed design chart for one chair.

    Attributes
    ----------
    chair_name : str
    trails, speeds : ndarray
        Grid (m; m/s).
    divergence_rate : ndarray, shape (len(trails), len(speeds))
        Largest real part of the chair's eigenvalues (free casters, exact
        model; 1/s); > 0 means directional (yaw) divergence.
    friction_needed : ndarray, shape (len(trails), len(speeds))
        Coulomb pin friction (N m) that suppresses caster shimmy up to
        ``amplitude`` (describing function; 0 where the caster is stable).
    pin_friction : float
        The chair's left pin friction (N m).
    amplitude : float
        Shimmy amplitude of the friction estimate (rad).
    critical_trail : ndarray
        Linear shimmy boundary (m) per speed, nominal compliance.
    critical_trail_range : ndarray, shape (2, len(speeds))
        Its lowest and highest value over the compliance range corners.
    friction_trail : ndarray
        Trail (m) below which the chair's pin friction does not hold shimmy of ``amplitude``.
    chair_trail : float
        The chair's own trail (m).
    note : str
        That the compliance values are estimates.
    """

    chair_name: str
    trails: np.ndarray
    speeds: np.ndarray
    divergence_rate: np.ndarray
    friction_needed: np.ndarray
    pin_friction: float
    amplitude: float
    critical_trail: np.ndarray
    critical_trail_range: np.ndarray
    friction_trail: np.ndarray
    chair_trail: float
    note: str = ESTIMATE_NOTE


def _divergence(chair: CasterSource, speeds: np.ndarray) -> np.ndarray:
    """Largest real part of the whole chair's linear eigenvalues at each speed, 1/s: the short form's exact model,
    or for a layout's caster its layout's linear model (in reverse at ``-speeds``)."""
    if isinstance(chair, LayoutCaster):
        from stability.layout.linear import growth_rates

        return growth_rates(chair.layout, -speeds if chair.reverse else speeds)
    from stability.linear import eigenvalues_vs_speed

    return eigenvalues_vs_speed(chair, speeds, track=False).real.max(axis=-1)


def trail_chart(chair: CasterSource, trails, speeds, compliance: CasterCompliance | None = None,
                amplitude: float = math.radians(5.0)) -> TrailChart:
    """Yaw divergence rate and caster shimmy over trail x speed (see :class:`TrailChart`).

    Parameters
    ----------
    chair : Chair or LayoutCaster
        The chair (its left caster), or one caster of a layout (at its own static load, recomputed at each trail;
        its row's trail is what changes, :meth:`LayoutCaster.replace`); the trail is replaced by each grid
        value.
    trails : array_like
        Trails, m (> 0).
    speeds : array_like
        Forward speeds, m/s (> 0).
    compliance : CasterCompliance or None, optional
        Caster compliance; default :class:`CasterCompliance` estimates.
    amplitude : float, optional
        Shimmy amplitude of the friction estimate, rad (default 5 deg).

    Returns
    -------
    TrailChart
        Divergence rate (1/s) and friction needed (N m) on the grid, critical
        and friction trails per speed (m), with the critical trail's range over
        the compliance range corners.
    """
    comp = compliance or CasterCompliance()
    trails = np.asarray(trails, dtype=float)
    speeds = np.asarray(speeds, dtype=float)
    check_speed_count("speeds", speeds.size, SECONDS_PER_SPEED["chart"] * trails.size / 26)
    div = np.empty((trails.size, speeds.size))
    need = np.empty_like(div)
    for i, t in enumerate(trails):
        c = chair.replace(trail=float(t))
        div[i] = _divergence(c, speeds)
        w = caster_wheel(c, comp)
        need[i] = [describing.suppressing_friction(w, u, amplitude).friction for u in speeds]
    crit = np.array([critical_trail(chair, u, comp) for u in speeds])
    corners = np.array([[critical_trail(chair, u, cc) for u in speeds] for cc in comp.corners()])
    rng = np.array([corners.min(axis=0), corners.max(axis=0)])
    ftrail = np.array([friction_trail(chair, u, amplitude, comp) for u in speeds])
    return TrailChart(chair.name, trails, speeds, div, need, chair.pin_friction_left, amplitude, crit, rng, ftrail,
                      chair.trail)


@dataclass(frozen=True)
class CasterSummary:
    """Shimmy of one chair's (left) caster against speed.

    Attributes
    ----------
    chair_name : str
    compliance : CasterCompliance
        The estimated caster compliance used.
    speeds : ndarray
        m/s.
    stable : ndarray of bool
        Linear caster model stable (viscous pin damping only, no Coulomb friction).
    shimmy_frequency_hz : ndarray
        Frequency of the least-damped oscillatory caster mode (Hz).
    shimmy_growth_rate : ndarray
        Its real part (1/s; > 0: shimmy grows).
    critical_trail, critical_trail_low, critical_trail_high : ndarray
        Linear shimmy boundary (m; below it shimmy), nominal and over the compliance range.
    friction_needed : ndarray
        Coulomb pin friction (N m) that suppresses shimmy up to ``amplitude``.
    pin_friction : float
        The chair's left pin friction (N m).
    friction_trail : ndarray
        Trail (m) below which the chair's pin friction does not hold shimmy of ``amplitude``.
    amplitude : float
        rad.
    trail : float
        The chair's trail (m).
    note : str
    """

    chair_name: str
    compliance: CasterCompliance
    speeds: np.ndarray
    stable: np.ndarray
    shimmy_frequency_hz: np.ndarray
    shimmy_growth_rate: np.ndarray
    critical_trail: np.ndarray
    critical_trail_low: np.ndarray
    critical_trail_high: np.ndarray
    friction_needed: np.ndarray
    pin_friction: float
    friction_trail: np.ndarray
    amplitude: float
    trail: float
    note: str = ESTIMATE_NOTE

    def to_mapping(self) -> dict:
        """JSON-ready dict (snake_case keys with units; inf written as null)."""
        def num(x):
            return [None if not math.isfinite(v) else float(v) for v in np.ravel(x)]

        return {
            "chair": self.chair_name, "note": self.note,
            "relaxation_length_m": self.compliance.relaxation_length,
            "relaxation_length_range_m": list(self.compliance.relaxation_length_range),
            "lateral_stiffness_N_per_m": self.compliance.lateral_stiffness,
            "lateral_stiffness_range_N_per_m": list(self.compliance.lateral_stiffness_range),
            "trail_m": self.trail, "pin_friction_N_m": self.pin_friction,
            "amplitude_deg": math.degrees(self.amplitude),
            "speeds_m_s": num(self.speeds), "stable_without_friction": [bool(s) for s in self.stable],
            "shimmy_frequency_hz": num(self.shimmy_frequency_hz),
            "shimmy_growth_rate_1_s": num(self.shimmy_growth_rate),
            "critical_trail_m": num(self.critical_trail), "critical_trail_low_m": num(self.critical_trail_low),
            "critical_trail_high_m": num(self.critical_trail_high),
            "friction_needed_N_m": num(self.friction_needed), "friction_trail_m": num(self.friction_trail),
            "null_means": "critical/friction trail above 0.2 m (unstable at every trail checked)",
        }


def caster_summary(chair: CasterSource, speeds, compliance: CasterCompliance | None = None,
                   amplitude: float = math.radians(5.0)) -> CasterSummary:
    """Shimmy summary of ``chair``'s left caster at ``speeds`` (see :class:`CasterSummary`).

    Parameters
    ----------
    chair : Chair
        The chair.
    speeds : array_like
        Forward speeds, m/s (> 0).
    compliance : CasterCompliance or None, optional
        Caster compliance; default :class:`CasterCompliance` estimates.
    amplitude : float, optional
        Shimmy amplitude of the friction estimate, rad (default 5 deg).

    Returns
    -------
    CasterSummary
        Stability, shimmy frequency (Hz) and growth rate (1/s), critical trail
        (m) with its range over the compliance corners, friction needed (N m)
        and friction trail (m) at each speed.
    """
    comp = compliance or CasterCompliance()
    U = np.asarray(speeds, dtype=float)
    check_speed_count("speeds", U.size, SECONDS_PER_SPEED["summary"])
    w = caster_wheel(chair, comp)
    ev = np.atleast_2d(w.eigenvalues(U))
    osc = np.abs(ev.imag) > 1e-9 * np.abs(ev).max(axis=-1, keepdims=True)
    j = np.argmax(np.where(osc, ev.real, -np.inf), axis=-1)
    lead = ev[np.arange(U.size), j]
    corners = np.array([[critical_trail(chair, u, cc) for u in U] for cc in comp.corners()])
    return CasterSummary(
        chair.name, comp, U, np.array([w.routh_hurwitz(u).stable for u in U]), np.abs(lead.imag) / (2 * math.pi),
        lead.real, np.array([critical_trail(chair, u, comp) for u in U]), corners.min(axis=0), corners.max(axis=0),
        np.array([describing.suppressing_friction(w, u, amplitude).friction for u in U]), w.pin_friction,
        np.array([friction_trail(chair, u, amplitude, comp) for u in U]), amplitude, chair.trail)
