"""The linear model of any layout: state matrices at many speeds, forward and in reverse.

The generated functions of :mod:`stability.models.layout` (from ``derivations/layout.py``: Kane's method for any
number of fixed wheels and casters) give ``M acc = K x + Bm Mz + Bf Fy``; each tire's lateral force is linear in
its slip with its cornering stiffness at its static load (:func:`.statics.cornering_stiffnesses`), the pins
viscous; a fixed wheel turned by its angle (toe, ``FixedWheel.angle_deg``) has its force along its own lateral
axis, linear in its slip at straight running (its cornering stiffness at the static load, so a toed wheel on a
curved tire is approximated by the slope at zero slip).  States ``[v, r, delta_0, delta_d_0, delta_1, delta_d_1,
...]`` (m/s, rad/s, rad, rad/s, ...).  A negative speed drives the chair backwards with every caster trailing the
other way (``delta = pi``): the linearisation about that state.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from stability import tires
from stability.layout.model import Layout, takes_layout
from stability.layout.statics import cornering_stiffnesses
from stability.models.layout import linear_layout_matrices, supported_shapes
from stability.settings.bounds import SIGNED_SPEED

__all__ = ["state_matrices", "input_matrices", "growth_rates", "LayoutSummary", "analyse_layout", "states",
           "critical_speed", "SEARCH_SPEEDS_M_S"]

#: Speeds searched for a critical speed (the growth rate's sign change), m/s (each direction).
SEARCH_SPEEDS_M_S = np.geomspace(0.02, 20.0, 240)


def states(layout: Layout) -> tuple[str, ...]:
    """State names of the layout's linear model.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    tuple of str
        ``v`` (m/s), ``r`` (rad/s), then per caster ``delta_k`` (rad) and ``delta_d_k`` (rad/s).
    """
    return ("v", "r") + tuple(n for k in range(len(layout.casters)) for n in (f"delta_{k}", f"delta_d_{k}"))


def _args(layout: Layout, reverse: bool) -> tuple[float, ...]:
    cw, cc = cornering_stiffnesses(layout, reverse)
    out: list[float] = [layout.m, layout.i_z]
    for w, c in zip(layout.wheels, cw, strict=True):
        out += [w.x, w.y, float(c), math.cos(math.radians(w.angle_deg)), math.sin(math.radians(w.angle_deg))]
    for k, c in enumerate(layout.casters):
        out += [c.x, c.trail, c.l, c.m_c, c.i_zp, float(cc[k]), c.pin_damping]
    return tuple(out)


def _matrices(layout: Layout, speeds, args: dict[bool, tuple[float, ...]] | None = None
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``(A, B_moment, B_force, U)`` at ``speeds``; ``args``: the generated functions' arguments by direction
    (:func:`_args`, which depend on the layout alone), when a search asks at many speeds one by one."""
    U = np.atleast_1d(np.asarray(speeds, dtype=float))
    if not np.all(SIGNED_SPEED.holds(U)):
        raise ValueError(f"speeds={speeds!r} is invalid; valid range: {SIGNED_SPEED.text('U')} (negative: reverse)")
    if layout.shape not in supported_shapes():
        raise ValueError(f"layout {layout.name!r} has {layout.shape[0]} fixed wheels and {layout.shape[1]} casters; "
                         f"valid shapes: {supported_shapes()} (add one to derivations/layout.py SHAPES)")
    n = 2 + 2 * len(layout.casters)
    A = np.zeros((len(U), n, n))
    B = np.zeros((len(U), n, 2))
    for reverse in (False, True):
        idx = np.nonzero((U < 0) == reverse)[0]
        if len(idx) == 0:
            continue
        M, K, Bm, Bf = linear_layout_matrices(layout.shape, reverse, U[idx],
                                              _args(layout, reverse) if args is None else args[reverse])
        sol = np.linalg.solve(M, np.concatenate([K, Bm[..., None], Bf[..., None]], axis=-1))
        F, G = sol[..., :n], sol[..., n:]
        rows = [0, 1] + [3 + 2 * k for k in range(len(layout.casters))]
        for a, row in enumerate(rows):
            A[idx, row, :] = F[:, a, :]
            B[idx, row, :] = G[:, a, :]
        for k in range(len(layout.casters)):
            A[idx, 2 + 2 * k, 3 + 2 * k] = 1.0
    return A, B[..., :1], B[..., 1:], U


@takes_layout
def state_matrices(layout: Layout, speeds) -> np.ndarray:
    """State matrices of the layout's linear model at each speed.

    Parameters
    ----------
    layout : Layout
    speeds : float or array_like
        m/s; negative drives backwards (casters trailing at pi).

    Returns
    -------
    ndarray
        Shape ``(len(speeds), n, n)``, n = 2 + 2 x casters (1/s and their ratios, SI).
    """
    return _matrices(layout, speeds)[0]


@takes_layout
def input_matrices(layout: Layout, speeds) -> tuple[np.ndarray, np.ndarray]:
    """Input columns of a yaw moment on the body (per N m) and a lateral force at the c.g. (per N).

    Parameters
    ----------
    layout : Layout
    speeds : float or array_like

    Returns
    -------
    (ndarray, ndarray)
        Each of shape ``(len(speeds), n, 1)``.
    """
    _, Bm, Bf, _ = _matrices(layout, speeds)
    return Bm, Bf


