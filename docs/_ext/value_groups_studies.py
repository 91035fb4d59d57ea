"""The value groups of docs/studies.md: the critical-impulse search's cost in runs, Figure 8-14 (see
``value_groups.py``)."""

from __future__ import annotations

from value_groups import fixed, group
from value_groups_pages import _preset

SEARCH_SPEEDS = (0.5, 0.6, 0.75, 0.9, 1.0, 1.2)


@group("studies_search", "stability.study.critical_impulses(ej_premier, SPEEDS[, RunSpec(friction_law='kinetic')]) "
       "(CriticalImpulse.runs: the simulations each search used)")
def studies_search() -> dict:
    """Simulations the critical-impulse search needs (deterministic, unlike its wall-clock time)."""
    from stability.settings.run import RunSpec
    from stability.study import critical_impulses

    ej = _preset("ej-premier")
    free = ej.replace(pin_friction_left=0.0, pin_friction_right=0.0)
    one = critical_impulses(ej, [0.75])[0]
    six = critical_impulses(ej, list(SEARCH_SPEEDS))
    kinetic = critical_impulses(ej, list(SEARCH_SPEEDS), RunSpec(friction_law="kinetic"))
    frictionless = critical_impulses(free, [0.5, 0.75])
    import numpy as np

    from stability.linear import eigenvalues_vs_speed

    sigma = float(np.max(eigenvalues_vs_speed(ej, [0.75], track=False).real))
    return {"sigma": fixed(sigma, 3), "inv_sigma": fixed(1 / sigma, 2), "low": fixed(one.low_Ns, 3),
            "high": fixed(one.high_Ns, 3), "one": str(one.runs), "six": str(sum(x.runs for x in six)),
            "kinetic": str(sum(x.runs for x in kinetic)), "free": str(sum(x.runs for x in frictionless)),
            "speeds": ", ".join(f"{u:g}" for u in SEARCH_SPEEDS), "ej_075": fixed(one.impulse_Ns, 2)}


@group("studies_fig814", "stability.study.equal_instability_speed(ej_premier.replace(m=75, i_z=4.7), "
       "run=RunSpec(model='thesis'))")
def studies_fig814() -> dict:
    """Figure 8-14's reduced-mass chair: its equal-instability speed (thesis variant)."""
    from stability import study
    from stability.settings.run import RunSpec

    light = _preset("ej-premier").replace(m=75.0, i_z=4.7)
    res = study.equal_instability_speed(light, run=RunSpec(model="thesis"), progress=False)
    return {"speed": fixed(res.speed, 3), "status": res.status}
