"""Stick-slip caster-pin friction of the fixed-step scheme in Python: one run (floats) or a batch (arrays).

The law of the compiled kernel's ``stick_slip`` and of its rate update
(:mod:`.kernel`, ``friction_law="stick-slip"``), transcribed with the same
operations in the same order for :mod:`.wchair` (one run) and
:mod:`.reference` (a batch, where each run holds or frees its own casters:
masks select the per-run variant).  Program WCHAIR's kinetic law (the moment
``-M_f sign(rate)``) stays in those modules; see ``docs/simulator.md``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from stability.simulate.physics import Physics, accelerations, held_accelerations

__all__ = ["stick_slip", "stick_slip_runs", "rest_rate", "rest_rates"]

#: break-away decisions per step: each frees at least one caster, so two suffice; three as in the kernel
PASSES = 3


def stick_slip(K: Physics, state, F, fy_ext, mz, rdc=None, grav=None) -> tuple[tuple, float, float]:
    """Accelerations and pin moments of one run under stick-slip Coulomb pin friction.

    A swivelling caster (rate not zero) gets the kinetic moment against its
    rate, as in program WCHAIR.  A caster at rest (rate exactly 0.0) is held
    while its holding moment is within its friction limit (Karnopp's stick
    phase); otherwise it breaks away with the limit moment in the holding
    moment's direction, and the other caster's hold is decided again (up to
    three passes).

    Parameters
    ----------
    K : Physics
        Parameters of the run (floats); ``K.maf``, ``K.mbf``: the friction
        limits of casters A and B, N m.
    state, F, fy_ext, mz, rdc, grav
        As in :func:`~stability.simulate.physics.accelerations` (floats).

    Returns
    -------
    acc : tuple of 5 float
        ``(u_dot, v_dot, r_dot, eta_dd, beta_dd)``: m/s^2, m/s^2, rad/s^2,
        rad/s^2, rad/s^2 (a held caster's swivel acceleration is zero).
    M_A, M_B : float
        Pin moments, N m: kinetic, holding, or the limit at break-away.
    """
    maf, mbf = K.maf, K.mbf
    ed, bd = state[7], state[8]
    ma = math.copysign(maf, -ed) if ed != 0.0 else 0.0
    mb = math.copysign(mbf, -bd) if bd != 0.0 else 0.0
    ha, hb = ed == 0.0, bd == 0.0
    for _ in range(PASSES):
        if not (ha or hb):
            break
        acc, ra, rb = held_accelerations(K, state, F, ma, mb, fy_ext, mz, ha, hb, rdc, grav)
        free_a = ha and abs(ra) > maf
        free_b = hb and abs(rb) > mbf
        if not (free_a or free_b):
            return acc, ra, rb
        if free_a:
            ma, ha = math.copysign(maf, ra), False
        if free_b:
            mb, hb = math.copysign(mbf, rb), False
    return accelerations(K, state, F, ma, mb, fy_ext, mz, rdc, grav), ma, mb


def _held_runs(K: Physics, state, F, ma, mb, ha, hb, fy_ext, mz, rdc, grav) -> tuple[list, Any, Any]:
    """Each run's held variant (A and B, A alone or B alone) by its flags ``ha``, ``hb``: ``(acc, M_A, M_B)``.

    Only the variants some run needs are evaluated (on every run; the flags
    select).  A run with neither flag keeps its moments; its accelerations
    are then zero placeholders (not used).
    """
    acc = [np.zeros(ha.shape) for _ in range(5)]
    ra, rb = ma, mb
    for hold_a, hold_b, sel in ((True, True, ha & hb), (True, False, ha & ~hb), (False, True, hb & ~ha)):
        if sel.any():
            a, x, y = held_accelerations(K, state, F, ma, mb, fy_ext, mz, hold_a, hold_b, rdc, grav)
            acc = [np.where(sel, ai, ci) for ai, ci in zip(a, acc, strict=True)]
            ra, rb = np.where(sel, x, ra), np.where(sel, y, rb)
    return acc, ra, rb


def stick_slip_runs(K: Physics, state, F, fy_ext, mz, rdc=None, grav=None) -> tuple[tuple, Any, Any]:
    """:func:`stick_slip` over the runs of a batch (arrays): each run holds and frees its own casters.

    The same decisions as :func:`stick_slip`, run by run: a run whose held
    casters can all be held keeps that pass's held solution and drops out of
    the later passes; the runs still open after the passes (every candidate
    freed, or none at rest) take the plain accelerations with their moments.

    Parameters
    ----------
    K : Physics
        Parameters of the runs (``K.maf``, ``K.mbf``: float or array, N m).
    state, F, fy_ext, mz, rdc, grav
        As in :func:`~stability.simulate.physics.accelerations` (arrays over
        the runs, shape ``(n,)``).

    Returns
    -------
    acc : tuple of 5 ndarray
        ``(u_dot, v_dot, r_dot, eta_dd, beta_dd)`` per run, as in :func:`stick_slip`.
    M_A, M_B : ndarray
        Pin moments per run, N m.
    """
    maf, mbf = K.maf, K.mbf
    ed, bd = state[7], state[8]
    ma = np.where(ed != 0.0, np.copysign(maf, -ed), 0.0)
    mb = np.where(bd != 0.0, np.copysign(mbf, -bd), 0.0)
    ha, hb = ed == 0.0, bd == 0.0
    held = np.zeros(ed.shape, dtype=bool)          # runs decided: every candidate held, at that pass's solution
    h_acc, h_ma, h_mb = [np.zeros(ed.shape) for _ in range(5)], ma, mb
    for _ in range(PASSES):
        if not (ha | hb).any():
            break
        acc, ra, rb = _held_runs(K, state, F, ma, mb, ha, hb, fy_ext, mz, rdc, grav)
        free_a = ha & (np.abs(ra) > maf)
        free_b = hb & (np.abs(rb) > mbf)
        stay = (ha | hb) & ~(free_a | free_b)
        if stay.any():
            h_acc = [np.where(stay, a, h) for a, h in zip(acc, h_acc, strict=True)]
            h_ma, h_mb = np.where(stay, ra, h_ma), np.where(stay, rb, h_mb)
            held |= stay
            ha, hb = ha & ~stay, hb & ~stay
        ma, ha = np.where(free_a, np.copysign(maf, ra), ma), ha & ~free_a
        mb, hb = np.where(free_b, np.copysign(mbf, rb), mb), hb & ~free_b
    plain = accelerations(K, state, F, ma, mb, fy_ext, mz, rdc, grav)
    if not held.any():
        return plain, ma, mb
    return (tuple(np.where(held, h, p) for h, p in zip(h_acc, plain, strict=True)), np.where(held, h_ma, ma),
            np.where(held, h_mb, mb))


def rest_rate(rate: float, acc: float, dt: float, limit: float) -> float:
    """The swivel rate after a step: ``rate + acc dt``, or 0.0 (at rest) where it would change sign.

    A nonzero rate whose new value has the opposite sign or is zero
    (``new * old <= 0``) comes to rest when the caster has pin friction
    (``limit > 0``, N m); without friction it passes through zero as in
    program WCHAIR.

    Parameters
    ----------
    rate : float
        Swivel rate at the start of the step, rad/s.
    acc : float
        Swivel acceleration over the step, rad/s^2.
    dt : float
        Step, s.
    limit : float
        The caster's pin friction limit, N m.

    Returns
    -------
    float
        The new swivel rate, rad/s.
    """
    new = rate + acc * dt
    return 0.0 if limit > 0.0 and rate != 0.0 and new * rate <= 0.0 else new


def rest_rates(old: np.ndarray, new: np.ndarray, limit) -> None:
    """:func:`rest_rate` over runs, in place: ``new`` (already ``old + acc dt``) set to 0.0 where it rests.

    Parameters
    ----------
    old, new : ndarray
        Swivel rates of one caster before and after the step, rad/s, shape ``(n,)``.
    limit : float or ndarray
        The caster's pin friction limit per run, N m.
    """
    new[(limit > 0.0) & (old != 0.0) & (new * old <= 0.0)] = 0.0
