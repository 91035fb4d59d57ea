"""Chair parameters, presets, TOML round trip, validation and quasi-static loads."""

import math

import numpy as np
import pytest

from stability import chair as chair_mod
from stability.chair import Chair
from stability.models.params import parameters
from stability.models.statics import normal_loads, static_loads


def wchair_statics(c: Chair, FC1, FC2, E, B):
    """Independent transcription of WCHAIR subroutine STATICS (Appendix C, lines 0593-0644)."""
    S1, S2, L, T1, T2, D1, D2, H, M, GR = c.s1, c.s2, c.trail, c.t1, c.t2, c.d1, c.d2, c.h, c.m, c.g
    AX = L * math.cos(E) + S2
    AY = L * math.sin(E) + T1
    BX = L * math.cos(B) + S2
    BY = -L * math.sin(B) + T2
    Z1 = 1.0 / (c.roll_k + 1.0)
    Z2 = 1.0 - Z1
    TERM1 = FC2 * H * Z1 * (S1 + AX) - FC1 * H * AY - M * GR * S1 * AY
    TERM2 = S1 * (AY + BY) + AY * BX + AX * BY
    TERM3 = FC2 * H * (Z2 * S1 / D1 - Z1 * AX / AY) + FC1 * H
    FBZ = -TERM1 / TERM2
    FEZ = (FBZ * (BX + AX * BY / AY) - TERM3) / (S1 * (1.0 + D2 / D1))
    FDZ = FEZ * D2 / D1 + FC2 * H * Z2 / D1
    FAZ = FBZ * BY / AY + FC2 * H * Z1 / AY
    return FAZ, FBZ, FDZ, FEZ


def test_default_chair_is_wchair_block_data():
    """BLOCK DATA (Appendix C lines 1011-1021) and chapter 8 defaults."""
    c = chair_mod.preset("ej-premier")
    assert (c.d1, c.d2, c.s1, c.s2) == (0.265, 0.265, 0.345, 0.175)
    assert (c.l1, c.trail, c.t1, c.t2, c.h) == (0.058, 0.08, 0.24, 0.24, 0.61)
    assert (c.i_z, c.i_zp, c.m, c.m_c, c.g) == (5.6, 0.02, 95.0, 1.2, 9.81)
    assert (c.pin_friction_left, c.pin_friction_right, c.roll_k) == (0.1, 0.1, 1.0)
    assert (c.main_rolling_scale, c.main_lateral_scale, c.caster_rolling_scale, c.caster_lateral_scale) == (0, 1, 0, 1)
    assert c.main_tire == "EJA" and c.caster_position == "rear"
    # eq 8-6: "a value for the ratio ... of 0.66"; rounding of the thesis's 2 decimals (half a unit; observed 0.0035)
    assert c.cg_ratio == pytest.approx(0.66, abs=0.005)


def test_presets():
    """Front-caster chair of chapter 8 (s1, s2 exchanged) and the chapter 9 revised design."""
    assert set(chair_mod.preset_names()) >= {"ej-premier", "ej-premier-front-caster", "revised"}
    f = chair_mod.preset("ej-premier-front-caster")
    assert (f.s1, f.s2, f.caster_position) == (0.175, 0.345, "front")
    assert f.x_main == -0.175 and f.x_pin == 0.345
    r = chair_mod.preset("revised")
    # Figure 9-1: trail 8 -> 6 cm, s1 .345 -> .245, s1+s2 reduced by only 5 cm.
    assert r.trail == 0.06 and r.s1 == 0.245
    assert r.s1 + r.s2 == pytest.approx(0.345 + 0.175 - 0.05, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.2e-16)
    with pytest.raises(ValueError, match="unknown chair preset 'nope'"):
        chair_mod.preset("nope")


def test_toml_round_trip_is_exact(tmp_path):
    c = chair_mod.preset("ej-premier").replace(s1=0.1 + 0.2, camber_deg=2.0, camber_coefficient=0.17,
                                               main_tire="linear:31.5", name='odd "name"')
    path = tmp_path / "chair.toml"
    chair_mod.save(c, path)
    assert chair_mod.load(path) == c
    assert not list(tmp_path.glob("*.tmp"))


@pytest.mark.parametrize("name,value,fragment", [
    ("m", 0.0, "m=0.0"), ("i_z", -1.0, "i_z=-1.0"), ("s1", 0.0, "s1=0.0"), ("trail", -0.01, "trail=-0.01"),
    ("pin_friction_left", -0.1, "pin_friction_left"), ("m", float("nan"), "finite"), ("main_tire", "XYZ", "main_tire"),
    ("caster_position", "middle", "caster_position"), ("i_zp", 0.001, "i_zp"), ("trail", 0.6, "trail=0.6"),
])
def test_validation_names_parameter_value_and_range(name, value, fragment):
    with pytest.raises(ValueError) as info:
        Chair(**{name: value})
    msg = str(info.value)
    assert name in msg and fragment in msg and "valid" in msg


