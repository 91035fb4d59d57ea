"""The value groups of the pages (README.md, docs/slopes.md, docs/driver.md, ...): one function per group.

Each function calls the toolkit's public API once per quantity it states and returns formatted strings (or
:class:`value_groups.Table`); the ``source`` of its registration is the command or API call a reader runs to
see the same numbers. Import :mod:`value_groups`, not this module.
"""

from __future__ import annotations

from value_groups import Table, fixed, group, pct, sig, signed

SLOPE_CHAIRS = ("ej-premier", "revised", "power-fwd", "ej-premier-front-caster", "manual-front-caster")
SLOPE_DEG, SLOPE_SPEED = 2.0, 0.75


def _preset(name: str):
    import stability

    return stability.preset(name)


# --- README.md, guide-clinician.md: the push convention ---------------------------------------------------

@group("push", "stability.study.push_impulse(RunSpec().push_force, RunSpec().push_duration, 'wchair', RunSpec().dt)",
       cheap=True)
def push() -> dict:
    """The default push on the WCHAIR step: steps and impulse."""
    import math

    from stability.settings.run import RunSpec
    from stability.study import push_impulse

    r = RunSpec()
    return {"steps": str(math.floor(r.push_duration / r.dt + 1e-9) + 1),
            "impulse": sig(push_impulse(r.push_force, r.push_duration, "wchair", r.dt)),
            "force": f"{r.push_force:g}", "duration": f"{r.push_duration:g}", "dt_ms": f"{1e3 * r.dt:g}"}


# --- docs/slopes.md ---------------------------------------------------------------------------------------

@group("slope_holding", "python -m stability.slope --chair NAME --cross-slope 2 --speed 0.75 "
       "(stability.slope.equilibrium.solve(chair, 2, 0.75).holding_moment / 2)")
def slope_holding() -> dict:
    """Holding moment per degree of cross slope and the statics' uncorrected turn, per preset."""
    from stability.slope.equilibrium import solve

    rows, out = [], {}
    for name in SLOPE_CHAIRS:
        eq = solve(_preset(name), SLOPE_DEG, SLOPE_SPEED)
        per_deg = abs(eq.holding_moment) / SLOPE_DEG
        rel = abs(eq.holding_moment - eq.closed_form) / abs(eq.holding_moment)
        out[f"{name}.rel_closed_form_pct"] = sig(100 * rel, 2)
        out[f"{name}.n_m_per_deg"] = fixed(per_deg, 2)
        rows.append((name, fixed(per_deg, 2), eq.uncorrected_turn))
    out["max_rel_closed_form_pct"] = sig(max(float(out[f"{n}.rel_closed_form_pct"]) for n in SLOPE_CHAIRS), 1)
    out["table"] = Table((f"chair ({SLOPE_DEG:g} deg, {SLOPE_SPEED:g} m/s)", "N m/deg", "uncorrected turn"),
                         tuple(rows))
    return out


@group("slope_paths", "python -m stability.slope --chair NAME --cross-slope 2 --speed 0.75 "
       "(stability.study.veer.simulator_path, both schemes, with and without pin friction)")
def slope_paths() -> dict:
    """The simulator's uncorrected turn on 2 deg at 0.75 m/s, both schemes, pin friction on and off."""
    from stability.slope.equilibrium import solve
    from stability.study.veer import REPORT_TIME, VEER_RUN, simulator_path

    def cell(p, rate: bool) -> str:
        at = "1 s" if abs(p.report_time - 1.0) < 1e-9 else f"{p.report_time:.2f} s"
        s = f"{signed(p.heading_change_deg, 2)} deg"
        if rate:
            s += f", {signed(p.yaw_rate_deg_s, 1)} deg/s"
        return f"{s} at {at}"

    rows, out = [], {}
    spread, ends = 0.0, []
    for name in ("ej-premier", "manual-front-caster", "ej-premier-front-caster"):
        c = _preset(name)
        eq = solve(c, SLOPE_DEG, SLOPE_SPEED)
        paths = {}
        for scheme in ("adaptive", "wchair"):
            for fr in (True, False):
                paths[scheme, fr] = simulator_path(c, eq, VEER_RUN.replace(scheme=scheme, horizon=REPORT_TIME),
                                                   pin_friction=fr, report_time=REPORT_TIME)
        for fr in (True, False):
            spread = max(spread, abs(paths["adaptive", fr].heading_change_deg - paths["wchair", fr].heading_change_deg))
        pin = f"{c.pin_friction_left:g} N m"
        for scheme in ("adaptive", "wchair"):
            rows.append((f"{name} ({pin})", scheme, cell(paths[scheme, True], True), cell(paths[scheme, False], True)))
        fric, free = paths["adaptive", True], paths["adaptive", False]
        out[f"{name}.slowdown_pct"] = pct(1 - fric.heading_change_deg / free.heading_change_deg)
        if name == "ej-premier":
            ends = [p.report_time for p in paths.values()]
    out["scheme_spread_deg"] = sig(spread, 1)
    out["ej_cut_from_s"] = fixed(min(ends), 2)
    out["ej_cut_to_s"] = fixed(max(ends), 2)
    out["table"] = Table(("chair", "scheme", "pin friction (chair's)", "frictionless"), tuple(rows))
    return out


@group("slope_manual", "python -m stability.slope --chair manual-front-caster --cross-slope 3 --speed 0.75 "
       "(stability.slope.equilibrium.solve, drive_report)")
def slope_manual() -> dict:
    """The manual-front-caster preset against the treadmill study: moment per degree and what drives it."""
    from stability.slope.equilibrium import drive_report, solve

    c = _preset("manual-front-caster")
    one = solve(c, 3.0, SLOPE_SPEED)
    lo, hi = sorted(abs(x) / 3.0 for x in one.friction_range)
    out = {"per_deg": fixed(abs(solve(c, SLOPE_DEG, SLOPE_SPEED).holding_moment) / SLOPE_DEG, 2),
           "band_lo": fixed(lo, 2), "band_hi": fixed(hi, 2),
           "s1_006": fixed(abs(solve(c.replace(s1=0.06), SLOPE_DEG, SLOPE_SPEED).holding_moment) / SLOPE_DEG, 2),
           "m_60": fixed(abs(solve(c.replace(m=60.0), SLOPE_DEG, SLOPE_SPEED).holding_moment) / SLOPE_DEG, 2)}
    base = abs(solve(c, SLOPE_DEG, SLOPE_SPEED).holding_moment)
    rolling = abs(solve(c.replace(main_rolling_scale=1.0), SLOPE_DEG, SLOPE_SPEED).holding_moment)
    out["rolling_pct"] = sig(100 * (rolling - base) / base, 1)
    import math

    per_kg_m = c.g * math.sin(math.radians(1.0))          # N m/deg per kg m of m s1 (leading order)
    lo_ms1, hi_ms1 = 0.25 / per_kg_m, 1.80 / per_kg_m      # Richter et al. 2007's range, N m/deg
    out.update(ms1_lo=sig(lo_ms1, 2), ms1_hi=sig(hi_ms1, 2),
               s1_lo_cm=fixed(100 * lo_ms1 / c.m, 0), s1_hi_cm=fixed(100 * hi_ms1 / c.m, 0), mass=f"{c.m:g}")
    eq1 = solve(c, 1.0, SLOPE_SPEED)
    out["rim_per_deg"] = sig(drive_report(c, eq1, "handrim")["handrim_force_difference_N"], 2)
    return out


