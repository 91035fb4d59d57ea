"""Static tip stability (stability.tipping): closed forms, mirror symmetry, slope statics, command line."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from stability import chair as chair_mod
from stability.models import slope as slope_model
from stability.models.params import parameters
from stability.tipping import DIRECTIONS, anti_tip_angle, fall_distance, slope_tip, tip_angles

PRESETS = chair_mod.preset_names()
# Distances are sums of a few products of O(1 m) lengths: rounding ~10 eps m; asserted at 1e-12 m (x >= 100).
TOL_M = 1e-12


def _deg(rho: float, h: float) -> float:
    return math.degrees(math.atan2(rho, h))


@pytest.mark.parametrize("name", PRESETS)
def test_fore_aft_closed_forms(name):
    """Toward the main wheels: tan a = s1/h; toward the casters, casters turned toward the c.g.: (s2 - l)/h."""
    c = chair_mod.preset(name)
    t = tip_angles(c)
    # error model: rounding: an atan of stored lengths, a few ulp of an angle below 90 deg (1.4e-14 deg each); observed 0; 1e-12 deg
    assert t.toward_main_wheels_deg == pytest.approx(_deg(c.s1, c.h), abs=1e-12)
    assert t.toward_casters_deg == pytest.approx(_deg(c.s2 - c.trail, c.h), abs=1e-12)
    assert t.lines["toward_casters"].distance_m == pytest.approx(c.s2 - c.trail, abs=TOL_M)


def test_ej_premier_tips_backwards_near_nine_degrees():
    """The issue's rigid E&J Premier, casters swivelled toward the c.g.: about 9 deg (atan(0.095/0.61) = 8.85)."""
    t = tip_angles(chair_mod.preset("ej-premier"))
    assert t.smallest_direction == "toward_casters"
    # error model: rounding: an atan of stored lengths, a few ulp of an angle below 90 deg (1.4e-14 deg each) (observed 1.8e-15 deg); the casters' angles likewise (observed 0)
    assert t.toward_casters_deg == pytest.approx(math.degrees(math.atan(0.095 / 0.61)), abs=1e-12)
    assert t.lines["toward_casters"].caster_angles_deg == (pytest.approx(180.0, abs=1e-12),
                                                           pytest.approx(180.0, abs=1e-12))


@pytest.mark.parametrize("name", ["ej-premier", "revised"])
def test_lateral_zero_trail_closed_form(name):
    """Zero trail (contacts at the pins): the left tipping line joins (s1, -d1) and (-s2, -t1):
    rho = (d1 s2 + t1 s1) / (s1 + s2) for a rear-caster chair."""
    c = chair_mod.preset(name).replace(trail=0.0, l1=0.0)
    t = tip_angles(c)
    rho_l = (c.d1 * c.s2 + c.t1 * c.s1) / (c.s1 + c.s2)
    rho_r = (c.d2 * c.s2 + c.t2 * c.s1) / (c.s1 + c.s2)
    assert t.lines["lateral_left"].distance_m == pytest.approx(rho_l, abs=TOL_M)
    assert t.lines["lateral_right"].distance_m == pytest.approx(rho_r, abs=TOL_M)


@pytest.mark.parametrize("name", PRESETS)
def test_lateral_matches_brute_force_over_the_swivel_angle(name):
    """The left tipping line joins the left main-wheel contact D and the left caster contact A(eta); the
    distance along -y is minus the line's y at x = 0.  Minimised over eta by Brent's method (independent of
    the closed-form crossings in fall_distance)."""
    c = chair_mod.preset(name)
    xm, xp, l = c.x_main, c.x_pin, c.trail

    def rho(eta: float) -> float:
        xa, ya = xp - l * math.cos(eta), -c.t1 - l * math.sin(eta)
        return -(-c.d1 + (ya + c.d1) * (0.0 - xm) / (xa - xm))

    grid = np.linspace(-math.pi, math.pi, 721)
    k = int(np.argmin([rho(e) for e in grid]))
    best = minimize_scalar(rho, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, 720)]), method="bounded",
                           options={"xatol": 1e-12})
    line = tip_angles(c).lines["lateral_left"]
    # Brent's value at a smooth minimum is within ~eps of it; 1e-9 m is >= 1e4 x that
    assert line.distance_m == pytest.approx(best.fun, abs=1e-9)
    assert math.radians(line.caster_angles_deg[0]) == pytest.approx(
        math.remainder(best.x, 2 * math.pi), abs=1e-4)


