"""A chair as a list of wheels: any number of fixed wheels and swivelling casters on one rigid body.

The thesis's chairs have two fixed main wheels and a caster pair; a mid-wheel-drive power base has its drive
wheels near the centre of gravity and a caster pair ahead and another behind.  A :class:`Layout` holds the body
(mass, yaw inertia about the centre of gravity with every caster trailing forward, c.g. height) and its wheels in
body coordinates relative to the c.g. (SAE axes: x forward, y right).  :meth:`Layout.from_chair` expands the
short form (:class:`stability.chair.Chair`) into this form; :mod:`.presets` has the power bases.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from stability import tires
from stability.chair import Chair
from stability.chair.model import LIMITS
from stability.runtime.checks import first_argument, value_text

__all__ = ["FixedWheel", "Caster", "Layout", "check_layout", "takes_layout", "FIELD_UNITS"]

#: Unit of every numeric field, by class (``""``: dimensionless): the field checks' messages and the command lines'
#: ``--set caster_1_trail=6cm`` conversions read them here.
FIELD_UNITS: dict[str, dict[str, str]] = {
    "FixedWheel": {"x": "m", "y": "m", "lateral_scale": "", "vertical_stiffness": "N/m", "rolling_scale": "",
                   "camber_deg": "deg", "camber_coefficient": "", "angle_deg": "deg"},
    "Caster": {"x": "m", "y": "m", "trail": "m", "l": "m", "m_c": "kg", "i_zp": "kg m^2",
               "pin_damping": "N m s/rad", "pin_friction": "N m", "lateral_scale": "", "vertical_stiffness": "N/m",
               "rolling_scale": ""},
    "Layout": {"m": "kg", "i_z": "kg m^2", "h": "m", "g": "m/s^2"},
}
_W, _C, _L = FIELD_UNITS["FixedWheel"], FIELD_UNITS["Caster"], FIELD_UNITS["Layout"]


def _check(name: str, value: float, lo: float, hi: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"{name}={value!r} is invalid; expected a number ({unit})")
    if not (math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"{name}={value!r} is invalid; valid range: {lo:g} to {hi:g} {unit}")
    return float(value)


#: Reference vertical stiffness of a wheel, N/m (a stated estimate: the scale only matters on bases of more than
#: two support lines, where the ratios share the load).
K_REF_N_PER_M = 2.0e5


def _roll_pair(roll_k: float, main_track: float, caster_track: float) -> tuple[float, float]:
    """Vertical stiffnesses (main wheel, caster), N/m, about :data:`K_REF_N_PER_M`, whose pairs' roll
    stiffnesses ``k track^2 / 2`` have the ratio ``roll_k`` (the thesis's ``k = k_f / k_r``, eq 6-28); both
    scaled up together when one would fall below the wheels' 1000 N/m (only their ratio matters on two support
    lines: every valid chair expands)."""
    r = math.sqrt(roll_k) * caster_track / main_track
    scale = max(1.0, 1e3 / (K_REF_N_PER_M * r), 1e3 * r / K_REF_N_PER_M)
    return K_REF_N_PER_M * r * scale, K_REF_N_PER_M / r * scale


def _chair(name: str) -> tuple[float, float]:
    """The short form's range of a field (:data:`stability.chair.model.LIMITS`)."""
    lo, hi, _ = LIMITS[name]
    return lo, hi


