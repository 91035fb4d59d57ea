"""The compiled WCHAIR step keeps no reference counts (issue 36: numba's NRT is off in ``run_one`` and its helpers,
``kernel_equations._NOREF``), so it must allocate nothing: an array allocated for it would never be freed.  numba's
own allocation statistics (``NUMBA_NRT_STATS``, read when numba starts, hence a subprocess) count every allocation
and free of its runtime: over repeated runs, with and without a sampled controller (whose scratch is a view of the
run's state, ``kernel_controller.scratch_columns``), one run and a batch, they must balance exactly.  The step also
reads its fixed-length rows as tuples without a bounds check (``kernel_equations.leading``): the rows the engine
packs must be exactly that long.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.simulate import engine
from stability.simulate.controller import SampledController
from stability.simulate.options import make_options
from stability.simulate.packing import Packed

EJ = preset("ej-premier")

_CHILD = textwrap.dedent("""
    import json
    import numpy as np
    from numba.core.runtime import rtsys
    from stability.chair import preset
    from stability.settings.run import RunSpec
    from stability.simulate import SampledController, simulate, simulate_batch

    ej = preset("ej-premier")
    ctl = SampledController.state_feedback(np.array([0.0, 20.0, 0.0, 0.0, 0.0, 0.0, 0.0]), 0.01, limit=15.0)
    run = RunSpec(horizon=0.2)

    def runs():
        simulate(ej, 0.75, run)
        simulate(ej, 0.75, run, controller=ctl)
        simulate(ej, 0.75, run, yaw_moment=lambda t, s: 0.5)
        simulate_batch(ej, [0.5, 1.0], run, progress=False)
        simulate_batch(ej, [0.5, 1.0], run, controller=ctl, progress=False)

    runs()                                   # compiled or loaded first: what numba itself keeps is counted here
    a = rtsys.get_allocation_stats()
    for _ in range(5):
        runs()
    b = rtsys.get_allocation_stats()
    print(json.dumps({"alloc": b.alloc - a.alloc, "free": b.free - a.free}))
""")


def test_repeated_runs_leave_no_allocation_of_numbas_runtime_behind():
    out = subprocess.run([sys.executable, "-c", _CHILD], check=True, capture_output=True, text=True,
                         env=dict(os.environ, NUMBA_NRT_STATS="1"))
    counts = json.loads(out.stdout.strip().splitlines()[-1])
    # exact counts: every allocation of the runtime during the runs is freed by their end
    assert counts["alloc"] == counts["free"]


def test_the_rows_the_step_reads_as_tuples_are_their_full_length():
    k = engine._kernel()
    opts = make_options(RunSpec(horizon=0.1))
    for mode in (0, 1, 2):
        assert engine._config(opts, mode, -1).shape == (k.NCFG,)
    pk = Packed([EJ, EJ.replace(m=90.0)], np.array([0.75, 1.0]), opts, None)
    assert pk.P.shape == (2, k.NPARAM)
    # the state: the slots read as a tuple, the settle tracker, the controller's states and scratch
    ctl = SampledController.state_feedback(np.zeros(7), 0.01).arrays()
    nz, ny = ctl[3].shape[0], ctl[1].shape[0]
    assert engine.initial_state(pk.S, ctl).shape == (2, k.NSTATE + nz + nz + ny + 10)
    assert k.ST_TRACK + 5 == k.NSTATE
    none = SampledController.none().arrays()
    assert engine.initial_state(pk.S, none).shape == (2, k.NSTATE + none[3].shape[0])
