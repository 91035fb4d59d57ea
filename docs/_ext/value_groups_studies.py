"""The value groups of docs/studies.md: the critical-impulse search's cost in runs, Figure 8-14 (see
``value_groups.py``)."""

from __future__ import annotations

from value_groups import fixed, group, sig
from value_groups_pages import _preset

SEARCH_SPEEDS = (0.5, 0.6, 0.75, 0.9, 1.0, 1.2)


@group("studies_search", "stability.study.critical_impulses(ej_premier, SPEEDS[, RunSpec(friction_law='kinetic')]) "
       "(CriticalImpulse.runs: the simulations each search used)")
def studies_search() -> dict:
    """Simulations the critical-impulse search needs (deterministic, unlike its wall-clock time)."""
    from stability.settings.run import RunSpec
    from stability.study import critical_impulses
    from stability.study.impulse import linear_critical_impulse

    ej = _preset("ej-premier")
    free = ej.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    one = critical_impulses(ej, [0.75])[0]
    six = critical_impulses(ej, list(SEARCH_SPEEDS))
    kinetic = critical_impulses(ej, list(SEARCH_SPEEDS), RunSpec(friction_law="kinetic"))
    frictionless = critical_impulses(free, [0.5, 0.75])
    import numpy as np

    from stability.linear import eigenvalues_vs_speed

    sigma = float(np.max(eigenvalues_vs_speed(ej, [0.75], track=False).real))
    fit = _rate_check(ej, sigma, one.impulse_Ns)
    return {"sigma": fixed(sigma, 3), "inv_sigma": fixed(1 / sigma, 2), "low": fixed(one.low_Ns, 3),
            "high": fixed(one.high_Ns, 3), "one": str(one.runs), "six": str(sum(x.runs for x in six)),
            "kinetic": str(sum(x.runs for x in kinetic)), "free": str(sum(x.runs for x in frictionless)),
            "speeds": ", ".join(f"{u:g}" for u in SEARCH_SPEEDS), "ej_075": fixed(one.impulse_Ns, 2),
            "linear_start": f"{linear_critical_impulse(ej, 0.75):.1e}".replace("e-0", "e-"), **fit}


#: The pushes of docs/studies.md's check of the growth-rate prediction (N s): three points of the search's path
#: (as tests/test_search_rate_fit.py takes them) and one just above the threshold
RATE_PUSHES = (5.0338, 4.2729, 3.8820, 3.26)


def _rate_check(chair, sigma: float, threshold: float) -> dict:
    """Times to 1 rad/s of four pushes above the threshold, the slope of t against ln(J - J0), and the threshold
    the two largest predict (``J0 = (q J1 - J2) / (q - 1)``, ``q = exp(sigma (t1 - t2))``)."""
    import math

    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.study.impulse import push_impulse

    per_newton = push_impulse(1.0, 0.1, "wchair", 0.001)
    t = [simulate(chair, 0.75, RunSpec(push_force=j / per_newton, push_duration=0.1)).first_time_abs_yaw_rate(1.0)
         for j in RATE_PUSHES]
    slopes = [(t[i + 1] - t[i]) / (math.log(RATE_PUSHES[i] - threshold) - math.log(RATE_PUSHES[i + 1] - threshold))
              for i in range(len(t) - 1)]
    (j2, j1), (t2, t1) = RATE_PUSHES[:2], t[:2]
    q = math.exp(sigma * (t1 - t2))
    out = {f"t{i}": fixed(x, 2) for i, x in enumerate(t)}
    out.update({f"j{i}": fixed(x, 2) for i, x in enumerate(RATE_PUSHES)})
    out.update(slope=f"{min(slopes):.2f}-{max(slopes):.2f}", predicted=fixed((q * j1 - j2) / (q - 1), 3))
    return out


@group("studies_fig814", "stability.study.equal_instability_speed(ej_premier.replace(m=75, i_z=4.7), "
       "run=RunSpec(model='thesis'))")
def studies_fig814() -> dict:
    """Figure 8-14's reduced-mass chair: its equal-instability speed (thesis variant)."""
    from stability import study
    from stability.settings.run import RunSpec

    light = _preset("ej-premier").replace(m=75.0, i_z=4.7)
    res = study.equal_instability_speed(light, run=RunSpec(model="thesis"), progress=False)
    return {"speed": fixed(res.speed, 3), "status": res.status}


@group("studies_kinetic", "python -m stability.critical_speed --chair NAME --uncertainty FILE --nonlinear with "
       "program WCHAIR's kinetic pin friction (stability.study.uncertain.nonlinear_intervals(chair, "
       "loads_uncertainty(FILE), RunSpec(friction_law='kinetic'), equal_instability=False); 200 draws, seed 0)")
def studies_kinetic() -> dict:
    """The critical impulse's 95 % interval over the studies' uncertainty file with the kinetic law."""
    from value_groups_pages import STUDIES_UNCERTAINTY

    from stability.settings.run import RunSpec
    from stability.study.uncertain import nonlinear_intervals
    from stability.uncertainty import loads_uncertainty

    out = {}
    for name in ("ej-premier", "revised"):
        k = nonlinear_intervals(_preset(name), loads_uncertainty(STUDIES_UNCERTAINTY), RunSpec(friction_law="kinetic"),
                                equal_instability=False).critical_impulse
        out[name] = f"{sig(k.nominal, 3)} N s, {sig(k.low, 3)}-{sig(k.high, 3)}"
    return out


