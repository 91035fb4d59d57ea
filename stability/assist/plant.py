"""The design plant: the linear chair model at one speed, augmented with the heading.

States ``[v, r, eta, eta_dot, beta, beta_dot, psi]`` (:data:`STATES`), inputs
the yaw moment ``Mz`` of the differential drive torque and a lateral force
``Fy`` at the c.g.  Rationale in ``docs/assist.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import control
import numpy as np

from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.linear import input_matrices, lateral_force_input, state_matrices
from stability.runtime.checks import check_model, check_nonnegative, check_speed

__all__ = ["STATES", "MOTOR_STATE", "YAW_LOOP", "Plant", "plant", "standstill_plant", "pivot_inertia", "reversed_chair",
           "measurement_matrix", "system_name"]

#: States of the design plant (SI units: m/s, rad/s, rad, rad/s, rad, rad/s, rad).
STATES = ("v", "r", "eta", "eta_dot", "beta", "beta_dot", "psi")
#: The eighth state when the drive has a motor lag: the yaw moment the wheels apply (N m).
MOTOR_STATE = "mz"
#: States of the standstill (kinematic) plant's yaw loop: ``r``, ``psi`` and, with a motor lag, ``mz``.
YAW_LOOP = ("r", "psi", "mz")


@dataclass(frozen=True, eq=False)
class Plant:
    """Linear plant at one speed, augmented with the heading (and the motor lag).

    Attributes
    ----------
    speed : float
        Forward speed (m/s).
    A : ndarray (n, n)
        State matrix for :attr:`states` (1/s); n = 7, or 8 with a motor lag.
    B : ndarray (n, 1)
        Yaw-moment command ``Mz`` (per N m).
    Bf : ndarray (n, 1)
        Lateral force at the c.g. ``Fy`` (per N).
    motor_time_constant : float
        First-order lag between the yaw-moment command and the moment the
        wheels apply (s); 0: none (seven states).
    chair_states : tuple of str
        Names of the chair's own states, which come first (the short form's six of :data:`STATES`; a wheel
        layout's ``v, r`` and each caster's angle and rate, :func:`stability.layout.linear.states`); the heading
        follows them, then the motor state.
    """

    speed: float
    A: np.ndarray
    B: np.ndarray
    Bf: np.ndarray
    motor_time_constant: float = 0.0
    chair_states: tuple[str, ...] = STATES[:6]

    @property
    def n(self) -> int:
        """Number of states."""
        return int(self.A.shape[0])

    @property
    def psi(self) -> int:
        """Index of the heading: after the chair's states."""
        return len(self.chair_states)

    @property
    def has_motor(self) -> bool:
        """Whether the last state is the motor lag's applied moment."""
        return self.n == self.psi + 2

    @property
    def states(self) -> tuple[str, ...]:
        """State names: the chair's, the heading, plus :data:`MOTOR_STATE` with a motor lag."""
        return self.chair_states + ("psi",) + ((MOTOR_STATE,) if self.has_motor else ())

    @property
    def internal(self) -> list[int]:
        """Indices of the states a controller models internally: all but the heading."""
        return [i for i in range(self.n) if i != self.psi]

    @property
    def A6(self) -> np.ndarray:
        """State matrix of the chair's states (without the heading and the motor; six for the short form)."""
        return self.A[:self.psi, :self.psi]

    @property
    def B6(self) -> np.ndarray:
        """Column of the applied yaw moment in the chair's states (per N m)."""
        return self.A[:self.psi, self.psi + 1:self.psi + 2] if self.has_motor else self.B[:self.psi]

    @property
    def Bf6(self) -> np.ndarray:
        """Lateral-force column of the chair's states."""
        return self.Bf[:self.psi]

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
            C, names = np.eye(self.n), list(self.states)
        elif outputs == "gyro":
            C, names = measurement_matrix("gyro", self.n, self.psi), ["r", "psi"]
        else:
            raise ValueError(f"outputs={outputs!r} is invalid; valid choices: ['states', 'gyro']")
        return control.ss(self.A, Bu, C, np.zeros((C.shape[0], 2)), states=list(self.states),
                          inputs=["Mz", "Fy"], outputs=names, name=system_name("chair", self.speed))


