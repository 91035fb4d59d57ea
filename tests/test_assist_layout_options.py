"""The assist's options on a wheel layout and in reverse (issue 38): --export-c, --min-torque, -o, --model thesis.

Independent statements used:

- the power chair (``power-fwd``) expanded as a layout (:meth:`stability.layout.Layout.from_chair`) is the short
  form's chair: its firmware tables and its smallest recovering torque limit are the short form's (another
  derivation of the plant, :mod:`stability.layout.linear` against :mod:`stability.linear`, and another simulator,
  the layout kernel with the compiled sampled controller against the short form's with the Python one);
- reverse on a layout is the turned layout (seen from behind, casters swung round) driven forwards
  (:func:`test_assist_layout._turned`): the firmware, a map from the sensors and the joystick to the wheel
  torques, is the same with the speed's sign flipped;
- the exported C, compiled with the system ``cc``, reproduces the Python sampled controller
  (:class:`stability.assist.controller.DigitalController`) on the layout's vectors.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_assist_layout import _turned

from stability.assist import c_harness, digital
from stability.assist.__main__ import main
from stability.assist.commands import COMMAND_FILTER
from stability.assist.export_c import export_c, vector_cases
from stability.assist.firmware import FirmwareController, firmware_tables, mirror_outputs
from stability.assist.layout import layout_design, layout_schedule
from stability.assist.layout_checks import layout_minimum_torque_limit, layout_vector_loop
from stability.assist.quantisation import FLOAT_RELATIVE, table_controller
from stability.assist.recovery import minimum_torque_limit
from stability.assist.schedule import schedule
from stability.assist.weights import EstimatorWeights
from stability.chair import preset
from stability.chair.power import DriveTrain
from stability.layout import Layout
from stability.layout.presets import layout_preset

needs_cc = pytest.mark.skipif(c_harness.find_cc() is None, reason="no system C compiler on this machine")


def test_the_power_chair_as_a_layout_has_the_short_forms_firmware_tables():
    """Every table entry at every grid speed: the same plant from two derivations, the same Riccati solvers and
    matrix exponential; observed 1e-11 of each table's largest entry (the Kalman gain's Riccati solution the
    worst); asserted 1e-9 (margin 100).  The lever, the torque conversion and the filter gains are equal."""
    c = preset("power-fwd")
    mine = firmware_tables(layout_schedule(Layout.from_chair(c), [1.0, 2.0, 3.0]), command_filter_s=COMMAND_FILTER)
    short = firmware_tables(schedule(c, [1.0, 2.0, 3.0], standstill=False), command_filter_s=COMMAND_FILTER)
    for name in short.TABLES:
        a, b = np.asarray(getattr(mine, name)), np.asarray(getattr(short, name))
        assert a.shape == b.shape
        assert np.abs(a - b).max() <= 1e-9 * np.abs(b).max(), name   # error model: two derivations' rounding (docstring)
    for name in ("track", "torque_per_moment", "torque_limit", "bias_gain", "command_gain", "windup_gain"):
        assert getattr(mine, name) == pytest.approx(getattr(short, name), rel=1e-12), name   # rounding: a few eps


def _replay(t_a, t_b, sign: float) -> tuple[float, float]:
    """Largest torque difference and largest torque of the two firmwares on the same sensor rows (speed of ``t_a``
    times ``sign``): a varying speed across the grid, a turning command, a noisy gyro with a bias."""
    rng = np.random.default_rng(1)
    fa, fb = FirmwareController(t_a), FirmwareController(t_b)
    err = top = 0.0
    for k in range(400):
        u = 1.5 + 0.8 * np.sin(k / 50)
        cmd, g = 0.3 * np.sin(k / 30), 0.2 * np.sin(k / 20) + 0.01 * rng.standard_normal()
        ta, tb = fa.step(sign * u, cmd, g, g - 0.01), fb.step(u, cmd, g, g - 0.01)
        err, top = max(err, float(np.abs(ta - tb).max())), max(top, float(np.abs(tb).max()))
    return err, top


@pytest.mark.parametrize("name", ["mid-wheel-drive", "power-fwd-base"])
def test_reversing_firmware_is_the_turned_layouts_driven_forwards(name):
    """With the estimator's process noise vanishing (its Kalman gain the plant's own minimum-energy gain, which
    does not depend on where the noise acts) the two firmwares agree to the Riccati solutions' conditioning:
    observed 1.3e-10 of the largest torque, asserted 1e-7.  With the default noise model they differ by the point
    of the lateral-force noise: the reversing layout's acts at its c.g. as given, the turned layout's at the c.g.
    moved by the casters swung round (``2 m_c l / m``, a few mm): observed 1e-4 of the largest torque, asserted
    1e-2 (margin 100)."""
    lay = layout_preset(name)
    turned = _turned(lay)
    for est, rel in ((EstimatorWeights(lateral_force=1e-9), 1e-7), (EstimatorWeights(), 1e-2)):
        rev = firmware_tables(layout_schedule(lay, [-2.5, -1.5, -0.5], estimator=est), command_filter_s=COMMAND_FILTER)
        fwd = firmware_tables(layout_schedule(turned, [0.5, 1.5, 2.5], estimator=est), command_filter_s=COMMAND_FILTER)
        assert rev.track == pytest.approx(fwd.track, rel=1e-12)     # rounding: the same sum, a few eps
        err, top = _replay(rev, fwd, -1.0)
        assert err <= rel * top, (est, err, top)


@pytest.fixture(scope="module")
def mid_wheel():
    lay = layout_preset("mid-wheel-drive")
    sched = layout_schedule(lay, [0.5, 1.5, 2.5])
    # the command line's 2 s cases (docs/assist.md): the reversing command saturates only after its reversal's
    # transient
    return lay, sched, vector_cases(sched, duration=2.0, closed_loop=layout_vector_loop(lay, sched)), \
        firmware_tables(sched, command_filter_s=COMMAND_FILTER)


def test_the_layouts_firmware_is_its_sampled_controller(mid_wheel):
    """The firmware mirror against :class:`DigitalController` on the layout's vectors: the same float64 operations
    in another order, round-off ~ eps * steps * |terms| (observed ~1e-13 N m); asserted 1e-10 N m.  At a grid speed
    the tables are :func:`stability.assist.digital.discrete_controller`'s matrices (two derivations of the
    discretisation): observed 1e-15 of the largest entry, asserted 1e-10.  The cases exercise what they are named
    for: only the saturating one reaches the torque limit, only the fault case trips the monitor."""
    _, sched, vectors, tables = mid_wheel
    for v in vectors:
        if not v.name.startswith("fault_"):
            # error model: round-off ~ eps * steps * |terms| (docstring), observed ~1e-13 N m
            assert np.max(np.abs(mirror_outputs(tables, v.controller_inputs) - v.controller_tau)) < 1e-10, v.name
        assert bool(np.any(np.abs(v.outputs[:, 0]) >= tables.torque_limit)) == v.name.startswith("saturating")
        fc = FirmwareController(tables)
        for row in v.inputs:
            fc.step(*row)
        assert fc.mode[0] == (1 if v.name.startswith("fault_") else 0), v.name
    for s in (0.5, 2.5):
        a, b = table_controller(tables, s), digital.discrete_controller(sched.at(s), tables.sample_time)
        for x, y in ((a.A, b.A), (a.B, b.B), (a.C, b.C)):
            # error model: two discretisations' rounding, observed 1e-15 of the largest entry
            assert np.max(np.abs(np.asarray(x) - np.asarray(y))) <= 1e-10 * np.max(np.abs(np.asarray(y)))


@needs_cc
@pytest.mark.parametrize("q", ["float", "Q15"])
def test_the_layouts_c_compiles_and_reproduces_the_controller(tmp_path, mid_wheel, q):
    """The C in single precision against the firmware mirror on the vectors' single-precision inputs: within the
    derived tolerance of each case (float: FLOAT_RELATIVE, 1e-5 of the torque limit, for single-precision round-off,
    observed ~1e-6; Q15: the quantisation bound of stability.assist.quantisation plus that)."""
    _, sched, vectors, _ = mid_wheel
    d = tmp_path / q
    info = export_c(sched, str(d), q, vectors=vectors)
    exe = c_harness.compile_replay(str(d), str(tmp_path / f"replay_{q}"))
    doc = json.loads((d / "assist_vectors.json").read_text())
    assert "#define ASSIST_ORDER 11" in (d / "assist.h").read_text()     # v, r, 4 casters x 2, the motor
    for case in doc["cases"]:
        err = float(np.max(np.abs(c_harness.replay(exe, np.array(case["inputs"])) - np.array(case["outputs"]))))
        assert err <= case["tolerance_N_m"], (case["name"], err)
    if q == "float":
        # rounding: the exporter's stated tolerance is this product, computed the same way
        assert all(t == pytest.approx(FLOAT_RELATIVE * sched.drive.torque_limit) for t in info["tolerance_N_m"].values())


def test_the_power_chair_as_a_layout_needs_the_short_forms_smallest_torque():
    """Both bisect to 0.25 N m from the same bracket; the two simulators' torques differ by < 1 % (the held
    command against the 1 ms step, test_assist_layout_checks), so a midpoint within that of the threshold may fall
    either way: asserted one bracket (0.25 N m) plus 1 % (observed: the same bracket, 9.98 N m)."""
    c = preset("power-fwd")
    sched = schedule(c, np.array([2.0]), "gyro")
    short = minimum_torque_limit(sched, 2.0)
    lay = Layout.from_chair(c)
    mine = layout_minimum_torque_limit(lay, layout_design(lay, 2.0, "gyro", drive=sched.drive, gyro=sched.gyro),
                                       sched.drive)
    assert abs(mine - short) <= 0.25 + 0.01 * short     # error model: one bisection bracket plus 1 % (docstring)
    assert 1.0 < short < sched.drive.torque_limit


@pytest.mark.parametrize("name", ["power-fwd-base", "mid-wheel-drive"])
def test_reversing_needs_the_turned_layouts_smallest_torque(name):
    """The full-state design, no motor lag (its gains map exactly, test_assist_layout): the same bisection on two
    descriptions of one chair; the push acts at the c.g. as given, a few mm apart in the two (the casters swung
    round), < 1 % of the torque: asserted one bracket (0.25 N m) plus 1 % (observed: the same bracket, 1.09 and
    1.37 N m)."""
    lay, drive = layout_preset(name), DriveTrain(motor_time_constant=0.0)
    turned = _turned(lay)
    rev = layout_minimum_torque_limit(lay, layout_design(lay, -1.0, "full-state", drive=drive), drive)
    fwd = layout_minimum_torque_limit(turned, layout_design(turned, 1.0, "full-state", drive=drive), drive)
    assert abs(rev - fwd) <= 0.25 + 0.01 * fwd     # error model: one bisection bracket plus 1 % (docstring)


@needs_cc
def test_the_command_exports_a_layout_and_writes_its_figures(tmp_path, capsys):
    """End to end: the command's C reproduces its own vectors (the derived tolerances), the JSON carries the
    firmware block, the PDF is written (one page of gains, the margins and top-speed pages per direction)."""
    fw, pdf, js = tmp_path / "fw", tmp_path / "a.pdf", tmp_path / "a.json"
    assert main(["--chair", "mid-wheel-drive", "--speeds", "0.5,1.5", "--no-check", "--export-c", str(fw),
                 "-o", str(pdf), "--json-file", str(js)]) == 0
    out = capsys.readouterr().out
    assert "Firmware export (float tables, 200 Hz)" in out and f"wrote {pdf}" in out
    assert pdf.read_bytes().startswith(b"%PDF")
    data = json.loads(js.read_text())
    assert data["firmware"]["q_format"] == "float" and data["options"]["export_c"] == str(fw)
    exe = c_harness.compile_replay(str(fw), str(tmp_path / "replay"))
    cases = json.loads((fw / "assist_vectors.json").read_text())["cases"]
    assert {len(c["inputs"]) for c in cases} == {2 * 200 + 1}     # docs/assist.md: 2 s each at 200 Hz
    for case in cases:
        # error model: the exporter's derived float/Q15 rounding tolerance per case
        assert np.max(np.abs(c_harness.replay(exe, np.array(case["inputs"])) - np.array(case["outputs"]))) \
            <= case["tolerance_N_m"]


#: The layout's --min-torque run with the checks, both directions: read by the smallest-torque test and the schema
#: test (``shared_run``: stdout only, one run per worker; the rows of --min-torque do not depend on the checks).
MIN_TORQUE_ARGV = ["--chair", "power-fwd-base", "--speeds", "1", "--reverse", "--min-torque", "--json"]


def test_the_command_gives_the_smallest_torque_each_way(shared_run):
    """--min-torque at each direction's check speed; the JSON's value is the API's (the same call)."""
    status, out, _ = shared_run("assist", MIN_TORQUE_ARGV)
    assert status == 0
    d = json.loads(out)
    rows = d["minimum_torque_limits"]
    assert [r["speed_m_s"] for r in rows] == [1.0, -1.0]
    lay = layout_preset("power-fwd-base")
    want = layout_minimum_torque_limit(lay, layout_design(lay, -1.0, "gyro"), DriveTrain())
    got = rows[1]["minimum_torque_limit_N_m"]
    assert got == ("inf" if want == float("inf") else want)


