"""The value groups of docs/shimmy.md's chair model and trail trade-off (see ``value_groups.py``)."""

from __future__ import annotations

from value_groups import Table, fixed, group, sig, signed
from value_groups_pages import _preset, _span

SHIMMY_SPEEDS = (0.5, 1.0, 3.0)
TRADE_TRAILS = (0.04, 0.05, 0.06, 0.08)


def _join(values, fmt) -> str:
    return " / ".join(fmt(v) for v in values)


@group("shimmy_tradeoff", "python -m stability.shimmy --chair NAME --speeds 0.5,1,3 --chair-model --pin compliant "
       "(stability.shimmy.chair_modes.chair_shimmy(chair.replace(trail=T), [0.5, 1, 3], pin='compliant'); "
       "stability.linear.eigenvalues_vs_speed; stability.shimmy.chair.critical_trail, friction_trail)")
def shimmy_tradeoff() -> dict:
    """The trail trade-off: divergence rate against trail (rigid tires and the chair model), the shimmy mode per
    trail, the revised design's margin, the compliance corners, the in-phase and anti-phase caster modes."""
    import math

    import numpy as np

    from stability.linear import eigenvalues_vs_speed
    from stability.shimmy.chair import critical_trail, friction_trail
    from stability.shimmy.chair_modes import (
        _TRAIL_GRID,
        SHIMMY_MIN_HZ,
        chair_critical_trail,
        chair_shimmy,
        relaxed_state_matrices,
    )
    from stability.shimmy.compliance import CasterCompliance

    ej, rv = _preset("ej-premier"), _preset("revised")
    comp = CasterCompliance()
    out: dict = {"sigma_mm": f"{1e3 * comp.relaxation_length:g}", "k_kn_m": f"{comp.lateral_stiffness / 1e3:g}"}

    # the exact linear chair (point-contact tires) at 3 m/s against trail
    rate = {t: float(np.max(eigenvalues_vs_speed(ej.replace(trail=t), [3.0], track=False).real))
            for t in (0.04, 0.06, 0.08)}
    for t, r in rate.items():
        out[f"ej_rate_3_{100 * t:g}"] = fixed(r, 2)
    out["ej_rate_step_pct"] = fixed(100 * (rate[0.06] / rate[0.08] - 1), 1)

    # the revised design's margin at 3 m/s (towed wheel, nominal estimates)
    amp = math.radians(5.0)
    lin, fr = critical_trail(rv, 3.0), friction_trail(rv, 3.0, amp)
    out.update(rv_linear_cm=fixed(100 * lin, 1), rv_friction_cm=fixed(100 * fr, 1),
               rv_pin_n_m=f"{rv.pin_friction_left:g}", rv_trail_cm=f"{100 * rv.trail:g}",
               rv_margin_cm=_span([100 * (rv.trail - lin), 100 * (rv.trail - fr)], lambda x: fixed(x, 1)))

    # the chair model's critical trail over the compliance corners (E&J Premier, 1 m/s, compliant pins)
    corners = {(c.relaxation_length, c.lateral_stiffness): float(chair_critical_trail(ej, [1.0], c, pin="compliant")[0])
               for c in comp.corners()}
    finite = {k: v for k, v in corners.items() if math.isfinite(v)}
    (s_lo, k_lo), (s_hi, k_hi) = min(finite, key=finite.get), max(finite, key=finite.get)
    soft = sorted({k for (_s, k), v in corners.items() if not math.isfinite(v)})
    out.update(corner_lo_cm=fixed(100 * finite[s_lo, k_lo], 1), corner_lo_sigma_mm=f"{1e3 * s_lo:g}",
               corner_lo_k=f"{k_lo / 1e3:g}", corner_hi_cm=fixed(100 * finite[s_hi, k_hi], 1),
               corner_hi_sigma_mm=f"{1e3 * s_hi:g}", corner_hi_k=f"{k_hi / 1e3:g}",
               corner_inf_cm=f"{100 * _TRAIL_GRID[1]:g}",
               corner_inf_k=", ".join(f"{k / 1e3:g}" for k in soft) or "none")

    # the two caster modes at 1 m/s, compliant pins: anti-phase (least damped) and in-phase
    for key, c in (("ej", ej), ("revised", rv)):
        ev = np.linalg.eigvals(relaxed_state_matrices(c, np.array([1.0]), comp, "exact", "compliant"))[0]
        osc = ev[ev.imag > 2 * math.pi * SHIMMY_MIN_HZ]
        anti, inphase = sorted(osc, key=lambda e: -e.real)[:2]
        for name, e in (("anti", anti), ("in", inphase)):
            out[f"{key}_{name}_hz"] = fixed(e.imag / (2 * math.pi), 2)
            out[f"{key}_{name}_re"] = fixed(e.real, 2)

    # the anti-phase mode against the towed wheel on a fixed pivot (compliant pins, 0.25-3 m/s)
    from stability.shimmy.chair import caster_wheel

    us = np.linspace(0.25, 3.0, 12)
    worst = 0.0
    for c in (ej, rv):
        ev = np.linalg.eigvals(relaxed_state_matrices(c, us, comp, "exact", "compliant"))
        wheel = caster_wheel(c, comp).eigenvalues(us)
        for i in range(us.size):
            w = wheel[i][wheel[i].imag > 2 * math.pi * SHIMMY_MIN_HZ]
            a = ev[i][ev[i].imag > 2 * math.pi * SHIMMY_MIN_HZ]
            worst = max(worst, min(abs(x - y) / abs(y) for x in a for y in w[np.argmax(w.real)][None]))
    out["anti_vs_wheel"] = f"{worst:.0e}".replace("e-0", "e-")
    out["anti_speeds"] = f"{us[0]:g}-{us[-1]:g}"
    out["caster_inertia"] = sig(caster_wheel(ej, comp).inertia, 2)
    out["ej_mass"] = f"{ej.m:g}"
    own = []
    for c in (ej, rv):
        own += list(chair_shimmy(c, SHIMMY_SPEEDS, comp, pin="compliant").frequency_hz)
    out["preset_hz"] = _span(own, lambda x: fixed(x, 0))

    # the divergence rate with and without tire relaxation, and the trade-off table
    rows, grows = [], []
    for name, c in (("ej-premier", ej), ("revised", rv)):
        m = chair_shimmy(c, SHIMMY_SPEEDS, comp, pin="compliant")
        out[f"{name}.rate_relaxed"] = _join(m.divergence_rate, lambda x: fixed(x, 3))
        out[f"{name}.rate_rigid_tire"] = _join(m.rigid_tire_rate, lambda x: fixed(x, 3))
        out[f"{name}.same_to_digits"] = "yes" if out[f"{name}.rate_relaxed"] == out[f"{name}.rate_rigid_tire"] \
            else "NO"
        rate3 = {}
        for t in TRADE_TRAILS:
            s = chair_shimmy(c.replace(trail=t), SHIMMY_SPEEDS, comp, pin="compliant")
            rate3[t] = float(s.divergence_rate[-1])
            hz = [fixed(f, 1) for f in s.frequency_hz]
            re = _join(s.real_part, lambda x: signed(x, 2)) + (" (shimmy)" if np.any(s.real_part > 0) else "")
            rows.append((name, f"{100 * t:g} cm", _join(s.divergence_rate, lambda x: fixed(x, 3)), re,
                         (hz[0] if len(set(hz)) == 1 else " / ".join(hz)) + " Hz"))
        grows.append(100 * float(np.max(chair_critical_trail(c, SHIMMY_SPEEDS, comp, pin="compliant"))))
        out[f"{name}.step_8_6_pct"] = fixed(100 * (1 - rate3[0.06] / rate3[0.08]), 1)
    out["step_8_6_pct"] = _span([float(out[f"{n}.step_8_6_pct"]) for n in ("ej-premier", "revised")],
                                lambda x: fixed(x, 1))
    out["grows_below_cm"] = _span(grows, lambda x: fixed(x, 1))
    out["table"] = Table(("chair", "trail", "divergence rate (1/s)", "shimmy real part (1/s)", "shimmy frequency"),
                         tuple(rows))
    return out


