"""The array layouts of the compiled kernels: chairs, tires and options packed per run.

Written by :class:`Packed` (and :func:`slope_slots`, :func:`policy_code`);
read by :mod:`stability.simulate.kernel` and
:mod:`stability.simulate.adaptive_kernel` (slot indices in
:mod:`stability.simulate.kernel_equations`).  The tire slots carry what the
tire law (:mod:`stability.tires.law`) takes: kind, segment table, scale,
fitted range.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence
from typing import Any

import numpy as np

from stability import tires as _tires
from stability.chair import Chair
from stability.models.params import parameters
from stability.simulate.options import LOAD_LIMIT_N, SLIP_LIMIT_DEG, Options, initial_velocities

__all__ = ["Packed", "chair_rows", "slope_slots", "policy_code", "ROWS_CACHE_SIZE"]


def policy_code(opts: Options) -> int:
    """The tire law's code of a policy.

    Parameters
    ----------
    opts : Options
        Uses ``out_of_range``.

    Returns
    -------
    int
        Its index in :data:`stability.tires.POLICIES`: 0 clamp, 1 extrapolate, 2 raise.
    """
    return _tires.POLICIES.index(opts.out_of_range)


def _tire_slot(tire: Any) -> tuple[int, np.ndarray, float, tuple[float, float]]:
    """(kind, (6, 8) segments, scale or N/deg, (slip limit deg, load limit N)) of one tire."""
    if isinstance(tire, _tires.LinearTire):
        return 1, np.zeros((6, 8)), tire.stiffness_N_per_deg * tire.lateral_scale, (math.inf, math.inf)
    lim = (float(getattr(tire, "slip_max_deg", SLIP_LIMIT_DEG)), float(getattr(tire, "fz_max_N", LOAD_LIMIT_N)))
    return 0, np.array(tire.segment_arrays(), dtype=float), float(tire.lateral_scale), lim


def _rolling_slot(tire: Any, on: bool) -> tuple[int, tuple[float, float, float], float]:
    if not on:
        return 0, (0.0, 0.0, 0.0), 0.0
    tire.rolling_resistance(1.0)          # a tire without rolling data raises its own error here
    if isinstance(tire, _tires.LinearTire):
        return 2, (float(tire.f_r), 0.0, 0.0), float(tire.rolling_scale)
    a, b, c = tire.rolling
    return 1, (float(a), float(b), float(c)), float(tire.rolling_scale)


class Packed:
    """The per-run arrays of the kernels (run = first axis): parameters, initial state, tires, rolling, camber.

    Parameters
    ----------
    chairs : sequence of Chair
        One chair per run.
    speeds : ndarray
        Initial forward speeds, m/s.
    opts : Options
        Checked options.
    forces : ndarray, optional
        Per-run push at the c.g., N (else ``opts.impulse_force``).
    """

    def __init__(self, chairs: Sequence[Chair], speeds: np.ndarray, opts: Options, forces: np.ndarray | None):
        n = len(chairs)
        self.P = np.empty((n, 18))
        self.S = np.zeros((n, 10))
        self.TK = np.zeros((n, 3), dtype=np.int64)
        self.TS = np.zeros((n, 3, 6, 8))
        self.TL = np.ones((n, 3))
        self.LIM = np.full((n, 3, 2), math.inf)
        self.RK = np.zeros((n, 2), dtype=np.int64)
        self.RC = np.zeros((n, 2, 3))
        self.RS = np.zeros((n, 2))
        self.CAM = np.zeros((n, 2))
        self.CHK = np.zeros((n, 4), dtype=np.bool_)
        u0, v0 = initial_velocities(opts, 1.0)
        seen: dict[int, tuple] = {}                   # a batch's runs of one chair: looked up once
        for i, c in enumerate(chairs):
            rows = seen.get(id(c))
            if rows is None:
                rows = seen[id(c)] = chair_rows(c, opts.scheme)
            self.P[i], toe_row, tire_rows = rows
            force = opts.impulse_force if forces is None else float(forces[i])
            self.S[i, :8] = (float(speeds[i]) * u0, v0, opts.eta0, opts.beta0, force, *toe_row)
            (self.TK[i], self.TS[i], self.TL[i], self.LIM[i], self.RK[i], self.RC[i], self.RS[i], self.CAM[i],
             self.CHK[i]) = tire_rows

    @staticmethod
    def _tire_arrays(c: Chair, scheme: str) -> tuple:
        main, caster = c.main_tire_model(), c.caster_tire_model()
        if scheme == "wchair":   # MECHAN: CAMCOF*POLYFT(TIRY, INT(CAMANG), FZ), the unscaled tire
            cam_tire, cam_deg = _tires.get(c.main_tire), float(math.trunc(c.camber_deg))
        else:
            cam_tire, cam_deg = main, float(c.camber_deg)
        slots = [_tire_slot(t) for t in (caster, main, cam_tire)]
        fc = 0.0
        if cam_deg != 0:
            fc = cam_tire.camber_coefficient if c.camber_coefficient is None else float(c.camber_coefficient)
        rolls = [_rolling_slot(caster, c.caster_rolling_scale != 0), _rolling_slot(main, c.main_rolling_scale != 0)]
        chk_c, chk_m = isinstance(caster, _tires.Tire), isinstance(main, _tires.Tire)
        return (np.array([s[0] for s in slots], dtype=np.int64), np.array([s[1] for s in slots]),
                np.array([s[2] for s in slots]), np.array([s[3] for s in slots]),
                np.array([r[0] for r in rolls], dtype=np.int64), np.array([r[1] for r in rolls]),
                np.array([r[2] for r in rolls]), np.array((cam_deg, fc)), np.array((chk_c, chk_c, chk_m, chk_m)))


#: chairs whose packed rows :func:`chair_rows` keeps (the oldest dropped): a run's packing cost about a tenth of a
#: single run's Python time before (the scaled tire models are rebuilt on every call), and the searches, the explorer
#: and repeated runs pack the same chairs again
ROWS_CACHE_SIZE = 256
_ROWS: dict[tuple, tuple] = {}
_ROWS_LOCK = threading.Lock()


def chair_rows(chair: Chair, scheme: str) -> tuple[np.ndarray, tuple[float, float, float], tuple[np.ndarray, ...]]:
    """One chair's packed rows: its parameters, its toe slots and its tire, rolling and camber slots (read-only).

    Kept per (chair, scheme, the chair's two tires as :func:`stability.tires.get` gives them now): a tire
    registered again under the same name, or a tire file that changed, is packed anew.

    Parameters
    ----------
    chair : Chair
    scheme : str
        The run's scheme (the camber tire differs: see :meth:`Packed._tire_arrays`).

    Returns
    -------
    params : ndarray, shape (18,)
        :func:`stability.models.params.parameters` of the chair.
    toe : tuple of float
        ``(cos(toe), sin(toe), 1.0 if toe else 0.0)``.
    tires : tuple of ndarray
        The rows of ``TK, TS, TL, LIM, RK, RC, RS, CAM, CHK`` (:class:`Packed`).
    """
    key = (chair, scheme, _tires.get(chair.main_tire), _tires.get(chair.caster_tire))
    hit = _ROWS.get(key)
    if hit is not None:
        return hit
    params = np.array(parameters(chair), dtype=float)
    toe = math.radians(chair.toe_deg)
    rows = Packed._tire_arrays(chair, scheme)
    for a in (params, *rows):
        a.flags.writeable = False
    out = (params, (math.cos(toe), math.sin(toe), 1.0 if toe != 0 else 0.0), rows)
    with _ROWS_LOCK:
        _ROWS[key] = out
        while len(_ROWS) > ROWS_CACHE_SIZE:
            del _ROWS[next(iter(_ROWS))]
    return out


def slope_slots(opts: Options) -> tuple[float, float, float, float, float]:
    """The kernels' plane slots.

    Parameters
    ----------
    opts : Options
        Uses ``slope``: the cross slope phi and the grade theta, deg.

    Returns
    -------
    tuple of 5 float
        ``(on, cos(phi), sin(phi), cos(theta), sin(theta))``; ``on`` is 1.0 on a slope.
    """
    phi, theta = math.radians(opts.slope[0]), math.radians(opts.slope[1])
    return (1.0 if opts.slope != (0.0, 0.0) else 0.0, math.cos(phi), math.sin(phi), math.cos(theta), math.sin(theta))
