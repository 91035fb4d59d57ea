"""The sampled linear yaw-moment controller of the compiled WCHAIR kernel (numba), one sample at a time.

Called by :func:`stability.simulate.kernel.run_one` through :func:`controller_step` (compiled only for a run with
a controller; see :mod:`stability.simulate.controller` for the controller's arrays).  Its compiled code is
flushed with the kernels' when any kernel source changes (:mod:`stability.simulate.cache_stamp`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numba import njit
from numba.core import types as _nbtypes
from numba.extending import overload

from stability.simulate.kernel_equations import _OVERLOAD, _inl

__all__ = ["controller_output", "controlled", "controller_step", "scratch_columns"]

_NOWRAP: dict[str, Any] = dict(no_cpython_wrapper=True, no_cfunc_wrapper=True)   # as the kernel's helpers


# compiled when a run with a controller first calls it (no explicit signature: that compiled it at import, for
# every first use); its callers pass a run-time sample index (a literal one would compile it a second time)
@njit(cache=True, nogil=True, **_NOWRAP)
def controller_output(k, z, znew, y, s, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    """Sample ``k`` of the linear sampled controller: measure, output, advance ``z`` (see controller.py)."""
    ny = Cy.shape[0]
    nz = Az.shape[0]
    for i in range(ny):
        acc = ctl_f[2 + i] if 2 + i < ctl_f.shape[0] else 0.0
        for j in range(Cy.shape[1]):       # the state's length: 10 (the thesis engine), 6 + 2 K (a layout)
            acc += Cy[i, j] * s[j]
        if k < noise.shape[0]:
            acc += noise[k, i]
        y[i] = acc
    out = 0.0
    for i in range(nz):
        out += Cz[i] * z[i]
    for i in range(ny):
        out += Dy[i] * y[i]
    lim = ctl_f[1]
    if out > lim:
        out = lim
    elif out < -lim:
        out = -lim
    for i in range(nz):
        acc = Bu[i] * out
        for j in range(nz):
            acc += Az[i, j] * z[j]
        for j in range(ny):
            acc += By[i, j] * y[j]
        znew[i] = acc
    for i in range(nz):
        z[i] = znew[i]
    return out


@_inl
def controlled(t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    """The sampled controller at ``t``: ``(yaw moment, next sample)`` after the samples ``next_k`` .. up to ``t`` are
    taken (``z`` advanced); the last one's output is held (``held`` when no sample falls due)."""
    ks = int(math.floor(t / ctl_f[0] + 1e-9))
    while next_k <= ks:
        for c in range(10):
            sv[c] = states[c]
        held = controller_output(next_k, z, znew, y, sv, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
        next_k += 1
    return held, next_k


def controller_step(ctl, t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    """:func:`controlled` where the variant has a controller, else nothing; compiled code only (numba overload).

    Parameters
    ----------
    ctl : int
        1 with a controller (a numba literal: 0 compiles none of the controller's code).
    t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise
        As :func:`controlled`'s (t in s, held in N m).

    Returns
    -------
    tuple
        ``(yaw moment N m, next sample)``; ``(held, next_k)`` without a controller.
    """
    raise NotImplementedError("compiled code only (numba overload)")


def scratch_columns(ctl_f: np.ndarray, Az: np.ndarray, Cy: np.ndarray) -> int:
    """The columns of a run's kernel state after the controller's states that hold its scratch.

    :func:`stability.simulate.kernel.run_one` takes the arrays :func:`controlled` writes as views of them, in this
    order, rather than having them allocated: the step keeps no reference counts
    (:data:`~stability.simulate.kernel_equations._NOREF`), so an array allocated for it would never be freed.

    Parameters
    ----------
    ctl_f, Az, Cy : ndarray
        The controller's arrays (:meth:`SampledController.arrays`; sample time first, 0 for none).

    Returns
    -------
    int
        ``nz`` next states, ``ny`` measurements and the ten states with a controller, else 0.
    """
    return Az.shape[0] + Cy.shape[0] + 10 if ctl_f[0] > 0.0 else 0


@overload(controller_step, **_OVERLOAD)
def _controller_step(ctl, t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
    if isinstance(ctl, _nbtypes.IntegerLiteral) and ctl.literal_value == 0:
        def none(ctl, t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
            return held, next_k
        return none

    def impl(ctl, t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise):
        return controlled(t, next_k, held, z, znew, y, sv, states, ctl_f, Cy, Dy, Az, Bu, By, Cz, noise)
    return impl
