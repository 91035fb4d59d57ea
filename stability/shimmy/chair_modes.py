"""Shimmy in the chair's own eigenvalues: the full-width model with relaxation-length caster tires.

The linear model of :mod:`stability.linear` with each caster's lateral tire
force as a state, ``(sigma/U) dF/dt + F = -C_alpha alpha`` (Pacejka 2006,
sec. 5.3), optionally with each caster pin on a lateral spring (the towed
wheel's compliant pivot).  Equations: ``derivations/full_width_relaxed.py``;
rationale and results: docs/shimmy.md.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair, takes_chairs
from stability.linear import state_matrices
from stability.models.params import Params, parameters
from stability.models.relaxed import STATES, relaxed_matrices
from stability.models.statics import static_stiffness
from stability.runtime.checks import check_choice, check_model, check_speed, check_speeds
from stability.shimmy.chair import ESTIMATE_NOTE, CasterCompliance

__all__ = ["PINS", "SHIMMY_MIN_HZ", "relaxed_state_matrices", "relaxed_state_space", "shimmy_mode",
           "ChairShimmy", "chair_shimmy", "chair_critical_trail", "ChairTrailChart", "chair_trail_chart"]

PINS = ("rigid", "compliant")
#: Oscillatory modes below this frequency (Hz) are chair modes, not shimmy (the chair's are of order 1/s).
SHIMMY_MIN_HZ = 2.0
_TRAIL_GRID = (0.002, 0.2, 50)


def _variant(model: str, pin: str) -> str:
    check_model(model)
    check_choice("pin", pin, PINS)
    if pin == "compliant":
        if model != "exact":
            raise ValueError(f"model={model!r} is invalid with pin='compliant'; valid choices: ['exact']")
        return "pin_exact"
    return model


def _batch(chairs: Chair | Sequence[Chair]) -> tuple[Params, dict[str, Any]]:
    if isinstance(chairs, Chair):
        return parameters(chairs), static_stiffness(chairs)
    rows = [static_stiffness(c) for c in chairs]
    return parameters(chairs), {k: np.array([r[k] for r in rows]) for k in ("A", "B", "D", "E")}


def _assemble(M: np.ndarray, K: np.ndarray, T: np.ndarray) -> np.ndarray:
    """First-order state matrix from ``M acc = K x`` and ``F_dot = T x`` (states of :data:`STATES`)."""
    F = np.linalg.solve(M, K)
    n, k = K.shape[-1], M.shape[-1]
    A = np.zeros(F.shape[:-2] + (n, n))
    A[..., 0, :], A[..., 1, :] = F[..., 0, :], F[..., 1, :]
    for j in range(2, k):  # (angle or offset, rate) pairs
        A[..., 2 * j - 2, 2 * j - 1] = 1.0
        A[..., 2 * j - 1, :] = F[..., j, :]
    A[..., -2:, :] = T
    return A


@takes_chairs
def relaxed_state_matrices(chair: Chair | Sequence[Chair], speeds: Any, compliance: CasterCompliance | None = None,
                           model: str = "exact", pin: str = "rigid") -> np.ndarray:
    """State matrices of the chair with relaxation-length caster tires, batched over speeds (and chairs).

    Parameters
    ----------
    chair : Chair or sequence of Chair
        One chair, or N chairs (broadcast against ``speeds``).
    speeds : float or array_like
        Forward speeds U > 0 (m/s).
    compliance : CasterCompliance, optional
        Caster tire relaxation length (and pin lateral stiffness for
        ``pin="compliant"``); default :class:`CasterCompliance` (estimates).
    model : {"exact", "thesis"}
        Equation variant; ``"thesis"`` only with rigid pins.
    pin : {"rigid", "compliant"}
        Rigid pins: 8 states ``[v, r, eta, eta_dot, beta, beta_dot, F_A, F_B]``;
        compliant: 12 states, ``y_A, y_A_dot, y_B, y_B_dot`` (pin lateral
        offsets, m and m/s) before ``F_A, F_B`` (caster lateral tire forces, N).

    Returns
    -------
    ndarray
        Shape (N, n, n), SI units.
    """
    p, st = _batch(chair)
    return _matrices(p, st, check_speeds(speeds), compliance or CasterCompliance(), _variant(model, pin))


def _matrices(p: Params, st: dict[str, Any], U: np.ndarray, comp: CasterCompliance, variant: str) -> np.ndarray:
    M, K, _, T = relaxed_matrices(p, U, st, comp.relaxation_length, variant, comp.lateral_stiffness)
    return _assemble(M, K, T)


@takes_chair
def relaxed_state_space(chair: Chair, speed: float, compliance: CasterCompliance | None = None,
                        model: str = "exact", pin: str = "rigid"):
    """The relaxed model at one speed as a :class:`control.StateSpace` with named states.

    Parameters
    ----------
    chair : Chair
    speed : float
        m/s, > 0.
    compliance : CasterCompliance, optional
    model : {"exact", "thesis"}
    pin : {"rigid", "compliant"}

    Returns
    -------
    control.StateSpace
        Input ``Mz`` (yaw moment on the chair, N m); outputs ``v`` (m/s), ``r`` (rad/s).
    """
    import control  # ~0.3 s to import; only this function needs it

    comp = compliance or CasterCompliance()
    U = check_speed(speed)
    variant = _variant(model, pin)
    M, K, Bm, T = relaxed_matrices(parameters(chair), U, static_stiffness(chair), comp.relaxation_length, variant,
                                   comp.lateral_stiffness)
    A = _assemble(M, K, T)[0]
    Bf = np.linalg.solve(M[0], Bm[0])
    B = np.zeros((A.shape[0], 1))
    B[0, 0], B[1, 0] = Bf[0], Bf[1]
    for j in range(2, Bf.size):
        B[2 * j - 1, 0] = Bf[j]
    states = list(STATES[variant])
    C = np.zeros((2, len(states)))
    C[0, 0] = C[1, 1] = 1.0
    name = f"{chair.name} (relaxed {model}, {pin} pins, U={U:g} m per s)".replace(".", "p")
    return control.ss(A, B, C, np.zeros((2, 1)), states=states, inputs=["Mz"], outputs=["v", "r"], name=name)


def shimmy_mode(eigenvalues: np.ndarray, min_hz: float = SHIMMY_MIN_HZ) -> np.ndarray:
    """The shimmy eigenvalue: the least damped with frequency above ``min_hz`` (upper half-plane).

    Parameters
    ----------
    eigenvalues : ndarray, shape (..., n)
        1/s.
    min_hz : float
        Frequencies below are chair modes.

    Returns
    -------
    ndarray, shape (...)
        Complex; ``nan`` where no mode oscillates above ``min_hz``.
    """
    ev = np.asarray(eigenvalues)
    osc = ev.imag > 2 * math.pi * min_hz
    re = np.where(osc, ev.real, -np.inf)
    j = np.argmax(re, axis=-1)
    lead = np.take_along_axis(ev, j[..., None], axis=-1)[..., 0]
    return np.where(osc.any(axis=-1), lead, np.nan + 0j)


def _divergence(ev: np.ndarray, min_hz: float = SHIMMY_MIN_HZ) -> np.ndarray:
    """Largest real part among the chair's own modes (all but the oscillatory ones above ``min_hz``)."""
    return np.where(np.abs(ev.imag) > 2 * math.pi * min_hz, -np.inf, ev.real).max(axis=-1)