@group("slope_stability", "stability.study.slope_stability.stability_vs_speed(chair, cross_deg, [0.75]) and "
       "grade_run(chair, -3, 0.75, duration=2, n=2)")
def slope_stability() -> dict:
    """Largest real part level and on 6 deg, and a 3 deg downhill grade's effect on the E&J Premier."""
    import math

    from stability.study.slope_stability import grade_run, stability_vs_speed

    ej, fc = _preset("ej-premier"), _preset("ej-premier-front-caster")
    out = {}
    for key, c in (("ej", ej), ("fc", fc)):
        for deg in (0.0, 6.0):
            st = stability_vs_speed(c, deg, [SLOPE_SPEED], critical=False)
            out[f"{key}_{deg:g}"] = fixed(float(st.max_real[0]), 3)
    g = grade_run(ej, -3.0, SLOPE_SPEED, duration=2.0, n=2)
    out.update(grade_u0=fixed(g.speeds[0], 2), grade_u1=fixed(g.speeds[-1], 2),
               grade_l0=fixed(g.max_real[0], 2), grade_l1=fixed(g.max_real[-1], 2),
               grade_d0=fixed(math.log(2) / g.max_real[0], 2), grade_d1=fixed(math.log(2) / g.max_real[-1], 2))
    return out


# --- docs/driver.md ---------------------------------------------------------------------------------------

DRIVER_CHAIRS = ("ej-premier", "revised", "power-fwd")
DRIVER_TAUS = (0.2, 0.3, 0.4, 0.5)


@group("driver_limits", "python -m stability.critical_speed --chair NAME --reaction-time TAU "
       "(stability.driver.linear.human_limit(chair, Driver(TAU)))")
def driver_limits() -> dict:
    """The divergence rule against the delayed loop, presets x reaction times."""
    from stability.driver.linear import human_limit
    from stability.driver.model import Driver

    rows, out = [], {}
    worst = (0.0, "", 0.0)
    usual = 0.0
    for name in DRIVER_CHAIRS:
        c = _preset(name)
        for tau in DRIVER_TAUS:
            h = human_limit(c, Driver(tau))
            rel = abs(h.loop_speed_m_s - h.rule_speed_m_s) / max(h.loop_speed_m_s, h.rule_speed_m_s)
            if rel > worst[0]:
                worst = (rel, name, tau)
            if tau >= 0.3:
                usual = max(usual, rel)
            mark = lambda side: "> " if side == ">" else ("< " if side == "<" else "")  # noqa: E731
            rows.append((name, f"{tau:g}", mark(h.rule_side) + fixed(h.rule_speed_m_s, 2),
                         mark(h.loop_side) + fixed(h.loop_speed_m_s, 2), pct(rel), h.limited_by))
            out[f"{name}.{tau:g}.rule"] = fixed(h.rule_speed_m_s, 2)
            out[f"{name}.{tau:g}.loop"] = fixed(h.loop_speed_m_s, 2)
    out["worst_pct"], out["worst_chair"], out["worst_tau"] = pct(worst[0]), worst[1], f"{worst[2]:g}"
    out["usual_pct"] = pct(usual)
    out["table"] = Table(("chair", "tau (s)", "divergence rule (m/s)", "delayed loop (m/s)",
                          "lower by (%)", "lower"), tuple(rows))
    return out


@group("driver_settings", "stability.driver.linear.PADE_ORDER, stability.study.lane (LANE_HALF_WIDTH_M, "
       "LANE_LENGTH_M, LANE_SPEEDS_M_S), stability.driver.REACTION_TIME_S", cheap=True)
def driver_settings() -> dict:
    """The driver model's fixed settings, read from the code (not results, but quoted from one place)."""
    from stability import driver
    from stability.driver.linear import PADE_ORDER
    from stability.study import lane

    return {"pade": str(PADE_ORDER), "pade2": str(2 * PADE_ORDER),
            "half_width": f"{lane.LANE_HALF_WIDTH_M:g}", "length": f"{lane.LANE_LENGTH_M:g}",
            "top": f"{lane.LANE_SPEEDS_M_S[-1]:g}", "tau": f"{driver.REACTION_TIME_S:g}",
            "sample_ms": f"{1e3 * lane.SAMPLE_TIME_S:g}"}


@group("tracking", "stability.driver.tracking (constants, escape_factor())", cheap=True)
def tracking() -> dict:
    """The critical tracking task's settings (read from the code) and its escape factor (computed)."""
    from stability.driver import tracking as T

    e = T.escape_factor()
    means = [m for _, m in e.by_tau]
    f = T.DISTURBANCE_FREQUENCY_RATIOS
    first = T.escape_factor(T.PRACTICE_RAMP_S_PER_S, lambda0_1_s=1.0 / T.FIRST_TIME_CONSTANT_S)
    off = {g: T.escape_factor(gains=(g,)).mean for g in (0.9, 0.95, 1.05, 1.1)}
    return {"first_mean": fixed(first.mean, 2), "first_sd": fixed(first.sd, 2),
            "practice_ramp": f"{T.PRACTICE_RAMP_S_PER_S:g}", "first_tc": f"{T.FIRST_TIME_CONSTANT_S:g}",
            "start": f"{T.START_FRACTION:g}", "deadband_pct": f"{100 * T.INPUT_DEADBAND:g}",
            "early_pct": f"{100 * (T.EARLY_RISE - 1):g}",
            **{f"e_gain_{g:g}": fixed(v, 2) for g, v in off.items()},
            **{f"long_pct_{g:g}": f"{100 * (e.mean / v - 1):.0f}" for g, v in off.items()},
            "ramp": f"{T.RAMP_S_PER_S:g}", "input": f"{T.INPUT_LIMIT_1_S:g}", "frame_hz": f"{1 / T.FRAME_S:.0f}",
            "f_lo": f"{f[0]:g}", "f_hi": f"{f[-1]:g}", "amp": f"{T.DISTURBANCE_AMPLITUDE_RATIO:g}",
            "tau_lo": f"{T.CALIBRATION_TAU_S[0]:g}", "tau_hi": f"{T.CALIBRATION_TAU_S[-1]:g}",
            "seeds": str(T.CALIBRATION_SEEDS), "e_mean": fixed(e.mean, 3), "e_sd": fixed(e.sd, 3),
            "e_n": str(e.samples), "e_lo": fixed(e.low, 2), "e_hi": fixed(e.high, 2),
            "e_by_lo": fixed(min(means), 2), "e_by_hi": fixed(max(means), 2)}


@group("driver_lane", "python -m stability.critical_speed --chair NAME --reaction-time 0.3 "
       "(stability.study.lane.lane_limit(chair, Driver(0.3)))")
def driver_lane() -> dict:
    """The nonlinear lane limit at 0.3 s, ej-premier and power-fwd (a bound printed with its side)."""
    from stability.driver.model import Driver
    from stability.study.lane import lane_limit

    out = {}
    for name in ("ej-premier", "power-fwd"):
        lim = lane_limit(_preset(name), Driver(0.3))
        out[name] = ("" if lim.side == "=" else f"{lim.side} ") + fixed(lim.speed_m_s, 2)
    return out


