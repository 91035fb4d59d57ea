"""The simulator on a slope (issue 12): zero slope unchanged, mirror symmetry, agreement with the slope
package's statics, turn directions, the grade's closed form, the fixed step against the adaptive scheme,
input checks."""

from __future__ import annotations

import json
import math
import os
import sys

import numpy as np
import pytest
from numerics import adaptive_run_tolerance, assert_signals_close, run_tolerance

from stability import chair as chair_mod
from stability.models import slope as msl
from stability.models.params import parameters
from stability.models.statics import normal_loads
from stability.settings.run import RunSpec
from stability.simulate import simulate, simulate_batch
from stability.simulate.__main__ import main as simulate_main
from stability.slope import solve
from stability.study.veer import simulator_path, simulator_slope

EJ = chair_mod.preset("ej-premier")                 # rear casters
FRONT = chair_mod.preset("manual-front-caster")     # front casters
FRICTIONLESS = {"pin_friction_left": 0.0, "pin_friction_right": 0.0}
STATES = ("x", "y", "heading", "yaw_rate", "u", "v", "eta", "eta_dot", "beta", "beta_dot")


def _same(a, b) -> None:
    """Bit-identical results (every recorded column, settings, warnings)."""
    assert json.dumps(a.to_dict(), sort_keys=True) == json.dumps(b.to_dict(), sort_keys=True)


def _same_states(a, b) -> None:
    """Bit-identical time histories of the ten states."""
    for name in ("t", *STATES):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


def _close(a, b, tol: float, what: str = "") -> None:
    """Every state agrees to ``tol`` of the signal's size (``tol`` from an error model, tests/numerics.py)."""
    assert a.t.shape == b.t.shape
    assert_signals_close(a, b, STATES, tol, what=what)


# -- zero slope --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("kw", [dict(), dict(model="exact"), dict(model="exact", casters="locked"),
                                dict(model="exact", scheme="adaptive", horizon=1.0)])
def test_zero_slope_is_todays_run(kw):
    base = RunSpec(**{"horizon": 2.0, **kw})
    ref = simulate(EJ, 0.75, base)
    _same(simulate(EJ, 0.75, base.replace(cross_slope_deg=0.0, grade_deg=0.0)), ref)
    _same(simulate(EJ, 0.75, base.replace(cross_slope_deg=-0.0, grade_deg=-0.0)), ref)
    assert "cross_slope_deg" not in ref.settings          # level runs record what they recorded before


def test_zero_slope_reference_paths_and_batch():
    ref = simulate_batch([EJ, FRONT], [0.6, 0.9], run=RunSpec(horizon=0.5, model="exact", friction_law="kinetic"), progress=False)
    got = simulate_batch([EJ, FRONT], [0.6, 0.9], run=RunSpec(horizon=0.5, model="exact", cross_slope_deg=0, grade_deg=0, friction_law="kinetic"), progress=False)
    for a, b in zip(got, ref, strict=True):
        _same(a, b)


