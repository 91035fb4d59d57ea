"""The simulator's own linearisation about straight running (central differences of its right-hand side).

On level ground about the casters trailing; on a plane (``slope``) about any
straight-running state (``at``: the lateral velocity and caster angles of an
equilibrium, :mod:`stability.study.slope_stability`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from stability import tires
from stability.chair import Chair
from stability.chair.model import takes_chair
from stability.runtime.checks import check_positive, check_speed
from stability.settings.run import RunSpec
from stability.simulate.adaptive import FREE_POS, LOCKED, AdaptiveModel
from stability.simulate.options import initial_velocities, make_options

__all__ = ["linearise", "forward_acceleration"]


def _rhs(chair: Chair, speed: float, model: str, casters: str, slope: tuple[float, float],
         drive: tuple[float, float]) -> tuple[Any, Any]:
    """``(f, opts)``: the compiled right-hand side of straight running (frictionless pins, no push, the drive held),
    ``f(x, mz) -> dy`` at ``x = [v, r, eta, eta_dot, beta, beta_dot]`` (SI) under the yaw moment ``mz`` (N m)."""
    chair = chair.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    # the defaults, except: the adaptive scheme's right-hand side, no disturbance, the tire-range policy in force
    opts = make_options(RunSpec(speed=speed, horizon=1.0, scheme="adaptive", model=model, casters=casters,
                                push_force=0.0, push_duration=0.0, stop_on_warnings=False,
                                out_of_range=tires.get_policy().evaluation, cross_slope_deg=float(slope[0]),
                                grade_deg=float(slope[1])))
    rhs = AdaptiveModel(chair, speed, opts)
    rhs.hold_drive(float(drive[0]), float(drive[1]))
    modes = (LOCKED, LOCKED) if opts.casters == "locked" else (FREE_POS, FREE_POS)
    u0, _ = initial_velocities(opts, speed)

    def f(x: np.ndarray, mz: float = 0.0) -> np.ndarray:
        rhs.guess[:] = 0.0              # every evaluation solves the load-transfer loop from scratch
        return rhs.point(0.0, np.array([0.0, 0.0, 0.0, u0, *x]), modes, False, mz)[0]

    return f, opts


def forward_acceleration(chair: Chair, speed: float, *, model: str = "exact",
                         slope: tuple[float, float] = (0.0, 0.0), drive: tuple[float, float] = (0.0, 0.0)) -> float:
    """Forward acceleration of straight running, m/s^2: the simulator's right-hand side, loads consistent.

    Casters trailing, no sideslip or yaw, frictionless pins, no push: what
    rolling resistance (with its pitch load transfer) and the in-plane weight
    on a plane do to the forward speed.

    Parameters
    ----------
    chair, speed, model, slope, drive
        As in :func:`linearise` (m/s; deg; N).

    Returns
    -------
    float
        ``u_dot``, m/s^2.
    """
    f, _ = _rhs(chair, check_speed(speed), model, "free", slope, drive)
    return float(f(np.zeros(6))[3])


@takes_chair
def linearise(chair: Chair, speed: float, *, model: str = "exact", casters: str = "free",
              step: float = 1e-6, slope: tuple[float, float] = (0.0, 0.0),
              at: tuple[float, float, float] = (0.0, 0.0, 0.0), drive: tuple[float, float] = (0.0, 0.0)) -> Any:
    """The simulator's own linearisation about straight running, by central differences.

    Differentiates the right-hand side the simulator integrates (the adaptive
    scheme's, whose normal loads are solved consistently with the tire
    forces) with respect to ``[v, r, eta, eta_dot, beta, beta_dot]`` (free
    casters) or ``[v, r]`` (locked) and the yaw-moment input, at forward
    speed ``speed`` held fixed, casters trailing, no disturbance.  Unlike
    :func:`stability.linear.state_space` it keeps everything the simulator
    has: rolling resistance (drag on the casters, pitch load transfer),
    camber and toe with the lateral load transfer they couple to, and each
    tire's force law at its actual (not static) load.  Pins are taken as
    frictionless (Coulomb friction has no linearisation) and without the
    linear models' viscous ``pin_damping``, which the simulator does not have.

    Parameters
    ----------
    chair : Chair
        The chair (pin friction is set to zero).
    speed : float
        Forward speed, m/s (> 0).
    model : {"thesis", "exact"}
        Equation variant.
    casters : {"free", "locked"}
        Free or locked casters.
    step : float
        Central-difference step in the state units (m/s, rad/s, rad); the
        slip angles stay far inside the first degree, where the tire model
        is linear in slip.
    slope : tuple of float
        ``(cross_slope_deg, grade_deg)`` of the plane seen from the chair's
        heading, deg (as :func:`stability.simulate.simulate`; needs
        ``model="exact"``).
    at : tuple of float
        The operating point: lateral velocity, m/s, and the left and right
        caster angles, rad (yaw rate and swivel rates zero); default the
        casters trailing with no sideslip.
    drive : tuple of float
        Drive forces on the left and right main wheels held constant, N (the
        statics' drive that holds a slope's equilibrium; the simulator's runs
        have none).

    Returns
    -------
    control.StateSpace
        Same states, input ``Mz`` (N m) and outputs ``v``, ``r`` as
        :func:`stability.linear.state_space`.
    """
    import control  # python-control is only needed here

    speed = check_speed(speed)
    step = check_positive("step", step)
    f, opts = _rhs(chair, speed, model, casters, slope, drive)
    x0 = np.array([at[0], 0.0, at[1], 0.0, at[2], 0.0])

    def derivative(dx, mz=0.0):
        return np.array(f(x0 + np.pad(dx, (0, 6 - len(dx))), mz)[4:4 + len(dx)], dtype=float)

    n = 2 if opts.casters == "locked" else 6
    eye = np.eye(n) * step
    A = np.column_stack([(derivative(eye[j]) - derivative(-eye[j])) / (2.0 * step) for j in range(n)])
    B = ((derivative(np.zeros(n), 1.0) - derivative(np.zeros(n), -1.0)) / 2.0)[:, None]
    states = ["v", "r", "eta", "eta_dot", "beta", "beta_dot"][:n]
    C = np.zeros((2, n))
    C[0, 0] = C[1, 1] = 1.0
    name = f"{chair.name} (simulator {opts.model}, {opts.casters} casters, U={speed:g} m per s)".replace(".", "p")
    return control.ss(A, B, C, np.zeros((2, 1)), states=states, inputs=["Mz"], outputs=["v", "r"], name=name)
