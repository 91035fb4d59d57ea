"""Classical root locus of yaw-rate feedback through the yaw-moment input, ``Mz = -K r``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.linear import input_matrices, state_matrices, state_space, track_modes
from stability.rootlocus.speed import readonly
from stability.runtime.checks import check_casters, check_model, check_speed
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["GainLocus", "gain_locus", "closed_loop_matrices"]


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


@takes_chair
def closed_loop_matrices(chair: Chair, speed: float, gains, *, model: str = "exact",
                         casters: str = "free") -> np.ndarray:
    """Closed-loop state matrices ``A - K B C_r`` of yaw-rate feedback ``Mz = -K r``, one per gain.

    Parameters
    ----------
    chair : Chair
        The chair.
    speed : float
        Forward speed U, m/s (> 0).
    gains : float or array_like
        Feedback gains K, N m s/rad.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Caster state (default ``"free"``).

    Returns
    -------
    numpy.ndarray
        Shape (N, n, n) for N gains: ``A - K B C_r`` with B the yaw-moment input
        column and C_r the row selecting the yaw rate r (state 1).
    """
    A = state_matrices(chair, speed, model, casters)[0]
    B = input_matrices(chair, speed, model, casters)[0]
    C = np.zeros((1, A.shape[0]))
    C[0, 1] = 1.0
    K = np.atleast_1d(np.asarray(gains, dtype=float))
    return A[None] - K[:, None, None] * (B @ C)[None]


def _stabilising_gain(chair, speed, model, casters, gains) -> float | None:
    from scipy.optimize import brentq  # deferred: scipy.optimize costs ~0.4 s to import

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


@takes_chair
def gain_locus(chair: Chair, speed: float = REFERENCE_SPEED, gains=None, *, model: str = "exact",
               casters: str = "free", max_gain: float = 300.0, n: int = 400) -> GainLocus:
    """Root locus of yaw-rate feedback through the yaw-moment input, with :func:`control.root_locus_map`.

    ``G(s) = r(s) / Mz(s)`` is the linear model's yaw-rate response to a yaw
    moment on the chair; ``control.root_locus_map`` returns the roots of
    ``1 + K G(s)``, i.e. the poles with ``Mz = -K r``.

    Parameters
    ----------
    chair : Chair
        The chair (open-loop plant).
    speed : float, optional
        Forward speed U, m/s (> 0); default 0.75 m/s.
    gains : array_like, optional
        Gains K >= 0 (N m s/rad), increasing; default 0 and ``n`` values
        geometrically spaced from 0.1 to ``max_gain``.
    model : {"exact", "thesis"}, optional
        Equation variant (default ``"exact"``).
    casters : {"free", "locked"}, optional
        Caster state (default ``"free"``).
    max_gain : float, optional
        Largest default gain, N m s/rad (default 300); ignored when ``gains`` is given.
    n : int, optional
        Number of geometrically spaced default gains (default 400); ignored when ``gains`` is given.

    Returns
    -------
    GainLocus
        Gains, tracked closed-loop poles (1/s), open-loop poles and zeros, and
        the smallest stabilising gain (N m s/rad) when there is one.

    Raises
    ------
    ValueError
        If ``gains`` is not an increasing 1-D array of values >= 0, or the
        speed, model or caster state is invalid.
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
    return GainLocus(chair, model, casters, speed, readonly(K), readonly(loci),
                     readonly(np.asarray(rl.poles)), readonly(np.asarray(rl.zeros)), k_stab)
