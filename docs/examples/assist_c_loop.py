"""
The exported C assist in a tiny simulation loop
===============================================

Export the power-fwd chair's gyro assist as C (``--export-c``), compile
``assist.c`` into a shared library with the system C compiler, and let the C
``assist_step`` steer the nonlinear simulator: every 5 ms sample the loop
hands the C the speed, the joystick's yaw-rate command, the gyro (true yaw
rate plus a 2 deg/s bias) and the wheel-speed yaw rate, and applies its
differential wheel torque as a yaw moment.  What to conclude: the firmware
built from the export follows the command like the Python controller does
(the same run with :class:`stability.assist.DigitalController` is drawn
dashed), and removes the gyro bias through its wheel-speed estimate.

Needs a C compiler (``cc``); standalone: ``python docs/examples/assist_c_loop.py``.
"""

import ctypes
import math
import os
import subprocess
import tempfile

import matplotlib.pyplot as plt
import numpy as np

from stability import chair as chair_mod
from stability.assist import DigitalController, schedule
from stability.assist.c_harness import find_cc
from stability.assist.commands import COMMAND_FILTER, step_command
from stability.assist.export_c import export_c
from stability.settings.run import RunSpec
from stability.simulate import simulate

SPEED = 2.0                      # m/s
BIAS = math.radians(2.0)         # gyro bias, rad/s
COMMAND = step_command(0.4, 0.5)  # rad/s from 0.5 s

chair = chair_mod.preset("power-fwd")
sched = schedule(chair, [1.0, 2.0, 3.0], "gyro")
work = tempfile.mkdtemp()
export_c(sched, work, "float")
lib_path = os.path.join(work, "libassist.so")
subprocess.run([find_cc() or "cc", "-std=c99", "-O2", "-shared", "-fPIC", os.path.join(work, "assist.c"),
                "-o", lib_path], check=True)
lib = ctypes.CDLL(lib_path)


class State(ctypes.Structure):
    """``struct assist_state`` of assist.h (ASSIST_ORDER estimator states)."""

    _fields_ = [("xhat", ctypes.c_float * 7), ("e", ctypes.c_float), ("bhat", ctypes.c_float),
                ("r", ctypes.c_float), ("rc", ctypes.c_float), ("u", ctypes.c_float), ("mz", ctypes.c_float),
                ("raw", ctypes.c_float), ("monitor", ctypes.c_float), ("frozen", ctypes.c_float),
                ("mode", ctypes.c_int), ("first", ctypes.c_int)]


f = ctypes.c_float
lib.assist_step.argtypes = [ctypes.POINTER(State), f, f, f, f, ctypes.POINTER(f), ctypes.POINTER(f)]


class CAssist:
    """The simulator's ``yaw_moment(t, state)`` hook around the C controller (zero-order hold, motor lag)."""

    def __init__(self):
        self.s = State()
        lib.assist_init(ctypes.byref(self.s))
        self.T = 1.0 / 200.0
        self.k = -1
        self.u = self.m = 0.0          # held yaw moment and motor state (N m)
        self.tau = sched.drive.motor_time_constant

    def __call__(self, t, st):
        k = int(math.floor(t / self.T + 1e-9))
        while self.k < k:
            self.k += 1
            left, right = f(), f()
            lib.assist_step(ctypes.byref(self.s), SPEED, COMMAND(self.k * self.T), st.yaw_rate + BIAS,
                            st.yaw_rate, ctypes.byref(left), ctypes.byref(right))
            self.m = self.u + (self.m - self.u) * math.exp(-self.T / self.tau) if self.k else 0.0
            self.u = float(sched.drive.yaw_moment(chair, left.value))
        return self.u + (self.m - self.u) * math.exp(-(t - self.k * self.T) / self.tau)


c_run = simulate(chair, SPEED, run=RunSpec(horizon=4.0, stop_on_warnings=False, friction_law="kinetic"), yaw_moment=CAssist())
gyro = sched.gyro.__class__(bias_deg_s=math.degrees(BIAS), noise_density_deg_s=0.0)
py = DigitalController(sched.at(SPEED), chair, sched.drive, gyro=gyro, command=COMMAND,
                       command_filter_s=COMMAND_FILTER)
py_run = simulate(chair, SPEED, run=RunSpec(horizon=4.0, stop_on_warnings=False, friction_law="kinetic"), yaw_moment=py)

fig, ax = plt.subplots(figsize=(7, 4))
t = np.asarray(c_run.t)
ax.plot(t, [math.degrees(COMMAND(x)) for x in t], color="0.5", label="joystick command")
ax.plot(t, np.degrees(c_run.yaw_rate), color="#0072B2", label="exported C (float tables)")
ax.plot(np.asarray(py_run.t), np.degrees(py_run.yaw_rate), "--", color="#E69F00", label="Python DigitalController")
ax.set_xlabel("time (s)")
ax.set_ylabel("yaw rate (deg/s)")
ax.set_title(f"power-fwd, gyro LQR assist at {SPEED:g} m/s (exact model): C firmware in the loop")
ax.legend()
fig.tight_layout()
print(f"largest yaw-rate difference C vs Python: "
      f"{np.max(np.abs(np.degrees(c_run.yaw_rate) - np.degrees(py_run.yaw_rate))):.2e} deg/s")
if __name__ == "__main__":
    plt.show()
