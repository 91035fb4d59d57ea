"""The value groups of docs/measure.md (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import Table, fixed, group

#: Appendix D's figures (Collins 1987): the ISO dummy and the chair, and their published combination
DUMMY_KG, DUMMY_IZ, CHAIR_KG, CHAIR_IZ, TOTAL_IZ = 75.0, 3.1, 20.0, 2.3, 5.6
#: Mochel's combined c.g. ahead of the front-caster chair's rear axle (m), as docs/measure.md cites it
MOCHEL_CG_M = 0.135


@group("measure_values", "stability.measure.bodies.separation_for_total_inertia(75, 20, 3.1, 2.3, TOTAL); "
       "stability.measure.anthropometry.user_yaw_inertia(MASS, STATURE)", cheap=True)
def measure_values() -> dict:
    """Appendix D's two-body separation and the seated user's yaw inertia estimates."""
    import math

    from stability.measure.anthropometry import user_yaw_inertia
    from stability.measure.bodies import separation_for_total_inertia

    def sep(total: float) -> float:
        return separation_for_total_inertia(DUMMY_KG, CHAIR_KG, DUMMY_IZ, CHAIR_IZ, total)

    d = sep(TOTAL_IZ)
    m = DUMMY_KG + CHAIR_KG
    mu = DUMMY_KG * CHAIR_KG / m
    dummy, chair = d * CHAIR_KG / m, d * DUMMY_KG / m
    out = {"mass": f"{m:g}", "mu": fixed(mu, 1), "extra": f"{TOTAL_IZ - DUMMY_IZ - CHAIR_IZ:.1f}",
           "d_cm": fixed(100 * d, 1), "dummy_cm": fixed(100 * dummy, 1), "chair_cm": fixed(100 * chair, 1),
           "lo_total": f"{TOTAL_IZ - 0.05:.2f}", "hi_total": f"{TOTAL_IZ + 0.05:.2f}",
           "lo_cm": fixed(100 * sep(TOTAL_IZ - 0.05), 1), "hi_cm": fixed(100 * sep(TOTAL_IZ + 0.05), 1),
           "chair_axle_cm": fixed(100 * (MOCHEL_CG_M - chair), 1),
           "dummy_axle_cm": fixed(100 * (MOCHEL_CG_M + dummy), 1)}
    assert math.isclose(d, math.sqrt((TOTAL_IZ - DUMMY_IZ - CHAIR_IZ) / mu))
    for key, (kg, st) in {"iso": (75.0, 1.75), "example": (78.0, 1.78)}.items():
        u = user_yaw_inertia(kg, st)
        out.update({f"{key}.value": fixed(u.value, 2), f"{key}.std": fixed(u.std, 2), f"{key}.low": fixed(u.low, 2),
                    f"{key}.high": fixed(u.high, 2)})
    return out


@group("measure_propagate", "python docs/examples/propagate_measured_chair.py (stability.uncertainty.propagate("
       "measured_chair, its uncertainty file, outputs, samples=2000, seed=1))")
def measure_propagate() -> dict:
    """The measured example chair's growth rate at 0.75 m/s and locked-caster critical speed, 95 % Monte Carlo."""
    import numpy as np
    from value_groups import ROOT

    from stability import chair, linear
    from stability.uncertainty import load_uncertainty, propagate

    ex = ROOT / "docs" / "examples"
    c = chair.load(ex / "measured_chair.toml")
    u = load_uncertainty(ex / "measured_chair.uncertainty.toml")

    def outputs(chairs):
        return np.array([[linear.divergence(ch, [0.75])[0].rate, linear.zero_width(ch).critical_speed]
                         for ch in chairs])

    mc = propagate(c, u, outputs, samples=2000, seed=1)
    return {"rate_lo": fixed(mc.low[0], 2), "rate_hi": fixed(mc.high[0], 2), "crit_lo": fixed(mc.low[1], 1),
           "crit_hi": fixed(mc.high[1], 1), "iz_share": fixed(float(mc.shares["i_z"][0]), 2)}


@group("measure_readings", "stability.measure.sheet.READINGS (the sheet's readings, their dimensions and ranges)",
       cheap=True)
def measure_readings() -> dict:
    """The measurement sheet's readings with their valid ranges, read from the code (inputs, not results)."""
    from stability.measure.sheet import READINGS

    rows = []
    for name, (dims, lo, hi, required, what) in READINGS.items():
        low = ">= 0" if lo < 0 else f"> {lo:g}"
        rows.append((name, " or ".join(dims), f"{low}, <= {hi:g}", "yes" if required else "no", what))
    return {"table": Table(("reading", "dimension", "valid range (SI)", "required", "what"), tuple(rows))}