@dataclass(frozen=True)
class FixedWheel:
    """A wheel that does not swivel (a drive wheel, a main wheel).

    Parameters
    ----------
    x, y : float
        Contact point relative to the c.g., m (x forward, y right).
    tire : str
        Tire spec (:func:`stability.tires.get`: a tire name or ``"linear:C"``).
    driven : bool
        Whether it is a drive wheel (power chairs: the motors act through it).
    lateral_scale : float
        Factor on the tire's lateral force (WCHAIR's TYMOD).
    vertical_stiffness : float
        Suspension plus tire vertical stiffness, N/m (shares the load of a base with more than two support lines;
        0: the wheel does not reach the ground and carries nothing).
    rolling_scale : float
        Factor on the tire's rolling-resistance force (WCHAIR's TXMOD; 0, the default, switches it off as the
        thesis's studies do).
    camber_deg : float
        Camber, deg, the wheel's top leaning toward the chair's centre line ``y = 0`` (a wheel on the centre line
        has none).
    camber_coefficient : float or None
        Camber coefficient ``f_c`` of eq 4-2; ``None``: the tire's own.
    angle_deg : float
        The wheel's angle (toe, a misalignment), deg: its plane turned from the body's forward axis about the
        vertical, positive turning its front to the right (``+y``, clockwise seen from above, the yaw sign).
        :meth:`Layout.from_chair` gives a chair's ``toe_deg`` to the left wheel as ``-toe`` and to the right
        as ``+toe`` (the thesis engine's convention: positive toe turns the fronts apart).
    """

    x: float
    y: float
    tire: str = "EJA"
    driven: bool = False
    lateral_scale: float = 1.0
    vertical_stiffness: float = 2.0e5
    rolling_scale: float = 0.0
    camber_deg: float = 0.0
    camber_coefficient: float | None = None
    angle_deg: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", _check("x", self.x, -2.0, 2.0, _W["x"]))
        object.__setattr__(self, "angle_deg", _check("angle_deg", self.angle_deg, *_chair("toe_deg"), _W["angle_deg"]))
        object.__setattr__(self, "y", _check("y", self.y, -1.0, 1.0, _W["y"]))
        object.__setattr__(self, "lateral_scale", _check("lateral_scale", self.lateral_scale, 0.0, 10.0,
                                                                 _W["lateral_scale"]))
        object.__setattr__(self, "rolling_scale", _check("rolling_scale", self.rolling_scale,
                                                         *_chair("main_rolling_scale"), _W["rolling_scale"]))
        object.__setattr__(self, "camber_deg", _check("camber_deg", self.camber_deg, *_chair("camber_deg"),
                                                              _W["camber_deg"]))
        if self.camber_deg != 0.0 and self.y == 0.0:
            raise ValueError(f"camber_deg={self.camber_deg!r} is invalid for a wheel on the centre line (y = 0); "
                             "valid: 0")
        if self.camber_coefficient is not None:
            object.__setattr__(self, "camber_coefficient", _check("camber_coefficient", self.camber_coefficient,
                                                                  *_chair("camber_coefficient"),
                                                                  _W["camber_coefficient"]))
        k = _check("vertical_stiffness", self.vertical_stiffness, 0.0, 1e9, _W["vertical_stiffness"])
        if 0.0 < k < 1e3:
            raise ValueError(f"vertical_stiffness={k!r} is invalid; valid range: 0 (off the ground) or 1000 to 1e9 N/m")
        object.__setattr__(self, "vertical_stiffness", k)
        tires.get(self.tire)


