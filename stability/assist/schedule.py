"""Gain schedule: designs over a speed grid, interpolated linearly in speed."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from stability.assist.design import Design, design, on_drive, realise
from stability.assist.plant import Plant, plant
from stability.assist.weights import (
    DEFAULT_ESTIMATOR,
    DEFAULT_GYRO,
    DEFAULT_WEIGHTS,
    DESIGNS,
    EstimatorWeights,
    GyroSensor,
    Weights,
)
from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.chair.power import DriveTrain
from stability.runtime.checks import check_choice, check_nonnegative, check_speeds

__all__ = ["Schedule", "schedule"]


@dataclass(frozen=True, eq=False)
class Schedule:
    """Designs over a speed grid and their interpolation.

    Attributes
    ----------
    chair : Chair
        The nominal chair.
    kind : {"full-state", "gyro"}
        Feedback structure.
    speeds : ndarray (N,)
        Increasing design speeds (m/s).
    designs : tuple of Design
        One per speed.
    drive : DriveTrain
        Drive wheels and motors.
    weights, gyro, estimator, model
        The design options.
    standstill : Design or None
        The design at 0 m/s on the kinematic plant
        (:func:`~stability.assist.plant.standstill_plant`); below the first
        grid speed the controller is interpolated between it and the first
        design.  None: the first design's gains are held below it.
    """

    chair: Chair
    kind: str
    speeds: np.ndarray
    designs: tuple[Design, ...]
    drive: DriveTrain
    weights: Weights
    gyro: GyroSensor
    estimator: EstimatorWeights
    model: str
    standstill: Design | None = None

    @property
    def gains(self) -> np.ndarray:
        """LQR gains (N, n)."""
        return np.array([d.K[0] for d in self.designs])

    @property
    def grid(self) -> tuple[np.ndarray, tuple[Design, ...]]:
        """Speeds (m/s) and designs the interpolation uses: the standstill design (if any) and the grid."""
        if self.standstill is None:
            return self.speeds, self.designs
        return np.concatenate([[0.0], self.speeds]), (self.standstill, *self.designs)

    def _interp(self, speed: float, attr: Callable[[Design], np.ndarray | None]) -> np.ndarray:
        speeds, designs = self.grid
        stack = np.array([attr(d) for d in designs], dtype=float)
        s = float(np.clip(speed, speeds[0], speeds[-1]))
        if len(speeds) == 1:
            return stack[0]
        flat = stack.reshape(len(speeds), -1)
        out = np.array([np.interp(s, speeds, flat[:, j]) for j in range(flat.shape[1])])
        return out.reshape(stack.shape[1:])

    def gains_at(self, speed: float) -> np.ndarray:
        """LQR gain (1, n) at ``speed``: linear interpolation in speed, held at the ends of the grid.

        Parameters
        ----------
        speed : float
            m/s, >= 0.

        Returns
        -------
        ndarray (1, n)
        """
        return self._interp(check_nonnegative("speed", speed), lambda d: d.K)

    def _check_speed(self, speed: float) -> float:
        """A speed of :meth:`at` (m/s, >= 0)."""
        return check_nonnegative("speed", speed)

    def true_plant(self, speed: float) -> Plant:
        """The true linear plant at ``speed`` (m/s): the chair's, with the drive's motor lag.

        Parameters
        ----------
        speed : float
            m/s.

        Returns
        -------
        Plant
        """
        return plant(self.chair, speed, self.model, self.drive.motor_time_constant)

    def at(self, speed: float) -> Design:
        """The scheduled controller at ``speed`` (m/s).

        Grid speeds give the designs themselves; between them the gains
        ``K`` and ``L`` and the estimator's model matrices (``A``, ``B`` of
        the plant) are interpolated entrywise, which is what a controller
        that stores tables does.  The ``plant`` of the returned design is
        the true linear plant at ``speed``.

        Parameters
        ----------
        speed : float
            m/s (0: the standstill design, when there is one).

        Returns
        -------
        Design
        """
        speed = self._check_speed(speed)
        speeds, designs = self.grid
        hit = np.flatnonzero(np.isclose(speeds, speed, rtol=0, atol=1e-12))
        if hit.size:
            return designs[int(hit[0])]           # designed with self.gyro: its sample time already
        if speed == 0:
            raise ValueError("speed=0 is invalid without a standstill design; valid range: > 0 m/s")
        K = self._interp(speed, lambda d: d.K)
        true_p = self.true_plant(speed)
        if self.kind == "full-state":
            return on_drive(realise(self.kind, true_p, K, None), self.gyro, self.drive, self.chair)
        L = self._interp(speed, lambda d: d.L)
        A = self._interp(speed, lambda d: d.plant.A)
        B = self._interp(speed, lambda d: d.plant.B)
        p_model = Plant(speed, A, B, true_p.Bf, true_p.motor_time_constant, true_p.chair_states)
        d = realise(self.kind, p_model, K, L)
        return on_drive(replace(d, plant=true_p), self.gyro, self.drive, self.chair)


@takes_chair
def schedule(chair: Chair, speeds: Sequence[float] | np.ndarray, kind: str = "gyro", *,
             weights: Weights = DEFAULT_WEIGHTS, drive: DriveTrain | None = None, gyro: GyroSensor = DEFAULT_GYRO,
             estimator: EstimatorWeights = DEFAULT_ESTIMATOR, model: str = "exact",
             standstill: bool = True) -> Schedule:
    """Design at every speed of an increasing grid (see :class:`Schedule`).

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float
        Strictly increasing design speeds (m/s, > 0).
    kind, weights, drive, gyro, estimator, model
        As :func:`~stability.assist.design.design`.
    standstill : bool
        Add the standstill design at 0 m/s (:attr:`Schedule.standstill`) so
        the schedule covers 0 up; False holds the first design's gains below
        the first grid speed.

    Returns
    -------
    Schedule
    """
    check_choice("design", kind, DESIGNS)
    U = np.asarray(speeds, dtype=float).reshape(-1)
    if U.size == 0:
        raise ValueError("speeds: expected at least one speed")
    check_speeds(U)
    if np.any(np.diff(U) <= 0):
        raise ValueError("speeds must be strictly increasing")
    drive = drive or DriveTrain()
    ds = tuple(design(chair, s, kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator, model=model)
               for s in U)
    still = design(chair, 0.0, kind, weights=weights, drive=drive, gyro=gyro, estimator=estimator, model=model) \
        if standstill else None
    return Schedule(chair, kind, U, ds, drive, weights, gyro, estimator, model, still)
