"""The layout kernel's linear algebra (numba, inlined into :func:`stability.simulate.layout_kernel.step_layouts`):
the normal loads of any layout and the accelerations under the pin laws.

The normal loads are :func:`stability.layout.statics.load_rule`'s (the lever rule, three contacts, compliance);
the accelerations solve the mass matrix of the generated equations with any set of held (locked or stuck) casters,
under WCHAIR's kinetic pin law or stick-slip (the thesis engine's pin-friction functions,
:mod:`stability.simulate.kernel_equations`).  Nothing here allocates: the step passes its scratch.
"""

from __future__ import annotations

import numpy as np

from stability.simulate.kernel_equations import _inl, _inl_py, break_away_moment, kinetic_pin_moment, pin_holds

__all__ = ["layout_loads"]

_LEVER, _THREE = 0, 1


@_inl
def _solve(A, b, n, x):
    """Solve the leading ``n x n`` system ``A x = b`` by Gaussian elimination with partial pivoting (``A``, ``b``
    overwritten)."""
    for c in range(n):
        p = c
        big = abs(A[c, c])
        for r in range(c + 1, n):
            if abs(A[r, c]) > big:
                big, p = abs(A[r, c]), r
        if p != c:
            for cc in range(n):
                A[c, cc], A[p, cc] = A[p, cc], A[c, cc]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, n):
            f = A[r, c] / A[c, c]
            if f != 0.0:
                for cc in range(c, n):
                    A[r, cc] -= f * A[c, cc]
                b[r] -= f * b[c]
    for c in range(n - 1, -1, -1):
        s = b[c]
        for cc in range(c + 1, n):
            s -= A[c, cc] * x[cc]
        x[c] = s / A[c, c]


@_inl
def _clear(A, b, x, sel):
    """Zero the leading 4 x 4 block of ``A`` and the first 4 entries of ``b``, ``x``, ``sel`` (fresh arrays)."""
    for r in range(4):
        b[r], x[r], sel[r] = 0.0, 0.0, 0
        for c in range(4):
            A[r, c] = 0.0


def layout_loads(mode: int, xs: np.ndarray, ys: np.ndarray, k: np.ndarray, line: np.ndarray, share: np.ndarray,
                 weight: float, h: float, sum_fx: float, sum_fy: float, out: np.ndarray) -> None:
    """Normal loads of the contacts (:func:`_layout_loads`, the kernel's, with scratch of its own): for Python
    callers (the layout's slope statics, the tests).

    Parameters
    ----------
    mode : int
        The load rule (:func:`stability.layout.statics.load_rule`).
    xs, ys : ndarray
        The contacts about the c.g., m.
    k, line, share : ndarray
        Per contact the vertical stiffness and support line; per line its share of the roll moment.
    weight : float
        N.
    h : float
        c.g. height, m.
    sum_fx, sum_fy : float
        The tire forces' resultant, N.
    out : ndarray
        Written: the loads, N.
    """
    _layout_loads(mode, xs, ys, k, line, share, weight, h, sum_fx, sum_fy, out, np.zeros((4, 4)), np.zeros(4),
                  np.zeros(4), np.zeros(4, dtype=np.int64))


@_inl_py
def _layout_loads(mode, xs, ys, k, line, share, weight, h, sum_fx, sum_fy, out, A, b, x, sel):
    """Normal loads of the contacts at ``(xs, ys)`` (m, about the c.g.) under the weight (N) and the tire forces'
    resultant ``(sum_fx, sum_fy)`` (N) at the ground ``h`` (m) below the c.g.: ``sum N = weight``,
    ``sum N x = -h sum_fx``, ``sum N y = -h sum_fy`` (:func:`stability.layout.statics.load_rule`).

    ``mode`` LEVER: two lines of two contacts (``line`` 0 or 1), each carrying ``share[line]`` of the roll moment;
    THREE: three contacts; COMPLIANT: ``N_i = k_i (z + theta x_i + phi y_i)``.  Contacts with ``k == 0`` carry
    nothing.  Written into ``out`` (N); ``A`` (at least 4 x 4), ``b``, ``x``, ``sel`` (int, each at least 4) are
    scratch, zeroed here."""
    n = xs.shape[0]
    pitch, roll = -h * sum_fx, -h * sum_fy
    for i in range(n):
        out[i] = 0.0
    # each rule's system in the leading m x m block, solved by one call (one inlined copy of the elimination)
    _clear(A, b, x, sel)
    b[0], b[1] = weight, pitch
    m = 0
    if mode == _LEVER:
        b[2], b[3] = share[0] * roll, share[1] * roll
        for i in range(n):
            if line[i] >= 0:
                sel[m] = i
                A[0, m] = 1.0
                A[1, m] = xs[i]
                A[2 + line[i], m] = ys[i]
                m += 1
        m = 4
    elif mode == _THREE:
        b[2] = roll
        for i in range(n):
            if k[i] != 0.0:
                sel[m] = i
                A[0, m], A[1, m], A[2, m] = 1.0, xs[i], ys[i]
                m += 1
        m = 3
    else:
        b[2] = roll
        for i in range(n):                               # sum_i k_i b_i b_i^T q = (weight, pitch, roll)
            bi = (1.0, xs[i], ys[i])
            for r in range(3):
                for c in range(3):
                    A[r, c] += k[i] * bi[r] * bi[c]
        m = 3
    _solve(A, b, np.int64(m), x)
    if mode == _LEVER or mode == _THREE:
        for j in range(m):
            out[sel[j]] = x[j]
        return
    for i in range(n):
        out[i] = k[i] * (x[0] + x[1] * xs[i] + x[2] * ys[i])


