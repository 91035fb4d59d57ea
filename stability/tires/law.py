"""The tire force law, written once: cubic fits (4-1), WCHAIR's interpolation, policies, camber, rolling resistance.

Every function here is plain scalar Python (``math`` and arithmetic), so the
same function runs on Python floats (what :class:`~stability.tires.Tire` and
:class:`~stability.tires.LinearTire` call, element by element for arrays) and
compiled by numba as it is (what the simulator's kernels call,
:mod:`stability.simulate.kernel_equations`): one copy of the law for every path.  Forces in N, angles in deg.

A tested tire is its segment table ``seg`` (shape ``(6, 8)``: rows ``a0, b0,
c0, da, db, dc``; :meth:`~stability.tires.Tire.segment_arrays`), its lateral
scale and its fitted range ``lim = (slip limit deg, load limit N)``; a linear
tire is its stiffness in N/deg (scale included).
"""

from __future__ import annotations

import math

__all__ = ["TESTED", "LINEAR", "CLAMP", "EXTRAPOLATE", "RAISE", "ROLLING_OFF", "ROLLING_CUBIC", "ROLLING_LINEAR",
           "cubic", "segment_force", "lateral_force", "camber_force", "rolling_resistance", "rolling_force"]

#: tire kinds of :func:`lateral_force`: a tested tire (segment table), a linear tire (N/deg)
TESTED, LINEAR = 0, 1
#: policy codes of :func:`lateral_force` (the order of :data:`stability.tires.POLICIES`)
CLAMP, EXTRAPOLATE, RAISE = 0, 1, 2
#: rolling-resistance kinds of :func:`rolling_resistance`: off, the Appendix B cubic, the linear ``f_r F_z`` (3-2)
ROLLING_OFF, ROLLING_CUBIC, ROLLING_LINEAR = 0, 1, 2


def cubic(a, b, c, fz):
    """Eq (4-1) without its constant: ``F = a F_z + b F_z^2 + c F_z^3`` in Horner form, N.

    Parameters
    ----------
    a, b, c : float or ndarray
        Coefficients: a [-], b [1/N], c [1/N^2].
    fz : float or ndarray
        Normal force, N.

    Returns
    -------
    float or ndarray
        ``fz (a + fz (b + fz c))``, N.
    """
    return fz * (a + fz * (b + fz * c))


def segment_force(seg, s, fz, col=0):
    """Magnitude of the cornering force of a tested tire (N): WCHAIR's MECHAN/POLYFT interpolation.

    ``F(s) = (s - I) (F_{I+1} - F_I) + F_I`` with ``I = min(floor(s), 7)``:
    interpolating the coefficients of segment ``I`` linearly in slip and
    evaluating one cubic (4-1) equals interpolating the forces, since the
    force is linear in the coefficients.  ``fz <= 0`` gives 0 (a wheel off
    the ground); NaN in gives NaN out.

    Parameters
    ----------
    seg : ndarray, shape (6, 8)
        Rows ``a0, b0, c0, da, db, dc`` of the eight one-degree segments.
    s : float
        Slip magnitude, deg (already limited as the policy says).
    fz : float
        Normal force, N.
    col : int
        Column of segment 0 in ``seg`` (0; the lanes kernel keeps a block of
        runs' tables side by side, ``8 j`` for run ``j``).

    Returns
    -------
    float
        Force magnitude before the lateral scale, N.
    """
    # max(fz, 0) with NaN kept, and I an integer from floor (written so, not with max/int: compiled, those are
    # numba functions of their own, compiled on a first use; the same values, -0.0 and NaN included)
    fzp = 0.0 if fz < 0.0 else fz
    i = math.floor(s) if s < 8.0 else 7    # min(floor(s), 7); NaN -> 7 (t stays NaN: NaN force)
    t = s - i
    k = i + col
    return cubic(seg[0, k] + t * seg[3, k], seg[1, k] + t * seg[4, k], seg[2, k] + t * seg[5, k], fzp)


