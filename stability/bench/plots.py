"""The bench's pages: one per manoeuvre family (starts, stops, turns), for ``python -m stability.bench -o FILE.pdf``.

Each page draws every case of its family as a bar: how far the effective centre of the case (where gravity and the
d'Alembert force meet the ground) lies inside the support polygon of the wheels, in cm, coloured by the case's
wheel-lift score; a bar below zero is a chair that tips.  The stops' page adds the braking distances.  The caption
says what to conclude from the page's own cases.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from matplotlib.figure import Figure
from matplotlib.patches import Patch

from stability.bench.loads import SCORE_WORDS
from stability.bench.matrix import BenchResult, Case
from stability.plotting import pages as P
from stability.plotting.style import OKABE_ITO, UNSTABLE

__all__ = ["FAMILIES", "SCORE_COLOURS", "family_page", "bench_pages"]

#: The matrix's manoeuvre families: key, page title.
FAMILIES = (("start", "starts (ISO 7176-2)"), ("stop", "stops (ISO 7176-2 wheel lift, ISO 7176-3 braking distance)"),
            ("turn", "turns at top speed (ISO 7176-2)"))
#: Colour of each score (Okabe-Ito: blue, orange, reddish purple, vermillion; colour-blind safe).
SCORE_COLOURS = {0: OKABE_ITO[0], 1: OKABE_ITO[1], 2: OKABE_ITO[3], 3: UNSTABLE}


def _label(c: Case) -> str:
    return f"{c.name}, {c.slope}"


def _caption(family: str, cases: Sequence[Case]) -> str:
    worst = max(cases, key=lambda c: (c.score, -c.loads.margin_m))
    closest = min(cases, key=lambda c: c.loads.margin_m)
    words = [f"What to conclude: the worst {family} case scores {worst.score} ({SCORE_WORDS[worst.score]}): "
             f"{_label(worst)}" + (f", {worst.limited_by}" if worst.limited_by else "") + "."]
    if closest.loads.margin_m >= 0:
        words.append(f" The closest to tipping is {_label(closest)}, its effective centre "
                     f"{100 * closest.loads.margin_m:.3g} cm inside the wheels' support polygon.")
    if family == "stop":
        finite = [c for c in cases if c.braking_distance_m is not None and math.isfinite(c.braking_distance_m)]
        never = [c for c in cases if c.braking_distance_m is not None and not math.isfinite(c.braking_distance_m)]
        if finite:
            longest = max(finite, key=lambda c: c.braking_distance_m or 0.0)
            words.append(f" The longest stop is {longest.braking_distance_m:.3g} m ({_label(longest)}).")
        if never:
            words.append(f" {len(never)} stop(s) never end: the slope pulls harder than the chair can brake.")
    words.append(" Quasi-static: a tip-over's own dynamics are not modelled.")
    return "".join(words)


def family_page(r: BenchResult, family: str) -> Figure:
    """One page: the support margin of every case of ``family`` (and the braking distances of the stops).

    Parameters
    ----------
    r : BenchResult
    family : {"start", "stop", "turn"}

    Returns
    -------
    matplotlib.figure.Figure
    """
    titles = dict(FAMILIES)
    if family not in titles:
        raise ValueError(f"family={family!r} is invalid; valid: {', '.join(titles)}")
    cases = [c for c in r.cases if c.family == family]
    d = r.drive
    ncols = 2 if family == "stop" else 1
    fig, axes = P.page(f"{r.layout}: virtual bench, {titles[family]}",
                       f"quasi-static load transfer, top speed {d.max_speed_m_s:g} m/s forward and "
                       f"{d.reverse_speed_m_s:g} m/s backwards, declared maximum safe slope {d.max_slope_deg:g} deg, "
                       f"drive traction {d.traction:g}", ncols=ncols)
    labels = [_label(c) for c in cases]
    y = list(range(len(cases)))[::-1]
    ax = axes[0, 0]
    margins = [100 * c.loads.margin_m if math.isfinite(c.loads.margin_m) else 0.0 for c in cases]
    ax.barh(y, margins, color=[SCORE_COLOURS[c.score] for c in cases], edgecolor="0.2", linewidth=0.5)
    ax.axvline(0.0, color="black", linewidth=1.0)
    ax.set_yticks(y, labels, fontsize=7.5)
    ax.set_xlabel("effective centre inside the wheels' support polygon (cm; < 0: tips)")
    ax.set_title("support margin of each case", fontsize=10)
    used = sorted({c.score for c in cases})
    ax.legend([Patch(color=SCORE_COLOURS[s]) for s in used], [f"score {s}: {SCORE_WORDS[s]}" for s in used],
              fontsize=7, loc="best", framealpha=0.9)
    if family == "stop":
        bx = axes[0, 1]
        dist = [c.braking_distance_m for c in cases]
        finite = [x for x in dist if x is not None and math.isfinite(x)]
        cap = 1.15 * max(finite) if finite else 1.0
        bx.barh(y, [x if x is not None and math.isfinite(x) else cap for x in dist],
                color=[OKABE_ITO[4] if x is not None and math.isfinite(x) else "white" for x in dist],
                hatch=["" if x is not None and math.isfinite(x) else "//" for x in dist], edgecolor="0.2",
                linewidth=0.5)
        for yi, x in zip(y, dist, strict=True):
            bx.text(min(x, cap) if x is not None and math.isfinite(x) else cap, yi,
                    f" {x:.2f} m" if x is not None and math.isfinite(x) else " no stop", va="center", fontsize=7)
        bx.set_yticks(y, [""] * len(y))
        bx.set_xlim(0.0, 1.3 * cap)
        bx.set_xlabel("braking distance (m): v t_delay + v^2 / (2 a)")
        bx.set_title("braking distance (ISO 7176-3)", fontsize=10)
    P.finish(fig, left=0.30, bottom=0.16, wspace=0.08)
    lines = P.wrap_text(_caption(family, cases), 150)
    fig.text(0.03, 0.085, "\n".join(lines), ha="left", va="top", fontsize=8.5)
    return fig


def bench_pages(r: BenchResult) -> list[Figure]:
    """Every family's page, in the matrix's order.

    Parameters
    ----------
    r : BenchResult

    Returns
    -------
    list of matplotlib.figure.Figure
    """
    present = {c.family for c in r.cases}
    return [family_page(r, f) for f, _ in FAMILIES if f in present]
