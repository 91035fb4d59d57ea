"""Text and files the explorer shows or offers, made from the views' results (no computing)."""

from __future__ import annotations

import io
from typing import Any

import numpy as np

from stability import chair as chair_mod
from stability.app.views import LinearView
from stability.chair import Chair

__all__ = ["summary_text", "geometry_text", "figure_file", "downloads", "field_rows", "FIELD_KINDS"]

#: Fields edited as text choices rather than numbers.
TEXT_FIELDS = ("name", "caster_position", "main_tire", "caster_tire")
#: Editor kind of every chair field: ``"number"``, ``"choice"`` or ``"text"``.
FIELD_KINDS: dict[str, str] = {
    f: ("choice" if f in ("caster_position", "main_tire", "caster_tire") else "text" if f == "name" else "number")
    for f in chair_mod.field_names()
}


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


def summary_text(v: LinearView) -> str:
    """The linear summary over the plots: verdict, critical speeds, the divergence table as ``critical_speed`` prints.

    Parameters
    ----------
    v : LinearView

    Returns
    -------
    str
        Markdown.
    """
    first_free = v.free_crossings[0].speed if v.free_crossings else None
    first_locked = v.locked_crossings[0].speed if v.locked_crossings else None
    lines = ["| speed (m/s) | growth rate (1/s) | doubling time (s) | frequency (rad/s) |",
             "|---:|---:|---:|---:|"]
    for r in v.table:
        t2 = "-" if r.time_to_double is None else f"{r.time_to_double:.3g}"
        lines.append(f"| {r.speed:.3g} | {r.rate:.4f} | {t2} | {r.frequency:.3g} |")
    g = v.growth_rate
    verdict = ("unstable at every speed from 0.01 to 30 m/s" if np.all(g > 0) else
               "stable at every speed from 0.01 to 30 m/s" if np.all(g < 0) else "stable in the shaded green "
               "ranges, unstable in the vermillion ones")
    return (f"**Free casters: {verdict}.** Critical speeds: free casters {_fmt(first_free, 'm/s')}, locked casters "
            f"{_fmt(first_locked, 'm/s')}, zero-width model (eq 5-15) {_fmt(v.zero_width.critical_speed, 'm/s')}."
            "\n\nLeast stable mode (what `python -m stability.critical_speed` prints):\n\n" + "\n".join(lines))


def figure_file(v: LinearView, fmt: str) -> io.BytesIO:
    """The toolkit's eigenvalues-against-speed figure (:func:`stability.plotting.loci.eigenvalues_vs_speed`) as a file.

    Parameters
    ----------
    v : LinearView
    fmt : {"png", "svg"}

    Returns
    -------
    io.BytesIO
    """
    from matplotlib.figure import Figure

    from stability.plotting.loci import eigenvalues_vs_speed

    fig = Figure(figsize=(7.5, 6.5))
    axes = fig.subplots(2, 1)
    eigenvalues_vs_speed(v.locus, axes, mode_names=v.names,
                         title=f"{v.chair.name}, {v.model} model: eigenvalues against speed")
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=150)
    buf.seek(0)
    return buf


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


def downloads(state: Any, view: Any) -> Any:
    """The download buttons: chair TOML, results JSON, eigenvalues CSV, the figure as PNG and SVG.

    Parameters
    ----------
    state : AppState
        The session's state (read when a button is pressed).
    view : callable
        ``view() -> LinearView`` of the current chair.

    Returns
    -------
    panel.Row
    """
    import panel as pn

    from stability.app.views import eigenvalues_csv

    return pn.Row(
        pn.widgets.FileDownload(callback=lambda: io.StringIO(state.chair_toml()), filename="chair.toml",
                                label="chair (TOML)", css_classes=["download-toml"], width=160),
        pn.widgets.FileDownload(callback=lambda: io.StringIO(state.results_json()), filename="results.json",
                                label="results (JSON)", css_classes=["download-json"], width=160),
        pn.widgets.FileDownload(callback=lambda: io.StringIO(eigenvalues_csv(view())),
                                filename="eigenvalues.csv", label="eigenvalues (CSV)",
                                css_classes=["download-csv"], width=170),
        pn.widgets.FileDownload(callback=lambda: figure_file(view(), "png"), filename="eigenvalues.png",
                                label="figure (PNG)", css_classes=["download-png"], width=150),
        pn.widgets.FileDownload(callback=lambda: figure_file(view(), "svg"), filename="eigenvalues.svg",
                                label="figure (SVG)", css_classes=["download-svg"], width=150),
    )

