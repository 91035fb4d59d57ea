"""stability.uncertainty: parsing, seeded sampling, Monte Carlo vs delta method, zero uncertainty."""

import math

import numpy as np
import pytest
from scipy.stats import norm

from stability import chair as chair_mod
from stability import linear
from stability.uncertainty import delta_method, load_uncertainty, loads_uncertainty, propagate

C = chair_mod.preset("ej-premier")

LINEAR_U = """
[s1]
distribution = "normal"
std = 0.01

[i_z]
distribution = "normal"
std = 0.1
relative = true

[pin_friction_left]
distribution = "uniform"
low = 0.09
high = 0.11
"""
COEF = {"s1": 2.0, "i_z": 0.1, "pin_friction_left": 3.0}


def linear_fn(chairs):
    return np.array([sum(k * getattr(c, n) for n, k in COEF.items()) for c in chairs])


def analytic_sigma():
    sds = {"s1": 0.01, "i_z": 0.1 * C.i_z, "pin_friction_left": 0.02 / math.sqrt(12)}
    return math.sqrt(sum((COEF[n] * sds[n]) ** 2 for n in COEF)), sds


def rate_075(chairs):
    return np.array([linear.divergence(c, [0.75])[0].rate for c in chairs])


def test_parse_and_round_trip(tmp_path):
    u = loads_uncertainty(LINEAR_U + '\n[pin]\nfields = ["pin_friction_right"]\ndistribution = "normal"\nstd = 0.5\n'
                          "relative = true\n")
    assert u.names == ("s1", "i_z", "pin_friction_left", "pin")
    assert u["i_z"].std_value(C.i_z) == pytest.approx(0.56, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.0e-16)
    assert u["pin_friction_left"].std_value(0.1) == pytest.approx(0.02 / math.sqrt(12), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.5e-16)
    path = tmp_path / "u.toml"
    path.write_text(u.dumps())
    assert load_uncertainty(path) == u


@pytest.mark.parametrize("text, word", [
    ('[s9]\ndistribution = "normal"\nstd = 1\n', "s9"),
    ('[s1]\ndistribution = "normal"\nstd = -1\n', "std"),
    ('[s1]\ndistribution = "uniform"\nlow = 2\nhigh = 1\n', "high"),
    ('[s1]\ndistribution = "cauchy"\nstd = 1\n', "distribution"),
    ('[s1]\ndistribution = "normal"\nsigma = 1\n', "unknown key"),
    ('[s1]\ndistribution = "normal"\nstd = 1\n[x]\nfields = ["s1"]\ndistribution = "normal"\nstd = 1\n', "both"),
    ('[name]\ndistribution = "normal"\nstd = 1\n', "name"),
])
def test_parse_errors(text, word):
    with pytest.raises(ValueError, match=word):
        loads_uncertainty(text)