def lateral_force(kind, seg, scale, lim, slip, fz, policy, col=0):
    """Cornering force of one tire, N, and whether a ``"raise"`` policy refuses the input.

    Parameters
    ----------
    kind : int
        :data:`TESTED` (``seg``, ``scale``, ``lim`` used) or :data:`LINEAR`
        (``scale`` is the stiffness, N/deg).
    seg : ndarray, shape (6, 8)
        Segment table of a tested tire (:func:`segment_force`).
    scale : float
        Lateral scale (TYMOD/CYMOD) of a tested tire, or a linear tire's N/deg.
    lim : pair of float
        Fitted range of a tested tire: largest slip, deg, and normal load, N.
    slip : float
        Slip angle, deg (any sign).
    fz : float
        Normal force, N (``<= 0``: no force).
    policy : int
        Outside the fitted range: :data:`CLAMP` evaluates at its edge,
        :data:`EXTRAPOLATE` extends the 7-8 deg segment and the cubic in
        load, :data:`RAISE` flags the input as refused.
    col : int
        Column of segment 0 in ``seg`` (:func:`segment_force`).

    Returns
    -------
    force : float
        ``-sign(slip) F scale``, N (opposes the slip; never ``-0.0``).
    refused : bool
        True when ``policy`` is :data:`RAISE` and the input is outside the range.
    """
    if kind == LINEAR:
        return (-scale * slip + 0.0 if fz > 0.0 else 0.0), False
    s = abs(slip)
    f = fz
    out = s > lim[0] or f > lim[1]
    if out and policy == CLAMP:
        if s > lim[0]:
            s = lim[0]
        if f > lim[1]:
            f = lim[1]
    c = segment_force(seg, s, f, col) * scale
    return (-c if slip > 0.0 else c) + 0.0, out and policy == RAISE


def camber_force(coefficient, lateral):
    """Eq (4-2): the camber force ``-f_c F_y(alpha = gamma)``, N (toward the side the wheel leans).

    Parameters
    ----------
    coefficient : float
        Camber coefficient ``f_c`` [-].
    lateral : float or ndarray
        The tire's cornering force at a slip angle equal to the camber angle, N (:func:`lateral_force`).

    Returns
    -------
    float or ndarray
        N.
    """
    return -coefficient * lateral


def rolling_resistance(kind, coef, scale, fz):
    """Magnitude of the rolling-resistance force, N; zero where ``fz <= 0``.

    Parameters
    ----------
    kind : int
        :data:`ROLLING_OFF` (zero), :data:`ROLLING_CUBIC` (Appendix B:
        ``|cubic(coef, fz)|``, used as is above 450 N) or :data:`ROLLING_LINEAR`
        (eq 3-2: ``coef[0] fz``).
    coef : sequence of 3 float
        ``(a, b, c)`` of the cubic, or ``(f_r, -, -)``.
    scale : float
        Rolling scale (TXMOD/CXMOD).
    fz : float
        Normal force, N.

    Returns
    -------
    float
        N (>= 0).
    """
    if kind == ROLLING_OFF or not fz > 0.0:
        return 0.0 * fz if kind == ROLLING_OFF else 0.0
    if kind == ROLLING_CUBIC:
        return abs(cubic(coef[0], coef[1], coef[2], fz)) * scale
    return coef[0] * scale * fz


def rolling_force(kind, coef, scale, fz, vx):
    """Rolling-resistance force along the wheel's heading, N, opposing its rolling velocity ``vx`` (m/s).

    Parameters
    ----------
    kind, coef, scale, fz
        As in :func:`rolling_resistance`.
    vx : float
        Velocity of the contact point along the wheel's heading, m/s.

    Returns
    -------
    float
        N (``0.0 * fz`` when rolling resistance is off).
    """
    if kind == ROLLING_OFF:
        return 0.0 * fz
    return math.copysign(rolling_resistance(kind, coef, scale, fz), -vx)

