"""The sampled linear yaw-moment controller of the compiled WCHAIR kernel (numba), one sample at a time.

Called by :func:`stability.simulate.kernel.run_one` (see :mod:`stability.simulate.controller` for the
controller's arrays).  Its compiled code is flushed with the kernels' when any kernel source changes
(:mod:`stability.simulate.cache_stamp`).
"""

from __future__ import annotations

from typing import Any

from numba import njit

__all__ = ["controller_output"]

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