def test_plane_loads_at_zero_slope_are_eq_6_25():
    """The generated loads from the force sums at gn = g equal statics.normal_loads (eq 6-25)."""
    rng = np.random.default_rng(1)
    for c in (EJ, FRONT):
        p = parameters(c)
        for _ in range(5):
            fx, fy, eta, beta = rng.normal(size=4) * (30.0, 60.0, 0.5, 0.5)
            trig = (math.cos(eta), math.sin(eta), math.cos(beta), math.sin(beta))
            np.testing.assert_allclose(msl.normal_loads_plane(p, fx, fy, p.g, *trig),
                                       normal_loads(p, fx, fy, *trig), rtol=1e-12, atol=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
            # and equal the acceleration form with m a = sum F + m g_in on a slope
            g1, g2, gn = msl.gravity(p.g, 0.05, -0.03, eta)
            # error model: rounding: the same statics in two arrangements, a few eps of loads up to 400 N (observed
            # 1.6e-16 relative), x100 (atol: eps x 400 N for a load near zero, x100)
            np.testing.assert_allclose(msl.normal_loads_plane(p, fx, fy, gn, *trig),
                                       msl.normal_loads(p, fx / p.m + g1, fy / p.m + g2, g1, g2, gn, *trig),
                                       rtol=1e-13, atol=1e-11)


# -- mirror symmetry -------------------------------------------------------------------------------------------

@pytest.mark.parametrize("scheme", ["wchair", "adaptive"])
@pytest.mark.parametrize("chair", [EJ, FRONT], ids=["rear-caster", "front-caster"])
def test_mirror_symmetry(scheme, chair):
    """Cross slope +phi and -phi on a symmetric chair: y, heading, yaw rate, v mirrored, casters swapped.

    Frictionless pins: Coulomb friction switches on the sign of a swivel rate that passes through zero, where
    a rounding-level difference between the mirrored runs would act for a step (and grow in a diverging run).
    The adaptive runs mirror to their integration error only (LSODA's step decisions see rounding-level
    differences): tolerance 100 rtol with rtol = 1e-9; the fixed-step runs to 1e-9 of the signal.
    """
    chair = chair.replace(**FRICTIONLESS)
    # 0.6 s: the rear-caster chair turns 13 deg; by 0.9 s its casters swing past 90 deg and the spin-out is
    # chaotic (there a rounding-level difference sent LSODA into steps of 1e-11 s)
    kw = dict(model="exact", scheme=scheme, horizon=0.6, push_force=0.0)
    if scheme == "adaptive":
        kw.update(rtol=1e-9, atol=1e-12)
    a = simulate(chair, 0.75, RunSpec(cross_slope_deg=3.0, grade_deg=1.0, **kw))
    b = simulate(chair, 0.75, RunSpec(cross_slope_deg=-3.0, grade_deg=1.0, **kw))
    # error models (tests/numerics.py): the fixed-step runs differ by rounding grown over the run; the
    # adaptive ones by at most the sum of their global errors (LSODA's step decisions may part)
    if scheme == "adaptive":
        tol = adaptive_run_tolerance(chair, 0.75, 0.6, 1e-9, max(a.settings["nfev"], b.settings["nfev"]), "exact")
    else:
        tol = run_tolerance(chair, 0.75, 0.6, model="exact")
    assert a.t.shape == b.t.shape
    for name, sign in (("x", 1), ("u", 1), ("y", -1), ("heading", -1), ("yaw_rate", -1), ("v", -1)):
        x, y = getattr(a, name), sign * getattr(b, name)
        np.testing.assert_allclose(x, y, rtol=0, atol=tol * max(float(np.max(np.abs(x))), 1e-12), err_msg=name)
    np.testing.assert_allclose(a.eta, -b.beta, rtol=0, atol=tol * float(np.max(np.abs(a.eta))))
    if os.environ.get("NUMERICS_REPORT"):
        print(f"numerics-ratio {np.max(np.abs(a.yaw_rate + b.yaw_rate)) / (tol * np.max(np.abs(a.yaw_rate))):.3g}"
              f" mirror {scheme}", file=sys.stderr)
    assert np.max(np.abs(a.heading)) > math.radians(1.0)       # a real turn, not a trivially symmetric zero


# -- turn directions --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("scheme", ["wchair", "adaptive"])
def test_front_casters_turn_downhill_rear_casters_uphill(scheme):
    """The plane falls to the right (+): downhill is a clockwise (+) heading change (issue 12, 'what is known')."""
    run = RunSpec(model="exact", scheme=scheme, horizon=0.5, push_force=0.0, cross_slope_deg=2.0)
    assert simulate(FRONT, 0.75, run).heading[-1] > math.radians(1.0)
    assert simulate(EJ, 0.75, run).heading[-1] < -math.radians(1.0)
    eq = solve(FRONT, -2.0, 0.75)
    assert simulator_path(FRONT, eq, RunSpec(scheme=scheme, horizon=0.5)).turn == "downhill"
    eq = solve(EJ, -2.0, 0.75)
    assert simulator_path(EJ, eq, RunSpec(scheme=scheme, horizon=0.5)).turn == "uphill"


# -- agreement with stability.study.veer ----------------------------------------------------------------------

def test_simulator_slope_is_the_same_plane():
    """The plane seen from the held heading has the same gravity: |g_in| and gn unchanged."""
    eq = solve(FRONT, 4.0, 0.75, 2.0)
    cross, grade = simulator_slope(FRONT, eq)
    a = msl.gravity(FRONT.g, math.radians(cross), math.radians(grade), 0.0)
    b = msl.gravity(FRONT.g, math.radians(eq.cross_slope_deg), math.radians(eq.grade_deg),
                    math.radians(eq.heading_deg))
    np.testing.assert_allclose(a, b, rtol=1e-13, atol=1e-13)  # rounding: equivalent arithmetic, a few ulp (observed 0)


# -- grade ------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("scheme", ["wchair", "adaptive"])
@pytest.mark.parametrize("grade", [5.0, -3.0])
def test_grade_speed_closed_form(scheme, grade):
    """Rolling resistance off, no side forces: u = U - g sin(theta) t, x = U t - g sin(theta) t^2/2."""
    res = simulate(EJ, 0.75, run=RunSpec(model="exact", scheme=scheme, horizon=1.0, push_force=0.0, cross_slope_deg=0.0, grade_deg=grade))
    a = -EJ.g * math.sin(math.radians(grade))
    # error model: rounding: the schemes integrate a constant acceleration (and its quadratic path) exactly up to
    # rounding, ~1000 steps x eps (observed 3.9e-14 m/s and 7.3e-15 m fixed-step; 4.4e-16 m/s and 1.5e-12 m
    # adaptive, its dense output's rounding), x100; heading: zero side forces (observed 0)
    np.testing.assert_allclose(res.u, 0.75 + a * res.t, rtol=0, atol=4e-12)
    np.testing.assert_allclose(res.x, 0.75 * res.t + 0.5 * a * res.t ** 2, rtol=0, atol=2e-10)
    assert np.max(np.abs(res.heading)) < 1e-12


# -- one arithmetic; two integrators -------------------------------------------------------------------------

@pytest.mark.parametrize("casters", ["free", "locked"])
def test_a_run_on_a_slope_is_the_same_alone_or_in_a_batch(casters):
    run = RunSpec(model="exact", horizon=1.0, cross_slope_deg=2.0, grade_deg=3.0, casters=casters)
    comp = simulate(EJ, 0.75, run)
    batch = simulate_batch([EJ, FRONT], [0.75, 0.6], run.replace(sample=0.001), progress=False)
    _same_states(batch[0], comp)                                            # one arithmetic, alone or batched


@pytest.mark.parametrize("chair", [FRONT, EJ], ids=["front-caster", "rear-caster"])
def test_fixed_step_converges_to_the_adaptive_scheme_on_a_slope(chair):
    """2 deg cross slope, 1 s, the chair's Coulomb pins (stick-slip law): the WCHAIR scheme's yaw rate differs
    from the adaptive scheme's (rtol 1e-9) by an amount that halves with the step (its Euler velocity update is
    first order; measured 7.0e-5 -> 3.5e-5 -> 1.7e-5 rad/s front caster, 9.0e-4 -> 4.5e-4 -> 2.3e-4 rear caster):
    two integrators of the generated slope equations."""
    run = RunSpec(model="exact", horizon=1.0, cross_slope_deg=2.0, push_force=0.0, sample=0.01)
    ref = np.asarray(simulate(chair, 0.75, run.replace(scheme="adaptive", rtol=1e-9, atol=1e-12)).yaw_rate)
    err = [np.abs(np.asarray(simulate(chair, 0.75, run.replace(dt=dt, stop_on_warnings=False)).yaw_rate)
                  - ref).max() for dt in (1e-3, 5e-4, 2.5e-4)]
    assert err[0] < 0.01 * np.abs(ref).max()
    for coarse, fine in zip(err[:-1], err[1:], strict=True):
        assert 0.35 < fine / coarse < 0.65, err


# -- inputs ------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("fields, match", [
    (dict(cross_slope_deg=15.5), r"cross_slope_deg=15\.5 is invalid; valid range: -15 <= cross_slope_deg <= 15 deg"),
    (dict(grade_deg=-16.0), r"grade_deg=-16\.0 is invalid; valid range"),
    (dict(cross_slope_deg=math.nan), r"cross_slope_deg=nan is invalid"),
])
def test_bad_slope_refused(fields, match):
    with pytest.raises(ValueError, match=match):
        simulate(EJ, 0.75, run=RunSpec(model="exact", **fields))


def test_a_slope_that_is_not_a_number_is_a_type_error():
    with pytest.raises(TypeError, match="cross_slope_deg='flat' is invalid; expected a number"):
        RunSpec(cross_slope_deg="flat")


def test_thesis_model_refused_on_slope():
    with pytest.raises(ValueError, match="model='thesis' is invalid on a slope"):
        simulate(EJ, 0.75, run=RunSpec(model="thesis", cross_slope_deg=2.0, grade_deg=0.0, friction_law="kinetic"))


def test_cli_slope(capsys):
    assert simulate_main(["--chair", "manual-front-caster", "--cross-slope", "2", "--horizon", "0.5",
                          "--push-force", "0", "--push-duration", "0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["settings"]["cross_slope_deg"], d["settings"]["grade_deg"]) == (2.0, 0.0)
    assert simulate_main(["--cross-slope", "20"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "slope" in err[0] and "15" in err[0]