@pytest.mark.parametrize("name", PRESETS)
def test_mirror_symmetry(name):
    """Swapping the chair left for right swaps the lateral angles and mirrors the worst caster angles."""
    c = chair_mod.preset(name).replace(d1=0.25, d2=0.29, t1=0.22, t2=0.26)
    m = c.replace(d1=c.d2, d2=c.d1, t1=c.t2, t2=c.t1)
    a, b = tip_angles(c), tip_angles(m)
    # error model: mirror images in exact arithmetic, the same closed forms on swapped lengths: rounding, a few ulp
    # (observed 0); 1e-12 deg
    assert a.lateral_left_deg == pytest.approx(b.lateral_right_deg, abs=1e-12)
    assert a.lateral_right_deg == pytest.approx(b.lateral_left_deg, abs=1e-12)
    assert a.toward_casters_deg == pytest.approx(b.toward_casters_deg, abs=1e-12)
    assert a.lines["lateral_left"].caster_angles_deg[0] == pytest.approx(
        -b.lines["lateral_right"].caster_angles_deg[1], abs=1e-12)
    # the asymmetry (3-4 cm of half-track) moves the angle by 3.8 deg, far beyond the rounding above
    assert a.lateral_left_deg != pytest.approx(a.lateral_right_deg, abs=0.1)


def _uphill_moment(c, key, alpha_deg: float) -> float:
    """Moment (N m) about the tipping line of the normal loads on the contacts off it, from the slope statics.

    ``key``: one of DIRECTIONS, or a fall line ``(ex, ey)`` (unit vector, body axes)."""
    p = parameters(c)
    if isinstance(key, str):
        line = tip_angles(c).lines[key]
        e = {"toward_main_wheels": (np.sign(c.x_main), 0.0), "toward_casters": (-np.sign(c.x_main), 0.0),
             "lateral_left": (0.0, -1.0), "lateral_right": (0.0, 1.0)}[key]
    else:
        e = key
        line = fall_distance(p, *e)
    a = math.radians(alpha_deg)
    g1, g2, gn = c.g * math.sin(a) * e[0], c.g * math.sin(a) * e[1], c.g * math.cos(a)
    ori = [(math.cos(math.radians(x)), math.sin(math.radians(x))) if x is not None else (1.0, 0.0)
           for x in line.caster_angles_deg]
    loads = slope_model.normal_loads(p, 0.0, 0.0, g1, g2, gn, ori[0][0], ori[0][1], ori[1][0], ori[1][1])
    pts = [(p.x_p - p.trail * ori[0][0], -p.t1 - p.trail * ori[0][1]),
           (p.x_p - p.trail * ori[1][0], p.t2 - p.trail * ori[1][1]), (p.x_m, -p.d1), (p.x_m, p.d2)]
    nx, ny = line.normal
    # distance inside the tipping line n.x = rho': positive for contacts uphill of it
    return sum(float(n) * (line.distance_m * (nx * e[0] + ny * e[1]) - (nx * x + ny * y))
               for n, (x, y) in zip(loads, pts, strict=True))


@pytest.mark.parametrize("name", ["ej-premier", "manual-front-caster", "power-fwd"])
@pytest.mark.parametrize("key", DIRECTIONS)
def test_slope_statics_unload_the_uphill_contacts_at_the_tip_angle(name, key):
    """The slope statics' normal loads (models.slope.normal_loads, eq 6-25 on a plane) put zero moment about the
    tipping line on the uphill contacts exactly at the tip angle, positive below it, negative above: the
    uphill contacts' load reaches zero there (fore-aft: their load sum itself, they share one distance)."""
    c = chair_mod.preset(name).replace(d1=0.25, d2=0.28)
    alpha = getattr(tip_angles(c), key + "_deg")
    w = c.m * c.g * 0.5                                   # a moment scale: weight x 0.5 m
    # loads are O(m g) sums of O(1) products: rounding ~100 eps m g; asserted at 1e-10 m g (x >= 1e4)
    assert abs(_uphill_moment(c, key, alpha)) < 1e-10 * w
    assert _uphill_moment(c, key, alpha - 0.1) > 1e-4 * w
    assert _uphill_moment(c, key, alpha + 0.1) < -1e-4 * w