#: The lane-operator decision's delay change, s: how far the lane limit moves when the delay changes this little.
LANE_OPERATOR_DTAU = 0.02
#: The lane-operator decision's linear case: chair, speed (m/s), delay (s) (where the single-run search missed the
#: notch by the most, stability.study.lane.LANE_STARTS).
LANE_OPERATOR_LINEAR = ("ej-premier", 1.25, 0.3)
#: The lane-operator decision's cases (docs/driver.md, "The lane operator"): chair, delay (s), push factor; the
#: pushes over half, once and twice the default, the delays 0.3 and 0.5 s and each -+ LANE_OPERATOR_DTAU.
LANE_OPERATOR_CASES = (*((n, t, f) for n, t in (("ej-premier", 0.3), ("ej-premier", 0.5), ("power-fwd", 0.3))
                         for f in (0.5, 1.0, 2.0)),
                       *(("ej-premier", round(t + d, 6), 1.0) for t in (0.3, 0.5)
                         for d in (-LANE_OPERATOR_DTAU, LANE_OPERATOR_DTAU)))


@group("driver_operator", "stability.study.lane.lane_limit(chair, Driver(tau), RunSpec(push_force=factor x "
       "default)) with three lane operators: the robust one (lane_gains' default, DELAY_SPREAD), the notch one "
       "(DELAY_SPREAD = 0) and the notch one by the single-run search used before (LANE_STARTS, LANE_RESTARTS = 1, "
       "0); stability.driver.loop abscissas at the E&J Premier, 1.25 m/s")
def driver_operator() -> dict:
    """The lane operator decision's measurements: the linear margin over the delay and the nonlinear lane limits
    of the three operators, with the push and delay monotonicity."""
    import contextlib
    from unittest import mock

    from stability.driver.loop import _Loop, delay_spread
    from stability.driver.model import Driver
    from stability.settings.run import RunSpec
    from stability.study import lane

    out: dict = {"spread_pct": f"{100 * lane.DELAY_SPREAD:g}", "starts": str(lane.ROBUST_STARTS),
                 "restarts": str(lane.ROBUST_RESTARTS)}
    # the linear margin at tau and tau -+ LANE_OPERATOR_DTAU
    name, speed, tau = LANE_OPERATOR_LINEAR
    A, B, C = lane.lane_plant(_preset(name), speed)
    ops = {"robust": lane.lane_gains(_preset(name), speed, Driver(tau)),
           "notch": lane.lane_gains(_preset(name), speed, Driver(tau), spread=0.0)}
    for key, g in ops.items():
        for lab, t in (("lo", tau - LANE_OPERATOR_DTAU), ("mid", tau), ("hi", tau + LANE_OPERATOR_DTAU)):
            out[f"{key}.{lab}"] = fixed(_Loop(A, B, C, t, lane.PADE_ORDER).abscissa_one(g.gains), 2)
    out["robust.worst"] = fixed(ops["robust"].abscissa_1_s, 2)
    out["speed"], out["tau"] = f"{speed:g}", f"{tau:g}"
    out["tau_lo"], out["tau_hi"] = (f"{t:g}" for t in delay_spread(tau, lane.DELAY_SPREAD)[::2])
    variants = {"single": {"DELAY_SPREAD": 0.0, "LANE_STARTS": 1, "LANE_RESTARTS": 0},
                "notch": {"DELAY_SPREAD": 0.0}, "robust": {}}
    limits: dict = {}
    for key, patch in variants.items():
        with mock.patch.multiple(lane, **patch) if patch else contextlib.nullcontext():
            for name, tau, f in LANE_OPERATOR_CASES:
                spec = RunSpec()
                lim = lane.lane_limit(_preset(name), Driver(tau), spec.replace(push_force=f * spec.push_force))
                limits[key, name, tau, f] = lim
    show = {k: ("" if v.side == "=" else f"{v.side} ") + fixed(v.speed_m_s, 2) for k, v in limits.items()}
    rows = []
    for name, tau, f in LANE_OPERATOR_CASES:
        push = limits["robust", name, tau, f].push_N_s
        rows.append((name, f"{tau:g}", f"{push:g}", *(show[k, name, tau, f] for k in variants)))
        for k in variants:
            out[f"{k}.{name}.{tau:g}.{push:g}"] = show[k, name, tau, f]
    out["table"] = Table(("chair", "tau (s)", "push (N s)", "single-run search, before (m/s)", "notch (m/s)",
                          "robust (m/s)"), tuple(rows))
    # monotonicity: the limit must not rise with the push (per chair and delay) nor with the delay
    for k in variants:
        rises, worst = 0, 0.0
        groups = sorted({(n, t) for n, t, f in LANE_OPERATOR_CASES if f != 1.0})
        for n, t in groups:
            v = [limits[k, n, t, f].speed_m_s for f in (0.5, 1.0, 2.0)]
            rise = max(v[j] - v[i] for i in range(3) for j in range(i + 1, 3))
            rises += rise > 0
            worst = max(worst, rise)
        out[f"{k}.push_rises"], out[f"{k}.push_rise"] = str(rises), fixed(worst, 2)
        taus = sorted({t for n, t, f in LANE_OPERATOR_CASES if n == "ej-premier" and f == 1.0})
        v = [limits[k, "ej-premier", t, 1.0].speed_m_s for t in taus]
        out[f"{k}.delay_rises"] = str(sum(b > a for a, b in zip(v[:-1], v[1:], strict=True)))
        out[f"{k}.delay_jump"] = fixed(max(abs(limits[k, "ej-premier", round(t + d, 6), 1.0].speed_m_s
                                                  - limits[k, "ej-premier", t, 1.0].speed_m_s)
                                              for t in (0.3, 0.5) for d in (-LANE_OPERATOR_DTAU, LANE_OPERATOR_DTAU)),
                                          2)
    out["dtau"] = f"{LANE_OPERATOR_DTAU:g}"
    out["push_groups"] = str(len({(n, t) for n, t, f in LANE_OPERATOR_CASES if f != 1.0}))
    return out


# --- docs/simulator.md, README.md: compile time ------------------------------------------------------------

@group("compile_time", "python -m stability.simulate --speed 0.75 --quiet, twice, in fresh processes with an "
       "empty NUMBA_CACHE_DIR (CPU time of the child: user + sys)")
def compile_time() -> dict:
    """CPU time of the first ``simulate`` command with an empty numba cache, and of the next one (cached)."""
    import os
    import resource
    import subprocess
    import sys
    import tempfile

    from value_groups import ROOT

    def child_cpu(env: dict) -> float:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, "-m", "stability.simulate", "--speed", "0.75", "--quiet"], cwd=ROOT,
                       env=env, check=True, stdout=subprocess.DEVNULL)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)

    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache, "PYTHONPATH": str(ROOT)}
        first = child_cpu(env)
        second = child_cpu(env)
    return {"first_s": sig(first, 2), "cached_s": sig(second, 2), "ratio": f"{first / second:.0f}"}


# --- docs/assist.md ---------------------------------------------------------------------------------------