@dataclass(frozen=True)
class Caster:
    """A swivelling caster.

    Parameters
    ----------
    x, y : float
        Pin relative to the c.g., m.
    trail : float
        Pin to contact, m (the contact trails behind the pin).
    l : float
        Pin to the caster's centre of mass, m.
    m_c : float
        Caster assembly mass, kg.
    i_zp : float
        Caster yaw inertia about its pin, kg m^2.
    tire : str
        Tire spec.
    pin_damping : float
        Viscous pin damping, N m s/rad (the linear model's pin law).
    pin_friction : float
        Coulomb pin friction, N m.
    lateral_scale : float
    vertical_stiffness : float
        N/m (0: off the ground, no load).
    rolling_scale : float
        Factor on the tire's rolling-resistance force (WCHAIR's CXMOD; 0, the default, switches it off).
    """

    x: float
    y: float
    trail: float = 0.05
    l: float = 0.035                                   # noqa: E741 (the thesis's l_1)
    m_c: float = 1.2
    i_zp: float = 0.02
    tire: str = "ER"
    pin_damping: float = 0.0
    pin_friction: float = 0.1
    lateral_scale: float = 1.0
    vertical_stiffness: float = 2.0e5
    rolling_scale: float = 0.0

    def __post_init__(self) -> None:
        # the short form's ranges where the quantity is the same (stability.chair.model.LIMITS): a valid chair
        # expands into a valid layout
        for name, lo, hi in (("x", -2.0, 2.0), ("y", -1.0, 1.0), ("trail", *_chair("trail")), ("l", *_chair("l1")),
                             ("m_c", *_chair("m_c")), ("i_zp", 0.0, LIMITS["i_zp"][1]),
                             ("pin_damping", *_chair("pin_damping")), ("pin_friction", *_chair("pin_friction_left")),
                             ("lateral_scale", 0.0, 10.0), ("vertical_stiffness", 0.0, 1e9),
                             ("rolling_scale", *_chair("caster_rolling_scale"))):
            object.__setattr__(self, name, _check(name, getattr(self, name), lo, hi, _C[name]))
        if 0.0 < self.vertical_stiffness < 1e3:
            raise ValueError(f"vertical_stiffness={self.vertical_stiffness!r} is invalid; valid range: 0 (off the "
                             "ground) or 1000 to 1e9 N/m")
        if self.i_zp < self.m_c * self.l ** 2:
            raise ValueError(f"i_zp={self.i_zp!r} is invalid; valid range: >= m_c l^2 = {self.m_c * self.l ** 2:.4g} "
                             "kg m^2 (the inertia about the pin includes the caster's mass at l)")
        tires.get(self.tire)

    @property
    def contact_x(self) -> float:
        """x of the contact with the caster trailing forward, m."""
        return self.x - self.trail

    @property
    def place(self) -> str:
        """Where the pin sits: ``"front"`` or ``"rear"`` of the c.g. (``x > 0``: front), then ``" left"``
        (``y < 0``), ``" right"`` (``y > 0``) or nothing on the centre line."""
        return ("front" if self.x > 0 else "rear") + (" left" if self.y < 0 else " right" if self.y > 0 else "")


