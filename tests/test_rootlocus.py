"""Root loci against speed, design parameters and a feedback gain (stability.rootlocus)."""

import numpy as np
import pytest
from numerics import assert_eigenvalues_match, eig_bounds, match_eigenvalues, poly_root_tolerance

from stability import linear, rootlocus
from stability.chair import preset


def _polynomial_roots_bound(roots, A):
    """Error bound of roots that python-control finds through a transfer function of the state matrix ``A``.

    The polynomial's coefficients inherit the eigenvalue errors of ``A`` and are rounded when formed
    (n eps relative to the sum of their terms' magnitudes); its roots then move by the root condition
    (tests/numerics.py: eig_bounds, poly_root_tolerance)."""
    roots = np.asarray(roots)
    return eig_bounds(roots, A) + poly_root_tolerance(np.poly(roots), roots)


@pytest.fixture(scope="module")
def ej():
    return preset("ej-premier")


# ---------------------------------------------------------------------------
# parameter loci
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("name", ["cg_ratio", "s1_plus_s2", "trail", "caster_mass_factor", "pin_damping",
                                  "mass_factor", "main_lateral_scale", "main_tire"])
def test_parameter_locus_equals_per_chair_eigenvalues(ej, name):
    """At each value the locus holds exactly the eigenvalues of state_matrices(chair.replace(...), speed)."""
    loc = rootlocus.parameter_locus(ej, name, speed=0.75, n=25)
    p = rootlocus.DESIGN_PARAMETERS[name]
    assert loc.eigenvalues.shape == (len(loc.values), 6)
    for k in range(0, len(loc.values), 4):
        c = p.apply(ej, float(loc.values[k]))
        assert c == loc.chairs[k]
        A = linear.state_matrices(c, 0.75)[0]
        # the same matrix's eigenvalues, batched and alone: each within n eps ||A|| kappa_i
        assert_eigenvalues_match(loc.eigenvalues[k], np.linalg.eigvals(A), A, A, what=f"{name}={loc.values[k]}")


