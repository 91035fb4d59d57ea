"""The shimmy-free trail band(s): every boundary, against a trail scan and the towed-wheel closed forms."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from stability import chair as chair_mod
from stability.models.statics import static_stiffness
from stability.shimmy.band import TRAIL_SEARCH_M, margin_to_boundaries, shimmy_band
from stability.shimmy.chair import CasterCompliance, caster_wheel, critical_trail

ROOT = Path(__file__).resolve().parents[1]
MEASURED = chair_mod.load(ROOT / "docs" / "examples" / "measured_chair.toml")
# bisection to 2.5 mm / 2^24 = 1.5e-10 m; boundaries asserted to 1e-8 m (x 60)
TOL_M = 1e-8


@pytest.mark.parametrize("c", [MEASURED, chair_mod.preset("power-fwd"), chair_mod.preset("manual-front-caster")],
                         ids=["measured", "power-fwd", "manual-front-caster"])
def test_band_agrees_with_a_trail_scan(c):
    """Each trail of an independent scan (caster_wheel on the changed chair, Routh-Hurwitz on the closed-form
    characteristic polynomial) is stable exactly when it lies in a reported band."""
    speed = 1.0
    band = shimmy_band(c, [speed])
    scan = np.arange(0.004, 0.249, 0.0035)
    for t in scan:
        stable = caster_wheel(c.replace(trail=float(t))).routh_hurwitz(speed).stable
        inside = any(a < t < b for a, b in band.intervals_m[0])
        # error model: bisection bracket: boundaries bisected to 1.5e-10 m; a scan trail within 1e-6 m of one is left
        # undecided (there the abscissa is within rounding of zero for either method)
        near = min((abs(t - x) for x in band.boundaries_m[0]), default=1.0) < 1e-6
        assert near or stable == inside, (t, stable, band.intervals_m)


def test_measured_example_is_a_band_with_two_boundaries():
    """The measured example chair: stable only between ~4.9 and ~21.6 cm (a lower and an upper boundary); the
    old single critical trail reported inf here (user journey, User 1 step 8)."""
    band = shimmy_band(MEASURED, [0.5, 1.0, 2.0])
    for iv, b in zip(band.intervals_m, band.boundaries_m, strict=True):
        assert len(iv) == 1 and len(b) == 2
        assert 0.045 < iv[0][0] < 0.055 and 0.19 < iv[0][1] < 0.24
    assert critical_trail(MEASURED, 1.0) == pytest.approx(band.boundaries_m[1][0], abs=TOL_M)
    assert band.shimmy_margin_m == pytest.approx(MEASURED.trail - band.boundaries_m[0][0], abs=TOL_M)
    # just outside each boundary the caster shimmies, just inside it does not
    for x, sign in ((band.boundaries_m[1][0], 1), (band.boundaries_m[1][1], -1)):
        w_in = caster_wheel(MEASURED.replace(trail=x + sign * 1e-5))
        w_out = caster_wheel(MEASURED.replace(trail=x - sign * 1e-5))
        assert w_in.routh_hurwitz(1.0).stable and not w_out.routh_hurwitz(1.0).stable


def test_rigid_pivot_closed_form_trail_above_relaxation_length():
    """Rigid pivot, relaxation tire, no pin damping (docs/shimmy.md table): stable iff L > sigma, at every speed."""
    c = chair_mod.preset("ej-premier")
    rigid = CasterCompliance(lateral_stiffness=math.inf, lateral_stiffness_range=(math.inf, math.inf),
                             relaxation_length=0.02, relaxation_length_range=(0.02, 0.02))
    band = shimmy_band(c, [0.5, 1.0, 2.0], rigid)
    for iv, b in zip(band.intervals_m, band.boundaries_m, strict=True):
        assert b == pytest.approx((0.02,), abs=TOL_M)
        assert iv[0][1] == pytest.approx(TRAIL_SEARCH_M[1], rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


@pytest.mark.parametrize("speed", [0.5, 1.0, 2.0])
def test_rigid_pivot_with_pin_damping_has_a_shimmy_zone_between_two_closed_form_roots(speed):
    """Rigid pivot, relaxation tire, viscous pin damping c (docs/shimmy.md): stable iff
    (J U + c sigma)(c U + C L^2) > J sigma C L U, J = I_zp: a quadratic in L whose two roots bound a shimmy zone,
    with a stable band below it and one above.  A linear caster tire keeps C independent of the trail's load."""
    c = chair_mod.preset("ej-premier").replace(caster_tire="linear:20", pin_damping=0.05)
    sigma = 0.02
    rigid = CasterCompliance(lateral_stiffness=math.inf, lateral_stiffness_range=(math.inf, math.inf),
                             relaxation_length=sigma, relaxation_length_range=(sigma, sigma))
    J, cd, C, U = c.i_zp, c.pin_damping, static_stiffness(c)["A"], speed
    qa, qb, qc = (J * U + cd * sigma) * C, -J * sigma * C * U, (J * U + cd * sigma) * cd * U
    disc = math.sqrt(qb * qb - 4 * qa * qc)
    roots = sorted(((-qb - disc) / (2 * qa), (-qb + disc) / (2 * qa)))
    band = shimmy_band(c, [speed], rigid)
    assert band.boundaries_m[0] == pytest.approx(tuple(roots), abs=TOL_M)
    (a0, b0), (a1, b1) = band.intervals_m[0]
    assert b0 == pytest.approx(roots[0], abs=TOL_M) and a1 == pytest.approx(roots[1], abs=TOL_M)


