"""The report's caster-shimmy section: the trail trade-off chart and the estimates' effect on it.

Every number comes from :mod:`stability.shimmy` (``shimmy.chair.trail_chart``, ``critical_trail``,
``chair_critical_trail``); the caster compliance values are estimates (docs/shimmy.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.shimmy import chair_critical_trail
from stability.shimmy.chair import (
    ESTIMATE_NOTE,
    CasterCompliance,
    TrailChart,
    caster_wheel,
    critical_trail,
    trail_chart,
)

__all__ = ["SHIMMY_SPEED", "ShimmySection", "shimmy_section", "shimmy_unavailable"]

#: Speed of the critical trails quoted in the text, m/s (without viscous pin damping they do not depend on it).
SHIMMY_SPEED = 1.0


@dataclass(frozen=True, eq=False)
class ShimmySection:
    """Trail x speed chart of one chair and the critical trail over the compliance estimates.

    Attributes
    ----------
    chart : TrailChart
        Yaw divergence rate (1/s) and shimmy boundaries (m) over trail x speed (caster as towed wheel).
    compliance : CasterCompliance
        The estimates used (relaxation length m, lateral stiffness at the pin N/m) and their ranges.
    speed : float
        m/s, of the numbers below.
    critical : float
        Linear shimmy boundary (m) with the nominal estimates: below this trail the caster shimmies.
    corners : tuple of (float, float, float)
        ``(relaxation length m, lateral stiffness N/m, critical trail m)`` at the four range corners
        (``inf``: shimmy at every trail up to 0.25 m).
    chair_model_critical : float
        The same boundary from the chair model with relaxed caster tires and compliant pins
        (:func:`stability.shimmy.chair_critical_trail`), m.
    divergence_at_trail : float
        Yaw divergence rate at the chair's trail and the chart's top speed, 1/s.
    note : str
        That the compliance values are estimates.
    """

    chart: TrailChart
    compliance: CasterCompliance
    speed: float
    critical: float
    corners: tuple
    chair_model_critical: float
    divergence_at_trail: float
    note: str = ESTIMATE_NOTE

    @property
    def divergence_span(self) -> tuple[float, float]:
        """Lowest and highest yaw divergence rate over the chart's trails at its top speed, 1/s."""
        col = self.chart.divergence_rate[:, -1]
        return float(np.min(col)), float(np.max(col))

    @property
    def margin(self) -> float:
        """The chair's trail minus the nominal critical trail, m (negative: inside the shimmy region)."""
        return self.chart.chair_trail - self.critical


def shimmy_unavailable(chair: Chair) -> str | None:
    """Why the shimmy page carries no information for ``chair`` (None if it does).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    str or None
    """
    try:
        caster_wheel(chair)
    except ValueError as exc:
        return f"the caster cannot be modelled as a towed wheel ({exc})"
    return None


def shimmy_section(chair: Chair, trails, speeds, speed: float = SHIMMY_SPEED) -> ShimmySection:
    """Compute the section (see :class:`ShimmySection`).

    Parameters
    ----------
    chair : Chair
    trails : array_like
        Trails of the chart, m.
    speeds : array_like
        Speeds of the chart, m/s.
    speed : float
        Speed of the quoted critical trails, m/s.

    Returns
    -------
    ShimmySection
    """
    comp = CasterCompliance()
    chart = trail_chart(chair, trails, speeds, comp)
    corners = tuple((cc.relaxation_length, cc.lateral_stiffness, critical_trail(chair, speed, cc))
                    for cc in comp.corners())
    cm = float(chair_critical_trail(chair, [speed], comp, "exact", "compliant")[0])
    rate = float(np.interp(chair.trail, chart.trails, chart.divergence_rate[:, -1]))
    return ShimmySection(chart, comp, float(speed), critical_trail(chair, speed, comp), corners, cm,
                         rate if math.isfinite(rate) else math.nan)