@takes_layout
def growth_rates(layout: Layout, speeds) -> np.ndarray:
    """Largest real part of the eigenvalues at each speed, 1/s.

    Parameters
    ----------
    layout : Layout
    speeds : float or array_like

    Returns
    -------
    ndarray
        Shape ``(len(speeds),)``.
    """
    return np.max(np.linalg.eigvals(state_matrices(layout, speeds)).real, axis=-1)


@takes_layout
def critical_speed(layout: Layout, reverse: bool = False) -> tuple[float, str]:
    """The first speed at which the layout's stability changes, forward or in reverse.

    Parameters
    ----------
    layout : Layout
    reverse : bool

    Returns
    -------
    (float, str)
        ``(speed m/s, kind)``: kind ``"destabilising"`` (stable below, unstable above), ``"stabilising"``, or
        ``"none-stable"`` / ``"none-unstable"`` with the speed the searched range's end (a bound: no change up
        to 20 m/s).

    Notes
    -----
    A function of the (frozen) layout and the direction alone: the last answers are kept per equal layout, so
    the same draws searched again (a comparison at another level, a report and its figure) cost nothing.
    """
    try:
        hash(layout)
    except TypeError:                                    # a field holding a list: searched without keeping it
        return _critical_speed.__wrapped__(layout, bool(reverse), ())
    # a wheel's tire is a name: what it names is part of the key (a registered name replaced, a tire file changed)
    return _critical_speed(layout, bool(reverse), tuple(_TireKey(tires.get(w.tire))
                                                        for w in (*layout.wheels, *layout.casters)))


class _TireKey:
    """A tire as a key part: equal to an equal tire when tires compare by value (hashable), else only to the
    same object, held so that its identity is not reused while the key lives."""

    __slots__ = ("tire", "by_value", "_hash")

    def __init__(self, tire: object) -> None:
        self.tire = tire
        try:
            self._hash, self.by_value = hash(tire), True
        except TypeError:                                # a tire holding arrays: by identity
            self._hash, self.by_value = id(tire), False

    def __hash__(self) -> int:
        return self._hash

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, _TireKey):
            return NotImplemented
        return other.tire is self.tire or (self.by_value and other.by_value and bool(other.tire == self.tire))


@functools.lru_cache(maxsize=4096)
def _critical_speed(layout: Layout, reverse: bool, _tires: tuple) -> tuple[float, str]:
    """:func:`critical_speed`'s search, kept per (layout, direction, the tires its names resolve to)."""
    sign = -1.0 if reverse else 1.0
    U = SEARCH_SPEEDS_M_S * sign
    args = {reverse: _args(layout, reverse)}           # the same at every speed: built once for the search

    def rates(speeds: np.ndarray) -> np.ndarray:
        return np.max(np.linalg.eigvals(_matrices(layout, speeds, args)[0]).real, axis=-1)

    g = rates(U)
    flips = np.nonzero(np.sign(g[1:]) != np.sign(g[:-1]))[0]
    if len(flips) == 0:
        return float(SEARCH_SPEEDS_M_S[-1]), "none-stable" if g[0] < 0 else "none-unstable"
    k = int(flips[0])
    lo, hi = float(SEARCH_SPEEDS_M_S[k]), float(SEARCH_SPEEDS_M_S[k + 1])
    glo = g[k]
    for _ in range(50):                                  # bisection to 1e-6 m/s
        mid = 0.5 * (lo + hi)
        gm = rates(np.array([sign * mid]))[0]
        if np.sign(gm) == np.sign(glo):
            lo = mid
        else:
            hi = mid
        if hi - lo < 1e-6:
            break
    return 0.5 * (lo + hi), "destabilising" if glo < 0 else "stabilising"


@dataclass(frozen=True)
class LayoutSummary:
    """Directional stability of a layout forward and in reverse (linear, frictionless casters).

    Attributes
    ----------
    layout : str
    speeds_m_s : ndarray
        Signed speeds, m/s.
    growth_rate_1_s : ndarray
        Largest real part at each speed, 1/s.
    forward_critical, reverse_critical : tuple
        :func:`critical_speed` forward and in reverse.
    """

    layout: str
    speeds_m_s: np.ndarray
    growth_rate_1_s: np.ndarray
    forward_critical: tuple = ()
    reverse_critical: tuple = ()

    @property
    def stable(self) -> np.ndarray:
        """Whether every eigenvalue has a negative real part at each speed."""
        return self.growth_rate_1_s < 0

    def to_mapping(self) -> dict:
        """JSON-ready dict."""
        def crit(c: tuple) -> dict | None:
            return None if not c else {"speed_m_s": c[0], "kind": c[1]}

        return {"layout": self.layout, "speeds_m_s": [float(u) for u in self.speeds_m_s],
                "growth_rate_1_s": [float(x) for x in self.growth_rate_1_s],
                "forward_critical": crit(self.forward_critical), "reverse_critical": crit(self.reverse_critical)}


@takes_layout
def analyse_layout(layout: Layout, speeds=(-1.5, -1.0, -0.5, 0.5, 1.0, 1.5, 2.0, 3.0)) -> LayoutSummary:
    """Growth rates of a layout at signed speeds (forward and reverse).

    Parameters
    ----------
    layout : Layout
    speeds : sequence of float
        m/s, negative for reverse.

    Returns
    -------
    LayoutSummary
    """
    U = np.asarray(speeds, dtype=float)
    return LayoutSummary(layout.name, U, growth_rates(layout, U), critical_speed(layout), critical_speed(layout, True))
