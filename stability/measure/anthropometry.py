"""Seated user's yaw inertia from body mass and stature (de Leva 1996 segments in a seated posture).

A 14-segment body (head, trunk, upper arms, forearms, hands, thighs, shanks,
feet) with the male segment masses, lengths, c.g. positions and radii of
gyration of de Leva (1996), *Adjustments to Zatsiorsky-Seluyanov's segment
inertia parameters*, J. Biomech. 29(9):1223-1230, Tables 1 and 4, scaled
to the user's stature, placed in a wheelchair-sitting posture (trunk
reclined, thighs level, shanks hanging forward, forearms forward).  The
posture and joint widths are assumptions; docs/measure.md lists them and
compares the estimate with the ISO 75 kg dummy (3.1 kg m^2, Collins 1987
Appendix D).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

__all__ = ["DE_LEVA_MALE", "REFERENCE_STATURE", "SeatedBody", "seated_body", "UserInertiaEstimate",
           "user_yaw_inertia", "POSTURE_RANGES", "INDIVIDUAL_RELATIVE_STD"]

#: stature of de Leva's (1996) male sample (m); segment lengths scale with stature / this
REFERENCE_STATURE = 1.741

#: segment -> (mass fraction, length (m, male mean), c.g. fraction from proximal end,
#: radii of gyration / length: sagittal, transverse, longitudinal); de Leva (1996) Tables 1 and 4, male
DE_LEVA_MALE: dict[str, tuple[float, float, float, tuple[float, float, float]]] = {
    "head": (0.0694, 0.2429, 0.5002, (0.303, 0.315, 0.261)),      # vertex to C7
    "trunk": (0.4346, 0.6033, 0.5138, (0.328, 0.306, 0.169)),     # C7 to mid-hip
    "upper_arm": (0.0271, 0.2817, 0.5772, (0.285, 0.269, 0.158)),  # shoulder to elbow joint centre
    "forearm": (0.0162, 0.2689, 0.4574, (0.276, 0.265, 0.121)),    # elbow to wrist joint centre
    "hand": (0.0061, 0.0862, 0.7900, (0.628, 0.513, 0.401)),       # wrist to 3rd metacarpale
    "thigh": (0.1416, 0.4222, 0.4095, (0.329, 0.329, 0.149)),     # hip to knee joint centre
    "shank": (0.0433, 0.4340, 0.4459, (0.255, 0.249, 0.103)),     # knee joint centre to malleolus
    "foot": (0.0137, 0.2581, 0.4415, (0.257, 0.245, 0.124)),      # heel to toe tip
}

#: assumed joint half-widths as fractions of stature (hip joint centres, shoulder joint centres)
HIP_HALF_WIDTH = 0.05
SHOULDER_HALF_WIDTH = 0.10

#: posture angles (deg): nominal and the range the estimate's uncertainty covers
POSTURE_RANGES = {"recline_deg": (5.0, 0.0, 15.0), "shank_deg": (10.0, 0.0, 30.0), "forearm_deg": (30.0, 0.0, 60.0)}

#: assumed relative standard deviation of the yaw inertia between people of equal mass and stature
INDIVIDUAL_RELATIVE_STD = 0.10


@dataclass(frozen=True)
class SeatedBody:
    """A seated user: mass, c.g. position ahead of the hip joints and yaw inertia about the c.g.

    Attributes
    ----------
    mass : float
        Total mass of the 14 segments, kg (equals the body mass up to rounding of
        de Leva's mass fractions).
    x : float
        c.g. ahead of the hip joint centres, m (positive forward).
    i_z : float
        Yaw inertia about a vertical axis through the c.g., kg m^2.
    """

    mass: float
    x: float
    i_z: float


def _segment(mass: float, scale: float, name: str, start: tuple[float, float], angle_deg: float):
    """(mass, x, y, own yaw inertia) of a segment from ``start`` (x, y), its axis tilted ``angle_deg``
    from vertical in the x-z plane (its horizontal projection points in +x for positive angles)."""
    frac, length, cg, (k_sag, k_tr, k_long) = DE_LEVA_MALE[name]
    m = frac * mass
    ln = length * scale
    a = math.radians(angle_deg)
    x = start[0] + cg * ln * math.sin(a)
    k_perp2 = 0.5 * (k_sag**2 + k_tr**2)
    i_own = m * ln**2 * (k_long**2 * math.cos(a) ** 2 + k_perp2 * math.sin(a) ** 2)
    return m, x, start[1], i_own, start[0] + ln * math.sin(a)


def seated_body(mass: float, stature: float, *, recline_deg: float = 5.0, shank_deg: float = 10.0,
                forearm_deg: float = 30.0) -> SeatedBody:
    """Yaw inertia of a seated person about their own c.g.

    Parameters
    ----------
    mass : float
        Body mass (kg).
    stature : float
        Standing height (m).
    recline_deg : float
        Trunk (and head, upper arms) tilt back from vertical (deg).
    shank_deg : float
        Shanks tilted forward from vertical (deg); thighs are level, feet level.
    forearm_deg : float
        Forearms (and hands) tilted down from horizontal (deg): 0 hands in the lap, ~60 on the push rims.

    Returns
    -------
    SeatedBody
    """
    if not mass > 0:
        raise ValueError(f"user mass={mass!r} is invalid; valid range: > 0 kg")
    if not 0.5 <= stature <= 2.5:
        raise ValueError(f"user stature={stature!r} is invalid; valid range: 0.5 to 2.5 m")
    s = stature / REFERENCE_STATURE
    parts = []
    trunk_len = DE_LEVA_MALE["trunk"][1] * s
    back = -recline_deg  # tilting back points the segment's projection towards -x (going up)
    parts.append(_segment(mass, s, "trunk", (0.0, 0.0), back))
    neck_x = trunk_len * math.sin(math.radians(back))
    parts.append(_segment(mass, s, "head", (neck_x, 0.0), back))
    for side in (-1, 1):
        hip_y = side * HIP_HALF_WIDTH * stature
        sh_y = side * SHOULDER_HALF_WIDTH * stature
        # upper arm hangs from the shoulder (taken at C7 height) along the trunk's line
        *ua, elbow_x = _segment(mass, s, "upper_arm", (neck_x, sh_y), -back)
        parts.append(tuple(ua))
        *fa, wrist_x = _segment(mass, s, "forearm", (elbow_x, sh_y), 90.0 - forearm_deg)
        parts.append(tuple(fa))
        parts.append(tuple(_segment(mass, s, "hand", (wrist_x, sh_y), 90.0 - forearm_deg)[:4]))
        *th, knee_x = _segment(mass, s, "thigh", (0.0, hip_y), 90.0)
        parts.append(tuple(th))
        *sh, ankle_x = _segment(mass, s, "shank", (knee_x, hip_y), shank_deg)
        parts.append(tuple(sh))
        # the foot's c.g. fraction is from the heel; the heel lies about 1/4 foot length behind the ankle
        foot_len = DE_LEVA_MALE["foot"][1] * s
        parts.append(tuple(_segment(mass, s, "foot", (ankle_x - 0.25 * foot_len, hip_y), 90.0)[:4]))
    m = sum(p[0] for p in parts)
    x = sum(p[0] * p[1] for p in parts) / m
    y = sum(p[0] * p[2] for p in parts) / m
    i_z = sum(p[3] + p[0] * ((p[1] - x) ** 2 + (p[2] - y) ** 2) for p in parts)
    return SeatedBody(m, x, i_z)


@dataclass(frozen=True)
class UserInertiaEstimate:
    """Estimated seated yaw inertia: nominal value, standard uncertainty and posture extremes.

    ``low`` and ``high`` are the extremes over the posture ranges of
    :data:`POSTURE_RANGES`; ``std`` combines that spread (as a uniform
    distribution) with :data:`INDIVIDUAL_RELATIVE_STD`.

    Attributes
    ----------
    value : float
        Yaw inertia about the user's c.g. in the nominal posture, kg m^2.
    std : float
        Standard uncertainty of ``value``, kg m^2:
        ``hypot((high - low)/sqrt(12), INDIVIDUAL_RELATIVE_STD * value)``.
    low, high : float
        Smallest and largest yaw inertia over the nominal posture and the corners
        of :data:`POSTURE_RANGES`, kg m^2.
    x : float
        c.g. ahead of the hip joint centres in the nominal posture, m.
    """

    value: float
    std: float
    low: float
    high: float
    x: float


def user_yaw_inertia(mass: float, stature: float) -> UserInertiaEstimate:
    """Estimate a seated wheelchair user's yaw inertia from mass and stature.

    Evaluates :func:`seated_body` at the nominal posture and at every corner
    of :data:`POSTURE_RANGES` (8 postures).  For comparison, Collins (1987)
    Appendix D uses 3.1 kg m^2 for the 75 kg ISO dummy.

    Parameters
    ----------
    mass : float
        Body mass, kg (> 0).
    stature : float
        Standing height, m (0.5 to 2.5).

    Returns
    -------
    UserInertiaEstimate
        Nominal yaw inertia about the user's c.g. (kg m^2), its standard
        uncertainty, the posture extremes and the c.g. position (m).

    Raises
    ------
    ValueError
        If ``mass`` <= 0 or ``stature`` is outside 0.5 to 2.5 m.
    """
    nominal = seated_body(mass, stature, **{k: v[0] for k, v in POSTURE_RANGES.items()})
    corners = [seated_body(mass, stature, **dict(zip(POSTURE_RANGES, c, strict=True))).i_z
               for c in itertools.product(*[(v[1], v[2]) for v in POSTURE_RANGES.values()])]
    lo, hi = min(corners + [nominal.i_z]), max(corners + [nominal.i_z])
    posture_std = (hi - lo) / math.sqrt(12)
    std = math.hypot(posture_std, INDIVIDUAL_RELATIVE_STD * nominal.i_z)
    return UserInertiaEstimate(nominal.i_z, std, lo, hi, nominal.x)
