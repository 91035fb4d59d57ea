"""Sweeps on a Dask LocalCluster (issue 25): the same file in-process, on local:2 and after a resume (marked scale)."""

from __future__ import annotations

from pathlib import Path

import pytest

from stability.sweep import loads_spec, run_sweep
from stability.sweep.cluster import chunk_cost, dask_mapper, parse_dask
from stability.sweep.run import chunk_dir

pytestmark = pytest.mark.scale

UNC = '''[pin_friction]
fields = ["pin_friction_left", "pin_friction_right"]
distribution = "uniform"
low = -0.3
high = 0.3
relative = true
'''
SPEC = '''speeds = [0.75, 1.0]
measures = ["growth_rate", "critical_impulse"]
chunk_rows = 4
[grid]
trail = [0.04, 0.06]
[draws]
n = 3
seed = 2
uncertainty = "u.toml"
'''


def test_local_cluster_and_resume_give_the_in_process_file(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    (tmp_path / "u.toml").write_text(UNC)
    spec = loads_spec(SPEC, tmp_path)
    alone = run_sweep(spec, tmp_path / "alone.csv").read_bytes()
    with dask_mapper(spec, "local:2") as mapper:
        on_two = run_sweep(spec, tmp_path / "two.csv", mapper=mapper).read_bytes()
    assert on_two == alone
    # interrupted after two chunks in-process, resumed on the cluster
    import stability.sweep.run as run_mod

    real, calls = run_mod.compute_chunk, []

    def dies(s, i):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(i)
        return real(s, i)

    monkeypatch.setattr(run_mod, "compute_chunk", dies)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, tmp_path / "resumed.csv")
    monkeypatch.setattr(run_mod, "compute_chunk", real)
    assert len(list(chunk_dir(tmp_path / "resumed.csv").glob("chunk-*.csv"))) == 2
    with dask_mapper(spec, "local:2") as mapper:
        resumed = run_sweep(spec, tmp_path / "resumed.csv", resume=True, mapper=mapper).read_bytes()
    assert resumed == alone


def test_dask_option_checks_and_cost_order():
    assert parse_dask("local:2") == ("local", 2)
    assert parse_dask("tcp://10.0.0.1:8786") == ("tcp://10.0.0.1:8786", None)
    for bad in ("local:0", "local:x", "nowhere"):
        with pytest.raises(ValueError, match="--dask"):
            parse_dask(bad)
    spec = loads_spec('speeds = [1.0]\nmeasures = ["critical_impulse"]\nchunk_rows = 2\n[grid]\ntrail = [0.04, 0.05, 0.06]\n')
    assert chunk_cost(spec, 0) == 2 * chunk_cost(spec, 1)      # the last chunk holds one design of three


def test_local_workers_warm_up_on_their_own_numba_caches(monkeypatch):
    """The warm-up task points every worker at its own numba cache before loading the kernels."""
    pytest.importorskip("distributed")
    from distributed import Client, LocalCluster

    from stability.sweep.cluster import _warm_up

    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None,
                      env={"NUMBA_NUM_THREADS": "1"}) as cluster, Client(cluster) as client:
        said = list(client.run(_warm_up).values())
    caches = {s.split("cache ")[1] for s in said}
    assert len(caches) == 2 and all("stability-numba-" in c for c in caches)
    # keyed by the workers' names (0 and 1), not by process ids: the next cluster's workers load these kernels
    # (a process-id key made every `--dask local:N` run compile again: 18 s instead of 6 s for a 6-row sweep)
    assert {Path(c).name for c in caches} == {"0", "1"}
    assert all(s.startswith("numba threads 1,") for s in said)
