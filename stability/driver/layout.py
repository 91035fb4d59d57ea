"""The human-limited speed of any wheel layout, forward and in reverse.

The short form's two linear limits (:mod:`.linear`: the divergence rule ``lambda(U) tau = 1`` and the best delayed
PD loop on heading and yaw rate) on the layout's own linear model (:mod:`stability.layout.linear`: free frictionless
casters, trailing at 0 deg forwards and at 180 deg in reverse), its yaw-moment column the driver's input.  In reverse
the plant is the layout's at ``-U``; the speeds searched and reported are sizes (m/s).  The short-form chair expanded
as a layout (:meth:`stability.layout.Layout.from_chair`) has the same matrices to rounding, hence the same limits.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from stability.driver.linear import PADE_ORDER, HumanLimit, plant_limit, rule_crossing, with_heading
from stability.driver.model import Driver
from stability.layout.linear import growth_rates, input_matrices, state_matrices
from stability.layout.model import Layout

__all__ = ["layout_human_limit", "layout_rule_speed", "layout_heading_plant"]


def layout_heading_plant(layout: Layout, speed: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The layout's free-caster linear model with its heading, driven by a yaw moment on the body.

    Parameters
    ----------
    layout : Layout
    speed : float
        Signed speed, m/s (negative: reverse).

    Returns
    -------
    (A, B, C)
        States ``[v, r, delta_0, delta_d_0, ..., psi]``; input the yaw moment (N m); outputs ``psi`` (rad) and ``r``
        (rad/s) (:func:`stability.driver.linear.with_heading`).
    """
    return with_heading(state_matrices(layout, [speed])[0], input_matrices(layout, [speed])[0][0])


def _rate(layout: Layout, sign: float) -> Callable[[float], float]:
    return lambda u: float(growth_rates(layout, [sign * u])[0])


def layout_rule_speed(layout: Layout, reaction_time: float, reverse: bool = False) -> tuple[float, str]:
    """The divergence rule's speed of a layout: where its largest growth rate reaches ``1 / reaction_time``.

    Parameters
    ----------
    layout : Layout
    reaction_time : float
        s (:class:`stability.driver.model.Driver`'s range).
    reverse : bool
        Backwards: the rates at ``-U``.

    Returns
    -------
    (float, str)
        The speed's size (m/s) and side (``"="``; ``">"``: beyond the speeds checked; ``"<"``: below them).
    """
    return rule_crossing(_rate(layout, -1.0 if reverse else 1.0), reaction_time)


def layout_human_limit(layout: Layout, driver: Driver | None = None, reverse: bool = False,
                       order: int = PADE_ORDER) -> HumanLimit:
    """The speeds above which this driver cannot hold this layout straight, forward or in reverse.

    Parameters
    ----------
    layout : Layout
    driver : Driver, optional
        Default :class:`Driver` (0.3 s).
    reverse : bool
        Backwards (the casters trailing at 180 deg).
    order : int
        Pade order of the delay.

    Returns
    -------
    HumanLimit
        :func:`stability.driver.linear.plant_limit` on :func:`layout_heading_plant`; model ``"exact"`` (a layout's
        equations are the exact model's), speeds are sizes (m/s).
    """
    d = driver or Driver()
    sign = -1.0 if reverse else 1.0
    return plant_limit(layout.name, "exact", lambda u: layout_heading_plant(layout, sign * u), _rate(layout, sign),
                       d.reaction_time_s, order)
