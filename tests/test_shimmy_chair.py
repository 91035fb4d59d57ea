"""Shimmy in the chair model (issue 13): the full-width model with relaxation-length caster tires.

Checks: the generated equations against the rigid-tire linear model (sigma -> 0,
an exact algebraic identity and the eigenvalue limit), the heavy-chair limit
against the towed wheel of ``stability.shimmy`` (its own derivation,
``derivations/shimmy.py``), mirror symmetry, and the characteristic polynomial
against an independent linear Newton-Euler derivation done here with sympy.
Relaxation (Pacejka, Tyre and Vehicle Dynamics, 2006, sec. 5.3):
``(sigma/U) dF/dt + F = -C alpha``.
"""

from __future__ import annotations

import importlib.util
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp
from numerics import assert_eigenvalues_match, match_eigenvalues

from stability.chair import preset
from stability.linear import state_matrices
from stability.models import linear_matrices
from stability.models.params import parameters
from stability.models.relaxed import relaxed_matrices
from stability.models.statics import static_stiffness
from stability.shimmy import TowedWheel, chair_critical_trail, relaxed_state_matrices, relaxed_state_space
from stability.shimmy.chair import CasterCompliance
from stability.shimmy.chair_modes import shimmy_mode

ROOT = Path(__file__).resolve().parents[1]
EJ = preset("ej-premier")


def _sorted(ev):
    return ev[np.lexsort((ev.imag, ev.real))]


@pytest.mark.parametrize("model", ["exact", "thesis"])
def test_quasi_static_tire_force_reproduces_linear_model(model):
    """Putting F = -C vAy/U (the sigma -> 0 limit of the relaxation row T) into the relaxed rows gives
    stability.models.linear_matrices exactly (an algebraic identity, for any sigma)."""
    p, st = parameters(EJ), static_stiffness(EJ)
    U = np.array([0.3, 1.0, 2.5])
    for sigma in (0.01, 0.05):
        M, K, Bm, T = relaxed_matrices(p, U, st, sigma, model)
        M0, K0, B0 = linear_matrices(p, U, st, variant=model)
        F_quasi = (sigma / U)[:, None, None] * T[:, :, :6]  # F = (sigma/U) T[:, :6] x at zero lag
        K_red = K[:, :, :6] + K[:, :, 6:] @ F_quasi
        np.testing.assert_allclose(M, np.broadcast_to(M0, M.shape), rtol=1e-13, atol=0)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        np.testing.assert_allclose(K_red, K0, rtol=1e-12, atol=1e-12 * np.abs(K0).max())  # rounding: equivalent arithmetic, a few ulp (observed 6.1e-16)
        np.testing.assert_allclose(Bm, B0, rtol=1e-13)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        np.testing.assert_allclose(np.diagonal(T[:, :, 6:], axis1=1, axis2=2), -(U / sigma)[:, None] * np.ones(2), rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.5e-16)


def test_sigma_to_zero_recovers_rigid_tire_eigenvalues():
    """sigma -> 0: six eigenvalues converge (linearly in sigma) to stability.linear's, two go as -U/sigma."""
    U = 1.0
    ref = _sorted(np.linalg.eigvals(state_matrices(EJ, U)[0]))
    errs = []
    for sigma in (1e-6, 1e-7):
        ev = np.linalg.eigvals(relaxed_state_matrices(EJ, U, CasterCompliance(relaxation_length=sigma))[0])
        ev = ev[np.argsort(ev.real)]
        fast, slow = ev[:2], ev[2:]
        # singular perturbation: fast roots -U/sigma (1 + O(sigma)), here within 1 %. error model: first order in
        # sigma (observed 5.3e-4 at 1e-6 m and 5.3e-5 at 1e-7 m)
        np.testing.assert_allclose(fast.real, -U / sigma, rtol=1e-2)
        r, c = match_eigenvalues(slow, ref)                  # paired by matching, not by sorting
        errs.append(np.max(np.abs(slow[r] - ref[c]) / np.abs(ref[c])))
    assert errs[1] < 1e-4
    assert errs[1] < 0.2 * errs[0]  # linear convergence: 10x smaller sigma, ~10x smaller error


def _first_order(M, K, T):
    """x_dot = A x from M acc = K x (acc: v, r, then the second derivative of each (angle, rate) pair) and T."""
    F = np.linalg.solve(M, K)
    n, k = K.shape[-1], M.shape[-1]
    A = np.zeros(F.shape[:-2] + (n, n))
    A[..., :2, :] = F[..., :2, :]
    for j in range(2, k):
        A[..., 2 * j - 2, 2 * j - 1] = 1.0
        A[..., 2 * j - 1, :] = F[..., j, :]
    A[..., -2:, :] = T
    return A


