"""``--faults``: the single sensor faults at every design speed, the torque requirement and the safe top speed."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from stability.assist.driving import torque_requirement
from stability.assist.faults import FaultRow, fault_runs, format_faults
from stability.assist.schedule import Schedule
from stability.assist.top_speed import TopSpeed, format_top_speed, full_turn_peaks, top_speed

__all__ = ["Safety", "run_safety"]


@dataclass(frozen=True)
class Safety:
    """Fault table and safe top speed of one schedule.

    Attributes
    ----------
    faults : list of FaultRow
    top : TopSpeed
    """

    faults: list[FaultRow]
    top: TopSpeed

    def to_dict(self) -> dict[str, Any]:
        """JSON keys ``faults``, ``safe_top_speed_m_s``, ``limited_by`` and ``top_speed_checks``."""
        t = self.top.to_dict()
        return {"faults": [f.to_dict() for f in self.faults], "safe_top_speed_m_s": t["safe_top_speed_m_s"],
                "limited_by": t["limited_by"], "top_speed_checks": t["checks"]}

    def format(self) -> str:
        """The text blocks."""
        return "\n" + format_faults(self.faults) + "\n\n" + format_top_speed(self.top) + "\n"


def run_safety(sched: Schedule, rows: Sequence[Any], *, seed: int = 0, progress: bool = True) -> Safety:
    """Faults at every design speed on level ground and a 2 deg cross slope, then the safe top speed.

    Parameters
    ----------
    sched : Schedule
        Gyro schedule.
    rows : sequence of GainRow
        :func:`~stability.assist.tables.gain_table` of ``sched``.
    seed : int
        Gyro-noise seed.
    progress : bool
        Progress bar of the simulation batches (on a terminal).

    Returns
    -------
    Safety
    """
    faults = fault_runs(sched, seed=seed, progress=progress)
    speeds = tuple(float(s) for s in sched.speeds)
    torques = torque_requirement(sched, speeds)
    return Safety(faults, top_speed(sched, rows, torques, faults, full_turn_peaks(sched, speeds)))
