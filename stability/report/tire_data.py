"""The numbers behind the report's tire page (Figures 4-1 and 4-2 analogues).

The static points use :func:`stability.models.statics.static_stiffness` (the one
home of stiffness at load, WITH the chair's lateral scale), so the page
shows the value ``python -m stability.critical_speed`` prints.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability import tires
from stability.chair import Chair
from stability.models.statics import static_loads, static_stiffness
from stability.tires.data import TABLE_4_1_FZ_N

__all__ = ["ForceCurves", "StaticPoint", "StiffnessCurves", "force_curves", "stiffness_curves", "TIRE_LOADS"]

#: Normal forces of the constant-load curves of Figure 4-1 (N).
TIRE_LOADS = TABLE_4_1_FZ_N


@dataclass(frozen=True, eq=False)
class ForceCurves:
    """Cornering force against slip angle of one tire at several constant loads (Figure 4-1).

    Attributes
    ----------
    tire, role : str
    slip_deg : ndarray
        Slip angles, deg.
    loads : tuple of float
        N.
    force : ndarray
        N, one row per load (positive).
    slip_points, force_points : ndarray
        The integer slip angles (deg) where the fits are defined and the forces there (N).
    mark_load : float or None
        The chair's static load on this tire, N.
    mark_force : ndarray or None
        The chair's tire (with its lateral scale) at that load, N.
    lateral_scale : float
    """

    tire: str
    role: str
    slip_deg: np.ndarray          # deg
    loads: tuple                  # N
    force: np.ndarray             # N, (len(loads), len(slip_deg)), positive
    slip_points: np.ndarray       # deg, where the cubic fits are defined (integers)
    force_points: np.ndarray      # N, (len(loads), len(slip_points))
    mark_load: float | None = None    # N, the chair's static load on this tire
    mark_force: np.ndarray | None = None  # N, the chair's (scaled) tire at that load
    lateral_scale: float = 1.0


@dataclass(frozen=True)
class StaticPoint:
    """One tire of the chair at its static load.

    Attributes
    ----------
    role : str
    load : float
        N.
    stiffness : float
        N/deg, with the chair's lateral scale.
    lateral_scale : float
    """

    role: str
    load: float
    stiffness: float
    lateral_scale: float


@dataclass(frozen=True, eq=False)
class StiffnessCurves:
    """Cornering stiffness against normal force of every tire (Figure 4-2), the chair's tires marked.

    Attributes
    ----------
    names, main_names : tuple of str
        Every tire; the main-wheel tires.
    fz : ndarray
        N.
    stiffness : ndarray
        N/deg, one row per tire (unscaled fits).
    table_fz : tuple of float
        Table 4-1 loads, N.
    table : dict
        Name -> Table 4-1 stiffnesses, N/deg.
    highlight : dict
        Name -> StaticPoint.
    """

    names: tuple
    main_names: tuple
    fz: np.ndarray                # N
    stiffness: np.ndarray         # N/deg, (len(names), len(fz)), unscaled tire fits
    table_fz: tuple               # N, Table 4-1 loads
    table: dict                   # name -> Table 4-1 stiffnesses (N/deg)
    highlight: dict               # name -> StaticPoint


def _force(t, slip: np.ndarray, fz: float) -> np.ndarray:
    return -np.asarray(t.lateral_force(slip, np.full_like(slip, fz), warn=False), dtype=float)


def force_curves(chair: Chair, role: str, *, loads=TIRE_LOADS) -> ForceCurves:
    """Figure 4-1 curves of the chair's main (``role="main"``) or caster tire.

    Parameters
    ----------
    chair : Chair
    role : {"main", "caster"}
        Which of the chair's tires.
    loads : sequence of float
        Constant normal forces of the curves (N).

    Returns
    -------
    ForceCurves
        The tabulated tire (unscaled) at ``loads``, and the chair's tire
        (with its lateral scale) at its mean static load on that pair.
    """
    name = chair.main_tire if role == "main" else chair.caster_tire
    own = chair.main_tire_model() if role == "main" else chair.caster_tire_model()
    scale = chair.main_lateral_scale if role == "main" else chair.caster_lateral_scale
    t = tires.get(name)
    slip = np.linspace(0, 8, 161)
    ints = np.arange(0, 9).astype(float)
    load = static_loads(chair)[role]
    return ForceCurves(
        tire=name, role="main wheels" if role == "main" else "casters", slip_deg=slip, loads=tuple(loads),
        force=np.array([_force(t, slip, fz) for fz in loads]), slip_points=ints,
        force_points=np.array([_force(t, ints, fz) for fz in loads]), mark_load=load,
        mark_force=_force(own, slip, load), lateral_scale=float(scale))


def stiffness_curves(chair: Chair | None = None) -> StiffnessCurves:
    """Figure 4-2 curves of every tabulated tire, with the chair's two tires at their static loads.

    Parameters
    ----------
    chair : Chair, optional
        The chair whose tires are marked.

    Returns
    -------
    StiffnessCurves
        The marked stiffness is :func:`stability.models.statics.static_stiffness`
        (mean of each pair), converted from N/rad to N/deg.
    """
    names = tuple(tires.names())
    fz = np.linspace(0, 450, 181)
    highlight = {}
    if chair is not None:
        loads = static_loads(chair)
        st = static_stiffness(chair)
        deg = math.radians(1.0)
        highlight[chair.main_tire] = StaticPoint("main", loads["main"], 0.5 * (st["D"] + st["E"]) * deg,
                                                 float(chair.main_lateral_scale))
        # a chair with the same tire on both axles: the caster entry is drawn (as before)
        highlight[chair.caster_tire] = StaticPoint("caster", loads["caster"], 0.5 * (st["A"] + st["B"]) * deg,
                                                   float(chair.caster_lateral_scale))
    return StiffnessCurves(
        names=names, main_names=tuple(tires.MAIN_TIRES), fz=fz,
        stiffness=np.array([np.asarray(tires.get(n).cornering_stiffness(fz), dtype=float) for n in names]),
        table_fz=tuple(tires.TABLE_4_1_FZ_N), table=dict(tires.table_4_1()), highlight=highlight)
