"""Design sweeps under uncertainty: a TOML spec -> one row per (design, draw, speed), resumable chunks.

``python -m stability.sweep SPEC.toml -o RESULTS.parquet`` (docs/sweep.md).
"""

from stability.sweep.measures import columns, compute_chunk, n_chunks
from stability.sweep.run import read_rows, run_sweep, summary
from stability.sweep.spec import MEASURES, SCHEMA, SweepSpec, load_spec, loads_spec

__all__ = ["MEASURES", "SCHEMA", "SweepSpec", "columns", "compute_chunk", "load_spec", "loads_spec", "n_chunks",
           "read_rows", "run_sweep", "summary"]
