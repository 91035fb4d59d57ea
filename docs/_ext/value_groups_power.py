"""The value groups of docs/power-chair.md: the power-fwd preset's derived numbers (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import fixed, group, pct, sig
from value_groups_pages import _preset

#: Table 4-1's cornering stiffness of the stiffest tested drive tire at its highest tested load (N/deg at 450 N),
#: and the thesis's pin friction for its chair's caster load (Appendix D: 0.10 N m for about 270 N)
TABLE_4_1_N_PER_DEG, TABLE_4_1_LOAD_N = 70.5, 450.0
THESIS_PIN_N_M, THESIS_CASTER_LOAD_N = 0.10, 270.0


@group("power_chair", "stability.chair.power.lumped_estimate(); stability.models.statics.static_loads(power_fwd); "
       "stability.assist.robustness box; stability.chair.power.drive_train()", cheap=True)
def power_chair() -> dict:
    """The power-fwd preset's estimates from its lumped masses, its static loads and what follows from them."""
    import inspect

    from stability.assist.robustness import robustness
    from stability.chair.power import COMPONENTS, drive_train, lumped_estimate
    from stability.models.statics import static_loads

    c = _preset("power-fwd")
    box = inspect.signature(robustness).parameters["box"].default
    est = lumped_estimate()
    loads = static_loads(c)
    per_lbf = TABLE_4_1_N_PER_DEG / TABLE_4_1_LOAD_N
    stiff = float(c.main_tire.split(":")[1])
    dt = drive_train()
    return {"box_mass": f"{c.m * (1 + box):.0f}", "user_iz": fixed(COMPONENTS[0][5], 1),
            "est_iz": fixed(est.i_z, 1), "est_s1": fixed(est.s1, 3), "est_h": fixed(est.h, 3),
            "drive_pct": pct(loads["main"] / (loads["main"] + loads["caster"])),
            "caster_pct": pct(loads["caster"] / (loads["main"] + loads["caster"])),
            "caster_N": f"{loads['caster']:.0f}", "drive_N": f"{loads['main']:.0f}",
            "pin_scaled": fixed(THESIS_PIN_N_M * loads["caster"] / THESIS_CASTER_LOAD_N, 2),
            "per_deg_N": fixed(per_lbf, 3), "scaled_stiffness": f"{per_lbf * loads['main']:.0f}",
            "box_lo": f"{stiff * (1 - box):.0f}", "box_hi": f"{stiff * (1 + box):.0f}",
            "mu": f"{dt.traction_coefficient:g}",
            "traction": f"{dt.traction_coefficient * loads['main'] * dt.wheel_radius:.0f}",
            "force_at_limit": sig(dt.torque_limit / dt.wheel_radius, 2)}


#: The caster of docs/power-chair.md's estimate: an 8 x 2 inch wheel of 0.9 kg at the trail, fork, bearings and
#: stem 0.7 kg at 0.015 m behind the pin, the fork's own inertia about the pin (kg m^2)
INCH = 0.0254
CASTER_WHEEL_KG, CASTER_FORK_KG, CASTER_FORK_M, CASTER_FORK_IZ = 0.9, 0.7, 0.015, 0.0009


@group("power_caster", "docs/power-chair.md's caster estimate (8 x 2 inch wheel, fork) against "
       "stability.preset('power-fwd') (m_c, l1, i_zp, trail)", cheap=True)
def power_caster() -> dict:
    """The power-fwd caster's l1 and pin inertia from its parts, and the validation bound m_c l1^2."""
    c = _preset("power-fwd")
    r, w = 4 * INCH, 2 * INCH
    m_c = CASTER_WHEEL_KG + CASTER_FORK_KG
    l1 = (CASTER_WHEEL_KG * c.trail + CASTER_FORK_KG * CASTER_FORK_M) / m_c
    own = CASTER_WHEEL_KG * (r ** 2 / 4 + w ** 2 / 12)
    offset = CASTER_WHEEL_KG * c.trail ** 2
    return {"l1": fixed(l1, 3), "wheel_own": sig(own, 2), "wheel_offset": sig(offset, 2),
            "i_zp": sig(own + offset + CASTER_FORK_IZ, 1), "bound": sig(m_c * l1 ** 2, 1)}
