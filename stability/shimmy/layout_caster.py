"""One caster of any wheel layout, for the shimmy analyses.

The shimmy model is the caster alone, a towed wheel on its pin moving straight ahead
(:func:`stability.shimmy.chair.caster_wheel`): it needs the caster's own mass, inertia, centre of mass, trail,
pin damping and friction, its tire, and the tire's static load, which is the only thing the rest of the chair
decides.  :class:`LayoutCaster` gives exactly those for caster ``k`` of a :class:`~stability.layout.Layout`,
with the load from the layout's statics (:func:`stability.layout.static_loads`: the lever rule on two support
lines, the stated vertical compliance on more), recomputed for every trail the analyses try (the contact
moves with the trail, and with it the load).  So a mid-wheel-drive base's front and rear casters, which carry
different loads, get their own shimmy bands.

Reverse driving: a caster trails behind its pin in the direction of travel.  At the moment the chair reverses,
every caster leads its pin; that straight-running state is unstable (a leading caster's swivel angle grows, for a
rigid pin and tire at the rate ``|U| / trail``, :func:`leading_divergence_rate`), so the caster swings round
and trails the other way.  Its shimmy in reverse is then that of the same towed wheel at ``|U|``, with the load
of the layout whose casters trail backwards: each contact has moved ``2 trail`` and each caster's centre of mass
``2 l`` (:func:`stability.layout.static_loads` with ``reverse=True``), so the rows share the weight differently
than forwards.  ``LayoutCaster(layout, k, reverse=True)`` is that caster.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from dataclasses import dataclass, replace

import numpy as np

from stability import tires
from stability.chair import Chair
from stability.chair.model import LIMITS
from stability.layout import Layout, static_loads
from stability.layout.model import Caster
from stability.layout.statics import centre_of_mass, contacts, distribute

__all__ = ["LayoutCaster", "layout_casters", "CasterSource", "leading_divergence_rate"]

#: The trails a caster may have, m (:class:`~stability.layout.model.Caster`'s check: the short form's range).
_TRAIL_RANGE = LIMITS["trail"][:2]
#: Memo of :func:`_row_loads`: per caster (by value: its layout's every field, its index and direction), the load
#: (N) at each trail asked (m); the casters least recently asked are dropped beyond :data:`_MEMO_CASTERS`.
_MEMO: OrderedDict[LayoutCaster, dict[float, float]] = OrderedDict()
_MEMO_CASTERS = 64
_MEMO_LOCK = threading.Lock()


@dataclass(frozen=True)
class LayoutCaster:
    """Caster ``index`` of ``layout`` with the attributes the shimmy analyses read from a chair.

    Parameters
    ----------
    layout : Layout
    index : int
        Position in ``layout.casters`` (0-based).
    reverse : bool
        The chair drives backwards: every caster has swung round and trails behind its pin the other way (its
        load from the reversed statics).
    """

    layout: Layout
    index: int
    reverse: bool = False

    def __post_init__(self) -> None:
        n = len(self.layout.casters)
        if not (isinstance(self.index, int) and 0 <= self.index < n):
            raise ValueError(f"index={self.index!r} is invalid; valid range: 0 to {n - 1} (the layout's casters)")

    @property
    def _c(self):
        return self.layout.casters[self.index]

    @property
    def name(self) -> str:
        """``"<layout> caster k (front left)"``, k from 1 (``", reverse"`` appended in reverse)."""
        return f"{self.layout.name} caster {self.index + 1} ({self._c.place}{', reverse' if self.reverse else ''})"

    @property
    def trail(self) -> float:
        """m."""
        return float(self._c.trail)

    @property
    def m_c(self) -> float:
        """kg."""
        return float(self._c.m_c)

    @property
    def i_zp(self) -> float:
        """Yaw inertia about the pin, kg m^2."""
        return float(self._c.i_zp)

    @property
    def l1(self) -> float:
        """Pin to the caster's centre of mass, m."""
        return float(self._c.l)

    @property
    def pin_damping(self) -> float:
        """N m s/rad."""
        return float(self._c.pin_damping)

    @property
    def pin_friction_left(self) -> float:
        """The caster's Coulomb pin friction, N m (one caster: "left" and "right" are the same pin)."""
        return float(self._c.pin_friction)

    pin_friction_right = pin_friction_left

    def caster_tire_model(self) -> tires.Tire | tires.LinearTire:
        """The caster's tire, scaled by its lateral scale."""
        return tires.get(self._c.tire).scaled(lateral=self._c.lateral_scale)

    def replace(self, **changes: float) -> LayoutCaster:
        """The same layout with the trail of this caster's row replaced (the only change the analyses make).

        The row: every caster on the same pin line (same ``x``) with the same trail, so a left-right pair
        changes together as a chair's trail does.

        Parameters
        ----------
        **changes
            ``trail=`` (m).

        Returns
        -------
        LayoutCaster
        """
        unknown = sorted(set(changes) - {"trail"})
        if unknown:
            raise ValueError(f"a layout caster's {unknown} cannot be replaced here; valid: ['trail']")
        casters = tuple(replace(c, **changes) if self._in_row(c) else c for c in self.layout.casters)
        return LayoutCaster(replace(self.layout, casters=casters), self.index, self.reverse)

    def _in_row(self, c: Caster) -> bool:
        """Whether caster ``c`` is on this caster's row: the same pin line (same ``x``) and the same trail (a
        left-right pair changes together, as a chair's trail does; changing one caster of a pair would tilt the base
        onto three lines)."""
        me = self._c
        return abs(c.x - me.x) < 1e-9 and c.trail == me.trail

    def static_load(self) -> float:
        """The caster's static load, N (casters trailing backwards in reverse)."""
        return float(static_loads(self.layout, self.reverse)[len(self.layout.wheels) + self.index])

    def loads(self, trails: np.ndarray) -> np.ndarray:
        """Static load of this caster at each trail (m), N; NaN where the layout would not stand.

        Parameters
        ----------
        trails : ndarray

        Returns
        -------
        ndarray
            Same shape as ``trails``.
        """
        t = np.asarray(trails, dtype=float)
        uniq, inv = np.unique(t, return_inverse=True)
        out = _row_loads(self, tuple(float(tr) for tr in uniq))
        return out[inv].reshape(t.shape)