def _heavy(p, scale=1e6):
    return p._replace(m=p.m * scale, i_z=p.i_z * scale)


@pytest.mark.parametrize("pin", ["rigid", "compliant"])
def test_heavy_chair_shimmy_is_the_towed_wheel(pin):
    """A chair a million times heavier (m, i_z) does not move: both casters behave as the towed wheel
    with a rigid pivot (or a pivot on the pin spring), relaxation tire and the same pin damping.
    Coupling enters as m_c/m ~ 1e-8; tolerance 1e-5 relative."""
    chair = EJ.replace(pin_damping=0.05)
    comp = CasterCompliance(relaxation_length=0.03, lateral_stiffness=6e4)
    p, st = parameters(chair), static_stiffness(chair)
    U = np.array([0.5, 2.0])
    variant = "pin_exact" if pin == "compliant" else "exact"
    M, K, _, T = relaxed_matrices(_heavy(p), U, st, comp.relaxation_length, variant, comp.lateral_stiffness)
    ev = np.linalg.eigvals(_first_order(M, K, T))
    lead = shimmy_mode(ev)
    wheel = TowedWheel(mass=chair.m_c, inertia=chair.i_zp - chair.m_c * chair.l1**2,
                       contact_behind_cm=chair.trail - chair.l1, pivot_ahead_of_cm=chair.l1,
                       lateral_stiffness=math.inf if pin == "rigid" else comp.lateral_stiffness,
                       cornering_stiffness=st["A"], relaxation_length=comp.relaxation_length,
                       pin_damping=chair.pin_damping)
    tw = wheel.eigenvalues(U)
    tw_lead = shimmy_mode(tw)
    np.testing.assert_allclose(lead, tw_lead, rtol=1e-10)  # rounding: equivalent arithmetic, a few ulp (observed 1.1e-15)
    # every towed-wheel eigenvalue appears (twice: two casters) in the chair's spectrum
    for i in range(U.size):
        for lam in tw[i]:
            d = np.sort(np.abs(ev[i] - lam))
            assert d[1] < 1e-5 * abs(lam), (lam, d[:2])


def test_real_chair_critical_trail_close_to_towed_wheel():
    """With the chair's real mass the coupling is weak: the rigid-pin critical trail stays within 1 mm of
    the towed wheel's closed form L = sigma (rigid pivot, no damping; docs/shimmy.md table)."""
    comp = CasterCompliance(relaxation_length=0.03)
    crit = chair_critical_trail(EJ, [0.5, 2.0], comp)
    # error model: first order in the caster-to-chair mass ratio, the coupling (observed 2.4e-6 m), x400
    np.testing.assert_allclose(crit, comp.relaxation_length, atol=1e-3)


def _mirror(c):
    return c.replace(d1=c.d2, d2=c.d1, t1=c.t2, t2=c.t1)


@pytest.mark.parametrize("pin", ["rigid", "compliant"])
def test_mirror_symmetry(pin):
    """Swapping left and right geometry (an asymmetric chair) leaves the eigenvalues unchanged."""
    chair = EJ.replace(d1=0.24, d2=0.29, t1=0.21, t2=0.26, pin_damping=0.02)
    U = np.array([0.4, 1.5, 3.0])
    A1 = relaxed_state_matrices(chair, U, pin=pin)
    A2 = relaxed_state_matrices(_mirror(chair), U, pin=pin)
    # the two models differ; only their spectra agree. error model: rounding: equal matrices would agree to a few
    # ulp; these differ by 3.1e3 in entries up to 2.4e5 (observed), far beyond allclose's 1e-5 relative
    assert not np.allclose(A1, A2)
    for a1, a2 in zip(A1, A2, strict=True):
        # a1, a2 are similar (a permutation with sign changes) up to the rounding of their entries:
        # each set within n eps ||A|| kappa_i of the exact spectrum
        assert_eigenvalues_match(np.linalg.eigvals(a1), np.linalg.eigvals(a2), a1, a2, what="mirror")


# ---------------------------------------------------------------------------
# independent derivation: linear Newton-Euler of chair + two casters


