"""Firmware export of the gyro assist: the numpy mirror, the C (compiled with the system cc), the quantisation bound."""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from stability import assist
from stability import chair as chair_mod
from stability.assist import c_harness, digital
from stability.assist.__main__ import main as assist_main
from stability.assist.commands import COMMAND_FILTER
from stability.assist.export_c import export_c, vector_cases
from stability.assist.firmware import FirmwareController, firmware_tables, half_steps, mirror_outputs, quantise
from stability.assist.quantisation import FLOAT_RELATIVE, margin_rows, output_bound, table_controller

CC = c_harness.find_cc()
needs_cc = pytest.mark.skipif(CC is None, reason="no system C compiler (cc, gcc, clang or $CC) on this machine")


@pytest.fixture(scope="module")
def sched():
    return assist.schedule(chair_mod.preset("power-fwd"), [1.0, 2.0, 3.0], "gyro")


@pytest.fixture(scope="module")
def vectors(sched):
    # 0.6 s per case keeps the default run short; the CLI writes 2 s cases
    return vector_cases(sched, duration=0.6)


@pytest.fixture(scope="module")
def tables(sched):
    return firmware_tables(sched, command_filter_s=COMMAND_FILTER)


def test_mirror_is_the_python_sampled_controller(vectors, tables):
    # same float64 operations in another order: round-off ~ eps * steps * |terms| (~1e-13 N m observed over 200
    # samples of up to 70 N m); 1e-10 N m keeps a margin of ~1000
    normal = [v for v in vectors if not v.name.startswith("fault_")]
    for v in normal:
        assert np.max(np.abs(mirror_outputs(tables, v.controller_inputs) - v.controller_tau)) < 1e-10, v.name
    # the cases exercise what they are named for: the saturating one saturates, the others do not; the
    # monitor stays quiet in every case but the fault case, where it trips (gyro at fault: mode 1)
    lim = tables.torque_limit
    for v in vectors:
        sat = np.any(np.abs(v.outputs[:, 0]) >= lim)
        assert sat == v.name.startswith("saturating"), v.name
        assert np.array_equal(v.outputs[:, 1], -v.outputs[:, 0])
        fc = FirmwareController(tables)
        for row in v.inputs:
            fc.step(*row)
        assert fc.mode[0] == (1 if v.name.startswith("fault_") else 0), v.name


def test_tables_at_a_grid_speed_are_the_sampled_controller_of_digital(sched, tables):
    # two derivations of the discretised controller: DigitalController's (read into the tables) and
    # digital.discrete_controller's; both exponentiate the same matrix, so they agree to round-off (~1e-15
    # relative to the entries, observed); 1e-10 of the largest entry
    for s in (1.0, 2.0):
        a = table_controller(tables, s)
        b = digital.discrete_controller(sched.at(s), tables.sample_time)
        for x, y in ((a.A, b.A), (a.B, b.B), (a.C, b.C)):
            x, y = np.asarray(x), np.asarray(y)
            assert np.max(np.abs(x - y)) <= 1e-10 * np.max(np.abs(y))


def test_quantisation_bound_holds_sample_by_sample_and_is_not_vacuous(vectors, tables):
    lim = tables.torque_limit
    for q in ("Q15", "Q31"):
        tq, ints = quantise(tables, q)
        bits = 15 if q == "Q15" else 31
        for name, arr in ints.items():           # every integer fits its signed word
            assert np.all(np.abs(arr) <= 2 ** bits - 1), (q, name)
        for name, h in half_steps(tq).items():   # the rounding is within half a step
            assert np.all(np.abs(getattr(tq, name) - getattr(tables, name)) <= h * (1 + 1e-12)), (q, name)
        for v in (vectors[1::2] if q == "Q15" else vectors[3::4]):    # Q31: the saturating cases
            bound = output_bound(tables, tq, v.inputs)
            err = np.abs(mirror_outputs(tq, v.inputs) - v.outputs[:, 0])
            # the bound is exact arithmetic on the same sums the runs make: 1e-12 of full scale for round-off
            assert np.all(err <= bound + 1e-12 * lim), (q, v.name, float(np.max(err - bound)))
            assert np.max(bound) < (2e-3 if q == "Q15" else 1e-6) * lim, (q, v.name, float(np.max(bound)))


