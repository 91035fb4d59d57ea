"""A sampled linear controller that the compiled simulator runs itself (yaw-moment input).

At each sample ``t_k = k T`` (the first step at or after it), with the
simulator's state ``s = [x, y, heading, u, v, yaw_rate, eta, eta_dot, beta,
beta_dot]``::

    y_k     = Cy s + offset + noise[k]              (measurements)
    Mz_k    = sat(Cz z_k + Dy y_k, limit)           (held until the next sample)
    z_{k+1} = Az z_k + Bu Mz_k + By y_k             (controller state, z_0 = 0)

This covers a full-state feedback (``Dy = -K``, no ``z``) and an observer-based
digital controller with one sample of computation delay (``Dy = 0``, ``z`` the
estimate).  See ``docs/simulator.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["STATE_ORDER", "SampledController"]

#: Order of the simulator state the measurement matrix ``Cy`` multiplies.
STATE_ORDER = ("x", "y", "heading", "u", "v", "yaw_rate", "eta", "eta_dot", "beta", "beta_dot")
_NONE: dict[type, SampledController] = {}      # SampledController.none(), per class


def _matrix(a, shape: tuple[int, ...], name: str) -> np.ndarray:
    m = np.ascontiguousarray(np.asarray(a, dtype=float).reshape(shape))
    if not np.all(np.isfinite(m)):
        raise ValueError(f"{name} is invalid; expected finite numbers, shape {shape}")
    return m


@dataclass(frozen=True, eq=False)
class SampledController:
    """Linear sampled controller of the yaw moment (N m), compiled into the simulator.

    Parameters
    ----------
    sample_time : float
        Sample period T, s (> 0).
    Cy : array_like, shape (ny, 10)
        Measurements from the state, in :data:`STATE_ORDER` (SI units).
    Dy : array_like, shape (ny,)
        Direct gain from measurements to the yaw moment, N m per unit.
    Az, Bu, By, Cz : array_like, optional
        Controller state update ``(nz, nz)``, ``(nz,)``, ``(nz, ny)`` and
        output ``(nz,)``; empty (nz = 0) by default.
    limit : float
        Saturation of the yaw moment, N m (default: none).
    offset : array_like, shape (ny,), optional
        Constant added to the measurements (e.g. a gyro bias).
    noise : array_like, shape (nk, ny), optional
        Added to the measurements at samples ``0 .. nk-1`` (zero afterwards).
    name : str
        Recorded in the result's settings.
    state_names : tuple of str
        The state ``Cy`` multiplies (default :data:`STATE_ORDER`; a wheel layout's is
        :func:`stability.simulate.layout.layout_state_order`).
    """

    sample_time: float
    Cy: np.ndarray
    Dy: np.ndarray
    Az: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    Bu: np.ndarray = field(default_factory=lambda: np.zeros(0))
    By: np.ndarray | None = None
    Cz: np.ndarray = field(default_factory=lambda: np.zeros(0))
    limit: float = math.inf
    offset: np.ndarray | None = None
    noise: np.ndarray | None = None
    name: str = "sampled controller"
    state_names: tuple = STATE_ORDER

    def __post_init__(self) -> None:
        ts = float(self.sample_time)
        if not (math.isfinite(ts) and ts > 0):
            raise ValueError(f"sample_time={self.sample_time!r} is invalid; valid range: > 0 s (finite)")
        Cy = np.asarray(self.Cy, dtype=float)
        ny = Cy.shape[0] if Cy.ndim == 2 else 1
        nz = np.asarray(self.Az, dtype=float).reshape(-1).size
        nz = int(round(math.sqrt(nz)))
        set_ = object.__setattr__
        set_(self, "sample_time", ts)
        set_(self, "Cy", _matrix(Cy, (ny, len(self.state_names)), "Cy"))
        set_(self, "Dy", _matrix(self.Dy, (ny,), "Dy"))
        set_(self, "Az", _matrix(self.Az, (nz, nz), "Az"))
        set_(self, "Bu", _matrix(self.Bu, (nz,), "Bu"))
        set_(self, "By", _matrix(np.zeros((nz, ny)) if self.By is None else self.By, (nz, ny), "By"))
        set_(self, "Cz", _matrix(self.Cz, (nz,), "Cz"))
        set_(self, "offset", _matrix(np.zeros(ny) if self.offset is None else self.offset, (ny,), "offset"))
        noise = np.zeros((0, ny)) if self.noise is None else np.asarray(self.noise, dtype=float)
        set_(self, "noise", _matrix(noise, (noise.size // max(ny, 1), ny), "noise"))
        lim = float(self.limit)
        if math.isnan(lim) or lim < 0:
            raise ValueError(f"limit={self.limit!r} is invalid; valid range: >= 0 N m (inf: no saturation)")
        set_(self, "limit", lim)

    @classmethod
    def state_feedback(cls, K, sample_time: float, *, limit: float = math.inf,
                       states: tuple[str, ...] = ("v", "yaw_rate", "eta", "eta_dot", "beta", "beta_dot", "heading"),
                       name: str = "state feedback") -> SampledController:
        """``Mz = sat(-K x(t_k))`` with ``x`` the named states (default: the linear model's six and the heading).

        Parameters
        ----------
        K : array_like, shape (len(states),)
            Gains, N m per state unit.
        sample_time, limit, name
            As the controller's (s, N m).
        states : tuple of str
            Names from :data:`STATE_ORDER`.

        Returns
        -------
        SampledController
        """
        Cy = np.zeros((len(states), len(STATE_ORDER)))
        for i, s in enumerate(states):
            Cy[i, STATE_ORDER.index(s)] = 1.0
        return cls(sample_time, Cy, -np.asarray(K, dtype=float).reshape(-1), limit=limit, name=name)

    @classmethod
    def none(cls) -> SampledController:
        """No controller (the kernel's "no input" arrays): one instance, made on first use (it is frozen and its
        arrays are empty; building it cost about a tenth of a short run's Python work)."""
        c = _NONE.get(cls)
        if c is None:
            c = cls(1.0, np.zeros((0, len(STATE_ORDER))), np.zeros(0), name="none")
            object.__setattr__(c, "sample_time", 0.0)
            _NONE[cls] = c
        return c

    def arrays(self) -> tuple[Any, ...]:
        """``(ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)`` for the kernel; ``ctl_f = [T, limit, *offset]``."""
        ctl_f = np.concatenate([[self.sample_time, self.limit], self.offset])
        return (ctl_f, self.Cy, self.Dy, self.Az, self.Bu, self.By, self.Cz, self.noise)
