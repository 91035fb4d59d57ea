"""Eigenvalue effect of each thesis-vs-exact difference, for the thesis chair.

Run ``python derivations/compare_variants.py`` (prints Markdown tables, the
ones quoted in ``derivations/README.md``).

Chair: the Everest & Jennings Premier of WCHAIR's BLOCK DATA (x_m = 0.345,
x_p = -0.175, d1 = d2 = 0.265, t1 = t2 = 0.24, trail = 0.08, l1 = 0.058,
m = 95, m_c = 1.2, i_z = 5.6, i_zp = 0.02, g = 9.81), EJA main tires and ER
casters (``stability.chair.preset("ej-premier")``).  Cornering stiffness of
each tire at its static load from :func:`stability.models.statics.static_stiffness`
(loads of :mod:`stability.loads`, eq 6-25 with the trail, as WCHAIR's STATICS).  Pin
damping: ``c_pin = 0`` by default (WCHAIR's pin friction is Coulomb, 0.1 N m,
which has no linearisation); ``--c-pin`` changes it.

The switchable linear model is :func:`derivations.full_width.hybrid_linear`;
its end points are the exact and thesis linearisations (tested).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

import sympy as sp  # noqa: E402

from derivations import full_width as fw  # noqa: E402
from stability import chair as chair_mod  # noqa: E402
from stability.models.params import parameters  # noqa: E402
from stability.models.statics import static_stiffness  # noqa: E402

#: the thesis chair (WCHAIR BLOCK DATA, chapter 8), from the package's one definition
THESIS_CHAIR = chair_mod.preset("ej-premier")
_P = parameters(THESIS_CHAIR)
CHAIR = dict(x_m=_P.x_m, x_p=_P.x_p, d1=_P.d1, d2=_P.d2, t1=_P.t1, t2=_P.t2, trail=_P.trail,
             l1=_P.l1, m=_P.m, m_c=_P.m_c, i_z=_P.i_z, i_zp=_P.i_zp)
SWITCHES = ("k_slip", "k_abs", "k_pin", "k_lat", "k_yaw")
SWITCH_TEXT = {
    "k_slip": "caster slip includes -trail*r (K-vAy/vBy)",
    "k_abs": "caster inertia on absolute accel. r_dot + eta_dd (D-eta 1)",
    "k_pin": "pin acceleration from kinematics, not F_tires/m (D-eta 2)",
    "k_lat": "lateral eq.: -m_c l1 (eta_dd + beta_dd) (D-v)",
    "k_yaw": "yaw eq.: +(i_zp - m_c l1 x_p)(eta_dd + beta_dd) (D-r)",
}


def chair_stiffness(chair=THESIS_CHAIR) -> dict[str, object]:
    """Per-tire stiffness (N/rad) at the static loads of :mod:`stability.loads` (eq 6-25,
    trail included as WCHAIR's STATICS does), from :func:`stability.models.statics.static_stiffness`."""
    from stability.models.statics import static_loads

    st = static_stiffness(chair)
    loads = static_loads(chair)
    return dict(C_A=st["A"], C_B=st["B"], C_D=st["D"], C_E=st["E"], fz_main=loads["main"],
                fz_caster=loads["caster"], source="stability.tires at stability.loads static loads")


_HYB = None


def _hybrid_numeric():
    """Lambdified hybrid_linear(M, K, Bm, Bf) in switches and parameters."""
    global _HYB
    if _HYB is None:
        ks = sp.symbols("k_slip k_abs k_pin k_lat k_yaw k_fext")
        M, K, Bm, Bf = fw.hybrid_linear(*ks)
        S = fw.S
        params = (S.U, S.C_A, S.C_B, S.C_D, S.C_E, S.c_pin, *fw.INERTIA)
        _HYB = sp.lambdify((ks, params), (M, K, Bm, Bf), "numpy")
    return _HYB


def matrices(U: float, switches: dict[str, float], c_pin: float = 0.0, k_fext: float = 0.0):
    """Numeric (M, K, Bm, Bf) of the hybrid model at speed ``U``."""
    C = chair_stiffness()
    ks = tuple(float(switches[k]) for k in SWITCHES) + (float(k_fext),)
    params = (U, C["C_A"], C["C_B"], C["C_D"], C["C_E"], c_pin, *CHAIR.values())
    M, K, Bm, Bf = _hybrid_numeric()(ks, params)
    return (np.array(M, float), np.array(K, float), np.array(Bm, float).ravel(),
            np.array(Bf, float).ravel())


def state_matrix(M: np.ndarray, K: np.ndarray) -> np.ndarray:
    """First-order matrix for x = [v, r, eta, eta_d, beta, beta_d]."""
    acc = np.linalg.solve(M, K)
    A = np.zeros((6, 6))
    A[0], A[1], A[3], A[5] = acc[0], acc[1], acc[2], acc[3]
    A[2, 3] = A[4, 5] = 1.0
    return A


def modes(A: np.ndarray, U: float) -> list[tuple[complex, str]]:
    """Eigenvalues with a label from the eigenvector (which coordinates move).

    The eigenvector is made dimensionless as angles: chair sideslip ``v/U``,
    yaw ``r s/U`` (``s`` the wheelbase to the caster contacts) and the caster
    angles in their in-phase ``(eta + beta)/2`` and anti-phase
    ``(eta - beta)/2`` combinations; the label names the largest share.
    """
    s = CHAIR["x_m"] - CHAIR["x_p"] + CHAIR["trail"]
    w, V = np.linalg.eig(A)
    out = []
    for i in np.argsort(w.real)[::-1]:
        vec = V[:, i]
        parts = {
            "chair sideslip": abs(vec[0] / U) ** 2,
            "chair yaw": abs(vec[1] * s / U) ** 2,
            "casters in phase": abs((vec[2] + vec[4]) / 2) ** 2,
            "casters anti-phase": abs((vec[2] - vec[4]) / 2) ** 2,
        }
        tot = sum(parts.values())
        top = sorted(parts.items(), key=lambda kv: -kv[1])
        lab = top[0][0] + (f" ({100 * top[0][1] / tot:.0f}%)")
        if top[1][1] / tot > 0.2:
            lab += f" + {top[1][0]} ({100 * top[1][1] / tot:.0f}%)"
        out.append((w[i], lab))
    return out


def fmt(z: complex) -> str:
    if abs(z.imag) < 1e-9:
        return f"{z.real:+.3f}"
    return f"{z.real:+.3f} ± {abs(z.imag):.3f}j"


ALL_ON = {k: 1 for k in SWITCHES}
ALL_OFF = {k: 0 for k in SWITCHES}


def table_switches(U: float, c_pin: float) -> str:
    """Eigenvalues: thesis, thesis + each correction, exact - each, exact."""
    rows = []

    def line(name, sw):
        M, K, _, _ = matrices(U, sw, c_pin)
        ev = modes(state_matrix(M, K), U)
        rows.append((name, ev))

    line("thesis (all switches 0)", ALL_OFF)
    for k in SWITCHES:
        line(f"thesis + {SWITCH_TEXT[k]}", dict(ALL_OFF, **{k: 1}))
    for k in SWITCHES:
        line(f"exact without {k}", dict(ALL_ON, **{k: 0}))
    line("exact (all switches 1)", ALL_ON)
    out = [f"Eigenvalues (1/s) at U = {U} m/s, c_pin = {c_pin} N m s/rad, sorted by real part:", "",
           "| model | eigenvalues |", "|---|---|"]
    for name, ev in rows:
        out.append(f"| {name} | " + ", ".join(fmt(z) for z, _ in ev) + " |")
    out += ["", "Mode labels (exact model): " + "; ".join(
        f"{fmt(z)}: {lab}" for z, lab in rows[-1][1])]
    out += ["Mode labels (thesis model): " + "; ".join(
        f"{fmt(z)}: {lab}" for z, lab in rows[0][1])]
    return "\n".join(out)


def table_speeds(speeds: Sequence[float], c_pin: float) -> str:
    out = ["| U (m/s) | thesis: largest Re | exact: largest Re | thesis caster-dominated modes "
           "| exact caster-dominated modes |",
           "|---|---|---|---|---|"]
    for U in speeds:
        cells = []
        cm = []
        for sw in (ALL_OFF, ALL_ON):
            M, K, _, _ = matrices(U, sw, c_pin)
            ev = modes(state_matrix(M, K), U)
            cells.append(fmt(ev[0][0]))
            cm.append(", ".join(fmt(z) for z, lab in ev if lab.startswith("casters")))
        out.append(f"| {U} | {cells[0]} | {cells[1]} | {cm[0]} | {cm[1]} |")
    return "\n".join(out)


def locked_critical_speeds() -> str:
    """Critical speed with the casters locked: exact, thesis, zero-width (5-15)."""
    from scipy.optimize import brentq

    out = []

    def det_locked(U, variant):
        M, K, _, _ = matrices(U, ALL_ON if variant == "exact" else ALL_OFF)
        return np.linalg.det(np.linalg.solve(M[:2, :2], K[:2, :2]))

    for variant in ("exact", "thesis"):
        Uc = brentq(lambda U, v=variant: det_locked(U, v), 1.0, 200.0)
        out.append((variant, Uc))
    from stability.linear import zero_width

    uz = zero_width(THESIS_CHAIR).critical_speed
    lines = ["| model (casters locked) | critical speed (m/s) |", "|---|---|"]
    for v, Uc in out:
        lines.append(f"| {v} | {Uc:.2f} |")
    lines.append(f"| zero-width eq 5-15 (s2 to the caster contact, static loads of 5-13) | {uz:.2f} |")
    return "\n".join(lines)


def lag_effect(U: float, dt: float, c_pin: float) -> str:
    """WCHAIR's discrete scheme (constant acceleration per step, ITRATE) with and
    without the one-step lag of THEDD in the caster equations: equivalent
    continuous eigenvalues ln(z)/dt of the thesis model."""
    M, K, _, _ = matrices(U, ALL_OFF, c_pin)
    n = 7  # [v, r, eta, eta_d, beta, beta_d, r_dot_prev]
    res = {}
    for lag in (False, True):
        # accelerations as linear functions of z
        Aacc = np.zeros((4, n))
        Aacc[0, :6] = K[0] / M[0, 0]
        Aacc[1, :6] = K[1] / M[1, 1]
        for row in (2, 3):
            Aacc[row, :6] = K[row] / M[row, row]
            coupling = -M[row, 1] / M[row, row]  # eta_dd = (K x - M[row,1] r_dot_c)/M[row,row]
            if lag:
                Aacc[row, 6] += coupling
            else:
                Aacc[row, :6] += coupling * Aacc[1, :6]
        T = np.zeros((n, n))
        T[0] = np.eye(n)[0] + dt * Aacc[0]
        T[1] = np.eye(n)[1] + dt * Aacc[1]
        T[2] = np.eye(n)[2] + dt * np.eye(n)[3] + 0.5 * dt * dt * Aacc[2]
        T[3] = np.eye(n)[3] + dt * Aacc[2]
        T[4] = np.eye(n)[4] + dt * np.eye(n)[5] + 0.5 * dt * dt * Aacc[3]
        T[5] = np.eye(n)[5] + dt * Aacc[3]
        T[6] = Aacc[1]
        z = np.linalg.eigvals(T).astype(complex)
        z = z[np.abs(z) > 1e-12]  # the r_dot_prev row adds a zero eigenvalue without lag
        s = np.log(z) / dt
        res[lag] = sorted(s, key=lambda c: -c.real)
    cont = sorted(np.linalg.eigvals(state_matrix(M, K)), key=lambda c: -c.real)
    return "\n".join([
        f"Thesis model at U = {U} m/s, dt = {dt} s (ln(z)/dt of WCHAIR's update):", "",
        "| scheme | eigenvalues (1/s) |", "|---|---|",
        "| continuous | " + ", ".join(fmt(c) for c in cont) + " |",
        "| WCHAIR step, current THEDD | " + ", ".join(fmt(c) for c in res[False]) + " |",
        "| WCHAIR step, previous THEDD (as DYNAM) | " + ", ".join(fmt(c) for c in res[True]) + " |",
    ])


def impulse_effect(U: float, c_pin: float, force: float = 40.0, duration: float = 0.10) -> str:
    """Response to WCHAIR's default disturbance (FCIMP = 40 N for 0.1 s)."""
    from scipy.linalg import expm

    rows = []
    cases = (("thesis (FCIMP not in the pin acceleration)", ALL_OFF, 0.0),
             ("thesis + FCIMP in the pin acceleration", ALL_OFF, 1.0),
             ("exact", ALL_ON, 0.0))
    for name, sw, kf in cases:
        M, K, _, Bf = matrices(U, sw, c_pin, k_fext=kf)
        A = state_matrix(M, K)
        b = np.zeros(6)
        acc_b = np.linalg.solve(M, Bf)
        b[0], b[1], b[3], b[5] = acc_b
        # exact zero-order-hold for the push, then free response
        aug = np.zeros((7, 7))
        aug[:6, :6] = A * duration
        aug[:6, 6] = b * force * duration
        x1 = expm(aug)[:6, 6]
        eta0 = acc_b[2] * force
        vals = [eta0]
        for t in (0.5, 1.0, 2.0):
            x = expm(A * (t - duration)) @ x1
            vals.append(x[1])
        rows.append((name, x1[2], vals))
    out = [f"Lateral push {force} N at C for {duration} s, U = {U} m/s (linear models):", "",
           "| model | eta_dd at onset (rad/s^2) | eta at 0.1 s (rad) | r at 0.5 s | r at 1 s | r at 2 s (rad/s) |",
           "|---|---|---|---|---|---|"]
    for name, eta1, v in rows:
        out.append(f"| {name} | {v[0]:+.3f} | {eta1:+.5f} | {v[1]:+.4f} | {v[2]:+.4f} | {v[3]:+.4f} |")
    return "\n".join(out)


def front_caster(speeds: Sequence[float], c_pin: float) -> str:
    """The thesis's front-caster check (section 8, Figure 8-4b): s1 and s2
    exchanged, i.e. x_m = -0.175, x_p = +0.345, moving forward."""
    from stability.linear import state_matrices

    fc = chair_mod.preset("ej-premier-front-caster").replace(pin_damping=c_pin)
    out = ["| U (m/s) | thesis: largest Re | exact: largest Re |", "|---|---|---|"]
    for U in speeds:
        cells = []
        for v in ("thesis", "exact"):
            ev = np.linalg.eigvals(state_matrices(fc, U, v, "free")[0])
            cells.append(fmt(ev[np.argmax(ev.real)]))
        out.append(f"| {U} | {cells[0]} | {cells[1]} |")
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description="Thesis-vs-exact eigenvalue comparison (E&J Premier).")
    p.add_argument("--speed", type=float, default=0.75)
    p.add_argument("--c-pin", type=float, default=0.0)
    a = p.parse_args(argv)
    C = chair_stiffness()
    print(f"Static loads: main {C['fz_main']:.1f} N, caster {C['fz_caster']:.1f} N; "
          f"C_D = C_E = {C['C_D']:.0f} N/rad (EJA), C_A = C_B = {C['C_A']:.0f} N/rad (ER), "
          f"from {C['source']}.\n")
    print(table_switches(a.speed, a.c_pin), "\n")
    print(table_speeds((0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0), a.c_pin), "\n")
    print(locked_critical_speeds(), "\n")
    print(lag_effect(a.speed, 1e-3, a.c_pin), "\n")
    print(impulse_effect(a.speed, a.c_pin), "\n")
    print("Front-caster chair (x_m = -0.175, x_p = +0.345):\n")
    print(front_caster((0.25, 0.75, 2.0, 5.0), a.c_pin))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
