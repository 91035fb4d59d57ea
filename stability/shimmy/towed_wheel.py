"""The towed wheel: a caster on a laterally compliant pivot, rigid or relaxation-length tire.

Model and sign conventions: ``derivations/shimmy.py`` and docs/shimmy.md.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from stability.models import shimmy as _model

__all__ = ["TowedWheel", "RouthHurwitz", "HopfBoundary", "hurwitz_determinants", "PARAMETERS"]

#: parameters :meth:`TowedWheel.hopf_boundary` can sweep (besides ``"speed"``)
PARAMETERS = ("mass", "inertia", "contact_behind_cm", "pivot_ahead_of_cm", "lateral_stiffness",
              "cornering_stiffness", "relaxation_length", "pin_damping")


_ARG = dict(mass="mass", inertia="inertia", contact_behind_cm="a", pivot_ahead_of_cm="b", lateral_stiffness="k",
            cornering_stiffness="C", relaxation_length="sigma", pin_damping="c")


def _bad(name: str, value: Any, valid: str) -> ValueError:
    return ValueError(f"towed wheel parameter {name}={value!r} is invalid; valid range: {valid}")


def _real(name: str, value: Any, *, allow_inf: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or math.isnan(value) or (
            math.isinf(value) and not allow_inf):
        raise _bad(name, value, "a finite real number" + (" or inf" if allow_inf else ""))
    return float(value)


def hurwitz_determinants(coeffs: Any) -> np.ndarray:
    """Leading principal minors Delta_1..Delta_n of the Hurwitz matrix.

    The polynomial is Hurwitz (every root in the open left half-plane) iff
    every ``Delta_i > 0`` (Routh-Hurwitz).  ``Delta_(n-1)`` vanishes exactly
    where a pair of roots sums to zero (Orlando's formula), i.e. at a Hopf
    crossing ``+-i w``.

    Parameters
    ----------
    coeffs : array_like
        Coefficients of ``a_0 s^n + a_1 s^(n-1) + ... + a_n``, highest power
        first, ``a_0 > 0``; shape (..., n + 1) for a batch of polynomials.

    Returns
    -------
    numpy.ndarray
        Shape (..., n): ``Delta_1 .. Delta_n`` (in the units of the coefficient products).
    """
    a = np.asarray(coeffs, dtype=float)
    n = a.shape[-1] - 1
    H = np.zeros(a.shape[:-1] + (n, n))
    for i in range(n):
        for j in range(n):
            idx = 2 * (j + 1) - (i + 1)
            if 0 <= idx <= n:
                H[..., i, j] = a[..., idx]
    return np.stack([np.linalg.det(H[..., :m, :m]) for m in range(1, n + 1)], axis=-1)


@dataclass(frozen=True)
class RouthHurwitz:
    """Routh-Hurwitz test of the towed wheel at one speed.

    Attributes
    ----------
    speed : float
        m/s.
    coefficients : ndarray
        Characteristic polynomial, highest power first (closed form from
        ``derivations/shimmy.py``).
    determinants : ndarray
        Hurwitz determinants Delta_1..Delta_n.
    stable : bool
        Every coefficient and every determinant positive.
    """

    speed: float
    coefficients: np.ndarray
    determinants: np.ndarray
    stable: bool


@dataclass(frozen=True)
class HopfBoundary:
    """Oscillatory (Hopf) stability boundary of a towed wheel against a parameter.

    Attributes
    ----------
    parameter : str
        Swept parameter (a :data:`PARAMETERS` name or ``"speed"``).
    speeds : ndarray
        Speeds (m/s) at which the parameter was swept (empty for ``"speed"``).
    crossings : tuple of ndarray
        Per speed, the parameter values (SI) where a complex pair crosses
        the imaginary axis, ascending.
    frequencies : tuple of ndarray
        The pair's angular frequency at each crossing (rad/s).
    destabilising : tuple of ndarray
        True where the pair moves into the right half-plane as the parameter
        increases.
    """

    parameter: str
    speeds: np.ndarray
    crossings: tuple[np.ndarray, ...]
    frequencies: tuple[np.ndarray, ...]
    destabilising: tuple[np.ndarray, ...]


@dataclass(frozen=True)
class TowedWheel:
    """A wheel and fork towed at constant speed by a pivot on a lateral spring.

    Constructed with keywords, SI units.

    Attributes
    ----------
    mass : float
        Wheel-and-fork mass m (kg), > 0.
    inertia : float
        Yaw inertia about its own centre of mass I (kg m^2), > 0.
    contact_behind_cm : float
        Distance a from the c.g. back to the tire contact (m).
    pivot_ahead_of_cm : float
        Distance b from the c.g. forward to the pivot (m); the trail
        ``a + b`` must be > 0.
    lateral_stiffness : float
        Pivot's lateral spring k (N/m), > 0; ``math.inf`` for a rigid pivot.
    cornering_stiffness, relaxation_length : float or None
        Cornering stiffness C_alpha (N/rad) and relaxation length sigma (m).
        Both None (default): rigid tire, no side slip (non-holonomic).  Both
        > 0: first-order relaxation ``sigma/U alpha_dot + alpha = slip``,
        lateral force ``C_alpha alpha`` (Pacejka 2006, sec. 5.3 and ch. 7).
    pin_damping : float
        Viscous pin damping c (N m s/rad), >= 0.
    pin_friction : float
        Coulomb pin friction M_f (N m), >= 0; not in the linear model (see
        :mod:`stability.shimmy.describing`).
    """

    mass: float
    inertia: float
    contact_behind_cm: float
    pivot_ahead_of_cm: float
    lateral_stiffness: float = math.inf
    cornering_stiffness: float | None = None
    relaxation_length: float | None = None
    pin_damping: float = 0.0
    pin_friction: float = 0.0

    def __post_init__(self) -> None:
        for name in ("mass", "inertia"):
            if _real(name, getattr(self, name)) <= 0:
                raise _bad(name, getattr(self, name), "> 0")
        a = _real("contact_behind_cm", self.contact_behind_cm)
        b = _real("pivot_ahead_of_cm", self.pivot_ahead_of_cm)
        if a + b <= 0:
            raise _bad("pivot_ahead_of_cm", self.pivot_ahead_of_cm,
                       f"> -contact_behind_cm = {-a:g} m (the trail a + b must be > 0)")
        if _real("lateral_stiffness", self.lateral_stiffness, allow_inf=True) <= 0:
            raise _bad("lateral_stiffness", self.lateral_stiffness, "> 0 N/m, or inf for a rigid pivot")
        tire = (self.cornering_stiffness, self.relaxation_length)
        if (tire[0] is None) != (tire[1] is None):
            raise _bad("cornering_stiffness" if tire[0] is None else "relaxation_length", None,
                       "> 0 when the other tire parameter is given (both None: rigid tire)")
        if tire[0] is not None:
            for name in ("cornering_stiffness", "relaxation_length"):
                if _real(name, getattr(self, name)) <= 0:
                    raise _bad(name, getattr(self, name), "> 0 (finite)")
        for name in ("pin_damping", "pin_friction"):
            if _real(name, getattr(self, name)) < 0:
                raise _bad(name, getattr(self, name), ">= 0 (finite)")

    # -- configuration ----------------------------------------------------
    @property
    def trail(self) -> float:
        """Pivot to contact distance a + b (m)."""
        return self.contact_behind_cm + self.pivot_ahead_of_cm

    @property
    def rigid_pivot(self) -> bool:
        return math.isinf(self.lateral_stiffness)

    @property
    def rigid_tire(self) -> bool:
        return self.cornering_stiffness is None

    @property
    def case(self) -> str:
        """Configuration key of :mod:`stability.models.shimmy`."""
        return _model.case_name(self.rigid_pivot, self.rigid_tire)

    @property
    def states(self) -> tuple[str, ...]:
        """State names: y (m), psi (rad), y_dot (m/s), psi_dot (rad/s), alpha (rad), as present."""
        return _model.STATES[self.case]

    def replace(self, **changes: Any) -> TowedWheel:
        """A validated copy with ``changes``."""
        return dataclasses.replace(self, **changes)

    def _params(self, **over: float) -> dict[str, float]:
        w = self.replace(**over) if over else self
        return dict(mass=w.mass, inertia=w.inertia, a=w.contact_behind_cm, b=w.pivot_ahead_of_cm,
                    k=1.0 if w.rigid_pivot else w.lateral_stiffness,
                    C=w.cornering_stiffness or 1.0, sigma=w.relaxation_length or 1.0, c=w.pin_damping)

    # -- linear model -----------------------------------------------------
    def state_matrix(self, speed: Any) -> tuple[np.ndarray, np.ndarray]:
        """``(A, B)`` of ``x_dot = A x + B T`` at ``speed`` (m/s; scalar or array), T the pin torque (N m)."""
        return _model.state_matrices(self.case, self._params(), _speeds(speed))

    def state_space(self, speed: float):
        """The linear model at one speed as a :class:`control.StateSpace` (input: pin torque, N m)."""
        import control

        A, B = self.state_matrix(float(_speeds(speed)))
        n = A.shape[-1]
        return control.ss(A, B.reshape(n, 1), np.eye(n), np.zeros((n, 1)), states=list(self.states),
                          inputs=["pin_torque"], outputs=list(self.states), name="towed_wheel")

    def eigenvalues(self, speed: Any) -> np.ndarray:
        """Eigenvalues (1/s) at ``speed``: shape (n,) for a scalar, (N, n) for N speeds; sorted by real part."""
        A, _ = self.state_matrix(speed)
        ev = np.linalg.eigvals(A)
        order = np.argsort(-ev.real, axis=-1, kind="stable")
        return np.take_along_axis(ev, order, axis=-1)

    def characteristic_polynomial(self, speed: Any) -> np.ndarray:
        """Closed-form characteristic polynomial coefficients (highest power first; leading one > 0)."""
        return _model.characteristic_coefficients(self.case, self._params(), _speeds(speed))

    def routh_hurwitz(self, speed: float) -> RouthHurwitz:
        """Routh-Hurwitz test at one speed (see :func:`hurwitz_determinants` and docs/shimmy.md)."""
        U = float(_speeds(speed))
        p = self.characteristic_polynomial(U)
        d = hurwitz_determinants(p / p[0])
        return RouthHurwitz(U, p, d, bool(np.all(p > 0) and np.all(d > 0)))

    def oscillatory_abscissa(self, speed: Any) -> np.ndarray:
        """Largest real part (1/s) among complex eigenvalues; ``-inf`` where all are real."""
        ev = np.atleast_2d(self.eigenvalues(speed))
        scale = np.maximum(np.abs(ev).max(axis=-1, keepdims=True), 1e-300)
        re = np.where(np.abs(ev.imag) > 1e-9 * scale, ev.real, -np.inf)
        out = re.max(axis=-1)
        return out if np.ndim(speed) else out[0]

    # -- Hopf boundaries --------------------------------------------------
    def _margin(self, value: float, parameter: str, speed: float | None) -> float:
        if parameter == "speed":
            p = self.characteristic_polynomial(value)
        else:
            p = _model.characteristic_coefficients(self.case, self._params(**{parameter: value}), speed)
        return float(hurwitz_determinants(p / p[0])[-2])

    def hopf_crossings(self, parameter: str, grid: Any, speed: float | None = None
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Values of ``parameter`` on ``grid``'s span where a complex pair crosses the imaginary axis.

        Sign changes of the Hurwitz determinant ``Delta_(n-1)`` between
        neighbouring grid points are refined with Brent's method (relative
        tolerance 1e-12) and kept if the system there has a pair ``+-i w``
        (a crossing of two real roots summing to zero is discarded).

        Returns ``(values, frequencies (rad/s), destabilising)``.
        """
        if parameter != "speed" and parameter not in PARAMETERS:
            raise ValueError(f"parameter={parameter!r} is invalid; valid choices: {['speed', *PARAMETERS]}")
        if len(self.states) < 3:
            raise ValueError(f"a {self.case} towed wheel (order {len(self.states)}) has no oscillatory mode; "
                             "valid: a compliant pivot or a compliant tire")
        grid = np.asarray(grid, dtype=float)
        if grid.ndim != 1 or grid.size < 2 or np.any(np.diff(grid) <= 0):
            raise ValueError("grid is invalid; valid: at least two strictly increasing values")
        U = None if parameter == "speed" else float(_speeds(speed))
        if parameter == "speed":
            p = self.characteristic_polynomial(grid)
        else:
            self._check_sweep(parameter, grid)
            params = self._params()
            params[_ARG[parameter]] = grid
            p = _model.characteristic_coefficients(self.case, params, U)
        f = hurwitz_determinants(p / p[..., :1])[:, -2]
        vals, freqs, dest = [], [], []
        for i in np.nonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)[0]:
            x = brentq(self._margin, grid[i], grid[i + 1], args=(parameter, U), xtol=1e-14, rtol=1e-12)
            w = self if parameter == "speed" else self.replace(**{parameter: x})
            ev = w.eigenvalues(x if parameter == "speed" else U)
            j = int(np.argmin(np.abs(ev.real)))
            if abs(ev[j].imag) <= 1e-6 * np.abs(ev).max() or abs(ev[j].real) > 1e-6 * abs(ev[j]):
                continue
            vals.append(x)
            freqs.append(abs(ev[j].imag))
            dest.append(bool(f[i + 1] < 0))  # Delta_(n-1) < 0 after the crossing: unstable
        return np.array(vals), np.array(freqs), np.array(dest, dtype=bool)

    def _check_sweep(self, parameter: str, grid: np.ndarray) -> None:
        if (parameter == "lateral_stiffness" and self.rigid_pivot) or (
                parameter in ("cornering_stiffness", "relaxation_length") and self.rigid_tire):
            raise ValueError(f"parameter={parameter!r} is invalid for a {self.case} towed wheel; "
                             "valid: a parameter the configuration has")
        if parameter in ("contact_behind_cm", "pivot_ahead_of_cm"):
            other = self.trail - getattr(self, parameter)
            if np.any(grid + other <= 0):
                raise ValueError(f"grid is invalid for {parameter}; valid range: every value > {-other:g} m "
                                 "(positive trail)")
        elif parameter == "pin_damping":
            if np.any(grid < 0):
                raise ValueError("grid is invalid for pin_damping; valid range: every value >= 0")
        elif np.any(grid <= 0):
            raise ValueError(f"grid is invalid for {parameter}; valid range: every value > 0")

    def hopf_boundary(self, parameter: str, grid: Any, speeds: Any = None) -> HopfBoundary:
        """The Hopf boundary against ``parameter`` (or against ``"speed"`` when ``parameter="speed"``).

        Parameters
        ----------
        parameter : str
            ``"speed"`` or one of :data:`PARAMETERS`.
        grid : array_like
            Increasing values of the parameter to scan (SI units); crossings
            closer together than a grid step may be missed.
        speeds : array_like, optional
            Speeds (m/s) at which to sweep the parameter (required unless
            ``parameter == "speed"``).
        """
        if parameter == "speed":
            out = [self.hopf_crossings("speed", grid)]
            U = np.array([])
        else:
            if speeds is None:
                raise ValueError("speeds=None is invalid; valid: speeds (m/s) at which to sweep " + parameter)
            U = _speeds(np.atleast_1d(speeds))
            out = [self.hopf_crossings(parameter, grid, u) for u in U]
        return HopfBoundary(parameter, U, tuple(o[0] for o in out), tuple(o[1] for o in out),
                            tuple(o[2] for o in out))


def _speeds(speed: Any) -> np.ndarray:
    U = np.asarray(speed, dtype=float)
    if U.size == 0 or not np.all(np.isfinite(U) & (U > 0)):
        bad = U[~(np.isfinite(U) & (U > 0))] if U.size else U
        raise ValueError(f"speed={float(bad.ravel()[0]) if bad.size else speed!r} is invalid; "
                         "valid range: speed > 0 m/s (forward motion)")
    return U
