"""A compiled run whose state leaves the finite numbers is an error, never a summary (issue 19).

Validated chairs cannot get here (``i_zp >= 1e-6 kg m^2`` and the other plausibility bounds), so the
fault is injected: a chair whose caster mass and inertia are 1e-300 (set past the validation) makes
the caster equations overflow within a few steps.  Before the kernel's non-finite stop, such a run
kept its last finite peak and an infinite level time, and a study counted it as "never reaches the
level", a silent wrong answer.
"""

from __future__ import annotations

import numpy as np
import pytest

from stability.chair import preset
from stability.settings.run import RunSpec
from stability.study.summaries import run_summaries


def _broken():
    c = preset("ej-premier")
    object.__setattr__(c, "i_zp", 1e-300)     # past the validation: the massless-caster singularity
    object.__setattr__(c, "m_c", 1e-300)
    return c


def test_a_non_finite_run_in_a_study_batch_is_an_error_naming_the_run():
    good = preset("ej-premier")
    with pytest.raises(FloatingPointError, match=r"'ej-premier' at 0\.75 m/s left the finite numbers.*1 of 2 runs"):
        run_summaries([good, _broken()], [0.5, 0.75], [10.0, 10.0], run=RunSpec(model="exact", scheme="wchair", push_duration=0.1, dt=0.001, horizon=4.0), level=0.5, steps=[0.001, 0.001])


def test_the_same_batch_without_the_broken_chair_is_finite():
    good = preset("ej-premier")
    s = run_summaries([good, good], [0.5, 0.75], [10.0, 10.0], run=RunSpec(model="exact", scheme="wchair", push_duration=0.1, dt=0.001, horizon=4.0), level=0.5, steps=[0.001, 0.001])
    assert np.all(np.isfinite(s.peak)) and np.all(np.isfinite(s.sim_time))


def test_a_non_finite_recorded_run_is_an_error():
    from stability.simulate import engine
    from stability.simulate.options import make_options

    opts = make_options(RunSpec(model="exact", horizon=1.0, dt=0.001, push_force=10.0), batch=True)
    with pytest.raises(FloatingPointError, match="left the finite numbers"):
        engine.run_compiled([_broken()], np.array([0.75]), opts)


def test_a_non_finite_run_in_a_packed_search_round_is_an_error():
    """The searches' packed rounds (SummaryRunner) raise as run_summaries does."""
    from stability.study.summaries import SummaryRunner

    runner = SummaryRunner([preset("ej-premier"), _broken()], [0.5, 0.75],
                           RunSpec(model="exact", push_duration=0.1, dt=0.001, horizon=4.0), level=0.5,
                           steps=[0.001, 0.001])
    runner([0], [10.0])                                  # the good pair alone is fine
    with pytest.raises(FloatingPointError, match=r"at 0\.75 m/s left the finite numbers.*1 of 2 runs"):
        runner([0, 1], [10.0, 10.0])
