"""The drive controller's and brakes' settings of the virtual test bench: one table (unit, range, help).

:class:`stability.bench.Drive` checks against it, ``python -m stability.bench`` builds its options from it and
:data:`stability.cli.numbers.OPTION_BOUNDS` its plausibility bounds.
"""

from __future__ import annotations

__all__ = ["DRIVE_SETTINGS", "BENCH_CHAIR", "drive_flag"]

#: Every drive setting: (default, unit, valid range, help).  The defaults are stated estimates of a typical
#: 6 mph (2.7 m/s) power chair, not a measured one: set the chair's own.
DRIVE_SETTINGS: dict[str, tuple[float, str, tuple[float, float], str]] = {
    "max_speed_m_s": (2.7, "m/s", (0.1, 10.0), "top speed forward"),
    "reverse_speed_m_s": (1.0, "m/s", (0.1, 5.0), "top speed backwards"),
    "accel_m_s2": (1.0, "m/s^2", (0.05, 10.0), "acceleration when starting"),
    "decel_m_s2": (2.5, "m/s^2", (0.05, 10.0), "deceleration when the control is released"),
    "reverse_decel_m_s2": (3.5, "m/s^2", (0.05, 15.0), "deceleration when reverse is commanded at speed"),
    "brake_decel_m_s2": (3.0, "m/s^2", (0.05, 15.0), "deceleration of the brakes when the power is cut"),
    "brake_delay_s": (0.25, "s", (0.0, 5.0), "time from the power cut to the brakes' full deceleration"),
    "turn_rate_rad_s": (0.8, "rad/s", (0.0, 5.0), "largest yaw rate the controller commands at the top speed"),
    "traction": (0.8, "", (0.05, 2.0), "friction coefficient of the drive tires on the test surface"),
    "max_slope_deg": (6.0, "deg", (0.0, 30.0), "the declared maximum safe slope"),
}
#: The bench's default chair: the mid-wheel-drive base (stability.layout.presets).
BENCH_CHAIR = "mid-wheel-drive"


def drive_flag(name: str) -> str:
    """The option of a drive setting: its name without the unit, dashes for underscores.

    Parameters
    ----------
    name : str
        A key of :data:`DRIVE_SETTINGS` (``"max_speed_m_s"``).

    Returns
    -------
    str
        ``"--max-speed"``.
    """
    for unit in ("_m_s2", "_m_s", "_rad_s", "_deg", "_s"):
        if name.endswith(unit):
            name = name[: -len(unit)]
            break
    return "--" + name.replace("_", "-")