def test_replace_rejects_unknown_field():
    with pytest.raises(ValueError, match="unknown chair parameter"):
        Chair().replace(wheel_size=3)


def test_parse_assignment():
    assert chair_mod.parse_assignment("trail=0.05") == ("trail", 0.05)
    assert chair_mod.parse_assignment("main_tire=AG") == ("main_tire", "AG")
    with pytest.raises(ValueError, match="needs a number"):
        chair_mod.parse_assignment("trail=abc")
    with pytest.raises(ValueError, match="unknown chair parameter 'foo'"):
        chair_mod.parse_assignment("foo=1")


def test_static_loads_eq_6_23():
    """h has no effect without tire forces: loads are W(s2+l)/2s and W s1/2s (eq 6-23, trail included as STATICS does)."""
    c = chair_mod.preset("ej-premier")
    loads = static_loads(c)
    W, s = c.m * c.g, c.s1 + c.s2 + c.trail
    assert loads["main"] == pytest.approx(W * (c.s2 + c.trail) / (2 * s), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert loads["caster"] == pytest.approx(W * c.s1 / (2 * s), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert sum(loads[k] for k in ("main_left", "main_right", "caster_left", "caster_right")) == pytest.approx(W, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


@pytest.mark.parametrize("overrides", [{}, {"d1": 0.2, "t2": 0.3, "roll_k": 2.0}, {"h": 0.4, "trail": 0.05}])
def test_load_transfer_matches_wchair_statics(overrides):
    """Closed-form solution of eq 6-25 == the thesis program's sequential solution (eq 6-27, STATICS)."""
    c = chair_mod.preset("ej-premier").replace(**overrides)
    p = parameters(c)
    rng = np.random.default_rng(1)
    for FC1, FC2, E, B in rng.uniform([-30, -60, -0.5, -0.5], [30, 60, 0.5, 0.5], size=(20, 4)):
        ours = normal_loads(p, FC1, FC2, math.cos(E), math.sin(E), math.cos(B), math.sin(B))
        np.testing.assert_allclose(ours, wchair_statics(c, FC1, FC2, E, B), rtol=1e-11)  # rounding: equivalent arithmetic, a few ulp (observed 5.9e-16)


def test_load_transfer_balances_moments_and_mirrors():
    """Eq 6-25: vertical, pitch and roll balance; a symmetric chair mirrors left/right under Fy -> -Fy."""
    c = chair_mod.preset("ej-premier")
    p = parameters(c)
    fx, fy = 12.0, 35.0
    na, nb, nd, ne = normal_loads(p, fx, fy)
    xa = xb = c.x_pin - c.trail
    assert na + nb + nd + ne == pytest.approx(c.m * c.g, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert xa * na + xb * nb + c.x_main * (nd + ne) == pytest.approx(-c.h * fx, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 9.7e-16)
    assert -c.t1 * na + c.t2 * nb - c.d1 * nd + c.d2 * ne == pytest.approx(-c.h * fy, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 1.7e-16)
    assert nd > ne and na > nb  # a rightward tire force (right turn) loads the left wheels
    ma, mb, md, me = normal_loads(p, fx, -fy)
    np.testing.assert_allclose([ma, mb, md, me], [nb, na, ne, nd], rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_front_caster_loads():
    """Front-caster chair: same load split with s1 and s2 exchanged in roles."""
    c = chair_mod.preset("ej-premier-front-caster")
    loads = static_loads(c)
    W = c.m * c.g
    assert loads["main"] == pytest.approx(W * (c.s2 - c.trail) / (2 * (c.s1 + c.s2 - c.trail)), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 2.0e-16)
    assert loads["main"] + loads["caster"] == pytest.approx(W / 2, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_batch_parameters_vectorise():
    chairs = [chair_mod.preset(n) for n in chair_mod.preset_names()]
    p = parameters(chairs)
    loads = np.array(normal_loads(p))
    for i, c in enumerate(chairs):
        np.testing.assert_allclose(loads[:, i], normal_loads(parameters(c)), rtol=1e-14)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_bad_value_of_a_field_without_unit_is_explained_without_one():
    """The explorer review: roll_k=abc said 'needs a number in - or a number with a unit of the same kind'."""
    with pytest.raises(ValueError, match=r"^chair parameter roll_k needs a number \(it has no unit\), got 'abc'$"):
        chair_mod.parse_assignment("roll_k=abc")
    with pytest.raises(ValueError, match=r"^chair parameter roll_k has no unit; give a plain number \(got '5cm'\)$"):
        chair_mod.parse_assignment("roll_k=5cm")