def _newton_euler_A(chair, U, sigma, k_pin=None):
    """State matrix of the relaxed chair from a linear Newton-Euler derivation (exact rationals).

    Chair frame moving at U; C the system c.g. with the casters trailing.  Lateral
    acceleration of a point (x, y) of the chair: v_dot + U r + x r_dot.  Caster
    c.g. at (x_p - l1, y) + pin offset y_pin - l1 eta laterally.  Equations: the whole
    system's lateral momentum and its angular momentum about C; each caster's moment
    about its (moving) pin, M_Q = I_G alpha + r_QG x m a_G; with compliant pins each
    caster's lateral momentum, the massless housing passing the spring force -k y_pin.
    """
    Q = sp.Rational
    p, st = parameters(chair), static_stiffness(chair)
    x_m, x_p, trail, l1 = (Q(str(v)) for v in (p.x_m, p.x_p, p.trail, p.l1))
    m, m_c, i_z, i_zp, c = (Q(str(v)) for v in (p.m, p.m_c, p.i_z, p.i_zp, p.pin_damping))
    CA, CB, CD, CE = (Q(repr(st[k])) for k in "ABDE")
    U, sigma = Q(str(U)), Q(str(sigma))
    pin = k_pin is not None
    v, r, ea, ead, eb, ebd, FA, FB, ya, yad, yb, ybd = sp.symbols("v r ea ead eb ebd FA FB ya yad yb ybd")
    vd, rd, ead_d, ebd_d, yadd, ybdd = sp.symbols("vd rd eadd ebdd yadd ybdd")
    if not pin:
        ya = yad = yb = ybd = yadd = ybdd = 0
    I_c = i_zp - m_c * l1**2
    a_chair = vd + U * r  # lateral acceleration of C
    casters = []
    for eta, eta_d, eta_dd, y, y_d, y_dd, F, C_ in ((ea, ead, ead_d, ya, yad, yadd, FA, CA),
                                                     (eb, ebd, ebd_d, yb, ybd, ybdd, FB, CB)):
        a_cg = a_chair + (x_p - l1) * rd + y_dd - l1 * eta_dd
        v_contact = v + (x_p - trail) * r + y_d - U * eta - trail * eta_d  # along a2
        casters.append((eta, eta_d, eta_dd, y, y_dd, F, C_, a_cg, v_contact))
    FD = -CD * (v + x_m * r) / U
    FE = -CE * (v + x_m * r) / U
    # whole system: lateral; yaw about C (frozen-caster part i_z r_dot, C the c.g.)
    lat = m * a_chair + sum(m_c * (y_dd - l1 * eta_dd) for (_, _, eta_dd, _, y_dd, *_r) in casters) \
        - (FA + FB + FD + FE)
    yaw = i_z * rd + sum(I_c * eta_dd + m_c * (x_p - l1) * (y_dd - l1 * eta_dd)
                         for (_, _, eta_dd, _, y_dd, *_r) in casters) \
        - ((FA + FB) * (x_p - trail) + (FD + FE) * x_m)
    eqs = [lat, yaw]
    for _eta, eta_d, eta_dd, y, _y_dd, F, _c, a_cg, _ in casters:
        eqs.append(I_c * (rd + eta_dd) - l1 * m_c * a_cg - (-c * eta_d - trail * F))
        if pin:
            eqs.append(m_c * a_cg - (F - Q(str(k_pin)) * y))
    accs = [vd, rd, ead_d, ebd_d] + ([yadd, ybdd] if pin else [])
    sol = sp.solve(eqs, accs, dict=True)[0]
    rows = [sol[vd], sol[rd], ead, sol[ead_d], ebd, sol[ebd_d]]
    states = [v, r, ea, ead, eb, ebd]
    if pin:
        rows += [yad, sol[yadd], ybd, sol[ybdd]]
        states += [ya, yad, yb, ybd]
    for _, _, _, _, _, F, C_, _, v_c in casters:
        rows.append(U / sigma * (-F - C_ * v_c / U))
    states += [FA, FB]
    return sp.Matrix([[sp.diff(e, s) for s in states] for e in rows])


