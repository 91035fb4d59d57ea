"""Names for the modes of a speed locus, from their eigenvectors (the rule is in docs/report.md).

Each eigenvector is made dimensionless as angles, as in
``derivations/compare_variants.py``: chair sideslip ``v/U``, chair yaw
``r s/U`` (``s`` the distance from the main axle to the caster contacts),
casters in phase ``(eta + beta)/2`` and anti-phase ``(eta - beta)/2``.  A
mode is named after its largest share, plus the second when that exceeds
20 %; modes with the same name are told apart by speed of decay ("slow",
"fast").
"""

from __future__ import annotations

from typing import Any

import numpy as np

from stability.linear import state_matrices
from stability.settings.reference import REFERENCE_SPEED

__all__ = ["mode_names", "mode_shares", "shape_arm", "SECOND_SHARE"]

#: A second component is named when its share exceeds this fraction.
SECOND_SHARE = 0.2


def mode_shares(vector: np.ndarray, speed: float, arm: float) -> dict[str, float]:
    """Shares (summing to 1) of a mode's eigenvector in sideslip, yaw and the two caster motions.

    Parameters
    ----------
    vector : ndarray of complex
        Eigenvector over the states ``(v, r)`` (locked casters) or
        ``(v, r, eta, eta_dot, beta, beta_dot)`` (free casters).
    speed : float
        Forward speed U, m/s.
    arm : float
        Distance from the main axle to the caster contacts, m.

    Returns
    -------
    dict
        ``"sideslip"``, ``"yaw"`` and, with free casters, ``"casters in phase"``,
        ``"casters opposed"``: squared magnitudes of the angle-like components, normalised.
    """
    parts = {"sideslip": abs(vector[0] / speed) ** 2, "yaw": abs(vector[1] * arm / speed) ** 2}
    if len(vector) >= 6:
        parts["casters in phase"] = abs((vector[2] + vector[4]) / 2) ** 2
        parts["casters opposed"] = abs((vector[2] - vector[4]) / 2) ** 2
    tot = sum(parts.values()) or 1.0
    return {k: float(v / tot) for k, v in parts.items()}


def shape_arm(chair: Any) -> float:
    """The length that makes the yaw rate an angle in :func:`mode_shares` (``r s/U``), m.

    Parameters
    ----------
    chair : Chair

    Returns
    -------
    float
        The wheelbase, main axle to caster contacts with the casters trailing
        (:attr:`stability.chair.Chair.wheelbase`): ``s1 + s2 + trail`` for rear
        casters (the contacts trail away from the axle), ``s1 + s2 - trail`` for
        front casters (eq 6-24's contacts lie ``trail`` behind the pins).
    """
    return float(chair.wheelbase)


def _label(shares: dict[str, float]) -> str:
    top = sorted(shares.items(), key=lambda kv: -kv[1])
    lab = top[0][0]
    if len(top) > 1 and top[1][1] > SECOND_SHARE:
        lab += " + " + top[1][0]
    return lab


def mode_names(locus: Any, speed: float = REFERENCE_SPEED) -> tuple[str, ...]:
    """A name for each branch of a speed locus, from its eigenvector at ``speed``.

    Parameters
    ----------
    locus : stability.rootlocus.SpeedLocus
    speed : float
        Speed at which the modes are named, m/s (the nearest speed of the locus).

    Returns
    -------
    tuple of str
        One name per column of ``locus.eigenvalues``; the two members of a
        complex pair get the same name; "(slow)"/"(fast)" (or "1", "2", ...)
        tell apart distinct modes of the same kind, by ``|Re|``.
    """
    U = np.asarray(locus.speeds)
    k = int(np.argmin(np.abs(U - speed)))
    u = float(U[k])
    eig = np.asarray(locus.eigenvalues)[k]
    n = eig.shape[0]
    a = np.asarray(state_matrices(locus.chair, u, locus.model, locus.casters), dtype=float).reshape(n, n)
    w, v = np.linalg.eig(a)
    arm = shape_arm(locus.chair)
    base = []
    for lam in eig:
        i = int(np.argmin(np.abs(w - lam)))
        base.append(_label(mode_shares(v[:, i], u, arm)))
    # distinct modes (a complex pair counts once) sharing a name: order by |Re| at this speed
    names = list(base)
    for name in set(base):
        idx = [j for j in range(n) if base[j] == name]
        groups: list[list[int]] = []
        for j in sorted(idx, key=lambda j: (abs(eig[j].real), abs(eig[j].imag))):
            pair = next((g for g in groups if abs(eig[g[0]] - np.conj(eig[j])) < 1e-9 * max(1.0, abs(eig[j]))
                         and abs(eig[j].imag) > 0), None)
            if pair is not None:
                pair.append(j)
            else:
                groups.append([j])
        if len(groups) > 1:
            tags = ["slow", "fast"] if len(groups) == 2 else [str(m + 1) for m in range(len(groups))]
            for tag, g in zip(tags, groups, strict=True):
                for j in g:
                    names[j] = f"{name} ({tag})"
        if any(abs(eig[j].imag) > 0 for j in idx):
            for j in idx:
                if abs(eig[j].imag) > 0 and "oscillatory" not in names[j]:
                    names[j] += ", oscillatory"
    return tuple(names)