@group("assist_weights", "stability.assist.loop_margins(stability.assist.design(power_fwd, 1.0, 'full-state'"
       "[, weights=Weights(max_yaw_rate_deg_s=10)])) and closed_loop_poles(...)")
def assist_weights() -> dict:
    """The full-state design at 1 m/s with and without a 10 deg/s yaw-rate weight: margins, slowest poles."""
    import warnings

    import numpy as np

    from stability import assist
    from stability.assist.weights import Weights
    from stability.settings import defaults as D

    c = _preset("power-fwd")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)    # polynomial overflow inside stability_margins
        plain_d = assist.design(c, 1.0, "full-state")
        plain = assist.loop_margins(plain_d)
        rate = assist.loop_margins(assist.design(c, 1.0, "full-state", weights=Weights(max_yaw_rate_deg_s=10.0)))
    poles = assist.closed_loop_poles(plain_d)
    slow = poles[np.argmax(poles.real)]
    budget = D.TORQUE_LIMIT / 2
    return {"budget_n_m": f"{budget:g}", "gain_per_deg": f"{budget / D.MAX_HEADING_ERROR:g}",
            "pole_re": fixed(slow.real, 1), "pole_im": fixed(abs(slow.imag), 1),
            "crossover": sig(plain.crossover_rad_s, 2), "crossover_rate": sig(rate.crossover_rad_s, 2),
            "delay_ms": fixed(1e3 * plain.delay_margin_s, 1), "delay_rate_ms": fixed(1e3 * rate.delay_margin_s, 1),
            "cut_pct": pct(1 - rate.delay_margin_s / plain.delay_margin_s)}


@group("assist_overshoot", "control.step_info(stability.assist.tracking.closed_loop(stability.assist.design(power_fwd, "
       "U, DESIGN), command_filter=0)[0, 0]) for U in 0.5:3:0.25 and both designs")
def assist_overshoot() -> dict:
    """Overshoot of a yaw-rate step through feedforward and integral alone (no reference model), linear loop."""
    import control
    import numpy as np

    from stability import assist
    from stability.assist.tracking import closed_loop

    c = _preset("power-fwd")
    over = [control.step_info(closed_loop(assist.design(c, u, kind), command_filter=0.0)[0, 0])["Overshoot"]
            for kind in assist.DESIGNS for u in np.arange(0.5, 3.0001, 0.25)]
    return {"min_pct": fixed(min(over), 0), "max_pct": fixed(max(over), 0)}


# --- docs/layouts.md --------------------------------------------------------------------------------------

@group("layout_mid", "stability.layout.statics.static_loads(stability.layout.presets.layout_preset('mid-wheel-drive'))",
       cheap=True)
def layout_mid() -> dict:
    """The mid-wheel-drive base's share of the weight on its drive wheels."""
    from stability.layout.presets import layout_preset
    from stability.layout.statics import contacts, static_loads

    lay = layout_preset("mid-wheel-drive")
    loads = static_loads(lay)
    drive = sum(w for (name, *_), w in zip(contacts(lay), loads, strict=True) if name.startswith("wheel"))
    return {"drive_pct": pct(drive / sum(loads))}


@group("layout_equal", "stability.study.layout_equal_instability.layout_equal_instability(Layout.from_chair(revised)) "
       "and (power-fwd-base, 80 N push)")
def layout_equal() -> dict:
    """The equal-instability speed on the layout runs: the revised chair as a layout (the thesis engine's speed) and
    the front-wheel-drive base under an 80 N push (the 40 N push leaves every power base above 3 m/s)."""
    from stability.chair import resolve
    from stability.layout.model import Layout
    from stability.layout.presets import layout_preset
    from stability.settings.run import RunSpec
    from stability.study.equal_instability import equal_instability_speed
    from stability.study.layout_equal_instability import layout_equal_instability

    rev = layout_equal_instability(Layout.from_chair(resolve("revised")))
    short = equal_instability_speed(resolve("revised"))
    fwd = layout_equal_instability(layout_preset("power-fwd-base"), RunSpec(push_force=80.0))
    return {"revised": sig(rev.speed, 4), "revised_short": sig(short.speed, 4), "fwd80": sig(fwd.speed, 3)}


@group("layout_advise", "stability.advise.layout_measures.layout_linear_measures(layout presets) and the advisor's "
       "levers (stability.advise.layout_levers)", cheap=True)
def layout_advise() -> dict:
    """The advisor's limits on the power bases: the shimmy margin of the row nearest a boundary, the number of
    single changes."""
    from stability.advise.layout_levers import layout_lever_changes
    from stability.advise.layout_measures import layout_linear_measures
    from stability.layout.presets import layout_preset

    out = {}
    for key, name in (("fwd", "power-fwd-base"), ("mid", "mid-wheel-drive")):
        lay = layout_preset(name)
        m = layout_linear_measures([lay], speeds=(0.5, 0.75, 1.0))[0]
        out[f"{key}_margin_cm"] = fixed(100 * (m.shimmy_margin_m.value or 0.0), 2)
        out[f"{key}_row"] = m.shimmy_row
        out[f"{key}_changes"] = str(len(layout_lever_changes(lay)[0]))
    return out


def _assist_rows(kind: str, speeds, drive=None):
    """Gain-table rows (margins only, no nonlinear check) of the power-fwd schedule."""
    import warnings

    from stability import assist
    from stability.assist.tables import gain_table

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # python-control's overflow note at a huge candidate frequency (harmless)
        kw = {} if drive is None else {"drive": drive}
        return gain_table(assist.schedule(_preset("power-fwd"), speeds, kind, **kw), check=False)


def _gain_db(m) -> float:
    import math

    return 20 * math.log10(min(m.gain_margin_upper, 1.0 / m.gain_margin_lower))


def _span(values, fmt) -> str:
    lo, hi = fmt(min(values)), fmt(max(values))
    return lo if lo == hi else f"{lo}-{hi}"


@group("assist_sampled", "python -m stability.assist --chair power-fwd --design gyro|full-state --no-check "
       "(gain_table(schedule(power_fwd, 0.5:3:0.25, DESIGN), check=False): margin_pair.continuous / .discrete)")
def assist_sampled() -> dict:
    """Continuous and sampled margins of the default schedule, with and without the motor lag."""
    import math

    import numpy as np

    from stability.chair.power import DriveTrain
    from stability.settings import defaults as D

    speeds = np.arange(0.5, 3.0001, 0.25)
    out = {}
    gyro_rows = []
    for kind in ("gyro", "full-state"):
        rows = _assist_rows(kind, speeds)
        if kind == "gyro":
            gyro_rows = rows
        for side in ("continuous", "discrete"):
            ms = [getattr(r.margin_pair, side) for r in rows]
            k = f"{kind}.{side}"
            out[f"{k}.gain_db"] = _span([_gain_db(m) for m in ms], lambda x: fixed(x, 1))
            out[f"{k}.phase_deg"] = _span([m.phase_margin_deg for m in ms], lambda x: fixed(x, 0))
            out[f"{k}.delay_ms"] = _span([1e3 * m.delay_margin_s for m in ms], lambda x: fixed(x, 0))
            out[f"{k}.return_difference"] = _span([m.min_return_difference for m in ms], lambda x: fixed(x, 2))
    no_lag = _assist_rows("gyro", speeds, DriveTrain(motor_time_constant=0.0))
    out["gyro.no_lag.phase_deg"] = _span([r.margin_pair.continuous.phase_margin_deg for r in no_lag],
                                         lambda x: fixed(x, 0))
    out["gyro.no_lag.return_difference"] = _span([r.margin_pair.continuous.min_return_difference for r in no_lag],
                                                  lambda x: fixed(x, 1))
    t = 1.0 / D.SAMPLE_RATE_HZ
    sampled_delay = [1e3 * r.margin_pair.discrete.delay_margin_s for r in gyro_rows]
    out["added_delay_ms"] = f"{1.5e3 * t:g}"
    out["added_phase_deg"] = fixed(math.degrees(1.5 * t * 20.0), 1)
    out["times_added"] = _span([d / (1.5e3 * t) for d in sampled_delay], lambda x: fixed(x, 0))
    return out