def test_fore_aft_uphill_load_sum_is_zero_at_the_tip():
    """Toward the main wheels the two casters are the uphill contacts; their load sum is zero at atan(s1/h)."""
    c = chair_mod.preset("ej-premier")
    a = math.atan2(c.s1, c.h)
    loads = slope_model.normal_loads(parameters(c), 0.0, 0.0, c.g * math.sin(a), 0.0, c.g * math.cos(a))
    # error model: rounding: O(m g) sums of O(1) products, ~100 eps m g, as above (x >= 1e4)
    assert abs(float(loads[0] + loads[1])) < 1e-10 * c.m * c.g


def test_slope_tip_reduces_to_the_iso_directions():
    c = chair_mod.preset("ej-premier")
    t = tip_angles(c)
    # error model: rounding: an atan of stored lengths, a few ulp of an angle below 90 deg (1.4e-14 deg each); the same closed forms along a fall line of exact direction (observed 0)
    assert slope_tip(c, 5.0).tip_deg == pytest.approx(t.lateral_right_deg, abs=1e-12)
    assert slope_tip(c, -5.0).tip_deg == pytest.approx(t.lateral_left_deg, abs=1e-12)
    assert slope_tip(c, 0.0, 4.0).tip_deg == pytest.approx(t.toward_casters_deg, abs=1e-12)   # uphill ahead
    assert slope_tip(c, 0.0, -4.0).tip_deg == pytest.approx(t.toward_main_wheels_deg, abs=1e-12)
    level = slope_tip(c, 0.0, 0.0)
    assert level.tilt_deg == 0.0 and level.tip_deg == t.smallest_deg
    s = slope_tip(c, 6.0, 3.0)
    # tilt of a plane with cross slope phi and grade theta: cos(tilt) = cos(phi) cos(theta); error model: rounding
    # amplified by acos's conditioning, eps / sin(tilt) = 1.9e-15 rad = 1.1e-13 deg (observed 2.7e-14), x100
    assert s.tilt_deg == pytest.approx(math.degrees(math.acos(math.cos(math.radians(6)) * math.cos(math.radians(3)))),
                                       abs=1.1e-11)
    g1, g2, _ = slope_model.gravity(c.g, math.radians(6.0), math.radians(3.0))
    e = (g1 / math.hypot(g1, g2), g2 / math.hypot(g1, g2))
    # error model: rounding of an atan2 of the same gravity components (observed 0)
    assert s.fall_direction_deg == pytest.approx(math.degrees(math.atan2(e[1], e[0])), abs=1e-12)
    w = c.m * c.g * 0.5          # the slope statics unload the uphill contacts at this tilt (as below)
    # error model: rounding: O(m g) sums of O(1) products, ~100 eps m g (x >= 1e4)
    assert abs(_uphill_moment(c, e, s.tip_deg)) < 1e-10 * w
    assert _uphill_moment(c, e, s.tip_deg - 0.1) > 1e-4 * w
    assert _uphill_moment(c, e, s.tip_deg + 0.1) < -1e-4 * w
    assert s.margin_deg == s.tip_deg - s.tilt_deg              # the same difference


def test_anti_tip():
    c = chair_mod.preset("manual-front-caster")
    assert anti_tip_angle(c) is None and tip_angles(c).anti_tip_deg is None
    flat = c.replace(anti_tip_reach=0.2)
    # error model: rounding: an atan of stored lengths, a few ulp of an angle below 90 deg (1.4e-14 deg each) (observed 3.6e-15)
    assert anti_tip_angle(flat) == pytest.approx(_deg(c.s1 + 0.2, c.h), abs=1e-12)   # touching: a longer base
    raised = c.replace(anti_tip_reach=0.2, anti_tip_clearance=0.05)
    assert tip_angles(c).toward_main_wheels_deg < anti_tip_angle(raised) < anti_tip_angle(flat)
    high = c.replace(anti_tip_reach=0.05, anti_tip_clearance=0.4)   # catches it only past its balance point
    assert anti_tip_angle(high) == pytest.approx(tip_angles(c).toward_main_wheels_deg, abs=1e-12)   # rounding