@dataclass(frozen=True)
class Layout:
    """A chair as a body and its wheels.

    Parameters
    ----------
    name : str
    m : float
        Total mass with the user and every caster, kg.
    i_z : float
        Total yaw inertia about the c.g. with every caster trailing forward, kg m^2.
    h : float
        c.g. height, m.
    wheels : tuple of FixedWheel
    casters : tuple of Caster
    g : float
        Gravity, m/s^2.
    anti_tip : tuple of (float, float)
        Anti-tip devices' ground contacts when the chair has tipped onto them, ``(x, y)`` m (none by default): they
        carry no load on level ground and catch the chair when it tips their way.
    """

    name: str
    m: float
    i_z: float
    h: float
    wheels: tuple = field(default_factory=tuple)
    casters: tuple = field(default_factory=tuple)
    g: float = 9.81
    anti_tip: tuple = field(default_factory=tuple)

    def __post_init__(self) -> None:
        object.__setattr__(self, "m", _check("m", self.m, *_chair("m"), _L["m"]))
        object.__setattr__(self, "i_z", _check("i_z", self.i_z, *_chair("i_z"), _L["i_z"]))
        object.__setattr__(self, "h", _check("h", self.h, *_chair("h"), _L["h"]))
        object.__setattr__(self, "g", _check("g", self.g, *_chair("g"), _L["g"]))
        object.__setattr__(self, "wheels", tuple(self.wheels))
        object.__setattr__(self, "casters", tuple(self.casters))
        object.__setattr__(self, "anti_tip", tuple((_check("anti_tip x", float(x), -2.0, 2.0, "m"),
                                                    _check("anti_tip y", float(y), -1.0, 1.0, "m"))
                                                   for x, y in self.anti_tip))
        if not all(isinstance(w, FixedWheel) for w in self.wheels):
            raise TypeError("wheels: expected FixedWheel objects")
        if not all(isinstance(c, Caster) for c in self.casters):
            raise TypeError("casters: expected Caster objects")
        if len(self.wheels) + len(self.casters) < 3:
            raise ValueError(f"layout {self.name!r} has {len(self.wheels) + len(self.casters)} wheels; valid: at "
                             "least 3 (a chair stands on three or more)")
        if sum(c.m_c for c in self.casters) >= self.m:
            raise ValueError(f"layout {self.name!r}: the casters' mass is not less than the chair's m={self.m:g} kg")

    @property
    def caster_labels(self) -> tuple[str, ...]:
        """Each caster's label, ``"caster k (front left)"`` with ``k`` from 1 in ``casters`` order (unique: the
        number tells apart two casters at the same place)."""
        return tuple(f"caster {k + 1} ({c.place})" for k, c in enumerate(self.casters))

    @property
    def shape(self) -> tuple[int, int]:
        """``(fixed wheels, casters)``."""
        return len(self.wheels), len(self.casters)

    @classmethod
    def from_chair(cls, chair: Chair) -> Layout:
        """The short form (two main wheels and a caster pair) as a layout.

        Parameters
        ----------
        chair : Chair

        Returns
        -------
        Layout
            Main wheels at ``(x_main, -d1)``, ``(x_main, d2)``; caster pins at ``(x_pin, -t1)``,
            ``(x_pin, t2)`` with the chair's trail, ``l1``, ``m_c``, ``i_zp``, pins, tires and scales (lateral and
            rolling), the main wheels' camber and toe (``angle_deg`` ``-toe_deg`` left, ``+toe_deg`` right); anti-tip
            devices ``anti_tip_reach`` beyond the main wheels; vertical stiffnesses whose pairs' roll stiffnesses
            have the chair's ratio ``roll_k`` (the load transfer of the simulator,
            :func:`stability.layout.statics.load_rule`).
        """
        from stability.chair.power import drive_kind

        driven = drive_kind(chair) == "motor"
        # vertical stiffnesses whose roll stiffnesses k (2 y)^2 / 2 stand in the ratio roll_k = k_f / k_r (eq 6-28)
        k_w, k_c = _roll_pair(chair.roll_k, chair.d1 + chair.d2, chair.t1 + chair.t2)
        wheels = tuple(FixedWheel(chair.x_main, y, chair.main_tire, driven, chair.main_lateral_scale, k_w,
                                  chair.main_rolling_scale, chair.camber_deg, chair.camber_coefficient,
                                  side * chair.toe_deg)
                       for y, side in ((-chair.d1, -1.0), (chair.d2, 1.0)))
        casters = tuple(Caster(chair.x_pin, y, chair.trail, chair.l1, chair.m_c, chair.i_zp, chair.caster_tire,
                               chair.pin_damping, mf, chair.caster_lateral_scale, k_c, chair.caster_rolling_scale)
                        for y, mf in ((-chair.t1, chair.pin_friction_left), (chair.t2, chair.pin_friction_right)))
        anti: tuple = ()
        if chair.anti_tip_reach > 0:                     # beyond the main wheels, away from the casters
            x = chair.x_main + (1.0 if chair.x_main > chair.x_pin else -1.0) * chair.anti_tip_reach
            anti = ((x, -chair.d1), (x, chair.d2))
        return cls(chair.name, chair.m, chair.i_z, chair.h, wheels, casters, chair.g, anti)


def check_layout(layout: object, name: str = "layout") -> Layout:
    """Return ``layout`` if it is a :class:`Layout`, else raise :class:`TypeError` naming the argument.

    Parameters
    ----------
    layout : object
        The argument to check.
    name : str, optional
        Its name in the message (default ``"layout"``).

    Returns
    -------
    Layout
        ``layout`` itself.

    Raises
    ------
    TypeError
        Naming ``name``, the value and what is accepted.
    """
    if not isinstance(layout, Layout):
        raise TypeError(f"{name}={value_text(layout)} is invalid; valid values: a stability.layout.Layout "
                        "(stability.layout.presets.layout_preset(name), stability.layout.io.load_layout(path) or "
                        "Layout.from_chair(chair))")
    return layout


#: Decorator: the public function's first argument ``layout`` passes :func:`check_layout` before the body runs.
takes_layout = first_argument(check_layout)
