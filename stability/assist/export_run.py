"""``--export-c``: check the option, write the firmware, and summarise what the number format costs."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

from stability.assist.commands import COMMAND_FILTER
from stability.assist.export_c import ClosedLoop, export_c, vector_cases
from stability.assist.firmware import firmware_tables
from stability.assist.quantisation import MarginRow, margin_rows, worst_change
from stability.assist.schedule import Schedule
from stability.assist.top_speed import TopSpeed

__all__ = ["check_export", "FirmwareReport", "run_export"]


def check_export(directory: str | None, design: str) -> None:
    """Refuse an ``--export-c`` directory or design before any work (one-line errors).

    Parameters
    ----------
    directory : str or None
        The option's value (None: no export).
    design : str
        The ``--design``; firmware needs the gyro design.

    Raises
    ------
    ValueError
    """
    if directory is None:
        return
    if design != "gyro":
        raise ValueError(f"--export-c needs --design gyro (got {design!r}): the full-state design needs the "
                         "lateral velocity and caster angles, which a chair does not measure")
    if not directory:
        raise ValueError("--export-c '' is invalid; expected a directory name")
    full = os.path.abspath(directory)
    if os.path.exists(full) and not os.path.isdir(full):
        raise ValueError(f"--export-c {directory!r} is a file; expected a directory (created if missing)")
    parent = full if os.path.isdir(full) else os.path.dirname(full)
    if not os.path.isdir(parent):
        raise ValueError(f"--export-c {directory!r}: directory {parent!r} does not exist")
    if not os.access(parent, os.W_OK):
        raise ValueError(f"--export-c {directory!r}: directory {parent!r} is not writable")


@dataclass(frozen=True)
class FirmwareReport:
    """What ``--export-c`` wrote and what the number format costs.

    Attributes
    ----------
    directory : str
    q_format : str
    sample_rate_hz : float
    tolerance_N_m : dict
        Case -> derived tolerance of the C against the vectors (N m).
    margins : list of MarginRow
        Ideal schedule vs the firmware's tables (float, Q15, Q31).
    top_speed : str
        The safe top speed in words (:meth:`~stability.assist.top_speed.TopSpeed.sentence`), as in the README.
    warning : str or None
        The schedule goes beyond the safe top speed (:meth:`~stability.assist.top_speed.TopSpeed.warning`).
    """

    directory: str
    q_format: str
    sample_rate_hz: float
    tolerance_N_m: dict[str, float]
    margins: list[MarginRow]
    top_speed: str = ""
    warning: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (key ``firmware`` of the command's JSON)."""
        from stability.assist._format import json_float

        # the convention of stability.schemas: no value (a case's speed, a number format) inside a key
        return {"directory": self.directory, "q_format": self.q_format, "sample_rate_hz": self.sample_rate_hz,
                "top_speed": self.top_speed, "warning": self.warning,
                "tolerances": [{"case": k, "tolerance_N_m": v} for k, v in self.tolerance_N_m.items()],
                "margins": [{"speed_m_s": r.speed_m_s,
                             "tables": [{"format": f, **{k: json_float(x) for k, x in m.items()}}
                                        for f, m in r.margins.items()]} for r in self.margins],
                "worst_margin_loss": [{"format": v, **{k: json_float(x)
                                                       for k, x in worst_change(self.margins, v).items()}}
                                      for v in ("float", "Q15", "Q31")]}

    def format(self) -> str:
        """The text block of the command."""
        lines = [f"Firmware export ({self.q_format} tables, {self.sample_rate_hz:g} Hz) written to {self.directory}: "
                 "assist.h, assist.c, assist_vectors.json, README.txt",
                 f"  largest derived tolerance against the vectors: {max(self.tolerance_N_m.values()):.3g} N m",
                 *([f"  WARNING (also in README.txt): {self.warning}"] if self.warning else
                   [f"  {self.top_speed} (also in README.txt)"]),
                 "  sampled margins, ideal schedule vs the firmware's tables (gain dB / phase deg / delay ms):"]
        for r in self.margins:
            lines.append(f"  {r.speed_m_s:5.3g} m/s  " + "  ".join(
                f"{k} {m['gain_db']:.3f}/{m['phase_deg']:.3f}/{m['delay_ms']:.3f}" for k, m in r.margins.items()))
        for v in ("float", "Q15", "Q31"):
            w = worst_change(self.margins, v)
            lines.append(f"  worst loss, {v} tables vs ideal: " + ", ".join(
                f"{x:.3g} {u}" if math.isfinite(x) else f"- {u}"
                for x, u in zip(w.values(), ("dB", "deg", "ms"), strict=True)))
        return "\n".join(lines)


def run_export(sched: Schedule, directory: str, q_format: str, *, seed: int = 0,
               top: TopSpeed | None = None, closed_loop: ClosedLoop | None = None) -> FirmwareReport:
    """Write the firmware (:func:`~stability.assist.export_c.export_c`) and the margins of its tables.

    Parameters
    ----------
    sched : Schedule
        Gyro schedule.
    directory : str
    q_format : str
    seed : int
        Noise seed of the vectors.
    top : TopSpeed, optional
        The schedule's safe top speed (default: checked on the sampled margins alone,
        :func:`~stability.assist.export_c.margin_top_speed`).
    closed_loop : ClosedLoop, optional
        Where the vectors are recorded (:func:`~stability.assist.export_c.vector_cases`; default the short form's
        simulator).

    Returns
    -------
    FirmwareReport
    """
    vectors = vector_cases(sched, seed=seed, closed_loop=closed_loop)
    info = export_c(sched, directory, q_format, vectors=vectors, top=top)
    rows = margin_rows(sched, firmware_tables(sched, command_filter_s=COMMAND_FILTER))
    t = info["top_speed"]
    return FirmwareReport(directory, q_format, sched.gyro.sample_rate_hz, info["tolerance_N_m"], rows,
                          t.sentence(), t.warning())
