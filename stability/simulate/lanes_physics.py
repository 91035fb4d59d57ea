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

import math

from numba import njit

from stability.models.forces import generated as _fo
from stability.models.full_width import generated as _fw
from stability.models.slope import generated as _sl
from stability.simulate import kernel as _k
from stability.simulate import kernel_equations as _ke
from stability.simulate.kernel_equations import _LINK, _NOWRAP, compiled
from stability.simulate.lanemath import LANE_MATH
from stability.tires import law as _tire_law

__all__ = ["lane_physics", "l_accelerations", "l_plane", "l_contact_loads", "l_kinematics", "l_slip_angles",
           "l_tire_resultant", "l_kinetic", "l_rest_rate", "l_tire_moment", "l_mechan", "l_segment_force", "l_table"]

_lane = njit(cache=False, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)

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
_cubic = compiled(_tire_law, ("cubic",), _lane, {"math": LANE_MATH}).cubic


@_lane
def _pick(i, w0, w1, w2, w3, w4, w5, w6, w7):
    """``w[int(i)]`` for ``i`` in 0 .. 7 by seven selects."""
    v = w1 if i >= 1.0 else w0
    v = w2 if i >= 2.0 else v
    v = w3 if i >= 3.0 else v
    v = w4 if i >= 4.0 else v
    v = w5 if i >= 5.0 else v
    v = w6 if i >= 6.0 else v
    return w7 if i >= 7.0 else v


@_lane
def l_table(W, r, j):
    """Lane ``j``'s tire table (rows ``r .. r + 47`` of ``W``: row ``r + 8 k + q`` coefficient ``k`` of segment
    ``q``) as a tuple of 48, read unconditionally: the lookups that use it (:func:`l_segment_force`, under MECHAN's
    conditions) then load nothing, which LLVM's vectoriser requires (a load under a condition, or at an index read
    from the data, keeps it from vectorising the loop)."""
    return (W[r + 0, j], W[r + 1, j], W[r + 2, j], W[r + 3, j], W[r + 4, j], W[r + 5, j],
            W[r + 6, j], W[r + 7, j], W[r + 8, j], W[r + 9, j], W[r + 10, j], W[r + 11, j],
            W[r + 12, j], W[r + 13, j], W[r + 14, j], W[r + 15, j], W[r + 16, j], W[r + 17, j],
            W[r + 18, j], W[r + 19, j], W[r + 20, j], W[r + 21, j], W[r + 22, j], W[r + 23, j],
            W[r + 24, j], W[r + 25, j], W[r + 26, j], W[r + 27, j], W[r + 28, j], W[r + 29, j],
            W[r + 30, j], W[r + 31, j], W[r + 32, j], W[r + 33, j], W[r + 34, j], W[r + 35, j],
            W[r + 36, j], W[r + 37, j], W[r + 38, j], W[r + 39, j], W[r + 40, j], W[r + 41, j],
            W[r + 42, j], W[r + 43, j], W[r + 44, j], W[r + 45, j], W[r + 46, j], W[r + 47, j])


@_lane
def l_segment_force(seg, s, fz, col=0):
    """:func:`stability.tires.law.segment_force` on a lane's table ``seg`` (:func:`l_table`; ``col`` unused): the
    same arithmetic, the segment ``min(floor(s), 7)``'s six coefficients picked by selects (:func:`_pick`) where
    the law indexes (``s >= 0`` or NaN: the law takes ``|slip|``; NaN picks segment 7 as the law does)."""
    fzp = max(fz, 0.0) if fz == fz else fz
    i = float(math.floor(s)) if s < 8.0 else 7.0    # min(floor(s), 7); NaN -> 7 (t stays NaN: NaN force)
    t = s - i
    g = seg
    return _cubic(_pick(i, g[0], g[1], g[2], g[3], g[4], g[5], g[6], g[7])
                  + t * _pick(i, g[24], g[25], g[26], g[27], g[28], g[29], g[30], g[31]),
                  _pick(i, g[8], g[9], g[10], g[11], g[12], g[13], g[14], g[15])
                  + t * _pick(i, g[32], g[33], g[34], g[35], g[36], g[37], g[38], g[39]),
                  _pick(i, g[16], g[17], g[18], g[19], g[20], g[21], g[22], g[23])
                  + t * _pick(i, g[40], g[41], g[42], g[43], g[44], g[45], g[46], g[47]), fzp)


#: the tire law and MECHAN (a block's tables are rows of its work array: :func:`l_segment_force`)
_law = compiled(_tire_law, ("lateral_force", "camber_force", "rolling_resistance", "rolling_force"), _lane,
                {"math": LANE_MATH, "segment_force": l_segment_force, "cubic": _cubic})
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