@pytest.mark.parametrize("argv,words", [
    (["--model", "thesis"], "--model thesis is invalid for a layout or reverse speeds: it is program WCHAIR's"),
    (["--export-c", "fw", "--reverse"], "a table over speed cannot pass through 0 m/s"),
    (["--export-c", "fw", "--speeds=-1,1"], "a table over speed cannot pass through 0 m/s"),
])
def test_what_a_layout_cannot_answer_is_refused_in_one_line(argv, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["--chair", "mid-wheel-drive", *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert not (tmp_path / "fw").exists()


def test_the_layouts_json_matches_its_schema(tmp_path, capsys, shared_run):
    """The layout's output (forward with the checks and --min-torque; reverse alone with the firmware) against
    stability/schemas/assist_layout.json; a renamed key is refused."""
    from stability import schemas

    status, out, _ = shared_run("assist", MIN_TORQUE_ARGV)
    assert status == 0
    a = json.loads(out)
    assert main(["--chair", "power-fwd", "--speeds=-1.5,-0.5", "--no-check", "--json", "--export-c",
                 str(tmp_path / "fw")]) == 0
    b = json.loads(capsys.readouterr().out)
    assert "minimum_torque_limits" in a and "firmware" in b and b["forward"] == []
    for data in (a, b):
        schemas.validate("assist_layout", data)
    b["minimum_torque_N_m"] = b.pop("firmware")
    with pytest.raises(ValueError, match="minimum_torque_N_m"):
        schemas.validate("assist_layout", b)
