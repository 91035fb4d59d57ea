"""Linear results over many chairs and with parameter uncertainty (issue 14)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from numerics import growth_rate_tolerance

from stability import chair as chair_mod
from stability import linear
from stability.chair import preset
from stability.critical_speed import main
from stability.linear.batch import ChairBatch
from stability.linear.intervals import linear_intervals
from stability.uncertainty import loads_uncertainty

EJ = preset("ej-premier")


def test_batch_rates_equal_one_chair_at_a_time():
    chairs = [EJ.replace(m=m, s1=s1) for m, s1 in [(80.0, 0.30), (95.0, 0.345), (120.0, 0.40)]]
    rates = ChairBatch(chairs).growth_rates([0.5, 0.75, 2.0])
    speeds = [0.5, 0.75, 2.0]
    for c, row in zip(chairs, rates, strict=True):
        # two eigenvalue computations of the same matrices; error model: their eigenvalue bounds, n eps ||A|| kappa
        # (tests/numerics.py)
        tol = [growth_rate_tolerance(A) for A in linear.state_matrices(c, speeds)]
        ref = [d.rate for d in linear.divergence(c, speeds)]
        assert np.all(np.abs(np.asarray(row) - ref) <= tol), (row, ref, tol)


def test_batch_locked_critical_speed_equals_zero_width_closed_form():
    """The full-width locked-caster model of a symmetric chair has the zero-width critical speed (eq 5-15),
    sqrt(-g s / k_us), which the bisection over the batch must find to its tolerance."""
    chairs = [EJ.replace(m=m) for m in (80.0, 95.0, 110.0)]
    crit = ChairBatch(chairs).first_critical_speed(np.geomspace(0.01, 30, 300), "locked", xtol=1e-7)
    closed = [linear.zero_width(c).critical_speed for c in chairs]
    # error model: bisection bracket: xtol 1e-7 m/s, two brackets (observed 2.7e-8 m/s; was rtol 1e-6, 1.2e-5 m/s)
    np.testing.assert_allclose(crit, closed, rtol=0, atol=2e-7)


UNC = """
[s1]
distribution = "normal"
std = {s1}
[i_z]
distribution = "normal"
std = {iz}
"""


def test_zero_uncertainty_gives_exactly_the_point_values():
    iv = linear_intervals(EJ, loads_uncertainty(UNC.format(s1=0.0, iz=0.0)), speeds=(0.5, 0.75), samples=20)
    rates = [d.rate for d in linear.divergence(EJ, [0.5, 0.75])]
    tol = [growth_rate_tolerance(A) for A in linear.state_matrices(EJ, [0.5, 0.75])]
    for (lo, hi), r, t in zip(iv.rate, rates, tol, strict=True):
        # error model: the batch's and the single chair's eigenvalue computations, each within n eps ||A|| kappa
        # (tests/numerics.py; observed 2.5e-13 1/s, where rel=1e-13 passed only by approx's default abs 1e-12)
        assert lo == hi and abs(lo - r) <= t
    zw = linear.zero_width(EJ).critical_speed
    assert iv.zero_width_critical[0] == iv.zero_width_critical[1] == pytest.approx(zw, rel=1e-13)  # rounding: equivalent arithmetic, a few ulp (observed 0)


@pytest.mark.slow       # 1000 draws x 600 critical-speed grid speeds: ~6 s; the statistics are also checked by
def test_monte_carlo_matches_delta_method_on_a_nearly_linear_case():   # test_uncertainty's linear-function case
    """Small normal spreads: the rate is nearly linear in s1 and I_z, so the MC 95 % interval equals
    value +- 1.96 sigma of the delta method within sampling error: the 2.5 % quantile of 1000 draws has a
    standard error of sqrt(0.025 * 0.975 / 1000) / phi(1.96) = 0.085 sigma, 2.2 % of the 3.92 sigma width;
    the test allows 8 % (3.6 standard errors)."""
    iv = linear_intervals(EJ, loads_uncertainty(UNC.format(s1=0.002, iz=0.05)), speeds=(0.75,), samples=1000)
    (lo, hi), (dlo, dhi) = iv.rate[0], iv.rate_delta[0]
    width = dhi - dlo
    # error model: the quantiles' standard error, 2.2 % of the width (docstring); 8 % is 3.6 standard errors
    assert abs(lo - dlo) < 0.08 * width and abs(hi - dhi) < 0.08 * width
    assert {n for n, _ in iv.dominant_parameters} == {"s1", "i_z"}


def test_cli_intervals_and_keys(tmp_path, capsys):
    f = tmp_path / "u.toml"
    f.write_text(UNC.format(s1=0.01, iz=0.3))
    assert main(["--uncertainty", str(f), "--samples", "200", "--speeds", "0.5,0.75", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    row = d["free_casters"]["divergence"][1]
    lo, hi = row["rate_1_s_interval"]
    assert lo < row["rate_1_s"] < hi
    assert d["uncertainty"]["samples"] == 200 and d["uncertainty"]["level"] == 0.95
    lo, hi = d["locked_casters"]["critical_speed_m_s_interval"]
    assert lo < d["locked_casters"]["critical_speed_m_s"] < hi
    assert d["free_casters"]["critical_speed_m_s_interval"] == [None, None]
    assert not math.isnan(d["uncertainty"]["dominant_parameters"][0][1])
    # the free casters of the rear-caster E&J Premier: no crossing in any draw, unstable from the slowest speed
    # searched in every one (the thesis's finding); every locked-caster draw has its crossing
    free, locked = d["free_casters"], d["locked_casters"]
    assert (free["critical_speed_exists_fraction"], free["stable_at_all_speeds_fraction"],
            free["unstable_at_the_slowest_speed_fraction"]) == (0.0, 0.0, 1.0)
    assert (locked["critical_speed_exists_fraction"], locked["stable_at_all_speeds_fraction"]) == (1.0, 0.0)


def test_draws_without_a_critical_speed_say_which_end_they_lie_beyond(capsys):
    """The c.g. 16 cm ahead of the main axle: the locked-caster critical speed (zero-width closed form, eq 5-15,
    26.7 m/s nominal) lies beyond the searched 30 m/s in some draws (the zero-width interval's high end is above
    30 m/s).  Those draws are stable at every speed searched, and the text says so beside the share that has a
    crossing; the shares of the three cases add up to 1."""
    from stability.linear import zero_width

    chair, unc = "docs/examples/measured_chair.toml", "docs/examples/measured_chair.uncertainty.toml"
    assert 20.0 < zero_width(chair_mod.load(chair).replace(s1=0.16)).critical_speed < 30.0
    assert main(["--chair", chair, "--uncertainty", unc, "--set", "s1=0.16", "--samples", "300", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    zw_high = d["zero_width"]["critical_speed_m_s_interval"][1]
    locked = d["locked_casters"]
    exists, above, below = (locked["critical_speed_exists_fraction"], locked["stable_at_all_speeds_fraction"],
                            locked["unstable_at_the_slowest_speed_fraction"])
    assert zw_high > 30.0 and 0 < above < 1 and below == 0.0
    assert exists + above == pytest.approx(1.0, abs=1e-12)   # rounding: two shares of 300 draws (observed 0)
    assert main(["--chair", chair, "--uncertainty", unc, "--set", "s1=0.16", "--samples", "300"]) == 0
    text = capsys.readouterr().out
    assert (f"(exists in {100 * exists:.0f} % of draws; stable at every speed searched in {100 * above:.0f} %)"
            in text)


def test_cli_refuses_too_many_samples(tmp_path, capsys):
    f = tmp_path / "u.toml"
    f.write_text(UNC.format(s1=0.01, iz=0.3))
    assert main(["--uncertainty", str(f), "--samples", "10000000"]) == 2
    err = capsys.readouterr().err
    assert "--samples" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("dt, label", [(0.0005, "0.25 ms step"), ("auto", "0.5 ms step")])
def test_the_critical_impulse_step_variant_halves_the_run_s_own_step(dt, label):
    """The step variant multiplies the run's fixed step (``step_factors``, labelled by the step in ms): half of a
    given 0.5 ms is 0.25 ms, and half of ``"auto"``, whose base is 1 ms (RunSpec's dt: "'auto': 1 ms, smaller
    where the step is unstable"), is 0.5 ms.  Short runs (0.5 s, two rounds): only the variants' steps are read."""
    from stability.settings.run import RunSpec
    from stability.study.impulse_intervals import critical_impulse_intervals

    iv = critical_impulse_intervals([preset("ej-premier")], 0.75, run=RunSpec(horizon=0.5, dt=dt),
                                    friction_factors=(), models=("exact",), step_factors=(0.5,), max_rounds=2)[0]
    assert [name for name, _ in iv.variants] == [label]


def test_the_reports_uncertainty_page_says_which_end_draws_without_a_crossing_lie_beyond():
    """The report's uncertainty paragraph states the same shares as the command: a critical speed found in some
    draws, the rest stable at every speed searched; none found, every draw unstable at the slowest speed."""
    from types import SimpleNamespace

    from stability.linear.intervals import LinearIntervals
    from stability.report.sections import uncertainty_text

    iv = LinearIntervals(speeds=(0.75,), level=0.95, samples=100, seed=0, rate=((1.0, 2.0),),
                         rate_delta=((1.0, 2.0),), zero_width_critical=(22.5, 33.9, 1.0),
                         locked_critical=(22.4, 29.7, 0.87), free_critical=(float("nan"), float("nan"), 0.0),
                         dominant_parameters=(("s1", 1.0),), locked_beyond=(0.13, 0.0), free_beyond=(0.0, 1.0))
    d = SimpleNamespace(uncertainty=SimpleNamespace(intervals=iv, spec=SimpleNamespace(source="u.toml"),
                                                    dominant=("s1", 1.0), nonlinear=None))
    crit = next(p for p in uncertainty_text(d) if p.startswith("Critical speeds"))
    assert "locked-caster 22.4-29.7 m/s (exists in 87 % of draws; stable at every speed searched in 13 %)" in crit
    assert "free-caster: none in 0.01-30 m/s in any draw (unstable at the slowest speed in 100 %)" in crit
    assert "zero-width locked-caster 22.5-33.9 m/s (exists in 100 % of draws)" in crit
