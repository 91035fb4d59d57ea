"""Text and files the explorer shows or offers, made from the views' results (no computing)."""

from __future__ import annotations

import numpy as np

from stability import chair as chair_mod
from stability.app.views import LinearView
from stability.chair import Chair

__all__ = ["summary_html", "geometry_text", "field_rows", "field_label", "FIELD_KINDS", "FIELD_GROUPS"]

#: Fields edited as text choices rather than numbers.
TEXT_FIELDS = ("name", "caster_position", "main_tire", "caster_tire")
#: Editor kind of every chair field: ``"number"``, ``"choice"`` or ``"text"``.
FIELD_KINDS: dict[str, str] = {
    f: ("choice" if f in ("caster_position", "main_tire", "caster_tire") else "text" if f == "name" else "number")
    for f in chair_mod.field_names()
}


#: The editor's groups of chair fields (title, fields, shown open), in the page's order; every field once.
FIELD_GROUPS: tuple[tuple[str, tuple[str, ...], bool], ...] = (
    ("Chair", ("name", "caster_position"), True),
    ("Wheel positions, from the c.g.", ("s1", "s2", "d1", "d2", "t1", "t2", "h"), True),
    ("Casters", ("trail", "l1", "m_c", "i_zp", "pin_friction_left", "pin_friction_right", "pin_damping"), True),
    ("Mass and inertia", ("m", "i_z"), True),
    ("Tires", ("main_tire", "caster_tire", "roll_k", "camber_deg", "camber_coefficient", "toe_deg",
               "main_lateral_scale", "main_rolling_scale", "caster_lateral_scale", "caster_rolling_scale"), False),
    ("Anti-tip wheels and gravity", ("anti_tip_reach", "anti_tip_clearance", "g"), False),
)


def field_label(row: dict[str, str]) -> str:
    """An editor field's label: its meaning in words, its name (as links and ``--set`` spell it) and its unit.

    Parameters
    ----------
    row : dict
        A row of :func:`field_rows`.

    Returns
    -------
    str
        E.g. ``"Caster trail, pin to contact: trail (m)"``.

    Examples
    --------
    >>> field_label({"name": "trail", "unit": "m", "doc": "caster trail, pin to contact"})
    'Caster trail, pin to contact: trail (m)'
    """
    doc = row["doc"][:1].upper() + row["doc"][1:]
    unit = f" ({row['unit']})" if row["unit"] != "-" else ""
    return f"{doc}: {row['name']}{unit}"


def field_rows() -> list[dict[str, str]]:
    """One row per chair field for the editor: name, unit, meaning, valid range (from ``chair.LIMITS``).

    Returns
    -------
    list of dict
        Keys ``name``, ``unit``, ``doc``, ``symbol``, ``range`` (empty for text fields) and ``kind``.
    """
    import dataclasses

    rows = []
    for f in dataclasses.fields(Chair):
        rng = chair_mod.valid_range(f.name) if f.name in chair_mod.LIMITS else ""
        rows.append({"name": f.name, "unit": f.metadata["unit"], "doc": f.metadata["doc"],
                     "symbol": f.metadata.get("symbol", ""), "range": rng, "kind": FIELD_KINDS[f.name]})
    return rows


def _fmt(x: float | None, unit: str, digits: int = 4) -> str:
    return "none in range" if x is None else f"{x:.{digits}g} {unit}"


def summary_html(v: LinearView) -> str:
    """The linear summary over the plots: verdict, critical speeds, the divergence table as ``critical_speed`` prints.

    HTML: the page shows it in a Bokeh ``Div`` (no Markdown to convert per edit).

    Parameters
    ----------
    v : LinearView

    Returns
    -------
    str
        HTML made of numbers and the page's own words only (no user text).
    """
    first_free = v.free_crossings[0].speed if v.free_crossings else None
    first_locked = v.locked_crossings[0].speed if v.locked_crossings else None
    rows = []
    for r in v.table:
        t2 = "-" if r.time_to_double is None else f"{r.time_to_double:.3g}"
        rows.append(f"<tr><td>{r.speed:.3g}</td><td>{r.rate:.4f}</td><td>{t2}</td><td>{r.frequency:.3g}</td></tr>")
    g = v.growth_rate
    searched = f"from {v.locus.speeds[0]:g} to {v.locus.speeds[-1]:g} m/s"      # the grid the rates are on
    verdict = (f"unstable at every speed {searched}" if np.all(g > 0) else
               f"stable at every speed {searched}" if np.all(g < 0) else "stable in the shaded green "
               "ranges, unstable in the vermillion ones")
    return (f"<p><b>Free casters: {verdict}.</b> Critical speeds: free casters {_fmt(first_free, 'm/s')}, locked "
            f"casters {_fmt(first_locked, 'm/s')}, zero-width model (eq 5-15) "
            f"{_fmt(v.zero_width.critical_speed, 'm/s')}.</p>"
            "<p>Least stable mode (what <code>python -m stability.critical_speed</code> prints):</p>"
            "<table><thead><tr><th>speed (m/s)</th><th>growth rate (1/s)</th><th>doubling time (s)</th>"
            "<th>frequency (rad/s)</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>")


def geometry_text(c: Chair, v: LinearView) -> str:
    """The text under the geometry views: the static stability angles, the static loads, the wheelbase.

    Parameters
    ----------
    c : Chair
    v : LinearView
        Its linear view (tip angles and static loads).

    Returns
    -------
    str
        Markdown.
    """
    tip, L = v.tip, v.static_loads
    least = tip.smallest_direction.replace("_", " ")
    return (f"**Static stability** (ISO 7176-1, rigid chair, brakes locked, casters in their least stable "
            f"orientation; `python -m stability.tipping`): toward the main wheels {tip.toward_main_wheels_deg:.1f}°, "
            f"toward the casters {tip.toward_casters_deg:.1f}°, left {tip.lateral_left_deg:.1f}°, right "
            f"{tip.lateral_right_deg:.1f}°; smallest {tip.smallest_deg:.1f}° ({least})."
            f"\n\nStatic loads: main wheel {L['main']:.1f} N, caster {L['caster']:.1f} N (per wheel); wheelbase "
            f"{c.wheelbase:.3f} m; c.g. ratio s1/(s1+s2) {c.cg_ratio:.3f}. Drawn from the chair's fields, c.g. at "
            "the origin; dotted: from the c.g. to each tipping line, with its angle.")
