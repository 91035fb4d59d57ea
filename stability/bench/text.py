"""The bench's matrix as text."""

from __future__ import annotations

from stability.bench.loads import SCORE_WORDS
from stability.bench.matrix import BenchResult

__all__ = ["bench_text"]


def bench_text(r: BenchResult) -> str:
    """The matrix as a table: case, slope, acceleration, score, braking distance, what limits it.

    Parameters
    ----------
    r : BenchResult

    Returns
    -------
    str
    """
    d = r.drive
    lines = [f"{r.layout}: virtual test bench (quasi-static; ISO 7176-2 manoeuvres and ISO 7176-3 stops), top speed "
             f"{d.max_speed_m_s:g} m/s forward, {d.reverse_speed_m_s:g} m/s backwards, declared maximum safe slope "
             f"{d.max_slope_deg:g} deg", "",
             f"  {'case':<36} {'slope':<26} {'ax m/s^2':>8} {'ay m/s^2':>8} {'score':>5} {'stop m':>7}  limited by"]
    for c in r.cases:
        dist = "" if c.braking_distance_m is None else (f"{c.braking_distance_m:7.2f}"
                                                        if c.braking_distance_m != float("inf") else "no stop")
        lines.append(f"  {c.name:<36} {c.slope:<26} {c.ax_m_s2:+8.2f} {c.ay_m_s2:+8.2f} {c.score:5d} {dist:>7}  "
                     f"{c.limited_by}")
    lines += ["", "Scores: " + "; ".join(f"{k} {v}" for k, v in SCORE_WORDS.items()) + ".",
              f"Worst score {r.worst_score}: {SCORE_WORDS[r.worst_score]}. Quasi-static: a tip-over's own dynamics "
              "are not modelled (docs/bench.md)."]
    return "\n".join(lines)
