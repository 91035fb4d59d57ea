"""Toe on wheel layouts: each fixed wheel's angle (``FixedWheel.angle_deg``), from the short form's ``toe_deg``.

Independent statements used:

- the short form's simulator turns each toed main wheel's contact velocity into its frame and its forces back
  (the thesis engine's SLIP and MECHAN, ``stability.simulate``), and its own linearisation
  (``stability.simulate.linearise``: central differences of the right-hand side it integrates) is a second,
  numerical route to the linear model; the layout's linear model is derived symbolically
  (``derivations/layout.py``: the wheel's slip ``atan(vy' / |vx'|)`` in its turned frame, its force turned back)
  and the layout simulator is another kernel: agreement of the E&J with toe as a layout with the short form, in
  eigenvalues and in a run, checks the derivation, the sign convention (left ``-toe``, right ``+toe``) and the
  wiring at once;
- with linear main tyres (a force independent of load) and the drive holding the speed against the toe's drag
  (no pitch load transfer, no deceleration), the simulator's linearisation has no load-transfer or
  tyre-curvature term that the linear model leaves out, so the two must agree to the finite differences'
  rounding;
- mirror symmetry: toe on a symmetric chair keeps straight running straight.
"""

from __future__ import annotations

import numpy as np
import pytest
from numerics import assert_eigenvalues_match

from stability.chair import preset
from stability.layout import FixedWheel, Layout
from stability.layout.linear import state_matrices
from stability.settings.run import RunSpec
from stability.simulate import simulate
from stability.simulate.layout import simulate_layout
from stability.simulate.linearise import forward_acceleration, linearise

TOE_DEG = 2.0


def _chair(toe: float):
    """The E&J Premier with linear main tyres (its own cornering stiffness at the static load), toe ``toe`` deg, no
    viscous pin damping (the simulator has none)."""
    from stability.layout.statics import cornering_stiffnesses

    c = preset("ej-premier").replace(pin_damping=0.0)
    cw, _ = cornering_stiffnesses(Layout.from_chair(c))
    return c.replace(main_tire=f"linear:{float(cw[0]) * np.pi / 180:.6g}", toe_deg=toe)


def test_the_chair_toe_reaches_each_fixed_wheel():
    lay = Layout.from_chair(preset("ej-premier").replace(toe_deg=1.5))
    assert [w.angle_deg for w in lay.wheels] == [-1.5, 1.5]           # left (y < 0) -toe, right +toe
    with pytest.raises(ValueError, match="angle_deg=60"):
        FixedWheel(0.0, 0.2, angle_deg=60.0)


@pytest.mark.parametrize("speed", [0.5, 1.5, 3.0])
def test_the_layout_linear_model_with_toe_is_the_short_form_simulator_linearised(speed):
    """Eigenvalues of the layout's generated linear model of the E&J with toe equal those of the short-form
    simulator's own linearisation (central differences, step 1e-6: truncation ~ step^2 x third derivatives and
    rounding ~ 1e-16 / step times entries of order 1e4, about 1e-8 1/s; observed at most 2.7e-8 1/s at 0.5 m/s);
    asserted 3e-6 1/s (margin 110).  The toe moves the eigenvalues by much more than that (checked), so the toe terms are tested."""
    c = _chair(TOE_DEG)
    lay = Layout.from_chair(c)
    A = state_matrices(lay, [speed])[0]
    ours = np.sort_complex(np.linalg.eigvals(A))
    # the linear model runs at constant speed: the drive holds it against the toe's drag (the simulator's held
    # drive along each wheel, equal on both: the forward acceleration is linear in it)
    a0, a1 = (forward_acceleration(c, speed, drive=(d, d)) for d in (0.0, 1.0))
    drive = -a0 / (a1 - a0)
    # error model: rounding of the acceleration's sum at the interpolated drive, a few eps of terms below 1 m/s^2
    # (observed 9.3e-18 and 0 m/s^2), x100 and more
    assert abs(forward_acceleration(c, speed, drive=(drive, drive))) <= 1e-14
    theirs = np.sort_complex(np.linalg.eigvals(linearise(c, speed, drive=(drive, drive)).A))
    # error model: truncation of the central differences (step^2) and their rounding (eps / step): about 1e-8 1/s
    # (observed 2.7e-8 1/s at 0.5 m/s, 9e-10 at 1.5 and 3 m/s), x110
    assert np.abs(ours - theirs).max() <= 3e-6
    untoed = np.sort_complex(np.linalg.eigvals(state_matrices(Layout.from_chair(_chair(0.0)), [speed])[0]))
    assert np.abs(untoed - ours).max() > 1e-3