@group("assist_reverse", "stability.linear.state_matrices(stability.assist.reversed_chair(power_fwd), U) "
       "(largest real part of the eigenvalues)", cheap=True)
def assist_reverse() -> dict:
    """The reversed front-wheel-drive chair's slowest eigenvalue at 0.5 and 3 m/s."""
    import numpy as np

    from stability import assist, linear

    rc = assist.reversed_chair(_preset("power-fwd"))
    out = {}
    for u in (0.5, 3.0):
        a = linear.state_matrices(rc, u, "exact", "free")[0]
        out[f"{u:g}"] = sig(float(np.max(np.linalg.eigvals(a).real)), 2)
    return out


@group("assist_standstill", "stability.assist.pivot_inertia(power_fwd); eigenvalues of "
       "stability.linear.state_matrices(power_fwd, 0.02)", cheap=True)
def assist_standstill() -> dict:
    """The pivot inertia about the drive-axle midpoint; the linear model's eigenvalues at 0.02 m/s."""
    import numpy as np

    from stability import assist, linear

    c = _preset("power-fwd")
    u = 0.02
    e = np.sort(np.linalg.eigvals(linear.state_matrices(c, u, "exact", "free")[0]).real)
    return {"pivot_inertia": fixed(assist.pivot_inertia(c), 1), "u": f"{u:g}",
            "fast": ", ".join(f"{x:.2g}".replace("e+0", "e") for x in e[:3]),
            "swivel": fixed(-u / c.trail, 2), "swivel_eig": fixed(e[3], 2), "divergence_per_u": fixed(e[-1] / u, 2)}


@group("assist_faults", "python -m stability.assist --chair power-fwd --speeds 0.5:5:0.25 --faults "
       "(faults.fault_runs(schedule(power_fwd, 0.5:5:0.25, 'gyro')), top_speed.top_speed(...))")
def assist_faults() -> dict:
    """Every single sensor fault at every speed to 5 m/s on level ground and 2 deg; the safe top speed."""
    import warnings

    import numpy as np

    from stability import assist
    from stability.assist import faults as F
    from stability.assist import top_speed as TS

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # python-control's overflow note at a huge candidate frequency (harmless)
        full = assist.schedule(_preset("power-fwd"), np.arange(0.5, 5.01, 0.25), "gyro")
        rows = F.fault_runs(full)
        torques = assist.torque_requirement(full, tuple(float(s) for s in full.speeds))
        gain = assist.tables.gain_table(full, check=False)
        turn = TS.full_turn_peaks(full, [3.0, 5.0])
        ts = TS.top_speed(full, gain, torques, rows, turn)
    low = [r for r in rows if r.speed_m_s <= 3.0 + 1e-9]
    by: dict = {}
    for r in rows:
        by.setdefault(r.fault, []).append(r)
    low_by: dict = {}
    for r in low:
        low_by.setdefault(r.fault, []).append(r)

    def times(rs) -> str:
        t = [r.detection_time_s for r in rs if r.detected]
        return _span(t, lambda x: sig(x, 2)) if t else "never"

    worst_h = max(low, key=lambda r: r.peak_heading_error_deg)
    worst_d = max(low, key=lambda r: r.drift_m)
    out = {"runs": str(len(low)),
           "all_safe": "every fault safe" if all(r.outcome == "safe" for r in low) else "NOT every fault safe",
           "peak_heading": sig(worst_h.peak_heading_error_deg, 3), "peak_heading_fault": worst_h.fault,
           "peak_heading_speed": f"{worst_h.speed_m_s:g}", "peak_heading_slope": f"{worst_h.slope_deg:g}",
           "drift": sig(worst_d.drift_m, 3), "drift_fault": worst_d.fault, "drift_speed": f"{worst_d.speed_m_s:g}",
           "pairs": str(len(by["gyro_stuck_last"])), "low_pairs": str(len(low_by["gyro_dropout_1_s"]))}
    for f in ("gyro_bias_5_deg_s", "gyro_bias_20_deg_s", "gyro_sign_inverted", "gyro_noise_x10",
              "gyro_stuck_last", "gyro_stuck_zero"):
        src = by[f] if f.startswith("gyro_stuck") else low_by[f]
        out[f"{f}.times"] = times(src)
        out[f"{f}.detected"] = str(sum(r.detected for r in src))
    out["gyro_dropout_1_s.detected"] = str(sum(r.detected for r in low_by["gyro_dropout_1_s"]))
    unstable = [float(np.max(np.linalg.eigvals(d.model_A).real)) for d in full.designs
                if d.speed <= 3.0 + 1e-9 and d.speed > 0]
    out["unassisted_rate_lo"], out["unassisted_rate_hi"] = sig(unstable[0], 2), sig(unstable[-1], 2)
    lvl = {r.speed_m_s: r for r in by["gyro_bias_1_deg_s"] if r.slope_deg == 0.0}
    out["unassisted_heading_1"] = sig(lvl[1.0].unassisted_heading_error_deg, 2)
    out["unassisted_heading_3"] = sig(lvl[3.0].unassisted_heading_error_deg, 2)
    bias1 = {(r.speed_m_s, r.slope_deg): r.drift_m for r in by["gyro_bias_1_deg_s"]}
    for u in (3.0, 3.5, 3.75, 5.0):
        out[f"bias1_drift_{u:g}"] = f"{bias1[u, 0.0]:.3f} m (level) / {bias1[u, 2.0]:.3f} m (2 deg)"
    out["top_speed"] = f"{ts.safe_top_speed_m_s:g}"
    out["limited_by"] = ts.limited_by
    checks = {c.speed_m_s: c.values for c in ts.checks}
    for u in (3.0, 5.0):
        v = checks[u]
        out[f"at_{u:g}"] = (f"gain {v['gain_margin'][0]:.1f} dB, phase {v['phase_margin'][0]:.1f} deg, delay margin "
                            f"{v['delay_margin'][0]:.1f} ms")
        out[f"turn_{u:g}"] = fixed(turn[u], 1)
    return out


# --- docs/getting-started.md ------------------------------------------------------------------------------

@group("getting_started", "python -m stability.critical_speed (stability.analyse(stability.preset('ej-premier')))",
       cheap=True)
