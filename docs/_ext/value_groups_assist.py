"""The value groups of docs/assist.md's nonlinear driving checks (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import Table, fixed, group, pct, sig, signed
from value_groups_pages import _gain_db, _preset, _span

SLOPE_SPEEDS = (0.5, 1.0, 1.5, 2.0, 2.5, 3.0)


def _schedule(chair, kind: str = "gyro"):
    import warnings

    import numpy as np

    from stability import assist

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # python-control's overflow note at a huge candidate frequency (harmless)
        return assist.schedule(chair, np.arange(0.5, 3.0001, 0.25), kind)


def _settle(h, fraction: float = 0.02) -> float:
    """When the closed loop's torque last leaves ``fraction`` of its steady value (s)."""
    import numpy as np

    run = h.closed
    out = np.flatnonzero(np.abs(run.torque - h.steady_torque_N_m) > fraction * abs(h.steady_torque_N_m))
    return float(run.torque_t[out[-1] + 1]) if out.size else 0.0


@group("assist_slope", "python -m stability.assist --chair power-fwd (the 'Cross slope' section: "
       "stability.assist.driving.slope_hold(schedule(power_fwd, 0.5:3:0.25, DESIGN), U, PHI), with the chair's "
       "pin friction and without)")
def assist_slope() -> dict:
    """The assist holding a straight line on 2 and 4 deg cross slopes: the table at 1 m/s, spans over speed."""
    import math
    import warnings

    from stability.assist.driving import CROSS_SLOPES, HOLD_TOLERANCE, slope_hold

    pf = _preset("power-fwd")
    free = pf.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    sched, sched_free = _schedule(pf), _schedule(free)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        holds = {(u, phi): slope_hold(sched, u, phi) for u in SLOPE_SPEEDS for phi in CROSS_SLOPES}
        frees = {(u, phi): slope_hold(sched_free, u, phi) for u in SLOPE_SPEEDS for phi in CROSS_SLOPES}
        full = {phi: slope_hold(_schedule(pf, "full-state"), 1.0, phi) for phi in CROSS_SLOPES}
    out: dict = {"slopes": " and ".join(f"{p:g}" for p in CROSS_SLOPES), "tol_pct": f"{100 * HOLD_TOLERANCE:g}",
                 "pin": f"{pf.pin_friction_left:g}", "speeds": f"{SLOPE_SPEEDS[0]:g}-{SLOPE_SPEEDS[-1]:g}"}
    rows = {k: [] for k in ("open", "heading", "offset", "steady", "free", "band", "peak", "limits")}
    for phi in CROSS_SLOPES:
        h, f = holds[1.0, phi], frees[1.0, phi]
        rows["open"].append(f"{signed(h.open_heading_deg, 1)} deg ({h.open_turn}) at {fixed(h.open_end_s, 2)} s")
        rows["heading"].append(f"{signed(h.closed_heading_deg, 2)} deg ({signed(h.crab_deg, 2)})")
        rows["offset"].append(f"{signed(1e3 * h.closed_offset_m, 1)} mm")
        rows["steady"].append(f"{fixed(h.steady_torque_N_m, 2)} vs {fixed(h.holding_torque_N_m, 2)} N m "
                              f"({signed(100 * h.relative_error, 0)} %)")
        rows["free"].append(f"{fixed(f.steady_torque_N_m, 3)} vs {fixed(f.holding_torque_N_m, 3)} N m "
                            f"({signed(100 * f.relative_error, 3)} %)")
        rows["band"].append(f"{fixed(h.holding_band_N_m[0], 2)}-{fixed(h.holding_band_N_m[1], 2)} N m")
        rows["peak"].append(f"{fixed(h.peak_torque_N_m, 1)} N m, {fixed(_settle(h), 1)} s")
        rows["limits"].append(f"{h.motor_limit_N_m:g}; {fixed(h.traction_limit_N_m, 0)} N m; "
                              f"{pct(h.friction_use)} %")
        k = f"{phi:g}"
        out.update({f"steady_{k}": fixed(h.steady_torque_N_m, 2), f"rel_{k}": signed(100 * h.relative_error, 0),
                    f"band_{k}": f"{fixed(h.holding_band_N_m[0], 1)}-{fixed(h.holding_band_N_m[1], 1)}",
                    f"free_{k}": fixed(f.steady_torque_N_m, 3), f"peak_{k}": fixed(h.peak_torque_N_m, 1),
                    f"full_heading_{k}": signed(full[phi].closed_heading_deg, 2),
                    f"full_offset_{k}": signed(1e3 * full[phi].closed_offset_m, 0)})
    labels = {"open": "open loop: heading where the run is cut (a caster beyond the tire data)",
              "heading": "assist: heading at 10 s (statics' crab angle)",
              "offset": "assist: lateral offset of the c.g. at 10 s",
              "steady": "steady torque (mean of the last 1 s) vs statics' holding torque, chair's pin friction "
                        "(stick-slip)",
              "free": "the same without pin friction",
              "band": f"holding torque band allowed by the pin friction ({pf.pin_friction_left:g} N m)",
              "peak": "peak torque (transient after the release); settled to within 2 % of the steady torque after",
              "limits": "motor limit; traction `mu N r` at the lighter drive wheel; friction use |(Fx, Fy)|/(mu N)"}
    out["table"] = Table(("", *(f"{p:g} deg" for p in CROSS_SLOPES)),
                         tuple((labels[k], *v) for k, v in rows.items()))
    hs, fs = list(holds.values()), list(frees.values())
    out["open_end"] = _span([h.open_end_s for h in hs], lambda x: fixed(x, 1))
    out["open_heading"] = _span([abs(h.open_heading_deg) for h in hs], lambda x: fixed(x, 0))
    out["open_side"] = "/".join(sorted({h.open_turn for h in hs}))
    out["settle"] = _span([_settle(h) for h in hs], lambda x: fixed(x, 1))
    out["free_rel"] = _span([100 * abs(f.relative_error) for f in fs], lambda x: sig(x, 2))
    out["free_torque"] = " / ".join(_span([f.steady_torque_N_m for f in fs if f.cross_slope_deg == p],
                                          lambda x: fixed(x, 3)) for p in CROSS_SLOPES)
    out["speed_fall"] = _span([100 * (1 - float(h.closed.result.u[-1]) / h.speed_m_s) for h in hs],
                              lambda x: fixed(x, 0))
    free1 = {phi: frees[1.0, phi] for phi in CROSS_SLOPES}
    out["hold_rel"] = sig(100 * max(abs(f.closed_heading_deg / f.hold_heading_deg - 1) for f in free1.values()), 2)
    out.update({"hold_2": signed(free1[2.0].hold_heading_deg, 3), "crab_2": signed(free1[2.0].crab_deg, 3)})
    out.update({f"course_free_{p:g}": signed(free1[p].course_deg, 3) for p in CROSS_SLOPES})
    out["course"] = _span([abs(h.closed_heading_deg - h.crab_deg) for h in hs], lambda x: fixed(x, 2))
    out["offset"] = _span([1e3 * abs(h.closed_offset_m) for h in hs], lambda x: fixed(x, 0))
    out["offset_side"] = "/".join(sorted({"uphill" if h.closed_offset_m * math.copysign(1, h.cross_slope_deg) < 0
                                          else "downhill" for h in hs}))
    out["full_side"] = "/".join(sorted({"uphill" if h.closed_offset_m * math.copysign(1, h.cross_slope_deg) < 0
                                        else "downhill" for h in full.values()}))
    out["max_use_pct"] = pct(max(h.friction_use for h in hs))
    out["max_steady_pct"] = pct(max(h.holding_band_N_m[1] for h in hs) / pf_motor(sched))
    out["max_peak"] = fixed(max(h.peak_torque_N_m for h in hs if h.speed_m_s == 1.0), 1)
    out["max_peak_pct"] = pct(max(h.peak_torque_N_m for h in hs if h.speed_m_s == 1.0) / pf_motor(sched))
    out["motor"] = f"{pf_motor(sched):g}"
    return out


