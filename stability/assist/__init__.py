"""Motor assist for a front-wheel-drive power chair: LQR yaw stabilisation (Collins 1987, chapter 9).

Plant (:mod:`.plant`), design options (:mod:`.weights`), LQR and Kalman
design and margins (:mod:`.design`; disk margins :mod:`.disk`), gain
schedule (:mod:`.schedule`), robustness box (:mod:`.robustness`), sampled
controller (:mod:`.controller`), command tracking and gyro-bias handling
(:mod:`.tracking`), the sampled loop and its margins (:mod:`.digital`), the
safe top speed (:mod:`.top_speed`), joystick commands (:mod:`.commands`),
commanded driving, the torque requirement and the cross-slope check
(:mod:`.driving`), nonlinear checks (:mod:`.recovery`), thesis Figure 9-4
(:mod:`.destabilising`), gain table (:mod:`.tables`), figures
(:mod:`.figures`, :mod:`.figures_slope`, imported on demand: matplotlib) and
the command line (``python -m stability.assist``).
Rationale and results: ``docs/assist.md``.
"""

from __future__ import annotations

from stability.assist.controller import ANTI_WINDUP, TRACKING_TIME, DigitalController
from stability.assist.design import GAIN_UNITS, Design, LoopMargins, closed_loop_poles, design, loop_margins, realise
from stability.assist.destabilising import (
    DestabilisingSummary,
    destabilising_moment,
    destabilising_summary,
    valid_until,
)
from stability.assist.digital import (
    MarginCurves,
    MarginPair,
    discrete_loop,
    discrete_margins,
    margin_curves,
    margin_pair,
)
from stability.assist.disk import DiskMargins, disk_margins
from stability.assist.driving import (
    CROSS_SLOPES,
    HOLD_TOLERANCE,
    CommandRun,
    SlopeHold,
    TorqueRow,
    TrackingRuns,
    command_run,
    ramp_command,
    slalom_command,
    slope_hold,
    step_command,
    torque_requirement,
    tracking_runs,
    tracking_step,
    traction_limit,
)
from stability.assist.plant import (
    MOTOR_STATE,
    STATES,
    YAW_LOOP,
    Plant,
    pivot_inertia,
    plant,
    reversed_chair,
    standstill_plant,
)
from stability.assist.recovery import (
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
from stability.assist.robustness import ROBUST_PARAMETERS, Robustness, WorstCorner, robustness
from stability.assist.schedule import Schedule, schedule
from stability.assist.tables import (
    GainRow,
    PoleCurves,
    ReverseRow,
    format_margins,
    format_recovery,
    format_table,
    gain_table,
    pole_curves,
    reverse_table,
)
from stability.assist.top_speed import TopSpeed, check_top_speed, margin_top_speed
from stability.assist.tracking import (
    DriftCurves,
    Feedforward,
    TrackingMetrics,
    closed_loop,
    drift_curves,
    feedforward,
    final_heading,
    heading_drift,
    step_metrics,
)
from stability.assist.weights import DESIGNS, EstimatorWeights, GyroSensor, Weights

__all__ = [
    "DESIGNS", "STATES", "Weights", "GyroSensor", "EstimatorWeights",
    "MOTOR_STATE", "YAW_LOOP", "Plant", "plant", "standstill_plant", "pivot_inertia",
    "reversed_chair",
    "Feedforward", "feedforward", "closed_loop", "final_heading", "heading_drift", "TrackingMetrics", "step_metrics",
    "MarginPair", "margin_pair", "discrete_loop", "discrete_margins", "MarginCurves", "margin_curves",
    "DriftCurves", "drift_curves", "TrackingRuns", "tracking_runs",
    "CommandRun", "command_run", "tracking_step", "step_command", "ramp_command", "slalom_command",
    "TorqueRow", "torque_requirement", "traction_limit", "CROSS_SLOPES", "HOLD_TOLERANCE", "SlopeHold", "slope_hold",
    "ReverseRow", "reverse_table", "format_margins",
    "Design", "design", "realise", "closed_loop_poles", "LoopMargins", "loop_margins", "GAIN_UNITS",
    "DiskMargins", "disk_margins", "TopSpeed", "check_top_speed", "margin_top_speed",
    "Schedule", "schedule",
    "ROBUST_PARAMETERS", "WorstCorner", "Robustness", "robustness",
    "ANTI_WINDUP", "TRACKING_TIME", "DigitalController",
    "SETTLE_FRACTION", "SETTLE_FLOOR_DEG", "RecoveryRun", "RecoveryPair", "recovery", "recovery_runs",
    "recovery_table", "minimum_torque_limit", "DecayAgreement", "decay_agreement", "settle_time", "fit_decay_rate",
    "DestabilisingSummary", "destabilising_moment", "destabilising_summary", "valid_until",
    "GainRow", "gain_table", "format_table", "format_recovery", "PoleCurves", "pole_curves",
]
