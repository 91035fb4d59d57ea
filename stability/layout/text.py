"""A layout's linear summary in words and JSON: the critical_speed command's output for any wheel layout."""

from __future__ import annotations

import math

from stability.layout.linear import LayoutSummary
from stability.layout.model import Layout
from stability.layout.statics import contacts, static_loads, tip_angles

__all__ = ["layout_text", "layout_mapping", "critical_words"]


def critical_words(c: tuple, direction: str) -> str:
    """A :func:`stability.layout.linear.critical_speed` in words: ``"Forward: stable below 1.2 m/s, unstable above"``.

    Parameters
    ----------
    c : tuple
        ``(speed m/s, kind)``.
    direction : str
        The words before the colon.

    Returns
    -------
    str
    """
    speed, kind = c
    if kind == "none-stable":
        return f"{direction}: stable at every speed up to {speed:g} m/s"
    if kind == "none-unstable":
        return f"{direction}: unstable at every speed up to {speed:g} m/s (the driver must steer continually)"
    if kind == "destabilising":
        return f"{direction}: stable below {speed:.3g} m/s, unstable above"
    return f"{direction}: unstable below {speed:.3g} m/s, stable above"


def layout_text(layout: Layout, s: LayoutSummary) -> str:
    """The layout's summary as text: wheels and loads, tip angles, growth rates forward and reverse.

    Parameters
    ----------
    layout : Layout
    s : LayoutSummary

    Returns
    -------
    str
    """
    loads = static_loads(layout)
    nf, nc = layout.shape
    lines = [f"{layout.name}: {nf} fixed wheel(s) ({sum(w.driven for w in layout.wheels)} driven), {nc} caster(s); "
             "linear model, free frictionless casters (forward: casters trailing at 0 deg; reverse: at 180 deg)",
             "", "  contact          x (m)    y (m)   static load (N)"]
    for (label, x, y, _), n in zip(contacts(layout), loads, strict=True):
        lines.append(f"  {label:<14} {x:+7.3f}  {y:+7.3f}  {n:10.1f}")
    tips = tip_angles(layout)
    lines += ["", "Static stability (ISO 7176-1, rigid, casters least stable): "
              + ", ".join(f"{k.removesuffix('_deg')} {v:.1f} deg" for k, v in tips.items()), "",
              "  speed (m/s)   growth rate (1/s)   time to double (s)"]
    for u, g in zip(s.speeds_m_s, s.growth_rate_1_s, strict=True):
        t2 = f"{math.log(2) / g:8.2f}" if g > 0 else "  stable"
        lines.append(f"  {u:+10.2f}   {g:+17.4f}   {t2}")
    lines += ["", critical_words(s.forward_critical, "Forward") + "; "
              + critical_words(s.reverse_critical, "in reverse") + "."]
    return "\n".join(lines)


def layout_mapping(layout: Layout, s: LayoutSummary) -> dict:
    """JSON-ready summary (key convention: unit last).

    Parameters
    ----------
    layout : Layout
    s : LayoutSummary

    Returns
    -------
    dict
    """
    loads = static_loads(layout)
    return {"layout": {"name": layout.name, "fixed_wheels": layout.shape[0], "casters": layout.shape[1],
                       "contacts": [{"label": lab, "x_m": x, "y_m": y, "static_load_N": float(n)}
                                    for (lab, x, y, _), n in zip(contacts(layout), loads, strict=True)],
                       "tip_angles_deg": {k.removesuffix("_deg"): v for k, v in tip_angles(layout).items()}},
            **s.to_mapping()}
