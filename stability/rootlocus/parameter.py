"""Eigenvalues at one speed as one design parameter varies (python-control has no parameter locus)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.chair.design import LOCUS_PARAMETERS, Parameter, get_parameter, main_tires
from stability.chair.model import takes_chair
from stability.linear import state_matrices, track_modes
from stability.rootlocus.speed import readonly
from stability.runtime.checks import check_casters, check_model, check_speed
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["ParameterLocus", "parameter_locus", "parameter_loci"]


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


@takes_chair
def parameter_locus(chair: Chair, parameter: str, values=None, *, speed: float = REFERENCE_SPEED,
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
        The base chair.
    parameter : str
        A key of :data:`DESIGN_PARAMETERS` (see :func:`parameter_names`);
        not ``"pin_friction"`` (Coulomb friction has no linearisation).
    values : array_like, optional
        Values to evaluate, in the parameter's unit and in the order to track;
        default: ``n`` values over the parameter's span plus the chair's own value.
    speed : float
        Forward speed (m/s, > 0), default the thesis's reference 0.75 m/s.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Caster state (default ``"free"``).
    n : int, optional
        Number of default values over the span (default 121); ignored when ``values`` is given.

    Returns
    -------
    ParameterLocus
        The values, the eigenvalues at each (1/s), the chairs built and, for the
        main tire, the tire names.

    Raises
    ------
    ValueError
        If the parameter is unknown or ``"pin_friction"``, a value makes an
        invalid chair, or the speed, model or caster state is invalid.
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
        labels = tuple(main_tires()[int(v)] for v in vals)
    else:
        eig = track_modes(eig)
        labels = None
    return ParameterLocus(p.name, p.label, p.unit, readonly(vals), readonly(eig), chair, model, speed,
                          casters, float(p.current(chair)), labels, chairs)


@takes_chair
def parameter_loci(chair: Chair, parameters: Sequence[str] = LOCUS_PARAMETERS, *, speed: float = REFERENCE_SPEED,
                   model: str = "exact", casters: str = "free", n: int = 121) -> list[ParameterLocus]:
    """:func:`parameter_locus` for several parameters.

    Parameters
    ----------
    chair : Chair
        The base chair.
    parameters : sequence of str, optional
        Keys of :data:`DESIGN_PARAMETERS`; default :data:`LOCUS_PARAMETERS`
        (those of Figures 8-9 to 8-15 with a linear effect).
    speed : float, optional
        Forward speed (m/s, > 0), default 0.75 m/s.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Caster state (default ``"free"``).
    n : int, optional
        Number of values over each parameter's span (default 121).

    Returns
    -------
    list of ParameterLocus
        One locus per parameter, in the order given.
    """
    return [parameter_locus(chair, p, speed=speed, model=model, casters=casters, n=n) for p in parameters]
