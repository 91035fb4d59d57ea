"""Power bases of one frame: front-, mid- and rear-wheel drive (as one frame is built three ways, e.g. the Varpo).

The body is the ``power-fwd`` preset's (docs/power-chair.md: 215 kg with a 100 kg user, yaw inertia 13 kg m^2,
c.g. 0.49 m high, lumped estimate in :mod:`stability.chair.power`), its drive wheels (track 0.55 m, linear tire of
110 N/deg) and its casters (8 in ER casters, trail 5 cm, pins 0.44 m apart).  Only where the drive axle sits
changes:

``power-fwd-base``
    drive axle 0.18 m ahead of the c.g., a caster pair with pins 0.32 m behind it: the ``power-fwd`` chair;
``power-rwd-base``
    drive axle 0.18 m behind the c.g., the caster pair with pins 0.32 m ahead;
``mid-wheel-drive``
    drive axle 0.03 m behind the c.g. (mid-wheel-drive bases put the c.g. just ahead of the drive axle), a
    caster pair with pins 0.32 m ahead and another 0.33 m behind.  Six contacts on more than two support lines:
    the loads follow from the vertical stiffnesses, stated estimates: 150 kN/m for a drive wheel (its
    suspension and pneumatic tire) and 30 kN/m for each caster on its suspension arm, so the drive wheels carry
    about 70 % of the weight, the share mid-wheel-drive bases are built for (traction on the drive wheels).

Stated estimates, not a measured chair: the comparison they support is of the layouts (docs/layouts.md).
"""

from __future__ import annotations

from stability.layout.model import Caster, FixedWheel, Layout

__all__ = ["layout_preset", "layout_preset_names", "BODY", "DRIVE_X_M"]

#: The frame's body: mass (kg), yaw inertia about the c.g. (kg m^2), c.g. height (m): the power-fwd preset's.
BODY: dict = dict(m=215.0, i_z=13.0, h=0.49)
#: Drive axle x relative to the c.g. (m) by drive layout.
DRIVE_X_M = {"power-fwd-base": 0.18, "mid-wheel-drive": -0.03, "power-rwd-base": -0.18}
_TRACK_HALF_M = 0.275
_PIN_HALF_M = 0.22
#: The casters: trail (m), pin to c.g. (m), mass (kg), yaw inertia about the pin (kg m^2), tire, pin friction (N m).
_CASTER: dict = dict(trail=0.05, l=0.035, m_c=1.6, i_zp=0.006, tire="ER", pin_friction=0.15)
#: Vertical stiffnesses of the mid-wheel-drive base (N/m): stated estimates (module docstring).
DRIVE_STIFFNESS_N_PER_M = 1.5e5
CASTER_STIFFNESS_N_PER_M = 3.0e4


def _drive(x: float, k: float = DRIVE_STIFFNESS_N_PER_M) -> tuple[FixedWheel, FixedWheel]:
    return tuple(FixedWheel(x, y, tire="linear:110", driven=True, vertical_stiffness=k)  # type: ignore[return-value]
                 for y in (-_TRACK_HALF_M, _TRACK_HALF_M))


def _pair(x: float, k: float = CASTER_STIFFNESS_N_PER_M) -> tuple[Caster, Caster]:
    return tuple(Caster(x, y, vertical_stiffness=k, **_CASTER)  # type: ignore[return-value]
                 for y in (-_PIN_HALF_M, _PIN_HALF_M))


def layout_preset_names() -> tuple[str, ...]:
    """The layout presets' names.

    Returns
    -------
    tuple of str
    """
    return tuple(DRIVE_X_M)


def layout_preset(name: str) -> Layout:
    """A power base of the frame.

    Parameters
    ----------
    name : {"power-fwd-base", "mid-wheel-drive", "power-rwd-base"}

    Returns
    -------
    Layout
    """
    if name == "power-fwd-base":
        return Layout(name, wheels=_drive(DRIVE_X_M[name]), casters=_pair(-0.32), **BODY)
    if name == "power-rwd-base":
        return Layout(name, wheels=_drive(DRIVE_X_M[name]), casters=_pair(0.32), **BODY)
    if name == "mid-wheel-drive":
        return Layout(name, wheels=_drive(DRIVE_X_M[name]), casters=_pair(0.32) + _pair(-0.33), **BODY)
    raise ValueError(f"unknown layout preset {name!r}; valid: {list(DRIVE_X_M)}")