@_inl
def _accelerations(Mm, F0, nc, mom, held, W, w, acc, free, x):
    """Accelerations with the pin moments ``mom`` on the free casters and the ``held`` casters' swivel
    accelerations zero: the free rows of ``M acc = F0 + sum_k M_k e_(3+k)``; each held caster's moment (written
    into ``mom``) is then its own row's balance.  ``free`` (int) and ``x`` (``3 + nc`` each) are scratch."""
    n = 3 + nc
    m = 0
    for i in range(n):
        if i < 3 or not held[i - 3]:
            free[m] = i
            m += 1
    for a in range(m):
        w[a] = F0[free[a]] + (mom[free[a] - 3] if free[a] >= 3 else 0.0)
        for c in range(m):
            W[a, c] = Mm[free[a], free[c]]
    for i in range(n):
        x[i] = 0.0
    _solve(W, w, np.int64(m), x)
    for i in range(n):
        acc[i] = 0.0
    for a in range(m):
        acc[free[a]] = x[a]
    for kk in range(nc):
        if held[kk]:
            s = -F0[3 + kk]
            for c in range(n):
                s += Mm[3 + kk, c] * acc[c]
            mom[kk] = s


@_inl
def _stick_slip(Mm, F0, nc, dd, mf, cpin, mom, held, W, w, acc, free, x):
    """Stick-slip Coulomb pins (the thesis engine's ``stick_slip`` for any number of casters): a swivelling caster
    gets the kinetic moment (plus its viscous part), a caster at rest is held while its holding moment is within
    its friction limit, else it breaks away with the limit moment in the holding moment's direction; decided again
    after each release (a held caster's moment changes the others')."""
    for kk in range(nc):
        mom[kk] = kinetic_pin_moment(dd[kk], mf[kk]) - cpin[kk] * dd[kk]
        held[kk] = dd[kk] == 0.0
    for it in range(nc + 2):      # one call of _accelerations (one inlined copy of the solve)
        anyheld = False
        for kk in range(nc):
            if it > nc:           # decided nc + 1 times: every caster free
                held[kk] = False
            anyheld = anyheld or held[kk]
        _accelerations(Mm, F0, nc, mom, held, W, w, acc, free, x)
        if not anyheld:
            return
        released = False
        for kk in range(nc):
            if held[kk] and not pin_holds(mom[kk], mf[kk]):
                mom[kk] = break_away_moment(mom[kk], mf[kk])
                held[kk] = False
                released = True
        if not released:
            return


@_inl
def _pins(pin_mode, Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc, free, x):
    """Accelerations under the pin law: 1 every caster held (locked), 2 stick-slip, 0 WCHAIR's kinetic law (each
    with the viscous part ``-c_pin rate``); ``free``, ``x``: :func:`_accelerations`' scratch."""
    if pin_mode == 2:
        _stick_slip(Mm, F0, nc, DD, mf, cpin, mom, held, W, w, acc, free, x)
        return
    for kk in range(nc):          # one call of _accelerations for both laws: one inlined copy of the solve
        if pin_mode == 1:
            held[kk] = True
        else:
            mom[kk] = kinetic_pin_moment(DD[kk], mf[kk]) - cpin[kk] * DD[kk]
            held[kk] = False
    _accelerations(Mm, F0, nc, mom, held, W, w, acc, free, x)