def pf_motor(sched) -> float:
    """The drive train's motor torque limit (N m per wheel)."""
    return float(sched.drive.torque_limit)


def _step_metrics(run, size: float) -> dict:
    """``stability.assist.tracking.step_metrics`` of a yaw-rate step (settled within 2 % of the command, s, None:
    never; overshoot %; error ``(r_cmd - r_end)/r_cmd`` %) and the saturated fraction (%)."""
    from stability.assist.tracking import step_metrics

    m = step_metrics(run.t, run.yaw_rate, run.torque, size)
    return {"settle": m.settling_time_s, "over": m.overshoot_pct, "error": m.steady_state_error_pct,
            "sat": 100 * run.saturated_fraction}


@group("assist_windup", "stability.assist.driving.command_run(schedule(power_fwd, 0.5:3:0.25, 'gyro') with "
       "DriveTrain(torque_limit=L), 1.0, step_command(0.8), duration=6, command_filter_s=F, anti_windup=A)")
def assist_windup() -> dict:
    """The saturated 0.8 rad/s step at 1 m/s under the three integrator schemes (nonlinear loop, noise-free)."""
    import dataclasses
    import warnings

    from stability.assist import driving
    from stability.assist.controller import TRACKING_TIME
    from stability.chair.power import DriveTrain

    base = _schedule(_preset("power-fwd"))
    cases = ((10.0, 0.0), (10.0, driving.COMMAND_FILTER), (15.0, 0.0), (base.drive.torque_limit, 0.0))
    schemes = ("none", "back-calculation", "conditional")
    size, dur = 0.8, 6.0

    def cell(m: dict, full: bool) -> str:
        if m["settle"] is None:
            s = f"never settles, {fixed(m['sat'], 1)} % saturated"
            return s + (f", error {signed(m['error'], 0)} %" if abs(m["error"]) >= 1 else "")
        over = "no overshoot" if m["over"] < 0.05 else f"{sig(m['over'], 2)} % overshoot"
        return f"{fixed(m['settle'], 2)} s, {over}" + (f", error {fixed(abs(m['error']), 2)} %" if full else "")

    rows, out = [], {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for lim, filt in cases:
            sched = dataclasses.replace(base, drive=DriveTrain(torque_limit=lim))
            ms = {aw: _step_metrics(driving.command_run(sched, 1.0, driving.step_command(size), duration=dur,
                                                        command_filter_s=filt, anti_windup=aw), size)
                  for aw in schemes}
            label = f"{lim:g} N m, " + (f"{1e3 * filt:g} ms reference model" if filt else "no reference model")
            if lim == base.drive.torque_limit:
                label += f" ({fixed(ms['none']['sat'], 0)} % saturated)"
            rows.append((label, *(cell(ms[aw], True) for aw in schemes)))
            key = f"{lim:g}{'_ref' if filt else ''}"
            for aw in schemes:
                for k, v in ms[aw].items():
                    out[f"{key}.{aw}.{k}"] = "never" if v is None else sig(v, 2)
        sched = dataclasses.replace(base, drive=DriveTrain(torque_limit=10.0))
        for tt in (0.02, 0.1):
            m = _step_metrics(driving.command_run(sched, 1.0, driving.step_command(size), duration=dur,
                                                  tracking_time_s=tt), size)
            out[f"tt_{1e3 * tt:g}.settle"] = "never" if m["settle"] is None else fixed(m["settle"], 2)
            out[f"tt_{1e3 * tt:g}.over"] = sig(m["over"], 2)
    out["tracking_ms"] = f"{1e3 * TRACKING_TIME:g}"
    out["table"] = Table(("case", "plain integrator", "back-calculation", "conditional"), tuple(rows))
    return out


@group("assist_tracking", "stability.assist.driving.command_run(schedule(power_fwd, 0.5:3:0.25, 'gyro'), 1.0, "
       "ramp_command(0.4, 0.8) | slalom_command(0.5, 3) | step_command(0.8), ...) (nonlinear loop, WCHAIR scheme)")
def assist_tracking() -> dict:
    """The commanded loop in the simulator: ramp, slalom, noisy step, saturated step, a command beyond the motors."""
    import dataclasses
    import warnings

    import numpy as np

    from stability.assist import driving
    from stability.chair.power import DriveTrain

    sched = _schedule(_preset("power-fwd"))
    out: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ramp = driving.command_run(sched, 1.0, driving.ramp_command(0.4, 0.8), duration=4.0)
        e = np.abs(ramp.yaw_rate - ramp.command)
        out["ramp_err"] = sig(float(e[ramp.t > 0.3].max()), 2)
        sl = driving.command_run(sched, 1.0, driving.slalom_command(0.5, 3.0), duration=6.0)
        out["slalom_err"] = sig(float(np.abs(sl.yaw_rate - sl.command)[sl.t > 1.0].max()), 2)
        noisy = driving.command_run(sched, 1.0, driving.step_command(0.8), duration=4.0, noise=True, seed=2,
                                    command_filter_s=driving.COMMAND_FILTER)
        last = noisy.t > 2.0
        out.update(noise_mean=fixed(float(np.mean(noisy.yaw_rate[last])), 3),
                   noise_std=sig(float(np.std(noisy.yaw_rate[last])), 1), noise_rms=sig(noisy.rms_torque_N_m, 2))
        weak = dataclasses.replace(sched, drive=DriveTrain(torque_limit=15.0))
        w = driving.command_run(weak, 1.0, driving.step_command(0.8), duration=4.0,
                                command_filter_s=driving.COMMAND_FILTER)
        out["weak_sat_pct"] = fixed(100 * w.saturated_fraction, 0)
        ten = dataclasses.replace(sched, drive=DriveTrain(torque_limit=10.0))
        for aw in ("back-calculation", "none"):
            r = driving.command_run(ten, 2.0, driving.step_command(0.5), duration=6.0, anti_windup=aw)
            m = _step_metrics(r, 0.5)
            out[f"beyond.{aw}.settle"] = "never" if m["settle"] is None else fixed(m["settle"], 1)
            out[f"beyond.{aw}.error"] = sig(abs(m["error"]), 1)
            out[f"beyond.{aw}.peak"] = sig(float(np.max(np.abs(r.yaw_rate))), 1)
    return out


@group("assist_step", "stability.assist.driving.tracking_step(schedule(power_fwd, 0.5:3:0.25, DESIGN), U) and "
       "command_run(..., 1.0, step_command(0.8), command_filter_s=COMMAND_FILTER) (nonlinear loop)")
def assist_step() -> dict:
    """The reference step through the reference model at every design speed, both designs; the steady torque."""
    import warnings

    import numpy as np

    from stability.assist import driving

    pf = _preset("power-fwd")
    ms = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for kind in ("gyro", "full-state"):
            sched = _schedule(pf, kind)
            ms += [driving.tracking_step(sched, float(u)) for u in sched.speeds]
        run = driving.command_run(_schedule(pf), 1.0, driving.step_command(0.8), duration=4.0,
                                  command_filter_s=driving.COMMAND_FILTER)
    over = max(m.overshoot_pct for m in ms)
    return {"overshoot": "no overshoot" if over < 0.05 else f"at most {sig(over, 2)} % overshoot",
            "settle": _span([m.settling_time_s for m in ms], lambda x: fixed(x, 2)),
            "error": _span([abs(m.steady_state_error_pct) for m in ms], lambda x: fixed(x, 2)),
            "filter_ms": f"{1e3 * driving.COMMAND_FILTER:g}",
            "steady_torque": fixed(float(np.mean(run.torque[run.torque_t > 3.0])), 0)}


@group("assist_constants", "stability.assist.faults (MONITOR_TIME, MONITOR_THRESHOLD_DEG_S), "
       "stability.settings.defaults (SAMPLE_RATE_HZ, MOTOR_LAG)", cheap=True)
def assist_constants() -> dict:
    """The monitor's detection time of a bias step (closed form of its low-pass) and the loop's own delay."""
    import math

    from stability.assist.faults import MONITOR_THRESHOLD_DEG_S, MONITOR_TIME
    from stability.settings import defaults as D

    t = 1.0 / D.SAMPLE_RATE_HZ

    def detect(b: float) -> str:
        n = next(n for n in range(10_000) if b * (1 - math.exp(-(n + 1) * t / MONITOR_TIME)) > MONITOR_THRESHOLD_DEG_S)
        return f"{n * t:.3f}"

    return {"monitor_ms": f"{1e3 * MONITOR_TIME:g}", "threshold": f"{MONITOR_THRESHOLD_DEG_S:g}",
            "detect_20": detect(20.0), "detect_5": detect(5.0),
            "own_delay_ms": f"{1e3 * (1.5 * t + D.MOTOR_LAG):g}", "rate_hz": f"{D.SAMPLE_RATE_HZ:g}",
            "lag_ms": f"{1e3 * D.MOTOR_LAG:g}"}


@group("assist_quantised", "stability.assist.quantisation.margin_rows(schedule(power_fwd, SPEEDS, 'gyro'), "
       "firmware_tables(schedule, command_filter_s=COMMAND_FILTER)) (the --export-c margins table)")
def assist_quantised() -> dict:
    """Sampled margins of the firmware tables (float, Q15, Q31) against the ideal schedule."""
    import math
    import warnings

    import numpy as np

    from stability import assist
    from stability.assist.driving import COMMAND_FILTER
    from stability.assist.firmware import firmware_tables
    from stability.assist.quantisation import margin_rows

    keys = ("gain_db", "phase_deg", "delay_ms")

    def diff(rows, a: str, b: str, key: str, at=None) -> float:
        d = [abs(r.margins[a][key] - r.margins[b][key]) for r in rows
             if (at is None or any(abs(r.speed_m_s - s) < 1e-9 for s in at))
             and math.isfinite(r.margins[a][key]) and math.isfinite(r.margins[b][key])]
        return max(d) if d else 0.0

    def e(x: float) -> str:
        return f"{x:.0e}".replace("e-0", "e-")

    pf = _preset("power-fwd")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sched = assist.schedule(pf, np.arange(0.5, 3.0001, 0.25), "gyro")
        rows = margin_rows(sched, firmware_tables(sched, command_filter_s=COMMAND_FILTER))
        coarse = assist.schedule(pf, [1.0, 2.0, 3.0], "gyro")
        crows = margin_rows(coarse, firmware_tables(coarse, command_filter_s=COMMAND_FILTER))
    grid = [float(s) for s in sched.speeds]
    mids = [r.speed_m_s for r in rows if all(abs(r.speed_m_s - s) > 1e-9 for s in grid)]
    out = {"n_speeds": str(len(rows)),
           "grid_equal": e(max(diff(rows, "float", "ideal", k, grid) for k in keys)),
           "mid_phase": fixed(diff(rows, "float", "ideal", "phase_deg", mids), 3),
           "mid_delay": fixed(diff(rows, "float", "ideal", "delay_ms", mids), 3),
           "mid_gain": e(diff(rows, "float", "ideal", "gain_db", mids)),
           "q15_gain": f"{diff(rows, 'Q15', 'float', 'gain_db'):.1e}".replace("e-0", "e-"),
           "q15_phase": f"{diff(rows, 'Q15', 'float', 'phase_deg'):.0e}".replace("e-0", "e-"),
           "q31": e(max(diff(rows, "Q31", "float", k) for k in keys)),
           "coarse_phase": fixed(diff(crows, "float", "ideal", "phase_deg"), 3)}
    top = next(r for r in rows if abs(r.speed_m_s - 3.0) < 1e-9)
    for v in ("ideal", "Q15"):
        m = top.margins[v]
        out[f"at3.{v}"] = f"{m['gain_db']:.3f} dB / {m['phase_deg']:.3f} deg / {m['delay_ms']:.3f} ms"
    return out


@group("assist_low_speed", "stability.assist.schedule(power_fwd, 0.5:3:0.25, DESIGN).at(U) for U in 0.02-0.4 m/s: "
       "closed_loop_poles, loop_margins, digital.discrete_margins; design(power_fwd, 0.1, 'full-state').K; "
       "driving.tracking_step(schedule, U); the linear model's Mz -> r response against 1/(J s)")
def assist_low_speed() -> dict:
    """The schedule from standstill: pivot limit of the linear model, gains, poles, margins, nonlinear turns."""
    import math
    import warnings

    import numpy as np

    from stability import assist
    from stability.assist import driving
    from stability.assist.digital import discrete_margins
    from stability.linear import input_matrices, state_matrices
    from stability.settings import defaults as D

    c = _preset("power-fwd")
    J = assist.pivot_inertia(c)
    mag, ph = 0.0, 0.0
    for u in (0.02, 0.05, 0.1):
        a, b = state_matrices(c, u)[0], input_matrices(c, u)[0]
        for w in (5.0, 20.0):
            g = (np.eye(a.shape[0])[1] @ np.linalg.solve(1j * w * np.eye(a.shape[0]) - a, b))[0] * J * 1j * w
            mag, ph = max(mag, abs(abs(g) - 1)), max(ph, abs(math.degrees(np.angle(g))))
    out = {"pivot_mag_pct": sig(100 * mag, 1), "pivot_phase_deg": sig(ph, 1)}
    low = (0.02, 0.1, 0.25, 0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        scheds = {k: _schedule(c, k) for k in ("gyro", "full-state")}
        k0 = scheds["full-state"].standstill.K[0]
        k1 = assist.design(c, 0.1, "full-state").K[0]
        out.update(k_r0=f"{k0[1]:.0f}", k_r=f"{k1[1]:.0f}", k_v=f"{abs(k1[0]):.0f}",
                   k_sum=f"{k1[1] - c.s1 * k1[0]:.0f}", s1=f"{c.s1:g}")
        stable = all(assist.closed_loop_poles(s.at(u)).real.max() < 0 for s in scheds.values() for u in low)
        out["stable"] = "stable" if stable else "NOT stable"
        lam = assist.closed_loop_poles(scheds["gyro"].at(0.02))
        pair = sorted((x for x in lam if x.imag > 0.1), key=lambda x: -x.real)[0]
        out["yaw_pole"] = f"{pair.real:.1f} +/- {pair.imag:.0f}j"
        t = 1.0 / D.SAMPLE_RATE_HZ
        for kind, s in scheds.items():
            cont = [assist.loop_margins(s.at(u)) for u in low]
            disc = [discrete_margins(s.at(u), t) for u in low]
            for name, ms in (("c", cont), ("d", disc)):
                out[f"{kind}.{name}.gain"] = _span([_gain_db(m) for m in ms], lambda x: fixed(x, 1))
                out[f"{kind}.{name}.phase"] = _span([m.phase_margin_deg for m in ms], lambda x: fixed(x, 0))
                out[f"{kind}.{name}.delay"] = _span([1e3 * m.delay_margin_s for m in ms], lambda x: fixed(x, 0))
        for u in (0.1, 0.25):
            m = driving.tracking_step(scheds["gyro"], u)
            out[f"step_{u:g}.settle"] = fixed(m.settling_time_s, 2) if m.settling_time_s is not None else "never"
            out[f"step_{u:g}.over"] = "no overshoot" if m.overshoot_pct < 0.05 else \
                f"{sig(m.overshoot_pct, 2)} % overshoot"
            out[f"step_{u:g}.error"] = fixed(abs(m.steady_state_error_pct), 2)
            out[f"step_{u:g}.peak"] = f"{m.peak_torque_N_m:.0f}"
    out["radius"] = fixed(0.1 / 0.8, 3)
    from stability.assist.tracking import feedforward

    sched = scheds["gyro"]
    for u, r in ((1.0, 0.8), (2.0, 0.5)):
        out[f"ff_{u:g}"] = fixed(abs(sched.drive.wheel_torque(c, feedforward(sched.at(u).plant).Nu * r)), 1)
    return out
