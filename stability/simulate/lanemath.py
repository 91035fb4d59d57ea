"""Branch-free sine, cosine and two-argument arctangent for the lanes kernel (numba), with their error bounds.

pip's numba has no SVML, so a call of libm's ``sin``/``cos``/``atan2`` in a
loop over runs keeps LLVM from vectorising that loop.  These are the same
functions written as range reduction, a polynomial and selects, which LLVM
inlines and vectorises.  The polynomials are fdlibm's (``k_sin.c``,
``k_cos.c``, ``s_atan.c``; Sun Microsystems, freely redistributable), whose
truncation errors are below 2^-58 relative on their intervals.

Error bounds (stated, and tested against numpy in ``tests/test_lanemath.py``
over the ranges the kernel uses):

* :func:`sin_cos` for ``|x| <= REDUCTION_LIMIT`` (2^19 pi/2, about 8.2e5 rad):
  within :data:`SIN_COS_ULP` units in the last place of the exact value, plus
  an absolute :data:`SIN_COS_ABS` near the zeros of ``sin`` and ``cos`` away
  from 0 (the Cody-Waite reduction with 3 x 33 bits of pi/2 leaves the
  reduced argument an absolute error below 2^-53 |r| + 2^-100 |n|).
  ``sin(0) = 0`` and ``cos(0) = 1`` exactly, and ``sin`` is odd, ``cos``
  even, exactly (the reduction rounds ``|x| 2/pi`` and restores the sign).
* :func:`atan2_pos` (``atan2(y, x)`` for ``x >= 0``, what the slip angle takes:
  ``atan2(vy, |vx|)``) within :data:`ATAN2_ULP` ulp; ``atan2(0, x) = 0`` and
  ``atan2(-y, x) = -atan2(y, x)`` exactly; ``atan2(0, 0) = 0`` as libm.

Non-finite inputs give NaN (libm gives finite values for some infinite
inputs); a run whose state leaves the finite numbers stops either way.
"""

from __future__ import annotations

import math
import types
from typing import Any

from numba import njit

from stability.simulate.kernel_link import AVAILABLE, LinkOnlyCompiler

__all__ = ["sin_cos", "sin", "cos", "atan2_pos", "atan2", "LANE_MATH", "SIN_COS_ULP", "SIN_COS_ABS", "ATAN2_ULP",
           "REDUCTION_LIMIT"]

#: stated bound of :func:`sin_cos`, units in the last place of the result (polynomial 2^-58, reduction 1 ulp of
#: ``r``, the polynomial's own roundings about 1 ulp)
SIN_COS_ULP = 2.0
#: absolute part of the bound of :func:`sin_cos` (the reduction's pi/2 to 99 bits, times ``|n| <= 2^19``)
SIN_COS_ABS = 2.0 ** -80
#: stated bound of :func:`atan2_pos`, ulp (the reduced argument's one division and one addition 1 ulp, the
#: polynomial 2^-58 and its roundings about 1 ulp, the final additions 0.5 ulp each)
ATAN2_ULP = 3.0
#: largest ``|x|`` (rad) for which the reduction of :func:`sin_cos` keeps its bound: ``n pi/2`` with ``|n| < 2^19``
REDUCTION_LIMIT = 2.0 ** 19 * math.pi / 2

_NOWRAP: dict[str, Any] = dict(no_cpython_wrapper=True, no_cfunc_wrapper=True)   # options numba's stubs omit
#: compiled for linking into the lanes kernel only (:mod:`stability.simulate.kernel_link`: no machine code of its own)
_LINK: dict[str, Any] = dict(pipeline_class=LinkOnlyCompiler) if AVAILABLE else {}
_lane = njit(cache=False, nogil=True, forceinline=True, error_model="numpy", **_NOWRAP, **_LINK)

# pi/2 in three 33-bit parts (fdlibm e_rem_pio2.c: pio2_1, pio2_2, pio2_3); n * part is exact for |n| < 2^20
_PIO2_1 = 1.57079632673412561417e+00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
_TWO_OVER_PI = 6.36619772367581382433e-01
_S1, _S2, _S3 = -1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04
_S4, _S5, _S6 = 2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10
_C1, _C2, _C3 = 4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05
_C4, _C5, _C6 = -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11
_AT = (3.33333333333329318027e-01, -1.99999999998764832476e-01, 1.42857142725034663711e-01,
       -1.11111104054623557880e-01, 9.09088713343650656196e-02, -7.69187620504482999495e-02,
       6.66107313738753120669e-02, -5.83357013379057348645e-02, 4.97687799461593236017e-02,
       -3.65315727442169155270e-02, 1.62858201153657823623e-02)
