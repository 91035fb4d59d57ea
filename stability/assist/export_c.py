"""Firmware export: the gyro assist as plain C99 (``assist.h``, ``assist.c``), test vectors and a README.

The C runs :class:`~stability.assist.firmware.FirmwareController`'s
arithmetic in single precision: no allocation, no library call but
``fabsf``, the tables over speed as ``float`` or as Q15/Q31 integers with one
binary scale per table (:func:`~stability.assist.firmware.quantise`).  The
test vectors come from the Python sampled controller
(:class:`~stability.assist.controller.DigitalController`) in the nonlinear
closed loop at three grid speeds; see docs/assist.md.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from stability.assist.commands import COMMAND_FILTER, MAX_YAW_RATE, ramp_command, reference_command, step_command
from stability.assist.controller import DigitalController
from stability.assist.firmware import (
    DEGRADED_SPEED,
    MONITOR_THRESHOLD_DEG_S,
    PLAUSIBLE_MIN_SPEED,
    WHEEL_PLAUSIBLE,
    FirmwareTables,
    firmware_tables,
    mirror_outputs,
    q_bits,
    quantise,
)
from stability.assist.readme import readme
from stability.assist.schedule import Schedule
from stability.assist.top_speed import TopSpeed, margin_top_speed
from stability.settings import defaults as D
from stability.settings.reference import THESIS_PUSH
from stability.settings.run import RunSpec
from stability.simulate import simulate

__all__ = ["VectorCase", "ClosedLoop", "short_form_loop", "vector_speeds", "vector_cases", "c_sources", "readme",
           "export_c", "VECTOR_DURATION"]

#: Length of each test-vector case (s).
VECTOR_DURATION = 2.0
#: Yaw-rate command of the saturating case (rad/s): the joystick's largest command doubled, reversed at half time.
SATURATING = 2.0 * MAX_YAW_RATE
#: Gyro-bias step of the monitor's test vector (deg/s).
FAULT_VECTOR_BIAS_DEG_S = 20.0
#: Gyro bias of the test vectors (deg/s): large enough that the bias estimate visibly acts.
VECTOR_BIAS_DEG_S = 2.0


@dataclass(frozen=True, eq=False)
class VectorCase:
    """One test-vector case.

    Attributes
    ----------
    name : str
    inputs : ndarray (N, 4)
        ``speed_m_s, yaw_rate_cmd_rad_s, gyro_rad_s, wheel_yaw_rate_rad_s`` per sample.
    outputs : ndarray (N, 2)
        ``torque_left_Nm, torque_right_Nm`` per sample.
    controller_inputs : ndarray (N, 4)
        The inputs before rounding to single precision.
    controller_tau : ndarray (N,)
        What :class:`DigitalController` commanded for them (N m): ``outputs`` replays the rounded inputs through
        :class:`~stability.assist.firmware.FirmwareController`, the same arithmetic (NaN for the fault case:
        the Python sampled controller has no monitor).
    """

    name: str
    inputs: np.ndarray
    outputs: np.ndarray
    controller_inputs: np.ndarray
    controller_tau: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """The JSON form of the issue's format (floats as repr, exact)."""
        return {"name": self.name, "inputs": self.inputs.tolist(), "outputs": self.outputs.tolist()}


class _Recorder(DigitalController):
    """A :class:`DigitalController` that records what it read at each sample (gyro, wheel-speed yaw rate)."""

    def reset(self) -> None:
        super().reset()
        self.read: list[tuple[float, float]] = []

    def _step(self, k: int, state: Any) -> None:
        super()._step(k, state)
        r = float(state.yaw_rate)
        # the gyro as _step read it (bias + the seeded noise sample); the wheels see the true yaw rate
        self.read.append((r + self._bias + self._noise_at(k), r))


def _reversing(size: float, at: float) -> Callable[[float], float]:
    """``r_cmd(t) = size`` before ``at``, ``-size`` after (rad/s)."""
    return lambda t: size if t < at else -size