def _check_c(tmp_path, sched, vectors, q):
    d = tmp_path / q
    info = export_c(sched, str(d), q, vectors=vectors)
    doc = json.loads((d / "assist_vectors.json").read_text())
    assert doc["sample_rate_hz"] == pytest.approx(200.0, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert set(os.listdir(d)) == {"assist.h", "assist.c", "assist_vectors.json", "README.txt"}
    src = (d / "assist.c").read_text()
    assert "malloc" not in src and "double" not in src
    exe = c_harness.compile_replay(str(d), str(tmp_path / f"replay_{q}"))
    worst = 0.0
    for case in doc["cases"]:
        out = c_harness.replay(exe, np.array(case["inputs"]))
        ref = np.array(case["outputs"])
        err = float(np.max(np.abs(out - ref)))
        assert err <= case["tolerance_N_m"], (q, case["name"], err, case["tolerance_N_m"])
        worst = max(worst, err / case["tolerance_N_m"])
    return info, worst


@needs_cc
def test_float_export_compiles_and_reproduces_the_vectors(tmp_path, sched, vectors):
    # the float tolerance: 1e-5 relative (here of full scale, the torque limit); observed <= 1.2e-6
    info, worst = _check_c(tmp_path, sched, vectors, "float")
    assert all(t == pytest.approx(FLOAT_RELATIVE * sched.drive.torque_limit, rel=1e-12) for t in info["tolerance_N_m"].values())  # rounding: equivalent arithmetic, a few ulp (observed 0)
    assert worst < 0.5


@needs_cc
def test_q15_export_compiles_and_stays_within_the_derived_bound(tmp_path, sched, vectors):
    info, worst = _check_c(tmp_path, sched, vectors, "Q15")
    assert "int16_t" in (tmp_path / "Q15" / "assist.c").read_text()
    assert worst < 1.0


def test_quantised_schedule_margins_against_the_ideal_one(sched, tables):
    rows = margin_rows(sched, tables, speeds=[2.0, 2.5])
    grid, mid = rows
    # at a grid speed the float tables are the design: margins equal to round-off of the margin search
    for k in ("gain_db", "phase_deg", "delay_ms"):
        assert grid.margins["float"][k] == pytest.approx(grid.margins["ideal"][k], rel=1e-9)
        # Q15 rounds each entry by 2**-16 of its range: the margins move by far less than their displayed digits
        assert abs(grid.margins["Q15"][k] - grid.margins["ideal"][k]) < 1e-2
    # half-way between grid speeds the tables are interpolated: a small, nonzero difference
    assert 0 < abs(mid.margins["float"]["phase_deg"] - mid.margins["ideal"]["phase_deg"]) < 1.0


def test_scheduled_speed_input_interpolates_between_grid_tables(tables):
    fc = FirmwareController(tables, runs=3)
    mid = fc.tables_at([1.0, 1.5, 2.0])
    for tab in mid:
        assert np.allclose(tab[1], 0.5 * (tab[0] + tab[2]), rtol=0, atol=1e-12 * np.max(np.abs(tab)))  # rounding: equivalent arithmetic, a few ulp (observed 1.8e-15)


def test_cli_refuses_bad_export_options_before_work(tmp_path, capsys):
    f = tmp_path / "a_file"
    f.write_text("x")
    for argv in (["--design", "full-state", "--export-c", str(tmp_path / "d")],
                 ["--export-c", str(f)],
                 ["--export-c", str(tmp_path / "missing" / "d")],
                 ["--export-c", str(tmp_path / "d"), "--q-format", "Q7"]):
        try:
            code = assist_main(argv)
        except SystemExit as exc:          # argparse's own refusal of a choice
            code = exc.code
        assert code == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert err[-1].startswith("error:") and ("export-c" in err[-1] or "q-format" in err[-1]), err
    assert not (tmp_path / "d").exists()


@pytest.mark.slow
@needs_cc
def test_cli_export_end_to_end(tmp_path, capsys):
    d = tmp_path / "fw"
    assert assist_main(["--speeds", "1:3:1", "--no-check", "--export-c", str(d), "--q-format", "Q31",
                        "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    fw = data["firmware"]
    assert fw["q_format"] == "Q31" and len(fw["margins"]) == 5
    exe = c_harness.compile_replay(str(d), str(tmp_path / "replay"))
    doc = json.loads((d / "assist_vectors.json").read_text())
    # error model: the export's derived per-case bound (quantisation.vector_tolerances: the Q format's rounding
    # propagated through the loop, plus FLOAT_RELATIVE of the torque limit for single precision)
    for case in doc["cases"]:
        assert np.max(np.abs(c_harness.replay(exe, np.array(case["inputs"])) - np.array(case["outputs"]))) \
            <= case["tolerance_N_m"]


@pytest.mark.slow
@needs_cc
def test_documented_export_numbers(tmp_path):
    """docs/assist.md, "Firmware export": the 2 s vectors at 1, 2, 3 m/s and the margins over 0.5:3.0:0.25."""
    from stability.assist.quantisation import worst_change

    s3 = assist.schedule(chair_mod.preset("power-fwd"), [1.0, 2.0, 3.0], "gyro")
    vecs = vector_cases(s3)
    errs = {}
    for q in ("float", "Q15"):
        d = tmp_path / q
        info = export_c(s3, str(d), q, vectors=vecs)
        exe = c_harness.compile_replay(str(d), str(tmp_path / f"r_{q}"))
        errs[q] = [float(np.max(np.abs(c_harness.replay(exe, v.inputs) - v.outputs))) for v in vecs]
        tol = list(info["tolerance_N_m"].values())
        if q == "Q15":
            assert 0.003 < min(tol) and max(tol) < 0.051           # "0.004 to 0.050 N m per case"
            assert 1e-4 < min(errs[q]) and max(errs[q]) < 5.3e-3  # "1.2e-4 to 5.2e-3 N m"
    assert max(errs["float"]) < 1e-4                              # "at most 8.1e-5 N m"
    full = assist.schedule(chair_mod.preset("power-fwd"), np.arange(0.5, 3.01, 0.25), "gyro")
    rows = margin_rows(full, firmware_tables(full, command_filter_s=COMMAND_FILTER))
    assert len(rows) == 21
    f, q15, q31 = (worst_change(rows, v) for v in ("float", "Q15", "Q31"))
    # error model: rounding: at the grid speeds the float tables are the design, so the gain margin moves by
    # rounding only (observed 8.9e-15 dB)
    assert f["phase_deg"] < 0.015 and f["delay_ms"] < 0.011 and abs(f["gain_db"]) < 1e-12
    # error model: rounding of the tables to Q15 (half a unit, 2^-16 of each entry's full scale) moves the phase and
    # delay margins by 4.4e-4 deg and 8.9e-5 ms (observed): the bound is the size of that effect, as documented
    assert q15["gain_db"] < 3.5e-4 and all(abs(q15[k] - f[k]) < 5e-4 for k in ("phase_deg", "delay_ms"))
    # error model: rounding: Q31 entries convert to single precision with 24 bits, as exact as the float tables
    # (2^-24 of an entry); observed 3.1e-9 dB, 1.5e-9 deg, 9.8e-9 ms; 1e-6 is 100x
    assert all(abs(q31[k] - f[k]) < 1e-6 for k in q31)


@pytest.mark.slow
@needs_cc
def test_docs_example_runs_the_c_in_the_loop():
    import subprocess
    import sys

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=root)
    p = subprocess.run([sys.executable, os.path.join(root, "docs", "examples", "assist_c_loop.py")],
                       capture_output=True, text=True, env=env, timeout=600, check=True)
    diff = float(p.stdout.strip().split()[-2])
    assert diff < 1e-3        # docs: 3.4e-5 deg/s (single precision against float64)


def test_c_source_states_the_torque_limit_and_an_unlimited_one_as_float_max_scale(tables):
    """The C carries the table's torque limit; an unlimited drive (inf) becomes 1e30f, a finite C float (FLT_MAX is
    about 3.4e38) beyond any torque, where the Python saturation never acts either."""
    import dataclasses
    import math

    from stability.assist.export_c import c_sources

    q, ints = quantise(tables, "float")
    _, c = c_sources(q, ints)
    line = next(x for x in c.splitlines() if x.startswith("static const float TORQUE_LIMIT = "))
    assert float(line.split("= ")[1].split("f;")[0]) == q.torque_limit
    _, c_inf = c_sources(dataclasses.replace(q, torque_limit=math.inf), ints)
    assert "static const float TORQUE_LIMIT = 1e30f;" in c_inf


def test_c_literals_sample_rate_and_anti_windup_scheme(tables):
    """The header's sample rate is the tables' (1 / T, 200 Hz here); the anti-windup scheme's switch is the one
    named; the most negative 32-bit integer is written as an expression (a bare -2147483648 is the negation of a
    long in C), every other integer as itself."""
    import dataclasses

    from stability.assist.export_c import _c_int, c_sources

    q, ints = quantise(tables, "float")
    h, c = c_sources(q, ints)
    line = next(x for x in h.splitlines() if x.startswith("#define ASSIST_SAMPLE_RATE_HZ "))
    assert float(line.split()[-1].rstrip("f")) == pytest.approx(1.0 / tables.sample_time, rel=1e-12)  # rounding: repr
    assert "#define ANTI_WINDUP 2 " in c
    for scheme, switch in (("conditional", 1), ("none", 0)):
        assert f"#define ANTI_WINDUP {switch} " in c_sources(dataclasses.replace(q, anti_windup=scheme), ints)[1]
    assert _c_int(-2 ** 31) == "(-2147483647 - 1)"
    assert _c_int(-2 ** 31 + 1) == "-2147483647" and _c_int(2 ** 31 - 1) == "2147483647" and _c_int(0) == "0"


def test_export_reports_what_it_wrote(tmp_path, sched, vectors):
    """What the export reports, and its README's derived tolerances: quantised (Q31) tables list each case's
    derived output tolerance, the one assist_vectors.json gives the case (the coefficient rounding a port must
    allow beyond the float allowance)."""
    info = export_c(sched, str(tmp_path / "fw"), "Q31", vectors=vectors)
    assert info["q_format"] == "Q31" and info["directory"] == str(tmp_path / "fw")
    assert info["files"] == ["README.txt", "assist.c", "assist.h", "assist_vectors.json"]
    text = (tmp_path / "fw" / "README.txt").read_text()
    cases = json.loads((tmp_path / "fw" / "assist_vectors.json").read_text())["cases"]
    listed = text.split("Derived tolerance of these quantised tables", 1)[1].splitlines()[1:]
    assert [x for x in listed if x] == [f"  {c['name']}: {c['tolerance_N_m']:.3g} N m" for c in cases]

