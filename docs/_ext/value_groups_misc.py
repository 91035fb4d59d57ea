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


@group("tires_fit", "stability.tires.tire_from_data(raw_cornering(NAME) slip_deg, Fz_N, Fy_N).fit_quality; "
       "stability.tires.refit(NAME, method='pwrstar') against Appendix B's published coefficients", cheap=True)
def tires_fit() -> dict:
    """The seven thesis tires' raw data through the user path: fit quality; the refit against the published a, b, c."""
    import numpy as np
    from value_groups import Table

    from stability import tires
    from stability.tires.data import _cornering_coefficients

    names = ("AG", "EJP", "SS", "IM", "EJA", "ER", "PU")
    published = _cornering_coefficients()
    rows, out, worst, caster_rms = [], {}, 0.0, []
    for name in names:
        raw = tires.raw_cornering(name)
        ok = np.isfinite(raw["Fz_N"]) & np.isfinite(raw["Fy_N"])
        t = tires.tire_from_data(raw["slip_deg"][ok], raw["Fz_N"][ok], raw["Fy_N"][ok], name=f"my{name}")
        q = t.fit_quality
        i = int(np.argmin(q.r_squared))
        j = int(np.argmax(q.rms_residual_N))
        rows.append((name, f"{q.r_squared[i]:.3f} ({q.slip_deg[i]} deg)",
                     f"{min(q.r_squared):.3f} to {max(q.r_squared):.3f}",
                     f"{q.rms_residual_N[j]:.2f} ({q.slip_deg[j]} deg)", f"0-{t.fz_max_N:.0f}"))
        out[f"{name}.min_r2"], out[f"{name}.min_r2_deg"] = f"{q.r_squared[i]:.2f}", str(q.slip_deg[i])
        if name in ("ER", "PU"):
            caster_rms += list(q.rms_residual_N)
        out[f"{name}.fz_max"] = f"{t.fz_max_N:.0f}"
        missing = {int(s) for s, f in zip(raw["slip_deg"], raw["flag"], strict=True) if f in ("missing", "partial")}
        ref = tires.refit(name, method="pwrstar").coefficients
        pub = np.asarray(published[name][0])
        for s in range(1, 9):
            if s not in missing:
                worst = max(worst, float(np.max(np.abs(ref[s - 1, :3] / pub[s] - 1))))
        out[f"{name}.missing"] = ", ".join(str(s) for s in sorted(missing))
    out["published_rel"] = f"{worst:.1e}".replace("e-0", "e-")
    from stability.models.statics import static_loads

    heavy = _preset("ej-premier").replace(m=200.0)
    out["heavy_caster_N"] = f"{static_loads(heavy)['caster']:.0f}"
    out["caster_rms"] = f"{min(caster_rms):.1f}-{max(caster_rms):.1f}"
    out["table"] = Table(("tire", "min R^2", "R^2 range (casters: see above)", "max RMS residual (N)",
                          "fitted load range (N)"), tuple(rows))
    return out
