"""python -m stability.sweep (issue 25): spec checks, rows against the library, resume, bad chairs, summary."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from stability.chair import preset
from stability.linear import state_matrices
from stability.linear.batch import ChairBatch
from stability.settings.run import RunSpec
from stability.study import critical_impulses
from stability.sweep import columns, compute_chunk, loads_spec, n_chunks, read_rows, run_sweep, summary
from stability.sweep.__main__ import main
from stability.sweep.measures import design_values
from stability.sweep.run import TEXT_COLUMNS, chunk_dir, summary_text
from stability.uncertainty import loads_uncertainty

UNC = '''[pin_friction]
fields = ["pin_friction_left", "pin_friction_right"]
distribution = "uniform"
low = -0.3
high = 0.3
relative = true

[i_z]
distribution = "normal"
std = 0.3
'''
LINEAR = '''chair = "ej-premier"
speeds = [0.5, 1.0]
measures = ["growth_rate", "critical_speeds"]
chunk_rows = 8
[grid]
trail = [0.04, 0.06, -1.0]
pin_friction = [0.05, 0.15]
[draws]
n = 3
seed = 4
uncertainty = "u.toml"
'''


@pytest.fixture
def spec_dir(tmp_path):
    (tmp_path / "u.toml").write_text(UNC)
    (tmp_path / "lin.toml").write_text(LINEAR)
    return tmp_path


def test_rows_equal_the_library_and_a_bad_chair_is_a_row(spec_dir):
    """Every row's growth rate is ChairBatch's for that row's chair (same arithmetic: equal to 1e-12 relative,
    one eigenvalue solve per chair either way); the design with trail -1 m is rows with their reason."""
    spec = loads_spec(LINEAR, spec_dir)
    assert spec.designs == 6 and spec.rows == 6 * 3 * 2 and n_chunks(spec) == math.ceil(18 / 4)
    rows = [r for i in range(n_chunks(spec)) for r in compute_chunk(spec, i)]
    cols = columns(spec)
    assert len(rows) == spec.rows
    data = {c: [r[j] for r in rows] for j, c in enumerate(cols)}
    bad = [i for i, e in enumerate(data["error"]) if e]
    assert len(bad) == 2 * 3 * 2 and all("trail" in data["error"][i] for i in bad)
    assert all(math.isnan(data["growth_rate_1_s"][i]) for i in bad)
    # rebuild one good row's chair independently: base -> grid values -> the same standardised draw
    u = loads_uncertainty(UNC)
    unit = u.unit_draws(3, 4)
    i = next(i for i in range(len(rows)) if not data["error"][i] and data["draw"][i] == 2 and data["speed_m_s"][i] == 1.0)
    d = data["design"][i]
    trail, mf = design_values(spec)[d]
    c = preset("ej-premier").replace(trail=trail, pin_friction_left=mf, pin_friction_right=mf)
    vals = u.field_values(c, {k: v[2:3] for k, v in unit.items()})
    c = c.replace(**{f: float(v[0]) for f, v in vals.items()})
    assert data["pin_friction_left"][i] == c.pin_friction_left and data["i_z"][i] == c.i_z
    expected = ChairBatch([c], "exact").growth_rates([1.0])[0, 0]
    assert data["growth_rate_1_s"][i] == pytest.approx(expected, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    # free casters: unstable at every speed searched (no critical speed); locked: the first destabilising crossing of
    # the locked-caster model that linear.analyse finds on its own grid (Brent to 1e-10 m/s; the batch bisects to
    # xtol = 1e-6 m/s and reports its midpoint: error at most 5e-7 m/s)
    from stability.linear import analyse

    s = analyse(c, "exact")
    # free casters: no crossing up to 30 m/s and unstable at the grid's first speed (0.01 m/s), so the chair is
    # stable up to at most 0.01 m/s: a bound, stored as its value with the status "below"
    assert not [x for x in s.free_crossings if x.speed <= 30.0]
    assert float(np.max(np.linalg.eigvals(state_matrices(c, np.array([0.01]))[0]).real)) > 0
    assert (data["critical_speed_m_s"][i], data["critical_speed_status"][i]) == (0.01, "below")
    assert data["locked_critical_speed_status"][i] == "found"
    # the bad design's rows: no chair, NaN values, the status "invalid" (their side "=": a missing value)
    j = next(j for j in range(len(rows)) if data["error"][j])
    assert math.isnan(data["critical_speed_m_s"][j]) and data["critical_speed_status"][j] == "invalid"
    locked = [x.speed for x in s.locked_crossings if x.direction == "destabilising"]
    # error model: bisection bracket: half the batch's xtol (5e-7 m/s) plus Brent's 1e-10 m/s
    assert data["locked_critical_speed_m_s"][i] == pytest.approx(locked[0], abs=5e-7 + 1e-10)


def test_the_api_writes_into_a_new_folder_and_reports_its_progress(spec_dir, monkeypatch):
    """run_sweep creates the results file's folders (the command checks its -o folder exists first) and calls
    ``progress(chunks_done, chunks_total, rows_done, seconds)`` after each chunk: the chunks in order, the rows of
    the chunks done (4 rows of 2 speeds per chunk here, 36 in all) and the seconds since the sweep started (read
    from a stand-in clock that ticks one second per reading, starting at 100 s: no wall-clock time is asserted)."""
    import itertools
    from types import SimpleNamespace

    import stability.sweep.run as run_mod

    ticks = itertools.count(100.0)
    monkeypatch.setattr(run_mod, "time", SimpleNamespace(perf_counter=lambda: float(next(ticks))))
    spec = loads_spec(LINEAR, spec_dir)
    calls = []
    out = run_sweep(spec, spec_dir / "new" / "deeper" / "r.csv", progress=lambda *a: calls.append(a))
    assert out == spec_dir / "new" / "deeper" / "r.csv" and len(read_rows(out.read_text())["design"]) == 36
    total = n_chunks(spec)
    assert [(c[0], c[1]) for c in calls] == [(k, total) for k in range(1, total + 1)]
    assert [c[2] for c in calls] == [min(8 * k, 36) for k in range(1, total + 1)]
    assert [c[3] for c in calls] == [float(k) for k in range(1, total + 1)]     # one tick per chunk after the start


def test_resume_after_an_interruption_gives_the_same_file(spec_dir, monkeypatch):
    spec = loads_spec(LINEAR, spec_dir)
    whole = run_sweep(spec, spec_dir / "a.csv").read_bytes()
    import stability.sweep.run as run_mod

    real = run_mod.compute_chunk
    calls = []

    def dies_after_two(s, i):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(i)
        return real(s, i)

    monkeypatch.setattr(run_mod, "compute_chunk", dies_after_two)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, spec_dir / "b.csv")
    assert sorted(p.name for p in chunk_dir(spec_dir / "b.csv").glob("chunk-*.csv")) == ["chunk-000000.csv",
                                                                                        "chunk-000001.csv"]
    assert not (spec_dir / "b.csv").exists()
    with pytest.raises(ValueError, match="--resume"):
        run_sweep(spec, spec_dir / "b.csv")
    monkeypatch.setattr(run_mod, "compute_chunk", real)
    done = []
    run_sweep(spec, spec_dir / "b.csv", resume=True, progress=lambda k, n, rows, t: done.append(k))
    assert done == [3, 4, 5] and (spec_dir / "b.csv").read_bytes() == whole
    assert not chunk_dir(spec_dir / "b.csv").exists()
    assert chunk_dir(spec_dir / "b.csv") == spec_dir / "b.csv.chunks"     # docs/sweep.md: RESULTS.chunks/


def test_parquet_equals_csv(spec_dir):
    pq = pytest.importorskip("pyarrow.parquet")
    spec = loads_spec(LINEAR, spec_dir)
    a = read_rows(run_sweep(spec, spec_dir / "a.csv").read_text())
    b = pq.read_table(run_sweep(spec, spec_dir / "a.parquet")).to_pydict()
    assert list(b) == columns(spec)
    for c in a:
        kind = object if c in TEXT_COLUMNS else float
        np.testing.assert_array_equal(np.asarray(b[c], dtype=kind), np.asarray(a[c], dtype=kind))
    assert set(b["critical_speed_status"]) == {"below", "invalid"}       # text columns stay text


def test_a_parquet_file_without_pyarrow_is_refused_before_any_work(spec_dir, monkeypatch):
    """Without pyarrow, a .parquet results file is refused in one line naming -o and the alternative, by the API
    as by the command, before a chunk is computed (compute_chunk is never called) and without leaving a chunk
    directory; a .csv file goes on."""
    import sys

    import stability.sweep.run as run_mod

    spec = loads_spec(LINEAR, spec_dir)
    monkeypatch.setitem(sys.modules, "pyarrow", None)             # import pyarrow now raises ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)

    def no_work(*a, **k):
        raise AssertionError("a chunk was computed")

    monkeypatch.setattr(run_mod, "compute_chunk", no_work)
    msg = "-o: a .parquet file needs pyarrow (pip install 'stability[scale]'); valid: a .csv file without it"
    with pytest.raises(ValueError) as exc:
        run_sweep(spec, spec_dir / "a.parquet")
    assert str(exc.value) == msg and not chunk_dir(spec_dir / "a.parquet").exists()
    assert main([str(spec_dir / "lin.toml"), "-o", str(spec_dir / "b.parquet")]) == 2
    assert not chunk_dir(spec_dir / "b.parquet").exists()
    run_mod.check_output_format(spec_dir / "a.csv")                 # nothing needed for CSV


def test_nonlinear_chunk_matches_the_batched_search(tmp_path):
    """The critical-impulse column is critical_impulses over the chunk's (chair, speed) pairs."""
    spec = loads_spec('speeds = [0.75]\nmeasures = ["critical_impulse"]\n[grid]\npin_friction = [0.1, 0.2]\n',
                      tmp_path)
    rows = compute_chunk(spec, 0)
    j = columns(spec).index("critical_impulse_Ns")
    ej = preset("ej-premier")
    direct = critical_impulses([ej.replace(pin_friction_left=f, pin_friction_right=f) for f in (0.1, 0.2)], 0.75)
    assert [r[j] for r in rows] == [x.impulse_Ns for x in direct]
    assert rows[1][j] > rows[0][j]            # more pin friction: a larger push needed (elasticity ~1)