def getting_started() -> dict:
    """The default chair's doubling time at 0.75 m/s."""
    import stability

    div = {d.speed: d for d in stability.analyse(_preset("ej-premier")).divergence}
    return {"doubling": sig(div[0.75].time_to_double, 2)}


# --- docs/simulator.md: the studies' answers against the step ----------------------------------------------

def _step_rows(law: str) -> Table:
    """Critical impulses and equal-instability speeds at several fixed steps with one pin-friction law, and
    with the adaptive scheme (event-located stick-slip)."""
    from stability.settings.run import RunSpec
    from stability.study import critical_impulses, equal_instability_speeds

    def run(dt, model="exact"):
        return RunSpec(scheme="adaptive", model=model) if dt is None else RunSpec(dt=dt, friction_law=law,
                                                                                  model=model)

    def ci(chair, speed):
        return lambda dt: f"{critical_impulses(chair, [speed], run(dt))[0].impulse_Ns:.3g}"

    def ei(chair, model, digits):
        def f(dt):
            r = equal_instability_speeds([chair], run(dt, model), progress=False)[0]
            return "above 3" if r.status == "above" else f"{r.speed:.{digits}g}"
        return f

    ej, pf, rv = _preset("ej-premier"), _preset("power-fwd"), _preset("revised")
    pf6 = pf.replace(trail=0.06)
    if law == "kinetic":
        steps = (1.0, 0.5, 0.25, 0.125, None)
        rows = [("E&J Premier, critical impulse at 0.75 m/s (N s)", ci(ej, 0.75), (1.0, 0.5, 0.25)),
                ("E&J Premier, critical impulse at 1.0 m/s (N s)", ci(ej, 1.0), steps),
                ("power-fwd with a 6 cm trail, critical impulse at 0.75 m/s (N s)", ci(pf6, 0.75), (1.0, 0.5, 0.25)),
                ("revised, equal-instability speed (m/s, thesis model)", ei(rv, "thesis", 4), (1.0, 0.5, 0.25)),
                ("power-fwd, equal-instability speed (m/s, exact model)", ei(pf, "exact", 3), steps)]
    else:
        steps = (1.0, 0.5, 0.25, None)
        rows = [("E&J Premier, critical impulse at 0.75 m/s (N s)", ci(ej, 0.75), steps),
                ("E&J Premier, critical impulse at 1.0 m/s (N s)", ci(ej, 1.0), steps),
                ("E&J Premier, critical impulse at 1.2 m/s (N s)", ci(ej, 1.2), steps),
                ("power-fwd, critical impulse at 1.5 m/s (N s)", ci(pf, 1.5), steps),
                ("power-fwd with a 6 cm trail, critical impulse at 0.75 m/s (N s)", ci(pf6, 0.75), steps),
                ("revised, equal-instability speed (m/s, thesis model)", ei(rv, "thesis", 4), steps),
                ("power-fwd, equal-instability speed (m/s, exact model)", ei(pf, "exact", 3), steps)]
    header = ("chair, measure" + (" (stick-slip)" if law != "kinetic" else ""),
              *("adaptive" if s is None else f"{s:g} ms" for s in steps))
    body = []
    for label, f, used in rows:
        body.append((label, *(f(None if s is None else s * 1e-3) if s in used else "" for s in steps)))
    return Table(header, tuple(body))


@group("step_kinetic", "stability.study.critical_impulses / equal_instability_speeds with "
       "RunSpec(dt=DT, friction_law='kinetic') and RunSpec(scheme='adaptive')")
def step_kinetic() -> dict:
    """Program WCHAIR's kinetic pin friction: the measures against the step."""
    t = _step_rows("kinetic")
    return {"table": t, **_step_cells(t)}


@group("step_stick_slip", "stability.study.critical_impulses / equal_instability_speeds with "
       "RunSpec(dt=DT, friction_law='stick-slip') and RunSpec(scheme='adaptive')")
def step_stick_slip() -> dict:
    """The stick-slip law: the measures against the step."""
    t = _step_rows("stick-slip")
    return {"table": t, **_step_cells(t)}


def _step_cells(t: Table) -> dict:
    """The power-fwd 6 cm chair's critical impulse per step (``pf6.1``, ``pf6.0.5``, ..., ``pf6.adaptive``)."""
    row = next(r for r in t.rows if r[0].startswith("power-fwd with a 6 cm trail"))
    return {f"pf6.{h.removesuffix(' ms')}": v for h, v in zip(t.header[1:], row[1:], strict=True) if v}


# --- docs/tipping.md --------------------------------------------------------------------------------------

TIP_CHAIRS = ("ej-premier", "ej-premier-front-caster", "revised", "power-fwd", "manual-front-caster")


@group("tipping", "python -m stability.tipping --chair NAME (stability.tipping.tip_angles(chair))", cheap=True)
def tipping() -> dict:
    """ISO 7176-1 static tip angles of the presets, and the E&J Premier's closed form toward its casters."""
    import math

    from stability.tipping import tip_angles

    rows, out = [], {}
    for name in TIP_CHAIRS:
        t = tip_angles(_preset(name))
        cells = (t.toward_main_wheels_deg, t.toward_casters_deg, t.lateral_left_deg, t.lateral_right_deg,
                 t.smallest_deg)
        rows.append((name, *(fixed(v, 1) for v in cells)))
        out[f"{name}.main"], out[f"{name}.casters"] = fixed(cells[0], 1), fixed(cells[1], 1)
        out[f"{name}.side"] = fixed(cells[2], 1)
    ej = _preset("ej-premier")
    arm = ej.s2 - ej.trail
    out.update(ej_arm=f"{arm:.3f}", ej_h=f"{ej.h:.2f}", ej_closed=fixed(math.degrees(math.atan2(arm, ej.h)), 2),
               ej_slope=fixed(math.degrees(math.atan2(arm, ej.h)), 0), revised_s1=f"{_preset('revised').s1:g}")
    out["table"] = Table(("chair", "toward main wheels (deg)", "toward casters (deg)", "left (deg)", "right (deg)",
                          "smallest (deg)"), tuple(rows))
    return out


# --- docs/shimmy.md ---------------------------------------------------------------------------------------

@group("shimmy_band", "python -m stability.shimmy --chair NAME --speeds 1 "
       "(stability.shimmy.band.shimmy_band(chair, [1.0]))")
def shimmy_band_group() -> dict:
    """The shimmy-free trail band at 1 m/s for the presets and the measured example chair."""
    import math

    from value_groups import ROOT

    from stability import chair as chair_mod
    from stability.shimmy.band import shimmy_band

    chairs = [chair_mod.preset(n) for n in chair_mod.preset_names()]
    chairs.append(chair_mod.load(ROOT / "docs" / "examples" / "measured_chair.toml"))

    def edge(x: float) -> str:
        return "every trail shimmies" if x == -math.inf else f"{x * 100:+.2f}"

    rows = []
    for c in chairs:
        b = shimmy_band(c, [1.0])
        lo, hi = b.shimmy_margin_interval_m
        rows.append((c.name, f"{c.trail * 100:g}", b.describe(0), f"{b.shimmy_margin_m * 100:+.2f}",
                     f"{b.damping_ratio[0]:.4f}", f"{edge(lo)} to {edge(hi)}"))
    return {"table": Table(("chair", "trail (cm)", "shimmy-free trail (cm)", "margin (cm)",
                            "damping ratio at its trail", "margin over the estimate ranges (cm)"), tuple(rows))}


