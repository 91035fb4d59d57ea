"""The lanes kernel's physics: the scalar kernel's helpers and the generated physics compiled again for lanes.

Each function here is the scalar kernel's (:mod:`stability.simulate.kernel`,
:mod:`stability.simulate.kernel_equations`), the generated physics'
(:mod:`stability.models`) or the tire law's (:mod:`stability.tires.law`), compiled
as it is (:func:`~stability.simulate.kernel_equations.compiled`) in a namespace
whose :mod:`math` is :data:`stability.simulate.lanemath.LANE_MATH` (polynomial
sine, cosine and arctangent LLVM can vectorise) and with numpy's error model (no
exceptions, so no loop exits), inlined into the lanes kernel's loops: nothing is
re-typed.  Used by :mod:`stability.simulate.lanes_step`.
"""

from __future__ import annotations

from numba import njit

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.simulate import kernel as _k
from stability.simulate import kernel_equations as _ke
from stability.simulate.kernel_equations import _NOWRAP, compiled
from stability.simulate.lanemath import LANE_MATH
from stability.tires import law as _tire_law

__all__ = ["lane_physics", "l_accelerations", "l_plane", "l_contact_loads", "l_kinematics", "l_slip_angles",
           "l_tire_resultant", "l_kinetic", "l_rest_rate", "l_tire_moment", "l_mechan"]

_lane = njit(cache=False, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP)

# The generated physics, compiled again with the lane math (the same source; nothing re-typed)
_lfo = compiled(_fo, tuple(_fo.__all__), _lane, {"math": LANE_MATH})
_lfw = compiled(_fw, ("contact_velocities_exact", "contact_velocities_thesis", "accelerations_exact",
                      "accelerations_thesis"), _lane, {"math": LANE_MATH})
_lsl = compiled(_sl, ("accelerations_slope_exact", "gravity_body"), _lane, {"math": LANE_MATH})
#: the scalar kernel's helpers of the step's arithmetic, calling the lane physics
_lke = compiled(_ke, ("accelerations", "_acc_thesis", "_acc_exact", "_acc_slope"), _lane, {
    "math": LANE_MATH, "acc_exact": _lfw.accelerations_exact, "acc_thesis": _lfw.accelerations_thesis,
    "acc_slope": _lsl.accelerations_slope_exact})
_lcv = compiled(_k, ("velocities", "_cv_thesis", "_cv_exact"), _lane, {
    "math": LANE_MATH, "cv_thesis": _lfw.contact_velocities_thesis, "cv_exact": _lfw.contact_velocities_exact})
_lk = compiled(_k, ("plane", "contact_loads", "kinematics", "slip_angles"), _lane, {
    "math": LANE_MATH, "gravity_body": _lsl.gravity_body, "normal_loads": _lfo.normal_loads,
    "model_velocities": _lcv.velocities, "slip_angle": _lfo.slip_angle})
l_accelerations = _lke.accelerations
l_plane, l_contact_loads, l_kinematics, l_slip_angles = _lk.plane, _lk.contact_loads, _lk.kinematics, _lk.slip_angles
l_tire_resultant, l_kinetic, l_rest_rate = _lfo.tire_resultant, _lfo.kinetic_pin_moment, _lfo.rest_rate
l_tire_moment = _lfo.tire_yaw_moment
#: the tire law and MECHAN (the tables of a block side by side: a run's first column is ``8 j``)
_law = compiled(_tire_law, ("cubic", "segment_force", "lateral_force", "camber_force", "rolling_resistance",
                            "rolling_force"), _lane, {"math": LANE_MATH})
l_mechan = compiled(_k, ("mechan",), _lane, {"math": LANE_MATH, "lateral_force": _law.lateral_force,
                                              "rolling_force": _law.rolling_force,
                                              "camber_force": _law.camber_force}).mechan


@_lane
def _p(W, j):
    """Lane ``j``'s chair parameters as a tuple (the scalar helpers index it like a run's ``P``)."""
    return (W[0, j], W[1, j], W[2, j], W[3, j], W[4, j], W[5, j], W[6, j], W[7, j], W[8, j], W[9, j],
            W[10, j], W[11, j], W[12, j], W[13, j], W[14, j], W[15, j], W[16, j], W[17, j])


@_lane
def _s(W, j):
    """Lane ``j``'s per-run scalars as a tuple (a run's ``S``)."""
    return (W[18, j], W[19, j], W[20, j], W[21, j], W[22, j], W[23, j], W[24, j], W[25, j], W[26, j], W[27, j])


def lane_physics() -> dict:
    """The lane versions by name: each the scalar kernel's function compiled in the lane namespace.

    Returns
    -------
    dict
        Name to numba dispatcher (inlined into the lanes kernel; no Python wrapper).
    """
    return {"accelerations": l_accelerations, "plane": l_plane, "contact_loads": l_contact_loads,
            "kinematics": l_kinematics, "slip_angles": l_slip_angles, "tire_resultant": l_tire_resultant}
