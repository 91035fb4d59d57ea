"""The linear full-width model: state-space matrices at many speeds, and its input columns.

Straight-line motion at forward speed U with the casters trailing; each tire's
lateral force linear in its slip angle with the cornering stiffness of its fit
at its static load (:func:`stability.models.statics.static_stiffness`); viscous pin
damping ``Chair.pin_damping`` (Coulomb friction has no linearisation).  States
(free casters) ``[v, r, eta, eta_dot, beta, beta_dot]`` (m/s, rad/s, rad,
rad/s, rad, rad/s); locked casters ``[v, r]``.  See ``docs/linear.md``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from stability.chair import Chair, check_chair
from stability.chair.model import takes_chair, takes_chairs
from stability.models import accelerations, linear_matrices
from stability.models.params import parameters
from stability.models.statics import static_stiffness
from stability.runtime.checks import check_casters, check_model, check_speed

__all__ = ["STATES_FREE", "STATES_LOCKED", "state_matrices", "input_matrices", "state_space",
           "lateral_force_input"]

STATES_FREE = ("v", "r", "eta", "eta_dot", "beta", "beta_dot")
STATES_LOCKED = ("v", "r")


def _stiffness_for(chairs: Chair | Sequence[Chair]) -> dict:
    if isinstance(chairs, Chair):
        return static_stiffness(chairs)
    rows = [static_stiffness(c) for c in chairs]
    return {k: np.array([r[k] for r in rows]) for k in ("A", "B", "D", "E")}


def _solve(M: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``M^-1 rhs`` batched over the leading axes of ``rhs``.

    The mass matrix of the linear model does not depend on speed: when it is a
    single (k, k) matrix (one chair) it is inverted once and every speed's
    right-hand side is multiplied by that inverse.  The mass matrix is symmetric
    positive definite and well conditioned (about 1e4 for the presets), so the
    explicit inverse costs no accuracy that matters next to the eigenvalue
    problem, and is several times faster than a batched solve.
    """
    if M.ndim == 2:
        return np.linalg.inv(M) @ rhs
    return np.linalg.solve(M, rhs)


def _assemble(M: np.ndarray, K: np.ndarray, Bm: np.ndarray, casters: str):
    """State and input matrices from ``M acc = K x + Bm u``."""
    sol = _solve(M, np.concatenate([K, Bm[..., None]], axis=-1))
    F, G = sol[..., :-1], sol[..., -1]
    shape = K.shape[:-2]
    if casters == "locked":
        return F, G[..., None]
    n = 6
    A = np.zeros(shape + (n, n))
    B = np.zeros(shape + (n, 1))
    A[..., 0, :] = F[..., 0, :]
    A[..., 1, :] = F[..., 1, :]
    A[..., 2, 3] = 1.0
    A[..., 3, :] = F[..., 2, :]
    A[..., 4, 5] = 1.0
    A[..., 5, :] = F[..., 3, :]
    B[..., 0, 0], B[..., 1, 0], B[..., 3, 0], B[..., 5, 0] = G[..., 0], G[..., 1], G[..., 2], G[..., 3]
    return A, B


def _matrices(chairs, speeds, model: str, casters: str):
    p = parameters(chairs)
    M, K, Bm = linear_matrices(p, speeds, _stiffness_for(chairs), variant=model, casters=casters)
    return _assemble(M, K, Bm, casters)


@takes_chairs
def state_matrices(chair: Chair | Sequence[Chair], speeds, model: str = "exact",
                   casters: str = "free") -> np.ndarray:
    """State matrices for many speeds (and chairs) in one batched call.

    Parameters
    ----------
    chair : Chair or sequence of Chair
        One chair, or N chairs (then ``speeds`` broadcasts against them).
    speeds : float or array_like
        Forward speeds U > 0 (m/s).
    model : {"exact", "thesis"}
        Equation variant (see :mod:`stability.models`).
    casters : {"free", "locked"}
        Free (6 states) or locked (2 states) casters.

    Returns
    -------
    ndarray
        Shape (N, n, n) with n = 6 (free) or 2 (locked), units of 1/s and
        their ratios (SI).
    """
    return _matrices(chair, speeds, model, casters)[0]


