"""What the explorer's linear views show for one chair, from the toolkit's own compute functions.

:func:`linear_view` is all the work a chair edit costs before the page can
redraw (the update the benchmark times): the tracked eigenvalues against
speed (:func:`stability.linear.eigenvalues_vs_speed`) as a
:class:`stability.rootlocus.SpeedLocus`, the free- and locked-caster critical
speeds (:func:`stability.linear.critical_speeds`),
the zero-width closed form, the divergence table (:func:`stability.linear.divergence`,
the rows ``critical_speed`` prints), the static loads and the mode names of
the report (:func:`stability.linear.names.mode_names`).  Nothing here is
physics: every number comes from those functions.  The background work (the
simulator's measures and the trail window) is in :mod:`stability.app.measures`.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.linear import (
    STATES_FREE,
    Crossing,
    Divergence,
    ZeroWidthResult,
    critical_speeds,
    divergence,
    eigenvalues_vs_speed,
    state_matrices,
    zero_width,
)
from stability.linear.names import mode_names, mode_shares, shape_arm
from stability.models.statics import static_loads
from stability.rootlocus.speed import SpeedLocus, readonly
from stability.settings import defaults as D
from stability.tipping import TipAngles, tip_angles

__all__ = ["LinearView", "linear_view", "ModeShape", "mode_shape", "eigenvalues_csv", "GRID", "TABLE_SPEEDS",
           "geometry_points", "SHAPE_COMPONENTS"]

#: Speeds of the eigenvalue curves, m/s: 160 geometrically spaced over the range ``critical_speed`` searches.
GRID = np.geomspace(0.01, D.MAX_SPEED, 160)
#: Grid of the critical-speed search, m/s: 100 geometrically spaced from 0.01 to 30 m/s (``critical_speed``
#: uses 600 over the same range).  Either grid's crossings are refined to 1e-10 m/s, so both give the same
#: critical speeds unless two crossings lie closer together than this grid's spacing (8.4 % of the speed) and
#: escape the double-crossing guard of :func:`stability.linear.critical_speeds`; a test compares them.
SEARCH = np.geomspace(0.01, D.MAX_SPEED, 100)
#: Speeds of the divergence table: ``critical_speed``'s default ``--speeds``, m/s.
TABLE_SPEEDS = D.SUMMARY_SPEEDS


@dataclass(frozen=True)
class LinearView:
    """Everything the linear views draw for one chair and model.

    Attributes
    ----------
    chair : Chair
    model : str
    locus : SpeedLocus
        Free-caster eigenvalues (1/s) at :data:`GRID` speeds, tracked, with the free critical speeds.
    names : tuple of str
        A name per branch of ``locus`` (the report's rule).
    locked_crossings : list of Crossing
        Locked-caster critical speeds, m/s.
    zero_width : ZeroWidthResult
    table : list of Divergence
        Growth rate of the least stable mode at :data:`TABLE_SPEEDS` (what ``critical_speed`` prints).
    static_loads : dict
        Static normal loads, N (per wheel and per pair mean).
    tip : TipAngles
        ISO 7176-1 static stability angles (deg) with their tipping lines (:func:`stability.tipping.tip_angles`).
    """

    chair: Chair
    model: str
    locus: SpeedLocus
    names: tuple[str, ...]
    locked_crossings: list[Crossing]
    zero_width: ZeroWidthResult
    table: list[Divergence]
    static_loads: dict
    tip: TipAngles

    @property
    def free_crossings(self) -> list[Crossing]:
        """Free-caster critical speeds, m/s."""
        return list(self.locus.crossings)

    @property
    def growth_rate(self) -> np.ndarray:
        """Largest real part at each grid speed, 1/s (positive: unstable)."""
        return self.locus.max_real

    def stable_intervals(self) -> list[tuple[float, float]]:
        """Speed intervals (m/s) in which every free-caster mode decays."""
        out, start = [], float(self.locus.speeds[0])
        for lo, hi in self.locus.unstable_intervals():
            if lo > start:
                out.append((start, lo))
            start = hi
        end = float(self.locus.speeds[-1])
        if start < end:
            out.append((start, end))
        return out


def linear_view(chair: Chair, model: str = D.MODEL, name_speed: float = D.SPEED) -> LinearView:
    """The linear views' data for ``chair`` (see the module docstring).

    Parameters
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    name_speed : float
        Speed at which the modes are named, m/s (default the reference 0.75 m/s).

    Returns
    -------
    LinearView
    """
    eig = eigenvalues_vs_speed(chair, GRID, model, "free", track=True)
    free = critical_speeds(lambda U: state_matrices(chair, U, model, "free"), SEARCH)
    locked = critical_speeds(lambda U: state_matrices(chair, U, model, "locked"), SEARCH)
    locus = SpeedLocus(chair, model, "free", readonly(GRID), readonly(eig), list(free), tuple(STATES_FREE))
    return LinearView(chair=chair, model=model, locus=locus, names=mode_names(locus, name_speed),
                      locked_crossings=locked, zero_width=zero_width(chair),
                      table=divergence(chair, TABLE_SPEEDS, model, "free"), static_loads=static_loads(chair),
                      tip=tip_angles(chair))


#: The mode-shape components, dimensionless (angles, rad): the report's scaling (stability.linear.names).
SHAPE_COMPONENTS = ("sideslip v/U", "yaw r·s/U", "left caster η", "right caster β")


@dataclass(frozen=True)
class ModeShape:
    """The eigenvector of one mode at one speed, as dimensionless angle-like components.

    Attributes
    ----------
    speed : float
        The speed asked for, m/s (the eigenvalue is computed there, not on the plot's grid).
    eigenvalue : complex
        1/s.
    name : str
        The name of the branch it lies on (the plotted branch nearest to it at the nearest grid speed).
    shares : dict
        Share of sideslip, yaw, casters in phase and casters opposed (sums to 1; the report's rule).
    components : tuple of str
        :data:`SHAPE_COMPONENTS`.
    magnitude : tuple of float
        ``|component|``, the largest scaled to 1.
    phase_deg : tuple of float
        Phase of each component relative to the largest one, deg (0 or 180 for a real mode).
    """

    speed: float
    eigenvalue: complex
    name: str
    shares: dict
    components: tuple[str, ...]
    magnitude: tuple[float, ...]
    phase_deg: tuple[float, ...]


def mode_shape(view: LinearView, speed: float, branch: int | None = None) -> ModeShape:
    """Eigenvector of the least stable mode (or of a branch) of the free-caster model at ``speed``.

    The eigenvalues are those of the state matrix at ``speed`` itself, so at a speed of the table
    (:data:`TABLE_SPEEDS`) the least stable one is the table's growth rate.

    Parameters
    ----------
    view : LinearView
    speed : float
        m/s (> 0).
    branch : int, optional
        Column of ``view.locus.eigenvalues``: the mode at ``speed`` nearest that branch's eigenvalue at the
        nearest grid speed; default the mode with the largest real part at ``speed``.

    Returns
    -------
    ModeShape
    """
    U = view.locus.speeds
    k = int(np.argmin(np.abs(np.log(U) - math.log(speed))))
    grid_eig = view.locus.eigenvalues[k]
    u = float(speed)
    a = np.asarray(state_matrices(view.chair, u, view.model, "free"))[0]
    w, v = np.linalg.eig(a)
    i = int(np.argmax(w.real)) if branch is None else int(np.argmin(np.abs(w - grid_eig[int(branch)])))
    j = int(np.argmin(np.abs(grid_eig - w[i]))) if branch is None else int(branch)
    vec = v[:, i]
    arm = shape_arm(view.chair)
    comp = np.array([vec[0] / u, vec[1] * arm / u, vec[2], vec[4]])
    big = comp[int(np.argmax(np.abs(comp)))]
    comp = comp / big
    return ModeShape(u, complex(w[i]), view.names[j], mode_shares(vec, u, arm), SHAPE_COMPONENTS,
                     tuple(float(x) for x in np.abs(comp)), tuple(float(x) for x in np.degrees(np.angle(comp))))


def eigenvalues_csv(view: LinearView) -> str:
    """The eigenvalues against speed as CSV: a speed column, then real and imaginary part of each branch.

    Parameters
    ----------
    view : LinearView

    Returns
    -------
    str
        Header ``speed_m_s, <branch> real_1_s, <branch> imag_rad_s, ...`` preceded by comment
        lines (``#``) naming the chair and model; one row per grid speed.
    """
    out = io.StringIO()
    out.write(f"# eigenvalues of the linear free-caster model against speed; chair {view.chair.name!r}, "
              f"{view.model} model; each branch tracked across speeds, named at 0.75 m/s\n")
    w = csv.writer(out, lineterminator="\n")
    header = ["speed_m_s"]
    for j, name in enumerate(view.names):
        header += [f"mode{j + 1} real_1_s ({name})", f"mode{j + 1} imag_rad_s ({name})"]
    w.writerow(header)
    for u, row in zip(view.locus.speeds, view.locus.eigenvalues, strict=True):
        cells = [repr(float(u))]
        for lam in row:
            cells += [repr(float(lam.real)), repr(float(lam.imag))]
        w.writerow(cells)
    return out.getvalue()


def geometry_points(chair: Chair) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Plan-view points of the chair (x forward, y right, m; c.g. at the origin), from the chair's fields.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    dict
        ``"cg"``, ``"main"`` (main-wheel contacts), ``"pins"`` (caster pins), ``"casters"``
        (caster contacts with the casters trailing), each ``(x, y)`` arrays.
    """
    xm, xp = chair.x_main, chair.x_pin
    xc = -chair.caster_contact_distance if chair.caster_position == "rear" else chair.caster_contact_distance
    return {"cg": (np.array([0.0]), np.array([0.0])),
            "main": (np.array([xm, xm]), np.array([-chair.d1, chair.d2])),
            "pins": (np.array([xp, xp]), np.array([-chair.t1, chair.t2])),
            "casters": (np.array([xc, xc]), np.array([-chair.t1, chair.t2]))}
