"""One caster of any wheel layout, for the shimmy analyses.

The shimmy model is the caster alone, a towed wheel on its pin moving straight ahead
(:func:`stability.shimmy.chair.caster_wheel`): it needs the caster's own mass, inertia, centre of mass, trail,
pin damping and friction, its tire, and the tire's static load, which is the only thing the rest of the chair
decides.  :class:`LayoutCaster` gives exactly those for caster ``k`` of a :class:`~stability.layout.Layout`,
with the load from the layout's statics (:func:`stability.layout.static_loads`: the lever rule on two support
lines, the stated vertical compliance on more), recomputed for every trail the analyses try (the contact
moves with the trail, and with it the load).  So a mid-wheel-drive base's front and rear casters, which carry
different loads, get their own shimmy bands.

Reverse driving: a caster swings round and trails in the new direction, so its shimmy is that of the same
towed wheel after the swing; the loads are the same (statics do not depend on the direction of travel).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from stability import tires
from stability.chair import Chair
from stability.layout import Layout, static_loads

__all__ = ["LayoutCaster", "layout_casters", "CasterSource"]


@dataclass(frozen=True)
class LayoutCaster:
    """Caster ``index`` of ``layout`` with the attributes the shimmy analyses read from a chair.

    Parameters
    ----------
    layout : Layout
    index : int
        Position in ``layout.casters`` (0-based).
    """

    layout: Layout
    index: int

    def __post_init__(self) -> None:
        n = len(self.layout.casters)
        if not (isinstance(self.index, int) and 0 <= self.index < n):
            raise ValueError(f"index={self.index!r} is invalid; valid range: 0 to {n - 1} (the layout's casters)")

    @property
    def _c(self):
        return self.layout.casters[self.index]

    @property
    def name(self) -> str:
        """``"<layout> caster k (front left)"``, k from 1."""
        c = self._c
        where = ("front" if c.x > 0 else "rear") + (" left" if c.y < 0 else " right" if c.y > 0 else "")
        return f"{self.layout.name} caster {self.index + 1} ({where})"

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
        me = self._c
        # the caster's row (the casters on the same pin line with the same trail: a left-right pair) changes
        # together, as a chair's trail does; changing one caster of a pair would tilt the base onto three lines
        casters = tuple(replace(c, **changes) if abs(c.x - me.x) < 1e-9 and c.trail == me.trail else c
                        for c in self.layout.casters)
        return LayoutCaster(replace(self.layout, casters=casters), self.index)

    def static_load(self) -> float:
        """The caster's static load, N."""
        return float(static_loads(self.layout)[len(self.layout.wheels) + self.index])

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
        out = np.empty(uniq.size)
        for i, tr in enumerate(uniq):
            try:
                out[i] = self.replace(trail=float(tr)).static_load()
            except ValueError:                    # out of the caster's range, or the layout no longer stands
                out[i] = np.nan
        return out[inv].reshape(t.shape)


def layout_casters(layout: Layout) -> list[LayoutCaster]:
    """Every caster of ``layout``, in order.

    Parameters
    ----------
    layout : Layout

    Returns
    -------
    list of LayoutCaster
    """
    return [LayoutCaster(layout, k) for k in range(len(layout.casters))]


#: What the shimmy analyses take: a chair (its left or right caster) or one caster of a layout.
CasterSource = Chair | LayoutCaster