@pytest.mark.parametrize("pin", ["rigid", "compliant"])
def test_characteristic_polynomial_against_newton_euler(pin):
    """det(sI - A) of the generated model equals the hand Newton-Euler derivation's (coefficients)."""
    chair = EJ.replace(d1=0.25, d2=0.28, t1=0.22, t2=0.25, pin_damping=0.03)
    U, sigma, k = 1.3, 0.025, 7e4
    comp = CasterCompliance(relaxation_length=sigma, lateral_stiffness=k)
    A_ne = _newton_euler_A(chair, U, sigma, k if pin == "compliant" else None)
    s = sp.Symbol("s")
    exact = [float(x) for x in A_ne.charpoly(s).all_coeffs()]
    A = relaxed_state_matrices(chair, U, comp, pin=pin)[0]
    ours = [float(x) for x in sp.Matrix(A).charpoly(s).all_coeffs()]
    # scale each coefficient by the size of the terms that build it: prod of the largest |eigenvalues|
    lam = np.sort(np.abs(np.linalg.eigvals(A)))[::-1]
    scale = [np.prod(lam[:j]) for j in range(len(exact))]
    # error model: rounding of the characteristic polynomials of float matrices (Berkowitz's sums of products,
    # cancelling terms larger than the scale where the stiff pin spreads the entries); observed 7.2e-14 (rigid),
    # 7.6e-11 (compliant), x130
    np.testing.assert_allclose(np.array(ours) / scale, np.array(exact) / scale, rtol=0, atol=1e-8)


def test_state_space_names_and_matrices():
    sys_ = relaxed_state_space(EJ, 1.0, pin="compliant")
    assert list(sys_.state_labels) == ["v", "r", "eta", "eta_dot", "beta", "beta_dot", "y_A", "y_A_dot",
                                       "y_B", "y_B_dot", "F_A", "F_B"]
    np.testing.assert_allclose(sys_.A, relaxed_state_matrices(EJ, 1.0, pin="compliant")[0], rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    with pytest.raises(ValueError, match="pin='compliant'"):
        relaxed_state_matrices(EJ, 1.0, model="thesis", pin="compliant")
    with pytest.raises(ValueError, match="pin="):
        relaxed_state_matrices(EJ, 1.0, pin="soft")


def _load(path: Path, name: str):
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.mark.slow
def test_generation_reproduces_committed_file(tmp_path):
    """derivations/full_width_relaxed.py reproduces the committed module (byte for byte with the header's sympy)."""
    subprocess.run([sys.executable, str(ROOT / "derivations" / "full_width_relaxed.py"), "--out", str(tmp_path)],
                   check=True, cwd=ROOT, capture_output=True, timeout=600)
    committed_path = ROOT / "stability" / "_generated" / "full_width_relaxed.py"
    committed, fresh = committed_path.read_text(), (tmp_path / "full_width_relaxed.py").read_text()
    header = re.search(r"^sympy version: (\S+)$", committed, re.M)
    assert header
    if header.group(1) == sp.__version__:
        assert fresh == committed
        return
    a, b = _load(committed_path, "committed_relaxed"), _load(tmp_path / "full_width_relaxed.py", "fresh_relaxed")
    rng = np.random.default_rng(3)
    for name in a.__all__:
        if name == "STATES":
            assert a.STATES == b.STATES
            continue
        fa, fb = getattr(a, name), getattr(b, name)
        args = rng.uniform(0.1, 2.0, fa.__code__.co_argcount)
        # error model: rounding: another sympy's expression forms are the same arithmetic reordered, a few eps times
        # the expressions' cancellation (not observable here: an equal sympy version compares the text exactly)
        assert np.allclose(_flat(fa(*args)), _flat(fb(*args)), rtol=1e-10), name


def _flat(x):
    if isinstance(x, (tuple, list)):
        return [y for e in x for y in _flat(e)]
    return [float(x)]


def test_cli_chair_model_option(capsys):
    """--chair-model adds the chair-model results; with compliant pins its critical trail agrees with the
    towed-wheel estimate in the same output within 0.1 mm (the chair is ~80x heavier than a caster)."""
    import json

    from stability.shimmy.__main__ import main

    assert main(["--chair", "revised", "--speeds", "0.5,2", "--chair-model", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    cm = out["chair_model"]
    assert set(cm) == {"rigid_pin", "compliant_pin"}
    # error model: first order in the caster-to-chair mass ratio (observed 2.5e-6 m), x40
    np.testing.assert_allclose(cm["compliant_pin"]["critical_trail_m"], out["critical_trail_m"], atol=1e-4)
    np.testing.assert_allclose(cm["compliant_pin"]["shimmy_frequency_hz"], out["shimmy_frequency_hz"], rtol=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 5.5e-16)
    assert main(["--chair", "revised", "--speeds", "1", "--json"]) == 0
    assert "chair_model" not in json.loads(capsys.readouterr().out)