@takes_chairs
def input_matrices(chair: Chair | Sequence[Chair], speeds, model: str = "exact",
                   casters: str = "free") -> np.ndarray:
    """Input matrices for a yaw moment on the chair.

    Parameters
    ----------
    chair : Chair or sequence of Chair
    speeds : float or array_like
        Forward speeds (m/s).
    model : {"exact", "thesis"}
    casters : {"free", "locked"}

    Returns
    -------
    ndarray
        Shape (N, n, 1): state derivatives per N m of yaw moment.
    """
    return _matrices(chair, speeds, model, casters)[1]


@takes_chair
def state_space(chair: Chair, speed: float, model: str = "exact", casters: str = "free"):
    """Linearised model at one speed as a :class:`control.StateSpace`.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed (m/s), > 0.
    model : {"exact", "thesis"}
    casters : {"free", "locked"}

    Returns
    -------
    control.StateSpace
        States ``[v, r, eta, eta_dot, beta, beta_dot]`` (free) or ``[v, r]``
        (locked), input ``Mz`` (yaw moment on the chair, N m), outputs ``v``
        (m/s) and ``r`` (rad/s).

    Raises
    ------
    TypeError
        ``chair`` is not a Chair.
    ValueError
        ``speed`` outside 0.01-100 m/s, or an unknown ``model`` or ``casters`` (named, with the valid values).
    """
    chair = check_chair(chair)
    speed = check_speed(speed)
    model, casters = check_model(model), check_casters(casters)
    import control  # python-control costs ~0.3 s to import; only this function needs it

    A, B = _matrices(chair, speed, model, casters)
    A, B = A[0], B[0]
    states = list(STATES_FREE if casters == "free" else STATES_LOCKED)
    C = np.zeros((2, len(states)))
    C[0, 0] = C[1, 1] = 1.0
    D = np.zeros((2, 1))
    # python-control forbids '.' in system names
    name = f"{chair.name} ({model}, {casters} casters, U={speed:g} m per s)".replace(".", "p")
    return control.ss(A, B, C, D, states=states, inputs=["Mz"], outputs=["v", "r"], name=name)


@takes_chair
def lateral_force_input(chair: Chair, speed: float, model: str = "exact", casters: str = "free") -> np.ndarray:
    """Input column of the linear model for a lateral force at the c.g. (state derivatives per N).

    From the nonlinear equations of motion, which are exactly linear in the
    external force: the accelerations produced by a unit lateral force at the
    c.g. in straight-line motion with no tire forces.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed (m/s).
    model : {"exact", "thesis"}
    casters : {"free", "locked"}

    Returns
    -------
    ndarray
        Shape (n,): ``[v, r, eta, eta_dot, beta, beta_dot]`` rows (free) or
        ``[v, r]`` (locked), in (m/s^2, rad/s^2, ...) per N.
    """
    check_model(model)
    check_casters(casters)
    U = check_speed(speed)
    if casters == "locked":
        return np.array([1.0 / chair.m, 0.0])
    p = parameters(chair)
    z = 0.0
    args = (p, U, z, z, 1.0, z, 1.0, z, z, z) + (z,) * 10
    a1 = accelerations(*args, Fy_ext=1.0, Mz_ext=0.0, variant=model)
    a0 = accelerations(*args, Fy_ext=0.0, Mz_ext=0.0, variant=model)
    d = [float(x1) - float(x0) for x1, x0 in zip(a1, a0, strict=True)]  # u_dot, v_dot, r_dot, eta_dd, beta_dd
    return np.array([d[1], d[2], 0.0, d[3], 0.0, d[4]])