# --- docs/advise.md: the advisor's table is in value_groups_advise.py -------------------------------------

@group("advise_linear", "stability.linear.eigenvalues_vs_speed(chair, [0.75]) (largest real part); "
       "sqrt(chair.i_z / chair.m)", cheap=True)
def advise_linear() -> dict:
    """The frictionless growth rates of the E&J Premier and the revised design, and the peak's s1."""
    import math

    import numpy as np

    from stability.linear import eigenvalues_vs_speed

    ej, rv = _preset("ej-premier"), _preset("revised")
    r_ej, r_rv = (float(np.max(eigenvalues_vs_speed(c, [0.75], track=False).real)) for c in (ej, rv))
    return {"ej": fixed(r_ej, 2), "revised": fixed(r_rv, 2), "peak_s1": f"{math.sqrt(ej.i_z / ej.m):.3f}",
            "revised_s1": f"{rv.s1:g}"}


# --- docs/studies.md --------------------------------------------------------------------------------------

#: The uncertainty file of docs/studies.md's nonlinear-interval table: s1 std 0.01 m, I_z std 0.3 kg m^2, both
#: pins' friction +-30 % uniform (one draw shared).
STUDIES_UNCERTAINTY = ('[pin_friction]\nfields = ["pin_friction_left", "pin_friction_right"]\n'
                       'distribution = "uniform"\nlow = -0.3\nhigh = 0.3\nrelative = true\n'
                       '\n[i_z]\ndistribution = "normal"\nstd = 0.3\n\n[s1]\ndistribution = "normal"\nstd = 0.01\n')


@group("studies_nonlinear", "python -m stability.critical_speed --chair NAME --uncertainty FILE --nonlinear "
       "(stability.study.uncertain.nonlinear_intervals(chair, loads_uncertainty(FILE)); 200 draws, seed 0)")
def studies_nonlinear() -> dict:
    """95 % intervals and variance shares of the critical impulse and the equal-instability speed."""
    from stability.study.uncertain import nonlinear_intervals
    from stability.uncertainty import loads_uncertainty

    names = {"pin_friction": "pin friction", "i_z": "I_z", "s1": "s1"}

    def shares(m) -> str:
        return ", ".join(f"{names.get(k, k)} {100 * s:.0f} %" for k, s in m.shares if round(100 * s) >= 1)

    rows, out = [], {}
    top = []
    for name in ("ej-premier", "revised"):
        iv = nonlinear_intervals(_preset(name), loads_uncertainty(STUDIES_UNCERTAINTY))
        k, e = iv.critical_impulse, iv.equal_instability
        rows.append((name, f"{k.nominal:.3g} N s, 95 %: {k.low:.4g}-{k.high:.4g} N s ({shares(k)})",
                     f"{e.nominal:.3g} m/s, 95 %: {e.low:.4g}-{e.high:.4g} ({shares(e)})"))
        top += [dict(m.shares).get("pin_friction", 0.0) for m in (k, e)]
    out["friction_share"] = _span([100 * x for x in top], lambda x: fixed(x, 0))
    out["table"] = Table(("chair", "critical impulse at 0.75 m/s", "equal-instability speed"), tuple(rows))
    return out


# --- docs/compare.md --------------------------------------------------------------------------------------

@group("compare_effects", "python -m stability.compare ej-premier revised "
       "(stability.compare.compute.single_effects(ej_premier, revised, 'revised'))", cheap=True)
def compare_effects() -> dict:
    """Single-parameter effects ej-premier -> revised and -> the front-caster chair; the growth rates."""
    import numpy as np

    from stability.compare.compute import single_effects
    from stability.linear import eigenvalues_vs_speed, zero_width

    ej, rv, fc = _preset("ej-premier"), _preset("revised"), _preset("ej-premier-front-caster")

    def num(x, nd):
        return "none" if x is None else ("+" if x >= 0 else "") + fixed(x, nd)

    es = single_effects(ej, rv, "revised")
    rows = [(f"{e.field} {e.reference_value:g} -> {e.value:g}", num(e.growth_rate, 4), num(e.locked_critical_speed, 2))
            for e in es.effects]
    rows += [("total", num(es.total_growth_rate, 4), num(es.total_locked_critical_speed, 2)),
             ("interaction", num(es.remainder_growth_rate, 4), num(es.remainder_locked_critical_speed, 2))]
    out = {"table": Table(("field", "growth rate at 0.75 m/s (1/s)", "locked critical speed (m/s)"), tuple(rows))}
    s1 = next(e for e in es.effects if e.field == "s1")
    out["s1_effect"] = num(s1.growth_rate, 3)
    r_ej, r_rv, r_fc = (float(np.max(eigenvalues_vs_speed(c, [0.75], track=False).real)) for c in (ej, rv, fc))
    out.update(ej=fixed(r_ej, 3), revised=fixed(r_rv, 3), rel_pct=signed(100 * (r_rv / r_ej - 1), 0), fc=fixed(r_fc, 2))
    ef = single_effects(ej, fc, "ej-premier-front-caster")
    cp = next(e for e in ef.effects if e.field == "caster_position")
    out["caster_position_effect"] = fixed(cp.growth_rate, 2)
    out["fc_kus"] = signed(zero_width(fc).understeer_coefficient, 4)
    import stability

    for key, c in (("ej_locked", ej), ("revised_locked", rv)):
        out[key] = fixed(stability.analyse(c).locked_crossings[0].speed, 1)
    return out


@group("shimmy_corners", "stability.shimmy.chair.critical_trail(ej_premier, 1.0, CasterCompliance("
       "relaxation_length=SIGMA, lateral_stiffness=K))")
def shimmy_corners() -> dict:
    """The E&J Premier's critical trail at 1 m/s over the two compliance estimates."""
    import math

    from stability.shimmy.band import TRAIL_SEARCH_M
    from stability.shimmy.chair import CasterCompliance, critical_trail

    ej = _preset("ej-premier")
    sigmas, ks = (0.01, 0.02, 0.04), (2e4, 5e4, 1e5, 2e5)
    rows = []
    for k in ks:
        cells = []
        for s in sigmas:
            t = critical_trail(ej, 1.0, CasterCompliance(relaxation_length=s, lateral_stiffness=k))
            cells.append(f"> {100 * TRAIL_SEARCH_M[1]:g}" if math.isinf(t) else fixed(100 * t, 1))
        rows.append((f"{k / 1e3:g} kN/m", *cells))
    return {"table": Table(("lateral stiffness \\ relaxation length", *(f"{1e3 * s:g} mm" for s in sigmas)),
                           tuple(rows))}


@group("shimmy_results", "python -m stability.shimmy --chair NAME --speeds 0.5,1,3 "
       "(stability.shimmy.chair.caster_summary(chair, [0.5, 1, 3]))", cheap=True)