def test_margin_sign_and_corners():
    """The margin to the nearest boundary, signed; the band over the compliance corners, and its JSON."""
    assert margin_to_boundaries(0.07, [(0.05, 0.2)], [0.05, 0.2]) == pytest.approx(0.02, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.7e-16)
    assert margin_to_boundaries(0.04, [(0.05, 0.2)], [0.05, 0.2]) == pytest.approx(-0.01, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.7e-16)
    assert margin_to_boundaries(0.04, [(0.001, 0.25)], []) == math.inf
    assert margin_to_boundaries(0.04, [], []) == -math.inf
    band = shimmy_band(MEASURED.replace(trail=0.05), [1.0])
    lo, hi = band.shimmy_margin_interval_m
    assert lo == -math.inf and hi > 0 and band.straddles     # the softest pin shimmies at every trail
    assert band.shimmy_margin_m == pytest.approx(0.05 - band.boundaries_m[0][0], abs=TOL_M)
    assert 0 < band.damping_ratio[0] < 0.01                  # half a millimetre inside: barely damped
    # its JSON has the keys of the hand-written schema of the shimmy command (stability/schemas/shimmy.json), the
    # corners' entries those of the schema's corner
    schema = json.loads((ROOT / "stability" / "schemas" / "shimmy.json").read_text())["else"]["properties"]["shimmy_band"]
    m = band.to_mapping()
    assert set(m) == set(schema["required"]) == set(schema["properties"])
    corner = schema["properties"]["corners"]["items"]
    assert m["corners"] and all(set(c) == set(corner["required"]) for c in m["corners"])


def _shimmy(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "stability.shimmy", *args], capture_output=True, text=True,
                          timeout=300, cwd=ROOT)


