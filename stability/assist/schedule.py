"""Gain schedule: designs over a speed grid, interpolated linearly in speed."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from .._validate import check_choice, check_speed, check_speeds
from ..chair import Chair
from ..power_chair import DriveTrain
from .design import Design, design, realise
from .plant import Plant, plant
from .weights import DEFAULT_ESTIMATOR, DEFAULT_GYRO, DEFAULT_WEIGHTS, DESIGNS, EstimatorWeights, GyroSensor, Weights

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

    @property
    def gains(self) -> np.ndarray:
        """LQR gains (N, n)."""
        return np.array([d.K[0] for d in self.designs])

    def _interp(self, speed: float, attr: Callable[[Design], np.ndarray | None]) -> np.ndarray:
        stack = np.array([attr(d) for d in self.designs], dtype=float)
        s = float(np.clip(speed, self.speeds[0], self.speeds[-1]))
        if len(self.speeds) == 1:
            return stack[0]
        flat = stack.reshape(len(self.speeds), -1)
        out = np.array([np.interp(s, self.speeds, flat[:, j]) for j in range(flat.shape[1])])
        return out.reshape(stack.shape[1:])

    def gains_at(self, speed: float) -> np.ndarray:
        """LQR gain (1, n) at ``speed`` (m/s): linear interpolation in speed, held at the ends of the grid."""
        return self._interp(check_speed(speed), lambda d: d.K)

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
            m/s.

        Returns
        -------
        Design
        """
        speed = check_speed(speed)
        hit = np.flatnonzero(np.isclose(self.speeds, speed, rtol=0, atol=1e-12))
        if hit.size:
            return self.designs[int(hit[0])]
        K = self._interp(speed, lambda d: d.K)
        true_p = plant(self.chair, speed, self.model, self.drive.motor_time_constant)
        if self.kind == "full-state":
            return realise(self.kind, true_p, K, None)
        L = self._interp(speed, lambda d: d.L)
        A = self._interp(speed, lambda d: d.plant.A)
        B = self._interp(speed, lambda d: d.plant.B)
        p_model = Plant(speed, A, B, true_p.Bf, true_p.motor_time_constant)
        d = realise(self.kind, p_model, K, L)
        return replace(d, plant=true_p)


def schedule(chair: Chair, speeds: Sequence[float] | np.ndarray, kind: str = "gyro", *,
             weights: Weights = DEFAULT_WEIGHTS, drive: DriveTrain | None = None, gyro: GyroSensor = DEFAULT_GYRO,
             estimator: EstimatorWeights = DEFAULT_ESTIMATOR, model: str = "exact") -> Schedule:
    """Design at every speed of an increasing grid (see :class:`Schedule`).

    Parameters
    ----------
    chair : Chair
    speeds : sequence of float
        Strictly increasing design speeds (m/s, > 0).
    kind, weights, drive, gyro, estimator, model
        As :func:`~stability.assist.design.design`.

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
    return Schedule(chair, kind, U, ds, drive, weights, gyro, estimator, model)