@group("studies_flip", "stability.simulate.simulate(chair, 0.75, RunSpec(push_force=J/0.101, friction_law=LAW)) on "
       "a 0.1 % grid of pushes over +-2 % around the critical impulse (reaching 1 rad/s within 10 s or not)")
def studies_flip() -> dict:
    """Where the outcome flips from miss to reach near the threshold, stick-slip and kinetic pin friction."""
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.study import critical_impulses
    from stability.study.impulse import push_impulse

    per_newton = push_impulse(1.0, 0.1, "wchair", 0.001)
    out = {}
    for name, law in (("ej-premier", "stick-slip"), ("revised", "stick-slip"), ("ej-premier", "kinetic")):
        c = _preset(name)
        run = RunSpec(friction_law=law)
        centre = critical_impulses(c, [0.75], run)[0].impulse_Ns
        grid = [centre * (1 + 0.001 * k) for k in range(-20, 21)]
        times = [simulate(c, 0.75, run.replace(push_force=j / per_newton, push_duration=0.1))
                 .first_time_abs_yaw_rate(1.0) for j in grid]
        reach = [x is not None and x < float("inf") for x in times]
        flips = sum(a != b for a, b in zip(reach, reach[1:], strict=False))
        first = next(i for i, r in enumerate(reach) if r)
        key = f"{name}.{law}"
        out[f"{key}.miss"] = f"{grid[first - 1]:.3f}" if first > 0 else "none"
        out[f"{key}.reach"] = f"{grid[first]:.3f}"
        out[f"{key}.flips"] = str(flips)
        out[f"{key}.monotone"] = "monotone" if flips <= 1 else "not monotone"
        last_miss = max(i for i, r in enumerate(reach) if not r) if not all(reach) else -1
        out[f"{key}.band"] = f"{grid[first]:.3f}-{grid[last_miss]:.3f}" if last_miss > first else "none"
    return out


@group("studies_linear_start", "stability.study.impulse.linear_critical_impulse(chair, U) against "
       "stability.study.critical_impulses(chair, [U]) at SPEEDS (frictionless E&J Premier: the linear prediction's "
       "error at the 1 rad/s level); critical_impulses with the pin friction x1.1 (elasticity of the critical "
       "impulse in M_f/l at 0.75 m/s)")
def studies_linear_start() -> dict:
    """How far the linear start is off without pin friction, and how the critical impulse scales with M_f/l."""
    import math

    from stability.study import critical_impulses
    from stability.study.impulse import linear_critical_impulse

    ej = _preset("ej-premier")
    free = ej.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    nl = critical_impulses(free, list(SEARCH_SPEEDS))
    errs = [abs(linear_critical_impulse(free, u) / r.impulse_Ns - 1) for u, r in zip(SEARCH_SPEEDS, nl, strict=True)
            if r.status == "found"]
    more = ej.replace(pin_friction_left=1.1 * ej.pin_friction_left, pin_friction_right=1.1 * ej.pin_friction_right)
    j0, j1 = (critical_impulses(c, [0.75])[0].impulse_Ns for c in (ej, more))
    return {"err_lo": fixed(100 * min(errs), 0), "err_hi": fixed(100 * max(errs), 0),
            "elasticity": fixed(math.log(j1 / j0) / math.log(1.1), 2), "step_pct": "10"}


#: how far below the kinetic law's critical impulse the creeping run of docs/studies.md is pushed
CREEP_BELOW = 0.01


@group("studies_creep", "stability.simulate.simulate(ej_premier, 0.75, RunSpec(push_force=J/0.101, "
       "friction_law='kinetic')) with J 1 % below critical_impulses(..., RunSpec(friction_law='kinetic')); "
       "its yaw rate at 5 s and at the horizon")
def studies_creep() -> dict:
    """A push just below the kinetic law's threshold: the yaw rate creeps up over the horizon."""
    import numpy as np

    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.study import critical_impulses
    from stability.study.impulse import push_impulse

    ej = _preset("ej-premier")
    run = RunSpec(friction_law="kinetic")
    j = critical_impulses(ej, [0.75], run)[0].low_Ns * (1 - CREEP_BELOW)
    res = simulate(ej, 0.75, run.replace(push_force=j / push_impulse(1.0, 0.1, "wchair", 0.001)))
    r = np.abs(np.asarray(res.yaw_rate))
    t = np.asarray(res.t)
    mid = float(np.interp(0.5 * t[-1], t, r))
    if res.first_time_abs_yaw_rate(1.0) is not None:
        raise RuntimeError("the push below the critical impulse reached 1 rad/s: choose CREEP_BELOW larger")
    return {"below_pct": f"{100 * CREEP_BELOW:g}", "mid_t": fixed(0.5 * t[-1], 0), "mid": sig(mid, 2),
            "end_t": fixed(t[-1], 0), "end": sig(float(r[-1]), 2),
            "growing": "still growing" if r[-1] > mid else "not growing"}


@group("studies_eis_runs", "stability.study.equal_instability_speed(NAME) for the presets "
       "(len(EqualInstability.evaluations): the runs each search made)")
def studies_eis_runs() -> dict:
    """Runs of the equal-instability search per chair."""
    from stability import study

    runs = [len(study.equal_instability_speed(_preset(n), progress=False).evaluations)
            for n in ("ej-premier", "revised", "power-fwd")]
    return {"lo": str(min(runs)), "hi": str(max(runs))}