def system_name(prefix: str, speed: float) -> str:
    """A python-control system name (no dots allowed), e.g. ``chair_U0p75``.

    Parameters
    ----------
    prefix : str
        Start of the name.
    speed : float
        Forward speed (m/s).

    Returns
    -------
    str
    """
    return f"{prefix}_U{speed:g}".replace(".", "p").replace("-", "_")


def measurement_matrix(kind: str, n: int = 7, psi: int = 6) -> np.ndarray:
    """What the controller measures of the ``n`` plant states: all (``"full-state"``) or ``[r, psi]`` (``"gyro"``).

    Parameters
    ----------
    kind : {"full-state", "gyro"}
    n : int
        Number of plant states (7, or 8 with a motor lag; a layout's own count).
    psi : int
        Index of the heading (6: after the short form's six chair states; ``r`` is always index 1).

    Returns
    -------
    ndarray (n, n) or (2, n)
    """
    if kind == "full-state":
        return np.eye(n)
    C = np.zeros((2, n))
    C[0, 1] = C[1, psi] = 1.0
    return C


@takes_chair
def plant(chair: Chair, speed: float, model: str = "exact", motor_time_constant: float = 0.0) -> Plant:
    """Linear plant of ``chair`` at ``speed``, augmented with the heading and, optionally, a motor lag.

    With ``motor_time_constant = tau > 0`` the eighth state is the applied
    yaw moment ``mz``, ``mz_dot = (Mz - mz) / tau`` (the motors' speed or
    current loop as a first-order lag), and the chair is driven by ``mz``.

    Parameters
    ----------
    chair : Chair
    speed : float
        Forward speed (m/s, > 0).
    model : {"exact", "thesis"}
        Equations of motion (:func:`stability.linear.state_matrices`).
    motor_time_constant : float
        s, >= 0.

    Returns
    -------
    Plant
    """
    speed = check_speed(speed)
    check_model(model)
    tau = check_nonnegative("motor_time_constant", motor_time_constant)
    A6 = state_matrices(chair, speed, model)[0]
    B6 = input_matrices(chair, speed, model)[0]
    n = 8 if tau > 0 else 7
    A = np.zeros((n, n))
    A[:6, :6] = A6
    A[6, 1] = 1.0
    B = np.zeros((n, 1))
    if tau > 0:
        A[:6, 7:8] = B6
        A[7, 7] = -1.0 / tau
        B[7, 0] = 1.0 / tau
    else:
        B[:6] = B6
    Bf = np.zeros((n, 1))
    Bf[:6, 0] = lateral_force_input(chair, speed, model)
    return Plant(speed, A, B, Bf, tau)


@takes_chair
def pivot_inertia(chair: Chair) -> float:
    """Yaw inertia about the midpoint of the drive axle, ``J = I_z + m s1^2`` (kg m^2; parallel axes).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    float
    """
    return float(chair.i_z + chair.m * chair.x_main ** 2)