def vector_speeds(sched: Schedule) -> tuple[float, ...]:
    """Three grid speeds of the vectors: the first, middle and last of the design grid (m/s).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    tuple of float
    """
    s = [float(x) for x in sched.speeds]
    return tuple(dict.fromkeys([s[0], s[len(s) // 2], s[-1]]))


#: A closed loop the vectors are recorded in: ``loop(speed, push_force, duration, controller)`` runs the controller
#: (a :class:`DigitalController`, called as the simulator's ``yaw_moment(t, state)`` hook) for ``duration`` s
#: after a push of ``push_force`` N (for :data:`~stability.settings.reference.THESIS_PUSH`'s duration).
ClosedLoop = Callable[[float, float, float, DigitalController], None]


def short_form_loop(sched: Schedule) -> ClosedLoop:
    """The schedule's chair in the nonlinear simulator (:func:`stability.simulate.simulate`, its model).

    Parameters
    ----------
    sched : Schedule

    Returns
    -------
    ClosedLoop
    """
    def loop(speed: float, force: float, duration: float, ctl: DigitalController) -> None:
        simulate(sched.chair, speed, RunSpec(horizon=duration, model=sched.model, push_force=force,
                                             push_duration=THESIS_PUSH.duration, stop_on_warnings=False),
                 yaw_moment=ctl)

    return loop


def vector_cases(sched: Schedule, *, seed: int = 0, duration: float = VECTOR_DURATION,
                 closed_loop: ClosedLoop | None = None) -> list[VectorCase]:
    """Inputs and outputs of the Python sampled controller in the nonlinear closed loop.

    At each of :func:`vector_speeds`: a yaw-rate step (the reference turn),
    a ramp (to it in 1 s), a push recovery (:data:`~stability.settings.reference.THESIS_PUSH`
    times 10 at the start, straight command) and a saturating command
    (:data:`SATURATING`, reversed at half time); the gyro reads the yaw rate
    plus :data:`VECTOR_BIAS_DEG_S` and the sensor's seeded noise, the wheel
    speeds the true yaw rate.  The controller runs with the reference model
    of :data:`~stability.assist.commands.COMMAND_FILTER` and back-calculation
    anti-windup, the schedule's torque limit.  A last case replays the middle
    speed's push with a :data:`FAULT_VECTOR_BIAS_DEG_S` gyro-bias step at half
    time, so the monitor trips.  The inputs are stored rounded to
    single precision (the C API's type) and the outputs are those of
    :class:`~stability.assist.firmware.FirmwareController` for them (equal to
    the controller's own, kept in ``controller_tau``, to round-off).

    Parameters
    ----------
    sched : Schedule
        A gyro schedule.
    seed : int
        Noise seed.
    duration : float
        s per case.
    closed_loop : ClosedLoop, optional
        Where the controller runs (default :func:`short_form_loop`; a wheel layout's:
        :func:`stability.assist.layout_checks.layout_vector_loop`).

    Returns
    -------
    list of VectorCase
    """
    gyro = replace(sched.gyro, bias_deg_s=VECTOR_BIAS_DEG_S)
    tables = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    loop = closed_loop or short_form_loop(sched)
    out = []
    for i, s in enumerate(vector_speeds(sched)):
        ref = reference_command(abs(s))       # a reverse grid (a layout's): the same turn rate
        cases: list[tuple[str, Callable[[float], float], float]] = [
            ("step", step_command(ref, 0.1), 0.0), ("ramp", ramp_command(ref, ref), 0.0),
            ("push", step_command(0.0), 10 * THESIS_PUSH.force),
            ("saturating", _reversing(SATURATING, duration / 2), 0.0)]
        for name, cmd, force in cases:
            ctl = _Recorder(sched.at(s), sched.chair, sched.drive, gyro=gyro, seed=seed + i, command=cmd,
                            command_filter_s=COMMAND_FILTER)
            loop(s, force, duration, ctl)
            nk = len(ctl.read)
            tau = np.array([h[3] for h in ctl._hist[:nk]])
            inputs = np.array([[s, float(cmd(k * ctl.Ts)), g, w] for k, (g, w) in enumerate(ctl.read)])
            # the API's inputs are single precision: store them so, and replay them through the mirror (which is
            # the controller's arithmetic: ``controller_tau`` keeps the controller's own outputs for that check)
            inputs32 = inputs.astype(np.float32).astype(float)
            mirror = mirror_outputs(tables, inputs32)
            out.append(VectorCase(f"{name}_{s:g}_m_s", inputs32, np.column_stack([mirror, -mirror]), inputs, tau))
    # the monitor: the middle speed's push case replayed with a 20 deg/s gyro-bias step at half time (an open-loop
    # replay; the Python sampled controller has no monitor, so the outputs are the firmware mirror's)
    push = next(c for c in out if c.name == f"push_{vector_speeds(sched)[len(vector_speeds(sched)) // 2]:g}_m_s")
    faulty = push.inputs.copy()
    faulty[len(faulty) // 2:, 2] += math.radians(FAULT_VECTOR_BIAS_DEG_S)
    faulty = faulty.astype(np.float32).astype(float)
    mirror = mirror_outputs(tables, faulty)
    out.append(VectorCase(f"fault_gyro_bias_{FAULT_VECTOR_BIAS_DEG_S:g}_deg_s_{faulty[0, 0]:g}_m_s", faulty,
                          np.column_stack([mirror, -mirror]), faulty, np.full(len(faulty), np.nan)))
    return out


def _c_float(x: float) -> str:
    """A float literal that rounds to the nearest single (17 significant digits, ``f`` suffix)."""
    if x == 0:
        return "0.0f"
    return f"{x:.17e}f"


def _c_int(v: Any) -> str:
    """An integer literal (the most negative 32-bit value written as an expression)."""
    v = int(v)
    return f"({v + 1} - 1)" if v <= -2 ** 31 else str(v)


def _c_array(a: np.ndarray, fmt: Any) -> str:
    if a.ndim == 1:
        return "{" + ", ".join(fmt(v) for v in a) + "}"
    return "{" + ",\n  ".join(_c_array(x, fmt) for x in a) + "}"


def c_sources(t: FirmwareTables, ints: dict[str, np.ndarray]) -> tuple[str, str]:
    """``assist.h`` and ``assist.c`` for quantised tables.

    Parameters
    ----------
    t : FirmwareTables
        From :func:`~stability.assist.firmware.quantise`.
    ints : dict
        The integers (empty for float).

    Returns
    -------
    tuple of str
        Header and source.
    """
    n, ns = t.n, len(t.speeds)
    header = f"""/* assist.h: gyro yaw assist of a power wheelchair, generated by python -m stability.assist --export-c.
 * Plain C99, no allocation.  Sample rate {1.0 / t.sample_time:g} Hz: call assist_step once per sample.
 * Tables: {t.q_format}.  Units: SI (m/s, rad/s, N m).  See README.txt. */
#ifndef ASSIST_H
#define ASSIST_H

#define ASSIST_SAMPLE_RATE_HZ {_c_float(1.0 / t.sample_time)}
#define ASSIST_ORDER {n}

/* The controller's memory; allocate it yourself and call assist_init before the first step. */
struct assist_state {{
    float xhat[ASSIST_ORDER]; /* estimator state */
    float e;                  /* heading-error integrator, rad */
    float bhat;               /* gyro-bias estimate, rad/s */
    float r;                  /* corrected gyro of the last sample, rad/s */
    float rc;                 /* reference-model output of the last sample, rad/s */
    float u;                  /* applied yaw moment of the last sample, N m */
    float mz;                 /* unsaturated yaw moment of the last sample, N m */
    float raw;                /* raw command of the last sample, rad/s */
    float monitor;            /* low-passed gyro minus wheel-speed yaw rate, rad/s */
    float frozen;             /* bias estimate at the monitor's alarm, rad/s */
    int mode;                 /* 0 normal, 1 gyro at fault (wheel-speed yaw rate steers), 2 wheel-speed at fault */
    int first;                /* 1 until the first step */
}};
typedef struct assist_state assist_state;

void assist_init(assist_state *s);
/* One sample: returns the torques computed from the samples before this one (one sample of delay). */
void assist_step(assist_state *s, float speed_m_s, float yaw_rate_cmd_rad_s,
                 float gyro_rad_s, float wheel_yaw_rate_rad_s,
                 float *torque_left_Nm, float *torque_right_Nm);
/* The sensor monitor's mode (latched until assist_init): 0 normal, 1 gyro fault, 2 wheel-speed sensor fault. */
int assist_mode(const assist_state *s);
/* The speed limit the controller asks for, m/s ({_c_float(DEGRADED_SPEED)} after a fault; 1e30f otherwise). */
float assist_speed_limit_m_s(const assist_state *s);

#endif
"""
    tables = []
    for name in FirmwareTables.TABLES:
        vals = np.asarray(getattr(t, name))
        dims = "".join(f"[{d}]" for d in vals.shape)
        if t.q_format == "float":
            tables.append(f"static const float T_{name.upper()}{dims} = {_c_array(vals, _c_float)};\n")
        else:
            ctype = "int16_t" if t.q_format == "Q15" else "int32_t"
            bits = q_bits(t.q_format)
            scale = 2.0 ** (np.asarray(t.exponents[name], dtype=float) - bits)
            sdims = "".join(f"[{d}]" for d in vals.shape[1:])
            tables.append(f"static const {ctype} T_{name.upper()}{dims} = {_c_array(ints[name], _c_int)};\n"
                          f"static const float S_{name.upper()}{sdims} = "
                          f"{_c_array(scale, _c_float) if scale.ndim else _c_float(float(scale))};\n")
    if t.q_format == "float":
        lerp = ("#define LERP(tab, i, w, idx) (T_##tab[i]idx + (w) * (T_##tab[(i) + ((i) < NS - 1)]idx "
                "- T_##tab[i]idx))")
    else:
        lerp = ("/* value = integer * scale (a power of two per entry, shared over speed) */\n"
                "#define LERP(tab, i, w, idx) (S_##tab idx * ((float)T_##tab[i]idx + (w) * "
                "((float)T_##tab[(i) + ((i) < NS - 1)]idx - (float)T_##tab[i]idx)))")
    aw = {"back-calculation": 2, "conditional": 1, "none": 0}[t.anti_windup]
    lim = "1e30f" if math.isinf(t.torque_limit) else _c_float(t.torque_limit)
    source = f"""/* assist.c: generated by python -m stability.assist --export-c ({t.q_format} tables). */
#include <math.h>
#include <stdint.h>
#include "assist.h"

#define NS {ns}
#define N ASSIST_ORDER
static const float SPEEDS[NS] = {_c_array(t.speeds, _c_float)};
{"".join(tables)}
static const float T_S = {_c_float(t.sample_time)};             /* sample period, s */
static const float TORQUE_PER_MZ = {_c_float(t.torque_per_moment)};  /* wheel torque per yaw moment */
static const float TORQUE_LIMIT = {lim};  /* N m per wheel */
static const float BIAS_GAIN = {_c_float(t.bias_gain)};
static const float COMMAND_GAIN = {_c_float(t.command_gain)};
static const float WINDUP_GAIN = {_c_float(t.windup_gain)};
static const float MONITOR_GAIN = {_c_float(t.monitor_gain)};
static const float MONITOR_THRESHOLD = {_c_float(MONITOR_THRESHOLD_DEG_S * math.pi / 180.0)};  /* rad/s */
static const float TRACK = {_c_float(t.track)};  /* m, d1 + d2 */
static const float WHEEL_PLAUSIBLE_RATIO = {_c_float(WHEEL_PLAUSIBLE)};
static const float PLAUSIBLE_SPEED = {_c_float(PLAUSIBLE_MIN_SPEED)};  /* m/s */
static const float DEGRADED_SPEED_M_S = {_c_float(DEGRADED_SPEED)};
#define ANTI_WINDUP {aw} /* 2 back-calculation, 1 conditional, 0 none */

void assist_init(assist_state *s)
{{
    int i;
    for (i = 0; i < N; ++i) s->xhat[i] = 0.0f;
    s->e = s->bhat = s->r = s->rc = s->u = s->mz = s->raw = s->monitor = s->frozen = 0.0f;
    s->mode = 0;
    s->first = 1;
}}

int assist_mode(const assist_state *s)
{{
    return s->mode;
}}

float assist_speed_limit_m_s(const assist_state *s)
{{
    return s->mode ? DEGRADED_SPEED_M_S : 1e30f;
}}

{lerp}

void assist_step(assist_state *s, float speed_m_s, float yaw_rate_cmd_rad_s,
                 float gyro_rad_s, float wheel_yaw_rate_rad_s,
                 float *torque_left_Nm, float *torque_right_Nm)
{{
    float w = 0.0f, mz = 0.0f, tau = 0.0f, u = 0.0f, kpsi, ff;
    float dphi[N][N], gam[N][2], kint[N];
    int i = 0, a, b;
    /* table position: held at the ends of the grid */
    if (!(speed_m_s > SPEEDS[0])) {{
        i = 0;
    }} else if (speed_m_s >= SPEEDS[NS - 1]) {{
        i = NS - 1;
    }} else {{
        while (i < NS - 2 && speed_m_s >= SPEEDS[i + 1]) ++i;
        w = (speed_m_s - SPEEDS[i]) / (SPEEDS[i + 1] - SPEEDS[i]);
    }}
    for (a = 0; a < N; ++a) {{
        for (b = 0; b < N; ++b) dphi[a][b] = LERP(PHI_MINUS_I, i, w, [a][b]);
        gam[a][0] = LERP(GAMMA, i, w, [a][0]);
        gam[a][1] = LERP(GAMMA, i, w, [a][1]);
        kint[a] = LERP(K_INT, i, w, [a]);
    }}
    kpsi = LERP(K_PSI, i, w, );
    ff = LERP(FEEDFORWARD, i, w, );
    /* sensor monitor and degraded mode (latched) */
    s->monitor += MONITOR_GAIN * ((gyro_rad_s - wheel_yaw_rate_rad_s) - s->monitor);
    if (s->mode == 0 && fabsf(s->monitor - s->bhat) > MONITOR_THRESHOLD) {{
        float v = fabsf(speed_m_s) > PLAUSIBLE_SPEED ? fabsf(speed_m_s) : PLAUSIBLE_SPEED;
        s->mode = (fabsf(wheel_yaw_rate_rad_s) * TRACK >= WHEEL_PLAUSIBLE_RATIO * v) ? 2 : 1;
        s->frozen = s->bhat;
    }}
    if (s->mode == 1) {{
        gyro_rad_s = wheel_yaw_rate_rad_s;
    }} else if (s->mode == 2) {{
        wheel_yaw_rate_rad_s = gyro_rad_s - s->frozen;
    }}
    if (!s->first) {{
        float err = s->r - s->rc, excess = (s->raw != 0.0f) ? s->mz - s->u : 0.0f, inc = T_S * err;
        float x[N];
#if ANTI_WINDUP == 2
        if (excess != 0.0f) inc += WINDUP_GAIN * excess / kpsi;
#elif ANTI_WINDUP == 1
        if (excess != 0.0f && -kpsi * err * excess > 0.0f) inc = 0.0f;
#endif
        s->e += inc;
        for (a = 0; a < N; ++a) x[a] = s->xhat[a];
        for (a = 0; a < N; ++a) {{
            float acc = x[a];
            for (b = 0; b < N; ++b) acc += dphi[a][b] * x[b];
            s->xhat[a] = acc + gam[a][0] * s->u + gam[a][1] * s->r;
        }}
    }}
    s->bhat += BIAS_GAIN * ((gyro_rad_s - wheel_yaw_rate_rad_s) - s->bhat);
    s->r = gyro_rad_s - s->bhat;
    if (!s->first) {{
        mz = -kpsi * s->e + ff * s->rc;
        for (a = 0; a < N; ++a) mz -= kint[a] * s->xhat[a];
        tau = mz * TORQUE_PER_MZ;
        if (tau > TORQUE_LIMIT) tau = TORQUE_LIMIT;
        if (tau < -TORQUE_LIMIT) tau = -TORQUE_LIMIT;
        u = tau / TORQUE_PER_MZ;
        if (!(fabsf(tau) >= TORQUE_LIMIT)) mz = u;
    }}
    s->u = u;
    s->mz = mz;
    s->rc += COMMAND_GAIN * (yaw_rate_cmd_rad_s - s->rc);
    s->raw = yaw_rate_cmd_rad_s;
    s->first = 0;
    *torque_left_Nm = tau;
    *torque_right_Nm = -tau;
}}
"""
    return header, source


def export_c(sched: Schedule, directory: str, q_format: str = D.Q_FORMAT, *, seed: int = 0,
             vectors: list[VectorCase] | None = None, top: TopSpeed | None = None) -> dict[str, Any]:
    """Write assist.h, assist.c, assist_vectors.json and README.txt into ``directory`` (all or none).

    Parameters
    ----------
    sched : Schedule
        A gyro schedule.
    directory : str
        Created if missing (its parent must exist).
    q_format : str
        :data:`~stability.assist.firmware.Q_FORMATS`.
    seed : int
        Noise seed of the vectors.
    vectors : list of VectorCase, optional
        Precomputed :func:`vector_cases`.
    top : TopSpeed, optional
        The schedule's safe top speed for the README (default:
        :func:`~stability.assist.top_speed.margin_top_speed`, the sampled margins alone).

    Returns
    -------
    dict
        ``{"directory", "q_format", "files", "tolerance_N_m", "top_speed"}`` (per-case derived tolerance; the
        :class:`~stability.assist.top_speed.TopSpeed` in the README).
    """
    from stability.assist.quantisation import vector_tolerances  # the bound needs the closed-loop trajectories

    ideal = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
    q, ints = quantise(ideal, q_format)
    vecs = vectors if vectors is not None else vector_cases(sched, seed=seed)
    tol = vector_tolerances(ideal, q, vecs)
    h, c = c_sources(q, ints)
    top = top if top is not None else margin_top_speed(sched)
    doc = {"sample_rate_hz": 1.0 / ideal.sample_time, "q_format": q_format,
           "cases": [dict(v.to_dict(), tolerance_N_m=tol[v.name]) for v in vecs]}
    files = {"assist.h": h, "assist.c": c, "assist_vectors.json": json.dumps(doc) + "\n",
             "README.txt": readme(q, tol if q_format != "float" else None, top)}
    full = os.path.abspath(directory)
    os.makedirs(full, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=".assist-export-", dir=full)
    try:
        for name, text in files.items():
            with open(os.path.join(tmp, name), "w", encoding="utf-8") as fh:
                fh.write(text)
        for name in files:
            os.replace(os.path.join(tmp, name), os.path.join(full, name))
    finally:
        for name in os.listdir(tmp):
            os.remove(os.path.join(tmp, name))
        os.rmdir(tmp)
    return {"directory": directory, "q_format": q_format, "files": sorted(files), "tolerance_N_m": tol,
            "top_speed": top}
