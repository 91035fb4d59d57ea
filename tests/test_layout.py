"""Any wheel layout (stability.layout, derivations/layout.py): the thesis's chairs as instances, invariants, and
the ordering of the drive layouts.

Independent statements used:

- the thesis's two-wheel-two-caster chair is one layout: its linear matrices (symbolically) and its state
  matrices, static loads and tip angles (numerically) are the thesis model's (``derivations/full_width.py``,
  ``stability.linear``, ``stability.models.statics``, ``stability.tipping``);
- driving backwards is the same chair turned by 180 deg driving forwards, with its centre of mass and yaw
  inertia recomputed for the casters trailing the other way (a rigid motion of the whole problem);
- a mirror image (y -> -y) has the same eigenvalues;
- a caster with no tire force, no mass and a vanishing inertia adds its own fast pin mode and changes nothing else;
- front-wheel-drive power chairs "fishtail" forward, rear-wheel drive is the most stable forward, mid-wheel drive
  in between (issue 38's literature ordering), and reversing turns the order round.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from numerics import assert_eigenvalues_match

from stability.chair import preset, preset_names
from stability.layout import Caster, Layout, analyse_layout, growth_rates, state_matrices, static_loads
from stability.layout.io import load_layout, resolve_layout
from stability.layout.presets import layout_preset, layout_preset_names
from stability.layout.statics import tip_angles
from stability.linear import state_matrices as chair_state_matrices
from stability.models.statics import static_loads as chair_static_loads
from stability.tipping import tip_angles as chair_tip_angles

SPEEDS = np.array([0.25, 0.75, 1.5, 3.0])


@pytest.mark.slow       # about 15 s of sympy
def test_the_thesis_layout_is_the_exact_model_symbolically():
    import sympy as sp

    from derivations import full_width as fw
    from derivations import layout as L

    M, K, Bm, _ = L.linearise(2, 2)
    s, S = L.symbols(2, 2), fw.S
    sub = {s.x_w[0]: S.x_m, s.x_w[1]: S.x_m, s.C_w[0]: S.C_D, s.C_w[1]: S.C_E, s.U: S.U, s.m: S.m, s.i_z: S.i_z,
           s.ca_w[0]: 1, s.ca_w[1]: 1, s.sa_w[0]: 0, s.sa_w[1]: 0}         # the thesis model has no toe
    for k, (y, C) in enumerate(((-S.t1, S.C_A), (S.t2, S.C_B))):
        sub.update({s.x_p[k]: S.x_p, s.y_p[k]: y, s.trail[k]: S.trail, s.l[k]: S.l1, s.m_c[k]: S.m_c,
                    s.i_zp[k]: S.i_zp, s.C_c[k]: C, s.c_pin[k]: S.c_pin})
    for ours, theirs in zip((M, K, Bm), fw.linearise("exact"), strict=True):
        assert (ours.xreplace(sub) - theirs).applyfunc(sp.simplify) == sp.zeros(*theirs.shape)


@pytest.mark.slow
def test_the_generated_layout_module_is_current():
    from pathlib import Path

    from derivations import layout as L

    path = Path(__file__).resolve().parents[1] / "stability" / "_generated" / "layout.py"
    assert path.read_text(encoding="utf-8") == L.render(), "regenerate: python derivations/layout.py"


@pytest.mark.parametrize("name", preset_names())
def test_every_preset_as_a_layout_is_the_thesis_model(name):
    """State matrices to 2e-14 of their size (the same arithmetic in another order: observed 2.1e-16), static
    loads and tip angles to 1e-9 (observed 1e-13)."""
    c = preset(name)
    layout = Layout.from_chair(c)
    A, A0 = state_matrices(layout, SPEEDS), chair_state_matrices(c, SPEEDS)
    assert np.max(np.abs(A - A0)) <= 2e-14 * np.max(np.abs(A0))     # rounding (docstring), x100
    loads = chair_static_loads(c)
    expected = [loads["main_left"], loads["main_right"], loads["caster_left"], loads["caster_right"]]
    assert np.allclose(static_loads(layout), expected, rtol=1e-9, atol=0)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    t0, t = chair_tip_angles(c), tip_angles(layout)
    main, casters = ("forward_deg", "backward_deg") if c.caster_position == "rear" else ("backward_deg", "forward_deg")
    assert t[main] == pytest.approx(t0.toward_main_wheels_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert t[casters] == pytest.approx(t0.toward_casters_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert t["left_deg"] == pytest.approx(t0.lateral_left_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def _turned(layout: Layout) -> Layout:
    """The layout turned by 180 deg about its vertical axis, its casters trailing the other way: what the chair is
    when it drives backwards.  The system c.g. moves with the casters' c.g.s (2 l each) and the yaw inertia about
    the new c.g. follows from the parallel-axis theorem."""
    m = layout.m
    dx = sum(c.m_c * 2 * c.l for c in layout.casters) / m
    dy = 0.0
    i_c = layout.i_z + sum(c.m_c * ((c.x + c.l) ** 2 - (c.x - c.l) ** 2) for c in layout.casters)
    i_new = i_c - m * (dx * dx + dy * dy)
    wheels = tuple(dataclasses.replace(w, x=-(w.x - dx), y=-(w.y - dy)) for w in layout.wheels)
    casters = tuple(dataclasses.replace(c, x=-(c.x - dx), y=-(c.y - dy)) for c in layout.casters)
    return Layout(layout.name + " turned", m, i_new, layout.h, wheels, casters, layout.g)


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd", "mid-wheel-drive", "power-rwd-base"])
def test_reverse_is_the_turned_chair_forward(name):
    """Eigenvalues of the reverse linearisation equal the turned chair's forward ones (observed 2.3e-15 of the
    largest; asserted within numerics' eigenvalue bounds)."""
    layout = layout_preset(name) if name in layout_preset_names() else Layout.from_chair(preset(name))
    turned = _turned(layout)
    for u in SPEEDS:
        A_rev, A_fwd = state_matrices(layout, [-u])[0], state_matrices(turned, [u])[0]
        # error model: n eps ||A|| kappa_i of each matrix (tests/numerics.py); the turned geometry's own rounding
        # perturbs A at the eps ||A|| level, inside the same bound
        assert_eigenvalues_match(np.linalg.eigvals(A_rev), np.linalg.eigvals(A_fwd), A_rev, A_fwd, what=f"{name} {u}")


