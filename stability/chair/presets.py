"""Built-in chairs: the thesis's E&J Premier, its front-caster counterpart, the chapter 9 revised design,
a front-wheel-drive power chair and a typical manual front-caster chair."""

from __future__ import annotations

from typing import Any

from stability.chair.model import Chair
from stability.runtime.checks import value_text

__all__ = ["POWER_FWD_FIELDS", "preset_names", "preset", "all_preset_names"]


def _presets() -> dict[str, dict[str, Any]]:
    # Everest & Jennings Premier, chapter 8 defaults and WCHAIR BLOCK DATA:
    # D1=D2=.265, S1=.345, S2=.175, L1=.058, L=.08, T1=T2=.24, H=.61,
    # IZ=5.6, IZP=.02, M=95, MC=1.2, GR=9.81, MAF=MBF=.1, ROLLK=1,
    # TXMOD=CXMOD=0, TYMOD=CYMOD=1; EJA main tires (chapter 8), ER casters
    # (CASY holds the ER coefficients).
    ej = dict(name="ej-premier")
    # Front-caster equivalent of chapter 8 ("Method one"): s1 and s2
    # exchanged, s1 = .175 m (c.g. to the main axle, now behind the c.g.),
    # s2 = .345 m (c.g. to the caster pins, now ahead of it).
    front = dict(name="ej-premier-front-caster", caster_position="front", s1=0.175, s2=0.345)
    # Chapter 9 revised design (Figure 9-1): trail 8 -> 6 cm, main axle moved
    # back so s1 = .345 -> .245 m, pins extended 5 cm behind the chair so
    # s1 + s2 drops by only 5 cm: s2 = .175 + .05 = .225 m.
    revised = dict(name="revised", s1=0.245, s2=0.225, trail=0.06)
    return {"ej-premier": ej, "ej-premier-front-caster": front, "revised": revised,
            "power-fwd": dict(POWER_FWD_FIELDS),
            # Typical manual front-caster chair of the cross-slope treadmill study (Richter et
            # al. 2007): 75 kg user + 13 kg lightweight chair, 24-inch pneumatic rear wheels,
            # 5-inch polyurethane casters, c.g. 7 cm ahead of the rear axle (~80 % rear load).
            # Every value and its source: docs/slopes.md.
            "manual-front-caster": dict(
                name="manual-front-caster", caster_position="front", d1=0.28, d2=0.28, s1=0.07,
                s2=0.36, trail=0.045, l1=0.03, t1=0.21, t2=0.21, h=0.65, m=88.0, m_c=0.5, i_z=5.2,
                i_zp=0.002, pin_friction_left=0.03, pin_friction_right=0.03, main_tire="EJP",
                caster_tire="PU")}


#: Field values of the ``power-fwd`` preset: a front-wheel-drive power chair
#: with rear casters and a 100 kg user; each value is argued in
#: ``docs/power-chair.md`` (lumped estimate in :mod:`stability.chair.power`).
POWER_FWD_FIELDS: dict[str, Any] = dict(
    name="power-fwd",
    caster_position="rear",
    d1=0.275, d2=0.275,
    s1=0.18, s2=0.32,
    trail=0.05, l1=0.035,
    t1=0.22, t2=0.22,
    h=0.49,
    m=215.0, m_c=1.6,
    i_z=13.0, i_zp=0.006,
    pin_friction_left=0.15, pin_friction_right=0.15,
    pin_damping=0.0,
    roll_k=1.0,
    camber_deg=0.0, toe_deg=0.0,
    main_tire="linear:110",
    caster_tire="ER",
    main_lateral_scale=1.0, main_rolling_scale=0.0,
    caster_lateral_scale=1.0, caster_rolling_scale=0.0,
    g=9.81,
)


def preset_names() -> tuple[str, ...]:
    """Names of the built-in chairs.

    Returns
    -------
    tuple of str
        Preset names accepted by :func:`preset` and ``--chair``, in table order.
    """
    return tuple(_presets())


def preset(name: str) -> Chair:
    """Return a built-in chair.

    Parameters
    ----------
    name : str
        One of :func:`preset_names`: ``"ej-premier"`` (the thesis's Everest &
        Jennings rear-caster chair, chapter 8 defaults), ``"ej-premier-front-caster"``
        (its front-caster equivalent, chapter 8) or ``"revised"`` (chapter 9).

    Returns
    -------
    Chair
        The preset's parameters (SI units, see :class:`Chair`).

    Raises
    ------
    ValueError
        If ``name`` is not a preset; the message lists the valid names.
    TypeError
        If ``name`` is not a string (the message names it and lists the valid names).
    """
    table = _presets()
    if not isinstance(name, str):
        raise TypeError(f"name={value_text(name)} is invalid; valid values: a preset name, one of {list(table)}")
    if name in table:
        return Chair(**table[name])
    raise ValueError(f"unknown chair preset {value_text(name)}; valid presets: {list(table)}")


def all_preset_names() -> tuple[str, ...]:
    """Names of all presets (kept for compatibility; same as :func:`preset_names`).

    Returns
    -------
    tuple of str
    """
    return preset_names()
