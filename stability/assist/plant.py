"""The design plant: the linear chair model at one speed, augmented with the heading.

States ``[v, r, eta, eta_dot, beta, beta_dot, psi]`` (:data:`STATES`), inputs
the yaw moment ``Mz`` of the differential drive torque and a lateral force
``Fy`` at the c.g.  Rationale in ``docs/assist.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import control
import numpy as np

from .._validate import check_model, check_speed
from ..chair import Chair
from ..linear import input_matrices, state_matrices
from ..models import accelerations
from ..params import parameters

__all__ = ["STATES", "Plant", "plant", "lateral_force_column", "measurement_matrix", "system_name"]

#: States of the design plant (SI units: m/s, rad/s, rad, rad/s, rad, rad/s, rad).
STATES = ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "psi")


@dataclass(frozen=True, eq=False)
class Plant:
    """Linear plant at one speed, augmented with the heading.

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    A : ndarray (7, 7)
        State matrix for :data:`STATES` (1/s).
    B : ndarray (7, 1)
        Yaw-moment input ``Mz`` (per N m).
    Bf : ndarray (7, 1)
        Lateral force at the c.g. ``Fy`` (per N).
    """

    speed: float
    A: np.ndarray
    B: np.ndarray
    Bf: np.ndarray

    @property
    def A6(self) -> np.ndarray:
        """State matrix of the six chair states (without the heading)."""
        return self.A[:6, :6]

    @property
    def B6(self) -> np.ndarray:
        """Yaw-moment column of the six chair states."""
        return self.B[:6]

    @property
    def Bf6(self) -> np.ndarray:
        """Lateral-force column of the six chair states."""
        return self.Bf[:6]

    def ss(self, outputs: str = "states") -> control.StateSpace:
        """:class:`control.StateSpace` with inputs ``Mz``, ``Fy``.

        Parameters
        ----------
        outputs : {"states", "gyro"}
            ``"states"``: all seven states; ``"gyro"``: ``r`` and ``psi``.

        Returns
        -------
        control.StateSpace
        """
        Bu = np.hstack([self.B, self.Bf])
        if outputs == "states":
            C, names = np.eye(7), list(STATES)
        elif outputs == "gyro":
            C, names = measurement_matrix("gyro"), ["r", "psi"]
        else:
            raise ValueError(f"outputs={outputs!r} is invalid; valid choices: ['states', 'gyro']")
        return control.ss(self.A, Bu, C, np.zeros((C.shape[0], 2)), states=list(STATES),
                          inputs=["Mz", "Fy"], outputs=names, name=system_name("chair", self.speed))


def system_name(prefix: str, speed: float) -> str:
    """A python-control system name (no dots allowed), e.g. ``chair_U0p75``."""
    return f"{prefix}_U{speed:g}".replace(".", "p").replace("-", "_")


def measurement_matrix(kind: str) -> np.ndarray:
    """What the controller measures of :data:`STATES`: all (``"full-state"``) or ``[r, psi]`` (``"gyro"``)."""
    if kind == "full-state":
        return np.eye(7)
    C = np.zeros((2, 7))
    C[0, 1] = C[1, 6] = 1.0
    return C


def lateral_force_column(chair: Chair, speed: float, model: str = "exact") -> np.ndarray:
    """Response ``d(x_dot)/d(Fy)`` (6,) of the six chair states to a lateral force at the c.g.

    The equations of motion (:func:`stability.models.accelerations`) are
    linear in the external loads at a fixed state, so the difference of the
    accelerations with ``Fy = 1 N`` and ``Fy = 0`` in straight running is
    the exact input column.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed (m/s).
    model : {"exact", "thesis"}

    Returns
    -------
    ndarray (6,)
        Per N, on ``[v, r, eta, eta_dot, beta, beta_dot]``.
    """
    p = parameters(chair)
    z = 0.0

    def acc(fy: float) -> np.ndarray:
        return np.array(accelerations(p, speed, z, z, 1.0, z, 1.0, z, z, z,
                                      z, z, z, z, z, z, z, z, z, z,
                                      Fy_ext=fy, Mz_ext=0.0, variant=model), dtype=float)

    d = acc(1.0) - acc(0.0)   # (u_dot, v_dot, r_dot, eta_dd, beta_dd)
    return np.array([d[1], d[2], 0.0, d[3], 0.0, d[4]])


def plant(chair: Chair, speed: float, model: str = "exact") -> Plant:
    """Linear plant of ``chair`` at ``speed``, augmented with the heading.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed (m/s, > 0).
    model : {"exact", "thesis"}
        Equations of motion (:func:`stability.linear.state_matrices`).

    Returns
    -------
    Plant
    """
    speed = check_speed(speed)
    check_model(model)
    A6 = state_matrices(chair, speed, model)[0]
    B6 = input_matrices(chair, speed, model)[0]
    A = np.zeros((7, 7))
    A[:6, :6] = A6
    A[6, 1] = 1.0
    B = np.zeros((7, 1))
    B[:6] = B6
    Bf = np.zeros((7, 1))
    Bf[:6, 0] = lateral_force_column(chair, speed, model)
    return Plant(speed, A, B, Bf)
