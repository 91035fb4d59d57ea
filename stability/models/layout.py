"""The equations of any wheel layout: the door to :mod:`stability._generated.layout` (linear) and
:mod:`stability._generated.layout_nonlinear`.

``derivations/layout.py`` derives the planar equations of a body with ``J`` fixed wheels and ``K`` casters by
Kane's method, linearises them about straight running forward (casters trailing at 0) and in reverse (at pi), and
generates one function per shape and direction; this module evaluates them for a batch of speeds.  It also
generates the nonlinear equations (mass matrix, forcing without the pin moments, contact velocities) per shape,
which the layout simulator (:mod:`stability.simulate.layout_kernel`) compiles as they are
(:data:`nonlinear`).
"""

from __future__ import annotations

import numpy as np

from stability._generated import layout as _g
from stability._generated import layout_nonlinear as _gn

__all__ = ["supported_shapes", "linear_layout_matrices", "nonlinear", "shape_index"]

#: The generated nonlinear module itself (what the layout simulator compiles): ``equations(shape, ...)`` writes
#: ``M`` and ``F0`` (``M acc = F0 + sum_k M_k e_(3+k)``), ``contact_velocities(shape, ...)`` the contacts'
#: velocities in their wheels' frames; ``shape`` is the index in ``SHAPES``.
nonlinear = _gn


def shape_index(shape: tuple[int, int]) -> int:
    """Index of a ``(fixed wheels, casters)`` shape in the generated nonlinear module's ``SHAPES``.

    Parameters
    ----------
    shape : (int, int)

    Returns
    -------
    int

    Raises
    ------
    ValueError
        A shape that is not generated.
    """
    shapes = tuple(tuple(s) for s in _gn.SHAPES)
    if tuple(shape) not in shapes:
        raise ValueError(f"shape={tuple(shape)!r} is not generated; valid shapes: {shapes} (add one to "
                         "derivations/layout.py SHAPES)")
    return shapes.index(tuple(shape))


def supported_shapes() -> tuple[tuple[int, int], ...]:
    """The generated ``(fixed wheels, casters)`` shapes.

    Returns
    -------
    tuple of (int, int)
    """
    return tuple(tuple(s) for s in _g.SHAPES)  # type: ignore[misc]


def linear_layout_matrices(shape: tuple[int, int], reverse: bool, speeds: np.ndarray,
                           args: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``M, K, Bm, Bf`` of the layout's linear model at each speed.

    Parameters
    ----------
    shape : (int, int)
        Fixed wheels, casters.
    reverse : bool
        Linearised about reverse running (the speeds negative).
    speeds : ndarray
        m/s.
    args : tuple of float
        ``m, i_z``, per fixed wheel ``x_w, y_w, C_w, ca_w, sa_w`` (the cosine and sine of the wheel's
        angle), per caster ``x_p, trail, l, m_c, i_zp, C_c, c_pin`` (SI).

    Returns
    -------
    (M, K, Bm, Bf)
        Shapes ``(S, n, n)``, ``(S, n, 2 n)``... with ``n = 2 + K``: ``M acc = K x + Bm Mz + Bf Fy``.
    """
    fn = getattr(_g, f"linear_{shape[0]}w{shape[1]}c_{'reverse' if reverse else 'forward'}")
    U = np.asarray(speeds, dtype=float)
    M, K, Bm, Bf = fn(U, *args)
    n = len(M)

    def full(rows, cols: int) -> np.ndarray:
        out = np.empty((len(U), len(rows), cols))
        for i, row in enumerate(rows):
            for j, x in enumerate(row):
                out[:, i, j] = x
        return out

    return full(M, n), full(K, len(K[0])), np.stack([np.broadcast_to(np.asarray(x, float), U.shape) for x in Bm],
                                                    axis=-1), \
        np.stack([np.broadcast_to(np.asarray(x, float), U.shape) for x in Bf], axis=-1)
