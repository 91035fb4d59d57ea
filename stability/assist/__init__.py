"""Motor assist for a front-wheel-drive power chair: LQR yaw stabilisation (Collins 1987, chapter 9).

Plant (:mod:`.plant`), design options (:mod:`.weights`), LQR and Kalman
design and margins (:mod:`.design`), gain schedule (:mod:`.schedule`),
robustness box (:mod:`.robustness`), sampled controller (:mod:`.controller`),
nonlinear checks (:mod:`.recovery`), thesis Figure 9-4 (:mod:`.destabilising`),
gain table (:mod:`.tables`), figures (:mod:`.figures`, imported on demand:
matplotlib) and the command line (``python -m stability.assist``).
Rationale and results: ``docs/assist.md``.
"""

from __future__ import annotations

from .controller import DigitalController
from .design import Design, LoopMargins, closed_loop_poles, design, loop_margins, realise
from .destabilising import DestabilisingSummary, destabilising_moment, destabilising_summary, valid_until
from .plant import STATES, Plant, lateral_force_column, plant
from .recovery import (
    SETTLE_FLOOR_DEG,
    SETTLE_FRACTION,
    DecayAgreement,
    RecoveryPair,
    RecoveryRun,
    decay_agreement,
    fit_decay_rate,
    minimum_torque_limit,
    recovery,
    recovery_runs,
    recovery_table,
    settle_time,
)
from .robustness import ROBUST_PARAMETERS, Robustness, WorstCorner, robustness
from .schedule import Schedule, schedule
from .tables import GainRow, PoleCurves, format_recovery, format_table, gain_table, pole_curves
from .weights import DESIGNS, EstimatorWeights, GyroSensor, Weights

__all__ = [
    "DESIGNS", "STATES", "Weights", "GyroSensor", "EstimatorWeights",
    "Plant", "plant", "lateral_force_column",
    "Design", "design", "realise", "closed_loop_poles", "LoopMargins", "loop_margins",
    "Schedule", "schedule",
    "ROBUST_PARAMETERS", "WorstCorner", "Robustness", "robustness",
    "DigitalController",
    "SETTLE_FRACTION", "SETTLE_FLOOR_DEG", "RecoveryRun", "RecoveryPair", "recovery", "recovery_runs",
    "recovery_table", "minimum_torque_limit", "DecayAgreement", "decay_agreement", "settle_time", "fit_decay_rate",
    "DestabilisingSummary", "destabilising_moment", "destabilising_summary", "valid_until",
    "GainRow", "gain_table", "format_table", "format_recovery", "PoleCurves", "pole_curves",
]
