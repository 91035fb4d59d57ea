"""The value groups of docs/scale.md: what a sweep row costs, measured when the site builds (see ``value_groups.py``).

The measurement is bounded (about 20-30 s of CPU on the build machine) and runs in a fresh process with one numba
thread (``NUMBA_NUM_THREADS=1``, as a Dask worker runs), so its CPU time is that of the sweep alone: process CPU
time (user + system) per measure, each measure warmed up first on a 6-row sweep (imports done, kernels loaded from
the numba cache), then timed on the page's spec. CPU time, not wall time, is the figure to scale from: the build
machine is shared, and the page states its core count and load average during the measurement. The counts (runs
and simulated seconds per critical-impulse row) are deterministic on one machine.

Run ``python docs/_ext/value_groups_scale.py`` to print the raw measurement (JSON) without building the site.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from value_groups import ROOT, Table, fixed, group, sig

#: The page's sweep: the E&J Premier, trails x draws (pin friction +-30 % uniform, I_z normal std 0.3 kg m^2,
#: seed 1) x speeds; a measure that costs more per row is timed on fewer draws (DRAWS)
UNCERTAINTY = '''[pin_friction]
fields = ["pin_friction_left", "pin_friction_right"]
distribution = "uniform"
low = -0.3
high = 0.3
relative = true

[i_z]
distribution = "normal"
std = 0.3
'''
TRAILS = (0.04, 0.06)
SPEEDS = (0.5, 0.75, 1.0)
DRAWS = {"growth_rate": 500, "critical_speeds": 100, "critical_impulse": 50, "equal_instability_speed": 50,
         "shimmy_margin": 30, "tip_angles": 100, "holding_moment": 30}
#: (chair, speed) pairs of the lanes-against-scalar comparison (E&J Premier, the speeds +-3 %, seed 0)
LANE_PAIRS = 100
#: the projection's sweep: rows and workers
PROJECTED_ROWS, WORKERS = 10**6, 64


def spec_text(measure: str, draws: int) -> str:
    """The sweep spec (TOML) of one measure with ``draws`` draws per trail."""
    return (f'chair = "ej-premier"\nspeeds = [{", ".join(f"{u:g}" for u in SPEEDS)}]\nmeasures = ["{measure}"]\n'
            f'chunk_rows = 100000\n[grid]\ntrail = [{", ".join(f"{t:g}" for t in TRAILS)}]\n'
            f'[draws]\nn = {draws}\nseed = 1\nuncertainty = "u.toml"\n')


def _machine() -> dict:
    model = ""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"cores": os.cpu_count() or 0, "cpu": model or "unknown CPU", "load": os.getloadavg()[0]}


def measure() -> dict:
    """The raw measurement (run in a fresh process with one numba thread: :func:`run_measurement`)."""
    import time

    import numpy as np

    from stability.study.summaries import SummaryRunner
    from stability.sweep import compute_chunk, loads_spec
    from stability.sweep.run import _chunk_text

    out: dict = {"machine_start": _machine(), "measures": {}}
    with tempfile.TemporaryDirectory() as tmp:
        base = Path(tmp)
        (base / "u.toml").write_text(UNCERTAINTY)
        seen = {"runs": 0, "sim": 0.0, "calls": 0}
        real = SummaryRunner.__call__

        def counting(self, pairs, forces):
            s = real(self, pairs, forces)
            seen["runs"] += len(pairs)
            seen["sim"] += float(np.sum(s.sim_time))
            seen["calls"] += 1
            return s

        SummaryRunner.__call__ = counting           # type: ignore[method-assign]   (this process only)
        for name, draws in DRAWS.items():
            compute_chunk(loads_spec(spec_text(name, 1), base), 0)          # warm-up: imports, cached kernels
            spec = loads_spec(spec_text(name, draws), base)
            seen.update(runs=0, sim=0.0, calls=0)
            t0 = time.process_time()
            rows = compute_chunk(spec, 0)
            cpu = time.process_time() - t0
            out["measures"][name] = {"rows": len(rows), "cpu": cpu, "runs": seen["runs"], "sim": seen["sim"],
                                     "calls": seen["calls"], "csv_bytes": len(_chunk_text(rows))}
        SummaryRunner.__call__ = real               # type: ignore[method-assign]
    out["lanes"] = _lanes()
    out["machine_end"] = _machine()
    return out


def _lanes() -> dict:
    """The critical impulse of LANE_PAIRS (chair, speed) pairs on the lanes and the scalar kernel, alternately
    (lanes, scalar, scalar, lanes: a drift of the machine's speed cancels in the ratio)."""
    import time

    import numpy as np

    from stability import preset
    from stability.simulate import engine
    from stability.study.impulse import critical_impulses

    ej = preset("ej-premier")
    speeds = np.tile(SPEEDS, LANE_PAIRS)[:LANE_PAIRS] * np.random.default_rng(0).uniform(0.97, 1.03, LANE_PAIRS)
    cpu = {"lanes": 0.0, "scalar": 0.0}
    res = {}
    for kernel in ("lanes", "scalar", "scalar", "lanes"):
        with engine.use_kernel(kernel):
            critical_impulses([ej] * 2, speeds[:2])                     # load the kernel
            t0 = time.process_time()
            res[kernel] = critical_impulses([ej] * LANE_PAIRS, speeds)
            cpu[kernel] += time.process_time() - t0
    a, b = res["lanes"], res["scalar"]
    rel = max(abs(x.impulse_Ns - y.impulse_Ns) / y.impulse_Ns for x, y in zip(a, b, strict=True)
              if x.status == "found" and y.status == "found")
    return {"lanes_ms": 1e3 * cpu["lanes"] / (2 * LANE_PAIRS), "scalar_ms": 1e3 * cpu["scalar"] / (2 * LANE_PAIRS),
            "max_rel": rel, "same_status": all(x.status == y.status for x, y in zip(a, b, strict=True)),
            "runs_per_row": sum(x.runs for x in a) / LANE_PAIRS}


def _startup(tmp: Path, env: dict) -> float:
    """CPU seconds of ``python -m stability.sweep`` on a 6-row growth-rate spec in a fresh process: the fixed cost
    of a process (imports, loading the cached kernels)."""
    import resource

    (tmp / "u.toml").write_text(UNCERTAINTY)
    (tmp / "spec.toml").write_text(spec_text("growth_rate", 1))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-m", "stability.sweep", str(tmp / "spec.toml"), "-o", str(tmp / "x.csv")],
                   check=True, env=env, cwd=ROOT, capture_output=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def run_measurement() -> dict:
    """:func:`measure` in a fresh process with one numba thread, and the start-up cost of the sweep command."""
    env = {**os.environ, "NUMBA_NUM_THREADS": "1", "PYTHONPATH": os.pathsep.join(
        [str(ROOT), str(Path(__file__).parent), os.environ.get("PYTHONPATH", "")])}
    proc = subprocess.run([sys.executable, __file__], check=True, env=env, cwd=ROOT, capture_output=True, text=True)
    data = json.loads(proc.stdout.strip().splitlines()[-1])
    with tempfile.TemporaryDirectory() as tmp:
        data["startup"] = _startup(Path(tmp), env)
    return data


LABELS = {"growth_rate": "growth_rate", "critical_speeds": "critical_speeds (free and locked)",
          "critical_impulse": "critical_impulse", "equal_instability_speed": "equal_instability_speed",
          "shimmy_margin": "shimmy_margin (shimmy band at the speeds)", "tip_angles": "tip_angles",
          "holding_moment": "holding_moment (cross-slope equilibrium per speed)"}     # plain text: a table cell


@group("scale_costs", "NUMBA_NUM_THREADS=1: stability.sweep.compute_chunk(loads_spec(SPEC), 0) per measure "
       "(process CPU time after a 6-row warm-up; SPEC: ej-premier, trail 0.04/0.06 x N draws x speeds 0.5, 0.75, "
       "1 m/s), stability.study.critical_impulses on the lanes and scalar kernels (engine.use_kernel), and "
       "python -m stability.sweep on a 6-row spec for the start-up (python docs/_ext/value_groups_scale.py)")
def scale_costs() -> dict:
    """Cost per row of each sweep measure, the critical impulse's counts, the kernels' ratio, a projection."""
    d = run_measurement()
    m = d["measures"]
    ms = {k: 1e3 * v["cpu"] / v["rows"] for k, v in m.items()}
    rows = tuple((LABELS[k], str(v["rows"]), fixed(v["cpu"], 2), sig(ms[k], 2)) for k, v in m.items())
    ci = m["critical_impulse"]
    lo_load = min(d["machine_start"]["load"], d["machine_end"]["load"])
    hi_load = max(d["machine_start"]["load"], d["machine_end"]["load"])
    ln = d["lanes"]
    row_s = ms["critical_impulse"] * 1e-3
    from stability.sweep import loads_spec

    chunk = loads_spec('chair = "ej-premier"\nspeeds = [1]\nmeasures = ["growth_rate"]\n').chunk_rows   # default
    out = {
        "table": Table(("measure", "rows", "CPU s", "ms of CPU per row"), rows),
        "cores": str(d["machine_start"]["cores"]), "cpu": d["machine_start"]["cpu"],
        "load_lo": fixed(lo_load, 1), "load_hi": fixed(hi_load, 1),
        "startup_s": fixed(d["startup"], 2),
        "speeds": ", ".join(f"{u:g}" for u in SPEEDS), "trails": " and ".join(f"{t:g}" for t in TRAILS),
        "ci_rows": str(ci["rows"]), "ci_runs": fixed(ci["runs"] / ci["rows"], 2),
        "ci_sim": sig(ci["sim"] / ci["rows"], 3), "ci_calls": str(ci["calls"]),
        "ci_ms": sig(ms["critical_impulse"], 2),
        "ci_eis_ms": sig(ms["critical_impulse"] + ms["equal_instability_speed"], 2),
        "lane_pairs": str(LANE_PAIRS), "lanes_ms": sig(ln["lanes_ms"], 3), "scalar_ms": sig(ln["scalar_ms"], 3),
        "lanes_ratio": fixed(ln["scalar_ms"] / ln["lanes_ms"], 2), "lanes_max_rel_pct": sig(100 * ln["max_rel"], 2),
        "lanes_status": "the same statuses" if ln["same_status"] else "some statuses differ",
        "lanes_runs": fixed(ln["runs_per_row"], 1),
        "rows_1e4_cpu": sig(1e4 * row_s, 2),
        "proj_rows": f"{PROJECTED_ROWS:,}", "workers": str(WORKERS),
        "proj_cpu": sig(PROJECTED_ROWS * row_s, 2), "proj_wall": sig(PROJECTED_ROWS * row_s / WORKERS, 2),
        "proj_wall_eis": sig(PROJECTED_ROWS * 1e-3 * (ms["critical_impulse"] + ms["equal_instability_speed"])
                             / WORKERS / 60, 2),
        "csv_bytes_row": sig(ci["csv_bytes"] / ci["rows"], 2),
        "proj_csv_gb": sig(PROJECTED_ROWS * ci["csv_bytes"] / ci["rows"] / 1e9, 2),
        "chunk_rows": str(chunk), "chunk_s": sig(chunk * row_s, 2), "chunks": f"{PROJECTED_ROWS // chunk:,}",
    }
    for k in m:
        out[f"{k}.ms"] = sig(ms[k], 2)
        out[f"{k}.rows"] = str(m[k]["rows"])
    return out


if __name__ == "__main__":
    print(json.dumps(measure()))