def test_missing_file(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        load_uncertainty(tmp_path / "nope.toml")


def test_seeded_reproducibility_and_independent_streams():
    u = loads_uncertainty(LINEAR_U)
    a = u.sample(C, 50, seed=4)
    b = u.sample(C, 50, seed=4)
    assert a == b
    assert u.sample(C, 50, seed=5) != a
    # adding a table leaves the other tables' draws unchanged
    u2 = loads_uncertainty(LINEAR_U + '[h]\ndistribution = "normal"\nstd = 0.02\n')
    assert [c.s1 for c in u2.sample(C, 50, seed=4)] == [c.s1 for c in a]
    r1 = propagate(C, u, linear_fn, samples=200, seed=9)
    r2 = propagate(C, u, linear_fn, samples=200, seed=9)
    assert (r1.low, r1.high, r1.median) == (r2.low, r2.high, r2.median)


def test_zero_uncertainty_gives_exactly_the_nominal_value():
    u = loads_uncertainty('[s1]\ndistribution = "normal"\nstd = 0.0\n[trail]\ndistribution = "uniform"\n'
                          'low = 0.08\nhigh = 0.08\n[i_z]\ndistribution = "normal"\nstd = 0\nrelative = true\n')
    nominal = rate_075([C])[0]
    r = propagate(C, u, rate_075, samples=20, seed=1)
    assert r.low == r.high == r.median == r.nominal == nominal
    assert r.std == 0.0 and r.dominant_parameters[0][1] == 0.0
    d = delta_method(C, u, rate_075)
    assert d.value == nominal and d.std == 0.0 and d.low == d.high == nominal


def test_monte_carlo_interval_matches_delta_method_on_linear_function():
    u = loads_uncertainty(LINEAR_U)
    sigma, sds = analytic_sigma()
    mean = linear_fn([C])[0] + COEF["pin_friction_left"] * (0.1 - C.pin_friction_left)  # uniform centre 0.1
    d = delta_method(C, u, linear_fn)
    # error model: rounding: central differences of a linear function are exact up to eps |f| over a step of 0.01
    # standard deviations (x100 amplification; observed 1.2e-13), x100
    assert d.std == pytest.approx(sigma, rel=1e-11)
    assert d.value == pytest.approx(mean, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert (d.low, d.high) == pytest.approx((mean - norm.ppf(0.975) * sigma, mean + norm.ppf(0.975) * sigma),
                                            rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 9.9e-15)
    n = 20000
    r = propagate(C, u, linear_fn, samples=n, seed=2)
    # output is nearly normal (two normal terms dominate the variance); the 2.5 % quantile's standard
    # error is sqrt(p (1 - p) / n) / pdf(z) sigma = 0.019 sigma: allow 4 standard errors
    se = math.sqrt(0.025 * 0.975 / n) / norm.pdf(norm.ppf(0.025)) * sigma
    # error model: the quantile's standard error se (above), 4 of them
    assert r.low == pytest.approx(mean - 1.96 * sigma, abs=4 * se)
    assert r.high == pytest.approx(mean + 1.96 * sigma, abs=4 * se)
    # the sample standard deviation's relative standard error is 1/sqrt(2 n) = 0.005 for a normal output: 4 of them
    assert r.std == pytest.approx(sigma, rel=4 / math.sqrt(2 * n))
    # error model: the sample mean's standard error sigma / sqrt(n), 4 of them
    assert r.mean == pytest.approx(mean, abs=4 * sigma / math.sqrt(n))
    shares = {k: (COEF[k] * sds[k]) ** 2 / sigma**2 for k in COEF}
    for k, v in shares.items():
        assert r.shares[k] == pytest.approx(v, abs=0.02)
        assert dict(d.dominant_parameters)[k] == pytest.approx(v, rel=1e-6)
    assert r.dominant_parameters[0][0] == max(shares, key=shares.get) == "i_z"
    assert r.r_squared == pytest.approx(1.0, abs=1e-12)


def test_monte_carlo_vs_delta_on_the_chair_model():
    # small parameter spread: the divergence rate is nearly linear in s1 and trail
    u = loads_uncertainty('[s1]\ndistribution = "normal"\nstd = 0.005\n[trail]\ndistribution = "normal"\n'
                          'std = 0.003\n')
    d = delta_method(C, u, rate_075)
    r = propagate(C, u, rate_075, samples=800, seed=3)
    assert r.std == pytest.approx(d.std, rel=0.1)  # MC std within ~2.5 of its 5 % standard error
    # error model: the median's standard error, sqrt(pi / 2) std / sqrt(n) = 0.044 std, 4 of them, and the rate's
    # curvature second order in the spread (observed 0.083 std)
    se_median = math.sqrt(math.pi / 2) * d.std / math.sqrt(800)
    assert r.median == pytest.approx(d.value, abs=4 * se_median)
    assert r.dominant_parameters[0][0] == d.dominant_parameters[0][0]


def test_shared_draw_and_truncation():
    u = loads_uncertainty('[pin]\nfields = ["pin_friction_left", "pin_friction_right"]\ndistribution = "normal"\n'
                          "std = 0.6\nrelative = true\n")
    c = C.replace(pin_friction_right=0.2)
    chairs = u.sample(c, 400, seed=0)
    ratio = np.array([ch.pin_friction_right / ch.pin_friction_left for ch in chairs])
    assert np.allclose(ratio, 2.0, rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0); one draw shared, relative to each field's own value
    r = propagate(c, u, lambda cs: np.array([ch.pin_friction_left for ch in cs]), samples=400, seed=0)
    assert r.rejected > 0  # N(0.1, 0.06) is negative 5 % of the time: redrawn (truncated)
    assert r.low >= 0
    wide = loads_uncertainty('[pin_friction_left]\ndistribution = "normal"\nmean = -0.1\nstd = 0.01\n')
    with pytest.raises(ValueError, match="invalid chair"):
        wide.sample(C, 50, seed=0)


def test_vector_outputs_and_nan_rows():
    u = loads_uncertainty(LINEAR_U)

    def fn(chairs):
        out = np.array([[c.s1, c.i_z if c.s1 > 0.345 else np.nan] for c in chairs])
        return out

    r = propagate(C, u, fn, samples=2000, seed=1, level=0.9)
    assert r.low.shape == (2,) and r.level == 0.9
    assert r.finite_fraction[0] == 1.0 and 0.4 < r.finite_fraction[1] < 0.6
    # error model: the 5 % quantile's standard error, sqrt(p (1 - p) / n) / pdf(z) x 0.01 m = 4.7e-4 m, 4 of them
    # (observed 9.0e-5 m)
    se = math.sqrt(0.05 * 0.95 / 2000) / norm.pdf(norm.ppf(0.05)) * 0.01
    assert r.low[0] == pytest.approx(C.s1 - norm.ppf(0.95) * 0.01, abs=4 * se)
    with pytest.raises(ValueError, match="level"):
        propagate(C, u, fn, level=95)




def test_propagate_refuses_an_fn_without_one_row_per_chair_naming_the_shape():
    """fn must return one row per chair: a scalar or a wrong first axis is refused in one line naming the shape
    returned and the one required (the nominal chair is evaluated first, alone)."""
    u = loads_uncertainty(LINEAR_U)
    with pytest.raises(ValueError, match=r"^fn returned shape \(3,\); valid: first axis of length 1 "
                                         r"\(one row per chair\)$"):
        propagate(C, u, lambda chairs: np.zeros(3), samples=20, seed=1)
    with pytest.raises(ValueError, match=r"^fn returned shape \(\); valid: first axis of length 1"):
        propagate(C, u, lambda chairs: 1.0, samples=20, seed=1)


def test_shares_of_an_output_that_jumps_by_one_and_of_a_constant_output():
    """Variance shares column by column: an output that is 0 or 1 (a pass/fail, range exactly 1) driven by the pin
    friction alone is ascribed to it by the regression (the two other parameters, independent of it, take what
    their sample correlation gives: SRC^2 of a sampling noise ~1/n each); a constant output has no variance to share
    (every share 0, R^2 undefined)."""
    u = loads_uncertainty(LINEAR_U)
    drawn: list = []

    def fn(chairs):
        drawn[:] = [[getattr(c, n) for n in COEF] for c in chairs]      # the last call: the draws
        return np.array([[1.0 if c.pin_friction_left > 0.1 else 0.0, 7.0] for c in chairs])

    r = propagate(C, u, fn, samples=400, seed=3)
    # R^2 by another route: the squared correlation of the output with its least-squares fit on the raw (not
    # standardised) fields, an affine change of the regressors that leaves the fit's R^2 unchanged.  Error model:
    # two least-squares solutions of a well-conditioned 400 x 4 system, ~1e-13 relative; asserted to 1e-9
    x = np.column_stack([np.asarray(drawn), np.ones(len(drawn))])
    y = np.array([1.0 if row[2] > 0.1 else 0.0 for row in drawn])
    fit = x @ np.linalg.lstsq(x, y, rcond=None)[0]
    assert float(np.asarray(r.r_squared)[0]) == pytest.approx(np.corrcoef(y, fit)[0, 1] ** 2, rel=1e-9)
    jump = {n: float(s[0]) for n, s in r.shares.items()}
    # the other parameters' SRC^2 is a squared sample correlation, ~1/400 each (observed 0.0019 together): 0.9
    # leaves a margin of ~50
    assert jump["pin_friction_left"] > 0.9 and sum(jump.values()) == pytest.approx(1.0, rel=1e-12), jump  # shares normalised: rounding of a 3-term sum, ~1e-16
    assert 0 < float(np.asarray(r.r_squared)[0]) < 1
    assert all(float(s[1]) == 0.0 for s in r.shares.values()) and math.isnan(float(np.asarray(r.r_squared)[1]))


def test_delta_method_ranks_parameters_by_their_share_averaged_over_the_outputs():
    """Two outputs: one linear in the pin friction alone (all its variance from it: share 1), one constant (no
    variance: share 0 for every parameter).  Averaged over the two, the pin friction's share is 1/2 and the other
    parameters' 0."""
    u = loads_uncertainty(LINEAR_U)

    def fn(chairs):
        return np.array([[3.0 * c.pin_friction_left, 7.0] for c in chairs])

    ranked = dict(delta_method(C, u, fn).dominant_parameters)
    assert ranked == pytest.approx({"pin_friction_left": 0.5, "s1": 0.0, "i_z": 0.0}, abs=1e-12)  # shares of exact zeros and one term over itself: rounding only
    assert list(ranked)[0] == "pin_friction_left"


def test_the_regression_needs_one_draw_more_than_its_coefficients():
    """The shares' regression fits p slopes and an intercept: p + 2 finite draws leave one residual degree of
    freedom and are enough (p + 1 fit any data exactly, so R^2 would say nothing, and the column is skipped).  Three
    draws of an output exactly linear in one parameter: its share is 1 and R^2 is 1."""
    from stability.uncertainty.propagation import _regression_shares

    x = {"a": np.array([0.0, 1.0, 2.0])}
    shares, r2 = _regression_shares(x, (2.0 * x["a"] + 1.0)[:, None])
    # error model: a least-squares fit of three exact points, rounding a few eps of values near 1
    assert float(shares["a"][0]) == 1.0 and float(r2[0]) == pytest.approx(1.0, abs=1e-12)
    shares, r2 = _regression_shares({"a": x["a"][:2]}, (2.0 * x["a"][:2] + 1.0)[:, None])
    assert float(shares["a"][0]) == 0.0 and math.isnan(float(r2[0]))


@pytest.mark.parametrize("method", [propagate, delta_method])
def test_a_level_of_one_is_refused(method):
    """A central interval of coverage 1 is the whole real line (the normal quantile of 1 is infinite): both
    propagations refuse it, as they refuse 0, in one line naming the valid range, before calling fn."""
    u = loads_uncertainty(LINEAR_U)
    for level in (1.0, 0.0):
        with pytest.raises(ValueError, match=rf"^level={level!r} is invalid; valid range: 0 < level < 1$"):
            method(C, u, linear_fn, level=level)


def test_delta_method_derivative_at_its_default_step_is_the_analytic_one():
    """The delta method's derivative is a central difference of steps of 0.01 standard deviations (its documented
    default).  For ``f = s1^3`` it is ``((mu + h sigma)^3 - (mu - h sigma)^3) / (2 h) = 3 mu^2 sigma + h^2
    sigma^3``: the analytic first-order contribution ``3 mu^2 sigma`` to a relative ``h^2 sigma^2 / (3 mu^2)``."""
    u = loads_uncertainty(LINEAR_U)
    d = delta_method(C, u, lambda chairs: np.array([c.s1 ** 3 for c in chairs]))
    mu, sigma, h = C.s1, 0.01, 0.01
    truncation = h**2 * sigma**2 / (3 * mu**2)
    # error model: the central difference's truncation at h = 0.01 (2.8e-9 relative) plus the rounding of a
    # difference of cubes near 0.04 over 2 h (about 1e-13 relative); 100 x the truncation
    assert float(d.contributions["s1"]) == pytest.approx(3 * mu**2 * sigma, rel=100 * truncation)


def test_a_parameter_without_spread_is_no_regressor():
    """Class: a degenerate input no test gave (issue 34, seed 50).  A parameter whose distribution has no spread
    (``std = 0``) does not move the chair, so it explains none of the output: its share is exactly 0 (not the
    share its unit draws' chance correlation with the output would get), and in the regression a column that
    does not vary takes no coefficient, so p varying columns still need only p + 2 draws (three exact points of
    a line in the varying one: share 1, R^2 1)."""
    from stability.uncertainty.propagation import _regression_shares

    u = loads_uncertainty(LINEAR_U + '\n[trail]\ndistribution = "normal"\nstd = 0.0\n')
    r = propagate(C, u, linear_fn, samples=40, seed=2)
    assert float(r.shares["trail"]) == 0.0 and sum(float(s) for s in r.shares.values()) == pytest.approx(1.0, rel=1e-12)  # shares normalised: rounding of a 4-term sum, ~1e-16
    x = {"a": np.array([0.0, 1.0, 2.0]), "b": np.array([5.0, 5.0, 5.0])}
    shares, r2 = _regression_shares(x, (2.0 * x["a"] + 1.0)[:, None])
    # error model: a least-squares fit of three exact points, rounding a few eps of values near 1
    assert float(shares["a"][0]) == 1.0 and float(shares["b"][0]) == 0.0 and float(r2[0]) == pytest.approx(1.0, abs=1e-12)


def test_a_result_built_without_its_optional_fields_has_no_parameter_and_no_rejection():
    """The result's optional fields, omitted: an empty dict of shares (the documented type, a dict), no dominant
    parameter, and the dominant parameters are the shares ranked by their mean (the invariant ``propagate`` keeps,
    here of the defaults), no rejected draw."""
    from stability.uncertainty.propagation import PropagationResult

    r = PropagationResult(samples=0, seed=0, level=0.95, low=0.0, high=0.0, median=0.0, mean=0.0, std=0.0,
                          nominal=0.0, finite_fraction=1.0)
    assert isinstance(r.shares, dict) and r.shares == {}
    ranked = tuple(sorted(((n, float(np.mean(s))) for n, s in r.shares.items()), key=lambda kv: -kv[1]))
    assert r.dominant_parameters == ranked == ()
    assert r.rejected == 0