@group("shimmy_reverse", "python -m stability.shimmy --chair NAME --speeds -1,1 "
       "(stability.shimmy.layout_caster.layout_casters(layout, reverse), leading_divergence_rate; "
       "stability.shimmy.band.shimmy_band)")
def shimmy_reverse() -> dict:
    """Each caster row of the three drive layouts and the E&J Premier forward and in reverse at 1 m/s: its static
    load, its margin to the nearest shimmy boundary, and the leading caster's divergence rate when reversing."""
    import warnings

    speed = 1.0
    rows, out = [], {"speed": f"{speed:g}"}
    with warnings.catch_warnings():
        # the trail searches reach caster loads beyond the ER tire's fitted range (extrapolated; the command notes it)
        warnings.simplefilter("ignore")
        for name in ("ej-premier", "power-fwd-base", "mid-wheel-drive", "power-rwd-base"):
            _reverse_rows(name, speed, rows, out)
    out["table"] = Table(("chair", "caster row", "load forward N", "load reverse N", "margin forward cm",
                          "margin reverse cm", f"leading caster 1/s at {speed:g} m/s reversing"), tuple(rows))
    return out


def _reverse_rows(name: str, speed: float, rows: list, out: dict) -> None:
    """One chair's caster rows for :func:`shimmy_reverse` (appended to ``rows``, keys into ``out``)."""
    from stability.layout import Layout
    from stability.layout.presets import layout_preset
    from stability.shimmy.band import shimmy_band
    from stability.shimmy.layout_caster import layout_casters, leading_divergence_rate

    lay = Layout.from_chair(_preset(name)) if name == "ej-premier" else layout_preset(name)
    seen: set = set()
    for fwd, rev in zip(layout_casters(lay), layout_casters(lay, reverse=True), strict=True):
        c = lay.casters[fwd.index]
        if round(c.x, 9) in seen:
            continue
        seen.add(round(c.x, 9))
        where = "front" if c.x > 0 else "rear"
        m_f = 100 * shimmy_band(fwd, [speed]).shimmy_margin_m
        m_r = 100 * shimmy_band(rev, [speed]).shimmy_margin_m
        rate = float(leading_divergence_rate(c.trail, [-speed])[0])
        rows.append((name, where, fixed(fwd.static_load(), 0), fixed(rev.static_load(), 0), signed(m_f, 2),
                     signed(m_r, 2), fixed(rate, 1)))
        key = f"{name}.{where}"
        out.update({f"{key}.load_fwd": fixed(fwd.static_load(), 0), f"{key}.load_rev": fixed(rev.static_load(), 0),
                    f"{key}.margin_fwd_cm": signed(m_f, 2), f"{key}.margin_rev_cm": signed(m_r, 2),
                    f"{key}.leading_1_s": fixed(rate, 1), f"{key}.trail_cm": f"{100 * c.trail:g}"})