def test_critical_impulse_in_slices_equals_one_call(tmp_path, monkeypatch):
    """A chunk's critical impulses are searched SEARCH_SLICE pairs per call (so a large chunk passes the studies'
    work check): the same numbers as one call, the searches of different pairs being independent."""
    import stability.sweep.measures as measures

    spec = loads_spec('speeds = [0.75, 1.0]\nmeasures = ["critical_impulse"]\n[grid]\npin_friction = [0.1, 0.2]\n',
                      tmp_path)
    whole = compute_chunk(spec, 0)
    monkeypatch.setattr(measures, "SEARCH_SLICE", 3)          # 4 pairs: slices of 3 and 1
    assert compute_chunk(spec, 0) == whole


def test_friction_law_reaches_the_nonlinear_measures(tmp_path):
    """The spec's friction_law (default "stick-slip", the step-converged law) reaches the critical impulse: power-fwd at 1.5 m/s
    needs a real push (7.8 N s; test_stick_slip.py checks it against the adaptive scheme), where WCHAIR's kinetic
    law at 1 ms says any push does ("below")."""
    text = 'chair = "power-fwd"\nspeeds = [1.5]\nmeasures = ["critical_impulse"]\n'
    kinetic = loads_spec('friction_law = "kinetic"\n' + text, tmp_path)
    sticky = loads_spec(text, tmp_path)                       # the measures' default law
    assert kinetic.friction_law == "kinetic" and sticky.to_dict()["friction_law"] == "stick-slip"
    j = columns(sticky).index("critical_impulse_Ns")
    k = columns(sticky).index("critical_impulse_status")
    row, = compute_chunk(sticky, 0)
    assert row[k] == "found"
    assert row[j] == critical_impulses(preset("power-fwd"), 1.5, run=RunSpec(friction_law="stick-slip"))[0].impulse_Ns
    assert compute_chunk(kinetic, 0)[0][k] == "below"