def test_cg_ratio_keeps_s1_plus_s2(ej):
    """Eq 8-6: the c.g. ratio is varied at constant s1 + s2."""
    loc = rootlocus.parameter_locus(ej, "cg_ratio", [0.5, 0.6, 0.66, 0.75], speed=0.75)
    for r, c in zip(loc.values, loc.chairs, strict=False):
        assert c.s1 + c.s2 == pytest.approx(ej.s1 + ej.s2, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        assert c.cg_ratio == pytest.approx(r, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert loc.nominal == pytest.approx(ej.cg_ratio, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_caster_mass_scales_mass_and_inertia_together(ej):
    """Figure 8-12: m_c and I_zp multiplied by the same factor."""
    loc = rootlocus.parameter_locus(ej, "caster_mass_factor", [1.0, 2.0, 3.0])
    for f, c in zip(loc.values, loc.chairs, strict=False):
        assert c.m_c == pytest.approx(ej.m_c * f, rel=1e-12) and c.i_zp == pytest.approx(ej.i_zp * f, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
        assert c.m == ej.m and c.i_z == ej.i_z


def test_batched_locus_equals_chair_by_chair_poles(ej):
    """Each row of the batched locus equals the poles python-control finds for that chair alone."""
    loc = rootlocus.parameter_locus(ej, "trail", speed=1.0, n=12)
    p = rootlocus.get_parameter("trail")
    for value, row in zip(loc.values, loc.eigenvalues, strict=True):
        sys = linear.state_space(p.apply(ej, value), 1.0)
        assert_eigenvalues_match(row, sys.poles(), sys.A, sys.A, what=f"trail={value}")


@pytest.mark.parametrize("name", ["cg_ratio", "s1_plus_s2", "trail", "pin_damping", "mass_factor"])
def test_branches_are_continuous(ej, name):
    """Tracked branches: the largest jump between neighbouring values is small against the locus's spread."""
    loc = rootlocus.parameter_locus(ej, name, speed=0.75, n=241)
    eig = loc.eigenvalues
    spread = np.abs(eig - eig.mean()).max()
    jumps = np.abs(np.diff(eig, axis=0)).max()
    assert jumps < 0.05 * spread
    # and tracking does at least as well as the raw order of eigvals
    raw = np.linalg.eigvals(linear.state_matrices(list(loc.chairs), np.full(len(loc.chairs), 0.75)))
    # error model: rounding: the tracked rows are the raw eigenvalues reordered (observed identical sets); where both
    # orders coincide the sums may differ by n eps of the sum (1446 terms: 3.2e-13 of it), x300
    assert np.abs(np.diff(eig, axis=0)).sum() <= np.abs(np.diff(raw, axis=0)).sum() * (1 + 1e-10)


def mirror(c):
    """The chair reflected left-right."""
    return c.replace(d1=c.d2, d2=c.d1, t1=c.t2, t2=c.t1, pin_friction_left=c.pin_friction_right,
                     pin_friction_right=c.pin_friction_left)


@pytest.mark.parametrize("name", ["cg_ratio", "trail", "s1_plus_s2"])
@pytest.mark.parametrize("model", ["exact", "thesis"])
def test_mirror_invariance(ej, name, model):
    """A chair and its mirror image have the same loci (dynamics do not know left from right)."""
    asym = ej.replace(d1=0.22, d2=0.30, t1=0.20, t2=0.27)
    a = rootlocus.parameter_locus(asym, name, speed=0.9, model=model, n=15)
    b = rootlocus.parameter_locus(mirror(asym), name, speed=0.9, model=model, n=15)
    for k in range(len(a.values)):
        # the two state matrices are similar in exact arithmetic (a sign change of the lateral states) and
        # differ by the rounding of their entries: each side within n eps ||A|| kappa_i of the exact spectrum
        A = linear.state_matrices(a.chairs[k], 0.9, model)[0]
        B = linear.state_matrices(b.chairs[k], 0.9, model)[0]
        assert_eigenvalues_match(a.eigenvalues[k], b.eigenvalues[k], A, B, what=f"{name}={a.values[k]}")


def test_symmetric_chair_cg_ratio_locus_is_real_symmetric(ej):
    """Real state matrices: each row of the locus is closed under complex conjugation."""
    loc = rootlocus.parameter_locus(ej, "cg_ratio", speed=0.75, n=31)
    for row in loc.eigenvalues:
        # LAPACK returns complex eigenvalues of a real matrix as exact conjugate pairs: no tolerance
        r, c = match_eigenvalues(row, np.conj(row))
        np.testing.assert_array_equal(row[r], np.conj(row)[c])


def test_main_tire_locus_is_categorical(ej):
    from stability import tires

    loc = rootlocus.parameter_locus(ej, "main_tire", speed=0.75)
    assert loc.categorical and loc.labels == tuple(tires.MAIN_TIRES)
    assert [c.main_tire for c in loc.chairs] == list(tires.MAIN_TIRES)
    assert loc.nominal == tires.MAIN_TIRES.index("EJA")


def test_bad_parameter_input(ej):
    with pytest.raises(ValueError, match="unknown parameter 'nope'"):
        rootlocus.parameter_locus(ej, "nope")
    with pytest.raises(ValueError, match="no linearisation"):
        rootlocus.parameter_locus(ej, "pin_friction")
    with pytest.raises(ValueError, match="speed"):
        rootlocus.parameter_locus(ej, "trail", speed=-1)
    with pytest.raises(ValueError, match="cg_ratio"):
        rootlocus.parameter_locus(ej, "cg_ratio", [1.2])


def test_pin_damping_stabilises_free_casters_at_reference_speed(ej):
    """Viscous pin damping, the linear stand-in for pin friction, lowers the growth rate (chapter 8 trend)."""
    loc = rootlocus.parameter_locus(ej, "pin_damping", [0.0, 0.5, 2.0], speed=0.75)
    assert loc.max_real[0] > loc.max_real[-1]


# ---------------------------------------------------------------------------
# speed loci
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("casters", ["free", "locked"])
def test_speed_locus_matches_linear(ej, casters):
    loc = rootlocus.speed_locus(ej, model="exact", casters=casters, n=200)
    ref = linear.eigenvalues_vs_speed(ej, loc.speeds, "exact", casters, track=True)
    np.testing.assert_allclose(loc.eigenvalues, ref, rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    crit = linear.critical_speeds(lambda U: linear.state_matrices(ej, U, "exact", casters), loc.speeds)
    assert [c.speed for c in loc.crossings] == pytest.approx([c.speed for c in crit], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    if casters == "locked":
        # Figure 8-6: the locked chair turns unstable between 10 and 12.5 m/s (full-width model ~ eq 5-15)
        first = [c.speed for c in loc.crossings if c.direction == "destabilising"][0]
        assert 9.0 < first < 13.5
        iv = loc.unstable_intervals()
        assert iv[0][0] == pytest.approx(first, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


# ---------------------------------------------------------------------------
# gain locus
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("speed", [0.75, 1.5])
def test_gain_locus_at_zero_gain_is_open_loop(ej, speed):
    g = rootlocus.gain_locus(ej, speed, n=60)
    assert g.gains[0] == 0.0
    A = linear.state_matrices(ej, speed)[0]
    lam = np.linalg.eigvals(A)
    # roots of the transfer function's denominator vs the state matrix's eigenvalues
    assert_eigenvalues_match(g.loci[0], lam, B=A, tol_a=_polynomial_roots_bound(g.loci[0], A), what="K = 0")
    assert_eigenvalues_match(g.poles, lam, B=A, tol_a=_polynomial_roots_bound(g.poles, A), what="poles")


def test_gain_locus_equals_closed_loop_eigenvalues(ej):
    """control.root_locus_map's roots of 1 + K G(s) are the eigenvalues of A - K B C_r."""
    g = rootlocus.gain_locus(ej, 0.75, gains=[0.0, 0.5, 2.0, 10.0, 50.0])
    Acl = rootlocus.closed_loop_matrices(ej, 0.75, g.gains)
    for k in range(len(g.gains)):
        lam = np.linalg.eigvals(Acl[k])
        assert_eigenvalues_match(g.loci[k], lam, B=Acl[k], tol_a=_polynomial_roots_bound(g.loci[k], Acl[k]),
                                 what=f"K = {g.gains[k]}")


def test_stabilising_gain(ej):
    g = rootlocus.gain_locus(ej, 0.75)
    if g.stabilising_gain:
        K = g.stabilising_gain
        below = np.linalg.eigvals(rootlocus.closed_loop_matrices(ej, 0.75, [0.98 * K])[0]).real.max()
        above = np.linalg.eigvals(rootlocus.closed_loop_matrices(ej, 0.75, [1.02 * K])[0]).real.max()
        assert below > 0 > above


# ---------------------------------------------------------------------------
# plots: labelled axes, titles naming the chair and model
# ---------------------------------------------------------------------------
def test_locus_plots_are_labelled(ej):
    from matplotlib.figure import Figure

    from stability import plotting

    fig = Figure()
    axes = fig.subplots(2, 2)
    plotting.speed_locus(rootlocus.speed_locus(ej, n=100), axes[0, 0])
    plotting.parameter_locus(rootlocus.parameter_locus(ej, "trail", n=20), axes[0, 1])
    plotting.gain_locus(rootlocus.gain_locus(ej, n=40), axes[1, 0])
    plotting.parameter_locus(rootlocus.parameter_locus(ej, "main_tire"), axes[1, 1])
    for ax in axes.flat:
        assert "(1/s" in ax.get_xlabel() and "(rad/s" in ax.get_ylabel()
    assert "ej-premier" in axes[0, 0].get_title() and "exact" in axes[0, 0].get_title()
    assert "ej-premier" in axes[1, 0].get_title()


@pytest.mark.parametrize("name", ["ej-premier", "ej-premier-front-caster", "power-fwd", "manual-front-caster"])
def test_mode_shape_arm_is_the_axle_to_caster_contact_distance(name):
    """The arm that turns a yaw rate into an angle for the mode names (r l / U) is the distance from the main
    axle to the caster contacts with the casters trailing, taken here from eq 6-24's contact points
    (stability.models.statics) and the axle's signed position, not from the chair's wheelbase property."""
    from stability.linear.names import shape_arm
    from stability.models.params import parameters
    from stability.models.statics import caster_contact_points

    c = preset(name)
    (xa, _), (xb, _) = caster_contact_points(parameters(c))
    assert xa == xb
    # a difference of three stored lengths: exact to a few ulps of the 1 m scale
    assert shape_arm(c) == pytest.approx(abs(c.x_main - xa), rel=0, abs=1e-14)
    far = c.s1 + c.s2 + c.trail           # rear casters trail away from the axle, front ones towards it
    assert shape_arm(c) == pytest.approx(far if c.caster_position == "rear" else far - 2 * c.trail, abs=1e-14)
