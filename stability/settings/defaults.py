"""The one table of defaults shared by the Python API and every command line.

Each entry names a default once: its value, its unit and what it means.
The API functions take their keyword defaults from here (directly, or
through the small frozen option classes that are built on this table:
:class:`stability.settings.run.RunSpec` (every run setting: its rows here are generated from it),
:class:`stability.chair.power.DriveTrain`,
:class:`stability.assist.weights.GyroSensor`,
:class:`stability.slope.equilibrium.HandRim`), and every command line takes
its option defaults from the same names, so ``stability.run_simulation(chair,
0.75)`` and ``python -m stability.simulate --speed 0.75`` run the same thing.
``tests/test_defaults.py`` walks every parser and the public API functions
and checks that both equal this table.

A new command or API function that needs a default already named here takes
it from here (``from stability.settings import defaults as D``; ``default=D.MODEL``);
a new default goes into :data:`TABLE` with its unit and meaning.

Examples
--------
>>> from stability.settings import defaults
>>> defaults.MODEL, defaults.TIRE_RANGE
('exact', 'warn')
>>> defaults.TABLE["sample_rate_hz"].unit
'Hz'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from stability.settings.drive import BENCH_CHAIR, DRIVE_SETTINGS
from stability.settings.reference import LEVEL, REFERENCE_CHAIR
from stability.settings.run import RUN_SETTINGS, RunSpec

__all__ = ["Default", "TABLE", "STEADY_YAW_RATE", "CHAIR", "POWER_CHAIR", "MODEL", "CASTERS", "FRICTION_LAW",
           "SCHEME", "DT", "SPEED",
           "PUSH_FORCE",
           "PUSH_DURATION", "YAW_RATE_LEVEL", "HORIZON_S", "MAX_IMPULSE", "TIRE_RANGE", "MAX_SPEED",
           "SAMPLES", "SEED", "COVERAGE", "NONLINEAR_SAMPLES", "SUMMARY_SPEEDS", "SHIMMY_SPEEDS", "STUDY_SPEEDS",
           "ASSIST_SPEEDS", "HANDRIM_WHEEL_RADIUS", "HANDRIM_RADIUS", "DRIVE_WHEEL_RADIUS", "TORQUE_LIMIT",
           "MOTOR_LAG", "TRACTION_COEFFICIENT", "SAMPLE_RATE_HZ", "BIAS_TIME_CONSTANT", "GYRO_NOISE", "GYRO_BIAS",
           "COMMAND_FILTER", "ASSIST_DESIGN", "MAX_HEADING_ERROR", "SHIMMY_AMPLITUDE_DEG", "SLOPE_SIM_TIME",
           "ADVISE_SPEEDS", "ADVISE_CROSS_SLOPE_DEG",
           "CROSS_SLOPE", "GRADE",
           "speeds_text"]


@dataclass(frozen=True)
class Default:
    """One default: its value, unit and meaning.

    Attributes
    ----------
    value : Any
        The default value (in the unit below).
    unit : str
        Unit of the value ("" for a choice or a count).
    doc : str
        What it is, in a few words.
    """

    value: Any
    unit: str
    doc: str


def speeds_text(speeds: tuple[float, ...]) -> str:
    """A speed tuple as the ``--speeds`` option writes it (comma list), e.g. ``"0.25,0.5,0.75"``.

    Parameters
    ----------
    speeds : tuple of float
        Speeds, m/s.

    Returns
    -------
    str
    """
    return ",".join(f"{s:g}" for s in speeds)


# --- chairs ---------------------------------------------------------------------------------------------
#: Yaw rate (rad/s) above which the end of a run is a steady turn rather than straight running: 0.01 rad/s is
#: 5.7 deg in 10 s, a drift a user notices over a corridor's length (the front-caster chair's is 0.04 rad/s).
#: The report's words and the assist's straight-again check both use it.
STEADY_YAW_RATE = 0.01
#: Chair of every command that takes ``--chair`` (the thesis's reference chair), and of the power-chair commands.
CHAIR = REFERENCE_CHAIR
POWER_CHAIR = "power-fwd"

# --- models and integration: the run settings' defaults are the RunSpec's (stability.settings.run) ----------
_RUN = RunSpec()
#: Equation variant of every analysis and simulation: "exact" (the thesis's linearisation mistakes
#: corrected) or "thesis" (program WCHAIR's equations); see docs/models.md.
MODEL = _RUN.model
#: Caster condition: "free" (swivelling, Coulomb pin friction) or "locked".
CASTERS = _RUN.casters
#: Pin friction law of every run: "stick-slip" (a caster at rest stays at rest while friction can hold it;
#: converged in the step where program WCHAIR's "kinetic" law is not: docs/simulator.md).
FRICTION_LAW = _RUN.friction_law
#: Integration scheme of the simulator: program WCHAIR's fixed step ("wchair") or error-controlled ("adaptive").
SCHEME = _RUN.scheme
#: Fixed time step of the wchair scheme, s (WCHAIR's TSTEP).
DT = _RUN.dt
#: Speed of a single run or check, m/s (the thesis's reference speed, Figure 8-3a).
SPEED = _RUN.speed
#: The reference push at the c.g.: force (N, to the right) and duration (s), thesis chapter 8.
PUSH_FORCE = _RUN.push_force
PUSH_DURATION = _RUN.push_duration
#: The instability criterion: |yaw rate| level (rad/s) reached within a horizon (s).
YAW_RATE_LEVEL = LEVEL
HORIZON_S = _RUN.horizon
#: Largest push a critical-impulse search tries, N s.
MAX_IMPULSE = 40.0
#: Tire data outside its fitted slip and load range: "warn" (extrapolate and note), "clamp" or "raise".
TIRE_RANGE = "warn"

# --- linear analysis and uncertainty ---------------------------------------------------------------------
#: Upper end of the critical-speed search, m/s.
MAX_SPEED = 30.0
#: Monte Carlo draws of the linear intervals, their seed and their coverage.
SAMPLES = 1000
SEED = 0
COVERAGE = 0.95
#: Monte Carlo draws of the nonlinear measures (critical impulse, equal-instability speed).
NONLINEAR_SAMPLES = 200

# --- speed lists of the commands (m/s) -------------------------------------------------------------------
#: Speeds of the growth-rate tables (critical_speed, compare, the linear intervals).
SUMMARY_SPEEDS = (0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0)
#: Speeds of the shimmy table (START:STOP:STEP).
SHIMMY_SPEEDS = "0.25:3:0.25"
#: Speeds of the critical-impulse study (START:STOP:STEP).
STUDY_SPEEDS = "0.5:1.0:0.25"
#: Design speeds of the motor assist's gain schedule (START:STOP:STEP).
ASSIST_SPEEDS = "0.5:3.0:0.25"

# --- manual drive (hand rims) ----------------------------------------------------------------------------
#: Rolling radius of a 24-inch drive wheel and its typical hand-rim radius, m.
HANDRIM_WHEEL_RADIUS = 0.305
HANDRIM_RADIUS = 0.265

# --- power drive and motor assist ------------------------------------------------------------------------
#: Drive-wheel rolling radius of a power chair, m; motor torque limit per wheel, N m;
#: first-order motor/speed-loop lag, s; tire-ground traction coefficient.
DRIVE_WHEEL_RADIUS = 0.178
TORQUE_LIMIT = 70.0
MOTOR_LAG = 0.02
TRACTION_COEFFICIENT = 0.7
#: Controller sample rate, Hz; time constant of the gyro-bias estimate from the wheel speeds, s (0: off);
#: gyro noise density (deg/s/sqrt(Hz)) and bias after calibration (deg/s).
SAMPLE_RATE_HZ = 200.0
BIAS_TIME_CONSTANT = 1.0
GYRO_NOISE = 0.05
GYRO_BIAS = 0.1
#: Reference-model time constant of a yaw-rate command, s (no overshoot, ~0.7 s settling; docs/assist.md).
COMMAND_FILTER = 0.2
#: Feedback structure of the assist and its Bryson weight on the heading error, deg.
ASSIST_DESIGN = "gyro"
MAX_HEADING_ERROR = 2.0
#: Number format of the assist's exported firmware tables (float, Q15 or Q31).
Q_FORMAT = "float"

# --- other commands --------------------------------------------------------------------------------------
#: Shimmy amplitude of the pin-friction (describing-function) estimate, deg.
SHIMMY_AMPLITUDE_DEG = 5.0
#: Cross slope and grade, deg: level ground unless asked for.
CROSS_SLOPE = 0.0
GRADE = 0.0
#: Report time of the simulated uncorrected turn on a cross slope, s.
SLOPE_SIM_TIME = 1.0
#: The advisor's use speeds (START:STOP:STEP, m/s): the thesis's indoor range around its 0.75 m/s reference.
ADVISE_SPEEDS = "0.5:1:0.25"
#: Cross slope of the advisor's hand-rim force constraint, deg (a typical sidewalk cross slope).
ADVISE_CROSS_SLOPE_DEG = 2.0

#: The table: name -> :class:`Default`.  The names are the API keywords and the command lines' option
#: names (``--sample-rate`` -> ``sample_rate_hz`` where the API keyword carries the unit).
TABLE: dict[str, Default] = {
    "chair": Default(CHAIR, "", "chair (preset name or TOML file) of the commands that take --chair"),
    "power_chair": Default(POWER_CHAIR, "", "chair of the power-chair commands (assist)"),
    "yaw_rate_level": Default(YAW_RATE_LEVEL, "rad/s", "|yaw rate| level of the instability criterion"),
    "max_impulse": Default(MAX_IMPULSE, "N s", "largest push a critical-impulse search tries"),
    "tire_range": Default(TIRE_RANGE, "", "tire data outside the fitted range: warn, clamp or raise"),
    "max_speed": Default(MAX_SPEED, "m/s", "upper end of the critical-speed search"),
    "samples": Default(SAMPLES, "", "Monte Carlo draws of the linear intervals"),
    "seed": Default(SEED, "", "seed of the draws"),
    "coverage": Default(COVERAGE, "", "coverage of the intervals"),
    "nonlinear_samples": Default(NONLINEAR_SAMPLES, "", "Monte Carlo draws of the nonlinear measures"),
    "summary_speeds": Default(SUMMARY_SPEEDS, "m/s", "speeds of the growth-rate tables"),
    "shimmy_speeds": Default(SHIMMY_SPEEDS, "m/s", "speeds of the shimmy table"),
    "study_speeds": Default(STUDY_SPEEDS, "m/s", "speeds of the critical-impulse study"),
    "assist_speeds": Default(ASSIST_SPEEDS, "m/s", "design speeds of the assist's gain schedule"),
    "handrim_wheel_radius": Default(HANDRIM_WHEEL_RADIUS, "m", "rolling radius of a manual chair's drive wheel"),
    "handrim_radius": Default(HANDRIM_RADIUS, "m", "hand-rim radius"),
    "drive_wheel_radius": Default(DRIVE_WHEEL_RADIUS, "m", "rolling radius of a power chair's drive wheel"),
    "torque_limit": Default(TORQUE_LIMIT, "N m", "motor torque limit per drive wheel"),
    "motor_lag": Default(MOTOR_LAG, "s", "first-order motor/speed-loop lag"),
    "traction_coefficient": Default(TRACTION_COEFFICIENT, "", "tire-ground traction coefficient"),
    "sample_rate_hz": Default(SAMPLE_RATE_HZ, "Hz", "assist controller sample rate"),
    "bias_time_constant": Default(BIAS_TIME_CONSTANT, "s", "time constant of the gyro-bias estimate (0: off)"),
    "gyro_noise": Default(GYRO_NOISE, "deg/s/sqrt(Hz)", "gyro noise density"),
    "gyro_bias": Default(GYRO_BIAS, "deg/s", "gyro bias after calibration"),
    "command_filter": Default(COMMAND_FILTER, "s", "reference-model time constant of a yaw-rate command"),
    "design": Default(ASSIST_DESIGN, "", "assist feedback structure"),
    "max_heading_error": Default(MAX_HEADING_ERROR, "deg", "Bryson weight: acceptable heading error"),
    "q_format": Default(Q_FORMAT, "", "number format of the exported firmware tables: float, Q15 or Q31"),
    "amplitude_deg": Default(SHIMMY_AMPLITUDE_DEG, "deg", "shimmy amplitude of the pin-friction estimate"),
    "sim_time": Default(SLOPE_SIM_TIME, "s", "report time of the simulated uncorrected turn"),
    "advise_speeds": Default(ADVISE_SPEEDS, "m/s", "the advisor's use speeds"),
    "advise_cross_slope_deg": Default(ADVISE_CROSS_SLOPE_DEG, "deg", "cross slope of the advisor's hand-rim force"),
    "cross_slope": Default(CROSS_SLOPE, "deg", "cross slope, falling to the right + (level ground)"),
    "grade": Default(GRADE, "deg", "grade, uphill + (level ground)"),
}
#: Every run setting's default, unit and meaning, from the RunSpec's own table (stability.settings.run).
TABLE.update({name: Default(getattr(_RUN, name), st.unit, st.help) for name, st in RUN_SETTINGS.items()})
# the virtual test bench's drive settings (stability.settings.drive) and its default chair
TABLE.update({name: Default(d, unit, text) for name, (d, unit, _, text) in DRIVE_SETTINGS.items()})
TABLE["bench_chair"] = Default(BENCH_CHAIR, "-", "the bench's default chair (a layout preset)")
