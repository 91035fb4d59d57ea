"""Design parameters a root locus or a parametric study can vary (chapter 8 of Collins 1987).

Each :class:`Parameter` knows its label, unit, how to apply a value to a chair
(:meth:`stability.chair.Chair.replace`), the chair's own value and a default span.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from stability import tires
from stability.chair import Chair

__all__ = ["Parameter", "DESIGN_PARAMETERS", "LOCUS_PARAMETERS", "parameter_names", "get_parameter", "main_tires"]


@dataclass(frozen=True)
class Parameter:
    """A design parameter a root locus or a parametric study can vary.

    Attributes
    ----------
    name : str
        Key (``"cg_ratio"``, ``"trail"``, ...).
    label : str
        Axis label, with the thesis symbol.
    unit : str
        Unit of the values (``"-"`` for ratios and factors).
    apply : callable
        ``apply(chair, value) -> Chair``: the chair with the parameter set.
    current : callable
        ``current(chair) -> float``: the chair's own value.
    span : callable
        ``span(chair) -> (low, high)``: default range of a locus.
    how : str
        How the parameter is varied, and the thesis figure it follows.
    categorical : bool
        True for parameters with named values (the main tire).
    """

    name: str
    label: str
    unit: str
    apply: Callable[[Chair, float], Chair]
    current: Callable[[Chair], float]
    span: Callable[[Chair], tuple]
    how: str
    categorical: bool = False

    def axis_label(self) -> str:
        return f"{self.label} ({self.unit})" if not self.categorical else self.label


def _cg_ratio(c: Chair, r: float) -> Chair:
    total = c.s1 + c.s2
    if not 0 < r < 1:
        raise ValueError(f"cg_ratio={r!r} is invalid; valid range: 0 < s1/(s1+s2) < 1")
    return c.replace(s1=r * total, s2=total - r * total)


#: Default span of the c.g. ratio (Figure 8-9), narrowed per chair by :func:`_cg_ratio_span`.
CG_RATIO_SPAN = (0.30, 0.90)
#: Smallest share of the weight each axle keeps at the ends of the c.g.-ratio span.
CG_RATIO_MIN_AXLE_SHARE = 0.02


def _cg_ratio_span(c: Chair) -> tuple[float, float]:
    """The c.g.-ratio span of a locus, kept within chairs whose static loads are positive.

    With the casters trailing, the caster contacts lie ``trail`` behind the pins, so
    the contact line is ``s2 + trail`` behind the c.g. for rear casters and
    ``s2 - trail`` ahead of it for front casters (eq 6-24); the main axle is
    ``s1`` away on the other side.  Moment balance about the c.g. gives the
    castered axle's share of the weight ``s1 / (s1 + s2 +- trail)`` (eq 6-25 with
    no tire forces), positive only while the c.g. lies between the axles:
    ``s1 > 0`` and ``s2 -+ trail > 0``.  With ``T = s1 + s2`` and ``r = s1/T`` the
    span :data:`CG_RATIO_SPAN` is cut where either axle's share falls to
    :data:`CG_RATIO_MIN_AXLE_SHARE` (a front-caster chair with a long trail: the
    casters would leave the ground before ``r = 1 - trail/T``).

    Parameters
    ----------
    c : Chair
        The chair (its ``s1 + s2``, ``trail`` and caster position are used).

    Returns
    -------
    tuple of float
        ``(low, high)`` c.g. ratios (-), inside :data:`CG_RATIO_SPAN`.
    """
    total = c.s1 + c.s2
    sign = 1.0 if c.caster_position == "rear" else -1.0
    q = CG_RATIO_MIN_AXLE_SHARE
    # castered-axle share r T / B >= q and main-axle share ((1 - r) T + sign trail) / B >= q, B = T + sign trail
    base = total + sign * c.trail
    lo = max(CG_RATIO_SPAN[0], q * base / total)
    hi = min(CG_RATIO_SPAN[1], (1.0 - q) * base / total)
    if not lo < hi:
        raise ValueError(f"chair {c.name!r}: no c.g. ratio gives positive static loads with trail = {c.trail:g} m "
                         f"and s1 + s2 = {total:g} m (valid: trail < s1 + s2 for front casters)")
    return lo, hi


def _wheelbase_span(c: Chair) -> tuple[float, float]:
    """The ``s1 + s2`` span of a locus (s2 varied), kept within chairs whose static loads are positive.

    Front casters: the contact line lies ``s2 - trail`` ahead of the c.g., and the main axle's share of
    the weight ``(s2 - trail) / (s1 + s2 - trail)`` must stay >= :data:`CG_RATIO_MIN_AXLE_SHARE` = q,
    i.e. ``s2 >= trail + q s1 / (1 - q)``.  Rear casters are not limited (the contacts trail away).

    Parameters
    ----------
    c : Chair

    Returns
    -------
    tuple of float
        ``(low, high)``, m.
    """
    lo = max(c.s1 + 0.02, 0.25)
    if c.caster_position == "front":
        q = CG_RATIO_MIN_AXLE_SHARE
        lo = max(lo, c.s1 + c.trail + q * c.s1 / (1.0 - q))
    return lo, max(lo, 0.85)


def _wheelbase(c: Chair, total: float) -> Chair:
    if total <= c.s1:
        raise ValueError(f"s1_plus_s2={total!r} is invalid; valid range: > s1 = {c.s1:g} m")
    return c.replace(s2=total - c.s1)


def _caster_mass_factor(c: Chair, f: float) -> Chair:
    return c.replace(m_c=c.m_c * f, i_zp=c.i_zp * f)


def _mass_factor(c: Chair, f: float) -> Chair:
    return c.replace(m=c.m * f, i_z=c.i_z * f)


def main_tires() -> tuple[str, ...]:
    """Names of the main tires a categorical tire locus steps through (thesis order).

    Returns
    -------
    tuple of str
        ``stability.tires.MAIN_TIRES`` if defined (Table 3-1 main wheels, Figure 8-15),
        else every tire in :func:`stability.tires.names`.
    """
    names = getattr(tires, "MAIN_TIRES", None)
    return tuple(names) if names else tuple(tires.names())


def _tire_index(c: Chair) -> float:
    names = main_tires()
    return float(names.index(c.main_tire)) if c.main_tire in names else float("nan")


def _apply_tire(c: Chair, v: float) -> Chair:
    return c.replace(main_tire=main_tires()[int(round(v))])


def _pin_friction(c: Chair, v: float) -> Chair:
    return c.replace(pin_friction_left=v, pin_friction_right=v)


def _pin_friction_factor(c: Chair, f: float) -> Chair:
    return c.replace(pin_friction_left=c.pin_friction_left * f, pin_friction_right=c.pin_friction_right * f)


def _width_factor(c: Chair, f: float) -> Chair:
    return c.replace(d1=c.d1 * f, d2=c.d2 * f, t1=c.t1 * f, t2=c.t2 * f)


DESIGN_PARAMETERS: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter("cg_ratio", "c.g. ratio s1/(s1+s2)", "-", _cg_ratio, lambda c: c.cg_ratio,
                  _cg_ratio_span, "s1 and s2 varied at constant s1 + s2 (eq 8-6, Figure 8-9)"),
        Parameter("s1_plus_s2", "main axle to caster pins s1+s2", "m", _wheelbase, lambda c: c.s1 + c.s2,
                  _wheelbase_span, "s2 varied at constant s1 (Figure 8-10)"),
        Parameter("s1", "c.g. to main axle s1", "m", lambda c, v: c.replace(s1=v), lambda c: c.s1,
                  lambda c: (0.10, 0.45), "main axle moved, caster pins fixed relative to the c.g. (chapter 9)"),
        Parameter("trail", "caster trail l", "m", lambda c, v: c.replace(trail=v), lambda c: c.trail,
                  lambda c: (0.02, 0.12), "trail varied at constant l1 (Figure 8-11)"),
        Parameter("caster_mass_factor", "caster mass and inertia factor", "-", _caster_mass_factor,
                  lambda c: 1.0, lambda c: (0.25, 3.5),
                  "m_c and I_zp multiplied by the same factor, total m and I_z fixed (Figure 8-12)"),
        Parameter("pin_damping", "viscous pin damping", "N m s/rad", lambda c, v: c.replace(pin_damping=v),
                  lambda c: c.pin_damping, lambda c: (0.0, 1.0),
                  "linear stand-in for pin friction (Coulomb friction has no linearisation)"),
        Parameter("pin_friction", "Coulomb pin friction M_f", "N m", _pin_friction,
                  lambda c: 0.5 * (c.pin_friction_left + c.pin_friction_right), lambda c: (0.0, 0.3),
                  "both pins (M_af = M_bf, Figure 8-13); nonlinear simulation only"),
        Parameter("mass_factor", "total mass and inertia factor", "-", _mass_factor, lambda c: 1.0,
                  lambda c: (0.6, 1.4), "m and I_z multiplied by the same factor (Figure 8-14)"),
        Parameter("main_lateral_scale", "main-tire cornering stiffness scale", "-",
                  lambda c, v: c.replace(main_lateral_scale=v), lambda c: c.main_lateral_scale,
                  lambda c: (0.5, 1.6), "main-tire cornering stiffness scaled (a continuous tire change)"),
        Parameter("main_tire", "main tire", "-", _apply_tire, _tire_index,
                  lambda c: (0, len(main_tires()) - 1), "main tire type (Figure 8-15)", categorical=True),
        Parameter("width_factor", "track width factor (d1, d2, t1, t2)", "-", _width_factor, lambda c: 1.0,
                  lambda c: (0.7, 1.3), "all four lateral offsets scaled together (chapter 8, other dimensions)"),
        Parameter("h", "c.g. height h", "m", lambda c, v: c.replace(h=v), lambda c: c.h,
                  lambda c: (0.4, 0.8), "c.g. height (chapter 8, other dimensions)"),
        Parameter("camber_deg", "main-wheel camber", "deg", lambda c, v: c.replace(camber_deg=v),
                  lambda c: c.camber_deg, lambda c: (0.0, 8.0), "both main wheels cambered inward (chapter 8)"),
        Parameter("roll_k", "roll coefficient k", "-", lambda c, v: c.replace(roll_k=v), lambda c: c.roll_k,
                  lambda c: (0.5, 2.0), "roll stiffness ratio k_f/k_r (chapter 8)"),
    )
}

#: The parameters of the linear parametric root loci (those with a linear effect).
LOCUS_PARAMETERS = ("cg_ratio", "s1_plus_s2", "trail", "caster_mass_factor", "pin_damping",
                    "mass_factor", "main_lateral_scale", "main_tire")


def parameter_names() -> tuple[str, ...]:
    """Names accepted by :func:`stability.rootlocus.parameter_locus` and :mod:`stability.study`.

    Returns
    -------
    tuple of str
        Keys of :data:`DESIGN_PARAMETERS`, in table order.
    """
    return tuple(DESIGN_PARAMETERS)


def get_parameter(name: str) -> Parameter:
    """Look up a design parameter by name.

    Parameters
    ----------
    name : str
        One of :func:`parameter_names` (e.g. ``"cg_ratio"``, ``"trail"``, ``"main_tire"``).

    Returns
    -------
    Parameter
        Its entry in :data:`DESIGN_PARAMETERS` (label, unit, how to apply it to a
        chair, current value, default range and thesis figure).

    Raises
    ------
    ValueError
        If ``name`` is unknown; the message lists the valid names.
    """
    try:
        return DESIGN_PARAMETERS[name]
    except KeyError:
        raise ValueError(f"unknown parameter {name!r}; valid names: {list(DESIGN_PARAMETERS)}") from None
