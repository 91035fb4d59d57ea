"""Linear stability analysis: state-space models, eigenvalues vs speed, critical speeds.

The linear models come from the symbolic linearisation in
``derivations/full_width.py`` (generated into :mod:`stability._generated`):
straight-line motion at forward speed ``U`` with the casters trailing, each
tire's lateral force linear in its slip angle with the cornering stiffness of
its fit at its static normal load (Table 4-1 method), and viscous pin damping
``Chair.pin_damping`` (Coulomb friction has no linearisation; the default 0
models frictionless pins).  Lateral load transfer has no first-order effect
(``dFy/dFz = 0`` at zero slip; see ``derivations/README.md``).

States (free casters) ``[v, r, eta, eta_dot, beta, beta_dot]``: lateral
velocity of the c.g. (m/s), yaw rate (rad/s, positive clockwise from above),
left and right caster angles (rad) and rates (rad/s).  Locked casters:
``[v, r]``.  Input: a yaw moment on the chair (N m).  Outputs: ``v``, ``r``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from .chair import Chair
from .models import linear_matrices
from .models import zero_width as zw
from .params import parameters
from .statics import static_loads, static_stiffness

__all__ = [
    "STATES_FREE",
    "STATES_LOCKED",
    "state_matrices",
    "input_matrices",
    "state_space",
    "eigenvalues_vs_speed",
    "track_modes",
    "Crossing",
    "critical_speeds",
    "max_real_part",
    "zero_width",
    "ZeroWidthResult",
    "divergence",
    "massless_caster_rate",
    "StabilitySummary",
    "analyse",
]

STATES_FREE = ("v", "r", "eta", "eta_dot", "beta", "beta_dot")
STATES_LOCKED = ("v", "r")


def _stiffness_for(chairs: Chair | Sequence[Chair]):
    if isinstance(chairs, Chair):
        return static_stiffness(chairs)
    rows = [static_stiffness(c) for c in chairs]
    return {k: np.array([r[k] for r in rows]) for k in ("A", "B", "D", "E")}


def _assemble(M: np.ndarray, K: np.ndarray, Bm: np.ndarray, casters: str):
    """State and input matrices from ``M acc = K x + Bm u``."""
    sol = np.linalg.solve(M, np.concatenate([K, Bm[..., None]], axis=-1))
    F, G = sol[..., :-1], sol[..., -1]
    shape = M.shape[:-2]
    if casters == "locked":
        return F, G[..., None]
    n = 6
    A = np.zeros(shape + (n, n))
    B = np.zeros(shape + (n, 1))
    A[..., 0, :] = F[..., 0, :]
    A[..., 1, :] = F[..., 1, :]
    A[..., 2, 3] = 1.0
    A[..., 3, :] = F[..., 2, :]
    A[..., 4, 5] = 1.0
    A[..., 5, :] = F[..., 3, :]
    B[..., 0, 0], B[..., 1, 0], B[..., 3, 0], B[..., 5, 0] = G[..., 0], G[..., 1], G[..., 2], G[..., 3]
    return A, B


def _matrices(chairs, speeds, model: str, casters: str):
    p = parameters(chairs)
    M, K, Bm = linear_matrices(p, speeds, _stiffness_for(chairs), variant=model, casters=casters)
    return _assemble(M, K, Bm, casters)


def state_matrices(chair: Chair | Sequence[Chair], speeds, model: str = "exact",
                   casters: str = "free") -> np.ndarray:
    """State matrices for many speeds (and chairs) in one batched call.

    Parameters
    ----------
    chair : Chair or sequence of Chair
        One chair, or N chairs (then ``speeds`` broadcasts against them).
    speeds : float or array_like
        Forward speeds U > 0 (m/s).
    model : {"exact", "thesis"}
        Equation variant (see :mod:`stability.models`).
    casters : {"free", "locked"}
        Free (6 states) or locked (2 states) casters.

    Returns
    -------
    ndarray
        Shape (N, n, n) with n = 6 (free) or 2 (locked).
    """
    return _matrices(chair, speeds, model, casters)[0]


def input_matrices(chair, speeds, model: str = "exact", casters: str = "free") -> np.ndarray:
    """Input matrices (N, n, 1) for the yaw-moment input (1/(kg m^2) on the yaw-rate row)."""
    return _matrices(chair, speeds, model, casters)[1]


def state_space(chair: Chair, speed: float, model: str = "exact", casters: str = "free"):
    """Linearised model at one speed as a :class:`control.StateSpace`.

    States ``[v, r, eta, eta_dot, beta, beta_dot]`` (free casters) or
    ``[v, r]`` (locked), input ``Mz`` (yaw moment on the chair, N m),
    outputs ``v`` (m/s) and ``r`` (rad/s).
    """
    import control

    speed = float(speed)
    A, B = _matrices(chair, speed, model, casters)
    A, B = A[0], B[0]
    states = list(STATES_FREE if casters == "free" else STATES_LOCKED)
    C = np.zeros((2, len(states)))
    C[0, 0] = C[1, 1] = 1.0
    D = np.zeros((2, 1))
    # python-control forbids '.' in system names
    name = f"{chair.name} ({model}, {casters} casters, U={speed:g} m per s)".replace(".", "p")
    return control.ss(A, B, C, D, states=states, inputs=["Mz"], outputs=["v", "r"], name=name)


# ---------------------------------------------------------------------------
# eigenvalues and mode tracking
# ---------------------------------------------------------------------------
def track_modes(eigs: np.ndarray) -> np.ndarray:
    """Reorder eigenvalues along the first axis so each column is one mode.

    Consecutive rows are matched by minimum total distance (an assignment
    problem, solved exactly with :func:`scipy.optimize.linear_sum_assignment`
    wherever the cheap nearest-neighbour match is not a permutation).  Rows
    are matched independently and the permutations composed, so the work is
    vectorised over rows; zero and repeated eigenvalues cause no special
    trouble because matching never divides by a gap.

    Parameters
    ----------
    eigs : ndarray, shape (N, n)
        Eigenvalues in arbitrary order per row.

    Returns
    -------
    ndarray, shape (N, n)
    """
    from scipy.optimize import linear_sum_assignment

    eigs = np.asarray(eigs)
    N, n = eigs.shape
    if N < 2 or n < 2:
        return eigs.copy()
    cost = np.abs(eigs[:-1, :, None] - eigs[1:, None, :])  # (N-1, n, n): i at k -> j at k+1
    match = np.argmin(cost, axis=2)                         # (N-1, n)
    ok = np.all(np.sort(match, axis=1) == np.arange(n), axis=1)
    for k in np.flatnonzero(~ok):
        _, cols = linear_sum_assignment(cost[k])
        match[k] = cols
    # compose: column c of output follows index order[k, c] in row k
    order = np.empty((N, n), dtype=int)
    order[0] = np.argsort(-eigs[0].real, kind="stable")
    for k in range(N - 1):
        order[k + 1] = match[k][order[k]]
    return np.take_along_axis(eigs, order, axis=1)


def eigenvalues_vs_speed(chair, speeds, model: str = "exact", casters: str = "free",
                         track: bool = True) -> np.ndarray:
    """Eigenvalues of the linear model at many speeds in one batched call.

    Returns an (N, n) complex array; with ``track=True`` each column follows
    one mode across the (sorted) speeds, see :func:`track_modes`.
    """
    eigs = np.linalg.eigvals(state_matrices(chair, speeds, model, casters))
    return track_modes(eigs) if track else eigs


# ---------------------------------------------------------------------------
# critical speeds
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class Crossing:
    """A speed where the largest real part of the eigenvalues crosses zero.

    Attributes
    ----------
    speed : float
        Critical speed (m/s), refined to 1e-10 m/s.
    kind : {"real", "complex"}
        "real": a real eigenvalue crosses (divergence); "complex": a complex
        pair crosses (oscillatory, flutter/shimmy-like instability).
    direction : {"destabilising", "stabilising"}
        Whether the system becomes unstable or stable as speed increases.
    eigenvalue : complex
        The crossing eigenvalue at the critical speed (imaginary part gives
        the frequency of an oscillatory crossing, rad/s).
    """

    speed: float
    kind: str
    direction: str
    eigenvalue: complex


def max_real_part(state_matrix: Callable[[np.ndarray], np.ndarray], speeds) -> np.ndarray:
    """Largest real part of the eigenvalues of ``state_matrix(speeds)`` (1/s)."""
    A = np.asarray(state_matrix(np.atleast_1d(np.asarray(speeds, dtype=float))))
    return np.linalg.eigvals(A).real.max(axis=-1)


def _slopes(state_matrix, speeds: np.ndarray, alpha: np.ndarray) -> np.ndarray:
    """d(alpha)/dU at the grid points from eigenvalue perturbation theory.

    ``d lambda = (w^H dA v) / (w^H v)`` for the eigenvalue of largest real
    part, with ``dA`` by a central difference of the state matrix.
    """
    h = 1e-6 * np.maximum(1.0, np.abs(speeds))
    lo = np.maximum(speeds - h, speeds * 0.5)
    dA = (np.asarray(state_matrix(speeds + h)) - np.asarray(state_matrix(lo))) / (speeds + h - lo)[:, None, None]
    A = np.asarray(state_matrix(speeds))
    lam, V = np.linalg.eig(A)
    lamL, W = np.linalg.eig(np.swapaxes(A, -1, -2).conj())
    out = np.empty(len(speeds))
    for k in range(len(speeds)):
        i = int(np.argmax(lam[k].real))
        j = int(np.argmin(np.abs(lamL[k].conj() - lam[k, i])))
        v, w = V[k][:, i], W[k][:, j]
        den = np.vdot(w, v)
        out[k] = (np.vdot(w, dA[k] @ v) / den).real if abs(den) > 1e-14 else 0.0
    return out


def critical_speeds(state_matrix: Callable[[np.ndarray], np.ndarray], speeds,
                    xtol: float = 1e-10) -> list[Crossing]:
    """Every speed in the grid's range where the largest real part crosses zero.

    Works for any speed-parameterised linear system.

    Parameters
    ----------
    state_matrix : callable
        Maps a 1-D array of N speeds to an (N, n, n) array of state matrices.
    speeds : array_like
        Search grid (m/s), increasing, positive.
    xtol : float
        Absolute tolerance of the refined speeds (m/s).

    Returns
    -------
    list of Crossing
        Sorted by speed.

    Notes
    -----
    ``alpha(U) = max Re(lambda)`` is continuous in U; each sign change between
    grid points is refined with Brent's method to ``xtol``.  A pair of roots
    that crosses and re-crosses between two grid points leaves no sign change
    on the grid.  The guard: the slope of ``alpha`` at every grid point is
    computed from eigenvalue perturbation theory, and on every interval where
    the cubic Hermite interpolant of ``alpha`` (values and slopes) comes within
    a margin of zero or where the slopes change sign, ``alpha`` is maximised
    (bounded Brent) inside the interval; if the maximum is positive the two
    crossings on either side are refined separately.  Only a crossing pair
    narrower than both the grid and the curvature implied by the endpoint
    slopes can escape, which the Hermite test makes a measurable hazard
    rather than a silent one.
    """
    from scipy.optimize import brentq, minimize_scalar

    U = np.asarray(speeds, dtype=float)
    if U.ndim != 1 or len(U) < 2:
        raise ValueError(f"speeds must be a 1-D grid of at least 2 speeds, got shape {U.shape}")
    if np.any(np.diff(U) <= 0):
        raise ValueError("speeds must be strictly increasing")
    if U[0] <= 0:
        raise ValueError(f"speeds[0]={U[0]!r} is invalid; valid range: speed > 0 m/s")

    def alpha(x: float) -> float:
        return float(max_real_part(state_matrix, np.array([x]))[0])

    a = max_real_part(state_matrix, U)
    brackets: list[tuple[float, float]] = []
    for k in range(len(U) - 1):
        if a[k] == 0.0:
            continue
        if np.sign(a[k]) != np.sign(a[k + 1]) and a[k + 1] != 0.0:
            brackets.append((U[k], U[k + 1]))
    # exact zeros on grid points: bracket around them
    for k in np.flatnonzero(a == 0.0):
        lo = U[k - 1] if k > 0 else U[k]
        hi = U[k + 1] if k < len(U) - 1 else U[k]
        if lo < hi and np.sign(alpha(lo)) != np.sign(alpha(hi)):
            brackets.append((lo, hi))

    # guard against double crossings hidden between grid points
    da = _slopes(state_matrix, U, a)
    scale = max(np.max(np.abs(a)), 1e-9)
    for k in range(len(U) - 1):
        if np.sign(a[k]) != np.sign(a[k + 1]):
            continue
        h = U[k + 1] - U[k]
        tt = np.linspace(0, 1, 9)[1:-1]
        h00, h10 = 2 * tt**3 - 3 * tt**2 + 1, tt**3 - 2 * tt**2 + tt
        h01, h11 = -2 * tt**3 + 3 * tt**2, tt**3 - tt**2
        herm = h00 * a[k] + h10 * h * da[k] + h01 * a[k + 1] + h11 * h * da[k + 1]
        suspicious = np.any(np.sign(herm) != np.sign(a[k])) or (
            np.sign(da[k]) != np.sign(da[k + 1]) and np.min(np.abs(herm)) < 0.05 * scale
        )
        if not suspicious:
            continue
        sgn = np.sign(a[k])
        res = minimize_scalar(lambda x: sgn * alpha(x), bounds=(U[k], U[k + 1]), method="bounded",
                              options={"xatol": 1e-9})
        if np.sign(alpha(res.x)) != sgn:
            brackets.append((U[k], res.x))
            brackets.append((res.x, U[k + 1]))

    out: list[Crossing] = []
    for lo, hi in sorted(set(brackets)):
        s = brentq(alpha, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps, maxiter=500)
        lam = np.linalg.eigvals(np.asarray(state_matrix(np.array([s])))[0])
        i = int(np.argmax(lam.real))
        kind = "complex" if abs(lam[i].imag) > 1e-8 * max(1.0, abs(lam[i])) else "real"
        direction = "destabilising" if alpha(hi) > alpha(lo) else "stabilising"
        out.append(Crossing(float(s), kind, direction, complex(lam[i])))
    return out


# ---------------------------------------------------------------------------
# chair-level analysis
# ---------------------------------------------------------------------------
@dataclass(frozen=True)
class ZeroWidthResult:
    """Zero-width (bicycle) model with locked casters (chapter 5).

    Attributes
    ----------
    load_main, load_caster : float
        Static load on one main wheel and one caster (N), eq 5-13 with the
        caster contact points at ``Chair.caster_contact_distance`` from the c.g.
    stiffness_main, stiffness_caster : float
        Cornering stiffness of one tire at that load (N/rad).
    understeer_coefficient : float
        k_us = W_f/C_f - W_r/C_r (rad), eq 5-16.
    critical_speed : float or None
        sqrt(-g s / k_us) (m/s), eq 5-15; None when k_us >= 0 (stable at all
        speeds).
    wheelbase : float
        s (m), main axle to caster contact points.
    """

    load_main: float
    load_caster: float
    stiffness_main: float
    stiffness_caster: float
    understeer_coefficient: float
    critical_speed: float | None
    wheelbase: float


def zero_width(chair: Chair) -> ZeroWidthResult:
    """Zero-width locked-caster understeer coefficient and critical speed (eqs 5-13..5-16).

    The front axle of the bicycle is the main axle for a rear-caster chair
    and the caster contacts for a front-caster chair.
    """
    s = chair.wheelbase
    d_main = chair.s1
    d_caster = chair.caster_contact_distance
    W = chair.m * chair.g
    load_main = W * d_caster / (2 * s)
    load_caster = W * d_main / (2 * s)
    c_main = float(chair.main_tire_model().cornering_stiffness_per_rad(load_main))
    c_caster = float(chair.caster_tire_model().cornering_stiffness_per_rad(load_caster))
    if chair.caster_position == "rear":
        W_f, W_r, C_f, C_r = load_main, load_caster, c_main, c_caster
    else:
        W_f, W_r, C_f, C_r = load_caster, load_main, c_caster, c_main
    k_us = float(zw.understeer_coefficient(W_f, W_r, C_f, C_r))
    crit = math.sqrt(-chair.g * s / k_us) if k_us < 0 else None
    return ZeroWidthResult(load_main, load_caster, c_main, c_caster, k_us, crit, s)


def divergence(chair: Chair, speeds, model: str = "exact", casters: str = "free") -> list[dict]:
    """Growth rate of the least stable mode and its time to double.

    Returns one dict per speed: ``speed_m_s``, ``rate_1_s`` (largest real
    part, 1/s), ``time_to_double_s`` (ln 2 / rate, or None when the rate is
    not positive), ``frequency_rad_s`` (imaginary part of that eigenvalue).
    """
    speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
    eigs = np.linalg.eigvals(state_matrices(chair, speeds, model, casters))
    idx = np.argmax(eigs.real, axis=1)
    lam = eigs[np.arange(len(speeds)), idx]
    rows = []
    for s, l in zip(speeds, lam):
        rate = float(l.real)
        rows.append({
            "speed_m_s": float(s),
            "rate_1_s": rate,
            "time_to_double_s": (math.log(2) / rate) if rate > 0 else None,
            "frequency_rad_s": abs(float(l.imag)),
        })
    return rows


def massless_caster_rate(chair: Chair, speed, caster_drag: float = 0.0):
    """Closed-form growth rate of the free-caster chair in the massless-caster limit (1/s).

    With massless, frictionless casters the caster tires can carry no lateral
    force (a caster aligns with its contact velocity at once), so the chair is a
    rigid body on one axle: the main wheels at signed position ``x_m`` with
    stiffness ``C`` per tire.  Eqs 5-4b/5-4c with eq 5-5 then give the
    characteristic equation

    ``lambda^2 + (2C/U)(1/m + x_m^2/I_z) lambda - 2 C x_m / I_z = 0``,

    whose constant term is negative for a rear-caster chair (``x_m > 0``): one
    real root is positive at every speed, which is chapter 5's "infinitely
    unstable" case two made quantitative.  At low speed the root tends to
    ``U m x_m / (I_z + m x_m^2)``: the chair pivots about its main axle as a
    trailer pushed backwards would.  For a front-caster chair (``x_m < 0``)
    both roots are stable.

    A caster's rolling drag ``D`` acts along its heading, which in this limit
    follows the contact velocity: its side component is ``-D`` times the
    contact's slip angle, so the caster pair is a second axle of cornering
    stiffness ``2 D`` (N/rad) at the caster contacts ``x_c = x_p - trail``
    (the feathers of an arrow).  The two-axle equation (5-9) then has

    ``p = (C_f + C_r)/(m U) + (C_f x_m^2 + C_r x_c^2)/(I_z U)``,
    ``q = C_f C_r (x_m - x_c)^2/(m I_z U^2) - (C_f x_m + C_r x_c)/I_z``

    with ``C_f = 2C``, ``C_r = 2D``: below ``U^2 = C_r (x_m - x_c)^2/(m x_m)``
    (``q > 0``) the rear-caster chair is stable.

    Parameters
    ----------
    chair : Chair
    speed : float or array_like
        Forward speed (m/s).
    caster_drag : float
        Rolling drag of one caster, N (default 0: the linear model's tires
        have no rolling resistance).

    Returns
    -------
    float or ndarray
        The larger real part of the two roots (1/s).
    """
    U = np.asarray(speed, dtype=float)
    drag = float(caster_drag)
    if not (math.isfinite(drag) and drag >= 0.0):
        raise ValueError(f"caster_drag={caster_drag!r} is invalid; valid range: >= 0 N")
    st = static_stiffness(chair)
    cf = st["D"] + st["E"]
    cr = 2.0 * drag
    prm = parameters(chair)
    xm, xc = float(prm.x_m), float(prm.x_p - prm.trail)
    m, iz = chair.m, chair.i_z
    b = (cf + cr) / (m * U) + (cf * xm**2 + cr * xc**2) / (iz * U)
    c = cf * cr * (xm - xc) ** 2 / (m * iz * U**2) - (cf * xm + cr * xc) / iz
    disc = b**2 - 4 * c
    root = np.where(disc >= 0, (-b + np.sqrt(np.abs(disc))) / 2, -b / 2)
    return float(root) if np.ndim(root) == 0 else root


@dataclass(frozen=True)
class StabilitySummary:
    """Everything ``python -m stability.critical_speed`` reports for one chair."""

    chair: Chair
    model: str
    static_loads: dict
    stiffness_n_per_deg: dict
    zero_width: ZeroWidthResult
    locked_crossings: list
    free_crossings: list
    free_stable_at_all_speeds: bool
    free_unstable_at_all_speeds: bool
    divergence: list
    search_range: tuple = field(default=(0.0, 0.0))


def analyse(chair: Chair, model: str = "exact", speeds=(0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0),
            max_speed: float = 30.0, n_grid: int = 600) -> StabilitySummary:
    """Full linear stability summary of a chair (see :class:`StabilitySummary`)."""
    if not (isinstance(max_speed, (int, float)) and max_speed > 0.01 and math.isfinite(max_speed)):
        raise ValueError(f"max_speed={max_speed!r} is invalid; valid range: 0.01 < max_speed < inf m/s")
    loads = static_loads(chair)
    main, caster = chair.main_tire_model(), chair.caster_tire_model()
    stiff = {"main": float(main.cornering_stiffness(loads["main"])),
             "caster": float(caster.cornering_stiffness(loads["caster"]))}
    grid = np.geomspace(0.01, max_speed, n_grid)
    locked = critical_speeds(lambda U: state_matrices(chair, U, model, "locked"), grid)
    free = critical_speeds(lambda U: state_matrices(chair, U, model, "free"), grid)
    a = max_real_part(lambda U: state_matrices(chair, U, model, "free"), grid)
    return StabilitySummary(
        chair=chair, model=model, static_loads=loads, stiffness_n_per_deg=stiff,
        zero_width=zero_width(chair), locked_crossings=locked, free_crossings=free,
        free_stable_at_all_speeds=bool(np.all(a < 0)), free_unstable_at_all_speeds=bool(np.all(a > 0)),
        divergence=divergence(chair, speeds, model, "free"), search_range=(float(grid[0]), float(grid[-1])),
    )