def test_fall_distance_sign_when_the_casters_can_swing_past_the_cg():
    """Front casters with trail longer than s2 reach behind the c.g.: a negative distance, tips on level ground."""
    c = chair_mod.preset("manual-front-caster")
    short = c.replace(s2=c.trail * 0.5 + 0.001, trail=c.trail)
    p = parameters(short)
    ln = fall_distance(p, 1.0, 0.0)
    assert ln.distance_m == pytest.approx(short.s2 - short.trail, abs=TOL_M)
    assert ln.angle_deg < 0


def _run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "stability.tipping", *args], capture_output=True, text=True,
                          timeout=120)


def test_cli_json_and_errors(capsys):
    """The entry point for the JSON (status 0 from the interpreter); the error and the text in this process."""
    from stability.tipping.__main__ import main

    r = _run("--chair", "revised", "--cross-slope", "6", "--grade", "2", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    for k in ("stability_version", "chair_parameters", "model", "options"):
        assert k in d
    t = tip_angles(chair_mod.preset("revised"))
    for k in DIRECTIONS:
        assert d[k + "_deg"] == pytest.approx(getattr(t, k + "_deg"), rel=1e-12)   # exact: JSON round trip
    assert d["static_stability_deg"] == t.smallest_deg                                 # (repr is exact)
    assert d["slope"]["tip_deg"] == slope_tip(chair_mod.preset("revised"), 6, 2).tip_deg
    assert main(["--cross-slope", "60"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--cross-slope" in err
    assert main(["--chair", "ej-premier"]) == 0
    out = capsys.readouterr().out
    assert "toward the casters" in out and "8.9 deg" in out


def test_derivation_statements_and_the_anti_tip_closed_form():
    """derivations/tipping.py checks its four statements symbolically; its anti-tip closed form, evaluated,
    is what anti_tip_angle gives."""
    from pathlib import Path

    import sympy as sp
    root = Path(__file__).resolve().parents[1]
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    from derivations import tipping as dt

    dt.gravity_line_foot()
    dt.moment_about_tipping_line()
    dt.least_stable_swivel()
    closed = dt.anti_tip()
    c = chair_mod.preset("manual-front-caster").replace(anti_tip_reach=0.15, anti_tip_clearance=0.01)
    sym = {str(s): s for s in closed.free_symbols}
    val = float(closed.subs({sym["s1"]: c.s1, sym["h"]: c.h, sym["reach"]: 0.15, sym["clearance"]: 0.01}))
    assert math.atan(val) > math.atan2(c.s1, c.h)                 # caught before it goes over
    # error model: rounding of sympy's float evaluation and the atan, a few ulp (observed 0)
    assert anti_tip_angle(c) == pytest.approx(math.degrees(math.atan(val)), abs=1e-12)
    assert isinstance(closed, sp.Expr)


@pytest.mark.parametrize("theta_deg", [0.0, 20.0, 75.0, 135.0, 200.0, 290.0])
def test_fixed_contacts_fall_distance_is_the_ray_to_the_support_polygon(theta_deg):
    """Fixed contacts only (r = 0), an asymmetric triangle: the distance along the fall line is where the ray from
    the c.g.'s foot point leaves the triangle (ray against each edge, solved here by Cramer's rule)."""
    from stability.tipping.angles import support_fall_distance

    tri = [(0.31, -0.22), (0.44, 0.37), (-0.27, 0.05)]
    th = math.radians(theta_deg)
    e = (math.cos(th), math.sin(th))
    hits = []
    for (px, py), (qx, qy) in zip(tri, tri[1:] + tri[:1], strict=True):
        # rho e = P + u (Q - P): [e, P - Q] [rho, u]^T = P
        det = e[0] * (py - qy) - e[1] * (px - qx)
        rho = (px * (py - qy) - py * (px - qx)) / det
        u = (e[0] * py - e[1] * px) / det
        if rho > 0 and 0.0 <= u <= 1.0:
            hits.append(rho)
    assert len(hits) == 1
    h = 0.55
    got = support_fall_distance([(x, y, 0.0) for x, y in tri], h, *e)
    assert got.distance_m == pytest.approx(hits[0], abs=TOL_M)
    # error model: rounding of Cramer's rule and the atan, a few ulp (observed 7.1e-15 deg), margin 140
    assert got.angle_deg == pytest.approx(_deg(hits[0], h), abs=1e-12)


def test_fall_line_is_a_frozen_value():
    """A FallLine is a value (settings and results travel as frozen objects): no field can be reassigned."""
    import dataclasses

    from stability.tipping.angles import support_fall_distance

    line = support_fall_distance([(0.3, -0.2, 0.0), (0.3, 0.2, 0.0), (-0.2, 0.0, 0.0)], 0.5, 1.0, 0.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        line.distance_m = 1.0  # type: ignore[misc]


@pytest.mark.parametrize("seed", range(12))
def test_the_tipping_distance_is_the_minimum_over_every_tipping_line_by_brute_force(seed):
    """support_fall_distance finds the tipping line from the pairwise intersections (closed-form roots); checked
    against a brute-force minimum of the same support function f(t) = max_k (a_k + t b_k - r_k sqrt(1 + t^2))
    over a dense grid of line directions refined by bounded Brent, on random supports around the c.g. (3-6
    contacts, some casters).  Error model: Brent's xatol 1e-12 on t, f Lipschitz with constant < 2 m: the
    brute-force value is within 1e-11 m of the minimum it brackets; observed differences 1e-16-1e-13 m;
    asserted 1e-9 m."""
    from stability.tipping.angles import support_fall_distance

    rng = np.random.default_rng(seed)
    n = int(rng.integers(3, 7))
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False) + rng.uniform(-0.3, 0.3, n) + rng.uniform(0, 2 * np.pi)
    radii = rng.uniform(0.2, 0.5, n)
    trails = np.where(rng.random(n) < 0.5, rng.uniform(0.02, 0.06, n), 0.0)
    points = [(float(rr * np.cos(t)), float(rr * np.sin(t)), float(tr)) for rr, t, tr in
              zip(radii, angles, trails, strict=True)]
    phi = rng.uniform(0, 2 * np.pi)
    ex, ey = float(np.cos(phi)), float(np.sin(phi))
    a = np.array([x * ex + y * ey for x, y, _ in points])
    b = np.array([-x * ey + y * ex for x, y, _ in points])
    r = np.array([p[2] for p in points])

    def f(t):
        return float(np.max(a + t * b - r * np.sqrt(1.0 + t * t)))

    grid = np.linspace(-30.0, 30.0, 60001)
    values = np.max(a[:, None] + grid[None, :] * b[:, None] - r[:, None] * np.sqrt(1.0 + grid**2)[None, :], axis=0)
    k = int(np.argmin(values))
    res = minimize_scalar(f, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]), method="bounded",
                          options={"xatol": 1e-12})
    brute = min(float(res.fun), float(values[k]))
    got = support_fall_distance(points, 0.5, ex, ey)
    # error model: the brute-force bracket (Brent's xatol 1e-12 on t, f Lipschitz < 2 m: 1e-11 m; observed
    # 1e-16-1e-13 m), x100
    assert got.distance_m == pytest.approx(brute, abs=1e-9)


def test_contacts_on_the_fall_line_alone_tip_about_the_line_normal_to_it():
    """Two fixed contacts on the fall line (no pair gives an intersection: the candidate set is empty): the
    tipping line passes through the farther one, normal to the fall line, whatever direction would give the same
    distance."""
    from stability.tipping.angles import support_fall_distance

    got = support_fall_distance([(0.3, 0.0, 0.0), (-0.2, 0.0, 0.0)], 0.5, 1.0, 0.0)
    # error model: exact: t = 0 gives these values with no rounding but the final atan2/degrees (a few ulp)
    assert got.distance_m == pytest.approx(0.3, abs=1e-15)
    assert got.normal == pytest.approx((1.0, 0.0), abs=1e-15)
    assert got.angle_deg == pytest.approx(math.degrees(math.atan2(0.3, 0.5)), abs=1e-12)


def test_the_slope_tip_json_keys_are_its_fields():
    """SlopeTip.to_mapping: one key per field, named as the field (snake_case with the unit suffix)."""
    import dataclasses

    tip = slope_tip(chair_mod.preset("ej-premier"), 5.0, 2.0)
    mapping = tip.to_mapping()
    assert list(mapping) == [f.name for f in dataclasses.fields(tip)]
    assert all(mapping[k] == getattr(tip, k) for k in mapping)


def test_a_tipping_line_through_a_wheel_tangent_to_a_caster_offset_by_its_trail():
    """Class: a branch for an input no random draw gives (seed 50: the pair whose quadratic degenerates).  A wheel
    at (1.0, 0.02) m and a caster pin at (1.2, -0.03) m with a 5 cm trail: across the fall line (+x) they are
    exactly one trail apart, so the pair's equation for the tipping line is linear, not quadratic.  The line
    through the wheel tangent to the caster's circle has the normal (8, 15)/17 (distance from the pin: (8 x 0.2
    - 15 x 0.05)/17 = 0.05 m, the trail), and meets the fall line at 1.0 + (15/8) 0.02 = 1.0375 m; with the rear
    wheels at (-0.3, +-0.25) m it is the tipping line, the caster on it pointing along its normal."""
    from stability.tipping.angles import support_fall_distance

    got = support_fall_distance([(1.0, 0.02, 0.0), (1.2, -0.03, 0.05), (-0.3, 0.25, 0.0), (-0.3, -0.25, 0.0)],
                                0.5, 1.0, 0.0)
    # error model: a few roundings of values about 1 (the offsets 0.02 and -0.03 m are not exact binary
    # fractions): ~1e-15; 1e-12, margin ~1000
    assert got.distance_m == pytest.approx(1.0375, abs=1e-12)
    assert got.normal == pytest.approx((8 / 17, 15 / 17), abs=1e-12)
    assert got.caster_angles_deg[0] == pytest.approx(math.degrees(math.atan2(15.0, 8.0)), abs=1e-9)  # error model: the normal's rounding, 1e-12 rad, in degrees x57: 6e-11


def test_the_rear_stability_reference_is_the_mean_docs_cite_from_loane_and_kirby():
    """Class: a cited constant no test read (seed 34).  The reference printed beside the angles is Loane & Kirby's
    (1985) mean rear stability, as docs/tipping.md quotes the paper: "mean rear stability 28.6 (SD 2.7) deg"."""
    import re
    from pathlib import Path

    from stability.tipping import LOANE_KIRBY_REAR_DEG

    page = (Path(__file__).resolve().parents[1] / "docs" / "tipping.md").read_text(encoding="utf-8")
    quoted = re.search(r"mean rear stability (\d+\.\d) \(SD", " ".join(page.split()))
    assert quoted and LOANE_KIRBY_REAR_DEG == float(quoted.group(1))


@pytest.mark.parametrize("name", ["ej-premier", "revised"])
def test_the_json_tipping_lines_give_each_angle_by_the_tilt_closed_form(name):
    """Class: JSON keys no test read (seed 34: a line's distance and normal, the least stable direction).  A rigid
    chair tilted about a tipping line tips when its c.g. passes over the line: ``tan(angle) = distance / h``, with
    ``distance`` the c.g.'s horizontal distance to the line; each line's normal is a unit vector in the ground
    plane; and the least stable direction is the one with the smallest of the four angles, read from the JSON."""
    c = chair_mod.preset(name)
    m = json.loads(json.dumps(tip_angles(c).to_mapping()))
    assert set(m["tipping_lines"]) == set(DIRECTIONS)
    for k, line in m["tipping_lines"].items():
        # error model: atan of a ratio of two stored lengths, rounding ~1e-16 relative; 1e-12 leaves a margin of 1e4
        assert m[k + "_deg"] == pytest.approx(math.degrees(math.atan(line["distance_m"] / c.h)), rel=1e-12), k
        assert math.hypot(*line["normal"]) == pytest.approx(1.0, abs=1e-12), k     # error model: as above
    assert m["least_stable_direction"] == min(DIRECTIONS, key=lambda k: m[k + "_deg"])
    assert m["static_stability_deg"] == m[m["least_stable_direction"] + "_deg"]
