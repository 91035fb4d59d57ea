"""The :class:`Chair` dataclass: chair-plus-user parameters with units, plausibility limits and validation.

Symbols follow Figure 6-1 of Collins (1987) and program WCHAIR's variables
(Appendix C, BLOCK DATA).  Distances in m, masses in kg, inertias in kg m^2,
moments in N m, angles in degrees.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Any

from stability import tires
from stability.runtime.checks import first_argument, is_real, real_value, value_text

__all__ = ["Chair", "LIMITS", "valid_range", "field_names", "check_chair", "check_chairs", "takes_chair",
           "takes_chairs"]




def _doc(text: str, unit: str, symbol: str = "") -> dict[str, str]:
    return {"doc": text, "unit": unit, "symbol": symbol}


@dataclass(frozen=True)
class Chair:
    """A wheelchair with its user, as seen by the planar model of chapter 6.

    Every field is validated on construction; a physically meaningless value
    raises :class:`ValueError` naming the parameter, its value and the valid
    range.  Field metadata (``dataclasses.fields(Chair)[i].metadata``) carries
    the unit, the thesis symbol and a one-line description.

    Attributes
    ----------
    name : str
        Label used in reports and plot titles.
    caster_position : {"rear", "front"}
        Where the swivelling casters are.  The thesis's chair is "rear".
    d1, d2 : float
        Lateral offsets of the left and right main-wheel contacts from the
        centre of gravity (m; d1, d2).
    s1 : float
        Longitudinal distance from the centre of gravity to the main axle
        (m; s1).
    s2 : float
        Longitudinal distance from the centre of gravity to the caster pins
        (m; s2).
    trail : float
        Caster trail, pin to caster contact point (m; l).
    l1 : float
        Pin to caster-assembly centre of gravity (m; l1).
    t1, t2 : float
        Lateral offsets of the left and right caster pins (m; t1, t2).
    h : float
        Height of the centre of gravity (m; h).
    m : float
        Total mass of chair, user and both casters (kg; m).
    m_c : float
        Mass of one caster assembly (kg; m_c).
    i_z : float
        Total yaw inertia about the system centre of gravity with the casters
        trailing (kg m^2; I_z).
    i_zp : float
        Yaw inertia of one caster assembly about its pin (kg m^2; I_zp).
    pin_friction_left, pin_friction_right : float
        Coulomb friction moments at the left (A) and right (B) caster pins
        (N m; M_af, M_bf).
    pin_damping : float
        Viscous pin damping used by the linear models (N m s/rad); Coulomb
        friction has no linearisation.  Default 0.
    roll_k : float
        Roll coefficient k = k_f / k_r (eq 6-28): ratio of the roll stiffness
        at the main wheels (the thesis's "front") to that at the casters.
    camber_deg : float
        Camber of the main wheels, tops inward (deg).
    camber_coefficient : float or None
        Camber coefficient f_c of eq 4-2; ``None`` uses the main tire's value
        derived from the camber data (Figure 4-3).
    toe_deg : float
        Toe angle of the main wheels (deg).
    main_tire, caster_tire : str
        Tire names from :func:`stability.tires.names` or ``"linear:<N/deg>"``.
    main_lateral_scale, main_rolling_scale : float
        Scale factors on main-tire lateral and rolling forces (TYMOD, TXMOD).
    caster_lateral_scale, caster_rolling_scale : float
        Scale factors on caster lateral and rolling forces (CYMOD, CXMOD).
        The thesis's studies switch rolling resistance off (TXMOD = CXMOD = 0).
    g : float
        Gravitational acceleration (m/s^2).
    anti_tip_reach : float
        Anti-tip devices (tipping toward the main wheels): longitudinal distance of their ground
        contact beyond the main-wheel contacts, away from the c.g. (m); 0 means none.  Used only by
        :mod:`stability.tipping`.
    anti_tip_clearance : float
        Ground clearance of the anti-tip devices with the chair level (m).
    """

    name: str = field(default="chair", metadata=_doc("label", "-"))
    caster_position: str = field(default="rear", metadata=_doc("casters at the rear or front", "-"))
    d1: float = field(default=0.265, metadata=_doc("c.g. to left main-wheel contact, lateral", "m", "d1"))
    d2: float = field(default=0.265, metadata=_doc("c.g. to right main-wheel contact, lateral", "m", "d2"))
    s1: float = field(default=0.345, metadata=_doc("c.g. to main axle, longitudinal", "m", "s1"))
    s2: float = field(default=0.175, metadata=_doc("c.g. to caster pins, longitudinal", "m", "s2"))
    trail: float = field(default=0.08, metadata=_doc("caster trail, pin to contact", "m", "l"))
    l1: float = field(default=0.058, metadata=_doc("pin to caster c.g.", "m", "l1"))
    t1: float = field(default=0.24, metadata=_doc("c.g. to left caster pin, lateral", "m", "t1"))
    t2: float = field(default=0.24, metadata=_doc("c.g. to right caster pin, lateral", "m", "t2"))
    h: float = field(default=0.61, metadata=_doc("c.g. height", "m", "h"))
    m: float = field(default=95.0, metadata=_doc("total mass incl. user and casters", "kg", "m"))
    m_c: float = field(default=1.2, metadata=_doc("one caster assembly mass", "kg", "m_c"))
    i_z: float = field(default=5.6, metadata=_doc("total yaw inertia about c.g.", "kg m^2", "I_z"))
    i_zp: float = field(default=0.02, metadata=_doc("caster yaw inertia about its pin", "kg m^2", "I_zp"))
    pin_friction_left: float = field(default=0.1, metadata=_doc("Coulomb pin friction, left caster", "N m", "M_af"))
    pin_friction_right: float = field(default=0.1, metadata=_doc("Coulomb pin friction, right caster", "N m", "M_bf"))
    pin_damping: float = field(default=0.0, metadata=_doc("viscous pin damping (linear models)", "N m s/rad"))
    roll_k: float = field(default=1.0, metadata=_doc("roll coefficient k_f/k_r", "-", "k"))
    camber_deg: float = field(default=0.0, metadata=_doc("main-wheel camber", "deg", "gamma"))
    camber_coefficient: float | None = field(default=None,
                                             metadata=_doc("camber coefficient (None: tire's)", "-", "f_c"))
    toe_deg: float = field(default=0.0, metadata=_doc("main-wheel toe", "deg"))
    main_tire: str = field(default="EJA", metadata=_doc("main tire", "-"))
    caster_tire: str = field(default="ER", metadata=_doc("caster tire", "-"))
    main_lateral_scale: float = field(default=1.0, metadata=_doc("main lateral force scale", "-", "TYMOD"))
    main_rolling_scale: float = field(default=0.0, metadata=_doc("main rolling force scale", "-", "TXMOD"))
    caster_lateral_scale: float = field(default=1.0, metadata=_doc("caster lateral force scale", "-", "CYMOD"))
    caster_rolling_scale: float = field(default=0.0, metadata=_doc("caster rolling force scale", "-", "CXMOD"))
    g: float = field(default=9.81, metadata=_doc("gravitational acceleration", "m/s^2", "g"))
    anti_tip_reach: float = field(default=0.0, metadata=_doc(
        "anti-tip contact beyond the main wheels (0: none)", "m"))
    anti_tip_clearance: float = field(default=0.0, metadata=_doc("anti-tip ground clearance", "m"))

    def __post_init__(self) -> None:
        _validate(self)

    # -- geometry -------------------------------------------------------
    @property
    def x_main(self) -> float:
        """Signed x coordinate of the main axle relative to the c.g. (m)."""
        return self.s1 if self.caster_position == "rear" else -self.s1

    @property
    def x_pin(self) -> float:
        """Signed x coordinate of the caster pins relative to the c.g. (m)."""
        return -self.s2 if self.caster_position == "rear" else self.s2

    @property
    def caster_contact_distance(self) -> float:
        """Distance from the c.g. to the caster contact points with the casters trailing (m).

        ``s2 + l`` for rear casters (the contacts trail behind the pins, away
        from the c.g.), ``s2 - l`` for front casters (they trail back towards
        the c.g.).
        """
        return self.s2 + self.trail if self.caster_position == "rear" else self.s2 - self.trail

    @property
    def wheelbase(self) -> float:
        """Main axle to caster contact points with the casters trailing (m)."""
        return self.s1 + self.caster_contact_distance

    @property
    def cg_ratio(self) -> float:
        """Centre-of-gravity ratio s1/(s1 + s2) of eq 8-6."""
        return self.s1 / (self.s1 + self.s2)

    def replace(self, **changes: Any) -> Chair:
        """A copy with ``changes`` applied (validated).

        Unless ``name`` is among the changes, a copy that differs from this
        chair is named after it with the changed fields, e.g.
        ``"ej-premier (modified: trail=0.05)"``, so that plots and JSON of a
        modified chair never carry the original's name alone.

        Parameters
        ----------
        **changes
            Field names and their new values.

        Returns
        -------
        Chair
        """
        unknown = set(changes) - {f.name for f in fields(self)}
        if unknown:
            raise ValueError(
                f"unknown chair parameter(s) {sorted(unknown)}; valid names: {field_names()}"
            )
        if "name" not in changes:
            changed = {k: v for k, v in changes.items() if getattr(self, k) != v}
            if changed:
                changes = {**changes, "name": _modified_name(self.name, changed)}
        return dataclasses.replace(self, **changes)

    def main_tire_model(self):
        """The main tire, scaled by TYMOD/TXMOD (:class:`stability.tires.Tire`)."""
        return tires.get(self.main_tire).scaled(
            lateral=self.main_lateral_scale, rolling=self.main_rolling_scale
        )

    def caster_tire_model(self):
        """The caster tire, scaled by CYMOD/CXMOD (:class:`stability.tires.Tire`)."""
        return tires.get(self.caster_tire).scaled(
            lateral=self.caster_lateral_scale, rolling=self.caster_rolling_scale
        )


# ---------------------------------------------------------------------------
# validation
# ---------------------------------------------------------------------------
#: Plausible range of every numeric field, ``(low, high, low_inclusive)`` in the field's unit.
#: Physical bounds, wide enough for any real wheelchair and user (a child's manual chair to a
#: bariatric power chair; g from the Moon's 1.62 to Jupiter's 24.8 m/s^2) and narrow enough that
#: a typo (1e6 m, 1e-300 kg) is refused with a sentence instead of producing nonsense.
LIMITS: dict[str, tuple[float, float, bool]] = {
    "d1": (0.05, 1.0, True), "d2": (0.05, 1.0, True),
    "s1": (0.0, 1.5, False), "s2": (0.0, 1.5, False),
    "trail": (0.0, 0.5, True), "l1": (0.0, 0.5, True),
    "t1": (0.05, 1.0, True), "t2": (0.05, 1.0, True),
    "h": (0.0, 2.0, True),
    "m": (5.0, 1000.0, True), "m_c": (0.0, 50.0, True),
    # i_zp >= 1e-6: with no swivel inertia the caster's swivel equation has none and the mass matrix is
    # singular.  The limit is regular (the swivel mode runs off to -infinity, the caster trails its contact
    # point): rates at 1e-6 equal the limit within 1e-4 relative (tests/test_cli_catalogue.py; closed form
    # stability.linear.massless_caster_rate), so the bound answers the massless-caster question; the
    # smallest real caster (a 50 mm wheel) has about 1e-4.
    "i_z": (0.01, 500.0, True), "i_zp": (1e-6, 5.0, True),
    "pin_friction_left": (0.0, 50.0, True), "pin_friction_right": (0.0, 50.0, True),
    "pin_damping": (0.0, 100.0, True),
    "roll_k": (0.001, 1000.0, True),
    "camber_deg": (-45.0, 45.0, False), "toe_deg": (-45.0, 45.0, False),
    "camber_coefficient": (0.0, 1.0, True),
    "main_lateral_scale": (0.01, 10.0, True), "caster_lateral_scale": (0.01, 10.0, True),
    "main_rolling_scale": (0.0, 10.0, True), "caster_rolling_scale": (0.0, 10.0, True),
    "g": (1.0, 30.0, True),
    "anti_tip_reach": (0.0, 1.0, True), "anti_tip_clearance": (0.0, 0.5, True),
}


def valid_range(name: str) -> str:
    """The valid range of a numeric chair field in words, with its unit.

    Parameters
    ----------
    name : str
        A key of :data:`LIMITS`.

    Returns
    -------
    str
        E.g. ``"5 to 1000 kg"`` or ``"0 < value < 1.5 m"``.
    """
    lo, hi, inclusive = LIMITS[name]
    unit = _FIELDS[name].metadata["unit"]
    unit = "" if unit == "-" else f" {unit}"
    return f"{lo:g} to {hi:g}{unit}" if inclusive else f"{lo:g} < value < {hi:g}{unit}"


_FIELDS = {f.name: f for f in fields(Chair)}
_MODIFIED = " (modified: "


def _modified_name(name: str, changed: Mapping[str, Any]) -> str:
    """``name`` with the changed fields listed (merged with an earlier list; at most three shown)."""
    root, _, rest = name.partition(_MODIFIED)
    items: dict[str, str] = {}
    if rest.endswith(")"):
        for part in rest[:-1].split(", "):
            key, eq, value = part.partition("=")
            if eq:
                items[key] = value
    for key, value in changed.items():
        items[key] = f"{value:.4g}" if isinstance(value, float) else str(value)
    shown = [f"{k}={v}" for k, v in items.items()]
    text = ", ".join(shown[:3]) + (f", +{len(shown) - 3} more" if len(shown) > 3 else "")
    return f"{root}{_MODIFIED}{text})"


def field_names() -> list[str]:
    """Names of all :class:`Chair` fields.

    Returns
    -------
    list of str
        In declaration order.
    """
    return [f.name for f in fields(Chair)]


def _bad(name: str, value: Any, valid: str) -> ValueError:
    return ValueError(f"chair parameter {name}={value_text(value)} is invalid; valid range: {valid}")


def check_chair(chair: Any, name: str = "chair") -> Chair:
    """Return ``chair`` if it is a :class:`Chair`, else raise :class:`TypeError` naming the argument.

    The public functions take a Chair, not a preset name or a file: ``stability.preset(name)`` and
    ``stability.load_chair(spec)`` make one.

    Parameters
    ----------
    chair : Any
        The argument to check.
    name : str, optional
        Its name in the message (default ``"chair"``).

    Returns
    -------
    Chair
        ``chair`` itself.

    Raises
    ------
    TypeError
        Naming ``name``, the value and what is accepted.
    """
    if not isinstance(chair, Chair):
        hint = (f" (a preset name: use stability.preset({chair!r}) or stability.load_chair({chair!r}))"
                if isinstance(chair, str) and len(chair) <= 200 else "")
        raise TypeError(f"{name}={value_text(chair)} is invalid; valid values: a stability.Chair, made by "
                        f"stability.preset(name), stability.load_chair(spec) or stability.Chair(...){hint}")
    return chair


def check_chairs(chairs: Any, name: str = "chairs") -> Any:
    """Return ``chairs`` if it is a Chair or a sequence of Chairs, else raise :class:`TypeError` naming it.

    Parameters
    ----------
    chairs : Any
        The argument to check: a :class:`Chair`, or a list, tuple or array of them.
    name : str, optional
        Its name in the message (default ``"chairs"``); an element is named ``chairs[i]`` after it.

    Returns
    -------
    Chair or sequence of Chair
        ``chairs`` itself.

    Raises
    ------
    TypeError
        Naming ``name`` (or its first wrong element), the value and what is accepted.
    """
    if isinstance(chairs, Chair):
        return chairs
    if isinstance(chairs, (str, bytes)) or not isinstance(chairs, Sequence) and not hasattr(chairs, "__array__"):
        raise TypeError(f"{name}={value_text(chairs)} is invalid; valid values: a stability.Chair or a sequence of "
                        "them (stability.preset(name), stability.load_chair(spec))")
    for i, chair in enumerate(chairs):
        check_chair(chair, f"{name}[{i}]")
    return chairs


#: Decorator: the public function's first argument ``chair`` passes :func:`check_chair` before the body runs.
takes_chair = first_argument(check_chair)
#: Decorator: the first argument (``chairs``, or ``chair`` where one chair or several are taken) passes
#: :func:`check_chairs` before the body runs.
takes_chairs = first_argument(check_chairs)


def _check_types(c: Chair) -> None:
    bad = _bad
    for f in fields(c):
        value = getattr(c, f.name)
        if f.name in ("name", "caster_position", "main_tire", "caster_tire"):
            if not isinstance(value, str):
                raise bad(f.name, value, "a string")
            continue
        if f.name == "camber_coefficient" and value is None:
            continue
        if not is_real(value):
            raise bad(f.name, value, "a real number" + (f", {valid_range(f.name)}" if f.name in LIMITS else ""))
        if not math.isfinite(real_value(value)):             # NaN, inf, or an integer beyond the float range
            raise bad(f.name, value, "a finite number" + (f", {valid_range(f.name)}" if f.name in LIMITS else ""))
        if type(value) not in (int, float):        # numpy scalars (np.float32(95), np.int64(2)) as Python floats
            object.__setattr__(c, f.name, float(value))


def _check_limits(c: Chair) -> None:
    bad = _bad
    if c.caster_position not in ("rear", "front"):
        raise bad("caster_position", c.caster_position, "'rear' or 'front'")
    for name, (lo, hi, inclusive) in LIMITS.items():
        value = getattr(c, name)
        if value is None:
            continue
        ok = (lo <= value <= hi) if inclusive else (lo < value < hi)
        if not ok:
            extra = ", or None for the tire's own" if name == "camber_coefficient" else ""
            if name == "i_zp" and value < lo:
                extra = (" (a caster with no swivel inertia about its pin makes the model singular; its "
                         f"massless-caster limit is reached at i_zp = {lo:g}, whatever m_c; closed form: "
                         "stability.linear.massless_caster_rate)")
            raise bad(name, value, valid_range(name) + extra)


def _validate(c: Chair) -> None:
    bad = _bad
    _check_types(c)
    _check_limits(c)
    if c.m_c * 2 >= c.m:
        raise bad("m_c", c.m_c, f"0 <= m_c < m/2 = {c.m / 2:g} kg")
    if c.l1 > c.trail + 0.5:
        raise bad("l1", c.l1, "<= trail + 0.5 m")
    if c.i_zp < c.m_c * c.l1**2 * (1 - 1e-12):
        raise bad(
            "i_zp", c.i_zp,
            f">= m_c*l1^2 = {c.m_c * c.l1**2:.6g} kg m^2 (a caster's inertia about its pin "
            "cannot be less than that of its mass concentrated at its c.g.)",
        )
    # the caster contact points must lie beyond the main axle (positive wheelbase)
    if c.caster_position == "front" and c.trail >= c.s1 + c.s2:
        raise bad("trail", c.trail, f"< s1 + s2 = {c.s1 + c.s2:g} m (zero or negative wheelbase)")
    if c.trail > 0.5:
        raise bad("trail", c.trail, "0 to 0.5 m (a longer trail leaves no wheelbase to speak of)")
    for name in ("main_tire", "caster_tire"):
        try:
            tires.get(getattr(c, name))
        except (KeyError, ValueError) as exc:
            spec = getattr(c, name)
            if spec.strip().lower().startswith(("file:", "linear:")):   # the loader's own, precise message
                raise ValueError(f"chair parameter {name}={spec!r}: {str(exc).strip(chr(39))}") from None
            raise bad(name, getattr(c, name),
                      f"one of {list(tires.names())}, a registered name, 'linear:<N/deg>' or 'file:<csv>'") from exc
    tires.check_chair_tires(c)