def test_mirror_image_has_the_same_eigenvalues():
    layout = layout_preset("mid-wheel-drive")
    mirror = dataclasses.replace(layout, wheels=tuple(dataclasses.replace(w, y=-w.y) for w in layout.wheels),
                                 casters=tuple(dataclasses.replace(c, y=-c.y) for c in layout.casters))
    for u in (-1.0, 1.0):
        a = np.sort_complex(np.linalg.eigvals(state_matrices(layout, [u])[0]))
        b = np.sort_complex(np.linalg.eigvals(state_matrices(mirror, [u])[0]))
        assert np.allclose(a, b, rtol=1e-10)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_caster_pair_without_force_or_mass_changes_nothing():
    """The six-wheel equations with the second caster pair stripped of tire force and mass (and a vanishing
    inertia with damping: its own fast pin mode near -c/i) have the four-wheel equations' eigenvalues."""
    from stability.models.layout import linear_layout_matrices

    c = preset("power-fwd")
    four = Layout.from_chair(c)
    from stability.layout.linear import _args

    args4 = _args(four, False)
    ghost = [c.x_pin - 0.1, 0.05, 0.0, 0.0, 1e-7, 0.0, 1e-3]      # x_p, trail, l, m_c, i_zp, C_c, c_pin
    args6 = args4 + tuple(ghost) + tuple(ghost)
    U = np.array([0.75, 2.0])
    for shape, args in (((2, 2), args4), ((2, 4), args6)):
        M, K, Bm, Bf = linear_layout_matrices(shape, False, U, args)
        n = M.shape[1]
        F = np.linalg.solve(M, K)
        A = np.zeros((len(U), 2 * n - 2, 2 * n - 2))
        rows = [0, 1] + [3 + 2 * k for k in range(n - 2)]
        for a, row in enumerate(rows):
            A[:, row, :] = F[:, a, :]
        for k in range(n - 2):
            A[:, 2 + 2 * k, 3 + 2 * k] = 1.0
        ev = np.linalg.eigvals(A)
        if shape == (2, 2):
            base = ev
        else:
            for i in range(len(U)):
                # each ghost adds a pin mode near -c/i = -1e4 1/s and a free swivel angle (a root at 0); error model:
                # rounding: a zero root comes out within n eps ||A|| kappa (||A|| ~3e4: ~4e-11 kappa; observed 0), far
                # below 1e-6 and the chair's slowest root (1.4 1/s). The kept roots: first order in the ghosts'
                # vanishing i_zp = 1e-7 plus that rounding (observed 6.7e-11 relative), x150
                keep = (np.abs(ev[i]) < 1e3) & (np.abs(ev[i]) > 1e-6)
                assert np.sum(np.abs(ev[i]) <= 1e-6) == 2 and np.sum(np.abs(ev[i]) >= 1e3) == 2
                assert np.allclose(np.sort_complex(ev[i][keep]), np.sort_complex(base[i]), rtol=1e-8, atol=1e-8)