@takes_chair
def standstill_plant(chair: Chair, motor_time_constant: float = 0.0, yaw_damping: float = 0.0) -> Plant:
    """The kinematic differential-drive plant, valid at standstill and in the low-speed limit.

    The tire terms of the linear model go like ``C/U``: as ``U -> 0`` the
    drive tires' lateral slip modes become infinitely fast (``-C/(m U)``),
    so the drive axle rolls without side slip (``v + x_main r = 0``), and
    every other mode scales with the distance travelled (``lambda = kappa
    U``: the casters' swivel at ``-U/trail``, the chair's divergence).  What
    is left at ``U = 0`` is the pivot about the drive-axle midpoint,
    ``J r_dot = mz - c_r r`` (:func:`pivot_inertia`; ``c_r`` the yaw
    damping of tire scrub and caster pin friction, 0 by default: no help
    assumed).  ``docs/assist.md`` has the argument and the check against
    the linear model at 0.02-0.25 m/s.

    States as :func:`plant` (speed 0): ``v = -x_main r`` is slaved to the
    yaw rate (its row is ``-x_main`` times the ``r`` row), and the caster
    rows are zero: at standstill a swivelled caster stays where it is (its
    modes ``-U/trail`` are at 0) and, rolling freely, puts no lateral force
    on the chair.  Only the yaw loop :data:`YAW_LOOP` is controllable.
    A lateral force at the c.g. acts with the lever ``x_main`` about the axle.

    Parameters
    ----------
    chair : Chair
    motor_time_constant : float
        s, >= 0 (as :func:`plant`).
    yaw_damping : float
        ``c_r`` (N m s/rad, >= 0).

    Returns
    -------
    Plant
    """
    tau = check_nonnegative("motor_time_constant", motor_time_constant)
    c_r = check_nonnegative("yaw_damping", yaw_damping)
    J, x = pivot_inertia(chair), chair.x_main
    n = 8 if tau > 0 else 7
    A, B, Bf = np.zeros((n, n)), np.zeros((n, 1)), np.zeros((n, 1))
    A[1, 1] = -c_r / J
    Bf[1, 0] = -x / J
    if tau > 0:
        A[1, 7] = 1.0 / J
        A[7, 7], B[7, 0] = -1.0 / tau, 1.0 / tau
    else:
        B[1, 0] = 1.0 / J
    A[0], B[0], Bf[0] = -x * A[1], -x * B[1], -x * Bf[1]
    A[6, 1] = 1.0
    return Plant(0.0, A, B, Bf, tau)


@takes_chair
def reversed_chair(chair: Chair) -> Chair:
    """The chair as seen when it drives backwards: casters and main wheels swap ends.

    Body axes turned by 180 deg about z (x and y flip, z stays down): the
    main axle is on the other side of the c.g., the caster pins on the other
    side, so ``caster_position`` swaps; left and right swap (``d1 <-> d2``,
    ``t1 <-> t2``, the pin frictions); the free casters swing round to trail in
    the new direction of travel, so ``trail`` and the caster properties are
    unchanged.  Each caster's c.g. (``l1`` from its pin) swings with it, by
    ``2 l1`` towards the old front: the system c.g. moves by
    ``dx = 2 m_c 2 l1 / m`` that way (``s1`` and ``s2`` change by ``dx``) and
    the yaw inertia about the new c.g. is ``i_z + sum m_c ((x_pin + l1)^2 -
    (x_pin - l1)^2) - m dx^2`` (parallel axes; ``x_pin`` the pins' signed
    position).  Mass and tires stay.  Its forward linear model is the chair's
    at the negative speed (:func:`stability.layout.linear.state_matrices`, which
    derives the reverse from first principles; tested).

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    Chair
    """
    dx = 2.0 * chair.m_c * 2.0 * chair.l1 / chair.m        # m, towards the old front (+x)
    i_z = chair.i_z + 2.0 * chair.m_c * 4.0 * chair.x_pin * chair.l1 - chair.m * dx * dx   # kg m^2
    sigma = 1.0 if chair.caster_position == "rear" else -1.0   # the main axle ahead of the c.g. (rear casters)
    return chair.replace(caster_position="front" if chair.caster_position == "rear" else "rear",
                         s1=chair.s1 - sigma * dx, s2=chair.s2 + sigma * dx, i_z=i_z,
                         d1=chair.d2, d2=chair.d1, t1=chair.t2, t2=chair.t1,
                         pin_friction_left=chair.pin_friction_right, pin_friction_right=chair.pin_friction_left,
                         name=f"{chair.name} (reversing)")
