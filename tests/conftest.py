"""Suite-wide settings: how many pytest-xdist workers ``-n auto`` (pyproject's addopts) starts.

Every worker compiles the numba kernels once on a cold cache (about 10-15 s of CPU each) and holds its own
copy of the imported stack (about 0.3 GB), so more workers than four buy little and cost memory; on the 2-core
reference machine this gives two.  ``PYTEST_XDIST_AUTO_NUM_WORKERS`` still overrides it, and ``-n 0`` runs
everything in one process.
"""

from __future__ import annotations

import os

#: Largest number of workers ``-n auto`` starts.
MAX_AUTO_WORKERS = 4


def pytest_xdist_auto_num_workers(config):
    """Cores this process may run on, at most :data:`MAX_AUTO_WORKERS` (None: the variable decides)."""
    if os.environ.get("PYTEST_XDIST_AUTO_NUM_WORKERS"):
        return None
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(cores, MAX_AUTO_WORKERS))
