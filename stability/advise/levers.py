"""The design levers the advisor weighs, and the single changes each offers over its feasible range.

Each change is a mapping of chair fields to new values, usable as ``--set NAME=VALUE``
assignments; a value the chair refuses (outside ``chair.LIMITS``, c.g. outside the wheels) is
left out with its reason.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.models.statics import check_static_loads
from stability.tires import CASTER_TIRES

__all__ = ["Change", "LEVERS", "lever_changes", "apply"]


@dataclass(frozen=True)
class Change:
    """One design change.

    Attributes
    ----------
    lever : str
        The lever's name (a key of :data:`LEVERS`).
    label : str
        The change in words (``"trail 8 -> 6 cm"``).
    fields : tuple of (str, float or str)
        Chair field and new value, in ``--set`` order.
    """

    lever: str
    label: str
    fields: tuple

    @property
    def assignments(self) -> list[str]:
        """``["trail=0.06", ...]``: the change as ``--set`` assignments."""
        return [f"{k}={v!r}" if isinstance(v, float) else f"{k}={v}" for k, v in self.fields]

    def to_mapping(self) -> dict:
        """Chair field -> new value."""
        return dict(self.fields)


def apply(chair: Chair, fields) -> Chair:
    """``chair`` with the changed fields (validated, c.g. inside the wheels).

    Parameters
    ----------
    chair : Chair
    fields : iterable of (str, value)

    Returns
    -------
    Chair
    """
    c = chair.replace(**dict(fields))
    check_static_loads(c)
    return c


def _r(x: float) -> float:
    return round(float(x), 6)


def _trail(c: Chair) -> list[Change]:
    out = []
    for d in (-0.03, -0.02, -0.01, 0.01):
        t = _r(c.trail + d)
        if t > 0:
            out.append(Change("trail", f"trail {c.trail * 100:g} -> {t * 100:g} cm", (("trail", t),)))
    return out


def _s1_fixed_sum(c: Chair) -> list[Change]:
    return [Change("s1_fixed_wheelbase", f"axle {abs(d) * 100:g} cm {'toward' if d < 0 else 'away from'} the c.g. "
                   f"at fixed s1+s2 (s1 {c.s1 * 100:.1f} -> {(c.s1 + d) * 100:.1f} cm)",
                   (("s1", _r(c.s1 + d)), ("s2", _r(c.s2 - d)))) for d in (-0.10, -0.05, 0.05)]


def _s1_fixed_s2(c: Chair) -> list[Change]:
    return [Change("s1_fixed_s2", f"axle {abs(d) * 100:g} cm {'toward' if d < 0 else 'away from'} the c.g. at fixed s2 "
                   f"(s1 {c.s1 * 100:.1f} -> {(c.s1 + d) * 100:.1f} cm)", (("s1", _r(c.s1 + d)),))
            for d in (-0.05, 0.05)]


def _wheelbase(c: Chair) -> list[Change]:
    return [Change("wheelbase", f"wheelbase x{k:g} at a fixed c.g. ratio (s1 {c.s1 * 100:.1f} -> {c.s1 * k * 100:.1f}, "
                   f"s2 {c.s2 * 100:.1f} -> {c.s2 * k * 100:.1f} cm)", (("s1", _r(c.s1 * k)), ("s2", _r(c.s2 * k))))
            for k in (0.9, 1.1)]


def _friction(c: Chair) -> list[Change]:
    base = max(c.pin_friction_left, c.pin_friction_right)
    out: list[Change] = []
    for f in (1.5 * base, 2.0 * base, 0.3):
        f = _r(f)
        if f > base + 1e-9 and all(abs(f - x.fields[0][1]) > 1e-9 for x in out):
            out.append(Change("pin_friction", f"pin friction {base:.3g} -> {f:.3g} N m (both pins)",
                              (("pin_friction_left", f), ("pin_friction_right", f))))
    return out


def _caster_tire(c: Chair) -> list[Change]:
    return [Change("caster_tire", f"caster tire {c.caster_tire} -> {t}", (("caster_tire", t),))
            for t in CASTER_TIRES if t != c.caster_tire]


def _caster_mass(c: Chair) -> list[Change]:
    out: list[Change] = []
    for k in (0.5, 0.75):
        m_c = _r(c.m_c * k)
        out.append(Change("caster_mass", f"caster mass {c.m_c:g} -> {m_c:g} kg (inertia x{k:g}, total mass "
                          f"{c.m:g} -> {c.m - 2 * (c.m_c - m_c):g} kg)",
                          (("m_c", m_c), ("i_zp", _r(c.i_zp * k)), ("m", _r(c.m - 2 * (c.m_c - m_c))))))
    return out


#: Lever name -> (description, change generator).
LEVERS: dict[str, tuple[str, Callable[[Chair], list[Change]]]] = {
    "trail": ("caster trail", _trail),
    "s1_fixed_wheelbase": ("axle position s1 at fixed s1+s2 (moves the c.g. ratio)", _s1_fixed_sum),
    "s1_fixed_s2": ("axle position s1 at fixed s2 (changes the wheelbase)", _s1_fixed_s2),
    "wheelbase": ("wheelbase at a fixed c.g. ratio", _wheelbase),
    "pin_friction": ("caster pin friction", _friction),
    "caster_tire": ("caster tire", _caster_tire),
    "caster_mass": ("caster mass", _caster_mass),
}


@takes_chair
def lever_changes(chair: Chair) -> tuple[list[tuple[Change, Chair]], list[tuple[Change, str]]]:
    """Every single change of every lever: the feasible ones with their chairs, the others with why not.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    tuple
        ``([(change, changed chair), ...], [(change, reason), ...])``.
    """
    ok, refused = [], []
    for _, gen in LEVERS.values():
        for ch in gen(chair):
            try:
                ok.append((ch, apply(chair, ch.fields)))
            except ValueError as exc:
                refused.append((ch, str(exc)))
    return ok, refused