def _grid_eigenvalues(chair: Chair, trails: np.ndarray, speeds: np.ndarray, comp: CasterCompliance,
                      model: str, pin: str) -> np.ndarray:
    """Eigenvalues over trails x speeds, shape (len(trails), len(speeds), n)."""
    chairs = [chair.replace(trail=float(t)) for t in trails]
    p, st = _batch(chairs)
    p = Params(*(np.asarray(f)[:, None] for f in p))
    st = {k: v[:, None] for k, v in st.items()}
    A = _matrices(p, st, speeds, comp, _variant(model, pin))
    return np.linalg.eigvals(A.reshape(len(trails), len(speeds), *A.shape[-2:]))


@takes_chair
def chair_critical_trail(chair: Chair, speeds: Any, compliance: CasterCompliance | None = None,
                         model: str = "exact", pin: str = "rigid", xtol: float = 1e-5) -> np.ndarray:
    """Largest trail (m) below which the chair model's shimmy mode is unstable, per speed.

    A scan over 2 mm-0.2 m (50 points) brackets the largest sign change of
    the shimmy mode's real part, then bisection on ``chair.replace(trail=...)``
    narrows it to ``xtol``.  ``0`` where the mode is stable at every trail
    scanned, ``inf`` where it is unstable at 0.2 m.

    Parameters
    ----------
    chair : Chair
    speeds : float or array_like
        m/s.
    compliance : CasterCompliance, optional
    model : {"exact", "thesis"}
    pin : {"rigid", "compliant"}
    xtol : float
        Trail tolerance (m).

    Returns
    -------
    ndarray
        Critical trail per speed (m).
    """
    comp = compliance or CasterCompliance()
    U = check_speeds(speeds)
    grid = np.linspace(*_TRAIL_GRID)
    re = shimmy_mode(_grid_eigenvalues(chair, grid, U, comp, model, pin)).real
    unstable = np.nan_to_num(re, nan=-np.inf) > 0
    out = np.zeros(U.size)
    for i in range(U.size):
        if unstable[-1, i]:
            out[i] = math.inf
            continue
        idx = np.nonzero(unstable[:-1, i] & ~unstable[1:, i])[0]
        if idx.size == 0:
            continue
        lo, hi = float(grid[idx[-1]]), float(grid[idx[-1] + 1])
        while hi - lo > xtol:
            mid = 0.5 * (lo + hi)
            ev = _grid_eigenvalues(chair, np.array([mid]), U[i:i + 1], comp, model, pin)
            if shimmy_mode(ev).real[0, 0] > 0:
                lo = mid
            else:
                hi = mid
        out[i] = 0.5 * (lo + hi)
    return out


