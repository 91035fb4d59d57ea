"""The thesis's reference case, named once: chair, speed, push, level, horizon, published numbers.

Chapter 8 of Collins (1987) judges a chair by the time its |yaw rate| takes to
reach 1 rad/s after a lateral push at the centre of gravity (Figure 8-3a: the
E&J Premier at 0.75 m/s, 40 N for 0.1 s, "slightly over 3 s").  Every study,
report and command line takes its defaults from here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Push", "THESIS_PUSH", "REFERENCE_CHAIR", "REFERENCE_SPEED", "LEVEL", "HORIZON", "THESIS_PUBLISHED",
           "CROSS_SLOPE_STUDY"]


@dataclass(frozen=True)
class Push:
    """A lateral push: a constant force at the c.g., to the right, for a duration.

    Attributes
    ----------
    force : float
        Lateral force, N (positive to the right).
    duration : float
        How long it acts, s.  The simulators apply it while ``t <= duration``
        (program WCHAIR's ``T .LE. DUIMP``), so a fixed step ``dt`` gives
        ``floor(duration/dt) + 1`` steps.
    """

    force: float = 40.0
    duration: float = 0.1

    def steps(self, dt: float) -> int:
        """Number of fixed steps of length ``dt`` (s) that carry the force (WCHAIR convention)."""
        return int(math.floor(self.duration / dt * (1.0 + 1e-12) + 1e-9)) + 1

    def impulse(self, dt: float | None = None) -> float:
        """Impulse delivered, N s: ``force * duration``, or ``force * steps * dt`` on a fixed step."""
        return self.force * (self.duration if dt is None else self.steps(dt) * dt)

    def describe(self, dt: float | None = 0.001) -> str:
        """The push convention in words, e.g. ``40 N for 0.1 s (101 steps of 1 ms, 4.04 N s)``."""
        if dt is None:
            return f"{self.force:g} N for {self.duration:g} s ({self.impulse():.3g} N s)"
        return (f"{self.force:g} N for {self.duration:g} s ({self.steps(dt)} steps of {dt * 1e3:g} ms, "
                f"{self.impulse(dt):.3g} N s)")

    @property
    def as_tuple(self) -> tuple[float, float]:
        """``(force N, duration s)``, the form the study functions take."""
        return (self.force, self.duration)


#: The thesis's reference push (chapter 8): 40 N at the c.g. for 0.1 s.
THESIS_PUSH = Push(40.0, 0.1)
#: The reference chair (preset name) and speed (m/s) of Figure 8-3a.
REFERENCE_CHAIR = "ej-premier"
REFERENCE_SPEED = 0.75
#: The instability criterion: |yaw rate| reaching LEVEL rad/s within HORIZON s.
LEVEL = 1.0
HORIZON = 10.0

#: Numbers the thesis reports, for comparison only (never used in computations).
THESIS_PUBLISHED = {
    "reference_time_to_1_rad_s": "slightly over 3 s (Figure 8-3a, 0.75 m/s)",
    "revised": "about 1.10-1.15 m/s (Figure 9-2)",
    "revised_half_friction": "about 0.65 m/s (Figure 9-3)",
    "revised_1.5x_friction": "about 1.65 m/s (Figure 9-3)",
    "reduced_mass": "about 0.85 m/s (Figure 8-14, m = 75 kg, I_z = 4.7 kg m^2)",
}

#: Treadmill study of 26 manual wheelchair users on a cross slope (Richter et al., Arch Phys Med Rehabil
#: 2007, 88:76-80): downhill turning moment per degree of cross slope, N m/deg, as (mean, lowest, highest).
CROSS_SLOPE_STUDY = (0.87, 0.25, 1.80)
