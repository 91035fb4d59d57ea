"""Chair-level linear results: zero-width closed forms, divergence rates, the stability summary."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stability.chair import Chair, check_chair
from stability.chair.model import takes_chair
from stability.linear.batch import MAX_MATRICES
from stability.linear.critical import critical_speeds, max_real_part
from stability.linear.model import state_matrices
from stability.models import zero_width as zw
from stability.models.params import parameters
from stability.models.statics import static_loads, static_stiffness
from stability.runtime.checks import check_model, check_speeds
from stability.settings.bounds import SEARCH_MAX_SPEED, Bound

__all__ = ["ZeroWidthResult", "zero_width", "Divergence", "divergence", "massless_caster_rate",
           "StabilitySummary", "analyse", "N_GRID"]

#: Valid ``n_grid`` of :func:`analyse`: at least two speeds to search between, at most the matrices of one
#: batched call (:data:`~stability.linear.batch.MAX_MATRICES`: memory bounded).
N_GRID = Bound(2, MAX_MATRICES, "")


@dataclass(frozen=True)
class ZeroWidthResult:
    """Zero-width (bicycle) model with locked casters (chapter 5).

    Attributes
    ----------
    load_main, load_caster : float
        Static load on one main wheel and one caster (N), eq 5-13 with the
        caster contact points at ``Chair.caster_contact_distance`` from the c.g.
    stiffness_main, stiffness_caster : float
        Cornering stiffness of one tire at that load (N/rad).
    understeer_coefficient : float
        k_us = W_f/C_f - W_r/C_r (rad), eq 5-16.
    critical_speed : float or None
        sqrt(-g s / k_us) (m/s), eq 5-15; None when k_us >= 0 (stable at all
        speeds).
    wheelbase : float
        s (m), main axle to caster contact points.
    """

    load_main: float
    load_caster: float
    stiffness_main: float
    stiffness_caster: float
    understeer_coefficient: float
    critical_speed: float | None
    wheelbase: float


@takes_chair
def zero_width(chair: Chair) -> ZeroWidthResult:
    """Zero-width locked-caster understeer coefficient and critical speed (eqs 5-13..5-16).

    The front axle of the bicycle is the main axle for a rear-caster chair
    and the caster contacts for a front-caster chair.

    Parameters
    ----------
    chair : Chair
        The chair; its total weight m g is split between the axles by the
        distances s1 (c.g. to main axle) and ``caster_contact_distance`` (c.g. to
        caster contacts), m.

    Returns
    -------
    ZeroWidthResult
        Per-wheel loads (N), cornering stiffnesses at those loads (N/rad), k_us
        (rad) and the critical speed sqrt(-g s / k_us) (m/s, None when k_us >= 0).
    """
    s = chair.wheelbase
    d_main = chair.s1
    d_caster = chair.caster_contact_distance
    W = chair.m * chair.g
    load_main = W * d_caster / (2 * s)
    load_caster = W * d_main / (2 * s)
    c_main = float(chair.main_tire_model().cornering_stiffness_per_rad(load_main))
    c_caster = float(chair.caster_tire_model().cornering_stiffness_per_rad(load_caster))
    if chair.caster_position == "rear":
        W_f, W_r, C_f, C_r = load_main, load_caster, c_main, c_caster
    else:
        W_f, W_r, C_f, C_r = load_caster, load_main, c_caster, c_main
    k_us = float(zw.understeer_coefficient(W_f, W_r, C_f, C_r))
    crit = math.sqrt(-chair.g * s / k_us) if k_us < 0 else None
    return ZeroWidthResult(load_main, load_caster, c_main, c_caster, k_us, crit, s)


@dataclass(frozen=True)
class Divergence:
    """The least stable mode at one speed.

    Attributes
    ----------
    speed : float
        Forward speed, m/s.
    rate : float
        Largest real part of the eigenvalues, 1/s (positive: unstable).
    time_to_double : float or None
        ``ln 2 / rate``, s; None when the rate is not positive.
    frequency : float
        ``|Im|`` of that eigenvalue, rad/s (0 for a real mode).
    """

    speed: float
    rate: float
    time_to_double: float | None
    frequency: float

    def to_dict(self) -> dict:
        """JSON keys with units: ``speed_m_s``, ``rate_1_s``, ``time_to_double_s``, ``frequency_rad_s``."""
        return {"speed_m_s": self.speed, "rate_1_s": self.rate, "time_to_double_s": self.time_to_double,
                "frequency_rad_s": self.frequency}


@takes_chair
def divergence(chair: Chair, speeds, model: str = "exact", casters: str = "free") -> list[Divergence]:
    """Growth rate of the least stable mode and its time to double, at each speed.

    Parameters
    ----------
    chair : Chair
    speeds : array_like
        Forward speeds (m/s).
    model : {"exact", "thesis"}
    casters : {"free", "locked"}

    Returns
    -------
    list of Divergence
        One per speed.
    """
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    eigs = np.linalg.eigvals(state_matrices(chair, speeds, model, casters))
    idx = np.argmax(eigs.real, axis=1)
    lam = eigs[np.arange(len(speeds)), idx]
    rows = []
    for s, ev in zip(speeds, lam, strict=True):
        rate = float(ev.real)
        rows.append(Divergence(float(s), rate, (math.log(2) / rate) if rate > 0 else None, abs(float(ev.imag))))
    return rows


@takes_chair
def massless_caster_rate(chair: Chair, speed, caster_drag: float = 0.0):
    """Closed-form growth rate of the free-caster chair in the massless-caster limit (1/s).

    With massless, frictionless casters the caster tires can carry no lateral
    force (a caster aligns with its contact velocity at once), so the chair is a
    rigid body on one axle: the main wheels at signed position ``x_m`` with
    stiffness ``C`` per tire.  Eqs 5-4b/5-4c with eq 5-5 then give the
    characteristic equation

    ``lambda^2 + (2C/U)(1/m + x_m^2/I_z) lambda - 2 C x_m / I_z = 0``,

    whose constant term is negative for a rear-caster chair (``x_m > 0``): one
    real root is positive at every speed, which is chapter 5's "infinitely
    unstable" case two made quantitative.  At low speed the root tends to
    ``U m x_m / (I_z + m x_m^2)``: the chair pivots about its main axle as a
    trailer pushed backwards would.  For a front-caster chair (``x_m < 0``)
    both roots are stable.

    A caster's rolling drag ``D`` acts along its heading, which in this limit
    follows the contact velocity: its side component is ``-D`` times the
    contact's slip angle, so the caster pair is a second axle of cornering
    stiffness ``2 D`` (N/rad) at the caster contacts ``x_c = x_p - trail``
    (the feathers of an arrow).  The two-axle equation (5-9) then has

    ``p = (C_f + C_r)/(m U) + (C_f x_m^2 + C_r x_c^2)/(I_z U)``,
    ``q = C_f C_r (x_m - x_c)^2/(m I_z U^2) - (C_f x_m + C_r x_c)/I_z``

    with ``C_f = 2C``, ``C_r = 2D``: below ``U^2 = C_r (x_m - x_c)^2/(m x_m)``
    (``q > 0``) the rear-caster chair is stable.

    Parameters
    ----------
    chair : Chair
    speed : float or array_like
        Forward speed (m/s).
    caster_drag : float
        Rolling drag of one caster, N (default 0: the linear model's tires
        have no rolling resistance).

    Returns
    -------
    float or ndarray
        The larger real part of the two roots (1/s).
    """
    check_speeds(speed)
    U = np.asarray(speed, dtype=float)
    drag = float(caster_drag)
    if not (math.isfinite(drag) and drag >= 0.0):
        raise ValueError(f"caster_drag={caster_drag!r} is invalid; valid range: >= 0 N")
    st = static_stiffness(chair)
    cf = st["D"] + st["E"]
    cr = 2.0 * drag
    prm = parameters(chair)
    xm, xc = float(prm.x_m), float(prm.x_p - prm.trail)
    m, iz = chair.m, chair.i_z
    b = (cf + cr) / (m * U) + (cf * xm**2 + cr * xc**2) / (iz * U)
    c = cf * cr * (xm - xc) ** 2 / (m * iz * U**2) - (cf * xm + cr * xc) / iz
    disc = b**2 - 4 * c
    root = np.where(disc >= 0, (-b + np.sqrt(np.abs(disc))) / 2, -b / 2)
    return float(root) if np.ndim(root) == 0 else root


@dataclass(frozen=True)
class StabilitySummary:
    """Everything ``python -m stability.critical_speed`` reports for one chair.

    Attributes
    ----------
    chair : Chair
        The chair analysed.
    model : str
        Equation variant, ``"exact"`` or ``"thesis"``.
    static_loads : dict
        Static normal loads per wheel and per pair mean, N (:func:`stability.models.statics.static_loads`).
    stiffness_n_per_deg : dict
        Cornering stiffness of one tire at its static load, N/deg: ``"main"``
        (mean of D and E) and ``"caster"`` (mean of A and B).
    zero_width : ZeroWidthResult
        Zero-width locked-caster closed form (chapter 5, eqs 5-13..5-16).
    locked_crossings : list of Crossing
        Speeds (m/s) where the locked-caster model's largest real part crosses zero.
    free_crossings : list of Crossing
        The same for free casters.
    free_stable_at_all_speeds : bool
        True if the free-caster largest real part is < 0 at every grid speed.
    free_unstable_at_all_speeds : bool
        True if it is > 0 at every grid speed.
    divergence : list of Divergence
        Growth rate (1/s), time to double (s) and frequency (rad/s) of the least
        stable free-caster mode at each table speed.
    search_range : tuple of float
        ``(lowest, highest)`` speed of the critical-speed search grid, m/s.
    """

    chair: Chair
    model: str
    static_loads: dict
    stiffness_n_per_deg: dict
    zero_width: ZeroWidthResult
    locked_crossings: list
    free_crossings: list
    free_stable_at_all_speeds: bool
    free_unstable_at_all_speeds: bool
    divergence: list
    search_range: tuple = field(default=(0.0, 0.0))


def analyse(chair: Chair, model: str = "exact", speeds=(0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0),
            max_speed: float = 30.0, n_grid: int = 600) -> StabilitySummary:
    """Full linear stability summary of a chair (see :class:`StabilitySummary`).

    Parameters
    ----------
    chair : Chair
        The chair.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    speeds : sequence of float, optional
        Speeds of the divergence table, m/s (> 0).
    max_speed : float, optional
        Upper end of the critical-speed search, m/s; valid range 0.01 < max_speed <= 100 (default 30).
    n_grid : int, optional
        Number of geometrically spaced grid speeds from 0.01 m/s to ``max_speed``
        (default 600; valid range :data:`N_GRID`); crossings are refined between grid points.

    Returns
    -------
    StabilitySummary
        Static loads, stiffnesses, zero-width closed form, locked and free
        critical speeds and the divergence table.

    Raises
    ------
    TypeError
        ``chair`` is not a Chair, ``max_speed`` not a number or ``n_grid`` not an integer.
    ValueError
        An argument outside its range (named, with its value and the range): ``max_speed``
        (:data:`stability.settings.bounds.SEARCH_MAX_SPEED`), ``n_grid`` (:data:`N_GRID`), ``speeds``
        (0.01-100 m/s, at most :data:`~stability.linear.batch.MAX_MATRICES`), ``model``.
    """
    chair = check_chair(chair)
    model = check_model(model)
    max_speed = SEARCH_MAX_SPEED.check("max_speed", max_speed)
    n_grid = int(N_GRID.check("n_grid", n_grid, integer=True))
    speeds = check_speeds(speeds, "speeds", max_count=MAX_MATRICES, one_dim=True)  # >= MIN_SPEED (round-off)
    loads = static_loads(chair)
    st = static_stiffness(chair)
    per_deg = math.pi / 180.0
    stiff = {"main": 0.5 * (st["D"] + st["E"]) * per_deg, "caster": 0.5 * (st["A"] + st["B"]) * per_deg}
    grid = np.geomspace(0.01, max_speed, n_grid)
    locked = critical_speeds(lambda U: state_matrices(chair, U, model, "locked"), grid)
    free = critical_speeds(lambda U: state_matrices(chair, U, model, "free"), grid)
    a = max_real_part(lambda U: state_matrices(chair, U, model, "free"), grid)
    return StabilitySummary(
        chair=chair, model=model, static_loads=loads, stiffness_n_per_deg=stiff,
        zero_width=zero_width(chair), locked_crossings=locked, free_crossings=free,
        free_stable_at_all_speeds=bool(np.all(a < 0)), free_unstable_at_all_speeds=bool(np.all(a > 0)),
        divergence=divergence(chair, speeds, model, "free"), search_range=(float(grid[0]), float(grid[-1])),
    )
