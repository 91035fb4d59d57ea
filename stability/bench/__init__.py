"""A virtual test bench for ISO 7176-2 (dynamic stability: wheel lift) and ISO 7176-3 (braking distance).

``loads`` (quasi-static wheel loads under acceleration on a slope, lift and tipping, the scores) -> ``matrix``
(the drive controller and brakes, the manoeuvre and slope matrix, braking distances) -> ``text`` and ``python -m
stability.bench``.  Quasi-static and on any layout (:mod:`stability.layout`); docs/bench.md.
"""

from __future__ import annotations

from stability.bench.loads import SCORE_WORDS, LoadCase, case_loads
from stability.bench.matrix import DRIVE_SETTINGS, BenchResult, Case, Drive, braking_distance, run_bench

__all__ = ["Drive", "DRIVE_SETTINGS", "Case", "BenchResult", "run_bench", "braking_distance", "LoadCase",
           "case_loads", "SCORE_WORDS"]