_AT0, _AT1, _AT2, _AT3, _AT4, _AT5, _AT6, _AT7, _AT8, _AT9, _AT10 = _AT
_ATAN_HALF_HI, _ATAN_HALF_LO = 4.63647609000806093515e-01, 2.26987774529616870924e-17   # atan(1/2)
_PIO4_HI, _PIO4_LO = 7.85398163397448278999e-01, 3.06161699786838301793e-17
_PIO2_HI, _PIO2_LO = 1.57079632679489655800e+00, 6.12323399573676603587e-17


@_lane
def sin_cos(x):
    """``(sin x, cos x)`` by Cody-Waite reduction modulo pi/2 and fdlibm's kernels; see the module's bounds.

    Parameters
    ----------
    x : float
        Angle, rad (``|x| <= REDUCTION_LIMIT`` for the stated bound).

    Returns
    -------
    tuple of float
        ``sin x``, ``cos x``.
    """
    ax = abs(x)
    n = math.floor(ax * _TWO_OVER_PI + 0.5)
    r = ((ax - n * _PIO2_1) - n * _PIO2_2) - n * _PIO2_3
    z = r * r
    s = r + (z * r) * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    c = w + (((1.0 - w) - hz) + z * (z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))))
    q = int(n) & 3
    a = c if (q & 1) != 0 else s
    b = s if (q & 1) != 0 else c
    sa = -a if (q & 2) != 0 else a
    cb = -b if ((q + 1) & 2) != 0 else b
    return (-sa if x < 0.0 else sa), cb


@_lane
def sin(x):
    """``sin x`` (:func:`sin_cos`), rad."""
    return sin_cos(x)[0]


@_lane
def cos(x):
    """``cos x`` (:func:`sin_cos`), rad."""
    return sin_cos(x)[1]


@_lane
def atan2_pos(y, x):
    """``atan2(y, x)`` for ``x >= 0`` (rad, in [-pi/2, pi/2]): fdlibm's atan on ``min/max`` of ``|y|, x``.

    Parameters
    ----------
    y : float
    x : float
        ``>= 0`` (the slip angle's ``|vx|``).

    Returns
    -------
    float
        rad.
    """
    ay = abs(y)
    p = min(ay, x)
    q = max(ay, x)
    mid = p > 0.4375 * q                                   # a = p/q in [7/16, 11/16): about atan(1/2)
    top = p > 0.6875 * q                                   # a in [11/16, 1]: about atan(1)
    # one division (LLVM's vector division is the slow part): u = a, (2a - 1)/(2 + a) or (a - 1)/(a + 1) as
    # (2p - q)/(2q + p) and (p - q)/(p + q), whose numerators are exact (Sterbenz) in their intervals
    num = (p - q) if top else ((2.0 * p - q) if mid else p)
    den = (p + q) if top else ((2.0 * q + p) if mid else (q if q > 0.0 else 1.0))
    u = num / den
    hi = _PIO4_HI if top else (_ATAN_HALF_HI if mid else 0.0)
    lo = _PIO4_LO if top else (_ATAN_HALF_LO if mid else 0.0)
    z = u * u
    w = z * z
    s1 = z * (_AT0 + w * (_AT2 + w * (_AT4 + w * (_AT6 + w * (_AT8 + w * _AT10)))))
    s2 = w * (_AT1 + w * (_AT3 + w * (_AT5 + w * (_AT7 + w * _AT9))))
    t = hi - ((u * (s1 + s2) - lo) - u)
    r = _PIO2_HI - (t - _PIO2_LO) if ay > x else t
    return -r if y < 0.0 else r


@_lane
def atan2(y, x):
    """``atan2(y, x)`` for ``x >= 0`` only (:func:`atan2_pos`): the one use the generated physics makes of it."""
    return atan2_pos(y, x)


def _lane_math() -> types.ModuleType:
    """A stand-in for :mod:`math` in which ``sin``, ``cos`` and ``atan2`` are this module's (the rest is math's)."""
    mod = types.ModuleType("stability.simulate.lanemath.LANE_MATH")
    for name in dir(math):
        if not name.startswith("_"):
            setattr(mod, name, getattr(math, name))
    for name, f in (("sin", sin), ("cos", cos), ("atan2", atan2)):
        setattr(mod, name, f)
    return mod


#: :mod:`math` with the lane functions: the namespace in which the lanes kernel compiles the generated physics
LANE_MATH = _lane_math()
