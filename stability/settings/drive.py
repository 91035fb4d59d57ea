"""The drive controller's and brakes' settings of the virtual test bench: one table (unit, range, help).

:class:`stability.bench.Drive` checks against it, ``python -m stability.bench`` builds its options from it and
:data:`stability.cli.numbers.OPTION_BOUNDS` its plausibility bounds.
"""

from __future__ import annotations

__all__ = ["DRIVE_SETTINGS", "drive_flag"]

#: Every drive setting: (unit, valid range, help).  The defaults are stated estimates of a typical 6 mph (2.7 m/s)
#: power chair; the decelerations put the bench's level braking distances from 2.7 m/s inside the range issue
#: 39 quotes for commercial chairs (Pearlman 2005: 7.4-117.3 cm) only for the strongest stops: set the chair's own.
DRIVE_SETTINGS: dict[str, tuple[str, tuple[float, float], str]] = {
    "max_speed_m_s": ("m/s", (0.1, 10.0), "top speed forward"),
    "reverse_speed_m_s": ("m/s", (0.1, 5.0), "top speed backwards"),
    "accel_m_s2": ("m/s^2", (0.05, 10.0), "acceleration when starting"),
    "decel_m_s2": ("m/s^2", (0.05, 10.0), "deceleration when the control is released"),
    "reverse_decel_m_s2": ("m/s^2", (0.05, 15.0), "deceleration when reverse is commanded at speed"),
    "brake_decel_m_s2": ("m/s^2", (0.05, 15.0), "deceleration of the brakes when the power is cut"),
    "brake_delay_s": ("s", (0.0, 5.0), "time from the power cut to the brakes' full deceleration"),
    "turn_rate_rad_s": ("rad/s", (0.0, 5.0), "largest yaw rate the controller commands at the top speed"),
    "traction": ("", (0.05, 2.0), "friction coefficient of the drive tires on the test surface"),
    "max_slope_deg": ("deg", (0.0, 30.0), "the declared maximum safe slope"),
}


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