def test_drive_layouts_forward_and_in_reverse():
    """Forward: rear-wheel drive (casters ahead) is the most stable, front-wheel drive (casters behind) diverges,
    mid-wheel drive lies between; in reverse the order turns round."""
    g = {n: growth_rates(layout_preset(n), [-1.5, 1.5]) for n in layout_preset_names()}
    fwd, mwd, rwd = g["power-fwd-base"], g["mid-wheel-drive"], g["power-rwd-base"]
    assert fwd[1] > 0 > mwd[1] > rwd[1]
    assert fwd[0] < 0 < mwd[0] < rwd[0]
    s = analyse_layout(layout_preset("power-fwd-base"))
    assert s.forward_critical[1] == "none-unstable" and s.reverse_critical[1] == "none-stable"


def test_mid_wheel_drive_loads_and_the_compliance_rule():
    """Six contacts: the loads balance the weight and the pitch and roll moments about the c.g., and each is its
    wheel's stiffness times the body's (heave + pitch x + roll y) deflection."""
    layout = layout_preset("mid-wheel-drive")
    from stability.layout.statics import contacts

    pts = contacts(layout)
    n = static_loads(layout)
    x = np.array([p[1] for p in pts])
    y = np.array([p[2] for p in pts])
    k = np.array([p[3] for p in pts])
    assert n.sum() == pytest.approx(layout.m * layout.g, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # error model: rounding: the moments of loads solved from these equations, a few eps of the load times the
    # lever arms (~0.3 m; observed 1.4e-17 m of the weight)
    assert abs(n @ x) < 1e-14 * n.sum() and abs(n @ y) < 1e-14 * n.sum()
    deflection = n / k
    coef, *_ = np.linalg.lstsq(np.stack([np.ones_like(x), x, y], axis=1), deflection, rcond=None)
    assert np.allclose(np.stack([np.ones_like(x), x, y], axis=1) @ coef, deflection, rtol=1e-10)  # rounding: equivalent arithmetic, a few ulp (observed 1.6e-15)


def test_a_layout_file_reads_and_refuses_by_name(tmp_path):
    text = """[body]
name = "three"
m = 90.0
i_z = 5.0
h = 0.6

[[wheel]]
kind = "fixed"
x = 0.3
y = -0.25

[[wheel]]
kind = "fixed"
x = 0.3
y = 0.25

[[wheel]]
kind = "caster"
x = -0.2
y = 0.0
"""
    f = tmp_path / "three.toml"
    f.write_text(text)
    layout = load_layout(f)
    assert layout.shape == (2, 1) and resolve_layout(str(f)).name == "three"
    assert np.isfinite(growth_rates(layout, [1.0])).all()
    f.write_text(text.replace('kind = "caster"', 'kind = "swivel"'))
    with pytest.raises(ValueError, match="wheel 3 has kind='swivel'; valid: 'fixed' or 'caster'"):
        load_layout(f)
    f.write_text(text.replace("x = -0.2", "x = -0.2\nspokes = 36"))
    with pytest.raises(ValueError, match=r"wheel 3 \(caster\) has unknown key\(s\) \['spokes'\]"):
        load_layout(f)
    with pytest.raises(ValueError, match="trail"):
        Caster(0.0, 0.0, trail=-1.0)
    with pytest.raises(ValueError, match=r"valid range: 0.01 <= \|U\| <= 20"):
        growth_rates(layout, [0.0])


def test_critical_speed_command_on_a_layout_and_in_reverse(capsys):
    from stability.critical_speed.command import main

    assert main(["--chair", "mid-wheel-drive"]) == 0
    out = capsys.readouterr().out
    assert "mid-wheel-drive: 2 fixed wheel(s) (2 driven), 4 caster(s)" in out and "in reverse" in out
    assert main(["--chair", "ej-premier", "--speeds", "-1,1"]) == 0
    out = capsys.readouterr().out
    g = growth_rates(Layout.from_chair(preset("ej-premier")), [-1.0, 1.0])
    assert f"{g[0]:+17.4f}" in out and f"{g[1]:+17.4f}" in out


@pytest.mark.parametrize("name", ["ej-premier", "power-fwd", "ej-premier-front-caster"])
@pytest.mark.parametrize("cross, grade", [(6.0, 0.0), (-4.0, 3.0), (0.0, -8.0), (10.0, 10.0)])
def test_a_layouts_slope_tip_is_the_short_forms(name, cross, grade):
    """A thesis chair expanded into a layout tips on a combined slope where the short form does: the short form's
    fall line over its own four contacts (``tipping.angles.fall_distance`` of the chair's parameters) against the
    layout's over its wheel list; both solve a one-dimensional minimisation to machine precision (1e-12 deg
    observed), so 1e-9 deg."""
    from stability.layout.statics import slope_tip as layout_slope_tip
    from stability.tipping.angles import slope_tip

    c = preset(name)
    a, b = slope_tip(c, cross, grade), layout_slope_tip(Layout.from_chair(c), cross, grade)
    assert b.tilt_deg == pytest.approx(a.tilt_deg, abs=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert b.fall_direction_deg == pytest.approx(a.fall_direction_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert b.tip_deg == pytest.approx(a.tip_deg, abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_the_tipping_command_answers_a_layout(capsys):
    """``python -m stability.tipping --chair mid-wheel-drive``: the four ISO 7176-1 angles over the outermost
    contacts; on a pure cross slope falling to the right the fall line is the right tip line (so the tip angle is
    the right angle)."""
    import json

    from stability.layout.statics import tip_angles as layout_tips
    from stability.tipping.__main__ import main

    assert main(["--chair", "mid-wheel-drive", "--cross-slope", "6", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    want = layout_tips(layout_preset("mid-wheel-drive"))
    assert {k: doc[k] for k in want} == pytest.approx(want, abs=0)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert doc["slope"]["tip_deg"] == pytest.approx(want["right_deg"], abs=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # --set on a layout by the advisor's names: a higher c.g. tips at the angles of the layout with that c.g.
    assert main(["--chair", "mid-wheel-drive", "--set", "h=0.6", "--json"]) == 0
    high = json.loads(capsys.readouterr().out)
    want_high = layout_tips(dataclasses.replace(layout_preset("mid-wheel-drive"), h=0.6))
    assert {k: high[k] for k in want_high} == pytest.approx(want_high, abs=0)   # exact: JSON's repr round-trips
    assert want_high["forward_deg"] < want["forward_deg"]
    assert main(["--chair", "mid-wheel-drive", "--set", "trail=0.06"]) == 2
    assert "'trail' is not a field of layout 'mid-wheel-drive'" in capsys.readouterr().err


def test_a_short_form_command_refuses_a_layout_by_name():
    """A command that answers the short form only (its chair from ``cli.load_chair``) refuses a layout with one line
    naming it and the commands that answer layouts (not 'unknown chair'); every command listed answers one."""
    from stability.cli import load_chair
    from stability.cli.chairs import LAYOUT_COMMANDS
    from stability.cli.commands import COMMANDS

    with pytest.raises(ValueError) as exc:
        load_chair("mid-wheel-drive", [])
    msg = str(exc.value)
    assert "\n" not in msg and "is a wheel layout" in msg
    for name in LAYOUT_COMMANDS:
        assert name.split()[0] in msg and name.split()[0] in COMMANDS