def _row_loads(caster: LayoutCaster, trails: tuple[float, ...]) -> np.ndarray:
    """Static load of ``caster`` (N) with its row's trail set to each of ``trails`` (m); NaN where the layout would
    not stand.

    The answer of :meth:`LayoutCaster.replace` then :meth:`LayoutCaster.static_load` at each trail, bit for bit,
    without building a layout per trail: the row's contacts move to ``x - trail`` (``x + trail`` in reverse) in the
    contact list of :func:`stability.layout.statics.contacts`, whose loads :func:`~stability.layout.statics.
    distribute` shares as :func:`~stability.layout.static_loads` does (the centre of mass does not move with the
    trail); a trail outside a caster's range (:class:`~stability.layout.model.Caster`'s check) or a load that is not
    positive gives NaN, as the layout's own checks refuse it.  Trails already asked of this caster are memoised
    (:func:`_memo`).

    Parameters
    ----------
    caster : LayoutCaster
    trails : tuple of float
        m.

    Returns
    -------
    ndarray
        N, one per trail.
    """
    layout = caster.layout
    nw = len(layout.wheels)
    row = [nw + k for k, c in enumerate(layout.casters) if caster._in_row(c)]
    pts = contacts(layout, caster.reverse)
    weight, centre = layout.m * layout.g, centre_of_mass(layout, caster.reverse)
    sign = -1.0 if caster.reverse else 1.0
    lo, hi = _TRAIL_RANGE
    memo = _memo(caster)
    out = np.empty(len(trails))
    for n, tr in enumerate(trails):
        known = memo.get(tr)
        if known is not None:
            out[n] = known
            continue
        load = math.nan
        if math.isfinite(tr) and lo <= tr <= hi:
            for i in row:
                label, _, y, kv = pts[i]
                pts[i] = (label, layout.casters[i - nw].x - sign * tr, y, kv)
            loads = distribute(pts, weight, centre)
            if all(x > 0 for x in loads):
                load = float(loads[nw + caster.index])
        out[n] = memo[tr] = load
    return out


def _memo(caster: LayoutCaster) -> dict[float, float]:
    """The memo of ``caster``'s loads by trail (:data:`_MEMO`): a band, a chart or a summary asks for the same
    trails of the same caster many times over (once per speed and per estimate corner)."""
    with _MEMO_LOCK:
        memo = _MEMO.get(caster)
        if memo is None:
            memo = _MEMO[caster] = {}
            if len(_MEMO) > _MEMO_CASTERS:
                _MEMO.popitem(last=False)
        else:
            _MEMO.move_to_end(caster)
        return memo


def layout_casters(layout: Layout, reverse: bool = False) -> list[LayoutCaster]:
    """Every caster of ``layout``, in order.

    Parameters
    ----------
    layout : Layout
    reverse : bool
        Driving backwards (each caster swung round, see :class:`LayoutCaster`).

    Returns
    -------
    list of LayoutCaster
    """
    return [LayoutCaster(layout, k, reverse) for k in range(len(layout.casters))]


def leading_divergence_rate(trail: float, speeds) -> np.ndarray:
    """Growth rate of a caster's swivel angle while it leads its pin (just after the chair reverses), 1/s.

    The generated towed wheel (:mod:`stability.models.shimmy`) with a rigid pin and a rigid tire, run at the
    speed ``-|U|``: its one state, the swivel angle, follows the no-side-slip constraint
    ``L psi_dot = U sin psi``, so it grows at ``|U| / L`` and the caster swings round (the reorientation the
    layout simulator shows).  Mass, inertia and tire do not enter this limit.

    Parameters
    ----------
    trail : float
        m (> 0).
    speeds : array_like
        Speeds, m/s (their size is used).

    Returns
    -------
    ndarray
        Per speed, the rate (1/s, > 0: it diverges).
    """
    from stability.models import shimmy as shimmy_model

    U = -np.abs(np.asarray(speeds, dtype=float))
    params = dict(mass=1.0, inertia=1.0, a=trail, b=0.0, k=1.0, C=1.0, sigma=1.0, c=0.0)
    A, _ = shimmy_model.state_matrices(shimmy_model.case_name(True, True), params, U)
    return np.linalg.eigvals(A).real.max(axis=-1)


#: What the shimmy analyses take: a chair (its left or right caster) or one caster of a layout.
CasterSource = Chair | LayoutCaster