@dataclass(frozen=True)
class ChairShimmy:
    """The chair model's shimmy mode against speed.

    Attributes
    ----------
    chair_name : str
    compliance : CasterCompliance
        Estimated caster compliance used.
    model, pin : str
        Equation variant and pin model (``"rigid"`` or ``"compliant"``).
    speeds : ndarray
        m/s.
    frequency_hz, damping_ratio, real_part : ndarray
        The shimmy mode (least damped oscillatory mode above
        :data:`SHIMMY_MIN_HZ`): frequency (Hz), damping ratio ``-Re/|lambda|``
        and real part (1/s; > 0: shimmy grows).
    divergence_rate : ndarray
        Largest real part of the chair's other modes (1/s): the yaw divergence.
    rigid_tire_rate : ndarray
        ``stability.linear``'s largest real part (point-contact tires), for comparison (1/s).
    critical_trail : ndarray
        Trail (m) below which the shimmy mode is unstable (0: none, inf: above 0.2 m).
    trail : float
        The chair's trail (m).
    note : str
        That the compliance values are estimates.
    """

    chair_name: str
    compliance: CasterCompliance
    model: str
    pin: str
    speeds: np.ndarray
    frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    real_part: np.ndarray
    divergence_rate: np.ndarray
    rigid_tire_rate: np.ndarray
    critical_trail: np.ndarray
    trail: float
    note: str = ESTIMATE_NOTE

    def to_mapping(self) -> dict:
        """JSON-ready dict (units in the keys; inf written as null)."""
        def num(x):
            return [None if not math.isfinite(v) else float(v) for v in np.ravel(x)]

        return {
            "chair": self.chair_name, "model": self.model, "pin": self.pin, "note": self.note,
            "relaxation_length_m": self.compliance.relaxation_length,
            "lateral_stiffness_N_per_m": self.compliance.lateral_stiffness if self.pin == "compliant" else None,
            "trail_m": self.trail, "speeds_m_s": num(self.speeds),
            "shimmy_frequency_hz": num(self.frequency_hz), "shimmy_damping_ratio": num(self.damping_ratio),
            "shimmy_real_part_1_s": num(self.real_part), "divergence_rate_1_s": num(self.divergence_rate),
            "rigid_tire_rate_1_s": num(self.rigid_tire_rate), "critical_trail_m": num(self.critical_trail),
            "null_means": "critical trail above 0.2 m (unstable at every trail checked)",
        }


