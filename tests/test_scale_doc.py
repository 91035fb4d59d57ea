"""docs/scale.md's counts for a critical-impulse sweep row, recomputed (marked slow: 300 rows, about 10 s).

The spec is the one the page measured: the E&J Premier, trails 0.04 and 0.06 m, 50 draws (pin friction
+-30 % uniform, I_z normal with std 0.3 kg m^2, seed 1), speeds 0.5, 0.75 and 1 m/s, the critical impulse.
The counts are deterministic on one machine.  On another CPU the kernel's rounding may differ in the last
bits, and with pin friction the outcome of a push near the threshold flips within a band about 1 % wide
(tests/test_search.py): a changed flip changes that row's search path by a run or two.  So the counts are
held to 5 % (15 of the 3,676 runs), not exactly; the CPU time per row only to a factor of 3 (a regression
guard: the page's figure is a measurement on a loaded machine).
"""

from __future__ import annotations

import re
import time
from pathlib import Path

import numpy as np
import pytest

from stability.study.summaries import SummaryRunner
from stability.sweep import compute_chunk, loads_spec

pytestmark = pytest.mark.slow

DOC = Path(__file__).resolve().parents[1] / "docs" / "scale.md"
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
SPEC = '''chair = "ej-premier"
speeds = [0.5, 0.75, 1.0]
measures = ["critical_impulse"]
[grid]
trail = [0.04, 0.06]
[draws]
n = 50
seed = 1
uncertainty = "u.toml"
'''


def test_critical_impulse_runs_per_row_as_documented(tmp_path, monkeypatch):
    text = " ".join(DOC.read_text().split())
    m = re.search(r"\*\*([\d.]+) simulations per row, ([\d.]+) s of simulated time per row\*\*", text)
    assert m, "docs/scale.md must state the runs and the simulated time per row"
    runs_doc, sim_doc = float(m.group(1)), float(m.group(2))
    cpu_doc = float(re.search(r"`critical_impulse` \| 300 \| [\d.]+ \| (\d+) ms", text).group(1)) * 1e-3
    (tmp_path / "u.toml").write_text(UNC)
    spec = loads_spec(SPEC, tmp_path)
    seen = {"runs": 0, "sim": 0.0}
    real = SummaryRunner.__call__

    def counting(self, pairs, forces):
        s = real(self, pairs, forces)
        seen["runs"] += len(pairs)
        seen["sim"] += float(np.sum(s.sim_time))
        return s

    monkeypatch.setattr(SummaryRunner, "__call__", counting)
    compute_chunk(spec, 0)                      # warm: kernels loaded, imports done
    seen.update(runs=0, sim=0.0)
    t0 = time.process_time()
    out = compute_chunk(spec, 0)
    cpu = time.process_time() - t0
    rows = len(out)
    assert rows == 300                          # one chunk holds the whole sweep
    assert seen["runs"] / rows == pytest.approx(runs_doc, rel=0.05)
    assert seen["sim"] / rows == pytest.approx(sim_doc, rel=0.05)
    # CPU time is recorded, not asserted (a shared machine; issue 34): the deterministic counts above are the check
    print(f"\nCPU per row {1e3 * cpu / rows:.0f} ms (docs/scale.md: {1e3 * cpu_doc:.0f} ms)")
