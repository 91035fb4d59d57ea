"""Stability limit of WCHAIR's fixed step, from the linear model's eigenvalues at the run's speed.

WCHAIR's update (``v += a dt``, ``x += v dt + a dt^2/2`` with ``a`` from the
start of the step) advances the velocities by forward Euler.  A decaying
mode ``lambda`` (Re < 0) is reproduced only if ``|1 + dt lambda| <= 1``,
i.e. ``dt <= -2 Re(lambda) / |lambda|^2`` (``2/|lambda|`` for a real one);
the stiff caster modes (``~ -C l^2 / (U I_zp)``, thousands of 1/s at walking
speed) set the limit.  Derivation and checks in ``docs/simulator.md``.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from collections.abc import Sequence

import numpy as np

from stability.chair import Chair
from stability.linear import state_matrices
from stability.simulate.options import WCHAIR_DT

__all__ = ["SAFETY", "CACHE_SIZE", "stable_steps", "step_limits_and_growth", "auto_step", "StepStabilityWarning"]

#: Fraction of the limit that ``dt="auto"`` uses.
SAFETY = 0.8
#: (chair, speed, model, casters) pairs whose limit and growth rate are kept (least recently used dropped): a
#: single run's eigen-decomposition cost about as much as its 10 s of simulation, and the searches, the explorer
#: and repeated runs ask for the same pairs again
CACHE_SIZE = 8192
_CACHE: OrderedDict[tuple[Chair, float, str, str], tuple[float, float]] = OrderedDict()
_CACHE_LOCK = threading.Lock()


class StepStabilityWarning(UserWarning):
    """A fixed step outside the scheme's stability limit: the run may be a numerical artefact."""


def stable_steps(chairs: Sequence[Chair], speeds: np.ndarray, model: str, casters: str) -> np.ndarray:
    """Largest stable fixed step of each (chair, speed) pair: ``min -2 Re(lambda)/|lambda|^2`` over Re < 0.

    Parameters
    ----------
    chairs, speeds, model, casters
        As in :func:`step_limits_and_growth`.

    Returns
    -------
    ndarray
        Seconds; ``inf`` where no mode decays.
    """
    return step_limits_and_growth(chairs, speeds, model, casters)[0]


def step_limits_and_growth(chairs: Sequence[Chair], speeds: np.ndarray, model: str,
                           casters: str) -> tuple[np.ndarray, np.ndarray]:
    """:func:`stable_steps` and the largest growth rate ``max Re(lambda)`` (1/s), from one eigen-decomposition.

    The growth rate is the linear model's (pins frictionless): the rate at
    which a response large against the pin friction grows
    (:func:`stability.study.search.bracket_search` starts its fit from it).

    Parameters
    ----------
    chairs : sequence of Chair
        One per run.
    speeds : ndarray
        Forward speeds, m/s (> 0), one per run.
    model, casters : str
        Equation variant and caster state of the runs.

    Returns
    -------
    limits : ndarray
        s; ``inf`` where no mode decays.
    growth : ndarray
        1/s; negative where every mode decays.
    """
    speeds = np.abs(np.asarray(speeds, dtype=float))
    out = np.empty(len(speeds))
    growth = np.empty(len(speeds))
    missing: dict[Chair, list[int]] = {}
    with _CACHE_LOCK:
        for i, (c, u) in enumerate(zip(chairs, speeds.tolist(), strict=True)):
            hit = _CACHE.get((c, u, model, casters))
            if hit is None:
                missing.setdefault(c, []).append(i)
            else:
                out[i], growth[i] = hit
                _CACHE.move_to_end((c, u, model, casters))
    for c, idx in missing.items():     # one chair's parameters built once, all its speeds in one batched call
        u, inverse = np.unique(speeds[idx], return_inverse=True)
        lam = np.linalg.eigvals(state_matrices(c, u, model=model, casters=casters))
        with np.errstate(divide="ignore", invalid="ignore"):
            lim = np.where(lam.real < 0, -2.0 * lam.real / np.abs(lam) ** 2, np.inf)
        lim_u, growth_u = lim.min(axis=-1), lam.real.max(axis=-1)
        out[idx] = lim_u[inverse.reshape(-1)]
        growth[idx] = growth_u[inverse.reshape(-1)]
        with _CACHE_LOCK:
            for uj, lj, gj in zip(u.tolist(), lim_u.tolist(), growth_u.tolist(), strict=True):
                _CACHE[(c, uj, model, casters)] = (lj, gj)
            while len(_CACHE) > CACHE_SIZE:
                _CACHE.popitem(last=False)
    return out, growth


def auto_step(limit: float) -> float:
    """The step ``dt="auto"`` picks.

    Parameters
    ----------
    limit : float
        Largest stable fixed step, s (``inf`` when no mode decays).

    Returns
    -------
    float
        Program WCHAIR's 1 ms (:data:`WCHAIR_DT`) when ``SAFETY * limit`` is
        at least that or ``limit`` is not finite, else ``1 ms / k`` with the
        smallest whole ``k`` for which ``dt <= SAFETY * limit``, s.
    """
    if not math.isfinite(limit) or limit * SAFETY >= WCHAIR_DT:
        return WCHAIR_DT
    return WCHAIR_DT / math.ceil(WCHAIR_DT / (SAFETY * limit))