def shimmy_results() -> dict:
    """Shimmy mode, critical trail and its range, and the pin-friction trail of three presets."""
    import math

    from stability.shimmy.band import TRAIL_SEARCH_M
    from stability.shimmy.chair import caster_summary

    def cm(x: float) -> str:
        return f"> {100 * TRAIL_SEARCH_M[1]:g} cm" if math.isinf(x) else f"{100 * x:.1f} cm"

    rows = []
    for name in ("ej-premier", "revised", "ej-premier-front-caster"):
        c = _preset(name)
        s = caster_summary(c, [0.5, 1.0, 3.0])
        rows.append((name, f"{100 * c.trail:g} cm",
                     f"{s.shimmy_frequency_hz[1]:.1f} Hz, {'damped' if s.stable[1] else 'GROWING'}",
                     cm(s.critical_trail[1]), f"{cm(s.critical_trail_low[1])} to {cm(s.critical_trail_high[1])}",
                     " / ".join(f"{100 * x:.1f}" for x in s.friction_trail) + " cm"))
    return {"table": Table(("chair", "trail", "shimmy mode", "linear shimmy below trail", "over the compliance range",
                            "pin friction holds 5 deg shimmy down to trail (0.5 / 1 / 3 m/s)"), tuple(rows))}


@group("shimmy_chair_model", "python -m stability.shimmy --chair NAME --speeds 0.5,1,3 --chair-model "
       "(stability.shimmy.chair_modes.chair_shimmy(chair, [0.5, 1, 3], pin=PIN); "
       "stability.shimmy.chair.critical_trail(chair, 1.0))")
def shimmy_chair_model() -> dict:
    """The chair model's shimmy mode with rigid and compliant pins against the towed wheel, two presets."""
    from stability.shimmy.chair import critical_trail
    from stability.shimmy.chair_modes import chair_shimmy
    from stability.shimmy.compliance import CasterCompliance

    sigma = CasterCompliance().relaxation_length
    rows = []
    for name in ("ej-premier", "revised"):
        c = _preset(name)
        for pin, nd in (("rigid", 1), ("compliant", 2)):
            m = chair_shimmy(c, [0.5, 1.0, 3.0], pin=pin)
            towed = f"L > sigma: {100 * sigma:.2f} cm" if pin == "rigid" else \
                f"{100 * critical_trail(c, 1.0):.2f} cm"
            rows.append((f"{name} ({100 * c.trail:g} cm)", pin,
                         " / ".join(f"{f:.{nd}f}" for f in m.frequency_hz) + " Hz",
                         " / ".join(f"{z:.3f}" for z in m.damping_ratio), f"{100 * m.critical_trail[1]:.2f} cm",
                         towed))
    return {"table": Table(("chair", "pins", "shimmy mode 0.5 / 1 / 3 m/s", "damping ratio 0.5 / 1 / 3 m/s",
                            "critical trail", "towed wheel (same inputs)"), tuple(rows))}


@group("assist_torque", "stability.assist.torque_requirement(schedule(power_fwd, 0.5:3:0.25, 'gyro')) "
       "(speeds 0.5, 1, 2, 3 m/s) and traction_limit(...)")
def assist_torque() -> dict:
    """Peak and RMS differential torque per wheel for the reference push and the commanded turn; the limits."""
    import dataclasses
    import warnings

    import numpy as np

    from stability import assist
    from stability.assist.driving import traction_limit

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # python-control's overflow note at a huge candidate frequency (harmless)
        sched = assist.schedule(_preset("power-fwd"), np.arange(0.5, 3.0001, 0.25), "gyro")
        rows = assist.torque_requirement(sched)

    def span(attr: str, f=lambda x: sig(x, 2)) -> str:
        return _span([abs(getattr(r, attr)) for r in rows], f)

    wet = dataclasses.replace(sched, drive=dataclasses.replace(sched.drive, traction_coefficient=0.4))
    return {"push_peak": span("push_peak_N_m"), "push_rms": span("push_rms_N_m", lambda x: fixed(x, 1)),
            "turn_peak": span("turn_peak_N_m", lambda x: fixed(x, 0)), "turn_rms": span("turn_rms_N_m"),
            "steady": span("steady_turn_N_m", lambda x: fixed(x, 0)),
            "motor": f"{rows[0].motor_limit_N_m:g}", "traction": fixed(traction_limit(sched), 0),
            "mu": f"{sched.drive.traction_coefficient:g}", "traction_wet": fixed(traction_limit(wet), 0)}


@group("assist_bias", "stability.assist.tracking.heading_drift(design(power_fwd, 1.0, 'gyro'), BIAS, 20, "
       "bias_time_constant=0 or GyroSensor().bias_time_constant_s)", cheap=True)
def assist_bias() -> dict:
    """Heading after 20 s of straight driving with a gyro bias, without and with the bias estimate (linear)."""
    import warnings

    from stability import assist
    from stability.assist.tracking import heading_drift
    from stability.assist.weights import GyroSensor

    tb = GyroSensor().bias_time_constant_s
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        d = assist.design(_preset("power-fwd"), 1.0, "gyro")
        out = {"tb": f"{tb:g}"}
        for b in (0.1, 1.0):
            out[f"without_{b:g}"] = fixed(heading_drift(d, b, 20.0), 1)
            out[f"with_{b:g}"] = fixed(heading_drift(d, b, 20.0, bias_time_constant=tb), 1)
    return out


@group("adaptive_stop", "python -m stability.simulate --chair power-fwd --speed 1.5 --scheme adaptive "
       "--push-force 400 (stability.simulate.simulate(power_fwd, 1.5, RunSpec(scheme='adaptive', push_force=400)))")
def adaptive_stop() -> dict:
    """Where the adaptive scheme's run of a spin-out ends, and why."""
    import re

    from stability.settings.run import RunSpec
    from stability.simulate import simulate

    r = simulate(_preset("power-fwd"), 1.5, RunSpec(scheme="adaptive", push_force=400.0, push_duration=0.1,
                                                      model="exact"))
    m = re.search(r"at t = ([\d.]+) s .*load (-?[\d.]+) N, yaw rate (-?[\d.]+) rad/s", r.stop_reason)
    if m is None:
        raise ValueError(f"adaptive_stop: unexpected stop reason {r.stop_reason!r}")
    return {"fail_s": m.group(1), "load_N": m.group(2), "yaw_rate": m.group(3), "end_s": f"{r.stop_time:.4f}",
            "level_s": f"{r.first_time_abs_yaw_rate(1.0):.3f}"}


@group("step_limit", "stability.simulate.stepcheck.stable_steps([ej_premier], SPEEDS, 'thesis', 'free')", cheap=True)
def step_limit() -> dict:
    """The fixed step's stability limit of the E&J Premier (thesis model) and the speed where it is 1 ms."""
    import numpy as np
    from scipy.optimize import brentq

    from stability.simulate.stepcheck import stable_steps

    c = _preset("ej-premier")
    speeds = (0.1, 0.25, 0.28, 0.75)
    lim = stable_steps([c] * len(speeds), np.array(speeds), "thesis", "free")
    out = {f"{u:g}": sig(1e3 * x, 2 if x < 1e-3 or x > 2e-3 else 3) for u, x in zip(speeds, lim, strict=True)}
    one = brentq(lambda u: stable_steps([c], np.array([u]), "thesis", "free")[0] - 1e-3, 0.1, 0.75, xtol=1e-4)
    out["one_ms_speed"] = fixed(one, 2)
    return out