def test_summary_ranks_by_the_conservative_end(spec_dir):
    spec = loads_spec(LINEAR, spec_dir)
    data = read_rows(run_sweep(spec, spec_dir / "s.csv").read_text())
    s = summary(spec, data, top=10)
    ranked = s["measures"]["growth_rate_1_s"]["best"][spec.speeds.index(1.0)]
    highs = [e["conservative"] for e in ranked]
    assert highs == sorted(highs) and len(ranked) == 4          # 4 valid designs, lower growth rate is better
    g = np.asarray(data["growth_rate_1_s"])
    sel = (np.asarray(data["design"]) == ranked[0]["design"]) & (np.asarray(data["speed_m_s"]) == 1.0)
    assert ranked[0]["conservative"] == pytest.approx(np.quantile(g[sel], 0.975), rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)


@pytest.mark.parametrize("text, word", [
    ('speeds = [0.5]\nmeasures = ["growth_rate", "growth_rate"]\n', "measures"),
    ('speeds = [0.5]\nmeasures = ["nope"]\n', "nope"),
    ('speeds = [0]\nmeasures = ["growth_rate"]\n', "speeds"),
    ('speeds = [0.5]\nmeasures = ["growth_rate"]\n[grid]\ncolour = [1]\n', "colour"),
    ('speeds = [0.5]\nmeasures = ["growth_rate"]\nfoo = 1\n', "foo"),
    ('friction_law = "sticky"\nspeeds = [0.5]\nmeasures = ["critical_impulse"]\n', "friction_law"),
    ('speeds = [0.5]\nmeasures = ["growth_rate"]\n[draws]\nn = 0\nuncertainty = "u.toml"\n', "draws.n"),
])
def test_bad_specs_are_one_line_errors_before_any_work(tmp_path, capsys, text, word):
    (tmp_path / "u.toml").write_text(UNC)
    (tmp_path / "s.toml").write_text(text)
    assert main([str(tmp_path / "s.toml"), "-o", str(tmp_path / "r.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and word in err[0]
    assert not (tmp_path / "r.csv").exists() and not chunk_dir(tmp_path / "r.csv").exists()


def test_command_writes_results_summary_and_figures(spec_dir, capsys):
    assert main([str(spec_dir / "lin.toml"), "-o", str(spec_dir / "r.csv")]) == 0
    out = capsys.readouterr()
    assert "growth_rate_1_s at 1 m/s" in out.out and "chunks" in out.err
    s = json.loads((spec_dir / "r.summary.json").read_text())
    assert s["spec"]["draws"] == 3 and "growth_rate_1_s" in s["measures"]
    assert (spec_dir / "r.pdf").stat().st_size > 1000
    assert main(["--schema"]) == 0
    schema = json.loads(capsys.readouterr().out)
    assert "pin_friction" in schema["properties"]["grid"]["propertyNames"]["enum"]
    assert set(schema["properties"]) == {"chair", "model", "friction_law", "speeds", "measures", "grid", "draws",
                                          "chunk_rows", "reaction_time_s"}
    assert Path(spec_dir / "r.csv").read_text().splitlines()[0].split(",")[:3] == ["design", "draw", "speed_m_s"]


def test_example_spec_is_the_issue_sweep():
    """docs/examples/sweep.toml: a 3 x 3 x 3 grid x 100 draws x 3 speeds of every measure that applies to its manual
    chair (the bench needs a powered chair: tests/test_sweep.py's bench test)."""
    from stability.sweep import MEASURES, load_spec

    spec = load_spec(Path(__file__).parent.parent / "docs" / "examples" / "sweep.toml")
    assert spec.designs == 27 and spec.draws == 100 and len(spec.speeds) == 3 and spec.rows == 8100
    assert set(spec.measures) == set(MEASURES) - {"bench"}


def test_statics_and_shimmy_measures_are_the_library_values(tmp_path):
    """tip_angles, holding_moment and shimmy_margin columns: stability.tipping, stability.slope and
    stability.shimmy.band on each row's chair (same calls, equal values)."""
    from stability.shimmy.band import shimmy_band
    from stability.slope import solve
    from stability.tipping import tip_angles

    spec = loads_spec('speeds = [0.5, 1.0]\nmeasures = ["tip_angles", "holding_moment", "shimmy_margin"]\n'
                      '[grid]\ns1 = [0.2, 0.3]\n', tmp_path)
    rows = compute_chunk(spec, 0)
    cols = columns(spec)
    for r in rows:
        c = preset("ej-premier").replace(s1=r[cols.index("grid_s1")])
        t = tip_angles(c)
        assert r[cols.index("static_stability_deg")] == t.smallest_deg
        assert r[cols.index("tip_toward_casters_deg")] == t.toward_casters_deg
        u = r[cols.index("speed_m_s")]
        assert r[cols.index("holding_moment_N_m_per_deg")] == abs(solve(c, 1.0, u).holding_moment)
        k = spec.speeds.index(u)
        assert r[cols.index("shimmy_margin_m")] == shimmy_band(c, np.array(spec.speeds)).margin_m[k]
    # s1 is the c.g.-to-main-axle distance (s2, c.g. to the caster pins, fixed): a larger s1 makes the chair
    # harder to tip over the main wheels and leaves the tip toward the casters unchanged
    a, b = rows[0], rows[2]
    assert b[cols.index("tip_toward_main_wheels_deg")] > a[cols.index("tip_toward_main_wheels_deg")]
    assert b[cols.index("tip_toward_casters_deg")] == a[cols.index("tip_toward_casters_deg")]


def test_each_dask_worker_gets_its_own_numba_cache_unless_the_environment_names_one():
    """Two workers never write one cache index; a user's NUMBA_CACHE_DIR is kept (stability/sweep/cluster.py)."""
    from stability.sweep.cluster import worker_cache_dir

    a, b = worker_cache_dir({}, "0"), worker_cache_dir({}, "1")
    assert a is not None and b is not None and a != b
    assert worker_cache_dir({}, "0") == a                       # the same worker name: the same (warm) cache
    assert "/" not in Path(worker_cache_dir({}, "tcp://10.0.0.1:4000") or "").name  # an address is made a name
    assert worker_cache_dir({"NUMBA_CACHE_DIR": "/shared/numba"}, "0") is None


def _write(folder: Path, name: str, text: str) -> Path:
    (folder / name).write_text(text)
    return folder


def _censored_data(values, statuses, col="equal_instability_speed_m_s", status_col="equal_instability_status"):
    """Result columns of a synthetic sweep: one design per (values, statuses) list, draws in order, speed 0.75."""
    data: dict = {"design": [], "draw": [], "speed_m_s": [], "grid_trail": [], col: [], status_col: []}
    for d, (vs, ss) in enumerate(zip(values, statuses, strict=True)):
        for k, (v, st) in enumerate(zip(vs, ss, strict=True)):
            data["design"].append(d)
            data["draw"].append(k)
            data["speed_m_s"].append(0.75)
            data["grid_trail"].append(0.04 + 0.01 * d)
            data[col].append(v)
            data[status_col].append(st)
    return data


def test_a_design_beyond_the_searched_range_ranks_first_as_its_bound(tmp_path):
    """Issue 33: a design whose equal-instability speed is above the searched 3 m/s in 45 of 100 draws ranked
    behind one at 1.164 m/s.  A bound is a value: design 1 (every draw 'above 3 m/s') is at least 3 m/s and
    ranks first; design 2 (45 % of draws above, the rest 2.0-2.9 m/s) next; design 0 (1.164 m/s) last.  The low
    end (2.5 % quantile) of design 1 is a bound and is printed as one."""
    spec = loads_spec('speeds = [0.75]\nmeasures = ["equal_instability_speed"]\n[grid]\ntrail = [0.04, 0.05, 0.06]\n'
                      '[draws]\nn = 100\nuncertainty = "u.toml"\n',
                      _write(tmp_path, "u.toml", UNC))

    found = [1.164] * 100
    above = [3.0] * 100
    mixed = list(np.linspace(2.0, 2.9, 55)) + [3.0] * 45
    data = _censored_data([found, above, mixed], [["found"] * 100, ["above"] * 100, ["found"] * 55 + ["above"] * 45])
    s = summary(spec, data, top=3)
    ranked = s["measures"]["equal_instability_speed_m_s"]["best"][0]
    assert [e["design"] for e in ranked] == [1, 2, 0]
    assert ranked[0]["conservative"] == 3.0 and ranked[0]["conservative_side"] == ">" and ranked[0]["bounds"] == 100
    assert ranked[1]["conservative_side"] == "=" and ranked[1]["median_side"] == "=" and ranked[1]["bounds"] == 45
    assert ranked[2]["conservative"] == pytest.approx(1.164, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    text = summary_text(spec, s)
    assert "> 3 m/s" in text and "{" not in text and "trail 0.05 m" in text     # a bound, no dict repr
    # class: words no test read (seed 50): the heading states the interval (summary's level 0.95: 95 %) and the
    # spec's 100 draws it ranks by, and how a bound ranks
    assert text.splitlines()[0] == ("best designs by the conservative end of the 95 % interval over 100 draw(s); a "
                                    "value beyond the searched range is ranked as its bound ('> 3 m/s' is at least "
                                    "3 m/s)")
    # a higher speed is better, so the designs are ranked by their interval's low end, said in the heading
    assert "equal_instability_speed_m_s at 0.75 m/s (low end | median | design):" in text.splitlines()
    from stability.sweep.run import _grid_text

    assert _grid_text({"cg_ratio": 0.5, "trail": 0.05}) == "cg_ratio 0.5, trail 0.05 m"   # a group has no unit
    assert _grid_text({}) == "the base chair"                        # a spec without a grid: one design


def test_a_design_with_bounds_and_missing_draws_says_both(tmp_path):
    """A design's row notes how many of its draws were beyond the searched range and how many have no value (an
    invalid chair), both, separated by a semicolon; its median of the defined draws is the bound."""
    spec = loads_spec('speeds = [0.75]\nmeasures = ["equal_instability_speed"]\n[grid]\ntrail = [0.04]\n'
                      '[draws]\nn = 4\nuncertainty = "u.toml"\n', _write(tmp_path, "u.toml", UNC))
    data = _censored_data([[3.0, 3.0, 1.5, math.nan]], [["above", "above", "found", "invalid"]])
    text = summary_text(spec, summary(spec, data))
    assert "trail 0.04 m (2 draw(s) beyond the searched range; 1 draw(s) without a value)" in text, text


def test_a_chair_stable_at_every_speed_searched_ranks_first_by_its_critical_speed(tmp_path):
    """A bound is a value for the critical speeds too.  The E&J Premier with its c.g. 5 or 15 cm ahead of the main
    axle (s1) is stable with locked casters at every speed up to the searched 30 m/s (zero-width model, eqs 5-15
    and 5-16: no critical speed at 5 cm, k_us > 0; 62.5 m/s at 15 cm), while at s1 = 0.25 and 0.345 m it turns
    unstable at 11.6 and 9.71 m/s: the two stable designs rank first as "> 30 m/s", not last as missing values.  With free casters every design is
    unstable from the grid's first speed: "< 0.01 m/s" each, the chair is never stable."""
    from stability.linear import zero_width

    spec = loads_spec('speeds = [0.75]\nmeasures = ["critical_speeds"]\n[grid]\ns1 = [0.345, 0.25, 0.15, 0.05]\n',
                      tmp_path)
    rows = compute_chunk(spec, 0)
    cols = columns(spec)
    data = {c: [r[j] for r in rows] for j, c in enumerate(cols)}
    chairs = [preset("ej-premier").replace(s1=s1) for s1 in (0.345, 0.25, 0.15, 0.05)]
    beyond = [zero_width(c).critical_speed is None or zero_width(c).critical_speed > 30.0 for c in chairs]
    assert beyond == [False, False, True, True]                     # 9.71, 11.6, 62.5 m/s and none (k_us > 0)
    s = summary(spec, data, top=4)
    ranked = s["measures"]["locked_critical_speed_m_s"]["best"][0]
    assert [(e["design"], e["conservative_side"]) for e in ranked[:2]] in ([(2, ">"), (3, ">")], [(3, ">"), (2, ">")])
    assert [e["design"] for e in ranked[2:]] == [1, 0]                   # 11.6 m/s before 9.71 m/s
    assert ranked[0]["conservative"] == 30.0 and ranked[2]["conservative_side"] == "="
    free = s["measures"]["critical_speed_m_s"]["best"][0]
    assert len(free) == 4 and {(e["conservative"], e["conservative_side"]) for e in free} == {(0.01, "<")}
    text = summary_text(spec, s)
    assert "> 30 m/s" in text and "< 0.01 m/s" in text and "no design has a value" not in text


def test_a_sweep_ranks_a_trail_with_no_shimmy_boundary_first():
    """Viscous pin damping of 0.5 N m s/rad leaves the E&J Premier's caster shimmy-free on every trail searched at
    0.75 m/s (its band is the whole search, 1 mm to 25 cm: no boundary, margin +inf), while without damping its 8 cm
    trail is 3.14 cm from a boundary.  The sweep stores the damped design's margin as its bound (at least 7.9 cm,
    "above") and ranks it first, not last as a missing value."""
    from stability import chair as chair_mod
    from stability.shimmy.band import shimmy_band

    damped = shimmy_band(chair_mod.preset("ej-premier").replace(pin_damping=0.5), [0.75])
    assert damped.intervals_m[0] == ((0.001, 0.25),) and damped.margin_m[0] == math.inf
    spec = loads_spec('speeds = [0.75]\nmeasures = ["shimmy_margin"]\n[grid]\npin_damping = [0.0, 0.5]\n')
    rows = compute_chunk(spec, 0)
    data = {c: [r[j] for r in rows] for j, c in enumerate(columns(spec))}
    assert data["shimmy_margin_status"] == ["found", "above"]
    ranked = summary(spec, data)["measures"]["shimmy_margin_m"]["best"][0]
    assert [(e["design"], e["conservative_side"]) for e in ranked] == [(1, ">"), (0, "=")]
    # rounding: the stored margin is one subtraction of two floats, 1 ulp of 0.25 (2.8e-17); 1e-15 ~ 40x (observed 0)
    assert ranked[0]["conservative"] == pytest.approx(0.079, abs=1e-15)
    assert ranked[1]["conservative"] == pytest.approx(shimmy_band(chair_mod.preset("ej-premier"), [0.75]).margin_m[0],
                                                      abs=1e-15)

def test_a_critical_impulse_never_reached_is_at_least_the_largest_push_and_ranks_first(tmp_path):
    spec = loads_spec('speeds = [0.75]\nmeasures = ["critical_impulse"]\n[grid]\ntrail = [0.04, 0.05, 0.06]\n',
                      tmp_path)
    data = _censored_data([[3.2], [40.0], [1e-6]], [["found"], ["never"], ["below"]], "critical_impulse_Ns",
                          "critical_impulse_status")
    ranked = summary(spec, data)["measures"]["critical_impulse_Ns"]["best"][0]
    assert [(e["design"], e["conservative_side"]) for e in ranked] == [(1, ">"), (0, "="), (2, "<")]


def test_censored_quantile_and_order_from_their_definitions():
    from stability.study.censored import describe, quantile, sort_key

    assert quantile([1.0, 3.0, 3.0], ["=", ">", ">"], 0.025) == (1.0, "=")
    assert quantile([1.0, 3.0, 3.0], ["=", ">", ">"], 0.5) == (3.0, ">")
    assert quantile([], [], 0.5)[0] != quantile([], [], 0.5)[0]          # nan without draws
    best_first = sorted([(2.0, "="), (3.0, ">"), (3.0, "="), (0.5, "<")], key=lambda v: sort_key(*v, True))
    assert best_first == [(3.0, ">"), (3.0, "="), (2.0, "="), (0.5, "<")]
    assert sorted([(2.0, "="), (1.0, "<"), (1.0, "=")], key=lambda v: sort_key(*v, False)) == \
        [(1.0, "<"), (1.0, "="), (2.0, "=")]
    assert describe(3.0, ">", "m/s") == "> 3 m/s" and describe(1.1642, "=", "m/s") == "1.164 m/s"


def test_every_measure_has_a_cost_for_the_dask_order():
    """Issue 33: --dask local:2 raised KeyError 'tip_angles' in the cost estimate."""
    from stability.sweep.cluster import COST_PER_ROW_S, chunk_cost
    from stability.sweep.spec import MEASURES

    assert set(COST_PER_ROW_S) == set(MEASURES)
    spec = loads_spec(f'speeds = [0.5]\nmeasures = {list(MEASURES)!r}\n'.replace("'", '"'), None)
    assert chunk_cost(spec, 0) > 0


def test_the_sweep_command_prints_its_summary_as_json(spec_dir, capsys):
    (spec_dir / "g.toml").write_text('speeds = [0.5, 1.0]\nmeasures = ["growth_rate"]\n[grid]\ntrail = [0.05, 0.07]\n')
    assert main([str(spec_dir / "g.toml"), "-o", str(spec_dir / "g.csv"), "--json", "--quiet"]) == 0
    doc = json.loads(capsys.readouterr().out)
    from stability.schemas import bad_keys

    assert doc["level"] == 0.95 and set(doc["measures"]) == {"growth_rate_1_s"} and bad_keys(doc) == []
    first = doc["measures"]["growth_rate_1_s"]["best"][1][0]
    assert first["conservative_side"] == "=" and first["grid"]["trail"] in (0.05, 0.07)


def test_human_limited_speed_measure_is_the_divergence_rule(spec_dir):
    """The sweep's human_limited_speed column is, for every design, the speed where the design's divergence rate
    (the linear model's eigenvalues, computed here directly) reaches 1/reaction_time; a stable design is a bound
    ('above') and ranks first."""
    from stability.linear import state_matrices
    from stability.sweep.run import summary

    text = ('chair = "ej-premier"\nspeeds = [1.0]\nmeasures = ["human_limited_speed"]\nreaction_time_s = 0.4\n'
            '[grid]\ns1 = [0.245, 0.345]\n')
    spec = loads_spec(text, spec_dir)
    rows = [r for i in range(n_chunks(spec)) for r in compute_chunk(spec, i)]
    cols = columns(spec)
    data = {c: [r[j] for r in rows] for j, c in enumerate(cols)}
    for u, status, s1 in zip(data["human_limited_speed_m_s"], data["human_limited_status"], data["s1"],
                             strict=True):
        c = preset("ej-premier").replace(s1=s1)
        rate = lambda v, c=c: float(np.max(np.linalg.eigvals(state_matrices(c, v)[0]).real))   # noqa: E731
        assert status == "found"
        assert rate(u - 0.01) * 0.4 < 1 < rate(u + 0.01) * 0.4
    front = loads_spec(text.replace('"ej-premier"', '"ej-premier-front-caster"'), spec_dir)
    frows = [r for i in range(n_chunks(front)) for r in compute_chunk(front, i)]
    fdata = {c: [r[j] for r in frows] for j, c in enumerate(columns(front))}
    assert set(fdata["human_limited_status"]) == {"above"}
    s = summary(spec, data)
    assert "human_limited_speed_m_s" in s["measures"]


def test_bench_measure_scores_and_stops_a_powered_chair_only(spec_dir):
    """The sweep's bench columns for a powered chair: a higher centre of mass never lifts fewer wheels (the worst
    score is non-decreasing in h: a taller chair's effective centre moves further per m/s^2), the level-ground stop
    of a controller-limited case is ``v delay + v^2 / (2 a)`` of the longest of the three stops at the default
    drive settings (the stop distances do not depend on h while traction does not limit them), and a chair
    pushed on its hand rims has no drive to bench (NaN).  The lower score and shorter stop rank first."""
    import math

    from stability.bench import Drive, braking_distance
    from stability.sweep.run import summary

    text = 'chair = "power-fwd"\nspeeds = [1.0]\nmeasures = ["bench"]\n[grid]\nh = [0.3, 0.5, 0.9]\n'
    spec = loads_spec(text, spec_dir)
    rows = [r for i in range(n_chunks(spec)) for r in compute_chunk(spec, i)]
    data = {c: [r[j] for r in rows] for j, c in enumerate(columns(spec))}
    scores = data["bench_worst_score"]
    assert scores == sorted(scores) and scores[0] < scores[-1]
    d = Drive()
    longest = max(braking_distance(d.max_speed_m_s, d.decel_m_s2), braking_distance(d.max_speed_m_s,
                  d.reverse_decel_m_s2), braking_distance(d.max_speed_m_s, d.brake_decel_m_s2, d.brake_delay_s))
    assert data["level_braking_distance_m"][0] == pytest.approx(longest, rel=1e-12)  # rounding: equivalent arithmetic, a few ulp (observed 0)
    best = summary(spec, data)["measures"]["bench_worst_score"]["best"]
    assert best[0][0]["grid"]["h"] == 0.3
    manual = loads_spec(text.replace('"power-fwd"', '"ej-premier"'), spec_dir)
    mrows = [r for i in range(n_chunks(manual)) for r in compute_chunk(manual, i)]
    j = columns(manual).index("bench_worst_score")
    assert all(math.isnan(r[j]) for r in mrows)


def test_a_design_with_failed_draws_ranks_behind_every_complete_one(tmp_path):
    """Draws without a value (an invalid chair, an error) count as the worst case: a design whose good draws are the
    best of the grid but which lost 1 of 100 draws ranks behind the complete designs, and says how many it lost."""
    spec = loads_spec('speeds = [0.75]\nmeasures = ["equal_instability_speed"]\n[grid]\ntrail = [0.04, 0.05, 0.06]\n'
                      '[draws]\nn = 100\nuncertainty = "u.toml"\n',
                      _write(tmp_path, "u.toml", UNC))
    lossy = [2.8] * 99 + [float("nan")]
    data = _censored_data([[1.2] * 100, lossy, [1.5] * 100], [["found"] * 100] * 3)
    ranked = summary(spec, data, top=3)["measures"]["equal_instability_speed_m_s"]["best"][0]
    assert [e["design"] for e in ranked] == [2, 0, 1]
    assert [e["missing"] for e in ranked] == [0, 0, 1]


def test_censored_sides_are_every_side_a_status_can_have():
    """SIDES lists exactly the sides the searches' statuses map to, and every one of them is described and
    ranked: at one value, a bound beyond it in the good direction ranks first, the bound on the bad side last."""
    from stability.study.censored import SIDES, describe, side_of, sort_key

    assert set(SIDES) == {side_of(s) for s in ("found", "above", "never", "below")} and len(SIDES) == 3
    # class: an input no test gave (seed 34): an empty status cell, as a CSV writes it or as a CSV reader fills it
    # (NaN), claims no bound: the value is taken as it is (and a NaN value then "has no value", below)
    assert side_of("") == side_of(math.nan) == side_of(float("nan")) == "="
    assert [describe(3.0, s, "m/s") for s in SIDES] == ["3 m/s", "> 3 m/s", "< 3 m/s"]
    # class: words no test read (seed 50): a value that does not exist (NaN, or an infinite one) "has no value"
    # (docs/studies.md), whatever its side and unit
    assert {describe(v, s, "m/s") for v in (math.nan, math.inf) for s in SIDES} == {"no value"}
    # class: a default no test omitted (seed 51): without a unit the value stands alone (no trailing space)
    assert [describe(3.0, s) for s in SIDES] == ["3", "> 3", "< 3"]
    assert sorted(SIDES, key=lambda s: sort_key(3.0, s, True)) == [">", "=", "<"]
    assert sorted(SIDES, key=lambda s: sort_key(3.0, s, False)) == ["<", "=", ">"]


def test_censored_quantile_takes_the_conservative_neighbour_and_compare_touching_sets():
    """Draws 1, 2 and '> 3': the 0.9 quantile lies between 2 and the bound, so it is the upper neighbour with its
    side (above the median the conservative side is up), the 0.1 quantile interpolates two values.  Sets that
    only touch are ordered: '< 3' allows only values below 3, so it is worse than 3 where higher is better (and
    '> 3' better), undecided against '< 4'."""
    from stability.study.censored import compare, quantile

    assert quantile([1.0, 2.0, 3.0], ["=", "=", ">"], 0.9) == (3.0, ">")
    assert quantile([1.0, 2.0, 3.0], ["<", "=", ">"], 0.1) == (1.0, "<")
    assert quantile([1.0, 2.0, 3.0], ["=", "=", ">"], 0.25) == (1.5, "=")
    assert compare(3.0, "<", 3.0, "=", True) == "worse"
    assert compare(3.0, "<", 3.0, "=", False) == "better"
    assert compare(3.0, ">", 3.0, "=", True) == "better"
    assert compare(3.0, "<", 4.0, "<", True) == "undecided"


def test_every_measure_column_has_a_direction_and_the_unit_its_name_ends_with():
    """Each numeric measure column is ranked (HIGHER_IS_BETTER) and printed with the unit its key's suffix names
    (the JSON key convention, stability.schemas); a dimensionless score has none."""
    from stability.sweep.run import COLUMN_UNITS, HIGHER_IS_BETTER, TEXT_COLUMNS
    from stability.sweep.spec import MEASURES

    numeric = {c for cols, _ in MEASURES.values() for c in cols if c not in TEXT_COLUMNS}
    assert set(HIGHER_IS_BETTER) == numeric and set(COLUMN_UNITS) == numeric
    suffixes = [("_N_m_per_deg", "N m/deg"), ("_1_s", "1/s"), ("_m_s", "m/s"), ("_Ns", "N s"), ("_deg", "deg"),
                ("_m", "m"), ("_score", "")]
    for col in numeric:
        assert COLUMN_UNITS[col] == next(u for s, u in suffixes if col.endswith(s)), col
    # larger is safer except where the measure is a rate, a needed effort, a score of faults or a distance
    assert {c for c in numeric if not HIGHER_IS_BETTER[c]} == {"growth_rate_1_s", "holding_moment_N_m_per_deg",
                                                               "bench_worst_score", "level_braking_distance_m"}


def test_censored_exact_value_against_a_bound_at_it():
    """3 exactly against '> 3': every value the bound allows is above 3, so 3 is worse where higher is better."""
    from stability.study.censored import compare

    assert compare(3.0, "=", 3.0, ">", True) == "worse"
    assert compare(3.0, "=", 3.0, "<", True) == "better"


def test_censored_found_values_compare_both_ways():
    """Two found values far apart (3 and 5, far outside the relative tolerance): the smaller is worse where higher
    is better and better where lower is, whichever side of the comparison it is on (the two sets do not even
    touch, so the exception for touching sets does not apply)."""
    from stability.study.censored import compare

    assert compare(3.0, "=", 5.0, "=", True) == compare(5.0, "=", 3.0, "=", False) == "worse"
    assert compare(3.0, "=", 5.0, "=", False) == compare(5.0, "=", 3.0, "=", True) == "better"


def test_censored_found_values_within_the_tolerance_are_equal_and_an_unknown_status_is_refused():
    """Two found values closer than ``rel_tol`` of the larger are equal, in either order (3 and 3.0003 at 1e-3);
    3 and 3.3 are not.  A search status other than the searches' four is refused naming them."""
    from stability.study.censored import compare, side_of

    assert compare(3.0, "=", 3.0003, "=", True, rel_tol=1e-3) == compare(3.0003, "=", 3.0, "=", False,
                                                                           rel_tol=1e-3) == "equal"
    assert compare(3.0, "=", 3.3, "=", True, rel_tol=1e-3) == "worse"
    with pytest.raises(ValueError, match=r"^status='stalled' is invalid; valid: found, above, never, below$"):
        side_of("stalled")


def test_unfinished_chunks_are_refused_naming_both_ways_on(spec_dir):
    """An output whose chunk directory is left from an interrupted run is refused before any work, in one line
    naming the output, the directory and both ways on."""
    import re

    from stability.sweep.run import chunk_dir

    spec = loads_spec(LINEAR, spec_dir)
    out = spec_dir / "b.csv"
    chunk_dir(out).mkdir(parents=True)
    with pytest.raises(ValueError, match=rf"^output {re.escape(repr(str(out)))} has unfinished chunks in "
                                         rf"{re.escape(repr(str(chunk_dir(out))))}; valid: --resume to finish them, "
                                         r"or remove that directory$"):
        run_sweep(spec, out)
    (chunk_dir(out) / "spec.json").write_text("{}")             # chunks of another spec
    with pytest.raises(ValueError, match=rf"^--resume: the chunks in {re.escape(repr(str(chunk_dir(out))))} come "
                                         r"from another spec; valid: the same spec, or remove that directory$"):
        run_sweep(spec, out, resume=True)


def test_progress_counts_the_rows_written_chunk_by_chunk(spec_dir):
    """The progress callback's counts, against the spec's arithmetic: 3 trails x 2 pin frictions = 6 designs, 3
    draws, 2 speeds: 36 rows; 8 rows a chunk = 4 (design, draw) pairs at 2 speeds, so 5 chunks of 8, 8, 8, 8 and 4
    rows.  The rows reported after the last chunk are the rows of the file."""
    spec = loads_spec(LINEAR, spec_dir)
    seen = []
    out = run_sweep(spec, spec_dir / "p.csv", progress=lambda k, n, rows, t: seen.append((k, n, rows)))
    assert seen == [(1, 5, 8), (2, 5, 16), (3, 5, 24), (4, 5, 32), (5, 5, 36)]
    assert len(read_rows(out.read_text())["design"]) == 36


def test_censored_quantile_at_the_ends_of_draws_tied_with_a_bound():
    """Two draws at 3, one found and one a bound: '< 3' lies below every value it is tied with and '> 3' above, so
    the smallest draw (q = 0) of '3' and '< 3' is '< 3', the largest (q = 1) of '3' and '> 3' is '> 3', whatever
    order the draws come in."""
    from stability.study.censored import quantile

    for sides in (["=", "<"], ["<", "="]):
        assert quantile([3.0, 3.0], sides, 0.0) == (3.0, "<"), sides
        assert quantile([3.0, 3.0], sides, 1.0) == (3.0, "="), sides
    for sides in ([">", "="], ["=", ">"]):
        assert quantile([3.0, 3.0], sides, 1.0) == (3.0, ">"), sides
        assert quantile([3.0, 3.0], sides, 0.0) == (3.0, "="), sides


def test_the_chair_files_user_is_the_sweeps_driver_unless_the_spec_names_one(spec_dir):
    """A spec without ``reaction_time_s`` takes the chair file's ``[user]``, as every command's ``--chair`` does; the
    spec's own value wins; a preset (no user) keeps the default driver.  Before, the file's user was ignored."""
    from stability.chair.io import save
    from stability.driver import REACTION_TIME_S

    save(preset("revised"), spec_dir / "mine.toml")
    with open(spec_dir / "mine.toml", "a", encoding="utf-8") as fh:
        fh.write('\n[user]\nreaction_time_s = 0.45\nsource = "clinic"\n')
    base = 'speeds = [1.0]\nmeasures = ["human_limited_speed"]\n'
    assert loads_spec('chair = "mine.toml"\n' + base, spec_dir).reaction_time_s == 0.45
    assert loads_spec('chair = "mine.toml"\nreaction_time_s = 0.6\n' + base, spec_dir).reaction_time_s == 0.6
    assert loads_spec('chair = "revised"\n' + base, spec_dir).reaction_time_s == REACTION_TIME_S
    with open(spec_dir / "mine.toml", "a", encoding="utf-8") as fh:
        fh.write("hand_force_N = 0.0\n")                   # a bad [user] is refused as the commands refuse it
    with pytest.raises(ValueError, match="hand_force_N"):
        loads_spec('chair = "mine.toml"\n' + base, spec_dir)