@takes_chair
def chair_shimmy(chair: Chair, speeds: Any, compliance: CasterCompliance | None = None, model: str = "exact",
                 pin: str = "rigid") -> ChairShimmy:
    """Shimmy mode, yaw divergence and critical trail of the chair model at ``speeds`` (see :class:`ChairShimmy`).

    Parameters
    ----------
    chair : Chair
    speeds : float or array_like
        m/s.
    compliance : CasterCompliance, optional
        Default :class:`CasterCompliance` (estimates).
    model : {"exact", "thesis"}
    pin : {"rigid", "compliant"}

    Returns
    -------
    ChairShimmy
    """
    comp = compliance or CasterCompliance()
    U = check_speeds(speeds)
    ev = np.linalg.eigvals(relaxed_state_matrices(chair, U, comp, model, pin))
    lead = shimmy_mode(ev)
    rigid = np.linalg.eigvals(state_matrices(chair, U, model)).real.max(axis=-1)
    return ChairShimmy(chair.name, comp, model, pin, U, lead.imag / (2 * math.pi), -lead.real / np.abs(lead),
                       lead.real, _divergence(ev), rigid, chair_critical_trail(chair, U, comp, model, pin),
                       chair.trail)


@dataclass(frozen=True)
class ChairTrailChart:
    """Trail x speed design chart from the chair model with relaxation-length caster tires.

    Attributes
    ----------
    chair_name, model, pin : str
    trails, speeds : ndarray
        Grid (m; m/s).
    divergence_rate : ndarray, shape (len(trails), len(speeds))
        Yaw divergence rate (1/s), largest real part of the chair's own modes.
    shimmy_real_part, shimmy_frequency_hz : ndarray, same shape
        The shimmy mode's real part (1/s; > 0 shimmy) and frequency (Hz).
    critical_trail : ndarray
        Shimmy boundary per speed (m), by bisection.
    compliance : CasterCompliance
    chair_trail : float
        m.
    note : str
    """

    chair_name: str
    model: str
    pin: str
    trails: np.ndarray
    speeds: np.ndarray
    divergence_rate: np.ndarray
    shimmy_real_part: np.ndarray
    shimmy_frequency_hz: np.ndarray
    critical_trail: np.ndarray
    compliance: CasterCompliance
    chair_trail: float
    note: str = ESTIMATE_NOTE


@takes_chair
def chair_trail_chart(chair: Chair, trails: Any, speeds: Any, compliance: CasterCompliance | None = None,
                      model: str = "exact", pin: str = "rigid") -> ChairTrailChart:
    """Yaw divergence and shimmy over trail x speed from the chair model (see :class:`ChairTrailChart`).

    Parameters
    ----------
    chair : Chair
    trails : array_like
        Caster trails (m).
    speeds : array_like
        m/s.
    compliance : CasterCompliance, optional
    model : {"exact", "thesis"}
    pin : {"rigid", "compliant"}

    Returns
    -------
    ChairTrailChart
    """
    comp = compliance or CasterCompliance()
    T = np.atleast_1d(np.asarray(trails, dtype=float))
    U = check_speeds(speeds)
    ev = _grid_eigenvalues(chair, T, U, comp, model, pin)
    lead = shimmy_mode(ev)
    return ChairTrailChart(chair.name, model, pin, T, U, _divergence(ev), lead.real, lead.imag / (2 * math.pi),
                           chair_critical_trail(chair, U, comp, model, pin), comp, chair.trail)