def test_cli_prints_the_band_and_the_margin(capsys):
    """The entry point for the text (status 0 from the interpreter); the JSON in this process."""
    from stability.shimmy.__main__ import main

    chair = str(ROOT / "docs" / "examples" / "measured_chair.toml")
    r = _shimmy("--chair", chair, "--set", "trail=0.05", "--speeds", "1")
    assert r.returncode == 0, r.stderr
    band = shimmy_band(MEASURED.replace(trail=0.05), [1.0])
    assert band.describe(0) in r.stdout and ">20" not in r.stdout and "inf" not in r.stdout
    assert f"{band.shimmy_margin_m * 100:.2f} cm inside the shimmy-free band" in r.stdout
    assert "measure pin lateral stiffness and caster relaxation length first" in r.stdout
    # each corner of the estimate ranges: its bands in cm, or in words where it shimmies at every trail (a corner
    # of this chair does: the margin interval below has no low end)
    for c, iv in zip(band.compliance.corners(), band.corner_intervals_m, strict=True):
        words = (f"shimmy-free {', '.join(f'{a * 100:.1f}-{b * 100:.1f}' for a, b in iv[0])} cm" if iv[0]
                 else "no shimmy-free trail")
        assert (f"relaxation {c.relaxation_length * 1000:g} mm, pin stiffness {c.lateral_stiffness / 1000:g} kN/m: "
                f"{words} at 1 m/s") in r.stdout
    assert "no shimmy-free trail at 1 m/s" in r.stdout and "none cm" not in r.stdout
    assert main(["--chair", chair, "--speeds", "0.5,1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["shimmy_band"]
    ref = shimmy_band(MEASURED, [0.5, 1.0])
    assert d["shimmy_margin_m"] == pytest.approx(ref.shimmy_margin_m, abs=1e-15)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert d["shimmy_free_intervals_m"][0] == [list(iv) for iv in ref.intervals_m[0]]
    assert d["shimmy_margin_interval_m"][0] is None        # -inf: a corner shimmies at every trail


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd"])
def test_the_margin_over_several_speeds_is_the_smallest_single_speed_margin(name):
    """The shimmy margin of a band over several use speeds is the worst (smallest) of the margins of the bands at
    each speed alone: the limit must hold at every speed of use.  Viscous pin damping (0.05 N m s/rad) makes the
    boundaries move with speed (without it they do not move for these chairs)."""
    c = chair_mod.preset(name).replace(pin_damping=0.05)
    speeds = [0.5, 1.0, 2.0, 3.0]
    alone = [shimmy_band(c, [u]).shimmy_margin_m for u in speeds]
    assert shimmy_band(c, speeds).shimmy_margin_m == pytest.approx(min(alone), abs=TOL_M)
    assert max(alone) - min(alone) > 10 * TOL_M           # the premise: the speeds disagree


def test_describe_writes_each_band_in_cm_with_a_plus_at_the_search_end():
    """The words of a band are its ends x 100 (cm, one decimal), a '+' only on a band reaching the search end."""
    import dataclasses
    import re

    band = shimmy_band(MEASURED, [1.0])
    end = TRAIL_SEARCH_M[1]
    fake = dataclasses.replace(band, intervals_m=[[(0.0123, 0.0456), (0.0789, end)]])
    text = fake.describe(0)
    numbers = [float(x) for x in re.findall(r"\d+\.\d", text)]
    assert numbers == [1.2, 4.6, 7.9, round(100 * end, 1)]
    assert text.count("+") == 1 and text.endswith("+") and text.count(",") == 1
    assert dataclasses.replace(band, intervals_m=[[]]).describe(0) == "none"
    # the search's own last grid point is its end, exactly: a band found reaching it carries the '+'
    from stability.shimmy.band import GRID_POINTS
    assert np.linspace(*TRAIL_SEARCH_M, GRID_POINTS)[-1] == end
    assert "+" not in dataclasses.replace(band, intervals_m=[[(0.01, np.nextafter(end, 0.0))]]).describe(0)


@pytest.mark.parametrize("c", [MEASURED, chair_mod.preset("ej-premier")], ids=["measured", "ej-premier"])
def test_a_band_core_serves_every_trail_and_coulomb_pin_friction(c):
    """The band search covers every trail of the search range with the chair's own trail replaced, and the linear
    towed wheel has no Coulomb pin friction: a core searched for one chair is the band of another that differs only
    in trail and pin friction (exact: the same arithmetic on the same inputs).  The advisor and its decision tests
    share cores on this."""
    from stability.shimmy.band import band_core

    a = c.replace(trail=0.03, pin_friction_left=0.0, pin_friction_right=0.0)
    b = c.replace(trail=0.09, pin_friction_left=0.3, pin_friction_right=0.25)
    speeds = (0.5, 1.0, 2.0)
    assert shimmy_band(b, speeds, core=band_core(a, speeds)).to_mapping() == shimmy_band(b, speeds).to_mapping()


def test_a_caster_that_does_not_roll_neither_grows_nor_decays():
    """Class: a boundary input no test gave (seed 50: speed 0 in the abscissa's trail-by-speed grid).  The tire's
    lateral forces build up at the rate ``U / sigma`` (relaxation length sigma): at standstill nothing builds up
    or decays, and with no pin damping (the E&J) every eigenvalue of the caster has zero real part, at any
    trail; the same grid's rolling column is the moving caster's own."""
    from stability.chair import preset
    from stability.shimmy.band import abscissa

    c = preset("ej-premier")
    trails = [0.03, 0.05, 0.08]
    got = abscissa(c, trails, [0.0, 1.0])
    # error model: eigenvalues of a 5x5 state matrix with entries up to 1.8e5 (the tire's stiffness over the
    # caster's inertia), rounding n eps ||A|| ~ 2e-10 (observed 2.7e-15): 1e-8, margin 50
    assert np.all(np.abs(got[:, 0]) < 1e-8), got[:, 0]
    assert np.array_equal(got[:, 1], abscissa(c, trails, [1.0])[:, 0])   # exact: the same eigenvalue problem


def test_a_margin_in_words_is_its_value_in_cm_or_what_its_infinity_means():
    """``margin_words``: a finite margin in cm with its sign, 2 decimals (m x 100); +inf (no boundary on the trails
    searched) and -inf (no trail searched is stable) as those statements, with the search range from
    TRAIL_SEARCH_M in cm (1 mm -> 0.1 cm, 0.25 m -> 25 cm)."""
    from stability.shimmy.band import margin_words

    assert TRAIL_SEARCH_M == (0.001, 0.25)
    assert margin_words(0.031426) == "+3.14 cm" and margin_words(-0.0057) == "-0.57 cm"
    assert margin_words(math.inf) == "no shimmy boundary between 0.1 and 25 cm"
    assert margin_words(-math.inf) == "it shimmies at every trail from 0.1 to 25 cm"


def test_the_advisors_measures_keep_the_bands_infinities():
    """The advisor's shimmy margin is the band's, unbounded ends included (an infinity is a value a limit is judged
    on; JSON writes it as null): the E&J Premier's range over the estimates has a corner that shimmies at every
    trail (its low end -inf, as ``shimmy_band`` gives it)."""
    from stability.advise.measures import chair_linear

    chair = chair_mod.preset("ej-premier")
    band = shimmy_band(chair, [1.0])
    sm = chair_linear(chair, speeds=[1.0], cross_slope_deg=0.0, cores={}).shimmy_margin_m
    assert (sm.value, sm.low, sm.high) == (band.shimmy_margin_m, *band.shimmy_margin_interval_m)
    assert sm.low == -math.inf and sm.to_mapping()["interval"][0] is None


def test_a_margin_in_a_table_cell_is_cm_to_two_decimals_or_two_words():
    """``margin_cell``: a finite margin x 100 (cm), signed, 2 decimals unless the caller asks another format; +inf
    (no boundary on the trails searched) is "none found" and -inf (every trail searched shimmies) "every trail"."""
    from stability.shimmy.band import margin_cell

    assert margin_cell(0.031426) == "+3.14" and margin_cell(-0.0057) == "-0.57"
    assert margin_cell(0.031426, ".1f") == "3.1"
    assert margin_cell(math.inf) == "none found" and margin_cell(-math.inf) == "every trail"


@pytest.mark.parametrize("i_zp, m_c", [(1.2 * 0.058**2, 1.2), (0.01, 0.0)], ids=["all-inertia-at-the-cg", "massless-caster"])
def test_a_caster_without_inertia_about_its_centre_is_refused_naming_i_zp_and_its_bound(i_zp, m_c):
    """The caster's yaw inertia about its own centre, ``i_zp - m_c l1^2`` (parallel axes), must be positive with a
    positive caster mass; the refusal names ``i_zp``, its value and the bound ``m_c l1^2`` in kg m^2 (6 significant
    figures), recomputed here from the chair's own fields.  (The chair itself refuses ``i_zp < m_c l1^2``; equality,
    all the caster's mass at its c.g., passes it and is refused here.)"""
    import re

    from stability.shimmy.band import band_core

    c = chair_mod.preset("ej-premier").replace(m_c=m_c, i_zp=i_zp)    # E&J: l1 = 0.058 m, m_c l1^2 = 0.0040 kg m^2
    bound = c.m_c * c.l1 ** 2
    with pytest.raises(ValueError, match=re.escape(
            f"chair parameter i_zp={c.i_zp!r} is invalid for shimmy; valid range: > m_c*l1^2 = {bound:.6g} kg m^2 "
            f"with m_c > 0")):
        band_core(c, [1.0])


def test_an_unbounded_margin_is_a_bound_at_the_searched_trails_nearer_end():
    """margin_bound: a finite margin is itself; with no boundary on the trails searched (1 mm to 25 cm) any
    boundary lies beyond them, so +inf is at least the trail's distance to the nearer end ("above") and -inf at
    most minus it ("below"); a trail beyond the search gets 0; NaN stays missing."""
    from stability.shimmy.band import margin_bound

    assert TRAIL_SEARCH_M == (0.001, 0.25)
    assert margin_bound(0.012, 0.08) == (0.012, "found") and margin_bound(-0.02, 0.08) == (-0.02, "found")
    # rounding: one subtraction of two stored decimals, 1 ulp of 0.25 (2.8e-17); 1e-15 is ~40x that (observed 0)
    assert margin_bound(math.inf, 0.08) == (pytest.approx(0.079, abs=1e-15), "above")   # 8 cm - 1 mm
    assert margin_bound(math.inf, 0.2) == (pytest.approx(0.05, abs=1e-15), "above")     # 25 cm - 20 cm
    assert margin_bound(-math.inf, 0.08) == (pytest.approx(-0.079, abs=1e-15), "below")
    assert margin_bound(math.inf, 0.3) == (0.0, "above")
    v, st = margin_bound(math.nan, 0.08)
    assert math.isnan(v) and st == ""



def test_two_shimmy_free_bands_are_listed_and_the_nearest_boundary_is_the_trails():
    """Viscous pin damping of 0.2 N m s/rad splits the E&J Premier's shimmy-free trails at 0.75 m/s into two
    bands, a sliver near zero and one from about 2.6 cm to the search's end: both are listed, comma-separated,
    and the boundary nearest the 8 cm trail is the second band's lower end, |margin| away (not the sliver's)."""
    band = shimmy_band(chair_mod.preset("ej-premier").replace(pin_damping=0.2), [0.75])
    (a1, b1), (a2, b2) = band.intervals_m[0]
    assert a1 == TRAIL_SEARCH_M[0] and b1 < 0.01 < 0.02 < a2 < band.trail_m and b2 == TRAIL_SEARCH_M[1]
    assert band.describe(0) == f"{a1 * 100:.1f}-{b1 * 100:.1f}, {a2 * 100:.1f}-25.0+"
    assert band.nearest_boundary_m == a2
    # rounding: the same subtraction of the same two floats (0.5 ulp of 0.08, 7e-18), 1e-15 ~ 100x (observed 0)
    assert band.margin_m[0] == pytest.approx(band.trail_m - a2, abs=1e-15)
