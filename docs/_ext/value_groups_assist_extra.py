"""More value groups of docs/assist.md: the estimator's poles, the nonlinear loop's gyro bias, the low-speed step,
the quantisation bounds, the next grid speed past the safe top speed (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import fixed, group, sig
from value_groups_pages import _preset

#: the default schedule's speeds (m/s), as docs/assist.md quotes its margins over 0.5-3 m/s
SCHEDULE = (0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0, 2.25, 2.5, 2.75, 3.0)


def _quiet():
    import warnings

    w = warnings.catch_warnings()
    w.__enter__()
    warnings.simplefilter("ignore")       # python-control's notes at extreme frequencies (harmless)
    return w


@group("assist_estimator", "stability.assist.design(power_fwd, U, 'gyro') for U in 0.5:3:0.25: eigenvalues of "
       "A6 - L C (C reads the yaw rate) that are not eigenvalues of A6 (the poles the Kalman gain places)")
def assist_estimator() -> dict:
    """The fastest pole the estimator places, over the schedule, against the sample rate."""
    import math

    import numpy as np

    from stability import assist

    w = _quiet()
    try:
        fastest, rate = [], 0.0
        for u in SCHEDULE:
            d = assist.design(_preset("power-fwd"), u, "gyro")
            A = d.plant.A6
            C = np.zeros((1, A.shape[0]))
            C[0, 1] = 1.0
            ev, e0 = np.linalg.eigvals(A - d.L @ C), np.linalg.eigvals(A)
            moved = [p for p in ev if np.min(np.abs(e0 - p)) > 0.01 * abs(p)]
            fastest.append(min(p.real for p in moved))
            rate = 1.0 / d.sample_time
    finally:
        w.__exit__(None, None, None)
    lo, hi = max(fastest), min(fastest)
    return {"pole_lo": f"{lo:.0f}", "pole_hi": f"{hi:.0f}", "rate_hz": f"{rate:g}",
            "fraction_lo": sig(abs(lo) / (2 * math.pi * rate), 2),
            "fraction_hi": sig(abs(hi) / (2 * math.pi * rate), 2)}


@group("assist_nonlinear_bias", "stability.assist.recovery(power_fwd, 1.0, DigitalController(schedule(power_fwd, "
       "0.5:3:0.25, 'gyro').at(1.0), power_fwd, DriveTrain(), gyro=GyroSensor(noise_density_deg_s=0, bias_deg_s=1, "
       "bias_time_constant_s=0 or 1)), impulse_force=0) (heading at the end)")
def assist_nonlinear_bias() -> dict:
    """The nonlinear loop with a 1 deg/s gyro bias, straight ahead: heading at the end, without and with the
    bias estimate."""
    import numpy as np

    from stability import assist
    from stability.chair.power import DriveTrain

    chair = _preset("power-fwd")
    w = _quiet()
    try:
        d = assist.schedule(chair, list(SCHEDULE), "gyro").at(1.0)
        out = {"bias": "1", "tb": "1"}
        for tb, key in ((0.0, "without"), (1.0, "with")):
            g = assist.GyroSensor(noise_density_deg_s=0.0, bias_deg_s=1.0, bias_time_constant_s=tb)
            run = assist.recovery(chair, 1.0, assist.DigitalController(d, chair, DriveTrain(), gyro=g),
                                  impulse_force=0.0)
            out[key] = fixed(float(np.degrees(run.result.heading[-1])), 1)
            out["duration"] = f"{float(run.result.t[-1]):.0f}"
    finally:
        w.__exit__(None, None, None)
    return out


@group("assist_auto_step", "stability.simulate.stepcheck.stable_steps([power_fwd], U, 'exact', 'free') (largest "
       "stable step, bisected in speed for 1 ms) and auto_step(...) at 0.1 m/s (the step of dt='auto')", cheap=True)
def assist_auto_step() -> dict:
    """Below which speed program WCHAIR's 1 ms step is unstable for the power chair, and the step at 0.1 m/s."""
    import numpy as np

    from stability.simulate.stepcheck import WCHAIR_DT, auto_step, stable_steps

    c = _preset("power-fwd")

    def limit(u: float) -> float:
        return float(stable_steps([c], np.array([u]), "exact", "free")[0])

    lo, hi = 0.01, 3.0
    if not (limit(lo) < WCHAIR_DT <= limit(hi)):
        raise RuntimeError("the 1 ms step is not unstable at low speed and stable at 3 m/s")
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if limit(mid) < WCHAIR_DT else (lo, mid)
    return {"speed": sig(hi, 2), "dt_01_ms": f"{1e3 * auto_step(limit(0.1)):.2g}", "wchair_ms": f"{1e3 * WCHAIR_DT:g}"}


@group("assist_quantisation", "stability.assist.quantisation.vector_tolerances(firmware_tables(schedule(power_fwd, "
       "[1, 2, 3], 'gyro')), quantise(..., 'Q15'|'Q31'), vector_cases(...)) (the derived per-case tolerance) and "
       "output_bound (python -m stability.assist --export-c DIR --q-format Q15 writes the same tolerances)")
def assist_quantisation() -> dict:
    """Per-case tolerance of the Q15 export, and the Q31 bound relative to the torque limit."""
    import numpy as np

    from stability import assist
    from stability.assist.export_c import COMMAND_FILTER, firmware_tables, quantise, vector_cases
    from stability.assist.quantisation import FLOAT_RELATIVE, output_bound, vector_tolerances

    w = _quiet()
    try:
        sched = assist.schedule(_preset("power-fwd"), [1.0, 2.0, 3.0], "gyro")
        ideal = firmware_tables(sched, command_filter_s=COMMAND_FILTER)
        vecs = vector_cases(sched)
        q15, _ = quantise(ideal, "Q15")
        tol = vector_tolerances(ideal, q15, vecs)
        q31, _ = quantise(ideal, "Q31")
        b31 = max(float(np.max(output_bound(ideal, q31, v.inputs))) for v in vecs)
    finally:
        w.__exit__(None, None, None)
    return {"q15_lo": sig(min(tol.values()), 1), "q15_hi": sig(max(tol.values()), 2),
            "q31_rel": f"{b31 / ideal.torque_limit:.0e}".replace("e-0", "e-"),
            "float_rel": f"{FLOAT_RELATIVE:.0e}".replace("e-0", "e-"), "rate_hz": f"{1.0 / ideal.sample_time:g}"}


@group("assist_next_speed", "python -m stability.assist --chair power-fwd --speeds 0.5:5:0.25 --faults (the grid "
       "speed after the safe top speed, from the assist_faults group)")
def assist_next_speed() -> dict:
    """The grid speed just past the safe top speed, and the 1 deg/s bias step's drift there."""
    import value_groups

    v = value_groups.evaluate("assist_faults")[0]
    nxt = float(v["top_speed"]) + 0.25
    key = f"bias1_drift_{nxt:g}"
    if key not in v:
        raise KeyError(f"assist_faults has no {key}: the safe top speed moved; quote the drift it has")
    return {"speed": f"{nxt:g}", "drift": v[key]}
