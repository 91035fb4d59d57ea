"""Root loci of the linear models: against speed, against design parameters, against a gain.

Follows python-control's split between *computing* a response (a data object)
and *plotting* it (:mod:`stability.plotting`):

:func:`speed_locus` -> :class:`SpeedLocus`
    eigenvalues of the linear model as the forward speed varies (the
    parametric root locus; free or locked casters, either model variant),
    branches tracked with :func:`stability.linear.track_modes`, and the
    critical speeds.
:func:`parameter_locus` -> :class:`ParameterLocus`
    eigenvalues at one fixed speed as one design parameter varies (the
    chapter-8 parameters: c.g. ratio at constant ``s1 + s2`` (eq 8-6),
    ``s1 + s2``, trail, caster mass and inertia scaled together (Figure
    8-12), viscous pin damping, total mass and inertia scaled together
    (Figure 8-14), main-tire lateral force scale and the main tire itself).
    python-control has no parameter root locus (its issue #43); this one is
    computed with **one** batched call to
    :func:`stability.linear.state_matrices` over the list of chairs built
    with :meth:`stability.chair.Chair.replace` and one batched
    :func:`numpy.linalg.eigvals`.
:func:`gain_locus` -> :class:`GainLocus`
    the classical root locus of yaw-rate feedback through the yaw-moment
    input, ``Mz = -K r``, from :func:`control.root_locus_map` (roots of
    ``1 + K G(s)`` with ``G = r / Mz``).

Examples
--------
>>> from stability import chair, rootlocus
>>> loc = rootlocus.parameter_locus(chair.preset("ej-premier"), "trail", speed=0.75)  # doctest: +SKIP
>>> loc.eigenvalues.shape                                                               # doctest: +SKIP
(121, 6)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from ._validate import check_casters, check_model, check_speed
from .chair import Chair
from .linear import (
    STATES_FREE,
    STATES_LOCKED,
    critical_speeds,
    state_matrices,
    state_space,
    track_modes,
)

__all__ = [
    "Parameter",
    "DESIGN_PARAMETERS",
    "parameter_names",
    "SpeedLocus",
    "speed_locus",
    "ParameterLocus",
    "parameter_locus",
    "parameter_loci",
    "GainLocus",
    "gain_locus",
    "closed_loop_matrices",
]


def _readonly(a) -> np.ndarray:
    a = np.array(a)
    a.setflags(write=False)
    return a


# ---------------------------------------------------------------------------
# speed
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SpeedLocus:
    """Eigenvalues of a linear model as the forward speed varies.

    Attributes
    ----------
    chair : Chair
    model : {"exact", "thesis"}
    casters : {"free", "locked"}
    speeds : ndarray, shape (N,)
        Increasing forward speeds (m/s).
    eigenvalues : ndarray, shape (N, n)
        Column ``j`` is one tracked branch (mode), 1/s.
    crossings : list of Crossing
        Critical speeds: where the largest real part crosses zero.
    states : tuple of str
        State names of the model.
    """

    chair: Chair
    model: str
    casters: str
    speeds: np.ndarray
    eigenvalues: np.ndarray
    crossings: list = field(default_factory=list)
    states: tuple = ()

    @property
    def max_real(self) -> np.ndarray:
        """Largest real part at each speed (1/s)."""
        return self.eigenvalues.real.max(axis=1)

    @property
    def unstable(self) -> np.ndarray:
        """Boolean mask of the speeds at which some eigenvalue has a positive real part."""
        return self.max_real > 0

    def unstable_intervals(self) -> list[tuple[float, float]]:
        """Speed intervals (m/s) in which the model is unstable, ends refined to the crossings."""
        out: list[tuple[float, float]] = []
        U = self.speeds
        crit = sorted(c.speed for c in self.crossings)
        inside = bool(self.unstable[0])
        start = float(U[0]) if inside else None
        for s in crit:
            if inside:
                out.append((start, s))
                inside = False
            else:
                start, inside = s, True
        if inside:
            out.append((start, float(U[-1])))
        return out

    @property
    def title(self) -> str:
        return f"{self.chair.name}, {self.model} model, {self.casters} casters"


def speed_locus(chair: Chair, speeds=None, *, model: str = "exact", casters: str = "free",
                max_speed: float = 15.0, n: int = 600) -> SpeedLocus:
    """Eigenvalues against forward speed, tracked, and the critical speeds.

    Parameters
    ----------
    chair : Chair
    speeds : array_like, optional
        Increasing speeds (m/s); default ``geomspace(0.05, max_speed, n)``.
    model, casters : str
        Model variant and caster state.
    """
    check_model(model)
    check_casters(casters)
    if speeds is None:
        if not (math.isfinite(max_speed) and max_speed > 0.05):
            raise ValueError(f"max_speed={max_speed!r} is invalid; valid range: > 0.05 m/s")
        speeds = np.geomspace(0.05, max_speed, int(n))
    U = np.asarray(speeds, dtype=float)
    if U.ndim != 1 or len(U) < 2 or np.any(np.diff(U) <= 0) or U[0] <= 0:
        raise ValueError("speeds must be an increasing 1-D array of at least 2 positive speeds (m/s)")
    A = state_matrices(chair, U, model, casters)
    eig = track_modes(np.linalg.eigvals(A))
    crossings = critical_speeds(lambda s: state_matrices(chair, s, model, casters), U)
    states = STATES_FREE if casters == "free" else STATES_LOCKED
    return SpeedLocus(chair, model, casters, _readonly(U), _readonly(eig), list(crossings), tuple(states))


# ---------------------------------------------------------------------------
# design parameters
# ---------------------------------------------------------------------------
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


def _wheelbase(c: Chair, total: float) -> Chair:
    if total <= c.s1:
        raise ValueError(f"s1_plus_s2={total!r} is invalid; valid range: > s1 = {c.s1:g} m")
    return c.replace(s2=total - c.s1)


def _caster_mass_factor(c: Chair, f: float) -> Chair:
    return c.replace(m_c=c.m_c * f, i_zp=c.i_zp * f)


def _mass_factor(c: Chair, f: float) -> Chair:
    return c.replace(m=c.m * f, i_z=c.i_z * f)


def _main_tires() -> tuple[str, ...]:
    from . import tires

    names = getattr(tires, "MAIN_TIRES", None)
    return tuple(names) if names else tuple(tires.names())


def _tire_index(c: Chair) -> float:
    names = _main_tires()
    return float(names.index(c.main_tire)) if c.main_tire in names else float("nan")


def _apply_tire(c: Chair, v: float) -> Chair:
    return c.replace(main_tire=_main_tires()[int(round(v))])


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
                  lambda c: (0.30, 0.90), "s1 and s2 varied at constant s1 + s2 (eq 8-6, Figure 8-9)"),
        Parameter("s1_plus_s2", "main axle to caster pins s1+s2", "m", _wheelbase, lambda c: c.s1 + c.s2,
                  lambda c: (max(c.s1 + 0.02, 0.25), 0.85), "s2 varied at constant s1 (Figure 8-10)"),
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
        Parameter("main_lateral_scale", "main-tire lateral force scale (TYMOD)", "-",
                  lambda c, v: c.replace(main_lateral_scale=v), lambda c: c.main_lateral_scale,
                  lambda c: (0.5, 1.6), "main-tire cornering stiffness scaled (a continuous tire change)"),
        Parameter("main_tire", "main tire", "-", _apply_tire, _tire_index,
                  lambda c: (0, len(_main_tires()) - 1), "main tire type (Figure 8-15)", categorical=True),
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
    """Names accepted by :func:`parameter_locus` and :mod:`stability.study`."""
    return tuple(DESIGN_PARAMETERS)


def get_parameter(name: str) -> Parameter:
    try:
        return DESIGN_PARAMETERS[name]
    except KeyError:
        raise ValueError(f"unknown parameter {name!r}; valid names: {list(DESIGN_PARAMETERS)}") from None


@dataclass(frozen=True, eq=False)
class ParameterLocus:
    """Eigenvalues of the linear model at one speed as one design parameter varies.

    Attributes
    ----------
    parameter : str
        Parameter name (a key of :data:`DESIGN_PARAMETERS`).
    label, unit : str
        Axis label and unit of the parameter.
    values : ndarray, shape (N,)
        Parameter values (for the categorical ``main_tire``: indices into ``labels``).
    eigenvalues : ndarray, shape (N, n)
        Column ``j`` is one tracked branch (1/s).
    chair : Chair
        The base chair (its own value is ``nominal``).
    model : str
    speed : float
        Forward speed (m/s).
    casters : str
    nominal : float
        The base chair's value of the parameter.
    labels : tuple of str or None
        Names of categorical values.
    chairs : tuple of Chair
        The chair at each value.
    """

    parameter: str
    label: str
    unit: str
    values: np.ndarray
    eigenvalues: np.ndarray
    chair: Chair
    model: str
    speed: float
    casters: str = "free"
    nominal: float = float("nan")
    labels: tuple | None = None
    chairs: tuple = ()

    @property
    def categorical(self) -> bool:
        return self.labels is not None

    @property
    def max_real(self) -> np.ndarray:
        """Largest real part at each value (1/s)."""
        return self.eigenvalues.real.max(axis=1)

    def stability_boundaries(self) -> list[float]:
        """Parameter values where the largest real part crosses zero (linear interpolation)."""
        if self.categorical:
            return []
        a, v = self.max_real, self.values
        out = []
        for k in np.flatnonzero(np.sign(a[:-1]) * np.sign(a[1:]) < 0):
            out.append(float(v[k] - a[k] * (v[k + 1] - v[k]) / (a[k + 1] - a[k])))
        return out

    def axis_label(self) -> str:
        return f"{self.label} ({self.unit})" if not self.categorical else self.label

    @property
    def title(self) -> str:
        return f"{self.chair.name}, {self.model} model, {self.casters} casters, U = {self.speed:g} m/s"


def _locus_values(chair: Chair, p: Parameter, values, n: int) -> np.ndarray:
    if values is None:
        lo, hi = p.span(chair)
        if p.categorical:
            return np.arange(int(lo), int(hi) + 1, dtype=float)
        vals = np.linspace(lo, hi, int(n))
        cur = p.current(chair)
        if math.isfinite(cur) and lo < cur < hi:
            vals = np.unique(np.append(vals, cur))
        return vals
    vals = np.atleast_1d(np.asarray(values, dtype=float))
    if vals.ndim != 1 or len(vals) < 1 or not np.all(np.isfinite(vals)):
        raise ValueError(f"values for {p.name} must be a 1-D array of finite numbers")
    return vals


def parameter_locus(chair: Chair, parameter: str, values=None, *, speed: float = 0.75,
                    model: str = "exact", casters: str = "free", n: int = 121) -> ParameterLocus:
    """Root locus against a design parameter at fixed speed.

    Every chair is built with :meth:`Chair.replace` (validated) and all state
    matrices come from **one** batched :func:`stability.linear.state_matrices`
    call; the eigenvalues from one batched :func:`numpy.linalg.eigvals`; the
    branches are tracked with :func:`stability.linear.track_modes` (in the
    order of ``values``; categorical parameters are sorted by real part).

    Parameters
    ----------
    chair : Chair
    parameter : str
        A key of :data:`DESIGN_PARAMETERS` (see :func:`parameter_names`).
    values : array_like, optional
        Values to evaluate, in the order to track; default: ``n`` values
        over the parameter's span plus the chair's own value.
    speed : float
        Forward speed (m/s), default the thesis's reference 0.75 m/s.
    """
    check_model(model)
    check_casters(casters)
    speed = check_speed(speed)
    p = get_parameter(parameter)
    if p.name == "pin_friction":
        raise ValueError("pin_friction (Coulomb) has no linearisation; use pin_damping for a root locus")
    vals = _locus_values(chair, p, values, n)
    chairs = tuple(p.apply(chair, float(v)) for v in vals)
    A = state_matrices(list(chairs), np.full(len(chairs), speed), model, casters)
    eig = np.linalg.eigvals(A)
    if p.categorical:
        eig = np.take_along_axis(eig, np.argsort(-eig.real, axis=1, kind="stable"), axis=1)
        labels = tuple(_main_tires()[int(v)] for v in vals)
    else:
        eig = track_modes(eig)
        labels = None
    return ParameterLocus(p.name, p.label, p.unit, _readonly(vals), _readonly(eig), chair, model, speed,
                          casters, float(p.current(chair)), labels, chairs)


def parameter_loci(chair: Chair, parameters: Sequence[str] = LOCUS_PARAMETERS, *, speed: float = 0.75,
                   model: str = "exact", casters: str = "free", n: int = 121) -> list[ParameterLocus]:
    """:func:`parameter_locus` for several parameters."""
    return [parameter_locus(chair, p, speed=speed, model=model, casters=casters, n=n) for p in parameters]


# ---------------------------------------------------------------------------
# feedback gain
# ---------------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class GainLocus:
    """Root locus of yaw-rate feedback ``Mz = -K r`` at one speed.

    Attributes
    ----------
    chair, model, casters, speed
        The open-loop linear model.
    gains : ndarray, shape (N,)
        Feedback gains K (N m s/rad), increasing from 0.
    loci : ndarray, shape (N, n)
        Closed-loop poles, tracked branches (1/s).
    poles, zeros : ndarray
        Open-loop poles and zeros of ``G(s) = r(s)/Mz(s)``.
    stabilising_gain : float or None
        Smallest gain with every closed-loop pole in the open left half plane
        (N m s/rad): None if the open loop is already stable (0) or no gain
        in the range stabilises.
    """

    chair: Chair
    model: str
    casters: str
    speed: float
    gains: np.ndarray
    loci: np.ndarray
    poles: np.ndarray
    zeros: np.ndarray
    stabilising_gain: float | None = None

    @property
    def title(self) -> str:
        return f"{self.chair.name}, {self.model} model, {self.casters} casters, U = {self.speed:g} m/s"


def closed_loop_matrices(chair: Chair, speed: float, gains, *, model: str = "exact",
                         casters: str = "free") -> np.ndarray:
    """Closed-loop state matrices ``A - K B C_r`` for many gains (N, n, n)."""
    A = state_matrices(chair, speed, model, casters)[0]
    from .linear import input_matrices

    B = input_matrices(chair, speed, model, casters)[0]
    C = np.zeros((1, A.shape[0]))
    C[0, 1] = 1.0
    K = np.atleast_1d(np.asarray(gains, dtype=float))
    return A[None] - K[:, None, None] * (B @ C)[None]


def _stabilising_gain(chair, speed, model, casters, gains) -> float | None:
    from scipy.optimize import brentq

    def alpha(k):
        return float(np.linalg.eigvals(closed_loop_matrices(chair, speed, [k], model=model,
                                                            casters=casters)[0]).real.max())

    a = np.linalg.eigvals(closed_loop_matrices(chair, speed, gains, model=model, casters=casters)).real.max(axis=1)
    if a[0] < 0:
        return 0.0
    ok = np.flatnonzero(a < 0)
    if len(ok) == 0:
        return None
    k = int(ok[0])
    return float(brentq(alpha, gains[k - 1], gains[k], xtol=1e-10 * max(1.0, gains[k])))


def gain_locus(chair: Chair, speed: float = 0.75, gains=None, *, model: str = "exact",
               casters: str = "free", max_gain: float = 300.0, n: int = 400) -> GainLocus:
    """Root locus of yaw-rate feedback through the yaw-moment input, with :func:`control.root_locus_map`.

    ``G(s) = r(s) / Mz(s)`` is the linear model's yaw-rate response to a yaw
    moment on the chair; ``control.root_locus_map`` returns the roots of
    ``1 + K G(s)``, i.e. the poles with ``Mz = -K r``.

    Parameters
    ----------
    gains : array_like, optional
        Gains K >= 0 (N m s/rad), increasing; default 0 and ``n`` values
        geometrically spaced from 0.1 to ``max_gain``.
    """
    import control

    check_model(model)
    check_casters(casters)
    speed = check_speed(speed)
    if gains is None:
        gains = np.concatenate([[0.0], np.geomspace(0.1, max_gain, int(n))])
    K = np.asarray(gains, dtype=float)
    if K.ndim != 1 or np.any(K < 0) or np.any(np.diff(K) <= 0):
        raise ValueError("gains must be an increasing 1-D array of gains K >= 0 (N m s/rad)")
    G = state_space(chair, speed, model, casters)[1, 0]   # Mz -> r (SISO)
    rl = control.root_locus_map(G, gains=K)
    loci = track_modes(np.asarray(rl.loci))
    k_stab = _stabilising_gain(chair, speed, model, casters, K)
    return GainLocus(chair, model, casters, speed, _readonly(K), _readonly(loci),
                     _readonly(np.asarray(rl.poles)), _readonly(np.asarray(rl.zeros)), k_stab)
