"""Value groups of the smaller pages: docs/interface.md, docs/compare.md, docs/studies.md's kinetic-law
comparison (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import fixed, group
from value_groups_pages import _preset


@group("interface_values", "stability.run_simulation(ej_premier, 0.75) and stability.simulate.simulate(ej_premier, "
       "0.75, RunSpec(model='thesis')) (first time |yaw rate| = 1 rad/s); stability.slope.equilibrium.drive_report("
       "ej_premier, solve(ej_premier, 6, 0.75))")
def interface_values() -> dict:
    """The default run against the thesis model's; the E&J Premier's hand-rim difference on 6 deg."""
    import stability
    from stability.settings.run import RunSpec
    from stability.simulate import simulate
    from stability.slope.equilibrium import drive_report, solve

    c = _preset("ej-premier")
    exact = stability.run_simulation(c, 0.75).first_time_abs_yaw_rate(1.0)
    thesis = simulate(c, 0.75, RunSpec(model="thesis")).first_time_abs_yaw_rate(1.0)
    d = drive_report(c, solve(c, 6.0, 0.75), "handrim")
    return {"exact_s": fixed(exact, 2), "thesis_s": fixed(thesis, 2),
            "rim_6": fixed(d["handrim_force_difference_N"], 2), "rim_6_side": d["harder_side"]}


@group("kinetic_law", "stability.study.critical_impulses(chair, [0.75], RunSpec(friction_law='kinetic')) "
       "(program WCHAIR's kinetic pin friction, 1 ms step)")
def kinetic_law() -> dict:
    """The critical impulses at 0.75 m/s with program WCHAIR's kinetic pin friction."""
    from stability.settings.run import RunSpec
    from stability.study import critical_impulses

    return {name: f"{critical_impulses(_preset(name), [0.75], RunSpec(friction_law='kinetic'))[0].impulse_Ns:.3g}"
            for name in ("ej-premier", "revised")}