def test_toe_as_a_layout_runs_as_the_short_form_with_toe():
    """The E&J with toe (its real tyres) after the reference push, 3 s: the layout simulator's run equals the
    thesis engine's short-form run (the same scheme, step, tyre law and generated physics; a numeric solve of the
    mass matrix instead of the closed form, about 1e-16 per step amplified by the run's growth, as
    tests/test_layout_slope_run.py; observed at most 6.8e-12, the lateral speed); asserted 1e-9 (rad, m/s)."""
    c = preset("ej-premier").replace(toe_deg=TOE_DEG)
    run = RunSpec(horizon=3.0, stop_on_warnings=False)
    ours = simulate_layout(Layout.from_chair(c), 1.0, run, caster_angles_deg=[0.0, 0.0])
    theirs = simulate(c, 1.0, run)
    assert len(theirs.t) == len(ours.t_s)
    untoed = simulate(c.replace(toe_deg=0.0), 1.0, run)
    assert np.abs(np.asarray(untoed.u) - np.asarray(theirs.u)).max() > 1e-3   # toe drags: it acts
    for mine, ref in ((ours.heading_rad, theirs.heading), (ours.u_m_s, theirs.u), (ours.v_m_s, theirs.v),
                      (ours.caster_angle_rad[0], theirs.eta), (ours.caster_angle_rad[1], theirs.beta)):
        # error model: rounding: ~eps per step grown over the 3 s run (observed at most 6.8e-12 m/s), x150
        assert np.abs(mine - np.asarray(ref)).max() <= 1e-9


def test_symmetric_toe_keeps_straight_running_straight():
    """No push: the symmetric E&J with toe runs straight (the toe forces cancel across the chair); heading and
    caster angles stay at zero to rounding (observed 4.6e-18 rad), while the speed falls (the toe's drag)."""
    c = preset("ej-premier").replace(toe_deg=TOE_DEG)
    r = simulate_layout(Layout.from_chair(c), 1.0, RunSpec(horizon=1.0, push_force=0.0),
                        caster_angles_deg=[0.0, 0.0])
    # error model: rounding: the toe's side forces cancel up to a few eps of their size (observed 4.6e-18 rad)
    assert np.abs(r.heading_rad).max() <= 1e-15
    assert r.u_m_s[-1] < r.u_m_s[0] - 1e-3


def test_toe_in_reverse_is_the_turned_chair_with_toe_forward():
    """The reverse linearisation of the E&J with toe equals the forward one of the chair turned round (a wheel
    turned by 180 deg keeps its angle to the body's axis), as tests/test_layout.py checks without toe; and the
    mirror image (each wheel's angle negated with its ``y``) has the same eigenvalues.  Rounding only: the
    eigenvalues' rounding bounds of tests/numerics.py (observed at most 3.3e-5 of them)."""
    import dataclasses

    lay = Layout.from_chair(preset("ej-premier").replace(toe_deg=TOE_DEG))
    m = lay.m
    dx = sum(c.m_c * 2 * c.l for c in lay.casters) / m
    i_c = lay.i_z + sum(c.m_c * ((c.x + c.l) ** 2 - (c.x - c.l) ** 2) for c in lay.casters)
    turned = Layout("turned", m, i_c - m * dx * dx, lay.h,
                    tuple(dataclasses.replace(w, x=-(w.x - dx), y=-w.y) for w in lay.wheels),
                    tuple(dataclasses.replace(c, x=-(c.x - dx), y=-c.y) for c in lay.casters), lay.g)
    mirror = dataclasses.replace(lay, wheels=tuple(dataclasses.replace(w, y=-w.y, angle_deg=-w.angle_deg)
                                                   for w in lay.wheels))
    for u in (0.5, 2.0):
        a_rev, a_fwd = state_matrices(lay, [-u])[0], state_matrices(turned, [u])[0]
        # error model: rounding: n eps ||A|| kappa_i per eigenvalue and matrix (the turned chair's parameters differ
        # from the reverse's by a few roundings, within the backward error); observed 3.3e-5 of the bound
        assert_eigenvalues_match(np.linalg.eigvals(a_rev), np.linalg.eigvals(a_fwd), a_rev, a_fwd,
                                 what=f"reverse vs turned at {u} m/s")
        a = np.sort_complex(np.linalg.eigvals(state_matrices(lay, [u])[0]))
        b = np.sort_complex(np.linalg.eigvals(state_matrices(mirror, [u])[0]))
        assert np.allclose(a, b, rtol=1e-9)  # rounding: equivalent arithmetic, a few ulp (observed 0)


def test_a_wheel_file_carries_each_fixed_wheels_angle(tmp_path):
    """The ``[[wheel]]`` form reads ``angle_deg`` as any other field: the E&J written out wheel by wheel, with its
    toe as two angles, has the linear model of the short form with that toe expanded (the same numbers: 1e-12)."""
    import dataclasses

    from stability.layout.io import load_layout

    lay = Layout.from_chair(preset("ej-premier").replace(toe_deg=TOE_DEG))
    lines = [f'[body]\nname = "toed"\nm = {lay.m!r}\ni_z = {lay.i_z!r}\nh = {lay.h!r}\n']
    for kind, items in (("fixed", lay.wheels), ("caster", lay.casters)):
        for w in items:
            fields = {f.name: getattr(w, f.name) for f in dataclasses.fields(w) if getattr(w, f.name) is not None}
            body = "\n".join(f"{k} = {v!r}" if not isinstance(v, (str, bool)) else
                             (f'{k} = "{v}"' if isinstance(v, str) else f"{k} = {str(v).lower()}")
                             for k, v in fields.items())
            lines.append(f'[[wheel]]\nkind = "{kind}"\n{body}\n')
    path = tmp_path / "toed.toml"
    path.write_text("\n".join(lines))
    read = load_layout(path)
    assert [w.angle_deg for w in read.wheels] == [-TOE_DEG, TOE_DEG]
    np.testing.assert_allclose(state_matrices(read, [1.0, -1.0]), state_matrices(lay, [1.0, -1.0]), rtol=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
